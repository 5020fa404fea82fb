//! The growth of the stem axis (thesis §3.2): one point per interval,
//! circumnutation of the top two internodes, contact with the supports
//! and the stems grown before, and apical dominance.
//!
//! The rotating part of an apex is a straight rod from the pivot P_k
//! through the points above it, one direction N at θp from the vertical
//! whose yaw turns in the twining direction. Besides the spheres of
//! P_{k+1} … P_f the rod carries the sphere of the point that grows next
//! (P_{f+1}, one step further along N): it must be clear before it grows,
//! so a point is never placed inside a support or a stem. When that
//! sphere is the first to touch, the turning stops for the interval and
//! the point grows there, touching: the tip presses against the support
//! and wraps round it.
//!
//! Decision (stems as supports): the fixed axes (every earlier stem, and
//! the apex's own stem below the pivot) are obstacles as the supports
//! are, each a chain of capsules of radius r (see [`Axes`]). Without them
//! a branch from a twined node winds round the pole along its parent's
//! helix, exactly on top of it; with them it twines round its parent, or
//! round the pole between the parent's coils, as real vines do.
//!
//! Decision (thigmotropism): a rod that touched a support or a stem in this
//! interval, or whose tip is twined, turns faster for the rest of it: at
//! most [`TOUCH_SPEEDUP`] times the interval's share of circumnutation in
//! all. Winding round a support of radius R takes a turn of about
//! 2·asin(l·sin θp / (2d(R + r))) per point: 11° at the base values on a
//! pole of radius 6, 18° on a post of radius 3. While the sped-up turn
//! per interval is larger, the contact keeps up with the growth and the
//! stem hugs its support; when the interval is shorter (t = 5: 7.5° of
//! circumnutation, 9.75° sped up), the stem grows faster than it can wind,
//! its rod lengthens, the contacts fall behind and come further apart,
//! and the coil loosens: the thesis' fig. 4.5 e. The growth interval so
//! stays coupled to the circling rate, on a support as before one.
//!
//! Apical dominance (the thesis' stop rule): an apex whose last two
//! internodes, the circumnutating part, touch nothing stops. It has grown
//! 2d points since its last contact (or since it began to turn).

use std::f64::consts::{PI, TAU};

use glam::DVec3;

use super::axes::Axes;
use super::params::VineParams;
use super::support::Supports;
use crate::rng::RandomStream;

/// A stem as the simulation leaves it, before shaping.
#[derive(Debug)]
pub(super) struct RawStem {
    /// The axis P_0 … P_f.
    pub(super) points: Vec<DVec3>,
    /// Per point: fixed by touching a support or a stem.
    pub(super) twined: Vec<bool>,
    /// (stem, point) this apex started from.
    pub(super) parent: Option<(usize, usize)>,
    /// The apex stopped (apical dominance).
    pub(super) stopped: bool,
}

/// How much faster a touching rod circles than the interval's share
/// (thigmotropism, module docs): enough to wind round a post of radius 3
/// at the base values, not so much that the growth interval stops
/// mattering on the pole of the thesis.
const TOUCH_SPEEDUP: f64 = 1.3;

/// The largest turn between two looks at the supports while a sphere is
/// near one (radians): the thesis' sub-step.
const MAX_STEP: f64 = 2.0 * PI / 180.0;
/// The smallest such turn, so that a sphere grazing a surface cannot
/// stall the turning.
const MIN_STEP: f64 = 0.05 * PI / 180.0;
/// How closely a contact is found: the motion of the farthest sphere
/// between the last clear turn and the first touching one, mm.
const TOLERANCE: f64 = 1e-9;
/// Bisection steps at most (64 halvings exhaust an f64).
const BISECTIONS: usize = 64;
/// The step of the search for a clear direction when the next point is
/// blocked (radians); 180 of them make a full turn.
const SCAN_STEP: f64 = 2.0 * PI / 180.0;

