//! The `lsystem` family (docs/SPEC.md §4): an L-system's 3D skeleton (from the
//! engine in [`crate::family::lsystem::engine`]) seen from its view, placed on the page,
//! and drawn as centre strokes or as outlines as wide as the turtle's
//! width.
//!
//! * **Seen**: orthographically, along the view's direction with its up up
//!   the page (the turtle's frame has y up; the page has y down).
//! * **Placed**: at each root of `at`, `step` mm per unit and turned by
//!   `rotate`; or at `count` points along the line `along`, standing on
//!   its upper side; or, with neither, fitted into `fit` (the page inside its
//!   margins by default), aspect kept, centred. A sketch lies on its
//!   stroke (points, an SVG's first path, or a region line of the
//!   scene's flow), in page millimetres, seen from the front.
//! * **Drawn**: each limb (a pen-down run of the turtle) is one path: the
//!   exact polyline, or with `smooth` a natural spline through its
//!   points; with `style = "outline"` a closed outline whose width follows
//!   the turtle's along it. `{ … }` polygons are closed paths. A placed
//!   drawing is a [solid](Group::solid) group, so in front of other
//!   layers its outlines hide what is behind them.
//! * **Ornaments**: flowers and leaves of the motif library at the limbs'
//!   tips or where the turtle met a symbol (`ornament`), painted after
//!   the limbs, leaves first.
//!
//! Ids: `<group>.plant-<i>` for each placed copy (or `<group>.plant-0`
//! fitted), its paths `…limb-<k>` and `…polygon-<k>`, its ornaments
//! `…flower-<i>` and `…leaf-<i>`.

pub(crate) mod description;
#[cfg(feature = "studio")]
pub(crate) mod gesture;
mod draw;
pub mod engine;
mod growing;
mod ornament;

#[cfg(test)]
mod tests;

use kurbo::{Affine, Point, Rect};

use crate::error::Result;
use crate::family::lsystem::engine::{Prune, PruneScale, Skeleton, Turtle, TurtleOptions};
use crate::geom::{PathWalker, Side, TOLERANCE};
use crate::motif::limb::{strokes_first, THIN};
use crate::motif::{fitted, flow_line, stroke_points, Context, Stroke};
use crate::scene::{Group, Style};
use crate::spec::{LSystemSpec, LimbStyle, Points, SketchSpec};
use draw::{flat, limb_path, polygon_path, Flat, Projection};
pub(crate) use growing::GrowingSketch;
use ornament::{check_budget, ornaments, sites, Kind};

/// The most modules a word may reach while rewriting (ABOP fig. 1.24a at
/// n = 10 has 24.4 million).
const MAX_MODULES: usize = 50_000_000;

/// The most segments the turtle or a sketch may draw.
const MAX_SEGMENTS: usize = 10_000_000;

/// Limbs shorter than this on the page (mm) are not drawn.
const MIN_LIMB: f64 = 0.05;

/// Builds an L-system table into a group with id `group_id`.
pub(super) fn build(spec: &LSystemSpec, group_id: &str, cx: &mut Context<'_>) -> Result<Group> {
    let mut group = Group::new(group_id);
    let (skeleton, projection) = match &spec.sketch {
        Some(sketch) => (grow_sketch(spec, sketch, group_id, cx)?, Projection::PAGE),
        None => (grow(spec, group_id, cx)?, Projection::of(spec.view.axes())),
    };
    let flat = flat(&skeleton, &projection);
    let placements: Vec<Affine> = if spec.sketch.is_some() {
        vec![Affine::IDENTITY]
    } else if let Some(line) = &spec.along {
        along(line, spec.count.unwrap_or(1), spec)
    } else if spec.at.is_empty() {
        let frame = fit_frame(spec, cx);
        vec![fitted(flat.bounds(spec.style == LimbStyle::Outline), frame)]
    } else {
        let turn = Affine::rotate(spec.rotate.to_radians()) * Affine::scale(spec.step);
        spec.at
            .iter()
            .map(|&[x, y]| Affine::translate((x, y)) * turn)
            .collect()
    };
    let paths = flat.limbs.len() + flat.polygons.len();
    cx.take_paths(paths * placements.len(), || {
        format!("the L-system {group_id} ({paths} limbs a copy)")
    })?;
    let ornamented = [
        (&spec.leaves, Kind::Leaf, "leaves"),
        (&spec.flowers, Kind::Flower, "flowers"),
    ];
    let at: Vec<_> = ornamented
        .iter()
        .map(|(o, _, _)| o.as_ref().map(|o| sites(&flat, o)))
        .collect();
    for ((ornament, _, name), at) in ornamented.iter().zip(&at) {
        if let (Some(o), Some(at)) = (ornament, at) {
            let field = cx.field(name);
            check_budget(o, at.len(), placements.len(), &field, cx)?;
        }
    }
    let style = Style::default();
    for (i, place) in placements.iter().enumerate() {
        let plant_id = format!("{group_id}.plant-{i}");
        let mut plant = Group::solid(&plant_id);
        let scale = place.determinant().abs().sqrt();
        let outline = spec.style == LimbStyle::Outline;
        let drawn = drawn_limbs(&flat, spec.smooth, outline, scale, cx.pen_width());
        for (k, path) in strokes_first(drawn) {
            plant.push_path(format!("{plant_id}.limb-{k}"), *place * path, style.clone());
        }
        for (k, polygon) in flat.polygons.iter().enumerate() {
            let path = polygon_path(polygon);
            plant.push_path(
                format!("{plant_id}.polygon-{k}"),
                *place * path,
                style.clone(),
            );
        }
        group.push_group(plant);
        for ((ornament, kind, _), at) in ornamented.iter().zip(&at) {
            if let (Some(o), Some(at)) = (ornament, at) {
                group.push_group(ornaments(o, *kind, at, *place, &plant_id, cx)?);
            }
        }
    }
    Ok(group)
}

