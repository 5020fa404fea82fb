//! Islands and bridges (katagami's *tsuri*): the pieces of a stencil sheet
//! that would fall out, the long slits that would flap, and the strips of
//! paper left uncut that hold them.
//!
//! The cut-outs come as shapes (the stencil's polygons): an outer contour,
//! the *wall*, and holes. An *island* is paper enclosed by one cut-out: a
//! hole of a shape. The paper just outside the wall is its *holder*,
//! which may be an island itself (rings inside rings), so holding every
//! island of a cut-out to its holder ties every piece to the sheet.
//! Islands narrower than the blade's smallest feature are *specks*: cut
//! away whole.
//!
//! A cut-out can be a web (a ground of waves, a lattice): its islands lie
//! side by side, most far from the wall. So bridges cross the cut
//! straight, from one contour to the next, and the narrowest crossings
//! that join what is not yet joined are taken until every island holds to
//! the wall, through its neighbours if need be (a spanning tree). Each
//! bridge reaches half its width into the paper at both ends, so that it
//! joins it whatever the curvature.
//!
//! Long outlines and long slits (cut-outs that run long, freeing
//! something or not) flap like a loose tongue: walking along every
//! contour, a bridge once `every` mm have passed since the last, and none
//! lies within ¾ of that (the slit's other side, walked back), where the
//! cut is no wider than [`MAX_SLIT`] and the contour turns little (not at
//! a corner or round a slit's end) (a wider cut-out is a
//! window, whose sides stand on their own).
//!
//! Crossings are looked for every [`SAMPLE_SPACING`] along every contour:
//! a bridge lands within that spacing of the narrowest place.

use i_overlay::core::overlay_rule::OverlayRule;
use kurbo::{BezPath, Point, Vec2};

use super::shapes::{contour_path, overlay, Contour, Shape};
use crate::error::{Error, Result};
use crate::geom::polylabel::pole_of_inaccessibility;
use crate::geom::region::Region;

/// Crossings of the cut are looked for this often along its contours, mm.
pub const SAMPLE_SPACING: f64 = 0.25;

/// The widest cut (mm) that counts as a slit and gets bridges along it.
pub const MAX_SLIT: f64 = 2.0;

/// One bridge: a strip of paper `width` mm wide from `from`, on one side
/// of a cut, to `to`, on the other.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bridge {
    /// Where it leaves the paper.
    pub from: Point,
    /// Where it reaches the paper across the cut.
    pub to: Point,
    /// Its width, mm.
    pub width: f64,
    /// An island it holds (index into the islands found with it); `None`
    /// for a bridge across a long slit, from the paper around a cut-out
    /// back to it.
    pub island: Option<usize>,
}

impl Bridge {
    /// The strip as a region: the segment from `from` to `to`, lengthened
    /// by half the width at both ends, `width` wide.
    pub fn region(&self) -> Result<Region> {
        Region::polygon(&self.corners(self.width / 2.0))
    }

    /// The corners of the strip from `from` to `to` lengthened by `reach`
    /// mm at both ends.
    pub fn corners(&self, reach: f64) -> [Point; 4] {
        let along = self.to - self.from;
        let length = along.hypot();
        let u = if length > 0.0 {
            along / length
        } else {
            Vec2::new(1.0, 0.0)
        };
        let n = Vec2::new(-u.y, u.x) * (self.width / 2.0);
        let (a, b) = (self.from - u * reach, self.to + u * reach);
        [a + n, b + n, b - n, a - n]
    }

    /// The strip as a shape (see [`Bridge::corners`]).
    pub(crate) fn shape(&self) -> Shape {
        let mut corners = self.corners(self.width / 2.0).map(|p| [p.x, p.y]);
        // Anticlockwise (y up), as outer contours run.
        if super::shapes::area(&corners) < 0.0 {
            corners.reverse();
        }
        vec![corners.to_vec()]
    }

    /// The length of the gap it crosses, mm.
    pub fn span(&self) -> f64 {
        self.from.distance(self.to)
    }
}

/// An island of the sheet and where it is held.
#[derive(Debug, Clone, PartialEq)]
pub struct Island {
    /// The island's outline (outer contour).
    pub outline: BezPath,
    /// A point well inside it (its pole of inaccessibility), for reports.
    pub centre: Point,
    /// The widest circle inside it, diameter in mm.
    pub across: f64,
}

