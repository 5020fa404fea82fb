//! Knightsbridge: a checkerboard. Only the black squares are drawn: in a
//! checkerboard every edge between two squares is the edge of exactly one
//! black square, so their outlines are the whole grid, each line once.

use std::f64::consts::PI;

use super::super::element::{Mark, Paint};
use super::shapes::{mark, near, polyline, Lattice};
use super::Section;
use crate::rng::RandomStream;

/// The marks: the black squares, `(i + j)` even.
pub(super) fn draw(s: &Section<'_>, rng: &mut RandomStream) -> Vec<Mark> {
    // A tangler turns the tile: a grid a little off square to the page.
    let angle = rng.symmetric(PI / 12.0);
    let pitch = 0.8 * s.unit;
    let Some(grid) = Lattice::new(s.region.bounds(), angle, pitch) else {
        return Vec::new();
    };
    grid.cells()
        .filter(|(i, j)| (i + j).rem_euclid(2) == 0)
        .map(|(i, j)| grid.cell(i, j, 1.0))
        .filter(|c| near(s.region, c[0].midpoint(c[2]), pitch))
        .map(|c| mark(polyline(&c, true), Paint::Black))
        .collect()
}
