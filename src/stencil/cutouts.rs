//! Cut-outs: the line art of a drawing as the shapes a knife frees, every
//! stroke as wide as its pen draws it.
//!
//! Strokes are flattened within the tolerance and turned into outlines by
//! i_overlay's stroker (round caps and joins, what a pen leaves), one call
//! per pen width and per kind (open or closed), each call unioning its own
//! outlines in one integer sweep; the few results are unioned and cut to
//! the sheet in one more.
//! Per-stroke regions swept one by one would cost a sweep each; kurbo's
//! stroker keeps curves but its outlines of strokes running opposite ways
//! cancel under the non-zero rule where they overlap.

use std::collections::BTreeMap;

use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::mesh::float::stroke::offset::StrokeOffset;
use i_overlay::mesh::float::style::{LineCap, LineJoin, StrokeStyle};
use kurbo::{PathEl, Point, Rect};

use super::shapes::{self, arc_step, Shape};
use crate::error::{Error, Result};
use crate::geom::region::Region;
use crate::geom::subpath::subpaths;
use crate::scene::{Pen, Scene};

/// The union of every drawn stroke of the plotted layers of `scene`, each
/// as wide as its pen or `min_width` mm, whichever is wider, in page
/// coordinates (origin at the sheet's top-left corner), within
/// `tolerance` mm, cut to the sheet.
///
/// # Errors
/// [`Error::Invalid`] (field `input`) when the drawing has no stroke.
pub fn cutouts(scene: &Scene, min_width: f64, tolerance: f64) -> Result<Region> {
    cutout_shapes(scene, min_width, tolerance).map(|(s, _)| shapes::to_region(&s))
}

/// [`cutouts`] as shapes, and the width of the thinnest stroke cut, mm.
pub(crate) fn cutout_shapes(
    scene: &Scene,
    min_width: f64,
    tolerance: f64,
) -> Result<(Vec<Shape>, f64)> {
    // (width in µm, closed) → polylines; a BTreeMap keeps the order fixed.
    let mut groups: BTreeMap<(u64, bool), Vec<Vec<[f64; 2]>>> = BTreeMap::new();
    let page = scene.page_transform();
    for layer in scene.layers.iter().filter(|l| l.is_plotted()) {
        let width = scene
            .pen(layer.pen)
            .map_or(Pen::FALLBACK_WIDTH, |p| p.width)
            .max(min_width);
        let microns = (width * 1000.0).round() as u64;
        layer.content.visit_paths(page, &mut |p, t| {
            if !p.style.is_drawn() {
                return;
            }
            let path = t * p.path.clone();
            for sub in subpaths(&path) {
                let points = flatten(sub.elements(), tolerance);
                if points.len() < 2 {
                    continue;
                }
                groups
                    .entry((microns, sub.is_closed()))
                    .or_default()
                    .push(points);
            }
        });
    }
    if groups.is_empty() {
        return Err(Error::invalid(
            "input",
            "the drawing has no stroke to cut (a stencil is cut from line art)",
        ));
    }
    // The groups' keys are in order: the first is the thinnest.
    let thinnest = groups
        .keys()
        .next()
        .map_or(0.0, |&(microns, _)| microns as f64 / 1000.0);
    let strokes: Vec<Shape> = groups
        .into_iter()
        .flat_map(|((microns, closed), lines)| {
            let width = microns as f64 / 1000.0;
            let step = arc_step(width / 2.0, tolerance);
            let style = StrokeStyle::new(width)
                .line_join(LineJoin::Round(step))
                .start_cap(LineCap::Round(step))
                .end_cap(LineCap::Round(step));
            lines.stroke(style, closed)
        })
        .collect();
    let sheet = Rect::new(0.0, 0.0, scene.page.width, scene.page.height);
    let cut = shapes::overlay(&strokes, &[shapes::rect(sheet)], OverlayRule::Intersect);
    Ok((cut, thinnest))
}

/// The points of one subpath flattened within `tolerance`, without
/// repeats; a closed subpath without its closing point.
fn flatten(elements: impl IntoIterator<Item = PathEl>, tolerance: f64) -> Vec<[f64; 2]> {
    let mut points: Vec<Point> = Vec::new();
    kurbo::flatten(elements, tolerance, |el| {
        if let PathEl::MoveTo(p) | PathEl::LineTo(p) = el {
            if points.last() != Some(&p) {
                points.push(p);
            }
        }
    });
    if points.len() > 2 && points.first() == points.last() {
        points.pop();
    }
    points.into_iter().map(|p| [p.x, p.y]).collect()
}

#[cfg(test)]
mod tests {
    use kurbo::{BezPath, Circle, Shape};

    use super::*;
    use crate::scene::{Group, Style};
    use crate::units::{Margins, Orientation, Page};

    fn scene(paths: Vec<BezPath>) -> Scene {
        let mut g = Group::new("g");
        for (k, p) in paths.into_iter().enumerate() {
            g.push_path(format!("p{k}"), p, Style::default());
        }
        Scene::one_pen(
            Page::sized(100.0, 100.0, Orientation::Portrait, Margins::uniform(0.0)),
            g,
        )
    }

    #[test]
    fn a_stroke_becomes_a_shape_as_wide_as_its_pen() {
        let mut line = BezPath::new();
        line.move_to((10.0, 10.0));
        line.line_to((60.0, 10.0));
        let cut = cutouts(&scene(vec![line.clone()]), 0.0, 0.01).unwrap();
        // 50 mm × 0.3 mm, plus two half-discs.
        let expected = 50.0 * 0.3 + std::f64::consts::PI * 0.15 * 0.15;
        assert!((cut.area() - expected).abs() < 0.01, "{}", cut.area());
        // Widened to at least 0.5 mm.
        let wide = cutouts(&scene(vec![line]), 0.5, 0.01).unwrap();
        assert!((wide.area() - (25.0 + std::f64::consts::PI * 0.0625)).abs() < 0.02);
    }

    #[test]
    fn crossing_strokes_are_unioned_and_a_ring_keeps_its_hole() {
        let mut a = BezPath::new();
        a.move_to((10.0, 50.0));
        a.line_to((90.0, 50.0));
        let mut b = BezPath::new();
        b.move_to((50.0, 90.0));
        b.line_to((50.0, 10.0));
        let ring = Circle::new((50.0, 50.0), 20.0).to_path(0.01);
        let cut = cutouts(&scene(vec![a, b, ring]), 0.0, 0.01).unwrap();
        assert_eq!(cut.components().len(), 1);
        assert!(!cut.contains(Point::new(40.0, 40.0)), "inside the ring");
        assert!(cut.contains(Point::new(50.0 + 20.0, 50.0)));
    }

    #[test]
    fn a_drawing_without_strokes_is_refused() {
        let e = cutouts(&scene(Vec::new()), 0.0, 0.01).unwrap_err();
        assert!(e.to_string().starts_with("input: "), "{e}");
    }
}