/// What [`bridge`] found.
#[derive(Debug, Clone, Default)]
pub(crate) struct Bridged {
    /// The cut-outs with the specks cut away whole and the bridges taken
    /// out.
    pub(crate) holes: Vec<Shape>,
    /// Every island.
    pub(crate) islands: Vec<Island>,
    /// Every bridge.
    pub(crate) bridges: Vec<Bridge>,
    /// Where specks were cut away.
    pub(crate) specks: Vec<Point>,
}

/// The islands that the cut-outs `cut` free, with the bridges that tie
/// them to the sheet: across the narrowest gaps, enough to hold every
/// island; more along outlines and slits longer than `every` mm (0: no
/// more); and the cut-outs with islands narrower than `min_feature`
/// (specks) cut away and the bridges taken out, each cut-out apart (a
/// bridge holds to its own cut-out: where it reaches into the paper past
/// another, that one stays whole).
///
/// # Errors
/// [`Error::Invalid`] (field `bridge`) when `width` is as wide as the
/// whole cut-out it must cross (the bridge would leave nothing of it);
/// the message names the place.
pub(crate) fn bridge(
    mut cut: Vec<Shape>,
    width: f64,
    every: f64,
    min_feature: f64,
    tolerance: f64,
) -> Result<Bridged> {
    // Each cut-out is bridged apart, so the two halves of the list (by
    // points, which the time follows) go on two threads, and the second's
    // islands are numbered on from the first's: the same as one pass.
    let points = |shapes: &[Shape]| shapes.iter().flatten().map(Vec::len).sum::<usize>();
    let half = points(&cut) / 2;
    let mut seen = 0;
    let split = cut
        .iter()
        .position(|s| {
            seen += points(std::slice::from_ref(s));
            seen >= half
        })
        .map_or(cut.len(), |k| k + 1);
    let second = cut.split_off(split);
    let (first, second) = std::thread::scope(|scope| {
        let other = scope.spawn(move || bridge_each(second, width, every, min_feature, tolerance));
        let first = bridge_each(cut, width, every, min_feature, tolerance);
        let second = other
            .join()
            .unwrap_or_else(|e| std::panic::resume_unwind(e));
        (first, second)
    });
    let (mut out, second) = (first?, second?);
    let numbered = out.islands.len();
    out.holes.extend(second.holes);
    out.islands.extend(second.islands);
    out.bridges
        .extend(second.bridges.into_iter().map(|b| Bridge {
            island: b.island.map(|k| k + numbered),
            ..b
        }));
    out.specks.extend(second.specks);
    Ok(out)
}

/// [`bridge`] on one thread, cut-out after cut-out.
fn bridge_each(
    cut: Vec<Shape>,
    width: f64,
    every: f64,
    min_feature: f64,
    tolerance: f64,
) -> Result<Bridged> {
    let mut out = Bridged::default();
    for shape in cut {
        let mut kept: Shape = Vec::with_capacity(shape.len());
        // The island (index into `out.islands`) of each kept contour.
        let mut held: Vec<Option<usize>> = Vec::with_capacity(shape.len());
        for (k, contour) in shape.into_iter().enumerate() {
            if k == 0 {
                kept.push(contour);
                held.push(None);
                continue;
            }
            // The island's outline, turned to enclose it.
            let mut ring = contour.clone();
            ring.reverse();
            // No circle wider than the box fits in it: most specks are
            // known without a search.
            let b = super::shapes::bounds(&ring);
            if b.width().min(b.height()) < min_feature {
                out.specks.push(b.center());
                continue;
            }
            let outline = contour_path(&ring);
            let (centre, radius) =
                pole_of_inaccessibility(&Region::from_normalised(outline.clone()), tolerance)
                    .unwrap_or((b.center(), 0.0));
            if 2.0 * radius < min_feature {
                out.specks.push(centre);
                continue;
            }
            held.push(Some(out.islands.len()));
            out.islands.push(Island {
                outline,
                centre,
                across: 2.0 * radius,
            });
            kept.push(contour);
        }
        let first_bridge = out.bridges.len();
        for (from, to, a, b) in shape_bridges(&kept, every) {
            let bridge = Bridge {
                from,
                to,
                width,
                island: held[a].or(held[b]),
            };
            if let Some(island) = [a, b].into_iter().find(|&c| c > 0) {
                check_gap(&bridge, &kept[island], &kept[0])?;
            }
            out.bridges.push(bridge);
        }
        let strips: Vec<Shape> = out.bridges[first_bridge..]
            .iter()
            .map(Bridge::shape)
            .collect();
        if strips.is_empty() {
            out.holes.push(kept);
        } else {
            out.holes
                .extend(overlay(&[kept], &strips, OverlayRule::Difference));
        }
    }
    Ok(out)
}

