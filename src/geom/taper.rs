//! Tapered limb outlines: a centre line turned into a closed shape whose
//! width falls smoothly from base to tip (docs/SPEC.md §1.3 "taper").

use kurbo::{BezPath, Point, Vec2};

use super::{natural_spline_cubics, PathWalker, Side, TOLERANCE};

/// Centre lines shorter than this (mm) have no direction to offset along.
const MIN_LENGTH: f64 = 1e-9;

/// Tip widths below this (mm) get no cap: the two sides meet at the tip.
const MIN_TIP: f64 = 1e-6;

/// Offset samples are at most this far apart (mm) along the centre, so the
/// offset splines follow the centre's curvature closely.
const MAX_SPACING: f64 = 1.5;

/// Each centre segment gets at least this many sample intervals, so short
/// but strongly curved segments are followed too.
const MIN_INTERVALS_PER_SEGMENT: usize = 4;

/// Upper bound on the number of samples, to keep long limbs cheap.
const MAX_SAMPLES: usize = 256;

/// Control-point distance, as a fraction of the radius, of a cubic that
/// approximates a quarter circle: 4/3·(√2 − 1).
const QUARTER_ARC_KAPPA: f64 = 0.552_284_749_830_793_4;

/// A closed outline around `centre` whose width varies linearly with arc
/// length from `base_width` at the start to `tip_width` at the end.
///
/// The outline runs up the left side (base → tip), round a half-circle cap
/// of diameter `tip_width` (none when the tip width is ~0: the sides meet),
/// down the right side (tip → base) and closes with a straight base edge.
/// Each side is a natural spline through offsets of arc-length samples of
/// the centre. Negative widths count as zero. `centre` should be a single
/// subpath; where it bends more tightly than half the width the sides will
/// loop, as any offset curve does. A zero-length or empty centre gives an
/// empty path.
pub fn tapered_outline(centre: &BezPath, base_width: f64, tip_width: f64) -> BezPath {
    // `max` also maps NaN widths to 0, so no NaN reaches the output.
    let base_width = base_width.max(0.0);
    let tip_width = tip_width.max(0.0);
    outline_with_widths(centre, &|f| base_width + (tip_width - base_width) * f)
}

/// A closed outline around `centre` as [`tapered_outline`] draws it, whose
/// width at each point is `width(f)`, `f` being the fraction (0 at the
/// base, 1 at the tip) of the centre's arc length before it: for limbs
/// whose width changes along them, not only linearly.
pub fn outline_with_widths(centre: &BezPath, width: &dyn Fn(f64) -> f64) -> BezPath {
    let walker = PathWalker::new(centre, TOLERANCE);
    let length = walker.length();
    if length.is_nan() || length < MIN_LENGTH {
        return BezPath::new();
    }
    // `max` also maps NaN widths to 0, so no NaN reaches the output.
    let width = |f: f64| width(f).max(0.0);
    let tip_width = Some(width(1.0)).filter(|&w| w >= MIN_TIP).unwrap_or(0.0);

    let intervals = (MIN_INTERVALS_PER_SEGMENT * centre.segments().count())
        .max((length / MAX_SPACING).ceil() as usize)
        .clamp(1, MAX_SAMPLES - 1);
    let samples = walker.sample_even_with_tangents(intervals + 1);

    let mut left = Vec::with_capacity(samples.len());
    let mut right = Vec::with_capacity(samples.len());
    for (k, &(p, d)) in samples.iter().enumerate() {
        let frac = k as f64 / intervals as f64;
        let half = 0.5 * width(frac);
        left.push(p + Side::Left.normal(d) * half);
        right.push(p + Side::Right.normal(d) * half);
    }
    right.reverse();

    let mut out = BezPath::new();
    out.move_to(left[0]);
    append_spline(&mut out, &left);
    match samples.last() {
        Some(&(tip, dir)) if tip_width > 0.0 => append_cap(&mut out, tip, dir, tip_width / 2.0),
        _ => {}
    }
    append_spline(&mut out, &right);
    out.close_path();
    out
}

