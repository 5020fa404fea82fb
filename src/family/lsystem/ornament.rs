//! Flowers and leaves on an L-system: motifs of the library (the kimono
//! family's, placed the same way) at the tips of the limbs or where the
//! turtle met a symbol. Flowers stand upright, turned by up to `turn`;
//! leaves point the way the turtle was heading there.
//!
//! Ids: `<plant>.flower-<i>`, `<plant>.leaf-<i>`; each draws its jitter
//! from its own stream, and `[[adjust]]` moves, turns, scales, swaps or
//! hides it by that id.

use kurbo::{Affine, Point, Vec2};

use super::draw::Flat;
use crate::error::Result;
use crate::motif::adjust::about;
use crate::motif::place::{angle_from_up, put, sized, Put};
use crate::motif::Context;
use crate::scene::Group;
use crate::spec::OrnamentSpec;
use crate::Error;

/// A place for an ornament in the drawing's units: where, and the
/// direction the limb or the turtle headed there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Site {
    pub(super) at: Point,
    pub(super) heading: Vec2,
}

/// The sites of `ornament`: the marks of its symbol, or the tips.
pub(super) fn sites(flat: &Flat, ornament: &OrnamentSpec) -> Vec<Site> {
    match ornament.symbol_char() {
        Some(symbol) => flat
            .marks
            .iter()
            .filter(|m| m.symbol == symbol)
            .map(|m| Site {
                at: m.at,
                heading: m.heading,
            })
            .collect(),
        None => flat.tips.clone(),
    }
}

/// Which ornaments: flowers stand up, leaves follow the heading.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    Flower,
    Leaf,
}

impl Kind {
    fn name(self) -> &'static str {
        match self {
            Kind::Flower => "flower",
            Kind::Leaf => "leaf",
        }
    }
}

/// The cost of `ornament` at `sites` in each of `copies` drawings,
/// estimated before any is drawn and refused (naming `field`, the
/// table's `leaves` or `flowers`) past what
/// is left of the scene's budget: one path each, and the segments of its
/// motif (each motif of the list drawn once to count them). A symbol met
/// a million times would otherwise build a million ornaments first.
pub(super) fn check_budget(
    ornament: &OrnamentSpec,
    sites: usize,
    copies: usize,
    field: &str,
    cx: &mut Context<'_>,
) -> Result<()> {
    let count = sites.saturating_mul(copies);
    let what = match ornament.symbol_char() {
        Some(symbol) => format!("the turtle meets `{symbol}` {sites} times"),
        None => format!("the drawing has {sites} tips"),
    };
    let copies = if copies > 1 {
        format!(" in each of {copies} drawings")
    } else {
        String::new()
    };
    let left = cx.budget().paths_left();
    if count > left {
        return Err(Error::invalid(
            field,
            format!(
                "{what}{copies}: {count} ornaments would make {count} paths, more than the \
                 {left} left of limits.max_paths; lower the iterations"
            ),
        ));
    }
    let mut rng = cx.stream(&format!("{field}/estimate"));
    let per_motif = ornament
        .motifs
        .iter()
        .map(|m| {
            let d = cx.library().draw(m, &mut rng)?;
            Ok(d.to_path(Affine::IDENTITY)
                .elements()
                .iter()
                .filter(|e| !matches!(e, kurbo::PathEl::MoveTo(_)))
                .count())
        })
        .collect::<Result<Vec<usize>>>()?;
    // Ornament i draws motif i mod n.
    let n = per_motif.len().max(1);
    let all: usize = per_motif.iter().sum();
    let first: usize = per_motif.iter().take(count % n).sum();
    let segments = (count / n).saturating_mul(all).saturating_add(first);
    let left = cx.budget().segments_left();
    if segments > left {
        return Err(Error::invalid(
            field,
            format!(
                "{what}{copies}: {count} ornaments would make about {segments} segments, \
                 more than the {left} left of limits.max_segments; lower the iterations"
            ),
        ));
    }
    Ok(())
}

/// Draws `ornament` at `sites` of the drawing placed by `place` into a
/// group `<plant>.flowers` or `<plant>.leaves`.
pub(super) fn ornaments(
    ornament: &OrnamentSpec,
    kind: Kind,
    sites: &[Site],
    place: Affine,
    plant_id: &str,
    cx: &mut Context<'_>,
) -> Result<Group> {
    let mut group = Group::new(format!("{plant_id}.{}s", kind.name()));
    // The placement's linear part, for headings.
    let [a, b, c, d, _, _] = place.as_coeffs();
    let linear = Affine::new([a, b, c, d, 0.0, 0.0]);
    let n = ornament.motifs.len();
    for (i, site) in sites.iter().enumerate() {
        let id = format!("{plant_id}.{}-{i}", kind.name());
        let adjust = cx.adjust().take(&id);
        if adjust.is_some_and(|a| a.hide) {
            continue;
        }
        let mut rng = cx.stream(&id);
        let turn = rng.symmetric(ornament.turn).to_radians();
        let at = place * site.at;
        let up = match kind {
            Kind::Flower => 0.0,
            Kind::Leaf => {
                let heading = (linear * site.heading.to_point()).to_vec2();
                if heading.hypot() > 1e-12 {
                    angle_from_up(heading)
                } else {
                    0.0
                }
            }
        };
        let item = Put {
            id,
            motif: &ornament.motifs[i % n],
            adjust,
            paint: &ornament.paint,
        };
        put(&mut group, item, cx, &mut rng, |drawing| {
            about(adjust, at)
                * Affine::translate(at.to_vec2())
                * Affine::rotate(up + turn)
                * sized(drawing, ornament.width, ornament.height)
        })?;
    }
    Ok(group)
}
