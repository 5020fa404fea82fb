//! The walk over usvg's tree: every painted, visible path converted to
//! page millimetres (all transforms baked in), with its layer, paint and
//! id, and a count of what was left out. A text's stand-in path is drawn
//! as the text's glyphs.
//!
//! What a viewer cannot see is not drawn: a stroke or fill is invisible
//! when its paint is fully transparent (`transparent`, an alpha of 0, a
//! gradient whose stops all are), its own opacity (`stroke-opacity`,
//! `fill-opacity`) is 0, or a group around it has `opacity` 0 (usvg turns
//! an element's own `opacity` into such a group). Only zero counts: a
//! white stroke is a white pen, a faint one a pen.

use std::collections::HashMap;

use kurbo::{Affine, BezPath, PathEl, Point};
use resvg::usvg::{
    self,
    tiny_skia_path::{PathSegment, PathVerb},
};

use super::page::round_size;
use super::scan::LayerSource;
use super::text::{stand_in_index, Lettered};
use crate::error::{Error, Result};
use crate::geom::region::{FillRule, Region};
use crate::scene::Color;
use crate::units::MAX_COORD;

/// A usvg path converted to page millimetres.
#[derive(Debug)]
pub(super) struct Drawn {
    /// Index into the scanned layers, `None` outside every layer.
    pub layer: Option<usize>,
    /// The element id (empty when it had none).
    pub id: String,
    /// The geometry in page millimetres.
    pub path: BezPath,
    /// Colour and drawn width in mm.
    pub stroke: Option<(Color, f64)>,
    /// Fill colour (a visible fill only).
    pub fill: Option<Color>,
    /// Filled, with a stroke the document declares but makes invisible
    /// (`stroke="transparent"`, `stroke-opacity="0"`): paint that the
    /// preview shows and hidden-line removal counts, whose outline no pen
    /// draws ([`Style::fill_only`](crate::scene::Style::fill_only)). A
    /// fill without any stroke keeps the plotter's convention instead:
    /// its pen draws the outline.
    pub paint_only: bool,
    /// The single-stroke glyphs of a text: line work only, whose fill
    /// colour chooses the pen as a filled path's does but fills nothing.
    pub glyphs: bool,
}

/// What the walk found, in paint order.
#[derive(Debug)]
pub(super) struct Walked {
    /// The paths.
    pub drawn: Vec<Drawn>,
    /// For each scanned layer, whether usvg kept it (it drops hidden ones).
    pub found: Vec<bool>,
    /// Paths with neither fill nor stroke, left out.
    pub unpainted: usize,
    /// Paths hidden by `visibility`, left out.
    pub hidden: usize,
    /// Paths whose stroke and fill are both invisible (transparent or
    /// zero opacity), left out.
    pub transparent: usize,
    /// Groups with a clip path that cuts, a mask or a filter (not applied).
    pub effects: usize,
    /// Texts drawn (a text a `use` repeats, as often as it is drawn).
    pub texts: usize,
}

/// The most segments (lines and curves) an imported SVG may hold: the
/// default segment budget of a scene, a thousand hours of plotting. The
/// heaviest SVG within it and the element limit (a million paths of ten
/// segments) peaks at about 1.9 GB through `plot --merge --sort` (see
/// `RELIABILITY.md`).
pub const MAX_IMPORT_SEGMENTS: usize = 10_000_000;

/// Walks `tree`, mapping its coordinates to mm with `to_mm`; `layers` are
/// the top-level layers the scan found, matched to usvg's groups by id;
/// `texts` the laid-out texts by number.
///
/// # Errors
/// [`Error::Invalid`] for a point beyond ±[`MAX_COORD`] mm, or more than
/// [`MAX_IMPORT_SEGMENTS`] segments.
pub(super) fn walk(
    tree: &usvg::Tree,
    to_mm: Affine,
    layers: &[LayerSource],
    texts: &[Option<Lettered>],
) -> Result<Walked> {
    walk_within(tree, to_mm, layers, texts, MAX_IMPORT_SEGMENTS)
}

/// [`walk`] with at most `max_segments` segments.
fn walk_within(
    tree: &usvg::Tree,
    to_mm: Affine,
    layers: &[LayerSource],
    texts: &[Option<Lettered>],
    max_segments: usize,
) -> Result<Walked> {
    let mut walker = Walker {
        to_mm,
        segments: 0,
        max_segments,
        texts,
        layer_of: layers
            .iter()
            .enumerate()
            .map(|(i, l)| (l.id.as_str(), i))
            .collect(),
        walked: Walked {
            drawn: Vec::new(),
            found: vec![false; layers.len()],
            unpainted: 0,
            hidden: 0,
            transparent: 0,
            effects: 0,
            texts: 0,
        },
    };
    walker.group(tree.root(), None, false)?;
    Ok(walker.walked)
}

