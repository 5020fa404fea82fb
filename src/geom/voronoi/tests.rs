//! Tests of the Voronoi diagram, the triangulations and relaxation.

use super::*;
use crate::geom::region::FillRule;
use crate::rng::Seed;
use kurbo::{Circle, Shape};
use proptest::prelude::*;

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Region {
    Region::from_rect(Rect::new(x0, y0, x1, y1)).unwrap()
}

fn polygon_region(points: &[(f64, f64)]) -> Region {
    let points: Vec<Point> = points.iter().map(|&p| p.into()).collect();
    Region::polygon(&points).unwrap()
}

/// An L: the 10×10 square without its top-right 5×5 quarter (y down).
fn l_shape() -> Region {
    polygon_region(&[
        (0.0, 0.0),
        (5.0, 0.0),
        (5.0, 5.0),
        (10.0, 5.0),
        (10.0, 10.0),
        (0.0, 10.0),
    ])
}

/// The 10×10 square with a 4×4 square hole in the middle: area 84.
fn square_with_hole() -> Region {
    rect(0.0, 0.0, 10.0, 10.0).difference(&rect(3.0, 3.0, 7.0, 7.0))
}

fn circle(x: f64, y: f64, r: f64) -> Region {
    Region::new(Circle::new((x, y), r).to_path(1e-9), FillRule::NonZero).unwrap()
}

/// `n` random points inside `domain`, by rejection in its bounds.
fn random_sites(domain: &Domain, n: usize, seed: u64) -> Vec<Point> {
    let b = domain.bounds();
    let mut s = Seed(seed).stream();
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let p = Point::new(s.range(b.x0, b.x1), s.range(b.y0, b.y1));
        if domain.contains(p) {
            out.push(p);
        }
    }
    out
}

fn domain(region: &Region) -> Domain {
    Domain::new(region, TOLERANCE).unwrap()
}

fn diagram(sites: &[Point], d: &Domain) -> Diagram {
    Diagram::new(sites, d, &CellOptions::DEFAULT).unwrap()
}

fn total_area(d: &Diagram) -> f64 {
    d.cells().iter().map(Cell::area).sum()
}

