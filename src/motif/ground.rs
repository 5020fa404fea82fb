//! The grounds as strokes over a window of the plane, in the repeat's own
//! frame (mm, y down): every line as long as the pattern lets it run, each
//! drawn once.
//!
//! * **Kagome**: three sets of parallel lines 120° apart, `scale` apart,
//!   placed so that no three meet in a point (offsets summing to half the
//!   spacing): hexagons with a triangle on each side.
//! * **Asanoha**: the triangle grid of side `scale` (three sets of lines
//!   through common points), and at every grid point three dashes across
//!   it, each along the height of the triangles it touches and reaching
//!   their centres: the corners of each triangle joined to its centre,
//!   drawn as the straight lines they lie on.
//! * **Kikkō**: a honeycomb of pointy-topped hexagons of radius `scale`,
//!   as the zigzags between rows and the upright edges within a row; each
//!   cell's inner outlines (`lines` − 1) as closed hexagons, a fifth of the
//!   radius apart.
//! * **Shippō**: circles of radius `scale` on a square grid of `scale`·√2,
//!   each crossing its four neighbours at their quarter points.
//! * **Seigaiha**: fans of `lines` concentric rings of radius up to
//!   `scale`, in rows `scale`/2 apart, each row shifted by a radius; a row
//!   in front (further down) hides what of the rows behind it lies under
//!   its fans, so each ring is drawn as its arcs in sight.
//! * **Same-komon**: seigaiha's fans with rings of dots in the middle of
//!   `lines` bands, the dots a band apart along each arc in sight, each
//!   a dot of ink (`motif::dot`), not a ring.
//! * **Uroko**: the triangle grid of side `scale`; its upward triangles
//!   are the dark shapes (closed, hatched by the pen), the others the
//!   paper between them, so no line but the dark triangles' edges.
//! * **Yagasuri**: upright lines `scale` apart, and in each column
//!   chevrons 1.5 `scale` apart, half a chevron higher in every other
//!   column.
//! * **Tatewaku**: upright waves `scale` apart, a quarter of that to
//!   either side, one wave `2·scale` long, each the mirror of the next:
//!   between two waves the paper swells and narrows in turn.

use std::f64::consts::{PI, TAU};

use kurbo::{Affine, Arc, BezPath, Circle, Line, Point, Rect, Shape, Vec2};

use serde::{Deserialize, Serialize};

use crate::error::Result;
use crate::geom::clip::StrokeClipper;
use crate::geom::natural_spline;
use crate::geom::region::{FillRule, Region};
use crate::geom::TOLERANCE;
use crate::motif::dot::dot;

/// The grounds, each a repeat that tiles the plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Ground {
    /// 青海波, blue ocean waves: rows of fans of concentric rings, each
    /// row half hidden by the row in front of it.
    Seigaiha,
    /// 麻の葉, hemp leaf: a triangle grid with a six-pointed star at every
    /// corner (each triangle's corners joined to its centre).
    Asanoha,
    /// 亀甲, tortoise shell: a honeycomb of hexagons, each with its inner
    /// outlines.
    Kikko,
    /// 七宝, seven treasures: circles overlapping by a quarter on a square
    /// grid.
    Shippo,
    /// 籠目, woven bamboo: three sets of straight lines, hexagons and
    /// triangles between them.
    Kagome,
    /// 鱗, scales: a triangle grid whose upward triangles are dark (hatched
    /// with the pen).
    Uroko,
    /// 矢絣, arrow feathers: columns of chevrons, each column half a
    /// chevron higher than the next.
    Yagasuri,
    /// 立涌, rising steam: wavy upright lines, each the mirror of the next,
    /// swelling and narrowing in turn.
    Tatewaku,
    /// 鮫小紋, shark skin: fans of concentric rings of fine dots, each row
    /// half hidden by the row in front, as seigaiha's rings are.
    #[serde(rename = "samekomon")]
    SameKomon,
}