struct Walker<'a> {
    to_mm: Affine,
    /// Segments in the paths walked so far.
    segments: usize,
    /// The most there may be.
    max_segments: usize,
    texts: &'a [Option<Lettered>],
    layer_of: HashMap<&'a str, usize>,
    walked: Walked,
}

impl Walker<'_> {
    /// Walks the children of `group`, inside `layer`; `transparent`: a
    /// group around it has opacity 0, so nothing in it is seen.
    fn group(
        &mut self,
        group: &usvg::Group,
        layer: Option<usize>,
        transparent: bool,
    ) -> Result<()> {
        for node in group.children() {
            match node {
                usvg::Node::Group(g) => {
                    let mut inner = layer;
                    if layer.is_none() {
                        if let Some(&i) = self.layer_of.get(g.id()) {
                            self.walked.found[i] = true;
                            inner = Some(i);
                        }
                    }
                    let transparent = transparent || g.opacity().get() == 0.0;
                    // An effect on what is not seen changes nothing drawn.
                    if !transparent
                        && (!clip_cuts_nothing(g) || g.mask().is_some() || !g.filters().is_empty())
                    {
                        self.walked.effects += 1;
                    }
                    self.group(g, inner, transparent)?;
                }
                usvg::Node::Path(p) => self.path(p, layer, transparent)?,
                // Counted, with their warnings, in the pre-pass.
                usvg::Node::Image(_) | usvg::Node::Text(_) => {}
            }
        }
        Ok(())
    }

    /// Converts `p`, inside `layer`, unless it is not seen (`transparent`:
    /// a group around it has opacity 0).
    fn path(&mut self, p: &usvg::Path, layer: Option<usize>, transparent: bool) -> Result<()> {
        if p.fill().is_none() && p.stroke().is_none() {
            self.walked.unpainted += 1;
            return Ok(());
        }
        if !p.is_visible() {
            self.walked.hidden += 1;
            return Ok(());
        }
        let stroke = p
            .stroke()
            .filter(|s| !transparent && shows(s.paint(), s.opacity()));
        let fill = p
            .fill()
            .filter(|f| !transparent && shows(f.paint(), f.opacity()));
        if stroke.is_none() && fill.is_none() {
            self.walked.transparent += 1;
            return Ok(());
        }
        let to_page = self.to_mm * affine(p.abs_transform());
        let scale = to_page.determinant().abs().sqrt();
        let stroke = stroke.map(|s| stroke_of(s, scale));
        let fill_color = fill.map(|f| paint_color(f.paint()));
        if let Some(text) = stand_in_index(p.data()).and_then(|i| self.texts.get(i)?.as_ref()) {
            return self.glyphs(text, to_page, stroke, fill_color, layer);
        }
        // Checked before the path is built: the file size alone lets a
        // few very long paths hold far more segments than a plot needs.
        let verbs = p.data().verbs();
        self.count(verbs.iter().filter(|v| **v != PathVerb::Move).count())?;
        // Sized once: a vector grown by pushes holds room for four
        // elements, twice what the typical two-element path needs.
        let mut path = BezPath::with_capacity(verbs.len());
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
        // Downstream, fills are non-zero (like an SVG without fill-rule).
        // An even-odd fill is redrawn as the same area's normalised
        // contours (holes wound against their outline): every edge of an
        // even-odd fill bounds it, so the lines drawn stay the same. An
        // invisible fill is no area: the lines stay as written.
        let even_odd = fill.is_some_and(|f| f.rule() == usvg::FillRule::EvenOdd);
        let path = if even_odd {
            match Region::new(path.clone(), FillRule::EvenOdd) {
                Ok(r) if !r.is_empty() => r.into_path(),
                _ => path,
            }
        } else {
            path
        };
        self.walked.drawn.push(Drawn {
            layer,
            id: p.id().to_string(),
            path,
            stroke,
            fill: fill_color,
            // Its outline is not to be seen; no fill means no stroke at
            // all, which leaves the outline to the pen.
            paint_only: stroke.is_none() && p.stroke().is_some(),
            glyphs: false,
        });
        Ok(())
    }

    /// Counts `segments` more, as the scene's budget counts them: every
    /// element but a move.
    ///
    /// # Errors
    /// When there are more than the most imported.
    fn count(&mut self, segments: usize) -> Result<()> {
        self.segments += segments;
        if self.segments > self.max_segments {
            return Err(Error::invalid(
                "svg",
                format!(
                    "the paths hold more than {} segments in all, the most moyo imports",
                    crate::output::grouped(self.max_segments)
                ),
            ));
        }
        Ok(())
    }

    /// Draws the glyphs of `text` where its stand-in landed: mapped to
    /// the page by `to_page`, with the stand-in's visible paint.
    fn glyphs(
        &mut self,
        text: &Lettered,
        to_page: Affine,
        stroke: Option<(Color, f64)>,
        fill: Option<Color>,
        layer: Option<usize>,
    ) -> Result<()> {
        let els = text.path.elements();
        self.count(
            els.iter()
                .filter(|e| !matches!(e, PathEl::MoveTo(_)))
                .count(),
        )?;
        let path = to_page * text.path.clone();
        if let Some(pt) = path
            .elements()
            .iter()
            .filter_map(PathEl::end_point)
            .find(|pt| !(pt.x.abs() <= MAX_COORD && pt.y.abs() <= MAX_COORD))
        {
            let id = if text.id.is_empty() {
                "(no id)"
            } else {
                &text.id
            };
            return Err(Error::invalid(
                format!("text {id}"),
                format!(
                    "point ({:.3}, {:.3}) mm is outside ±{MAX_COORD} mm",
                    pt.x, pt.y
                ),
            ));
        }
        self.walked.drawn.push(Drawn {
            layer,
            id: text.id.clone(),
            path,
            stroke,
            fill,
            // Glyphs are lines, whichever paint shows them.
            paint_only: false,
            glyphs: true,
        });
        self.walked.texts += 1;
        Ok(())
    }
}

