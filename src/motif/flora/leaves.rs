//! Leaf motifs: momiji, matsu, take, leaf.
//!
//! Each leaf is built in its own *natural* units — the stem end on the
//! y axis, the leaf growing up (−y) — from a few parts: pointed blades
//! grown along a curved axis ([`Blade`]), thin tapered stems ([`stem`]),
//! an ellipse. The parts are united into one silhouette, and the drawing is
//! then stretched into the motif box with its stem end at `(0, 0.5)`
//! ([`fit`]). With `jitter == 0` nothing random is drawn and every leaf is
//! left-right symmetric.

use std::f64::consts::PI;

use kurbo::{
    Affine, BezPath, CubicBez, Ellipse, ParamCurve, ParamCurveDeriv, Point, QuadBez, Shape, Vec2,
};

use super::{Drawing, MotifParams};
use crate::geom::region::{FillRule, Region};
use crate::geom::subpath::subpaths;
use crate::rng::RandomStream;

/// 紅葉 momiji, a Japanese maple leaf: a palmate blade of pointed,
/// lance-shaped lobes spread like fingers over about 250° (for seven
/// lobes), the longest pointing up and the lowest pair angled down beside
/// a short stem; straight veins run from the heart of the leaf to every
/// lobe tip.
///
/// `petals` counts the lobes (default 7; clamped to 3–11, odd counts look
/// best). Jitter varies the lobe lengths, widths and angles and bends the
/// stem.
pub(super) fn momiji(p: &MotifParams, rng: &mut RandomStream) -> Drawing {
    let n = p.petals.unwrap_or(7).clamp(3, 11) as usize;
    let j = jitter(p);
    // Half the spread of the lobe fan, from the top lobe to the lowest.
    let half = (132.0 - 82.0 * (-((n - 3) as f64) / 2.2).exp()).to_radians();
    let step = 2.0 * half / (n - 1) as f64;
    let width = (0.42 * (step / 2.0).tan()).clamp(0.1, 0.24);
    let mut parts = Vec::new();
    let mut details = BezPath::new();
    let heart = Point::new(0.0, 0.0);
    for i in 0..n {
        let base_angle = -half + step * i as f64;
        let angle = base_angle + rng.symmetric(0.1 * step * j);
        let rel = base_angle / 135f64.to_radians();
        let length = (1.0 - 0.5 * rel * rel) * (1.0 + rng.symmetric(0.12 * j));
        let w = width * (1.0 + rng.symmetric(0.12 * j));
        let blade = Blade::new(heart, angle, length, 0.0, w, 1.3, 1.3);
        parts.push(blade.outline(10));
        push_cubic(&mut details, blade.midrib(0.0, 0.86));
    }
    let blade_bottom = union(&parts).bounding_box().y1;
    let length = blade_bottom + 0.14;
    let bend = rng.symmetric(0.25 * j);
    // The stem starts inside the top lobe, so its end is not seen.
    let top = heart - Vec2::new(0.0, 0.06);
    parts.push(stem(top, length + 0.06, bend, 0.05, 0.04));
    fit(union(&parts), details)
}

