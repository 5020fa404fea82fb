//! The stroke model of the plotter writers (G-code and HPGL): what a pen
//! draws, in the order it draws it, as polylines in millimetres.
//!
//! - [`pen_blocks`] walks the plotted layers: pens in ascending number,
//!   within a pen its layers back to front (as in the SVG), within a layer
//!   the paths in scene order, each subpath flattened into one pen-down
//!   [`Stroke`] within a tolerance (never below [`MIN_TOLERANCE`]);
//!   documentation layers and fill-only paths are left out.
//! - A stroke knows whether it is closed (a `ClosePath`, or a return to its
//!   start within [`CLOSE_EPSILON`]); a closed stroke ends exactly on its
//!   first point, so a writer draws the outline shut and a cutter can
//!   overcut it.
//! - [`ToMachine`] maps page millimetres (origin top-left, y down) to a
//!   machine's: x mirrored or not, y measured from the top or the bottom
//!   edge, and negated or not.
//!
//! Writers add what is theirs: units, rounding, pen commands, travel.

use kurbo::{PathEl, Point};

use crate::error::{Error, Result};
use crate::scene::{LayerCodes, Scene};

/// The smallest flattening tolerance honoured, in mm; smaller values
/// (including zero and negative ones) are raised to it so that flattening
/// always ends.
pub const MIN_TOLERANCE: f64 = 1e-4;

/// Closing gaps up to this length (mm) make a subpath closed even without a
/// `ClosePath`: generators that repeat the first point mean a closed outline.
const CLOSE_EPSILON: f64 = 1e-6;

/// One pen-down stroke: a flattened subpath in page millimetres.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Stroke {
    /// At least one point. A closed stroke ends exactly on its first point.
    pub points: Vec<Point>,
    /// The subpath was closed (`ClosePath`, or it ends on its start).
    pub closed: bool,
    /// The pen is refilled before this stroke ([`super::runs`]).
    pub refill_before: bool,
}

/// The strokes of one scene path.
#[derive(Debug)]
pub(super) struct PathStrokes<'a> {
    /// The scene path's id.
    pub id: &'a str,
    /// Its subpaths, in order.
    pub strokes: Vec<Stroke>,
}

/// Everything one pen draws, in output order.
#[derive(Debug)]
pub(super) struct PenBlock<'a> {
    /// The pen number.
    pub number: u32,
    /// The pen's name, empty when the pen is missing from the pen list.
    pub name: &'a str,
    /// AxiDraw's codes in the pen's name.
    pub codes: LayerCodes,
    /// The paths the pen draws, in output order.
    pub paths: Vec<PathStrokes<'a>>,
}

/// The scene's strokes grouped by pen: pens in ascending number (only those
/// with at least one stroke), within a pen its layers back to front, within
/// a layer the paths in scene order, each flattened within `tolerance` mm in
/// page coordinates. Paths without strokes (and fill-only paths) are left
/// out, and so are layers that are not plotted
/// ([`Layer::is_plotted`](crate::scene::Layer::is_plotted)).
pub(super) fn pen_blocks(scene: &Scene, tolerance: f64) -> Vec<PenBlock<'_>> {
    let tolerance = if tolerance.is_finite() {
        tolerance.max(MIN_TOLERANCE)
    } else {
        0.02
    };
    let mut layers = scene.layers_back_to_front();
    layers.retain(|l| l.is_plotted());
    let page = scene.page_transform();
    let mut blocks = Vec::new();
    for (number, layers) in Scene::layers_by_pen(layers) {
        let mut paths = Vec::new();
        for layer in layers {
            layer.content.visit_paths(page, &mut |p, t| {
                if !p.style.is_drawn() {
                    return;
                }
                let strokes = flatten_strokes(p.path.iter().map(|el| t * el), tolerance);
                if !strokes.is_empty() {
                    paths.push(PathStrokes { id: &p.id, strokes });
                }
            });
        }
        if !paths.is_empty() {
            let name = scene.pen(number).map_or("", |p| p.name.as_str());
            blocks.push(PenBlock {
                number,
                name,
                codes: LayerCodes::of(name),
                paths,
            });
        }
    }
    blocks
}

/// Flattens one path into strokes. A lone move-to draws nothing and is
/// dropped; a subpath of coincident points stays as a one-point stroke (a
/// dot). Consecutive equal points are merged.
pub(super) fn flatten_strokes(
    elements: impl IntoIterator<Item = PathEl>,
    tolerance: f64,
) -> Vec<Stroke> {
    // kurbo's flatten drops a segment that follows a close-path without a
    // move-to; the SVG meaning is "start again at the subpath's start".
    let mut start = None;
    let mut after_close = false;
    let mut fixed = Vec::new();
    for el in elements {
        match el {
            PathEl::MoveTo(p) => start = Some(p),
            PathEl::ClosePath => {}
            _ => {
                if after_close {
                    if let Some(s) = start {
                        fixed.push(PathEl::MoveTo(s));
                    }
                }
            }
        }
        after_close = el == PathEl::ClosePath;
        fixed.push(el);
    }

    let mut b = StrokeBuilder::default();
    kurbo::flatten(fixed, tolerance, |el| match el {
        PathEl::MoveTo(p) => {
            b.finish(false);
            b.points.push(p);
        }
        PathEl::LineTo(p) => {
            b.drawn = true;
            if b.points.last() != Some(&p) {
                b.points.push(p);
            }
        }
        PathEl::ClosePath => {
            b.drawn = true;
            b.finish(true);
        }
        // flatten only emits the three above.
        PathEl::QuadTo(..) | PathEl::CurveTo(..) => {}
    });
    b.finish(false);
    b.strokes
}

