//! Static: zig-zag lines like lightning, one beside the other in a band
//! across the section; every fourth strip between two of them is black.

use std::f64::consts::PI;

use kurbo::{Point, Vec2};

use super::super::element::{Mark, Paint};
use super::shapes::{mark, polyline, MAX_ITEMS};
use super::Section;
use crate::rng::RandomStream;

/// Of this many strips between neighbouring zig-zags, the first is black.
const EVERY: i64 = 4;

/// The marks: the black strips (whose outlines are the zig-zags on
/// either side), then the zig-zags that border no black strip.
pub(super) fn draw(s: &Section<'_>, rng: &mut RandomStream) -> Vec<Mark> {
    let b = s.region.bounds();
    let angle = rng.symmetric(PI / 8.0);
    let (u, v) = (Vec2::from_angle(angle), Vec2::from_angle(angle).turn_90());
    let spacing = (0.38 * s.unit).max(4.0 * s.pen);
    let (run, rise) = (0.45 * s.unit, 0.55 * s.unit);
    let half = 0.5 * b.width().hypot(b.height()) + rise;
    let steps = (half / run).ceil() as i64 + 1;
    let lines = (half / spacing).ceil() as i64 + 1;
    if ((2 * steps + 1) * (2 * lines + 1)) as usize > MAX_ITEMS {
        return Vec::new();
    }
    let centre = b.center();
    // Zig-zag k: its corners, alternately up and down, along u.
    let zigzag = |k: i64| -> Vec<Point> {
        (-steps..=steps)
            .map(|m| {
                let up = if m.rem_euclid(2) == 0 { 0.0 } else { rise };
                centre + u * (m as f64 * run) + v * (k as f64 * spacing + up)
            })
            .collect()
    };
    let black = |k: i64| k.rem_euclid(EVERY) == 0;
    let mut out = Vec::new();
    for k in -lines..lines {
        if black(k) {
            let mut strip = zigzag(k);
            strip.extend(zigzag(k + 1).into_iter().rev());
            out.push(mark(polyline(&strip, true), Paint::Black));
        }
    }
    for k in -lines..=lines {
        if !black(k) && !black(k - 1) {
            out.push(mark(polyline(&zigzag(k), false), Paint::Line));
        }
    }
    out
}
