//! `[[layers.voronoi]]`: Voronoi and Delaunay patterns inside a region
//! (docs/SPEC.md §3) — cell outlines, Delaunay edges, inset cells (stained glass,
//! cracked earth), the sites as dots, and one pen-down tour through them.
//!
//! The region is the page inside its margins unless a `[region]` names a
//! circle, a polygon or the closed shapes of an SVG file, less any
//! `holes`. Sites are spread by `sites.distribution`, or given by hand as
//! `sites.points`, and then moved towards their cells' centroids `relax`
//! times (Lloyd).

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::error::{Error, Result};
use crate::family::Family;
use crate::geom::density::Formula;
use crate::spec::region::RegionSpec;
use crate::spec::validate::{point, range};
use crate::spec::Points;

/// A Voronoi/Delaunay pattern on a layer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VoronoiSpec {
    /// Id of the pattern, unique in its layer (default `voronoi-K`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
    /// Where the pattern lies (default: the page inside its margins).
    #[serde(default, skip_serializing_if = "RegionSpec::is_page")]
    pub region: RegionSpec,
    /// How the sites are spread, or where they are given.
    #[serde(default)]
    pub sites: SitesSpec,
    /// Relaxation: at most this many times each site moves to its cell's
    /// centroid, evening out the cells (0–1000, default 0; see
    /// `relaxation` and `converge`).
    #[serde(default, skip_serializing_if = "is_zero_u32")]
    pub relax: u32,
    /// How the sites relax (default `"lloyd"`); `"lbg"` (weighted
    /// Linde-Buzo-Gray) also splits and removes sites until each cell
    /// holds one site's worth of density, so the count follows the
    /// density: `sites.spacing` apart where it is 1.
    #[serde(default, skip_serializing_if = "RelaxationMethod::is_lloyd")]
    pub relaxation: RelaxationMethod,
    /// Stop relaxing once a step moves the sites less than this on
    /// average, mm (0.00001–100; default: run all `relax` steps, or with
    /// `"lbg"` until no site splits or goes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub converge: Option<f64>,
    /// What is drawn, in this order (default `["cells"]`).
    #[serde(default = "default_draw")]
    pub draw: Vec<Draw>,
    /// With `"inset"`: how far each cell's outline moves in, mm (0.01–100,
    /// default 1). Cells narrower than twice this vanish.
    #[serde(default = "default_inset")]
    pub inset: f64,
    /// With `"inset"`: radius of the inset cells' rounded corners, mm (0–50,
    /// default 0, sharp). Cells narrower than twice `inset + round` vanish.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub round: f64,
    /// With `"sites"`: radius of the dot of ink at each site, mm (0.05–50,
    /// default 0.3): a tap of the pen when the pen is that wide, else a rim
    /// and a spiral that fill it.
    #[serde(default = "default_dot")]
    pub dot: f64,
    /// With `"cells"` and `"delaunay"`: draw the region's outline too
    /// (default true). Off when another pen already draws that outline —
    /// the shapes `moyo fill` fills — so that it is not drawn twice.
    #[serde(default = "default_outline", skip_serializing_if = "is_true")]
    pub outline: bool,
    /// With `"sites"` and sites weighted by `sites.image` or
    /// `sites.density`: each dot's radius follows the density at its site,
    /// from the first radius where the density is 0 to the second where
    /// it is 1, mm (each 0.05–50, the first no larger), as StippleGen
    /// sizes its stipples. Default: every dot `dot`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dot_range: Option<[f64; 2]>,
    /// With `"cracks"`: the width of the first crack and the narrowest
    /// any crack gets, mm (each 0.05–20, the first no smaller; default
    /// `[1.6, 0.7]`); each generation of cracks is 0.8 of the one before.
    #[serde(default = "default_crack")]
    pub crack: [f64; 2],
}