fn distance_to_outline(d: &Domain, p: Point) -> f64 {
    d.edges
        .iter()
        .map(|&[a, b]| {
            let ab = b - a;
            let t = ((p - a).dot(ab) / ab.hypot2()).clamp(0.0, 1.0);
            p.distance(a + ab * t)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Winding of a set of contours around `p` (by kurbo on the path).
fn cell_contains(cell: &Cell, p: Point) -> bool {
    cell.to_path().winding(p) != 0
}

/// The invariants every diagram must keep: cells tile the domain, lie
/// in it, and contain their own (inside) sites.
fn check_tiling(d: &Domain, diagram: &Diagram) {
    let total = total_area(diagram);
    assert!(
        (total - d.area()).abs() <= 1e-6 * d.area(),
        "cells cover {total}, the region {}",
        d.area()
    );
    for (i, cell) in diagram.cells().iter().enumerate() {
        assert!(cell.area() >= 0.0);
        for c in cell.contours() {
            for &v in c {
                assert!(
                    d.contains(v) || distance_to_outline(d, v) < 1e-6,
                    "cell {i} has a vertex {v:?} outside the region"
                );
            }
        }
        let site = diagram.sites()[i];
        if diagram.status()[i] == SiteStatus::Own
            && d.contains(site)
            && distance_to_outline(d, site) > 1e-6
        {
            assert!(
                cell_contains(cell, site),
                "cell {i} misses its site {site:?}"
            );
        }
    }
}

/// No overlaps: the area of the union of the cells is their sum.
fn check_no_overlap(diagram: &Diagram) {
    let regions: Vec<Region> = diagram.cells().iter().map(Cell::to_region).collect();
    let union = Region::union_all(&regions).area();
    let total = total_area(diagram);
    assert!(
        (union - total).abs() <= 1e-6 * total,
        "union {union} vs sum {total}: cells overlap"
    );
}

#[test]
fn cells_tile_a_square() {
    let d = domain(&rect(0.0, 0.0, 10.0, 10.0));
    let sites = random_sites(&d, 50, 1);
    let v = diagram(&sites, &d);
    assert!((total_area(&v) - 100.0).abs() < 1e-6 * 100.0);
    check_tiling(&d, &v);
    check_no_overlap(&v);
}

#[test]
fn cells_tile_a_concave_l() {
    let d = domain(&l_shape());
    assert!((d.area() - 75.0).abs() < 1e-12);
    let sites = random_sites(&d, 40, 2);
    let v = diagram(&sites, &d);
    check_tiling(&d, &v);
    check_no_overlap(&v);
    // The bay is left empty: no cell reaches into the missing quarter.
    for cell in v.cells() {
        for c in cell.contours() {
            for p in c {
                assert!(!(p.x > 5.0 + 1e-9 && p.y < 5.0 - 1e-9), "{p:?} in the bay");
            }
        }
    }
}

#[test]
fn cells_do_not_cover_a_hole() {
    // geo's VoronoiClip gives 100 here: it skips clipping cells whose
    // box lies inside the region's box, filling the hole.
    let d = domain(&square_with_hole());
    assert!((d.area() - 84.0).abs() < 1e-12);
    let sites = random_sites(&d, 30, 3);
    let v = diagram(&sites, &d);
    assert!(
        (total_area(&v) - 84.0).abs() < 1e-6 * 84.0,
        "{}",
        total_area(&v)
    );
    check_tiling(&d, &v);
    check_no_overlap(&v);
    // Nothing of any cell inside the hole.
    let hole = rect(3.0, 3.0, 7.0, 7.0);
    for cell in v.cells() {
        assert!(cell.to_region().intersection(&hole).area() < 1e-9);
    }
}

#[test]
fn a_cell_around_a_hole_keeps_it_as_a_hole() {
    // One site: its cell is the whole square, the hole a hole in it.
    let d = domain(&square_with_hole());
    let v = diagram(&[Point::new(1.0, 1.0)], &d);
    assert_eq!(v.cells()[0].contours().len(), 2);
    assert!((v.cells()[0].area() - 84.0).abs() < 1e-9);
    assert_eq!(v.cells()[0].piece_count(), 1);
}

#[test]
fn a_concave_region_can_cut_a_cell_in_two() {
    // A U: two arms joined at the bottom. A site in the middle of the
    // gap, above the base, owns the top of both arms.
    let u = polygon_region(&[
        (0.0, 0.0),
        (3.0, 0.0),
        (3.0, 7.0),
        (7.0, 7.0),
        (7.0, 0.0),
        (10.0, 0.0),
        (10.0, 10.0),
        (0.0, 10.0),
    ]);
    let d = domain(&u);
    let sites = [Point::new(5.0, 0.5), Point::new(5.0, 9.0)];
    let v = Diagram::new(&sites, &d, &CellOptions::DEFAULT).unwrap();
    assert_eq!(v.cells()[0].piece_count(), 2);
    check_tiling(&d, &v);
    // Its centroid is in the gap, outside the region: Lloyd moves the
    // site elsewhere, inside.
    let step = lloyd_step(&sites, &d, &CellOptions::DEFAULT).unwrap();
    assert!(d.contains(step.sites[0]));
}

#[test]
fn cells_tile_a_region_with_round_holes_and_many_tiles() {
    let region = rect(0.0, 0.0, 60.0, 40.0)
        .difference(&circle(20.0, 20.0, 8.0))
        .difference(&circle(42.0, 18.0, 6.0));
    let d = domain(&region);
    assert!(d.grid.nx * d.grid.ny > 1, "the test wants several tiles");
    assert!(d.pieces.len() > 1, "the region was not cut into pieces");
    let sites = random_sites(&d, 2000, 4);
    let v = diagram(&sites, &d);
    check_tiling(&d, &v);
}

/// A wavy disc: `n` vertices on a circle of radius `r` modulated by
/// `waves` bumps, with a wavy hole.
fn wavy(n: usize, r: f64, waves: f64) -> Region {
    let ring = |scale: f64, reverse: bool| -> Vec<(f64, f64)> {
        let mut pts: Vec<(f64, f64)> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                let rr = scale * r * (1.0 + 0.08 * (waves * a).sin());
                (100.0 + rr * a.cos(), 100.0 + rr * a.sin())
            })
            .collect();
        if reverse {
            pts.reverse();
        }
        pts
    };
    let mut path = BezPath::new();
    for pts in [ring(1.0, false), ring(0.3, true)] {
        path.move_to(pts[0]);
        for &p in &pts[1..] {
            path.line_to(p);
        }
        path.close_path();
    }
    Region::new(path, FillRule::NonZero).unwrap()
}

#[test]
fn cells_tile_a_detailed_outline() {
    // 6 000 outline edges: a 78×78 grid of tiles, and cells clipped
    // against the pieces near them only.
    let d = domain(&wavy(3000, 90.0, 150.0));
    assert!(d.grid.nx > 50 && d.pieces.len() > 1000);
    let sites = random_sites(&d, 3000, 17);
    let v = diagram(&sites, &d);
    check_tiling(&d, &v);
    // A few huge cells, each spanning hundreds of tiles: clipped against
    // the whole region instead of its pieces.
    let v = diagram(&sites[..5], &d);
    check_tiling(&d, &v);
}

#[test]
fn pieces_add_up_to_the_region() {
    let region = rect(0.0, 0.0, 50.0, 50.0).difference(&circle(25.0, 25.0, 10.0));
    let d = domain(&region);
    let total: f64 = d.pieces.iter().flatten().map(|c| shoelace_arr(c)).sum();
    assert!((total - d.area()).abs() < 1e-6 * d.area());
}

#[test]
fn domain_contains_agrees_with_the_polygons() {
    let d = domain(&square_with_hole());
    let path = {
        let mut p = BezPath::new();
        for c in d.polygons() {
            p.move_to(c[0]);
            for &q in &c[1..] {
                p.line_to(q);
            }
            p.close_path();
        }
        p
    };
    let mut s = Seed(5).stream();
    for _ in 0..2000 {
        let p = Point::new(s.range(-2.0, 12.0), s.range(-2.0, 12.0));
        assert_eq!(d.contains(p), path.winding(p) != 0, "{p:?}");
    }
}

#[test]
fn one_cell_per_distinct_site() {
    let d = domain(&rect(0.0, 0.0, 10.0, 10.0));
    let mut sites = random_sites(&d, 20, 6);
    sites.push(sites[3]); // exact duplicate
    sites.push(sites[7] + Vec2::new(1e-8, -1e-8)); // near-duplicate
    sites.push(sites[7] + Vec2::new(1e-3, 0.0)); // distinct, close
    let v = diagram(&sites, &d);
    assert_eq!(v.status()[20], SiteStatus::MergedInto(3));
    assert_eq!(v.status()[21], SiteStatus::MergedInto(7));
    assert_eq!(v.status()[22], SiteStatus::Own);
    assert!(v.cells()[20].is_empty() && v.cells()[21].is_empty());
    let non_empty = v.cells().iter().filter(|c| !c.is_empty()).count();
    assert_eq!(non_empty, 21);
    check_tiling(&d, &v);
}

#[test]
fn outside_sites_kept_dropped_or_rejected() {
    let d = domain(&l_shape());
    let sites = [
        Point::new(2.0, 2.0),
        Point::new(8.0, 4.0), // in the bay, outside
        Point::new(8.0, 8.0),
        Point::new(30.0, 30.0), // far outside
    ];
    let keep = diagram(&sites, &d);
    check_tiling(&d, &keep);
    assert!(!keep.cells()[1].is_empty(), "its cell reaches into the L");
    assert!(keep.cells()[3].is_empty());
    let drop_opts = CellOptions::DEFAULT.with_outside(OutsideSites::Drop);
    let dropped = Diagram::new(&sites, &d, &drop_opts).unwrap();
    assert_eq!(dropped.status()[1], SiteStatus::Dropped);
    assert_eq!(dropped.status()[3], SiteStatus::Dropped);
    assert!(dropped.cells()[1].is_empty());
    check_tiling(&d, &dropped);
    let reject = CellOptions::DEFAULT.with_outside(OutsideSites::Reject);
    let err = Diagram::new(&sites, &d, &reject).unwrap_err();
    assert!(
        matches!(&err, Error::Invalid { field, .. } if field == "sites[1]"),
        "{err}"
    );
}

#[test]
fn single_and_collinear_sites() {
    let d = domain(&l_shape());
    let one = diagram(&[Point::new(1.0, 9.0)], &d);
    assert!((one.cells()[0].area() - 75.0).abs() < 1e-9);
    let line: Vec<Point> = (0..10).map(|i| Point::new(0.5 + i as f64, 9.0)).collect();
    let v = diagram(&line, &d);
    check_tiling(&d, &v);
    check_no_overlap(&v);
}

#[test]
fn deterministic() {
    let region = rect(0.0, 0.0, 30.0, 30.0).difference(&circle(15.0, 15.0, 5.0));
    let d = domain(&region);
    let sites = random_sites(&d, 500, 7);
    assert_eq!(diagram(&sites, &d), diagram(&sites, &domain(&region)));
    let opts = CellOptions::DEFAULT;
    assert_eq!(
        lloyd_step(&sites, &d, &opts).unwrap(),
        lloyd_step(&sites, &d, &opts).unwrap()
    );
    assert_eq!(
        constrained_delaunay(&sites, &d, &opts).unwrap(),
        constrained_delaunay(&sites, &d, &opts).unwrap()
    );
    assert_eq!(
        delaunay_edges(&sites, &d, &opts).unwrap(),
        delaunay_edges(&sites, &d, &opts).unwrap()
    );
}

/// The triangles of a set of edges: triples of sites joined pairwise
/// with no site strictly inside (faces of a planar triangulation).
fn faces(sites: &[Point], edges: &[[usize; 2]]) -> Vec<[usize; 3]> {
    let mut adjacent = vec![std::collections::BTreeSet::new(); sites.len()];
    for &[i, j] in edges {
        adjacent[i].insert(j);
        adjacent[j].insert(i);
    }
    let mut out = Vec::new();
    for &[i, j] in edges {
        for &k in adjacent[i].intersection(&adjacent[j]) {
            if k <= j {
                continue;
            }
            let (a, b, c) = (sites[i], sites[j], sites[k]);
            let s = cross(a, b, c).signum();
            let strictly_inside = |p: Point| {
                cross(a, b, p) * s > 0.0 && cross(b, c, p) * s > 0.0 && cross(c, a, p) * s > 0.0
            };
            if !sites.iter().any(|&p| strictly_inside(p)) {
                out.push([i, j, k]);
            }
        }
    }
    out
}

fn empty_circumcircle(sites: &[Point], [a, b, c]: [Point; 3]) -> bool {
    let centre = circumcentre(a, b, c);
    let r = centre.distance(a);
    sites
        .iter()
        .all(|&p| p.distance(centre) >= r * (1.0 - 1e-9))
}

/// Hull size by Andrew's monotone chain (strict turns only).
fn hull_size(points: &[Point]) -> usize {
    let mut p = points.to_vec();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    let mut hull: Vec<Point> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Point>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull.len()
}

#[test]
fn delaunay_edges_are_delaunay_in_a_square() {
    let d = domain(&rect(0.0, 0.0, 100.0, 100.0));
    let sites = random_sites(&d, 200, 8);
    let edges = delaunay_edges(&sites, &d, &CellOptions::DEFAULT).unwrap();
    let tris = faces(&sites, &edges);
    // A full triangulation of n points with h on the hull has 2n − 2 − h
    // triangles and 3n − 3 − h edges: nothing is missing.
    let h = hull_size(&sites);
    assert_eq!(tris.len(), 2 * sites.len() - 2 - h);
    assert_eq!(edges.len(), 3 * sites.len() - 3 - h);
    for t in tris {
        assert!(
            empty_circumcircle(&sites, t.map(|i| sites[i])),
            "a site inside the circumcircle of {t:?}"
        );
    }
    // The constrained one, in a convex region: triangles between sites
    // are Delaunay too, and all triangles cover the square.
    let cdt = constrained_delaunay(&sites, &d, &CellOptions::DEFAULT).unwrap();
    let area: f64 = cdt.triangles.iter().map(|t| shoelace(t).abs()).sum();
    assert!((area - 10_000.0).abs() < 1e-6);
    for t in faces(&sites, &cdt.between_sites) {
        assert!(empty_circumcircle(&sites, t.map(|i| sites[i])));
    }
}

/// Brute-force: the segment stays in the region (middle inside, no
/// proper crossing with any edge of the flattened outline).
fn segment_in_region(region: &Region, d: &Domain, a: Point, b: Point) -> bool {
    region.contains(a.midpoint(b))
        && !d
            .polygons()
            .iter()
            .flat_map(|c| (0..c.len()).map(move |k| (c[k], c[(k + 1) % c.len()])))
            .any(|(p, q)| segments_cross_properly(a, b, p, q))
}

#[test]
fn delaunay_edges_stay_inside_an_l() {
    let region = l_shape();
    let d = domain(&region);
    let sites = random_sites(&d, 150, 9);
    let edges = delaunay_edges(&sites, &d, &CellOptions::DEFAULT).unwrap();
    assert!(edges.len() > 300);
    for &[i, j] in &edges {
        assert!(segment_in_region(&region, &d, sites[i], sites[j]));
    }
    // And the edges across the bay were there to be removed.
    let all = delaunay_edges(
        &sites,
        &domain(&rect(0.0, 0.0, 10.0, 10.0)),
        &CellOptions::DEFAULT,
    )
    .unwrap();
    assert!(all.len() > edges.len());
    let cdt = constrained_delaunay(&sites, &d, &CellOptions::DEFAULT).unwrap();
    for &[i, j] in &cdt.between_sites {
        assert!(segment_in_region(&region, &d, sites[i], sites[j]));
    }
    for l in cdt.to_outline.iter().chain(&cdt.outline) {
        assert!(!d
            .polygons()
            .iter()
            .flat_map(|c| (0..c.len()).map(move |k| (c[k], c[(k + 1) % c.len()])))
            .any(|(p, q)| segments_cross_properly(l.p0, l.p1, p, q)));
    }
    let area: f64 = cdt.triangles.iter().map(|t| shoelace(t).abs()).sum();
    assert!((area - 75.0).abs() < 1e-9, "{area}");
    assert_eq!(cdt.outline.len(), 6);
}

#[test]
fn constrained_delaunay_leaves_holes_empty() {
    let region = square_with_hole();
    let d = domain(&region);
    let sites = random_sites(&d, 60, 10);
    let cdt = constrained_delaunay(&sites, &d, &CellOptions::DEFAULT).unwrap();
    let area: f64 = cdt.triangles.iter().map(|t| shoelace(t).abs()).sum();
    assert!((area - 84.0).abs() < 1e-9, "{area}");
    assert_eq!(cdt.outline.len(), 8);
    for &[i, j] in &delaunay_edges(&sites, &d, &CellOptions::DEFAULT).unwrap() {
        assert!(segment_in_region(&region, &d, sites[i], sites[j]));
    }
}

#[test]
fn lloyd_energy_falls() {
    let d = domain(&rect(0.0, 0.0, 100.0, 100.0));
    let mut sites = random_sites(&d, 100, 11);
    let opts = CellOptions::DEFAULT;
    let mut energies = Vec::new();
    for _ in 0..10 {
        let step = lloyd_step(&sites, &d, &opts).unwrap();
        energies.push(step.energy);
        sites = step.sites;
    }
    assert!(energies[1] < energies[0], "{energies:?}");
    for w in energies.windows(2) {
        assert!(w[1] <= w[0] * (1.0 + 1e-12), "{energies:?}");
    }
    // Sites stay inside.
    assert!(sites.iter().all(|&p| d.contains(p)));
}

#[test]
fn lloyd_energy_falls_around_holes() {
    let region = rect(0.0, 0.0, 40.0, 40.0)
        .difference(&circle(15.0, 15.0, 6.0))
        .difference(&rect(25.0, 5.0, 35.0, 30.0));
    let d = domain(&region);
    let mut sites = random_sites(&d, 150, 12);
    let mut energies = Vec::new();
    for _ in 0..10 {
        let step = lloyd_step(&sites, &d, &CellOptions::DEFAULT).unwrap();
        energies.push(step.energy);
        assert!(step.sites.iter().all(|&p| d.contains(p)));
        sites = step.sites;
    }
    for w in energies.windows(2) {
        assert!(w[1] <= w[0] * (1.0 + 1e-12), "{energies:?}");
    }
}

#[test]
fn unit_density_is_plain_lloyd() {
    let d = domain(&l_shape());
    let sites = random_sites(&d, 60, 13);
    let opts = CellOptions::DEFAULT;
    let plain = lloyd_step(&sites, &d, &opts).unwrap();
    let weighted = weighted_lloyd_step(&sites, &d, &opts, &|_| 1.0).unwrap();
    for (a, b) in plain.sites.iter().zip(&weighted.sites) {
        assert!(a.distance(*b) < 1e-9, "{a:?} {b:?}");
    }
    assert!((plain.energy - weighted.energy).abs() < 1e-9 * plain.energy);
    // A density that is linear is integrated exactly too: compare with
    // a finer subdivision.
    let rho = |p: Point| 1.0 + p.x + 0.5 * p.y;
    let coarse = weighted_lloyd_step(&sites, &d, &opts, &rho).unwrap();
    let fine = weighted_lloyd_step(&sites, &d, &opts.with_density_subdivisions(6), &rho).unwrap();
    for (a, b) in coarse.sites.iter().zip(&fine.sites) {
        assert!(a.distance(*b) < 1e-9);
    }
}

#[test]
fn weighted_lloyd_moves_towards_density() {
    let d = domain(&rect(0.0, 0.0, 100.0, 100.0));
    let sites = random_sites(&d, 100, 14);
    let step =
        weighted_lloyd_step(&sites, &d, &CellOptions::DEFAULT, &|p: Point| p.x * p.x).unwrap();
    let mean_dx: f64 = sites
        .iter()
        .zip(&step.sites)
        .map(|(a, b)| b.x - a.x)
        .sum::<f64>()
        / sites.len() as f64;
    assert!(mean_dx > 0.1, "{mean_dx}");
    // Energies computed with density still fall over steps.
    let next = weighted_lloyd_step(&step.sites, &d, &CellOptions::DEFAULT, &|p: Point| {
        p.x * p.x
    })
    .unwrap();
    assert!(next.energy < step.energy);
    // Where the density is zero (or NaN) nothing pulls a site: it
    // stays, rather than drifting into the blank part.
    let nan = weighted_lloyd_step(&sites, &d, &CellOptions::DEFAULT, &|_| f64::NAN).unwrap();
    assert_eq!(nan.sites, sites);
    let left = |p: Point| if p.x < 50.0 { 1.0 } else { 0.0 };
    let half = weighted_lloyd_step(&sites, &d, &CellOptions::DEFAULT, &left).unwrap();
    let plain = lloyd_step(&sites, &d, &CellOptions::DEFAULT).unwrap();
    let diagram = Diagram::new(&sites, &d, &CellOptions::DEFAULT).unwrap();
    for (i, cell) in diagram.cells().iter().enumerate() {
        let b = cell.to_path().bounding_box();
        if b.x0 > 50.0 {
            assert_eq!(half.sites[i], sites[i], "a site on the blank side moved");
        } else if b.x1 < 50.0 {
            // Uniform density there: the area centroid, up to the
            // quadrature's rounding.
            assert!(half.sites[i].distance(plain.sites[i]) < 1e-9);
        }
    }
}

#[test]
fn bad_input_is_an_error() {
    let d = domain(&rect(0.0, 0.0, 10.0, 10.0));
    let opts = CellOptions::DEFAULT;
    let invalid = |r: Result<Diagram>| matches!(r, Err(Error::Invalid { .. }));
    assert!(invalid(Diagram::new(&[], &d, &opts)));
    assert!(invalid(Diagram::new(
        &[Point::new(f64::NAN, 1.0)],
        &d,
        &opts
    )));
    assert!(invalid(Diagram::new(
        &[Point::new(1.0, 1.0), Point::new(1.0, f64::INFINITY)],
        &d,
        &opts
    )));
    assert!(invalid(Diagram::new(&[Point::new(1e9, 1.0)], &d, &opts)));
    let err = Diagram::new(
        &[Point::new(1.0, 1.0), Point::new(2.0, 2.0)],
        &d,
        &opts.with_max_sites(1),
    )
    .unwrap_err();
    assert!(matches!(err, Error::Budget { limit: 1, .. }), "{err}");
    assert!(matches!(
        lloyd_step(&[], &d, &opts),
        Err(Error::Invalid { .. })
    ));
    assert!(matches!(
        delaunay_edges(&[Point::new(f64::NAN, 0.0)], &d, &opts),
        Err(Error::Invalid { .. })
    ));
    assert!(matches!(
        Domain::new(&Region::empty(), TOLERANCE),
        Err(Error::Invalid { .. })
    ));
}

/// Finite but awkward coordinates: on the outline (0, 3, 7, 10), at the
/// range limit, tiny, and clusters of near-duplicates.
fn wild() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -20.0..20.0f64,
        1 => Just(0.0),
        1 => Just(3.0),
        1 => Just(7.0),
        1 => Just(10.0),
        1 => Just(1e-300),
        1 => Just(-1e5),
        1 => Just(1e5),
        2 => (-1.0..1.0f64).prop_map(|v| 5.0 + v * 1e-6),
        1 => (-1.0..1.0f64).prop_map(|v| 1.0 + v * 1e-12),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    #[test]
    fn wild_sites_never_panic(
        points in prop::collection::vec((wild(), wild()), 0..40),
        poison in prop::option::weighted(
            0.2,
            (0..40usize, prop_oneof![
                Just(f64::NAN),
                Just(f64::INFINITY),
                Just(-f64::INFINITY),
                Just(1e9),
            ]),
        ),
        outside in prop_oneof![
            Just(OutsideSites::Keep),
            Just(OutsideSites::Drop),
            Just(OutsideSites::Reject)
        ],
    ) {
        let d = domain(&square_with_hole());
        let mut sites: Vec<Point> = points.iter().map(|&(x, y)| Point::new(x, y)).collect();
        if let Some((i, v)) = poison {
            if let Some(p) = sites.get_mut(i) {
                p.y = v;
            }
        }
        let opts = CellOptions::DEFAULT.with_outside(outside);
        match Diagram::new(&sites, &d, &opts) {
            Ok(v) => {
                // With every site dropped, nothing owns a cell.
                if v.status().contains(&SiteStatus::Own) {
                    let total = total_area(&v);
                    prop_assert!((total - 84.0).abs() < 1e-6 * 84.0, "{}", total);
                }
                let step = lloyd_step(&sites, &d, &opts).unwrap();
                prop_assert!(step.energy.is_finite() && step.mean_movement.is_finite());
                prop_assert!(step.sites.iter().all(|p| p.is_finite()));
                for [i, j] in delaunay_edges(&sites, &d, &opts).unwrap() {
                    prop_assert!(d.contains(sites[i].midpoint(sites[j])));
                }
                let cdt = constrained_delaunay(&sites, &d, &opts).unwrap();
                let area: f64 = cdt.triangles.iter().map(|t| shoelace(t).abs()).sum();
                prop_assert!((area - 84.0).abs() < 1e-6, "{}", area);
            }
            Err(e) => {
                prop_assert!(matches!(e, Error::Invalid { .. }), "unexpected error: {}", e);
                prop_assert!(lloyd_step(&sites, &d, &opts).is_err());
                prop_assert!(delaunay_edges(&sites, &d, &opts).is_err());
                prop_assert!(constrained_delaunay(&sites, &d, &opts).is_err());
            }
        }
    }
}

