//! A density sampled on a grid of square cells and integrated over
//! polygons exactly for that piecewise-constant density, strip by strip:
//! the moments a weighted Lloyd or LBG step needs, at a cost that grows
//! with a cell's height in grid rows, not with its area. Sampling a
//! density at a dozen points per cell misses an edge in an image that
//! runs through a large cell; this does not.

use kurbo::{Point, Rect, Vec2};

use super::relax::Moments;

/// Most grid cells (three running sums of 8 bytes each per cell: 96 MB):
/// a finer grid than that is coarsened.
const MAX_CELLS: f64 = 4_000_000.0;

/// Fewest strips a polygon is cut into across its height: within a strip
/// without a vertex its width changes linearly and the middle line is
/// exact, so the error is confined to strips holding a vertex.
const MIN_STRIPS: f64 = 8.0;

/// A density on a grid of square cells over a rectangle, with running
/// sums along each row of `∫ρ`, `∫ρx` and `∫ρx²` (x from the grid's left).
#[derive(Debug, Clone)]
pub(super) struct DensityGrid {
    origin: Point,
    cell: f64,
    width: usize,
    height: usize,
    /// Per row, `width + 1` running sums from the row's left edge.
    sums: [Vec<f64>; 3],
    /// The density of each cell, row by row.
    values: Vec<f64>,
}

impl DensityGrid {
    /// `rho` sampled at the centres of square cells of side `cell` (mm)
    /// over `bounds` (coarser if that would be more than [`MAX_CELLS`]);
    /// values that are negative or not finite count as 0.
    pub(super) fn new(bounds: Rect, cell: f64, rho: &dyn Fn(Point) -> f64) -> DensityGrid {
        let cell = cell.max((bounds.area() / MAX_CELLS).sqrt());
        let width = (bounds.width() / cell).ceil().max(1.0) as usize;
        let height = (bounds.height() / cell).ceil().max(1.0) as usize;
        let mut values = Vec::with_capacity(width * height);
        let mut sums = [0, 1, 2].map(|_| Vec::with_capacity((width + 1) * height));
        for j in 0..height {
            let y = bounds.y0 + (j as f64 + 0.5) * cell;
            let mut acc = [0.0; 3];
            for s in &mut sums {
                s.push(0.0);
            }
            for i in 0..width {
                let r = rho(Point::new(bounds.x0 + (i as f64 + 0.5) * cell, y));
                let r = if r.is_finite() && r > 0.0 { r } else { 0.0 };
                values.push(r);
                let (a, b) = (i as f64 * cell, (i + 1) as f64 * cell);
                acc[0] += r * (b - a);
                acc[1] += r * (b * b - a * a) / 2.0;
                acc[2] += r * (b * b * b - a * a * a) / 3.0;
                for (s, v) in sums.iter_mut().zip(acc) {
                    s.push(v);
                }
            }
        }
        DensityGrid {
            origin: bounds.origin(),
            cell,
            width,
            height,
            sums,
            values,
        }
    }

    /// `∫ρ`, `∫ρx`, `∫ρx²` along row `j` from its left edge to `x` (grid
    /// coordinates, mm).
    fn running(&self, j: usize, x: f64) -> [f64; 3] {
        let x = x.clamp(0.0, self.width as f64 * self.cell);
        let i = ((x / self.cell) as usize).min(self.width - 1);
        let base = j * (self.width + 1) + i;
        let r = self.values[j * self.width + i];
        let a = i as f64 * self.cell;
        [
            self.sums[0][base] + r * (x - a),
            self.sums[1][base] + r * (x * x - a * a) / 2.0,
            self.sums[2][base] + r * (x * x * x - a * a * a) / 3.0,
        ]
    }