/// One kind of line a Voronoi pattern draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Draw {
    /// The cell outlines, clipped to the region; shared edges drawn once.
    Cells,
    /// The constrained Delaunay triangulation of the sites and the
    /// region's outline: no edge leaves the region, the triangles reach
    /// its border.
    Delaunay,
    /// Each cell shrunk by `inset` (and rounded by `round`): stained glass,
    /// cracked earth.
    Inset,
    /// A dot of radius `dot` at each site: stippling.
    Sites,
    /// One pen-down line through the sites of each connected part of the
    /// region (nearest neighbour, then 2-opt).
    Tour,
    /// Mud cracks: the region split again and again, largest piece first,
    /// by curved cracks that end on older ones (T-junctions), narrower
    /// each generation and tapering; drawn as the outlines of the plates
    /// between them, about `sites.spacing` across (the sites themselves
    /// take no part).
    Cracks,
}

/// How sites relax.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RelaxationMethod {
    /// Lloyd: each site moves to its cell's centroid, weighted by the
    /// density when there is one (weighted Voronoi stippling, Secord
    /// 2002); the count stays.
    #[default]
    Lloyd,
    /// Weighted Linde-Buzo-Gray (Deussen et al. 2017): as Lloyd, and a
    /// site whose cell holds much less than one site's worth of density
    /// goes, one whose cell holds much more splits in two.
    Lbg,
}

impl RelaxationMethod {
    fn is_lloyd(&self) -> bool {
        *self == RelaxationMethod::Lloyd
    }
}

/// How sites are spread over the region, or where they are.
///
/// Either a `distribution` spreads them (with `count`, `spacing`,
/// `jitter`, weighed by `image` and `density`), or `points` gives them by
/// hand. [`SitesSpec::default`] is the `poisson` distribution, as an empty
/// `[layers.voronoi.sites]` is; a table given in code with `points` sets
/// `distribution` to `None` (see [`VoronoiSpec::pinned`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
// Derived into inherent functions, wrapped by the impls below: parsing
// reads a missing `distribution` as `poisson` unless `points` is given.
#[serde(remote = "Self", deny_unknown_fields)]
pub struct SitesSpec {
    /// The distribution (default `"poisson"`; not with `points`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distribution: Option<Distribution>,
    /// With `"uniform"`: how many sites (1–1,000,000).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub count: Option<u32>,
    /// With `"grid"` and `"poisson"`: the distance between sites, mm
    /// (0.1–10,000; default 10). With `points`, only when the sites relax
    /// with `"lbg"` (the distance it aims at where the density is 1) or
    /// weighted by `image` or `density` (half of it is the finest scale
    /// the density is weighed on; default: the spacing the points would
    /// have evenly spread, √(area ÷ their number)).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spacing: Option<f64>,
    /// With `"grid"`: how far each site may move from its grid point, as a
    /// fraction of half the spacing (0–1, default 0.5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub jitter: Option<f64>,
    /// A PNG or JPEG file (relative to the description) whose dark parts
    /// get more sites, fitted to the region's bounding box, aspect kept,
    /// centred: `uniform` sites fall in proportion to darkness, `grid`
    /// points are kept in proportion to it, `poisson` spacing grows to
    /// `spacing × 10` where the image is white; and Lloyd steps weigh each
    /// cell by darkness (weighted Voronoi stippling, Secord 2002). With
    /// `points` it only weighs the steps, so it needs `relax`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub image: Option<String>,
    /// Density as a formula of the position, used as `image` is (and
    /// multiplied with it when both are given): `x`, `y` in mm, `u`, `v`
    /// 0–1 across the region's bounding box, clamped to 0–1; e.g.
    /// `"1 - v"` or `"0.5 + 0.5 * sin(x / 8)"` (see
    /// [`crate::geom::density::Formula`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density: Option<String>,
    /// With `image`: how much of the weight comes from the image's edges
    /// (where it changes: an eye, a mouth, a face's outline) rather than
    /// its darkness, 0–1 (default 0). Sites then gather on edges and
    /// features, so a low-poly mesh keeps them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edges: Option<f64>,
    /// With `"rose"`: how many cells the first ring holds; every ring
    /// holds a multiple, so the window turns into itself by 360° ÷
    /// `petals` (3–64, default 12).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub petals: Option<u32>,
    /// With `"rose"`: the width of the rings of stone tracery cut from the
    /// region where the cells' count doubles, mm (0–20, default 0: none).
    /// Kept with `points` pinned from a rose, as the window's frame.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tracery: Option<f64>,
    /// The sites given by hand, `[[x, y], …]` in mm from the top left
    /// corner inside the margins, as every point of a description (1 to
    /// 1,000,000 points, each within ±100,000 mm); instead of
    /// `distribution`, `count` and `jitter`, and of `spacing` unless
    /// relaxation reads it (see there). They are the sites
    /// exactly, in their order (the dots' ids `site-<i>` count them), less
    /// those outside the region, which are left out (a dragged site may
    /// land there; at least one must be inside), and less repeats: a point
    /// within a millionth of a millimetre of an earlier one is the same
    /// site ([`crate::geom::voronoi::MERGE_DISTANCE`]). `relax` moves them
    /// as it moves spread sites. (`moyo fill` spreads its sites from its
    /// options and takes none given.)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub points: Option<Points>,
}

