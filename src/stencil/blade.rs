//! Blade limits: what a knife cannot cut cleanly — features narrower than
//! the smallest it can leave, and corners sharper than it can follow —
//! and the rounding that makes such corners cuttable.
//!
//! A feature narrower than `w` is what an opening by a disc of diameter
//! `w` (shrink by `w/2`, grow back) takes away: thin paper between two
//! cut-outs tears, a thin cut-out does not come clean. A corner is sharp
//! when the cut turns through more than `180° − min_angle` within a
//! blade's length: a drag knife swivels round it and tears the tip of the
//! paper. Where two strokes meet at a narrow angle, the paper between
//! them ends in such a tip; a closing of the cut-outs by a disc (grow,
//! shrink back) rounds it off to the disc's radius, which the knife
//! follows.

use i_overlay::core::overlay_rule::OverlayRule;
use kurbo::Point;

use super::shapes::{self, Shape};

/// How far along the cut (mm) each side of a corner is measured: about a
/// drag knife's blade offset.
pub const CORNER_REACH: f64 = 0.25;

/// Places (centres of bounding boxes) where the shapes are narrower than
/// `width` mm (less `tolerance`), for parts larger than a tenth of a
/// `width`-wide square and wider on average than four times `tolerance`.
///
/// The places are a report, not a cut: they are found on the contours
/// simplified within half the tolerance (fewer vertices to offset).
pub(crate) fn narrow_places(region: &[Shape], width: f64, tolerance: f64) -> Vec<Point> {
    // A feature exactly `width` wide passes: the opening's disc is smaller
    // by the offsets' own error, which would otherwise close it.
    let width = width - 2.0 * tolerance;
    if width <= 0.0 || region.is_empty() {
        return Vec::new();
    }
    let region = &shapes::simplified(region, tolerance / 2.0);
    let opened = shapes::offset(
        &shapes::offset(region, -width / 2.0, tolerance),
        width / 2.0,
        tolerance,
    );
    let thin = shapes::overlay(region, &opened, OverlayRule::Difference);
    // Along the sides of a feature that passes, the two offsets leave
    // slivers as thin as their own error: a part counts when its mean
    // width (2·area / perimeter) is above that.
    thin.iter()
        .filter(|s| {
            let area = shapes::shape_area(s);
            let perimeter: f64 = s.iter().map(|c| shapes::perimeter(c)).sum();
            area > 0.1 * width * width && 2.0 * area > 4.0 * tolerance * perimeter
        })
        .map(|s| shapes::bounds(&s[0]).center())
        .collect()
}

/// The shapes with every concave corner rounded to at least `radius` mm
/// (a closing: grown by it, shrunk back), within `tolerance`. Paper
/// narrower than `2·radius` between two cut-outs goes with it.
pub(crate) fn rounded(region: &[Shape], radius: f64, tolerance: f64) -> Vec<Shape> {
    if radius <= 0.0 || region.is_empty() {
        return region.to_vec();
    }
    shapes::offset(
        &shapes::offset(region, radius, tolerance),
        -radius,
        tolerance,
    )
}

/// Corners of the boundary of the shapes where the cut turns through
/// more than `180° − min_angle_deg` within [`CORNER_REACH`] on either side.
/// Neighbouring vertices of one corner are reported once.
pub(crate) fn sharp_corners(region: &[Shape], min_angle_deg: f64) -> Vec<Point> {
    let limit = min_angle_deg.to_radians().cos();
    let mut out: Vec<Point> = Vec::new();
    for ring in region.iter().flatten() {
        let ring: Vec<Point> = ring.iter().map(|p| Point::new(p[0], p[1])).collect();
        let n = ring.len();
        if n < 3 {
            continue;
        }
        let reach = |i: usize, step: isize| {
            let mut j = i;
            for _ in 0..n {
                j = (j as isize + step).rem_euclid(n as isize) as usize;
                if ring[j].distance(ring[i]) >= CORNER_REACH {
                    break;
                }
            }
            ring[j]
        };
        for (i, &p) in ring.iter().enumerate() {
            let (a, b) = (reach(i, -1) - p, reach(i, 1) - p);
            let (la, lb) = (a.hypot(), b.hypot());
            if la == 0.0 || lb == 0.0 {
                continue;
            }
            // The angle between the two arms: small at a sharp corner.
            let sharp = a.dot(b) / (la * lb) > limit;
            // Corners found so far lie near the end of the list: only
            // the last few can be the same corner.
            let seen = out
                .iter()
                .rev()
                .take(8)
                .any(|q| q.distance(p) < 2.0 * CORNER_REACH);
            if sharp && !seen {
                out.push(p);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use kurbo::Rect;

    use super::*;

    fn union(parts: Vec<Shape>) -> Vec<Shape> {
        shapes::overlay(&parts, &[], OverlayRule::Union)
    }

    #[test]
    fn a_strip_narrower_than_the_blade_is_found_and_a_wide_one_is_not() {
        let both = union(vec![
            shapes::rect(Rect::new(0.0, 0.0, 20.0, 0.3)),
            shapes::rect(Rect::new(0.0, 10.0, 20.0, 12.0)),
        ]);
        let places = narrow_places(&both, 0.5, 0.01);
        assert_eq!(places.len(), 1);
        assert!((places[0].y - 0.15).abs() < 0.1, "{places:?}");
    }

    /// A V of two 1 mm bars meeting at 20° at the origin: the paper
    /// between its arms ends in a sharp tip.
    fn vee() -> Vec<Shape> {
        let bar = |angle: f64| {
            let (u, n) = (
                kurbo::Vec2::from_angle(angle),
                kurbo::Vec2::from_angle(angle + std::f64::consts::FRAC_PI_2) * 0.5,
            );
            let o = Point::new(10.0, 10.0);
            let ring = [o + n, o + u * 30.0 + n, o + u * 30.0 - n, o - n];
            let mut c: Vec<[f64; 2]> = ring.iter().map(|p| [p.x, p.y]).collect();
            if shapes::area(&c) < 0.0 {
                c.reverse();
            }
            vec![c]
        };
        union(vec![bar(0.0), bar(20f64.to_radians())])
    }

    #[test]
    fn a_needle_has_a_sharp_corner_and_a_square_has_none() {
        let square = vec![shapes::rect(Rect::new(0.0, 0.0, 10.0, 10.0))];
        assert!(sharp_corners(&square, 30.0).is_empty());
        let needle = vec![vec![vec![[0.0, 0.0], [20.0, 1.0], [0.0, 2.0]]]];
        let corners = sharp_corners(&needle, 30.0);
        assert_eq!(corners.len(), 1, "{corners:?}");
        assert!(corners[0].distance(Point::new(20.0, 1.0)) < 0.5);
    }

    #[test]
    fn rounding_takes_the_sharp_tip_of_paper_between_two_cuts() {
        let v = vee();
        let before = sharp_corners(&v, 30.0);
        // The paper's tip inside the V, about 2.9 mm out along its middle.
        let tip = Point::new(10.0, 10.0) + kurbo::Vec2::from_angle(10f64.to_radians()) * 2.9;
        assert!(before.iter().any(|c| c.distance(tip) < 0.5), "{before:?}");
        let after = sharp_corners(&rounded(&v, 0.3, 0.01), 30.0);
        assert!(!after.iter().any(|c| c.distance(tip) < 0.5), "{after:?}");
        // The outer corners of the bars stay.
        assert!(after.len() + 1 >= before.len(), "{before:?} → {after:?}");
    }
}
