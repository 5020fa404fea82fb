//! Placement templates (docs/SPEC.md §2.1, the paper's 図8): where the elements
//! of a symmetric pattern go. Nothing is drawn here: each template returns
//! placed instances, an [`Affine`] that maps the element square
//! [`UNIT`] onto the page and the slot (a–d) saying which of the
//! pattern's elements goes there; the procedure fills the slots, wobbles
//! the elements and composes them into its region.
//!
//! The paper's figure is lost; the SPEC decides:
//! - **MR** ([`scatter`]): random scatter, little symmetry. Centres are a
//!   Poisson-disk set one element apart inside the region (holes stay
//!   empty), each element turned and scaled at random, slots a and b at
//!   random.
//! - **MT** ([`triangles`]): the triangular lattice, as the tiling by
//!   equilateral triangles: slot a points up, slot b (turned half a turn)
//!   down between them; an element of side 2 (`tr`) tiles the plane.
//! - **MS** ([`squares`]): the square lattice, slot a everywhere
//!   (translation symmetry).
//! - **MA** ([`rows`]): rows one step apart, every other row shifted by
//!   half a step, slots a and b alternating along each row.
//! - **MC** ([`rotational`]): `fold`-fold rotation about the centre: slot
//!   a at the centre, then rings one step apart, ring `k` holding a
//!   multiple of `fold` elements about one step apart, each turned to
//!   face outwards; odd rings slot b, even rings slot c.
//! - **ML** ([`plant`]): a plant branch: a curved main stem up the box,
//!   alternating leaves along it (slot a), side branches from every third
//!   node (and branches of those), with their own alternating leaves (slot
//!   b), and a leaf at every tip.
//!
//! Beyond the paper (its §5.6: patterns not mapped to the region's
//! shape), [`along_contours`] lays MT, MS and MA along the region's
//! outline instead of on a lattice: rows that bend with it.
//!
//! Lattices are anchored at a given centre (the region's box centre plus
//! the procedure's jitter, docs/SPEC.md §2.4) and cover the box: every instance
//! whose square meets the box is returned, so that clipping to the region
//! leaves no gap at its edge. `size` is the lattice step, and an instance
//! maps [`UNIT`] onto a square of side `size` (elements touch their
//! neighbours; multiply on the right by `Affine::scale(k)`, `k < 1`, to
//! leave gaps).

use std::collections::BTreeMap;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

use kurbo::{Affine, BezPath, Point, Rect, Shape as _, Vec2};

use super::element::UNIT;
use crate::error::{Error, Result};
use crate::geom::offset::offset;
use crate::geom::region::Region;
use crate::geom::sample::poisson_disk;
use crate::geom::{PathWalker, TOLERANCE};
use crate::rng::RandomStream;

/// The most instances one template places: a box holding more elements
/// than this is a mistake (an element size far too small for the region),
/// refused before any work.
pub(crate) const MAX_INSTANCES: usize = 100_000;

/// Accuracy (in units of the element size) of arc lengths along stems.
const STEM_ACCURACY: f64 = 1e-4;

/// Which element of a pattern goes where (the paper's a, b, c; no
/// template here needs its d).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) enum Slot {
    /// The pattern's first element.
    A,
    /// The second.
    B,
    /// The third.
    C,
}

/// One element of a pattern: where and which.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Placed {
    /// Maps the element square [`UNIT`] onto the page.
    pub(crate) at: Affine,
    /// Which of the pattern's elements.
    pub(crate) slot: Slot,
}

impl Placed {
    /// An element of side `size` centred at `centre`, turned by `angle`
    /// (radians, clockwise on the page, as kurbo turns with y down).
    fn new(centre: Point, size: f64, angle: f64, slot: Slot) -> Placed {
        Placed {
            at: Affine::translate(centre.to_vec2())
                * Affine::rotate(angle)
                * Affine::scale(size / 2.0),
            slot,
        }
    }

    /// Where the centre of [`UNIT`] lands.
    pub(crate) fn centre(&self) -> Point {
        self.at * Point::ORIGIN
    }

    /// The page box of the element's square.
    fn bounds(&self) -> Rect {
        self.at.transform_rect_bbox(UNIT)
    }
}

