//! Flower motifs: ume, sakura, kiku, tsubaki, kikyo, botan.
//!
//! Every flower is drawn the same way, in the spirit of a family crest
//! (kamon) or a Kaga-Yuzen drawing:
//!
//! * Each petal is a closed shape of cubic Béziers, symmetric about its own
//!   axis, drawn pointing up (−y) with its tip at distance 1 from the
//!   centre ("nominal units"), then rotated into place. Petal `k` of `n`
//!   points at `2πk/n` clockwise from straight up, so one petal points up
//!   and the flower is left-right symmetric when there is no jitter.
//! * Petals have a **depth**. The silhouette (the outline) is the union of
//!   all petals, with any gap they enclose filled. Where a petal lies over
//!   a petal further back, its edge is visible and becomes a detail line,
//!   hidden wherever a petal further in front covers it. Two neighbouring
//!   petals at the same depth (all petals of a crest-like flower, or the
//!   mirrored pair where a layered ring meets the mirror axis) are
//!   separated by a straight **seam** from the notch between them towards
//!   the centre.
//! * A **cover** at the centre (a stamen cup, a disc) hides petal lines;
//!   the stamens and centre circles are drawn on top of everything. Petals
//!   start just inside the cover rather than at the centre, so that they do
//!   not all cross one another there.
//! * The drawing is scaled to fill the box `[-0.5, 0.5]²` around the
//!   centre: uniformly, or stretched by up to [`MAX_STRETCH`] in its
//!   shorter direction. Where a small petal count leaves the lower half
//!   short (three petals make a triangle), the lower petals are first
//!   turned a little further down and then lengthened, as if the flower
//!   were seen slightly from below, so that the drawing still nearly fills
//!   its box (see [`boosted`]).
//!
//! Which petal hides which is [`crate::geom::depth`]'s composition (the
//! one vines will use too); the seams, the cover, the fitting and the
//! scaling are this file's. Boolean work is done at a scale of [`WORK`] so
//! that the region toolkit's tolerances (given in mm) are far below
//! anything visible here.

use std::f64::consts::{PI, TAU};

use kurbo::{
    Affine, BezPath, ParamCurve, ParamCurveDeriv, ParamCurveNearest, PathEl, Point, Rect, Shape,
    Vec2,
};

use super::{Drawing, MotifParams};
use crate::geom::depth::{self, DepthStack};
use crate::geom::region::{FillRule, Region};
use crate::geom::subpath::subpaths;
use crate::rng::RandomStream;

/// Scale of the boolean work space: motif units × `WORK` (a flower is
/// 100 "mm" there).
const WORK: f64 = 100.0;

/// Flattening tolerance of the clipping regions, in work units (1e-4 of
/// the motif: 0.01 mm on a flower 100 mm wide).
const CLIP_TOLERANCE: f64 = 0.01;

/// Lines shorter than this (work units) are dropped from the outline.
const SPECK: f64 = 1e-7;

/// Detail pieces shorter than this (work units) are dropped: crumbs left
/// where a line just grazes a petal.
const MIN_PIECE: f64 = 0.4;

/// The fewest petals a flower has; smaller counts are raised to it.
const MIN_PETALS: u32 = 3;

/// The most petals a flower has; larger counts are lowered to it.
const MAX_PETALS: u32 = 64;

/// The most outer petals of a botan, whose ruffled petals are large.
const MAX_BOTAN_PETALS: u32 = 24;

/// How much of its box a flower without jitter fills at least (width and
/// height over the box side).
const TARGET_FILL: f64 = 0.92;

/// The most a flower is stretched across (or along) to fill its box: a
/// three-petal flower is wider than high.
const MAX_STRETCH: f64 = 1.15;

/// The part of the fill boost that turns petals down rather than
/// lengthening them (see [`boosted`]).
const MAX_SPREAD: f64 = 0.4;

/// The handle length of a quarter circle of radius 1 drawn as one cubic.
const KAPPA: f64 = 0.551_915_024_494;

/// 梅 plum blossom: `petals` round petals (default 5, each a circle)
/// meeting in shallow notches, separated by short seams, around a ring of
/// stamens — fine lines radiating from a small centre circle, alternately
/// long and short, each ending in a dot.
pub(super) fn ume(p: &MotifParams, rng: &mut RandomStream) -> Drawing {
    let n = petal_count(p, 5, MAX_PETALS);
    let j = jitter_of(p);
    let jit = jitters(rng, j, n);
    let stamens = stamen_count(n);
    let sjit = jitters(rng, j, stamens);
    let sin = (PI / n as f64).sin();
    let r = (1.08 * sin / (1.0 + sin)).min(0.46);
    let c = 1.0 - r;
    let shape = round_petal(c, r);
    // The hub fills the hole between the inner ends of the petal circles:
    // a disc through the middle of the lens where two neighbours overlap,
    // which lies inside the circles (its points nearest the gap between two
    // circles are at distance c·sin(π/n) < r from their centres).
    let hub = 0.98 * c * (PI / n as f64).cos();
    let build = |boost: f64, jit: &[Jit]| {
        let pieces = ring(n, 0.0, jit, boost, |k, angle, len| {
            let jk = &jit[k];
            Piece::placed(
                &shape,
                &BezPath::new(),
                angle + 0.15 * jk[1] * PI / n as f64,
                len * (1.0 + 0.06 * jk[0]),
                1.0 + 0.06 * jk[2],
                0,
            )
        });
        let mut top = BezPath::new();
        top.extend(circle_path(Point::ZERO, 0.16 * hub).iter());
        for (m, sj) in sjit.iter().enumerate() {
            let a = ring_angle(m as f64, stamens) + 0.3 * sj[0] * PI / stamens as f64;
            let long = m % 2 == 1;
            let reach = hub * if long { 0.86 } else { 0.66 } * (1.0 + 0.08 * sj[1]);
            stamen(&mut top, a, 0.16 * hub, reach, 0.07 * hub);
        }
        Layout {
            pieces,
            seams: ring_pairs(0, n),
            filler: vec![circle_path(Point::ZERO, hub)],
            cover: Some(circle_path(Point::ZERO, 0.6 * hub)),
            top,
        }
    };
    compose(&fitted(build, &jit))
}

