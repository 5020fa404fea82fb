//! The layered SVG writer: one Inkscape layer per pen, page size in mm.
//!
//! It writes one of two documents of a scene ([`SvgOptions::preview`]):
//!
//! - **the plot** (the default): only what pens draw, meant to be sent to a
//!   plotter or cutter as is. vpype and cutter software draw every path
//!   they find (only AxiDraw knows to skip `%` layers), so nothing else is
//!   in it: no layer that is not plotted and no
//!   [fill-only](crate::scene::Style::fill_only) path (the preview colour
//!   that hidden-line removal leaves).
//! - **the colour preview**: the plot plus those, for people to look at
//!   (`moyo render --preview-svg`) and for the PNG preview. Its pen layers
//!   are the plot's, byte for byte, with the fill-only paths in between.
//!
//! Both are byte-identical for equal scenes: element order follows the
//! scene, numbers go through [`write_number`], and nothing depends on
//! hashing or the machine.
//!
//! Shape of the document:
//!
//! ```text
//! <?xml …?>
//! <svg … width="210mm" height="297mm" viewBox="0 0 210 297">   one user unit = 1 mm
//!  <metadata><moyo:scene …><![CDATA[scene description]]></moyo:scene></metadata>
//!  <g id="{layer id}" inkscape:groupmode="layer" inkscape:label="%guides"   preview only:
//!     style="stroke…" transform="translate({margin left} {margin top})">   a layer that
//!   <g id="{group id}"> …                                                  is not plotted
//!  <g id="pen-1" inkscape:groupmode="layer" inkscape:label="1 black" style="stroke…">
//!   <g id="{layer id}" transform="translate({margin left} {margin top})">
//!    <g id="{group id}">                    transform="matrix(…)" when not identity
//!     <path id="{path id}" d="M … L … Q … C … Z"/>
//! ```
//!
//! # Layer names (AxiDraw's conventions)
//!
//! Each pen's Inkscape layer is labelled with the pen number first, then
//! the pen's name (`1 black`): AxiDraw and vpype read the leading integer as
//! the layer number. AxiDraw's codes in a pen's name go where AxiDraw reads
//! them, a pause before the number and the others right after it (pen 3
//! named `!+S40 fine` is labelled `!3+S40 fine`: [`LayerCodes::label`]). Pens come in ascending number, and only pens that draw
//! at least one plotted layer get an Inkscape layer; within a pen, scene
//! layers are written back to front.
//!
//! In the colour preview, a scene layer that is not plotted (a
//! *documentation layer*, whose name starts with `%`: [`Layer::is_plotted`])
//! is not merged into its pen's layer: it becomes an Inkscape layer of its
//! own, labelled with the layer's name exactly as it is (`%guides`, no pen
//! number). These layers come first, back to front, so that they paint
//! behind the drawing; each takes its stroke colour and width from its pen.
//! The plot leaves them out: AxiDraw would skip them, but vpype and cutter
//! software do not know the convention and would draw them.
//!
//! Stroke colour and width live on the Inkscape layer; a path carries a
//! `style` only when it has a fill.

use kurbo::{Affine, BezPath, PathEl, Point};

use super::number::{write_number, MAX_PRECISION};
use crate::scene::{embed, Color, Group, Layer, LayerCodes, Node, Pen, Scene, StyledPath};

/// Options of [`to_svg`].
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SvgOptions {
    /// Decimals of path coordinates, in the path's own units (mm unless a
    /// group scales them); at most 8. Page size, stroke widths and
    /// transforms are always written at full precision (8 decimals), since
    /// rounding them would move or resize the whole drawing.
    pub precision: u8,
    /// Write the colour preview: the plot plus the layers that are not
    /// plotted and the fill-only paths (see the module documentation).
    /// Default `false`: the plot, only what pens draw.
    pub preview: bool,
}

impl SvgOptions {
    /// The largest precision honoured; larger values are clamped.
    pub const MAX_PRECISION: u8 = MAX_PRECISION;

    /// The plot, at three decimals: a micrometre, well below any
    /// plotter's step.
    pub const DEFAULT: SvgOptions = SvgOptions {
        precision: 3,
        preview: false,
    };

    /// The colour preview at three decimals.
    pub const PREVIEW: SvgOptions = SvgOptions::DEFAULT.with_preview(true);

    /// These options with `precision` decimals (clamped to
    /// [`SvgOptions::MAX_PRECISION`]).
    pub const fn with_precision(mut self, precision: u8) -> SvgOptions {
        self.precision = if precision > MAX_PRECISION {
            MAX_PRECISION
        } else {
            precision
        };
        self
    }