/// A plant branch (ML): its stems and leaves.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Plant {
    /// The centre lines of the stems, main stem first, each from its base
    /// to its tip (one cubic each).
    pub(crate) stems: Vec<BezPath>,
    /// The leaves: each maps the leaf `le` (tip up, base at (0, 1)) so
    /// that its base lies on a stem; slot a on the main stem, b on side
    /// branches.
    pub(crate) leaves: Vec<Placed>,
}

/// Checks a template's box and element size, and that the box holds at
/// most [`MAX_INSTANCES`] cells.
fn check(bounds: Rect, size: f64) -> Result<()> {
    if !(size.is_finite() && size > 0.0) {
        return Err(Error::invalid(
            "placement.size",
            format!("must be a finite number of mm > 0, got {size}"),
        ));
    }
    let b = bounds.abs();
    if ![b.x0, b.y0, b.x1, b.y1].iter().all(|v| v.is_finite()) || b.area() <= 0.0 {
        return Err(Error::invalid(
            "placement.bounds",
            format!("must be finite with a positive area, got {bounds:?}"),
        ));
    }
    let cells = (b.width() / size + 2.0) * (b.height() / size + 2.0);
    if cells > MAX_INSTANCES as f64 {
        return Err(Error::invalid(
            "placement.size",
            format!(
                "{size} mm elements over a {:.1} × {:.1} mm box would be more than \
                 {MAX_INSTANCES} elements; use larger elements",
                b.width(),
                b.height()
            ),
        ));
    }
    Ok(())
}

/// The lattice indices `k` whose positions `origin + k·step` may reach
/// from `lo` to `hi` (one more each way; callers keep what meets the box).
fn indices(lo: f64, hi: f64, origin: f64, step: f64) -> std::ops::RangeInclusive<i64> {
    let a = ((lo - origin) / step).floor() as i64 - 1;
    let b = ((hi - origin) / step).ceil() as i64 + 1;
    a..=b
}

/// The instances whose square meets `bounds`.
fn meeting(bounds: Rect, all: impl Iterator<Item = Placed>) -> Vec<Placed> {
    all.filter(|p| p.bounds().overlaps(bounds)).collect()
}

/// MR: elements of side `size`, scaled by 0.6–1 and turned at random,
/// centred on a Poisson-disk set of points `size` apart inside `region`,
/// slots a and b at random.
///
/// # Errors
/// As the lattices ([`squares`]) for the region's box and `size`.
pub(crate) fn scatter(region: &Region, size: f64, rng: &mut RandomStream) -> Result<Vec<Placed>> {
    if region.is_empty() {
        return Ok(Vec::new());
    }
    check(region.bounds(), size)?;
    // The check above bounds the count; the sampler's own estimate (for
    // the densest packing) may be a little higher.
    let centres = poisson_disk(region, &|_| size, size..=size, rng, 2 * MAX_INSTANCES)?;
    Ok(centres
        .into_iter()
        .map(|c| {
            let scale = rng.range(0.6, 1.0);
            let angle = rng.range(0.0, TAU);
            let slot = if rng.below(2) == 0 { Slot::A } else { Slot::B };
            Placed::new(c, size * scale, angle, slot)
        })
        .collect())
}

/// MT: the tiling by equilateral triangles of side `size`, one pointing
/// up (slot a) centred at `centre`, rows `size·√3/2` apart.
///
/// # Errors
/// When `size` is not a finite positive number, `bounds` not finite with
/// a positive area, or the box would hold more than [`MAX_INSTANCES`].
pub(crate) fn triangles(bounds: Rect, centre: Point, size: f64) -> Result<Vec<Placed>> {
    check(bounds, size)?;
    let h = size * 3f64.sqrt() / 2.0;
    let rows = indices(bounds.y0, bounds.y1, centre.y, h);
    let all = rows.flat_map(move |j| {
        // Each row is shifted by half a side from the one above.
        let shift = centre.x + j as f64 * size / 2.0;
        indices(bounds.x0, bounds.x1, shift, size).flat_map(move |i| {
            let up = Point::new(shift + i as f64 * size, centre.y + j as f64 * h);
            [
                Placed::new(up, size, 0.0, Slot::A),
                Placed::new(up + Vec2::new(size / 2.0, 0.0), size, PI, Slot::B),
            ]
        })
    });
    Ok(meeting(bounds, all))
}

