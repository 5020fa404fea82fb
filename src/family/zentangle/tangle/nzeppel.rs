//! 'Nzeppel: a grid with a diagonal across every cell, its triangles
//! each drawn as a rounded pebble inside; the grid itself is the pencil
//! guide and is not inked.

use std::f64::consts::PI;

use kurbo::Point;

use super::super::element::{Mark, Paint};
use super::shapes::{mark, near, smooth_closed, Lattice};
use super::Section;
use crate::rng::RandomStream;

/// A pebble's corners are pulled this share of the way to the
/// triangle's centre, the middles of its sides less: rounded, with a gap
/// to its neighbours.
const CORNER_PULL: f64 = 0.42;
const SIDE_PULL: f64 = 0.2;

/// The marks: one white pebble per triangle.
pub(super) fn draw(s: &Section<'_>, rng: &mut RandomStream) -> Vec<Mark> {
    let pitch = 1.1 * s.unit;
    let Some(grid) = Lattice::new(s.region.bounds(), rng.symmetric(PI / 12.0), pitch) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for (i, j) in grid.cells() {
        let [a, b, c, d] = grid.cell(i, j, 1.0);
        if !near(s.region, a.midpoint(c), pitch) {
            continue;
        }
        for tri in [[a, b, c], [c, d, a]] {
            out.push(mark(pebble(tri, rng, 0.04 * pitch), Paint::White));
        }
    }
    out
}

/// The pebble in triangle `t`, its points moved by up to `jitter` mm as a
/// hand moves them.
fn pebble(t: [Point; 3], rng: &mut RandomStream, jitter: f64) -> kurbo::BezPath {
    let centre = Point::new(
        (t[0].x + t[1].x + t[2].x) / 3.0,
        (t[0].y + t[1].y + t[2].y) / 3.0,
    );
    let mut points = Vec::with_capacity(6);
    for k in 0..3 {
        let (p, q) = (t[k], t[(k + 1) % 3]);
        points.push(p.lerp(centre, CORNER_PULL));
        points.push(p.midpoint(q).lerp(centre, SIDE_PULL));
    }
    let moved: Vec<Point> = points
        .into_iter()
        .map(|p| p + kurbo::Vec2::new(rng.symmetric(jitter), rng.symmetric(jitter)))
        .collect();
    smooth_closed(&moved)
}
