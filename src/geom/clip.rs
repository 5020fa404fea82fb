//! Clipping open strokes by a region: the parts of a stroke inside and the
//! parts outside (docs/SPEC.md §2.4 "draw only inside that region", and hidden
//! lines for occlusion).
//!
//! The stroke keeps its curves: each of its segments is cut at the
//! parameters where it crosses the region's boundary, and each piece is
//! classified by the containment of its middle point. The boundary is the
//! region's outline flattened within `tolerance` (straight edges), so cut
//! points and the inside/outside decision near the boundary are right to
//! within the flattening's accuracy, `tolerance` (kurbo's estimate, which
//! it can exceed a little); the pieces are exact sub-curves of the stroke,
//! so inside and outside together have exactly the stroke's length.
//! Strokes that run along the boundary go either way.
//!
//! **Every crossing is found.** The middle point can speak for a whole
//! piece only if the piece does not cross the flattened outline, so the
//! cuts must be all the crossings of the exact stroke curve with the
//! edges. Relative to an edge, a segment is a cubic polynomial (its signed
//! distance from the edge's line) whose Bernstein coefficients are cross
//! products with the control points; its sign changes are isolated by
//! Descartes' rule of signs with de Casteljau halving and refined by a
//! bracketing root-finder (ITP), decisions that rest on signs of computed
//! values only. kurbo's `PathSeg::intersect_line`, used before, solves the
//! same cubic in closed form in the power basis and loses roots when its
//! cubic coefficient nearly cancels — a circle's arc against an edge
//! parallel to its chord, as near-tangent circles and rectangles tilted by
//! rounding produce — and a kept piece then ran deep inside the region.
//! Crossings at or within 1e-9 mm of an edge's end count for the edge, so
//! a stroke through a vertex of the outline is cut there; an extra cut
//! costs nothing, as pieces on the same side are joined again. Where the
//! stroke touches or grazes an edge (roots closer than about 1e-12 in
//! parameter) it is cut only if it changes side. Containment is decided by
//! the same polygon (non-zero winding) within the polygon's own box, not
//! the region's: kurbo flattens a cubic through quadratic curves, so the
//! polygon can stick out of the region's box a little.
//!
//! **Cost.** A segment is tested against the outline edges whose boxes
//! meet the box of its control points (the edges are kept in horizontal
//! bands); one that does not reach an edge's line costs a few products,
//! one that does is halved only while the crossing may lie off the edge,
//! and each crossing is refined once. The work is linear in the segments
//! times the edges near each, never all against all.

use kurbo::{BezPath, Line, ParamCurve, PathSeg, Point, Rect};

use super::region::Region;
use super::subpath::{subpaths, Subpath};
use super::TOLERANCE;

/// Cuts closer than this in a segment's parameter are merged, and pieces
/// shorter than this in parameter are not made (a stroke that touches the
/// boundary at a vertex of the flattened outline would otherwise be cut
/// twice at the same place).
const PARAM_EPS: f64 = 1e-9;

/// A stroke split by a region.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Clipped {
    /// The parts inside the region, in the order and direction of the
    /// stroke.
    pub inside: Vec<BezPath>,
    /// The parts outside the region, likewise.
    pub outside: Vec<BezPath>,
}

/// Splits `stroke` into its parts inside and outside `region`, with the
/// region's boundary flattened within `tolerance` (mm; non-finite or
/// non-positive means [`TOLERANCE`]).
///
/// Each subpath of the stroke is cut where it crosses the boundary; runs of
/// pieces on the same side are joined into one path. A subpath that ends
/// with a close-path and never crosses stays closed; one that does is split
/// into open paths (the run through its start point is joined across it).
/// Subpaths are read as [`super::subpath`] says.
///
/// To clip many strokes by one region, make a [`StrokeClipper`] once.
pub fn clip_stroke(stroke: &BezPath, region: &Region, tolerance: f64) -> Clipped {
    StrokeClipper::new(region, tolerance).clip(stroke)
}

/// A region prepared for clipping many strokes: its flattened outline in a
/// grid of horizontal bands, so that each query looks at the edges nearby.
#[derive(Debug, Clone)]
pub struct StrokeClipper {
    edges: Vec<Line>,
    bounds: Rect,
    y0: f64,
    band_height: f64,
    bands: Vec<Vec<u32>>,
}

impl StrokeClipper {
    /// Prepares `region` (boundary flattened within `tolerance` mm;
    /// non-finite or non-positive means [`TOLERANCE`]).
    pub fn new(region: &Region, tolerance: f64) -> StrokeClipper {
        StrokeClipper::for_union([region], tolerance)
    }

