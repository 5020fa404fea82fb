//! The region a pattern fills, from its `[region]` table (voronoi,
//! zentangle): the page inside its margins, a circle, a polygon, the
//! closed shapes of an SVG file or the light parts of an image, less the
//! holes. Like every coordinate of
//! a description, they are millimetres from the top left corner inside
//! the margins.

use kurbo::{Circle, Point, Rect, Shape};

use super::Context;
use crate::error::{Error, Result};
use crate::geom::region::{FillRule, Region};
use crate::geom::trace::light_parts;
use crate::spec::{CircleSpec, RegionSpec};

/// Flattening accuracy of circles turned into regions (mm): the region
/// machinery keeps curves, so this only bounds kurbo's arc fitting.
const CIRCLE_ACCURACY: f64 = 1e-6;

/// The region of a pattern; `field` is the table's `region` field path.
///
/// # Errors
/// [`Error::Invalid`] naming the field when the shape encloses no area or
/// the holes leave nothing; an SVG file that was not loaded.
pub(crate) fn region(spec: &RegionSpec, cx: &Context<'_>) -> Result<Region> {
    let field = cx.field("region");
    let outer = if let Some(c) = &spec.circle {
        circle(c, &format!("{field}.circle"))?
    } else if let Some(p) = &spec.polygon {
        polygon(p, &format!("{field}.polygon"))?
    } else if let Some(name) = &spec.svg {
        let paths = cx.library().paths(name)?;
        Region::new(paths.clone(), FillRule::EvenOdd).map_err(|e| match e {
            Error::Invalid { message, .. } => Error::invalid(
                format!("{field}.svg"),
                format!("{name}: its closed shapes are no region: {message}"),
            ),
            other => other,
        })?
    } else {
        // Layers draw in the drawable area's own coordinates (the SVG
        // moves them in by the margins).
        let page = Rect::from_origin_size(Point::ZERO, cx.page().drawable().size());
        match &spec.image {
            Some(name) => {
                let light = light_parts(cx.library().image(name)?, page)?;
                if light.is_empty() {
                    return Err(Error::invalid(
                        format!("{field}.image"),
                        format!("{name}: has no light part (darkness below one half) to fill"),
                    ));
                }
                light
            }
            None => Region::from_rect(page)?,
        }
    };
    if spec.holes.is_empty() {
        return Ok(outer);
    }
    let holes = spec
        .holes
        .iter()
        .enumerate()
        .map(|(i, h)| {
            let hf = format!("{field}.holes[{i}]");
            match (&h.circle, &h.polygon) {
                (Some(c), _) => circle(c, &format!("{hf}.circle")),
                (_, Some(p)) => polygon(p, &format!("{hf}.polygon")),
                (None, None) => Err(Error::invalid(hf, "needs a circle or a polygon")),
            }
        })
        .collect::<Result<Vec<_>>>()?;
    let region = outer.difference_all(&holes);
    if region.is_empty() {
        return Err(Error::invalid(
            format!("{field}.holes"),
            "leave nothing of the region",
        ));
    }
    Ok(region)
}

fn circle(c: &CircleSpec, field: &str) -> Result<Region> {
    let path = Circle::new(Point::new(c.centre[0], c.centre[1]), c.radius).to_path(CIRCLE_ACCURACY);
    Region::new(path, FillRule::NonZero).map_err(|e| at(field, e))
}

fn polygon(points: &[[f64; 2]], field: &str) -> Result<Region> {
    let points: Vec<Point> = points.iter().map(|&[x, y]| Point::new(x, y)).collect();
    Region::polygon(&points).map_err(|e| at(field, e))
}

/// A region's complaint about its shape, put on the description's field.
fn at(field: &str, e: Error) -> Error {
    match e {
        Error::Invalid { message, .. } => Error::invalid(field, message),
        other => other,
    }
}
