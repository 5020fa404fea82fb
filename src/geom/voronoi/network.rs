//! Lines a plotter draws once: the edges of a clipped Voronoi diagram
//! without the doubles two neighbouring cells share, and edge lists joined
//! into long strokes.

use kurbo::{BezPath, Point, Vec2};

use super::{Diagram, Domain};
use crate::geom::PointIndex;

/// How far (mm) beyond an edge's middle the other side is probed: well
/// above the rounding of clipped cells (about 1e-9 of a cell), well below
/// the smallest spacing of sites (0.1 mm).
const PROBE: f64 = 1e-5;

/// The cells' outlines with every edge once: an edge two cells share is
/// drawn by the cell of the lower site, an edge on the region's outline
/// (`domain`'s, holes included) by its only cell, when `outline` asks for
/// the region's outline. Runs of drawn edges along a contour are one
/// stroke (a closed one when the whole contour is drawn).
///
/// An edge lies on the outline when a point just beyond its middle lies
/// outside the region; else the cell across is the site nearest to that
/// point (the edge lies on their bisector). The nearest site alone cannot
/// tell: beyond a narrow hole (a rose window's ring of tracery) the
/// nearest site may be another cell's, across the hole.
pub(crate) fn cell_network(diagram: &Diagram, domain: &Domain, outline: bool) -> Vec<BezPath> {
    let cells = diagram.cells();
    // Sites without a cell (merged, dropped, outside) are never the nearest.
    let owners: Vec<Point> = diagram
        .sites()
        .iter()
        .zip(cells)
        .map(|(p, c)| {
            if c.is_empty() {
                Point::new(f64::NAN, f64::NAN)
            } else {
                *p
            }
        })
        .collect();
    let mut index = PointIndex::new(&owners);
    let mut strokes = Vec::new();
    for (i, cell) in cells.iter().enumerate() {
        for contour in cell.contours() {
            let n = contour.len();
            if n < 2 {
                continue;
            }
            let drawn: Vec<bool> = (0..n)
                .map(|k| {
                    let (a, b) = (contour[k], contour[(k + 1) % n]);
                    let across = beyond(a, b, owners[i]);
                    if !domain.contains(across) {
                        return outline;
                    }
                    match index.nearest_within(across, f64::INFINITY) {
                        Some((j, _)) if j as usize != i => j as usize > i,
                        // Inside, with no other cell across: a sliver the
                        // clipping left on the outline.
                        _ => outline,
                    }
                })
                .collect();
            strokes.extend(runs(contour, &drawn));
        }
    }
    strokes
}

/// A point just beyond the middle of edge `a`–`b`, on the side away from
/// `site`.
fn beyond(a: Point, b: Point, site: Point) -> Point {
    let mid = a.midpoint(b);
    let along = b - a;
    let mut normal = Vec2::new(-along.y, along.x).normalize();
    if !normal.is_finite() {
        return mid;
    }
    if normal.dot(mid - site) < 0.0 {
        normal = -normal;
    }
    mid + normal * PROBE
}

/// The strokes of a closed contour whose edge `k` (from point `k` to
/// `k + 1`) is drawn where `drawn[k]`.
fn runs(contour: &[Point], drawn: &[bool]) -> Vec<BezPath> {
    let n = contour.len();
    if drawn.iter().all(|d| *d) {
        let mut p = BezPath::new();
        p.move_to(contour[0]);
        for q in &contour[1..] {
            p.line_to(*q);
        }
        p.close_path();
        return vec![p];
    }
    // Start just after an edge that is not drawn, so no run is cut in two.
    let Some(gap) = drawn.iter().position(|d| !d) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut current: Option<BezPath> = None;
    for step in 1..=n {
        let k = (gap + step) % n;
        if drawn[k] {
            let p = current.get_or_insert_with(|| {
                let mut p = BezPath::new();
                p.move_to(contour[k]);
                p
            });
            p.line_to(contour[(k + 1) % n]);
        } else if let Some(p) = current.take() {
            out.push(p);
        }
    }
    out.extend(current);
    out
}

/// The edges `[i, j]` between `points` joined into strokes: from a point
/// with edges left, along unused edges until none is left there. Each edge
/// is in exactly one stroke; odd-degree points start strokes first, so a
/// path that can be drawn in one go is.
pub(crate) fn chains(points: &[Point], edges: &[[usize; 2]]) -> Vec<BezPath> {
    let mut adjacent: Vec<Vec<(usize, usize)>> = vec![Vec::new(); points.len()];
    for (e, &[i, j]) in edges.iter().enumerate() {
        adjacent[i].push((j, e));
        adjacent[j].push((i, e));
    }
    let mut used = vec![false; edges.len()];
    let mut next_unused = vec![0usize; points.len()];
    let starts = (0..points.len())
        .filter(|&v| adjacent[v].len() % 2 == 1)
        .chain(0..points.len());
    let mut out = Vec::new();
    for start in starts {
        loop {
            let mut at = start;
            let mut path: Option<BezPath> = None;
            while let Some(&(to, e)) = adjacent[at][next_unused[at]..]
                .iter()
                .find(|(_, e)| !used[*e])
            {
                used[e] = true;
                let p = path.get_or_insert_with(|| {
                    let mut p = BezPath::new();
                    p.move_to(points[at]);
                    p
                });
                p.line_to(points[to]);
                at = to;
            }
            advance(&adjacent[start], &used, &mut next_unused[start]);
            match path {
                Some(p) => out.push(p),
                None => break,
            }
        }
    }
    out
}

/// Moves a point's cursor past its used edges, so each edge list is read
/// once overall.
fn advance(adjacent: &[(usize, usize)], used: &[bool], cursor: &mut usize) {
    while *cursor < adjacent.len() && used[adjacent[*cursor].1] {
        *cursor += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::path_length;

    #[test]
    fn chains_use_every_edge_once() {
        // A square with both diagonals: 4 points of degree 3.
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(0.0, 1.0),
        ];
        let edges = [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2], [1, 3]];
        let strokes = chains(&pts, &edges);
        let total: f64 = strokes.iter().map(path_length).sum();
        assert!((total - (4.0 + 2.0 * 2f64.sqrt())).abs() < 1e-12);
        // Four odd points: two strokes suffice, and the walk finds them.
        assert_eq!(strokes.len(), 2);
        // A path graph is one stroke.
        let line = chains(&pts, &[[0, 1], [1, 2], [2, 3]]);
        assert_eq!(line.len(), 1);
    }

    #[test]
    fn runs_split_at_undrawn_edges() {
        let square = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(0.0, 1.0),
        ];
        assert_eq!(runs(&square, &[true; 4]).len(), 1);
        assert!(runs(&square, &[false; 4]).is_empty());
        // Edges 3 and 0 form one run across the contour's start.
        let r = runs(&square, &[true, false, false, true]);
        assert_eq!(r.len(), 1);
        assert!((path_length(&r[0]) - 2.0).abs() < 1e-12);
        assert_eq!(runs(&square, &[true, false, true, false]).len(), 2);
    }
}