/// Timing on the measurement in the module's brief; asserts only the
/// tiling. `cargo test --release --lib geom::voronoi -- --ignored
/// --nocapture`.
#[test]
#[ignore]
#[allow(clippy::print_stderr)]
fn timing_large() {
    use std::time::Instant;
    let region = rect(0.0, 0.0, 200.0, 200.0)
        .difference(&circle(60.0, 70.0, 30.0))
        .difference(&circle(140.0, 130.0, 40.0));
    let t = Instant::now();
    let d = domain(&region);
    eprintln!(
        "domain: {:?} ({} edges, {}×{} tiles, {} pieces)",
        t.elapsed(),
        d.edges.len(),
        d.grid.nx,
        d.grid.ny,
        d.pieces.len()
    );
    let sites = random_sites(&d, 100_000, 15);
    let t = Instant::now();
    let v = diagram(&sites, &d);
    eprintln!("100 000 cells: {:?}", t.elapsed());
    let total = total_area(&v);
    assert!((total - d.area()).abs() < 1e-6 * d.area());
    let t = Instant::now();
    let edges = delaunay_edges(&sites, &d, &CellOptions::DEFAULT).unwrap();
    eprintln!(
        "100 000 sites, Delaunay edges: {:?} ({})",
        t.elapsed(),
        edges.len()
    );
    let t = Instant::now();
    let cdt = constrained_delaunay(&sites, &d, &CellOptions::DEFAULT).unwrap();
    eprintln!(
        "100 000 sites, constrained: {:?} ({} triangles)",
        t.elapsed(),
        cdt.triangles.len()
    );

    let t = Instant::now();
    let detailed = domain(&wavy(20_000, 90.0, 400.0));
    eprintln!(
        "domain of {} edges: {:?} ({}×{} tiles, {} pieces)",
        detailed.edges.len(),
        t.elapsed(),
        detailed.grid.nx,
        detailed.grid.ny,
        detailed.pieces.len()
    );
    let many = random_sites(&detailed, 100_000, 18);
    let t = Instant::now();
    let v = diagram(&many, &detailed);
    eprintln!(
        "100 000 cells in an outline of {} edges: {:?}",
        detailed.edges.len(),
        t.elapsed()
    );
    assert!((total_area(&v) - detailed.area()).abs() < 1e-6 * detailed.area());

    let small = random_sites(&d, 10_000, 16);
    let t = Instant::now();
    let step = lloyd_step(&small, &d, &CellOptions::DEFAULT).unwrap();
    eprintln!("Lloyd step, 10 000 sites: {:?}", t.elapsed());
    let t = Instant::now();
    let w = weighted_lloyd_step(&small, &d, &CellOptions::DEFAULT, &|p: Point| {
        1.0 + (p.x * 0.1).sin() * (p.y * 0.1).cos()
    })
    .unwrap();
    eprintln!("weighted Lloyd step, 10 000 sites: {:?}", t.elapsed());
    let t = Instant::now();
    let mut s = small.clone();
    for _ in 0..10 {
        s = lloyd_step(&s, &d, &CellOptions::DEFAULT).unwrap().sites;
    }
    eprintln!("10 Lloyd steps, 10 000 sites: {:?}", t.elapsed());
    assert!(step.energy > 0.0 && w.energy > 0.0);
}

