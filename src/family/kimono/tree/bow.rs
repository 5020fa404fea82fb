//! Two-point limbs: a chord bowed sideways into a single cubic Bézier
//! (docs/SPEC.md §1.3, eqs. 5–7 of the source).

use kurbo::{CubicBez, Point};

use crate::geom::Side;

/// A cubic from `p0` to `p3` that bows towards `side` of the chord.
///
/// The inner control points are the 1/3 and 2/3 points of the chord pushed
/// by `bow·|chord|` along the chord's unit normal on `side` (`bow` is a
/// fraction of the chord length, e.g. 0.08). The curve's midpoint then sits
/// `0.75·bow·|chord|` from the chord. A zero-length chord gives a cubic
/// collapsed onto `p0`.
pub(super) fn bowed_cubic(p0: Point, p3: Point, bow: f64, side: Side) -> CubicBez {
    let chord = p3 - p0;
    let len = chord.hypot();
    if len == 0.0 {
        // No direction to push along; normalising would give NaN.
        return CubicBez::new(p0, p0, p0, p0);
    }
    let push = side.normal(chord / len) * (bow * len);
    let pa = p0 + chord / 3.0;
    let pb = p0 + chord * (2.0 / 3.0);
    CubicBez::new(p0, pa + push, pb + push, p3)
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{ParamCurve, Vec2};

    #[test]
    fn endpoints_are_exact() {
        let (a, b) = (Point::new(1.5, -2.0), Point::new(17.25, 30.0));
        let c = bowed_cubic(a, b, 0.08, Side::Right);
        assert_eq!((c.eval(0.0), c.eval(1.0)), (a, b));
    }

    #[test]
    fn midpoint_sits_on_the_requested_side_at_three_quarters_bow() {
        let (a, b) = (Point::new(0.0, 0.0), Point::new(30.0, 40.0));
        let len = 50.0;
        let dir = (b - a) / len;
        for side in [Side::Left, Side::Right] {
            let mid = bowed_cubic(a, b, 0.08, side).eval(0.5);
            let off = mid - a.midpoint(b);
            let along_normal = off.dot(side.normal(dir));
            assert!(
                (along_normal - 0.75 * 0.08 * len).abs() < 1e-9,
                "{side:?}: {along_normal}"
            );
            assert!(off.dot(dir).abs() < 1e-9);
        }
    }

    #[test]
    fn left_of_a_rightward_chord_is_up_the_page() {
        let c = bowed_cubic(Point::new(0.0, 0.0), Point::new(10.0, 0.0), 0.1, Side::Left);
        assert!(c.eval(0.5).y < 0.0);
    }

    #[test]
    fn zero_bow_is_straight() {
        let c = bowed_cubic(Point::new(0.0, 0.0), Point::new(9.0, 3.0), 0.0, Side::Left);
        for t in [0.2, 0.5, 0.9] {
            let q = c.eval(t);
            assert!((q.y - q.x / 3.0).abs() < 1e-12);
        }
    }

    #[test]
    fn zero_length_chord_is_degenerate_not_nan() {
        let p = Point::new(4.0, 4.0);
        let c = bowed_cubic(p, p, 0.08, Side::Left);
        assert_eq!([c.p0, c.p1, c.p2, c.p3], [p; 4]);
        assert_eq!(c.eval(0.5) - p, Vec2::ZERO);
    }
}