/// MS: the square lattice of step `size` through `centre`, slot a.
///
/// # Errors
/// As [`triangles`].
pub(crate) fn squares(bounds: Rect, centre: Point, size: f64) -> Result<Vec<Placed>> {
    check(bounds, size)?;
    let all = indices(bounds.y0, bounds.y1, centre.y, size).flat_map(move |j| {
        indices(bounds.x0, bounds.x1, centre.x, size).map(move |i| {
            let c = centre + Vec2::new(i as f64 * size, j as f64 * size);
            Placed::new(c, size, 0.0, Slot::A)
        })
    });
    Ok(meeting(bounds, all))
}

/// MA: rows `size` apart through `centre`, odd rows shifted by half a
/// step, slots a and b alternating along each row (a at `centre`).
///
/// # Errors
/// As [`triangles`].
pub(crate) fn rows(bounds: Rect, centre: Point, size: f64) -> Result<Vec<Placed>> {
    check(bounds, size)?;
    let all = indices(bounds.y0, bounds.y1, centre.y, size).flat_map(move |j| {
        let shift = centre.x + j.rem_euclid(2) as f64 * size / 2.0;
        indices(bounds.x0, bounds.x1, shift, size).map(move |i| {
            let c = Point::new(shift + i as f64 * size, centre.y + j as f64 * size);
            let slot = if i.rem_euclid(2) == 0 {
                Slot::A
            } else {
                Slot::B
            };
            Placed::new(c, size, 0.0, slot)
        })
    });
    Ok(meeting(bounds, all))
}

/// The most rotational symmetry [`rotational`] accepts.
pub(crate) const MAX_FOLD: usize = 64;

/// MC: `fold`-fold rotation about `centre`: slot a at the centre, then
/// rings `size` apart; ring `k` holds `fold·m` elements (`m` the whole
/// number that spaces them about `size` apart, at least 1), the first
/// straight above the centre, each turned so that its top faces outwards;
/// odd rings slot b, even ones slot c. Rings continue until they clear the
/// box.
///
/// # Errors
/// As [`triangles`], and when `fold` is not between 1 and [`MAX_FOLD`].
pub(crate) fn rotational(
    bounds: Rect,
    centre: Point,
    size: f64,
    fold: usize,
) -> Result<Vec<Placed>> {
    check(bounds, size)?;
    if !(1..=MAX_FOLD).contains(&fold) {
        return Err(Error::invalid(
            "placement.fold",
            format!("must be between 1 and {MAX_FOLD}, got {fold}"),
        ));
    }
    // The farthest corner of the box from the centre, and one element more.
    let reach = [
        Point::new(bounds.x0, bounds.y0),
        Point::new(bounds.x1, bounds.y0),
        Point::new(bounds.x0, bounds.y1),
        Point::new(bounds.x1, bounds.y1),
    ]
    .iter()
    .map(|p| p.distance(centre))
    .fold(0.0, f64::max)
        + size;
    let rings = (reach / size).ceil() as usize;
    let mut all = vec![Placed::new(centre, size, 0.0, Slot::A)];
    for k in 1..=rings {
        let r = k as f64 * size;
        let m = ((TAU * k as f64) / fold as f64).round().max(1.0) as usize;
        let count = fold * m;
        let slot = if k % 2 == 1 { Slot::B } else { Slot::C };
        for e in 0..count {
            // Polar angle on the page (y down), from straight above.
            let theta = -FRAC_PI_2 + TAU * e as f64 / count as f64;
            let c = centre + Vec2::new(r * theta.cos(), r * theta.sin());
            all.push(Placed::new(c, size, theta + FRAC_PI_2, slot));
        }
    }
    Ok(meeting(bounds, all.into_iter()))
}

/// ML: a branch growing up `bounds` from the middle of its bottom side,
/// with leaves about `size` long (shrinking towards the tips), alternating
/// sides along each stem; every third node of a stem starts a side branch
/// instead of a leaf, down to `branching` levels below the main stem (0:
/// the paper's single stem). Random: the stems' sway, the leaves' angles
/// (35°–55° off the stem) and the branches'.
///
/// # Errors
/// As [`triangles`].
pub(crate) fn plant(
    bounds: Rect,
    size: f64,
    branching: u32,
    rng: &mut RandomStream,
) -> Result<Plant> {
    check(bounds, size)?;
    let b = bounds.abs();
    let base = Point::new(b.center().x, b.y1);
    let length = 0.92 * b.height();
    let mut plant = Plant {
        stems: Vec::new(),
        leaves: Vec::new(),
    };
    let stem = Stem {
        base,
        dir: Vec2::new(0.0, -1.0),
        length,
        size,
    };
    grow(&mut plant, stem, 0, branching, rng);
    Ok(plant)
}

