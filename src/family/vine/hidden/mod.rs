//! Exact hidden-line removal for 3D line drawings: which parts of 3D
//! polylines a [`Camera`] sees past a scene of triangles.
//!
//! A vine's stem winding round its pole vanishes where it passes behind
//! the pole and hides the pole's lines where it passes in front; a leaf
//! hides what lies behind it. The 2D sibling, [`super::depth`], stacks
//! flat shapes at given depths; here depth comes from the model itself.
//!
//! **What it owns.** [`Occluders`]: the triangles that can hide lines (the
//! surfaces of the stem, the supports, the leaves), in a bounding-volume
//! hierarchy. [`Occluders::visible_runs`] and
//! [`Occluders::visible_loop_runs`] cut a polyline into its visible pieces;
//! [`tube_silhouette`] gives the two contour lines of a tube (the stem), to
//! be cut in turn.
//!
//! **Method** (as fogleman's `ln`, with exact cuts). A polyline is sampled
//! so that consecutive samples are at most a step apart *in the picture*;
//! each sample is visible when the ray from the eye to it meets no
//! triangle before it (Möller–Trumbore, both sides of a triangle), and
//! every change between visible and hidden is refined by bisection to a
//! tolerance in the picture. Vector throughout: no raster, no z-buffer. A
//! hidden or visible stretch shorter than the step can fall between two
//! samples and be missed: the step is the smallest detail the test sees.
//!
//! **Cost.** Building [`Occluders`] takes O(n log n) for n triangles
//! (median splits); one visibility test visits O(log n) boxes for a scene
//! spread out in space. A polyline costs one test per sample (its length
//! in the picture over the step), and one per halving at each cut
//! (log2(step / tolerance)).

use glam::DVec3;

use super::camera::{Camera, NEAR};

mod bvh;
#[cfg(test)]
mod tests;

use bvh::Bvh;

/// Most samples one segment of a polyline gets: a segment reaching close
/// to a perspective eye is arbitrarily long in the picture.
const MAX_SAMPLES: usize = 1 << 16;

/// Most halvings refining one cut; after 64 the bracket is below the
/// resolution of an f64 parameter.
const MAX_HALVINGS: usize = 64;

/// The triangles of a scene that hide lines, ready for visibility tests
/// (see the [module docs](self)).
#[derive(Debug, Clone, Default)]
pub(crate) struct Occluders {
    bvh: Bvh,
}

impl Occluders {
    /// The occluders made of `triangles` (corners in any order: both sides
    /// hide). Triangles with a non-finite corner are left out: they hide
    /// nothing.
    pub(crate) fn new(mut triangles: Vec<[DVec3; 3]>) -> Occluders {
        triangles.retain(|t| t.iter().all(|c| c.is_finite()));
        Occluders {
            bvh: Bvh::new(triangles),
        }
    }

    /// The number of triangles.
    #[cfg(test)]
    pub(crate) fn len(&self) -> usize {
        self.bvh.len()
    }

    /// Whether there are no triangles.
    #[cfg(test)]
    pub(crate) fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Whether anything hides `p` from `camera`: a triangle meets the ray
    /// to `p` ([`Camera::ray_to`]) before `t_p − eps` (after the eye, for a
    /// perspective view). `eps` (model units, along the ray) keeps a point
    /// from being hidden by the very surface it lies on.
    pub(crate) fn hides(&self, camera: &Camera, p: DVec3, eps: f64) -> bool {
        let (origin, direction, t) = camera.ray_to(p);
        let from = if camera.is_perspective() {
            0.0
        } else {
            f64::NEG_INFINITY
        };
        self.bvh.any_hit(origin, direction, from, t - eps)
    }

    /// Whether `camera` sees `p`: in front of the eye and not hidden.
    fn sees(&self, camera: &Camera, p: DVec3, eps: f64) -> bool {
        camera.project(p).is_some() && !self.hides(camera, p, eps)
    }

