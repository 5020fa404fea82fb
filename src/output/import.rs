//! SVG import: any SVG document (moyo's own output, an Inkscape drawing, a
//! hand-written file) read back into a [`Scene`] in millimetres.
//!
//! [`import_svg`] lets usvg resolve the document — CSS, inherited styles,
//! `use`, `symbol`, nested `svg`, markers, basic shapes and arcs all become
//! plain Bézier paths with absolute transforms — and then maps it onto the
//! scene graph:
//!
//! - **Units.** One CSS pixel is `1/px_per_inch` inch (96 dpi, as in SVG);
//!   `width="210mm" height="297mm" viewBox="0 0 210 297"` therefore maps one
//!   user unit to exactly one millimetre. Every transform, the viewBox
//!   included, is baked into the path coordinates, so the imported scene has
//!   flat layers, identity transforms, zero margins and a page the size of
//!   the document.
//! - **Pens.** Top-level Inkscape layers (`<g inkscape:groupmode="layer">`)
//!   become one scene layer and pen each. The pen number is the leading
//!   integer of `inkscape:label` (`"3 blue"` → pen 3 named `blue`, the
//!   convention of moyo, AxiDraw and vpype); layers without one get the
//!   smallest number no other layer claims. Without layers, paths are
//!   grouped by stroke colour (fill colour when unstroked): one pen per
//!   colour, numbered in order of first appearance. A pen's colour and width
//!   are the most common stroke colour and drawn stroke width of its paths.
//! - **Layer names**, following AxiDraw's layer control:
//!   - Leading whitespace is ignored. A label whose first character is then
//!     `%` marks a *documentation layer*: it is imported whole (its
//!     sub-layers included) as a scene layer named by the trimmed label
//!     (`"%guides"`, `"% 2 notes"`), which is therefore not plotted
//!     ([`Layer::is_plotted`]): it survives in SVG output and the preview,
//!     but G-code, HPGL, the plot stages and the plot statistics leave it
//!     out. It reads no pen number (`"% 2 notes"` is not pen 2): each such
//!     layer gets a pen of its own (its colour and width for the preview),
//!     numbered after every plotted pen, so that adding or removing a `%`
//!     layer never renumbers the others. This holds when grouping by colour
//!     too: a documentation layer's paths never join a colour's pen.
//!   - Otherwise a leading integer 1–999 is the pen number, and the
//!     separators after it (whitespace, `-`, `_`, `:`) are dropped: `"3
//!     red"`, `"3-red"`, `"3_red"` and `"3: red"` are all pen 3 named `red`.
//!     A label that is only a number (`"3"`) names the layer by the whole
//!     label. When the rest of the label starts with `%` (`"3 %odd"`), the
//!     layer is plotted (AxiDraw reads the number first) and keeps the
//!     whole label as its name. A label that starts otherwise (`"red"`,
//!     `"0 red"`, `"!2 pause"`) has no pen number: the whole label is the
//!     name, and the pen takes a free number. AxiDraw's other codes (`!`
//!     pause, `+H`, `+S`, `+D` after the number) are kept in the name and
//!     not acted upon.
//!   - Sub-layers are not parsed, as in AxiDraw 3 and later: they belong to
//!     their top-level layer, so a `%` sub-layer inside a plotted layer is
//!     plotted with it, and everything inside a `%` layer is not plotted.
//!   - A hidden layer (`display:none`) is skipped with a warning, `%` or
//!     not.
//! - **Paint.** A filled path keeps its fill colour in [`Style::fill`] (the
//!   region that hatching and occlusion work on); the stroke is implied by
//!   the pen. Paths with neither fill nor stroke are dropped.
//! - **Not imported, with a warning:** text (moyo is built without fonts;
//!   convert text to paths first), raster images, and the effect of clip
//!   paths, masks and filters (the paths are imported unclipped).
//!
//! Bad input is an [`Error`], never a panic: an empty file, malformed XML, a
//! root element other than `<svg>`, a document without a usable size, and
//! numbers that cannot be plotted (NaN, infinities, coordinates beyond
//! ±[`MAX_COORD`] mm).
//!
//! Round trip: importing what [`to_svg`](super::to_svg) wrote gives back
//! the same pens (numbers, names, colours, widths), the same paths per pen
//! in the same order within 1e-3 mm, the fills and the embedded scene
//! description; the scene layers drawn by one pen come back merged into
//! one layer, and groups come back flattened. A documentation layer comes
//! back as a layer of its own with the same name (the `%` label), paths,
//! colour and width; its pen number is not in the SVG, so it is the one
//! numbered as above.
//!
//! Limits: usvg computes in `f32`, so coordinates carry a relative error
//! of about 1e-7 (0.04 µm on an A3 sheet). Only top-level layers are pens;
//! sub-layers belong to their top-level layer. [`Style`] has no fill rule:
//! fills are non-zero downstream, so an `evenodd` fill is redrawn as the
//! normalised contours of its area (the same lines; holes wound against
//! their outline). Layer visibility set by a
//! CSS stylesheet (rather than `style`/`display` on the layer) hides the
//! layer without the "hidden" wording in its warning.

use std::collections::{HashMap, HashSet};

use kurbo::{Affine, BezPath, Point};
use resvg::usvg::{self, roxmltree, tiny_skia_path::PathSegment};
use serde::{Deserialize, Serialize};

use super::embedded_description;
use crate::error::{Error, LineCol, Result};
use crate::geom::region::{FillRule, Region};
use crate::scene::{Color, Group, Layer, Pen, Scene, Style};
use crate::units::MAX_COORD;
use crate::units::{Margins, Page, MM_PER_INCH};

const SVG_NS: &str = "http://www.w3.org/2000/svg";
const INKSCAPE_NS: &str = "http://www.inkscape.org/namespaces/inkscape";

/// Width of a pen none of whose paths is stroked (a fine liner).
const DEFAULT_PEN_WIDTH: f64 = 0.3;

/// Pen numbers a layer label may carry (as in the scene description).
const PEN_NUMBERS: std::ops::RangeInclusive<u32> = 1..=999;

/// Page sizes and pen widths are rounded to 1/this mm (a nanometre), which
/// removes usvg's `f32` noise (`420.00001`) without changing anything a
/// plotter could draw.
const SIZE_STEPS_PER_MM: f64 = 1e6;

/// Attributes whose numbers become geometry; they are checked for NaN,
/// infinities and values usvg cannot hold before usvg sees them (it would
/// drop such elements silently).
const GEOMETRY_ATTRIBUTES: [&str; 17] = [
    "d",
    "points",
    "x",
    "y",
    "x1",
    "y1",
    "x2",
    "y2",
    "cx",
    "cy",
    "r",
    "rx",
    "ry",
    "width",
    "height",
    "transform",
    "viewBox",
];

/// How imported paths are assigned to pens.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PenGrouping {
    /// Top-level Inkscape layers when the document has any, otherwise
    /// stroke colours.
    #[default]
    Auto,
    /// Always by stroke colour (fill colour for unstroked paths), ignoring
    /// layers.
    StrokeColor,
}

/// Options of [`import_svg`].
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ImportOptions {
    /// CSS pixels per inch: the size of a unitless length. 96 is the SVG
    /// standard; some old Illustrator files assume 72.
    pub px_per_inch: f64,
    /// How paths are assigned to pens.
    pub pens: PenGrouping,
}

impl ImportOptions {
    /// 96 px per inch, pens from layers when there are any.
    pub const DEFAULT: ImportOptions = ImportOptions {
        px_per_inch: 96.0,
        pens: PenGrouping::Auto,
    };

    /// These options with `px_per_inch` pixels per inch.
    pub const fn with_px_per_inch(mut self, px_per_inch: f64) -> ImportOptions {
        self.px_per_inch = px_per_inch;
        self
    }

    /// These options with another pen grouping.
    pub const fn with_pens(mut self, pens: PenGrouping) -> ImportOptions {
        self.pens = pens;
        self
    }
}

impl Default for ImportOptions {
    fn default() -> ImportOptions {
        ImportOptions::DEFAULT
    }
}

/// The result of [`import_svg`]: the scene and what was left out of it.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq)]
pub struct Imported {
    /// The drawing, in millimetres, with flat layers and zero margins.
    pub scene: Scene,
    /// One sentence per kind of content that was skipped or approximated
    /// (text, images, unpainted paths, clipping, hidden layers…), in a
    /// fixed order. Empty when the import is exact.
    pub warnings: Vec<String>,
}

