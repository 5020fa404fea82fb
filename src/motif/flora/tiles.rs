//! Shapes for background stamps and tiles: circle, seigaiha, kikko, shippo.
//!
//! The tiles are cut from endless patterns so that tiles placed edge to
//! edge continue the pattern: seigaiha and shippo without a seam on a
//! square grid (seigaiha also in rows offset by half a tile). Kikko
//! hexagons in a square grid share their flat sides and leave small
//! diamond gaps between their points. Tiles ignore `jitter`: a pattern must repeat
//! exactly.

use std::f64::consts::{PI, TAU};

use kurbo::{Affine, Arc, BezPath, Circle, Point, Rect, Shape, Vec2};

use super::{Drawing, MotifParams};

/// A plain disc filling the box (the default background stamp).
pub(super) fn circle() -> Drawing {
    Drawing {
        outline: Circle::new(Point::ZERO, 0.5).to_path(1e-3),
        details: BezPath::new(),
        anchor: Point::ZERO,
        aspect: 1.0,
    }
}

/// Radius of a seigaiha scale in the tile: two scales across.
const WAVE_R: f64 = 0.25;

/// 青海波 seigaiha, the blue-ocean waves: a square tile of overlapping
/// scales, two across, each a fan of concentric arcs; the rows are half a
/// scale's radius apart, every row offset by half a scale and laid over
/// the row above it. The outline is the tile square (the pattern covers
/// it all); the details are the visible parts of every arc, so tiles
/// placed edge to edge — in a square grid or in rows offset by half a
/// tile — continue the waves without a seam.
///
/// `petals` counts the concentric arcs of a scale, the outermost being its
/// rim (default 4; clamped to 1–5).
pub(super) fn seigaiha(p: &MotifParams) -> Drawing {
    let n = p.petals.unwrap_or(4).clamp(1, 5);
    let r = WAVE_R;
    // Scales lie over the ones behind them, with larger y; only those
    // nearer than two radii can hide part of a scale.
    let mut front = Vec::new();
    for row in 1..=4 {
        for col in -4i32..=4 {
            if (col - row).rem_euclid(2) == 0 {
                let d = Vec2::new(f64::from(col) * r, f64::from(row) * r / 2.0);
                if d.hypot() < 2.0 * r - 1e-9 {
                    front.push(d);
                }
            }
        }
    }
    let mut details = BezPath::new();
    // Rows of scale centres from just below the tile to just above it; the
    // tile's top and bottom edges run through rows of centres.
    let rows = (2.0 * (1.0 + 2.0 * r) / r).round() as i32;
    for row in 0..=rows {
        let y = 0.5 + r - f64::from(row) * r / 2.0;
        for col in -4i32..=4 {
            if (col - row).rem_euclid(2) != 0 {
                continue;
            }
            let c = Point::new(f64::from(col) * r, y);
            if c.x.abs() > 0.5 + r + 1e-9 {
                continue;
            }
            for k in 1..=n {
                let radius = r * f64::from(k) / f64::from(n);
                let mut hidden: Vec<(f64, f64)> = front
                    .iter()
                    .filter_map(|d| disc_cover(*d, r, radius))
                    .collect();
                hidden.extend(box_cover(c, radius));
                for (a, b) in visible(&hidden) {
                    push_arc(&mut details, c, radius, a, b);
                }
            }
        }
    }
    Drawing {
        outline: Rect::new(-0.5, -0.5, 0.5, 0.5).to_path(0.0),
        details,
        anchor: Point::ZERO,
        aspect: 1.0,
    }
}

