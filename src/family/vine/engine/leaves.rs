//! Leaves at the nodes (thesis §3.3.3, eq. 3.6–3.8), made to look like
//! real leaves: a petiole from the stem's surface and a drooping blade,
//! turned away from the supports (and from the stems a twined node lies
//! against), its face turned to the light.
//!
//! A blade's orientation, step by step:
//!
//! 1. the midrib points away from the stem (and from what the node
//!    touches), [`DROOP`] below that direction, as eq. 3.6–3.8;
//! 2. the blade's normal is the light direction made perpendicular to
//!    the midrib (Gram–Schmidt), so the face turns to the light as far as
//!    the midrib lets it; when the light lies along the midrib the normal
//!    is the one the thesis' square has (the stem's direction made
//!    perpendicular to the midrib);
//! 3. the blade droops [`BLADE_DROOP`]: it turns as a whole so that the
//!    midrib tilts that much further down, towards −y (about the level
//!    axis across the midrib: the blade's across axis when the light
//!    comes from above; a blade facing a low light droops about the same
//!    axis, so its midrib still goes down rather than sideways);
//! 4. it rolls about the midrib by a random angle within ±[`ROLL`], one
//!    draw per leaf from the plant's stream.
//!
//! A blade that would enter a support droops less (down to none), and if
//! that is not enough turns about the stem, as a whole, until it is clear.

use std::f64::consts::{FRAC_PI_2, PI};

use glam::{DQuat, DVec3};

use super::axes::Axes;
use super::params::VineParams;
use super::support::Supports;
use super::{Leaf, Stem};
use crate::rng::RandomStream;

/// The petiole rises this far above the leaf's outward direction
/// (towards the stem's tip).
const PETIOLE_TILT: f64 = 30.0 * PI / 180.0;
/// The petiole's length in leaf sizes γ.
const PETIOLE_LENGTH: f64 = 0.4;
/// The midrib points this far below the outward direction (towards the
/// stem's base).
const DROOP: f64 = 20.0 * PI / 180.0;
/// The blade, once facing the light, droops this much more: its midrib
/// tilts this much further towards −y.
const BLADE_DROOP: f64 = 30.0 * PI / 180.0;
/// A drooping blade that would enter a support droops less, in this many
/// steps down to none, before it turns about the stem.
const DROOP_STEPS: u32 = 3;
/// The blade rolls about its midrib by a random angle up to this either
/// way.
const ROLL: f64 = 15.0 * PI / 180.0;
/// The light is taken to lie along the midrib when the part of it
/// perpendicular to the midrib is shorter than this (unit light).
const ALONG: f64 = 1e-6;
/// A twined node touches a support or a stem's axis within this much of
/// the contact distance (r, 2r), mm.
const TOUCH: f64 = 0.5;
/// Opposite leaves on a twined node stand this far either side of the
/// direction away from the support, so neither points into it.
const OPPOSITE_ON_SUPPORT: f64 = 75.0 * PI / 180.0;
/// A leaf that would lie inside a support turns about the stem by this
/// much at a time…
const TURN_STEP: f64 = 15.0 * PI / 180.0;
/// …at most a full turn.
const TURN_STEPS: u32 = 24;

/// The leaves of every stem: node 0 of the first stem has `cotyledons`,
/// every other node `leaves`, except one fewer where a new apex started
/// and none at a branch's own first point (its parent's node). Each leaf
/// draws its roll from `rng`, in order.
pub(super) fn leaves(
    stems: &[Stem],
    params: &VineParams,
    supports: &Supports,
    rng: &mut RandomStream,
) -> Vec<Leaf> {
    let mut out = Vec::new();
    if params.leaf_size <= 0.0 {
        return out;
    }
    let d = params.even_steps();
    let light = params.light_direction();
    // What each twined node lies against, found near it, not among all.
    let mut axes = Axes::new(params);
    for (si, stem) in stems.iter().enumerate() {
        axes.add_stem(stem.parent);
        axes.add_all(si, &stem.points, 0);
    }
    for (si, stem) in stems.iter().enumerate() {
        for node in stem.nodes() {
            let count = if stem.parent.is_some() && node == 0 {
                0
            } else if node == 0 {
                params.cotyledons
            } else {
                let branched = stems.iter().any(|s| s.parent == Some((si, node)));
                params.leaves.saturating_sub(u32::from(branched))
            };
            if count == 0 {
                continue;
            }
            let (p, t) = (stem.points[node], tangent(&stem.points, node));
            let around_support = if stem.twined[node] {
                away(stems, &axes, (si, node), params.radius, supports)
                    .and_then(|o| (o - t * o.dot(t)).try_normalize())
            } else {
                None
            };
            let pair = if around_support.is_some() {
                OPPOSITE_ON_SUPPORT
            } else {
                FRAC_PI_2
            };
            // On a free stem, alternate leaves turn half a turn from node
            // to node and opposite pairs a quarter turn (decussate), the
            // first pair (two cotyledons) across x, as the front camera
            // sees both.
            let (base, angles): (DVec3, &[f64]) = match (around_support, count) {
                (Some(o), 1) => (o, &[0.0]),
                (Some(o), _) => (o, &[pair, -pair]),
                (None, 1) => (rotate(free_reference(t), t, PI * (node / d) as f64), &[0.0]),
                (None, _) => (
                    rotate(free_reference(t), t, FRAC_PI_2 * (node / d + 1) as f64),
                    &[pair, -pair],
                ),
            };
            for &angle in angles {
                let cotyledon = stem.parent.is_none() && node == 0;
                let roll = rng.symmetric(ROLL);
                let at = Node {
                    stem: si,
                    node,
                    cotyledon,
                    p,
                    t,
                };
                // Out of the supports: less droop first, then turned
                // about the stem.
                let leaf = (0..TURN_STEPS).find_map(|i| {
                    let o = rotate(base, t, angle + TURN_STEP * f64::from(i));
                    (0..=DROOP_STEPS).rev().find_map(|k| {
                        let droop = BLADE_DROOP * f64::from(k) / f64::from(DROOP_STEPS);
                        let leaf = make(&at, o, light, droop, roll, params);
                        clear_of(&leaf, supports).then_some(leaf)
                    })
                });
                out.extend(leaf);
            }
        }
    }
    out
}

