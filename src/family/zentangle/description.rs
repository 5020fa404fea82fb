//! `[[layers.zentangle]]`: zentangle fills (docs/SPEC.md §2) — the filling
//! process of the source paper in exact vector form: the white region
//! with the largest inscribed circle gets the procedure its seed names,
//! drawn only inside it; the drawing splits it into new regions with new
//! seeds; black regions are finished; `steps` times.
//!
//! The region is the page inside its margins unless a `[region]` names a
//! circle, a polygon, the closed shapes of an SVG file or the light parts
//! of a monochrome image (less `holes`).
//! `lines` split it before the loop starts, and `manual` steps choose the
//! procedure of the region under a point before the automatic ones (or,
//! with `after`, once they are done).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::family::Family;
use crate::geom::density::Formula;
use crate::spec::region::RegionSpec;
use crate::spec::validate::{point, points, range};
use crate::spec::Points;

/// A zentangle fill on a layer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ZentangleSpec {
    /// Id of the fill, unique in its layer (default `zentangle-K`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
    /// Where it fills (default: the page inside its margins).
    #[serde(default, skip_serializing_if = "RegionSpec::is_page")]
    pub region: RegionSpec,
    /// Filling steps after the manual ones: each draws one procedure into
    /// the white region with the largest inscribed circle (0–5,000,
    /// default 50). The loop ends early when no region is left that is
    /// wider than `smallest`.
    #[serde(default = "default_steps")]
    pub steps: u32,
    /// The procedures the loop may use, by id (0–19, default all of
    /// these) or, for the named tangles, by name (`"printemps"`, …: see
    /// [`TANGLES`]) or id (20–31). A region whose seed names a procedure
    /// left out gets an allowed one from the same seed group, or any
    /// allowed one.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "procedure_ids"
    )]
    pub procedures: Option<Vec<u32>>,
    /// The elements procedures may use, by the paper's names (`tr`, `sq`,
    /// `cl`, `mtr1`, …; default all). A procedure whose elements are all
    /// left out falls back to the allowed ones.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elements: Option<Vec<String>>,
    /// Element size as a fraction of the square root of the region's
    /// bounding-box area (the paper's self-similarity; 0.05–1, default
    /// 0.35).
    #[serde(default = "default_scale")]
    pub scale: f64,
    /// Regions whose largest inscribed circle is narrower than this
    /// radius (mm) are left white: too small to draw in (0.2–100, default
    /// 1.5).
    #[serde(default = "default_smallest")]
    pub smallest: f64,
    /// How much each element is deformed by hand (the free-form
    /// deformation of docs/SPEC.md §2.2, as a fraction of the paper's amount:
    /// control points move up to half a lattice cell × this; 0–2,
    /// default 0.6 — the paper's full amount turns circles into blobs).
    #[serde(default = "default_wobble")]
    pub wobble: f64,
    /// Per-stroke hand: every line is bent by its own smooth random
    /// deformation of up to this many mm, as a hand never draws the same
    /// curve twice (0–2, default 0: off). Beyond the paper, whose §5.6
    /// names the mechanical look of whole-element deformation.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub hand: f64,
    /// Line weight by hand: every line is drawn a second time, bent by up
    /// to this many mm, so it thickens unevenly as a pen going over it
    /// again does (0–1, default 0: once). Beyond the paper (§5.6: no
    /// line-weight variation).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub retrace: f64,
    /// How often the lattice patterns (MT, MS, MA: procedures 5, 6, 9,
    /// 10) lay their rows along the region's outline — rings that bend
    /// with it and go round its holes — instead of on a straight lattice
    /// (0–1, default 0: never). Beyond the paper (§5.6: patterns not
    /// mapped to the region's shape).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub follow: f64,
    /// How deep the plant branches of ML (procedure 7) branch: 0 is the
    /// paper's single stem with leaves; 1 adds side branches from every
    /// third node; 2 (the default) side branches of those (0–3). Beyond the
    /// paper (§5.6: no branching placement).
    #[serde(default = "default_branching")]
    pub branching: u32,
    /// Tone control: a target darkness over the region, so that dark
    /// parts get denser tangles and more black and light parts stay open
    /// (default: none, the paper's even tone). Beyond the paper (§5.6: the
    /// largest region is always filled next, no global contrast).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tone: Option<ToneSpec>,
    /// How sections are filled (default `"tangles"`): `"tangles"`, each
    /// section (a part of the region the string or the `lines` make) by
    /// one tangle, chosen by `weights` against its neighbours, whose
    /// elements may hold one nested tangle each (their seed group's, the
    /// same in all of them), as a tangler fills a tile; or `"sampler"`,
    /// the paper's loop, where every white piece left, however small,
    /// gets a pattern of its own (the paper's figures).
    #[serde(default, skip_serializing_if = "Look::is_tangles")]
    pub look: Look,
    /// With `look = "tangles"`: how likely each procedure is to fill a
    /// section, by id (`{ "16" = 3, "17" = 0 }`; ≥ 0, default 1 each).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub weights: BTreeMap<String, f64>,
    /// With `look = "tangles"`: neighbouring sections differ in tangle,
    /// dark beside light and organic beside geometric as far as the
    /// allowed tangles let them (default true).
    #[serde(default = "yes", skip_serializing_if = "is_true")]
    pub alternate: bool,
    /// How deep tangles nest: the elements of a section's tangle hold
    /// tangles of depth 1, theirs of depth 2, … (0–20; default: as deep as
    /// `smallest` lets them).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub depth: Option<u32>,
    /// The tile's border: the region's outline inked once, before
    /// anything else, with rounded corners if asked and bent by `hand`;
    /// everything else lies inside it (default: none, the region's edge is
    /// not drawn).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub border: Option<BorderSpec>,
    /// The string: curves that split the region into sections before the
    /// loop starts, as a tangler's pencil string does; no tangle crosses
    /// it. Inked with the layer's pen, or left out (to be drawn lightly by
    /// a layer of its own, in its own pen).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub string: Option<StringSpec>,
    /// The shortest piece of an element's line that may end on the edge
    /// of the region it is drawn in (a section's edge, the border, a
    /// string): shorter pieces left where a clipped element meets the edge
    /// are dropped, so no stubs or corner debris line the edges (mm, 0–20;
    /// default four pen widths with `look = "tangles"`, 0 with the
    /// sampler: every piece kept, as the paper does).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fragment: Option<f64>,
    /// Lines (polylines, mm, ≥ 2 points each) drawn first: they split the
    /// region as a pen line does.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub lines: Vec<Points>,
    /// Steps chosen by hand: run before the automatic ones, or after them
    /// with `after = true`, in the order written.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub manual: Vec<ManualStep>,
    /// How black regions are drawn (default `"hatch"`).
    #[serde(default, skip_serializing_if = "Black::is_hatch")]
    pub black: Black,
    /// With `black = "hatch"`: distance between hatch lines, mm (0.1–10,
    /// default 0.5).
    #[serde(default = "default_hatch")]
    pub hatch: f64,
}

