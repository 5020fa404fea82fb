//! Offsetting regions: grow or shrink a region by a distance with round
//! joins, and the contour lines of a region (successive inward offsets,
//! docs/SPEC.md §2.1 `contour_line`).
//!
//! Method: i_overlay's polygon `outline` on the region's boundary flattened
//! within `tolerance`, with round joins whose arcs are split finely enough
//! to stay within `tolerance` too. i_overlay offsets every contour (outer
//! ones outwards, holes inwards for a positive distance) and unions the
//! results with an exact integer sweep, so curvature tighter than the
//! distance, merging parts, closing holes and vanishing parts all come out
//! right. The result is the Minkowski sum with (or erosion by) a disc:
//! convex corners round off when growing, concave ones when shrinking.
//!
//! Why not keep curves (kurbo's stroker gives a cubic offset band, and
//! region ∪ band / region − band would be the offset): kurbo's band is
//! only right for rendering strokes; where the distance exceeds the radius
//! of curvature its inner side folds over and the non-zero band has holes,
//! so a shrunk region kept spurious islands (see the test
//! `tight_bumps_vanish_when_shrinking`). The price of i_overlay is that
//! offsets are polygons (many short lines), not cubics.

use i_overlay::mesh::float::outline::offset::OutlineOffset;
use i_overlay::mesh::float::style::{LineJoin, OutlineStyle};
use kurbo::{BezPath, Point, Rect};

use super::region::{path_from_shapes, FillRule, Region};
use super::simplify::rdp;
use super::TOLERANCE;
use crate::error::{Error, Result};
use crate::units::MAX_COORD;

/// Smallest angular step i_overlay accepts for round joins (it clamps to
/// `0.01·π`): with it, arcs of radius above `8·tolerance / step²` (about
/// 81 mm at `tolerance` 0.01 mm) deviate a little more than `tolerance`.
const MIN_ARC_STEP: f64 = 0.01 * std::f64::consts::PI;

/// `region` grown by `distance` mm (shrunk when `distance` is negative),
/// with round joins, within `tolerance` mm (non-finite or non-positive
/// means [`TOLERANCE`]). Shrinking may split a region into parts or leave
/// nothing (the empty region); growing may merge parts and fill holes. The
/// result's boundary is made of straight lines.
///
/// # Errors
/// When `distance` is not finite, or growing would reach beyond
/// ±[`MAX_COORD`].
pub fn offset(region: &Region, distance: f64, tolerance: f64) -> Result<Region> {
    if !distance.is_finite() {
        return Err(Error::invalid(
            "offset.distance",
            format!("must be a finite number of mm, got {distance}"),
        ));
    }
    let tolerance = usable(tolerance);
    if region.is_empty() || distance == 0.0 {
        return Ok(region.clone());
    }
    let b = region.bounds();
    if distance > 0.0 {
        let reach = [b.x0, b.y0, b.x1, b.y1]
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()))
            + distance;
        if reach > MAX_COORD {
            return Err(Error::invalid(
                "offset.distance",
                format!("growing by {distance} mm would reach beyond ±{MAX_COORD} mm"),
            ));
        }
    } else if -distance * 2.0 >= b.width().min(b.height()) {
        // Nothing survives: every point is within |d| of the boundary.
        return Ok(Region::empty());
    }
    // Contours that certainly vanish are left out: holes no wider than
    // 2d when growing, outer contours no wider than 2|d| when shrinking.
    // Besides saving work this avoids i_overlay's worst case, a contour
    // with many vertices offset past its own centre, whose offset edges
    // all cross one another (seconds for a few hundred vertices).
    let contours: Vec<Vec<[f64; 2]>> = region
        .polygons(tolerance)
        .into_iter()
        .filter(|poly| {
            let outer = shoelace(poly) > 0.0;
            let r = Rect::from_points(poly[0], poly[0]);
            let b = poly.iter().fold(r, |b, p| b.union_pt(*p));
            let vanishes = b.width().min(b.height()) <= 2.0 * distance.abs();
            !(vanishes && outer == (distance < 0.0))
        })
        .map(|poly| poly.into_iter().map(|p| [p.x, p.y]).collect())
        .collect();
    // Sagitta of an arc step θ on radius r: r·θ²/8 ≤ tolerance.
    let step = (8.0 * tolerance / distance.abs()).sqrt().max(MIN_ARC_STEP);
    let style = OutlineStyle::new(distance).line_join(LineJoin::Round(step));
    let shapes = contours.outline(&style);
    // Parts thinner than `tolerance` on average are mostly the offset's own
    // error and are dropped: the round joins are inscribed polygons, so a
    // shape shrunk by exactly its inradius would otherwise leave a dot.
    Ok(Region::from_normalised(path_from_shapes(
        &shapes, tolerance,
    )))
}

