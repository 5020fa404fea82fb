//! Shaping the simulated axis into the drawn one (thesis §3.3.1): sharp
//! turns smoothed by a cubic spline (eq. 3.2), the untwined base and the
//! free tips bent into random cubic Béziers (eq. 3.3), the free tips
//! drooping under their weight, and every point kept out of the supports.
//!
//! Decision (droop): the simulation's free tip is a straight rod standing
//! in the air; a real bindweed tip with nothing to hold arches over and
//! hangs. Past its last contact the axis bends as a cantilever under its
//! own weight does: the slope turns fastest at the root, most where the
//! free part is longest, and a free part of two internodes ends pointing
//! down and outward. The number of points, and so the node
//! indices, never change.
//!
//! Eq. 3.2 also blends the yaw of the directions N_i linearly across a
//! smoothed window; here the directions are not kept (what is drawn is
//! the axis), and the tangent of the spline, which is what the blend
//! approximates, serves wherever a direction is needed.

use std::f64::consts::{FRAC_PI_4, PI, TAU};

use glam::DVec3;

use super::growth::RawStem;
use super::params::VineParams;
use super::support::Supports;
use crate::rng::RandomStream;

/// A turn of the yaw between consecutive directions at least this large
/// is smoothed (thesis: 45°).
const SHARP_TURN: f64 = FRAC_PI_4;

/// How many times a point that came too close to a support is pushed out
/// along the support's normal (more than once only in a concave corner)
/// before it falls back to its simulated position.
const PUSHES: usize = 8;

/// How far a free tip of two internodes or more turns down from its
/// root to its end (radians): 150°, so it hangs outward. Shorter tips
/// turn in proportion.
const DROOP: f64 = 150.0 * PI / 180.0;

/// The most a drooping tip points away from straight up (radians): it
/// hangs, it does not curl back under itself.
const HANG: f64 = 170.0 * PI / 180.0;

/// The shaped axis P'_i of every stem, in the same order. Parents come
/// before their branches (a branch grows from the first stem), so a
/// branch starts where its parent's node was shaped to.
pub(super) fn shape(
    stems: &[RawStem],
    params: &VineParams,
    supports: &Supports,
    rng: &mut RandomStream,
) -> Vec<Vec<DVec3>> {
    let d = params.even_steps();
    let amplitude = 5.0 * params.internode / d as f64;
    let base_end = (params.untwined as usize + 1) * d;
    let mut shaped: Vec<Vec<DVec3>> = Vec::with_capacity(stems.len());
    for stem in stems {
        let mut p = stem.points.clone();
        let f = p.len() - 1;
        smooth(&mut p, &stem.twined, d);
        let first_twined = stem.twined.iter().position(|&t| t).unwrap_or(f);
        // Only what is free is bent: a twined point stays on its support.
        let mut free_from = stem.twined.iter().rposition(|&t| t).unwrap_or(0);
        if stem.parent.is_none() {
            // The cotyledon and the untwined internodes: P_{s+d} moves.
            let end = base_end.min(first_twined);
            bend(&mut p, 0, end, d, [true, false, false], amplitude, rng);
            free_from = free_from.max(end);
        }
        // The tip's last two internodes: P_{e−d} and P_e move.
        let start = f.saturating_sub(2 * d).max(free_from);
        bend(&mut p, start, f, d, [false, true, true], amplitude, rng);
        if params.droop {
            droop(&mut p, free_from, 2.0 * params.internode);
        }
        if let Some((ps, pn)) = stem.parent {
            // Follow the parent's node, fading out before the first twined
            // point (or after one internode).
            let moved = shaped[ps][pn] - stems[ps].points[pn];
            let fade = first_twined.min(d).max(1);
            for (i, q) in p.iter_mut().enumerate().take(fade) {
                *q += moved * (1.0 - i as f64 / fade as f64);
            }
        }
        push_out(&mut p, &stem.points, params.radius, supports);
        if let Some((ps, pn)) = stem.parent {
            p[0] = shaped[ps][pn];
        }
        shaped.push(p);
    }
    shaped
}