impl Ground {
    /// Every ground, in the order of the enum.
    pub const ALL: [Ground; 9] = [
        Ground::Seigaiha,
        Ground::Asanoha,
        Ground::Kikko,
        Ground::Shippo,
        Ground::Kagome,
        Ground::Uroko,
        Ground::Yagasuri,
        Ground::Tatewaku,
        Ground::SameKomon,
    ];

    /// Its name in a description (`"seigaiha"`), and in the ids it draws.
    pub fn name(self) -> &'static str {
        match self {
            Ground::Seigaiha => "seigaiha",
            Ground::Asanoha => "asanoha",
            Ground::Kikko => "kikko",
            Ground::Shippo => "shippo",
            Ground::Kagome => "kagome",
            Ground::Uroko => "uroko",
            Ground::Yagasuri => "yagasuri",
            Ground::Tatewaku => "tatewaku",
            Ground::SameKomon => "samekomon",
        }
    }

    /// The `lines` it takes: `(least, most, default)`, or `None`.
    pub fn lines(self) -> Option<(u32, u32, u32)> {
        match self {
            Ground::Seigaiha => Some((1, 8, 4)),
            Ground::Kikko => Some((1, 3, 2)),
            Ground::SameKomon => Some((1, 8, 3)),
            Ground::Asanoha
            | Ground::Shippo
            | Ground::Kagome
            | Ground::Uroko
            | Ground::Yagasuri
            | Ground::Tatewaku => None,
        }
    }
}

/// Curves are made within this distance of the true circle, mm.
const ACCURACY: f64 = 1e-3;

/// The inner outlines of a kikkō cell: each a fifth of the radius inside
/// the one around it.
const KIKKO_STEP: f64 = 0.2;

/// What a ground draws over a window, in the repeat's frame.
#[derive(Debug, Clone, Default)]
pub(crate) struct Drawn {
    /// Lines, arcs and dots.
    pub strokes: Vec<BezPath>,
    /// Closed shapes inked all over (hatched by the pen).
    pub dark: Vec<BezPath>,
}

/// A repeat laid over a region: its frame placed on the page, and the
/// window of the frame that covers the region's box, a repeat to spare.
pub(crate) struct Laid {
    place: Affine,
    window: Rect,
}

impl Laid {
    /// A repeat of `scale` mm over `bounds`, its frame's origin at
    /// `origin` on the page and turned clockwise by `angle_deg`.
    pub(crate) fn new(bounds: Rect, scale: f64, origin: Point, angle_deg: f64) -> Laid {
        let place = Affine::translate(origin.to_vec2()) * Affine::rotate(angle_deg.to_radians());
        let window = place
            .inverse()
            .transform_rect_bbox(bounds)
            .inflate(scale, scale);
        Laid { place, window }
    }

    /// The part of the frame it covers.
    pub(crate) fn window(&self) -> Rect {
        self.window
    }

    /// `ground` in `region` on the page: the strokes clipped to it, the
    /// dark shapes cut to it as areas (so they stay closed); dots for a
    /// pen `pen_width` mm wide.
    ///
    /// # Errors
    /// From the region machinery on a degenerate dark shape.
    pub(crate) fn draw(
        &self,
        region: &Region,
        ground: Ground,
        scale: f64,
        lines: u32,
        pen_width: f64,
    ) -> Result<Drawn> {
        let drawn = draw(ground, scale, lines, pen_width, self.window);
        let clipper = StrokeClipper::new(region, TOLERANCE);
        let strokes = drawn
            .strokes
            .into_iter()
            .flat_map(|stroke| clipper.clip(&(self.place * stroke)).inside)
            .collect();
        let mut dark = Vec::new();
        for shape in drawn.dark {
            let cut = Region::new(self.place * shape, FillRule::NonZero)?.intersection(region);
            if !cut.is_empty() {
                dark.push(cut.into_path());
            }
        }
        Ok(Drawn { strokes, dark })
    }
}

