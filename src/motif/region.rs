//! The region a pattern fills, from its `[region]` table (voronoi,
//! zentangle): the page inside its margins, a circle, a polygon, the
//! closed shapes of an SVG file, the light parts of an image or the
//! regions an earlier layer drew, less the holes. Like every coordinate
//! of a description, they are millimetres from the top left corner
//! inside the margins.

use kurbo::{Circle, Point, Rect, Shape};

use super::Context;
use crate::error::{Error, Result};
use crate::geom::region::{FillRule, Region};
use crate::geom::trace::light_parts;
use crate::spec::{CircleSpec, RegionSpec};

/// Flattening accuracy of circles turned into regions (mm): the region
/// machinery keeps curves, so this only bounds kurbo's arc fitting.
const CIRCLE_ACCURACY: f64 = 1e-6;

/// The region of a pattern, all its parts in one; `field` is the
/// table's `region` field path.
///
/// # Errors
/// As [`regions`].
pub(crate) fn region(spec: &RegionSpec, cx: &Context<'_>) -> Result<Region> {
    let parts = regions(spec, cx)?;
    Ok(match <[Region; 1]>::try_from(parts) {
        Ok([one]) => one,
        Err(parts) => Region::union_all(&parts),
    })
}

/// The regions of a pattern: one, unless it takes the regions of another
/// layer, which stay apart (the cells of a Voronoi tiling).
///
/// # Errors
/// [`Error::Invalid`] naming the field when the shape encloses no area or
/// the holes leave nothing; a layer that offered no region, or none at a
/// point of `at`; an SVG file that was not loaded.
pub(crate) fn regions(spec: &RegionSpec, cx: &Context<'_>) -> Result<Vec<Region>> {
    let field = cx.field("region");
    let outer = if let Some(name) = &spec.layer {
        of_layer(spec, name, &field, cx)?
    } else {
        vec![outer(spec, &field, cx)?]
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
    let left: Vec<Region> = outer
        .iter()
        .map(|r| r.difference_all(&holes))
        .filter(|r| !r.is_empty())
        .collect();
    if left.is_empty() {
        return Err(Error::invalid(
            format!("{field}.holes"),
            "leave nothing of the region",
        ));
    }
    Ok(left)
}

/// The one shape a region names: a circle, a polygon, an SVG file's
/// shapes, an image's light parts or the page.
fn outer(spec: &RegionSpec, field: &str, cx: &Context<'_>) -> Result<Region> {
    if let Some(c) = &spec.circle {
        return circle(c, &format!("{field}.circle"));
    }
    if let Some(p) = &spec.polygon {
        return polygon(p, &format!("{field}.polygon"));
    }
    if let Some(name) = &spec.svg {
        let paths = cx.library().paths(name)?;
        return Region::new(paths.clone(), FillRule::EvenOdd).map_err(|e| match e {
            Error::Invalid { message, .. } => Error::invalid(
                format!("{field}.svg"),
                format!("{name}: its closed shapes are no region: {message}"),
            ),
            other => other,
        });
    }
    // Layers draw in the drawable area's own coordinates (the SVG moves
    // them in by the margins).
    let page = Rect::from_origin_size(Point::ZERO, cx.page().drawable().size());
    let Some(name) = &spec.image else {
        return Region::from_rect(page);
    };
    let light = light_parts(cx.library().image(name)?, page)?;
    if light.is_empty() {
        return Err(Error::invalid(
            format!("{field}.image"),
            format!("{name}: has no light part (darkness below one half) to fill"),
        ));
    }
    Ok(light)
}

/// The regions the layer `name` offered, those holding a point of
/// `spec.at` when it lists any.
fn of_layer(spec: &RegionSpec, name: &str, field: &str, cx: &Context<'_>) -> Result<Vec<Region>> {
    let offered = cx.offered(name);
    if offered.is_empty() {
        return Err(Error::invalid(
            format!("{field}.layer"),
            format!("layer '{name}' drew no region to fill"),
        ));
    }
    if spec.at.is_empty() {
        return Ok(offered.to_vec());
    }
    let mut picked = vec![false; offered.len()];
    for (i, &[x, y]) in spec.at.iter().enumerate() {
        let p = Point::new(x, y);
        let k = offered.iter().position(|r| r.contains(p)).ok_or_else(|| {
            Error::invalid(
                format!("{field}.at[{i}]"),
                format!("({x}, {y}) lies in none of the regions of layer '{name}'"),
            )
        })?;
        picked[k] = true;
    }
    Ok(offered
        .iter()
        .zip(picked)
        .filter(|(_, p)| *p)
        .map(|(r, _)| r.clone())
        .collect())
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

#[cfg(test)]
mod tests {
    //! Regions of another layer: what a later table fills is the cells
    //! (or mask) an earlier one drew, each apart, and only those.

    use std::collections::BTreeMap;

    use kurbo::{Affine, PathEl, Point, Shape};

    use crate::project::build_scene;
    use crate::scene::{Layer, Scene};
    use crate::spec::{Format, SceneSpec};

    /// A coarse Voronoi tiling with its sites drawn, then `table` on a
    /// second layer (pen 0.3 mm).
    fn text(table: &str) -> String {
        format!(
            "version = 1\nseed = 3\npage = {{ size = \"A5\", margin = 10 }}\n\
             [[layers]]\nname = \"cells\"\n\
             [[layers.voronoi]]\nid = \"tiling\"\nrelax = 5\ndraw = [\"cells\", \"sites\"]\n\
             dot = 0.5\nsites = {{ distribution = \"uniform\", count = 6 }}\n\
             [[layers]]\nname = \"fill\"\n{table}"
        )
    }

    fn scene(table: &str) -> Scene {
        let text = text(table);
        let spec = SceneSpec::parse(&text, Format::Toml).unwrap_or_else(|e| panic!("{e}\n{text}"));
        build_scene(&spec).unwrap_or_else(|e| panic!("{e}\n{text}"))
    }

    fn error(table: &str) -> String {
        let text = text(table);
        match SceneSpec::parse(&text, Format::Toml).and_then(|s| build_scene(&s)) {
            Ok(_) => panic!("accepted:\n{text}"),
            Err(e) => e.to_string(),
        }
    }

    /// The tiling's sites: the centres of its dots.
    fn sites(s: &Scene) -> Vec<Point> {
        let mut out = Vec::new();
        s.layers[0]
            .content
            .visit_paths(Affine::IDENTITY, &mut |p, t| {
                if p.id.contains(".site-") {
                    out.push(t * p.path.bounding_box().center());
                }
            });
        out
    }

    /// The points of the second layer's lines, by the group (a zentangle
    /// step, a voronoi kind) that drew them.
    fn points_by_group(layer: &Layer) -> BTreeMap<String, Vec<Point>> {
        let mut out: BTreeMap<String, Vec<Point>> = BTreeMap::new();
        layer.content.visit_paths(Affine::IDENTITY, &mut |p, t| {
            let group = p.id.rsplit_once('.').map_or("", |(g, _)| g).to_string();
            let points = out.entry(group).or_default();
            kurbo::flatten(t * p.path.clone(), 0.05, |el| {
                if let PathEl::MoveTo(q) | PathEl::LineTo(q) = el {
                    points.push(q);
                }
            });
        });
        out
    }

    /// The site whose cell holds every point, within `slack` mm of its
    /// edges (a point is in the cell of its nearest site).
    fn cell_holding(points: &[Point], sites: &[Point], slack: f64) -> Option<usize> {
        (0..sites.len()).find(|&i| {
            points.iter().all(|p| {
                let own = p.distance(sites[i]);
                // Moving across a bisector by d changes the difference of
                // distances by up to 2d.
                sites.iter().all(|s| own <= p.distance(*s) + 2.0 * slack)
            })
        })
    }

    #[test]
    fn each_zentangle_step_draws_inside_one_cell_of_the_earlier_layer() {
        let s = scene("[[layers.zentangle]]\nsteps = 40\nregion = { layer = \"cells\" }\n");
        let sites = sites(&s);
        assert_eq!(sites.len(), 6);
        let groups = points_by_group(&s.layers[1]);
        assert!(groups.len() >= 30, "{} steps drew", groups.len());
        let mut cells = std::collections::BTreeSet::new();
        for (group, points) in &groups {
            let cell = cell_holding(points, &sites, 0.15 + 0.05);
            let cell = cell.unwrap_or_else(|| panic!("{group} crosses a cell edge"));
            cells.insert(cell);
        }
        // Every cell is a region of its own, and each gets tangles.
        assert_eq!(cells.len(), 6, "{cells:?}");
    }

    #[test]
    fn at_picks_the_cells_holding_its_points() {
        let all = scene("[[layers.voronoi]]\nrelax = 0\nregion = { layer = \"cells\" }\n");
        let sites = sites(&all);
        let at = sites[2];
        let table = format!(
            "[[layers.voronoi]]\nsites = {{ distribution = \"uniform\", count = 60 }}\nrelax = 2\n\
             region = {{ layer = \"cells\", at = [[{}, {}]] }}\n",
            at.x, at.y
        );
        let s = scene(&table);
        for (group, points) in points_by_group(&s.layers[1]) {
            // The fine pattern's outline is the cell's, so no slack
            // beyond the flattening.
            assert_eq!(
                cell_holding(&points, &sites, 0.05),
                Some(2),
                "{group} leaves the cell"
            );
        }
    }

    #[test]
    fn a_region_of_a_layer_that_cannot_give_one_is_refused() {
        let e = error("[[layers.zentangle]]\nregion = { layer = \"later\" }\n");
        assert!(
            e.contains("layers[1].zentangle[0].region.layer")
                && e.contains("no layer named 'later' comes before this one")
                && e.contains("earlier layers: cells"),
            "{e}"
        );
        let e = error("[[layers.zentangle]]\nregion = { layer = \"fill\" }\n");
        assert!(e.contains("no layer named 'fill'"), "{e}");
        let e = error("[[layers.zentangle]]\nregion = { at = [[1, 1]] }\n");
        assert!(e.contains("region.at: picks regions of a `layer`"), "{e}");
        let e = error(
            "[[layers.zentangle]]\nregion = { layer = \"cells\", circle = { centre = [1, 1], \
             radius = 3 } }\n",
        );
        assert!(e.contains("give at most one of"), "{e}");
        let e = error("[[layers.zentangle]]\nregion = { layer = \"cells\", at = [[-50, 1]] }\n");
        assert!(
            e.contains("region.at[0]")
                && e.contains("lies in none of the regions of layer 'cells'"),
            "{e}"
        );
        // A layer of trees draws no region to fill.
        let text = "version = 1\n[[layers]]\nname = \"t\"\n[[layers.trees]]\nrule = \"tree1\"\n\
                    centre = [[0, 100], [100, 100]]\n[[layers]]\nname = \"z\"\n\
                    [[layers.zentangle]]\nregion = { layer = \"t\" }\n";
        let e = SceneSpec::parse(text, Format::Toml)
            .unwrap_err()
            .to_string();
        assert!(e.contains("layer 't' draws no regions to fill"), "{e}");
    }
}
