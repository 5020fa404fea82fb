//! The triangles `draw = ["delaunay"]` draws: a constrained Delaunay
//! triangulation of the sites inside the region's outline, refined until
//! no triangle has an angle under [`MIN_ANGLE`] (or is smaller than
//! [`SMALLEST`]).
//!
//! Two faults of the plain triangulation go. *Fans of slivers*: a
//! rectangle's outline has four vertices, so every site near the border
//! joined a page corner, and a dozen thin triangles met there; refinement
//! (Ruppert and Chew, as spade does it) splits the outline and adds
//! points where a triangle is thin, so the mesh meets the border in
//! triangles of its own size. *Chords across curves*: the outline was
//! flattened coarsely (to keep the slivers down), and its chords cut into
//! holes by tenths of a millimetre. Now the outline is flattened within
//! [`FOLLOW`] of a copy of it moved [`INSIDE`] into the region, so every
//! edge lies inside the region and within a pen's width of its curves;
//! refinement keeps the slivers a fine flattening would make away.

use std::collections::BTreeSet;

use kurbo::{BezPath, Point};
use spade::{
    AngleLimit, ConstrainedDelaunayTriangulation, DelaunayTriangulation, Point2,
    RefinementParameters, Triangulation,
};

use crate::error::{Error, Result};
use crate::geom::offset::offset;
use crate::geom::region::Region;
use crate::geom::voronoi::chains;
use crate::geom::{PointIndex, TOLERANCE};

/// The smallest angle refinement lets a triangle keep, degrees, save
/// where the outline itself makes a sharper corner.
pub(crate) const MIN_ANGLE: f64 = 22.0;

/// Triangles of less area (mm²) are not refined further: along a tight
/// curve refinement would go on splitting, and a mesh of triangles a
/// millimetre across is about as much line as a fine pen lays down solid
/// (3.5 mm of line per mm² for equilateral ones).
const SMALLEST: f64 = 0.5;

/// How far inside the region the triangulated outline lies, mm.
const INSIDE: f64 = 0.06;

/// How closely the triangulated outline follows the moved-in one, mm:
/// with [`INSIDE`], every edge is inside the region and its outline is
/// within 0.1 mm of the region's.
const FOLLOW: f64 = 0.04;

/// A site closer to the outline than this fraction of the distance to
/// its nearest site is left out: refinement would fill the thin gap
/// between it and the outline with a cluster of tiny triangles.
const CLEARANCE: f64 = 0.5;

/// The outline is looked at in steps of this, mm, to find how far a site
/// is from it.
const OUTLINE_STEP: f64 = 0.5;

/// Refinement adds at most this many points per site, and a share of
/// outline vertices (bounds the work on any input).
const ADDED_PER_VERTEX: usize = 3;

/// A triangulation of a region.
#[derive(Debug, Clone, Default)]
pub(crate) struct Mesh {
    /// The corners of the triangles: sites, outline vertices and points
    /// refinement added.
    pub(crate) points: Vec<Point>,
    /// Every edge between two triangles, as `[i, j]` into `points`.
    pub(crate) inner: Vec<[usize; 2]>,
    /// Every edge of the outline, likewise.
    pub(crate) outline: Vec<[usize; 2]>,
    /// The triangles, as indices into `points`.
    pub(crate) triangles: Vec<[usize; 3]>,
}

impl Mesh {
    /// The inner edges chained into strokes. The outline a pen draws is
    /// the region's own, exact, not these edges a hair inside it.
    pub(crate) fn strokes(&self) -> Vec<BezPath> {
        chains(&self.points, &self.inner)
    }

    /// A triangle's corners.
    pub(crate) fn corners(&self, t: [usize; 3]) -> [Point; 3] {
        t.map(|i| self.points[i])
    }
}