impl Default for SitesSpec {
    /// The `poisson` distribution with every other key left out.
    fn default() -> SitesSpec {
        SitesSpec {
            distribution: Some(Distribution::Poisson),
            count: None,
            spacing: None,
            jitter: None,
            image: None,
            density: None,
            edges: None,
            petals: None,
            tracery: None,
            points: None,
        }
    }
}

impl<'de> Deserialize<'de> for SitesSpec {
    /// A missing `distribution` is `poisson` unless `points` is given: a
    /// description without points reads as it always has (and writes back
    /// with `distribution = "poisson"`), while one with points keeps
    /// `None`, so that a distribution given beside them is refused.
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> std::result::Result<Self, D::Error> {
        let mut sites = SitesSpec::deserialize(deserializer)?;
        if sites.points.is_none() && sites.distribution.is_none() {
            sites.distribution = Some(Distribution::Poisson);
        }
        Ok(sites)
    }
}

impl Serialize for SitesSpec {
    fn serialize<S: Serializer>(&self, serializer: S) -> std::result::Result<S::Ok, S::Error> {
        SitesSpec::serialize(self, serializer)
    }
}

/// A distribution of sites.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Distribution {
    /// Independent uniform points: clumps and gaps.
    Uniform,
    /// A square grid, each point moved at random by up to `jitter`.
    Grid,
    /// Poisson-disk: no two sites closer than `spacing`, no gap wider than
    /// twice it. Even without looking regular.
    #[default]
    Poisson,
    /// A rose window: rings of sites about the centre of the region's
    /// bounds, `petals` in the first, the first ring's cells about
    /// `spacing` wide, the count doubling outwards (with `tracery` rings
    /// there); radially symmetric, ordered by ring.
    Rose,
}

/// The most relaxation steps.
pub const MAX_RELAX: u32 = 1000;

/// The most sites one pattern may have.
pub const MAX_SITES: usize = 1_000_000;

/// Distance between sites when `spacing` is not given, mm.
pub const DEFAULT_SPACING: f64 = 10.0;

fn default_draw() -> Vec<Draw> {
    vec![Draw::Cells]
}

fn default_inset() -> f64 {
    1.0
}

/// The widths of the first and the narrowest crack, mm, when not given.
pub const DEFAULT_CRACK: [f64; 2] = [1.6, 0.7];

fn default_crack() -> [f64; 2] {
    DEFAULT_CRACK
}

fn default_dot() -> f64 {
    0.3
}

fn default_outline() -> bool {
    true
}

