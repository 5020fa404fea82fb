//! The plot pipeline in its fixed order, every stage optional:
//!
//! transform → hatch → occlude → (one layer per pen) → dedupe → merge →
//! blots → debris → simplify → sort (inside first, for a cutter) →
//! multipass.
//!
//! Geometry is transformed first so that hatch spacing and tolerances are
//! measured on the final page; fills become hatch lines before hidden lines
//! are removed, so the hatching of a back shape is hidden like any other
//! stroke while its closed outline still hides what lies behind it; hidden
//! lines are removed while the depth layers still exist; the per-pen stages
//! work on one flat layer per pen, which is what a plotter runs. Masks
//! ([`crate::scene::Style::mask`]) leave the scene after hidden-line
//! removal, which is all they are for.
//!
//! The *pen stage* — dedupe, merge, blots, debris, sort — is what makes a
//! drawing what a pen should draw: no line twice, no puddle of ink where
//! lines converge, no slivers, little travel
//! ([`PlotOptions::pen_ready`]). Every render runs it unless the
//! description turns a step off ([`crate::spec::PlotSpec`]); `moyo plot`
//! runs what its options ask. With merging, strokes are joined before
//! doubled line work is taken out (an overlap split among short pieces is
//! weighed whole) and again after (the pieces left join up with what they
//! meet); blots are thinned once strokes are whole (an end is only an end
//! once nothing joins it), and debris goes last, so that pieces that join
//! are not taken for it and what thinning leaves of a stroke is weighed.

use serde::{Deserialize, Serialize};

use super::{
    blots, debris, dedupe, flatten, hatch, merge, multipass, nest, occlude, simplify, sort,
    transform, BlotOptions, DebrisOptions, DedupeOptions, HatchOptions, MergeOptions,
    MultipassOptions, OccludeOptions, SimplifyOptions, SortOptions, TransformOptions,
};
use crate::cancel::Cancel;
use crate::error::{Error, Result};
use crate::scene::{Group, Node, Scene};

/// Which stages run, with their options. `None` (absent in a file) skips a
/// stage; an empty table runs it with its defaults.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlotOptions {
    /// Rotate, scale, fit to the page, centre.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transform: Option<TransformOptions>,
    /// Remove strokes hidden behind closed shapes in front.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub occlude: Option<OccludeOptions>,
    /// Turn fills into hatch lines.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hatch: Option<HatchOptions>,
    /// Take out line work that lies on line work of the same pen.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dedupe: Option<DedupeOptions>,
    /// Join paths whose ends meet.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub merge: Option<MergeOptions>,
    /// Trim line ends where a square millimetre would hold more ink than
    /// the limit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub blots: Option<BlotOptions>,
    /// Take out strokes shorter than the pen is wide that touch others.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub debris: Option<DebrisOptions>,
    /// Drop points within a tolerance.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub simplify: Option<SimplifyOptions>,
    /// Order paths to shorten pen-up travel.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sort: Option<SortOptions>,
    /// Draw every path several times.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub multipass: Option<MultipassOptions>,
    /// Cut every closed path after the paths inside it ([`nest`]), the
    /// travel sort ordering each nesting level when it runs: what a
    /// cutter needs, so that a piece is not freed before its holes are
    /// cut.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub inside_first: bool,
}

fn finite_range(field: &str, v: f64, lo: f64, hi: f64) -> Result<()> {
    if lo <= v && v <= hi {
        Ok(())
    } else {
        Err(Error::invalid(
            field,
            format!("must be between {lo} and {hi}, got {v}"),
        ))
    }
}

impl PlotOptions {
    /// True when no stage runs.
    pub fn is_empty(&self) -> bool {
        *self == PlotOptions::default()
    }

