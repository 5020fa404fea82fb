//! Simplification: fewer points where the pen would not show the
//! difference.
//!
//! Every run of consecutive straight segments (a polyline, as in flattened
//! or imported paths) is reduced with Ramer–Douglas–Peucker: a point is
//! dropped when it lies within [`SimplifyOptions::tolerance`] of the
//! straight line (segment, not infinite line, so spikes stay) that then
//! replaces it. The ends of a run — where a curve, a move-to or the path's
//! end meets it — are kept, so are curves: quadratic and cubic segments are
//! left exactly as they are (they are already compact, and refitting them
//! would trade one small error for another). A closed polyline keeps its
//! first point; its closing segment takes part in the simplification.
//!
//! Guarantees: every dropped point lies within `tolerance` of the result,
//! nothing else moves, and the pen-down length never grows (a straight
//! line is never longer than the polyline it replaces); it shrinks by the
//! detours the tolerance allows (for a zigzag of amplitude below the
//! tolerance, the whole zigzag). Works on any layer, in the coordinates of
//! the flat scene (see [`super::flatten`]).

use kurbo::{BezPath, PathEl, Point};
use serde::{Deserialize, Serialize};

use super::flatten::{set_paths, take_paths};
use crate::geom::simplify::rdp;
use crate::scene::Scene;

/// Options of [`run`] and [`simplify_path`].
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SimplifyOptions {
    /// Largest distance, in mm, of a dropped point from the result. Zero
    /// drops only points exactly on the line; a negative or NaN value
    /// counts as zero.
    pub tolerance: f64,
}

impl SimplifyOptions {
    /// 0.05 mm: a sixth of a fine pen's line width.
    pub const DEFAULT: SimplifyOptions = SimplifyOptions { tolerance: 0.05 };

    /// These options with [`SimplifyOptions::tolerance`] set.
    pub const fn with_tolerance(mut self, tolerance: f64) -> SimplifyOptions {
        self.tolerance = tolerance;
        self
    }
}

impl Default for SimplifyOptions {
    fn default() -> SimplifyOptions {
        SimplifyOptions::DEFAULT
    }
}

/// Simplifies every path of every layer of `scene` (see the module
/// documentation). Paths keep their ids, order and subpaths.
pub fn run(scene: &mut Scene, options: &SimplifyOptions) {
    for layer in &mut scene.layers {
        let mut paths = take_paths(layer);
        for p in &mut paths {
            p.path = simplify_path(&p.path, options);
        }
        set_paths(layer, paths);
    }
}

/// `path` with its polyline runs simplified.
pub fn simplify_path(path: &BezPath, options: &SimplifyOptions) -> BezPath {
    let tolerance = if options.tolerance >= 0.0 {
        options.tolerance
    } else {
        0.0
    };
    let mut out = Vec::with_capacity(path.elements().len());
    // The current polyline run; `run[0]` is already written.
    let mut run: Vec<Point> = Vec::new();
    let mut start = Point::ORIGIN;
    let mut keep = Vec::new();
    for &el in path.elements() {
        match el {
            PathEl::LineTo(p) => run.push(p),
            PathEl::ClosePath => {
                if run.len() > 1 {
                    // The closing segment joins the run; its end (the
                    // start) is written by the close-path itself.
                    run.push(start);
                    flush(&mut run, tolerance, &mut keep, &mut out, true);
                }
                run.clear();
                run.push(start);
                out.push(el);
            }
            PathEl::MoveTo(p) => {
                flush(&mut run, tolerance, &mut keep, &mut out, false);
                start = p;
                run.push(p);
                out.push(el);
            }
            PathEl::QuadTo(_, p) | PathEl::CurveTo(_, _, p) => {
                flush(&mut run, tolerance, &mut keep, &mut out, false);
                run.push(p);
                out.push(el);
            }
        }
    }
    flush(&mut run, tolerance, &mut keep, &mut out, false);
    BezPath::from_vec(out)
}