/// One stem of a plant: where it starts, its unit direction, its length
/// and the size of its leaves.
struct Stem {
    base: Point,
    dir: Vec2,
    length: f64,
    size: f64,
}

/// Grows one stem `depth` levels below the main stem, with its leaves and
/// (above `deepest`) its side branches.
fn grow(
    plant: &mut Plant,
    Stem {
        base,
        dir,
        length,
        size,
    }: Stem,
    depth: u32,
    deepest: u32,
    rng: &mut RandomStream,
) {
    // One cubic whose inner control points sway sideways.
    let side = Vec2::new(-dir.y, dir.x);
    let tip = base + dir * length;
    let sway = |rng: &mut RandomStream| side * rng.symmetric(0.22 * length);
    let mut stem = BezPath::new();
    stem.move_to(base);
    stem.curve_to(
        base + dir * (length / 3.0) + sway(rng),
        base + dir * (2.0 * length / 3.0) + sway(rng),
        tip,
    );
    let walker = PathWalker::new(&stem, STEM_ACCURACY * size);
    let total = walker.length();
    plant.stems.push(stem);
    let slot = if depth == 0 { Slot::A } else { Slot::B };
    // Nodes a leaf's length apart, starting a little above the base.
    let spacing = 0.8 * size;
    let nodes = ((total - 0.5 * spacing) / spacing).floor().max(0.0) as usize;
    let mut left = rng.below(2) == 0;
    for n in 0..nodes {
        let s = 0.5 * spacing + n as f64 * spacing;
        let p = walker.point_at(s);
        let t = walker.tangent_at(s);
        // Leaves shrink to 60 % towards the tip.
        let leaf = size * (1.0 - 0.4 * s / total);
        let turn = rng.range(35f64.to_radians(), 55f64.to_radians());
        let out = rotate(t, if left { -turn } else { turn });
        if depth < deepest && n % 3 == 2 {
            let branch = Stem {
                base: p,
                dir: out,
                length: 0.6 * (total - s),
                size: leaf * 0.8,
            };
            if branch.length > spacing {
                grow(plant, branch, depth + 1, deepest, rng);
            }
        } else {
            plant.leaves.push(leaf_at(p, out, leaf, slot));
        }
        left = !left;
    }
    plant
        .leaves
        .push(leaf_at(tip, walker.tangent_at(total), size * 0.6, slot));
}

/// The unit vector `v` turned by `angle` (clockwise on the page for a
/// positive angle, as kurbo turns with y down).
fn rotate(v: Vec2, angle: f64) -> Vec2 {
    let (s, c) = angle.sin_cos();
    Vec2::new(v.x * c - v.y * s, v.x * s + v.y * c)
}

/// The leaf `le` (tip up, base at (0, 1) in [`UNIT`]) `length` long with
/// its base at `base`, pointing along the unit vector `dir`.
fn leaf_at(base: Point, dir: Vec2, length: f64, slot: Slot) -> Placed {
    // `le` points along −y; turn that onto `dir`.
    let angle = dir.x.atan2(-dir.y);
    Placed {
        at: Affine::translate(base.to_vec2())
            * Affine::rotate(angle)
            * Affine::scale(length / 2.0)
            * Affine::translate((0.0, -1.0)),
        slot,
    }
}

/// Which lattice [`along_contours`] bends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Lattice {
    /// MT: triangles half a step apart, slot a pointing out towards the
    /// outline and slot b, turned half a turn, pointing in.
    Triangles,
    /// MS: slot a a step apart.
    Squares,
    /// MA: slots a and b alternating a step apart.
    Rows,
}