    /// Prepares the union of `regions` without computing it (no boolean
    /// sweep): their outlines, flattened within `tolerance` as in
    /// [`StrokeClipper::new`], are simply put together. Strokes come out
    /// as [`StrokeClipper::new`] of [`Region::union_all`] would cut them,
    /// except that they are also cut where they cross an outline inside
    /// another region (the pieces on either side are joined again), and
    /// that a stroke along an edge two regions share may go either way.
    ///
    /// This rests on two facts, which the tests here check: every
    /// [`Region`] is normalised (winding number 1 inside, 0 outside, so
    /// the outlines put together wind as many times round a point as
    /// there are regions holding it, never less than zero), and
    /// [`StrokeClipper::contains`] uses the non-zero rule (so a point in
    /// two regions at once is inside, where the even-odd rule would put
    /// it outside).
    pub fn for_union<'a>(
        regions: impl IntoIterator<Item = &'a Region>,
        tolerance: f64,
    ) -> StrokeClipper {
        let tolerance = if tolerance.is_finite() && tolerance > 0.0 {
            tolerance
        } else {
            TOLERANCE
        };
        let mut edges = Vec::new();
        for poly in regions.into_iter().flat_map(|r| r.polygons(tolerance)) {
            for i in 0..poly.len() {
                edges.push(Line::new(poly[i], poly[(i + 1) % poly.len()]));
            }
        }
        // The box of the flattened outline, not the region's: kurbo
        // flattens a cubic through quadratic curves, so a vertex may lie a
        // little outside the region's box, and points near it would be
        // taken for outside the polygon without looking at its edges.
        let bounds = edges
            .iter()
            .map(|e| Rect::from_points(e.p0, e.p1))
            .reduce(|a, b| a.union(b))
            .unwrap_or(Rect::ZERO);
        let n_bands = (edges.len() / 4).clamp(1, 4096);
        let band_height = (bounds.height() / n_bands as f64).max(f64::MIN_POSITIVE);
        let mut bands = vec![Vec::new(); n_bands];
        let mut clipper = StrokeClipper {
            edges: Vec::new(),
            bounds,
            y0: bounds.y0,
            band_height,
            bands: Vec::new(),
        };
        for (k, e) in edges.iter().enumerate() {
            let (lo, hi) = clipper.band_range(e.p0.y.min(e.p1.y), e.p0.y.max(e.p1.y), n_bands);
            for band in &mut bands[lo..=hi] {
                band.push(k as u32);
            }
        }
        clipper.edges = edges;
        clipper.bands = bands;
        clipper
    }

    fn band_range(&self, y_lo: f64, y_hi: f64, n: usize) -> (usize, usize) {
        let idx = |y: f64| {
            let k = ((y - self.y0) / self.band_height).floor();
            if k.is_nan() || k < 0.0 {
                0
            } else {
                (k as usize).min(n - 1)
            }
        };
        (idx(y_lo), idx(y_hi))
    }

    /// Whether `p` is inside the flattened region (non-zero winding; points
    /// on the outline may go either way).
    pub fn contains(&self, p: Point) -> bool {
        if self.bands.is_empty() || !self.bounds.contains(p) {
            return false;
        }
        let (k, _) = self.band_range(p.y, p.y, self.bands.len());
        let mut winding = 0;
        for &e in &self.bands[k] {
            let Line { p0: a, p1: b } = self.edges[e as usize];
            if (a.y <= p.y) != (b.y <= p.y) {
                let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if x > p.x {
                    winding += if b.y > a.y { 1 } else { -1 };
                }
            }
        }
        winding != 0
    }

    /// The edges whose bounding boxes meet `r`, each once, in index order.
    fn edges_near(&self, r: Rect) -> Vec<usize> {
        if self.bands.is_empty() || r.y1 < self.bounds.y0 || r.y0 > self.bounds.y1 {
            return Vec::new();
        }
        let (lo, hi) = self.band_range(r.y0, r.y1, self.bands.len());
        let mut found: Vec<usize> = Vec::new();
        for band in &self.bands[lo..=hi] {
            for &e in band {
                let l = self.edges[e as usize];
                let eb = Rect::from_points(l.p0, l.p1);
                if eb.overlaps(r) {
                    found.push(e as usize);
                }
            }
        }
        found.sort_unstable();
        found.dedup();
        found
    }

    /// Splits `stroke` into its parts inside and outside (see
    /// [`clip_stroke`]).
    pub fn clip(&self, stroke: &BezPath) -> Clipped {
        let mut out = Clipped::default();
        for sub in subpaths(stroke) {
            self.clip_subpath(sub, &mut out);
        }
        out
    }

    fn clip_subpath(&self, sub: Subpath, out: &mut Clipped) {
        // Pieces in order: (segment piece, inside?).
        let mut pieces: Vec<(PathSeg, bool)> = Vec::new();
        for seg in sub.segments() {
            let cuts = self.cuts(&seg);
            for w in cuts.windows(2) {
                let (t0, t1) = (w[0], w[1]);
                let inside = self.contains(seg.eval(0.5 * (t0 + t1)));
                pieces.push((seg.subsegment(t0..t1), inside));
            }
        }
        if pieces.is_empty() {
            return;
        }
        // Runs of pieces on one side.
        let mut runs: Vec<(Vec<PathSeg>, bool)> = Vec::new();
        for (p, side) in pieces {
            match runs.last_mut() {
                Some((run, s)) if *s == side => run.push(p),
                _ => runs.push((vec![p], side)),
            }
        }
        let whole = runs.len() == 1;
        // Only a written close-path makes a run go on through the start:
        // a stroke that merely comes back to its start is cut there, as
        // it is drawn.
        let closed = sub.ends_with_close();
        if closed && !whole && runs[0].1 == runs[runs.len() - 1].1 {
            // The last run goes on through the start point into the first.
            let (first, _) = runs.remove(0);
            if let Some((last, _)) = runs.last_mut() {
                last.extend(first);
            }
        }
        for (run, inside) in runs {
            let mut path = BezPath::new();
            path.move_to(run[0].start());
            for seg in &run {
                match *seg {
                    PathSeg::Line(l) => path.line_to(l.p1),
                    PathSeg::Quad(q) => path.quad_to(q.p1, q.p2),
                    PathSeg::Cubic(c) => path.curve_to(c.p1, c.p2, c.p3),
                }
            }
            if whole && closed {
                path.close_path();
            }
            if inside {
                out.inside.push(path);
            } else {
                out.outside.push(path);
            }
        }
    }

    /// The parameters where `seg` crosses the outline, with 0 and 1, sorted
    /// and without near-duplicates.
    fn cuts(&self, seg: &PathSeg) -> Vec<f64> {
        let mut ts = vec![0.0];
        let ctrl = cubic_points(seg);
        // The box of the control points holds the segment, whatever the
        // rounding (the exact bounding box rests on solving for extrema).
        let bb = ctrl[1..]
            .iter()
            .fold(Rect::from_points(ctrl[0], ctrl[0]), |r, p| r.union_pt(*p));
        for e in self.edges_near(bb.inflate(1e-9, 1e-9)) {
            edge_crossings(seg, &ctrl, self.edges[e], &mut ts);
        }
        ts.push(1.0);
        ts.sort_by(f64::total_cmp);
        ts.dedup_by(|b, a| *b - *a < PARAM_EPS);
        if let Some(last) = ts.last_mut() {
            // `dedup` may have merged 1 into a cut just before it.
            *last = 1.0;
        }
        ts
    }
}

