//! The region-dependent patterns of the paper's §4.3 (図10): drawn from
//! the shape of the region they fill, not centred in it — contour lines,
//! the paradox whirl, Voronoi cells, Delaunay triangles, a fill of one
//! element, and elements along the border. Each gives marks in page
//! coordinates; what they leave of the region is `compose`'s business.

use kurbo::{Affine, BezPath, Point, Shape as _};

use super::element::{marks, paradox, Mark, Paint, Shape};
use crate::error::Result;
use crate::geom::offset::offset;
use crate::geom::region::Region;
use crate::geom::simplify::rdp;
use crate::geom::voronoi::{cell_network, constrained_delaunay, CellOptions, Diagram, Domain};
use crate::geom::{sample, TOLERANCE};
use crate::rng::RandomStream;

/// Most sites a Voronoi or Delaunay pattern puts in one region.
const MAX_SITES: usize = 400;

/// Most elements along one border.
const MAX_ALONG: usize = 60;

/// Most contour lines in one region.
const MAX_CONTOURS: usize = 40;

/// `contour_line`: the region's outline moved in by `gap`, `2·gap`, …
/// until nothing is left: rings that follow the shape, holes included.
pub(super) fn contour_lines(region: &Region, gap: f64) -> Result<Vec<Mark>> {
    let mut out = Vec::new();
    for k in 1..=MAX_CONTOURS {
        let inner = offset(region, -(k as f64) * gap, TOLERANCE)?;
        if inner.is_empty() {
            break;
        }
        out.push(Mark {
            path: inner.into_path(),
            paint: Paint::Line,
        });
    }
    Ok(out)
}

/// `paradox`: the outermost outline approximated by a polygon of a few
/// corners, then the polygon through points a fixed fraction along each
/// side of the previous one, repeated inwards: the whirl.
pub(super) fn paradox_whirl(region: &Region, corners: usize) -> Vec<Mark> {
    let Some(outline) = outermost(region) else {
        return Vec::new();
    };
    let polygon = coarse(&outline, corners);
    if polygon.len() < 3 {
        return Vec::new();
    }
    paradox(&polygon, Paint::White)
        .into_iter()
        .map(|m| Mark {
            path: m.path,
            paint: Paint::Line,
        })
        .collect()
}

/// `voronoi` and `delaunay_triangles`: Poisson-disk points `spacing`
/// apart inside the region, and their cells or their triangulation.
pub(super) fn cells_or_triangles(
    region: &Region,
    spacing: f64,
    triangles: bool,
    rng: &mut RandomStream,
) -> Result<Vec<Mark>> {
    let options = CellOptions::DEFAULT.with_max_sites(MAX_SITES);
    let spacing = spacing.max((region.area() / MAX_SITES as f64).sqrt() * 1.2);
    let sites = sample::poisson_disk(region, &|_| spacing, spacing..=spacing, rng, MAX_SITES)?;
    if sites.len() < 2 {
        return Ok(Vec::new());
    }
    let lines = if triangles {
        // The outline as points about `spacing` apart along it, so the
        // triangles reach the border without fanning out to every vertex
        // of a finely cut outline; the outline itself is drawn already.
        let coarse = resampled(region, spacing)?;
        let cdt = constrained_delaunay(&sites, &Domain::new(&coarse, TOLERANCE)?, &options)?;
        let mut lines: Vec<BezPath> = cdt
            .between_sites
            .iter()
            .map(|&[i, j]| kurbo::Line::new(sites[i], sites[j]).to_path(TOLERANCE))
            .collect();
        lines.extend(cdt.to_outline.iter().map(|l| l.to_path(TOLERANCE)));
        lines
    } else {
        let domain = Domain::new(region, TOLERANCE)?;
        cell_network(&Diagram::new(&sites, &domain, &options)?, &domain, true)
    };
    Ok(lines
        .into_iter()
        .map(|path| Mark {
            path,
            paint: Paint::Line,
        })
        .collect())
}

/// `fill`: the region's bounding box tiled with `shape` (`size` mm across,
/// on a square lattice), as lines or white-filled.
pub(super) fn tiled(region: &Region, shape: Shape, size: f64, paint: Paint) -> Vec<Mark> {
    let b = region.bounds();
    let n = ((b.width() / size).ceil() as usize + 1) * ((b.height() / size).ceil() as usize + 1);
    if n > 10_000 {
        return Vec::new();
    }
    let unit = marks(shape, paint);
    let mut out = Vec::new();
    let mut y = b.y0 + size / 2.0;
    while y < b.y1 + size / 2.0 {
        let mut x = b.x0 + size / 2.0;
        while x < b.x1 + size / 2.0 {
            let place = Affine::translate((x, y)) * Affine::scale(size / 2.0 * 0.9);
            out.extend(unit.iter().map(|m| m.transformed(place)));
            x += size;
        }
        y += size;
    }
    out
}

