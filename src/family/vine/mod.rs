//! The `vine` family (docs/SPEC.md §5): a twining vine grown in 3D round its
//! supports ([`crate::family::vine::engine`]), seen through a camera, and drawn as pen
//! lines with the hidden ones removed.
//!
//! * **Lines**: each stem as the two contour lines of its tube (and a
//!   rounded tip), each leaf as the outline and veins of the leaf motif
//!   laid on its blade, with its stalk, each support as its contour lines
//!   and rims (a pole) or its edges (a box).
//! * **Hidden lines**: every line is cut where something lies in front of
//!   it — the stems' tubes, the leaf blades, the supports, as triangles —
//!   by casting rays from the eye ([`crate::family::vine::hidden`]): exact for the
//!   plotter, no raster. So the stem passes behind its pole on one side and
//!   hides it on the other, and leaves hide what is behind them.
//! * **Camera** ([`crate::spec::CameraSpec`]): `"front"`,
//!   `"three-quarter"` and an orbit (`{ turn, tilt }`, degrees round the
//!   vertical from the front and above the horizontal) look at the middle
//!   of the box holding the plant and its supports, orthographic from 2 ×
//!   its diagonal away, or, for an orbit in perspective, from where the
//!   sphere round the box just fills the field of view; front is the
//!   orbit at 0, 0. `"below"` looks up the vine from near the ground; a
//!   placed camera is where its table puts it.
//! * **Fitted**: the camera's picture of all parts is fitted into `fit`
//!   (the page inside its margins by default), aspect kept, centred, and
//!   `draw` picks the parts this table draws; so the same vine in two
//!   layers (same `id`) lines up exactly, each layer one pen.
//!   With `scale` the picture keeps that scale instead, centred across
//!   `fit` and standing on its bottom edge, so a row of panels compares.
//! * **Model**: the parts drawn also go to the 3D export
//!   ([`Context::model`]): stem axes and tubes, leaves as the thesis'
//!   quads, supports as meshes.
//!
//! * **Mask**: a table that draws every part also gives, first in its
//!   group, the area the vine covers as a [mask](Style::mask), never drawn
//!   (`<group>.mask`): with `[plot.occlude]` the vine hides what lies
//!   behind it in a composition. A table drawing only some parts (one pen
//!   of a vine in two layers) gives none, so it hides nothing of its twin.
//!
//! Ids: `<group>.stem-<i>`, `<group>.leaf-<i>`, `<group>.support-<i>`, one
//! path each (its visible pieces as subpaths).

pub(crate) mod description;
#[cfg(feature = "studio")]
mod gesture;
pub(crate) mod camera;
mod ears;
pub mod engine;
mod guide;
pub(crate) mod hidden;
mod model;
mod sight;

#[cfg(test)]
mod tests;

use glam::DVec3;
use kurbo::{Affine, BezPath, Point, Rect};

use crate::error::{Error, Result};
use crate::family::vine::engine::{Plant, Shape, Supports, VineParams};
use crate::geom::region::Region;
use crate::geom::simplify::rdp;
use crate::motif::{fitted, stroke_points, Context, Stroke};
use crate::scene::{Group, Style};
use crate::spec::{Part, VineSpec};
use guide::Guide;
use sight::{camera_for, page_camera, Line, Rod, Sight};

/// Visible pieces are found every this many mm on the page.
const STEP: f64 = 0.25;

/// Cuts between visible and hidden are exact to this many mm on the page.
const CUT: f64 = 0.002;

/// Lines are kept within this many mm of their samples (Ramer–Douglas–
/// Peucker), so the plotter gets few points on straight runs.
const KEEP: f64 = 0.01;