/// How sections are filled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Look {
    /// One tangle a section, chosen against its neighbours.
    #[default]
    Tangles,
    /// The paper's loop: a pattern in every white piece.
    Sampler,
}

impl Look {
    fn is_tangles(&self) -> bool {
        *self == Look::Tangles
    }
}

/// The largest weight of a procedure.
const MAX_WEIGHT: f64 = 1000.0;

/// The deepest `depth`.
const MAX_DEPTH: u32 = 20;

/// The tile's border (`[…border]`).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BorderSpec {
    /// Corners rounded to this radius, mm (0–50, default 0: as the
    /// region has them); the region shrinks to the rounded outline.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub corner: f64,
}

/// The string (`[…string]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StringSpec {
    /// The curves, each through these points (mm, ≥ 2 points each).
    pub lines: Vec<Points>,
    /// Smooth curves (natural splines) through the points, as a pencil
    /// string is drawn (default), or straight lines between them.
    #[serde(default = "yes", skip_serializing_if = "is_true")]
    pub smooth: bool,
    /// Inked with the layer's pen (default) or left out: the sections
    /// still end a pen's width short of it on each side.
    #[serde(default = "yes", skip_serializing_if = "is_true")]
    pub ink: bool,
}

fn yes() -> bool {
    true
}

fn is_true(v: &bool) -> bool {
    *v
}