/// The refined constrained Delaunay triangulation of the `sites` inside
/// `region` (those outside, or within [`INSIDE`] of its outline, take no
/// part, nor do those too near it: see [`CLEARANCE`]) and of its outline:
/// the sites are corners, and so are the points refinement adds where a
/// triangle would be thinner than [`MIN_ANGLE`].
///
/// # Errors
/// [`Error::Geometry`] should the triangulation fail.
pub(crate) fn triangulate(sites: &[Point], region: &Region) -> Result<Mesh> {
    let inner = offset(region, -INSIDE, TOLERANCE)?;
    let contours = inner.polygons(FOLLOW);
    let inside: Vec<Point> = sites.iter().copied().filter(|p| inner.contains(*p)).collect();
    let mut vertices: Vec<Point2<f64>> = clear_of(&inside, &contours)?
        .into_iter()
        .map(|p| Point2::new(p.x, p.y))
        .collect();
    let mut constraints = Vec::new();
    for contour in contours {
        let first = vertices.len();
        vertices.extend(contour.iter().map(|p| Point2::new(p.x, p.y)));
        for k in 0..contour.len() {
            constraints.push([first + k, first + (k + 1) % contour.len()]);
        }
    }
    let budget = ADDED_PER_VERTEX * vertices.len() + 100;
    // spade asserts on inputs it cannot take; that is an error here, not a
    // panic, and nothing is printed of it.
    crate::geom::engine_panic::catch(move || {
        let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
            ConstrainedDelaunayTriangulation::try_bulk_load_cdt(vertices, constraints, |_| {})
                .ok()?;
        let result = cdt.refine(
            RefinementParameters::new()
                .with_angle_limit(AngleLimit::from_deg(MIN_ANGLE))
                .with_min_required_area(SMALLEST)
                .exclude_outer_faces(true)
                .with_max_additional_vertices(budget),
        );
        let outside: BTreeSet<usize> = result.excluded_faces.iter().map(|f| f.index()).collect();
        let mut mesh = Mesh {
            points: cdt
                .vertices()
                .map(|v| Point::new(v.position().x, v.position().y))
                .collect(),
            ..Mesh::default()
        };
        let mut seen = BTreeSet::new();
        for face in cdt.inner_faces() {
            if outside.contains(&face.fix().index()) {
                continue;
            }
            mesh.triangles
                .push(face.vertices().map(|v| v.fix().index()));
            for e in face.adjacent_edges() {
                let u = e.as_undirected();
                if !seen.insert(u.fix().index()) {
                    continue;
                }
                let [a, b] = e.vertices().map(|v| v.fix().index());
                let edge = [a.min(b), a.max(b)];
                if cdt.is_constraint_edge(u.fix()) {
                    mesh.outline.push(edge);
                } else {
                    mesh.inner.push(edge);
                }
            }
        }
        mesh.inner.sort_unstable();
        mesh.outline.sort_unstable();
        Some(mesh)
    })
    .flatten()
    .ok_or_else(geometry)
}

/// The sites no nearer the outline (`contours`) than [`CLEARANCE`] of
/// the distance to their nearest site, in their order.
fn clear_of(sites: &[Point], contours: &[Vec<Point>]) -> Result<Vec<Point>> {
    if sites.len() < 2 {
        return Ok(sites.to_vec());
    }
    let mut outline = Vec::new();
    for c in contours {
        for (k, &a) in c.iter().enumerate() {
            let b = c[(k + 1) % c.len()];
            let n = (a.distance(b) / OUTLINE_STEP).ceil().max(1.0) as usize;
            outline.extend((0..n).map(|i| a.lerp(b, i as f64 / n as f64)));
        }
    }
    let mut near = PointIndex::new(&outline);
    let points: Vec<Point2<f64>> = sites.iter().map(|p| Point2::new(p.x, p.y)).collect();
    let dt: DelaunayTriangulation<Point2<f64>> =
        DelaunayTriangulation::bulk_load_stable(points).map_err(|_| geometry())?;
    // The nearest site is a Delaunay neighbour.
    let mut nearest = vec![f64::INFINITY; sites.len()];
    for v in dt.vertices() {
        let d2 = v
            .out_edges()
            .map(|e| e.length_2())
            .fold(f64::INFINITY, f64::min);
        nearest[v.fix().index()] = d2;
    }
    Ok(sites
        .iter()
        .zip(nearest)
        .filter(|(p, d2)| {
            let wall = near
                .nearest_within(**p, f64::INFINITY)
                .map_or(f64::INFINITY, |(_, w2)| w2);
            wall >= CLEARANCE * CLEARANCE * d2
        })
        .map(|(p, _)| *p)
        .collect())
}