/// A crossing this close (mm) beyond either end of an outline edge still
/// counts: where the stroke crosses the outline at a vertex, rounding may
/// put the crossing just outside both edges that meet there. An extra cut
/// costs nothing (pieces on the same side are joined again); a missed one
/// would leave a piece on both sides.
const EDGE_SLACK: f64 = 1e-9;

/// Refining a crossing stops when its bracket is this narrow in the
/// segment's parameter.
const ROOT_EPS: f64 = 1e-14;

/// Subdividing a parameter interval stops at this depth (an interval of
/// 2⁻⁴⁰ ≈ 1e-12); see [`isolate`].
const MAX_DEPTH: u32 = 40;

/// An interval holding one crossing of an edge's line is halved until it
/// lies on the edge, or is dropped as off the edge, down to this depth;
/// below it, the crossing is found and then checked (see [`isolate`]).
const REFINE_DEPTH: u32 = 16;

/// Bernstein coefficients of a polynomial of degree ≤ 3, as a cubic.
type Coefs = [f64; 4];

/// The control points of a segment as a cubic (lines and quadratic curves
/// degree-elevated: the same curve, with the same parameter).
fn cubic_points(seg: &PathSeg) -> [Point; 4] {
    match *seg {
        PathSeg::Line(l) => [
            l.p0,
            l.p0.lerp(l.p1, 1.0 / 3.0),
            l.p0.lerp(l.p1, 2.0 / 3.0),
            l.p1,
        ],
        PathSeg::Quad(q) => {
            let c = q.raise();
            [c.p0, c.p1, c.p2, c.p3]
        }
        PathSeg::Cubic(c) => [c.p0, c.p1, c.p2, c.p3],
    }
}

/// Appends the parameters in (0, 1) where `seg` (with control points
/// `ctrl`, as a cubic) crosses the straight edge `edge`.
///
/// Two cubic polynomials describe the segment relative to the edge: its
/// signed distance from the edge's line (times the edge's length) and its
/// position along the edge (0 at the edge's start, 1 at its end). Their
/// Bernstein coefficients are the cross and dot products of the edge's
/// direction with the control points, and [`isolate`] finds the sign
/// changes of the first where the second may lie in [0, 1]. (kurbo's
/// `PathSeg::intersect_line` solves the same polynomial in closed form in
/// the power basis, which loses roots when the cubic coefficient nearly
/// cancels: a circular arc against an edge parallel to its chord, as the
/// flattened outline of a near-tangent circle or a rectangle that rounding
/// has tilted by 1e-16 has.) A crossing counts when it lies on the edge,
/// within [`EDGE_SLACK`].
fn edge_crossings(seg: &PathSeg, ctrl: &[Point; 4], edge: Line, out: &mut Vec<f64>) {
    let d = edge.p1 - edge.p0;
    let len2 = d.hypot2();
    if len2 == 0.0 || !len2.is_finite() {
        return;
    }
    let f = ctrl.map(|p| d.cross(p - edge.p0));
    if sign_variations(&f) == 0 {
        // The segment does not cross the edge's line (the common case).
        return;
    }
    let inv = len2.recip();
    let g = ctrl.map(|p| d.dot(p - edge.p0) * inv);
    let slack = EDGE_SLACK / len2.sqrt();
    let first = out.len();
    isolate(&f, (-slack, 1.0 + slack), f, g, (0.0, 1.0), 0, out);
    // The hull test in `isolate` is coarse; check each crossing exactly.
    let mut k = first;
    while k < out.len() {
        let u = (seg.eval(out[k]) - edge.p0).dot(d) * inv;
        if (-slack..=1.0 + slack).contains(&u) {
            k += 1;
        } else {
            out.swap_remove(k);
        }
    }
}