// ---------------------------------------------------------------------------
// Relaxation to convergence.

#[test]
fn lloyd_relaxation_stops_once_settled_and_reports_every_step() {
    let d = domain(&rect(0.0, 0.0, 100.0, 100.0));
    let sites = random_sites(&d, 200, 3);
    let how = Relaxation::lloyd(500).with_settled(0.01);
    let mut heard = 0;
    let r = relax(sites, &d, &CellOptions::DEFAULT, None, &how, &mut |_| {
        heard += 1
    })
    .unwrap();
    assert!(r.converged);
    assert_eq!(heard, r.steps.len());
    assert!(
        r.steps.len() > 3 && r.steps.len() < 500,
        "{}",
        r.steps.len()
    );
    let last = r.steps.last().unwrap();
    assert!(last.mean_movement < 0.01);
    // Every step but the last moved more than the threshold.
    assert!(r.steps[..r.steps.len() - 1]
        .iter()
        .all(|s| s.mean_movement >= 0.01));
    for w in r.steps.windows(2) {
        assert!(w[1].energy <= w[0].energy * (1.0 + 1e-12));
    }
    assert!(r.steps.iter().all(|s| s.sites == 200));
    // Without a threshold every step runs.
    let sites = random_sites(&d, 200, 3);
    let r = relax(
        sites,
        &d,
        &CellOptions::DEFAULT,
        None,
        &Relaxation::lloyd(7),
        &mut |_| {},
    )
    .unwrap();
    assert_eq!(r.steps.len(), 7);
    assert!(!r.converged);
}

