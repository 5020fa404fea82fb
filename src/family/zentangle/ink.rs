//! Ink on the page per square millimetre, as the filling loop lays it
//! down: what lets line work that converges (whirls spiralling into a
//! point, borders nested in borders, small elements piled up) stop before
//! a felt tip blots or tears the paper (docs/SPEC.md §6 "ink density").
//!
//! A pen `w` mm wide covers paper solid with `1 / w` mm of line per mm²
//! (one line every width). [`Ink`] counts line length per 1 mm cell of the
//! page, cells aligned to the page origin, as `moyo stats` counts its
//! densest mm² (`plot::stats::densest`), and black area as the lines its
//! hatch will draw (once, however often it is painted black). The loop measures what it is about to draw
//! ([`Cells`]), asks whether it [`fits`](Ink::fits) under the limit, and
//! [`adds`](Ink::add) what it drew.

use kurbo::{BezPath, PathEl, Point};
use rustc_hash::FxHashMap;

/// Curves are measured on a polyline this close to them (mm).
const FLATTENING: f64 = 0.01;

/// Line is counted in pieces of at most this length (mm), each in the
/// cell of its middle, as `moyo stats` counts it.
const PIECE: f64 = 0.05;

/// A hatched area is measured along rows this far apart (mm).
const ROW: f64 = 0.1;

/// What a drawing puts into each cell of one millimetre (by the cell's
/// corner nearest the origin): mm of line, and mm² of black area that
/// the pen will hatch.
#[derive(Debug, Clone, Default)]
pub(super) struct Cells(FxHashMap<(i64, i64), [f64; 2]>);

impl Cells {
    /// The ink of `path` drawn as a line.
    pub(super) fn line(&mut self, path: &BezPath) {
        for (a, b) in segments(path) {
            let length = a.distance(b);
            let pieces = (length / PIECE).ceil().max(1.0);
            let each = length / pieces;
            for k in 0..pieces as usize {
                let mid = a.lerp(b, (k as f64 + 0.5) / pieces);
                self.0.entry(cell(mid)).or_default()[0] += each;
            }
        }
    }

    /// The area `path` encloses (even-odd), painted black: the pen hatches
    /// it.
    pub(super) fn black(&mut self, path: &BezPath) {
        let edges: Vec<(Point, Point)> = segments(path).collect();
        let (Some(top), Some(bottom)) = (
            edges.iter().map(|(a, b)| a.y.min(b.y)).reduce(f64::min),
            edges.iter().map(|(a, b)| a.y.max(b.y)).reduce(f64::max),
        ) else {
            return;
        };
        let mut y = (top / ROW).floor() * ROW + ROW / 2.0;
        let mut crossings = Vec::new();
        while y < bottom {
            crossings.clear();
            crossings.extend(
                edges
                    .iter()
                    .filter(|(a, b)| (a.y <= y) != (b.y <= y))
                    .map(|&(a, b)| a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x)),
            );
            crossings.sort_by(f64::total_cmp);
            for span in crossings.chunks_exact(2) {
                self.row(y, span[0], span[1]);
            }
            y += ROW;
        }
    }

    /// Adds `other`'s ink to this.
    pub(super) fn merge(&mut self, other: Cells) {
        for (c, [line, area]) in other.0 {
            let held = self.0.entry(c).or_default();
            held[0] += line;
            held[1] += area;
        }
    }

    /// Adds the area of the row at `y` from `x0` to `x1` ([`ROW`] wide),
    /// split at cell borders.
    fn row(&mut self, y: f64, x0: f64, x1: f64) {
        let row = y.floor() as i64;
        let mut x = x0;
        while x < x1 {
            let column = x.floor();
            let end = (column + 1.0).min(x1);
            self.0.entry((column as i64, row)).or_default()[1] += (end - x) * ROW;
            x = end;
        }
    }
}

/// The ink laid down so far, and how much a cell may hold.
#[derive(Debug, Clone)]
pub(super) struct Ink {
    cells: FxHashMap<(i64, i64), [f64; 2]>,
    /// mm of line a cell may hold.
    limit: f64,
    /// mm of hatch line per mm² of black (0: black is not hatched).
    hatch: f64,
}

impl Ink {
    /// An empty page for a pen `pen` mm wide, each cell holding at most
    /// `solid` times solid ink; black is hatched `hatch` mm apart
    /// (`None`: filled, no lines).
    pub(super) fn new(pen: f64, solid: f64, hatch: Option<f64>) -> Ink {
        Ink {
            cells: FxHashMap::default(),
            limit: solid / pen,
            hatch: hatch.map_or(0.0, |spacing| 1.0 / spacing),
        }
    }

    /// mm of line in a cell holding `line` mm of line and `area` mm² of
    /// black: black painted twice over (a black mark on a black ground)
    /// is hatched once, so a cell's hatch is at most its whole area's.
    fn ink(&self, [line, area]: [f64; 2]) -> f64 {
        line + area.min(1.0) * self.hatch
    }

