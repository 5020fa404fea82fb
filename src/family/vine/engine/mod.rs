//! Twining vines (source 004): a growth simulation of a vine winding
//! round supports, in 3D.
//!
//! Pure: this module turns [`VineParams`] and [`Supports`] into a
//! [`Plant`] — stem axes and leaves in millimetres — and a stem into a
//! [`tube`] mesh. Projecting the plant to the page, drawing outlines and
//! hiding lines, and writing OBJ files are the callers' work.
//!
//! Coordinates: millimetres, right-handed, +y up (the thesis is
//! left-handed; we are not). Round a vertical axis, angles are measured
//! as ψ = atan2(−z, x), which grows counter-clockwise seen from above.
//! [`Twining::Right`] (clockwise seen from below, the thesis' definition)
//! is a positive turn about +y: the circumnutating tip's yaw, and so the
//! ψ of a stem round its pole, grows as the stem climbs; for
//! [`Twining::Left`] they fall.
//!
//! The stages:
//!
//! 1. growth (§3.2): one axis point per interval, the top two internodes
//!    circumnutating as a straight rod at θp from the vertical; spheres of
//!    radius r on the rod touch the supports and fix the stem there, which
//!    winds it round them; an apex whose last two internodes touch
//!    nothing stops (the thesis' rule) and the next node up the first
//!    stem takes over, then the nodes of the later stems (a node with no
//!    room to sprout, every direction touching, stays a bud and keeps its
//!    leaf); a touching rod circles faster, but not without bound, so the
//!    growth interval sets how much stem grows per turn on a support too;
//! 2. shaping (§3.3.1): sharp turns smoothed, the untwined base and the
//!    free tips bent at random, and the free tips drooping under their
//!    weight;
//! 3. leaves (§3.3.3) at the nodes: pointing away from the stem and from
//!    what a twined node touches, their faces turned to
//!    [`VineParams::light`], drooping 30° and rolled at random up to 15°
//!    about the midrib.
//!
//! Stems are obstacles too: the axes grown before (every earlier stem,
//! and the growing stem below its rod) stop the rod as a support does,
//! their capsules of radius r meeting its spheres at 2r between axes, and
//! a touch fixes the stem there and winds it on (so [`Stem::twined`]
//! marks points that touched a support or a stem). Stems lie beside each
//! other, a branch twining round its parent or beside it round the pole,
//! never through each other. Two neighbourhoods may come closer: a stem's
//! own last two internodes or so, and a branch's first points, which grow
//! out of its parent's axis (the clearance from the parent grows from 0,
//! from other stems from r, to 2r over 2r/tan(θp/2) of stem).
//!
//! No axis point of the simulation or of the shaped stem is ever closer
//! than r to a support. No simulated axis point is closer than 2r to the
//! axis of another stem, outside those neighbourhoods; shaping bends only
//! free parts (the base, the tips) and may bring those closer.
//!
//! ```
//! use glam::DVec3;
//! use moyo::vine::{grow, Shape, Supports, VineParams};
//! use moyo::Seed;
//!
//! let pole = Supports::new(vec![Shape::Pole {
//!     base: DVec3::new(20.0, 0.0, 0.0),
//!     top: DVec3::new(20.0, 400.0, 0.0),
//!     radius: 6.0,
//! }]);
//! let plant = grow(&VineParams::default(), &pole, &mut Seed(7).stream())?;
//! let first = &plant.stems[0];
//! assert!(first.twined.contains(&true));
//! assert!(first.points.iter().all(|&p| pole.distance(p) >= 2.0 - 1e-6));
//! # Ok::<(), moyo::Error>(())
//! ```

use glam::DVec3;

use crate::error::{Error, Result};
use crate::rng::RandomStream;

mod axes;
mod growth;
mod leaves;
mod params;
mod shaping;
mod support;
#[cfg(test)]
mod tests;
mod tube;

pub use crate::geom::mesh::TriMesh;
pub use params::{Twining, VineParams, MAX_POINTS};
pub use support::{cross, fence, tee, Shape, Supports};
pub use tube::tube;