/// Reads an SVG document into a scene (see the module documentation for
/// the mapping and its limits).
///
/// # Errors
///
/// [`Error::Parse`] for an empty file, malformed XML or a document that is
/// not SVG; [`Error::Invalid`] for bad options, a document without a usable
/// size, or numbers that cannot be plotted.
pub fn import_svg(text: &str, options: &ImportOptions) -> Result<Imported> {
    if !(options.px_per_inch.is_finite() && options.px_per_inch > 0.0) {
        return Err(Error::invalid(
            "px_per_inch",
            format!("must be a positive number, got {}", options.px_per_inch),
        ));
    }
    let doc = parse_xml(text)?;
    let source = scan(text, &doc)?;
    let usvg_options = usvg::Options {
        dpi: options.px_per_inch as f32,
        // Images are never imported: don't decode them, and never read
        // files named by `href`.
        image_href_resolver: usvg::ImageHrefResolver {
            resolve_data: Box::new(|_, _, _| None),
            resolve_string: Box::new(|_, _| None),
        },
        ..usvg::Options::default()
    };
    let tree = match &source.rewritten {
        Some(rewritten) => {
            let doc = parse_xml(rewritten)?;
            usvg::Tree::from_xmltree(&doc, &usvg_options)
        }
        None => usvg::Tree::from_xmltree(&doc, &usvg_options),
    }
    .map_err(usvg_error)?;

    let mm_per_px = MM_PER_INCH / options.px_per_inch;
    let page = page_of(&tree, exact_size(doc.root_element(), mm_per_px), mm_per_px)?;

    let mut collector = Collector {
        to_mm: Affine::scale(mm_per_px),
        layer_of: source
            .layers
            .iter()
            .enumerate()
            .map(|(i, l)| (l.id.as_str(), i))
            .collect(),
        found: vec![false; source.layers.len()],
        drawn: Vec::new(),
        unpainted: 0,
        invisible: 0,
        effects: 0,
    };
    collector.group(tree.root(), None)?;

    let mut warnings = Vec::new();
    let mut plural = |n: usize, one: &str, many: &str, rest: &str| {
        if n > 0 {
            let noun = if n == 1 { one } else { many };
            warnings.push(format!("skipped {n} {noun}: {rest}"));
        }
    };
    plural(
        source.texts,
        "text element",
        "text elements",
        "text is not imported (convert it to paths first, \
         e.g. Inkscape's Path > Object to Path)",
    );
    plural(
        source.images,
        "image",
        "images",
        "raster images cannot be plotted",
    );
    plural(
        collector.unpainted,
        "path",
        "paths",
        "no fill and no stroke",
    );
    plural(
        collector.invisible,
        "path",
        "paths",
        "hidden by `visibility`",
    );
    if collector.effects > 0 {
        let n = collector.effects;
        let groups = if n == 1 { "group" } else { "groups" };
        warnings.push(format!(
            "clip paths, masks and filters are not applied ({n} {groups}): \
             their paths are imported whole"
        ));
    }
    warnings.extend(source.warnings);

    let (buckets, stacked) = match options.pens {
        PenGrouping::Auto if !source.layers.is_empty() => {
            (by_layer(&source.layers, &collector, &mut warnings), true)
        }
        _ => (by_color(&collector.drawn, &source.layers), false),
    };
    let scene = assemble(
        page,
        buckets,
        stacked,
        collector.drawn,
        embedded_description(text),
        &mut warnings,
    );
    Ok(Imported { scene, warnings })
}

/// An `Error::Parse` without a position.
fn parse_error(message: impl Into<String>) -> Error {
    Error::Parse {
        at: None,
        field: None,
        message: message.into(),
    }
}

/// Parses XML the way usvg does (DTDs with entities allowed; roxmltree
/// guards against entity expansion attacks).
fn parse_xml(text: &str) -> Result<roxmltree::Document<'_>> {
    if text.trim().is_empty() {
        return Err(parse_error("the file is empty; expected an SVG document"));
    }
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..roxmltree::ParsingOptions::default()
    };
    roxmltree::Document::parse_with_options(text, options).map_err(|e| {
        let pos = e.pos();
        // The position goes into `at`; keep it out of the sentence.
        let message = e.to_string().replace(&format!(" at {pos}"), "");
        Error::Parse {
            at: Some(LineCol {
                line: pos.row as usize,
                column: pos.col as usize,
            }),
            field: None,
            message: format!("malformed SVG (not well-formed XML): {message}"),
        }
    })
}

fn usvg_error(e: usvg::Error) -> Error {
    match e {
        usvg::Error::InvalidSize => Error::invalid(
            "svg",
            "the document has no usable size: width and height must be \
             positive, or a viewBox must be given",
        ),
        usvg::Error::ElementsLimitReached => {
            parse_error("the document has more than 1,000,000 elements")
        }
        usvg::Error::ParsingFailed(roxmltree::Error::NoRootNode) => {
            parse_error("not an SVG document: the root element must be <svg>")
        }
        e => parse_error(format!("malformed SVG: {e}")),
    }
}

/// Is this an element of the SVG vocabulary (namespaced or, as usvg also
/// accepts, without namespace) with this local name?
fn is_svg(node: roxmltree::Node<'_, '_>, name: &str) -> bool {
    node.is_element()
        && node.tag_name().name() == name
        && matches!(node.tag_name().namespace(), None | Some(SVG_NS))
}

/// A top-level Inkscape layer as written in the source.
#[derive(Debug)]
struct LayerSource {
    /// Its id in the text handed to usvg (added when the source had none).
    id: String,
    /// `inkscape:label`, else the id, else `layer {n}`.
    label: String,
    /// `display="none"` or `style="display:none"`: usvg drops it.
    hidden: bool,
    /// False for a documentation layer (`%` label): see [`Layer::is_plotted`].
    plotted: bool,
}

/// What the pre-pass over the raw XML learns: what usvg drops or cannot
/// tell (Inkscape attributes, text and images).
#[derive(Debug)]
struct Source {
    layers: Vec<LayerSource>,
    texts: usize,
    images: usize,
    warnings: Vec<String>,
    /// The source with ids given to layers that had none (or shared one),
    /// so that usvg's groups can be matched to layers by id.
    rewritten: Option<String>,
}

fn scan(text: &str, doc: &roxmltree::Document<'_>) -> Result<Source> {
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

    let mut texts = 0;
    let mut images = 0;
    let mut id_count: HashMap<&str, usize> = HashMap::new();
    for node in doc.descendants().filter(|n| n.is_element()) {
        if is_svg(node, "text") || is_svg(node, "flowRoot") {
            texts += 1;
        } else if is_svg(node, "image") {
            images += 1;
        }
        if let Some(id) = node.attribute("id") {
            *id_count.entry(id).or_default() += 1;
        }
        if matches!(node.tag_name().namespace(), None | Some(SVG_NS)) {
            check_numbers(text, node)?;
        }
    }

    let mut layers = Vec::new();
    let mut warnings = Vec::new();
    // (byte range replaced, replacement), applied back to front.
    let mut edits: Vec<(std::ops::Range<usize>, String)> = Vec::new();
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
                    warnings.push(format!(
                        "layer '{label}' could not be located in the source \
                         (it comes from an entity?); its paths count as outside layers"
                    ));
                    continue;
                };
                edits.push(edit);
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

    let rewritten = (!edits.is_empty()).then(|| {
        let mut out = text.to_string();
        edits.sort_by_key(|(range, _)| std::cmp::Reverse(range.start));
        for (range, replacement) in edits {
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

/// Rejects NaN, infinities and numbers beyond `f32` in the geometry
/// attributes of `node`.
fn check_numbers(text: &str, node: roxmltree::Node<'_, '_>) -> Result<()> {
    for attr in node.attributes() {
        if attr.namespace().is_some() || !GEOMETRY_ATTRIBUTES.contains(&attr.name()) {
            continue;
        }
        if let Some(bad) = bad_number(attr.value()) {
            let element = match node.attribute("id") {
                Some(id) => format!("<{} id=\"{id}\">", node.tag_name().name()),
                None => format!("<{}>", node.tag_name().name()),
            };
            return Err(Error::Invalid {
                at: Some(LineCol::of_offset(text, attr.range_value().start)),
                field: format!("{element} {}", attr.name()),
                message: format!(
                    "'{bad}' is not a plottable number (NaN, infinite, or beyond \
                     ±{:e})",
                    f32::MAX
                ),
            });
        }
    }
    Ok(())
}

/// The end of the SVG number starting at byte `i` of `b`
/// (`[sign] digits [. digits] [e [sign] digits]`), or `i` when none does.
fn number_end(b: &[u8], start: usize) -> usize {
    let digits = |mut i: usize| {
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        i
    };
    let mut i = start;
    if i < b.len() && matches!(b[i], b'+' | b'-') {
        i += 1;
    }
    let mut end = digits(i);
    let mut seen = end > i;
    if end < b.len() && b[end] == b'.' {
        let fraction_end = digits(end + 1);
        if fraction_end > end + 1 || seen {
            seen = true;
            end = fraction_end;
        }
    }
    if !seen {
        return start;
    }
    if end < b.len() && matches!(b[end], b'e' | b'E') {
        let mut j = end + 1;
        if j < b.len() && matches!(b[j], b'+' | b'-') {
            j += 1;
        }
        if j < b.len() && b[j].is_ascii_digit() {
            end = digits(j);
        }
    }
    end
}

/// The first NaN/infinity word or out-of-range number in an attribute
/// value.
fn bad_number(value: &str) -> Option<&str> {
    let b = value.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i].is_ascii_alphabetic() {
            let start = i;
            while i < b.len() && b[i].is_ascii_alphabetic() {
                i += 1;
            }
            let word = &value[start..i];
            if ["nan", "inf", "infinity"]
                .iter()
                .any(|w| word.eq_ignore_ascii_case(w))
            {
                return Some(word);
            }
            continue;
        }
        let end = number_end(b, i);
        if end == i {
            i += 1;
            continue;
        }
        let token = &value[i..end];
        if let Ok(v) = token.parse::<f64>() {
            if v.is_nan() || v.abs() > f64::from(f32::MAX) {
                return Some(token);
            }
        }
        i = end;
    }
    None
}

/// An absolute length (`12`, `12px`, `210mm`, `8.5in`…) in mm; `None` for
/// percentages, font-relative units and anything malformed.
fn length_mm(value: &str, mm_per_px: f64) -> Option<f64> {
    let value = value.trim();
    let end = number_end(value.as_bytes(), 0);
    let number: f64 = value[..end].parse().ok()?;
    let mm_per_unit = match value[end..].trim() {
        "" | "px" => mm_per_px,
        "mm" => 1.0,
        "cm" => 10.0,
        "in" => MM_PER_INCH,
        "pt" => MM_PER_INCH / 72.0,
        "pc" => MM_PER_INCH / 6.0,
        "Q" | "q" => 0.25,
        _ => return None,
    };
    Some(number * mm_per_unit)
}

/// The page size in mm computed in `f64` from the root's `width`,
/// `height` and `viewBox`, following usvg's rules; `None` where usvg would
/// need more (percentages, font units).
fn exact_size(root: roxmltree::Node<'_, '_>, mm_per_px: f64) -> Option<(f64, f64)> {
    let side = |name| root.attribute(name).map(|v| length_mm(v, mm_per_px));
    let view_box = root.attribute("viewBox").and_then(|v| {
        let b = v.as_bytes();
        let mut numbers = Vec::new();
        let mut i = 0;
        while i < b.len() {
            let end = number_end(b, i);
            if end == i {
                i += 1;
            } else {
                numbers.push(v[i..end].parse::<f64>().ok()?);
                i = end;
            }
        }
        match numbers[..] {
            [_, _, w, h] if w > 0.0 && h > 0.0 => Some((w, h)),
            _ => None,
        }
    });
    match (side("width"), side("height"), view_box) {
        (Some(Some(w)), Some(Some(h)), _) => Some((w, h)),
        (Some(Some(w)), None, Some((vw, vh))) => Some((w, w * vh / vw)),
        (None, Some(Some(h)), Some((vw, vh))) => Some((h * vw / vh, h)),
        (None, None, Some((vw, vh))) => Some((vw * mm_per_px, vh * mm_per_px)),
        _ => None,
    }
}

/// The page: the document's size in mm, no margins. usvg's size is `f32`;
/// the same size computed in `f64` from the source replaces it when the
/// two agree, so that `width="148mm"` is exactly 148.
fn page_of(tree: &usvg::Tree, exact: Option<(f64, f64)>, mm_per_px: f64) -> Result<Page> {
    let size = tree.size();
    let mut mm = [0.0; 2];
    for (i, (px, name)) in [(size.width(), "width"), (size.height(), "height")]
        .into_iter()
        .enumerate()
    {
        let approx = f64::from(px) * mm_per_px;
        let v = match exact.map(|(w, h)| if i == 0 { w } else { h }) {
            Some(v) if (v - approx).abs() <= 1e-5 * approx.abs() => v,
            _ => round_size(approx),
        };
        if !(v.is_finite() && v > 0.0 && v <= MAX_COORD) {
            return Err(Error::invalid(
                format!("svg {name}"),
                format!("the page {name} must be within 0–{MAX_COORD} mm, got {v} mm"),
            ));
        }
        mm[i] = v;
    }
    Ok(Page {
        width: mm[0],
        height: mm[1],
        margins: Margins::default(),
    })
}

/// `v` mm rounded to a nanometre. Dividing by the exact `1e6` gives the
/// double nearest to the decimal, so `0.30000001` becomes exactly `0.3`.
fn round_size(v: f64) -> f64 {
    (v * SIZE_STEPS_PER_MM).round() / SIZE_STEPS_PER_MM
}

/// A usvg path converted to page millimetres.
#[derive(Debug)]
struct Drawn {
    /// Index into `Source::layers`, `None` outside every layer.
    layer: Option<usize>,
    /// The element id (empty when it had none).
    id: String,
    path: BezPath,
    /// Colour and drawn width in mm.
    stroke: Option<(Color, f64)>,
    fill: Option<Color>,
}

/// Walks usvg's tree, collecting paths with their layer.
struct Collector<'a> {
    to_mm: Affine,
    layer_of: HashMap<&'a str, usize>,
    found: Vec<bool>,
    drawn: Vec<Drawn>,
    unpainted: usize,
    invisible: usize,
    effects: usize,
}