/// `ground` over `window`, in the repeat's frame (the repeat's origin is
/// the frame's); dots are drawn for a pen `pen_width` mm wide.
pub(crate) fn draw(ground: Ground, scale: f64, lines: u32, pen_width: f64, window: Rect) -> Drawn {
    let strokes = match ground {
        Ground::Kagome => kagome(scale, window),
        Ground::Asanoha => asanoha(scale, window),
        Ground::Kikko => kikko(scale, lines, window),
        Ground::Shippo => shippo(scale, window),
        Ground::Seigaiha => seigaiha(scale, lines, window),
        Ground::SameKomon => same_komon(scale, lines, pen_width, window),
        Ground::Yagasuri => yagasuri(scale, window),
        Ground::Tatewaku => tatewaku(scale, window),
        Ground::Uroko => {
            return Drawn {
                strokes: Vec::new(),
                dark: uroko(scale, window),
            }
        }
    };
    Drawn {
        strokes,
        dark: Vec::new(),
    }
}

/// About how many strokes [`strokes`] makes over `window`, never fewer
/// (for the path budget, taken before the work).
pub(crate) fn estimate(ground: Ground, scale: f64, lines: u32, window: Rect) -> f64 {
    // Motifs per square `scale` (the pattern's density), and lines
    // across the window.
    let per_square = match ground {
        Ground::Kagome => 0.0,
        // Three dashes at each grid point (1.15 points per square).
        Ground::Asanoha => 3.5,
        // An upright edge and the inner outlines of each cell (0.39 cells
        // per square).
        Ground::Kikko => 0.4 * f64::from(lines),
        // Half a circle per square.
        Ground::Shippo => 0.5,
        // One fan per square, each ring in up to three arcs.
        Ground::Seigaiha => 3.0 * f64::from(lines),
        // One fan per square, ring k of it about 2.1·k dots in sight.
        Ground::SameKomon => 1.5 * f64::from(lines * (lines + 1)),
        // 1.15 upward triangles per square.
        Ground::Uroko => 1.2,
        // A chevron per 1.5 squares.
        Ground::Yagasuri => 0.7,
        Ground::Tatewaku => 0.0,
    };
    let (w, h) = (window.width() / scale + 2.0, window.height() / scale + 2.0);
    per_square * w * h + 4.0 * (w + h) + 16.0
}

/// Lines `p·n = offset + k·spacing` crossing `window`, each cut to it.
fn parallels(normal: Vec2, spacing: f64, offset: f64, window: Rect) -> Vec<BezPath> {
    let corners = [
        Point::new(window.x0, window.y0),
        Point::new(window.x1, window.y0),
        Point::new(window.x0, window.y1),
        Point::new(window.x1, window.y1),
    ];
    let (lo, hi) = corners
        .iter()
        .map(|c| c.to_vec2().dot(normal))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    let along = Vec2::new(-normal.y, normal.x);
    let reach = window.width().hypot(window.height());
    let centre = window.center().to_vec2();
    let first = ((lo - offset) / spacing).ceil() as i64;
    let last = ((hi - offset) / spacing).floor() as i64;
    (first..=last)
        .map(|k| {
            let level = offset + k as f64 * spacing;
            // The point of the line nearest the window's centre.
            let foot = centre + normal * (level - centre.dot(normal));
            let line = Line::new(
                (foot - along * reach).to_point(),
                (foot + along * reach).to_point(),
            );
            let mut path = BezPath::new();
            path.move_to(line.p0);
            path.line_to(line.p1);
            path
        })
        .collect()
}

/// The unit normal at `deg` degrees.
fn unit(deg: f64) -> Vec2 {
    Vec2::from_angle(deg.to_radians())
}

fn kagome(scale: f64, window: Rect) -> Vec<BezPath> {
    // Offsets 0, 0 and half a spacing: where two lines cross, the third
    // set's nearest line is half a spacing away, never through the point.
    [(90.0, 0.0), (210.0, 0.0), (330.0, 0.5 * scale)]
        .into_iter()
        .flat_map(|(deg, offset)| parallels(unit(deg), scale, offset, window))
        .collect()
}

