//! The scene description: the file format (TOML, JSON also accepted).
//!
//! A description together with its `seed` fully determines the drawing. It
//! is parsed with `deny_unknown_fields` and then validated once, here, at the
//! boundary ([`SceneSpec::validate`]): every number is finite and inside its
//! documented range, every reference (pen numbers, override ids) exists.
//! Everything downstream trusts a validated description.
//!
//! Errors name the field path (`layers[0].trees[1].params.ratio1`), the
//! allowed range, and — for TOML — the line and column of the value.

pub mod field;
pub(crate) mod flora;
mod locate;
mod plot;
pub(crate) mod region;
pub mod seed;
mod stroke;
mod valid;
pub(crate) mod validate;

pub use crate::family::tables::*;
pub use crate::family::{LayerItem, LayerSpec, Table};
pub use flora::{
    AdjustSpec, Assign, BokashiSpec, BuiltMotif, FileMotif, FlowerSites, FlowerSpec, JointLeafSpec,
    LeafRingSpec, LeavesSpec, MainLargest, MotifKind, MotifRef, OrnamentSpec, PaintSpec, ShadeFrom,
};
pub use plot::{PlotSpec, Step};
pub use region::{CircleSpec, HoleSpec, RegionSpec};
pub(crate) use stroke::one_stroke;
pub use stroke::FlowLine;
pub use valid::ValidSpec;
pub use validate::FieldRange;

use serde::{Deserialize, Serialize};

use crate::error::{Error, LineCol, Result};
pub use crate::output::device::DeviceSpec;
use crate::scene::traditional::{self, Palette};
use crate::units::{Margins, Orientation, Page, PaperName};

/// The newest file format version this build reads and writes.
pub const FORMAT_VERSION: u32 = 1;

/// The largest `limits.max_paths`: a million short paths render in
/// about 1 GB; at the former 5 million a description could ask for more
/// memory than a desktop has.
pub const MAX_PATHS: usize = 1_000_000;

/// The largest `limits.max_segments`, also its default: a render holds
/// a few hundred bytes a segment at its peak (4.2 million segments of a
/// Hilbert curve took 1.5 GB in release). At the former 50 million a
/// million leaves on an L-system aborted past 11 GB.
pub const MAX_SEGMENTS: usize = crate::scene::PathBudget::DEFAULT_SEGMENT_LIMIT;

/// The most layers a description may have. Each is a group of its own
/// through every stage of the plot; 10,000 render in under a second,
/// 80,000 took 15 s and 1.1 GB (release, one short path each).
pub const MAX_LAYERS: usize = 10_000;

/// File format of a scene description.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// TOML (the primary format).
    Toml,
    /// JSON with the same structure.
    Json,
}

impl Format {
    /// Guesses the format from a file name: `.json` is JSON, everything else
    /// TOML.
    pub fn from_path(path: &std::path::Path) -> Format {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("json") => Format::Json,
            _ => Format::Toml,
        }
    }
}

/// A whole scene description.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSpec {
    /// File format version; must be 1.
    pub version: u32,
    /// A short title.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub title: Option<String>,
    /// One line saying what the design is (shown by `moyo templates`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// The seed of every random choice (0 ..= [`seed::MAX_SEED`], 2^63−1).
    #[serde(default, deserialize_with = "seed::deserialize")]
    pub seed: u64,
    /// Paper.
    #[serde(default)]
    pub page: PageSpec,
    /// Output settings.
    #[serde(default)]
    pub output: OutputSpec,
    /// Safety limits.
    #[serde(default)]
    pub limits: LimitsSpec,
    /// The palette whose colours `@1`–`@5` name in any colour field
    /// ([`crate::traditional::PALETTES`]); default: the first,
    /// `kaga-gosai`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub palette: Option<String>,
    /// Pens; default: pen 1, black, 0.3 mm.
    #[serde(default = "default_pens")]
    pub pens: Vec<PenSpec>,
    /// The overall flow: upper and lower region lines.
    #[serde(default)]
    pub lines: RegionLinesSpec,
    /// Depth layers; the first listed is in front unless `depth` says
    /// otherwise (at most [`MAX_LAYERS`]).
    #[serde(default)]
    pub layers: Vec<LayerSpec>,
    /// Plot pipeline stages applied before writing: the pen stage unless
    /// turned off, the others when asked for ([`PlotSpec`]).
    #[serde(default, skip_serializing_if = "PlotSpec::is_default")]
    pub plot: PlotSpec,
    /// Final adjustment of single trees, flowers and leaves by id.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub adjust: Vec<AdjustSpec>,
    /// The machine the design is plotted on ([`DeviceSpec`]): what `moyo
    /// render -o x.gcode` writes for, and what `moyo plot` finds again in
    /// the SVG.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub device: Option<DeviceSpec>,
}

