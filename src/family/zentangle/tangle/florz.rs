//! Florz: a diagonal grid with alternate cells black (their outlines are
//! the grid, as in Knightsbridge), and at every crossing a small diamond
//! drawn over it, white.

use std::f64::consts::FRAC_PI_4;

use super::super::element::{Mark, Paint};
use super::shapes::{mark, near, polyline, Lattice};
use super::Section;
use crate::rng::RandomStream;

/// A crossing's diamond is this share of a cell across (its sides run
/// with the grid's lines, its corners point between them: up, down,
/// left and right on a diagonal grid).
const DIAMOND: f64 = 0.45;

/// The marks: the black cells, then the diamonds on the crossings.
pub(super) fn draw(s: &Section<'_>, rng: &mut RandomStream) -> Vec<Mark> {
    let angle = FRAC_PI_4 + rng.symmetric(FRAC_PI_4 / 6.0);
    let pitch = s.unit;
    let Some(grid) = Lattice::new(s.region.bounds(), angle, pitch) else {
        return Vec::new();
    };
    let mut out: Vec<Mark> = grid
        .cells()
        .filter(|(i, j)| (i + j).rem_euclid(2) == 0)
        .map(|(i, j)| grid.cell(i, j, 1.0))
        .filter(|c| near(s.region, c[0].midpoint(c[2]), pitch))
        .map(|c| mark(polyline(&c, true), Paint::Black))
        .collect();
    for (i, j) in grid.cells() {
        let (x, y) = (i as f64, j as f64);
        if !near(s.region, grid.at(x, y), pitch) {
            continue;
        }
        let h = DIAMOND / 2.0;
        let corners = [
            grid.at(x - h, y - h),
            grid.at(x + h, y - h),
            grid.at(x + h, y + h),
            grid.at(x - h, y + h),
        ];
        out.push(mark(polyline(&corners, true), Paint::White));
    }
    out
}