/// 桜 cherry blossom: `petals` petals (default 5), each narrow at the
/// centre, broad at the top and cleft by the characteristic notch at its
/// tip, separated by seams; a small centre circle with short dotted
/// stamens.
pub(super) fn sakura(p: &MotifParams, rng: &mut RandomStream) -> Drawing {
    let n = petal_count(p, 5, MAX_PETALS);
    let j = jitter_of(p);
    let jit = jitters(rng, j, n);
    let stamens = stamen_count(n).min(2 * n);
    let sjit = jitters(rng, j, stamens);
    let w = (0.55 * (PI / n as f64).tan() * 1.04).min(0.62);
    let shape = mirrored(
        Point::new(0.0, -0.1),
        &[
            ((0.5 * w, -0.1), (w, -0.25), (w, -0.56)),
            ((w, -0.8), (0.84 * w, -0.99), (0.5 * w, -1.0)),
            ((0.24 * w, -1.0), (0.07 * w, -0.95), (0.0, -0.85)),
        ],
    );
    let build = |boost: f64, jit: &[Jit]| {
        let pieces = ring(n, 0.0, jit, boost, |k, angle, len| {
            let jk = &jit[k];
            Piece::placed(
                &shape,
                &BezPath::new(),
                angle + 0.12 * jk[1] * PI / n as f64,
                len * (1.0 + 0.06 * jk[0]),
                1.0 + 0.06 * jk[2],
                0,
            )
        });
        let mut top = BezPath::new();
        top.extend(circle_path(Point::ZERO, 0.06).iter());
        for (m, sj) in sjit.iter().enumerate() {
            let a = ring_angle(m as f64, stamens) + 0.3 * sj[0] * PI / stamens as f64;
            let reach = if m % 2 == 1 { 0.24 } else { 0.19 } * (1.0 + 0.08 * sj[1]);
            stamen(&mut top, a, 0.06, reach, 0.022);
        }
        Layout {
            pieces,
            seams: ring_pairs(0, n),
            filler: vec![circle_path(Point::ZERO, 0.12)],
            cover: Some(circle_path(Point::ZERO, 0.2)),
            top,
        }
    };
    compose(&fitted(build, &jit))
}

/// 菊 chrysanthemum: a dense radial burst of `petals` narrow petals with
/// rounded tips (default 20); up to 24 petals a second row of as many
/// petals peeks out between them, and a small circle marks the centre.
pub(super) fn kiku(p: &MotifParams, rng: &mut RandomStream) -> Drawing {
    let n = petal_count(p, 20, MAX_PETALS);
    let j = jitter_of(p);
    let two_rows = n <= 24;
    let jit = jitters(rng, j, if two_rows { 2 * n } else { n });
    let step = PI / n as f64;
    let front_half = if two_rows { 0.6 * step } else { 1.04 * step };
    let centre = (0.12 + 0.2 * step).min(0.3);
    let front = rayed_petal(front_half.min(0.5), 0.6 * centre);
    let back = rayed_petal((0.72 * step).min(0.55), 0.6 * centre);
    let build = |boost: f64, jit: &[Jit]| {
        let mut pieces = ring(n, 0.0, jit, boost, |k, angle, len| {
            let jk = &jit[k];
            Piece::placed(
                &front,
                &BezPath::new(),
                angle + 0.12 * jk[1] * step,
                len * (1.0 + 0.05 * jk[0]),
                1.0 + 0.05 * jk[2],
                1,
            )
        });
        if two_rows {
            pieces.extend(ring(n, 0.5, &jit[n..], boost, |k, angle, len| {
                let jk = &jit[n + k];
                Piece::placed(
                    &back,
                    &BezPath::new(),
                    angle + 0.12 * jk[1] * step,
                    0.95 * len * (1.0 + 0.04 * jk[0]),
                    1.0 + 0.05 * jk[2],
                    0,
                )
            }));
        }
        let mut top = BezPath::new();
        top.extend(circle_path(Point::ZERO, centre).iter());
        top.extend(circle_path(Point::ZERO, 0.45 * centre).iter());
        Layout {
            pieces,
            seams: ring_pairs(0, n),
            filler: Vec::new(),
            cover: Some(circle_path(Point::ZERO, centre)),
            top,
        }
    };
    compose(&fitted(build, &jit))
}

/// 椿 camellia: `petals` broad, rounded petals (default 5), each with a
/// slight dent at its tip, overlapping one another — the upper petals lie
/// over the lower ones, the two bottom ones meet in a seam — around a cup
/// of stamens: a ring of anthers on short filaments round a small centre.
pub(super) fn tsubaki(p: &MotifParams, rng: &mut RandomStream) -> Drawing {
    let n = petal_count(p, 5, MAX_PETALS);
    let j = jitter_of(p);
    let jit = jitters(rng, j, n);
    let anthers = (2 * n + 4).clamp(12, 22);
    let ajit = jitters(rng, j, anthers);
    let w = (0.55 * (PI / n as f64).tan() * 1.22).min(0.8);
    let shape = mirrored(
        Point::new(0.0, -0.15),
        &[
            ((0.5 * w, -0.15), (w, -0.2), (w, -0.55)),
            ((w, -0.86), (0.62 * w, -1.0), (0.2 * w, -1.0)),
            ((0.1 * w, -1.0), (0.04 * w, -0.985), (0.0, -0.97)),
        ],
    );
    let cup = 0.3;
    let build = |boost: f64, jit: &[Jit]| {
        let pieces = ring(n, 0.0, jit, boost, |k, angle, len| {
            let jk = &jit[k];
            Piece::placed(
                &shape,
                &BezPath::new(),
                angle + 0.15 * jk[1] * PI / n as f64,
                len * (1.0 + 0.05 * jk[0]),
                1.0 + 0.05 * jk[2],
                stacked(k as f64, n, Stacking::TopFront),
            )
        });
        let mut top = BezPath::new();
        top.extend(circle_path(Point::ZERO, 0.1).iter());
        for (m, aj) in ajit.iter().enumerate() {
            let a = ring_angle(m as f64 + 0.5, anthers) + 0.25 * aj[0] * PI / anthers as f64;
            let reach = (cup - 0.045) * (1.0 + 0.05 * aj[1]);
            stamen(&mut top, a, 0.1, reach, 0.04);
        }
        Layout {
            pieces,
            seams: ring_pairs(0, n),
            filler: Vec::new(),
            cover: Some(circle_path(Point::ZERO, cup)),
            top,
        }
    };
    compose(&fitted(build, &jit))
}

/// 桔梗 bellflower: `petals` broad petals (default 5) drawn out to sharp
/// points, forming a star, separated by seams, each with a vein along its
/// middle; a small star-shaped pistil at the centre.
pub(super) fn kikyo(p: &MotifParams, rng: &mut RandomStream) -> Drawing {
    let n = petal_count(p, 5, MAX_PETALS);
    let j = jitter_of(p);
    let jit = jitters(rng, j, n);
    let w = (0.5 * (PI / n as f64).tan() * 0.95).min(0.6);
    let shape = mirrored(
        Point::new(0.0, -0.08),
        &[
            ((0.5 * w, -0.08), (w, -0.24), (w, -0.48)),
            ((w, -0.66), (0.2 * w, -0.8), (0.0, -1.0)),
        ],
    );
    let mut vein = BezPath::new();
    vein.move_to((0.0, -0.16));
    vein.curve_to((0.0, -0.4), (0.0, -0.6), (0.0, -0.8));
    let build = |boost: f64, jit: &[Jit]| {
        let pieces = ring(n, 0.0, jit, boost, |k, angle, len| {
            let jk = &jit[k];
            Piece::placed(
                &shape,
                &vein,
                angle + 0.12 * jk[1] * PI / n as f64,
                len * (1.0 + 0.06 * jk[0]),
                1.0 + 0.06 * jk[2],
                0,
            )
        });
        let points: Vec<f64> = (0..n).map(|k| ring_angle(k as f64, n)).collect();
        let mut top = star_path(&points, 0.13, 0.05);
        top.extend(circle_path(Point::ZERO, 0.025).iter());
        Layout {
            pieces,
            seams: ring_pairs(0, n),
            filler: vec![circle_path(Point::ZERO, 0.12)],
            cover: Some(circle_path(Point::ZERO, 0.15)),
            top,
        }
    };
    compose(&fitted(build, &jit))
}