/// The placements of `count` drawings evenly spread along `line` by arc
/// length, each turned from heading up the page to standing on the
/// line's upper side, then by `rotate`.
fn along(line: &Points, count: u32, spec: &LSystemSpec) -> Vec<Affine> {
    let walker = PathWalker::new(&flow_line(line), TOLERANCE);
    (0..count)
        .map(|i| {
            let s = walker.length() * (f64::from(i) + 0.5) / f64::from(count);
            let left = Side::Left.normal(walker.tangent_at(s));
            let up = if left.y > 0.0 { -left } else { left };
            // Turning (0, −1) clockwise by θ gives (sin θ, −cos θ).
            let turn = up.x.atan2(-up.y) + spec.rotate.to_radians();
            Affine::translate(walker.point_at(s).to_vec2())
                * Affine::rotate(turn)
                * Affine::scale(spec.step)
        })
        .collect()
}

/// The skeleton of a rewritten system, drawn by the turtle.
fn grow(spec: &LSystemSpec, group_id: &str, cx: &mut Context<'_>) -> Result<Skeleton> {
    let field = cx.item_field();
    let system = spec.system(&field)?;
    let mut rng = cx.stream(group_id);
    let word = system.derive(spec.iterations as usize, &mut rng, MAX_MODULES)?;
    let mut options = TurtleOptions::DEFAULT
        .with_angle(spec.angle)
        .with_width(spec.width)
        .with_width_factor(spec.width_factor)
        .with_max_segments(MAX_SEGMENTS.min(cx.budget().segments_left()))
        .with_marks(&marked(spec));
    if let Some(t) = &spec.tropism {
        let [x, y, z] = t.direction;
        options = options.with_tropism(glam::DVec3::new(x, y, z), t.elasticity);
    }
    // Branches no pen draws are left out as the turtle meets them (a
    // fitted ABOP 1.24a at n = 10 is millions of limbs under `MIN_LIMB`);
    // not with ornaments, which sit on tips and marks of any size.
    if spec.flowers.is_none() && spec.leaves.is_none() {
        let (right, up) = Projection::of(spec.view.axes()).axes();
        let scale = if spec.at.is_empty() && spec.along.is_none() {
            let frame = fit_frame(spec, cx);
            PruneScale::Fit(frame.width(), frame.height())
        } else {
            PruneScale::Scale(spec.step)
        };
        options = options.with_prune(Prune {
            right,
            up,
            min_length: MIN_LIMB,
            scale,
        });
    }
    Turtle::new(options).interpret(&word)
}

/// The frame a drawing placed neither `at` nor `along` is fitted into:
/// `fit`, or the page inside its margins (scene coordinates start at the
/// margins' corner).
fn fit_frame(spec: &LSystemSpec, cx: &Context<'_>) -> Rect {
    spec.fit.map_or_else(
        || Rect::from_origin_size(Point::ZERO, cx.page().drawable().size()),
        |[x0, y0, x1, y1]| Rect::new(x0, y0, x1, y1),
    )
}

/// The symbols whose places the ornaments need.
fn marked(spec: &LSystemSpec) -> String {
    spec.flowers
        .iter()
        .chain(&spec.leaves)
        .filter_map(|o| o.symbol_char())
        .collect()
}

/// Each limb of `flat` that a pen `pen_width` wide can draw at `scale`
/// with its index, as a path (see [`limb_path`]): with `outline`, a limb
/// whose outline would be narrower than [`THIN`] pen widths is drawn as
/// its centre curve.
fn drawn_limbs(
    flat: &Flat,
    smooth: bool,
    outline: bool,
    scale: f64,
    pen_width: f64,
) -> impl Iterator<Item = (usize, kurbo::BezPath)> + '_ {
    flat.limbs
        .iter()
        .enumerate()
        // Old lineages shrink geometrically: what no pen can draw is left
        // out rather than plotted as a dot.
        .filter(move |(_, limb)| limb.length() * scale >= MIN_LIMB)
        .map(move |(k, limb)| {
            let widest = limb.widths.iter().copied().fold(0.0, f64::max);
            let wide = widest * scale >= THIN * pen_width;
            (k, limb_path(limb, smooth, outline && wide))
        })
}

/// The skeleton of a sketch grown along its whole stroke.
fn grow_sketch(
    spec: &LSystemSpec,
    sketch: &SketchSpec,
    group_id: &str,
    cx: &mut Context<'_>,
) -> Result<Skeleton> {
    let stroke = stroke_points(
        &Stroke {
            points: sketch.points.as_ref(),
            smooth: sketch.smooth,
            svg: sketch.svg.as_deref(),
            line: sketch.line,
        },
        &cx.field("sketch"),
        cx,
    )?;
    let mut growing = GrowingSketch::new(spec, &cx.item_field(), cx.budget().segments_left())?
        .with_pen_width(cx.pen_width())
        .within(cx.page().drawable().size());
    growing.extend(&stroke)?;
    if growing.off_page() {
        cx.note(
            group_id,
            format!(
                "the stroke leaves the page (inside its margins) after {:.1} mm: \
                 the sketch stops there",
                growing.steps() as f64 * sketch.module
            ),
        );
    }
    Ok(growing.skeleton())
}
