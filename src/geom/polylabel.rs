//! The pole of inaccessibility: the point of a region farthest from its
//! boundary, i.e. the centre of the largest inscribed circle, together with
//! that circle's radius (docs/SPEC.md §2.4 step 2: the zentangle filling loop picks
//! the region whose largest inscribed circle is largest).
//!
//! The classic grid and priority-queue search (Mapbox's "polylabel") over
//! the flattened region, holes included: square cells are split in four,
//! best potential first, and a cell is dropped once it cannot beat the best
//! point by more than `precision`.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use kurbo::{Point, Rect};

use super::region::Region;
use super::TOLERANCE;

/// Upper bound on the cells examined, so that a tiny `precision` on a huge
/// region still finishes (in milliseconds); the answer is then the best
/// found so far.
const MAX_CELLS: usize = 200_000;

/// `precision` is raised to at least this fraction of the region's size.
const MIN_RELATIVE_PRECISION: f64 = 1e-9;

/// The centre and radius (mm) of the largest circle inside `region`.
///
/// The result is within `precision` (mm) of the true optimum radius, for
/// the region's boundary flattened within `min(precision, TOLERANCE)`; the
/// radius is the distance from the centre to the nearest boundary point.
/// For a region of several parts the best part wins. A non-finite or
/// non-positive `precision` means [`TOLERANCE`]. `None` for the empty region.
pub fn pole_of_inaccessibility(region: &Region, precision: f64) -> Option<(Point, f64)> {
    let bounds = region.bounds();
    let size = bounds.width().max(bounds.height());
    let precision = if precision.is_finite() && precision > 0.0 {
        precision
    } else {
        TOLERANCE
    }
    .max(size * MIN_RELATIVE_PRECISION);
    let edges = Edges::new(&region.polygons(precision.min(TOLERANCE)));
    if edges.is_empty() {
        return None;
    }
    Some(search(&edges, bounds, precision))
}

fn search(edges: &Edges, bounds: Rect, precision: f64) -> (Point, f64) {
    let cell_size = bounds.width().min(bounds.height());
    let centre = bounds.center();
    if cell_size <= 0.0 {
        return (centre, 0.0);
    }
    let h = cell_size / 2.0;
    let mut queue = BinaryHeap::new();
    let mut y = bounds.y0;
    while y < bounds.y1 {
        let mut x = bounds.x0;
        while x < bounds.x1 {
            queue.push(Cell::new(Point::new(x + h, y + h), h, edges));
            x += cell_size;
        }
        y += cell_size;
    }
    // Good first guesses: the centroid of the boundary vertices' polygon
    // area, and the middle of the bounds.
    let mut best = Cell::new(edges.centroid().unwrap_or(centre), 0.0, edges);
    let middle = Cell::new(centre, 0.0, edges);
    if middle.d > best.d {
        best = middle;
    }
    let mut examined = queue.len();
    while let Some(cell) = queue.pop() {
        let (c, h, max) = (cell.c, cell.h / 2.0, cell.max);
        if cell.d > best.d {
            best = cell;
        }
        if max - best.d <= precision || examined >= MAX_CELLS {
            continue;
        }
        for (dx, dy) in [(-h, -h), (h, -h), (-h, h), (h, h)] {
            queue.push(Cell::new(c + (dx, dy), h, edges));
        }
        examined += 4;
    }
    (best.c, best.d.max(0.0))
}

/// A square cell: centre, half size, signed distance of the centre to the
/// boundary (positive inside) and the best distance any point of the cell
/// could have.
struct Cell {
    c: Point,
    h: f64,
    d: f64,
    max: f64,
}

impl Cell {
    fn new(c: Point, h: f64, edges: &Edges) -> Cell {
        let d = edges.signed_distance(c);
        Cell {
            c,
            h,
            d,
            max: d + h * std::f64::consts::SQRT_2,
        }
    }
}

impl PartialEq for Cell {
    fn eq(&self, other: &Self) -> bool {
        self.max.total_cmp(&other.max) == Ordering::Equal
    }
}
impl Eq for Cell {}
impl PartialOrd for Cell {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Cell {
    fn cmp(&self, other: &Self) -> Ordering {
        self.max.total_cmp(&other.max)
    }
}

/// The boundary as line segments (a→b), oriented as the region's contours.
struct Edges {
    edges: Vec<(Point, Point)>,
}

impl Edges {
    fn new(polygons: &[Vec<Point>]) -> Edges {
        let mut edges = Vec::new();
        for poly in polygons {
            for i in 0..poly.len() {
                edges.push((poly[i], poly[(i + 1) % poly.len()]));
            }
        }
        Edges { edges }
    }