/// Appends the natural spline through `points` as curves from the current
/// point, which must be `points[0]`.
fn append_spline(out: &mut BezPath, points: &[Point]) {
    for c in natural_spline_cubics(points) {
        out.curve_to(c.p1, c.p2, c.p3);
    }
}

/// Appends a half circle of radius `r` round `centre`, bulging along `dir`,
/// from the left of `dir` to its right, as two quarter-circle cubics.
fn append_cap(out: &mut BezPath, centre: Point, dir: Vec2, r: f64) {
    let n = Side::Left.normal(dir);
    let k = QUARTER_ARC_KAPPA * r;
    let (from, apex, to) = (centre + n * r, centre + dir * r, centre - n * r);
    out.curve_to(from + dir * k, apex + n * k, apex);
    out.curve_to(apex - n * k, to + dir * k, to);
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{Arc, ParamCurve, PathEl, Shape};
    use std::f64::consts::{FRAC_PI_2, PI};

    fn line(a: (f64, f64), b: (f64, f64)) -> BezPath {
        let mut p = BezPath::new();
        p.move_to(a);
        p.line_to(b);
        p
    }

    fn quarter_arc() -> BezPath {
        Arc::new((0.0, 0.0), (30.0, 30.0), 0.0, FRAC_PI_2, 0.0).to_path(1e-6)
    }

    /// Distance from `p` to the polyline through `pts`.
    fn polyline_distance(pts: &[Point], p: Point) -> f64 {
        pts.windows(2)
            .map(|w| {
                let (a, ab) = (w[0], w[1] - w[0]);
                let t = ((p - a).dot(ab) / ab.hypot2()).clamp(0.0, 1.0);
                p.distance(a + ab * t)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Checks that the whole outline stays within half the widest width
    /// (plus slack) of the centre.
    fn assert_hugs_centre(centre: &BezPath, outline: &BezPath, max_width: f64) {
        let centre_pts = PathWalker::new(centre, 1e-4).sample_even(2000);
        let limit = max_width / 2.0 + 0.05;
        for seg in outline.segments() {
            for i in 0..=20 {
                let q = seg.eval(i as f64 / 20.0);
                let d = polyline_distance(&centre_pts, q);
                assert!(d <= limit, "{q:?} is {d} from the centre (limit {limit})");
            }
        }
    }

    #[test]
    fn widths_along_the_centre_are_the_ones_asked_for() {
        // A straight centre 40 mm up the page, thick in the middle (a
        // smooth width: the sides are splines through samples).
        let centre = line((0.0, 0.0), (0.0, -40.0));
        let width = |f: f64| 1.0 + 4.0 * (PI * f).sin();
        let out = outline_with_widths(&centre, &width);
        assert!(matches!(out.elements().last(), Some(PathEl::ClosePath)));
        // Across the centre at height 40 f, the outline lies width(f)/2 to
        // either side: find where it crosses that height.
        for f in [0.1, 0.25, 0.5, 0.7, 0.9] {
            let y = -40.0 * f;
            let crossings: Vec<f64> = out
                .segments()
                .flat_map(|seg| {
                    (0..400).filter_map(move |i| {
                        let (a, b) = (seg.eval(i as f64 / 400.0), seg.eval((i + 1) as f64 / 400.0));
                        ((a.y - y) * (b.y - y) <= 0.0 && a.y != b.y)
                            .then(|| a.x + (b.x - a.x) * (y - a.y) / (b.y - a.y))
                    })
                })
                .collect();
            let (lo, hi) = crossings
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &x| {
                    (l.min(x), h.max(x))
                });
            assert!(
                (hi - lo - width(f)).abs() < 0.02,
                "at {f}: {} wide",
                hi - lo
            );
            assert!((hi + lo).abs() < 0.01);
        }
    }

    #[test]
    fn outline_is_closed() {
        let out = tapered_outline(&line((0.0, 0.0), (0.0, -40.0)), 4.0, 1.0);
        assert!(matches!(out.elements().last(), Some(PathEl::ClosePath)));
        assert_eq!(
            out.elements()
                .iter()
                .filter(|e| matches!(e, PathEl::MoveTo(_)))
                .count(),
            1
        );
    }

    #[test]
    fn straight_centre_area_is_trapezoid_plus_cap() {
        let (len, base, tip) = (40.0, 4.0, 1.0);
        let out = tapered_outline(&line((5.0, 5.0), (5.0 + len, 5.0)), base, tip);
        let expected = len * (base + tip) / 2.0 + PI * (tip / 2.0) * (tip / 2.0) / 2.0;
        let area = out.area().abs();
        assert!(
            (area - expected).abs() < 0.01 * expected,
            "{area} vs {expected}"
        );
    }

    #[test]
    fn base_edge_is_base_width_long() {
        let out = tapered_outline(&line((0.0, 0.0), (30.0, 10.0)), 3.0, 0.5);
        let start = match out.elements()[0] {
            PathEl::MoveTo(p) => p,
            ref el => panic!("starts with {el:?}"),
        };
        let right_end = match out.elements()[out.elements().len() - 2] {
            PathEl::CurveTo(_, _, p) => p,
            ref el => panic!("right side ends with {el:?}"),
        };
        assert!((start.distance(right_end) - 3.0).abs() < 1e-9);
    }

    #[test]
    fn left_side_is_left_of_travel() {
        // Travelling +x with y down, left is up the page (smaller y).
        let out = tapered_outline(&line((0.0, 0.0), (10.0, 0.0)), 2.0, 1.0);
        let PathEl::MoveTo(start) = out.elements()[0] else {
            panic!("no MoveTo");
        };
        assert!((start - Point::new(0.0, -1.0)).hypot() < 1e-9);
    }

    #[test]
    fn straight_outline_hugs_centre() {
        let centre = line((0.0, 0.0), (25.0, 25.0));
        assert_hugs_centre(&centre, &tapered_outline(&centre, 5.0, 2.0), 5.0);
    }

    #[test]
    fn quarter_arc_centre_hugs_centre() {
        let centre = quarter_arc();
        let out = tapered_outline(&centre, 4.0, 1.0);
        assert_hugs_centre(&centre, &out, 4.0);
        // The area of a tapered annulus sector, to 1%.
        let expected = 30.0 * FRAC_PI_2 * 2.5 + PI * 0.25 / 2.0;
        assert!((out.area().abs() - expected).abs() < 0.01 * expected);
    }

    #[test]
    fn widening_limb_hugs_centre() {
        let centre = quarter_arc();
        assert_hugs_centre(&centre, &tapered_outline(&centre, 1.0, 3.0), 3.0);
    }

    #[test]
    fn zero_tip_sides_meet_at_the_tip() {
        let out = tapered_outline(&line((0.0, 0.0), (20.0, 0.0)), 2.0, 0.0);
        assert!(out.segments().any(|s| s.end() == Point::new(20.0, 0.0)));
        // 14 intervals of at most 1.5 mm on each side, then the base edge:
        // no cap curves.
        assert_eq!(out.segments().count(), 2 * 14 + 1);
    }

    #[test]
    fn degenerate_input_gives_empty_path() {
        assert!(tapered_outline(&BezPath::new(), 2.0, 1.0)
            .elements()
            .is_empty());
        let dot = line((3.0, 3.0), (3.0, 3.0));
        assert!(tapered_outline(&dot, 2.0, 1.0).elements().is_empty());
    }

    #[test]
    fn never_nan() {
        let mut centre = BezPath::new();
        centre.move_to((0.0, 0.0));
        centre.curve_to((0.0, 0.0), (10.0, 0.0), (10.0, 0.0));
        for (b, t) in [
            (2.0, 1.0),
            (f64::NAN, 1.0),
            (2.0, f64::NAN),
            (-1.0, -1.0),
            (0.0, 0.0),
        ] {
            let out = tapered_outline(&centre, b, t);
            for seg in out.segments() {
                let c = seg.to_cubic();
                assert!(
                    [c.p0, c.p1, c.p2, c.p3].iter().all(|p| p.is_finite()),
                    "{b} {t}"
                );
            }
        }
    }
}
