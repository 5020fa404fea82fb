//! Hollibaugh: bands — pairs of parallel lines — criss-crossing the
//! section. The first band lies on top; each next one passes behind all
//! drawn before it, so its lines stop where they meet a band in front;
//! the ground left between the bands is black.

use std::f64::consts::PI;

use kurbo::{Point, Vec2};

use super::super::element::{Mark, Paint};
use super::shapes::{mark, polyline};
use super::Section;
use crate::rng::RandomStream;

/// Most bands in one section.
const MAX_BANDS: usize = 40;

/// The marks: the black ground, then the bands as white strips from the
/// last drawn (the farthest back) to the first (in front).
pub(super) fn draw(s: &Section<'_>, rng: &mut RandomStream) -> Vec<Mark> {
    let b = s.region.bounds();
    let width = 0.55 * s.unit;
    let diagonal = b.width().hypot(b.height());
    let count = ((1.3 * diagonal / s.unit) as usize).clamp(4, MAX_BANDS);
    let mut bands = Vec::with_capacity(count);
    let mut tries = 0;
    while bands.len() < count && tries < 50 * MAX_BANDS {
        tries += 1;
        let through = Point::new(rng.range(b.x0, b.x1), rng.range(b.y0, b.y1));
        if !s.region.contains(through) {
            continue;
        }
        bands.push(band(through, rng.unit() * PI, width, diagonal));
    }
    let mut out = vec![mark(
        kurbo::Shape::to_path(&b.inflate(1.0, 1.0), 0.0),
        Paint::Black,
    )];
    out.extend(
        bands
            .into_iter()
            .rev()
            .map(|corners| mark(polyline(&corners, true), Paint::White)),
    );
    out
}

/// The strip `width` mm wide through `through` at `angle`, `length` mm
/// each way: its four corners.
fn band(through: Point, angle: f64, width: f64, length: f64) -> [Point; 4] {
    let along = Vec2::from_angle(angle) * length;
    let across = Vec2::from_angle(angle).turn_90() * (width / 2.0);
    [
        through - along - across,
        through + along - across,
        through + along + across,
        through - along + across,
    ]
}
