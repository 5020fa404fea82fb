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

/// The grounds, each a repeat that tiles the plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Ground {
    /// 青海波, blue ocean waves: rows of fans of concentric rings, each
    /// row half hidden by the row in front of it.
    Seigaiha,
    /// 麻の葉, hemp leaf: a triangle grid with a six-pointed star at every
    /// corner (each triangle's corners joined to its centre).
    Asanoha,
    /// 亀甲, tortoise shell: a honeycomb of hexagons, each with its inner
    /// outlines.
    Kikko,
    /// 七宝, seven treasures: circles overlapping by a quarter on a square
    /// grid.
    Shippo,
    /// 籠目, woven bamboo: three sets of straight lines, hexagons and
    /// triangles between them.
    Kagome,
    /// 鱗, scales: a triangle grid whose upward triangles are dark (hatched
    /// with the pen).
    Uroko,
    /// 矢絣, arrow feathers: columns of chevrons, each column half a
    /// chevron higher than the next.
    Yagasuri,
    /// 立涌, rising steam: wavy upright lines, each the mirror of the next,
    /// swelling and narrowing in turn.
    Tatewaku,
    /// 鮫小紋, shark skin: fans of concentric rings of fine dots, each row
    /// half hidden by the row in front, as seigaiha's rings are.
    #[serde(rename = "samekomon")]
    SameKomon,
}

impl Ground {
    /// Every ground, in the order of the enum.
    pub const ALL: [Ground; 9] = [
        Ground::Seigaiha,
        Ground::Asanoha,
        Ground::Kikko,
        Ground::Shippo,
        Ground::Kagome,
        Ground::Uroko,
        Ground::Yagasuri,
        Ground::Tatewaku,
        Ground::SameKomon,
    ];

    /// Its name in a description (`"seigaiha"`), and in the ids it draws.
    pub fn name(self) -> &'static str {
        match self {
            Ground::Seigaiha => "seigaiha",
            Ground::Asanoha => "asanoha",
            Ground::Kikko => "kikko",
            Ground::Shippo => "shippo",
            Ground::Kagome => "kagome",
            Ground::Uroko => "uroko",
            Ground::Yagasuri => "yagasuri",
            Ground::Tatewaku => "tatewaku",
            Ground::SameKomon => "samekomon",
        }
    }

    /// The `lines` it takes: `(least, most, default)`, or `None`.
    pub fn lines(self) -> Option<(u32, u32, u32)> {
        match self {
            Ground::Seigaiha => Some((1, 8, 4)),
            Ground::Kikko => Some((1, 3, 2)),
            Ground::SameKomon => Some((1, 8, 3)),
            Ground::Asanoha
            | Ground::Shippo
            | Ground::Kagome
            | Ground::Uroko
            | Ground::Yagasuri
            | Ground::Tatewaku => None,
        }
    }
}

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