    /// Whether `extra` can be drawn with no cell passing the limit. Cells
    /// already past it (by ink added regardless) take nothing more.
    pub(super) fn fits(&self, extra: &Cells) -> bool {
        extra.0.iter().all(|(c, [line, area])| {
            let [held_line, held_area] = self.cells.get(c).copied().unwrap_or_default();
            self.ink([held_line + line, held_area + area]) <= self.limit
        })
    }

    /// Counts `drawn` as laid down.
    pub(super) fn add(&mut self, drawn: &Cells) {
        for (c, [line, area]) in &drawn.0 {
            let held = self.cells.entry(*c).or_default();
            held[0] += line;
            held[1] += area;
        }
    }

    /// Takes back `drawn`, counted by [`Ink::add`] before.
    pub(super) fn remove(&mut self, drawn: &Cells) {
        for (c, [line, area]) in &drawn.0 {
            if let Some(held) = self.cells.get_mut(c) {
                held[0] -= line;
                held[1] -= area;
            }
        }
    }

    /// The most ink in any cell, as a multiple of the limit.
    #[cfg(test)]
    pub(super) fn fullest(&self) -> f64 {
        self.cells
            .values()
            .map(|&held| self.ink(held))
            .fold(0.0, f64::max)
            / self.limit
    }
}

/// The cell holding `p`.
fn cell(p: Point) -> (i64, i64) {
    (p.x.floor() as i64, p.y.floor() as i64)
}

/// The straight pieces of `path` flattened, closing segments included.
fn segments(path: &BezPath) -> impl Iterator<Item = (Point, Point)> {
    let mut out = Vec::new();
    let (mut start, mut last) = (Point::ORIGIN, Point::ORIGIN);
    kurbo::flatten(path, FLATTENING, |el| match el {
        PathEl::MoveTo(p) => (start, last) = (p, p),
        PathEl::LineTo(p) => {
            out.push((last, p));
            last = p;
        }
        PathEl::ClosePath => {
            out.push((last, start));
            last = start;
        }
        PathEl::QuadTo(..) | PathEl::CurveTo(..) => unreachable!("flattened"),
    });
    out.into_iter().filter(|(a, b)| a != b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{Line, Rect, Shape};

    fn line(a: (f64, f64), b: (f64, f64)) -> BezPath {
        Line::new(a, b).to_path(0.0)
    }

    #[test]
    fn a_line_puts_its_length_in_the_cells_it_crosses() {
        let mut c = Cells::default();
        c.line(&line((0.5, 0.5), (3.5, 0.5)));
        assert!((c.0[&(0, 0)][0] - 0.5).abs() < 1e-9);
        assert!((c.0[&(1, 0)][0] - 1.0).abs() < 1e-9);
        assert!((c.0[&(3, 0)][0] - 0.5).abs() < 1e-9);
        let total: f64 = c.0.values().map(|v| v[0]).sum();
        assert!((total - 3.0).abs() < 1e-9);
    }

    #[test]
    fn black_is_hatched_once_however_often_it_is_painted() {
        // A 4 × 2 mm rectangle hatched 0.5 mm apart: 16 mm of line, 2 mm
        // in each cell, the same when painted black twice.
        let rect = Rect::new(10.0, 20.0, 14.0, 22.0).to_path(0.0);
        let mut c = Cells::default();
        c.black(&rect);
        assert_eq!(c.0.len(), 8);
        let mut ink = Ink::new(0.25, 1.0, Some(0.5));
        assert!(ink.fits(&c), "2 mm of line in a cell of 4");
        ink.add(&c);
        assert!((ink.fullest() - 0.5).abs() < 1e-6, "{}", ink.fullest());
        ink.add(&c);
        assert!((ink.fullest() - 0.5).abs() < 1e-6, "{}", ink.fullest());
        // Black that is not hatched adds no line.
        let mut filled = Ink::new(0.25, 1.0, None);
        filled.add(&c);
        assert_eq!(filled.fullest(), 0.0);
    }

    #[test]
    fn ink_past_the_limit_does_not_fit_and_what_fits_is_counted() {
        // A 0.5 mm pen is solid at 2 mm per mm²; twice solid is 4 mm.
        let mut ink = Ink::new(0.5, 2.0, None);
        let mut three = Cells::default();
        three.line(&line((0.0, 0.5), (1.0, 0.5)));
        three.line(&line((0.0, 0.3), (1.0, 0.3)));
        three.line(&line((0.0, 0.7), (1.0, 0.7)));
        assert!(ink.fits(&three));
        ink.add(&three);
        let mut one = Cells::default();
        one.line(&line((0.0, 0.9), (1.0, 0.9)));
        assert!(ink.fits(&one), "four of four");
        ink.add(&one);
        assert!(!ink.fits(&one), "five of four");
        ink.remove(&one);
        assert!(ink.fits(&one), "four of four again");
        // Elsewhere there is room.
        let mut away = Cells::default();
        away.line(&line((5.0, 5.5), (6.0, 5.5)));
        assert!(ink.fits(&away));
        assert!((ink.fullest() - 0.75).abs() < 1e-9);
    }
}
