//! A dot as a pen draws it (a stipple's, a same-komon ground's): ink of
//! the dot's radius, with no unpainted hole.
//!
//! A circle drawn round a site with a pen as wide as the circle is small
//! is a ring — a donut with paper in the middle, so a dark tone reads as
//! pinholes, never black. So a dot no wider than the pen is a *tap*: the
//! pen goes down and up at the site (written `M p L p`, a line of no
//! length, which vpype reads as a two-point line and the G-code and HPGL
//! writers draw as a pen-down at that point). A larger dot is one stroke:
//! its rim, a circle whose ink reaches the dot's radius, then rings inside
//! it closer together than a pen width, each joined to the next by a short
//! step inwards, and a last step to the centre — ink all over, one pen
//! lift, and no ring on top of another (a spiral would run along its rim
//! within a fraction of a pen width: drawn twice).

use kurbo::{BezPath, Point, Vec2};

/// Rings lie this share of a pen width apart: a little less than the
/// width, so that no hairline of paper shows between them.
const PITCH: f64 = 0.8;

/// Chords stray at most this far (mm) from the rings.
const CHORD_ERROR: f64 = 0.01;

/// The path of a dot whose ink has radius `radius` (mm) at `at`, drawn by
/// a pen `width` mm wide (see the module documentation).
pub(crate) fn dot(at: Point, radius: f64, width: f64) -> BezPath {
    let mut path = BezPath::new();
    // The centre line of the rim; a dot the pen covers in one touch is a
    // tap.
    let rim = radius - width / 2.0;
    if !(rim > 0.0 && width > 0.0) {
        path.move_to(at);
        path.line_to(at);
        return path;
    }
    let pitch = PITCH * width;
    let tau = std::f64::consts::TAU;
    path.move_to(at + Vec2::new(rim, 0.0));
    let mut r = rim;
    while r > 0.0 {
        if r < rim {
            // The step in from the ring outside.
            path.line_to(at + Vec2::new(r, 0.0));
        }
        // The chord that strays CHORD_ERROR from the ring, at most a
        // twelfth of a turn.
        let ratio = (1.0 - CHORD_ERROR / r.max(CHORD_ERROR)).clamp(-1.0, 1.0);
        let step = (2.0 * ratio.acos()).clamp(1e-3, tau / 12.0);
        let n = (tau / step).ceil() as usize;
        for k in 1..=n {
            path.line_to(at + r * Vec2::from_angle(tau * k as f64 / n as f64));
        }
        r -= pitch;
    }
    // The paper inside the last ring, if any, is within half a width of
    // the centre.
    path.line_to(at);
    path
}

#[cfg(test)]
mod tests {
    use kurbo::{ParamCurve, ParamCurveNearest, Shape};

    use super::*;

    #[test]
    fn a_dot_no_wider_than_the_pen_is_a_tap() {
        let p = Point::new(10.0, 20.0);
        let tap = dot(p, 0.15, 0.3);
        assert_eq!(tap.elements().len(), 2);
        assert_eq!(tap.segments().count(), 1);
        let seg = tap.segments().next().unwrap();
        assert_eq!((seg.start(), seg.end()), (p, p));
    }

    /// Every point of the dot's disc lies within half a pen width of the
    /// stroke: no paper shows inside; and nothing of the ink reaches past
    /// the dot's radius.
    #[test]
    fn a_larger_dot_is_ink_all_over_and_no_larger() {
        for (radius, width) in [(0.3, 0.3), (0.35, 0.3), (1.0, 0.3), (2.5, 0.5)] {
            let c = Point::new(5.0, 5.0);
            let path = dot(c, radius, width);
            assert_eq!(
                path.elements()
                    .iter()
                    .filter(|e| matches!(e, kurbo::PathEl::MoveTo(_)))
                    .count(),
                1,
                "one stroke"
            );
            let reach = |q: Point| {
                path.segments()
                    .map(|s| s.nearest(q, 1e-9).distance_sq.sqrt())
                    .fold(f64::INFINITY, f64::min)
            };
            let steps = 40;
            for i in 0..=steps {
                for j in 0..=steps {
                    let q = Point::new(
                        c.x - radius + 2.0 * radius * i as f64 / steps as f64,
                        c.y - radius + 2.0 * radius * j as f64 / steps as f64,
                    );
                    if q.distance(c) <= radius - 0.02 {
                        assert!(reach(q) <= width / 2.0, "paper at {q:?} in a dot {radius}");
                    }
                }
            }
            let b = path.bounding_box();
            assert!(b.width() + width <= 2.0 * radius + 1e-9, "{b:?}");
            // No ring lies on another: the pen stage leaves it whole.
            let styled = crate::scene::StyledPath {
                id: "dot".into(),
                path: path.clone(),
                style: crate::scene::Style::default(),
            };
            let deduped = crate::plot::dedupe::dedupe(vec![styled.clone()], width / 4.0, width);
            assert_eq!(deduped, [styled]);
        }
    }
}
