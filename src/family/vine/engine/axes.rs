//! The stems' axes as obstacles: a growing apex touches an earlier stem,
//! or its own stem further down, as it touches a support, so that stems
//! lie beside each other and never on top of each other.
//!
//! Each axis is a chain of segments between consecutive points, and a
//! sphere of radius r on the rod touches one when its centre is closer
//! than 2r to the segment (the stem's capsule, radius r, meets the
//! sphere). Two kinds of places must be allowed closer:
//!
//! - a stem's own recent points: a segment of the same stem is an
//!   obstacle only when both its ends lie more than [`Axes::near`] points
//!   away along the stem (the rod and the stem just below its pivot touch
//!   by construction);
//! - a branch's first points: it starts on its parent's axis, so the
//!   clearance its points keep from the parent grows from 0 at its start
//!   to 2r once it has grown [`Axes::emergence`] of stem. Another stem
//!   often lies against the parent at the node, 2r from the branch's
//!   start, and the rod, at θp from the vertical, cannot leave such a
//!   groove without coming a little closer: the clearance from other stems
//!   grows the same way but from r (`CROWD`), enough that the branch
//!   cannot pass through them.
//!
//! The segments sit in a uniform grid of cubes at least 4r and one step
//! l/d on a side, keyed by integer cube coordinates: a query looks at the
//! few cubes within its reach of the point, never at every segment.

use std::collections::HashMap;

use glam::DVec3;

use super::params::VineParams;

/// The least part of 2r a branch's first points keep from a stem other
/// than their parent (one that lies against the parent at the node): the
/// axes of two stems r apart overlap by half, but do not cross.
const CROWD: f64 = 0.5;

/// A piece of one stem's axis between two of its points (the same point
/// twice for a stem of one point).
#[derive(Debug, Clone, Copy)]
struct Segment {
    ends: [DVec3; 2],
    stem: usize,
    /// The point indices of the ends.
    at: [usize; 2],
}

/// The axes of a plant's stems, indexed for distance queries.
#[derive(Debug, Clone)]
pub(super) struct Axes {
    /// The side of a grid cube, mm.
    cell: f64,
    /// Stem radius r.
    r: f64,
    /// Step length l/d.
    step: f64,
    /// Points of one stem at most this far apart may touch.
    near: usize,
    /// The length of stem over which a branch grows out of its node, mm.
    emergence: f64,
    /// Per stem: the stem it branched from.
    parent: Vec<Option<usize>>,
    segments: Vec<Segment>,
    grid: HashMap<[i64; 3], Vec<usize>>,
}

impl Axes {
    /// An empty index for the stems of a vine grown with `params`.
    pub(super) fn new(params: &VineParams) -> Axes {
        let d = params.even_steps();
        let step = params.internode / d as f64;
        Axes {
            cell: (4.0 * params.radius).max(step),
            r: params.radius,
            step,
            near: Axes::near(params),
            emergence: Axes::emergence(params),
            parent: Vec::new(),
            segments: Vec::new(),
            grid: HashMap::new(),
        }
    }

    /// How many points apart along the plant two points may touch: the
    /// rod's two internodes (2d), or more when 4r of stem takes more
    /// steps, so that a stem may turn round a thin support or an edge
    /// without meeting itself.
    pub(super) fn near(params: &VineParams) -> usize {
        let d = params.even_steps();
        let step = params.internode / d as f64;
        (2 * d).max((4.0 * params.radius / step).ceil() as usize)
    }

    /// The length of stem over which a branch grows out of the crowd at
    /// its node, mm: it starts on its parent's axis (and so may start
    /// touching whatever touches its parent there), and the clearance it
    /// must keep from every other stem grows from 0 at its start to 2r at
    /// this length, 2r / tan(θp/2): about the length over which a rod θp/2
    /// off its parent's direction moves 2r away from the parent's axis.
    pub(super) fn emergence(params: &VineParams) -> f64 {
        2.0 * params.radius / (params.angle.to_radians() / 2.0).tan()
    }

    /// The size of a query that answers exactly up to one cell away.
    pub(super) fn cell(&self) -> f64 {
        self.cell
    }

    /// Registers the next stem, branching from `parent`; returns its
    /// index.
    pub(super) fn add_stem(&mut self, parent: Option<(usize, usize)>) -> usize {
        self.parent.push(parent.map(|(stem, _)| stem));
        self.parent.len() - 1
    }

    /// Forgets the last stem registered, which must have no segments yet
    /// (a bud that found no room to grow).
    pub(super) fn drop_stem(&mut self) {
        let stem = self.parent.len() - 1;
        debug_assert!(!matches!(self.segments.last(), Some(s) if s.stem == stem));
        self.parent.pop();
    }

