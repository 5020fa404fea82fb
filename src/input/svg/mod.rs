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
//!   smallest number no other layer claims. Without layers
//!   ([`PenGrouping::Auto`]), or always ([`PenGrouping::StrokeColor`]),
//!   paths are grouped by stroke colour (fill colour when unstroked): one
//!   pen per colour, numbered in order of first appearance, but at most
//!   [`ImportOptions::max_pens`] pens (8 by default): when there are more
//!   colours, they are clustered into that many pens by nearest colour in
//!   OKLab (Björn Ottosson's perceptual space; an sRGB to OKLab conversion
//!   of a few lines), and one warning says how many colours went into how
//!   many pens. The clustering is k-means with a deterministic start: the
//!   most used colour (ties to the first seen), then each time the colour
//!   farthest from every centre chosen so far (maximin), then weighted
//!   Lloyd steps (each centre to the use-weighted mean of its colours,
//!   each colour to its nearest centre) until nothing moves, at most 32
//!   rounds and fewer when colours times pens is very large (100,000
//!   colours into 999 pens), so that the work stays bounded. Maximin
//!   rather than "the N most used colours" because a drawing's most used
//!   colours are often shades of one hue, which would leave another hue
//!   without a pen of its own; k-means rather than merging the two nearest
//!   clusters until N remain because it stays linear in the colours (a
//!   logo can have thousands). `max_pens` 0 keeps one pen per colour and
//!   refuses a file with more than 999. [`PenGrouping::Single`] puts every
//!   plotted path on pen 1. A file with layers is not clustered — its
//!   layers are its pens — but it may not need pen numbers past 999 (more
//!   than 999 layers, or 999 numbered ones and more): that is an error, not
//!   a silent renumbering, since a layer's number is the pen its author
//!   chose. A pen's colour and width are the most common stroke colour and
//!   drawn stroke width of its paths (for a merged pen, its most used
//!   colour); a pen from layers that draws several stroke colours says so
//!   in a warning.
//! - **Layer names**, following AxiDraw's layer control:
//!   - Leading whitespace is ignored. A label whose first character is then
//!     `%` marks a *documentation layer*: it is imported whole (its
//!     sub-layers included) as a scene layer named by the trimmed label
//!     (`"%guides"`, `"% 2 notes"`), which is therefore not plotted
//!     ([`Layer::is_plotted`](crate::scene::Layer::is_plotted)): it survives in SVG output and the preview,
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
//!     `"0 red"`) has no pen number: the whole label is the name, and the
//!     pen takes a free number. AxiDraw's other codes stay in the name,
//!     where the G-code and HPGL writers act on them
//!     ([`LayerCodes`](crate::scene::LayerCodes)): a `!` before the number
//!     (`"!2 pause"` is pen 2 named `!pause`) and `+S`, `+H`, `+D` after it
//!     (`"3+S40 fine"` is pen 3 named `+S40 fine`; moyo also reads them
//!     after a space, where AxiDraw takes them for text).
//!   - Sub-layers are not parsed, as in AxiDraw 3 and later: they belong to
//!     their top-level layer, so a `%` sub-layer inside a plotted layer is
//!     plotted with it, and everything inside a `%` layer is not plotted.
//!   - A hidden layer (`display:none`) is skipped with a warning, `%` or
//!     not.
//! - **What cannot be seen is not imported**, and each kind is counted in
//!   one warning:
//!   - `display: none` (as an attribute or in `style`) on an element or a
//!     group: the element with all it holds, counted once. A hidden
//!     top-level layer has a warning of its own (above); content only
//!     drawn by reference (`defs`, `symbol`, clip paths, masks, markers,
//!     patterns) is not counted.
//!   - `visibility: hidden` (or `collapse`): the path, unless it makes
//!     itself `visible` again inside a hidden group.
//!   - Invisible paint: a stroke or a fill is invisible when its colour is
//!     fully transparent (`transparent`, `rgba(…, 0)`, `#rrggbb00`, a
//!     gradient all of whose stops have `stop-opacity` 0), its own
//!     `stroke-opacity` or `fill-opacity` is 0, or the element or a group
//!     around it has `opacity` 0. A path whose stroke and fill are both
//!     invisible is skipped. Only zero counts: white is a colour (a white
//!     pen on dark paper is real), and a faint stroke is drawn.
//!   - Paths with neither fill nor stroke.
//! - **Paint.** A visible fill is kept in
//!   [`Style::fill`](crate::scene::Style::fill): the region that `moyo
//!   fill`, hatching and occlusion work on. An invisible fill is no
//!   region: a stroked path with a transparent fill is its line alone.
//!   The stroke is implied by the pen, which draws every path with a
//!   visible stroke, and every filled path without any stroke (a plotter
//!   draws a filled shape as its outline). A filled path whose stroke is
//!   there but invisible (`stroke="transparent"`: the white page that
//!   graphviz puts behind a graph) is paint alone
//!   ([`Style::fill_only`](crate::scene::Style::fill_only)): the preview
//!   shows it and it hides what lies behind it, but no pen draws its
//!   outline and `moyo fill` does not fill it. Grouping by colour gives
//!   such paint no pen of its own: it goes with the first pen, whose layer
//!   is the back one (a white page is no pen to load, nor may it cover the
//!   drawing in the preview).
//! - **Text** (`text`, `tspan`) is drawn in single strokes, in moyo's
//!   built-in Hershey font ([`crate::text`]), in place of the fonts the
//!   document names (one warning says so): at its `x` and `y` on the
//!   baseline, by its `text-anchor`, at a cap height of 0.7 times its
//!   `font-size`, through every transform above it. Its fill colour (its
//!   stroke's, when stroked) chooses the pen as a filled path's does, but
//!   the glyphs are lines and fill nothing. A character without a glyph
//!   is drawn as a box and named in a warning. At most
//!   [`MAX_CHARS`](crate::text::MAX_CHARS) characters are drawn from one
//!   file; text elements past them are skipped with a warning. Read:
//!   the characters of `text`, `tspan` and `a`; the first length of `x`,
//!   `y`, `dx` and `dy`; `font-size`, `text-anchor` and `xml:space` as
//!   attributes or in `style`, inherited. Not read: a stylesheet's font
//!   size or anchor (its paint is), a `tspan`'s own paint (the text's is
//!   used), per-character positions, `rotate`, `textLength` and vertical
//!   writing; the letters' widths are the Hershey font's, not the named
//!   font's.
//! - **Not imported, with a warning:** flowed text (Inkscape's
//!   `flowRoot`) and text along a path (`textPath`), raster images, and
//!   the effect of clip paths, masks and filters (the paths are imported
//!   unclipped).
//!
//! Bad input is an [`Error`], never a panic: an empty file, malformed XML, a
//! root element other than `<svg>`, a document without a usable size, and
//! numbers that cannot be plotted (NaN, infinities, coordinates beyond
//! ±[`MAX_COORD`](crate::units::MAX_COORD) mm).
//!
//! Round trip: importing what [`to_svg`](crate::output::to_svg) wrote gives
//! back the same pens (numbers, names, colours, widths), the same paths per pen
//! in the same order within 1e-3 mm, the fills and the embedded scene
//! description; the scene layers drawn by one pen come back merged into
//! one layer, and groups come back flattened. A documentation layer comes
//! back as a layer of its own with the same name (the `%` label), paths,
//! colour and width; its pen number is not in the SVG, so it is the one
//! numbered as above.
//!
//! Limits: usvg computes in `f32`, so coordinates carry a relative error
//! of about 1e-7 (0.04 µm on an A3 sheet). Only top-level layers are pens;
//! sub-layers belong to their top-level layer.
//! [`Style`](crate::scene::Style) has no fill rule: fills are non-zero
//! downstream, so an `evenodd` fill is redrawn as the normalised contours of
//! its area (the same lines; holes wound against their outline). Layer
//! visibility set by a CSS stylesheet (rather than `style`/`display` on the
//! layer) hides the layer without the "hidden" wording in its warning, and
//! an element a stylesheet hides with `display: none` is left out without
//! being counted (the count reads the raw XML, usvg the stylesheet).
//!
//! # The steps, one file each
//!
//! 1. `scan`: a pass over the raw XML for what usvg drops or cannot tell —
//!    the root element, Inkscape layers (given ids where they lack one, so
//!    that usvg's groups can be matched to them), text (laid out by
//!    `text`, each text element replaced by a stand-in path that usvg
//!    places and paints), images and what `display: none` hides — and,
//!    through `numbers`, a check of
//!    every number that becomes geometry (svgtypes parses them as usvg
//!    will).
//! 2. usvg builds its tree; `page` takes the page size from it, exact in
//!    `f64` where the source allows.
//! 3. `walk`: usvg's tree to paths in page millimetres, each with its
//!    layer, visible paint and id; a text's stand-in becomes its glyphs.
//! 4. `pens`: paths to pens (by layer or by colour), then the scene.