fn geometry() -> Error {
    Error::Geometry {
        operation: "triangulating sites and outline".into(),
    }
}

#[cfg(test)]
mod tests {
    use kurbo::{Circle, Rect, Shape};

    use super::*;
    use crate::geom::region::FillRule;

    /// The three angles of a triangle, degrees.
    fn angles([a, b, c]: [Point; 3]) -> [f64; 3] {
        let at = |p: Point, q: Point, r: Point| {
            let (u, v) = (q - p, r - p);
            u.cross(v).abs().atan2(u.dot(v)).to_degrees()
        };
        [at(a, b, c), at(b, c, a), at(c, a, b)]
    }

    fn grid(step: f64, rect: Rect) -> Vec<Point> {
        let mut out = Vec::new();
        let mut y = rect.y0 + step / 2.0;
        while y < rect.y1 {
            let mut x = rect.x0 + step / 2.0 + (y * 0.37).sin();
            while x < rect.x1 {
                out.push(Point::new(x, y + (x * 0.71).sin()));
                x += step;
            }
            y += step;
        }
        out
    }

    /// A disc with a hole, the curves the chords cut.
    fn ring() -> Region {
        let mut path = Circle::new((50.0, 50.0), 45.0).to_path(1e-4);
        path.extend(Circle::new((50.0, 50.0), 12.0).to_path(1e-4));
        Region::new(path, FillRule::EvenOdd).unwrap()
    }

    #[test]
    fn no_edge_leaves_a_curved_region_and_the_outline_follows_its_curves() {
        let region = ring();
        let sites = grid(6.0, Rect::new(0.0, 0.0, 100.0, 100.0));
        let mesh = triangulate(&sites, &region).unwrap();
        let centre = Point::new(50.0, 50.0);
        let mut samples = 0;
        for &[i, j] in mesh.inner.iter().chain(&mesh.outline) {
            let (a, b) = (mesh.points[i], mesh.points[j]);
            for k in 0..=20 {
                let p = a.lerp(b, k as f64 / 20.0);
                let r = p.distance(centre);
                assert!((12.0..=45.0).contains(&r), "{p:?} at radius {r}");
                samples += 1;
            }
        }
        assert!(samples > 1000);
        // Every point of both circles is within 0.1 mm of the outline.
        for &[i, j] in &mesh.outline {
            let m = mesh.points[i].midpoint(mesh.points[j]);
            let r = m.distance(centre);
            assert!((r - 45.0).abs() < 0.1 || (r - 12.0).abs() < 0.1, "{r}");
        }
    }

    #[test]
    fn no_sliver_fans_at_the_page_corners() {
        let page = Rect::new(0.0, 0.0, 120.0, 170.0);
        let region = Region::from_rect(page).unwrap();
        // Dense sites in the middle, none near the border: what left a
        // dozen edges meeting in a page corner.
        let sites = grid(2.0, Rect::new(40.0, 50.0, 80.0, 120.0));
        let mesh = triangulate(&sites, &region).unwrap();
        let smallest = mesh
            .triangles
            .iter()
            .flat_map(|&t| angles(mesh.corners(t)))
            .fold(f64::INFINITY, f64::min);
        assert!(smallest > 15.0, "smallest angle {smallest}°");
        let corner = Point::new(INSIDE, INSIDE);
        let at_corner = mesh
            .inner
            .iter()
            .chain(&mesh.outline)
            .filter(|e| e.iter().any(|&i| mesh.points[i].distance(corner) < 1e-6))
            .count();
        assert!(at_corner <= 4, "{at_corner} edges meet at the corner");
        let area: f64 = mesh
            .triangles
            .iter()
            .map(|&t| {
                let [a, b, c] = mesh.corners(t);
                (b - a).cross(c - a).abs() / 2.0
            })
            .sum();
        let inside = (120.0 - 2.0 * INSIDE) * (170.0 - 2.0 * INSIDE);
        assert!((area - inside).abs() < 1e-3, "{area}");
    }
}