/// The stroke's colour and drawn width: the width scaled with the path
/// by `scale` (the geometric mean for non-uniform scales).
fn stroke_of(s: &usvg::Stroke, scale: f64) -> (Color, f64) {
    let width = round_size(f64::from(s.width().get()) * scale);
    (paint_color(s.paint()), width)
}

/// Whether a paint at `opacity` (usvg's product of the colour's alpha and
/// `stroke-opacity` or `fill-opacity`) leaves any mark: not at opacity 0,
/// nor a gradient all of whose stops are transparent. A pattern counts as
/// seen (its content is not looked into).
fn shows(paint: &usvg::Paint, opacity: usvg::Opacity) -> bool {
    let stops_show = |stops: &[usvg::Stop]| stops.iter().any(|s| s.opacity().get() > 0.0);
    opacity.get() > 0.0
        && match paint {
            usvg::Paint::Color(_) | usvg::Paint::Pattern(_) => true,
            usvg::Paint::LinearGradient(g) => stops_show(g.stops()),
            usvg::Paint::RadialGradient(g) => stops_show(g.stops()),
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

#[cfg(test)]
mod tests {
    use super::super::test_support::{assert_rect_near, doc, import, near, only_path, paths};
    use crate::geom::path_length;
    use crate::geom::region::{FillRule, Region};
    use crate::scene::Color;
    use kurbo::{PathEl, Rect, Shape};
    use std::f64::consts::PI;

    #[test]
    fn more_segments_than_the_limit_are_refused_before_they_are_built() {
        let text = doc(r#"<path d="M0 0 L1 1 L2 0 Z" stroke="black"/>
                          <path d="M5 5 h1 v1 h-1" stroke="black"/>"#);
        let tree = resvg::usvg::Tree::from_str(&text, &resvg::usvg::Options::default()).unwrap();
        // Three and three segments: a close is one, a move is not.
        let none = [];
        let walked = super::walk_within(&tree, kurbo::Affine::IDENTITY, &[], &none, 6).unwrap();
        assert_eq!(walked.drawn.len(), 2);
        let e = super::walk_within(&tree, kurbo::Affine::IDENTITY, &[], &none, 5).unwrap_err();
        assert!(e.to_string().contains("more than 5 segments"), "{e}");
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
    fn invisible_paint_is_not_drawn_and_is_counted() {
        // Each of these is invisible: a transparent colour, zero alpha,
        // zero stroke- or fill-opacity, zero opacity on the element or on
        // a group around it, a gradient whose stops are all transparent.
        let invisible = [
            r#"<path d="M0 0 L10 0" stroke="transparent" fill="none"/>"#,
            r#"<path d="M0 1 L10 1" stroke="rgba(255,0,0,0)" fill="none"/>"#,
            r##"<path d="M0 2 L10 2" stroke="#ff000000" fill="none"/>"##,
            r#"<path d="M0 3 L10 3" stroke="black" stroke-opacity="0" fill="none"/>"#,
            r#"<path d="M0 4 L10 4" style="stroke:black;opacity:0" fill="none"/>"#,
            r#"<rect x="0" y="5" width="5" height="5" fill="transparent"/>"#,
            r#"<rect x="0" y="5" width="5" height="5" fill="red" fill-opacity="0"/>"#,
            r#"<rect x="0" y="5" width="5" height="5" fill="red" stroke="blue" opacity="0"/>"#,
            r#"<g opacity="0"><g opacity="1"><path d="M0 6 L10 6" stroke="black"/></g></g>"#,
            r##"<linearGradient id="clear"><stop offset="0" stop-color="red" stop-opacity="0"/>
               <stop offset="1" stop-color="blue" stop-opacity="0"/></linearGradient>
               <path d="M0 7 L10 8" stroke="url(#clear)" fill="none"/>"##,
            r#"<text x="10" y="20" font-size="10" fill="transparent">hidden</text>"#,
        ];
        for body in invisible {
            let imported = import(&doc(body));
            assert_eq!(imported.scene.path_count(), 0, "{body}");
            assert_eq!(
                imported.warnings,
                ["skipped 1 path: invisible (transparent or zero opacity)"],
                "{body}"
            );
        }
        // All at once: one warning with the count.
        let imported = import(&doc(&invisible.concat()));
        assert_eq!(
            imported.warnings,
            ["skipped 11 paths: invisible (transparent or zero opacity)"]
        );
        // Faint is not invisible, and white is a pen (on dark paper).
        let seen = [
            r#"<path d="M0 0 L10 0" stroke="black" stroke-opacity="0.01" fill="none"/>"#,
            r#"<path d="M0 1 L10 1" stroke="white" fill="none"/>"#,
            r#"<path d="M0 2 L10 2" stroke="rgba(0,0,0,0.5)" opacity="0.1" fill="none"/>"#,
            r##"<linearGradient id="half"><stop offset="0" stop-color="red" stop-opacity="0"/>
               <stop offset="1" stop-color="blue"/></linearGradient>
               <path d="M0 3 L10 4" stroke="url(#half)" fill="none"/>"##,
        ];
        for body in seen {
            let imported = import(&doc(body));
            assert_eq!(imported.scene.path_count(), 1, "{body}");
            assert!(
                imported.warnings.is_empty(),
                "{body}: {:?}",
                imported.warnings
            );
        }
        assert_eq!(
            import(&doc(seen[1])).scene.pens[0].color,
            Color::rgb(255, 255, 255)
        );
    }

    #[test]
    fn a_transparent_fill_is_no_region_and_a_transparent_stroke_draws_no_outline() {
        let imported = import(&doc(
            r##"<rect id="ring" x="0" y="0" width="10" height="10" stroke="blue"
                  fill="red" fill-opacity="0" fill-rule="evenodd"/>
               <rect id="page" x="20" y="0" width="10" height="10" fill="white"
                  stroke="transparent"/>
               <rect id="plain" x="40" y="0" width="10" height="10" fill="green"/>
               <text id="label" x="60" y="10" font-size="10" stroke="transparent">A</text>"##,
        ));
        let mut got = Vec::new();
        imported.scene.visit_paths(|l, p, _| {
            got.push((p.id.clone(), l.pen, p.style.fill, p.style.fill_only))
        });
        assert_eq!(
            got,
            [
                // The line alone.
                ("ring".to_string(), 1, None, false),
                // Paint no pen draws, with the first pen (not a pen of
                // its own, nor its colour).
                ("page".to_string(), 1, Some(Color::rgb(255, 255, 255)), true),
                // A fill without a stroke: the pen draws its outline.
                ("plain".to_string(), 2, Some(Color::rgb(0, 128, 0)), false),
                // Text is lines, whichever paint shows it.
                ("label".to_string(), 3, None, false),
            ]
        );
        assert_eq!(imported.scene.pens[0].color, Color::rgb(0, 0, 255));
        // Paint alone is a pen's (its colour's) when nothing is drawn.
        let alone = import(&doc(
            r#"<rect x="0" y="0" width="9" height="9" fill="red" stroke="transparent"/>"#,
        ));
        assert_eq!(alone.scene.pens[0].color, Color::rgb(255, 0, 0));
        assert_eq!(alone.scene.stats().paths, 0);
        assert_eq!(imported.warnings.len(), 1, "{:?}", imported.warnings);
        // The plot statistics count what the pens draw.
        assert_eq!(imported.scene.stats().paths, 3);
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
}