/// 松 matsu, a pine-needle cluster in the manner of the tiers of the
/// "sangai-matsu" crest: a fan of straight needles, about 136° wide,
/// springing from a small sheath on a short stalk. The outline is the fan:
/// solid up to about three quarters of the needle length, then a sharp
/// spike for every needle tip with a V notch, rounded at its bottom,
/// between neighbours; the details are the needles, drawn as lines from
/// the sheath (at staggered heights) to near their tips, and a collar
/// across the sheath.
///
/// `petals` counts the needles (default 11; clamped to 7–41: fewer do not
/// make a fan). Jitter varies needle angles and lengths and bends the
/// stalk.
pub(super) fn matsu(p: &MotifParams, rng: &mut RandomStream) -> Drawing {
    let n = p.petals.unwrap_or(11).clamp(7, 41) as usize;
    let j = jitter(p);
    let half = (20.0 + 12.0 * (n - 1) as f64).min(68.0).to_radians();
    let step = 2.0 * half / (n - 1) as f64;
    let base = Point::new(0.0, 0.0);
    let needles: Vec<(Vec2, f64)> = (0..n)
        .map(|i| {
            let a0 = -half + step * i as f64;
            let a = a0 + rng.symmetric(0.2 * step * j);
            let rel = a0 / half;
            let len = (1.0 - 0.06 * rel * rel) * (1.0 + rng.symmetric(0.07 * j));
            (dir(a), len)
        })
        .collect();
    let tip = |i: usize| base + needles[i].0 * needles[i].1;
    // The needles are free for the outer part of their length: the fan is
    // solid only up to the notches between them.
    let depth = 0.26;
    let notch = |a: f64, len: f64| base + dir(a) * (len - depth).max(0.2);
    let shoulder =
        |i: usize, side: f64| notch(-half + step * (i as f64 + 0.5 * side), needles[i].1);
    // A notch is a V rounded at its bottom.
    let round = 0.12;
    let mut fan = BezPath::new();
    fan.move_to(base);
    fan.line_to(shoulder(0, -1.0));
    fan.line_to(tip(0));
    for i in 0..n - 1 {
        let a = -half + step * (i as f64 + 0.5);
        let bottom = notch(a, 0.5 * (needles[i].1 + needles[i + 1].1));
        fan.line_to(bottom.lerp(tip(i), round * step));
        fan.quad_to(bottom, bottom.lerp(tip(i + 1), round * step));
        fan.line_to(tip(i + 1));
    }
    fan.line_to(shoulder(n - 1, 1.0));
    fan.close_path();
    let sheath = Ellipse::new(Point::new(0.0, 0.03), (0.045, 0.08), 0.0).to_path(1e-4);
    let bend = rng.symmetric(0.3 * j);
    let stalk = stem(Point::new(0.0, 0.0), 0.36, bend, 0.05, 0.045);
    let mut details = BezPath::new();
    for (i, (u, len)) in needles.iter().enumerate() {
        // Needles start at staggered heights so they do not all crowd into
        // the sheath.
        let r0 = if i % 2 == 0 { 0.08 } else { 0.2 };
        details.move_to(base + *u * r0);
        details.line_to(base + *u * (len - 0.06));
    }
    // A collar where the needles leave the sheath.
    details.move_to(Point::new(-0.035, 0.0));
    details.quad_to(Point::new(0.0, 0.025), Point::new(0.035, 0.0));
    fit(union(&[fan, sheath, stalk]), details)
}

/// 竹 take, bamboo leaves: a spray of long, narrow leaves with drawn-out
/// points fanning up from one node on a short twig, the outer leaves
/// curving gently outwards; each leaf has a midrib.
///
/// `petals` counts the leaves (default 3; clamped to 1–7). Jitter varies
/// leaf lengths, angles and curvature.
pub(super) fn take(p: &MotifParams, rng: &mut RandomStream) -> Drawing {
    let n = p.petals.unwrap_or(3).clamp(1, 7) as usize;
    let j = jitter(p);
    let half = (20.0 * (n - 1) as f64).min(64.0).to_radians();
    let step = if n > 1 {
        2.0 * half / (n - 1) as f64
    } else {
        0.0
    };
    let node = Point::new(0.0, 0.0);
    let mut parts = Vec::new();
    let mut details = BezPath::new();
    for i in 0..n {
        let a0 = -half + step * i as f64;
        let rel = if half > 0.0 { a0 / half } else { 0.0 };
        // A lone leaf only trembles: it must stay centred on its stem.
        let swing = if n == 1 { 0.01 } else { 0.12 * step.max(0.2) };
        let angle = a0 + rng.symmetric(swing * j);
        let length = (1.0 - 0.14 * rel * rel) * (1.0 + rng.symmetric(0.1 * j));
        let bend = 0.1 * rel + rng.symmetric(if n == 1 { 0.005 } else { 0.04 } * j);
        let start = node + dir(angle) * 0.02;
        let blade = Blade::new(start, angle, length, bend, 0.085, 1.25, 2.0);
        parts.push(blade.outline(16));
        let rib = blade.midrib(0.0, 0.9);
        details.move_to(node);
        details.line_to(rib.p0);
        details.curve_to(rib.p1, rib.p2, rib.p3);
    }
    let bend = if n == 1 { 0.0 } else { rng.symmetric(0.2 * j) };
    parts.push(stem(Point::new(0.0, -0.03), 0.21, bend, 0.045, 0.04));
    fit(union(&parts), details)
}