/// Sites of LBG relaxation from one site in the middle of a square.
fn lbg_from_one(rho: &dyn Fn(Point) -> f64, spacing: f64) -> Result<Relaxed> {
    let d = domain(&rect(0.0, 0.0, 100.0, 100.0));
    let how = Relaxation::lbg(200, Lbg::new(Lbg::mass_for_spacing(spacing)));
    relax(
        vec![Point::new(50.0, 50.0)],
        &d,
        &CellOptions::DEFAULT,
        Some(rho),
        &how,
        &mut |_| {},
    )
}

#[test]
fn lbg_grows_the_count_the_density_asks_for_from_a_single_site() {
    // Density 1: one site per (√3/2)·s² — 100² / (0.866·25) ≈ 462 at 5 mm.
    // Every cell ends within the band the hysteresis allows, so the count
    // is within it too (from one site the count doubles while every cell
    // is too big: 512 here).
    let r = lbg_from_one(&|_| 1.0, 5.0).unwrap();
    assert!(r.converged, "{} steps", r.steps.len());
    let mass = Lbg::mass_for_spacing(5.0);
    let h = 0.6 + 0.01 * (r.steps.len() - 1) as f64;
    let d = domain(&rect(0.0, 0.0, 100.0, 100.0));
    let diagram = Diagram::new(&r.sites, &d, &CellOptions::DEFAULT).unwrap();
    for cell in diagram.cells() {
        let m = cell.area() / mass;
        assert!(m > 1.0 - h / 2.0 - 0.05 && m < 1.0 + h / 2.0 + 0.05, "{m}");
    }
    let n = r.sites.len() as f64;
    assert!(
        n > 461.9 / (1.0 + h / 2.0) && n < 461.9 / (1.0 - h / 2.0),
        "{n} sites"
    );
    let last = r.steps.last().unwrap();
    assert_eq!((last.split, last.removed), (0, 0));
    assert!(r.steps[0].split == 1, "the first step splits the one site");
    // Evenly spaced: no two sites much closer than the spacing.
    let mut nearest = f64::INFINITY;
    for (i, a) in r.sites.iter().enumerate() {
        for b in &r.sites[i + 1..] {
            nearest = nearest.min(a.distance(*b));
        }
    }
    assert!(nearest > 0.5 * 5.0, "nearest pair {nearest} mm");
}