    /// The pen stage alone, every step with its defaults: dedupe, merge,
    /// blots, debris and sort.
    pub fn pen_ready() -> PlotOptions {
        PlotOptions {
            dedupe: Some(DedupeOptions::DEFAULT),
            merge: Some(MergeOptions::DEFAULT),
            blots: Some(BlotOptions::DEFAULT),
            debris: Some(DebrisOptions::DEFAULT),
            sort: Some(SortOptions::DEFAULT),
            ..PlotOptions::default()
        }
    }

    /// These options without the stages that need one flat layer per pen,
    /// so that the scene keeps its layers, groups and ids (a preview to
    /// point at, not to plot).
    pub fn keeping_groups(&self) -> PlotOptions {
        PlotOptions {
            dedupe: None,
            merge: None,
            blots: None,
            debris: None,
            simplify: None,
            sort: None,
            multipass: None,
            inside_first: false,
            ..self.clone()
        }
    }

    /// True when a stage needs one flat layer per pen.
    pub fn per_pen(&self) -> bool {
        self.dedupe.is_some()
            || self.debris.is_some()
            || self.blots.is_some()
            || self.merge.is_some()
            || self.simplify.is_some()
            || self.sort.is_some()
            || self.multipass.is_some()
            || self.inside_first
    }

    /// Checks every option's range; `field` prefixes the error paths
    /// (`plot` in a scene description).
    pub fn validate(&self, field: &str) -> Result<()> {
        if let Some(t) = &self.transform {
            finite_range(
                &format!("{field}.transform.rotate_deg"),
                t.rotate_deg,
                -360.0,
                360.0,
            )?;
            finite_range(&format!("{field}.transform.scale"), t.scale, 1e-3, 1e3)?;
            if let Some(m) = t.margin {
                finite_range(&format!("{field}.transform.margin"), m, 0.0, 1000.0)?;
            }
        }
        if let Some(o) = &self.occlude {
            finite_range(
                &format!("{field}.occlude.tolerance"),
                o.tolerance,
                1e-4,
                1.0,
            )?;
        }
        if let Some(h) = &self.hatch {
            // The hatch's own errors already say `hatch.…`.
            h.validate().map_err(|e| prefix(e, field))?;
        }
        if let Some(tolerance) = self.dedupe.and_then(|d| d.tolerance) {
            finite_range(&format!("{field}.dedupe.tolerance"), tolerance, 0.0, 10.0)?;
        }
        if let Some(m) = &self.merge {
            finite_range(&format!("{field}.merge.tolerance"), m.tolerance, 0.0, 10.0)?;
        }
        if let Some(b) = &self.blots {
            finite_range(&format!("{field}.blots.limit"), b.limit, 0.5, 10.0)?;
        }
        if let Some(length) = self.debris.and_then(|d| d.length) {
            finite_range(&format!("{field}.debris.length"), length, 0.0, 10.0)?;
        }
        if let Some(s) = &self.simplify {
            finite_range(
                &format!("{field}.simplify.tolerance"),
                s.tolerance,
                0.0,
                10.0,
            )?;
        }
        if let Some(s) = &self.sort {
            if s.window > 10_000 || s.max_passes > 1_000 {
                return Err(Error::invalid(
                    format!("{field}.sort"),
                    "window must be at most 10000 and max_passes at most 1000",
                ));
            }
        }
        if let Some(m) = &self.multipass {
            if !(1..=100).contains(&m.passes) {
                return Err(Error::invalid(
                    format!("{field}.multipass.passes"),
                    format!("must be between 1 and 100, got {}", m.passes),
                ));
            }
        }
        Ok(())
    }
}

/// Removes every [mask](crate::scene::Style::mask) below `group`.
fn drop_masks(group: &mut Group) {
    group.children.retain_mut(|child| match child {
        Node::Group(g) => {
            drop_masks(g);
            true
        }
        Node::Path(p) => !p.style.mask,
    });
}

/// Puts `prefix.` before the field of an [`Error::Invalid`].
fn prefix(e: Error, prefix: &str) -> Error {
    match e {
        Error::Invalid { at, field, message } => Error::Invalid {
            at,
            field: format!("{prefix}.{field}"),
            message,
        },
        e => e,
    }
}