/// Refuses a bridge as wide as the whole cut-out it crosses, measured
/// across the bridge (the wall's extent along the bridge's width): it
/// would cover the cut and the island with it. The island lies inside the
/// wall, so a bridge narrower than the island across needs no look at the
/// wall.
fn check_gap(b: &Bridge, island: &[[f64; 2]], wall: &[[f64; 2]]) -> Result<()> {
    let along = b.to - b.from;
    let n = if along.hypot() > 0.0 {
        Vec2::new(-along.y, along.x).normalize()
    } else {
        Vec2::new(0.0, 1.0)
    };
    let extent = |c: &[[f64; 2]]| {
        let (lo, hi) = c
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                let s = p[0] * n.x + p[1] * n.y;
                (lo.min(s), hi.max(s))
            });
        hi - lo
    };
    if b.width < extent(island) {
        return Ok(());
    }
    let gap = extent(wall);
    if b.width < gap {
        return Ok(());
    }
    Err(Error::invalid(
        "bridge",
        format!(
            "a bridge {} mm wide is wider than the gap it must cross at ({:.1}, {:.1}) mm: \
             the cut-out there is {gap:.2} mm across, so the bridge would cover it whole; \
             give a bridge narrower than {gap:.2} mm",
            b.width, b.from.x, b.from.y
        ),
    ))
}

/// A place where a bridge could cross the cut: from `from` on contour
/// `a`, straight across the cut, to `to` on contour `b`, `span` mm away.
#[derive(Debug, Clone, Copy)]
struct Crossing {
    from: Point,
    to: Point,
    a: usize,
    b: usize,
    span: f64,
    /// Whether the contour runs straight here (turns by less than 20°
    /// from one sample to the next).
    straight: bool,
}

/// The bridges of one cut-out whose contours are `shape` (the wall first,
/// then the islands' outlines), as (from, to, contour from, contour to).
///
/// Crossings are looked for every [`SAMPLE_SPACING`] along every contour,
/// straight across the cut ([`Segments::first_hit`]). The contours are
/// the nodes of a graph, the wall standing for the paper outside; its
/// narrowest crossings that join two unjoined nodes are bridges (Kruskal's
/// spanning tree), so every island is held, through its neighbours if
/// need be, by the narrowest gaps. Then, walking along each contour, a
/// bridge once `every` mm have passed since the last and none lies
/// within ¾ of that, where the contour runs straight and a
/// crossing is no wider than [`MAX_SLIT`] — from an island to anything,
/// from the wall only back to the wall (a slit; the wall's crossings to
/// islands are the islands' own).
fn shape_bridges(shape: &[Contour], every: f64) -> Vec<(Point, Point, usize, usize)> {
    let islands = shape.len() - 1;
    if islands == 0 && (every <= 0.0 || super::shapes::perimeter(&shape[0]) < 2.0 * every) {
        return Vec::new();
    }
    let segments = Segments::new(shape);
    // Inside the cut is on the left of an anticlockwise (y up) wall, and
    // of its holes, which run the other way.
    let left = if super::shapes::area(&shape[0]) > 0.0 {
        1.0
    } else {
        -1.0
    };
    let crossings: Vec<Vec<Crossing>> = shape
        .iter()
        .enumerate()
        .map(|(a, contour)| {
            let points = resample(contour);
            let n = points.len();
            (0..n)
                .filter_map(|i| {
                    let (before, after) = (
                        points[i] - points[(i + n - 1) % n],
                        points[(i + 1) % n] - points[i],
                    );
                    let tangent = before + after;
                    if n < 3 || tangent.hypot() == 0.0 {
                        return None;
                    }
                    let turn = before.cross(after).atan2(before.dot(after)).abs();
                    let inward = Vec2::new(-tangent.y, tangent.x).normalize() * left;
                    let (to, b, span) = segments.first_hit(points[i], inward)?;
                    (b != a || a == 0).then_some(Crossing {
                        from: points[i],
                        to,
                        a,
                        b,
                        span,
                        straight: turn < 20f64.to_radians(),
                    })
                })
                .collect()
        })
        .collect();
    let mut chosen: Vec<Crossing> = Vec::new();
    if islands > 0 {
        let mut order: Vec<&Crossing> = crossings.iter().flatten().filter(|c| c.a != c.b).collect();
        order.sort_by(|x, y| x.span.total_cmp(&y.span));
        let mut joined = UnionFind::new(shape.len());
        for c in order {
            if joined.join(c.a, c.b) {
                chosen.push(*c);
            }
        }
    }
    if every > 0.0 {
        for (a, along) in crossings.iter().enumerate() {
            let mut since = 0.0;
            let mut last: Option<Point> = None;
            for c in along {
                since += last.map_or(0.0, |p| p.distance(c.from));
                last = Some(c.from);
                let wanted = c.straight && c.span <= MAX_SLIT && (a > 0 || c.b == 0);
                if since < every || !wanted {
                    continue;
                }
                let near = |q: Point| q.distance(c.from) < 0.75 * every;
                if chosen.iter().any(|b| near(b.from) || near(b.to)) {
                    continue;
                }
                chosen.push(*c);
                since = 0.0;
            }
        }
    }
    chosen
        .into_iter()
        .map(|c| (c.from, c.to, c.a, c.b))
        .collect()
}