/// Appends the parameters in (a, b) where the polynomial `whole` (the
/// distance from an edge's line, coefficients on [0, 1]) changes sign
/// while the position along the edge may lie in `range`; `f` and `g` are
/// the coefficients of the distance and the position on [a, b].
///
/// Root isolation by Descartes' rule of signs in the Bernstein basis: an
/// interval whose coefficients of `f` never change sign holds no root, one
/// whose coefficients change sign once holds exactly one (found by
/// [`refine`]), and any other is halved (de Casteljau) and both halves
/// looked at again. Every decision compares signs of values computed from
/// the coefficients, so no crossing is lost however ill-conditioned the
/// power-basis form would be. Only an interval still undecided at
/// [`MAX_DEPTH`] (several roots within about 1e-12 of each other: a stroke
/// touching or grazing the line) is decided by the signs at its ends: one
/// cut in its middle if they differ, none if not.
///
/// An interval whose coefficients of `g` all lie on one side of `range`
/// is off the edge (the convex hull property) and dropped. Many edges near
/// a segment have a line that crosses it somewhere but not on the edge, so
/// an interval with one crossing is halved on while it may lie off the
/// edge (to [`REFINE_DEPTH`]): halving is cheaper than refining.
fn isolate(
    whole: &Coefs,
    range: (f64, f64),
    f: Coefs,
    g: Coefs,
    (a, b): (f64, f64),
    depth: u32,
    out: &mut Vec<f64>,
) {
    let (lo, hi) = range;
    if g.iter().all(|u| *u < lo) || g.iter().all(|u| *u > hi) {
        return;
    }
    match sign_variations(&f) {
        0 => {}
        1 if depth >= REFINE_DEPTH || g.iter().all(|u| (lo..=hi).contains(u)) => {
            out.push(refine(whole, a, b, first_sign(&f)))
        }
        v if depth >= MAX_DEPTH => {
            if v > 0 && first_sign(&f) != last_sign(&f) {
                out.push(0.5 * (a + b));
            }
        }
        _ => {
            let (fl, fr) = split_half(&f);
            let (gl, gr) = split_half(&g);
            let m = 0.5 * (a + b);
            if fl[3] == 0.0 && last_sign(&fl) != first_sign(&fr) {
                // A sign change exactly at the split point is interior to
                // neither half.
                out.push(m);
            }
            isolate(whole, range, fl, gl, (a, m), depth + 1, out);
            isolate(whole, range, fr, gr, (m, b), depth + 1, out);
        }
    }
}

/// How often the sign changes along `c`, zeros skipped.
fn sign_variations(c: &Coefs) -> u32 {
    let mut v = 0;
    let mut last = 0.0;
    for &x in c {
        if x != 0.0 {
            if last != 0.0 && (x > 0.0) != (last > 0.0) {
                v += 1;
            }
            last = x;
        }
    }
    v
}

/// Whether the first non-zero value of `c` is positive (the sign of the
/// polynomial just after the interval's start).
fn first_sign(c: &Coefs) -> bool {
    c.iter().find(|x| **x != 0.0).is_some_and(|x| *x > 0.0)
}

/// Whether the last non-zero value of `c` is positive (the sign of the
/// polynomial just before the interval's end).
fn last_sign(c: &Coefs) -> bool {
    c.iter()
        .rev()
        .find(|x| **x != 0.0)
        .is_some_and(|x| *x > 0.0)
}

/// The Bernstein coefficients of the two halves of an interval (de
/// Casteljau).
fn split_half(c: &Coefs) -> (Coefs, Coefs) {
    let [c0, c1, c2, c3] = *c;
    let (m01, m12, m23) = (0.5 * (c0 + c1), 0.5 * (c1 + c2), 0.5 * (c2 + c3));
    let (m012, m123) = (0.5 * (m01 + m12), 0.5 * (m12 + m23));
    let mid = 0.5 * (m012 + m123);
    ([c0, m01, m012, mid], [mid, m123, m23, c3])
}

/// The polynomial with Bernstein coefficients `c` (on [0, 1]) at `t`.
fn bernstein_eval(c: &Coefs, t: f64) -> f64 {
    let mt = 1.0 - t;
    let [c0, c1, c2, c3] = *c;
    let (m01, m12, m23) = (mt * c0 + t * c1, mt * c1 + t * c2, mt * c2 + t * c3);
    let (m012, m123) = (mt * m01 + t * m12, mt * m12 + t * m23);
    mt * m012 + t * m123
}

