//! The "far side of a line" test used for the kimono upper and lower region
//! lines (docs/SPEC.md §1.2).
//!
//! A point is beyond a line when it lies on the far side of the line
//! measured along the line's normal at the nearest point, not when its y is
//! smaller, so the test also works for lines that are not graphs of x.

use kurbo::{BezPath, ParamCurve, ParamCurveNearest, PathSeg, Point, Rect};

use super::walk::segment_tangent;
use super::{Side, TOLERANCE};

/// Points closer than this (mm) to the line on the far side still count as
/// on the line, so a point taken from the line itself is never beyond it
/// despite rounding in the nearest-point search.
const ON_LINE: f64 = 1e-7;

/// Segments whose control points all lie within this distance (mm) of each
/// other are dots with no direction; they are dropped so they cannot be
/// chosen as the nearest piece of the line.
const MIN_EXTENT: f64 = 1e-9;

/// A line (any path) with a chosen far side, ready for point queries.
///
/// Beyond the ends of the line the nearest point is the end itself, so the
/// line behaves as if extended along its end tangents.
#[derive(Debug, Clone)]
pub struct SideTest {
    /// Segments with the bounding box of their control points, which contains
    /// the segment and lets queries skip segments that cannot be nearest.
    segments: Vec<(PathSeg, Rect)>,
    far: Side,
}

impl SideTest {
    /// Prepares `path` for queries; `far` is the side, relative to the
    /// path's direction of travel, that counts as beyond.
    pub fn new(path: &BezPath, far: Side) -> SideTest {
        let segments = path
            .segments()
            .map(|seg| (seg, control_box(seg)))
            .filter(|(_, bbox)| bbox.width().hypot(bbox.height()) > MIN_EXTENT)
            .collect();
        SideTest { segments, far }
    }

    /// Whether `p` lies strictly on the far side of the line. Points on the
    /// line are not beyond; an empty line has nothing beyond it.
    pub fn is_beyond(&self, p: Point) -> bool {
        self.signed_distance(p) > ON_LINE
    }

    /// Distance in mm from `p` to the line, measured along the unit normal
    /// at the nearest point of the line: positive on the far side, negative
    /// on the near side. Beyond the ends this is the distance to the end
    /// tangent extended. `-∞` for an empty line.
    pub fn signed_distance(&self, p: Point) -> f64 {
        let mut best: Option<(PathSeg, f64, f64)> = None;
        for &(seg, bbox) in &self.segments {
            let best_sq = best.map_or(f64::INFINITY, |(_, _, d)| d);
            // The box contains the segment, so the segment is no nearer than
            // the box; at equal distance it could only tie, and ties keep
            // the first minimum.
            if rect_distance_sq(bbox, p) >= best_sq {
                continue;
            }
            let near = seg.nearest(p, TOLERANCE * 0.1);
            if near.distance_sq < best_sq {
                best = Some((seg, near.t, near.distance_sq));
            }
        }
        let Some((seg, t, _)) = best else {
            return f64::NEG_INFINITY;
        };
        // Only a segment shorter than rounding noise has no tangent; it has
        // no sides either, so the point counts as on the line.
        segment_tangent(seg, t).map_or(0.0, |d| (p - seg.eval(t)).dot(self.far.normal(d)))
    }
}

/// The bounding box of a segment's control points.
fn control_box(seg: PathSeg) -> Rect {
    let c = seg.to_cubic();
    [c.p1, c.p2, c.p3]
        .into_iter()
        .fold(Rect::from_points(c.p0, c.p0), |r, q| r.union_pt(q))
}

/// Squared distance from `p` to the rectangle (0 inside).
fn rect_distance_sq(r: Rect, p: Point) -> f64 {
    let dx = (r.x0 - p.x).max(p.x - r.x1).max(0.0);
    let dy = (r.y0 - p.y).max(p.y - r.y1).max(0.0);
    dx * dx + dy * dy
}

#[cfg(test)]
mod tests {
    use super::super::{natural_spline, PathWalker};
    use super::*;
    use proptest::prelude::*;

    fn polyline(pts: &[(f64, f64)]) -> BezPath {
        let mut p = BezPath::new();
        p.move_to(pts[0]);
        for &q in &pts[1..] {
            p.line_to(q);
        }
        p
    }

    #[test]
    fn above_a_rightward_line_is_beyond_its_left() {
        let test = SideTest::new(&polyline(&[(0.0, 50.0), (100.0, 50.0)]), Side::Left);
        assert!(test.is_beyond(Point::new(30.0, 49.0)));
        assert!(!test.is_beyond(Point::new(30.0, 51.0)));
        assert!((test.signed_distance(Point::new(30.0, 40.0)) - 10.0).abs() < 1e-9);
        assert!((test.signed_distance(Point::new(30.0, 60.0)) + 10.0).abs() < 1e-9);
    }