/// 亀甲 kikko, tortoise shell: a regular hexagon lying on its flat side
/// (points left and right), with concentric hexagons inside it.
///
/// `petals` counts the inner hexagons (default 1; clamped to 1–6).
pub(super) fn kikko(p: &MotifParams) -> Drawing {
    let n = p.petals.unwrap_or(1).clamp(1, 6);
    let gap = (0.8 / f64::from(n + 1)).min(0.16);
    let h = 3f64.sqrt() / 2.0;
    // Natural hexagon of circumradius 1 (2 wide, √3 high) into the box.
    let to_box = Affine::scale_non_uniform(0.5, 0.5 / h);
    let hexagon = |scale: f64| -> BezPath {
        let mut path = BezPath::new();
        for i in 0..6 {
            let a = f64::from(i) * PI / 3.0;
            let pt = Point::new(scale * a.cos(), scale * a.sin());
            if i == 0 {
                path.move_to(pt);
            } else {
                path.line_to(pt);
            }
        }
        path.close_path();
        to_box * path
    };
    let mut details = BezPath::new();
    for k in 1..=n {
        details.extend(hexagon(1.0 - gap * f64::from(k)).elements().iter().copied());
    }
    Drawing {
        outline: hexagon(1.0),
        details,
        anchor: Point::ZERO,
        aspect: h,
    }
}

/// 七宝 shippo, the seven treasures: a circle filling the tile with four
/// pointed lens-shaped petals inside it, on the diagonals, each cut off by
/// a quarter arc of the circle centred on the nearest tile corner. Tiles
/// placed edge to edge in a square grid join those quarter arcs into the
/// circles around the corners, which gives the endless pattern of
/// interlocking circles.
///
/// `petals` is not used.
pub(super) fn shippo(_p: &MotifParams) -> Drawing {
    let mut details = BezPath::new();
    for (cx, cy) in [(0.5, 0.5), (-0.5, 0.5), (-0.5, -0.5), (0.5, -0.5)] {
        // The quarter of the corner circle inside the tile, from the point
        // where it meets the horizontal axis to the vertical one.
        let centre = Point::new(cx, cy);
        let a = 0f64.atan2(-cx);
        let b = (-cy).atan2(0.0);
        let sweep = (b - a + PI).rem_euclid(TAU) - PI;
        push_arc(&mut details, centre, 0.5, a, a + sweep);
    }
    Drawing {
        outline: Circle::new(Point::ZERO, 0.5).to_path(1e-4),
        details,
        anchor: Point::ZERO,
        aspect: 1.0,
    }
}

/// The angles (an interval that may run past 2π) of the circle of radius
/// `radius` around the origin that lie inside the disc of radius `r`
/// centred at `d`, or `None`.
fn disc_cover(d: Vec2, r: f64, radius: f64) -> Option<(f64, f64)> {
    let dist = d.hypot();
    let cos = (radius * radius + dist * dist - r * r) / (2.0 * radius * dist);
    cover(d.y.atan2(d.x), cos)
}

/// The angles of the circle of radius `radius` around `c` that lie
/// outside the tile `[-0.5, 0.5]²`.
fn box_cover(c: Point, radius: f64) -> Vec<(f64, f64)> {
    [
        (0.0, 0.5 - c.x),
        (PI, 0.5 + c.x),
        (PI / 2.0, 0.5 - c.y),
        (-PI / 2.0, 0.5 + c.y),
    ]
    .into_iter()
    .filter_map(|(towards, room)| cover(towards, room / radius))
    .collect()
}

/// The angles around `towards` where the cosine of the angle between them
/// exceeds `cos`: all of the circle, none of it, or an interval.
fn cover(towards: f64, cos: f64) -> Option<(f64, f64)> {
    if !cos.is_finite() || cos >= 1.0 {
        None
    } else if cos <= -1.0 {
        Some((0.0, TAU))
    } else {
        let half = cos.acos();
        Some((towards - half, towards + half))
    }
}

/// The angle intervals of a circle (start < end, within 0–4π) not covered
/// by any of the `hidden` intervals.
fn visible(hidden: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut spans: Vec<(f64, f64)> = Vec::new();
    for &(a, b) in hidden {
        if b - a >= TAU {
            return Vec::new();
        }
        let len = (b - a).max(0.0);
        let a = a.rem_euclid(TAU);
        let b = a + len;
        if b > TAU {
            spans.push((a, TAU));
            spans.push((0.0, b - TAU));
        } else {
            spans.push((a, b));
        }
    }
    spans.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut free = Vec::new();
    let mut at = 0.0;
    for (a, b) in spans {
        if a > at {
            free.push((at, a));
        }
        at = f64::max(at, b);
    }
    if at < TAU {
        free.push((at, TAU));
    }
    // An arc through angle 0 is one arc, not two.
    if free.len() > 1 && free[0].0 <= 0.0 && free[free.len() - 1].1 >= TAU {
        let first = free.remove(0);
        if let Some(last) = free.last_mut() {
            last.1 = TAU + first.1;
        }
    }
    free.retain(|(a, b)| b - a > 1e-6);
    free
}

