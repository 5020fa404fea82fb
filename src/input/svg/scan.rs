//! The pass over the raw XML before usvg sees it: what usvg drops or
//! cannot tell. It checks the root element, finds the top-level Inkscape
//! layers (with their labels and visibility, and an id for each so that
//! usvg's groups can be matched to them), lays out text (`text`, which
//! puts a stand-in for each text element in the source handed to usvg),
//! counts images, and has every number that becomes geometry checked
//! (`numbers`).

use std::collections::HashMap;

use resvg::usvg::roxmltree;

use super::numbers::check_numbers;
use super::text::Texts;
use crate::error::{Error, LineCol, Result};
use crate::scene::Layer;

pub(super) const SVG_NS: &str = "http://www.w3.org/2000/svg";
const INKSCAPE_NS: &str = "http://www.inkscape.org/namespaces/inkscape";

/// Is this an element of the SVG vocabulary (namespaced or, as usvg also
/// accepts, without namespace) with this local name?
pub(super) fn is_svg(node: roxmltree::Node<'_, '_>, name: &str) -> bool {
    node.is_element()
        && node.tag_name().name() == name
        && matches!(node.tag_name().namespace(), None | Some(SVG_NS))
}

/// A top-level Inkscape layer as written in the source.
#[derive(Debug)]
pub(super) struct LayerSource {
    /// Its id in the text handed to usvg (added when the source had none).
    pub id: String,
    /// `inkscape:label`, else the id, else `layer {n}`.
    pub label: String,
    /// `display="none"` or `style="display:none"`: usvg drops it.
    pub hidden: bool,
    /// False for a documentation layer (`%` label): see [`Layer::is_plotted`].
    pub plotted: bool,
}

/// What the pre-pass over the raw XML learns: what usvg drops or cannot
/// tell (Inkscape attributes, text and images).
#[derive(Debug)]
pub(super) struct Source {
    /// The top-level layers, in document order.
    pub layers: Vec<LayerSource>,
    /// The text, laid out.
    pub texts: Texts,
    /// `image` elements.
    pub images: usize,
    /// Layers that could not be located in the source.
    pub warnings: Vec<String>,
    /// The source with ids given to layers that had none (or shared one),
    /// so that usvg's groups can be matched to layers by id, and text
    /// elements replaced by their stand-ins.
    pub rewritten: Option<String>,
}