/// 牡丹 peony: a big, lush flower of layered petals with ruffled,
/// scalloped edges and creases running in from the notches next to their
/// tips: `petals` outer petals (default 8, at most 24), lying over them an
/// inner ring of three fewer (at least 3), and a cup of three small petals
/// round a cluster of stamen dots.
pub(super) fn botan(p: &MotifParams, rng: &mut RandomStream) -> Drawing {
    let n = petal_count(p, 8, MAX_BOTAN_PETALS);
    let m = n.saturating_sub(3).max(3);
    let cup = 3;
    let j = jitter_of(p);
    let jit = jitters(rng, j, n + m + cup);
    let anthers = (m + 1).clamp(6, 10);
    let ajit = jitters(rng, j, anthers);
    let outer_w = (0.6 * (PI / n as f64).tan() * 1.5).min(0.8);
    let inner_w = (0.6 * (PI / m as f64).tan() * 1.45).min(0.8);
    let lobes = if n <= 12 { 2 } else { 1 };
    let build = |boost: f64, jit: &[Jit]| {
        let mut pieces = ring(n, 0.0, jit, boost, |k, angle, len| {
            let jk = &jit[k];
            let (shape, creases) = ruffled_petal(outer_w, lobes, 1, jk);
            Piece::placed(
                &shape,
                &creases,
                angle + 0.12 * jk[1] * PI / n as f64,
                len * (1.0 + 0.05 * jk[0]),
                1.0,
                stacked(k as f64, n, Stacking::BottomFront),
            )
        });
        pieces.extend(ring(m, 0.5, &jit[n..], boost, |k, angle, len| {
            let jk = &jit[n + k];
            let (shape, creases) = ruffled_petal(inner_w, 1, 1, jk);
            Piece::placed(
                &shape,
                &creases,
                angle + 0.12 * jk[1] * PI / m as f64,
                0.64 * len * (1.0 + 0.05 * jk[0]),
                1.0,
                1000 + stacked(k as f64 + 0.5, m, Stacking::Alternate),
            )
        }));
        // A cup of three small petals round the stamens.
        pieces.extend(ring(cup, 0.0, &jit[n + m..], boost, |k, angle, len| {
            let jk = &jit[n + m + k];
            let (shape, _) = ruffled_petal(0.62, 1, 0, jk);
            Piece::placed(
                &shape,
                &BezPath::new(),
                angle + 0.1 * jk[1],
                0.36 * len * (1.0 + 0.05 * jk[0]),
                1.0,
                2000,
            )
        }));
        let mut top = BezPath::new();
        top.extend(circle_path(Point::ZERO, 0.06).iter());
        for (q, aj) in ajit.iter().enumerate() {
            let a = ring_angle(q as f64 + 0.5, anthers) + 0.25 * aj[0] * PI / anthers as f64;
            let at = direction(a) * 0.13 * (1.0 + 0.05 * aj[1]);
            top.extend(circle_path(at.to_point(), 0.032).iter());
        }
        Layout {
            pieces,
            seams: [ring_pairs(0, n), ring_pairs(n, m), ring_pairs(n + m, cup)].concat(),
            filler: Vec::new(),
            cover: Some(circle_path(Point::ZERO, 0.19)),
            top,
        }
    };
    compose(&fitted(build, &jit))
}

// ---------------------------------------------------------------------
// Petal shapes (nominal units: base near the origin, tip at (0, −1)).

/// A circle of radius `r` around `(0, −c)`, as a petal.
fn round_petal(c: f64, r: f64) -> BezPath {
    let k = KAPPA * r;
    mirrored(
        Point::new(0.0, -c + r),
        &[
            ((k, -c + r), (r, -c + k), (r, -c)),
            ((r, -c - k), (k, -c - r), (0.0, -c - r)),
        ],
    )
}

/// A narrow kiku petal: a sector of the flower between radial sides at
/// `half_angle` either side of its axis, from radius `base` (hidden under
/// the centre) to a round tip. Radial sides meet those of the other petals
/// only at the centre, so neighbouring petals overlap without crossings.
fn rayed_petal(half_angle: f64, base: f64) -> BezPath {
    let t = half_angle.tan();
    let w = t / (1.0 + t);
    let s = Point::new(w, -(1.0 - w));
    let b = Point::new(0.0, -base);
    let corner = Point::new(base * t, -base);
    let k = KAPPA * w;
    mirrored_points(
        b,
        &[
            (b.lerp(corner, 1.0 / 3.0), b.lerp(corner, 2.0 / 3.0), corner),
            (corner.lerp(s, 1.0 / 3.0), corner.lerp(s, 2.0 / 3.0), s),
            (
                Point::new(w, -(1.0 - w) - k),
                Point::new(k, -1.0),
                Point::new(0.0, -1.0),
            ),
        ],
    )
}

/// A broad botan petal of half-width `w` whose rounded top is broken into
/// scalloped lobes (`lobes` notches on each side of the middle lobe), and
/// the creases running in from its `creased` notches nearest the top.
/// `jk` varies the notches.
fn ruffled_petal(w: f64, lobes: usize, creased: usize, jk: &Jit) -> (BezPath, BezPath) {
    let base = Point::new(0.0, -0.12);
    let centre = Point::new(0.0, -0.55);
    let (rx, ry) = (w, 0.45);
    let on_cap = |phi: f64, inset: f64| {
        Point::new(
            centre.x + (1.0 - inset) * rx * phi.cos(),
            centre.y - (1.0 - inset) * ry * phi.sin(),
        )
    };
    // Notch angles on the right half, from the side (0) to the top (π/2).
    let span = 0.5 * PI / (lobes as f64 + 0.5);
    let notches: Vec<(f64, f64)> = (0..=lobes)
        .map(|i| {
            let phi = span * i as f64 + if i > 0 { 0.15 * span * jk[3] } else { 0.0 };
            let depth = if i == 0 {
                0.0
            } else {
                0.1 * (1.0 + 0.4 * jk[4])
            };
            (phi, depth)
        })
        .collect();
    let s = on_cap(0.0, 0.0);
    let mut half: Vec<(Point, Point, Point)> =
        vec![(Point::new(0.5 * w, -0.12), Point::new(w, -0.25), s)];
    let mut creases = BezPath::new();
    let bulge = 0.22 * (1.0 + 0.3 * jk[5]);
    for (i, win) in notches.windows(2).enumerate() {
        let a = on_cap(win[0].0, win[0].1);
        let b = on_cap(win[1].0, win[1].1);
        half.push(lobe(a, b, centre, bulge));
        if i + creased < lobes {
            continue;
        }
        // A crease from the notch in towards the base, on both sides.
        let inward = base - b;
        let c0 = b + inward * 0.02;
        let c1 = b + inward * 0.25;
        for m in [1.0, -1.0] {
            let f = |p: Point| Point::new(m * p.x, p.y);
            creases.move_to(f(c0));
            creases.curve_to(f(c0.lerp(c1, 0.33)), f(c0.lerp(c1, 0.66)), f(c1));
        }
    }
    // Half of the middle lobe, flat at the top.
    let a = on_cap(notches[lobes].0, notches[lobes].1);
    let top = Point::new(
        0.0,
        centre.y - ry * (1.0 + 0.5 * bulge * (0.5 * PI - notches[lobes].0)),
    );
    let rest = 0.5 * PI - notches[lobes].0;
    half.push((
        on_cap(notches[lobes].0 + 0.35 * rest, -0.06),
        Point::new(0.45 * a.x, top.y),
        top,
    ));
    (mirrored_points(base, &half), creases)
}