/// Appends the arc of the circle around `c` of radius `radius` from angle
/// `a` to `b` (radians, y down) as an open stroke.
fn push_arc(path: &mut BezPath, c: Point, radius: f64, a: f64, b: f64) {
    path.move_to(c + Vec2::from_angle(a) * radius);
    path.extend(Arc::new(c, (radius, radius), a, b - a, 0.0).append_iter(1e-4));
}

#[cfg(test)]
mod tests {
    use kurbo::{ParamCurve, PathEl, Point, Shape};

    use super::super::leaves::tests::{check, drawn};
    use super::super::{draw, MotifParams};
    use crate::geom::subpath::subpaths;
    use crate::rng::Seed;
    use crate::spec::MotifKind;

    const TILES: [MotifKind; 4] = [
        MotifKind::Circle,
        MotifKind::Seigaiha,
        MotifKind::Kikko,
        MotifKind::Shippo,
    ];

    /// Start and end points of the detail strokes.
    fn ends(kind: MotifKind, petals: Option<u32>) -> Vec<Point> {
        let d = drawn(kind, petals, 0.0, 1);
        let mut out = Vec::new();
        for sub in subpaths(&d.details) {
            out.push(sub.start());
            if let Some(p) = sub.body().last().and_then(PathEl::end_point) {
                out.push(p);
            }
        }
        out
    }

    /// The coordinates (`along` of each point) of the `ends` lying on the
    /// line where `across` is `at`, corners left out, sorted.
    fn on_edge(
        ends: &[Point],
        at: f64,
        across: fn(&Point) -> f64,
        along: fn(&Point) -> f64,
    ) -> Vec<f64> {
        let mut v: Vec<f64> = ends
            .iter()
            .filter(|p| (across(p) - at).abs() < 1e-9 && along(p).abs() < 0.5 - 1e-9)
            .map(along)
            .collect();
        v.sort_by(f64::total_cmp);
        v
    }

    /// The x of a point.
    fn px(p: &Point) -> f64 {
        p.x
    }

    /// The y of a point.
    fn py(p: &Point) -> f64 {
        p.y
    }