/// Scans `doc`, parsed from `text`, whose lengths have `px_per_inch`
/// pixels to the inch.
///
/// # Errors
/// [`Error::Parse`] when the root is not `<svg>`; [`Error::Invalid`] for a
/// number that cannot be plotted.
pub(super) fn scan(text: &str, doc: &roxmltree::Document<'_>, px_per_inch: f64) -> Result<Source> {
    let root = doc.root_element();
    if !is_svg(root, "svg") {
        let name = root.tag_name().name();
        return Err(Error::Parse {
            at: Some(LineCol::of_offset(text, root.range().start)),
            field: None,
            message: format!(
                "not an SVG document: the root element is <{name}>, expected <svg> \
                 (in the namespace {SVG_NS})"
            ),
        });
    }

    let mut images = 0;
    let mut id_count: HashMap<&str, usize> = HashMap::new();
    for node in doc.descendants().filter(|n| n.is_element()) {
        if is_svg(node, "image") {
            images += 1;
        }
        if let Some(id) = node.attribute("id") {
            *id_count.entry(id).or_default() += 1;
        }
        if matches!(node.tag_name().namespace(), None | Some(SVG_NS)) {
            check_numbers(text, node)?;
        }
    }

    let mut texts = Texts::read(text, doc, px_per_inch);

    let mut layers = Vec::new();
    let mut warnings = Vec::new();
    // (byte range replaced, replacement, the layer or text it is for).
    let mut edits: Vec<(std::ops::Range<usize>, String, EditFor)> = Vec::new();
    let mut fresh = 0;
    for node in root.children().filter(|n| is_svg(*n, "g")) {
        if node.attribute((INKSCAPE_NS, "groupmode")) != Some("layer") {
            continue;
        }
        let old_id = node.attribute("id");
        let label = match node.attribute((INKSCAPE_NS, "label")).or(old_id) {
            Some(label) => label.to_string(),
            None => format!("layer {}", layers.len() + 1),
        };
        let hidden = node.attribute("display").map(str::trim) == Some("none")
            || node.attribute("style").is_some_and(|s| {
                let s: String = s.chars().filter(|c| !c.is_whitespace()).collect();
                s.to_ascii_lowercase()
                    .split(';')
                    .any(|decl| decl == "display:none")
            });
        let id = match old_id {
            Some(id) if id_count.get(id) == Some(&1) => id.to_string(),
            _ => {
                // Missing or shared: give the layer an id of its own.
                let id = loop {
                    fresh += 1;
                    let candidate = format!("moyo-import-layer-{fresh}");
                    if !id_count.contains_key(candidate.as_str()) {
                        break candidate;
                    }
                };
                let edit = match node
                    .attributes()
                    .find(|a| a.name() == "id" && a.namespace().is_none())
                {
                    Some(attr) => Some((attr.range_value(), id.clone())),
                    None => after_tag_name(text, node).map(|at| (at..at, format!(" id=\"{id}\""))),
                };
                let Some(edit) = edit else {
                    warnings.push(unlocated_layer(&label));
                    continue;
                };
                edits.push((edit.0, edit.1, EditFor::Layer(label.clone())));
                id
            }
        };
        let plotted = Layer::name_is_plotted(&label);
        layers.push(LayerSource {
            id,
            label,
            hidden,
            plotted,
        });
    }

    edits.extend(
        texts
            .edits
            .drain(..)
            .map(|e| (e.range, e.markup, EditFor::Text(e.index))),
    );
    // Edits that overlap one before them (only elements from entities
    // can) are left out: their layer or text was not located.
    edits.sort_by_key(|(range, _, _)| range.start);
    let mut kept = Vec::with_capacity(edits.len());
    let mut end = 0;
    for (range, replacement, owner) in edits {
        if range.start < end {
            match owner {
                EditFor::Layer(label) => warnings.push(unlocated_layer(&label)),
                EditFor::Text(index) => {
                    texts.laid[index] = None;
                    texts.unlocated += 1;
                }
            }
            continue;
        }
        end = range.end;
        kept.push((range, replacement));
    }
    let rewritten = (!kept.is_empty()).then(|| {
        let mut out = text.to_string();
        for (range, replacement) in kept.into_iter().rev() {
            out.replace_range(range, &replacement);
        }
        out
    });
    Ok(Source {
        layers,
        texts,
        images,
        warnings,
        rewritten,
    })
}

fn unlocated_layer(label: &str) -> String {
    format!(
        "layer '{label}' could not be located in the source \
         (it comes from an entity?); its paths count as outside layers"
    )
}

/// What an edit of the source is for.
enum EditFor {
    /// Giving the layer with this label an id.
    Layer(String),
    /// Putting the stand-in of this text in place of its element.
    Text(usize),
}

/// The byte offset just after `<name` of `node`'s start tag, if the source
/// text really has the tag there.
fn after_tag_name(text: &str, node: roxmltree::Node<'_, '_>) -> Option<usize> {
    let start = node.range().start;
    let rest = text.get(start..)?.strip_prefix('<')?;
    let len = rest.find(|c: char| c.is_whitespace() || c == '/' || c == '>')?;
    let qname = &rest[..len];
    let local = qname.rsplit(':').next()?;
    (local == node.tag_name().name()).then_some(start + 1 + len)
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{doc, import};

    #[test]
    fn images_are_skipped_with_warnings_and_text_is_drawn() {
        let imported = import(&doc(r#"<text x="10" y="10">Hello</text>
               <g><text x="10" y="20"><tspan>again</tspan></text></g>
               <image href="data:image/png;base64,iVBORw0KGgo=" width="10" height="10"/>
               <image xlink:href="/etc/passwd" width="10" height="10"/>
               <path d="M0 0 L5 5" stroke="black"/>"#));
        assert_eq!(imported.scene.path_count(), 3);
        assert_eq!(imported.warnings.len(), 2, "{:?}", imported.warnings);
        assert!(imported.warnings[0].starts_with("2 text elements drawn in "));
        assert!(imported.warnings[1].starts_with("skipped 2 images: "));
    }
}
