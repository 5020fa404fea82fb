//! Where a pattern lies (`[…region]`): the page inside its margins, a
//! circle, a polygon, the closed shapes of an SVG file, the light parts of
//! an image or the regions another layer drew, less holes. Shared by the
//! families that fill a region (voronoi, zentangle).

use serde::{Deserialize, Serialize};

use super::validate::{point, points, range};
use super::Points;
use crate::error::{Error, Result};

/// Where a pattern lies: at most one outer shape, less the holes.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegionSpec {
    /// A circle.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub circle: Option<CircleSpec>,
    /// A polygon through these points (≥ 3, mm).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub polygon: Option<Points>,
    /// The closed shapes of an SVG file, relative to the description, in
    /// its own millimetres; shapes inside shapes are holes (even-odd).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub svg: Option<String>,
    /// The light parts of a PNG or JPEG (darkness below one half),
    /// relative to the description, fitted to the area inside the
    /// margins, aspect kept, centred: a monochrome picture whose white
    /// parts are the regions to fill.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub image: Option<String>,
    /// The regions a layer before this one drew, by its name: the cells
    /// of its voronoi tables (the inset cells when it draws those, its
    /// Delaunay triangles when it draws only those) and the mask of its
    /// background. Each is a region of its own: a zentangle starts from
    /// them as from the sections of a string; a voronoi pattern fills
    /// them all.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub layer: Option<String>,
    /// With `layer`: only the regions holding one of these points (mm).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub at: Points,
    /// Shapes cut out of the region.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub holes: Vec<HoleSpec>,
}

impl RegionSpec {
    pub(crate) fn is_page(&self) -> bool {
        *self == RegionSpec::default()
    }

    /// The layer it takes its regions from, as [`super::Family::layers_read`]
    /// lists it for a table whose region is its field `region`.
    pub(crate) fn layers_read(&self) -> Vec<(&'static str, &str)> {
        self.layer
            .as_deref()
            .map(|name| ("region.layer", name))
            .into_iter()
            .collect()
    }
}

/// A circle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CircleSpec {
    /// Centre, mm.
    pub centre: [f64; 2],
    /// Radius, mm (0.1–100,000).
    pub radius: f64,
}

/// A shape cut out of a region: a circle or a polygon.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HoleSpec {
    /// A circle.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub circle: Option<CircleSpec>,
    /// A polygon (≥ 3 points, mm).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub polygon: Option<Points>,
}

impl CircleSpec {
    fn check(&self, f: &str) -> Result<()> {
        point(&format!("{f}.centre"), self.centre)?;
        range(&format!("{f}.radius"), self.radius, 0.1, 100_000.0)
    }
}

/// Checks that exactly one (`outer`: at most one) shape is given.
fn one_shape(f: &str, given: &[(&str, bool)], outer: bool) -> Result<()> {
    let n = given.iter().filter(|(_, set)| *set).count();
    let names: Vec<&str> = given.iter().map(|(k, _)| *k).collect();
    if n > 1 || (!outer && n == 0) {
        let what = if outer { "at most one" } else { "exactly one" };
        return Err(Error::invalid(
            f,
            format!("give {what} of {}", names.join(", ")),
        ));
    }
    Ok(())
}

impl RegionSpec {
    pub(crate) fn check(&self, f: &str) -> Result<()> {
        one_shape(
            f,
            &[
                ("circle", self.circle.is_some()),
                ("polygon", self.polygon.is_some()),
                ("svg", self.svg.is_some()),
                ("image", self.image.is_some()),
                ("layer", self.layer.is_some()),
            ],
            true,
        )?;
        if !self.at.is_empty() && self.layer.is_none() {
            return Err(Error::invalid(
                format!("{f}.at"),
                "picks regions of a `layer`: give the layer too",
            ));
        }
        for (i, &p) in self.at.iter().enumerate() {
            point(&format!("{f}.at[{i}]"), p)?;
        }
        if let Some(c) = &self.circle {
            c.check(&format!("{f}.circle"))?;
        }
        if let Some(p) = &self.polygon {
            points(&format!("{f}.polygon"), p, 3)?;
        }
        for (key, name) in [("svg", &self.svg), ("image", &self.image)] {
            if name.as_deref().is_some_and(|n| n.trim().is_empty()) {
                return Err(Error::invalid(format!("{f}.{key}"), "needs a file name"));
            }
        }
        if self.layer.as_deref().is_some_and(|n| n.trim().is_empty()) {
            return Err(Error::invalid(format!("{f}.layer"), "needs a layer's name"));
        }
        for (i, h) in self.holes.iter().enumerate() {
            let hf = format!("{f}.holes[{i}]");
            one_shape(
                &hf,
                &[
                    ("circle", h.circle.is_some()),
                    ("polygon", h.polygon.is_some()),
                ],
                false,
            )?;
            if let Some(c) = &h.circle {
                c.check(&format!("{hf}.circle"))?;
            }
            if let Some(p) = &h.polygon {
                points(&format!("{hf}.polygon"), p, 3)?;
            }
        }
        Ok(())
    }
}