/// Paper size, orientation and margins.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PageSpec {
    /// A named size or `[width, height]` in mm.
    #[serde(default = "default_paper")]
    pub size: PaperSize,
    /// `portrait` or `landscape`. Default: portrait for named sizes; an
    /// explicit `[width, height]` is taken as written.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orientation: Option<Orientation>,
    /// One margin for all sides, or `[top, right, bottom, left]`, in mm.
    #[serde(default = "default_margin")]
    pub margin: MarginSpec,
}

impl Default for PageSpec {
    fn default() -> Self {
        PageSpec {
            size: default_paper(),
            orientation: None,
            margin: default_margin(),
        }
    }
}

fn default_paper() -> PaperSize {
    PaperSize::Named(PaperName::A4)
}

fn default_margin() -> MarginSpec {
    MarginSpec::Uniform(10.0)
}

/// A named paper size or an explicit `[width, height]` in mm.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(
    untagged,
    expecting = "a paper name (A5, A4, A3, A2, letter, legal, tabloid) or [width, height] in mm"
)]
pub enum PaperSize {
    /// A5 … tabloid.
    Named(PaperName),
    /// `[width, height]` in mm.
    Custom([f64; 2]),
}

/// Margins: one number for all sides or `[top, right, bottom, left]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(
    untagged,
    expecting = "a margin in mm, or [top, right, bottom, left] in mm"
)]
pub enum MarginSpec {
    /// The same on all sides.
    Uniform(f64),
    /// `[top, right, bottom, left]`.
    Sides([f64; 4]),
}

impl PageSpec {
    /// The resolved page.
    pub fn page(&self) -> Page {
        let margins = match self.margin {
            MarginSpec::Uniform(m) => Margins::uniform(m),
            MarginSpec::Sides([top, right, bottom, left]) => Margins {
                top,
                right,
                bottom,
                left,
            },
        };
        match self.size {
            PaperSize::Named(n) => Page::named(n, self.orientation.unwrap_or_default(), margins),
            PaperSize::Custom([w, h]) => match self.orientation {
                Some(o) => Page::sized(w, h, o, margins),
                None => Page {
                    width: w,
                    height: h,
                    margins,
                },
            },
        }
    }
}

/// Output settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Decimal places of numbers in the SVG (0–8).
    #[serde(default = "default_precision")]
    pub precision: u8,
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            precision: default_precision(),
        }
    }
}

fn default_precision() -> u8 {
    3
}

/// Safety limits.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LimitsSpec {
    /// The most paths the scene may make (1 – [`MAX_PATHS`], default
    /// 200,000); generation stops with an error past it.
    #[serde(default = "default_max_paths")]
    pub max_paths: usize,
    /// The most path segments (lines and curves) all paths may hold
    /// (1 – [`MAX_SEGMENTS`], the default); generation stops with an error
    /// past it.
    #[serde(
        default = "default_max_segments",
        skip_serializing_if = "is_default_max_segments"
    )]
    pub max_segments: usize,
}

impl Default for LimitsSpec {
    fn default() -> Self {
        LimitsSpec {
            max_paths: default_max_paths(),
            max_segments: default_max_segments(),
        }
    }
}

fn default_max_paths() -> usize {
    crate::scene::PathBudget::DEFAULT_LIMIT
}

fn default_max_segments() -> usize {
    crate::scene::PathBudget::DEFAULT_SEGMENT_LIMIT
}

/// The default is left out of a written description, so descriptions
/// written before the limit existed read the same.
fn is_default_max_segments(n: &usize) -> bool {
    *n == default_max_segments()
}