/// Rows that follow the region's shape: rings inset from its outline by
/// half a step, one and a half, … (around its holes too, and splitting
/// where it narrows), each holding elements of side `size` evenly along
/// it, turned so that their tops face the outline, in the order
/// `lattice` says. A ring too short for three elements holds one, at its
/// middle. Where rings from two edges meet (across a narrow part, or
/// between the outline and a hole) an element closer than 0.8 `size` to
/// one of another ring laid before it is left out, so rows never pile up.
///
/// # Errors
/// As [`triangles`]; from the offsetting on degenerate geometry.
pub(crate) fn along_contours(region: &Region, size: f64, lattice: Lattice) -> Result<Vec<Placed>> {
    check(region.bounds(), size)?;
    let spacing = match lattice {
        Lattice::Triangles => size / 2.0,
        Lattice::Squares | Lattice::Rows => size,
    };
    let mut out = Vec::new();
    let mut laid = Laid::new(0.8 * size);
    let mut row = 0;
    for k in 0.. {
        let ring = offset(region, -(k as f64 + 0.5) * size, TOLERANCE)?;
        if ring.is_empty() {
            break;
        }
        for contour in ring.polygons(TOLERANCE) {
            row += 1;
            let mut keep = |p: Placed, out: &mut Vec<Placed>| {
                if laid.free(p.centre(), row) {
                    out.push(p);
                }
            };
            let mut path = BezPath::new();
            path.move_to(contour[0]);
            for p in &contour[1..] {
                path.line_to(*p);
            }
            path.close_path();
            let walker = PathWalker::new(&path, TOLERANCE);
            let n = (walker.length() / spacing).floor() as usize;
            if n < 3 {
                let middle = path.bounding_box().center();
                keep(Placed::new(middle, size, 0.0, Slot::A), &mut out);
                continue;
            }
            let every = walker.length() / n as f64;
            for i in 0..n {
                let s = (i as f64 + 0.5) * every;
                let at = walker.point_at(s);
                let normal = walker.tangent_at(s).turn_90();
                // Outwards is whichever side leaves the ring (a contour's
                // winding says nothing once offset and split).
                let outward = if ring.contains(at + normal * (0.05 * size)) {
                    -normal
                } else {
                    normal
                };
                // The element's top (−y in its square) turned onto it.
                let up = outward.atan2() + FRAC_PI_2;
                let (slot, turn) = match (lattice, i % 2) {
                    (Lattice::Triangles, 1) => (Slot::B, PI),
                    (Lattice::Rows, 1) => (Slot::B, 0.0),
                    _ => (Slot::A, 0.0),
                };
                keep(Placed::new(at, size, up + turn, slot), &mut out);
            }
        }
        if out.len() > MAX_INSTANCES {
            return Err(Error::invalid(
                "placement.size",
                format!("{size} mm lays more than {MAX_INSTANCES} elements along the outline"),
            ));
        }
    }
    Ok(out)
}

/// The centres laid so far, on a grid of cells `apart` wide, with the row
/// each belongs to.
struct Laid {
    apart: f64,
    cells: BTreeMap<(i64, i64), Vec<(Point, usize)>>,
}

impl Laid {
    fn new(apart: f64) -> Laid {
        Laid {
            apart,
            cells: BTreeMap::new(),
        }
    }

    fn cell(&self, p: Point) -> (i64, i64) {
        (
            (p.x / self.apart).floor() as i64,
            (p.y / self.apart).floor() as i64,
        )
    }