/// Builds a vine table into a group with id `group_id`.
pub(super) fn build(spec: &VineSpec, group_id: &str, cx: &mut Context<'_>) -> Result<Group> {
    let field_of_table = cx.item_field();
    let guide = match &spec.guide {
        Some(g) => {
            let stroke = Stroke {
                points: g.points.as_ref(),
                smooth: g.smooth,
                svg: g.svg.as_deref(),
                line: g.line,
            };
            let field = cx.field("guide");
            let line = stroke_points(&stroke, &field, cx)?;
            guide::checked_length(&line, &field)?;
            Some((Guide::new(&line), g.radius))
        }
        None => None,
    };
    let (supports, roots) = match &guide {
        // Round an upright pole as long as the guide, from beside its foot.
        Some((line, rod)) => (
            Supports::new(vec![Shape::Pole {
                base: DVec3::ZERO,
                top: DVec3::Y * line.length(),
                radius: *rod,
            }]),
            vec![[rod + 2.0 * spec.radius, 0.0, 0.0]],
        ),
        None => {
            let library = cx.library();
            let shapes = spec.shapes(&field_of_table, &|name| library.mesh(name).cloned())?;
            (Supports::new(shapes), spec.roots.clone())
        }
    };
    // Keyed by the vine's own id when it has one, so that the same table
    // in two layers grows the same plant.
    let key = spec
        .id
        .as_deref()
        .map_or_else(|| group_id.to_string(), |id| format!("vine:{id}"));
    let mut rng = cx.stream(&key);
    let mut plants = Vec::with_capacity(roots.len());
    for (i, root) in roots.iter().enumerate() {
        let params = VineParams {
            // Along a guide, up is along the page's line: nothing hangs.
            droop: guide.is_none(),
            ..spec.params(*root)
        };
        let grown = engine::grow(&params, &supports, &mut rng).map_err(|e| match e {
            // The simulation names its own fields; the table's are these.
            Error::Invalid { at, field, message } => Error::Invalid {
                at,
                field: match field.as_str() {
                    "base" => format!("{field_of_table}.roots[{i}]"),
                    _ => format!("{field_of_table}.{field}"),
                },
                message,
            },
            e => e,
        })?;
        plants.push(grown);
        cx.advance(params.internodes as usize);
    }
    let mut plant = merged(plants);
    if let Some((line, _)) = &guide {
        trim(&mut plant, line.length());
    }
    let leaves = plant
        .leaves
        .iter()
        .map(|_| cx.library().draw(&spec.leaf, &mut rng))
        .collect::<Result<Vec<_>>>()?;
    let (sight, place) = match &guide {
        // On the page as it is.
        Some((line, radius)) => {
            let rod = line.rod();
            let rod = Rod {
                axis: &rod,
                radius: *radius,
            };
            let bent = line.bend_plant(&plant);
            let sight = Sight::new(page_camera(), spec.radius, &bent, &[], Some(rod), &leaves);
            (sight, Affine::IDENTITY)
        }
        None => {
            let camera = camera_for(&spec.camera, &plant, &supports);
            let sight = Sight::new(
                camera,
                spec.radius,
                &plant,
                supports.shapes(),
                None,
                &leaves,
            );
            let frame = spec.fit.map_or_else(
                || Rect::from_origin_size(Point::ZERO, cx.page().drawable().size()),
                |[x0, y0, x1, y1]| Rect::new(x0, y0, x1, y1),
            );
            let place = match spec.scale {
                Some(scale) => {
                    // The ground under the first root: where the panels of a
                    // row stand.
                    let root = DVec3::from_array(spec.roots[0]);
                    let bounds = sight.bounds();
                    let ground = sight.project(root).map_or(bounds.y1, |p| p.y);
                    at_scale(bounds, ground, frame, scale, &format!("{group_id}.scale"))?
                }
                None => fitted(sight.bounds(), frame),
            };
            (sight, place)
        }
    };
    let scale = place.determinant().abs().sqrt();
    let drawn: Vec<&Line> = sight
        .lines()
        .iter()
        .filter(|l| spec.draw.contains(&l.part))
        .collect();
    let mut paths: Vec<(String, BezPath)> = Vec::new();
    for line in drawn {
        let runs = sight.visible(line, STEP / scale, CUT / scale);
        let name = format!("{group_id}.{}-{}", part_name(line.part), line.item);
        let path = match paths.last_mut() {
            Some((id, path)) if *id == name => path,
            _ => {
                paths.push((name, BezPath::new()));
                &mut paths.last_mut().expect("just pushed").1
            }
        };
        for piece in runs.iter().flat_map(|run| sight.picture(run)) {
            push_run(path, &piece.iter().map(|p| place * *p).collect::<Vec<_>>());
        }
    }
    paths.retain(|(_, p)| !p.elements().is_empty());
    let mask = if [Part::Stem, Part::Leaves, Part::Supports]
        .iter()
        .all(|p| spec.draw.contains(p))
    {
        mask(&sight, place)
    } else {
        None
    };
    cx.take_paths(paths.len() + usize::from(mask.is_some()), || {
        format!("the vine {group_id}")
    })?;
    let mut group = Group::new(group_id);
    if let Some(mask) = mask {
        // First, so that it hides nothing of the vine's own lines.
        let style = Style {
            mask: true,
            ..Style::default()
        };
        group.push_path(format!("{group_id}.mask"), mask, style);
    }
    for (id, path) in paths {
        group.push_path(id, path, Style::default());
    }
    let shapes = if guide.is_some() {
        &[][..]
    } else {
        supports.shapes()
    };
    cx.model(model::model(group_id, spec, &plant, shapes, &sight));
    Ok(group)
}

