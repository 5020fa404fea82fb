//! The stencil's regions as polygons in the boolean library's own form:
//! shapes, each an outer contour followed by its holes.
//!
//! A stencil is polygons anyway (a cutter flattens every curve), and a
//! kimono design makes thousands of contours, so the stencil works with
//! i_overlay directly: one integer sweep an operation, and the result
//! comes grouped, every hole with the part it belongs to, where a
//! [`Region`] would sweep curves and find the owner of each hole by
//! winding numbers (a full A3 design took seconds for each). Outer
//! contours run anticlockwise (in y-up terms, as [`Region::polygons`]
//! gives them), holes the other way, so that the non-zero rule reads any
//! list of contours as the union of their shapes.

use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::float::single::SingleFloatOverlay;
use i_overlay::mesh::float::outline::offset::OutlineOffset;
use i_overlay::mesh::float::style::{LineJoin, OutlineStyle};
use kurbo::{BezPath, Point, Rect};

use crate::geom::region::{path_from_shapes, Region, SLIVER_WIDTH};
use crate::geom::simplify::rdp;

/// A closed polygon, the first point not repeated.
pub(crate) type Contour = Vec<[f64; 2]>;

/// An outer contour, then its holes.
pub(crate) type Shape = Vec<Contour>;

/// Smallest angular step i_overlay takes for round joins.
pub(crate) const MIN_ARC_STEP: f64 = 0.01 * std::f64::consts::PI;

/// The angular step of round joins and caps of radius `radius` within
/// `tolerance` (sagitta `r·θ²/8`).
pub(crate) fn arc_step(radius: f64, tolerance: f64) -> f64 {
    (8.0 * tolerance / radius.abs()).sqrt().max(MIN_ARC_STEP)
}

/// Every contour of `shapes`, in order.
fn contours(shapes: &[Shape]) -> Vec<Contour> {
    shapes.iter().flatten().cloned().collect()
}

/// `subject` combined with `clip` by `rule`, both read by the non-zero
/// rule (overlapping shapes unite).
pub(crate) fn overlay(subject: &[Shape], clip: &[Shape], rule: OverlayRule) -> Vec<Shape> {
    if subject.is_empty() && matches!(rule, OverlayRule::Intersect | OverlayRule::Difference) {
        return Vec::new();
    }
    contours(subject).overlay(&contours(clip), rule, FillRule::NonZero)
}

/// `shapes` grown by `distance` mm (shrunk when negative) with round
/// joins, within `tolerance`. Contours that certainly vanish are left out
/// first (outer ones no wider than twice the distance when shrinking,
/// holes when growing): offsetting a long thin contour past its own
/// middle is i_overlay's worst case, all its offset edges crossing.
pub(crate) fn offset(shapes: &[Shape], distance: f64, tolerance: f64) -> Vec<Shape> {
    let mut kept: Vec<Contour> = Vec::new();
    for shape in shapes {
        for (k, contour) in shape.iter().enumerate() {
            let b = bounds(contour);
            let vanishes = b.width().min(b.height()) <= 2.0 * distance.abs();
            let outer = k == 0;
            if vanishes && outer == (distance < 0.0) {
                if outer {
                    break;
                }
                continue;
            }
            kept.push(contour.clone());
        }
    }
    if kept.is_empty() || distance == 0.0 {
        return overlay(&[kept], &[], OverlayRule::Union);
    }
    let style =
        OutlineStyle::new(distance).line_join(LineJoin::Round(arc_step(distance, tolerance)));
    kept.outline(&style)
}

/// The shapes with every contour simplified within `tolerance`
/// (Ramer–Douglas–Peucker, from its first point); contours left with
/// fewer than three points dropped (an outer one with its holes).
pub(crate) fn simplified(shapes: &[Shape], tolerance: f64) -> Vec<Shape> {
    let mut keep = Vec::new();
    shapes
        .iter()
        .filter_map(|shape| {
            let mut out: Shape = Vec::with_capacity(shape.len());
            for (k, contour) in shape.iter().enumerate() {
                let mut line: Vec<Point> = contour.iter().map(|p| Point::new(p[0], p[1])).collect();
                line.push(line[0]);
                rdp(&line, tolerance, &mut keep);
                line.pop();
                let kept: Contour = line
                    .iter()
                    .zip(&keep)
                    .filter(|(_, k)| **k)
                    .map(|(p, _)| [p.x, p.y])
                    .collect();
                if kept.len() >= 3 {
                    out.push(kept);
                } else if k == 0 {
                    return None;
                }
            }
            Some(out)
        })
        .collect()
}