/// `region` closed by a disc of `radius` mm: grown by it, then shrunk by
/// it, within `tolerance` (as [`offset`]). Every concave corner becomes an
/// arc of at least that radius, notches and holes narrower than `2
/// radius` fill, parts closer than that join; convex parts stay where
/// they are. The two offsets' integer grid leaves jogs of a few µm
/// between the arcs' chords; they are smoothed away within `tolerance`,
/// so no corner is left that a pen could show.
///
/// # Errors
/// As [`offset`].
pub fn closing(region: &Region, radius: f64, tolerance: f64) -> Result<Region> {
    let tolerance = usable(tolerance);
    if region.is_empty() || radius == 0.0 {
        return Ok(region.clone());
    }
    let closed = offset(&offset(region, radius, tolerance)?, -radius, tolerance)?;
    let mut path = BezPath::new();
    for ring in closed.polygons(tolerance) {
        // The ring as an open line back to its start, so that its start
        // stays a vertex.
        let mut line = ring.clone();
        line.push(ring[0]);
        let mut keep = Vec::new();
        rdp(&line, tolerance, &mut keep);
        let mut kept = line.iter().zip(&keep).filter(|(_, k)| **k).map(|(p, _)| *p);
        if let Some(first) = kept.next() {
            path.move_to(first);
            kept.for_each(|p| path.line_to(p));
            path.close_path();
        }
    }
    Ok(Region::new(path, FillRule::NonZero).unwrap_or_else(|_| Region::empty()))
}

/// `tolerance`, or [`TOLERANCE`] when it is not a finite positive number.
fn usable(tolerance: f64) -> f64 {
    if tolerance.is_finite() && tolerance > 0.0 {
        tolerance
    } else {
        TOLERANCE
    }
}

/// Twice the signed area of a closed polygon (positive for outer contours
/// of a region).
fn shoelace(poly: &[Point]) -> f64 {
    (0..poly.len())
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            a.x * b.y - b.x * a.y
        })
        .sum()
}

