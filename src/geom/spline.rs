//! Parametric natural cubic splines through a list of points, emitted as
//! exact cubic Béziers (docs/SPEC.md §1.1, §1.3).
//!
//! The parameter is the cumulative chord length, not x, so a line may run
//! vertically or loop back on itself. Both ends are "natural" (S'' = 0).

use kurbo::{BezPath, CubicBez, Point, Vec2};

/// Consecutive input points closer than this (mm) are treated as one: a
/// zero-length chord would make the chord parameter stall and divide by zero.
const MERGE_DISTANCE: f64 = 1e-9;

/// The cubic Béziers of the natural cubic spline through `points`, one per
/// span between consecutive (distinct) points.
///
/// The spline `S(t)` is parametrised by chord length (`t_0 = 0`,
/// `t_{i+1} = t_i + |P_{i+1} − P_i|`) and has `S'' = 0` at both ends. Each
/// span is converted exactly: a cubic polynomial on `[t_i, t_i + h]` with end
/// derivatives `D_i`, `D_{i+1}` is the Bézier with control points
/// `P_i + D_i·h/3` and `P_{i+1} − D_{i+1}·h/3`.
///
/// Consecutive points closer than 1e-9 mm are merged first. Fewer than two
/// distinct points give no cubics; two give one straight cubic.
pub fn natural_spline_cubics(points: &[Point]) -> Vec<CubicBez> {
    let pts = merge_close(points);
    if pts.len() < 2 {
        return Vec::new();
    }
    let h: Vec<f64> = pts.windows(2).map(|w| w[0].distance(w[1])).collect();
    let m = second_derivatives(&pts, &h);
    (0..h.len())
        .map(|i| {
            let (p0, p3, hi) = (pts[i], pts[i + 1], h[i]);
            let slope = (p3 - p0) / hi;
            // First derivatives of the span's cubic at its two ends, from the
            // standard second-derivative form of the spline.
            let d0 = slope - (m[i] * 2.0 + m[i + 1]) * (hi / 6.0);
            let d1 = slope + (m[i] + m[i + 1] * 2.0) * (hi / 6.0);
            CubicBez::new(p0, p0 + d0 * (hi / 3.0), p3 - d1 * (hi / 3.0), p3)
        })
        .collect()
}

/// The natural cubic spline through `points` as a path: one `MoveTo` and a
/// `CurveTo` per span. Empty when fewer than two distinct points are given.
///
/// See [`natural_spline_cubics`] for the construction.
pub fn natural_spline(points: &[Point]) -> BezPath {
    let cubics = natural_spline_cubics(points);
    let mut path = BezPath::new();
    if let Some(first) = cubics.first() {
        path.move_to(first.p0);
        for c in &cubics {
            path.curve_to(c.p1, c.p2, c.p3);
        }
    }
    path
}

/// `points` with runs of (nearly) coincident consecutive points reduced to
/// their first point.
fn merge_close(points: &[Point]) -> Vec<Point> {
    let mut out: Vec<Point> = Vec::with_capacity(points.len());
    for &p in points {
        if !out.last().is_some_and(|&q| q.distance(p) < MERGE_DISTANCE) {
            out.push(p);
        }
    }
    out
}