    /// Whether two sorted lists hold the same numbers (within 1e-6).
    fn same(a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-6)
    }

    /// Every tile keeps the motif invariants and is centred on (0, 0).
    #[test]
    fn tiles_fit_fill_and_hold_their_details() {
        for kind in TILES {
            for petals in [None, Some(1), Some(2), Some(3), Some(6), Some(7), Some(64)] {
                for jitter in [0.0, 0.5] {
                    let d = drawn(kind, petals, jitter, 1);
                    let what = format!("{kind:?} petals {petals:?} jitter {jitter}");
                    check(&d, &what);
                    assert_eq!(d.anchor, Point::ZERO, "{what}");
                    let b = d.outline.bounding_box();
                    assert!((b.x0 + b.x1).abs() < 1e-6, "{what}: {b:?}");
                    assert!((b.y0 + b.y1).abs() < 1e-6, "{what}: {b:?}");
                }
            }
        }
    }

    /// Tiles repeat exactly: jitter changes nothing and draws nothing.
    #[test]
    fn tiles_ignore_jitter_and_draw_nothing_random() {
        for kind in TILES {
            let mut rng = Seed(5).stream();
            let params = MotifParams {
                petals: None,
                jitter: 0.8,
            };
            let d = draw(kind, &params, &mut rng);
            assert_eq!(rng.next_u64(), Seed(5).stream().next_u64(), "{kind:?}");
            assert_eq!(d, drawn(kind, None, 0.0, 9), "{kind:?}");
        }
    }

    /// Square tiles, and a hexagon lying on its side.
    #[test]
    fn tile_aspects() {
        assert_eq!(drawn(MotifKind::Seigaiha, None, 0.0, 1).aspect, 1.0);
        assert_eq!(drawn(MotifKind::Shippo, None, 0.0, 1).aspect, 1.0);
        let kikko = drawn(MotifKind::Kikko, None, 0.0, 1).aspect;
        assert!((kikko - 3f64.sqrt() / 2.0).abs() < 1e-12);
    }

    /// Arcs leaving a seigaiha tile re-enter on the opposite edge, also
    /// with rows offset by half a tile.
    #[test]
    fn seigaiha_continues_across_tile_edges() {
        for petals in [None, Some(1), Some(3), Some(6)] {
            let e = ends(MotifKind::Seigaiha, petals);
            let (x, y) = (px, py);
            let left = on_edge(&e, -0.5, x, y);
            let right = on_edge(&e, 0.5, x, y);
            let top = on_edge(&e, -0.5, y, x);
            let bottom = on_edge(&e, 0.5, y, x);
            assert!(!left.is_empty() && !top.is_empty(), "{petals:?}");
            // Square grid: what leaves one edge enters the opposite one.
            assert!(same(&left, &right), "{petals:?}: {left:?} {right:?}");
            assert!(same(&top, &bottom), "{petals:?}: {top:?} {bottom:?}");
            // Rows offset by half a tile: the bottom edge shifted by half.
            let mut shifted: Vec<f64> = bottom
                .iter()
                .map(|x| if *x < 0.0 { x + 0.5 } else { x - 0.5 })
                .collect();
            shifted.sort_by(f64::total_cmp);
            assert!(same(&top, &shifted), "{petals:?}: {top:?} {shifted:?}");
        }
    }

    /// `petals` counts the concentric arcs of a scale.
    #[test]
    fn seigaiha_petals_count_the_arcs_of_a_scale() {
        // The scale in the middle of the tile, centred at (0, 0.25), shows
        // the crowns of all its arcs on the line x = 0 above its centre.
        for n in 1..=5 {
            let d = drawn(MotifKind::Seigaiha, Some(n), 0.0, 1);
            let crowns = (1..=n)
                .filter(|k| {
                    let p = Point::new(0.0, 0.25 - super::WAVE_R * f64::from(*k) / f64::from(n));
                    d.details
                        .segments()
                        .any(|s| (0..=50).any(|i| s.eval(f64::from(i) / 50.0).distance(p) < 2e-3))
                })
                .count();
            assert_eq!(crowns, n as usize, "{n}");
        }
    }

    /// The shippo quarter arcs are circles around the tile corners.
    #[test]
    fn shippo_quarter_arcs_close_into_circles_around_the_corners() {
        let d = drawn(MotifKind::Shippo, None, 0.0, 1);
        assert_eq!(subpaths(&d.details).count(), 4);
        for seg in d.details.segments() {
            for i in 0..=10 {
                let p = seg.eval(f64::from(i) / 10.0);
                let corner = Point::new(0.5f64.copysign(p.x), 0.5f64.copysign(p.y));
                assert!((p.distance(corner) - 0.5).abs() < 1e-3, "{p:?}");
            }
        }
        // Each arc runs between the midpoints of two edges, where the
        // neighbouring tiles continue it.
        for p in ends(MotifKind::Shippo, None) {
            let mid = (p.x.abs() - 0.5).abs() < 1e-9 && p.y.abs() < 1e-9
                || (p.y.abs() - 0.5).abs() < 1e-9 && p.x.abs() < 1e-9;
            assert!(mid, "{p:?}");
        }
    }

    /// `petals` counts the inner hexagons.
    #[test]
    fn kikko_petals_count_the_inner_hexagons() {
        for n in 1..=6 {
            let d = drawn(MotifKind::Kikko, Some(n), 0.0, 1);
            assert_eq!(subpaths(&d.details).count(), n as usize);
            assert_eq!(d.outline.elements().len(), 7);
        }
        assert_eq!(
            subpaths(&drawn(MotifKind::Kikko, None, 0.0, 1).details).count(),
            1
        );
    }
}
