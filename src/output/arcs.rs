//! Arcs for G-code (`G2`/`G3`): the runs of a flattened stroke that lie on
//! one circle, written as one move instead of many short lines. Fewer,
//! longer moves plot smoother on GRBL and Marlin, whose planners slow down
//! at every junction of short segments, and make programs smaller.
//!
//! [`fit`] walks the stroke's points and, from each point, takes the
//! longest run of at least three segments (at most [`MAX_RUN`]) whose
//! points lie within the arc tolerance of the circle through the run's
//! first, middle and last point, turning one way, sweeping less than
//! [`MAX_SWEEP`], with a radius of at most [`MAX_RADIUS`] (flatter runs
//! are lines). The points of a flattened stroke lie on its curve, and the
//! middle of a segment up to the flattening tolerance off it, so segment
//! midpoints are allowed the two tolerances together: that keeps the arc
//! within the arc tolerance of the curve between the points too, while a
//! polyline that really has corners never passes. Where no run starts, a
//! line goes to the next point.

use kurbo::{Point, Vec2};

/// The most segments one arc replaces (bounds the fitting work).
pub(super) const MAX_RUN: usize = 256;

/// The largest radius written as an arc, mm: flatter runs are straight
/// enough for lines, and controllers lose precision on huge radii.
pub(super) const MAX_RADIUS: f64 = 1000.0;

/// The largest sweep of one arc, radians (350°): a full circle's end is
/// its start, which controllers read differently.
pub(super) const MAX_SWEEP: f64 = 350.0 * std::f64::consts::PI / 180.0;

/// One move of a stroke after its first point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Move {
    /// A straight line to the point.
    Line(Point),
    /// An arc to `to` around `center`, counter-clockwise (`G3`) or
    /// clockwise (`G2`) in machine coordinates.
    Arc {
        /// Where the arc ends.
        to: Point,
        /// The circle's centre.
        center: Point,
        /// Counter-clockwise, seen with X right and Y up.
        ccw: bool,
    },
}

/// The moves that draw `points` (after the first), flattened within
/// `flattening` mm, with arcs where they fit within `tolerance` mm.
pub(super) fn fit(points: &[Point], tolerance: f64, flattening: f64) -> Vec<Move> {
    let mut moves = Vec::new();
    let mut i = 0;
    while i + 1 < points.len() {
        let mut best = None;
        let mut j = i + 3;
        while j < points.len() && j - i <= MAX_RUN {
            match arc(&points[i..=j], tolerance, flattening) {
                Some(found) => best = Some((j, found)),
                None => break,
            }
            j += 1;
        }
        match best {
            Some((j, (center, ccw))) => {
                moves.push(Move::Arc {
                    to: points[j],
                    center,
                    ccw,
                });
                i = j;
            }
            None => {
                moves.push(Move::Line(points[i + 1]));
                i += 1;
            }
        }
    }
    moves
}

/// The centre and direction of the circle `run` lies on, if it does (see
/// the module documentation).
fn arc(run: &[Point], tolerance: f64, flattening: f64) -> Option<(Point, bool)> {
    let (a, m, b) = (run[0], run[run.len() / 2], run[run.len() - 1]);
    let center = circumcenter(a, m, b)?;
    let r = center.distance(a);
    if !(r.is_finite() && r <= MAX_RADIUS) {
        return None;
    }
    let off = |p: Point| (p.distance(center) - r).abs();
    let mut sweep = 0.0;
    let mut direction = 0.0;
    for w in run.windows(2) {
        if off(w[1]) > tolerance || off(w[0].midpoint(w[1])) > tolerance + flattening {
            return None;
        }
        let (u, v): (Vec2, Vec2) = (w[0] - center, w[1] - center);
        let turn = u.cross(v).atan2(u.dot(v));
        if turn == 0.0 || turn * direction < 0.0 {
            return None;
        }
        direction = turn.signum();
        sweep += turn;
    }
    (sweep.abs() < MAX_SWEEP).then_some((center, sweep > 0.0))
}