/// The largest corner radius of a border, mm.
const MAX_CORNER: f64 = 50.0;

/// The longest `fragment`, mm.
const MAX_FRAGMENT: f64 = 20.0;

/// A target darkness (0 white – 1 black) over the region, from a picture,
/// a formula or both multiplied. A region is filled in order of its
/// largest inscribed circle times its weight, `1 − contrast + contrast ×
/// darkness` at the circle's centre; it is left white once that product
/// falls below `smallest`; and its black elements and black-painted
/// grounds are `(1 − contrast + contrast × 2 × darkness)` times as likely
/// as the paper's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToneSpec {
    /// A PNG or JPEG (relative to the description), fitted to the
    /// region's bounding box, aspect kept, centred.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub image: Option<String>,
    /// A formula of the position: `x`, `y` in mm, `u`, `v` 0–1 across the
    /// region's bounding box, clamped to 0–1; e.g. `"v"` (dark at the
    /// bottom) or `"1 - 2 * abs(u - 0.5)"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub formula: Option<String>,
    /// How strongly the darkness steers the loop (0–1, default 0.9): 0
    /// not at all (the paper's order); 1 fully, so that where the target
    /// is white nothing is drawn.
    #[serde(default = "default_contrast")]
    pub contrast: f64,
}

fn default_branching() -> u32 {
    2
}

fn default_contrast() -> f64 {
    0.9
}

/// One step chosen by hand: the white region under `at` gets `procedure`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ManualStep {
    /// A point of the region, mm.
    pub at: [f64; 2],
    /// The procedure (0–19), or a named tangle by name or id (20–31).
    #[serde(deserialize_with = "procedure_id")]
    pub procedure: u32,
    /// Run after the automatic steps, in a region they left white (a
    /// touch-up of the finished tile; what the studio writes for a click
    /// on one), rather than before them (the default: the paper's manual
    /// mode, choosing from the blank tile on).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub after: bool,
}

/// How black regions are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Black {
    /// Hatched with the layer's pen (plottable), shown black in previews.
    #[default]
    Hatch,
    /// Filled: a closed outline only (for cutters, and for previews); the
    /// pen draws the outline.
    Solid,
}

impl Black {
    fn is_hatch(&self) -> bool {
        *self == Black::Hatch
    }
}

/// The number of drawing procedures of the paper's table 1 (ids 0–19).
pub const PROCEDURES: u32 = 20;

/// The named tangles (`tangle`), procedures `PROCEDURES + k` for the
/// k-th name.
pub const TANGLES: [&str; 12] = [
    "printemps",
    "crescent-moon",
    "hollibaugh",
    "florz",
    "knightsbridge",
    "nzeppel",
    "static",
    "tipple",
    "cadent",
    "betweed",
    "shattuck",
    "mooka",
];

/// The largest procedure id: the paper's and then the named tangles.
const LAST_PROCEDURE: u32 = PROCEDURES + TANGLES.len() as u32 - 1;

/// A procedure as a description writes it: an id, or a tangle's name.
#[derive(Deserialize)]
#[serde(untagged)]
enum ProcedureRef {
    Id(u32),
    Name(String),
}

impl ProcedureRef {
    fn id<E: serde::de::Error>(self) -> std::result::Result<u32, E> {
        match self {
            ProcedureRef::Id(id) => Ok(id),
            ProcedureRef::Name(name) => TANGLES
                .iter()
                .position(|t| *t == name)
                .map(|k| PROCEDURES + k as u32)
                .ok_or_else(|| {
                    E::custom(format!(
                        "unknown tangle `{name}` (known: {}; or a procedure id 0–{LAST_PROCEDURE})",
                        TANGLES.join(", ")
                    ))
                }),
        }
    }
}

fn procedure_id<'de, D: serde::Deserializer<'de>>(d: D) -> std::result::Result<u32, D::Error> {
    ProcedureRef::deserialize(d)?.id()
}

fn procedure_ids<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> std::result::Result<Option<Vec<u32>>, D::Error> {
    Option::<Vec<ProcedureRef>>::deserialize(d)?
        .map(|list| list.into_iter().map(ProcedureRef::id).collect())
        .transpose()
}

/// The most filling steps of one table.
pub const MAX_STEPS: u32 = 5000;