fn is_true(v: &bool) -> bool {
    *v
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

fn is_zero_u32(v: &u32) -> bool {
    *v == 0
}

impl SitesSpec {
    /// The spacing of `grid` and `poisson` sites, mm.
    pub fn spacing(&self) -> f64 {
        self.spacing.unwrap_or(DEFAULT_SPACING)
    }

    /// The petals of a `rose`.
    pub fn petals(&self) -> u32 {
        self.petals.unwrap_or(12)
    }

    /// The jitter of `grid` sites (0–1).
    pub fn jitter(&self) -> f64 {
        self.jitter.unwrap_or(0.5)
    }

    /// Whether `image` or `density` is given.
    pub fn is_weighted(&self) -> bool {
        self.image.is_some() || self.density.is_some()
    }

    /// The distribution that spreads the sites (`poisson` when none is
    /// given; with `points` there is none to speak of).
    pub fn distribution(&self) -> Distribution {
        self.distribution.unwrap_or_default()
    }

    /// `relax`: the most relaxation steps; `lbg`: the sites relax by
    /// weighted Linde-Buzo-Gray, whose target spacing is `spacing`
    /// whatever the distribution.
    fn check(&self, f: &str, relax: u32, lbg: bool) -> Result<()> {
        match &self.points {
            Some(points) => self.check_given(f, points, relax, lbg)?,
            None => self.check_spread(f, lbg)?,
        }
        if let Some(n) = self.count {
            range(&format!("{f}.count"), n, 1, MAX_SITES as u32)?;
        }
        if let Some(s) = self.spacing {
            range(&format!("{f}.spacing"), s, 0.1, 10_000.0)?;
        }
        if let Some(j) = self.jitter {
            range(&format!("{f}.jitter"), j, 0.0, 1.0)?;
        }
        if let Some(n) = self.petals {
            range(&format!("{f}.petals"), n, 3, 64)?;
        }
        if let Some(t) = self.tracery {
            range(&format!("{f}.tracery"), t, 0.0, 20.0)?;
        }
        if let Some(e) = self.edges {
            range(&format!("{f}.edges"), e, 0.0, 1.0)?;
            if self.image.is_none() {
                return Err(Error::invalid(
                    format!("{f}.edges"),
                    "weighs the image's edges: give sites.image",
                ));
            }
        }
        if self.image.as_deref().is_some_and(|i| i.trim().is_empty()) {
            return Err(Error::invalid(format!("{f}.image"), "needs a file name"));
        }
        if let Some(text) = &self.density {
            Formula::parse(text).map_err(|e| match e {
                Error::Invalid { message, .. } => Error::invalid(format!("{f}.density"), message),
                other => other,
            })?;
        }
        Ok(())
    }

    /// Sites given by hand: the keys that spread sites do not apply, and
    /// those that weigh or scale relaxation only when the sites relax.
    fn check_given(&self, f: &str, points: &[[f64; 2]], relax: u32, lbg: bool) -> Result<()> {
        for (key, set) in [
            ("distribution", self.distribution.is_some()),
            ("count", self.count.is_some()),
            ("jitter", self.jitter.is_some()),
        ] {
            if set {
                return Err(Error::invalid(
                    format!("{f}.{key}"),
                    "does not apply to given points: they are the sites (give one or the other)",
                ));
            }
        }
        // A rose's tracery rings are placed by its petals and spacing,
        // sites given or not.
        let rose = self.tracery.is_some();
        for (key, set) in [
            ("spacing", self.spacing.is_some() && !rose),
            ("image", self.image.is_some()),
            ("density", self.density.is_some()),
        ] {
            if set && relax == 0 {
                return Err(Error::invalid(
                    format!("{f}.{key}"),
                    "does nothing to given points without relax steps (give relax = 1–1000)",
                ));
            }
        }
        if self.spacing.is_some() && !lbg && !self.is_weighted() && !rose {
            return Err(Error::invalid(
                format!("{f}.spacing"),
                "does not apply to given points relaxed by unweighted lloyd steps (it takes \
                 relaxation = \"lbg\", or an image or a density)",
            ));
        }
        let field = format!("{f}.points");
        if points.is_empty() {
            return Err(Error::invalid(field, "needs at least one point [x, y]"));
        }
        if points.len() > MAX_SITES {
            return Err(Error::invalid(
                field,
                format!("at most {MAX_SITES} sites, got {}", points.len()),
            ));
        }
        for (i, p) in points.iter().enumerate() {
            point(&format!("{field}[{i}]"), *p)?;
        }
        Ok(())
    }

    /// Sites spread by a distribution: the keys it takes.
    fn check_spread(&self, f: &str, lbg: bool) -> Result<()> {
        let distribution = self.distribution();
        let allowed: &[&str] = match (distribution, lbg) {
            (Distribution::Uniform, false) => &["count"],
            (Distribution::Uniform, true) => &["count", "spacing"],
            (Distribution::Grid, _) => &["spacing", "jitter"],
            (Distribution::Poisson, _) => &["spacing"],
            (Distribution::Rose, _) => &["spacing", "petals", "tracery"],
        };
        for (key, set) in [
            ("count", self.count.is_some()),
            ("spacing", self.spacing.is_some()),
            ("jitter", self.jitter.is_some()),
            ("petals", self.petals.is_some()),
            ("tracery", self.tracery.is_some()),
        ] {
            if set && !allowed.contains(&key) {
                return Err(Error::invalid(
                    format!("{f}.{key}"),
                    format!(
                        "does not apply to the {} distribution{} (it takes {})",
                        distribution.name(),
                        if lbg { "" } else { " with lloyd relaxation" },
                        allowed.join(", ")
                    ),
                ));
            }
        }
        if distribution == Distribution::Uniform && self.count.is_none() {
            return Err(Error::invalid(
                format!("{f}.count"),
                "the uniform distribution needs a count (1–1,000,000)",
            ));
        }
        Ok(())
    }
}

impl Distribution {
    fn name(self) -> &'static str {
        match self {
            Distribution::Uniform => "uniform",
            Distribution::Grid => "grid",
            Distribution::Poisson => "poisson",
            Distribution::Rose => "rose",
        }
    }
}