impl Collector<'_> {
    fn group(&mut self, group: &usvg::Group, layer: Option<usize>) -> Result<()> {
        for node in group.children() {
            match node {
                usvg::Node::Group(g) => {
                    let mut inner = layer;
                    if layer.is_none() {
                        if let Some(&i) = self.layer_of.get(g.id()) {
                            self.found[i] = true;
                            inner = Some(i);
                        }
                    }
                    if !clip_cuts_nothing(g) || g.mask().is_some() || !g.filters().is_empty() {
                        self.effects += 1;
                    }
                    self.group(g, inner)?;
                }
                usvg::Node::Path(p) => self.path(p, layer)?,
                // Counted, with their warnings, in the pre-pass.
                usvg::Node::Image(_) | usvg::Node::Text(_) => {}
            }
        }
        Ok(())
    }

    fn path(&mut self, p: &usvg::Path, layer: Option<usize>) -> Result<()> {
        if p.fill().is_none() && p.stroke().is_none() {
            self.unpainted += 1;
            return Ok(());
        }
        if !p.is_visible() {
            self.invisible += 1;
            return Ok(());
        }
        let to_page = self.to_mm * affine(p.abs_transform());
        let mut path = BezPath::new();
        let map = |q: usvg::tiny_skia_path::Point| -> Result<Point> {
            let pt = to_page * Point::new(f64::from(q.x), f64::from(q.y));
            if pt.x.abs() <= MAX_COORD && pt.y.abs() <= MAX_COORD {
                Ok(pt)
            } else {
                let id = if p.id().is_empty() { "(no id)" } else { p.id() };
                Err(Error::invalid(
                    format!("path {id}"),
                    format!(
                        "point ({:.3}, {:.3}) mm is outside ±{MAX_COORD} mm",
                        pt.x, pt.y
                    ),
                ))
            }
        };
        for seg in p.data().segments() {
            match seg {
                PathSegment::MoveTo(a) => path.move_to(map(a)?),
                PathSegment::LineTo(a) => path.line_to(map(a)?),
                PathSegment::QuadTo(a, b) => path.quad_to(map(a)?, map(b)?),
                PathSegment::CubicTo(a, b, c) => path.curve_to(map(a)?, map(b)?, map(c)?),
                PathSegment::Close => path.close_path(),
            }
        }
        // The drawn width: the stroke is scaled with the path (by the
        // geometric mean for non-uniform scales).
        let scale = to_page.determinant().abs().sqrt();
        let stroke = p.stroke().map(|s| {
            let width = round_size(f64::from(s.width().get()) * scale);
            (paint_color(s.paint()), width)
        });
        // Downstream, fills are non-zero (like an SVG without fill-rule).
        // An even-odd fill is redrawn as the same area's normalised
        // contours (holes wound against their outline): every edge of an
        // even-odd fill bounds it, so the lines drawn stay the same.
        let even_odd = p
            .fill()
            .is_some_and(|f| f.rule() == usvg::FillRule::EvenOdd);
        let path = if even_odd {
            match Region::new(path.clone(), FillRule::EvenOdd) {
                Ok(r) if !r.is_empty() => r.into_path(),
                _ => path,
            }
        } else {
            path
        };
        self.drawn.push(Drawn {
            layer,
            id: p.id().to_string(),
            path,
            stroke,
            fill: p.fill().map(|f| paint_color(f.paint())),
        });
        Ok(())
    }
}

fn affine(t: usvg::Transform) -> Affine {
    Affine::new([t.sx, t.ky, t.kx, t.sy, t.tx, t.ty].map(f64::from))
}

/// Whether the group has no clip path, or one that cuts nothing off: a
/// single rectangle (what usvg makes for the viewport of a `symbol` or
/// nested `svg`) around all of the group's geometry. Strokes may still be
/// trimmed at the edge; for a plotter only the centre line counts.
fn clip_cuts_nothing(g: &usvg::Group) -> bool {
    let Some(clip) = g.clip_path() else {
        return true;
    };
    let [usvg::Node::Path(rect)] = clip.root().children() else {
        return false;
    };
    if clip.clip_path().is_some() {
        return false;
    }
    let data = rect.data();
    let b = data.bounds();
    let on_corner = |p: &usvg::tiny_skia_path::Point| {
        (p.x == b.left() || p.x == b.right()) && (p.y == b.top() || p.y == b.bottom())
    };
    if data.points().len() < 4 || !data.points().iter().all(on_corner) {
        return false;
    }
    let to_canvas =
        affine(g.abs_transform()) * affine(clip.transform()) * affine(rect.abs_transform());
    if to_canvas.determinant().abs() < 1e-12 {
        return false;
    }
    let to_clip = to_canvas.inverse();
    let slack = 1e-4 * f64::from(b.width().max(b.height()));
    let content = g.abs_bounding_box();
    [
        (content.left(), content.top()),
        (content.right(), content.top()),
        (content.right(), content.bottom()),
        (content.left(), content.bottom()),
    ]
    .into_iter()
    .all(|(x, y)| {
        let p = to_clip * Point::new(f64::from(x), f64::from(y));
        p.x >= f64::from(b.left()) - slack
            && p.x <= f64::from(b.right()) + slack
            && p.y >= f64::from(b.top()) - slack
            && p.y <= f64::from(b.bottom()) + slack
    })
}