/// Runs the configured stages. Without per-pen stages the scene keeps its
/// layers, groups and ids; with them it becomes one flat layer per pen.
pub fn run(scene: Scene, o: &PlotOptions) -> Result<Scene> {
    run_cancellable(scene, o, Cancel::never())
}

/// [`run`] that stops with [`Error::Cancelled`]
/// soon after `cancel` is raised: between the stages, and inside
/// hidden-line removal (the slow one).
pub fn run_cancellable(mut scene: Scene, o: &PlotOptions, cancel: &Cancel) -> Result<Scene> {
    o.validate("plot")?;
    if let Some(t) = &o.transform {
        transform::apply(&mut scene, t);
    }
    // Layers that are not plotted (`%` labels) are guides: neither
    // hatched, nor hidden, nor hiding.
    let unplotted = flatten::take_unplotted(&mut scene);
    if let Some(h) = &o.hatch {
        hatch::run(&mut scene, h)?;
    } else if hatch::has_own_hatch(&scene) {
        hatch::run_own(&mut scene)?;
    }
    if let Some(occ) = &o.occlude {
        let mut occ = occ.clone();
        occ.skip_layers
            .retain(|id| !unplotted.iter().any(|(_, l)| l.id == *id));
        occlude::run_cancellable(&mut scene, &occ, cancel)?;
    }
    cancel.check()?;
    flatten::restore_unplotted(&mut scene, unplotted);
    // Masks have hidden what they hide (or there was nothing to hide).
    for layer in &mut scene.layers {
        drop_masks(&mut layer.content);
    }
    if !o.per_pen() {
        return Ok(scene);
    }
    // Reordered, a fill would cover what its pen now draws before it.
    occlude::fills_behind(&mut scene);
    let mut flat = flatten::by_pen(&scene);
    if let Some(d) = &o.dedupe {
        // Strokes joined first, so that an overlap split among pieces
        // is weighed whole.
        if let Some(m) = &o.merge {
            merge::run(&mut flat, m);
        }
        dedupe::run(&mut flat, d);
    }
    cancel.check()?;
    if let Some(m) = &o.merge {
        merge::run(&mut flat, m);
    }
    if let Some(b) = &o.blots {
        blots::run(&mut flat, b);
    }
    if let Some(d) = &o.debris {
        debris::run(&mut flat, d);
    }
    cancel.check()?;
    if let Some(s) = &o.simplify {
        simplify::run(&mut flat, s);
    }
    if o.inside_first {
        nest::run(&mut flat, o.sort.as_ref());
    } else if let Some(s) = &o.sort {
        sort::run(&mut flat, s);
    }
    if let Some(m) = &o.multipass {
        multipass::run(&mut flat, m);
    }
    Ok(flat)
}

#[cfg(test)]
mod tests {
    use kurbo::{Rect, Shape};

    use super::*;
    use crate::scene::Style;
    use crate::units::{Margins, Orientation, Page, PaperName};

    #[test]
    fn masks_leave_the_scene_with_or_without_hidden_line_removal() {
        let mut content = Group::new("g");
        let mask = Style {
            mask: true,
            ..Style::default()
        };
        content.push_path("mask", Rect::new(0.0, 0.0, 5.0, 5.0).to_path(0.0), mask);
        content.push_path(
            "line",
            Rect::new(1.0, 1.0, 9.0, 9.0).to_path(0.0),
            Style::default(),
        );
        let page = Page::named(PaperName::A5, Orientation::Portrait, Margins::uniform(10.0));
        let scene = Scene::one_pen(page, content);
        for options in [
            PlotOptions::default(),
            PlotOptions {
                occlude: Some(OccludeOptions::DEFAULT),
                ..PlotOptions::default()
            },
        ] {
            let out = run(scene.clone(), &options).unwrap();
            let mut ids = Vec::new();
            out.visit_paths(|_, p, _| ids.push(p.id.clone()));
            assert_eq!(ids, ["line"]);
        }
    }
}
