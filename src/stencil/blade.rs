//! Blade limits: what a knife cannot cut cleanly — features narrower than
//! the smallest it can leave, and corners sharper than it can follow.
//!
//! A feature narrower than `w` is what an opening by a disc of diameter
//! `w` (shrink by `w/2`, grow back) takes away ([`crate::geom::offset`]):
//! thin paper between two cut-outs tears, a thin cut-out does not come
//! clean. A corner is sharp when the cut turns through more than
//! `180° − min_angle` within a blade's length: a drag knife swivels round
//! it and tears the tip of the paper.

use kurbo::{PathEl, Point};

use crate::error::Result;
use crate::geom::offset::offset;
use crate::geom::region::Region;
use crate::geom::subpath::subpaths;

/// How far along the cut (mm) each side of a corner is measured: about a
/// drag knife's blade offset.
pub const CORNER_REACH: f64 = 0.25;

/// Places (centres of bounding boxes) where `region` is narrower than
/// `width` mm (less `tolerance`), for parts larger than a tenth of a
/// `width`-wide square and wider on average than four times `tolerance`.
///
/// # Errors
/// When an offset fails (coordinates out of range).
pub fn narrow_places(region: &Region, width: f64, tolerance: f64) -> Result<Vec<Point>> {
    // A feature exactly `width` wide passes: the opening's disc is smaller
    // by the offsets' own error, which would otherwise close it.
    let width = width - 2.0 * tolerance;
    if width <= 0.0 || region.is_empty() {
        return Ok(Vec::new());
    }
    let opened = offset(
        &offset(region, -width / 2.0, tolerance)?,
        width / 2.0,
        tolerance,
    )?;
    let thin = region.difference(&opened);
    // Along the sides of a feature that passes, the two offsets leave
    // slivers as thin as their own error: a part counts when its mean
    // width (2·area / perimeter) is above that.
    Ok(thin
        .components()
        .into_iter()
        .filter(|c| {
            let area = c.area();
            area > 0.1 * width * width && 2.0 * area > 4.0 * tolerance * c.perimeter(tolerance)
        })
        .map(|c| c.bounds().center())
        .collect())
}

/// Corners of the boundary of `region` where the cut turns through more
/// than `180° − min_angle_deg` within [`CORNER_REACH`] on either side.
/// Neighbouring vertices of one corner are reported once.
pub fn sharp_corners(region: &Region, min_angle_deg: f64, tolerance: f64) -> Vec<Point> {
    let limit = min_angle_deg.to_radians().cos();
    let mut out: Vec<Point> = Vec::new();
    for sub in subpaths(region.path()) {
        let mut ring: Vec<Point> = Vec::new();
        kurbo::flatten(sub.elements(), tolerance, |el| {
            if let PathEl::MoveTo(p) | PathEl::LineTo(p) = el {
                ring.push(p);
            }
        });
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
            if sharp && !out.iter().any(|q| q.distance(p) < 2.0 * CORNER_REACH) {
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

    #[test]
    fn a_strip_narrower_than_the_blade_is_found_and_a_wide_one_is_not() {
        let thin = Region::from_rect(Rect::new(0.0, 0.0, 20.0, 0.3)).unwrap();
        let wide = Region::from_rect(Rect::new(0.0, 10.0, 20.0, 12.0)).unwrap();
        let both = thin.union(&wide);
        let places = narrow_places(&both, 0.5, 0.01).unwrap();
        assert_eq!(places.len(), 1);
        assert!((places[0].y - 0.15).abs() < 0.1, "{places:?}");
    }

    #[test]
    fn a_needle_has_a_sharp_corner_and_a_square_has_none() {
        let square = Region::from_rect(Rect::new(0.0, 0.0, 10.0, 10.0)).unwrap();
        assert!(sharp_corners(&square, 30.0, 0.01).is_empty());
        let needle = Region::polygon(&[
            Point::new(0.0, 0.0),
            Point::new(20.0, 1.0),
            Point::new(0.0, 2.0),
        ])
        .unwrap();
        let corners = sharp_corners(&needle, 30.0, 0.01);
        assert_eq!(corners.len(), 1, "{corners:?}");
        assert!(corners[0].distance(Point::new(20.0, 1.0)) < 0.5);
    }
}
