//! Putting a motif of the library on the page: sized from its unit
//! drawing, turned from straight up, drawn with its paint and shading,
//! swapped or moved by its final adjustment. Every family that carries
//! flowers and leaves (tree sets, L-systems) puts them this way.

use kurbo::{Affine, Vec2};

use super::bokashi::shade;
use super::flora::Drawing;
use super::Context;
use crate::error::Result;
use crate::rng::RandomStream;
use crate::scene::traditional::Palette;
use crate::scene::{Group, Style};
use crate::spec::{AdjustSpec, MotifRef, PaintSpec};

/// Unit motif → page: anchor at the origin, sized `w × h`.
pub(crate) fn sized(d: &Drawing, w: f64, h: Option<f64>) -> Affine {
    let h = h.unwrap_or(w * d.aspect);
    Affine::scale_non_uniform(w, h) * Affine::translate(-d.anchor.to_vec2())
}

/// Clockwise angle (radians) from straight up to `d` on the page.
pub(crate) fn angle_from_up(d: Vec2) -> f64 {
    d.x.atan2(-d.y)
}

fn style(paint: &PaintSpec, palette: &Palette) -> Style {
    Style {
        fill: paint.color(palette),
        hatch: paint.hatch,
        fill_only: false,
        edge_drawn: false,
        mask: false,
    }
}

/// Where a motif goes and what it looks like.
pub(crate) struct Put<'a> {
    /// Its id (the path's in the SVG, and what `[[adjust]]` names).
    pub(crate) id: String,
    /// What is drawn (unless the adjustment swaps it).
    pub(crate) motif: &'a MotifRef,
    /// Its final adjustment.
    pub(crate) adjust: Option<&'a AdjustSpec>,
    /// Its preview colour and hatching.
    pub(crate) paint: &'a PaintSpec,
}

/// Draws a motif (swapped for the adjustment's when it names one), maps
/// it by `place` (which sees the drawing, for its anchor and aspect),
/// takes it from the budget and appends it to `group`.
pub(crate) fn put(
    group: &mut Group,
    item: Put<'_>,
    cx: &mut Context<'_>,
    rng: &mut RandomStream,
    place: impl Fn(&Drawing) -> Affine,
) -> Result<()> {
    let motif = item
        .adjust
        .and_then(|a| a.motif.as_ref())
        .unwrap_or(item.motif);
    let d = cx.library().draw(motif, rng)?;
    cx.take_paths(1, || format!("motif {}", item.id))?;
    let placement = place(&d);
    let mut path = d.to_path(placement);
    if let Some(b) = &item.paint.bokashi {
        let lines = shade(&(placement * d.outline.clone()), b)?;
        path.extend(lines.elements().iter().copied());
    }
    group.push_path(item.id, path, style(item.paint, cx.palette()));
    Ok(())
}