/// The centre of the circle through three points; `None` when they are
/// (nearly) on one line.
fn circumcenter(a: Point, b: Point, c: Point) -> Option<Point> {
    let (ab, ac) = (b - a, c - a);
    let d = 2.0 * ab.cross(ac);
    if d.abs() < 1e-12 {
        return None;
    }
    let (ab2, ac2) = (ab.hypot2(), ac.hypot2());
    let ux = (ac.y * ab2 - ab.y * ac2) / d;
    let uy = (ab.x * ac2 - ac.x * ab2) / d;
    Some(a + Vec2::new(ux, uy))
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{BezPath, Circle, ParamCurveNearest, Shape};

    fn flattened(path: &BezPath, tolerance: f64) -> Vec<Point> {
        let mut points = Vec::new();
        kurbo::flatten(path, tolerance, |el| match el {
            kurbo::PathEl::MoveTo(p) | kurbo::PathEl::LineTo(p) => points.push(p),
            _ => {}
        });
        points
    }

    /// Points along the moves, a point every ~0.05 mm of arc.
    fn trace(start: Point, moves: &[Move]) -> Vec<Point> {
        let mut at = start;
        let mut out = vec![start];
        for m in moves {
            match *m {
                Move::Line(p) => {
                    out.push(p);
                    at = p;
                }
                Move::Arc { to, center, ccw } => {
                    let (u, v) = (at - center, to - center);
                    let mut sweep = u.cross(v).atan2(u.dot(v));
                    if ccw && sweep < 0.0 {
                        sweep += std::f64::consts::TAU;
                    } else if !ccw && sweep > 0.0 {
                        sweep -= std::f64::consts::TAU;
                    }
                    let r = u.hypot();
                    let steps = ((sweep.abs() * r / 0.05).ceil() as usize).max(1);
                    for k in 1..=steps {
                        let t = u.atan2() + sweep * k as f64 / steps as f64;
                        out.push(center + Vec2::from_angle(t) * r);
                    }
                    at = to;
                }
            }
        }
        out
    }

    #[test]
    fn a_circle_becomes_a_few_arcs_on_it() {
        let circle = Circle::new((50.0, 40.0), 12.0).to_path(1e-3);
        let points = flattened(&circle, 0.01);
        let moves = fit(&points, 0.01, 0.01);
        let arcs = moves
            .iter()
            .filter(|m| matches!(m, Move::Arc { .. }))
            .count();
        assert!(arcs >= 2 && moves.len() <= 4, "{moves:?}");
        for p in trace(points[0], &moves) {
            let d = (p.distance((50.0, 40.0).into()) - 12.0).abs();
            assert!(d < 0.02, "{d}");
        }
        // Ends where the polyline ends.
        let end = match moves.last().unwrap() {
            Move::Arc { to, .. } | Move::Line(to) => *to,
        };
        assert_eq!(end, *points.last().unwrap());
    }

    #[test]
    fn direction_follows_the_turn() {
        // Counter-clockwise with Y up: from (10, 0) round the origin to (0, 10).
        let ccw: Vec<Point> = (0..=30)
            .map(|k| Point::new(0.0, 0.0) + Vec2::from_angle(k as f64 * 0.05) * 10.0)
            .collect();
        let moves = fit(&ccw, 0.01, 0.0);
        assert!(
            matches!(moves[..], [Move::Arc { ccw: true, .. }]),
            "{moves:?}"
        );
        let cw: Vec<Point> = ccw.iter().rev().copied().collect();
        assert!(matches!(
            fit(&cw, 0.01, 0.0)[..],
            [Move::Arc { ccw: false, .. }]
        ));
    }

    #[test]
    fn straight_lines_and_sharp_corners_stay_lines() {
        let zigzag: Vec<Point> = (0..10)
            .map(|k| Point::new(k as f64, if k % 2 == 0 { 0.0 } else { 1.0 }))
            .collect();
        assert!(fit(&zigzag, 0.01, 0.01)
            .iter()
            .all(|m| matches!(m, Move::Line(_))));
        let straight: Vec<Point> = (0..10).map(|k| Point::new(k as f64, 0.0)).collect();
        assert_eq!(fit(&straight, 0.01, 0.01).len(), 9);
        // An S curve turns both ways: never one arc across the inflection,
        // and what is drawn stays near the curve itself.
        let s = kurbo::CubicBez::new((0.0, 0.0), (10.0, 10.0), (20.0, -10.0), (30.0, 0.0));
        let mut path = BezPath::new();
        path.move_to(s.p0);
        path.curve_to(s.p1, s.p2, s.p3);
        let points = flattened(&path, 0.005);
        let moves = fit(&points, 0.01, 0.005);
        assert!(
            moves.iter().any(|m| matches!(m, Move::Arc { .. })),
            "{moves:?}"
        );
        for p in trace(points[0], &moves) {
            let off = s.nearest(p, 1e-9).distance_sq.sqrt();
            assert!(off <= 0.015, "{off}");
        }
    }
}