/// Eq. 3.2: around each point C where the yaw of N turns by 45° or more,
/// the points C − d/2 … C + d/2 are replaced, one window after the other
/// as in the thesis, by a cubic (Hermite) spline between the points just
/// outside the window, with the tangents the axis has there.
///
/// Decision: a turn between points that all touch a support is left
/// alone. It is the support's own curvature (round a thin pole or the
/// edge of a block the stem turns 45° per point), and a spline across it
/// would cut through the support.
fn smooth(p: &mut [DVec3], twined: &[bool], d: usize) {
    let f = p.len() - 1;
    if f < 3 {
        return;
    }
    let half = d / 2;
    // The yaw of N_i = P_{i+1} − P_i; none where N is vertical.
    let yaw: Vec<Option<f64>> = p
        .windows(2)
        .map(|w| {
            let n = w[1] - w[0];
            (n.x.hypot(n.z) > 1e-6 * n.length()).then(|| (-n.z).atan2(n.x))
        })
        .collect();
    for c in 1..f {
        let (Some(a), Some(b)) = (yaw[c - 1], yaw[c]) else {
            continue;
        };
        let turn = (b - a + PI).rem_euclid(TAU) - PI;
        if turn.abs() < SHARP_TURN || twined[c - 1..=c + 1].iter().all(|&t| t) {
            continue;
        }
        let (lo, hi) = (c.saturating_sub(half).max(1), (c + half).min(f - 1));
        let (i0, i1) = (lo - 1, hi + 1);
        let span = (i1 - i0) as f64;
        let (p0, p1) = (p[i0], p[i1]);
        let t0 = if i0 >= 1 {
            (p0 - p[i0 - 1]) * span
        } else {
            p1 - p0
        };
        let t1 = if i1 < f {
            (p[i1 + 1] - p1) * span
        } else {
            p1 - p0
        };
        for (i, q) in p.iter_mut().enumerate().take(hi + 1).skip(lo) {
            let u = (i - i0) as f64 / span;
            let (u2, u3) = (u * u, u * u * u);
            *q = p0 * (2.0 * u3 - 3.0 * u2 + 1.0)
                + t0 * (u3 - 2.0 * u2 + u)
                + p1 * (-2.0 * u3 + 3.0 * u2)
                + t1 * (u3 - u2);
        }
    }
}

/// Eq. 3.3: points s … e become the cubic Bézier with control points
/// P_s, P_{s+d}, P_{e−d}, P_e, β = (j − s)/(e − s); the controls flagged
/// in `moved` (P_{s+d}, P_{e−d}, P_e) get random x and z offsets within
/// ±`amplitude`. A window shorter than two internodes uses controls at a
/// third… half of it and a bend in proportion.
fn bend(
    p: &mut [DVec3],
    s: usize,
    e: usize,
    d: usize,
    moved: [bool; 3],
    amplitude: f64,
    rng: &mut RandomStream,
) {
    if e < s + 2 {
        return;
    }
    let width = e - s;
    let h = d.min(width / 2);
    let a = amplitude * (width as f64 / (2 * d) as f64).min(1.0);
    let mut offset = |on: bool| {
        if on {
            DVec3::new(rng.symmetric(a), 0.0, rng.symmetric(a))
        } else {
            DVec3::ZERO
        }
    };
    let c0 = p[s];
    let c1 = p[s + h] + offset(moved[0]);
    let c2 = p[e - h] + offset(moved[1]);
    let c3 = p[e] + offset(moved[2]);
    for (j, q) in p.iter_mut().enumerate().take(e + 1).skip(s) {
        let b = (j - s) as f64 / width as f64;
        let nb = 1.0 - b;
        *q = c0 * (nb * nb * nb)
            + c1 * (3.0 * nb * nb * b)
            + c2 * (3.0 * nb * b * b)
            + c3 * (b * b * b);
    }
}

/// Bends the free part `from` … tip down under its weight, each segment
/// keeping its length: the slope of a uniformly loaded cantilever, turned
/// about the level axis across the part's lean by DROOP·(length/`full`)
/// at the end (at most DROOP, and never past HANG from straight up).
fn droop(p: &mut [DVec3], from: usize, full: f64) {
    let f = p.len() - 1;
    if from + 1 >= f {
        return;
    }
    let lengths: Vec<f64> = p[from..].windows(2).map(|w| w[0].distance(w[1])).collect();
    let total: f64 = lengths.iter().sum();
    let lean = p[f] - p[from];
    let Some(root) = (p[from + 1] - p[from]).try_normalize() else {
        return;
    };
    if total <= 0.0 {
        return;
    }
    let level = DVec3::new(lean.x, 0.0, lean.z)
        .try_normalize()
        .or_else(|| DVec3::new(root.x, 0.0, root.z).try_normalize())
        .unwrap_or(DVec3::X);
    let axis = DVec3::Y.cross(level).normalize();
    let tilt = root.y.clamp(-1.0, 1.0).acos();
    let turn = (DROOP * (total / full).min(1.0)).min((HANG - tilt).max(0.0));
    let directions: Vec<DVec3> = p[from..].windows(2).map(|w| w[1] - w[0]).collect();
    let mut at = 0.0;
    let mut q = p[from];
    for (i, (v, len)) in directions.iter().zip(&lengths).enumerate() {
        // The slope at the middle of the segment: 1 − (1 − u)³ of the turn.
        let u = (at + 0.5 * len) / total;
        let angle = turn * (1.0 - (1.0 - u).powi(3));
        q += glam::DQuat::from_axis_angle(axis, angle) * *v;
        p[from + i + 1] = q;
        at += len;
    }
}

/// Moves every point closer than `r` to a support out along the support's
/// normal; a point that cannot be cleared goes back to its simulated
/// position (which is clear).
fn push_out(p: &mut [DVec3], raw: &[DVec3], r: f64, supports: &Supports) {
    for (q, &original) in p.iter_mut().zip(raw) {
        let mut gap = supports.distance(*q);
        for _ in 0..PUSHES {
            if gap >= r {
                break;
            }
            let Some(out) = supports.outward(*q) else {
                break;
            };
            *q += out * (r - gap + 1e-9);
            gap = supports.distance(*q);
        }
        if gap < r {
            *q = original;
        }
    }
}