impl VoronoiSpec {
    /// This table with `points` as its sites, given by hand, and nothing
    /// else changed that it draws: when `points` are the sites it spreads
    /// ([`crate::project::voronoi_sites`]), the pinned table draws the
    /// same lines, byte for byte. The keys that spread sites go
    /// (`distribution`, `count`, `jitter`); `image` and `density` stay
    /// when the sites relax, and `spacing` (the default written out,
    /// where the distribution used it) when relaxation reads it.
    ///
    /// ```
    /// use moyo::spec::{Distribution, VoronoiSpec};
    /// let spec = moyo::templates::get("voronoi-stained-glass")?.spec()?;
    /// let table = &spec.layers[0].voronoi[0];
    /// let pinned = table.pinned(vec![[10.0, 20.0], [30.0, 40.0]]);
    /// assert_eq!(pinned.sites.points.as_deref(), Some(&[[10.0, 20.0], [30.0, 40.0]][..]));
    /// assert_eq!((pinned.sites.distribution, pinned.relax), (None, table.relax));
    /// # Ok::<(), moyo::Error>(())
    /// ```
    pub fn pinned(&self, points: Points) -> VoronoiSpec {
        let s = &self.sites;
        let relaxes = self.relax > 0;
        let lbg = self.relaxation == RelaxationMethod::Lbg;
        let spacing = if s.tracery.is_some() {
            Some(s.spacing())
        } else if !(relaxes && (lbg || s.is_weighted())) {
            None
        } else if s.points.is_some() || s.distribution() == Distribution::Uniform {
            // Unset, relaxation takes the spacing of evenly spread sites,
            // as it does for these: keep it unset.
            s.spacing
        } else {
            Some(s.spacing())
        };
        VoronoiSpec {
            sites: SitesSpec {
                distribution: None,
                count: None,
                spacing,
                jitter: None,
                image: s.image.clone().filter(|_| relaxes),
                density: s.density.clone().filter(|_| relaxes),
                edges: s.edges.filter(|_| relaxes),
                petals: s.petals,
                tracery: s.tracery,
                points: Some(points),
            },
            ..self.clone()
        }
    }
}