/// A solid colour standing for a paint: the colour itself, a gradient's
/// first stop, black for a pattern.
fn paint_color(paint: &usvg::Paint) -> Color {
    let c = match paint {
        usvg::Paint::Color(c) => *c,
        usvg::Paint::LinearGradient(g) => g
            .stops()
            .first()
            .map_or(usvg::Color::black(), |s| s.color()),
        usvg::Paint::RadialGradient(g) => g
            .stops()
            .first()
            .map_or(usvg::Color::black(), |s| s.color()),
        usvg::Paint::Pattern(_) => usvg::Color::black(),
    };
    Color::rgb(c.red, c.green, c.blue)
}

/// One future scene layer: a pen number, names and its paths (indices
/// into the drawn list, in paint order).
#[derive(Debug)]
struct Bucket {
    pen: u32,
    pen_name: String,
    layer_name: String,
    members: Vec<usize>,
    /// False for a documentation layer (its `layer_name` starts with `%`).
    plotted: bool,
}

impl Bucket {
    /// A bucket for a documentation layer labelled `label`; its pen is
    /// numbered later, after every plotted pen ([`number_unplotted`]).
    fn unplotted(label: &str) -> Bucket {
        let name = label.trim().to_string();
        Bucket {
            pen: 0,
            pen_name: name.clone(),
            layer_name: name,
            members: Vec::new(),
            plotted: false,
        }
    }
}

/// Gives each documentation layer's bucket a pen of its own: the smallest
/// numbers no other bucket uses, in document order. They come after all the
/// plotted pens are numbered, so a `%` layer never changes the numbering of
/// the layers that are plotted.
fn number_unplotted(buckets: &mut [Bucket]) {
    let mut taken: HashSet<u32> = buckets
        .iter()
        .filter(|b| b.plotted)
        .map(|b| b.pen)
        .collect();
    for bucket in buckets.iter_mut().filter(|b| !b.plotted) {
        let n = (1..)
            .find(|n| !taken.contains(n))
            .expect("some number is free");
        taken.insert(n);
        bucket.pen = n;
    }
}

/// One bucket per found top-level layer (in document order), plus one for
/// paths outside every layer.
fn by_layer(
    layers: &[LayerSource],
    collector: &Collector<'_>,
    warnings: &mut Vec<String>,
) -> Vec<Bucket> {
    // Documentation layers claim no pen number: "% 2 notes" is not pen 2.
    let labels: Vec<(Option<u32>, String)> = layers
        .iter()
        .map(|l| {
            if l.plotted {
                split_label(&l.label)
            } else {
                (None, String::new())
            }
        })
        .collect();
    let mut taken: HashSet<u32> = labels.iter().filter_map(|(n, _)| *n).collect();
    let mut next_free = || {
        let n = (1..)
            .find(|n| !taken.contains(n))
            .expect("some number is free");
        taken.insert(n);
        n
    };
    let mut buckets = Vec::new();
    let mut index_of = vec![None; layers.len()];
    for (i, (layer, (number, name))) in layers.iter().zip(labels).enumerate() {
        if !collector.found[i] {
            let why = if layer.hidden {
                "it is hidden"
            } else {
                "it is hidden or has nothing usvg could draw"
            };
            warnings.push(format!("skipped layer '{}': {why}", layer.label));
            continue;
        }
        index_of[i] = Some(buckets.len());
        if !layer.plotted {
            buckets.push(Bucket::unplotted(&layer.label));
            continue;
        }
        let pen = number.unwrap_or_else(&mut next_free);
        // The layer keeps the whole label when the rest alone would be no
        // name, or would read as a documentation layer ("3 %odd" is
        // plotted, with pen 3).
        let layer_name = if name.is_empty() || !Layer::name_is_plotted(&name) {
            layer.label.clone()
        } else {
            name.clone()
        };
        buckets.push(Bucket {
            pen,
            pen_name: name,
            layer_name,
            members: Vec::new(),
            plotted: true,
        });
    }
    let mut outside = Vec::new();
    for (k, d) in collector.drawn.iter().enumerate() {
        match d.layer.and_then(|i| index_of[i]) {
            Some(b) => buckets[b].members.push(k),
            None => outside.push(k),
        }
    }
    if !outside.is_empty() {
        let pen = next_free();
        let n = outside.len();
        let paths = if n == 1 { "path" } else { "paths" };
        warnings.push(format!(
            "{n} {paths} outside every layer went to an extra layer 'unlayered' (pen {pen})"
        ));
        buckets.push(Bucket {
            pen,
            pen_name: "unlayered".into(),
            layer_name: "unlayered".into(),
            members: outside,
            plotted: true,
        });
    }
    number_unplotted(&mut buckets);
    buckets
}

/// Splits `"3 blue"` into pen 3 and `blue`; a label without a leading pen
/// number (1–999) is all name. Whitespace before the number and
/// separators after it (whitespace, `-`, `_`, `:`) are dropped, so
/// `"3-blue"`, `"3_blue"`, `"3: blue"` and `" 3 blue"` are all pen 3 named
/// `blue`.
fn split_label(label: &str) -> (Option<u32>, String) {
    let label = label.trim();
    let digits = label.len() - label.trim_start_matches(|c: char| c.is_ascii_digit()).len();
    match label[..digits].parse::<u32>() {
        Ok(n) if PEN_NUMBERS.contains(&n) => {
            let rest = label[digits..]
                .trim_start_matches(|c: char| c.is_whitespace() || "-_:".contains(c));
            (Some(n), rest.trim_end().to_string())
        }
        _ => (None, label.to_string()),
    }
}

/// One bucket per colour (stroke, else fill), pens numbered in order of
/// first appearance; the paths of each documentation layer (`%` label)
/// stay apart, in a bucket of their own after the colours.
fn by_color(drawn: &[Drawn], layers: &[LayerSource]) -> Vec<Bucket> {
    let mut buckets: Vec<Bucket> = Vec::new();
    let mut index: HashMap<u32, usize> = HashMap::new();
    // Documentation layer (index into `layers`) → its paths.
    let mut unplotted: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for (k, d) in drawn.iter().enumerate() {
        let Some(color) = d.stroke.map(|(c, _)| c).or(d.fill) else {
            continue;
        };
        if let Some(i) = d.layer.filter(|&i| !layers[i].plotted) {
            unplotted.entry(i).or_default().push(k);
            continue;
        }
        let i = *index.entry(color_key(color)).or_insert_with(|| {
            buckets.push(Bucket {
                pen: buckets.len() as u32 + 1,
                pen_name: color.to_string(),
                layer_name: color.to_string(),
                members: Vec::new(),
                plotted: true,
            });
            buckets.len() - 1
        });
        buckets[i].members.push(k);
    }
    for (i, members) in unplotted {
        let mut bucket = Bucket::unplotted(&layers[i].label);
        bucket.members = members;
        buckets.push(bucket);
    }
    number_unplotted(&mut buckets);
    buckets
}

fn color_key(c: Color) -> u32 {
    u32::from_be_bytes([0, c.r, c.g, c.b])
}

/// The most frequent value by `key`, ties going to the one seen first.
fn most_common<T: Copy, K: std::hash::Hash + Eq>(
    values: impl IntoIterator<Item = T>,
    key: impl Fn(T) -> K,
) -> Option<T> {
    // key → (count, first position, value)
    let mut counts: HashMap<K, (usize, usize, T)> = HashMap::new();
    for (i, v) in values.into_iter().enumerate() {
        counts.entry(key(v)).or_insert((0, i, v)).0 += 1;
    }
    counts
        .into_values()
        .max_by_key(|&(n, first, _)| (n, std::cmp::Reverse(first)))
        .map(|(_, _, v)| v)
}

/// Hands out ids unique within the scene: the wanted one, else with
/// `-2`, `-3`… appended.
struct Ids(HashSet<String>);

impl Ids {
    fn unique(&mut self, wanted: &str) -> String {
        let mut id = wanted.to_string();
        let mut n = 1;
        while self.0.contains(&id) {
            n += 1;
            id = format!("{wanted}-{n}");
        }
        self.0.insert(id.clone());
        id
    }
}