/// One scallop of a ruffled edge from `a` to `b`, bulging away from `c`.
fn lobe(a: Point, b: Point, c: Point, bulge: f64) -> (Point, Point, Point) {
    let d = b - a;
    let mut normal = Vec2::new(d.y, -d.x);
    if normal.dot(a.midpoint(b) - c) < 0.0 {
        normal = -normal;
    }
    (
        a + d / 3.0 + normal * bulge,
        a + d * (2.0 / 3.0) + normal * bulge,
        b,
    )
}

/// A point given as `(x, y)`.
type Xy = (f64, f64);

/// A closed petal symmetric about the y axis: from `start` (on the axis,
/// at the base) along the right half given as cubic segments (two control
/// points and an end point each) up to a point on the axis, and back down
/// the mirror image.
fn mirrored(start: Point, half: &[(Xy, Xy, Xy)]) -> BezPath {
    let pts: Vec<(Point, Point, Point)> = half
        .iter()
        .map(|&(a, b, c)| (a.into(), b.into(), c.into()))
        .collect();
    mirrored_points(start, &pts)
}

/// [`mirrored`] with the right half given as points.
fn mirrored_points(start: Point, half: &[(Point, Point, Point)]) -> BezPath {
    let m = |q: Point| Point::new(-q.x, q.y);
    let mut path = BezPath::new();
    path.move_to(start);
    for &(a, b, c) in half {
        path.curve_to(a, b, c);
    }
    for i in (0..half.len()).rev() {
        let prev = if i == 0 { start } else { half[i - 1].2 };
        let (a, b, _) = half[i];
        path.curve_to(m(b), m(a), m(prev));
    }
    path.close_path();
    path
}

// ---------------------------------------------------------------------
// Centres and stamens.

/// A circle of four cubics, starting at its top.
fn circle_path(c: Point, r: f64) -> BezPath {
    let k = KAPPA * r;
    let mut p = BezPath::new();
    p.move_to((c.x, c.y - r));
    p.curve_to((c.x + k, c.y - r), (c.x + r, c.y - k), (c.x + r, c.y));
    p.curve_to((c.x + r, c.y + k), (c.x + k, c.y + r), (c.x, c.y + r));
    p.curve_to((c.x - k, c.y + r), (c.x - r, c.y + k), (c.x - r, c.y));
    p.curve_to((c.x - r, c.y - k), (c.x - k, c.y - r), (c.x, c.y - r));
    p.close_path();
    p
}

/// A stamen at `angle`: a line from radius `r0` to the edge of a dot of
/// radius `dot` whose centre lies at radius `r1`.
fn stamen(out: &mut BezPath, angle: f64, r0: f64, r1: f64, dot: f64) {
    let d = direction(angle);
    out.move_to((d * r0).to_point());
    out.line_to((d * (r1 - dot)).to_point());
    out.extend(circle_path((d * r1).to_point(), dot).iter());
}

/// A star with a point of radius `r_out` at each of `angles` and valleys
/// of radius `r_in` between, its arms slightly pinched.
fn star_path(angles: &[f64], r_out: f64, r_in: f64) -> BezPath {
    let n = angles.len();
    let mut path = BezPath::new();
    let valley = |k: usize| {
        let a = angles[k];
        let b = angles[(k + 1) % n];
        // The mid angle, going clockwise from a to b.
        let mut delta = b - a;
        while delta <= 0.0 {
            delta += TAU;
        }
        (direction(a + 0.5 * delta) * r_in).to_point()
    };
    for (k, &angle) in angles.iter().enumerate() {
        let v0 = valley((k + n - 1) % n);
        let tip = (direction(angle) * r_out).to_point();
        let v1 = valley(k);
        if k == 0 {
            path.move_to(v0);
        }
        let pinch = |p: Point| (p.to_vec2() * 0.85).to_point();
        path.curve_to(pinch(v0.lerp(tip, 0.4)), pinch(v0.lerp(tip, 0.75)), tip);
        path.curve_to(pinch(tip.lerp(v1, 0.25)), pinch(tip.lerp(v1, 0.6)), v1);
    }
    path.close_path();
    path
}

/// Stamens around a centre: about three per petal, an even number (so
/// that long and short ones alternate symmetrically), 10–24.
fn stamen_count(n: usize) -> usize {
    (2 * (3 * n).div_ceil(2)).clamp(10, 24)
}

// ---------------------------------------------------------------------
// Parameters and randomness.

/// Per-petal random numbers, each in `[-jitter, jitter)`.
type Jit = [f64; 6];

/// `count` sets of random numbers; none are drawn when `jitter` is 0.
fn jitters(rng: &mut RandomStream, jitter: f64, count: usize) -> Vec<Jit> {
    (0..count)
        .map(|_| std::array::from_fn(|_| rng.symmetric(jitter)))
        .collect()
}

/// The jitter clamped to `[0, 1]` (NaN is 0).
fn jitter_of(p: &MotifParams) -> f64 {
    if p.jitter > 0.0 {
        p.jitter.min(1.0)
    } else {
        0.0
    }
}

/// The petal count: `default` when unset, clamped to 3–`max`.
fn petal_count(p: &MotifParams, default: u32, max: u32) -> usize {
    p.petals.unwrap_or(default).clamp(MIN_PETALS, max) as usize
}

/// The unit vector at `angle` clockwise from straight up (−y).
fn direction(angle: f64) -> Vec2 {
    Vec2::new(angle.sin(), -angle.cos())
}

/// The angle of position `pos` (0, 1, … or 0.5, 1.5, …) of `n` around
/// the centre, clockwise from up, in (−π, π]; mirror positions give
/// exactly opposite angles.
fn ring_angle(pos: f64, n: usize) -> f64 {
    let n = n as f64;
    let t = if pos > 0.5 * n { pos - n } else { pos };
    TAU * t / n
}

/// How the petals of a ring lie over one another.
#[derive(Clone, Copy)]
enum Stacking {
    /// Every other petal from the top lies in front (the top one among
    /// them), the others behind.
    Alternate,
    /// The lower a petal, the further in front.
    BottomFront,
    /// The higher a petal, the further in front.
    TopFront,
}