/// A generic pointed leaf like a camellia or tea leaf: an almond-shaped
/// blade, widest a little below the middle, with a rounded base and a
/// slightly drawn-out point, on a short stem; a midrib runs up the middle
/// and pairs of side veins leave it at an angle and arch towards the tip.
///
/// `petals` counts the pairs of side veins (default 3; clamped to 1–8).
/// Jitter curves the leaf a little and varies its width and the veins.
pub(super) fn leaf(p: &MotifParams, rng: &mut RandomStream) -> Drawing {
    let n = p.petals.unwrap_or(3).clamp(1, 8) as usize;
    let j = jitter(p);
    let width = 0.24 * (1.0 + rng.symmetric(0.1 * j));
    let bend = rng.symmetric(0.05 * j);
    let blade = Blade::new(Point::ZERO, 0.0, 1.0, bend, width, 0.8, 1.2);
    let mut details = BezPath::new();
    // The midrib starts in the stem, where the blade is joined.
    details.move_to(Point::new(0.0, 0.03));
    let rib = blade.midrib(0.0, 0.93);
    details.line_to(rib.p0);
    details.curve_to(rib.p1, rib.p2, rib.p3);
    let (first, last) = (0.16, 0.6);
    let gap = if n > 1 {
        (last - first) / (n - 1) as f64
    } else {
        0.0
    };
    for k in 0..n {
        let s0 = if n > 1 { first + gap * k as f64 } else { 0.4 };
        for side in [-1.0, 1.0] {
            let s = s0 + rng.symmetric(0.25 * gap.max(0.1) * j);
            let reach = 0.22 - 0.08 * (s0 - first) / (last - first) + rng.symmetric(0.04 * j);
            push_cubic(&mut details, blade.vein(s, reach, side));
        }
    }
    let stem = stem(Point::new(0.0, -0.04), 0.16, 0.0, 0.03, 0.022);
    fit(union(&[blade.outline(14), stem]), details)
}

/// `params.jitter` clamped to 0–1 (NaN counts as 0).
fn jitter(p: &MotifParams) -> f64 {
    if p.jitter.is_nan() {
        0.0
    } else {
        p.jitter.clamp(0.0, 1.0)
    }
}

/// The unit vector pointing at `angle` radians from straight up, turning
/// clockwise on the page (towards +x).
fn dir(angle: f64) -> Vec2 {
    Vec2::new(angle.sin(), -angle.cos())
}

/// The unit vector to the right of the direction `angle` (see [`dir`]).
fn right(angle: f64) -> Vec2 {
    Vec2::new(angle.cos(), angle.sin())
}

/// A pointed blade — a whole leaf or one lobe — grown along a curved axis
/// from its base to its tip, with a half-width that swells from zero at
/// the base to `width × chord length` and tapers to zero at the tip.
struct Blade {
    /// The axis from base to tip.
    axis: CubicBez,
    /// The largest half-width.
    half_width: f64,
    /// Profile exponent at the base: below 1 a rounded base, 1 a wedge.
    base: f64,
    /// Profile exponent at the tip: above 1 a drawn-out point.
    tip: f64,
    /// Normalises the profile `s^base (1-s)^tip` to a peak of 1.
    peak: f64,
}