/// A grown vine.
#[derive(Debug, Clone, PartialEq)]
pub struct Plant {
    /// The stems: the first from the seed, then one per apex that took
    /// over, in the order they grew.
    pub stems: Vec<Stem>,
    /// Every leaf, stem by stem, node by node.
    pub leaves: Vec<Leaf>,
    /// The points per internode d used (`steps` made even).
    pub steps: u32,
}

/// One stem: the axis grown by one apex.
#[derive(Debug, Clone, PartialEq)]
pub struct Stem {
    /// The shaped axis P'_i (after smoothing and bends): what is drawn.
    pub points: Vec<DVec3>,
    /// The simulated axis P_i, before shaping (as many points).
    pub raw: Vec<DVec3>,
    /// Per point: fixed where it touched a support or another stem's axis
    /// (or its own, further down), and so wound round or laid against it.
    pub twined: Vec<bool>,
    /// The (stem, point) this apex started from; `None` for the first.
    pub parent: Option<(usize, usize)>,
    /// The apex stopped (apical dominance: it found nothing to twine
    /// round) rather than the growth ending.
    pub stopped: bool,
    /// Points per internode.
    steps: usize,
}

impl Stem {
    /// The point indices of the nodes of this stem: 0, d, 2d, … up to its
    /// tip.
    pub fn nodes(&self) -> impl Iterator<Item = usize> {
        (0..self.points.len()).step_by(self.steps)
    }
}

/// One leaf at a node: a petiole and a blade (the thesis' square leaf,
/// with real leaves' stalk and droop), its face turned to the light: the
/// face's normal is `midrib × across`.
#[derive(Debug, Clone, PartialEq)]
pub struct Leaf {
    /// The stem it grows on (index into [`Plant::stems`]).
    pub stem: usize,
    /// The node's point index on that stem.
    pub node: usize,
    /// A seed leaf (node 0 of the first stem).
    pub cotyledon: bool,
    /// The petiole: from the stem's surface to where the blade starts.
    pub stalk: [DVec3; 2],
    /// Unit direction of the blade from its start to its tip.
    pub midrib: DVec3,
    /// Unit direction across the blade, at right angles to `midrib`: the
    /// light made perpendicular to the midrib, crossed with it, after the
    /// droop and the roll.
    pub across: DVec3,
    /// Blade length, 2γ (the thesis' square's diagonal).
    pub length: f64,
    /// The thesis' square leaf: blade start, centre + γ·across, tip,
    /// centre − γ·across.
    pub quad: [DVec3; 4],
}

/// Grows a vine round `supports`, its random choices (the first yaw of
/// each apex's circumnutation, the bends, the leaves' roll) drawn from
/// `rng`: the same parameters, supports and stream give the same plant.
///
/// Errors: a parameter out of range (named as by [`VineParams::check`]
/// with an empty field), or a seed closer than the stem's radius to a
/// support (`base`).
pub fn grow(params: &VineParams, supports: &Supports, rng: &mut RandomStream) -> Result<Plant> {
    params.check("")?;
    let gap = supports.distance(params.base);
    if gap < params.radius {
        return Err(Error::invalid(
            "base",
            format!(
                "the seed is {gap:.3} mm from a support; it must be at least the stem \
                 radius ({} mm) away",
                params.radius
            ),
        ));
    }
    let raw = growth::simulate(params, supports, rng);
    let shaped = shaping::shape(&raw, params, supports, rng);
    let d = params.even_steps();
    let stems: Vec<Stem> = raw
        .into_iter()
        .zip(shaped)
        .map(|(r, points)| Stem {
            points,
            raw: r.points,
            twined: r.twined,
            parent: r.parent,
            stopped: r.stopped,
            steps: d,
        })
        .collect();
    let leaves = leaves::leaves(&stems, params, supports, rng);
    Ok(Plant {
        stems,
        leaves,
        steps: d as u32,
    })
}
