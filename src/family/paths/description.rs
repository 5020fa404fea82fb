//! `[[layers.paths]]`: the user's own paths — a point list, SVG path data
//! or the paths of an SVG file — placed, scaled, turned and repeated along
//! a line. Later families reuse it for strokes, supports and regions.
//!
//! Where copies stand: at `at`; or at `count` points (or every `spacing`
//! mm) along the line `along`, spread by arc length like trees on a centre
//! line; or, with neither, where the source lies (drawn as it is). Each
//! copy puts the source's `anchor` on its site, scales it by `scale` (and
//! to `width` mm wide when given), turns it by `rotate` degrees clockwise,
//! and along a line also by the line's direction when `orient = "line"`.

use kurbo::{BezPath, PathEl, Point};
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::family::Family;
use crate::spec::validate::{point, points, range};
use crate::spec::{PaintSpec, Points};
use crate::units::MAX_COORD;

/// A set of user paths on a layer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PathsSpec {
    /// Id of the set, unique in its layer (default `paths-K`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
    /// Source 1: a point list `[[x, y], …]` in mm (≥ 2 points).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub points: Option<Points>,
    /// With `points`: a natural spline through them instead of straight
    /// lines.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub smooth: bool,
    /// With `points`: close the line into a loop.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub closed: bool,
    /// Source 2: SVG path data in mm (`M 0 0 C 5 -5 10 5 15 0`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub d: Option<String>,
    /// Source 3: an SVG file, relative to the description; all its paths,
    /// in its own millimetres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub svg: Option<String>,
    /// One copy with its anchor here (mm).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<[f64; 2]>,
    /// Copies along this line (≥ 2 control points of a natural spline, mm).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub along: Option<Points>,
    /// With `along`: this many copies, evenly spread (1–10,000; default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub count: Option<u32>,
    /// With `along`: a copy every `spacing` mm instead (0.1–10,000).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spacing: Option<f64>,
    /// With `along`: whether copies turn with the line.
    #[serde(default, skip_serializing_if = "Orient::is_default")]
    pub orient: Orient,
    /// The point of the source that is put on each site.
    #[serde(default, skip_serializing_if = "Anchor::is_default")]
    pub anchor: Anchor,
    /// Turn every copy by this many degrees, clockwise (−360–360).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub rotate: f64,
    /// Scale every copy (0.001–1000).
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub scale: f64,
    /// Scale every copy to this width in mm (0.01–10,000), times `scale`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<f64>,
    /// Fill colour and hatching of closed paths.
    #[serde(default, skip_serializing_if = "PaintSpec::is_default")]
    pub paint: PaintSpec,
}

/// How copies along a line are turned.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Orient {
    /// The source's x axis follows the line's direction.
    #[default]
    Line,
    /// Upright on the page, whatever the line does.
    Page,
}

impl Orient {
    fn is_default(&self) -> bool {
        *self == Orient::default()
    }
}

/// The point of the source placed on a site.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Anchor {
    /// The centre of the source's bounding box.
    #[default]
    Centre,
    /// The source's own origin `(0, 0)`.
    Origin,
    /// The first point of the source.
    Start,
}

impl Anchor {
    fn is_default(&self) -> bool {
        *self == Anchor::default()
    }
}

fn one() -> f64 {
    1.0
}

fn is_one(v: &f64) -> bool {
    *v == 1.0
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// The most copies one set makes, with `count` or `spacing`.
pub const MAX_COPIES: usize = 10_000;

impl PathsSpec {
    /// The source path data parsed (`d`), if that is the source.
    ///
    /// # Errors
    /// [`Error::Invalid`] naming `field.d` when the data is not SVG path
    /// data or has a coordinate that is not finite or beyond ±MAX_COORD.
    pub fn parsed_d(&self, field: &str) -> Result<Option<BezPath>> {
        let Some(d) = &self.d else { return Ok(None) };
        let f = format!("{field}.d");
        let path = BezPath::from_svg(d)
            .map_err(|e| Error::invalid(&f, format!("is not SVG path data: {e}")))?;
        if path.elements().is_empty() {
            return Err(Error::invalid(&f, "draws nothing"));
        }
        let within = |p: &Point| p.x.abs() <= MAX_COORD && p.y.abs() <= MAX_COORD;
        if let Some(p) = path
            .elements()
            .iter()
            .flat_map(el_points)
            .find(|p| !within(p))
        {
            return Err(Error::invalid(
                &f,
                format!("point ({}, {}) is not within ±{MAX_COORD} mm", p.x, p.y),
            ));
        }
        Ok(Some(path))
    }
}

/// Every point of a path element, control points included.
fn el_points(el: &PathEl) -> Vec<Point> {
    match *el {
        PathEl::MoveTo(p) | PathEl::LineTo(p) => vec![p],
        PathEl::QuadTo(a, b) => vec![a, b],
        PathEl::CurveTo(a, b, c) => vec![a, b, c],
        PathEl::ClosePath => Vec::new(),
    }
}

impl Family for PathsSpec {
    fn check(&self, f: &str) -> Result<()> {
        let sources = [self.points.is_some(), self.d.is_some(), self.svg.is_some()];
        if sources.iter().filter(|s| **s).count() != 1 {
            return Err(Error::invalid(
                f,
                "give exactly one source: points = [[x, y], …], d = \"SVG path data\" or svg = \"file.svg\"",
            ));
        }
        if let Some(p) = &self.points {
            points(&format!("{f}.points"), p, 2)?;
        } else if self.smooth || self.closed {
            let key = if self.smooth { "smooth" } else { "closed" };
            return Err(Error::invalid(
                format!("{f}.{key}"),
                "applies to a point list (points = …) only",
            ));
        }
        self.parsed_d(f)?;
        if let Some(svg) = &self.svg {
            if svg.trim().is_empty() {
                return Err(Error::invalid(format!("{f}.svg"), "needs a file name"));
            }
        }
        if let Some(at) = self.at {
            point(&format!("{f}.at"), at)?;
            if self.along.is_some() {
                return Err(Error::invalid(
                    format!("{f}.at"),
                    "give either at (one copy) or along (copies along a line), not both",
                ));
            }
        }
        match &self.along {
            Some(line) => points(&format!("{f}.along"), line, 2)?,
            None => {
                for (key, set) in [
                    ("count", self.count.is_some()),
                    ("spacing", self.spacing.is_some()),
                ] {
                    if set {
                        return Err(Error::invalid(
                            format!("{f}.{key}"),
                            "applies to copies along a line (along = …) only",
                        ));
                    }
                }
            }
        }
        if let Some(n) = self.count {
            range(&format!("{f}.count"), n, 1, MAX_COPIES as u32)?;
            if self.spacing.is_some() {
                return Err(Error::invalid(
                    format!("{f}.spacing"),
                    "give either count or spacing, not both",
                ));
            }
        }
        if let Some(s) = self.spacing {
            range(&format!("{f}.spacing"), s, 0.1, 10_000.0)?;
        }
        range(&format!("{f}.rotate"), self.rotate, -360.0, 360.0)?;
        range(&format!("{f}.scale"), self.scale, 0.001, 1000.0)?;
        if let Some(w) = self.width {
            range(&format!("{f}.width"), w, 0.01, 10_000.0)?;
        }
        self.paint.check(&format!("{f}.paint"))
    }

    fn path_files(&self) -> Vec<&str> {
        self.svg.as_deref().into_iter().collect()
    }
}