impl Blade {
    /// A blade from `base` pointing at `angle` (radians from up,
    /// clockwise), `length` long, its tip moved sideways by
    /// `bend × length` (positive: to the right of the direction), its
    /// largest half-width `width × length`, with profile exponents
    /// `base_exp` and `tip_exp`.
    fn new(
        base: Point,
        angle: f64,
        length: f64,
        bend: f64,
        width: f64,
        base_exp: f64,
        tip_exp: f64,
    ) -> Blade {
        let (u, v) = (dir(angle), right(angle));
        let axis = QuadBez::new(
            base,
            base + u * (0.5 * length),
            base + u * length + v * (bend * length),
        )
        .raise();
        let s = base_exp / (base_exp + tip_exp);
        Blade {
            axis,
            half_width: width * length,
            base: base_exp,
            tip: tip_exp,
            peak: s.powf(base_exp) * (1.0 - s).powf(tip_exp),
        }
    }

    /// The half-width at axis parameter `s` in 0–1.
    fn width_at(&self, s: f64) -> f64 {
        let s = s.clamp(0.0, 1.0);
        self.half_width * s.powf(self.base) * (1.0 - s).powf(self.tip) / self.peak
    }

    /// The point at axis parameter `s`, moved sideways by `offset` (to the
    /// right of the axis for positive values).
    fn at(&self, s: f64, offset: f64) -> Point {
        let t = self.axis.deriv().eval(s).to_vec2();
        let t = if t.hypot() > 1e-12 {
            t.normalize()
        } else {
            Vec2::new(0.0, -1.0)
        };
        self.axis.eval(s) + Vec2::new(-t.y, t.x) * offset
    }

    /// The closed outline: up the right edge from base to tip and back down
    /// the left edge, through `samples + 1` points on each edge (denser at
    /// the ends, where the edge turns fastest).
    fn outline(&self, samples: usize) -> BezPath {
        let ss: Vec<f64> = (0..=samples)
            .map(|i| 0.5 - 0.5 * (PI * i as f64 / samples as f64).cos())
            .collect();
        let rightside: Vec<Point> = ss.iter().map(|&s| self.at(s, self.width_at(s))).collect();
        let mut leftside: Vec<Point> = ss.iter().map(|&s| self.at(s, -self.width_at(s))).collect();
        leftside.reverse();
        let mut path = BezPath::new();
        path.move_to(rightside[0]);
        spline_to(&mut path, &rightside);
        spline_to(&mut path, &leftside);
        path.close_path();
        path
    }

    /// The part of the axis between parameters `s0` and `s1`.
    fn midrib(&self, s0: f64, s1: f64) -> CubicBez {
        self.axis.subsegment(s0..s1)
    }

    /// A side vein on `side` (−1 left, +1 right) leaving the midrib at `s`
    /// at a slant and arching forward by `reach` (in axis parameter) to end
    /// at 80% of the half-width there.
    fn vein(&self, s: f64, reach: f64, side: f64) -> CubicBez {
        let s = s.clamp(0.05, 0.85);
        let end = (s + reach).min(0.92);
        let lateral = 0.8 * self.width_at(end);
        let q = s + 0.3 * (end - s);
        QuadBez::new(
            self.at(s, 0.0),
            self.at(q, side * 0.6 * lateral),
            self.at(end, side * lateral),
        )
        .raise()
    }
}

/// A thin stem, a closed sliver: from `top` straight down `length`, its
/// middle pushed sideways by `bend × length`, `w_top` wide at the top and
/// `w_end` at the end, which is cut square so that its midpoint is the
/// lowest point of the stem, straight below `top`.
fn stem(top: Point, length: f64, bend: f64, w_top: f64, w_end: f64) -> BezPath {
    let end = top + Vec2::new(0.0, length);
    let axis = CubicBez::new(
        top,
        top + Vec2::new(bend * length, length / 3.0),
        end - Vec2::new(0.0, length / 3.0),
        end,
    );
    let deriv = axis.deriv();
    let samples = 6;
    let side = |sign: f64| -> Vec<Point> {
        (0..=samples)
            .map(|i| {
                let s = i as f64 / samples as f64;
                let t = deriv.eval(s).to_vec2().normalize();
                let w = w_top + (w_end - w_top) * s;
                axis.eval(s) + Vec2::new(-t.y, t.x) * (sign * w / 2.0)
            })
            .collect()
    };
    let left = side(1.0);
    let mut right = side(-1.0);
    right.reverse();
    let mut path = BezPath::new();
    path.move_to(left[0]);
    spline_to(&mut path, &left);
    path.line_to(right[0]);
    spline_to(&mut path, &right);
    path.close_path();
    path
}

