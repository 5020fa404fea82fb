//! The `wagara` family: a traditional ground (和柄) over a region, drawn
//! as one seamless repeat — no tile frame, no seam, every line drawn once
//! and as long as the pattern lets it run (see `motif::ground`, which
//! kimono backgrounds share).
//!
//! The repeat is laid out in its own frame (origin at the region's centre
//! plus `offset`, turned by `angle`) over the region's box, then mapped
//! onto the page and clipped to the region exactly. Ids:
//! `<layer>.<ground>.<pattern>.stroke-<i>` (`front.waves.seigaiha.stroke-3`),
//! `….dark-<i>` for a dark shape (uroko's triangles, hatched by the pen),
//! so `[[adjust]]` can hide or move one, and
//! `<layer>.<ground>.<pattern>.outline` for the region's edge.

pub(crate) mod description;

#[cfg(test)]
mod tests;

use kurbo::Vec2;

use crate::error::Result;
use crate::motif::adjust::about;
use crate::motif::ground;
use crate::motif::region::region;
use crate::motif::Context;
use crate::scene::{Color, Group, Style};
use crate::spec::WagaraSpec;

/// Builds the ground into a group with id `group_id`.
///
/// # Errors
/// A region that encloses nothing; more strokes than the path budget
/// allows (found before they are made); an SVG region file that was not
/// loaded; an adjustment that does not fit a stroke.
pub(super) fn build(spec: &WagaraSpec, group_id: &str, cx: &mut Context<'_>) -> Result<Group> {
    let region = region(&spec.region, cx)?;
    let bounds = region.bounds();
    let origin = bounds.center() + Vec2::new(spec.offset[0], spec.offset[1]);
    let laid = ground::Laid::new(bounds, spec.scale, origin, spec.angle);
    let name = spec.pattern.name();
    let lines = spec.line_count();
    let what = || format!("wagara {group_id} ({name} at scale {} mm)", spec.scale);
    // A ground too fine for its region fails here, before the work.
    let estimate = ground::estimate(spec.pattern, spec.scale, lines, laid.window());
    cx.budget()
        .clone()
        .take(estimate.min(usize::MAX as f64) as usize, what)?;
    let ground::Drawn { strokes, dark } =
        laid.draw(&region, spec.pattern, spec.scale, lines, cx.pen_width())?;
    cx.take_paths(strokes.len() + dark.len(), what)?;
    let id = format!("{group_id}.{name}");
    let mut part = Group::new(&id);
    let ink = Style {
        fill: Some(Color::BLACK),
        hatch: Some(spec.hatch_spacing()),
        ..Style::default()
    };
    let paths = strokes
        .into_iter()
        .map(|p| ("stroke", p, Style::default()))
        .chain(dark.into_iter().map(|p| ("dark", p, ink.clone())));
    let mut counts = [0usize; 2];
    for (kind, path, style) in paths {
        let n = &mut counts[usize::from(kind == "dark")];
        let path_id = format!("{id}.{kind}-{n}");
        *n += 1;
        let adjusted = cx.adjust().take_without_motif(&path_id, "a wagara stroke")?;
        if adjusted.is_some_and(|a| a.hide) {
            continue;
        }
        let path = about(adjusted, kurbo::Shape::bounding_box(&path).center()) * path;
        part.push_path(path_id, path, style);
    }
    if spec.outline {
        cx.take_paths(1, what)?;
        part.push_path(format!("{id}.outline"), region.into_path(), Style::default());
    }
    let mut group = Group::new(group_id);
    group.push_group(part);
    cx.advance(1);
    Ok(group)
}
