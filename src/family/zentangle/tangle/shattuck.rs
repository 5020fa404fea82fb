//! Shattuck: bands that follow a wave across the section, one of tight
//! lines drawn across it, the next black, and so on.

use std::f64::consts::{PI, TAU};

use kurbo::{Point, Vec2};

use super::super::element::{Mark, Paint};
use super::shapes::{mark, polyline, MAX_ITEMS};
use super::Section;
use crate::rng::RandomStream;

/// Points per wavelength of a band's edge.
const POINTS_PER_WAVE: f64 = 24.0;

/// The marks: the black bands (whose outlines are the edges of all the
/// bands), then the tight lines across the others.
pub(super) fn draw(s: &Section<'_>, rng: &mut RandomStream) -> Vec<Mark> {
    let b = s.region.bounds();
    let angle = rng.symmetric(PI / 5.0);
    let (u, v) = (Vec2::from_angle(angle), Vec2::from_angle(angle).turn_90());
    let width = 0.75 * s.unit;
    let (amplitude, wave, phase) = (0.45 * s.unit, 3.5 * s.unit, rng.unit() * TAU);
    let tight = (0.2 * s.unit).max(3.5 * s.pen);
    let half = 0.5 * b.width().hypot(b.height()) + amplitude;
    let bands = (half / width).ceil() as i64 + 1;
    let step = wave / POINTS_PER_WAVE;
    let points = (half / step).ceil() as i64;
    let across = (half / tight).ceil() as i64;
    if ((2 * bands + 1) * (2 * points + 2 * across + 2)) as usize > 4 * MAX_ITEMS {
        return Vec::new();
    }
    let centre = b.center();
    let edge_at = |k: i64, x: f64| -> Point {
        centre + u * x + v * (k as f64 * width + amplitude * (TAU * x / wave + phase).sin())
    };
    let edge = |k: i64| -> Vec<Point> {
        (-points..=points)
            .map(|m| edge_at(k, m as f64 * step))
            .collect()
    };
    let mut out = Vec::new();
    for k in -bands..bands {
        if k.rem_euclid(2) == 0 {
            let mut band = edge(k);
            band.extend(edge(k + 1).into_iter().rev());
            out.push(mark(polyline(&band, true), Paint::Black));
        }
    }
    for k in -bands..bands {
        if k.rem_euclid(2) == 1 {
            for m in -across..=across {
                let x = m as f64 * tight;
                let line = [edge_at(k, x), edge_at(k + 1, x)];
                out.push(mark(polyline(&line, false), Paint::Line));
            }
        }
    }
    out
}
