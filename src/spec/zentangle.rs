//! `[[layers.zentangle]]`: zentangle fills (SPEC §2) — the filling
//! process of the source paper in exact vector form: the white region
//! with the largest inscribed circle gets the procedure its seed names,
//! drawn only inside it; the drawing splits it into new regions with new
//! seeds; black regions are finished; `steps` times.
//!
//! The region is the page inside its margins unless a `[region]` names a
//! circle, a polygon, the closed shapes of an SVG file or the light parts
//! of a monochrome image (less `holes`).
//! `lines` split it before the loop starts, and `manual` steps choose the
//! procedure of the region under a point before the automatic ones.

use serde::{Deserialize, Serialize};

use super::layer::Family;
use super::region::RegionSpec;
use super::validate::{point, points, range};
use super::Points;
use crate::error::{Error, Result};

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
    /// The procedures the loop may use, by id (0–19, default all). A
    /// region whose seed names a procedure left out gets an allowed one
    /// from the same seed group, or any allowed one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
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
    /// deformation of SPEC §2.2, as a fraction of the paper's amount:
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
    /// Lines (polylines, mm, ≥ 2 points each) drawn first: they split the
    /// region as a pen line does.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub lines: Vec<Points>,
    /// Steps chosen by hand, run before the automatic ones.
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

/// One step chosen by hand: the white region under `at` gets `procedure`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ManualStep {
    /// A point of the region, mm.
    pub at: [f64; 2],
    /// The procedure (0–19).
    pub procedure: u32,
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

/// The most filling steps of one table.
pub const MAX_STEPS: u32 = 5000;

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
            lines: Vec::new(),
            manual: Vec::new(),
            black: Black::default(),
            hatch: default_hatch(),
        }
    }
}

impl Family for ZentangleSpec {
    fn check(&self, f: &str) -> Result<()> {
        self.region.check(&format!("{f}.region"))?;
        range(&format!("{f}.steps"), self.steps, 0, MAX_STEPS)?;
        if let Some(procedures) = &self.procedures {
            if procedures.is_empty() {
                return Err(Error::invalid(
                    format!("{f}.procedures"),
                    "allows nothing: list one or more ids 0–19, or leave it out for all",
                ));
            }
            for (i, &p) in procedures.iter().enumerate() {
                range(&format!("{f}.procedures[{i}]"), p, 0, PROCEDURES - 1)?;
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
        range(&format!("{f}.smallest"), self.smallest, 0.2, 100.0)?;
        range(&format!("{f}.wobble"), self.wobble, 0.0, 2.0)?;
        range(&format!("{f}.hand"), self.hand, 0.0, 2.0)?;
        range(&format!("{f}.retrace"), self.retrace, 0.0, 1.0)?;
        for (i, line) in self.lines.iter().enumerate() {
            points(&format!("{f}.lines[{i}]"), line, 2)?;
        }
        for (i, step) in self.manual.iter().enumerate() {
            point(&format!("{f}.manual[{i}].at"), step.at)?;
            range(
                &format!("{f}.manual[{i}].procedure"),
                step.procedure,
                0,
                PROCEDURES - 1,
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
        self.region.image.as_deref().into_iter().collect()
    }

    fn layers_read(&self) -> Vec<(&'static str, &str)> {
        self.region.layers_read()
    }
}