    /// The moments of the polygons `contours` (outer contours and holes,
    /// even-odd) about `origin`.
    pub(super) fn moments(&self, contours: &[Vec<Point>], origin: Vec2) -> Moments {
        let mut m = Moments::default();
        let (mut top, mut bottom) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in contours.iter().flatten() {
            top = top.min(p.y);
            bottom = bottom.max(p.y);
        }
        if bottom.partial_cmp(&top) != Some(std::cmp::Ordering::Greater) {
            return m;
        }
        let strips = ((bottom - top) / self.cell).ceil().max(MIN_STRIPS);
        let dy = (bottom - top) / strips;
        let mut xs = Vec::new();
        // Grid coordinates of the origin.
        let o = origin - self.origin.to_vec2();
        for k in 0..strips as usize {
            let y = top + (k as f64 + 0.5) * dy;
            let gy = y - self.origin.y;
            if gy < 0.0 || gy >= self.height as f64 * self.cell {
                continue;
            }
            let j = ((gy / self.cell) as usize).min(self.height - 1);
            xs.clear();
            for c in contours {
                for (e, a) in c.iter().enumerate() {
                    let b = c[(e + 1) % c.len()];
                    if (a.y <= y) != (b.y <= y) {
                        xs.push(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x) - self.origin.x);
                    }
                }
            }
            xs.sort_by(f64::total_cmp);
            let dyo = gy - o.y;
            for span in xs.chunks_exact(2) {
                let [a0, a1, a2] = self.running(j, span[0]);
                let [b0, b1, b2] = self.running(j, span[1]);
                let (f0, f1, f2) = ((b0 - a0) * dy, (b1 - a1) * dy, (b2 - a2) * dy);
                // About the origin: ∫ρ(x − ox) = f1 − ox·f0, and so on.
                let fx = f1 - o.x * f0;
                m.mass += f0;
                m.first += Vec2::new(fx, dyo * f0);
                m.xx += f2 - 2.0 * o.x * f1 + o.x * o.x * f0;
                m.xy += dyo * fx;
                m.yy += dyo * dyo * f0;
            }
        }
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x0: f64, y0: f64, s: f64) -> Vec<Point> {
        vec![
            Point::new(x0, y0),
            Point::new(x0 + s, y0),
            Point::new(x0 + s, y0 + s),
            Point::new(x0, y0 + s),
        ]
    }

    #[test]
    fn an_even_density_gives_the_polygon_moments() {
        let g = DensityGrid::new(Rect::new(0.0, 0.0, 100.0, 100.0), 0.5, &|_| 1.0);
        let origin = Vec2::new(12.0, 7.0);
        let tri = vec![
            Point::new(10.0, 10.0),
            Point::new(40.0, 15.0),
            Point::new(20.0, 45.0),
        ];
        for contours in [vec![square(10.0, 20.0, 30.0)], vec![tri]] {
            let exact = Moments::of(&contours, origin);
            let m = g.moments(&contours, origin);
            assert!(
                (m.mass - exact.mass).abs() < 2e-3 * exact.mass,
                "{m:?} {exact:?}"
            );
            for (a, b) in [
                (m.first.x, exact.first.x),
                (m.first.y, exact.first.y),
                (m.xx, exact.xx),
                (m.xy, exact.xy),
                (m.yy, exact.yy),
            ] {
                assert!((a - b).abs() < 5e-3 * exact.mass * 30.0 * 30.0, "{a} {b}");
            }
        }
        // A hole takes its part away.
        let with_hole = vec![square(10.0, 10.0, 40.0), {
            let mut h = square(20.0, 20.0, 10.0);
            h.reverse();
            h
        }];
        let m = g.moments(&with_hole, origin);
        assert!((m.mass - 1500.0).abs() < 1.0, "{}", m.mass);
    }

    #[test]
    fn an_edge_in_the_density_is_found_inside_a_large_cell() {
        // Dark only in a thin band x ∈ [50, 52): a big square over it holds
        // exactly the band's part, wherever a few samples would fall.
        let g = DensityGrid::new(Rect::new(0.0, 0.0, 100.0, 100.0), 1.0, &|p: Point| {
            if (50.0..52.0).contains(&p.x) {
                1.0
            } else {
                0.0
            }
        });
        let m = g.moments(&[square(0.0, 0.0, 100.0)], Vec2::ZERO);
        assert!((m.mass - 200.0).abs() < 1e-6, "{}", m.mass);
        assert!((m.first.x / m.mass - 51.0).abs() < 1e-6);
        // Beyond the grid there is no density.
        let out = g.moments(&[square(200.0, 200.0, 10.0)], Vec2::ZERO);
        assert_eq!(out.mass, 0.0);
    }
}
