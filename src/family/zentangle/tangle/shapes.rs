//! What the tangles draw with: discs, polygons, smooth closed curves, a
//! turned lattice over a section, circles packed into it, points along
//! its outline.

use kurbo::{BezPath, Circle, Point, Rect, Shape as _, Vec2};
use rustc_hash::FxHashMap;

use super::super::element::{Mark, Paint};
use crate::geom::region::Region;
use crate::geom::TOLERANCE;
use crate::rng::RandomStream;

/// Most cells of one lattice, most circles of one packing, most points
/// along one outline: a section a metre across at the smallest unit
/// stays within this, anything beyond is cut off.
pub(super) const MAX_ITEMS: usize = 20_000;

/// A mark.
pub(super) fn mark(path: BezPath, paint: Paint) -> Mark {
    Mark { path, paint }
}

/// A circle as a path.
pub(super) fn circle(c: Point, r: f64) -> BezPath {
    Circle::new(c, r).to_path(TOLERANCE)
}

/// The polyline through `points`, closed when `close` says.
pub(super) fn polyline(points: &[Point], close: bool) -> BezPath {
    let mut path = BezPath::new();
    for (i, p) in points.iter().enumerate() {
        if i == 0 {
            path.move_to(*p);
        } else {
            path.line_to(*p);
        }
    }
    if close && points.len() > 2 {
        path.close_path();
    }
    path
}

/// The smooth closed curve through `points` (Catmull-Rom, as cubics): a
/// hand's curve through the points a tangler aims at.
pub(super) fn smooth_closed(points: &[Point]) -> BezPath {
    let n = points.len();
    let mut path = BezPath::new();
    if n < 3 {
        return path;
    }
    path.move_to(points[0]);
    for i in 0..n {
        let (p0, p1, p2, p3) = (
            points[(i + n - 1) % n],
            points[i],
            points[(i + 1) % n],
            points[(i + 2) % n],
        );
        path.curve_to(p1 + (p2 - p0) / 6.0, p2 - (p3 - p1) / 6.0, p2);
    }
    path.close_path();
    path
}

/// A lattice turned by an angle, centred on a section's box and reaching
/// past all of it: cells `(i, j)` of `pitch` mm, their corners mapped to
/// the page.
pub(super) struct Lattice {
    centre: Point,
    /// The lattice's first axis on the page, and its second.
    u: Vec2,
    v: Vec2,
    pitch: f64,
    /// Cells from the centre to past the box, each way.
    reach: i64,
}

impl Lattice {
    /// The lattice over `bounds` turned by `angle` (radians), `pitch` mm
    /// a cell; `None` when it would have more than [`MAX_ITEMS`] cells.
    pub(super) fn new(bounds: Rect, angle: f64, pitch: f64) -> Option<Lattice> {
        let half = 0.5 * bounds.width().hypot(bounds.height());
        let reach = (half / pitch).ceil() as i64 + 1;
        ((2 * reach + 1).pow(2) as usize <= MAX_ITEMS).then(|| Lattice {
            centre: bounds.center(),
            u: Vec2::from_angle(angle),
            v: Vec2::from_angle(angle).turn_90(),
            pitch,
            reach,
        })
    }

    /// Every cell `(i, j)` (its corner at [`Lattice::at`]`(i, j)`).
    pub(super) fn cells(&self) -> impl Iterator<Item = (i64, i64)> + '_ {
        let r = self.reach;
        (-r..=r).flat_map(move |j| (-r..=r).map(move |i| (i, j)))
    }

    /// The page point at lattice coordinates `(x, y)` (in cells).
    pub(super) fn at(&self, x: f64, y: f64) -> Point {
        self.centre + (self.u * x + self.v * y) * self.pitch
    }

    /// The corners of cell `(i, j)` shrunk about its centre to `share`.
    pub(super) fn cell(&self, i: i64, j: i64, share: f64) -> [Point; 4] {
        let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
        let h = share / 2.0;
        [
            self.at(x - h, y - h),
            self.at(x + h, y - h),
            self.at(x + h, y + h),
            self.at(x - h, y + h),
        ]
    }
}

/// Whether a shape centred at `centre` and reaching `reach` mm from it
/// may show in `region` (shapes wholly off its box are not drawn).
pub(super) fn near(region: &Region, centre: Point, reach: f64) -> bool {
    region.bounds().inflate(reach, reach).contains(centre)
}

/// Circles packed into `region` by a hand that draws the big ones first:
/// `tries` random centres inside it, the radius falling from `largest` to
/// `smallest` over the tries, each circle kept when it lies at least
/// `gap` from every circle kept before. A circle may run off the region
/// (its centre lies inside), as a tangle runs off its section. At most
/// [`MAX_ITEMS`].
pub(super) fn pack(
    region: &Region,
    (smallest, largest): (f64, f64),
    gap: f64,
    rng: &mut RandomStream,
) -> Vec<(Point, f64)> {
    let b = region.bounds();
    // Tries: enough to fill the box many times over with the small ones.
    let tries = ((8.0 * b.area() / (smallest * smallest)) as usize).min(10 * MAX_ITEMS);
    let cell = 2.0 * largest + gap;
    let mut grid: FxHashMap<(i64, i64), Vec<usize>> = FxHashMap::default();
    let mut kept: Vec<(Point, f64)> = Vec::new();
    let key = |p: Point| ((p.x / cell).floor() as i64, (p.y / cell).floor() as i64);
    for k in 0..tries {
        if kept.len() >= MAX_ITEMS {
            break;
        }
        let c = Point::new(rng.range(b.x0, b.x1), rng.range(b.y0, b.y1));
        let fall = (k as f64 / tries as f64 * 3.0).min(1.0);
        let r = largest + (smallest - largest) * fall * rng.range(0.7, 1.0);
        if !region.contains(c) {
            continue;
        }
        let (gx, gy) = key(c);
        let clear = (gx - 1..=gx + 1)
            .flat_map(|x| (gy - 1..=gy + 1).map(move |y| (x, y)))
            .filter_map(|g| grid.get(&g))
            .flatten()
            .all(|&i| kept[i].0.distance(c) >= kept[i].1 + r + gap);
        if clear {
            grid.entry((gx, gy)).or_default().push(kept.len());
            kept.push((c, r));
        }
    }
    kept
}

/// Points about `step` mm apart along every contour of `region`, each with
/// the unit normal pointing into it; at most [`MAX_ITEMS`].
pub(super) fn along_outline(region: &Region, step: f64) -> Vec<(Point, Vec2)> {
    let mut out = Vec::new();
    for contour in region.polygons(TOLERANCE) {
        let n = contour.len();
        let length: f64 = (0..n).map(|i| contour[i].distance(contour[(i + 1) % n])).sum();
        let count = (length / step).round() as usize;
        if count < 2 {
            continue;
        }
        let every = length / count as f64;
        let (mut walked, mut next) = (0.0, every / 2.0);
        for i in 0..n {
            let (a, b) = (contour[i], contour[(i + 1) % n]);
            let len = a.distance(b);
            while next < walked + len && out.len() < MAX_ITEMS {
                let at = a.lerp(b, (next - walked) / len);
                let normal = (b - a).turn_90().normalize();
                // Inwards is whichever side the region is on.
                let probe = 0.01 * step;
                let inward = if region.contains(at + normal * probe) {
                    normal
                } else {
                    -normal
                };
                out.push((at, inward));
                next += every;
            }
            walked += len;
        }
    }
    out
}