#[derive(Default)]
struct StrokeBuilder {
    strokes: Vec<Stroke>,
    /// The subpath being flattened, without consecutive duplicates.
    points: Vec<Point>,
    /// A line or close followed the move-to (so even one point is a dot).
    drawn: bool,
}

impl StrokeBuilder {
    fn finish(&mut self, close: bool) {
        let mut points = std::mem::take(&mut self.points);
        if self.drawn && !points.is_empty() {
            let first = points[0];
            let n = points.len();
            let ends_on_start = n > 2 && first.distance(points[n - 1]) <= CLOSE_EPSILON;
            let closed = close || ends_on_start;
            if closed && n > 1 {
                // End exactly on the start.
                if ends_on_start {
                    points.pop();
                }
                points.push(first);
            }
            self.strokes.push(Stroke {
                points,
                closed,
                refill_before: false,
            });
        }
        self.drawn = false;
    }
}

/// Page millimetres (origin at the sheet's top-left corner, y down) to a
/// machine's millimetres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct ToMachine {
    /// The sheet's width and height, mm.
    pub page: (f64, f64),
    /// X runs from the right edge: `width − x`.
    pub mirror_x: bool,
    /// Y is measured from the bottom edge: `height − y`.
    pub from_bottom: bool,
    /// Y, so measured, is negated.
    pub negate_y: bool,
}

impl ToMachine {
    /// `p` in machine millimetres.
    pub(super) fn map(&self, p: Point) -> Point {
        let (width, height) = self.page;
        let x = if self.mirror_x { width - p.x } else { p.x };
        let from_edge = if self.from_bottom { height - p.y } else { p.y };
        let y = if self.negate_y { -from_edge } else { from_edge };
        Point::new(x, y)
    }

    /// `stroke` in machine millimetres.
    pub(super) fn stroke(&self, stroke: &Stroke) -> Stroke {
        Stroke {
            points: stroke.points.iter().map(|&p| self.map(p)).collect(),
            ..*stroke
        }
    }
}

