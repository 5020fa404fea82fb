//! Walking a path by arc length: points and unit tangents at a distance
//! along the path, and evenly spaced samples.

use kurbo::{BezPath, ParamCurve, ParamCurveArclen, ParamCurveDeriv, PathSeg, Point, Vec2};

/// Derivatives shorter than this (mm per unit of the segment parameter) are
/// treated as zero: their direction is rounding noise.
const MIN_DERIVATIVE: f64 = 1e-12;

/// How far (in segment parameter) to step inwards when the derivative
/// vanishes at a point, e.g. at an end whose control point coincides with it.
const NUDGE: f64 = 1e-3;

/// Direction used when a path has no direction at all (empty or a single
/// point), so callers never see NaN.
const NO_DIRECTION: Vec2 = Vec2::new(1.0, 0.0);

/// A path prepared for queries by arc length.
///
/// Segments are walked in order, across subpaths; the jump from one subpath
/// to the next (a `MoveTo`) adds no length.
#[derive(Debug, Clone)]
pub struct PathWalker {
    segments: Vec<PathSeg>,
    /// Arc length from the start of the path to the end of each segment.
    cumulative: Vec<f64>,
    accuracy: f64,
}

impl PathWalker {
    /// Measures every segment of `path` to within `accuracy` mm.
    pub fn new(path: &BezPath, accuracy: f64) -> PathWalker {
        let segments: Vec<PathSeg> = path.segments().collect();
        let cumulative = segments
            .iter()
            .scan(0.0, |total, seg| {
                *total += seg.arclen(accuracy);
                Some(*total)
            })
            .collect();
        PathWalker {
            segments,
            cumulative,
            accuracy,
        }
    }

    /// Total arc length in mm (0 for an empty path).
    pub fn length(&self) -> f64 {
        self.cumulative.last().copied().unwrap_or(0.0)
    }

    /// The point at arc length `s` from the start, `s` clamped to
    /// `[0, length]`. The origin for an empty path.
    pub fn point_at(&self, s: f64) -> Point {
        match self.locate(s) {
            Some((i, t)) => self.segments[i].eval(t),
            None => Point::ORIGIN,
        }
    }

    /// The unit tangent (direction of travel) at arc length `s`, `s` clamped
    /// to `[0, length]`.
    ///
    /// Where the derivative vanishes the direction is taken from just inside
    /// the segment, then from its chord, then from the nearest segment that
    /// has one; a path with no direction at all gives +x. Never NaN.
    pub fn tangent_at(&self, s: f64) -> Vec2 {
        match self.locate(s) {
            Some((i, t)) => self.tangent_near(i, t),
            None => NO_DIRECTION,
        }
    }

    /// `n` points equally spaced by arc length; the first and last are
    /// exactly the ends of the path. `n = 1` gives just the start; an empty
    /// path gives no points.
    pub fn sample_even(&self, n: usize) -> Vec<Point> {
        self.sample_params(n)
            .map(|(i, t)| self.exact_eval(i, t))
            .collect()
    }

    /// Like [`sample_even`](Self::sample_even), with the unit tangent at each
    /// point.
    pub fn sample_even_with_tangents(&self, n: usize) -> Vec<(Point, Vec2)> {
        self.sample_params(n)
            .map(|(i, t)| (self.exact_eval(i, t), self.tangent_near(i, t)))
            .collect()
    }

    /// (segment index, segment parameter) of `n` evenly spaced samples.
    fn sample_params(&self, n: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let len = self.length();
        let n = if self.segments.is_empty() { 0 } else { n };
        let step = if n > 1 { len / (n - 1) as f64 } else { 0.0 };
        (0..n).filter_map(move |k| {
            // The last sample is placed by index, not by `k·step`, so rounding
            // cannot leave it short of the end.
            let s = if k + 1 == n && n > 1 {
                len
            } else {
                k as f64 * step
            };
            self.locate(s)
        })
    }

    /// Evaluates a segment, returning its stored end points exactly at
    /// t = 0 and t = 1 (evaluating the polynomial may be off by an ulp).
    fn exact_eval(&self, i: usize, t: f64) -> Point {
        let seg = self.segments[i];
        if t <= 0.0 {
            seg.start()
        } else if t >= 1.0 {
            seg.end()
        } else {
            seg.eval(t)
        }
    }

    /// The segment holding arc length `s` (clamped) and the parameter there.
    fn locate(&self, s: f64) -> Option<(usize, f64)> {
        let last = self.segments.len().checked_sub(1)?;
        let s = s.clamp(0.0, self.length());
        // First segment whose end reaches s; only a leading zero-length
        // segment can be picked with zero length, and only for s = 0.
        let i = self.cumulative.partition_point(|&end| end < s).min(last);
        let start = if i == 0 { 0.0 } else { self.cumulative[i - 1] };
        let seg_len = self.cumulative[i] - start;
        let local = s - start;
        let t = if local <= 0.0 || seg_len <= 0.0 {
            0.0
        } else if local >= seg_len {
            1.0
        } else {
            self.segments[i].inv_arclen(local, self.accuracy)
        };
        Some((i, t))
    }

    /// Unit tangent of segment `i` at `t`, falling back to the closest
    /// segment (earlier ones first at equal distance) that has a direction.
    fn tangent_near(&self, i: usize, t: f64) -> Vec2 {
        if let Some(d) = segment_tangent(self.segments[i], t) {
            return d;
        }
        let n = self.segments.len();
        (1..n)
            .flat_map(|k| {
                let before = i.checked_sub(k).map(|j| (j, 1.0));
                let after = (i + k < n).then_some((i + k, 0.0));
                before.into_iter().chain(after)
            })
            .find_map(|(j, tj)| segment_tangent(self.segments[j], tj))
            .unwrap_or(NO_DIRECTION)
    }
}