/// Appends a smooth curve through `points` (the path is at `points[0]`):
/// one cubic per gap, with tangents along the neighbouring chords and arms
/// a third of the gap long, so unevenly spaced points give no loops.
fn spline_to(path: &mut BezPath, points: &[Point]) {
    let n = points.len();
    if n < 2 {
        return;
    }
    let tangent = |i: usize| -> Vec2 {
        let a = points[i.saturating_sub(1)];
        let b = points[(i + 1).min(n - 1)];
        let t = b - a;
        if t.hypot() > 1e-12 {
            t.normalize()
        } else {
            Vec2::ZERO
        }
    };
    for i in 0..n - 1 {
        let (a, b) = (points[i], points[i + 1]);
        let arm = (b - a).hypot() / 3.0;
        path.curve_to(a + tangent(i) * arm, b - tangent(i + 1) * arm, b);
    }
}

/// Appends `c` as an open stroke.
fn push_cubic(path: &mut BezPath, c: CubicBez) {
    path.move_to(c.p0);
    path.curve_to(c.p1, c.p2, c.p3);
}

/// The outline of the union of the closed `parts`: one silhouette without
/// self-crossings, its holes (small gaps enclosed where parts meet again)
/// filled, since an outline is wound all one way. Parts that are not valid
/// regions are skipped; should the union fail, the parts are returned as
/// they are.
fn union(parts: &[BezPath]) -> BezPath {
    let regions: Vec<Region> = parts
        .iter()
        .filter_map(|p| Region::new(p.clone(), FillRule::NonZero).ok())
        .collect();
    let merged = Region::union_all(&regions);
    if merged.is_empty() {
        let mut all = BezPath::new();
        for p in parts {
            all.extend(p.elements().iter().copied());
        }
        return all;
    }
    let contours: Vec<BezPath> = subpaths(merged.path()).map(|s| s.to_path()).collect();
    let outer = contours
        .iter()
        .map(Shape::area)
        .max_by(|a, b| a.abs().total_cmp(&b.abs()))
        .unwrap_or(1.0)
        .signum();
    let mut out = BezPath::new();
    for c in contours.iter().filter(|c| c.area() * outer > 0.0) {
        out.extend(c.elements().iter().copied());
    }
    out
}

/// Stretches a leaf drawn in natural units (stem end on the y axis, at
/// the bottom of the outline) into the motif box: the stem end goes to
/// `(0, 0.5)`, the top of the outline to y = −0.5, and the side reaching
/// furthest from the y axis to x = ±0.5. The aspect is the natural height
/// over twice that reach.
///
/// A jittered leaf can lean so far to one side that, stretched about its
/// stem, it would leave much of the box empty on the other; it is then
/// sheared back (about its stem end) until it is nearly balanced.
fn fit(outline: BezPath, details: BezPath) -> Drawing {
    let bottom = outline.bounding_box().y1;
    let mut lean = 0.0;
    let mut outline = outline;
    let mut details = details;
    for _ in 0..6 {
        let b = outline.bounding_box();
        let (left, right) = (-b.x0, b.x1);
        if left.min(right) >= 0.9 * left.max(right) || b.height() <= 0.0 {
            break;
        }
        let step = (-0.5 * (b.x0 + b.x1) / (0.6 * b.height())).clamp(-0.1, 0.1);
        lean += step;
        if lean.abs() > 0.3 {
            break;
        }
        let shear = Affine::new([1.0, 0.0, -step, 1.0, step * bottom, 0.0]);
        outline = shear * outline;
        details = shear * details;
    }
    let b = outline.bounding_box();
    let reach = b.x0.abs().max(b.x1.abs()).max(1e-9);
    let height = (b.y1 - b.y0).max(1e-9);
    let (sx, sy) = (0.5 / reach, 1.0 / height);
    let map = Affine::new([sx, 0.0, 0.0, sy, 0.0, 0.5 - b.y1 * sy]);
    Drawing {
        outline: map * outline,
        details: map * details,
        anchor: Point::new(0.0, 0.5),
        aspect: height / (2.0 * reach),
    }
}