/// `Err` unless `v` is finite and greater than zero (for options).
pub(super) fn positive(field: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(
            field,
            format!("must be a number greater than 0, got {v}"),
        ))
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::scene::{Color, Group, Layer, Pen, Style};
    use crate::units::{Margins, Orientation, Page};
    use kurbo::{Affine, BezPath, Circle, Rect, Shape};

    /// Two pens on a 100 × 80 mm landscape page with 5 mm margins: pen 1
    /// draws a square (front layer) and an open curve (back layer, so it
    /// comes first); pen 2, listed first in the description, a circle
    /// inside a transformed group.
    pub(in crate::output) fn two_pen_scene() -> Scene {
        let mut square = Group::new("outline");
        square.push_path(
            "square",
            Rect::new(5.0, 5.0, 25.0, 25.0).to_path(0.1),
            Style::default(),
        );

        let mut vine = Group::new("vine");
        let mut curve = BezPath::new();
        curve.move_to((5.0, 60.0));
        curve.curve_to((20.0, 40.0), (40.0, 70.0), (55.0, 50.0));
        vine.push_path("curve", curve, Style::default());

        let mut ring = Group::new("ring");
        ring.transform = Affine::translate((60.0, 30.0)) * Affine::scale(2.0);
        ring.push_path(
            "circle",
            Circle::new((0.0, 0.0), 4.0).to_path(0.1),
            Style::default(),
        );

        let layer = |id: &str, pen, depth, content| Layer {
            id: id.into(),
            name: id.into(),
            pen,
            depth,
            content,
        };
        Scene {
            page: Page::sized(100.0, 80.0, Orientation::Landscape, Margins::uniform(5.0)),
            pens: vec![
                Pen {
                    number: 1,
                    name: "black".into(),
                    color: Color::BLACK,
                    width: 0.3,
                },
                Pen {
                    number: 2,
                    name: "red".into(),
                    color: Color::rgb(255, 0, 0),
                    width: 0.3,
                },
            ],
            layers: vec![
                layer("circle-layer", 2, 0, ring),
                layer("square-layer", 1, 0, square),
                layer("vine-layer", 1, 1, vine),
            ],
            description: None,
        }
    }

    /// [`two_pen_scene`] with two layers that are not plotted: `%guides`
    /// (pen 1, a frame near the sheet's edge, in front of everything) and
    /// `% 3 notes` (pen 3, which draws nothing else).
    pub(in crate::output) fn with_unplotted_layers(mut scene: Scene) -> Scene {
        let mut frame = Group::new("frame");
        frame.push_path(
            "frame-outline",
            Rect::new(-4.0, -4.0, 94.0, 74.0).to_path(0.1),
            Style::default(),
        );
        let mut notes = Group::new("notes");
        notes.transform = Affine::translate((70.0, 10.0));
        let mut arrow = BezPath::new();
        arrow.move_to((0.0, 0.0));
        arrow.quad_to((7.0, 3.0), (13.0, 17.0));
        notes.push_path("arrow", arrow, Style::default());
        let layer = |id: &str, name: &str, pen, depth, content| Layer {
            id: id.into(),
            name: name.into(),
            pen,
            depth,
            content,
        };
        scene
            .layers
            .insert(1, layer("guides", "%guides", 1, -1, frame));
        scene.layers.push(layer("notes", "% 3 notes", 3, 5, notes));
        scene.pens.push(Pen {
            number: 3,
            name: "pencil".into(),
            color: Color::rgb(128, 128, 128),
            width: 0.1,
        });
        scene
    }

    #[test]
    fn flattening_keeps_within_tolerance() {
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.curve_to((10.0, 20.0), (30.0, -20.0), (40.0, 0.0));
        let exact = p.clone();
        // kurbo's subdivision count is an estimate: the error may exceed
        // the tolerance somewhat (by about a quarter on this S-curve).
        for tol in [0.5, 0.02] {
            let slack = 1.5;
            let s = flatten_strokes(p.iter(), tol);
            assert_eq!(s.len(), 1);
            assert!(!s[0].closed);
            let pts = &s[0].points;
            assert_eq!(pts[0], Point::new(0.0, 0.0));
            assert_eq!(*pts.last().unwrap(), Point::new(40.0, 0.0));
            // The polyline stays within the tolerance of the curve: its
            // vertices and the middles of its segments.
            let seg = exact.segments().next().unwrap();
            let off = |q: Point| {
                kurbo::ParamCurveNearest::nearest(&seg, q, 1e-9)
                    .distance_sq
                    .sqrt()
            };
            for w in pts.windows(2) {
                assert!(off(w[0]) <= tol, "{tol}");
                let mid = off(w[0].midpoint(w[1]));
                assert!(mid <= tol * slack, "{tol}: {mid}");
            }
            assert!(pts.len() > 3);
        }
        // Zero and negative tolerances do not hang.
        assert!(!pen_blocks(&two_pen_scene(), 0.0).is_empty());
        assert!(!pen_blocks(&two_pen_scene(), -1.0).is_empty());
    }

    #[test]
    fn strokes_of_odd_paths() {
        let mut p = BezPath::new();
        // A lone move-to draws nothing.
        p.move_to((1.0, 1.0));
        // A dot.
        p.move_to((2.0, 2.0));
        p.line_to((2.0, 2.0));
        // A closed triangle, then a segment after the close without move-to,
        // which starts again at the triangle's start.
        p.move_to((0.0, 0.0));
        p.line_to((10.0, 0.0));
        p.line_to((10.0, 10.0));
        p.close_path();
        p.line_to((0.0, 5.0));
        // An explicitly repeated start point counts as closed.
        p.move_to((20.0, 0.0));
        p.line_to((30.0, 0.0));
        p.line_to((30.0, 10.0));
        p.line_to((20.0, 0.0));
        let s = flatten_strokes(p.iter(), 0.1);
        let pts =
            |i: usize| -> Vec<(f64, f64)> { s[i].points.iter().map(|p| (p.x, p.y)).collect() };
        assert_eq!(s.len(), 4);
        assert_eq!(pts(0), [(2.0, 2.0)]);
        assert_eq!(pts(1), [(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 0.0)]);
        assert!(s[1].closed);
        assert_eq!(pts(2), [(0.0, 0.0), (0.0, 5.0)]);
        assert!(!s[2].closed);
        assert_eq!(
            pts(3),
            [(20.0, 0.0), (30.0, 0.0), (30.0, 10.0), (20.0, 0.0)]
        );
        assert!(s[3].closed);
    }

    #[test]
    fn machine_mapping_mirrors_measures_and_negates() {
        let p = Point::new(10.0, 30.0);
        let map = |mirror_x, from_bottom, negate_y| {
            let m = ToMachine {
                page: (100.0, 80.0),
                mirror_x,
                from_bottom,
                negate_y,
            };
            let q = m.map(p);
            (q.x, q.y)
        };
        assert_eq!(map(false, false, false), (10.0, 30.0));
        assert_eq!(map(false, true, false), (10.0, 50.0));
        assert_eq!(map(false, true, true), (10.0, -50.0));
        assert_eq!(map(false, false, true), (10.0, -30.0));
        assert_eq!(map(true, false, false), (90.0, 30.0));
    }
}