    /// The visible pieces of `polyline`, in order, each of two points or
    /// more.
    ///
    /// Each segment is sampled so that consecutive samples are at most
    /// `step` apart in the picture ([`Camera::project`]'s units: a caller
    /// who fits the picture to the page at s mm per unit passes about
    /// 0.2 / s), every sample is tested with [`Occluders::hides`], and
    /// every change between visible and hidden is refined by bisection
    /// until the cut is known within `tolerance` (picture units). A cut
    /// lies on the visible side of the change, so no hidden part is drawn.
    /// The polyline's own vertices are kept inside visible runs, and
    /// nothing is added between them: straight pieces stay straight,
    /// curves keep their shape, and a polyline wholly visible comes back
    /// as it is, as one run.
    ///
    /// A perspective view does not see what is not in front of the eye
    /// ([`Camera::project`] gives None); a segment reaching close to the
    /// eye gets at most 65536 samples. Fewer than two points: no runs.
    pub(crate) fn visible_runs(
        &self,
        camera: &Camera,
        polyline: &[DVec3],
        step: f64,
        tolerance: f64,
        eps: f64,
    ) -> Vec<Vec<DVec3>> {
        let mut runs = Vec::new();
        let Some(&first) = polyline.first() else {
            return runs;
        };
        let sees = |p| self.sees(camera, p, eps);
        // The run being drawn; empty while the pen is up.
        let mut run = Vec::new();
        let mut seen = sees(first);
        if seen {
            run.push(first);
        }
        let mut params = Vec::new();
        for pair in polyline.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            sample_params(camera, a, b, step, &mut params);
            let mut before = 0.0;
            for &t in &params {
                let now = sees(point_at(a, b, t));
                if now != seen {
                    let (from, to) = if seen { (before, t) } else { (t, before) };
                    let cut = self.cut(camera, (a, b), from, to, tolerance, eps);
                    if seen {
                        // At 0 the cut is `a`, already in the run.
                        if cut > 0.0 {
                            run.push(point_at(a, b, cut));
                        }
                        finish(&mut runs, &mut run);
                    } else if cut < 1.0 {
                        // At 1 the cut is `b`, added below.
                        run.push(point_at(a, b, cut));
                    }
                    seen = now;
                }
                before = t;
            }
            if seen {
                run.push(b);
            }
        }
        finish(&mut runs, &mut run);
        runs
    }

    /// The visible pieces of the closed loop through `ring` (its last
    /// point joined to its first; a ring given closed, last point equal to
    /// the first, is not closed twice), as [`Occluders::visible_runs`]
    /// cuts them. A loop wholly visible is one run that ends where it
    /// starts. Otherwise no run breaks at the ring's first point: the run
    /// through it comes first, from the last cut before it to the first
    /// cut after it, and the others follow in the loop's order.
    pub(crate) fn visible_loop_runs(
        &self,
        camera: &Camera,
        ring: &[DVec3],
        step: f64,
        tolerance: f64,
        eps: f64,
    ) -> Vec<Vec<DVec3>> {
        let (Some(&start), Some(&end)) = (ring.first(), ring.last()) else {
            return Vec::new();
        };
        let mut closed = ring.to_vec();
        if end != start {
            closed.push(start);
        }
        let mut runs = self.visible_runs(camera, &closed, step, tolerance, eps);
        // A run starts or ends at a vertex only when the vertex is seen (a
        // cut never falls on one that is hidden), and the loop's start and
        // end are one point.
        let through_start = |runs: &[Vec<DVec3>]| {
            runs.first().is_some_and(|r| r[0] == start)
                && runs.last().is_some_and(|r| r[r.len() - 1] == start)
        };
        if runs.len() >= 2 && through_start(&runs) {
            let first = runs.remove(0);
            let through = runs.last_mut().expect("two runs or more");
            through.extend_from_slice(&first[1..]);
            runs.rotate_right(1);
        }
        runs
    }

    /// The parameter on the segment `a`–`b` of the visible end of the
    /// change between `seen` (visible) and `hidden`, halving the bracket
    /// until its ends are within `tolerance` in the picture.
    fn cut(
        &self,
        camera: &Camera,
        (a, b): (DVec3, DVec3),
        mut seen: f64,
        mut hidden: f64,
        tolerance: f64,
        eps: f64,
    ) -> f64 {
        for _ in 0..MAX_HALVINGS {
            let ends = camera
                .project(point_at(a, b, seen))
                .zip(camera.project(point_at(a, b, hidden)));
            if ends.is_some_and(|((p, _), (q, _))| p.distance(q) <= tolerance) {
                break;
            }
            let mid = 0.5 * (seen + hidden);
            if self.sees(camera, point_at(a, b, mid), eps) {
                seen = mid;
            } else {
                hidden = mid;
            }
        }
        seen
    }
}

/// Ends the run being drawn: kept if it has two points or more.
fn finish(runs: &mut Vec<Vec<DVec3>>, run: &mut Vec<DVec3>) {
    if run.len() >= 2 {
        runs.push(std::mem::take(run));
    } else {
        run.clear();
    }
}