/// The contour lines of `region`: its boundaries shrunk by `spacing`,
/// `2·spacing`, … (each computed from the original region, so errors do
/// not add up), until nothing is left or `count_limit` lines are made. The
/// region's own outline is not included. Each entry is the whole boundary
/// of one offset (all its parts and holes), outermost first.
///
/// # Errors
/// When `spacing` is not a finite positive number.
pub fn contour_lines(region: &Region, spacing: f64, count_limit: usize) -> Result<Vec<BezPath>> {
    if !(spacing.is_finite() && spacing > 0.0) {
        return Err(Error::invalid(
            "contour_lines.spacing",
            format!("must be a finite number of mm > 0, got {spacing}"),
        ));
    }
    let mut lines = Vec::new();
    for k in 1..=count_limit {
        let shrunk = offset(region, -(k as f64) * spacing, TOLERANCE)?;
        if shrunk.is_empty() {
            break;
        }
        lines.push(shrunk.into_path());
    }
    Ok(lines)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::polylabel::pole_of_inaccessibility;
    use crate::geom::region::tests::{arb_region, circle, rect, star};
    use kurbo::Point;
    use proptest::prelude::*;
    use std::f64::consts::PI;

    #[test]
    fn circles_grow_and_shrink_by_the_radius() {
        let c = circle(0.0, 0.0, 10.0);
        let g = offset(&c, 3.0, 1e-4).unwrap();
        let s = offset(&c, -3.0, 1e-4).unwrap();
        assert!((g.area() - PI * 169.0).abs() < 1e-2, "{}", g.area());
        assert!((s.area() - PI * 49.0).abs() < 1e-2, "{}", s.area());
    }

    #[test]
    fn closing_fills_the_notch_between_two_discs_with_an_arc() {
        // Two discs of radius 5 whose centres are 8 apart meet at two
        // notches of 74° each way; closed by a disc of radius 2 they are one
        // smooth shape holding both, its notches filled by arcs.
        let (a, b) = (circle(0.0, 0.0, 5.0), circle(8.0, 0.0, 5.0));
        let union = a.union(&b);
        let closed = closing(&union, 2.0, 0.01).unwrap();
        // Within the tolerance (both outlines are inscribed polygons).
        let near = offset(&closed, 0.02, 0.01).unwrap();
        assert!(union.difference(&near).area() < 1e-3);
        let filled = closed.area() - union.area();
        assert!(filled > 1.0, "{filled}");
        // The largest turn between consecutive edges: a polygon of arcs
        // within 0.01 turns by well under 20° anywhere.
        for ring in closed.polygons(0.01) {
            let n = ring.len();
            for i in 0..n {
                let (p, q, r) = (ring[i], ring[(i + 1) % n], ring[(i + 2) % n]);
                let (u, v) = (q - p, r - q);
                let turn = u.cross(v).atan2(u.dot(v)).abs().to_degrees();
                assert!(turn < 20.0, "{turn}° at {q:?}");
            }
        }
        // At the notch (x = 4) the outline is an arc of radius 2 round
        // where that disc touches both circles: y = sqrt(7² − 4²) at the
        // disc's centre, less 2.
        let top = closed
            .polygons(0.01)
            .iter()
            .flatten()
            .filter(|p| (p.x - 4.0).abs() < 0.2)
            .map(|p| p.y.abs())
            .fold(f64::INFINITY, f64::min);
        assert!((top - (33.0_f64.sqrt() - 2.0)).abs() < 0.05, "{top}");
        // Radius 0 changes nothing.
        assert_eq!(closing(&union, 0.0, 0.01).unwrap(), union);
    }

    #[test]
    fn square_corners_round_outwards_and_stay_sharp_inwards() {
        let sq = rect(0.0, 0.0, 10.0, 10.0);
        let g = offset(&sq, 1.0, 1e-4).unwrap();
        assert!(
            (g.area() - (100.0 + 40.0 + PI)).abs() < 1e-2,
            "{}",
            g.area()
        );
        assert!(!g.contains(Point::new(-0.9, -0.9)));
        assert!(g.contains(Point::new(-0.6, -0.6)));
        let s = offset(&sq, -1.0, 1e-4).unwrap();
        assert!((s.area() - 64.0).abs() < 1e-3, "{}", s.area());
        assert!(s.contains(Point::new(1.05, 1.05)));
    }

    #[test]
    fn holes_shrink_when_growing() {
        let ring = circle(0.0, 0.0, 10.0).difference(&circle(0.0, 0.0, 4.0));
        let g = offset(&ring, 1.0, 1e-4).unwrap();
        assert!((g.area() - PI * (121.0 - 9.0)).abs() < 1e-2);
        let filled = offset(&ring, 5.0, 1e-4).unwrap();
        assert!(
            (filled.area() - PI * 225.0).abs() < 2e-2,
            "{}",
            filled.area()
        );
        assert_eq!(filled.components().len(), 1);
    }

    #[test]
    fn shrinking_splits_and_vanishes() {
        // Two discs joined by a thin bridge fall apart.
        let dumbbell = circle(0.0, 0.0, 5.0)
            .union(&circle(20.0, 0.0, 5.0))
            .union(&rect(0.0, -0.5, 20.0, 0.5));
        assert_eq!(dumbbell.components().len(), 1);
        let s = offset(&dumbbell, -1.0, 1e-3).unwrap();
        assert_eq!(s.components().len(), 2);
        assert!(offset(&dumbbell, -6.0, 1e-3).unwrap().is_empty());
        assert!(offset(&Region::empty(), 1.0, 1e-3).unwrap().is_empty());
    }

    #[test]
    fn tight_bumps_vanish_when_shrinking() {
        let blob = circle(0.0, 0.0, 10.0).union(&circle(11.0, 0.0, 2.0));
        let s = offset(&blob, -3.0, 1e-3).unwrap();
        // The bump's centre is 2 mm from the outside: gone. The concave
        // corners where bump and disc meet let the shrunk disc bulge a
        // little towards the bump (to ~7.2 mm from the centre).
        assert_eq!(s.components().len(), 1);
        assert!(!s.contains(Point::new(11.0, 0.0)));
        assert!(s.contains(Point::new(7.1, 0.0)) && !s.contains(Point::new(7.4, 0.0)));
        assert!(
            s.area() > PI * 49.0 && s.area() < PI * 49.0 + 0.3,
            "{}",
            s.area()
        );
    }

    #[test]
    fn vanishing_contours_are_cheap() {
        // Regression: growing a ring by more than its hole's radius took
        // 90 s in a debug build when the hole was flattened finely.
        let ring = circle(0.0, 0.0, 10.0).difference(&circle(0.0, 0.0, 4.0));
        let t = std::time::Instant::now();
        let g = offset(&ring, 5.0, 3e-4).unwrap();
        // Polygon error: about perimeter × tolerance.
        assert!(
            (g.area() - PI * 225.0).abs() < 30.0 * PI * 3e-4,
            "{}",
            g.area()
        );
        assert!(t.elapsed().as_secs_f64() < 5.0);
    }

    #[test]
    fn bad_distances_are_errors() {
        let c = circle(0.0, 0.0, 1.0);
        assert!(offset(&c, f64::NAN, 0.01).is_err());
        assert!(offset(&c, f64::INFINITY, 0.01).is_err());
        assert!(offset(&c, 2e5, 0.01).is_err());
        assert_eq!(offset(&c, 0.0, 0.01).unwrap(), c);
        assert!(contour_lines(&c, 0.0, 10).is_err());
        assert!(contour_lines(&c, f64::NAN, 10).is_err());
    }

    #[test]
    fn contour_lines_of_a_star() {
        let s = star(Point::new(0.0, 0.0), 20.0, 10.0, 5, 0.0, false);
        let (_, inradius) = pole_of_inaccessibility(&s, 1e-3).unwrap();
        let lines = contour_lines(&s, 1.0, 100).unwrap();
        // One line per mm of depth, until the middle.
        assert!((inradius - 10.0).abs() < 1e-2, "{inradius}");
        assert_eq!(lines.len(), 9);
        assert_eq!(contour_lines(&s, 1.0, 3).unwrap().len(), 3);
        // Each lies inside the previous.
        let mut prev = s.clone();
        for l in &lines {
            let r = Region::new(l.clone(), crate::geom::region::FillRule::NonZero).unwrap();
            assert!(r.difference(&prev).area() < 1e-6);
            prev = r;
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        #[test]
        fn offsets_nest_and_keep_their_distance(r in arb_region(), d in 0.2..4.0f64) {
            let grown = offset(&r, d, 1e-3).unwrap();
            let shrunk = offset(&r, -d, 1e-3).unwrap();
            prop_assert!(r.difference(&grown).area() < 1e-6);
            prop_assert!(shrunk.difference(&r).area() < 1e-6);
            // Boundary points of both lie about d from the region's
            // boundary (flattening and arc steps cost up to 2·tolerance).
            let edges: Vec<kurbo::Line> = r.polygons(1e-4).iter().flat_map(|poly| {
                (0..poly.len()).map(move |i| kurbo::Line::new(poly[i], poly[(i + 1) % poly.len()]))
            }).collect();
            for poly in grown.polygons(1e-3).iter().chain(shrunk.polygons(1e-3).iter()) {
                for p in poly.iter().step_by(5) {
                    let dist = edges.iter()
                        .map(|e| kurbo::ParamCurveNearest::nearest(e, *p, 1e-9).distance_sq)
                        .fold(f64::INFINITY, f64::min)
                        .sqrt();
                    prop_assert!((dist - d).abs() < 5e-3, "{p:?}: {dist} vs {d}");
                }
            }
            prop_assert!(grown.area() >= r.area());
            prop_assert!(shrunk.area() <= r.area());
        }
    }
}