/// The depth (larger in front) of the petal at position `pos` of `n` in a
/// ring (see [`ring_angle`]); mirror petals get the same depth.
fn stacked(pos: f64, n: usize, how: Stacking) -> i32 {
    let from_top = pos.min(n as f64 - pos);
    match how {
        Stacking::Alternate => i32::from(from_top.floor() as i64 % 2 == 0),
        Stacking::BottomFront => (from_top * 2.0).round() as i32,
        Stacking::TopFront => -(from_top * 2.0).round() as i32,
    }
}

/// The fill `boost` (see the module docs) applied to a petal at `angle`:
/// its angle and length. The first [`MAX_SPREAD`] of the boost turns the
/// lower petals further down (`θ + b·sin θ`, which keeps the top and bottom
/// petals and the order); the rest lengthens them, most for a bottom petal.
fn boosted(angle: f64, boost: f64) -> (f64, f64) {
    let spread = boost.clamp(0.0, MAX_SPREAD);
    let stretch = (boost - MAX_SPREAD).max(0.0);
    let angle = angle + spread * angle.sin();
    let down = 0.5 * (1.0 - angle.cos());
    (angle, 1.0 + stretch * down * down)
}

/// A ring of `n` petals at positions `k + offset`, made by `make(k,
/// angle, length)` with the fill-boosted nominal angle and length.
fn ring(
    n: usize,
    offset: f64,
    jit: &[Jit],
    boost: f64,
    make: impl Fn(usize, f64, f64) -> Piece,
) -> Vec<Piece> {
    (0..n.min(jit.len()))
        .map(|k| {
            let (angle, length) = boosted(ring_angle(k as f64 + offset, n), boost);
            make(k, angle, length)
        })
        .collect()
}

/// The neighbouring pairs of a ring of `n` pieces starting at index
/// `first`.
fn ring_pairs(first: usize, n: usize) -> Vec<(usize, usize)> {
    (0..n).map(|k| (first + k, first + (k + 1) % n)).collect()
}

// ---------------------------------------------------------------------
// Composition: silhouette, visible edges, seams.

/// One petal, in nominal units.
struct Piece {
    /// Its closed shape.
    shape: BezPath,
    /// Lines on it (veins, creases), hidden where it is covered.
    lines: BezPath,
    /// Larger lies in front.
    depth: i32,
}

impl Piece {
    /// `shape` and `lines` (drawn pointing up, tip at distance 1) turned to
    /// `angle`, scaled to `length` and widened by `widen`.
    fn placed(
        shape: &BezPath,
        lines: &BezPath,
        angle: f64,
        length: f64,
        widen: f64,
        depth: i32,
    ) -> Piece {
        let a = Affine::rotate(angle) * Affine::scale_non_uniform(length * widen, length);
        Piece {
            shape: a * shape,
            lines: a * lines,
            depth,
        }
    }
}

/// A flower before composition, in nominal units.
struct Layout {
    pieces: Vec<Piece>,
    /// Candidate seams: neighbouring pieces; those at the same depth get
    /// one.
    seams: Vec<(usize, usize)>,
    /// Closed shapes that only fill the silhouette.
    filler: Vec<BezPath>,
    /// A closed shape in front of every piece that hides their lines (and
    /// fills the silhouette); not drawn itself.
    cover: Option<BezPath>,
    /// Lines drawn on top of everything.
    top: BezPath,
}

impl Layout {
    /// The bounds of everything that makes the silhouette.
    fn bounds(&self) -> Rect {
        let shapes = self
            .pieces
            .iter()
            .map(|p| &p.shape)
            .chain(self.filler.iter())
            .chain(self.cover.iter());
        shapes
            .map(Shape::bounding_box)
            .reduce(|a, b| a.union(b))
            .unwrap_or(Rect::new(-1.0, -1.0, 1.0, 1.0))
    }
}

/// The scales `(sx, sy)` that fit bounds around the centre into the box
/// `[-0.5, 0.5]²`: uniform, except that the shorter direction may be
/// stretched by up to [`MAX_STRETCH`] to fill more of the box.
fn fit_scales(b: Rect) -> (f64, f64) {
    let ex = (-b.x0).max(b.x1);
    let ey = (-b.y0).max(b.y1);
    if !(ex.is_finite() && ey.is_finite() && ex > 0.0 && ey > 0.0) {
        return (1.0, 1.0);
    }
    let (sx, sy) = (0.5 / ex, 0.5 / ey);
    let s = sx.min(sy);
    (sx.min(s * MAX_STRETCH), sy.min(s * MAX_STRETCH))
}

/// How much of its box the layout fills once fitted (the smaller of width
/// and height over the box side).
fn fill_of(layout: &Layout) -> f64 {
    let b = layout.bounds();
    let (sx, sy) = fit_scales(b);
    (b.width() * sx).min(b.height() * sy)
}

/// The layout made by `build(boost, jit)`, with the smallest boost
/// (turning down and lengthening the lower petals, see [`boosted`]) from a
/// few tries that makes the flower without jitter fill [`TARGET_FILL`] of
/// its box: the boost depends on the petal count, not on the jitter.
fn fitted(build: impl Fn(f64, &[Jit]) -> Layout, jit: &[Jit]) -> Layout {
    let plain = vec![[0.0; 6]; jit.len()];
    let mut boost = 0.0;
    for _ in 0..8 {
        let fill = fill_of(&build(boost, &plain));
        if fill >= TARGET_FILL || boost >= 1.5 {
            break;
        }
        boost = (boost + 2.5 * (TARGET_FILL - fill)).min(1.5);
    }
    build(boost, jit)
}

/// The region of a petal. Petals are simple closed curves by construction,
/// so turning one the way normalised regions go (outer contours have a
/// positive area) normalises it without a sweep (see
/// `Region::from_normalised` for what that promises).
fn petal_region(path: &BezPath) -> Region {
    let area = path.area();
    if !area.is_finite() || area.abs() < 1e-9 {
        return Region::empty();
    }
    Region::from_normalised(if area > 0.0 {
        path.clone()
    } else {
        path.reverse_subpaths()
    })
}

/// The region of a closed shape, empty if it encloses nothing.
fn region_of(path: &BezPath) -> Region {
    Region::new(path.clone(), FillRule::NonZero).unwrap_or_default()
}

/// The outer contours of a normalised path (positive area), without its
/// holes (a gap enclosed by petals is part of the silhouette) and without
/// lines shorter than [`SPECK`].
fn outer_contours(path: &BezPath) -> BezPath {
    let mut out = BezPath::new();
    let mut contour = BezPath::new();
    let mut flush = |c: &mut BezPath| {
        if c.area() > 0.0 {
            out.extend(c.iter());
        }
        *c = BezPath::new();
    };
    let mut at = Point::ZERO;
    for el in path.elements() {
        match *el {
            PathEl::MoveTo(p) => {
                flush(&mut contour);
                at = p;
            }
            // The sweep joins some curves with lines a hair long.
            PathEl::LineTo(p) if p.distance(at) < SPECK => continue,
            _ => {}
        }
        contour.push(*el);
        at = el.end_point().unwrap_or(at);
    }
    flush(&mut contour);
    out
}