/// Grows every apex in turn: the first from `params.base`, each later one
/// from the next free node of the first stem, until `params.internodes`
/// internodes have grown or no free node is left.
pub(super) fn simulate(
    params: &VineParams,
    supports: &Supports,
    rng: &mut RandomStream,
) -> Vec<RawStem> {
    let mut world = World::new(params, supports);
    let d = world.d;
    let total = params.internodes as usize * d;
    let mut grown = 0;
    let mut stems: Vec<RawStem> = Vec::new();
    // The next bud: (stem, node index) to try.
    let mut bud = (0, (params.untwined as usize + 1) * d);
    let first = world.axes.add_stem(None);
    let mut apex = Apex::new(params.base, None, params.untwined as usize * d, first);
    loop {
        // A fresh apex has nothing to turn yet: this only starts its
        // circumnutation if due and makes sure its first point is clear.
        apex.prepare(&mut world, rng);
        while !apex.stopped && grown < total {
            apex.tick(&mut world, rng);
            grown += 1;
        }
        if apex.parent.is_some() && apex.points.len() == 1 {
            // A bud with no room to grow (every direction touches a
            // support or a stem) stays a bud: no stem, and its node keeps
            // its leaf.
            world.axes.drop_stem();
        } else {
            stems.push(apex.finish(&mut world.axes));
        }
        if grown >= total {
            break;
        }
        // Apical dominance passes to the lowest free node below the first
        // stem's tip; when the first stem has none left (it stopped short),
        // to the next stem's nodes, and so on.
        let Some((from, node)) = next_bud(&stems, &mut bud, d) else {
            break;
        };
        let parent = Some((from, node));
        let stem = world.axes.add_stem(parent);
        apex = Apex::new(stems[from].points[node], parent, 0, stem);
    }
    stems
}

/// The bud that takes over next, `bud` or the first node after it: a node
/// below its stem's tip (stems in the order they grew, a later stem from
/// its first node on), `bud` moved on past it; `None` when none is left.
fn next_bud(stems: &[RawStem], bud: &mut (usize, usize), d: usize) -> Option<(usize, usize)> {
    loop {
        let (from, node) = *bud;
        let stem = stems.get(from)?;
        if node + 1 < stem.points.len() {
            *bud = (from, node + d);
            return Some((from, node));
        }
        *bud = (from + 1, d);
    }
}

/// What the simulation needs of the parameters, the supports and the
/// stems fixed so far.
struct World<'a> {
    supports: &'a Supports,
    /// The fixed axes: the stems grown before, and the growing one up to
    /// its pivot.
    axes: Axes,
    /// Stem radius r.
    r: f64,
    /// Step length l/d.
    s: f64,
    sin: f64,
    cos: f64,
    /// +1: yaw grows (right twining), −1: it falls.
    sign: f64,
    /// Points per internode (even).
    d: usize,
    /// Circumnutation per interval, radians (at most a full turn).
    turn: f64,
}