    /// These options writing the colour preview (`true`) or the plot.
    pub const fn with_preview(mut self, preview: bool) -> SvgOptions {
        self.preview = preview;
        self
    }
}

impl Default for SvgOptions {
    fn default() -> SvgOptions {
        SvgOptions::DEFAULT
    }
}

/// Writes `scene` as a layered SVG document (see the module documentation
/// for its exact shape).
pub fn to_svg(scene: &Scene, options: &SvgOptions) -> String {
    let mut w = Writer {
        out: String::new(),
        precision: options.precision.min(MAX_PRECISION),
        preview: options.preview,
    };
    w.document(scene);
    w.out
}

/// Appends the path data of `path` (`M x y L x y … Z`, absolute commands,
/// single spaces) with coordinates at `precision` decimals. Shared with the
/// path dump so that both show the same text for the same geometry.
pub(crate) fn write_path_data(out: &mut String, path: &BezPath, precision: u8) {
    for (i, el) in path.elements().iter().enumerate() {
        if i > 0 {
            // A path of millions of segments takes most of a second to
            // write: a render called off stops here, and throws away what
            // was written (it checks its flag once the SVG is written).
            if i % 65_536 == 0 && crate::cancel::called_off() {
                return;
            }
            out.push(' ');
        }
        let (cmd, points): (char, &[Point]) = match el {
            PathEl::MoveTo(p) => ('M', std::slice::from_ref(p)),
            PathEl::LineTo(p) => ('L', std::slice::from_ref(p)),
            PathEl::QuadTo(p1, p2) => ('Q', &[*p1, *p2]),
            PathEl::CurveTo(p1, p2, p3) => ('C', &[*p1, *p2, *p3]),
            PathEl::ClosePath => ('Z', &[]),
        };
        out.push(cmd);
        for p in points {
            out.push(' ');
            write_number(out, p.x, precision);
            out.push(' ');
            write_number(out, p.y, precision);
        }
    }
}

/// The document being written.
struct Writer {
    out: String,
    /// Path coordinate precision, already clamped.
    precision: u8,
    /// The colour preview rather than the plot.
    preview: bool,
}

impl Writer {
    fn document(&mut self, scene: &Scene) {
        let page = &scene.page;
        self.out
            .push_str("<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n");
        self.out.push_str(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" \
             xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" \
             xmlns:sodipodi=\"http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd\" width=\"",
        );
        self.exact(page.width);
        self.out.push_str("mm\" height=\"");
        self.exact(page.height);
        self.out.push_str("mm\" viewBox=\"0 0 ");
        self.exact(page.width);
        self.out.push(' ');
        self.exact(page.height);
        self.out.push_str("\">\n");

        if let Some(description) = &scene.description {
            self.indent(1);
            self.out.push_str("<metadata>");
            embed::write_element(&mut self.out, description);
            self.out.push_str("</metadata>\n");
        }

        let back_to_front = scene.layers_back_to_front();
        let (plotted, mut unplotted): (Vec<&Layer>, Vec<&Layer>) =
            back_to_front.into_iter().partition(|l| l.is_plotted());
        if !self.preview {
            unplotted.clear();
        }
        let page_transform = scene.page_transform().translation();
        let translate = |w: &mut Writer| {
            w.out.push_str(" transform=\"translate(");
            w.exact(page_transform.x);
            w.out.push(' ');
            w.exact(page_transform.y);
            w.out.push_str(")\"");
        };

        // Documentation layers: one Inkscape layer each, behind the pens,
        // in the preview only.
        for layer in unplotted {
            let pen = pen_or_fallback(scene, layer.pen);
            self.indent(1);
            self.out.push_str("<g id=\"");
            escape_into(&mut self.out, &layer.id);
            self.out
                .push_str("\" inkscape:groupmode=\"layer\" inkscape:label=\"");
            escape_into(&mut self.out, &layer.name);
            self.out.push('"');
            self.stroke_style(&pen);
            translate(self);
            self.out.push_str(">\n");
            self.group(&layer.content, 2);
            self.indent(1);
            self.out.push_str("</g>\n");
        }

        for (number, layers) in Scene::layers_by_pen(plotted) {
            let pen = pen_or_fallback(scene, number);
            self.pen_open(&pen);
            for layer in layers {
                self.indent(2);
                self.out.push_str("<g id=\"");
                escape_into(&mut self.out, &layer.id);
                self.out.push('"');
                translate(self);
                self.out.push_str(">\n");
                self.group(&layer.content, 3);
                self.indent(2);
                self.out.push_str("</g>\n");
            }
            self.indent(1);
            self.out.push_str("</g>\n");
        }
        self.out.push_str("</svg>\n");
    }