/// Writes the simplified run (without its first point, which is written,
/// and without its last if `closing`) and empties it.
fn flush(
    run: &mut Vec<Point>,
    tolerance: f64,
    keep: &mut Vec<bool>,
    out: &mut Vec<PathEl>,
    closing: bool,
) {
    if run.len() > 1 {
        rdp(run, tolerance, keep);
        let last = run.len() - 1;
        for (i, p) in run.iter().enumerate().skip(1) {
            if keep[i] && !(closing && i == last) {
                out.push(PathEl::LineTo(*p));
            }
        }
    }
    run.clear();
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::path_length;
    use kurbo::ParamCurveNearest;
    use proptest::prelude::*;

    fn polyline(pts: &[(f64, f64)], close: bool) -> BezPath {
        let mut p = BezPath::new();
        p.move_to(pts[0]);
        for &q in &pts[1..] {
            p.line_to(q);
        }
        if close {
            p.close_path();
        }
        p
    }

    fn distance_to(path: &BezPath, p: Point) -> f64 {
        path.segments()
            .map(|s| s.nearest(p, 1e-9).distance_sq.sqrt())
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn drops_near_collinear_points_keeps_corners() {
        let p = polyline(
            &[
                (0.0, 0.0),
                (5.0, 0.01),
                (10.0, 0.0),
                (10.0, 10.0),
                (10.0, 20.0),
            ],
            false,
        );
        let s = simplify_path(&p, &SimplifyOptions::DEFAULT);
        assert_eq!(s, polyline(&[(0.0, 0.0), (10.0, 0.0), (10.0, 20.0)], false));
    }

    #[test]
    fn keeps_spikes_and_dots() {
        // Back along the same line: a spike the segment distance keeps.
        let p = polyline(&[(0.0, 0.0), (10.0, 0.0), (5.0, 0.0)], false);
        assert_eq!(simplify_path(&p, &SimplifyOptions::DEFAULT), p);
        let dot = polyline(&[(1.0, 1.0), (1.0, 1.0)], false);
        assert_eq!(simplify_path(&dot, &SimplifyOptions::DEFAULT), dot);
    }

    #[test]
    fn curves_and_closed_polygons() {
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.line_to((1.0, 0.0));
        p.line_to((2.0, 0.0));
        p.curve_to((3.0, 1.0), (4.0, 1.0), (5.0, 0.0));
        p.line_to((5.0, 5.0));
        p.line_to((5.0, 10.0));
        p.line_to((0.0, 10.0));
        p.line_to((0.0, 5.0));
        p.close_path();
        let s = simplify_path(&p, &SimplifyOptions::DEFAULT);
        let mut want = BezPath::new();
        want.move_to((0.0, 0.0));
        want.line_to((2.0, 0.0));
        want.curve_to((3.0, 1.0), (4.0, 1.0), (5.0, 0.0));
        want.line_to((5.0, 10.0));
        want.line_to((0.0, 10.0));
        want.close_path();
        assert_eq!(s, want);
    }

    proptest! {
        #[test]
        fn dropped_points_stay_within_tolerance(
            pts in prop::collection::vec((-50.0..50.0f64, -50.0..50.0f64), 2..60),
            close: bool,
            tol in 0.0..3.0f64,
        ) {
            let p = polyline(&pts, close);
            let s = simplify_path(&p, &SimplifyOptions::DEFAULT.with_tolerance(tol));
            prop_assert!(s.elements().len() <= p.elements().len());
            prop_assert!(path_length(&s) <= path_length(&p) + 1e-9);
            prop_assert_eq!(s.elements()[0], p.elements()[0]);
            prop_assert_eq!(s.elements().last().copied() == Some(PathEl::ClosePath), close);
            if !close {
                prop_assert_eq!(s.elements().last(), p.elements().last());
            }
            for &q in &pts {
                let d = distance_to(&s, Point::from(q));
                prop_assert!(d <= tol + 1e-9, "{} > {}", d, tol);
            }
        }
    }
}