impl Family for VoronoiSpec {
    #[cfg(feature = "studio")]
    fn gestures(&self) -> Option<&dyn crate::family::gesture::Gestures> {
        Some(self)
    }

    fn check(&self, f: &str) -> Result<()> {
        self.region.check(&format!("{f}.region"))?;
        let lbg = self.relaxation == RelaxationMethod::Lbg;
        self.sites.check(&format!("{f}.sites"), self.relax, lbg)?;
        range(&format!("{f}.relax"), self.relax, 0, MAX_RELAX)?;
        if lbg && self.relax == 0 {
            return Err(Error::invalid(
                format!("{f}.relax"),
                "lbg relaxation needs steps: give relax = 1–1000 (50 is usually plenty)",
            ));
        }
        if let Some(c) = self.converge {
            if self.relax == 0 {
                return Err(Error::invalid(
                    format!("{f}.converge"),
                    "does nothing without relax steps (give relax = 1–1000)",
                ));
            }
            range(&format!("{f}.converge"), c, 0.00001, 100.0)?;
        }
        if self.draw.is_empty() {
            return Err(Error::invalid(
                format!("{f}.draw"),
                "draws nothing: list one or more of cells, delaunay, inset, sites, tour, cracks",
            ));
        }
        for (i, d) in self.draw.iter().enumerate() {
            if self.draw[..i].contains(d) {
                return Err(Error::invalid(format!("{f}.draw[{i}]"), "is listed twice"));
            }
        }
        range(&format!("{f}.inset"), self.inset, 0.01, 100.0)?;
        range(&format!("{f}.round"), self.round, 0.0, 50.0)?;
        range(&format!("{f}.dot"), self.dot, 0.05, 50.0)?;
        let [first, narrowest] = self.crack;
        range(&format!("{f}.crack[0]"), first, 0.05, 20.0)?;
        range(&format!("{f}.crack[1]"), narrowest, 0.05, 20.0)?;
        if narrowest > first {
            return Err(Error::invalid(
                format!("{f}.crack"),
                format!("runs from the first crack's width to the narrowest: {narrowest} is larger than {first}"),
            ));
        }
        if let Some([light, dark]) = self.dot_range {
            let field = format!("{f}.dot_range");
            range(&format!("{field}[0]"), light, 0.05, 50.0)?;
            range(&format!("{field}[1]"), dark, 0.05, 50.0)?;
            if light > dark {
                return Err(Error::invalid(
                    field,
                    format!(
                        "runs from the lightest dot to the darkest: {light} is larger than {dark}"
                    ),
                ));
            }
            if !self.sites.is_weighted() {
                return Err(Error::invalid(
                    field,
                    "follows the density of the sites: give sites.image or sites.density",
                ));
            }
        }
        Ok(())
    }

    /// One unit per relaxation step and one for drawing.
    fn work(&self) -> usize {
        self.relax as usize + 1
    }

    fn path_files(&self) -> Vec<&str> {
        self.region.svg.as_deref().into_iter().collect()
    }

    fn image_files(&self) -> Vec<&str> {
        self.sites
            .image
            .as_deref()
            .into_iter()
            .chain(self.region.image.as_deref())
            .collect()
    }

    fn layers_read(&self) -> Vec<(&'static str, &str)> {
        self.region.layers_read()
    }

    fn offers_regions(&self) -> bool {
        true
    }
}