/// Builds the scene. `stacked`: the buckets are in paint order (layers),
/// so the first is the furthest back; colour buckets all get depth 0.
fn assemble(
    page: Page,
    buckets: Vec<Bucket>,
    stacked: bool,
    drawn: Vec<Drawn>,
    description: Option<String>,
    warnings: &mut Vec<String>,
) -> Scene {
    // Pen number → its buckets, in ascending pen order.
    let mut of_pen: std::collections::BTreeMap<u32, Vec<&Bucket>> = Default::default();
    for bucket in &buckets {
        of_pen.entry(bucket.pen).or_default().push(bucket);
    }
    let numbers: Vec<u32> = of_pen.keys().copied().collect();

    let mut pens = Vec::new();
    for (&number, pen_buckets) in &of_pen {
        let members = || {
            pen_buckets
                .iter()
                .flat_map(|b| b.members.iter().map(|&k| &drawn[k]))
        };
        let strokes = || members().filter_map(|d| d.stroke);
        let color = most_common(strokes().map(|(c, _)| c), color_key)
            .or_else(|| most_common(members().filter_map(|d| d.fill), color_key))
            .unwrap_or(Color::BLACK);
        let width =
            most_common(strokes().map(|(_, w)| w), f64::to_bits).unwrap_or(DEFAULT_PEN_WIDTH);
        let colors: HashSet<u32> = strokes().map(|(c, _)| color_key(c)).collect();
        if colors.len() > 1 {
            warnings.push(format!(
                "pen {number} draws {} stroke colours; it takes the most common one, {color}",
                colors.len()
            ));
        }
        pens.push(Pen {
            number,
            name: pen_buckets[0].pen_name.clone(),
            color,
            width,
        });
    }

    // The writer names its pen layers `pen-N`; keep those free.
    let mut ids = Ids(numbers.iter().map(|n| format!("pen-{n}")).collect());
    let layer_ids: Vec<(String, String)> = (1..=buckets.len())
        .map(|k| {
            let id = ids.unique(&format!("layer-{k}"));
            let group = ids.unique(&format!("{id}-paths"));
            (id, group)
        })
        .collect();
    let mut drawn: Vec<Option<Drawn>> = drawn.into_iter().map(Some).collect();
    let count = buckets.len();
    let layers = buckets
        .into_iter()
        .zip(layer_ids)
        .enumerate()
        .map(|(i, (bucket, (id, group_id)))| {
            let mut content = Group::new(group_id);
            for (n, k) in bucket.members.into_iter().enumerate() {
                let d = drawn[k].take().expect("each path is in one bucket");
                let wanted = if d.id.is_empty() {
                    format!("{id}-path-{}", n + 1)
                } else {
                    d.id
                };
                content.push_path(
                    ids.unique(&wanted),
                    d.path,
                    Style {
                        fill: d.fill,
                        ..Style::default()
                    },
                );
            }
            Layer {
                id,
                name: bucket.layer_name,
                pen: bucket.pen,
                depth: if stacked { (count - 1 - i) as i32 } else { 0 },
                content,
            }
        })
        .collect();
    Scene {
        page,
        pens,
        layers,
        description,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::{to_svg, SvgOptions};
    use crate::scene::path_length;
    use crate::units::{Orientation, PaperName};
    use kurbo::{Line, PathEl, Rect, Shape};
    use proptest::prelude::*;
    use std::f64::consts::PI;

    const OPEN: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" width="200mm" height="100mm" viewBox="0 0 200 100">"#;

    /// A 200 × 100 mm document, one user unit per mm, around `body`.
    fn doc(body: &str) -> String {
        format!("{OPEN}\n{body}\n</svg>\n")
    }

    fn import(text: &str) -> Imported {
        import_svg(text, &ImportOptions::DEFAULT).unwrap_or_else(|e| panic!("{e}\n{text}"))
    }

    fn import_err(text: &str) -> Error {
        match import_svg(text, &ImportOptions::DEFAULT) {
            Ok(imported) => panic!("expected an error, got {imported:?}"),
            Err(e) => e,
        }
    }

    /// Every path in page coordinates with its pen number and style, in
    /// scene order.
    fn paths(scene: &Scene) -> Vec<(u32, BezPath, Style)> {
        let mut v = Vec::new();
        scene.visit_paths(|l, p, t| v.push((l.pen, t * p.path.clone(), p.style.clone())));
        v
    }

    /// The one path of a document made of `body`.
    fn only_path(body: &str) -> BezPath {
        let imported = import(&doc(body));
        let all = paths(&imported.scene);
        assert_eq!(all.len(), 1, "{body}: {all:?}");
        all[0].1.clone()
    }

    fn near(a: Point, b: Point, tol: f64) -> bool {
        (a - b).hypot() <= tol
    }

    fn assert_rect_near(a: Rect, b: Rect, tol: f64) {
        assert!(
            near(a.origin(), b.origin(), tol)
                && near((a.x1, a.y1).into(), (b.x1, b.y1).into(), tol),
            "{a:?} != {b:?}"
        );
    }

    #[test]
    fn nested_transforms_land_where_expected() {
        let line = only_path(
            r#"<g transform="translate(50 20)"><g transform="rotate(90)"><g transform="scale(2)">
               <line x1="0" y1="0" x2="10" y2="5" stroke="black" transform="translate(1 0)"/>
               </g></g></g>"#,
        );
        // (1, 0) → scale 2 → (2, 0) → rotate 90° → (0, 2) → translate → (50, 22);
        // (11, 5) → (22, 10) → (-10, 22) → (40, 42).
        let els = line.elements();
        assert!(
            matches!(els[0], PathEl::MoveTo(p) if near(p, (50.0, 22.0).into(), 1e-4)),
            "{els:?}"
        );
        assert!(
            matches!(els[1], PathEl::LineTo(p) if near(p, (40.0, 42.0).into(), 1e-4)),
            "{els:?}"
        );
        assert_eq!(els.len(), 2);
    }

    #[test]
    fn basic_shapes_and_arcs_have_their_analytic_lengths() {
        let ellipse = |a: f64, b: f64| {
            // Ramanujan's second approximation: ~1e-9 relative error here.
            let h = ((a - b) / (a + b)).powi(2);
            PI * (a + b) * (1.0 + 3.0 * h / (10.0 + (4.0 - 3.0 * h).sqrt()))
        };
        // The rotated ellipse: centre (100, 50), semi-axes 30 and 10 at 30°.
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let (ex, ey) = (30.0 * c, 30.0 * s);
        let rotated = format!(
            "M {} {} A 30 10 30 0 1 {} {} A 30 10 30 0 1 {} {} Z",
            100.0 + ex,
            50.0 + ey,
            100.0 - ex,
            50.0 - ey,
            100.0 + ex,
            50.0 + ey
        );
        let cases: Vec<(String, f64)> = vec![
            (
                r#"<rect x="10" y="10" width="40" height="20"/>"#.into(),
                120.0,
            ),
            (
                r#"<rect x="10" y="10" width="40" height="20" rx="5"/>"#.into(),
                120.0 - 8.0 * 5.0 + 2.0 * PI * 5.0,
            ),
            (
                r#"<circle cx="50" cy="50" r="10"/>"#.into(),
                2.0 * PI * 10.0,
            ),
            (
                r#"<ellipse cx="50" cy="50" rx="20" ry="10"/>"#.into(),
                ellipse(20.0, 10.0),
            ),
            (r#"<line x1="0" y1="0" x2="30" y2="40"/>"#.into(), 50.0),
            (r#"<polyline points="0,0 30,0 30,40"/>"#.into(), 70.0),
            (r#"<polygon points="0,0 30,0 30,40"/>"#.into(), 120.0),
            (
                r#"<path d="M 10 50 A 20 20 0 0 1 50 50"/>"#.into(),
                PI * 20.0,
            ),
            (
                r#"<path d="m 10 80 a 5 5 0 0 0 10 0 l 0 10"/>"#.into(),
                PI * 5.0 + 10.0,
            ),
            (format!(r#"<path d="{rotated}"/>"#), ellipse(30.0, 10.0)),
        ];
        for (shape, expected) in cases {
            let shape = shape.replace("/>", r#" stroke="black" fill="none"/>"#);
            let length = path_length(&only_path(&shape));
            assert!(
                ((length - expected) / expected).abs() < 1e-3,
                "{shape}: length {length}, expected {expected}"
            );
        }
        // Arcs are where they should be: the upper half circle from (10, 50)
        // to (50, 50) reaches up to y = 30.
        let arc =
            only_path(r#"<path d="M 10 50 A 20 20 0 0 1 50 50" stroke="black" fill="none"/>"#);
        assert_rect_near(arc.bounding_box(), Rect::new(10.0, 30.0, 50.0, 50.0), 1e-3);
    }

    #[test]
    fn use_of_defs_and_symbol_is_resolved() {
        let imported = import(&doc(
            r##"<defs><path id="tri" d="M0 0 L10 0 L0 10 Z" stroke="black" fill="none"/></defs>
               <symbol id="box" viewBox="0 0 10 10">
                 <rect width="10" height="10" stroke="red" fill="none"/>
               </symbol>
               <use xlink:href="#tri" x="100" y="50"/>
               <use href="#box" x="20" y="30" width="20" height="20"/>
               <use href="#tri" transform="translate(150 0) scale(0.5)"/>"##,
        ));
        let all = paths(&imported.scene);
        assert_eq!(all.len(), 3, "{all:?}");
        // Document order is kept within the black pen: both triangles.
        assert_eq!(all[0].0, 1);
        assert_rect_near(
            all[0].1.bounding_box(),
            Rect::new(100.0, 50.0, 110.0, 60.0),
            1e-4,
        );
        assert_rect_near(
            all[1].1.bounding_box(),
            Rect::new(150.0, 0.0, 155.0, 5.0),
            1e-4,
        );
        // The symbol's viewBox scales it to the use's 20 × 20.
        assert_eq!(all[2].0, 2);
        assert_rect_near(
            all[2].1.bounding_box(),
            Rect::new(20.0, 30.0, 40.0, 50.0),
            1e-4,
        );
        assert_eq!(imported.scene.pens[1].color, Color::rgb(255, 0, 0));
        assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
    }

    #[test]
    fn inkscape_layers_become_numbered_pens() {
        let imported = import(&doc(
            r##"<g id="L"><path d="M0 90 L10 90" stroke="#008000" fill="none"/></g>
            <g inkscape:groupmode="layer" id="layer1" inkscape:label="3 blue"
               style="stroke:#0000ff;stroke-width:0.5;fill:none">
              <path d="M0 0 L10 0"/>
              <g transform="translate(0 5)"><path id="second" d="M0 0 L10 0"/></g>
              <g inkscape:groupmode="layer" inkscape:label="sub-layer"><path d="M0 9 L10 9"/></g>
            </g>
            <g inkscape:groupmode="layer" inkscape:label="Outline" stroke="#ff0000"
               stroke-width="0.25" fill="none">
              <rect x="1" y="1" width="5" height="5"/>
            </g>
            <g inkscape:groupmode="layer" id="layer3" inkscape:label="1 black" stroke="black"
               fill="none" stroke-width="2" transform="scale(0.5)">
              <circle cx="10" cy="10" r="4"/>
            </g>
            <g inkscape:groupmode="layer" id="hid" inkscape:label="4 hidden"
               style="display: none" stroke="black">
              <path d="M0 0 L1 1"/>
            </g>
            <g inkscape:groupmode="layer" id="L" inkscape:label="2 - green" stroke="#008000">
              <path d="M0 50 L10 50" fill="none"/>
            </g>"##,
        ));
        let scene = &imported.scene;
        let pens: Vec<(u32, &str, String, f64)> = scene
            .pens
            .iter()
            .map(|p| (p.number, p.name.as_str(), p.color.to_string(), p.width))
            .collect();
        // "Outline" takes the smallest free number (5); the unlayered path
        // comes after it (6); the hidden layer's pen 4 is unused. Without a
        // stroke-width, SVG's default of one user unit (here 1 mm) holds.
        assert_eq!(
            pens,
            [
                (1, "black", "#000000".to_string(), 1.0),
                (2, "green", "#008000".to_string(), 1.0),
                (3, "blue", "#0000ff".to_string(), 0.5),
                (5, "Outline", "#ff0000".to_string(), 0.25),
                (6, "unlayered", "#008000".to_string(), 1.0),
            ]
        );
        let layers: Vec<(&str, u32, i32, usize)> = scene
            .layers
            .iter()
            .map(|l| (l.name.as_str(), l.pen, l.depth, l.content.children.len()))
            .collect();
        assert_eq!(
            layers,
            [
                ("blue", 3, 4, 3),
                ("Outline", 5, 3, 1),
                ("black", 1, 2, 1),
                ("green", 2, 1, 1),
                ("unlayered", 6, 0, 1),
            ]
        );
        // The layer's transform is baked in: circle at (5, 5), radius 2.
        let circle = &paths(scene)[4].1;
        assert_rect_near(circle.bounding_box(), Rect::new(3.0, 3.0, 7.0, 7.0), 1e-4);
        // Element ids survive; the rest are made from the layer's.
        let ids: Vec<String> = scene.layers[0]
            .content
            .children
            .iter()
            .map(|n| match n {
                crate::scene::Node::Path(p) => p.id.clone(),
                crate::scene::Node::Group(g) => panic!("flat layers, got {}", g.id),
            })
            .collect();
        assert_eq!(ids, ["layer-1-path-1", "second", "layer-1-path-3"]);
        assert_eq!(
            imported.warnings,
            [
                "skipped layer '4 hidden': it is hidden",
                "1 path outside every layer went to an extra layer 'unlayered' (pen 6)",
            ]
        );
    }

    #[test]
    fn without_layers_pens_follow_stroke_colours() {
        let imported = import(&doc(r##"<path d="M0 0 L10 0" stroke="red"/>
               <path d="M0 1 L10 1" stroke="#00f" stroke-width="0.7" fill="none"/>
               <path d="M0 2 L10 2" stroke="rgb(255,0,0)" fill="none"/>
               <rect x="0" y="5" width="5" height="5" fill="green"/>
               <path d="M0 3 L10 3" fill="none"/>
               <path d="M0 4 L10 4" fill="none" stroke="none"/>
               <path d="M0 4 L10 4" stroke="red" fill="none" visibility="hidden"/>"##));
        let scene = &imported.scene;
        let pens: Vec<(u32, String, String, f64)> = scene
            .pens
            .iter()
            .map(|p| (p.number, p.name.clone(), p.color.to_string(), p.width))
            .collect();
        assert_eq!(
            pens,
            [
                (1, "#ff0000".into(), "#ff0000".into(), 1.0),
                (2, "#0000ff".into(), "#0000ff".into(), 0.7),
                (3, "#008000".into(), "#008000".into(), 0.3),
            ]
        );
        assert_eq!(scene.pen_stats(1).paths, 2);
        assert_eq!(scene.pen_stats(2).paths, 1);
        assert_eq!(scene.pen_stats(3).paths, 1);
        assert!(scene.layers.iter().all(|l| l.depth == 0));
        // The fill-only rect is a region; SVG's default black fill stays on
        // the first line, as the renderer would paint it.
        let all = paths(scene);
        assert_eq!(all[3].2.fill, Some(Color::rgb(0, 128, 0)));
        assert_eq!(all[0].2.fill, Some(Color::BLACK));
        assert_eq!(all[1].2.fill, None);
        assert_eq!(
            imported.warnings,
            [
                "skipped 2 paths: no fill and no stroke",
                "skipped 1 path: hidden by `visibility`",
            ]
        );
    }

    #[test]
    fn ring_with_a_hole_stays_one_path_with_its_fill() {
        let imported = import(&doc(
            r##"<path fill-rule="evenodd" fill="#336699" stroke="black" stroke-width="0.2"
                d="M0 0 H40 V40 H0 Z M10 10 H30 V30 H10 Z"/>"##,
        ));
        let all = paths(&imported.scene);
        assert_eq!(all.len(), 1);
        let (pen, ring, style) = &all[0];
        assert_eq!(*pen, 1);
        assert_eq!(style.fill, Some(Color::rgb(0x33, 0x66, 0x99)));
        let moves = ring
            .elements()
            .iter()
            .filter(|e| matches!(e, PathEl::MoveTo(_)))
            .count();
        let closes = ring
            .elements()
            .iter()
            .filter(|e| matches!(e, PathEl::ClosePath))
            .count();
        assert_eq!((moves, closes), (2, 2), "{ring:?}");
        assert_rect_near(ring.bounding_box(), Rect::new(0.0, 0.0, 40.0, 40.0), 1e-4);
        let mut second = ring.elements().iter().filter_map(|e| match e {
            PathEl::MoveTo(p) => Some(*p),
            _ => None,
        });
        assert!(near(second.next_back().unwrap(), (10.0, 10.0).into(), 1e-4));
        assert_eq!(imported.scene.pens[0].width, 0.2);
    }

    #[test]
    fn even_odd_ring_wound_one_way_keeps_its_hole() {
        // Both contours clockwise: solid under non-zero, a ring under
        // even-odd (as the file says).
        let imported = import(&doc(r##"<path fill-rule="evenodd" fill="#336699"
                d="M0 0 H40 V40 H0 Z M10 10 H30 V10 H30 V30 H10 Z"/>"##));
        let all = paths(&imported.scene);
        assert_eq!(all.len(), 1);
        let region = Region::new(all[0].1.clone(), FillRule::NonZero).unwrap();
        assert!(
            (region.area() - (1600.0 - 400.0)).abs() < 1e-3,
            "{}",
            region.area()
        );
        assert!(!region.contains((20.0, 20.0).into()));
    }

    #[test]
    fn inkscape_file_with_sublayer_hidden_layer_and_text() {
        let imported = import(include_str!(
            "../../tests/fixtures/import/inkscape_layers.svg"
        ));
        let scene = &imported.scene;
        assert_eq!((scene.page.width, scene.page.height), (210.0, 297.0));
        let pens: Vec<(u32, &str, String, f64)> = scene
            .pens
            .iter()
            .map(|p| (p.number, p.name.as_str(), p.color.to_string(), p.width))
            .collect();
        assert_eq!(
            pens,
            [
                (1, "black outline", "#000000".to_string(), 0.5),
                (2, "red", "#ff0000".to_string(), 0.3),
            ]
        );
        // The sub-layer's wave belongs to pen 1.
        assert_eq!(scene.pen_stats(1).paths, 3);
        assert_eq!(scene.pen_stats(2).paths, 1);
        let all = paths(scene);
        assert_eq!(all[1].2.fill, Some(Color::rgb(0xd4, 0xaa, 0x00)));
        // The layer's translate(10,-5) is baked in.
        assert_rect_near(
            all[3].1.bounding_box(),
            Rect::new(135.0, 30.0, 185.0, 80.0),
            1e-3,
        );
        assert_eq!(
            imported.warnings,
            [
                "skipped 1 text element: text is not imported (convert it to paths \
                 first, e.g. Inkscape's Path > Object to Path)",
                "skipped layer '3 guides': it is hidden",
            ]
        );
    }

    #[test]
    fn axidraw_documentation_layers_are_imported_but_not_plotted() {
        let imported = import(include_str!(
            "../../tests/fixtures/import/axidraw_layers.svg"
        ));
        assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
        let scene = &imported.scene;
        let pens: Vec<(u32, &str, String, f64)> = scene
            .pens
            .iter()
            .map(|p| (p.number, p.name.as_str(), p.color.to_string(), p.width))
            .collect();
        // The documentation layers' pens come after the plotted ones.
        assert_eq!(
            pens,
            [
                (1, "black", "#000000".to_string(), 0.3),
                (2, "red", "#ff0000".to_string(), 0.5),
                (3, "%guides", "#00aaff".to_string(), 0.2),
                (4, "% 2 notes", "#888888".to_string(), 0.1),
            ]
        );
        let layers: Vec<(&str, u32, i32, bool, usize)> = scene
            .layers
            .iter()
            .map(|l| {
                let n = l.content.children.len();
                (l.name.as_str(), l.pen, l.depth, l.is_plotted(), n)
            })
            .collect();
        assert_eq!(
            layers,
            [
                ("%guides", 3, 3, false, 2),
                ("black", 1, 2, true, 3),
                ("red", 2, 1, true, 1),
                ("% 2 notes", 4, 0, false, 1),
            ]
        );
        // The "%" sub-layer's path belongs to pen 1 and is plotted; the
        // frame keeps its fill.
        assert_eq!(scene.pen_stats(1).paths, 3);
        let all = paths(scene);
        assert_eq!(all[0].2.fill, Some(Color::rgb(0xe8, 0xf4, 0xff)));
        assert!((path_length(&all[0].1) - 560.0).abs() < 1e-3);
    }

    #[test]
    fn layer_labels_follow_axidraw() {
        let layer = |label: &str, y: f64| {
            format!(
                r#"<g inkscape:groupmode="layer" inkscape:label="{label}" stroke="black">
                   <path d="M0 {y} L10 {y}"/></g>"#
            )
        };
        let labels = [
            "%notes",
            "3 red",
            "% 2 guides",
            "7-green",
            "Outline",
            "5 %odd",
            "  %  spaced",
            "0 zero",
            "!2 pause",
            "9",
        ];
        let body: String = labels
            .iter()
            .enumerate()
            .map(|(i, l)| layer(l, i as f64))
            .collect();
        let imported = import(&doc(&body));
        assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
        let got: Vec<(&str, u32, &str, bool)> = imported
            .scene
            .layers
            .iter()
            .map(|l| {
                let pen = imported.scene.pen(l.pen).unwrap();
                (l.name.as_str(), l.pen, pen.name.as_str(), l.is_plotted())
            })
            .collect();
        // Numbered: 3, 7, 5, 9. Free numbers in document order: plotted
        // layers first (1, 2, 4), then the documentation layers (6, 8, 10).
        assert_eq!(
            got,
            [
                ("%notes", 6, "%notes", false),
                ("red", 3, "red", true),
                ("% 2 guides", 8, "% 2 guides", false),
                ("green", 7, "green", true),
                ("Outline", 1, "Outline", true),
                ("5 %odd", 5, "%odd", true),
                ("%  spaced", 10, "%  spaced", false),
                ("0 zero", 2, "0 zero", true),
                ("!2 pause", 4, "!2 pause", true),
                ("9", 9, "", true),
            ]
        );

        // Grouping by colour still keeps each documentation layer apart.
        let by_color = import_svg(
            &doc(&body),
            &ImportOptions::DEFAULT.with_pens(PenGrouping::StrokeColor),
        )
        .unwrap();
        let got: Vec<(&str, u32, bool, usize)> = by_color
            .scene
            .layers
            .iter()
            .map(|l| {
                let n = l.content.children.len();
                (l.name.as_str(), l.pen, l.is_plotted(), n)
            })
            .collect();
        assert_eq!(
            got,
            [
                ("#000000", 1, true, 7),
                ("%notes", 2, false, 1),
                ("% 2 guides", 3, false, 1),
                ("%  spaced", 4, false, 1),
            ]
        );
    }

    #[test]
    fn documentation_layers_round_trip_through_the_writer() {
        let mut original = sample_scene();
        let mut guides = Group::new("guides");
        guides.push_path(
            "frame",
            Rect::new(-5.0, -5.0, 100.0, 150.0).into_path(0.1),
            Style::default(),
        );
        original.layers.insert(
            1,
            Layer {
                id: "guides-layer".into(),
                name: "%guides & notes".into(),
                pen: 1,
                depth: 9,
                content: guides,
            },
        );
        let svg = to_svg(&original, &SvgOptions::DEFAULT.with_preview(true));
        assert!(
            svg.contains("inkscape:label=\"%guides &amp; notes\""),
            "{svg}"
        );
        let imported = import(&svg);
        assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
        let scene = &imported.scene;
        // The plotted pens (1 and 7) are as before; the guides get a pen of
        // their own, the smallest free number, with pen 1's colour and width.
        assert_eq!(
            [scene.pens[0].clone(), scene.pens[2].clone()],
            original.pens[..]
        );
        let pen = &scene.pens[1];
        assert_eq!(
            (pen.number, pen.name.as_str(), pen.color, pen.width),
            (2, "%guides & notes", Color::BLACK, 0.3)
        );
        let guides = &scene.layers[0];
        assert_eq!(
            (guides.name.as_str(), guides.pen, guides.is_plotted()),
            ("%guides & notes", 2, false)
        );
        let frame = &paths(scene)[0].1;
        assert_rect_near(
            frame.bounding_box(),
            Rect::new(5.0, 5.0, 110.0, 160.0),
            1e-4,
        );
        // Plotted paths are unchanged by the documentation layer.
        assert_eq!(
            scene.path_count() - 1,
            import(&to_svg(&sample_scene(), &SvgOptions::DEFAULT))
                .scene
                .path_count()
        );
        // And once more: the label survives a second round.
        let again = to_svg(scene, &SvgOptions::DEFAULT.with_preview(true));
        assert!(again.contains("inkscape:label=\"%guides &amp; notes\""));
        assert!(!import(&again).scene.layers[0].is_plotted());
    }

    #[test]
    fn clipping_that_cuts_is_reported() {
        let imported = import(&doc(
            r##"<clipPath id="c"><rect x="0" y="0" width="5" height="5"/></clipPath>
               <path d="M0 0 L10 10" stroke="black" clip-path="url(#c)"/>
               <svg x="50" y="50" width="10" height="10" viewBox="0 0 1 1">
                 <path d="M0 0 L1 1" stroke="black"/>
               </svg>"##,
        ));
        // The path is imported whole; the nested svg's viewport clips nothing.
        assert_eq!(imported.scene.path_count(), 2);
        assert!(
            (paths(&imported.scene)[0].1.bounding_box().x1 - 10.0).abs() < 1e-4,
            "unclipped"
        );
        assert_eq!(
            imported.warnings,
            ["clip paths, masks and filters are not applied (1 group): \
              their paths are imported whole"]
        );
    }

    #[test]
    fn text_and_images_are_skipped_with_warnings() {
        let imported = import(&doc(r#"<text x="10" y="10">Hello</text>
               <g><text x="10" y="20"><tspan>again</tspan></text></g>
               <image href="data:image/png;base64,iVBORw0KGgo=" width="10" height="10"/>
               <image xlink:href="/etc/passwd" width="10" height="10"/>
               <path d="M0 0 L5 5" stroke="black"/>"#));
        assert_eq!(imported.scene.path_count(), 1);
        assert_eq!(imported.warnings.len(), 2, "{:?}", imported.warnings);
        assert!(imported.warnings[0].starts_with("skipped 2 text elements: "));
        assert!(imported.warnings[1].starts_with("skipped 2 images: "));
    }

    #[test]
    fn bad_input_is_a_clear_error() {
        let cases: [(&str, &str); 9] = [
            ("", "empty"),
            (" \n\t ", "empty"),
            ("<notsvg/>", "root element is <notsvg>"),
            ("hello", "not well-formed XML"),
            (
                r#"<svg xmlns="http://www.w3.org/2000/svg"><g>"#,
                "not well-formed XML",
            ),
            (&doc("<path d='M0 0 L1 1'")[..60], "not well-formed XML"),
            (
                r#"<svg xmlns="http://example.com/not-svg"/>"#,
                "not an SVG document",
            ),
            (r#"<?xml version="1.0"?>"#, "not well-formed XML"),
            (
                r#"<svg xmlns="http://www.w3.org/2000/svg" width="0" height="10"/>"#,
                "no usable size",
            ),
        ];
        for (text, expected) in cases {
            let e = import_err(text);
            assert!(e.to_string().contains(expected), "{text:?}: {e}");
        }
        // Positions are reported once, in `at`.
        let e = import_err("<svg xmlns=\"http://www.w3.org/2000/svg\">\n  <g>\n</svg>");
        let Error::Parse { at: Some(at), .. } = &e else {
            panic!("{e:?}")
        };
        assert_eq!(at.line, 3);
        assert_eq!(e.to_string().matches(&at.to_string()).count(), 1, "{e}");
    }

    #[test]
    fn huge_and_nan_coordinates_are_rejected() {
        for (body, expected) in [
            (
                r#"<path id="p" d="M 0 0 L NaN 5" stroke="black"/>"#,
                "<path id=\"p\"> d",
            ),
            (r#"<path d="M0-1e39L5 5" stroke="black"/>"#, "'-1e39'"),
            (r#"<circle r="inf" stroke="black"/>"#, "<circle> r"),
            (
                r#"<g transform="scale(1e400)"><path d="M0 0L1 1" stroke="black"/></g>"#,
                "'1e400'",
            ),
            (
                r#"<path id="far" d="M 0 0 L 1e9 0" stroke="black"/>"#,
                "path far: point (1000000",
            ),
            (
                r#"<g transform="scale(1e6)"><path d="M0 0L1 1" stroke="black"/></g>"#,
                "outside",
            ),
        ] {
            let e = import_err(&doc(body));
            assert!(matches!(e, Error::Invalid { .. }), "{body}: {e:?}");
            assert!(e.to_string().contains(expected), "{body}: {e}");
        }
        assert_eq!(bad_number("M.5.5 1e5-2E+3"), None);
        assert_eq!(bad_number("translate(1,2) scale(-1e38)"), None);
        assert_eq!(bad_number("1-1e39"), Some("-1e39"));
        assert_eq!(bad_number("M 0 0 L Infinity 3"), Some("Infinity"));
    }

    #[test]
    fn px_and_mm_documents_scale_right() {
        let px = import(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="50">
               <line x1="0" y1="0" x2="96" y2="0" stroke="black"/></svg>"#,
        );
        let page = px.scene.page;
        assert!((page.width - 26.458_333).abs() < 1e-6, "{page:?}");
        assert!((page.height - 13.229_167).abs() < 1e-6, "{page:?}");
        assert_eq!(page.margins, Margins::default());
        assert!((px.scene.stats().pen_down_mm - 25.4).abs() < 1e-4);

        let scaled = import(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="50mm" viewBox="0 0 1000 500">
               <line x1="0" y1="0" x2="1000" y2="0" stroke="black" stroke-width="10"/></svg>"#,
        );
        assert_eq!(
            (scaled.scene.page.width, scaled.scene.page.height),
            (100.0, 50.0)
        );
        assert!((scaled.scene.stats().pen_down_mm - 100.0).abs() < 1e-4);
        assert_eq!(scaled.scene.pens[0].width, 1.0);

        let inches = import(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="4in" height="2in">
               <line x1="0" y1="0" x2="96" y2="0" stroke="black"/></svg>"#,
        );
        assert_eq!(
            (inches.scene.page.width, inches.scene.page.height),
            (101.6, 50.8)
        );
        assert!((inches.scene.stats().pen_down_mm - 25.4).abs() < 1e-4);

        // moyo's own page: one user unit is one millimetre.
        let a3 = import(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="420mm" height="297mm" viewBox="0 0 420 297">
               <path d="M 0 0 L 420 297" stroke="black"/></svg>"#,
        );
        assert_eq!((a3.scene.page.width, a3.scene.page.height), (420.0, 297.0));
        let els = paths(&a3.scene)[0].1.elements().to_vec();
        assert!(matches!(els[1], PathEl::LineTo(p) if near(p, (420.0, 297.0).into(), 1e-4)));

        // An old Illustrator file at 72 px per inch.
        let options = ImportOptions::DEFAULT.with_px_per_inch(72.0);
        let old = import_svg(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="72" height="144"/>"#,
            &options,
        )
        .unwrap();
        assert_eq!((old.scene.page.width, old.scene.page.height), (25.4, 50.8));
        assert_eq!(old.scene.path_count(), 0);
    }

    #[test]
    fn options_validate_and_deserialize() {
        for bad in [0.0, -96.0, f64::NAN, f64::INFINITY] {
            let e =
                import_svg(&doc(""), &ImportOptions::DEFAULT.with_px_per_inch(bad)).unwrap_err();
            assert!(
                e.to_string()
                    .starts_with("px_per_inch: must be a positive number"),
                "{e}"
            );
        }
        let options: ImportOptions =
            serde_json::from_str(r#"{"px_per_inch": 72, "pens": "stroke_color"}"#).unwrap();
        assert_eq!(
            options,
            ImportOptions::DEFAULT
                .with_px_per_inch(72.0)
                .with_pens(PenGrouping::StrokeColor)
        );
        let defaults: ImportOptions = serde_json::from_str("{}").unwrap();
        assert_eq!(defaults, ImportOptions::default());
        assert!(serde_json::from_str::<ImportOptions>(r#"{"dpi": 72}"#).is_err());

        // Grouping by colour ignores the layers.
        let layered = doc(r##"<g inkscape:groupmode="layer" inkscape:label="1 a">
                 <path d="M0 0 L1 0" stroke="red"/><path d="M0 1 L1 1" stroke="blue"/></g>
               <g inkscape:groupmode="layer" inkscape:label="2 b"><path d="M0 2 L1 2" stroke="red"/></g>"##);
        let auto = import(&layered);
        assert_eq!(auto.scene.pen_stats(1).paths, 2);
        assert_eq!(
            auto.warnings,
            ["pen 1 draws 2 stroke colours; it takes the most common one, #ff0000"]
        );
        let by_color = import_svg(
            &layered,
            &ImportOptions::DEFAULT.with_pens(PenGrouping::StrokeColor),
        )
        .unwrap();
        assert_eq!(by_color.scene.pen_stats(1).paths, 2);
        assert_eq!(by_color.scene.pens[1].color, Color::rgb(0, 0, 255));
    }

    /// A scene like the writer's own test scene: two pens, three layers at
    /// different depths, margins, a scaled group with a filled quad/cubic
    /// petal, and a description.
    fn sample_scene() -> Scene {
        let mut front = Group::new("front");
        front.push_path(
            "stem",
            Line::new((0.0, 0.0), (20.0, 10.0)).into_path(0.1),
            Style::default(),
        );
        let mut leaf = BezPath::new();
        leaf.move_to((5.0, 5.0));
        leaf.quad_to((7.5, 0.0), (10.0, 5.0));
        leaf.curve_to((9.0, 7.0), (6.0, 7.0), (5.0, 5.0));
        leaf.close_path();
        let mut flower = Group::new("flower");
        flower.transform =
            Affine::translate((30.0, 40.0)) * Affine::rotate(0.3) * Affine::scale(0.5);
        flower.push_path(
            "petal",
            leaf,
            Style {
                fill: Some(Color::rgb(0xdc, 0x14, 0x3c)),
                ..Style::default()
            },
        );
        front.push_group(flower);
        let mut back = Group::new("back");
        back.push_path(
            "box",
            Rect::new(0.0, 0.0, 100.0, 50.0).into_path(0.1),
            Style::default(),
        );
        back.push_path(
            "ring",
            {
                let mut ring = Rect::new(10.0, 10.0, 40.0, 40.0).into_path(0.1);
                ring.extend(kurbo::Circle::new((25.0, 25.0), 5.0).path_elements(0.1));
                ring
            },
            Style {
                fill: Some(Color::rgb(1, 2, 3)),
                ..Style::default()
            },
        );
        let mut sky = Group::new("sky");
        sky.push_path(
            "cloud",
            Line::new((1.0 / 3.0, -0.0001), (2.0 / 3.0, 1.0)).into_path(0.1),
            Style::default(),
        );
        let pen = |number, name: &str, color, width| Pen {
            number,
            name: name.into(),
            color,
            width,
        };
        let layer = |id: &str, pen, depth, content| Layer {
            id: id.into(),
            name: id.into(),
            pen,
            depth,
            content,
        };
        Scene {
            page: Page::named(PaperName::A5, Orientation::Portrait, Margins::uniform(10.0)),
            pens: vec![
                pen(1, "black", Color::BLACK, 0.3),
                pen(7, "red & \"fine\"", Color::rgb(255, 0, 0), 0.25),
            ],
            layers: vec![
                layer("sky-layer", 7, 1, sky),
                layer("front-layer", 1, 0, front),
                layer("back-layer", 1, 2, back),
            ],
            description: Some("seed = 7\n[page]\nsize = \"A5\"\n".into()),
        }
    }

    #[test]
    fn moyo_svg_round_trips() {
        let original = sample_scene();
        let svg = to_svg(&original, &SvgOptions::DEFAULT);
        let imported = import(&svg);
        assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
        let scene = &imported.scene;
        assert_eq!(scene.pens, original.pens);
        assert_eq!(scene.description, original.description);
        assert_eq!(
            (scene.page.width, scene.page.height),
            (original.page.width, original.page.height)
        );
        // The writer puts each pen's layers back to front; so does the import.
        let mut expected: Vec<(u32, BezPath, Style)> = Vec::new();
        for pen in [1, 7] {
            for layer in original
                .layers_back_to_front()
                .into_iter()
                .filter(|l| l.pen == pen)
            {
                layer
                    .content
                    .visit_paths(original.page_transform(), &mut |p, t| {
                        expected.push((pen, t * p.path.clone(), p.style.clone()))
                    });
            }
        }
        let got = paths(scene);
        assert_eq!(got.len(), expected.len());
        for ((pen_a, a, style_a), (pen_b, b, style_b)) in got.iter().zip(&expected) {
            assert_eq!((pen_a, style_a), (pen_b, style_b));
            assert_eq!(a.elements().len(), b.elements().len(), "{a:?} vs {b:?}");
            for (ea, eb) in a.elements().iter().zip(b.elements()) {
                let points = |e: &PathEl| -> Vec<Point> {
                    match *e {
                        PathEl::MoveTo(p) | PathEl::LineTo(p) => vec![p],
                        PathEl::QuadTo(p, q) => vec![p, q],
                        PathEl::CurveTo(p, q, r) => vec![p, q, r],
                        PathEl::ClosePath => vec![],
                    }
                };
                assert_eq!(std::mem::discriminant(ea), std::mem::discriminant(eb));
                for (pa, pb) in points(ea).into_iter().zip(points(eb)) {
                    assert!(near(pa, pb, 1e-3), "{pa:?} vs {pb:?}");
                }
            }
        }
        // And once more: importing the re-export changes nothing.
        let again = import(&to_svg(scene, &SvgOptions::DEFAULT.with_precision(6)));
        assert_eq!(again.scene.pens, scene.pens);
        assert_eq!(again.scene.path_count(), scene.path_count());
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn truncated_or_mangled_svg_never_panics(
            cut in 0usize..4000,
            at in 0usize..4000,
            junk in "[ -~]{0,12}",
        ) {
            let svg = to_svg(&sample_scene(), &SvgOptions::DEFAULT);
            let mut text = svg[..cut.min(svg.len())].to_string();
            text.insert_str(at.min(text.len()), &junk);
            let _ = import_svg(&text, &ImportOptions::DEFAULT);
        }

        #[test]
        fn arbitrary_text_never_panics(text in "\\PC{0,300}") {
            let _ = import_svg(&text, &ImportOptions::DEFAULT);
        }
    }
}