#[cfg(test)]
pub(super) mod tests {
    use kurbo::{Affine, BezPath, ParamCurve, ParamCurveNearest, Point, Shape};

    use super::super::{draw, Drawing, MotifParams};
    use crate::geom::region::{FillRule, Region};
    use crate::geom::subpath::subpaths;
    use crate::rng::Seed;
    use crate::spec::MotifKind;

    const LEAVES: [MotifKind; 4] = [
        MotifKind::Momiji,
        MotifKind::Matsu,
        MotifKind::Take,
        MotifKind::Leaf,
    ];

    /// Draws `kind` with `petals` and `jitter` from seed `seed`.
    pub(in crate::motif::flora) fn drawn(
        kind: MotifKind,
        petals: Option<u32>,
        jitter: f64,
        seed: u64,
    ) -> Drawing {
        let params = MotifParams { petals, jitter };
        draw(kind, &params, &mut Seed(seed).stream())
    }

    /// Distance from `p` to the nearest point of `path`.
    fn distance(path: &BezPath, p: Point) -> f64 {
        path.segments()
            .map(|s| s.nearest(p, 1e-9).distance_sq.sqrt())
            .fold(f64::INFINITY, f64::min)
    }

    /// The invariants every motif keeps, whatever its kind and settings:
    /// finite, within and filling the box, a closed outline without
    /// self-crossings, details inside it, and few path elements.
    pub(in crate::motif::flora) fn check(d: &Drawing, what: &str) {
        let all = d.to_path(Affine::IDENTITY);
        assert!(
            all.elements().len() <= 300,
            "{what}: {} elements",
            all.elements().len()
        );
        for el in all.elements() {
            if let Some(p) = el.end_point() {
                assert!(p.x.is_finite() && p.y.is_finite(), "{what}: {p:?}");
            }
        }
        assert!(
            d.aspect.is_finite() && d.aspect > 0.0,
            "{what}: aspect {}",
            d.aspect
        );
        let b = d.outline.bounding_box();
        let eps = 1e-6;
        assert!(b.x0 >= -0.5 - eps && b.x1 <= 0.5 + eps, "{what}: {b:?}");
        assert!(b.y0 >= -0.5 - eps && b.y1 <= 0.5 + eps, "{what}: {b:?}");
        assert!(b.width() >= 0.9 && b.height() >= 0.9, "{what}: {b:?}");
        let db = d.details.bounding_box();
        if !d.details.elements().is_empty() {
            assert!(b.inflate(1e-3, 1e-3).contains_rect(db), "{what}: {db:?}");
        }
        for sub in subpaths(&d.outline) {
            assert!(sub.is_closed(), "{what}: open outline subpath");
        }
        // One clean silhouette: untangling the outline changes nothing.
        let region = Region::new(d.outline.clone(), FillRule::NonZero).expect(what);
        let (clean, raw) = (region.area(), d.outline.area().abs());
        assert!(
            (clean - raw).abs() < 1e-6 * raw.max(1.0),
            "{what}: {clean} vs {raw}"
        );
        for seg in d.details.segments() {
            for i in 0..=20 {
                let p = seg.eval(f64::from(i) / 20.0);
                assert!(
                    d.outline.winding(p) != 0 || distance(&d.outline, p) < 1e-3,
                    "{what}: detail point {p:?} outside the outline"
                );
            }
        }
    }

    /// Asserts that outline and details are centred on x = 0.
    fn assert_symmetric(d: &Drawing, what: &str) {
        let b = d.outline.bounding_box();
        assert!((b.x0 + b.x1).abs() < 1e-6, "{what}: outline {b:?}");
        let db = d.details.bounding_box();
        assert!((db.x0 + db.x1).abs() < 1e-6, "{what}: details {db:?}");
    }