/// The crossing of the curves `a` and `b` near `p`, a crossing found on
/// their flattened forms: Newton's method from the nearest points of both;
/// `p` itself if that does not converge close by.
fn refine_crossing(a: &BezPath, b: &BezPath, p: Point) -> Point {
    let nearest = |path: &BezPath| {
        path.segments()
            .map(|s| {
                let n = s.nearest(p, 1e-12);
                (s.to_cubic(), n.t, n.distance_sq)
            })
            .min_by(|x, y| x.2.total_cmp(&y.2))
    };
    let (Some((ca, mut t, _)), Some((cb, mut u, _))) = (nearest(a), nearest(b)) else {
        return p;
    };
    let (da, db) = (ca.deriv(), cb.deriv());
    for _ in 0..30 {
        let f = ca.eval(t) - cb.eval(u);
        if f.hypot() < 1e-12 {
            break;
        }
        // Solve  da·Δt − db·Δu = −f.
        let (ta, tb) = (da.eval(t).to_vec2(), db.eval(u).to_vec2());
        let det = ta.cross(-tb);
        if det.abs() < 1e-18 {
            return p;
        }
        let dt = (-f).cross(-tb) / det;
        let du = ta.cross(-f) / det;
        t = (t + dt).clamp(0.0, 1.0);
        u = (u + du).clamp(0.0, 1.0);
    }
    let q = ca.eval(t);
    if q.distance(cb.eval(u)) < 1e-9 && q.distance(p) < 100.0 * CLIP_TOLERANCE {
        q
    } else {
        p
    }
}

/// The on-curve points of a path: where it moves to and where each of its
/// segments ends.
fn vertices(path: &BezPath) -> impl Iterator<Item = Point> + '_ {
    path.elements().iter().filter_map(PathEl::end_point)
}

/// The finished drawing of a layout: scaled to fill the box, the
/// silhouette as the union of everything, the visible edges of petals over
/// petals further back, their lines (a [`DepthStack`]), the seams and the
/// top lines.
fn compose(layout: &Layout) -> Drawing {
    let (sx, sy) = fit_scales(layout.bounds());
    let fit = Affine::scale_non_uniform(sx, sy);
    let to_work = Affine::scale(WORK) * fit;
    let back = Affine::scale(1.0 / WORK);

    let shapes: Vec<BezPath> = layout.pieces.iter().map(|p| to_work * &p.shape).collect();
    let pieces = layout
        .pieces
        .iter()
        .zip(&shapes)
        .map(|(p, shape)| {
            depth::Piece::new(petal_region(shape), p.depth)
                .with_edge(shape.clone())
                .with_lines(to_work * &p.lines)
        })
        .collect();
    let cover = layout.cover.as_ref().map(|c| region_of(&(to_work * c)));
    let stack = DepthStack::new(pieces, cover, CLIP_TOLERANCE);
    // The closed shapes drawn on top (stamen heads) belong to the
    // silhouette too: with few petals they can stand beyond them, and a
    // fill must cover them.
    let heads = subpaths(&layout.top)
        .filter(|s| s.is_closed())
        .map(|s| s.to_path());
    let filler: Vec<Region> = layout
        .filler
        .iter()
        .cloned()
        .chain(heads)
        .map(|f| region_of(&(to_work * f)))
        .collect();
    let outline = back * outer_contours(&stack.silhouette(&filler).into_path());

    let mut lines = stack.visible_lines();
    for &(i, k) in &layout.seams {
        let (Some(a), Some(b)) = (layout.pieces.get(i), layout.pieces.get(k)) else {
            continue;
        };
        if i == k || a.depth != b.depth {
            continue;
        }
        // The notch: where the edges cross farthest from the centre.
        let crossings = stack.clipper(k).clip(&shapes[i]).inside;
        let notch = crossings
            .iter()
            .flat_map(vertices)
            .max_by(|p, q| p.to_vec2().hypot2().total_cmp(&q.to_vec2().hypot2()));
        let Some(notch) = notch else { continue };
        let notch = refine_crossing(&shapes[i], &shapes[k], notch);
        let mut seam = BezPath::new();
        seam.move_to(notch);
        seam.line_to(Point::ZERO);
        let inside: Vec<BezPath> = stack
            .clipper(i)
            .clip(&seam)
            .inside
            .iter()
            .flat_map(|s| stack.clipper(k).clip(s).inside)
            .collect();
        let Some(first) = inside.into_iter().min_by(|p, q| {
            let dist = |s: &BezPath| {
                subpaths(s)
                    .next()
                    .map_or(f64::MAX, |s| s.start().distance(notch))
            };
            dist(p).total_cmp(&dist(q))
        }) else {
            continue;
        };
        // From the notch itself (the clip may have cut a hair off it).
        let Some(end) = vertices(&first).last() else {
            continue;
        };
        let mut seam = BezPath::new();
        seam.move_to(notch);
        seam.line_to(end);
        // The neighbour does not hide the seam along its edge.
        lines.extend(stack.hide_on(i, &[k], vec![seam]));
    }

    let mut details = BezPath::new();
    for l in lines {
        if l.perimeter(1e-3) >= MIN_PIECE {
            details.extend((back * l).iter());
        }
    }
    details.extend((fit * &layout.top).iter());
    Drawing {
        outline,
        details,
        anchor: Point::ZERO,
        aspect: 1.0,
    }
}

#[cfg(test)]
mod tests {
    use std::sync::OnceLock;

    use kurbo::{ParamCurve, ParamCurveNearest};

    use super::super::draw;
    use super::*;
    use crate::geom::clip::StrokeClipper;
    use crate::rng::Seed;
    use crate::spec::MotifKind;

    /// Parameters with a petal count and a jitter.
    fn params(petals: u32, jitter: f64) -> MotifParams {
        MotifParams {
            petals: Some(petals),
            jitter,
        }
    }

    /// A flower drawn with its own stream of `seed`.
    fn drawing(kind: MotifKind, petals: u32, jitter: f64, seed: u64) -> Drawing {
        draw(kind, &params(petals, jitter), &mut Seed(seed).stream())
    }

    /// One drawing of the test grid.
    struct Case {
        kind: MotifKind,
        petals: u32,
        jitter: f64,
        drawing: Drawing,
    }

    impl Case {
        /// The case, for messages.
        fn name(&self) -> String {
            format!(
                "{:?} petals {} jitter {}",
                self.kind, self.petals, self.jitter
            )
        }
    }