mod numbers;
mod page;
mod pens;
mod scan;
mod text;
mod walk;

#[cfg(test)]
mod test_support;

pub use walk::MAX_IMPORT_SEGMENTS;

use kurbo::Affine;
use resvg::usvg::{self, roxmltree};
use serde::{Deserialize, Serialize};

use crate::error::{Error, LineCol, Result};
use crate::scene::embedded_description;
use crate::scene::Scene;
use crate::units::MM_PER_INCH;

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
    /// Every plotted path on pen 1, layers and colours ignored;
    /// documentation layers (`%`) still apart (vpype's `--single-layer`).
    Single,
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
    /// When pens come from colours: the most pens, colours beyond being
    /// merged by nearest colour (see the module documentation); 0 for one
    /// pen per colour, never merged. At most 999. Pens from layers ignore
    /// it: a file's layers are its pens.
    pub max_pens: u32,
}

impl ImportOptions {
    /// 96 px per inch, pens from layers when there are any, otherwise
    /// from colours, at most [`DEFAULT_MAX_PENS`](Self::DEFAULT_MAX_PENS).
    pub const DEFAULT: ImportOptions = ImportOptions {
        px_per_inch: 96.0,
        pens: PenGrouping::Auto,
        max_pens: ImportOptions::DEFAULT_MAX_PENS,
    };

