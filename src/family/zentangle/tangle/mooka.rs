//! Mooka: stems rising from the bottom of the section, each curling over
//! at its top into a teardrop loop that hangs to one side, an echo line
//! inside the loop; rows of them overlap, the nearer in front.

use std::f64::consts::{FRAC_PI_4, TAU};

use kurbo::{BezPath, CubicBez, ParamCurve, ParamCurveDeriv, Point, Vec2};

use super::super::element::{Mark, Paint};
use super::shapes::{mark, near, polyline, smooth_closed, MAX_ITEMS};
use super::Section;
use crate::rng::RandomStream;

/// Points along a stem's side, and around a loop.
const STEM_POINTS: usize = 20;
const LOOP_POINTS: usize = 28;

/// The marks: row by row from the top (the farthest back), each Mooka a
/// white stem, a white loop over its top and the loop's echo.
pub(super) fn draw(s: &Section<'_>, rng: &mut RandomStream) -> Vec<Mark> {
    let b = s.region.bounds();
    let height = 2.6 * s.unit;
    let (row, column) = (0.7 * height, 0.62 * height);
    let rows = ((b.height() + height) / row).ceil() as usize + 1;
    let columns = ((b.width() + height) / column).ceil() as usize + 1;
    if rows * columns > MAX_ITEMS {
        return Vec::new();
    }
    let mut out = Vec::new();
    for r in 0..rows {
        let y = b.y0 + 0.6 * height + r as f64 * row;
        let shift = if r % 2 == 0 { 0.0 } else { column / 2.0 };
        for c in 0..columns {
            let base = Point::new(
                b.x0 - 0.3 * height + shift + c as f64 * column + rng.symmetric(0.1 * column),
                y + rng.symmetric(0.1 * row),
            );
            let side = if rng.unit() < 0.5 { -1.0 } else { 1.0 };
            let h = height * rng.range(0.85, 1.1);
            if near(s.region, base - Vec2::new(0.0, h / 2.0), h) {
                out.extend(mooka(base, h, side, s.pen));
            }
        }
    }
    out
}

/// One Mooka `h` mm tall standing on `base`, its loop hanging to `side`
/// (−1 left, 1 right).
fn mooka(base: Point, h: f64, side: f64, pen: f64) -> [Mark; 3] {
    let tip = base + Vec2::new(side * 0.3 * h, -h);
    let stem = CubicBez::new(
        base,
        base + Vec2::new(-side * 0.1 * h, -0.5 * h),
        tip + Vec2::new(-side * 0.12 * h, 0.3 * h),
        tip,
    );
    // The loop's axis leaves the tip turned down to the side, as the
    // stem curls over.
    let axis = Vec2::from_angle(if side > 0.0 { FRAC_PI_4 } else { 3.0 * FRAC_PI_4 });
    let (length, width) = (0.5 * h, 0.28 * h);
    let echo_scale = 0.55;
    let head = teardrop(tip, axis, length, width);
    // The echo: a smaller teardrop in the round end.
    let round = tip + axis * (0.62 * length);
    let echo = teardrop(
        round - axis * (0.62 * length * echo_scale),
        axis,
        length * echo_scale,
        (width * echo_scale).max(2.0 * pen),
    );
    [
        mark(ribbon(&stem, 0.1 * h, 0.05 * h), Paint::White),
        mark(head, Paint::White),
        mark(echo, Paint::Line),
    ]
}

/// The teardrop with its point at `tip`, its round end `length` mm along
/// `axis`, at most about `width` mm across.
fn teardrop(tip: Point, axis: Vec2, length: f64, width: f64) -> BezPath {
    let across = axis.turn_90();
    let points: Vec<Point> = (0..LOOP_POINTS)
        .map(|k| {
            let t = k as f64 / LOOP_POINTS as f64 * TAU;
            let along = (1.0 - t.cos()) / 2.0 * length;
            let off = t.sin() * (t / 2.0).sin().powf(1.5) * width * 0.65;
            tip + axis * along + across * off
        })
        .collect();
    smooth_closed(&points)
}

/// The strip along `curve`, `start` mm wide at its start narrowing to
/// `end` mm at its end: a stem drawn as two lines.
fn ribbon(curve: &CubicBez, start: f64, end: f64) -> BezPath {
    let d = curve.deriv();
    let (mut left, mut right) = (Vec::new(), Vec::new());
    for k in 0..=STEM_POINTS {
        let t = k as f64 / STEM_POINTS as f64;
        let normal = d.eval(t).to_vec2().normalize().turn_90();
        let half = (start + (end - start) * t) / 2.0;
        let p = curve.eval(t);
        left.push(p + normal * half);
        right.push(p - normal * half);
    }
    left.extend(right.into_iter().rev());
    polyline(&left, true)
}