/// The point at parameter `t` on the segment `a`–`b`: exactly `a` at 0
/// and exactly `b` at 1.
fn point_at(a: DVec3, b: DVec3, t: f64) -> DVec3 {
    if t == 1.0 {
        b
    } else {
        a + (b - a) * t
    }
}

/// Fills `out` with increasing parameters in (0, 1] on the segment `a`–`b`,
/// the last exactly 1, whose points are at most `step` apart in the
/// picture. Of a segment a perspective view sees only in part, the part
/// not in front of the eye gets no samples but its end.
fn sample_params(camera: &Camera, a: DVec3, b: DVec3, step: f64, out: &mut Vec<f64>) {
    out.clear();
    // The stretch [lo, hi] the camera sees: where the depth, linear along
    // the segment, exceeds the near distance (twice it, so its ends
    // project despite rounding).
    let (mut lo, mut hi) = (0.0, 1.0);
    if camera.is_perspective() {
        let (da, db, near) = (camera.depth(a), camera.depth(b), 2.0 * NEAR);
        if da < near && db < near {
            out.push(1.0);
            return;
        }
        if da < near {
            lo = (near - da) / (db - da);
        } else if db < near {
            hi = (near - da) / (db - da);
        }
    }
    let ends = camera
        .project(point_at(a, b, lo))
        .zip(camera.project(point_at(a, b, hi)));
    let Some(((pa, da), (pb, db))) = ends else {
        out.push(1.0);
        return;
    };
    let k = sample_count(pa.distance(pb) / step);
    if lo > 0.0 {
        out.push(lo);
    }
    for j in 1..k {
        let s = j as f64 / k as f64;
        // Evenly spaced in the picture: for a perspective view, 1 / depth
        // (not the parameter) is linear along the picture of a segment.
        let u = if camera.is_perspective() {
            s * da / ((1.0 - s) * db + s * da)
        } else {
            s
        };
        out.push(lo + (hi - lo) * u);
    }
    out.push(hi);
    if hi < 1.0 {
        out.push(1.0);
    }
}

/// The number of pieces for a segment `ratio` steps long in the picture:
/// at least one (also for a step that is negative or NaN), at most
/// [`MAX_SAMPLES`] (also for a step of 0).
fn sample_count(ratio: f64) -> usize {
    if ratio >= MAX_SAMPLES as f64 {
        MAX_SAMPLES
    } else if ratio > 1.0 {
        ratio.ceil() as usize
    } else {
        1
    }
}

/// The two silhouette lines of a tube of `radius` round the polyline
/// `axis` as `camera` sees it: at every axis point `p`, the points
/// `p ± radius · s` with `s` the unit vector along `tangent × looking_at(p)`
/// (the generators of a cylinder's contour; first-order exact for a
/// perspective view). Returns (left, right), as many points as `axis`:
/// left is `p + radius · s`, to the left of the axis as its picture runs
/// (y down, as [`super::Side`]), until a flip that keeps `s` continuous
/// (below) swaps the sides from there on.
///
/// The tangent at a point is the sum of the unit directions of its two
/// segments. Where it is (nearly) along the view, or zero, `s` is the
/// previous point's; before the first point with a proper `s`, that
/// point's, and for an axis seen wholly end on, picture x. `s` turns its
/// sign wherever it would turn by more than 90° from the previous point's,
/// so the lines never jump from one side to the other.
pub(crate) fn tube_silhouette(
    camera: &Camera,
    axis: &[DVec3],
    radius: f64,
) -> (Vec<DVec3>, Vec<DVec3>) {
    let n = axis.len();
    let unit = |from: usize, to: usize| (axis[to] - axis[from]).normalize_or_zero();
    let sides: Vec<Option<DVec3>> = (0..n)
        .map(|i| {
            let tangent = unit(i.saturating_sub(1), i) + unit(i, (i + 1).min(n - 1));
            let s = tangent.cross(camera.looking_at(axis[i]));
            (s.length() > 1e-9 * tangent.length()).then(|| s.normalize())
        })
        .collect();
    let mut previous = sides.iter().find_map(|&s| s).unwrap_or(camera.right());
    let (mut left, mut right) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for (&p, side) in axis.iter().zip(&sides) {
        let mut s = side.unwrap_or(previous);
        if s.dot(previous) < 0.0 {
            s = -s;
        }
        previous = s;
        left.push(p + radius * s);
        right.push(p - radius * s);
    }
    (left, right)
}