/// The most work the steps of one table may ask for, in steps ÷ scale³
/// (see `ZentangleSpec::check`), estimated before the loop starts: every
/// step at the default scale (0.35), 18 at the smallest (0.05). 5,000
/// steps at scale 0.05 ran past 300 s; 5,000 at 0.35 take 7 s (release,
/// A4, `smallest = 0.2`).
pub const MAX_STEP_WORK: f64 = 150_000.0;

/// The deepest ML plants branch (`branching`): beyond it the twigs are
/// shorter than their leaves.
const MAX_BRANCHING: u32 = 3;

/// The elements, by the paper's names: the basic shapes of its figure 4
/// and the compound ones of figure 7 (and `mtr2`, `msq3`, which its table
/// names).
pub const ELEMENTS: [&str; 26] = [
    "cr", "tr", "sq", "sp", "as", "cl", "c0", "c1", "c2", "c3", "c4", "st", "ss", "le", "mtr0",
    "mtr1", "mtr2", "ptr", "msq0", "msq1", "msq2", "msq3", "psq", "mcl0", "mcl1", "scl",
];

fn default_steps() -> u32 {
    50
}

fn default_scale() -> f64 {
    0.35
}

fn default_smallest() -> f64 {
    1.5
}

fn default_wobble() -> f64 {
    0.6
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

fn default_hatch() -> f64 {
    0.5
}

impl Default for ZentangleSpec {
    /// The page, 50 steps, every procedure and element, the defaults of
    /// each field.
    fn default() -> ZentangleSpec {
        ZentangleSpec {
            id: None,
            region: RegionSpec::default(),
            steps: default_steps(),
            procedures: None,
            elements: None,
            scale: default_scale(),
            smallest: default_smallest(),
            wobble: default_wobble(),
            hand: 0.0,
            retrace: 0.0,
            follow: 0.0,
            branching: default_branching(),
            tone: None,
            look: Look::default(),
            weights: BTreeMap::new(),
            alternate: true,
            depth: None,
            border: None,
            string: None,
            fragment: None,
            lines: Vec::new(),
            manual: Vec::new(),
            black: Black::default(),
            hatch: default_hatch(),
        }
    }
}

impl ZentangleSpec {
    /// The loop's cost, known before it starts: a step draws about
    /// 1/scale² elements (each is `scale` times the side of its region's
    /// bounding box), and its time grows as the 1.5th power of that
    /// (measured: 5,000 steps at 0.35, 500 at 0.1 and 125 at 0.05 take
    /// 60–75 µs a unit of steps ÷ scale³). Past [`MAX_STEP_WORK`],
    /// refused naming `steps`.
    fn check_work(&self, f: &str) -> Result<()> {
        let steps = self.steps as usize + self.manual.len();
        let work = steps as f64 / self.scale.powi(3);
        if work > MAX_STEP_WORK {
            return Err(Error::invalid(
                format!("{f}.steps"),
                format!(
                    "{steps} steps at scale {} are about {work:.0} units of work (steps ÷ \
                     scale³), more than {MAX_STEP_WORK}: fewer steps, or a larger scale \
                     (at {}, {} steps)",
                    self.scale,
                    self.scale,
                    (MAX_STEP_WORK * self.scale.powi(3)).floor()
                ),
            ));
        }
        Ok(())
    }
}

impl Family for ZentangleSpec {
    #[cfg(feature = "studio")]
    fn gestures(&self) -> Option<&dyn crate::family::gesture::Gestures> {
        Some(self)
    }

    fn check(&self, f: &str) -> Result<()> {
        self.region.check(&format!("{f}.region"))?;
        range(&format!("{f}.steps"), self.steps, 0, MAX_STEPS)?;
        if let Some(procedures) = &self.procedures {
            if procedures.is_empty() {
                return Err(Error::invalid(
                    format!("{f}.procedures"),
                    "allows nothing: list one or more ids 0–19 or tangle names, or leave it \
                     out for all",
                ));
            }
            for (i, &p) in procedures.iter().enumerate() {
                range(&format!("{f}.procedures[{i}]"), p, 0, LAST_PROCEDURE)?;
            }
        }
        if let Some(elements) = &self.elements {
            if elements.is_empty() {
                return Err(Error::invalid(
                    format!("{f}.elements"),
                    "allows nothing: list one or more elements, or leave it out for all",
                ));
            }
            for (i, e) in elements.iter().enumerate() {
                if !ELEMENTS.contains(&e.as_str()) {
                    return Err(Error::invalid(
                        format!("{f}.elements[{i}]"),
                        format!("unknown element `{e}` (known: {})", ELEMENTS.join(", ")),
                    ));
                }
            }
        }
        range(&format!("{f}.scale"), self.scale, 0.05, 1.0)?;
        self.check_work(f)?;
        range(&format!("{f}.smallest"), self.smallest, 0.2, 100.0)?;
        range(&format!("{f}.wobble"), self.wobble, 0.0, 2.0)?;
        range(&format!("{f}.hand"), self.hand, 0.0, 2.0)?;
        range(&format!("{f}.retrace"), self.retrace, 0.0, 1.0)?;
        range(&format!("{f}.follow"), self.follow, 0.0, 1.0)?;
        range(&format!("{f}.branching"), self.branching, 0, MAX_BRANCHING)?;
        if let Some(tone) = &self.tone {
            tone.check(&format!("{f}.tone"))?;
        }
        for (id, &w) in &self.weights {
            let field = format!("{f}.weights.{id}");
            match id.parse::<u32>() {
                Ok(p) if p < PROCEDURES => {}
                _ => {
                    return Err(Error::invalid(
                        field,
                        format!("names no procedure: keys are ids 0–{}", PROCEDURES - 1),
                    ))
                }
            }
            range(&field, w, 0.0, MAX_WEIGHT)?;
        }
        if let Some(depth) = self.depth {
            range(&format!("{f}.depth"), depth, 0, MAX_DEPTH)?;
        }
        if let Some(border) = &self.border {
            range(&format!("{f}.border.corner"), border.corner, 0.0, MAX_CORNER)?;
        }
        if let Some(string) = &self.string {
            if string.lines.is_empty() {
                return Err(Error::invalid(
                    format!("{f}.string.lines"),
                    "needs one or more curves, or leave the string out",
                ));
            }
            for (i, line) in string.lines.iter().enumerate() {
                points(&format!("{f}.string.lines[{i}]"), line, 2)?;
            }
        }
        if let Some(fragment) = self.fragment {
            range(&format!("{f}.fragment"), fragment, 0.0, MAX_FRAGMENT)?;
        }
        for (i, line) in self.lines.iter().enumerate() {
            points(&format!("{f}.lines[{i}]"), line, 2)?;
        }
        for (i, step) in self.manual.iter().enumerate() {
            point(&format!("{f}.manual[{i}].at"), step.at)?;
            range(
                &format!("{f}.manual[{i}].procedure"),
                step.procedure,
                0,
                LAST_PROCEDURE,
            )?;
        }
        range(&format!("{f}.hatch"), self.hatch, 0.1, 10.0)
    }

    /// One unit per step (manual and automatic).
    fn work(&self) -> usize {
        self.steps as usize + self.manual.len() + 1
    }

    fn path_files(&self) -> Vec<&str> {
        self.region.svg.as_deref().into_iter().collect()
    }

    fn image_files(&self) -> Vec<&str> {
        self.region
            .image
            .as_deref()
            .into_iter()
            .chain(self.tone.as_ref().and_then(|t| t.image.as_deref()))
            .collect()
    }

    fn layers_read(&self) -> Vec<(&'static str, &str)> {
        self.region.layers_read()
    }
}

impl ToneSpec {
    fn check(&self, f: &str) -> Result<()> {
        if self.image.is_none() && self.formula.is_none() {
            return Err(Error::invalid(
                f,
                "needs an `image`, a `formula` or both: the darkness to aim at",
            ));
        }
        if self.image.as_deref().is_some_and(|i| i.trim().is_empty()) {
            return Err(Error::invalid(format!("{f}.image"), "needs a file name"));
        }
        if let Some(text) = &self.formula {
            Formula::parse(text).map_err(|e| match e {
                Error::Invalid { message, .. } => Error::invalid(format!("{f}.formula"), message),
                other => other,
            })?;
        }
        range(&format!("{f}.contrast"), self.contrast, 0.0, 1.0)
    }
}