    /// Whether `p` of `row` is at least `apart` from every centre of
    /// another row; if so it is laid.
    fn free(&mut self, p: Point, row: usize) -> bool {
        let (i, j) = self.cell(p);
        let crowded = (i - 1..=i + 1)
            .flat_map(|a| (j - 1..=j + 1).map(move |b| (a, b)))
            .filter_map(|c| self.cells.get(&c))
            .flatten()
            .any(|&(q, r)| r != row && q.distance(p) < self.apart);
        if !crowded {
            self.cells.entry((i, j)).or_default().push((p, row));
        }
        !crowded
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::region::FillRule;
    use crate::rng::Seed;
    use kurbo::{ParamCurve, ParamCurveDeriv, ParamCurveNearest};

    fn boxed() -> Rect {
        Rect::new(0.0, 0.0, 120.0, 90.0)
    }

    /// Whether some instance of `set` has its centre at `p` with `slot`.
    fn has(set: &[Placed], p: Point, slot: Slot) -> bool {
        set.iter()
            .any(|q| q.slot == slot && q.centre().distance(p) < 1e-9)
    }

    /// Instances well inside the box, whose images under a symmetry of the
    /// lattice must be instances too.
    fn interior(set: &[Placed], margin: f64) -> Vec<Placed> {
        let inner = boxed().inset(-margin);
        set.iter()
            .copied()
            .filter(|p| inner.contains(p.centre()))
            .collect()
    }

    #[test]
    fn rows_along_contours_follow_the_outline_and_face_it() {
        // A disc of radius 30 less a hole of radius 8: rings at 28, 24, …
        // around the outside, and outward from the hole's edge, at 10, 14.
        let c = Point::new(50.0, 40.0);
        let disc =
            Region::new(kurbo::Circle::new(c, 30.0).to_path(1e-4), FillRule::NonZero).unwrap();
        let hole =
            Region::new(kurbo::Circle::new(c, 8.0).to_path(1e-4), FillRule::NonZero).unwrap();
        let ring = disc.difference(&hole);
        for lattice in [Lattice::Triangles, Lattice::Squares, Lattice::Rows] {
            let set = along_contours(&ring, 4.0, lattice).unwrap();
            assert!(set.len() > 60, "{lattice:?}: {}", set.len());
            let (mut a, mut b) = (0usize, 0usize);
            for p in &set {
                let r = p.centre().distance(c);
                // Half a step, one and a half, … from the outline or the
                // hole's edge.
                let from_edge = (30.0 - r).min(r - 8.0);
                let k = (from_edge / 4.0 - 0.5).round();
                assert!(
                    (from_edge - (k + 0.5) * 4.0).abs() < 0.05,
                    "{lattice:?}: {r} from the centre"
                );
                // Its top faces the nearer edge (slot b of triangles the
                // other way).
                let top = p.at * Point::new(0.0, -1.0) - p.centre();
                let radial = (p.centre() - c).normalize();
                let out = if 30.0 - r < r - 8.0 { 1.0 } else { -1.0 };
                let flip = if lattice == Lattice::Triangles && p.slot == Slot::B {
                    -1.0
                } else {
                    1.0
                };
                assert!(
                    top.normalize().dot(radial) * out * flip > 0.999,
                    "{lattice:?}: faces {top:?} at {:?}",
                    p.centre()
                );
                match p.slot {
                    Slot::A => a += 1,
                    _ => b += 1,
                }
            }
            match lattice {
                Lattice::Squares => assert_eq!(b, 0),
                _ => assert!(a.abs_diff(b) <= set.len() / 10, "{lattice:?}: {a} a, {b} b"),
            }
        }
    }

    #[test]
    fn squares_have_translation_symmetry_and_cover_the_box() {
        let c = Point::new(61.3, 44.2);
        let set = squares(boxed(), c, 10.0).unwrap();
        assert!(has(&set, c, Slot::A));
        for p in interior(&set, 15.0) {
            for d in [
                Vec2::new(10.0, 0.0),
                Vec2::new(0.0, 10.0),
                Vec2::new(-10.0, 0.0),
            ] {
                assert!(has(&set, p.centre() + d, Slot::A));
            }
        }
        // Every point of the box lies in some instance's square.
        for k in 0..200 {
            let q = Point::new((k * 37 % 120) as f64 + 0.5, (k * 53 % 90) as f64 + 0.5);
            assert!(set.iter().any(|p| p.bounds().contains(q)), "{q:?}");
        }
        // Nothing far outside.
        assert!(set.iter().all(|p| p.bounds().overlaps(boxed())));
    }

    #[test]
    fn triangles_tile_up_and_down() {
        let c = Point::new(60.0, 45.0);
        let s = 12.0;
        let h = s * 3f64.sqrt() / 2.0;
        let set = triangles(boxed(), c, s).unwrap();
        assert!(has(&set, c, Slot::A));
        assert!(has(&set, c + Vec2::new(s / 2.0, 0.0), Slot::B));
        for p in interior(&set, 20.0) {
            for d in [
                Vec2::new(s, 0.0),
                Vec2::new(s / 2.0, h),
                Vec2::new(-s / 2.0, h),
            ] {
                assert!(has(&set, p.centre() + d, p.slot));
            }
        }
        // Down triangles are up triangles turned half a turn.
        for p in &set {
            let top = p.at * Point::new(0.0, -1.0);
            assert_eq!(top.y < p.centre().y, p.slot == Slot::A);
        }
        // Triangles of side `s` tile: every point of the box lies in
        // exactly one (points chosen off the edges).
        let h2 = 3f64.sqrt() / 2.0;
        let unit_tri = [
            Point::new(0.0, -h2),
            Point::new(1.0, h2),
            Point::new(-1.0, h2),
        ];
        for k in 0..500 {
            let q = Point::new(
                (k as f64 * 0.618_034 * 120.0) % 120.0,
                (k as f64 * 0.414_214 * 90.0) % 90.0,
            );
            let holding = set
                .iter()
                .filter(|p| {
                    let v = unit_tri.map(|u| p.at * u);
                    let mut tri = BezPath::new();
                    tri.move_to(v[0]);
                    tri.line_to(v[1]);
                    tri.line_to(v[2]);
                    tri.close_path();
                    tri.winding(q) != 0
                })
                .count();
            assert_eq!(holding, 1, "{q:?}");
        }
    }

    #[test]
    fn rows_alternate_and_shift() {
        let c = Point::new(50.0, 40.0);
        let s = 8.0;
        let set = rows(boxed(), c, s).unwrap();
        for p in interior(&set, 15.0) {
            let other = if p.slot == Slot::A { Slot::B } else { Slot::A };
            // Along the row: the other slot one step away, the same two.
            assert!(has(&set, p.centre() + Vec2::new(s, 0.0), other));
            assert!(has(&set, p.centre() + Vec2::new(2.0 * s, 0.0), p.slot));
            // The next row is shifted by half a step.
            assert!(set
                .iter()
                .any(|q| q.centre().distance(p.centre() + Vec2::new(s / 2.0, s)) < 1e-9));
            assert!(!set
                .iter()
                .any(|q| q.centre().distance(p.centre() + Vec2::new(0.0, s)) < 1e-9));
        }
    }

    #[test]
    fn rotation_by_a_fold_maps_the_pattern_onto_itself() {
        let c = Point::new(60.0, 45.0);
        for fold in [1, 3, 5, 6, 8] {
            // A box centred on the centre, so that no ring is cut unevenly.
            let square = Rect::new(0.0, -15.0, 120.0, 105.0);
            let set = rotational(square, c, 9.0, fold).unwrap();
            let turn = Affine::rotate_about(TAU / fold as f64, c);
            // Only rings wholly inside the box are complete.
            // The centre element stands upright (the pattern is as
            // symmetric as it): only its place is checked.
            assert!(has(&set, c, Slot::A));
            let complete: Vec<&Placed> = set
                .iter()
                .filter(|p| (1.0..50.0).contains(&p.centre().distance(c)))
                .collect();
            assert!(complete.len() > 20);
            for p in complete {
                let image = turn * p.at;
                let found = set.iter().any(|q| {
                    q.slot == p.slot
                        && (image * Point::ORIGIN).distance(q.centre()) < 1e-9
                        && (image * Point::new(0.0, -1.0)).distance(q.at * Point::new(0.0, -1.0))
                            < 1e-9
                });
                assert!(found, "fold {fold}: {:?}", p.centre());
            }
        }
        assert!(rotational(boxed(), c, 9.0, 0).is_err());
        assert!(rotational(boxed(), c, 9.0, MAX_FOLD + 1).is_err());
    }

    #[test]
    fn scatter_stays_in_the_region_and_apart() {
        let ring = Region::from_rect(boxed())
            .unwrap()
            .difference(&Region::from_rect(Rect::new(40.0, 30.0, 80.0, 60.0)).unwrap());
        let set = scatter(&ring, 10.0, &mut Seed(5).stream()).unwrap();
        assert!(set.len() > 40);
        for (i, p) in set.iter().enumerate() {
            assert!(ring.contains(p.centre()));
            for q in &set[..i] {
                assert!(p.centre().distance(q.centre()) >= 10.0 - 1e-9);
            }
        }
        assert!(set.iter().any(|p| p.slot == Slot::A) && set.iter().any(|p| p.slot == Slot::B));
        assert_eq!(set, scatter(&ring, 10.0, &mut Seed(5).stream()).unwrap());
        assert!(scatter(&Region::empty(), 10.0, &mut Seed(5).stream())
            .unwrap()
            .is_empty());
    }

    #[test]
    fn plants_alternate_their_leaves_along_their_stems() {
        let bounds = Rect::new(0.0, 0.0, 60.0, 100.0);
        let plant = plant(bounds, 9.0, 2, &mut Seed(2).stream()).unwrap();
        assert!(plant.stems.len() >= 3, "{}", plant.stems.len());
        assert!(plant.leaves.len() > 15);
        // Each stem is one cubic.
        let cubic = |k: usize| plant.stems[k].segments().next().unwrap().to_cubic();
        // Where `p` lies on a stem: which one, and at what parameter.
        let on_stem = |p: Point| -> Option<(usize, f64)> {
            (0..plant.stems.len()).find_map(|k| {
                let n = cubic(k).nearest(p, 1e-12);
                (n.distance_sq < 1e-12).then_some((k, n.t))
            })
        };
        // Along each stem, the nodes (leaves and branches, not the tip
        // leaf) turn to alternate sides.
        let mut nodes: Vec<Vec<(f64, bool)>> = vec![Vec::new(); plant.stems.len()];
        let side = |k: usize, t: f64, towards: Vec2| {
            cubic(k).deriv().eval(t).to_vec2().cross(towards) > 0.0
        };
        for leaf in &plant.leaves {
            let base = leaf.at * Point::new(0.0, 1.0);
            let tip = leaf.at * Point::new(0.0, -1.0);
            let Some((k, t)) = on_stem(base) else {
                panic!("leaf base {base:?} is on no stem");
            };
            if t < 1.0 - 1e-9 {
                nodes[k].push((t, side(k, t, tip - base)));
            }
        }
        for j in 1..plant.stems.len() {
            let branch = cubic(j);
            let (parent, t) = on_stem(branch.p0).expect("a branch starts on a stem");
            assert!(parent < j);
            nodes[parent].push((t, side(parent, t, branch.p1 - branch.p0)));
        }
        assert!(nodes[0].len() >= 8, "{:?}", nodes[0]);
        for n in &mut nodes {
            n.sort_by(|a, b| a.0.total_cmp(&b.0));
            assert!(n.windows(2).all(|w| w[0].1 != w[1].1), "{n:?}");
        }
        assert!(plant
            .stems
            .iter()
            .all(|s| s.bounding_box().overlaps(bounds)));
        let again = super::plant(bounds, 9.0, 2, &mut Seed(2).stream()).unwrap();
        assert_eq!(plant, again);
    }

    #[test]
    fn branching_sets_how_deep_plants_branch() {
        let bounds = Rect::new(0.0, 0.0, 60.0, 140.0);
        // How deep each stem starts: 0 for the main one, one more for a
        // branch of it.
        let depths = |branching: u32| -> Vec<u32> {
            let plant = plant(bounds, 9.0, branching, &mut Seed(4).stream()).unwrap();
            let mut depth: Vec<u32> = vec![0];
            for k in 1..plant.stems.len() {
                let start = plant.stems[k].segments().next().unwrap().start();
                let parent = (0..k)
                    .find(|&j| {
                        let c = plant.stems[j].segments().next().unwrap().to_cubic();
                        c.nearest(start, 1e-12).distance_sq < 1e-12
                    })
                    .expect("a branch starts on an earlier stem");
                depth.push(depth[parent] + 1);
            }
            depth
        };
        // The paper's plant: one stem, a leaf at every node.
        assert_eq!(depths(0), vec![0]);
        let single = plant(bounds, 9.0, 0, &mut Seed(4).stream()).unwrap();
        assert!(single.leaves.len() >= 12, "{}", single.leaves.len());
        for branching in 1..=3 {
            let d = depths(branching);
            assert_eq!(d.iter().max(), Some(&branching), "{d:?}");
        }
        assert!(depths(2).len() > depths(1).len());
    }

    #[test]
    fn bad_sizes_and_boxes_are_errors() {
        let c = Point::new(0.0, 0.0);
        for s in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(squares(boxed(), c, s).is_err());
        }
        assert!(squares(Rect::new(0.0, 0.0, 0.0, 5.0), c, 1.0).is_err());
        assert!(squares(Rect::new(0.0, 0.0, f64::NAN, 5.0), c, 1.0).is_err());
        let e = squares(boxed(), c, 0.01).unwrap_err().to_string();
        assert!(e.contains("more than 100000 elements"), "{e}");
        assert!(plant(boxed(), -2.0, 2, &mut Seed(1).stream()).is_err());
    }
}