/// The bounding box of a contour.
pub(crate) fn bounds(contour: &[[f64; 2]]) -> Rect {
    let first = Point::new(contour[0][0], contour[0][1]);
    contour
        .iter()
        .fold(Rect::from_points(first, first), |b, p| {
            b.union_pt(Point::new(p[0], p[1]))
        })
}

/// The signed area of a contour (positive for outer contours).
pub(crate) fn area(contour: &[[f64; 2]]) -> f64 {
    let n = contour.len();
    0.5 * (0..n)
        .map(|i| {
            let (a, b) = (contour[i], contour[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
}

/// The length of a closed contour.
pub(crate) fn perimeter(contour: &[[f64; 2]]) -> f64 {
    let n = contour.len();
    (0..n)
        .map(|i| {
            let (a, b) = (contour[i], contour[(i + 1) % n]);
            (b[0] - a[0]).hypot(b[1] - a[1])
        })
        .sum()
}

/// The area of a shape, holes taken off.
pub(crate) fn shape_area(shape: &Shape) -> f64 {
    shape
        .iter()
        .map(|c| area(c).abs())
        .enumerate()
        .fold(0.0, |sum, (k, a)| if k == 0 { sum + a } else { sum - a })
}

/// A closed contour as a path.
pub(crate) fn contour_path(contour: &[[f64; 2]]) -> BezPath {
    let mut path = BezPath::new();
    for (k, p) in contour.iter().enumerate() {
        if k == 0 {
            path.move_to((p[0], p[1]));
        } else {
            path.line_to((p[0], p[1]));
        }
    }
    path.close_path();
    path
}

/// The shapes as a region (slivers thinner than [`SLIVER_WIDTH`] dropped).
pub(crate) fn to_region(shapes: &[Shape]) -> Region {
    Region::from_normalised(path_from_shapes(shapes, SLIVER_WIDTH))
}

/// A region's parts as shapes, its boundary flattened within `tolerance`.
#[cfg(test)]
pub(crate) fn from_region(region: &Region, tolerance: f64) -> Vec<Shape> {
    let rings: Vec<Contour> = region
        .polygons(tolerance)
        .into_iter()
        .map(|ring| ring.into_iter().map(|p| [p.x, p.y]).collect())
        .collect();
    overlay(&[rings], &[], OverlayRule::Union)
}

/// A rectangle as a shape.
pub(crate) fn rect(r: Rect) -> Shape {
    vec![vec![[r.x0, r.y0], [r.x1, r.y0], [r.x1, r.y1], [r.x0, r.y1]]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_difference_comes_grouped_with_its_holes() {
        let big = rect(Rect::new(0.0, 0.0, 10.0, 10.0));
        let small = rect(Rect::new(2.0, 2.0, 4.0, 4.0));
        let far = rect(Rect::new(20.0, 0.0, 22.0, 2.0));
        let shapes = overlay(&[big, far], &[small], OverlayRule::Difference);
        assert_eq!(shapes.len(), 2);
        let holed = shapes
            .iter()
            .find(|s| s.len() == 2)
            .expect("a shape with a hole");
        assert!((shape_area(holed) - 96.0).abs() < 1e-6);
        assert!(area(&holed[0]) > 0.0 && area(&holed[1]) < 0.0);
    }

    #[test]
    fn shrinking_past_the_middle_leaves_nothing_and_growing_fills_small_holes() {
        let square = overlay(
            &[rect(Rect::new(0.0, 0.0, 10.0, 10.0))],
            &[rect(Rect::new(4.0, 4.0, 5.0, 5.0))],
            OverlayRule::Difference,
        );
        assert!(offset(&square, -6.0, 0.01).is_empty());
        let grown = offset(&square, 1.0, 0.01);
        assert_eq!(grown.len(), 1);
        assert_eq!(grown[0].len(), 1, "the 1 mm hole is filled");
    }
}