#[test]
fn lbg_count_follows_the_density() {
    // ρ = x/100: half the mass of density 1, all of it weighted right.
    let r = lbg_from_one(&|p: Point| p.x / 100.0, 5.0).unwrap();
    let n = r.sites.len() as f64;
    assert!((n / (461.9 / 2.0) - 1.0).abs() < 0.12, "{n} sites");
    let right = r.sites.iter().filter(|p| p.x > 50.0).count() as f64;
    // ∫ρ over the right half is 3/4 of the whole.
    assert!(
        (right / n - 0.75).abs() < 0.06,
        "{right} of {n} on the right"
    );
}

#[test]
fn lbg_refuses_a_density_too_faint_for_one_site() {
    let e = lbg_from_one(&|_| 1e-6, 5.0).unwrap_err();
    assert!(
        matches!(&e, Error::Invalid { field, .. } if field == "mass"),
        "{e}"
    );
    // And one whose sites would pass the cap.
    let d = domain(&rect(0.0, 0.0, 100.0, 100.0));
    let how = Relaxation::lbg(50, Lbg::new(Lbg::mass_for_spacing(1.0)));
    let opts = CellOptions::DEFAULT.with_max_sites(100);
    let e = relax(
        vec![Point::new(50.0, 50.0)],
        &d,
        &opts,
        None,
        &how,
        &mut |_| {},
    )
    .unwrap_err();
    assert!(matches!(e, Error::Budget { limit: 100, .. }), "{e}");
}