/// The unit tangent of `seg` at parameter `t`, or `None` when the segment has
/// no direction (all its points coincide).
///
/// Where the derivative vanishes (a control point on top of an end point, or
/// a cusp) the direction is taken from slightly inside the segment, then
/// from the chord.
pub(crate) fn segment_tangent(seg: PathSeg, t: f64) -> Option<Vec2> {
    let cubic = seg.to_cubic();
    let deriv = cubic.deriv();
    let inside = if t < 0.5 { t + NUDGE } else { t - NUDGE };
    [
        deriv.eval(t).to_vec2(),
        deriv.eval(inside).to_vec2(),
        cubic.p3 - cubic.p0,
    ]
    .into_iter()
    .find(|d| d.hypot() > MIN_DERIVATIVE)
    .map(Vec2::normalize)
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{Arc, Shape};
    use std::f64::consts::FRAC_PI_2;

    fn line(a: (f64, f64), b: (f64, f64)) -> BezPath {
        let mut p = BezPath::new();
        p.move_to(a);
        p.line_to(b);
        p
    }

    #[test]
    fn straight_line_length() {
        let w = PathWalker::new(&line((0.0, 0.0), (30.0, 40.0)), 1e-4);
        assert!((w.length() - 50.0).abs() < 1e-3);
    }

    #[test]
    fn quarter_circle_length() {
        let r = 20.0;
        let arc = Arc::new((0.0, 0.0), (r, r), 0.0, FRAC_PI_2, 0.0);
        let w = PathWalker::new(&arc.to_path(1e-6), 1e-4);
        assert!((w.length() - r * FRAC_PI_2).abs() < 1e-3, "{}", w.length());
    }

    #[test]
    fn samples_on_a_line_are_equally_spaced_and_hit_the_ends() {
        let w = PathWalker::new(&line((1.0, 2.0), (31.0, 42.0)), 1e-4);
        let pts = w.sample_even(11);
        assert_eq!(pts.len(), 11);
        assert_eq!(pts[0], Point::new(1.0, 2.0));
        assert_eq!(pts[10], Point::new(31.0, 42.0));
        for pair in pts.windows(2) {
            assert!((pair[0].distance(pair[1]) - 5.0).abs() < 1e-6);
        }
    }

    #[test]
    fn samples_on_a_curve_are_equally_spaced() {
        let arc = Arc::new((0.0, 0.0), (10.0, 10.0), 0.0, 3.0, 0.0);
        let w = PathWalker::new(&arc.to_path(1e-6), 1e-6);
        let pts = w.sample_even(31);
        // Equal arc steps on a circle subtend equal chords.
        let chord = pts[0].distance(pts[1]);
        for pair in pts.windows(2) {
            assert!((pair[0].distance(pair[1]) - chord).abs() < 1e-4);
        }
    }

    #[test]
    fn tangent_of_a_line_is_its_direction() {
        let w = PathWalker::new(&line((0.0, 0.0), (0.0, -5.0)), 1e-4);
        for s in [-1.0, 0.0, 2.5, 5.0, 99.0] {
            assert!((w.tangent_at(s) - Vec2::new(0.0, -1.0)).hypot() < 1e-12);
        }
    }

    #[test]
    fn s_is_clamped() {
        let w = PathWalker::new(&line((0.0, 0.0), (10.0, 0.0)), 1e-4);
        assert_eq!(w.point_at(-3.0), Point::new(0.0, 0.0));
        assert_eq!(w.point_at(13.0), Point::new(10.0, 0.0));
    }

    #[test]
    fn walks_through_subpaths_in_order() {
        let mut p = line((0.0, 0.0), (10.0, 0.0));
        p.move_to((100.0, 0.0));
        p.line_to((100.0, 10.0));
        let w = PathWalker::new(&p, 1e-4);
        assert!((w.length() - 20.0).abs() < 1e-9);
        assert!((w.point_at(15.0) - Point::new(100.0, 5.0)).hypot() < 1e-9);
        assert!((w.tangent_at(15.0) - Vec2::new(0.0, 1.0)).hypot() < 1e-12);
    }

    #[test]
    fn coincident_control_point_still_has_a_tangent() {
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.curve_to((0.0, 0.0), (10.0, 0.0), (10.0, 0.0));
        let w = PathWalker::new(&p, 1e-4);
        for (q, d) in w.sample_even_with_tangents(5) {
            assert!(q.is_finite() && d.is_finite());
            assert!((d - Vec2::new(1.0, 0.0)).hypot() < 1e-9, "{d:?}");
        }
    }

    #[test]
    fn zero_length_segments_fall_back_to_a_neighbour() {
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.line_to((0.0, 0.0));
        p.line_to((0.0, 8.0));
        let w = PathWalker::new(&p, 1e-4);
        assert!((w.tangent_at(0.0) - Vec2::new(0.0, 1.0)).hypot() < 1e-12);
    }

    #[test]
    fn empty_path_has_no_length_and_no_samples() {
        let w = PathWalker::new(&BezPath::new(), 1e-4);
        assert_eq!(w.length(), 0.0);
        assert!(w.sample_even(5).is_empty());
        assert!(w.sample_even_with_tangents(5).is_empty());
        assert!(w.tangent_at(1.0).is_finite());
    }
}