fn asanoha(scale: f64, window: Rect) -> Vec<BezPath> {
    let height = scale * 3f64.sqrt() / 2.0;
    // The grid: lines along 0°, 60° and 120° through common points.
    let mut strokes: Vec<BezPath> = [90.0, 150.0, 210.0]
        .into_iter()
        .flat_map(|deg| parallels(unit(deg), height, 0.0, window))
        .collect();
    // Every grid point, with the three dashes across it: from the centre
    // of a triangle on one side to the centre of the one on the other,
    // along their heights (the corner is 2/3 of a height from each).
    let reach = 2.0 / 3.0 * height;
    let (a, b) = (Vec2::new(scale, 0.0), Vec2::new(0.5 * scale, height));
    let rows = (window.y0 / height).floor() as i64 - 1..=(window.y1 / height).ceil() as i64 + 1;
    for j in rows {
        let shift = j as f64 * b.x;
        let columns = ((window.x0 - shift) / scale).floor() as i64 - 1
            ..=((window.x1 - shift) / scale).ceil() as i64 + 1;
        for i in columns {
            let p = (a * i as f64 + b * j as f64).to_point();
            if !window.inflate(reach, reach).contains(p) {
                continue;
            }
            for deg in [30.0, 90.0, 150.0] {
                let d = unit(deg) * reach;
                let mut dash = BezPath::new();
                dash.move_to(p - d);
                dash.line_to(p + d);
                strokes.push(dash);
            }
        }
    }
    strokes
}

fn kikko(scale: f64, lines: u32, window: Rect) -> Vec<BezPath> {
    let width = scale * 3f64.sqrt();
    let pitch = 1.5 * scale;
    let mut strokes = Vec::new();
    let rows = (window.y0 / pitch).floor() as i64 - 1..=(window.y1 / pitch).ceil() as i64 + 1;
    let columns = |shift: f64| {
        ((window.x0 - shift) / width).floor() as i64 - 1
            ..=((window.x1 - shift) / width).ceil() as i64 + 1
    };
    for j in rows {
        let y = j as f64 * pitch;
        let shift = if j.rem_euclid(2) == 1 {
            0.5 * width
        } else {
            0.0
        };
        // The zigzag above row j: the row's top corners and the corners
        // between them, shared with the row above.
        let mut zigzag = BezPath::new();
        for (n, i) in columns(shift).enumerate() {
            let x = shift + i as f64 * width;
            let left = Point::new(x - 0.5 * width, y - 0.5 * scale);
            let top = Point::new(x, y - scale);
            if n == 0 {
                zigzag.move_to(left);
            } else {
                zigzag.line_to(left);
            }
            zigzag.line_to(top);
        }
        strokes.push(zigzag);
        for i in columns(shift) {
            let x = shift + i as f64 * width - 0.5 * width;
            let mut edge = BezPath::new();
            edge.move_to((x, y - 0.5 * scale));
            edge.line_to((x, y + 0.5 * scale));
            strokes.push(edge);
            let centre = Point::new(x + 0.5 * width, y);
            for m in 1..lines {
                strokes.push(hexagon(centre, scale * (1.0 - KIKKO_STEP * f64::from(m))));
            }
        }
    }
    strokes
}

/// A closed pointy-topped hexagon.
fn hexagon(centre: Point, radius: f64) -> BezPath {
    let mut path = BezPath::new();
    for k in 0..6 {
        let corner = centre + Vec2::from_angle(PI / 6.0 + f64::from(k) * PI / 3.0) * radius;
        if k == 0 {
            path.move_to(corner);
        } else {
            path.line_to(corner);
        }
    }
    path.close_path();
    path
}

fn shippo(scale: f64, window: Rect) -> Vec<BezPath> {
    let step = scale * 2f64.sqrt();
    let grid = |lo: f64, hi: f64| (lo / step).floor() as i64 - 1..=(hi / step).ceil() as i64 + 1;
    let mut strokes = Vec::new();
    for j in grid(window.y0, window.y1) {
        for i in grid(window.x0, window.x1) {
            let centre = Point::new(i as f64 * step, j as f64 * step);
            if window.inflate(scale, scale).contains(centre) {
                strokes.push(Circle::new(centre, scale).to_path(ACCURACY));
            }
        }
    }
    strokes
}