    fn pen_open(&mut self, pen: &Pen) {
        self.indent(1);
        let number = pen.number.to_string();
        self.out.push_str("<g id=\"pen-");
        self.out.push_str(&number);
        self.out
            .push_str("\" inkscape:groupmode=\"layer\" inkscape:label=\"");
        // AxiDraw and vpype read the leading number as the pen/layer
        // number, AxiDraw the codes around it.
        escape_into(&mut self.out, &LayerCodes::label(pen.number, &pen.name));
        self.out.push('"');
        self.stroke_style(pen);
        self.out.push_str(">\n");
    }

    /// ` style="…"` with the pen's stroke colour and width.
    fn stroke_style(&mut self, pen: &Pen) {
        self.out.push_str(" style=\"fill:none;stroke:");
        self.out.push_str(&pen.color.to_string());
        self.out.push_str(";stroke-width:");
        self.exact(pen.width);
        self.out
            .push_str(";stroke-linecap:round;stroke-linejoin:round\"");
    }

    fn group(&mut self, group: &Group, depth: usize) {
        self.indent(depth);
        self.out.push_str("<g id=\"");
        escape_into(&mut self.out, &group.id);
        self.out.push('"');
        if group.transform != Affine::IDENTITY {
            self.out.push_str(" transform=\"matrix(");
            for (i, c) in group.transform.as_coeffs().into_iter().enumerate() {
                if i > 0 {
                    self.out.push(' ');
                }
                self.exact(c);
            }
            self.out.push_str(")\"");
        }
        self.out.push_str(">\n");
        for child in &group.children {
            match child {
                Node::Group(g) => self.group(g, depth + 1),
                // Preview colour: no pen draws it. A mask is not drawn at
                // all.
                Node::Path(p) if p.style.mask || (p.style.fill_only && !self.preview) => {}
                Node::Path(p) => self.path(p, depth + 1),
            }
        }
        self.indent(depth);
        self.out.push_str("</g>\n");
    }

    fn path(&mut self, path: &StyledPath, depth: usize) {
        self.indent(depth);
        self.out.push_str("<path id=\"");
        escape_into(&mut self.out, &path.id);
        self.out.push('"');
        if let Some(fill) = path.style.fill {
            self.out.push_str(" style=\"fill:");
            self.out.push_str(&fill.to_string());
            if path.style.fill_only {
                self.out.push_str(";stroke:none");
            }
            self.out.push('"');
        }
        self.out.push_str(" d=\"");
        write_path_data(&mut self.out, &path.path, self.precision);
        self.out.push_str("\"/>\n");
    }

    /// A number that must not be rounded to the coordinate precision.
    fn exact(&mut self, v: f64) {
        write_number(&mut self.out, v, MAX_PRECISION);
    }

    fn indent(&mut self, depth: usize) {
        for _ in 0..depth {
            self.out.push(' ');
        }
    }
}

/// Pen `number` of the scene, or a black fine liner of that number when the
/// scene's pen list lacks it.
fn pen_or_fallback(scene: &Scene, number: u32) -> Pen {
    scene.pen(number).cloned().unwrap_or_else(|| Pen {
        number,
        name: String::new(),
        color: Color::BLACK,
        width: Pen::FALLBACK_WIDTH,
    })
}

