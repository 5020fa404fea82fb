//! `[[layers.wagara]]`: a traditional Japanese ground (和柄) filling a
//! region as one seamless repeat: seigaiha, asanoha, kikkō, shippō,
//! kagome, uroko, yagasuri, tatewaku or same-komon, at a scale, turned by
//! an angle, shifted by an offset.
//!
//! The region is the page inside its margins unless a `[region]` names a
//! circle, a polygon, an SVG's shapes, an image's light parts or the
//! regions of an earlier layer (a background's mask, Voronoi cells).

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::family::Family;
use crate::spec::region::RegionSpec;
use crate::spec::validate::{point, range};

/// A ground pattern on a layer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WagaraSpec {
    /// Id of the ground, unique in its layer (default `wagara-K`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
    /// Which ground.
    pub pattern: Ground,
    /// The size of one repeat, mm (1–200, default 10): a seigaiha or
    /// same-komon fan's radius, an asanoha or uroko triangle's side, a
    /// kikkō hexagon's radius, a shippō circle's radius, the spacing of
    /// kagome's lines, the width of a yagasuri column or of a tatewaku
    /// wave.
    #[serde(default = "default_scale")]
    pub scale: f64,
    /// Lines of one motif: a seigaiha fan's rings (1–8, default 4), a
    /// same-komon fan's rings of dots (1–8, default 3), a kikkō hexagon's
    /// outlines, the cell and those inside it (1–3, default 2). The other
    /// grounds take none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lines: Option<u32>,
    /// Uroko: the distance between the hatch lines that ink its dark
    /// triangles, mm (0.1–10, default 0.5). The other grounds take none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hatch: Option<f64>,
    /// The repeat turned clockwise by this many degrees (−180–180,
    /// default 0) about the region's centre.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub angle: f64,
    /// The repeat shifted by `[dx, dy]` mm from the region's centre
    /// (default none).
    #[serde(default, skip_serializing_if = "is_origin")]
    pub offset: [f64; 2],
    /// Draw the region's outline too (default false): the ground's edge
    /// inked, as a cloud or a panel holding it is.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub outline: bool,
    /// Where the ground lies (default: the page inside its margins).
    #[serde(default, skip_serializing_if = "RegionSpec::is_page")]
    pub region: RegionSpec,
}

pub use crate::motif::ground::Ground;



fn default_scale() -> f64 {
    10.0
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

fn is_origin(v: &[f64; 2]) -> bool {
    *v == [0.0, 0.0]
}

impl WagaraSpec {
    /// The lines of one motif, as given or by default (1 for the grounds
    /// that take none).
    pub fn line_count(&self) -> u32 {
        self.pattern
            .lines()
            .map_or(1, |(_, _, default)| self.lines.unwrap_or(default))
    }

    /// The hatch spacing of the dark parts, as given or by default, mm.
    pub fn hatch_spacing(&self) -> f64 {
        self.hatch.unwrap_or(0.5)
    }
}

impl Family for WagaraSpec {
    fn check(&self, f: &str) -> Result<()> {
        range(&format!("{f}.scale"), self.scale, 1.0, 200.0)?;
        match (self.pattern.lines(), self.lines) {
            (Some((least, most, _)), Some(n)) => range(&format!("{f}.lines"), n, least, most)?,
            (None, Some(_)) => {
                return Err(Error::invalid(
                    format!("{f}.lines"),
                    format!(
                        "{} takes no `lines` (only seigaiha, kikko and samekomon do)",
                        self.pattern.name()
                    ),
                ));
            }
            (_, None) => {}
        }
        match (self.pattern, self.hatch) {
            (Ground::Uroko, Some(h)) => range(&format!("{f}.hatch"), h, 0.1, 10.0)?,
            (_, Some(_)) => {
                return Err(Error::invalid(
                    format!("{f}.hatch"),
                    format!(
                        "{} takes no `hatch` (only uroko has dark parts)",
                        self.pattern.name()
                    ),
                ));
            }
            (_, None) => {}
        }
        range(&format!("{f}.angle"), self.angle, -180.0, 180.0)?;
        point(&format!("{f}.offset"), self.offset)?;
        self.region.check(&format!("{f}.region"))
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