/// A pen (one SVG layer per pen).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PenSpec {
    /// Pen number 1–999; the SVG layer label starts with it.
    pub number: u32,
    /// Short name, e.g. `black`.
    #[serde(default = "default_pen_name")]
    pub name: String,
    /// `#rrggbb`, `#rgb`, a CSS or traditional colour name, or a palette
    /// slot `@1`–`@5`.
    #[serde(default = "default_pen_color")]
    pub color: String,
    /// Line width in mm (0.01–20).
    #[serde(default = "default_pen_width")]
    pub width: f64,
}

fn default_pens() -> Vec<PenSpec> {
    vec![PenSpec {
        number: 1,
        name: default_pen_name(),
        color: default_pen_color(),
        width: default_pen_width(),
    }]
}

fn default_pen_name() -> String {
    "black".into()
}

fn default_pen_color() -> String {
    "black".into()
}

fn default_pen_width() -> f64 {
    0.3
}

/// A list of control points `[[x, y], …]` in mm.
pub type Points = Vec<[f64; 2]>;

/// The overall flow (docs/SPEC.md §1, "Flow"): lines bounding the pattern.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegionLinesSpec {
    /// Upper region line (上領域線): no tree vertex grows above it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub upper: Option<Points>,
    /// Lower region line (下領域線): trees growing downward stop below it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lower: Option<Points>,
}

impl SceneSpec {
    /// Parses and validates a description: the same as
    /// [`ValidSpec::parse`].
    ///
    /// # Errors
    /// As [`ValidSpec::parse`].
    pub fn parse(text: &str, format: Format) -> Result<ValidSpec> {
        ValidSpec::parse(text, format)
    }

    /// Checks every range and reference (see the module docs) and gives
    /// the description back as a [`ValidSpec`].
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the first field that is wrong.
    pub fn validate(self) -> Result<ValidSpec> {
        ValidSpec::new(self)
    }

    /// The resolved page.
    pub fn page(&self) -> Page {
        self.page.page()
    }

    /// The palette `@1`–`@5` refer to (an unknown name, which validation
    /// refuses, gives the default).
    pub fn palette(&self) -> &'static Palette {
        self.palette
            .as_deref()
            .and_then(traditional::palette)
            .unwrap_or(&traditional::PALETTES[0])
    }
}

/// The description in `text`, not yet validated.
fn parse_text(text: &str, format: Format) -> Result<SceneSpec> {
    match format {
        Format::Toml => parse_toml(text),
        Format::Json => parse_json(text),
    }
}

fn parse_toml(text: &str) -> Result<SceneSpec> {
    let de = toml::Deserializer::parse(text).map_err(|e| toml_error(text, None, &e))?;
    serde_path_to_error::deserialize(de).map_err(|e| {
        let field = e.path().to_string();
        toml_error(text, Some(field), e.inner())
    })
}

fn toml_error(text: &str, field: Option<String>, e: &toml::de::Error) -> Error {
    let at = e.span().map(|s| LineCol::of_offset(text, s.start));
    Error::Parse {
        at,
        field,
        message: e.message().trim().to_string(),
    }
}

fn parse_json(text: &str) -> Result<SceneSpec> {
    let mut de = serde_json::Deserializer::from_str(text);
    let spec = serde_path_to_error::deserialize(&mut de).map_err(|e| {
        let field = e.path().to_string();
        let inner = e.into_inner();
        Error::Parse {
            at: (inner.line() > 0).then(|| LineCol {
                line: inner.line(),
                column: inner.column(),
            }),
            field: Some(field),
            message: strip_json_position(&inner.to_string()),
        }
    })?;
    de.end().map_err(|e| Error::Parse {
        at: Some(LineCol {
            line: e.line(),
            column: e.column(),
        }),
        field: None,
        message: strip_json_position(&e.to_string()),
    })?;
    Ok(spec)
}

/// serde_json appends " at line L column C"; moyo prints the place itself.
fn strip_json_position(msg: &str) -> String {
    match msg.rfind(" at line ") {
        Some(i) => msg[..i].to_string(),
        None => msg.to_string(),
    }
}

#[cfg(test)]
mod tests;