    fn is_empty(&self) -> bool {
        self.edges.is_empty()
    }

    /// Distance from `p` to the nearest edge, positive inside (non-zero
    /// winding: the region is normalised, so that is its interior).
    fn signed_distance(&self, p: Point) -> f64 {
        let mut winding = 0i32;
        let mut best = f64::INFINITY;
        for &(a, b) in &self.edges {
            if (a.y <= p.y) != (b.y <= p.y) {
                let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if x > p.x {
                    winding += if b.y > a.y { 1 } else { -1 };
                }
            }
            best = best.min(segment_distance_sq(p, a, b));
        }
        let d = best.sqrt();
        if winding != 0 {
            d
        } else {
            -d
        }
    }

    /// Area centroid of all contours (holes count negatively).
    fn centroid(&self) -> Option<Point> {
        let (mut area, mut cx, mut cy) = (0.0, 0.0, 0.0);
        for &(a, b) in &self.edges {
            let f = a.x * b.y - b.x * a.y;
            area += f;
            cx += (a.x + b.x) * f;
            cy += (a.y + b.y) * f;
        }
        (area.abs() > 0.0).then(|| Point::new(cx / (3.0 * area), cy / (3.0 * area)))
    }
}

fn segment_distance_sq(p: Point, a: Point, b: Point) -> f64 {
    let ab = b - a;
    let len2 = ab.hypot2();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * t - p).hypot2()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::region::tests::{arb_region, circle, rect};
    use proptest::prelude::*;

    #[test]
    fn circle_pole_is_its_centre() {
        let (c, r) = pole_of_inaccessibility(&circle(10.0, 20.0, 5.0), 1e-3).unwrap();
        assert!((c - Point::new(10.0, 20.0)).hypot() < 0.02, "{c:?}");
        assert!((r - 5.0).abs() < 0.02, "{r}");
    }

    #[test]
    fn rectangle_pole_has_half_the_short_side() {
        let (c, r) = pole_of_inaccessibility(&rect(0.0, 0.0, 40.0, 10.0), 1e-3).unwrap();
        assert!((r - 5.0).abs() < 2e-3, "{r}");
        assert!((c.y - 5.0).abs() < 0.01 && c.x > 5.0 - 1e-6 && c.x < 35.0 + 1e-6);
    }

    #[test]
    fn holes_push_the_pole_away() {
        // A disc of radius 10 with a hole of radius 4 in the middle: the
        // largest circle sits in the ring, radius 3.
        let ring = circle(0.0, 0.0, 10.0).difference(&circle(0.0, 0.0, 4.0));
        let (c, r) = pole_of_inaccessibility(&ring, 1e-2).unwrap();
        assert!((r - 3.0).abs() < 0.02, "{r}");
        assert!((c.to_vec2().hypot() - 7.0).abs() < 0.05, "{c:?}");
        assert!(!ring.contains(Point::ORIGIN));
    }

    #[test]
    fn several_parts_best_one_wins() {
        let two = circle(0.0, 0.0, 2.0).union(&circle(50.0, 0.0, 6.0));
        let (c, r) = pole_of_inaccessibility(&two, 1e-3).unwrap();
        assert!((c.x - 50.0).abs() < 0.05 && (r - 6.0).abs() < 0.02);
    }

    #[test]
    fn empty_and_silly_precision() {
        assert!(pole_of_inaccessibility(&Region::empty(), 1e-3).is_none());
        let r = rect(0.0, 0.0, 10.0, 10.0);
        for p in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-300] {
            let (_, rad) = pole_of_inaccessibility(&r, p).unwrap();
            assert!((rad - 5.0).abs() < 0.02, "{p}: {rad}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(32))]
        #[test]
        fn the_circle_is_inside_and_touches(r in arb_region()) {
            let (c, rad) = pole_of_inaccessibility(&r, 1e-3).unwrap();
            prop_assert!(rad > 0.0);
            prop_assert!(r.contains(c));
            // Points of the circle, slightly shrunk, are inside.
            for k in 0..16 {
                let a = k as f64 * std::f64::consts::TAU / 16.0;
                let q = c + kurbo::Vec2::new(a.cos(), a.sin()) * (rad - 2.0 * TOLERANCE).max(0.0);
                prop_assert!(r.contains(q));
            }
        }
    }
}
