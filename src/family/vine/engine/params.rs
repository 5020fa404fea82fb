//! The parameters of a vine (the thesis' table 3.1) and their ranges.

use glam::DVec3;

use crate::error::{Error, Result};

/// The most axis points a vine may grow in all (`internodes` × `steps`):
/// every point becomes a ring of the stem's tube and a piece of its
/// outline, so this bounds the work downstream as well as here.
pub const MAX_POINTS: u64 = 100_000;

/// Which way the stem winds round its support.
///
/// As in the thesis, seen from below: [`Twining::Right`] winds clockwise
/// seen from below, which is counter-clockwise seen from above (+y) and
/// a positive (right-handed) turn about +y.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Twining {
    /// Counter-clockwise seen from below (the thesis' base shape).
    #[default]
    Left,
    /// Clockwise seen from below.
    Right,
}

impl Twining {
    /// +1 for a positive turn about +y (right), −1 for a negative one.
    pub(super) fn sign(self) -> f64 {
        match self {
            Twining::Right => 1.0,
            Twining::Left => -1.0,
        }
    }
}

/// How a vine grows: the thesis' parameters (table 3.1) with its base
/// values (table 4.1) as defaults, in millimetres (one thesis unit = 1 mm).
#[derive(Debug, Clone, PartialEq)]
pub struct VineParams {
    /// Internode length l, mm (1–1000; 60). Longer internodes space the
    /// leaves further apart.
    pub internode: f64,
    /// Stem radius r, mm (0.05–100; 2): the radius of the spheres that
    /// touch the supports, and of the drawn stem.
    pub radius: f64,
    /// Twining direction (left).
    pub twining: Twining,
    /// Growth interval t: the time between two axis points (0.1–1000; 10).
    /// A shorter interval grows more stem per turn of circumnutation, so
    /// the tip reaches supports further away.
    pub interval: f64,
    /// Circumnutation angle θp: degrees between the vertical and the
    /// turning tip (1–80; 18). A larger angle spreads the vine wider and
    /// packs its coils closer.
    pub angle: f64,
    /// Untwined nodes U: how many internodes above the cotyledons grow
    /// straight up before the tip starts to turn (0–20; 1).
    pub untwined: u32,
    /// Points per internode d (2–64; 12). An odd value is lowered by one,
    /// as the thesis does (its smoothing window is d/2 either side).
    pub steps: u32,
    /// The time of one full turn of circumnutation (1–100 000; 240: at
    /// t = 10 and d = 12, one turn while two internodes grow). At most
    /// one turn happens per interval.
    pub period: f64,
    /// How many internodes grow in all, every apex together (1–2000; 24).
    pub internodes: u32,
    /// Leaves per node: 0 none, 1 alternate, 2 opposite (1).
    pub leaves: u32,
    /// Leaves at node 0 (the cotyledons): 0, 1 or 2 (1).
    pub cotyledons: u32,
    /// Leaf size γ, mm: half the blade's length, the diagonal of the
    /// thesis' square leaf (0–1000; 12). 0 grows no leaves.
    pub leaf_size: f64,
    /// Where the seed sprouts (the origin). It must be at least `radius`
    /// away from every support.
    pub base: DVec3,
    /// Free tips arch over and hang under their weight (true). A vine
    /// grown along a guide on the page, where up is along the guide and
    /// not against gravity, keeps them as grown (false).
    pub droop: bool,
    /// The direction the light comes from, towards which the leaf blades
    /// turn their faces ((0, 0.5, 1): from the front and above). Any
    /// finite non-zero vector; only its direction matters.
    pub light: DVec3,
}

impl Default for VineParams {
    fn default() -> Self {
        VineParams {
            internode: 60.0,
            radius: 2.0,
            twining: Twining::Left,
            interval: 10.0,
            angle: 18.0,
            untwined: 1,
            steps: 12,
            period: 240.0,
            internodes: 24,
            leaves: 1,
            cotyledons: 1,
            leaf_size: 12.0,
            base: DVec3::ZERO,
            droop: true,
            light: DVec3::new(0.0, 0.5, 1.0),
        }
    }
}

impl VineParams {
    /// Checks every value against its range. Errors name
    /// `{field}.internode`, `{field}.radius`, … (just `internode` when
    /// `field` is empty) and give the allowed range.
    pub fn check(&self, field: &str) -> Result<()> {
        let name = |n: &str| {
            if field.is_empty() {
                n.to_string()
            } else {
                format!("{field}.{n}")
            }
        };
        let reals = [
            ("internode", self.internode, 1.0, 1000.0),
            ("radius", self.radius, 0.05, 100.0),
            ("interval", self.interval, 0.1, 1000.0),
            ("angle", self.angle, 1.0, 80.0),
            ("period", self.period, 1.0, 1e5),
            ("leaf_size", self.leaf_size, 0.0, 1000.0),
        ];
        for (n, v, lo, hi) in reals {
            // `!(lo <= v)` also catches NaN.
            if !(lo <= v && v <= hi) {
                return Err(Error::invalid(
                    name(n),
                    format!("must be between {lo} and {hi}, got {v}"),
                ));
            }
        }
        let counts = [
            ("untwined", self.untwined, 0, 20),
            ("steps", self.steps, 2, 64),
            ("internodes", self.internodes, 1, 2000),
            ("leaves", self.leaves, 0, 2),
            ("cotyledons", self.cotyledons, 0, 2),
        ];
        for (n, v, lo, hi) in counts {
            if !(lo..=hi).contains(&v) {
                return Err(Error::invalid(
                    name(n),
                    format!("must be between {lo} and {hi}, got {v}"),
                ));
            }
        }
        let points = u64::from(self.internodes) * self.even_steps() as u64;
        if points > MAX_POINTS {
            return Err(Error::invalid(
                name("internodes"),
                format!(
                    "{} internodes of {} points make {points} axis points; at most \
                     {MAX_POINTS} (lower internodes or steps)",
                    self.internodes,
                    self.even_steps()
                ),
            ));
        }
        if !self.base.is_finite() {
            return Err(Error::invalid(
                name("base"),
                format!("must be a finite point, got {}", self.base),
            ));
        }
        if !self.light.is_finite() || self.light == DVec3::ZERO {
            return Err(Error::invalid(
                name("light"),
                format!("must be a finite, non-zero direction, got {}", self.light),
            ));
        }
        Ok(())
    }

    /// The unit direction towards the light.
    pub(super) fn light_direction(&self) -> DVec3 {
        // `check` makes sure this is finite and non-zero; a vector too
        // small to normalise directly is scaled up first.
        let l = self.light;
        l.try_normalize()
            .unwrap_or_else(|| (l / l.abs().max_element()).normalize())
    }

    /// The d the simulation uses: `steps`, made even.
    pub(super) fn even_steps(&self) -> usize {
        (self.steps as usize) & !1
    }
}