/// `along_border`: elements `size` mm across along the outermost outline,
/// a little more than their size apart, each turned to follow it; `pick`
/// chooses each one's shape and paint.
pub(super) fn along_border(
    region: &Region,
    size: f64,
    pick: &mut dyn FnMut(usize) -> (Shape, Paint),
) -> Vec<Mark> {
    let Some(outline) = outermost(region) else {
        return Vec::new();
    };
    let n = outline.len();
    let length: f64 = (0..n)
        .map(|i| outline[i].distance(outline[(i + 1) % n]))
        .sum();
    let count = ((length / (size * 1.3)).floor() as usize).min(MAX_ALONG);
    if count < 3 {
        return Vec::new();
    }
    let step = length / count as f64;
    let mut out = Vec::new();
    let mut walked = 0.0;
    let mut next = step / 2.0;
    let mut k = 0;
    for i in 0..n {
        let (a, b) = (outline[i], outline[(i + 1) % n]);
        let len = a.distance(b);
        while next < walked + len && k < count {
            let at = a.lerp(b, (next - walked) / len);
            let tangent = b - a;
            // Inwards is whichever side the region is on (an outline's
            // winding cannot be trusted to say so once cut and merged).
            let normal = tangent.turn_90().normalize() * (size / 2.0);
            let Some(centre) = [at + normal, at - normal]
                .into_iter()
                .find(|c| region.contains(*c))
            else {
                next += step;
                k += 1;
                continue;
            };
            let (shape, paint) = pick(k);
            let place = Affine::translate(centre.to_vec2())
                * Affine::rotate(tangent.atan2())
                * Affine::scale(size / 2.0 * 0.85);
            out.extend(marks(shape, paint).iter().map(|m| m.transformed(place)));
            next += step;
            k += 1;
        }
        walked += len;
    }
    out
}

/// The region with each contour replaced by points about `step` apart
/// along it (each contour keeps at least its three farthest-apart
/// points' worth: a dozen).
fn resampled(region: &Region, step: f64) -> Result<Region> {
    let mut path = BezPath::new();
    for contour in region.polygons(TOLERANCE) {
        let n = contour.len();
        let length: f64 = (0..n)
            .map(|i| contour[i].distance(contour[(i + 1) % n]))
            .sum();
        let count = ((length / step).round() as usize).max(12);
        let every = length / count as f64;
        let mut next = 0.0;
        let mut walked = 0.0;
        let mut points = Vec::with_capacity(count);
        for i in 0..n {
            let (a, b) = (contour[i], contour[(i + 1) % n]);
            let len = a.distance(b);
            while next < walked + len && points.len() < count {
                points.push(a.lerp(b, (next - walked) / len));
                next += every;
            }
            walked += len;
        }
        for (i, p) in points.iter().enumerate() {
            if i == 0 {
                path.move_to(*p);
            } else {
                path.line_to(*p);
            }
        }
        path.close_path();
    }
    Region::new(path, crate::geom::region::FillRule::EvenOdd)
}

/// The region's largest contour (its outermost outline), flattened.
fn outermost(region: &Region) -> Option<Vec<Point>> {
    region
        .polygons(TOLERANCE)
        .into_iter()
        .max_by(|a, b| polygon_area(a).abs().total_cmp(&polygon_area(b).abs()))
}

/// Signed area (positive clockwise on the page, y down).
fn polygon_area(p: &[Point]) -> f64 {
    let mut s = 0.0;
    for (i, a) in p.iter().enumerate() {
        let b = p[(i + 1) % p.len()];
        s += a.x * b.y - b.x * a.y;
    }
    s / 2.0
}

/// The outline with about `corners` corners: the points of it farthest
/// from each other's chords (Ramer-Douglas-Peucker, the tolerance raised
/// until few enough corners are left).
fn coarse(outline: &[Point], corners: usize) -> Vec<Point> {
    let size = outline
        .iter()
        .fold(kurbo::Rect::from_points(outline[0], outline[0]), |r, p| {
            r.union_pt(*p)
        });
    let mut tolerance = size.width().max(size.height()) * 0.02;
    loop {
        let kept = simplify(outline, tolerance);
        if kept.len() <= corners || tolerance > size.width().max(size.height()) {
            return kept;
        }
        tolerance *= 1.5;
    }
}

/// Ramer-Douglas-Peucker on a closed polygon, split at its first point
/// and the point farthest from it.
fn simplify(p: &[Point], tolerance: f64) -> Vec<Point> {
    if p.len() < 4 {
        return p.to_vec();
    }
    let far = (1..p.len())
        .max_by(|&i, &j| p[0].distance(p[i]).total_cmp(&p[0].distance(p[j])))
        .unwrap_or(1);
    let mut closed = p.to_vec();
    closed.push(p[0]);
    let mut out = Vec::new();
    let mut keep = Vec::new();
    for half in [&closed[..=far], &closed[far..]] {
        rdp(half, tolerance, &mut keep);
        // Each half's last point is the next one's first.
        out.extend(
            half.iter()
                .zip(&keep)
                .take(half.len() - 1)
                .filter(|(_, k)| **k)
                .map(|(q, _)| *q),
        );
    }
    out
}
