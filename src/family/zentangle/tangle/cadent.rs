//! Cadent: a grid of dots; along every row an S-curve from the top of
//! each dot to the bottom of the next, and along every column one from
//! the left of each dot to the right of the next — the curves of rows and
//! columns weave between each other.

use std::f64::consts::PI;

use kurbo::BezPath;

use super::super::element::{Mark, Paint};
use super::shapes::{circle, mark, near, Lattice};
use super::Section;
use crate::rng::RandomStream;

/// A dot's radius, in cells.
const DOT: f64 = 0.1;

/// How far an S-curve swings off the line between its dots, in cells.
const SWING: f64 = 0.55;

/// The marks: the S-curves, then the dots over their ends, black.
pub(super) fn draw(s: &Section<'_>, rng: &mut RandomStream) -> Vec<Mark> {
    let pitch = s.unit;
    let Some(grid) = Lattice::new(s.region.bounds(), rng.symmetric(PI / 12.0), pitch) else {
        return Vec::new();
    };
    let dot = DOT.max(1.5 * s.pen / pitch);
    let mut curves = Vec::new();
    let mut dots = Vec::new();
    for (i, j) in grid.cells() {
        let (x, y) = (i as f64, j as f64);
        if !near(s.region, grid.at(x, y), 1.5 * pitch) {
            continue;
        }
        dots.push(mark(circle(grid.at(x, y), dot * pitch), Paint::Black));
        // Along the row: from the top of this dot to the bottom of the next.
        let mut row = BezPath::new();
        row.move_to(grid.at(x, y - dot));
        row.curve_to(
            grid.at(x + SWING, y - dot - SWING),
            grid.at(x + 1.0 - SWING, y + dot + SWING),
            grid.at(x + 1.0, y + dot),
        );
        curves.push(mark(row, Paint::Line));
        // Along the column: from the right of this dot to the left of the
        // next.
        let mut column = BezPath::new();
        column.move_to(grid.at(x + dot, y));
        column.curve_to(
            grid.at(x + dot + SWING, y + SWING),
            grid.at(x - dot - SWING, y + 1.0 - SWING),
            grid.at(x - dot, y + 1.0),
        );
        curves.push(mark(column, Paint::Line));
    }
    curves.extend(dots);
    curves
}
