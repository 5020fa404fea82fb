//! The pass over the raw XML before usvg sees it: what usvg drops or
//! cannot tell. It checks the root element, finds the top-level Inkscape
//! layers (with their labels and visibility, and an id for each so that
//! usvg's groups can be matched to them), lays out text (`text`, which
//! puts a stand-in for each text element in the source handed to usvg),
//! counts images and the elements `display: none` hides (usvg drops them
//! without a word), and has every number that becomes geometry checked
//! (`numbers`).

use std::collections::HashMap;

use resvg::usvg::roxmltree;

use super::numbers::{check_composed_transforms, check_numbers};
use super::text::{property, Texts};
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
    /// `image` elements, but those `display: none` hides.
    pub images: usize,
    /// Elements that `display: none` hides (see [`display_none`]).
    pub display_none: usize,
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

    let mut images: usize = 0;
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

    check_composed_transforms(text, doc)?;

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
        let hidden = is_display_none(node);
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
    let hidden = display_none(root);
    Ok(Source {
        layers,
        texts,
        images: images.saturating_sub(hidden.images),
        display_none: hidden.elements,
        warnings,
        rewritten,
    })
}

/// Whether `node` says `display: none`, in its `style` or as an
/// attribute (what usvg reads; a stylesheet's rules are not seen here).
fn is_display_none(node: roxmltree::Node<'_, '_>) -> bool {
    property(node, "display") == Some("none")
}

/// What `display: none` hides, as [`display_none`] counts it.
struct Hidden {
    /// Hidden elements, each counted once with what it holds.
    elements: usize,
    /// `image` elements among what they and hidden layers hold.
    images: usize,
}

/// The elements that would be drawn but for `display: none`: the outermost
/// hidden element of each hidden part, a group with all it holds counted
/// once. Left out: what is only drawn by reference (`defs`, `symbol`,
/// clip paths, masks, markers, patterns), whose visibility is the `use`'s
/// or the referrer's; `switch`, which draws one child of its choice; and
/// hidden top-level layers, which have a warning of their own. Walked
/// with a stack, so no depth of nesting can overflow it.
fn display_none(root: roxmltree::Node<'_, '_>) -> Hidden {
    const CONTAINERS: [&str; 3] = ["svg", "g", "a"];
    const DRAWN: [&str; 10] = [
        "path", "rect", "circle", "ellipse", "line", "polyline", "polygon", "text", "use", "image",
    ];
    let mut hidden = Hidden {
        elements: 0,
        images: 0,
    };
    let mut stack: Vec<_> = root.children().collect();
    while let Some(node) = stack.pop() {
        let name = node.tag_name().name();
        let container = CONTAINERS.iter().any(|&c| is_svg(node, c));
        if !container && !DRAWN.iter().any(|&d| is_svg(node, d)) {
            continue;
        }
        if is_display_none(node) {
            let layer = node.parent() == Some(root)
                && name == "g"
                && node.attribute((INKSCAPE_NS, "groupmode")) == Some("layer");
            if !layer {
                hidden.elements += 1;
            }
            hidden.images += node.descendants().filter(|n| is_svg(*n, "image")).count();
        } else if container {
            stack.extend(node.children());
        }
    }
    hidden
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
    fn what_display_none_hides_is_counted_once_per_hidden_element() {
        let imported = import(&doc(r##"<path d="M0 0 L10 0" stroke="black"/>
               <path d="M0 1 L10 1" stroke="black" display="none"/>
               <g style="stroke: black; display: none !important">
                 <path d="M0 2 L10 2"/><path d="M0 3 L10 3" display="none"/>
                 <image href="a.png" width="5" height="5"/>
               </g>
               <g><a><circle cx="5" cy="5" r="2" stroke="black" style="display:none"/></a></g>
               <text x="10" y="20" display="none">hidden</text>
               <image href="b.png" width="5" height="5" display="none"/>
               <defs><path id="d" d="M0 4 L10 4" stroke="black" display="none"/></defs>
               <g inkscape:groupmode="layer" inkscape:label="off" display="none">
                 <path d="M0 5 L10 5" stroke="black"/>
                 <image href="c.png" width="5" height="5"/>
               </g>
               <image href="shown.png" width="5" height="5"/>
               <path d="M0 6 L10 6" stroke="black" display="inline"/>"##));
        assert_eq!(imported.scene.path_count(), 2);
        assert_eq!(
            imported.warnings,
            [
                "skipped 1 image: raster images cannot be plotted",
                "skipped 5 elements: hidden by `display:none`",
                "skipped layer 'off': it is hidden",
                "2 paths outside every layer went to an extra layer 'unlayered' (pen 1)",
            ]
        );
    }

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
