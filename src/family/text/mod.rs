//! The `text` family (docs/SPEC.md §8): words on the page in
//! single-stroke letters (see [`TextSpec`]; the lettering itself is
//! [`crate::text`]'s).
//!
//! Each drawn character is one path, id `<layer>.<text>.glyph-<i>`, its
//! strokes subpaths, unfilled: the pen draws the letters' lines and
//! nothing else. `[[adjust]]` moves, turns, scales or hides the text as a
//! whole by its group's id. Characters without a glyph are drawn as boxes
//! and named in a note.

pub(crate) mod description;

use kurbo::{Affine, Shape};

use crate::error::{Error, Result};
use crate::motif::Context;
use crate::scene::{Group, Style};
use crate::spec::TextSpec;
use crate::text::layout;
use crate::units::MAX_COORD;

/// Lays out a text table into a group with id `group_id`.
///
/// # Errors
/// The path budget; a text that would reach beyond ±MAX_COORD.
pub(super) fn build(spec: &TextSpec, group_id: &str, cx: &mut Context<'_>) -> Result<Group> {
    let lettering = layout(&spec.text, &spec.style());
    cx.take_paths(lettering.glyphs.len(), || format!("text {group_id}"))?;
    if !lettering.missing.is_empty() {
        cx.note(
            group_id,
            format!(
                "no single-stroke glyph for {}: drawn as boxes",
                lettering.missing_list()
            ),
        );
    }
    let [x, y] = spec.at;
    let place = Affine::translate((x, y)) * Affine::rotate(spec.rotate.to_radians());
    let mut group = Group::new(group_id);
    for (i, glyph) in lettering.glyphs.into_iter().enumerate() {
        let path = place * glyph;
        let b = path.bounding_box();
        if ![b.x0, b.y0, b.x1, b.y1]
            .iter()
            .all(|v| v.is_finite() && v.abs() <= MAX_COORD)
        {
            return Err(Error::invalid(
                cx.field("at"),
                format!("the text would reach beyond ±{MAX_COORD} mm"),
            ));
        }
        group.push_path(format!("{group_id}.glyph-{i}"), path, Style::default());
    }
    Ok(group)
}

#[cfg(test)]
mod tests;
