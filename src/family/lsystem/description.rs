//! `[[layers.lsystem]]`: an L-system (docs/SPEC.md §4) — the rules of *The
//! Algorithmic Beauty of Plants* drawn by a 3D turtle and projected to the
//! page, or the stroke-guided Sketching L-System (source 003) grown along a
//! stroke.
//!
//! Where it stands: with `at`, the turtle starts at each point, one unit of
//! `F` being `step` mm; with `along`, at `count` points of a line, upright
//! on its upper side; with none of these nor `sketch`, the drawing is
//! fitted into `fit` (default: the page inside its margins), aspect kept,
//! centred. A sketch lies on its stroke, in page millimetres.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::family::lsystem::engine::sketch::SketchRules;
use crate::family::lsystem::engine::LSystem;
use crate::family::Family;
use crate::spec::validate::{point, points, range};
use crate::spec::LimbStyle;
use crate::spec::{one_stroke, FlowLine, MotifRef, OrnamentSpec, Points};

/// An L-system on a layer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LSystemSpec {
    /// Id of the system, unique in its layer (default `lsystem-K`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
    /// The start word (ABOP's axiom), e.g. `"F"` or `"A(10, 1)"`.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub axiom: String,
    /// The productions, one a string: `F -> F[+F]F[-F]F`; stochastic
    /// `F ->(0.33) F[+F]F`; parametric with a condition
    /// `A(l) : l > 1 -> F(l)[+A(l * 0.7)]`; context-sensitive
    /// `B < A > C -> …`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rules: Vec<String>,
    /// How many times the rules rewrite the word (0–100).
    #[serde(default, skip_serializing_if = "is_zero_u32")]
    pub iterations: u32,
    /// The turtle's turning angle δ for `+ - & ^ \ /`, degrees (0–360,
    /// default 25.7).
    #[serde(default = "default_angle")]
    pub angle: f64,
    /// Named numbers the rules and the axiom may use.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub constants: BTreeMap<String, f64>,
    /// Symbols that context matching passes over (ABOP's `#ignore`), e.g.
    /// `"+-F"`.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub ignore: String,
    /// With `at` or `along`: millimetres per unit of `F` (0.001–1000,
    /// default 1).
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub step: f64,
    /// `stroke` (the default: centre lines, one pen pass) or `outline`
    /// (each limb a closed outline as wide as the turtle's width there).
    #[serde(default = "stroke", skip_serializing_if = "is_stroke")]
    pub style: LimbStyle,
    /// The turtle's starting width, in units of `F` (0–1000, default 1):
    /// `!` multiplies it by `width_factor`, `!(w)` sets it. Drawn only by
    /// `style = "outline"`.
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub width: f64,
    /// What plain `!` multiplies the width by (0–1, default 0.7).
    #[serde(default = "default_width_factor")]
    pub width_factor: f64,
    /// Limbs as smooth curves through the turtle's points (natural
    /// splines) instead of the exact straight segments (default false:
    /// Koch, Hilbert and dragon curves stay exact).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub smooth: bool,
    /// Bending of every step towards a direction (ABOP's tropism), e.g.
    /// `{ direction = [0, -1, 0], elasticity = 0.2 }` for weeping limbs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tropism: Option<TropismSpec>,
    /// Where the 3D drawing is seen from (default `"front"`).
    #[serde(default, skip_serializing_if = "View::is_front")]
    pub view: View,
    /// Roots (mm): one drawing starts at each, heading up the page.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub at: Points,
    /// Or roots along this line (≥ 2 control points of a natural spline,
    /// mm): `count` drawings evenly spread by arc length, each standing
    /// perpendicular to the line on its upper side, as trees on a centre
    /// line.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub along: Option<Points>,
    /// With `along`: how many drawings (1–1000, default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub count: Option<u32>,
    /// Turn every drawing placed by `at` or `along` by this many degrees,
    /// clockwise (−360–360).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub rotate: f64,
    /// Without `at`: the box `[x0, y0, x1, y1]` (mm) the drawing is fitted
    /// into (default: the page inside its margins).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fit: Option<[f64; 4]>,
    /// The Sketching L-System instead of `axiom` and `rules`: grown along a
    /// stroke.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sketch: Option<SketchSpec>,
    /// Flowers, upright (turned by up to `turn`), at the limbs' tips or
    /// where the turtle meets `symbol`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flowers: Option<OrnamentSpec>,
    /// Leaves, pointing the way the turtle heads, at the limbs' tips or
    /// where it meets `symbol`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub leaves: Option<OrnamentSpec>,
}