    #[test]
    fn points_on_the_line_are_not_beyond() {
        let test = SideTest::new(&polyline(&[(0.0, 50.0), (100.0, 50.0)]), Side::Left);
        assert!(!test.is_beyond(Point::new(30.0, 50.0)));
        assert!(!test.is_beyond(Point::new(0.0, 50.0)));
    }

    #[test]
    fn vertical_line() {
        // Walking down the page (+y), left is +x.
        let test = SideTest::new(&polyline(&[(10.0, 0.0), (10.0, 100.0)]), Side::Left);
        assert!(test.is_beyond(Point::new(11.0, 50.0)));
        assert!(!test.is_beyond(Point::new(9.0, 50.0)));
        let right = SideTest::new(&polyline(&[(10.0, 0.0), (10.0, 100.0)]), Side::Right);
        assert!(right.is_beyond(Point::new(9.0, 50.0)));
    }

    #[test]
    fn s_shaped_spline_follows_the_normal() {
        let pts = [
            (0.0, 0.0),
            (20.0, -30.0),
            (40.0, 0.0),
            (60.0, 30.0),
            (80.0, 0.0),
        ]
        .map(|(x, y)| Point::new(x, y));
        let line = natural_spline(&pts);
        let test = SideTest::new(&line, Side::Left);
        let walker = PathWalker::new(&line, 1e-4);
        for (q, d) in walker.sample_even_with_tangents(40) {
            let n = Side::Left.normal(d);
            let out = test.signed_distance(q + n * 2.0);
            let inside = test.signed_distance(q - n * 2.0);
            assert!((out - 2.0).abs() < 1e-2, "at {q:?}: {out}");
            assert!((inside + 2.0).abs() < 1e-2, "at {q:?}: {inside}");
        }
        // Directly above the trough at x = 60 is beyond even though it is
        // below the crest at x = 20: the test is not "y smaller than".
        assert!(test.is_beyond(Point::new(60.0, 25.0)));
        assert!(!test.is_beyond(Point::new(20.0, -25.0)));
    }

    #[test]
    fn beyond_the_ends_the_end_tangent_is_extended() {
        // Flat, then rising at 45° up-right.
        let test = SideTest::new(
            &polyline(&[(0.0, 0.0), (10.0, 0.0), (20.0, -10.0)]),
            Side::Left,
        );
        // Above the flat part's height but under the extended rising tangent.
        assert!(!test.is_beyond(Point::new(30.0, -15.0)));
        assert!(test.is_beyond(Point::new(25.0, -20.0)));
        let extended = test.signed_distance(Point::new(30.0, -15.0));
        assert!((extended + 5.0 / 2f64.sqrt()).abs() < 1e-9, "{extended}");
        // Before the start, the flat start tangent is extended.
        assert!(test.is_beyond(Point::new(-50.0, -1.0)));
        assert!(!test.is_beyond(Point::new(-50.0, 1.0)));
    }

    #[test]
    fn empty_line_has_nothing_beyond() {
        let test = SideTest::new(&BezPath::new(), Side::Left);
        assert!(!test.is_beyond(Point::new(0.0, 0.0)));
        assert_eq!(
            test.signed_distance(Point::new(0.0, 0.0)),
            f64::NEG_INFINITY
        );
    }

    #[test]
    fn many_segment_line_gives_same_answer_as_its_local_piece() {
        // A long zigzag: the bbox early-out must not change the result.
        let pts: Vec<(f64, f64)> = (0..200)
            .map(|i| (i as f64 * 2.0, if i % 2 == 0 { 0.0 } else { 1.0 }))
            .collect();
        let test = SideTest::new(&polyline(&pts), Side::Left);
        assert!(test.is_beyond(Point::new(201.0, -5.0)));
        assert!(!test.is_beyond(Point::new(201.0, 6.0)));
    }

    proptest! {
        #[test]
        fn offsets_along_the_normal_of_a_spline_have_that_signed_distance(
            ys in prop::collection::vec(-20.0..20.0f64, 4..=8),
            frac in 0.05..0.95f64,
            off in 0.2..3.0f64,
        ) {
            // Gentle graphs of x with 30 mm spacing keep the curvature radius
            // well above the offset, so the offset point's nearest point is
            // the point it was offset from.
            let pts: Vec<Point> = ys.iter().enumerate()
                .map(|(i, &y)| Point::new(i as f64 * 30.0, y * 0.3)).collect();
            let line = natural_spline(&pts);
            let walker = PathWalker::new(&line, 1e-5);
            let s = frac * walker.length();
            let (q, n) = (walker.point_at(s), Side::Right.normal(walker.tangent_at(s)));
            let test = SideTest::new(&line, Side::Right);
            prop_assert!((test.signed_distance(q + n * off) - off).abs() < 1e-2);
            prop_assert!((test.signed_distance(q - n * off) + off).abs() < 1e-2);
            prop_assert!(!test.is_beyond(q - n * off));
        }
    }
}
