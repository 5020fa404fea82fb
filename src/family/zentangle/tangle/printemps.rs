//! Printemps: rolled circles. Each is a spiral drawn from its centre
//! outwards, turn beside turn, closed by the circle it grows into; they
//! are packed close, and the ground between them is black.

use std::f64::consts::TAU;

use kurbo::{BezPath, Point, Vec2};

use super::super::element::{Mark, Paint};
use super::shapes::{circle, mark, pack};
use super::Section;
use crate::rng::RandomStream;

/// The turns of a spiral lie this many pen widths apart at least.
const PITCH_PENS: f64 = 3.5;

/// Points per turn of a spiral (a polyline this fine is within a few
/// hundredths of a millimetre of the curve at these sizes).
const POINTS_PER_TURN: usize = 48;

/// The marks: the black ground, then each circle painted white over it
/// with its spiral inside.
pub(super) fn draw(s: &Section<'_>, rng: &mut RandomStream) -> Vec<Mark> {
    let b = s.region.bounds().inflate(1.0, 1.0);
    let mut out = vec![mark(kurbo::Shape::to_path(&b, 0.0), Paint::Black)];
    let circles = pack(s.region, (0.45 * s.unit, 0.85 * s.unit), 0.18 * s.unit, rng);
    for (c, r) in circles {
        out.push(mark(circle(c, r), Paint::White));
        let pitch = (r / 3.2).max(PITCH_PENS * s.pen);
        out.push(mark(spiral(c, r, pitch, rng.unit() * TAU), Paint::Line));
    }
    out
}

/// The spiral from `c` out to radius `r`, `pitch` mm a turn, starting
/// at angle `start`: Archimedes' spiral, ending on the circle of radius
/// `r`.
pub(super) fn spiral(c: Point, r: f64, pitch: f64, start: f64) -> BezPath {
    let turns = r / pitch;
    let n = ((turns * POINTS_PER_TURN as f64).ceil() as usize).max(8);
    let mut path = BezPath::new();
    for k in 0..=n {
        let f = k as f64 / n as f64;
        let p = c + Vec2::from_angle(start + f * turns * TAU) * (f * r);
        if k == 0 {
            path.move_to(p);
        } else {
            path.line_to(p);
        }
    }
    path
}