/// Union–find over the contours of a cut-out.
struct UnionFind(Vec<usize>);

impl UnionFind {
    fn new(n: usize) -> UnionFind {
        UnionFind((0..n).collect())
    }

    fn root(&mut self, mut i: usize) -> usize {
        while self.0[i] != i {
            self.0[i] = self.0[self.0[i]];
            i = self.0[i];
        }
        i
    }

    /// Joins the sets of `a` and `b`; whether they were apart.
    fn join(&mut self, a: usize, b: usize) -> bool {
        let (ra, rb) = (self.root(a), self.root(b));
        self.0[ra.max(rb)] = ra.min(rb);
        ra != rb
    }
}

/// The sides of a cut-out's contours in a grid of square cells, for rays
/// across the cut.
struct Segments {
    /// (start, end, contour) of every side.
    sides: Vec<(Point, Point, usize)>,
    origin: Point,
    columns: usize,
    rows: usize,
    /// Sides by cell, row by row.
    cells: Vec<Vec<u32>>,
}

/// The cell size of [`Segments`], mm.
const CELL: f64 = 1.0;

/// The farthest a crossing reaches, mm: a cut wider than this round an
/// island is a window, and the island is reported loose.
const REACH: f64 = 10.0;

impl Segments {
    fn new(shape: &[Contour]) -> Segments {
        let mut sides = Vec::new();
        for (k, c) in shape.iter().enumerate() {
            for i in 0..c.len() {
                let (a, b) = (c[i], c[(i + 1) % c.len()]);
                sides.push((Point::new(a[0], a[1]), Point::new(b[0], b[1]), k));
            }
        }
        let bounds = super::shapes::bounds(&shape[0]);
        let origin = Point::new(bounds.x0, bounds.y0);
        let columns = (bounds.width() / CELL).floor() as usize + 1;
        let rows = (bounds.height() / CELL).floor() as usize + 1;
        let mut cells = vec![Vec::new(); columns * rows];
        for (i, &(a, b, _)) in sides.iter().enumerate() {
            let (c0, r0) = Self::cell(origin, Point::new(a.x.min(b.x), a.y.min(b.y)));
            let (c1, r1) = Self::cell(origin, Point::new(a.x.max(b.x), a.y.max(b.y)));
            for r in r0..=r1.min(rows - 1) {
                for c in c0..=c1.min(columns - 1) {
                    cells[r * columns + c].push(i as u32);
                }
            }
        }
        Segments {
            sides,
            origin,
            columns,
            rows,
            cells,
        }
    }

    fn cell(origin: Point, p: Point) -> (usize, usize) {
        (
            ((p.x - origin.x) / CELL).floor().max(0.0) as usize,
            ((p.y - origin.y) / CELL).floor().max(0.0) as usize,
        )
    }