impl<'a> World<'a> {
    fn new(params: &VineParams, supports: &'a Supports) -> World<'a> {
        let d = params.even_steps();
        let angle = params.angle.to_radians();
        World {
            supports,
            axes: Axes::new(params),
            r: params.radius,
            s: params.internode / d as f64,
            sin: angle.sin(),
            cos: angle.cos(),
            sign: params.twining.sign(),
            d,
            turn: (TAU * params.interval / params.period).min(TAU),
        }
    }

    /// The rod's unit direction at `yaw`: θp from +y, its horizontal part
    /// at angle `yaw` = atan2(−z, x).
    fn dir(&self, yaw: f64) -> DVec3 {
        DVec3::new(self.sin * yaw.cos(), self.cos, -self.sin * yaw.sin())
    }

    /// Whether the sphere at `p`, of point `at` = (stem, index), touches
    /// neither a support nor a fixed axis.
    fn clear(&self, p: DVec3, at: (usize, usize)) -> bool {
        let touch = 2.0 * self.r;
        self.supports.distance(p) >= self.r && self.axes.nearest(p, at, touch) >= touch
    }

    /// The lowest of the `n` spheres on the rod from pivot `k` of `stem`
    /// (at `pivot`) at `yaw` that touches (1 is the one next to the
    /// pivot).
    fn contact(
        &self,
        pivot: DVec3,
        yaw: f64,
        n: usize,
        (stem, k): (usize, usize),
    ) -> Option<usize> {
        let step = self.dir(yaw) * self.s;
        (1..=n).find(|&m| !self.clear(pivot + step * m as f64, (stem, k + m)))
    }

    /// How far the rod may turn before any of its `n` spheres can touch:
    /// sphere m moves on a circle of radius m·s·sin θp, and the distance to
    /// the supports and the axes changes no faster than the sphere moves.
    fn free_turn(&self, pivot: DVec3, yaw: f64, n: usize, (stem, k): (usize, usize)) -> f64 {
        let step = self.dir(yaw) * self.s;
        let arm = self.s * self.sin;
        let reach = self.axes.cell();
        (1..=n)
            .map(|m| {
                let p = pivot + step * m as f64;
                let axis = self.axes.nearest(p, (stem, k + m), reach);
                let gap = (self.supports.distance(p) - self.r).min(axis - 2.0 * self.r);
                gap / (arm * m as f64)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// A yaw at which the point one step from `pivot` (the point `at`) is
    /// clear, found by turning back from `yaw` (against the twining
    /// direction) to where the turning would have met the support; `None`
    /// if every direction at θp is blocked.
    ///
    /// Turning back, not on: on from a blocked direction leads round to
    /// the far edge of the support, and the stem would wind the wrong way.
    fn unblock(&self, pivot: DVec3, yaw: f64, at: (usize, usize)) -> Option<f64> {
        let blocked = |y: f64| !self.clear(pivot + self.dir(y) * self.s, at);
        let arm = self.s * self.sin;
        let back = -self.sign * SCAN_STEP;
        let clear = (1..=180)
            .map(|i| yaw + back * i as f64)
            .find(|&y| !blocked(y))?;
        // Between the last blocked and the first clear yaw: keep the clear
        // side, touching.
        let (mut lo, mut hi) = (clear - back, clear);
        for _ in 0..BISECTIONS {
            if (hi - lo).abs() * arm <= TOLERANCE {
                break;
            }
            let mid = 0.5 * (lo + hi);
            if blocked(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(hi)
    }
}

/// How a sweep of the rod ended.
enum Sweep {
    /// It turned as far as asked without touching.
    Free,
    /// The sphere of this point touched first.
    Contact(usize),
    /// The sphere of the point to come touched first.
    Blocked,
}

/// A growing apex: its stem so far and the state of its circumnutation.
struct Apex {
    /// Its index among the stems.
    stem: usize,
    points: Vec<DVec3>,
    twined: Vec<bool>,
    parent: Option<(usize, usize)>,
    stopped: bool,
    /// The point index at which circumnutation starts (U·d for the first
    /// stem, 0 for later apexes).
    nutate_from: usize,
    nutating: bool,
    /// The pivot k: points up to it are fixed (and their axis indexed).
    k: usize,
    /// Yaw of the rod's direction, radians.
    yaw: f64,
    /// The point to come touches a support or a stem: it will be twined.
    pending: bool,
    /// The last point that touched (or where the turning began): the apex
    /// stops when its tip is two internodes past it.
    contact: usize,
}

impl Apex {
    fn new(start: DVec3, parent: Option<(usize, usize)>, nutate_from: usize, stem: usize) -> Apex {
        Apex {
            stem,
            points: vec![start],
            twined: vec![false],
            parent,
            stopped: false,
            nutate_from,
            nutating: false,
            k: 0,
            yaw: 0.0,
            pending: false,
            contact: 0,
        }
    }

    fn tip(&self) -> usize {
        self.points.len() - 1
    }

    /// The number of spheres on the rod: P_{k+1} … P_f and the point to
    /// come.
    fn spheres(&self) -> usize {
        self.tip() + 1 - self.k
    }

    /// Moves the pivot up to `k`, fixing the points below it: their axis
    /// becomes an obstacle for the spheres further up.
    fn fix(&mut self, k: usize, axes: &mut Axes) {
        for i in self.k..k {
            axes.add(self.stem, i, self.points[i], self.points[i + 1]);
        }
        self.k = k;
    }

    /// The (stem, index) of the point that grows next.
    fn next_at(&self) -> (usize, usize) {
        (self.stem, self.tip() + 1)
    }

    /// Where the next point grows (eq. 3.1 along the current direction).
    fn next_point(&self, w: &World<'_>) -> DVec3 {
        if self.nutating {
            // Computed as the sweep computes its spheres, to the last bit.
            self.points[self.k] + w.dir(self.yaw) * w.s * self.spheres() as f64
        } else {
            self.points[self.tip()] + DVec3::Y * w.s
        }
    }

    /// One interval: a point grows, then the rod turns.
    fn tick(&mut self, w: &mut World<'_>, rng: &mut RandomStream) {
        let p = self.next_point(w);
        self.points.push(p);
        self.twined.push(self.pending);
        if self.pending {
            self.fix(self.tip(), &mut w.axes);
            self.contact = self.tip();
            self.pending = false;
        }
        if self.prepare(w, rng) {
            self.rotate(w);
        }
    }

    /// Starts circumnutation when its time has come (or when the straight
    /// stem would grow into a support or a stem) and makes sure the point
    /// to come is clear (the rod is never longer than two internodes: the
    /// apex stops first). Returns whether the rod may turn now.
    fn prepare(&mut self, w: &mut World<'_>, rng: &mut RandomStream) -> bool {
        let f = self.tip();
        if !self.nutating {
            if f < self.nutate_from && w.clear(self.next_point(w), self.next_at()) {
                return false;
            }
            self.nutating = true;
            self.fix(f, &mut w.axes);
            self.yaw = rng.range(-PI, PI);
            self.contact = f;
        }
        if w.clear(self.next_point(w), self.next_at()) {
            return true;
        }
        // The rod points into a support or a stem (it grew towards it):
        // fix the rod and turn the tip until its next point is clear,
        // touching.
        self.fix(f, &mut w.axes);
        match w.unblock(self.points[f], self.yaw, self.next_at()) {
            Some(yaw) => {
                self.yaw = yaw;
                self.pending = true;
            }
            None => self.stopped = true,
        }
        false
    }

    /// The interval's circumnutation, about a pivot that moves up at each
    /// contact; then apical dominance.
    fn rotate(&mut self, w: &mut World<'_>) {
        let mut remaining = w.turn;
        // Touching a support or a stem this interval speeds the turning
        // up, once (thigmotropism, module docs).
        let mut touched = self.k == self.tip() && self.twined[self.k];
        let mut sped_up = false;
        loop {
            let (outcome, done) = self.sweep(w, remaining);
            match outcome {
                Sweep::Free => {
                    if sped_up || !touched {
                        break;
                    }
                    sped_up = true;
                    remaining = (TOUCH_SPEEDUP - 1.0) * w.turn;
                }
                Sweep::Contact(i) => {
                    self.fix(i, &mut w.axes);
                    self.twined[i] = true;
                    self.contact = self.contact.max(i);
                    touched = true;
                    remaining = (remaining - done).max(0.0);
                }
                Sweep::Blocked => {
                    self.pending = true;
                    break;
                }
            }
        }
        // Apical dominance: the last two internodes touch nothing.
        if !self.pending && self.tip() - self.contact >= 2 * w.d {
            self.stopped = true;
        }
    }

    /// Turns the rod by up to `budget` in the twining direction, stopping
    /// at the first contact (found by bisection, so no sphere ever enters
    /// a support). Returns how it ended and how far it turned.
    fn sweep(&mut self, w: &World<'_>, budget: f64) -> (Sweep, f64) {
        let n = self.spheres();
        let pivot = self.points[self.k];
        let at = (self.stem, self.k);
        let reach = n as f64 * w.s * w.sin;
        // Turns small enough that the farthest sphere moves less than its
        // radius, unless everything is far away.
        let floor = (w.r / reach).clamp(MIN_STEP, MAX_STEP);
        let mut done = 0.0;
        let outcome = loop {
            if budget - done <= 1e-12 {
                break Sweep::Free;
            }
            let step = (budget - done).min(w.free_turn(pivot, self.yaw, n, at).max(floor));
            let Some(mut hit) = w.contact(pivot, self.yaw + w.sign * step, n, at) else {
                self.yaw += w.sign * step;
                done += step;
                continue;
            };
            // The first contact lies in (0, step]: lo is clear, hi touches.
            let (mut lo, mut hi) = (0.0, step);
            for _ in 0..BISECTIONS {
                if (hi - lo) * reach <= TOLERANCE {
                    break;
                }
                let mid = 0.5 * (lo + hi);
                match w.contact(pivot, self.yaw + w.sign * mid, n, at) {
                    Some(m) => {
                        hi = mid;
                        hit = m;
                    }
                    None => lo = mid,
                }
            }
            self.yaw += w.sign * lo;
            done += lo;
            break if hit == n {
                Sweep::Blocked
            } else {
                Sweep::Contact(self.k + hit)
            };
        };
        let step = w.dir(self.yaw) * w.s;
        for j in self.k + 1..=self.tip() {
            self.points[j] = pivot + step * (j - self.k) as f64;
        }
        (outcome, done)
    }

    /// The stem as grown; its axis becomes an obstacle for the apexes to
    /// come. A stopped apex's free rod does not: it droops (shaping), and
    /// a rod standing in the air would hold up the next apex, and that one
    /// the next, a tower of stems above the support.
    fn finish(self, axes: &mut Axes) -> RawStem {
        axes.add_all(self.stem, &self.points, self.k);
        RawStem {
            points: self.points,
            twined: self.twined,
            parent: self.parent,
            stopped: self.stopped,
        }
    }
}