    /// The most pens made from colours unless told otherwise: a plotter's
    /// pen carousel, or a person's patience for changing pens.
    pub const DEFAULT_MAX_PENS: u32 = 8;

    /// These options with at most `max_pens` pens from colours (0: one per
    /// colour).
    pub const fn with_max_pens(mut self, max_pens: u32) -> ImportOptions {
        self.max_pens = max_pens;
        self
    }

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
    /// (text, images, hidden or invisible content, unpainted paths,
    /// clipping, hidden layers…), in a fixed order. Empty when the import
    /// is exact.
    pub warnings: Vec<String>,
    /// Whether the pens are the document's Inkscape layers (its author's
    /// pens, which [`ImportOptions::max_pens`] does not regroup), rather
    /// than grouped from colours.
    pub pens_from_layers: bool,
}

/// Reads an SVG document into a scene (see the module documentation for
/// the mapping and its limits).
///
/// ```
/// use moyo::{import_svg, ImportOptions};
///
/// let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="40mm" height="20mm"
///     viewBox="0 0 400 200">
///   <circle cx="100" cy="100" r="50" stroke="red" fill="none"/>
///   <text x="10" y="180" font-size="20">signed</text>
///   <image href="photo.png" width="10" height="10"/>
/// </svg>"#;
/// let imported = import_svg(svg, &ImportOptions::DEFAULT)?;
/// // Millimetres: the viewBox is ten units to the millimetre.
/// let page = &imported.scene.page;
/// assert_eq!((page.width, page.height), (40.0, 20.0));
/// // The circle, and the text in single strokes: one path.
/// assert_eq!(imported.scene.path_count(), 2);
/// // What was changed or could not be plotted is said, not done silently.
/// assert_eq!(
///     imported.warnings,
///     [
///         "1 text element drawn in moyo's single-stroke Hershey Sans in place of \
///          the document's font",
///         "skipped 1 image: raster images cannot be plotted",
///     ]
/// );
/// # Ok::<(), moyo::Error>(())
/// ```
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
    if options.max_pens > 999 {
        return Err(Error::invalid(
            "max_pens",
            format!("must be 0 to 999, got {}", options.max_pens),
        ));
    }
    let doc = parse_xml(text)?;
    let source = scan::scan(text, &doc, options.px_per_inch)?;
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
    let mm_per_px = MM_PER_INCH / options.px_per_inch;
    let exact_size = page::exact_size(doc.root_element(), mm_per_px);
    let tree = match &source.rewritten {
        Some(rewritten) => {
            let doc = parse_xml(rewritten)?;
            usvg::Tree::from_xmltree(&doc, &usvg_options)
        }
        None => usvg::Tree::from_xmltree(&doc, &usvg_options),
    }
    .map_err(usvg_error)?;
    // Each stage's copy of the drawing is let go as soon as the next one
    // is built: on a million-path file the XML tree and usvg's tree are
    // each larger than the paths themselves.
    drop(doc);

    let page = page::page_of(&tree, exact_size, mm_per_px)?;
    let walked = walk::walk(
        &tree,
        Affine::scale(mm_per_px),
        &source.layers,
        &source.texts.laid,
    )?;
    drop(tree);

    let mut warnings = source.texts.warnings(walked.texts);
    let mut plural = |n: usize, one: &str, many: &str, rest: &str| {
        if n > 0 {
            let noun = if n == 1 { one } else { many };
            warnings.push(format!("skipped {n} {noun}: {rest}"));
        }
    };
    plural(
        source.images,
        "image",
        "images",
        "raster images cannot be plotted",
    );
    plural(
        source.display_none,
        "element",
        "elements",
        "hidden by `display:none`",
    );
    plural(walked.unpainted, "path", "paths", "no fill and no stroke");
    plural(walked.hidden, "path", "paths", "hidden by `visibility`");
    plural(
        walked.transparent,
        "path",
        "paths",
        "invisible (transparent or zero opacity)",
    );
    if walked.effects > 0 {
        let n = walked.effects;
        let groups = if n == 1 { "group" } else { "groups" };
        warnings.push(format!(
            "clip paths, masks and filters are not applied ({n} {groups}): \
             their paths are imported whole"
        ));
    }
    warnings.extend(source.warnings);

    // Layers are in the document's paint order; colours are not.
    let (buckets, pens_from_layers) = match options.pens {
        PenGrouping::Auto if !source.layers.is_empty() => {
            (pens::by_layer(&source.layers, &walked, &mut warnings), true)
        }
        PenGrouping::Single => (
            pens::by_color(
                &walked.drawn,
                &source.layers,
                pens::ColorPens::Single,
                &mut warnings,
            )?,
            false,
        ),
        _ => (
            pens::by_color(
                &walked.drawn,
                &source.layers,
                pens::ColorPens::AtMost(options.max_pens),
                &mut warnings,
            )?,
            false,
        ),
    };
    pens::check_pen_numbers(&buckets)?;
    let scene = pens::assemble(
        page,
        buckets,
        pens_from_layers,
        walked.drawn,
        embedded_description(text),
        &mut warnings,
    );
    Ok(Imported {
        scene,
        warnings,
        pens_from_layers,
    })
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
        usvg::Error::ElementsLimitReached
        | usvg::Error::ParsingFailed(roxmltree::Error::NodesLimitReached) => parse_error(
            "the document has more than 1,000,000 elements, or elements nested more than \
             1,024 deep: the most moyo imports (usvg's limits)",
        ),
        usvg::Error::ParsingFailed(roxmltree::Error::NoRootNode) => {
            parse_error("not an SVG document: the root element must be <svg>")
        }
        e => parse_error(format!("malformed SVG: {e}")),
    }
}

#[cfg(test)]
mod tests {
    use super::test_support::{assert_rect_near, doc, import, import_err, near, paths};
    use super::*;
    use crate::output::{to_svg, SvgOptions};
    use crate::scene::{Color, Group, Layer, Pen, Style};
    use crate::units::{Margins, Orientation, Page, PaperName};
    use kurbo::{BezPath, Line, PathEl, Point, Rect, Shape};
    use proptest::prelude::*;

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
        let svg = to_svg(&original, &SvgOptions::PREVIEW);
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
        let again = to_svg(scene, &SvgOptions::PREVIEW);
        assert!(again.contains("inkscape:label=\"%guides &amp; notes\""));
        assert!(!import(&again).scene.layers[0].is_plotted());
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