    /// Where the ray from `p` along the unit vector `d` first meets a
    /// side (beyond a hair's breadth), within [`MAX_SLIT`] and failing
    /// that within [`REACH`]: the point, the side's contour and the
    /// distance.
    fn first_hit(&self, p: Point, d: Vec2) -> Option<(Point, usize, f64)> {
        [MAX_SLIT, REACH]
            .into_iter()
            .find_map(|reach| self.hit_within(p, d, reach))
    }

    fn hit_within(&self, p: Point, d: Vec2, reach: f64) -> Option<(Point, usize, f64)> {
        let end = p + d * reach;
        let (c0, r0) = Self::cell(self.origin, Point::new(p.x.min(end.x), p.y.min(end.y)));
        let (c1, r1) = Self::cell(self.origin, Point::new(p.x.max(end.x), p.y.max(end.y)));
        let mut best: Option<(f64, usize)> = None;
        for r in r0..=r1.min(self.rows - 1) {
            for c in c0..=c1.min(self.columns - 1) {
                for &i in &self.cells[r * self.columns + c] {
                    let (a, b, k) = self.sides[i as usize];
                    let e = b - a;
                    let denom = d.cross(e);
                    if denom == 0.0 {
                        continue;
                    }
                    let w = a - p;
                    let t = w.cross(e) / denom;
                    let s = w.cross(d) / denom;
                    let better = best.is_none_or(|(bt, _)| t < bt);
                    if (0.0..=1.0).contains(&s) && t > 1e-3 && t <= reach && better {
                        best = Some((t, k));
                    }
                }
            }
        }
        best.map(|(t, k)| (p + d * t, k, t))
    }
}

/// Points along the closed polygon `contour`, about [`SAMPLE_SPACING`]
/// apart (long sides split).
fn resample(contour: &[[f64; 2]]) -> Vec<Point> {
    let mut out = Vec::new();
    let mut carry = 0.0;
    for i in 0..contour.len() {
        let (a, b) = (contour[i], contour[(i + 1) % contour.len()]);
        let (a, b) = (Point::new(a[0], a[1]), Point::new(b[0], b[1]));
        let length = a.distance(b);
        let mut s = carry;
        while s < length {
            out.push(a.lerp(b, s / length));
            s += SAMPLE_SPACING;
        }
        carry = s - length;
    }
    out
}

#[cfg(test)]
mod tests {
    use kurbo::{Circle, Rect, Shape as _};

    use super::super::shapes::{from_region, rect};
    use super::*;
    use crate::geom::region::FillRule;

    fn disc(r: f64) -> Vec<Shape> {
        let region = Region::new(
            Circle::new((50.0, 50.0), r).to_path(0.01),
            FillRule::NonZero,
        )
        .unwrap();
        from_region(&region, 0.01)
    }

    /// A ring 1 mm wide cut out round a disc island of radius 10.
    fn ring_cut() -> Vec<Shape> {
        overlay(&disc(11.0), &disc(10.0), OverlayRule::Difference)
    }

    #[test]
    fn a_disc_in_a_ring_is_an_island_held_across_the_ring() {
        let found = bridge(ring_cut(), 0.8, 0.0, 0.5, 0.01).unwrap();
        assert_eq!(found.islands.len(), 1);
        assert!((found.islands[0].across - 20.0).abs() < 0.1);
        assert_eq!(found.bridges.len(), 1);
        let b = found.bridges[0];
        assert!((b.span() - 1.0).abs() < 0.05, "{b:?}");
        assert_eq!(b.island, Some(0));
    }

    #[test]
    fn bridges_are_spread_along_long_outlines() {
        // The disc's outline is about 63 mm long. The ring's wall (69 mm)
        // is no slit: its crossings meet the island, and count as the
        // island's.
        let found = bridge(ring_cut(), 0.8, 20.0, 0.5, 0.01).unwrap();
        let held: Vec<&Bridge> = found
            .bridges
            .iter()
            .filter(|b| b.island.is_some())
            .collect();
        assert!((3..=4).contains(&held.len()), "{held:?}");
        for (i, a) in held.iter().enumerate() {
            for b in &held[i + 1..] {
                assert!(a.from.distance(b.from) > 9.9, "{a:?} {b:?}");
            }
        }
        // Without spacing, one.
        assert_eq!(
            bridge(ring_cut(), 0.8, 0.0, 0.5, 0.01)
                .unwrap()
                .bridges
                .len(),
            1
        );
    }