/// Appends `value` escaped for a double-quoted XML attribute.
fn escape_into(out: &mut String, value: &str) {
    for c in value.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{embedded_description, Layer, Style};
    use crate::units::{Margins, Orientation, Page, PaperName};
    use kurbo::{Line, Rect, Shape};
    use resvg::usvg;

    fn pen(number: u32, name: &str, color: Color, width: f64) -> Pen {
        Pen {
            number,
            name: name.into(),
            color,
            width,
        }
    }

    fn layer(id: &str, pen: u32, depth: i32, content: Group) -> Layer {
        Layer {
            id: id.into(),
            name: id.into(),
            pen,
            depth,
            content,
        }
    }

    /// Two pens, three layers: pen 2 is listed first in the description and
    /// pen 1 draws two layers at different depths.
    fn two_pen_scene() -> Scene {
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
        flower.transform = Affine::translate((30.0, 40.0)) * Affine::scale(0.5);
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

        let mut sky = Group::new("sky");
        sky.push_path(
            "cloud",
            Line::new((1.0 / 3.0, -0.0001), (2.0 / 3.0, 1.0)).into_path(0.1),
            Style::default(),
        );

        Scene {
            page: Page::named(PaperName::A5, Orientation::Portrait, Margins::uniform(10.0)),
            pens: vec![
                pen(1, "black", Color::BLACK, 0.3),
                pen(2, "red & \"fine\"", Color::rgb(255, 0, 0), 0.25),
                pen(3, "unused", Color::rgb(0, 0, 255), 0.5),
            ],
            layers: vec![
                layer("sky-layer", 2, 1, sky),
                layer("front-layer", 1, 0, front),
                layer("back-layer", 1, 2, back),
            ],
            description: Some("seed = 7\n[page]\nsize = \"A5\"\n".into()),
        }
    }

    fn parse(svg: &str) -> usvg::Tree {
        usvg::Tree::from_str(svg, &usvg::Options::default()).expect("usvg parses our SVG")
    }

    #[test]
    fn snapshot_of_two_pen_scene() {
        insta::assert_snapshot!(to_svg(&two_pen_scene(), &SvgOptions::DEFAULT));
    }

    #[test]
    fn deterministic() {
        let a = to_svg(&two_pen_scene(), &SvgOptions::DEFAULT);
        let b = to_svg(&two_pen_scene().clone(), &SvgOptions::default());
        assert_eq!(a, b);
    }

    #[test]
    fn usvg_parses_it_with_the_page_size_in_mm() {
        let mut scene = two_pen_scene();
        scene.page = Page::named(PaperName::A4, Orientation::Portrait, Margins::uniform(10.0));
        let tree = parse(&to_svg(&scene, &SvgOptions::DEFAULT));
        // usvg reports px at 96 dpi: 210 mm = 793.70 px, 297 mm = 1122.52 px.
        let size = tree.size();
        assert!((size.width() - 793.700_8).abs() < 0.01, "{size:?}");
        assert!((size.height() - 1_122.519_7).abs() < 0.01, "{size:?}");
        // The fill colour, the transform and the margin reach the renderer.
        let petal = tree.node_by_id("petal").expect("petal survives parsing");
        let usvg::Node::Path(petal) = petal else {
            panic!("petal is a path")
        };
        assert!(petal.fill().is_some());
        let t = petal.abs_transform();
        assert!((t.sx - 0.5 * 96.0 / 25.4).abs() < 1e-3, "{t:?}");
    }

    #[test]
    fn one_inkscape_layer_per_used_pen_in_pen_order() {
        let svg = to_svg(&two_pen_scene(), &SvgOptions::DEFAULT);
        let labels: Vec<&str> = svg
            .lines()
            .filter(|l| l.contains("inkscape:groupmode=\"layer\""))
            .map(|l| {
                let start = l.find("inkscape:label=\"").unwrap() + "inkscape:label=\"".len();
                &l[start..start + l[start..].find('"').unwrap()]
            })
            .collect();
        assert_eq!(labels, ["1 black", "2 red &amp; &quot;fine&quot;"]);
        assert_eq!(svg.matches("id=\"pen-1\"").count(), 1);
        assert!(!svg.contains("pen-3"), "pens without layers are omitted");
        // Within pen 1, the back layer (depth 2) is painted first.
        let back = svg.find("id=\"back-layer\"").unwrap();
        let front = svg.find("id=\"front-layer\"").unwrap();
        let pen2 = svg.find("id=\"pen-2\"").unwrap();
        assert!(back < front && front < pen2);
        assert!(svg.contains("stroke:#ff0000;stroke-width:0.25;"));
    }

    /// The two-pen scene with two documentation layers: `%guides` (pen 3,
    /// at the back) and `% 1 notes <b>` (pen 1, in front).
    fn scene_with_documentation_layers() -> Scene {
        let mut scene = two_pen_scene();
        let mut guides = Group::new("guides");
        guides.push_path(
            "frame",
            Rect::new(-5.0, -5.0, 123.0, 185.0).into_path(0.1),
            Style::default(),
        );
        let mut notes = Group::new("notes");
        notes.push_path(
            "arrow",
            Line::new((50.0, 50.0), (60.0, 55.0)).into_path(0.1),
            Style::default(),
        );
        let mut g = layer("guides-layer", 3, 7, guides);
        g.name = "%guides".into();
        let mut n = layer("notes-layer", 1, 0, notes);
        n.name = "% 1 notes <b>".into();
        scene.layers.insert(0, n);
        scene.layers.push(g);
        scene
    }

    fn layer_labels(svg: &str) -> Vec<&str> {
        svg.lines()
            .filter(|l| l.contains("inkscape:groupmode=\"layer\""))
            .map(|l| {
                let start = l.find("inkscape:label=\"").unwrap() + "inkscape:label=\"".len();
                &l[start..start + l[start..].find('"').unwrap()]
            })
            .collect()
    }

    /// The document from the first pen layer on.
    fn from_pen_1(svg: &str) -> &str {
        &svg[svg.find("<g id=\"pen-1\"").unwrap()..]
    }

    #[test]
    fn unplotted_layers_are_inkscape_layers_of_their_own_in_the_preview() {
        let scene = scene_with_documentation_layers();
        let svg = to_svg(&scene, &SvgOptions::DEFAULT.with_preview(true));
        // Unplotted first, back to front, labelled by their names alone;
        // pen 3 draws nothing plotted, so it gets no pen layer.
        assert_eq!(
            layer_labels(&svg),
            [
                "%guides",
                "% 1 notes &lt;b&gt;",
                "1 black",
                "2 red &amp; &quot;fine&quot;"
            ]
        );
        assert!(!svg.contains("id=\"pen-3\""));
        assert!(svg.contains(
            "<g id=\"guides-layer\" inkscape:groupmode=\"layer\" inkscape:label=\"%guides\" \
             style=\"fill:none;stroke:#0000ff;stroke-width:0.5;stroke-linecap:round;\
             stroke-linejoin:round\" transform=\"translate(10 10)\">\n  <g id=\"guides\">\n   \
             <path id=\"frame\" d=\"M -5 -5 L 123 -5 L 123 185 L -5 185 Z\"/>"
        ));
        // The notes are not in pen 1's layer.
        let pen1 = svg.find("id=\"pen-1\"").unwrap();
        assert!(svg.find("id=\"arrow\"").unwrap() < pen1);
        // The preview draws them: the frame reaches the sheet's corner.
        let tree = parse(&svg);
        let frame = tree.node_by_id("frame").expect("the frame is drawn");
        let b = frame.abs_stroke_bounding_box();
        assert!(b.left() < 5.0 * 96.0 / 25.4 + 1.0, "{b:?}");
        // The plotted layers are written exactly as without the others.
        let plain = to_svg(&two_pen_scene(), &SvgOptions::DEFAULT);
        assert_eq!(from_pen_1(&svg), from_pen_1(&plain));
    }

    #[test]
    fn the_plot_leaves_unplotted_layers_out() {
        let scene = scene_with_documentation_layers();
        let svg = to_svg(&scene, &SvgOptions::DEFAULT);
        assert_eq!(
            layer_labels(&svg),
            ["1 black", "2 red &amp; &quot;fine&quot;"]
        );
        for id in ["guides-layer", "frame", "notes-layer", "arrow"] {
            assert!(!svg.contains(&format!("id=\"{id}\"")), "{id}");
        }
        // Exactly the document of the scene without them.
        assert_eq!(svg, to_svg(&two_pen_scene(), &SvgOptions::DEFAULT));
    }

    #[test]
    fn fill_only_paths_are_in_the_preview_only() {
        let mut scene = two_pen_scene();
        let Node::Group(front) = &mut scene.layers[1].content.children[1] else {
            panic!("the flower group")
        };
        let mut visible = BezPath::new();
        visible.move_to((5.0, 5.0));
        visible.line_to((10.0, 5.0));
        visible.line_to((7.0, 7.0));
        visible.close_path();
        front.children.insert(
            0,
            Node::Path(StyledPath {
                id: "petal.fill".into(),
                path: visible,
                style: Style {
                    fill: Some(Color::rgb(0xdc, 0x14, 0x3c)),
                    fill_only: true,
                    ..Style::default()
                },
            }),
        );
        let preview = to_svg(&scene, &SvgOptions::DEFAULT.with_preview(true));
        assert!(preview.contains(
            "<path id=\"petal.fill\" style=\"fill:#dc143c;stroke:none\" d=\"M 5 5 L 10 5 L 7 7 Z\"/>"
        ));
        let plot = to_svg(&scene, &SvgOptions::DEFAULT);
        assert!(!plot.contains("petal.fill") && !plot.contains("stroke:none"));
        assert_eq!(plot, to_svg(&two_pen_scene(), &SvgOptions::DEFAULT));
    }

    #[test]
    fn pen_missing_from_the_list_still_gets_its_layer() {
        let mut scene = two_pen_scene();
        scene.pens.retain(|p| p.number != 2);
        let svg = to_svg(&scene, &SvgOptions::DEFAULT);
        assert!(svg.contains("inkscape:label=\"2\" style=\"fill:none;stroke:#000000;"));
        assert!(svg.contains("id=\"cloud\""));
        parse(&svg);
    }

    #[test]
    fn precision_changes_digits() {
        let scene = two_pen_scene();
        let coarse = to_svg(&scene, &SvgOptions::DEFAULT.with_precision(1));
        let fine = to_svg(&scene, &SvgOptions::DEFAULT.with_precision(5));
        assert!(coarse.contains("d=\"M 0.3 0 L 0.7 1\""), "{coarse}");
        assert!(
            fine.contains("d=\"M 0.33333 -0.0001 L 0.66667 1\""),
            "{fine}"
        );
        let capped = SvgOptions::DEFAULT.with_precision(40);
        assert_eq!(capped.precision, SvgOptions::MAX_PRECISION);
        // Transforms and sizes keep full precision even at precision 0.
        let zero = to_svg(&scene, &SvgOptions::DEFAULT.with_precision(0));
        assert!(zero.contains("matrix(0.5 0 0 0.5 30 40)"));
        assert!(zero.contains("stroke-width:0.3;"));
    }

    #[test]
    fn filled_path_gets_its_own_style() {
        let svg = to_svg(&two_pen_scene(), &SvgOptions::DEFAULT);
        assert!(svg.contains(
            "<path id=\"petal\" style=\"fill:#dc143c\" d=\"M 5 5 Q 7.5 0 10 5 C 9 7 6 7 5 5 Z\"/>"
        ));
        assert!(svg.contains("<path id=\"stem\" d=\"M 0 0 L 20 10\"/>"));
    }

    #[test]
    fn identity_groups_have_no_transform() {
        let svg = to_svg(&two_pen_scene(), &SvgOptions::DEFAULT);
        assert!(svg.contains("<g id=\"front\">"));
        assert!(svg.contains("<g id=\"front-layer\" transform=\"translate(10 10)\">"));
    }

    #[test]
    fn description_is_embedded_as_metadata() {
        let mut scene = two_pen_scene();
        // The hardest text for CDATA (see `scene::embed`): the document
        // stays well-formed and gives it back.
        let text = "a = \"]]>\"\n</moyo:scene> <![CDATA[ & < > 模様";
        scene.description = Some(text.into());
        let svg = to_svg(&scene, &SvgOptions::DEFAULT);
        assert_eq!(embedded_description(&svg).as_deref(), Some(text));
        parse(&svg);
        scene.description = None;
        let svg = to_svg(&scene, &SvgOptions::DEFAULT);
        assert!(!svg.contains("<metadata>"));
        assert_eq!(embedded_description(&svg), None);
    }

    #[test]
    fn negative_zero_never_appears() {
        let mut scene = two_pen_scene();
        let mut g = Group::new("mirrored");
        g.transform = Affine::scale_non_uniform(-1.0, 1.0) * Affine::rotate(std::f64::consts::PI);
        g.push_path(
            "z",
            Line::new((-0.0, -0.000_01), (-1e-12, 0.0)).into_path(0.1),
            Style::default(),
        );
        scene.layers.push(layer("neg", 1, 0, g));
        scene.page.margins.left = -0.0;
        let svg = to_svg(&scene, &SvgOptions::DEFAULT);
        assert!(svg.contains("<path id=\"z\" d=\"M 0 0 L 0 0\"/>"), "{svg}");
        let tokens = svg.split(|c: char| c.is_whitespace() || "\"()".contains(c));
        assert!(tokens.clone().all(|t| t != "-0"), "{svg}");
        assert!(tokens.clone().any(|t| t == "0"));
    }

    #[test]
    fn attribute_values_are_escaped() {
        let mut scene = two_pen_scene();
        scene.layers[0].id = "a<b>&'c\"".into();
        let svg = to_svg(&scene, &SvgOptions::DEFAULT);
        assert!(svg.contains("id=\"a&lt;b&gt;&amp;&apos;c&quot;\""));
        parse(&svg);
    }
}