fn seigaiha(scale: f64, lines: u32, window: Rect) -> Vec<BezPath> {
    let radii: Vec<f64> = (0..lines)
        .map(|k| scale * f64::from(lines - k) / f64::from(lines))
        .collect();
    fan_arcs(scale, &radii, window)
        .into_iter()
        .map(|arc| arc.to_path(ACCURACY))
        .collect()
}

fn same_komon(scale: f64, lines: u32, pen_width: f64, window: Rect) -> Vec<BezPath> {
    // Rings in the middle of `lines` bands; dots a band apart, their ink
    // a little under half a band across (a pen's tap at the least).
    let band = scale / f64::from(lines);
    let radii: Vec<f64> = (0..lines).map(|k| band * (f64::from(k) + 0.5)).collect();
    let ink = (0.22 * band).max(0.5 * pen_width);
    let mut dots = Vec::new();
    for arc in fan_arcs(scale, &radii, window) {
        let length = arc.sweep_angle * arc.radii.x;
        let n = (length / band).round().max(1.0);
        for i in 0..n as usize {
            let angle = arc.start_angle + arc.sweep_angle * (i as f64 + 0.5) / n;
            dots.push(dot(
                arc.center + Vec2::from_angle(angle) * arc.radii.x,
                ink,
                pen_width,
            ));
        }
    }
    dots
}

/// The arcs in sight of fans of rings of `radii` (at most `scale`), in
/// rows `scale`/2 apart, each row shifted by `scale` and hiding what of
/// the rows behind it lies under its fans (discs of radius `scale`).
fn fan_arcs(scale: f64, radii: &[f64], window: Rect) -> Vec<Arc> {
    let pitch = 0.5 * scale;
    let fan = |i: i64, j: i64| {
        let shift = if j.rem_euclid(2) == 1 { scale } else { 0.0 };
        Point::new(shift + i as f64 * 2.0 * scale, j as f64 * pitch)
    };
    let mut arcs = Vec::new();
    let rows = (window.y0 / pitch).floor() as i64 - 1..=(window.y1 / pitch).ceil() as i64 + 4;
    for j in rows {
        let shift = if j.rem_euclid(2) == 1 { scale } else { 0.0 };
        let columns = ((window.x0 - shift) / (2.0 * scale)).floor() as i64 - 1
            ..=((window.x1 - shift) / (2.0 * scale)).ceil() as i64 + 1;
        for i in columns {
            let centre = fan(i, j);
            if !window.inflate(scale, scale).contains(centre) {
                continue;
            }
            // The fans in front that reach this one: the next four rows,
            // within two radii.
            let front: Vec<Point> = (1..=4)
                .flat_map(|dj| (-2..=2).map(move |di| (di, dj)))
                .map(|(di, dj)| fan(i + di, j + dj))
                .filter(|c| c.distance(centre) < 2.0 * scale)
                .collect();
            for &radius in radii {
                for (start, sweep) in in_sight(centre, radius, &front, scale) {
                    arcs.push(Arc::new(centre, (radius, radius), start, sweep, 0.0));
                }
            }
        }
    }
    arcs
}

fn uroko(scale: f64, window: Rect) -> Vec<BezPath> {
    let height = scale * 3f64.sqrt() / 2.0;
    let mut dark = Vec::new();
    let rows = (window.y0 / height).floor() as i64 - 1..=(window.y1 / height).ceil() as i64 + 2;
    for j in rows {
        let y = j as f64 * height;
        let shift = if j.rem_euclid(2) == 1 {
            0.5 * scale
        } else {
            0.0
        };
        let columns = ((window.x0 - shift) / scale).floor() as i64 - 1
            ..=((window.x1 - shift) / scale).ceil() as i64 + 1;
        for i in columns {
            let x = shift + i as f64 * scale;
            let mut triangle = BezPath::new();
            triangle.move_to((x, y));
            triangle.line_to((x + scale, y));
            triangle.line_to((x + 0.5 * scale, y - height));
            triangle.close_path();
            dark.push(triangle);
        }
    }
    dark
}