    #[test]
    fn a_bridge_as_wide_as_the_whole_gap_is_refused_with_the_place() {
        // A 3 mm disc in a 0.5 mm ring: the cut-out is 4 mm across.
        let small = overlay(&disc(2.0), &disc(1.5), OverlayRule::Difference);
        // Wider than the island, narrower than the cut: held.
        assert_eq!(
            bridge(small.clone(), 3.5, 0.0, 0.5, 0.01)
                .unwrap()
                .bridges
                .len(),
            1
        );
        let e = bridge(small, 4.5, 0.0, 0.5, 0.01).unwrap_err();
        let text = e.to_string();
        assert!(text.starts_with("bridge: "), "{text}");
        assert!(text.contains("wider than the gap"), "{text}");
        assert!(
            text.contains(" mm across, so the bridge would cover it"),
            "{text}"
        );
    }

    #[test]
    fn islands_narrower_than_the_blade_are_cut_away() {
        let speck = overlay(&disc(0.6), &disc(0.2), OverlayRule::Difference);
        let found = bridge(speck, 0.3, 0.0, 0.5, 0.01).unwrap();
        assert!(found.islands.is_empty() && found.bridges.is_empty());
        assert_eq!(found.specks.len(), 1);
        assert_eq!(found.holes[0].len(), 1, "the speck's hole is cut away");
    }

    #[test]
    fn a_short_slot_gets_no_bridges_and_a_long_one_one_every_spacing() {
        let slot = |length: f64| vec![rect(Rect::new(10.0, 10.0, 10.0 + length, 10.5))];
        let short = bridge(slot(30.0), 0.8, 40.0, 0.5, 0.01).unwrap();
        assert!(short.islands.is_empty() && short.bridges.is_empty());
        let long = bridge(slot(130.0), 0.8, 40.0, 0.5, 0.01).unwrap();
        assert!(long.islands.is_empty());
        assert!((3..=4).contains(&long.bridges.len()), "{:?}", long.bridges);
        for (i, b) in long.bridges.iter().enumerate() {
            assert_eq!(b.island, None);
            // Straight across the 0.5 mm slot.
            assert!((b.span() - 0.5).abs() < 1e-6, "{b:?}");
            assert!((b.from.x - b.to.x).abs() < 1e-6, "{b:?}");
            for c in &long.bridges[i + 1..] {
                assert!((b.from.x - c.from.x).abs() >= 30.0, "{b:?} {c:?}");
            }
        }
        // A window (a cut wider than a slit) gets none.
        let window = vec![rect(Rect::new(10.0, 10.0, 140.0, 40.0))];
        assert!(bridge(window, 0.8, 40.0, 0.5, 0.01)
            .unwrap()
            .bridges
            .is_empty());
    }

    #[test]
    fn a_web_holds_every_island_through_its_neighbours() {
        // A 5 × 5 lattice of 0.4 mm lines, 4 mm apart: 16 islands, most
        // far from the wall; a spanning tree holds them with 16 bridges,
        // each straight across one line.
        let mut bars = Vec::new();
        for k in 0..5 {
            let at = 10.0 + 4.0 * f64::from(k);
            bars.push(rect(Rect::new(at, 10.0, at + 0.4, 26.4)));
            bars.push(rect(Rect::new(10.0, at, 26.4, at + 0.4)));
        }
        let web = overlay(&bars, &[], OverlayRule::Union);
        let found = bridge(web, 0.8, 0.0, 0.5, 0.01).unwrap();
        assert_eq!(found.islands.len(), 16);
        assert_eq!(found.bridges.len(), 16, "{:?}", found.bridges);
        for b in &found.bridges {
            assert!((b.span() - 0.4).abs() < 1e-6, "{b:?}");
        }
        // The paper is one piece: the sheet minus the bridged cut.
        let paper = vec![rect(Rect::new(0.0, 0.0, 40.0, 40.0))];
        let sheet = overlay(&paper, &found.holes, OverlayRule::Difference);
        assert_eq!(sheet.len(), 1);
    }
}