/// The direction away from what the twined point `at` = (stem, index)
/// touches: the outward normal of a support it lies on, and away from the
/// axis of every other stem (or of its own stem further than two
/// internodes away) it lies against; `None` when it touches nothing (a
/// bend moved it) or the directions cancel.
fn away(
    stems: &[Stem],
    axes: &Axes,
    (si, i): (usize, usize),
    r: f64,
    supports: &Supports,
) -> Option<DVec3> {
    let p = stems[si].points[i];
    let mut sum = DVec3::ZERO;
    if supports.distance(p) < r + TOUCH {
        sum += supports.outward(p).unwrap_or(DVec3::ZERO);
    }
    let near = 2 * stems[si].steps;
    // One direction per stem: away from its nearest segment.
    let own = |sj: usize, j: usize| sj == si && i.abs_diff(j).max(i.abs_diff(j + 1)) <= near;
    for (_, _, q) in axes.nearest_per_stem(p, 2.0 * r + TOUCH, own) {
        sum += (p - q).try_normalize().unwrap_or(DVec3::ZERO);
    }
    sum.try_normalize()
}

/// The stem's unit direction at point `i` (central difference).
fn tangent(points: &[DVec3], i: usize) -> DVec3 {
    let a = points[i.saturating_sub(1)];
    let b = points[(i + 1).min(points.len() - 1)];
    (b - a).try_normalize().unwrap_or(DVec3::Y)
}

/// A direction at right angles to `t` that does not turn with the stem's
/// helix: +x, or +z on a stem along x, made perpendicular.
fn free_reference(t: DVec3) -> DVec3 {
    let x = DVec3::X - t * t.x;
    if x.length() > 0.1 {
        x.normalize()
    } else {
        (DVec3::Z - t * t.z).normalize()
    }
}

fn rotate(v: DVec3, axis: DVec3, angle: f64) -> DVec3 {
    DQuat::from_axis_angle(axis, angle) * v
}

/// Where a leaf grows: the node `node` of stem `stem` at `p`, the stem
/// going `t` there.
struct Node {
    stem: usize,
    node: usize,
    cotyledon: bool,
    p: DVec3,
    t: DVec3,
}

/// The leaf at `at` facing `o` (unit, at right angles to the stem), its
/// face turned to `light` (unit), then drooped by `droop` and rolled by
/// `roll` (module docs).
fn make(at: &Node, o: DVec3, light: DVec3, droop: f64, roll: f64, params: &VineParams) -> Leaf {
    let (p, t) = (at.p, at.t);
    let gamma = params.leaf_size;
    let foot = p + o * params.radius;
    let petiole = o * PETIOLE_TILT.cos() + t * PETIOLE_TILT.sin();
    let start = foot + petiole * (PETIOLE_LENGTH * gamma);
    let midrib = o * DROOP.cos() - t * DROOP.sin();
    // The normal: the light made perpendicular to the midrib, or, with
    // the light along it, the thesis' square's (t made perpendicular).
    let lit = light - midrib * light.dot(midrib);
    let normal = if lit.length() > ALONG {
        lit.normalize()
    } else {
        (t - midrib * t.dot(midrib)).normalize()
    };
    // across = normal × midrib, so that midrib × across = normal.
    let across = normal.cross(midrib).normalize();
    // The droop: the whole blade turns so that its midrib tilts `droop`
    // further down, towards −y (about the level axis across the midrib,
    // which is the blade's across axis when it lies level), but not past
    // straight down.
    let (midrib, across) = match midrib.cross(DVec3::NEG_Y).try_normalize() {
        Some(axis) => {
            let tilt = droop.min(midrib.angle_between(DVec3::NEG_Y));
            let droop = DQuat::from_axis_angle(axis, tilt);
            ((droop * midrib).normalize(), droop * across)
        }
        None => (midrib, across),
    };
    // The roll about the midrib.
    let across = rotate(across, midrib, roll).normalize();
    let centre = start + midrib * gamma;
    Leaf {
        stem: at.stem,
        node: at.node,
        cotyledon: at.cotyledon,
        stalk: [foot, start],
        midrib,
        across,
        length: 2.0 * gamma,
        quad: [
            start,
            centre + across * gamma,
            start + midrib * (2.0 * gamma),
            centre - across * gamma,
        ],
    }
}

/// Whether no corner of the blade, its centre or the petiole's end lies
/// inside a support.
fn clear_of(leaf: &Leaf, supports: &Supports) -> bool {
    let [a, b, c, d] = leaf.quad;
    [a, b, c, d, (a + c) * 0.5, leaf.stalk[1]]
        .iter()
        .all(|&q| supports.distance(q) > 0.0)
}