    /// Every flower with 3–40 petals, at jitter 0 and 0.5 (seed 1), drawn
    /// once (on a few threads) for all the tests that check them.
    fn cases() -> &'static [Case] {
        static CASES: OnceLock<Vec<Case>> = OnceLock::new();
        CASES.get_or_init(|| {
            let grid: Vec<(MotifKind, u32, f64)> = MotifKind::FLOWERS
                .into_iter()
                .flat_map(|kind| {
                    (3..=40u32).flat_map(move |n| [0.0, 0.5].map(move |j| (kind, n, j)))
                })
                .collect();
            let threads = std::thread::available_parallelism().map_or(4, |t| t.get().min(8));
            let chunk = grid.len().div_ceil(threads);
            std::thread::scope(|scope| {
                let handles: Vec<_> = grid
                    .chunks(chunk)
                    .map(|part| {
                        scope.spawn(move || {
                            part.iter()
                                .map(|&(kind, petals, jitter)| Case {
                                    kind,
                                    petals,
                                    jitter,
                                    drawing: drawing(kind, petals, jitter, 1),
                                })
                                .collect::<Vec<_>>()
                        })
                    })
                    .collect();
                handles
                    .into_iter()
                    .flat_map(|h| h.join().expect("drawing a flower panicked"))
                    .collect()
            })
        })
    }

    /// Points along every segment of a path.
    fn samples(path: &BezPath, per_segment: usize) -> Vec<Point> {
        path.segments()
            .flat_map(|s| (0..=per_segment).map(move |i| s.eval(i as f64 / per_segment as f64)))
            .collect()
    }

    /// The distance from `p` to the nearest point of `path`.
    fn distance_to(path: &BezPath, p: Point) -> f64 {
        path.segments()
            .map(|s| s.nearest(p, 1e-9).distance_sq)
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    }

    /// How many subpaths a path has.
    fn subpath_count(path: &BezPath) -> usize {
        path.elements()
            .iter()
            .filter(|e| matches!(e, PathEl::MoveTo(_)))
            .count()
    }

    /// Every flower lies in the box `[-0.5, 0.5]²`, anchored at its centre.
    #[test]
    fn flowers_fit_their_box() {
        for c in cases() {
            let b = c.drawing.outline.bounding_box();
            assert!(
                b.x0 >= -0.5 - 1e-6 && b.x1 <= 0.5 + 1e-6,
                "{}: {b:?}",
                c.name()
            );
            assert!(
                b.y0 >= -0.5 - 1e-6 && b.y1 <= 0.5 + 1e-6,
                "{}: {b:?}",
                c.name()
            );
            assert_eq!(c.drawing.anchor, Point::ZERO);
            assert_eq!(c.drawing.aspect, 1.0);
        }
    }

    /// Without jitter a flower is at least 0.9 wide and high (0.8 with).
    #[test]
    fn flowers_nearly_fill_their_box() {
        for c in cases() {
            let b = c.drawing.outline.bounding_box();
            let least = if c.jitter == 0.0 { 0.9 } else { 0.8 };
            assert!(
                b.width() >= least && b.height() >= least,
                "{}: {b:?}",
                c.name()
            );
        }
    }

    /// No NaN or infinity, and paths of a modest size for any petal count.
    #[test]
    fn paths_are_finite_and_modest() {
        for c in cases() {
            let d = &c.drawing;
            for el in d.outline.elements().iter().chain(d.details.elements()) {
                let pts: Vec<Point> = match *el {
                    PathEl::MoveTo(p) | PathEl::LineTo(p) => vec![p],
                    PathEl::QuadTo(a, p) => vec![a, p],
                    PathEl::CurveTo(a, b, p) => vec![a, b, p],
                    PathEl::ClosePath => vec![],
                };
                assert!(pts.iter().all(|p| p.is_finite()), "{}", c.name());
            }
            let size = d.outline.elements().len() + d.details.elements().len();
            assert!(size < 800, "{}: {size} path elements", c.name());
        }
    }

    /// A flower with its default petals (any jitter) has fewer than 300
    /// path elements, and details.
    #[test]
    fn default_flowers_stay_well_under_300_path_elements() {
        for kind in MotifKind::FLOWERS {
            for (j, seed) in [(0.0, 1), (0.5, 1), (1.0, 2)] {
                let p = MotifParams {
                    petals: None,
                    jitter: j,
                };
                let d = draw(kind, &p, &mut Seed(seed).stream());
                let size = d.outline.elements().len() + d.details.elements().len();
                assert!(size < 300, "{kind:?} jitter {j}: {size} path elements");
                assert!(!d.details.elements().is_empty(), "{kind:?}");
            }
        }
    }

    /// The outline is one closed contour (no holes), drawn in curves.
    #[test]
    fn outline_is_one_closed_contour_of_curves() {
        for c in cases() {
            let els = c.drawing.outline.elements();
            assert_eq!(subpath_count(&c.drawing.outline), 1, "{}", c.name());
            assert!(
                matches!(els.first(), Some(PathEl::MoveTo(_))),
                "{}",
                c.name()
            );
            assert!(
                matches!(els.last(), Some(PathEl::ClosePath)),
                "{}",
                c.name()
            );
            let curves = els
                .iter()
                .filter(|e| matches!(e, PathEl::CurveTo(..)))
                .count();
            let lines = els
                .iter()
                .filter(|e| matches!(e, PathEl::LineTo(..)))
                .count();
            assert!(lines * 5 <= curves, "{}: not drawn in curves", c.name());
            assert!(c.drawing.outline.area() > 0.0, "{}", c.name());
        }
    }

    /// Points sampled along every detail segment lie inside the outline or
    /// within 1e-3 of it.
    #[test]
    fn details_lie_inside_the_outline() {
        for c in cases() {
            let d = &c.drawing;
            // The outline is normalised already (one simple contour), so it
            // is used as it is, flattened finely: `Region::new` would referee
            // it with the toolkit's flattening tolerance of 0.01 (meant for
            // mm, coarse in motif units), and kurbo's exact winding number
            // misses crossings near the joints of nearly level curves.
            let inside = StrokeClipper::new(&Region::from_normalised(d.outline.clone()), 1e-5);
            for p in samples(&d.details, 8) {
                assert!(
                    inside.contains(p) || distance_to(&d.outline, p) < 1e-3,
                    "{}: detail point {p:?} outside",
                    c.name()
                );
            }
        }
    }

    /// Without jitter the outline's bounds are mirror symmetric (1e-6), the
    /// details' nearly so (1e-4), and the top of the outline is a petal
    /// tip on the axis.
    #[test]
    fn without_jitter_flowers_are_symmetric_with_a_petal_up() {
        for c in cases().iter().filter(|c| c.jitter == 0.0) {
            let d = &c.drawing;
            let b = d.outline.bounding_box();
            assert!((b.x0 + b.x1).abs() < 1e-6, "{}: {b:?}", c.name());
            let db = d.details.bounding_box();
            assert!((db.x0 + db.x1).abs() < 1e-4, "{}: details {db:?}", c.name());
            // A petal tip straight up: the top of the outline is on the
            // axis (sakura: its two lobes either side of the notch).
            let pts = samples(&d.outline, 16);
            let top: Vec<&Point> = pts.iter().filter(|p| p.y < b.y0 + 1e-3).collect();
            let mean = top.iter().map(|p| p.x).sum::<f64>() / top.len() as f64;
            assert!(mean.abs() < 1e-3, "{}: top at {mean}", c.name());
            assert!(top.iter().all(|p| p.x.abs() < 0.2), "{}: {top:?}", c.name());
        }
    }

    /// Without jitter the mirror image of every detail point lies on a
    /// detail line.
    #[test]
    fn without_jitter_details_are_mirror_symmetric() {
        for c in cases().iter().filter(|c| c.jitter == 0.0) {
            let d = &c.drawing;
            let mirror = Affine::scale_non_uniform(-1.0, 1.0);
            // Every detail point has a mirror image on a detail line.
            let mirrored = mirror * &d.details;
            for p in samples(&mirrored, 2).into_iter().step_by(7) {
                let e = distance_to(&d.details, p);
                assert!(e < 1e-4, "{}: {p:?} has no mirror image ({e})", c.name());
            }
        }
    }

    /// Jitter 0 draws no random numbers, so the seed does not matter.
    #[test]
    fn no_random_numbers_without_jitter() {
        for kind in MotifKind::FLOWERS {
            let mut rng = Seed(5).stream();
            let _ = draw(kind, &MotifParams::DEFAULT, &mut rng);
            assert_eq!(rng.next_u64(), Seed(5).stream().next_u64(), "{kind:?}");
            assert_eq!(
                drawing(kind, 5, 0.0, 1),
                drawing(kind, 5, 0.0, 2),
                "{kind:?}"
            );
        }
    }

    /// With jitter, the same seed gives the same flower and another seed a
    /// different one.
    #[test]
    fn jitter_is_deterministic_per_seed_and_varies_between_seeds() {
        for kind in MotifKind::FLOWERS {
            for n in [3, 5, 8, 20] {
                let a = drawing(kind, n, 0.5, 11);
                let again = drawing(kind, n, 0.5, 11);
                let other = drawing(kind, n, 0.5, 12);
                assert_eq!(a, again, "{kind:?} {n}");
                assert_ne!(a.outline, other.outline, "{kind:?} {n}");
                assert_ne!(a.details, other.details, "{kind:?} {n}");
            }
        }
    }

    /// Petal counts of 0–2 draw 3 petals, counts above the maximum the
    /// maximum; jitter out of range (or NaN) is clamped; nothing panics.
    #[test]
    fn petal_counts_out_of_range_are_clamped_without_panic() {
        for kind in MotifKind::FLOWERS {
            for n in [0, 1, 2, 41, 63, 64, 65, 1000, u32::MAX] {
                for j in [0.0, 1.0, 7.0, -1.0, f64::NAN, f64::INFINITY] {
                    let d = drawing(kind, n, j, 9);
                    let b = d.outline.bounding_box();
                    let what = format!("{kind:?} {n} {j}: {b:?}");
                    assert!(b.width() > 0.8 && b.height() > 0.8, "{what}");
                    assert!(b.x0 >= -0.5 - 1e-6 && b.x1 <= 0.5 + 1e-6, "{what}");
                    assert!(b.y0 >= -0.5 - 1e-6 && b.y1 <= 0.5 + 1e-6, "{what}");
                }
            }
            for n in [0, 1, 2] {
                assert_eq!(
                    drawing(kind, n, 0.0, 1),
                    drawing(kind, 3, 0.0, 1),
                    "{kind:?}"
                );
            }
            assert_eq!(
                drawing(kind, 65, 0.0, 1),
                drawing(kind, 64, 0.0, 1),
                "{kind:?}"
            );
        }
    }

    /// The default petal counts: 5, 5, 20, 5, 5, 8.
    #[test]
    fn default_petal_counts() {
        assert_eq!(petal_count(&MotifParams::DEFAULT, 5, MAX_PETALS), 5);
        assert_eq!(petal_count(&params(2, 0.0), 5, MAX_PETALS), 3);
        assert_eq!(petal_count(&params(500, 0.0), 5, MAX_PETALS), 64);
        for (kind, n) in [
            (MotifKind::Ume, 5),
            (MotifKind::Sakura, 5),
            (MotifKind::Kiku, 20),
            (MotifKind::Tsubaki, 5),
            (MotifKind::Kikyo, 5),
            (MotifKind::Botan, 8),
        ] {
            assert_eq!(
                draw(kind, &MotifParams::DEFAULT, &mut Seed(1).stream()),
                drawing(kind, n, 0.0, 1),
                "{kind:?}"
            );
        }
    }

    /// An SVG sheet of flowers, one row per `(petals, jitter, seed)` (0
    /// petals: the default), filled light pink, with black lines.
    fn sheet(rows: &[(u32, f64, u64)], kinds: &[MotifKind], cell: f64) -> String {
        let cols = kinds.len();
        let mut svg = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}mm\" height=\"{h}mm\" \
             viewBox=\"0 0 {w} {h}\">\n",
            w = cols as f64 * cell,
            h = rows.len() as f64 * cell
        );
        let size = cell * 0.92;
        let stroke = 0.01 * size * 0.3;
        for (r, &(petals, jitter, seed)) in rows.iter().enumerate() {
            for (c, &kind) in kinds.iter().enumerate() {
                let p = MotifParams {
                    petals: (petals > 0).then_some(petals),
                    jitter,
                };
                let d = draw(kind, &p, &mut Seed(seed).stream());
                let place = Affine::translate(((c as f64 + 0.5) * cell, (r as f64 + 0.5) * cell))
                    * Affine::scale(size);
                svg.push_str(&format!(
                    "<path d=\"{}\" fill=\"#f6d5dc\" stroke=\"black\" stroke-width=\"{stroke}\"/>\n\
                     <path d=\"{}\" fill=\"none\" stroke=\"black\" stroke-width=\"{stroke}\"/>\n",
                    (place * &d.outline).to_svg(),
                    (place * &d.details).to_svg()
                ));
            }
        }
        svg.push_str("</svg>\n");
        svg
    }

    /// Writes /tmp/flowers.svg and /tmp/flowers.png: every flower with its
    /// default petals at jitter 0 and 0.3, with 3 petals, and with 12
    /// petals at jitter 0.3; /tmp/flowers_large1.png and 2: the defaults, large.
    /// Run with `cargo test --lib flowers::tests::preview_sheet -- --ignored`.
    #[test]
    #[ignore = "writes preview images to /tmp"]
    fn preview_sheet() {
        let rows = [(0, 0.0, 1), (0, 0.3, 7), (3, 0.0, 1), (12, 0.3, 4)];
        let svg = sheet(&rows, &MotifKind::FLOWERS, 40.0);
        std::fs::write("/tmp/flowers.svg", &svg).unwrap();
        let png = crate::output::render_png(&svg, 150.0).unwrap();
        std::fs::write("/tmp/flowers.png", png).unwrap();
        for (i, kinds) in MotifKind::FLOWERS.chunks(3).enumerate() {
            let large = sheet(&[(0, 0.0, 1)], kinds, 100.0);
            let png = crate::output::render_png(&large, 110.0).unwrap();
            std::fs::write(format!("/tmp/flowers_large{}.png", i + 1), png).unwrap();
        }
    }
}