    /// Adds the segment between points `i` and `i + 1` of `stem`.
    pub(super) fn add(&mut self, stem: usize, i: usize, a: DVec3, b: DVec3) {
        self.insert(Segment {
            ends: [a, b],
            stem,
            at: [i, i + 1],
        });
    }

    /// Adds the segments of `points` (the whole axis of `stem`) from point
    /// `from` on; a single point as a segment of no length.
    pub(super) fn add_all(&mut self, stem: usize, points: &[DVec3], from: usize) {
        if points.len() == 1 {
            self.insert(Segment {
                ends: [points[0]; 2],
                stem,
                at: [0, 0],
            });
        }
        for i in from..points.len().saturating_sub(1) {
            self.add(stem, i, points[i], points[i + 1]);
        }
    }

    fn insert(&mut self, segment: Segment) {
        let id = self.segments.len();
        let [a, b] = segment.ends;
        let (lo, hi) = (self.key(a.min(b)), self.key(a.max(b)));
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    self.grid.entry([x, y, z]).or_default().push(id);
                }
            }
        }
        self.segments.push(segment);
    }

    fn key(&self, p: DVec3) -> [i64; 3] {
        (p / self.cell).floor().as_i64vec3().to_array()
    }

    /// The distance from `p`, the position of point `index` of `stem`, to
    /// the nearest axis that is an obstacle to it, less the slack it is
    /// allowed there; exact up to `reach` (at most [`Axes::cell`]), and
    /// `reach` when nothing is closer.
    pub(super) fn nearest(&self, p: DVec3, (stem, index): (usize, usize), reach: f64) -> f64 {
        let mut best = reach;
        for s in self.around(p, reach) {
            let distance = p.distance(nearest_on_segment(p, s.ends[0], s.ends[1]));
            if distance >= best {
                continue;
            }
            if let Some(slack) = self.slack((stem, index), s) {
                best = best.min(distance + slack);
            }
        }
        best
    }

    /// The nearest point of each stem's axis to `p` that lies within
    /// `reach` of it, as (stem, the segment's first point index, the
    /// point); a stem's segments whose first point is in `skip(stem, i)`
    /// are left out.
    pub(super) fn nearest_per_stem(
        &self,
        p: DVec3,
        reach: f64,
        skip: impl Fn(usize, usize) -> bool,
    ) -> Vec<(usize, usize, DVec3)> {
        let mut best: Vec<(usize, usize, DVec3)> = Vec::new();
        for s in self.around(p, reach) {
            if skip(s.stem, s.at[0]) {
                continue;
            }
            let q = nearest_on_segment(p, s.ends[0], s.ends[1]);
            if p.distance(q) >= reach {
                continue;
            }
            match best.iter_mut().find(|b| b.0 == s.stem) {
                Some(b) if p.distance(q) < p.distance(b.2) => *b = (s.stem, s.at[0], q),
                Some(_) => {}
                None => best.push((s.stem, s.at[0], q)),
            }
        }
        best.sort_by_key(|b| b.0);
        best
    }

    /// The segments in the cells that the cube of half-side `reach` round
    /// `p` meets: every segment within `reach` of `p` (and a few further;
    /// one that spans several cells comes once for each).
    fn around(&self, p: DVec3, reach: f64) -> impl Iterator<Item = &Segment> + '_ {
        let (lo, hi) = (
            self.key(p - DVec3::splat(reach)),
            self.key(p + DVec3::splat(reach)),
        );
        (lo[0]..=hi[0])
            .flat_map(move |x| {
                (lo[1]..=hi[1]).flat_map(move |y| (lo[2]..=hi[2]).map(move |z| [x, y, z]))
            })
            .filter_map(|key| self.grid.get(&key))
            .flatten()
            .map(|&id| &self.segments[id])
    }

    /// How much closer than 2r the point `at` may come to segment `s`:
    /// `None` when it may touch it (a recent point of its own stem), 0
    /// when it must keep 2r, and for the first points of a branch the part
    /// of 2r it has not grown out of yet (module docs).
    fn slack(&self, (stem, index): (usize, usize), s: &Segment) -> Option<f64> {
        if s.stem == stem {
            let far = s.at.iter().map(|&i| i.abs_diff(index)).max().unwrap_or(0);
            return (far > self.near).then_some(0.0);
        }
        let Some(parent) = self.parent[stem] else {
            return Some(0.0);
        };
        let grown = (index as f64 * self.step / self.emergence).min(1.0);
        let keep = if s.stem == parent {
            grown
        } else {
            grown.max(CROWD)
        };
        Some(2.0 * self.r * (1.0 - keep))
    }
}

/// The point of the segment from `a` to `b` nearest to `p`.
pub(super) fn nearest_on_segment(p: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let ab = b - a;
    let length2 = ab.length_squared();
    if length2 == 0.0 {
        return a;
    }
    a + ab * ((p - a).dot(ab) / length2).clamp(0.0, 1.0)
}
