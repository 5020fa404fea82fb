//! The `zentangle` family (docs/SPEC.md §2): the filling process of the zentangle
//! paper in exact vector form (see [`ZentangleSpec`]).
//!
//! - `element`: the 26 elements (basic and compound shapes) as marks in
//!   painter's order, and their hand-drawn deformation;
//! - `placement`: the placement templates MR, MT, MS, MA, MC and ML of
//!   symmetric patterns;
//! - `pattern`: the region-dependent patterns;
//! - `procedure`: the twenty procedures of the paper's table 1 and their
//!   seed groups;
//! - `tangle`: twelve named Zentangle tangles (Printemps, Hollibaugh, …),
//!   procedures from id 20;
//! - `choice`: which tangle fills each section;
//! - `compose`: what a procedure's marks do to a white region — the
//!   visible lines, the white pieces left and the black area;
//! - `tile`: the border and the string, and the sections they leave;
//! - `filling`: the loop;
//! - `ink`: the ink per square millimetre the loop may not pass;
//! - `edges`: the stretches of a hatched black part's edge that no line
//!   draws.
//!
//! Each step is a group `<layer>.<table>.step-K-pP` (step K drew
//! procedure P; `step-K-printemps` for a named tangle) of its lines
//! (`line-I`) and black parts (`black-I`, hatched or filled as `black`
//! says; a hatched part's edge is drawn by the lines, and where none runs
//! by `black-I.edge`); `step-0-lines` holds the
//! description's own `lines` and an inked string; `border` the border's
//! lines, one closed path per contour.

pub(crate) mod description;
#[cfg(feature = "studio")]
mod gesture;
mod choice;
mod compose;
mod edges;
mod element;
pub(crate) mod ffd;
mod filling;
mod ink;
mod pattern;
mod placement;
mod procedure;
mod tangle;
mod tile;

use kurbo::{BezPath, Point};

use crate::error::{Error, Result};
use crate::geom::density::{Density, Formula};
use crate::geom::region::Region;
use crate::motif::region::regions;
use crate::motif::Context;
use crate::rng::RandomStream;
use crate::scene::{Color, Group, Style};
use crate::spec::{Black, Look, ZentangleSpec, ELEMENTS, PROCEDURES};
use choice::Choice;
use element::Shape;
use filling::{Filling, Settings, Step};
use tile::polyline;
use procedure::Allowed;
use tangle::Tangle;

/// Builds a zentangle fill into a group with id `group_id`.
///
/// # Errors
/// A region that encloses nothing; a manual step whose point lies in no
/// white region; the path budget.
pub(super) fn build(spec: &ZentangleSpec, group_id: &str, cx: &mut Context<'_>) -> Result<Group> {
    let regions = regions(&spec.region, cx)?;
    let mut rng = cx.stream(group_id);
    let allowed = Allowed {
        procedures: spec
            .procedures
            .clone()
            .unwrap_or_else(|| (0..PROCEDURES).collect()),
        elements: spec.elements.as_ref().map_or_else(
            || Shape::ALL.to_vec(),
            |names| names.iter().filter_map(|n| Shape::from_name(n)).collect(),
        ),
    };
    debug_assert!(ELEMENTS.iter().all(|n| Shape::from_name(n).is_some()));
    let pen = cx.pen_width();
    let mut hand = cx.stream(&format!("{group_id}/hand"));
    let tile = tile::tile(
        &regions,
        spec.border.as_ref(),
        spec.string.as_ref(),
        spec.hand,
        pen,
        &mut hand,
    )
    .map_err(|e| match e {
        Error::Invalid { field, message, .. } if field == "border.corner" => {
            Error::invalid(cx.field("border.corner"), message)
        }
        other => other,
    })?;
    let lines: Vec<BezPath> = spec
        .lines
        .iter()
        .map(|l| polyline(&l.iter().map(|&[x, y]| Point::new(x, y)).collect::<Vec<_>>()))
        .chain(tile.string)
        .collect();
    let formula = match spec.tone.as_ref().and_then(|t| t.formula.as_deref()) {
        Some(text) => Some(Formula::parse(text).map_err(|e| match e {
            Error::Invalid { message, .. } => Error::invalid(cx.field("tone.formula"), message),
            other => other,
        })?),
        None => None,
    };
    let image = match spec.tone.as_ref().and_then(|t| t.image.as_deref()) {
        Some(name) => Some(cx.library().image(name)?),
        None => None,
    };
    let frame = regions
        .iter()
        .map(Region::bounds)
        .reduce(|a, b| a.union(b))
        .unwrap_or_default();
    let mut darkness = Density::new(frame);
    if let Some(img) = image {
        darkness = darkness.with_image(img);
    }
    if let Some(f) = &formula {
        darkness = darkness.with_formula(f);
    }
    let tone = |p: Point| darkness.at(p);
    let weight = |p: u32| spec.weights.get(&p.to_string()).copied().unwrap_or(1.0);
    let settings = Settings {
        scale: spec.scale,
        smallest: spec.smallest,
        wobble: spec.wobble,
        hand: spec.hand,
        retrace: spec.retrace,
        pen,
        fragment: spec.fragment.unwrap_or(match spec.look {
            Look::Tangles => FRAGMENT_PENS * pen,
            Look::Sampler => 0.0,
        }),
        choice: (spec.look == Look::Tangles).then_some(Choice {
            weight: &weight,
            contrast: spec.alternate,
        }),
        depth: spec.depth.unwrap_or(u32::MAX),
        hatch: (spec.black == Black::Hatch).then_some(spec.hatch),
        follow: spec.follow,
        branching: spec.branching,
        tone: spec
            .tone
            .as_ref()
            .map(|t| (&tone as &dyn Fn(Point) -> f64, t.contrast)),
    };
    let (mut filling, first) = Filling::new(&tile.sections, lines, allowed, settings, hand)?;
    if filling.open() == 0 {
        return Err(Error::invalid(
            cx.field("region"),
            format!(
                "is too small to draw in: no part of it holds a circle of radius `smallest` \
                 = {} mm",
                spec.smallest
            ),
        ));
    }
    filling.choose_tangles(&mut rng);
    let mut group = Group::new(group_id);
    if !tile.border.is_empty() {
        let id = format!("{group_id}.border");
        cx.take_paths(tile.border.len(), || format!("zentangle {id}"))?;
        let mut border = Group::new(&id);
        for (i, line) in tile.border.into_iter().enumerate() {
            border.push_path(format!("{id}.line-{i}"), line, Style::default());
        }
        group.push_group(border);
    }
    emit(spec, &mut group, group_id, 0, first, cx)?;
    // The manual steps chosen for the blank tile, then the loop, then
    // the manual steps that touch up what the loop left white.
    let mut steps = Steps {
        spec,
        group: &mut group,
        group_id,
        k: 0,
    };
    steps.by_hand(false, &mut filling, &mut rng, cx)?;
    // The loop ends early when no white region left can take a step
    // (none is wide enough, or every one left draws nothing under the
    // ink limit): asking for more steps then costs nothing more.
    let mut stopped = None;
    for n in 0..spec.steps {
        let Some(step) = filling.step(&mut rng)? else {
            stopped = Some((steps.k, n));
            break;
        };
        steps.emit(step, cx)?;
    }
    steps.by_hand(true, &mut filling, &mut rng, cx)?;
    let k = steps.k;
    let drawn = edges::draw_bare_edges(&mut group, pen);
    cx.take_paths(drawn, || format!("zentangle {group_id} black edges"))?;
    let stop = stopped.map_or_else(String::new, |(at, n)| {
        format!(
            "; the loop stopped after step {at} ({n} of the {} steps asked for): no white \
             region left could take a step",
            spec.steps
        )
    });
    cx.note(
        group_id,
        format!(
            "{k} steps; {} white regions wide enough to draw in are left{stop}",
            filling.open()
        ),
    );
    Ok(group)
}