/// Second derivatives `M_i` (w.r.t. the chord parameter) at every point of
/// the natural spline, with `M_0 = M_{n−1} = 0`.
///
/// The interior equations
/// `h_{i−1}·M_{i−1} + 2(h_{i−1}+h_i)·M_i + h_i·M_{i+1} = 6(Δ_i − Δ_{i−1})`
/// (Δ = chord slope) form a strictly diagonally dominant tridiagonal system,
/// so the Thomas algorithm is stable without pivoting. x and y share the
/// matrix and differ only in the right-hand side, so both are solved at once
/// by carrying the right-hand side as a `Vec2`.
fn second_derivatives(pts: &[Point], h: &[f64]) -> Vec<Vec2> {
    let n = pts.len();
    let mut m = vec![Vec2::ZERO; n];
    if n < 3 {
        return m;
    }
    let slope = |i: usize| (pts[i + 1] - pts[i]) / h[i];
    // Forward sweep over the interior unknowns 1..=n-2: c_prime holds the
    // eliminated super-diagonal, d_prime the updated right-hand side.
    let interior = n - 2;
    let mut c_prime = vec![0.0; interior];
    let mut d_prime = vec![Vec2::ZERO; interior];
    for k in 0..interior {
        let i = k + 1;
        let a = h[i - 1];
        let b = 2.0 * (h[i - 1] + h[i]);
        let c = h[i];
        let d = (slope(i) - slope(i - 1)) * 6.0;
        let (denom, rhs) = if k == 0 {
            (b, d)
        } else {
            (b - a * c_prime[k - 1], d - d_prime[k - 1] * a)
        };
        c_prime[k] = c / denom;
        d_prime[k] = rhs / denom;
    }
    // Back substitution; m[n-1] stays zero (natural end).
    for k in (0..interior).rev() {
        m[k + 1] = d_prime[k] - m[k + 2] * c_prime[k];
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::ParamCurve;
    use proptest::prelude::*;

    /// Chord-parameter derivatives (first, second) at the start of `c`,
    /// whose span has chord-parameter length `h`.
    fn start_derivs(c: &CubicBez, h: f64) -> (Vec2, Vec2) {
        (
            (c.p1 - c.p0) * (3.0 / h),
            (c.p0.to_vec2() - c.p1.to_vec2() * 2.0 + c.p2.to_vec2()) * (6.0 / (h * h)),
        )
    }

    /// Chord-parameter derivatives (first, second) at the end of `c`.
    fn end_derivs(c: &CubicBez, h: f64) -> (Vec2, Vec2) {
        (
            (c.p3 - c.p2) * (3.0 / h),
            (c.p3.to_vec2() - c.p2.to_vec2() * 2.0 + c.p1.to_vec2()) * (6.0 / (h * h)),
        )
    }

    fn close(a: Vec2, b: Vec2) -> bool {
        (a - b).hypot() <= 1e-6 * a.hypot().max(b.hypot()).max(1.0)
    }

    /// Checks pass-through, C1/C2 at joins and natural ends; returns a
    /// description of the first violation.
    fn check_spline(points: &[Point]) -> Result<(), String> {
        let cubics = natural_spline_cubics(points);
        if cubics.len() != points.len() - 1 {
            return Err(format!(
                "{} cubics for {} points",
                cubics.len(),
                points.len()
            ));
        }
        for (i, c) in cubics.iter().enumerate() {
            if c.p0 != points[i] || c.p3 != points[i + 1] {
                return Err(format!("span {i} misses its points"));
            }
        }
        let h: Vec<f64> = points.windows(2).map(|w| w[0].distance(w[1])).collect();
        for i in 0..cubics.len() - 1 {
            let (d1a, d2a) = end_derivs(&cubics[i], h[i]);
            let (d1b, d2b) = start_derivs(&cubics[i + 1], h[i + 1]);
            if !close(d1a, d1b) {
                return Err(format!("C1 broken at join {i}: {d1a:?} vs {d1b:?}"));
            }
            if !close(d2a, d2b) {
                return Err(format!("C2 broken at join {i}: {d2a:?} vs {d2b:?}"));
            }
        }
        let first = start_derivs(&cubics[0], h[0]).1;
        let last = end_derivs(cubics.last().unwrap(), *h.last().unwrap()).1;
        if !close(first, Vec2::ZERO) || !close(last, Vec2::ZERO) {
            return Err(format!("ends not natural: {first:?}, {last:?}"));
        }
        Ok(())
    }

    fn pts(xy: &[(f64, f64)]) -> Vec<Point> {
        xy.iter().map(|&(x, y)| Point::new(x, y)).collect()
    }

    #[test]
    fn passes_through_points_with_c2_joins_and_natural_ends() {
        let p = pts(&[
            (0.0, 0.0),
            (30.0, 10.0),
            (50.0, -20.0),
            (90.0, 5.0),
            (120.0, 0.0),
            (150.0, 40.0),
        ]);
        check_spline(&p).unwrap();
    }

    #[test]
    fn vertical_input_is_not_a_function_of_x() {
        let p = pts(&[(10.0, 0.0), (10.0, 20.0), (10.0, 50.0), (10.0, 60.0)]);
        check_spline(&p).unwrap();
        for c in natural_spline_cubics(&p) {
            for q in [c.p1, c.p2] {
                assert!((q.x - 10.0).abs() < 1e-12, "left the vertical: {q:?}");
            }
        }
    }

    #[test]
    fn looping_input_works() {
        // Goes round and comes back near its start: no single-valued y(x).
        let p = pts(&[
            (0.0, 0.0),
            (40.0, 0.0),
            (40.0, 40.0),
            (0.0, 40.0),
            (5.0, 5.0),
        ]);
        check_spline(&p).unwrap();
    }

    #[test]
    fn collinear_points_give_a_straight_line() {
        let p = pts(&[(0.0, 0.0), (10.0, 5.0), (14.0, 7.0), (40.0, 20.0)]);
        for c in natural_spline_cubics(&p) {
            for t in [0.1, 0.37, 0.5, 0.81] {
                let q = c.eval(t);
                assert!((q.y - q.x / 2.0).abs() < 1e-9, "off the line: {q:?}");
            }
        }
    }

    #[test]
    fn two_points_give_one_straight_cubic_with_thirds_controls() {
        let c = natural_spline_cubics(&pts(&[(0.0, 0.0), (9.0, 3.0)]));
        assert_eq!(c.len(), 1);
        assert!((c[0].p1 - Point::new(3.0, 1.0)).hypot() < 1e-12);
        assert!((c[0].p2 - Point::new(6.0, 2.0)).hypot() < 1e-12);
    }

    #[test]
    fn fewer_than_two_distinct_points_give_nothing() {
        assert!(natural_spline_cubics(&[]).is_empty());
        assert!(natural_spline(&pts(&[(1.0, 1.0)])).elements().is_empty());
        assert!(natural_spline(&pts(&[(1.0, 1.0), (1.0, 1.0 + 1e-12)]))
            .elements()
            .is_empty());
    }

    #[test]
    fn duplicate_points_are_merged() {
        let c = natural_spline_cubics(&pts(&[
            (0.0, 0.0),
            (0.0, 0.0),
            (10.0, 0.0),
            (20.0, 5.0),
            (20.0, 5.0),
        ]));
        assert_eq!(c.len(), 2);
        assert!(c.iter().all(|c| [c.p1, c.p2].iter().all(|p| p.is_finite())));
    }

    #[test]
    fn path_has_a_move_and_one_curve_per_span() {
        let path = natural_spline(&pts(&[(0.0, 0.0), (10.0, 10.0), (20.0, 0.0)]));
        assert_eq!(path.elements().len(), 3);
        assert_eq!(path.segments().count(), 2);
    }

    proptest! {
        #[test]
        fn random_point_sets_pass_through_and_are_c2(
            xy in prop::collection::vec((0.0..200.0f64, 0.0..200.0f64), 3..=12)
        ) {
            let p = pts(&xy);
            // A minimum spacing keeps the chord parameter well-conditioned.
            prop_assume!(p.windows(2).all(|w| w[0].distance(w[1]) >= 1.0));
            prop_assert_eq!(check_spline(&p), Ok(()));
        }
    }
}