fn yagasuri(scale: f64, window: Rect) -> Vec<BezPath> {
    let pitch = 1.5 * scale;
    let depth = 0.5 * scale;
    let mut strokes = parallels(Vec2::new(1.0, 0.0), scale, 0.0, window);
    let columns = (window.x0 / scale).floor() as i64 - 1..=(window.x1 / scale).ceil() as i64;
    for k in columns {
        let x = k as f64 * scale;
        let lift = if k.rem_euclid(2) == 1 {
            0.5 * pitch
        } else {
            0.0
        };
        let rows = ((window.y0 - lift) / pitch).floor() as i64 - 1
            ..=((window.y1 - lift) / pitch).ceil() as i64 + 1;
        for m in rows {
            let y = lift + m as f64 * pitch;
            let mut chevron = BezPath::new();
            chevron.move_to((x, y));
            chevron.line_to((x + 0.5 * scale, y + depth));
            chevron.line_to((x + scale, y));
            strokes.push(chevron);
        }
    }
    strokes
}

fn tatewaku(scale: f64, window: Rect) -> Vec<BezPath> {
    let sway = 0.25 * scale;
    let wave = 2.0 * scale;
    // Points 1/16 of a wave apart: the spline through them stays within
    // a micrometre of the sine at these sizes.
    let step = wave / 16.0;
    let first = ((window.y0 - wave) / wave).floor() * wave;
    let count = ((window.y1 + wave - first) / step).ceil() as usize + 1;
    let columns = (window.x0 / scale).floor() as i64 - 1..=(window.x1 / scale).ceil() as i64 + 1;
    columns
        .map(|k| {
            let side = if k.rem_euclid(2) == 1 { -sway } else { sway };
            let points: Vec<Point> = (0..count)
                .map(|n| {
                    let y = first + n as f64 * step;
                    Point::new(k as f64 * scale + side * (TAU * y / wave).cos(), y)
                })
                .collect();
            natural_spline(&points)
        })
        .collect()
}

/// The arcs of the circle (`centre`, `radius`) outside every disc of
/// radius `cover` about `front`, as `(start angle, sweep)` in radians.
fn in_sight(centre: Point, radius: f64, front: &[Point], cover: f64) -> Vec<(f64, f64)> {
    // The hidden angles, as intervals from 0 up to 2π (split where they
    // wrap round).
    let mut hidden: Vec<(f64, f64)> = Vec::new();
    for &d in front {
        let dist = d.distance(centre);
        if dist + radius <= cover {
            return Vec::new();
        }
        if dist >= radius + cover || dist < 1e-12 {
            continue;
        }
        let towards = (d - centre).atan2();
        let half = ((radius * radius + dist * dist - cover * cover) / (2.0 * radius * dist))
            .clamp(-1.0, 1.0)
            .acos();
        let (a, b) = (
            (towards - half).rem_euclid(TAU),
            (towards + half).rem_euclid(TAU),
        );
        if a <= b {
            hidden.push((a, b));
        } else {
            hidden.push((a, TAU));
            hidden.push((0.0, b));
        }
    }
    hidden.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut seen = Vec::new();
    let mut at = 0.0;
    for (a, b) in hidden {
        if a > at {
            seen.push((at, a - at));
        }
        at = f64::max(at, b);
    }
    if at < TAU {
        seen.push((at, TAU - at));
    }
    // An arc through angle 0 is one arc, not two.
    if seen.len() > 1 {
        let (first, last) = (seen[0], seen[seen.len() - 1]);
        if first.0 == 0.0 && last.0 + last.1 >= TAU {
            seen.pop();
            seen[0] = (last.0 - TAU, last.1 + first.1);
        }
    }
    seen.retain(|&(_, sweep)| sweep * radius > 1e-6);
    seen
}