#[test]
fn the_main_axis_of_a_long_cell_lies_along_it() {
    let origin = Vec2::new(3.0, 1.0);
    // A 4 × 1 rectangle turned by 30°.
    let t = kurbo::Affine::rotate(30f64.to_radians());
    let c: Vec<Point> = [(0.0, 0.0), (4.0, 0.0), (4.0, 1.0), (0.0, 1.0)]
        .iter()
        .map(|&(x, y)| t * Point::new(x, y))
        .collect();
    let m = relax::Moments::of(&[c], origin);
    let (axis, sd) = m.main_axis();
    let along = Vec2::new(30f64.to_radians().cos(), 30f64.to_radians().sin());
    assert!(axis.dot(along).abs() > 1.0 - 1e-9, "{axis:?}");
    assert!((sd - 4.0 / 12f64.sqrt()).abs() < 1e-9, "{sd}");
    // Weighted moments with ρ = 1 agree with the exact ones.
    let rect = [[
        Point::new(0.0, 0.0),
        Point::new(4.0, 0.0),
        Point::new(4.0, 1.0),
        Point::new(0.0, 1.0),
    ]
    .to_vec()];
    let exact = relax::Moments::of(&rect, origin);
    let sampled = relax::Moments::weighted(&rect, origin, &|_| 1.0, 3);
    for (a, b) in [
        (exact.xx, sampled.xx),
        (exact.xy, sampled.xy),
        (exact.yy, sampled.yy),
    ] {
        assert!((a - b).abs() < 1e-9, "{a} {b}");
    }
}