/// The map that draws `drawn` at `scale`, centred across `frame`, the
/// level `ground` (in `drawn`'s units, y down) on its bottom edge; an
/// error (naming `field`) when what stands above the ground does not fit,
/// with the scale that would. What hangs below the ground (a seed leaf)
/// may reach under the edge.
fn at_scale(drawn: Rect, ground: f64, frame: Rect, scale: f64, field: &str) -> Result<Affine> {
    let tall = (ground - drawn.y0).max(0.0);
    let fits = (frame.width() / drawn.width()).min(frame.height() / tall);
    if scale > fits * (1.0 + 1e-9) {
        return Err(Error::invalid(
            field,
            format!(
                "draws the picture {:.1} × {:.1} mm, larger than its box ({:.1} × {:.1} mm): at most {fits:.4}",
                drawn.width() * scale,
                tall * scale,
                frame.width(),
                frame.height()
            ),
        ));
    }
    let foot = Point::new(drawn.center().x, ground);
    let edge = Point::new(frame.center().x, frame.y1);
    Ok(Affine::translate(edge.to_vec2()) * Affine::scale(scale) * Affine::translate(-foot.to_vec2()))
}

/// The area the vine covers on the page, as a [mask](Style::mask): with
/// hidden-line removal (`[plot.occlude]`) it hides what lies behind the
/// vine in other layers and groups, as the trees of a kimono composition
/// do.
fn mask(sight: &Sight, place: Affine) -> Option<BezPath> {
    let parts: Vec<Region> = sight
        .silhouette()
        .iter()
        .filter_map(|ring| {
            let ring: Vec<Point> = ring.iter().map(|p| place * *p).collect();
            Region::polygon(&ring).ok()
        })
        .collect();
    let union = Region::union_all(&parts);
    (!union.is_empty()).then(|| union.into_path())
}

/// Several plants as one: stems and leaves in order, their references to
/// stems renumbered.
fn merged(plants: Vec<Plant>) -> Plant {
    let mut all = Plant {
        stems: Vec::new(),
        leaves: Vec::new(),
        steps: plants.first().map_or(2, |p| p.steps),
    };
    for plant in plants {
        let offset = all.stems.len();
        all.stems.extend(plant.stems.into_iter().map(|mut s| {
            s.parent = s.parent.map(|(stem, point)| (stem + offset, point));
            s
        }));
        all.leaves.extend(plant.leaves.into_iter().map(|mut l| {
            l.stem += offset;
            l
        }));
    }
    all
}

/// Cuts every stem where it passes `height` (the end of a guide: beyond
/// it a stem would go on straight, off the border), with the leaves there.
fn trim(plant: &mut Plant, height: f64) {
    for stem in &mut plant.stems {
        let keep = stem
            .points
            .iter()
            .position(|p| p.y > height)
            .unwrap_or(stem.points.len());
        stem.points.truncate(keep);
        stem.raw.truncate(keep);
        stem.twined.truncate(keep);
    }
    let stems = &plant.stems;
    plant
        .leaves
        .retain(|l| l.node < stems[l.stem].points.len() && l.stalk[1].y <= height);
}

/// The name of a part in ids and the 3D export.
fn part_name(part: Part) -> &'static str {
    match part {
        Part::Stem => "stem",
        Part::Leaves => "leaf",
        Part::Supports => "support",
    }
}

/// Appends a visible run as a polyline, with the points a pen cannot tell
/// from the line between their neighbours left out.
fn push_run(path: &mut BezPath, run: &[Point]) {
    if run.len() < 2 {
        return;
    }
    let mut keep = Vec::new();
    rdp(run, KEEP, &mut keep);
    let mut points = run.iter().zip(&keep).filter(|(_, k)| **k).map(|(p, _)| *p);
    if let Some(first) = points.next() {
        path.move_to(first);
        for p in points {
            path.line_to(p);
        }
    }
}