/// ABOP's tropism: after each step the heading turns towards `direction`
/// by `elasticity` × |heading × direction|.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TropismSpec {
    /// In the turtle's frame: x right, y up, z towards the viewer.
    pub direction: [f64; 3],
    /// How strongly (−1–1).
    pub elasticity: f64,
}

/// Where a 3D drawing is seen from (orthographic): a preset by name, or a
/// direction with the page's up.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum View {
    /// `"front"` (the default), `"side"` or `"top"`.
    Named(NamedView),
    /// Looking along `direction` (the turtle's frame), with `up` up the
    /// page.
    Along {
        /// From the eye into the drawing.
        direction: [f64; 3],
        /// Which way is up on the page (not along `direction`).
        up: [f64; 3],
    },
}

impl Default for View {
    fn default() -> Self {
        View::Named(NamedView::Front)
    }
}

/// The named views.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum NamedView {
    /// From +z: x right, y up.
    Front,
    /// From +x: −z right, y up.
    Side,
    /// From +y down: x right, −z up the page.
    Top,
}

impl View {
    fn is_front(&self) -> bool {
        *self == View::Named(NamedView::Front)
    }

    /// The direction looked along and the page's up, both in the turtle's
    /// frame.
    pub fn axes(&self) -> ([f64; 3], [f64; 3]) {
        match self {
            View::Named(NamedView::Front) => ([0.0, 0.0, -1.0], [0.0, 1.0, 0.0]),
            View::Named(NamedView::Side) => ([-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            View::Named(NamedView::Top) => ([0.0, -1.0, 0.0], [0.0, 0.0, -1.0]),
            View::Along { direction, up } => (*direction, *up),
        }
    }
}

/// The Sketching L-System (source 003): the special branch `a` follows a stroke;
/// each time the stroke has grown by `module` mm the rule of `a` applies
/// once and every growing `c` is rewritten by its own rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SketchSpec {
    /// The stroke as points (mm, ≥ 2); see `smooth`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub points: Option<Points>,
    /// With `points`: a natural spline through them (default true), not
    /// straight lines.
    #[serde(default = "yes", skip_serializing_if = "Clone::clone")]
    pub smooth: bool,
    /// Or the first path of an SVG file (relative to the description), in
    /// its own millimetres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub svg: Option<String>,
    /// Or a region line of the scene's `[lines]` (the kimono flow),
    /// `"upper"` or `"lower"`, grown along from left to right.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub line: Option<FlowLine>,
    /// Stroke length per rule application, mm (0.1–1000, default 8).
    #[serde(default = "default_module")]
    pub module: f64,
    /// The rule of `a`, e.g. `a -> b(40) b(-40) c(30, 0, 0.7, 0.6) a` —
    /// each branch with its angle, roll (degrees), width and length ratios
    /// (default: the paper's `a -> b b c a`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub a: Option<String>,
    /// The rule of `c` (default: the paper's `c -> b b c`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub c: Option<String>,
    /// Width of the first `a`, mm (0–50, default 1.5); drawn by `style =
    /// "outline"`.
    #[serde(default = "default_sketch_width")]
    pub width: f64,
    /// Stop after this many module steps (default: as many as the stroke
    /// holds), to show the growth step by step.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps: Option<u32>,
}

/// The most rewriting steps of one system.
pub const MAX_LSYSTEM_ITERATIONS: u32 = 100;

fn default_angle() -> f64 {
    25.7
}

fn default_width_factor() -> f64 {
    0.7
}

fn default_module() -> f64 {
    8.0
}

fn default_sketch_width() -> f64 {
    1.5
}

fn one() -> f64 {
    1.0
}

fn yes() -> bool {
    true
}

fn stroke() -> LimbStyle {
    LimbStyle::Stroke
}

fn is_stroke(s: &LimbStyle) -> bool {
    *s == LimbStyle::Stroke
}

fn is_one(v: &f64) -> bool {
    *v == 1.0
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

fn is_zero_u32(v: &u32) -> bool {
    *v == 0
}

impl Default for LSystemSpec {
    fn default() -> Self {
        LSystemSpec {
            id: None,
            axiom: String::new(),
            rules: Vec::new(),
            iterations: 0,
            angle: default_angle(),
            constants: BTreeMap::new(),
            ignore: String::new(),
            step: 1.0,
            style: LimbStyle::Stroke,
            width: 1.0,
            width_factor: default_width_factor(),
            smooth: false,
            tropism: None,
            view: View::default(),
            at: Vec::new(),
            along: None,
            count: None,
            rotate: 0.0,
            fit: None,
            sketch: None,
            flowers: None,
            leaves: None,
        }
    }
}

impl LSystemSpec {
    /// The engine's system: axiom, rules, constants and ignored symbols
    /// parsed, with errors at `f.axiom`, `f.rules[i]`, `f.constants`.
    ///
    /// # Errors
    /// [`Error::Invalid`] with the column in the rule's text.
    pub fn system(&self, f: &str) -> Result<LSystem> {
        let rules: Vec<&str> = self.rules.iter().map(String::as_str).collect();
        LSystem::parse(&self.axiom, &rules, &self.constants, &self.ignore, f)
    }
}

impl SketchSpec {
    /// The sketch's rules, with errors at `f.a`, `f.c`, `f.module`.
    ///
    /// # Errors
    /// [`Error::Invalid`] with the column in the rule's text.
    pub fn rules(&self, f: &str) -> Result<SketchRules> {
        let mut rules = match (&self.a, &self.c) {
            (None, None) => SketchRules::paper(),
            (a, c) => {
                let paper = SketchRules::paper();
                let a = a.as_deref().map_or_else(|| paper.a_text(), str::to_string);
                let c = c.as_deref().map_or_else(|| paper.c_text(), str::to_string);
                SketchRules::parse(&a, &c, f)?
            }
        };
        rules.module = self.module;
        rules.width = self.width;
        rules.field = f.to_string();
        Ok(rules)
    }

    fn check(&self, f: &str) -> Result<()> {
        one_stroke(f, self.points.as_ref(), self.svg.as_deref(), self.line)?;
        range(&format!("{f}.module"), self.module, 0.1, 1000.0)?;
        range(&format!("{f}.width"), self.width, 0.0, 50.0)?;
        self.rules(f).map(|_| ())
    }
}

impl Family for LSystemSpec {
    #[cfg(feature = "studio")]
    fn gestures(&self) -> Option<&dyn crate::family::gesture::Gestures> {
        Some(self)
    }

    fn check(&self, f: &str) -> Result<()> {
        range(&format!("{f}.angle"), self.angle, 0.0, 360.0)?;
        range(&format!("{f}.step"), self.step, 0.001, 1000.0)?;
        range(&format!("{f}.width"), self.width, 0.0, 1000.0)?;
        range(&format!("{f}.width_factor"), self.width_factor, 0.0, 1.0)?;
        range(&format!("{f}.rotate"), self.rotate, -360.0, 360.0)?;
        if let Some(t) = &self.tropism {
            for (i, v) in t.direction.iter().enumerate() {
                range(&format!("{f}.tropism.direction[{i}]"), *v, -1e6, 1e6)?;
            }
            if t.direction.iter().all(|v| *v == 0.0) {
                return Err(Error::invalid(
                    format!("{f}.tropism.direction"),
                    "has no direction: give a vector that is not zero",
                ));
            }
            range(&format!("{f}.tropism.elasticity"), t.elasticity, -1.0, 1.0)?;
        }
        if let View::Along { direction, up } = self.view {
            let field = format!("{f}.view");
            for v in direction.iter().chain(&up) {
                range(&field, *v, -1e6, 1e6)?;
            }
            let [a, b, c] = direction;
            let [x, y, z] = up;
            let cross = [b * z - c * y, c * x - a * z, a * y - b * x];
            if cross.iter().all(|v| v.abs() < 1e-9) {
                return Err(Error::invalid(
                    field,
                    "`up` must not lie along `direction` (nor either be zero)",
                ));
            }
        }
        for (i, p) in self.at.iter().enumerate() {
            point(&format!("{f}.at[{i}]"), *p)?;
        }
        match (&self.along, self.count) {
            (Some(_), _) if !self.at.is_empty() => {
                return Err(Error::invalid(
                    format!("{f}.along"),
                    "and `at` both place the drawing: give one",
                ));
            }
            (Some(line), count) => {
                points(&format!("{f}.along"), line, 2)?;
                range(&format!("{f}.count"), count.unwrap_or(1), 1, 1000)?;
            }
            (None, Some(_)) => {
                return Err(Error::invalid(
                    format!("{f}.count"),
                    "spreads drawings along a line: give `along` too",
                ));
            }
            (None, None) => {}
        }
        if let Some([x0, y0, x1, y1]) = self.fit {
            let field = format!("{f}.fit");
            if !self.at.is_empty() || self.along.is_some() {
                return Err(Error::invalid(
                    field,
                    "is for a drawing fitted to the page; one placed by `at` or `along` is `step` mm per unit",
                ));
            }
            for v in [x0, y0, x1, y1] {
                range(&field, v, -1e6, 1e6)?;
            }
            if x1 <= x0 || y1 <= y0 {
                return Err(Error::invalid(
                    field,
                    "must be [x0, y0, x1, y1] with x1 > x0 and y1 > y0",
                ));
            }
        }
        for (name, ornament) in [("flowers", &self.flowers), ("leaves", &self.leaves)] {
            let Some(o) = ornament else { continue };
            let field = format!("{f}.{name}");
            o.check(&field)?;
            if o.symbol.is_some() && self.sketch.is_some() {
                return Err(Error::invalid(
                    format!("{field}.symbol"),
                    "a sketch has no symbols to meet: leave it out for the tips",
                ));
            }
        }
        if let Some(sketch) = &self.sketch {
            for (name, given) in [
                ("axiom", !self.axiom.is_empty()),
                ("rules", !self.rules.is_empty()),
                ("iterations", self.iterations > 0),
                ("at", !self.at.is_empty()),
                ("along", self.along.is_some()),
                ("fit", self.fit.is_some()),
            ] {
                if given {
                    return Err(Error::invalid(
                        format!("{f}.{name}"),
                        "is not used by a sketch, which grows along its stroke: leave it out",
                    ));
                }
            }
            return sketch.check(&format!("{f}.sketch"));
        }
        if self.axiom.trim().is_empty() {
            return Err(Error::invalid(
                format!("{f}.axiom"),
                "is empty: give the start word (e.g. \"F\"), or a `sketch`",
            ));
        }
        range(
            &format!("{f}.iterations"),
            self.iterations,
            0,
            MAX_LSYSTEM_ITERATIONS,
        )?;
        for (name, v) in &self.constants {
            range(&format!("{f}.constants.{name}"), *v, -1e12, 1e12)?;
        }
        self.system(f).map(|_| ())
    }

    fn motifs(&self) -> Vec<&MotifRef> {
        self.flowers
            .iter()
            .chain(&self.leaves)
            .flat_map(|o| &o.motifs)
            .collect()
    }

    fn path_files(&self) -> Vec<&str> {
        self.sketch
            .as_ref()
            .and_then(|s| s.svg.as_deref())
            .into_iter()
            .collect()
    }
}