    /// Every leaf, for many counts, jitters and seeds, keeps [`check`].
    #[test]
    fn leaves_fit_fill_and_hold_their_details() {
        for kind in LEAVES {
            for petals in [
                None,
                Some(1),
                Some(2),
                Some(3),
                Some(5),
                Some(7),
                Some(11),
                Some(64),
            ] {
                for jitter in [0.0, 0.5, 1.0] {
                    for seed in 1..6 {
                        let what =
                            format!("{kind:?} petals {petals:?} jitter {jitter} seed {seed}");
                        check(&drawn(kind, petals, jitter, seed), &what);
                    }
                }
            }
        }
    }

    /// Leaves are anchored at their stem end, the bottom centre of the box.
    #[test]
    fn leaves_stand_on_their_stem_end() {
        for kind in LEAVES {
            for petals in [None, Some(1), Some(4), Some(9)] {
                for jitter in [0.0, 0.5] {
                    let d = drawn(kind, petals, jitter, 7);
                    let what = format!("{kind:?} {petals:?} {jitter}");
                    assert_eq!(d.anchor, Point::new(0.0, 0.5), "{what}");
                    let b = d.outline.bounding_box();
                    assert!((b.y1 - 0.5).abs() < 1e-9, "{what}: {b:?}");
                    // The stem end is at the bottom centre: what of the
                    // outline lies at the very bottom is centred on x = 0.
                    assert!(d.outline.winding(Point::new(0.0, 0.498)) != 0, "{what}");
                    let xs: Vec<f64> = d
                        .outline
                        .segments()
                        .flat_map(|s| (0..=20).map(move |i| s.eval(f64::from(i) / 20.0)))
                        .filter(|p| p.y > 0.495)
                        .map(|p| p.x)
                        .collect();
                    let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
                    let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                    assert!(lo < 0.0 && hi > 0.0 && hi - lo < 0.5, "{what}: {lo} {hi}");
                    assert!((lo + hi).abs() < 0.05, "{what}: {lo} {hi}");
                    // Upright: most of the leaf lies above its stem end.
                    let area_centre = Region::new(d.outline.clone(), FillRule::NonZero)
                        .unwrap()
                        .bounds()
                        .center();
                    assert!(area_centre.y < 0.1, "{what}");
                }
            }
        }
    }

    /// Without jitter a leaf is mirror-symmetric and leaves the stream alone.
    #[test]
    fn leaves_without_jitter_are_symmetric_and_draw_nothing_random() {
        for kind in LEAVES {
            for petals in [None, Some(1), Some(2), Some(3), Some(6), Some(11)] {
                let mut rng = Seed(1).stream();
                let params = MotifParams {
                    petals,
                    jitter: 0.0,
                };
                let d = draw(kind, &params, &mut rng);
                assert_symmetric(&d, &format!("{kind:?} {petals:?}"));
                assert_eq!(rng.next_u64(), Seed(1).stream().next_u64(), "{kind:?}");
            }
        }
    }

    /// One seed gives one drawing; with jitter, another seed another one.
    #[test]
    fn leaves_are_deterministic_and_vary_with_the_seed() {
        for kind in LEAVES {
            let a = drawn(kind, None, 0.3, 1);
            assert_eq!(a, drawn(kind, None, 0.3, 1), "{kind:?}");
            assert_ne!(a, drawn(kind, None, 0.3, 2), "{kind:?}");
            assert_eq!(
                drawn(kind, None, 0.0, 1),
                drawn(kind, None, 0.0, 2),
                "{kind:?}"
            );
        }
    }

    /// The aspects are those of the natural shapes.
    #[test]
    fn leaf_aspects_are_natural() {
        let aspect = |kind| drawn(kind, None, 0.0, 1).aspect;
        assert!(
            (0.8..1.3).contains(&aspect(MotifKind::Momiji)),
            "{}",
            aspect(MotifKind::Momiji)
        );
        assert!(
            (0.5..0.9).contains(&aspect(MotifKind::Matsu)),
            "{}",
            aspect(MotifKind::Matsu)
        );
        assert!(
            (0.7..1.6).contains(&aspect(MotifKind::Take)),
            "{}",
            aspect(MotifKind::Take)
        );
        assert!(
            (1.9..2.6).contains(&aspect(MotifKind::Leaf)),
            "{}",
            aspect(MotifKind::Leaf)
        );
    }