/// The steps of one fill as they are drawn, numbered from 1.
struct Steps<'s> {
    spec: &'s ZentangleSpec,
    group: &'s mut Group,
    group_id: &'s str,
    /// The number of the last step drawn.
    k: usize,
}

impl Steps<'_> {
    /// Draws the next step and counts it done.
    fn emit(&mut self, step: Step, cx: &mut Context<'_>) -> Result<()> {
        self.k += 1;
        emit(self.spec, self.group, self.group_id, self.k, step, cx)?;
        cx.advance(1);
        Ok(())
    }

    /// The manual steps run `after` the loop (or before it), each in the
    /// white region under its point; errors name the step's `at`.
    fn by_hand(
        &mut self,
        after: bool,
        filling: &mut Filling,
        rng: &mut RandomStream,
        cx: &mut Context<'_>,
    ) -> Result<()> {
        let spec = self.spec;
        for (i, m) in spec
            .manual
            .iter()
            .enumerate()
            .filter(|(_, m)| m.after == after)
        {
            let at = Point::new(m.at[0], m.at[1]);
            let step = filling.step_at(at, m.procedure, rng).map_err(|e| match e {
                Error::Invalid { message, .. } => {
                    Error::invalid(cx.field(&format!("manual[{i}].at")), message)
                }
                other => other,
            })?;
            self.emit(step, cx)?;
        }
        Ok(())
    }
}

/// Puts a step's lines and black parts into the group, as `step-K`.
fn emit(
    spec: &ZentangleSpec,
    group: &mut Group,
    group_id: &str,
    k: usize,
    step: Step,
    cx: &mut Context<'_>,
) -> Result<()> {
    if step.strokes.is_empty() && step.black.is_empty() {
        return Ok(());
    }
    let id = match step.procedure {
        Some(p) => match Tangle::from_id(p) {
            Some(named) => format!("{group_id}.step-{k}-{}", named.name()),
            None => format!("{group_id}.step-{k}-p{p}"),
        },
        None => format!("{group_id}.step-{k}-lines"),
    };
    cx.take_paths(step.strokes.len() + step.black.len(), || {
        format!("zentangle {id}")
    })?;
    let mut part = Group::new(&id);
    // A hatched black part's edge is the line of the mark that painted it
    // or of a later mark over it, drawn among the step's lines: the part
    // itself is paint whose hatch keeps clear of that line, so its edge is
    // drawn once. A solid part keeps its closed outline (a cutter's cut).
    let hatched = spec.black == Black::Hatch;
    for (i, region) in step.black.into_iter().enumerate() {
        let style = Style {
            fill: Some(Color::BLACK),
            hatch: hatched.then_some(spec.hatch),
            fill_only: hatched,
            edge_drawn: hatched,
            mask: false,
        };
        part.push_path(format!("{id}.black-{i}"), region.into_path(), style);
    }
    for (i, path) in step.strokes.into_iter().enumerate() {
        part.push_path(format!("{id}.line-{i}"), path, Style::default());
    }
    group.push_group(part);
    Ok(())
}

/// The shortest piece of a clipped element's line left on an edge, in
/// pen widths (the description's `fragment` when it gives none): shorter,
/// a stub reads as a dot or a blot.
const FRAGMENT_PENS: f64 = 4.0;

#[cfg(test)]
mod tests;