/// The one sign change of the polynomial `c` (coefficients on [0, 1]) in
/// (a, b), where it starts positive if `start_positive`: by the ITP method
/// (bisection's worst case, usually far fewer steps), evaluating the
/// polynomial afresh from `c` at every step, to [`ROOT_EPS`]. Where
/// rounding makes the values at the ends disagree with the signs the
/// coefficients gave, by bisection on the sign alone.
fn refine(c: &Coefs, a: f64, b: f64, start_positive: bool) -> f64 {
    let s = if start_positive { -1.0 } else { 1.0 };
    let f = |t: f64| s * bernstein_eval(c, t);
    let (ya, yb) = (f(a), f(b));
    if ya < 0.0 && yb > 0.0 {
        return kurbo::common::solve_itp(f, a, b, ROOT_EPS, 1, 0.2 / (b - a), ya, yb);
    }
    let (mut a, mut b) = (a, b);
    while b - a > ROOT_EPS {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        let v = f(m);
        if v == 0.0 {
            return m;
        }
        if v < 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::path_length;
    use crate::geom::region::tests::{arb_region, circle, rect};
    use crate::geom::region::FillRule;
    use kurbo::{Affine, Circle, CubicBez, ParamCurveNearest, PathEl, Shape};
    use proptest::prelude::*;

    fn total(paths: &[BezPath]) -> f64 {
        paths.iter().map(path_length).sum()
    }

    #[test]
    fn line_through_a_square() {
        let sq = rect(0.0, 0.0, 10.0, 10.0);
        let mut l = BezPath::new();
        l.move_to((-5.0, 5.0));
        l.line_to((15.0, 5.0));
        let c = clip_stroke(&l, &sq, 0.01);
        assert_eq!(c.inside.len(), 1);
        assert_eq!(c.outside.len(), 2);
        assert!((total(&c.inside) - 10.0).abs() < 1e-9);
        assert!((total(&c.outside) - 10.0).abs() < 1e-9);
        // Direction of the stroke is kept.
        assert_eq!(
            c.outside[0].elements()[0],
            PathEl::MoveTo(Point::new(-5.0, 5.0))
        );
    }

    #[test]
    fn curves_stay_curves_and_cut_at_the_circle() {
        let disc = circle(0.0, 0.0, 5.0);
        let mut s = BezPath::new();
        s.move_to((-10.0, 0.0));
        s.curve_to((-3.0, 8.0), (3.0, -8.0), (10.0, 0.0));
        let c = clip_stroke(&s, &disc, 1e-4);
        assert_eq!(c.inside.len(), 1);
        let inner = &c.inside[0];
        assert!(matches!(inner.elements()[1], PathEl::CurveTo(..)));
        for p in [
            inner.segments().next().unwrap().start(),
            inner.segments().last().unwrap().end(),
        ] {
            assert!((p.to_vec2().hypot() - 5.0).abs() < 1e-3, "{p:?}");
        }
        let len = path_length(&s);
        assert!((total(&c.inside) + total(&c.outside) - len).abs() < 1e-6);
    }

    #[test]
    fn holes_cut_strokes_too() {
        let ring = circle(0.0, 0.0, 10.0).difference(&circle(0.0, 0.0, 4.0));
        let mut l = BezPath::new();
        l.move_to((-20.0, 0.0));
        l.line_to((20.0, 0.0));
        let c = clip_stroke(&l, &ring, 1e-4);
        assert_eq!(c.inside.len(), 2);
        assert_eq!(c.outside.len(), 3);
        assert!((total(&c.inside) - 12.0).abs() < 1e-3);
    }

    #[test]
    fn closed_strokes() {
        let sq = rect(0.0, 0.0, 10.0, 10.0);
        // Wholly inside: stays one closed path.
        let inner = Rect::new(2.0, 2.0, 4.0, 4.0).to_path(0.0);
        let c = clip_stroke(&inner, &sq, 0.01);
        assert_eq!(c.inside.len(), 1);
        assert!(c.outside.is_empty());
        assert_eq!(c.inside[0].elements().last(), Some(&PathEl::ClosePath));
        // Crossing: the run through the start point is one path.
        let across = Rect::new(5.0, 2.0, 15.0, 4.0).to_path(0.0);
        let c = clip_stroke(&across, &sq, 0.01);
        assert_eq!((c.inside.len(), c.outside.len()), (1, 1));
        assert!((total(&c.inside) - 12.0).abs() < 1e-9);
        assert!((total(&c.outside) - 12.0).abs() < 1e-9);
    }

    /// [`StrokeClipper::for_union`] rests on normalised regions and the
    /// non-zero rule: with even-odd, or with a region whose contours wind
    /// the wrong way, the lens where two discs overlap (winding 2) and a
    /// ring's hole covered by a disc (winding 0 + 1) would come out wrong.
    #[test]
    fn a_union_clips_without_a_sweep() {
        let line = |y: f64| {
            let mut l = BezPath::new();
            l.move_to((-30.0, y));
            l.line_to((40.0, y));
            l
        };
        let discs = [circle(0.0, 0.0, 10.0), circle(12.0, 0.0, 10.0)];
        let put_together = StrokeClipper::for_union(&discs, 1e-4);
        assert!(put_together.contains(Point::new(6.0, 0.0)));
        let c = put_together.clip(&line(0.0));
        assert_eq!((c.inside.len(), c.outside.len()), (1, 2));
        assert!((total(&c.inside) - 32.0).abs() < 1e-6);
        let swept = clip_stroke(&line(0.0), &Region::union_all(&discs), 1e-4);
        assert!((total(&swept.inside) - total(&c.inside)).abs() < 1e-3);

        let ring = circle(0.0, 0.0, 10.0).difference(&circle(0.0, 0.0, 4.0));
        let cover = circle(0.0, 0.0, 5.0);
        let put_together = StrokeClipper::for_union([&ring, &cover], 1e-4);
        assert!(put_together.contains(Point::ZERO));
        let c = put_together.clip(&line(0.0));
        assert_eq!((c.inside.len(), c.outside.len()), (1, 2));
        assert!((total(&c.inside) - 20.0).abs() < 1e-6);
        // Nothing: nothing inside.
        let none = StrokeClipper::for_union([], 1e-4).clip(&line(0.0));
        assert_eq!((none.inside.len(), none.outside.len()), (0, 1));
    }

    #[test]
    fn empty_inputs() {
        let sq = rect(0.0, 0.0, 1.0, 1.0);
        assert_eq!(clip_stroke(&BezPath::new(), &sq, 0.01), Clipped::default());
        let mut l = BezPath::new();
        l.move_to((0.5, 0.5));
        l.line_to((2.0, 0.5));
        let c = clip_stroke(&l, &Region::empty(), 0.01);
        assert!(c.inside.is_empty());
        assert_eq!(c.outside.len(), 1);
    }

    /// Distance from `p` to the clipper's flattened outline.
    fn outline_distance(clipper: &StrokeClipper, p: Point) -> f64 {
        clipper
            .edges
            .iter()
            .map(|e| e.nearest(p, 0.0).distance_sq)
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    }

    /// Points of a piece that lie on the wrong side of the flattened
    /// outline, farther than `slack` from it (sampled finely: a missed cut
    /// shows as a run of wrong points, wherever the midpoint falls).
    fn wrong_side(clipper: &StrokeClipper, c: &Clipped, slack: f64) -> Vec<(Point, bool)> {
        let mut wrong = Vec::new();
        for (paths, inside) in [(&c.inside, true), (&c.outside, false)] {
            for p in paths {
                for seg in p.segments() {
                    for k in 1..32 {
                        let q = seg.eval(k as f64 / 32.0);
                        if clipper.contains(q) != inside && outline_distance(clipper, q) > slack {
                            wrong.push((q, inside));
                        }
                    }
                }
            }
        }
        wrong
    }

    /// The sign changes in (0, 1) of the polynomial with Bernstein
    /// coefficients `c` (degree 1 to 3), all on the edge.
    fn bernstein_roots(c: &[f64], out: &mut Vec<f64>) {
        // Degree elevation to a cubic.
        let f = match *c {
            [a, b] => [a, (2.0 * a + b) / 3.0, (a + 2.0 * b) / 3.0, b],
            [a, b, c] => [a, (a + 2.0 * b) / 3.0, (2.0 * b + c) / 3.0, c],
            [a, b, c, d] => [a, b, c, d],
            _ => unreachable!(),
        };
        isolate(&f, (0.0, 1.0), f, [0.5; 4], (0.0, 1.0), 0, out);
    }

    #[test]
    fn roots_of_a_polynomial_in_bernstein_form() {
        // -(1-t)³ + 9t(1-t)² - 9t²(1-t) + t³: three roots, one of them
        // exactly at the first split point.
        let c = [-1.0, 3.0, -3.0, 1.0];
        let mut roots = Vec::new();
        bernstein_roots(&c, &mut roots);
        roots.sort_by(f64::total_cmp);
        assert_eq!(roots.len(), 3, "{roots:?}");
        assert_eq!(roots[1], 0.5);
        for t in roots {
            assert!(bernstein_eval(&c, t).abs() < 1e-12, "{t}");
        }
        // No sign change: no root, even where the curve touches zero.
        let mut none = Vec::new();
        bernstein_roots(&[1.0, -1.0, 1.0], &mut none);
        bernstein_roots(&[1.0, 0.0, 1.0], &mut none);
        bernstein_roots(&[0.0, 0.0, 0.0, 0.0], &mut none);
        // (1 - 2t)² touches zero at 1/2: a double root, no crossing.
        bernstein_roots(&[1.0, -1.0, 1.0], &mut none);
        assert!(none.is_empty(), "{none:?}");
        let mut line = Vec::new();
        bernstein_roots(&[-1.0, 3.0], &mut line);
        assert_eq!(line, [0.25]);
    }

    /// Regression (proptest-regressions/plot/occlude.txt, the rectangle):
    /// a circle's quarter arc, symmetric about a horizontal axis, against
    /// the left edge of a rectangle that rounding has tilted by 5e-15 mm.
    /// The cubic coefficient of the distance polynomial nearly cancels, and
    /// kurbo's closed-form solver (`PathSeg::intersect_line`) lost the
    /// crossing: the arc's part inside the rectangle was kept as outside.
    #[test]
    fn an_arc_crosses_an_edge_tilted_by_rounding() {
        let arc = CubicBez::new(
            (63.177462179298104, 13.25980549061136),
            (62.185423071280475, 11.199815056576211),
            (62.185423071280475, 8.80018494342379),
            (63.177462179298104, 6.740194509388642),
        );
        let edge = Line::new(
            (62.533462714872755, 39.445086108874875),
            (62.53346271487276, 10.0),
        );
        let seg = PathSeg::Cubic(arc);
        let mut ts = Vec::new();
        edge_crossings(&seg, &cubic_points(&seg), edge, &mut ts);
        assert_eq!(ts.len(), 1, "{ts:?}");
        let q = arc.eval(ts[0]);
        assert!((q.x - 62.53346271487276).abs() < 1e-9, "{q:?}");
        assert!((q.y - 11.2222).abs() < 1e-3, "{q:?}");

        let mut outline = BezPath::new();
        outline.move_to(edge.p0);
        outline.line_to(edge.p1);
        outline.line_to((63.53346271487277, 10.0));
        outline.line_to((63.53346271487277, 39.445086108874875));
        outline.close_path();
        let r = Region::new(outline, FillRule::NonZero).unwrap();
        let clipper = StrokeClipper::new(&r, TOLERANCE);
        let c = clipper.clip(&BezPath::from_path_segments(std::iter::once(seg)));
        assert_eq!((c.inside.len(), c.outside.len()), (1, 1), "{c:?}");
        assert_eq!(c.inside[0].elements()[0], PathEl::MoveTo(arc.p0));
        assert!(wrong_side(&clipper, &c, 1e-9).is_empty());
    }

    /// Regression (proptest-regressions/plot/occlude.txt, the circles): a
    /// circle crossing a smaller one almost tangentially. A flattened edge
    /// of the small circle is nearly parallel to the chord of the big
    /// circle's arc, so again the cubic coefficient nearly cancels and a
    /// crossing was lost; the arc went on as outside while 0.5 mm deep
    /// inside.
    #[test]
    fn near_tangent_circles() {
        // As on the page: drawn, then moved by the margins.
        let page = Affine::translate((10.0, 10.0));
        let back = page
            * Circle::new((54.7371805476822, 28.615197635560634), 17.14878561741582).to_path(1e-4);
        let radius = 12.607902449699154;
        let centre = page * Point::new(52.03490236404308, 33.144545148469895);
        let front = Region::new(
            page * Circle::new((52.03490236404308, 33.144545148469895), radius).to_path(1e-4),
            FillRule::NonZero,
        )
        .unwrap();
        let clipper = StrokeClipper::new(&front, TOLERANCE);
        let c = clipper.clip(&back);
        assert_eq!((c.inside.len(), c.outside.len()), (1, 1), "{c:?}");
        assert!(wrong_side(&clipper, &c, 1e-9).is_empty());
        // The hidden arc ends on the front circle (within the flattening).
        let inner = &c.inside[0];
        for p in [
            inner.segments().next().unwrap().start(),
            inner.segments().last().unwrap().end(),
        ] {
            let d = (p - centre).hypot() - radius;
            assert!(d.abs() <= TOLERANCE, "{p:?}: {d}");
        }
        // Nothing kept lies deeper inside the front circle than the
        // flattening allows.
        for seg in c.outside.iter().flat_map(|p| p.segments()) {
            for k in 0..=64 {
                let d = radius - (seg.eval(k as f64 / 64.0) - centre).hypot();
                assert!(d <= TOLERANCE, "{d}");
            }
        }
        let len = path_length(&back);
        assert!((total(&c.inside) + total(&c.outside) - len).abs() < 1e-6);
    }

    /// Regression (proptest-regressions/geom/clip.txt): kurbo flattens a
    /// cubic through quadratic curves, so the lowest vertex of a flattened
    /// circle lay 2e-4 mm below the circle's box. The clipper took its box
    /// for the polygon's and called every point below the region's box
    /// outside, so a circle stroke grazing the bottom of the outline was
    /// cut where it crosses an edge but classified by its box.
    #[test]
    fn the_flattened_outline_may_leave_the_regions_box() {
        let centre = Point::new(10.0, 10.0);
        let (r, offset, gap) = (5.459614719484401, 0.12114267007316325, -0.18670842278100108);
        let disc = Region::new(Circle::new(centre, r).to_path(1e-4), FillRule::NonZero).unwrap();
        let clipper = StrokeClipper::new(&disc, TOLERANCE);
        let lowest = clipper
            .edges
            .iter()
            .map(|e| e.p0)
            .max_by(|a, b| a.y.total_cmp(&b.y))
            .unwrap();
        let bottom = disc.bounds().y1;
        assert!(lowest.y > bottom, "{lowest:?} {bottom}");
        let q = Point::new(lowest.x, 0.5 * (lowest.y + bottom));
        assert!(clipper.contains(q));

        let u = kurbo::Vec2::from_angle(3.7219823555689757);
        let stroke = Circle::new(centre - u * offset, r + offset + gap).to_path(1e-4);
        let c = clipper.clip(&stroke);
        let wrong = wrong_side(&clipper, &c, 1e-9);
        assert!(wrong.is_empty(), "{wrong:?}");
    }

    #[test]
    fn strokes_through_vertices_and_along_edges() {
        // A diamond: the stroke crosses it exactly at two vertices.
        let mut d = BezPath::new();
        d.move_to((0.0, -1.0));
        d.line_to((1.0, 0.0));
        d.line_to((0.0, 1.0));
        d.line_to((-1.0, 0.0));
        d.close_path();
        let diamond = Region::new(d, FillRule::NonZero).unwrap();
        let mut l = BezPath::new();
        l.move_to((-3.0, 0.0));
        l.line_to((3.0, 0.0));
        let c = clip_stroke(&l, &diamond, 0.01);
        assert_eq!((c.inside.len(), c.outside.len()), (1, 2), "{c:?}");
        assert!((total(&c.inside) - 2.0).abs() < 1e-12);
        // A stroke along an edge of a square and past its ends: cut at the
        // corners, and the part on the edge goes either way.
        let sq = rect(0.0, 0.0, 10.0, 10.0);
        let mut along = BezPath::new();
        along.move_to((-5.0, 0.0));
        along.line_to((15.0, 0.0));
        let c = clip_stroke(&along, &sq, 0.01);
        assert!((total(&c.inside) + total(&c.outside) - 20.0).abs() < 1e-12);
        assert!(total(&c.outside) >= 10.0 - 1e-12, "{c:?}");
    }

    /// A stroke piece a few µm long crossing an edge at a shallow angle
    /// (as pieces already cut by another shape can be) is still cut:
    /// kurbo's line–line test took lines whose cross product was below
    /// 1e-9 for parallel.
    #[test]
    fn a_tiny_piece_crossing_at_a_shallow_angle_is_cut() {
        let sq = rect(0.0, 0.0, 1.0, 1.0);
        let mut l = BezPath::new();
        l.move_to((0.5 - 1e-6, -1e-10));
        l.line_to((0.5 + 1e-6, 1e-10));
        let c = clip_stroke(&l, &sq, 0.01);
        assert_eq!((c.inside.len(), c.outside.len()), (1, 1), "{c:?}");
        assert!((total(&c.inside) - 1e-6).abs() < 1e-12);
    }

    fn arb_stroke() -> impl Strategy<Value = BezPath> {
        prop::collection::vec((-10.0..100.0f64, -10.0..100.0f64), 4..13).prop_map(|pts| {
            let mut p = BezPath::new();
            p.move_to(pts[0]);
            let mut i = 1;
            while i + 2 < pts.len() {
                let c = CubicBez::new(pts[i - 1], pts[i], pts[i + 1], pts[i + 2]);
                p.curve_to(c.p1, c.p2, c.p3);
                i += 3;
            }
            while i < pts.len() {
                p.line_to(pts[i]);
                i += 1;
            }
            p
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn inside_plus_outside_is_the_whole_length(r in arb_region(), s in arb_stroke()) {
            let c = clip_stroke(&s, &r, TOLERANCE);
            let len = path_length(&s);
            let sum = total(&c.inside) + total(&c.outside);
            let segments = s.segments().count() as f64;
            prop_assert!((sum - len).abs() <= TOLERANCE * segments, "{sum} vs {len}");
        }

        /// Every point of every part, not just the middle points the
        /// pieces were classified by, lies on its side of the flattened
        /// outline (or on it), also for circles against outlines that
        /// rounding has tilted (a round trip through a rotation).
        #[test]
        fn cuts_are_complete(
            r in arb_region(),
            s in arb_stroke(),
            circles in prop::collection::vec((0.0..60.0f64, 0.0..60.0f64, 1.0..30.0f64), 0..3),
            angle in -0.5..0.5f64,
            scale in 0.5..2.0f64,
        ) {
            let a = Affine::rotate(angle) * Affine::scale(scale);
            let r = r.transformed(a).unwrap().transformed(a.inverse()).unwrap();
            let mut stroke = s;
            for (x, y, radius) in circles {
                let c = Circle::new((x, y), radius).to_path(1e-4);
                stroke.extend(a.inverse() * (a * c));
            }
            let clipper = StrokeClipper::new(&r, TOLERANCE);
            let c = clipper.clip(&stroke);
            let wrong = wrong_side(&clipper, &c, 1e-7);
            prop_assert!(wrong.is_empty(), "{wrong:?}");
            let len = path_length(&stroke);
            let sum = total(&c.inside) + total(&c.outside);
            let segments = stroke.segments().count() as f64;
            // Each length is measured within 1e-3 (`path_length`).
            let pieces = c.inside.iter().chain(&c.outside).map(|p| p.segments().count()).sum::<usize>();
            prop_assert!((sum - len).abs() <= 1e-3 * (segments + pieces as f64), "{sum} vs {len}");
        }

        /// The same near tangencies, where they are likely: a circle
        /// stroke against a circle or a rectangle that it almost touches
        /// (internally or externally), at the angles where the circles'
        /// arcs and flattened edges run parallel (multiples of 22.5°) or
        /// anywhere, shapes through a rotation round trip as in a
        /// transformed group.
        #[test]
        fn cuts_are_complete_near_tangencies(
            (cx, cy, r) in (10.0..50.0f64, 10.0..50.0f64, 1.0..25.0f64),
            direction in prop_oneof![
                (0u32..16, -1e-3..1e-3f64).prop_map(|(k, e)| k as f64 * std::f64::consts::PI / 8.0 + e),
                0.0..std::f64::consts::TAU,
            ],
            (kind, offset, gap) in (0u32..4, 0.0..6.0f64, -0.6..0.6f64),
            angle in -0.5..0.5f64,
            scale in 0.5..2.0f64,
        ) {
            let a = Affine::rotate(angle) * Affine::scale(scale);
            let round_trip = |p: BezPath| a.inverse() * (a * p);
            let u = kurbo::Vec2::from_angle(direction);
            let centre = Point::new(cx, cy);
            let (region, stroke) = match kind {
                // Around the front circle, touching it inside.
                0 => (
                    Circle::new(centre, r).to_path(1e-4),
                    Circle::new(centre - u * offset, r + offset + gap).to_path(1e-4),
                ),
                // Inside it, touching it.
                1 => (
                    Circle::new(centre, r + offset).to_path(1e-4),
                    Circle::new(centre + u * offset, r + gap).to_path(1e-4),
                ),
                // Outside it, touching it.
                2 => (
                    Circle::new(centre, r).to_path(1e-4),
                    Circle::new(centre + u * (r + offset + gap), offset + 0.5).to_path(1e-4),
                ),
                // A rectangle whose side almost touches the circle.
                _ => {
                    let x = cx - r - gap;
                    (
                        Rect::new(x, cy - offset - 1.0, x + 1.0 + offset, cy + 30.0).to_path(0.0),
                        Circle::new(centre, r).to_path(1e-4),
                    )
                }
            };
            let Ok(region) = Region::new(round_trip(region), FillRule::NonZero) else {
                return Ok(());
            };
            let stroke = round_trip(stroke);
            let clipper = StrokeClipper::new(&region, TOLERANCE);
            let c = clipper.clip(&stroke);
            let wrong = wrong_side(&clipper, &c, 1e-7);
            prop_assert!(wrong.is_empty(), "{wrong:?}");
        }

        #[test]
        fn parts_are_on_their_side(r in arb_region(), s in arb_stroke()) {
            let c = clip_stroke(&s, &r, 1e-4);
            let clipper = StrokeClipper::new(&r, 1e-4);
            for p in &c.inside {
                for seg in p.segments() {
                    prop_assert!(clipper.contains(seg.eval(0.5)));
                }
            }
            for p in &c.outside {
                for seg in p.segments() {
                    prop_assert!(!clipper.contains(seg.eval(0.5)));
                }
            }
        }
    }
}