    /// `petals` counts what each leaf's documentation says.
    #[test]
    fn petals_count_lobes_needles_leaves_and_veins() {
        // Counted as detail strokes: one vein per lobe, one line per needle
        // (plus the collar), one midrib per leaf, a midrib and two
        // veins per pair.
        let strokes = |kind, n| subpaths(&drawn(kind, Some(n), 0.0, 1).details).count();
        assert_eq!(strokes(MotifKind::Momiji, 7), 7);
        assert_eq!(strokes(MotifKind::Momiji, 5), 5);
        assert_eq!(strokes(MotifKind::Matsu, 11), 11 + 1);
        assert_eq!(strokes(MotifKind::Take, 3), 3);
        assert_eq!(strokes(MotifKind::Take, 5), 5);
        assert_eq!(strokes(MotifKind::Leaf, 3), 1 + 6);
        assert_eq!(strokes(MotifKind::Leaf, 1), 1 + 2);
    }

    /// Writes /tmp/leaves.png: every leaf without and with jitter, and a
    /// 4×4 patch of every tile (square grid, and seigaiha and kikko also in
    /// rows offset by half a tile). Run with
    /// `cargo test --lib leaves::tests::preview_sheet -- --ignored`.
    #[test]
    #[ignore]
    fn preview_sheet() {
        use std::fmt::Write as _;
        let mut svg = String::from(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"240mm\" height=\"100mm\" \
             viewBox=\"0 0 240 100\">\n<rect width=\"240\" height=\"100\" fill=\"white\"/>\n",
        );
        let mut put = |d: &Drawing, place: Affine, fill: &str| {
            let _ = writeln!(
                svg,
                "<path d=\"{}\" fill=\"{fill}\" stroke=\"black\" stroke-width=\"0.25\"/>",
                (place * d.outline.clone()).to_svg()
            );
            let _ = writeln!(
                svg,
                "<path d=\"{}\" fill=\"none\" stroke=\"black\" stroke-width=\"0.2\"/>",
                (place * d.details.clone()).to_svg()
            );
        };
        // Leaves: stem end at the bottom of a 28 × 46 mm cell.
        for (i, kind) in LEAVES.iter().enumerate() {
            for (k, jitter) in [0.0, 0.3].into_iter().enumerate() {
                let d = drawn(*kind, None, jitter, 3 + k as u64);
                let cell = 2.0 + 29.5 * (2 * i + k) as f64;
                let w = (26.0f64).min(44.0 / d.aspect);
                let h = w * d.aspect;
                let place = Affine::translate((cell + 14.0, 48.0))
                    * Affine::scale_non_uniform(w, h)
                    * Affine::translate((-d.anchor.x, -d.anchor.y));
                put(&d, place, "#d8e8c8");
            }
        }
        // Tiles: 4 × 4 patches, edge to edge.
        let tiles = [
            (MotifKind::Seigaiha, false),
            (MotifKind::Seigaiha, true),
            (MotifKind::Shippo, false),
            (MotifKind::Kikko, false),
            (MotifKind::Kikko, true),
        ];
        for (i, (kind, offset)) in tiles.into_iter().enumerate() {
            let d = drawn(kind, None, 0.0, 1);
            let w = 10.0;
            let h = w * d.aspect;
            for row in 0..4 {
                for col in 0..4 {
                    let shift = if offset && row % 2 == 1 { w / 2.0 } else { 0.0 };
                    let x = 4.0 + 47.0 * i as f64 + shift + w * (f64::from(col) + 0.5);
                    let y = 54.0 + h * (f64::from(row) + 0.5);
                    let place = Affine::translate((x, y)) * Affine::scale_non_uniform(w, h);
                    put(&d, place, "#c8d8e8");
                }
            }
        }
        svg.push_str("</svg>\n");
        std::fs::write("/tmp/leaves.svg", &svg).unwrap();
        let png = crate::output::render_png(&svg, 150.0).unwrap();
        std::fs::write("/tmp/leaves.png", png).unwrap();
    }
}
