//! Points spread inside a region: uniformly at random ([`uniform`]), one
//! near each node of a square grid ([`jittered_grid`]), and as a
//! Poisson-disk ("blue noise") set whose spacing may vary over the page
//! ([`poisson_disk`]) — the seeds of stippling, scattered motifs and
//! cell-like fills — and points given by hand kept where they fall inside
//! ([`inside`]).
//!
//! Every function keeps a point only where [`Region::contains`] says it is
//! inside, so holes stay empty (points on the boundary may go either way).
//! That test costs time in proportion to the region's segments, so it is
//! asked through a grid of tiles that answers at once away from the
//! boundary and looks only at the nearby segments close to it, with the
//! same answers. All lengths are millimetres. The randomness is the
//! caller's [`RandomStream`], drawn in a fixed order and without the
//! platform's `sin` and `cos`, so one seed gives the same points, bit for
//! bit, on every platform.
//!
//! Poisson-disk sampling is Bridson's algorithm ("Fast Poisson disk
//! sampling in arbitrary dimensions", 2007) on a background grid, written
//! here rather than taken from a crate (`fast_poisson` measured
//! superlinear; see DESIGN.md), with a radius that may vary from point to
//! point, and a seed in every connected part of the region. Its work is
//! linear in the region's area over the square of the smallest radius; its
//! memory is linear in the points plus a small index over the region's
//! bounds.
//!
//! ```
//! use kurbo::Rect;
//! use moyo::geom::{region::Region, sample};
//! use moyo::Seed;
//!
//! let square = Region::from_rect(Rect::new(0.0, 0.0, 50.0, 50.0))?;
//! let mut rng = Seed(7).derive("stipple").stream();
//! // Denser on the left: 1 mm apart at x = 0, 3 mm apart at x = 50.
//! let radius = |p: kurbo::Point| 1.0 + p.x / 25.0;
//! let points = sample::poisson_disk(&square, &radius, 1.0..=3.0, &mut rng, 10_000)?;
//! assert!(points.iter().all(|p| square.contains(*p)));
//! # Ok::<(), moyo::Error>(())
//! ```

use std::ops::RangeInclusive;

use kurbo::{BezPath, ParamCurve, Point, Rect, Shape, Vec2};

use super::region::Region;
use crate::error::{Error, Result};
use crate::rng::RandomStream;

/// The smallest radius [`poisson_disk`] accepts, in mm: a hundredth of a
/// millimetre, far below what a pen can show.
pub const MIN_RADIUS: f64 = 0.01;

/// The largest radius [`poisson_disk`] accepts is at most this many times
/// the smallest (a density ratio of 10,000 to 1).
pub const MAX_RADIUS_RATIO: f64 = 100.0;

/// The most points [`uniform`] makes, and the most grid nodes
/// [`jittered_grid`] visits, in one call.
pub const MAX_POINTS: usize = 10_000_000;

/// [`uniform`] refuses regions that fill less than this fraction of their
/// bounds: rejection sampling would need more than a thousand tries a
/// point.
const MIN_FILL: f64 = 1e-3;

/// Candidates tried around an active point before it is retired, as in
/// Bridson's paper.
const CANDIDATES: usize = 30;

/// Random tries for the seed of each connected part of the region.
const SEED_TRIES: usize = 1000;

/// The background grid is kept in square blocks of this many cells a side,
/// allocated where points are, so that a region with large bounds and a
/// small area (a thin ring, islands far apart) does not pay for its bounds.
const BLOCK: usize = 16;

/// A block of the background grid that holds no point yet.
const NONE: u32 = u32::MAX;

/// `count` points drawn uniformly at random inside `region`, in the order
/// drawn.
///
/// Rejection sampling in the region's bounds: about
/// `count × bounds area / area` tries, each a lookup in a grid of tiles
/// (and a winding number of the nearby segments for tries near the
/// boundary).
///
/// # Errors
/// [`Error::Invalid`] when `count` is above [`MAX_POINTS`] (field
/// `count`), or when `count` is not 0 and the region is empty or fills
/// less than 0.1 % of its bounds (field `region`; sample its parts, or
/// use [`poisson_disk`], which follows the region).
pub fn uniform(region: &Region, count: usize, rng: &mut RandomStream) -> Result<Vec<Point>> {
    if count > MAX_POINTS {
        return Err(Error::invalid(
            "count",
            format!("at most {MAX_POINTS} points can be drawn at once, got {count}"),
        ));
    }
    if count == 0 {
        return Ok(Vec::new());
    }
    if region.is_empty() {
        return Err(Error::invalid(
            "region",
            "the region is empty: no point can be drawn inside it",
        ));
    }
    let b = region.bounds();
    let fill = region.area() / b.area();
    if !fill.is_finite() || fill < MIN_FILL {
        return Err(Error::invalid(
            "region",
            format!(
                "the region's area, {:.4} mm², is {:.4} % of its bounds ({:.1} × {:.1} mm): \
                 uniform sampling by rejection would take more than {:.0} tries a point",
                region.area(),
                fill * 100.0,
                b.width(),
                b.height(),
                1.0 / MIN_FILL
            ),
        ));
    }
    // Four times the expected number of tries: reached only if the area
    // and the containment test disagree.
    let max_tries = (4.0 * count as f64 / fill) as u64 + 1000;
    let inside = Containment::new(region, count.clamp(4096, 1 << 20));
    let mut points = Vec::with_capacity(count);
    let mut tries = 0u64;
    while points.len() < count {
        if tries == max_tries {
            return Err(Error::invalid(
                "region",
                format!(
                    "only {} of {count} points fell inside the region in {max_tries} tries",
                    points.len()
                ),
            ));
        }
        tries += 1;
        let p = Point::new(rng.range(b.x0, b.x1), rng.range(b.y0, b.y1));
        if inside.contains(p) {
            points.push(p);
        }
    }
    Ok(points)
}

/// One point near each node of a square grid, kept where it falls inside
/// `region`, row by row (top to bottom, left to right).
///
/// The nodes are the whole multiples of `spacing` in page coordinates
/// (so regions side by side share one grid), and each is moved by up to
/// `jitter × spacing / 2` in x and in y, uniformly: `jitter` 0 keeps the
/// exact grid, 1 puts one point uniformly anywhere in each node's cell
/// (stratified sampling). About `area / spacing²` points; the cost is one
/// containment test (as in [`uniform`]) per node over the region's bounds.
///
/// # Errors
/// [`Error::Invalid`] when `spacing` is not a finite number above 0 or
/// would make more than [`MAX_POINTS`] nodes over the region's bounds
/// (field `spacing`), or when `jitter` is not between 0 and 1 (field
/// `jitter`).
pub fn jittered_grid(
    region: &Region,
    spacing: f64,
    jitter: f64,
    rng: &mut RandomStream,
) -> Result<Vec<Point>> {
    if !(spacing.is_finite() && spacing > 0.0) {
        return Err(Error::invalid(
            "spacing",
            format!("must be a finite number of mm above 0, got {spacing}"),
        ));
    }
    if !(0.0..=1.0).contains(&jitter) {
        return Err(Error::invalid(
            "jitter",
            format!("must be between 0 and 1, got {jitter}"),
        ));
    }
    if region.is_empty() {
        return Ok(Vec::new());
    }
    let b = region.bounds();
    // Nodes just outside the bounds may be jittered into the region.
    let reach = jitter * spacing / 2.0;
    let (i0, i1) = (
        ((b.x0 - reach) / spacing).floor(),
        ((b.x1 + reach) / spacing).ceil(),
    );
    let (j0, j1) = (
        ((b.y0 - reach) / spacing).floor(),
        ((b.y1 + reach) / spacing).ceil(),
    );
    let nodes = (i1 - i0 + 1.0) * (j1 - j0 + 1.0);
    if nodes > MAX_POINTS as f64 {
        return Err(Error::invalid(
            "spacing",
            format!(
                "a grid of spacing {spacing} mm over the region's bounds \
                 ({:.1} × {:.1} mm) would have {nodes:.0} nodes, more than {MAX_POINTS}",
                b.width(),
                b.height()
            ),
        ));
    }
    let inside = Containment::new(region, (nodes as usize).clamp(4096, 1 << 20));
    let (i0, i1, j0, j1) = (i0 as i64, i1 as i64, j0 as i64, j1 as i64);
    let mut points = Vec::new();
    for j in j0..=j1 {
        for i in i0..=i1 {
            let node = Point::new(i as f64 * spacing, j as f64 * spacing);
            let p = node + Vec2::new(rng.symmetric(reach), rng.symmetric(reach));
            if inside.contains(p) {
                points.push(p);
            }
        }
    }
    Ok(points)
}

/// A Poisson-disk set inside `region`: points at least `radius` apart,
/// added until Bridson's search finds no room for another, in the order
/// they were placed.
///
/// **Variable radius.** `radius(p)` is the spacing wanted at `p` (smaller
/// where the drawing should be dense), clamped to `range`; it is called
/// once for each candidate point, which may lie anywhere in the region's
/// bounds (and never when `range` holds a single value, which is then the
/// radius everywhere). A point is placed only if no point placed *before* it lies
/// closer than the radius at the new point: every point is at least its
/// own radius away from all earlier ones, so any two points are at least
/// the smaller of their two radii apart. (Asking for the larger would
/// make each test search as far as the largest radius.)
///
/// **Coverage.** Each connected part of the region ([`Region::components`])
/// gets its own seed, a random point inside it (up to a thousand tries, so
/// a part that fills less than about 0.5 % of its bounds may be missed),
/// and grows from it by Bridson's algorithm: 30 candidates in the
/// annulus between one and two radii around a random active point, which
/// is retired when none fits. Bridson's walk leaves no gap wider than
/// twice the local radius (in the tests, no point of the region is
/// farther than 1.3 radii from a sample), but it is not strictly maximal:
/// a few places could still take a point. Within one part, growth follows
/// the region through any neck it can step into; a neck much narrower
/// than the radius may stop it, and what lies beyond stays empty.
///
/// **Cost.** The background grid has cells of `range.start() / √2`; each
/// candidate looks at the cells within its radius (21 for a constant
/// radius, nearest first, stopping at the first point too close), and
/// only a candidate that fits is tested for containment. Each point costs
/// about 36 candidates. Linear in `area / range.start()²`, as is the
/// number of points for a constant radius: 600,000 points in about 1.1 s
/// on a shared 2-core build machine, whether the region is a square or
/// has hundreds of curved segments.
///
/// # Errors
/// - [`Error::Invalid`] (field `radius`) when `range.start()` is not a
///   finite number of at least [`MIN_RADIUS`], when `range.end()` is below
///   it, not finite or more than [`MAX_RADIUS_RATIO`] times it, or when
///   `radius` returns NaN (infinities are clamped).
/// - [`Error::Budget`] with `max_points` as the limit, before any sampling,
///   when the region could hold more than `max_points` points at the
///   smallest radius (hexagonal packing: `area × 2 / (√3 r²)`), or when its
///   bounds are so much larger than its area that the grid's index would
///   outgrow the budget; and, should the estimate be passed all the same
///   (thin shapes, where the boundary lets more points in), as soon as one
///   point more would be placed.
pub fn poisson_disk(
    region: &Region,
    radius: &dyn Fn(Point) -> f64,
    range: RangeInclusive<f64>,
    rng: &mut RandomStream,
    max_points: usize,
) -> Result<Vec<Point>> {
    let (r_min, r_max) = range.into_inner();
    if !(r_min.is_finite() && r_min >= MIN_RADIUS) {
        return Err(Error::invalid(
            "radius",
            format!("the smallest radius must be a finite number of at least {MIN_RADIUS} mm, got {r_min}"),
        ));
    }
    if !(r_max.is_finite() && r_max >= r_min && r_max <= r_min * MAX_RADIUS_RATIO) {
        return Err(Error::invalid(
            "radius",
            format!(
                "the largest radius must be between the smallest ({r_min} mm) and \
                 {MAX_RADIUS_RATIO} times it, got {r_max}"
            ),
        ));
    }
    if region.is_empty() {
        return Ok(Vec::new());
    }
    let area = region.area();
    let most = area * 2.0 / (3f64.sqrt() * r_min * r_min);
    if most > max_points as f64 {
        return Err(Error::Budget {
            limit: max_points,
            what: format!(
                "Poisson-disk sampling at a radius of {r_min} mm over {area:.1} mm² \
                 (room for {most:.0} points)"
            ),
        });
    }
    let mut sampler = Sampler::new(region, radius, r_min, r_max, max_points)?;
    for part in region.components() {
        sampler.seed(&part, rng)?;
    }
    Ok(sampler.points)
}

/// Directions in the table candidates are drawn from.
const DIRECTIONS: usize = 1024;

/// `DIRECTIONS + 1` unit vectors evenly around the circle, the first
/// repeated at the end, made by successive rotations: only `+` and `×`, so
/// the table is the same on every platform (`sin` and `cos` are not
/// guaranteed to be). Its rounding error is below 1e-13.
fn directions() -> Vec<Vec2> {
    // cos and sin of 2π / 1024.
    let (c, s) = (0.999_981_175_282_601_1, 0.006_135_884_649_154_475);
    let mut out = Vec::with_capacity(DIRECTIONS + 1);
    let mut v = Vec2::new(1.0, 0.0);
    for _ in 0..DIRECTIONS {
        out.push(v);
        v = Vec2::new(v.x * c - v.y * s, v.x * s + v.y * c);
    }
    out.push(out[0]);
    out
}

/// A point in the annulus between `r` and `2r` around the origin, from the
/// 64 random bits `bits`: uniform in area, its direction interpolated
/// between the two nearest of `table` ([`directions`]) and so uniform to
/// within 1e-5, and its distance from the origin at least `r(1 − 5e-6)`
/// (the chord between two table directions). One random number and no
/// branch a candidate.
fn annulus(r: f64, bits: u64, table: &[Vec2]) -> Vec2 {
    let k = (bits >> 54) as usize;
    let f = f64::from(((bits >> 32) & 0x3f_ffff) as u32) * (1.0 / (1u64 << 22) as f64);
    let u = f64::from(bits as u32) * (1.0 / (1u64 << 32) as f64);
    let d = table[k] + (table[k + 1] - table[k]) * f;
    // Uniform in area: the distance squared is uniform in [r², 4r²).
    d * ((1.0 + 3.0 * u).sqrt() * r)
}

/// What a tile of a [`Containment`] knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Tile {
    /// Not classified yet (only while a [`Containment`] is built).
    Unknown,
    /// The boundary may pass through: sum the winding numbers of the
    /// segments near.
    Boundary,
    /// Wholly inside the region.
    Inside,
    /// Wholly outside the region.
    Outside,
}

/// Flattening tolerance (mm) of the outline a [`Containment`] marks its
/// boundary tiles from.
const FLAT_TOLERANCE: f64 = 1e-3;

/// Tiles this close (mm) to the flattened outline count as boundary tiles:
/// ten times the flattening tolerance, so that the exact boundary is
/// nowhere near another tile.
const EDGE_MARGIN: f64 = 1e-2;

/// The points of `points` that lie inside `region`, in their order: the
/// same test the samplers keep their points by, so the points one of
/// them made are all kept. Costs one lookup in a grid of tiles per point
/// (and a winding number of the nearby segments near the boundary).
///
/// ```
/// use kurbo::{Point, Rect};
/// use moyo::geom::{region::Region, sample};
///
/// let square = Region::from_rect(Rect::new(0.0, 0.0, 10.0, 10.0))?;
/// let points = [Point::new(5.0, 5.0), Point::new(15.0, 5.0), Point::new(1.0, 9.0)];
/// assert_eq!(sample::inside(&square, &points), vec![points[0], points[2]]);
/// # Ok::<(), moyo::Error>(())
/// ```
pub fn inside(region: &Region, points: &[Point]) -> Vec<Point> {
    if region.is_empty() {
        return Vec::new();
    }
    let containment = Containment::new(region, points.len().clamp(4096, 1 << 20));
    points
        .iter()
        .copied()
        .filter(|&p| containment.contains(p))
        .collect()
}

/// [`Region::contains`] with the same answers, made cheap: a grid of tiles
/// over the region's bounds knows which tiles the boundary keeps away
/// from, and those are wholly inside or wholly outside. A point in a tile
/// near the boundary gets the exact test, the winding number of the
/// boundary, summed over only the segments that reach its row of tiles
/// (the others add 0), where `Region::contains` sums over every segment.
///
/// Tiles within [`EDGE_MARGIN`] of the outline flattened within
/// [`FLAT_TOLERANCE`] are marked; the exact boundary lies within the
/// tolerance of that outline, so it does not come within 9 µm of an
/// unmarked tile. Neighbouring unmarked tiles are then on the same side
/// (the boundary between them would have marked one), and each run of
/// them costs one exact test. Building is linear in the tiles and in the
/// outline's length over the tile side.
struct Containment<'a> {
    region: &'a Region,
    bounds: Rect,
    inv_side: f64,
    cols: usize,
    rows: usize,
    tiles: Vec<Tile>,
    /// For each row of tiles, the segments of the region's boundary that
    /// reach it: the only ones whose winding number about a point of the
    /// row may not be 0.
    rows_segments: Vec<BezPath>,
}

impl<'a> Containment<'a> {
    /// About `tiles` tiles over the bounds of `region` (not empty).
    fn new(region: &'a Region, tiles: usize) -> Containment<'a> {
        let bounds = region.bounds();
        let (w, h) = (bounds.width(), bounds.height());
        let n = tiles as f64;
        let side = (w * h / n).sqrt().max(w.max(h) / n).max(1e-9);
        let inv_side = 1.0 / side;
        let cols = ((w * inv_side).ceil() as usize).max(1);
        let rows = ((h * inv_side).ceil() as usize).max(1);
        let mut c = Containment {
            region,
            bounds,
            inv_side,
            cols,
            rows,
            tiles: vec![Tile::Unknown; cols * rows],
            rows_segments: vec![BezPath::new(); rows],
        };
        for seg in region.path().segments() {
            let b = seg.bounding_box();
            let (_, j0) = c.tile_of(Point::new(b.x0, b.y0 - EDGE_MARGIN));
            let (_, j1) = c.tile_of(Point::new(b.x0, b.y1 + EDGE_MARGIN));
            for row in &mut c.rows_segments[j0..=j1] {
                if row.elements().last().and_then(|e| e.end_point()) != Some(seg.start()) {
                    row.move_to(seg.start());
                }
                row.push(seg.as_path_el());
            }
        }
        for poly in region.polygons(FLAT_TOLERANCE) {
            for k in 0..poly.len() {
                let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
                // Pieces no longer than a tile, so each box covers few.
                let pieces = ((b - a).hypot() * inv_side).ceil().max(1.0) as usize;
                for m in 0..pieces {
                    let p = a.lerp(b, m as f64 / pieces as f64);
                    let q = a.lerp(b, (m + 1) as f64 / pieces as f64);
                    let r = Rect::from_points(p, q).inflate(EDGE_MARGIN, EDGE_MARGIN);
                    let ((i0, j0), (i1, j1)) =
                        (c.tile_of(r.origin()), c.tile_of(Point::new(r.x1, r.y1)));
                    for j in j0..=j1 {
                        c.tiles[j * cols + i0..=j * cols + i1].fill(Tile::Boundary);
                    }
                }
            }
        }
        for j in 0..rows {
            for i in 0..cols {
                let k = j * cols + i;
                if c.tiles[k] == Tile::Boundary {
                    continue;
                }
                c.tiles[k] = if i > 0 && c.tiles[k - 1] != Tile::Boundary {
                    c.tiles[k - 1]
                } else if j > 0 && c.tiles[k - cols] != Tile::Boundary {
                    c.tiles[k - cols]
                } else {
                    let centre = bounds.origin() + Vec2::new(i as f64 + 0.5, j as f64 + 0.5) * side;
                    if region.contains(centre) {
                        Tile::Inside
                    } else {
                        Tile::Outside
                    }
                };
            }
        }
        c
    }

    /// The tile (column, row) holding `p`, clamped to the grid.
    fn tile_of(&self, p: Point) -> (usize, usize) {
        // `as` saturates: NaN and negative numbers give 0.
        let i = ((p.x - self.bounds.x0) * self.inv_side) as usize;
        let j = ((p.y - self.bounds.y0) * self.inv_side) as usize;
        (i.min(self.cols - 1), j.min(self.rows - 1))
    }

    /// Whether `p` lies inside the region, as [`Region::contains`] says.
    fn contains(&self, p: Point) -> bool {
        if !self.bounds.contains(p) {
            return false;
        }
        let (i, j) = self.tile_of(p);
        match self.tiles[j * self.cols + i] {
            Tile::Inside => true,
            Tile::Outside => false,
            // The winding number of the whole boundary, summed over the
            // segments that can add to it: `Region::contains` exactly.
            Tile::Boundary | Tile::Unknown => self.rows_segments[j].winding(p) != 0,
        }
    }
}

/// The background grid: at most one point per cell (cells are less than
/// the smallest radius across), stored in the cell itself, in blocks of
/// `BLOCK × BLOCK` cells allocated on first use.
struct Grid {
    origin: Point,
    inv_cell: f64,
    cols: usize,
    rows: usize,
    /// Blocks per row.
    block_cols: usize,
    /// For each block of the bounds, its number among the allocated ones,
    /// or `NONE`.
    blocks: Vec<u32>,
    /// `BLOCK²` cells per allocated block: the point, or NaN for none
    /// (which no distance comparison accepts).
    cells: Vec<Point>,
}

impl Grid {
    /// The cell (column, row) of `p`, which lies in the bounds.
    fn cell_of(&self, p: Point) -> (usize, usize) {
        // `as` saturates: points a rounding error outside stay in range.
        let i = ((p.x - self.origin.x) * self.inv_cell) as usize;
        let j = ((p.y - self.origin.y) * self.inv_cell) as usize;
        (i.min(self.cols - 1), j.min(self.rows - 1))
    }

    /// The point in cell `(i, j)`: `None` in a block not allocated, NaN
    /// in an empty cell of an allocated one.
    fn get(&self, i: usize, j: usize) -> Option<Point> {
        let b = self.blocks[(j / BLOCK) * self.block_cols + i / BLOCK];
        (b != NONE)
            .then(|| self.cells[b as usize * BLOCK * BLOCK + (j % BLOCK) * BLOCK + i % BLOCK])
    }

    fn set(&mut self, i: usize, j: usize, p: Point) {
        let slot = &mut self.blocks[(j / BLOCK) * self.block_cols + i / BLOCK];
        if *slot == NONE {
            *slot = (self.cells.len() / (BLOCK * BLOCK)) as u32;
            let none = Point::new(f64::NAN, f64::NAN);
            self.cells.resize(self.cells.len() + BLOCK * BLOCK, none);
        }
        let b = *slot as usize;
        let cell = &mut self.cells[b * BLOCK * BLOCK + (j % BLOCK) * BLOCK + i % BLOCK];
        debug_assert!(cell.x.is_nan(), "two points in one cell");
        *cell = p;
    }
}

/// The state of one Poisson-disk sampling.
struct Sampler<'a> {
    inside: Containment<'a>,
    radius: &'a dyn Fn(Point) -> f64,
    r_min: f64,
    r_max: f64,
    bounds: Rect,
    grid: Grid,
    /// Cell offsets `(columns, rows)` with the smallest distance between a
    /// point in a cell and one in the offset cell (a little less, for
    /// rounding), nearest first, as far as `r_max`.
    offsets: Vec<(isize, isize, f64)>,
    /// The candidates' directions ([`directions`]).
    directions: Vec<Vec2>,
    points: Vec<Point>,
    /// The points that may still have room around them, with their radii.
    active: Vec<(Point, f64)>,
    limit: usize,
}

impl<'a> Sampler<'a> {
    fn new(
        region: &'a Region,
        radius: &'a dyn Fn(Point) -> f64,
        r_min: f64,
        r_max: f64,
        limit: usize,
    ) -> Result<Sampler<'a>> {
        let bounds = region.bounds();
        // A hair below r/√2, so that two points in one cell are always
        // closer than `r_min` despite rounding.
        let cell = r_min * std::f64::consts::FRAC_1_SQRT_2 * (1.0 - 1e-9);
        let cols = (bounds.width() / cell).ceil().max(1.0);
        let rows = (bounds.height() / cell).ceil().max(1.0);
        let (block_cols, block_rows) = ((cols / BLOCK as f64).ceil(), (rows / BLOCK as f64).ceil());
        let index_limit = limit.max(1 << 16) as f64;
        if block_cols * block_rows > index_limit {
            return Err(Error::Budget {
                limit,
                what: format!(
                    "Poisson-disk sampling at a radius of {r_min} mm over a region of \
                     {:.1} mm² whose bounds are {:.1} × {:.1} mm (a grid index of \
                     {:.0} blocks)",
                    region.area(),
                    bounds.width(),
                    bounds.height(),
                    block_cols * block_rows
                ),
            });
        }
        let (cols, rows) = (cols as usize, rows as usize);
        let (block_cols, block_rows) = (block_cols as usize, block_rows as usize);
        let grid = Grid {
            origin: bounds.origin(),
            inv_cell: 1.0 / cell,
            cols,
            rows,
            block_cols,
            blocks: vec![NONE; block_cols * block_rows],
            cells: Vec::new(),
        };
        // About one tile for four points at the smallest radius.
        let tiles = (region.area() / (r_min * r_min) / 4.0).clamp(4096.0, 1_048_576.0);
        Ok(Sampler {
            inside: Containment::new(region, tiles as usize),
            radius,
            r_min,
            r_max,
            bounds,
            offsets: offsets(cell, r_max),
            grid,
            directions: directions(),
            points: Vec::new(),
            active: Vec::new(),
            limit,
        })
    }

    /// The radius at `p`, clamped to the range.
    fn radius_at(&self, p: Point) -> Result<f64> {
        if self.r_min == self.r_max {
            return Ok(self.r_min);
        }
        let r = (self.radius)(p);
        if r.is_nan() {
            return Err(Error::invalid(
                "radius",
                format!(
                    "the radius function returned NaN at ({:.3}, {:.3}) mm",
                    p.x, p.y
                ),
            ));
        }
        Ok(r.clamp(self.r_min, self.r_max))
    }

    /// Whether no point lies closer to `p` than `r`.
    fn fits(&self, p: Point, r: f64) -> bool {
        let (i, j) = self.grid.cell_of(p);
        let r2 = r * r;
        for &(di, dj, d) in &self.offsets {
            if d >= r {
                break;
            }
            let (Some(ni), Some(nj)) = (i.checked_add_signed(di), j.checked_add_signed(dj)) else {
                continue;
            };
            if ni >= self.grid.cols || nj >= self.grid.rows {
                continue;
            }
            // An empty cell holds NaN, and `NaN < r2` is false.
            if self.grid.get(ni, nj).is_some_and(|q| (q - p).hypot2() < r2) {
                return false;
            }
        }
        true
    }

    /// Places `p` if it is in the bounds, inside (`part`, or the region if
    /// `None`) and far enough from every point; says whether it did.
    fn try_place(&mut self, p: Point, part: Option<&Region>) -> Result<bool> {
        if !self.bounds.contains(p) {
            return Ok(false);
        }
        let r = self.radius_at(p)?;
        if !self.fits(p, r) {
            return Ok(false);
        }
        let inside = match part {
            Some(part) => part.contains(p),
            None => self.inside.contains(p),
        };
        if !inside {
            return Ok(false);
        }
        if self.points.len() >= self.limit {
            return Err(Error::Budget {
                limit: self.limit,
                what: format!(
                    "Poisson-disk sampling at a radius of {} mm over {:.1} mm²",
                    self.r_min,
                    self.inside.region.area()
                ),
            });
        }
        let (i, j) = self.grid.cell_of(p);
        self.grid.set(i, j, p);
        self.points.push(p);
        self.active.push((p, r));
        Ok(true)
    }

    /// Bridson's loop: grows from the active points until none is left.
    fn grow(&mut self, rng: &mut RandomStream) -> Result<()> {
        while !self.active.is_empty() {
            // Each turn evaluates the radius (a density formula, an
            // image) up to CANDIDATES times: a newer edit stops it here.
            crate::cancel::checkpoint()?;
            let a = rng.below(self.active.len());
            let (p, r) = self.active[a];
            let mut placed = false;
            for _ in 0..CANDIDATES {
                let step = annulus(r, rng.next_u64(), &self.directions);
                let mut c = p + step;
                // Where the radius grows faster than the annulus reaches
                // (a white margin beside a dark shape), a candidate at
                // p's own distance is always too close to p for its own
                // radius, and the front would stop there: take the step at
                // the candidate's scale instead.
                if self.r_min != self.r_max {
                    let rc = self.radius_at(c)?;
                    if rc > r {
                        c = p + step * (rc / r);
                    }
                }
                if self.try_place(c, None)? {
                    placed = true;
                    break;
                }
            }
            if !placed {
                self.active.swap_remove(a);
            }
        }
        Ok(())
    }

    /// Seeds `part` (a connected part of the region) with a random point
    /// inside it, if one fits, and grows from it.
    fn seed(&mut self, part: &Region, rng: &mut RandomStream) -> Result<()> {
        let b = part.bounds();
        for _ in 0..SEED_TRIES {
            let p = Point::new(rng.range(b.x0, b.x1), rng.range(b.y0, b.y1));
            if self.try_place(p, Some(part))? {
                return self.grow(rng);
            }
        }
        Ok(())
    }
}

/// The cell offsets a search as far as `r_max` must look at, with the
/// smallest distance between points of the two cells (less 1e-6 of a cell,
/// for rounding), nearest first.
fn offsets(cell: f64, r_max: f64) -> Vec<(isize, isize, f64)> {
    let k = (r_max / cell).ceil() as isize + 1;
    let mut out = Vec::new();
    for dj in -k..=k {
        for di in -k..=k {
            let gx = (di.abs() - 1).max(0) as f64;
            let gy = (dj.abs() - 1).max(0) as f64;
            let d = ((gx * gx + gy * gy).sqrt() - 1e-6).max(0.0) * cell;
            if d < r_max {
                out.push((di, dj, d));
            }
        }
    }
    // The candidate's own cell first: a point there is always too close.
    out.sort_by(|a, b| {
        a.2.total_cmp(&b.2)
            .then((a.0.abs() + a.1.abs()).cmp(&(b.0.abs() + b.1.abs())))
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::region::tests::{circle, rect, star};
    use crate::geom::region::FillRule;
    use crate::geom::PointIndex;
    use crate::rng::Seed;

    fn stream(seed: u64) -> RandomStream {
        Seed(seed).derive("sample").stream()
    }

    fn polygon(points: &[(f64, f64)]) -> Region {
        let points: Vec<Point> = points.iter().map(|&p| p.into()).collect();
        Region::polygon(&points).unwrap()
    }

    /// An L: the 60 × 60 square without its top right 30 × 30 quarter.
    fn l_shape() -> Region {
        polygon(&[
            (0.0, 0.0),
            (30.0, 0.0),
            (30.0, 30.0),
            (60.0, 30.0),
            (60.0, 60.0),
            (0.0, 60.0),
        ])
    }

    fn in_l_notch(p: Point) -> bool {
        p.x > 30.0 && p.y < 30.0
    }

    /// The 60 × 60 square with a 20 × 20 square hole in the middle.
    fn holed_square() -> Region {
        rect(0.0, 0.0, 60.0, 60.0).difference(&rect(20.0, 20.0, 40.0, 40.0))
    }

    fn in_hole(p: Point) -> bool {
        (20.0..=40.0).contains(&p.x) && (20.0..=40.0).contains(&p.y)
    }

    /// Two 20 × 20 squares 30 mm apart, as one region of two subpaths.
    fn two_islands() -> Region {
        let mut path = rect(0.0, 0.0, 20.0, 20.0).into_path();
        path.extend(rect(50.0, 0.0, 70.0, 20.0).path().iter());
        Region::new(path, FillRule::EvenOdd).unwrap()
    }

    /// A test shape: its name, the region, and a test of the points that
    /// must stay empty that does not use `Region::contains`.
    type Shape = (&'static str, Region, fn(Point) -> bool);

    fn shapes() -> Vec<Shape> {
        vec![
            ("square", rect(0.0, 0.0, 60.0, 60.0), |_| false),
            ("L", l_shape(), in_l_notch),
            ("holed square", holed_square(), in_hole),
        ]
    }

    fn check_inside(name: &str, region: &Region, empty: fn(Point) -> bool, points: &[Point]) {
        assert!(!points.is_empty(), "{name}: no points");
        let b = region.bounds();
        for p in points {
            assert!(region.contains(*p), "{name}: {p:?} is outside");
            assert!(b.contains(*p), "{name}: {p:?} is outside the bounds");
            assert!(!empty(*p), "{name}: {p:?} is in the part left out");
        }
    }

    /// Checks that for `i < j`, `|p_i − p_j| ≥ r(p_j) − 1e-9`.
    fn check_spacing(points: &[Point], r: impl Fn(Point) -> f64) {
        let mut index = PointIndex::new(points);
        for j in (0..points.len()).rev() {
            index.remove(j as u32);
            let rj = r(points[j]) - 1e-9;
            if let Some((i, d2)) = index.nearest_within(points[j], rj * rj) {
                if d2 < rj * rj {
                    panic!("points {i} and {j} are {} apart, less than {rj}", d2.sqrt());
                }
            }
        }
    }

    /// Checks that every point of a fine grid inside `region` is within
    /// `reach` of a sample.
    fn check_coverage(name: &str, region: &Region, points: &[Point], reach: f64) {
        let mut index = PointIndex::new(points);
        let b = region.bounds();
        let step = reach / 8.0;
        let (nx, ny) = ((b.width() / step) as usize, (b.height() / step) as usize);
        for j in 0..=ny {
            for i in 0..=nx {
                let probe = Point::new(b.x0 + i as f64 * step, b.y0 + j as f64 * step);
                if region.contains(probe) {
                    assert!(
                        index.nearest_within(probe, reach * reach).is_some(),
                        "{name}: {probe:?} is farther than {reach} from every sample"
                    );
                }
            }
        }
    }

    #[test]
    fn every_point_is_inside() {
        for (name, region, empty) in shapes() {
            let mut rng = stream(1);
            check_inside(
                name,
                &region,
                empty,
                &uniform(&region, 2000, &mut rng).unwrap(),
            );
            check_inside(
                name,
                &region,
                empty,
                &jittered_grid(&region, 1.5, 1.0, &mut rng).unwrap(),
            );
            check_inside(
                name,
                &region,
                empty,
                &poisson_disk(&region, &|_| 1.5, 1.5..=1.5, &mut rng, 100_000).unwrap(),
            );
        }
    }

    #[test]
    fn containment_answers_as_the_region_does() {
        let shapes = [
            circle(0.0, 0.0, 30.0),
            star(Point::new(50.0, 50.0), 40.0, 15.0, 7, 0.3, true),
            holed_square(),
            l_shape(),
            two_islands(),
        ];
        let mut rng = stream(13);
        for region in &shapes {
            for tiles in [16, 4096, 4099, 9973, 100_000] {
                let inside = Containment::new(region, tiles);
                let b = region.bounds().inflate(1.0, 1.0);
                for _ in 0..20_000 {
                    let p = Point::new(rng.range(b.x0, b.x1), rng.range(b.y0, b.y1));
                    assert_eq!(inside.contains(p), region.contains(p), "{p:?}");
                }
                // The exact boundary keeps 9 µm away from every tile that
                // answers without the exact test, also between the
                // flattened outline's vertices, where the two part most.
                for seg in region.path().segments() {
                    for k in 0..200 {
                        let v = kurbo::ParamCurve::eval(&seg, f64::from(k) / 200.0);
                        let near = Rect::from_center_size(v, (0.018, 0.018));
                        let ((i0, j0), (i1, j1)) = (
                            inside.tile_of(near.origin()),
                            inside.tile_of(Point::new(near.x1, near.y1)),
                        );
                        for j in j0..=j1 {
                            for i in i0..=i1 {
                                let t = inside.tiles[j * inside.cols + i];
                                assert_eq!(t, Tile::Boundary, "tile ({i}, {j}) by {v:?}");
                            }
                        }
                    }
                }
                // Near the boundary, on both sides.
                for poly in region.polygons(0.1) {
                    for &v in &poly {
                        for d in [1e-6, 1e-3, 0.02, 0.3] {
                            let p = v + Vec2::new(rng.symmetric(d), rng.symmetric(d));
                            assert_eq!(inside.contains(p), region.contains(p), "{p:?}");
                        }
                    }
                }
                if tiles >= 4096 {
                    // Most tiles answer without the exact test.
                    let far = inside
                        .tiles
                        .iter()
                        .filter(|t| **t != Tile::Boundary)
                        .count();
                    assert!(
                        far * 10 > inside.tiles.len() * 7,
                        "{far} of {}",
                        inside.tiles.len()
                    );
                }
            }
        }
    }

    #[test]
    fn candidates_fill_the_annulus_evenly() {
        let table = directions();
        assert_eq!(table.len(), DIRECTIONS + 1);
        for (k, d) in table.iter().enumerate() {
            assert!((d.hypot() - 1.0).abs() < 1e-13, "{k}: {d:?}");
        }
        assert!((table[DIRECTIONS / 4] - Vec2::new(0.0, 1.0)).hypot() < 1e-13);
        let mut rng = stream(14);
        let (r, n) = (0.5, 200_000);
        let mut octants = [0usize; 8];
        let mut inner = 0;
        for _ in 0..n {
            let v = annulus(r, rng.next_u64(), &table);
            let d = v.hypot();
            assert!(d >= r * (1.0 - 5e-6) && d < 2.0 * r, "{v:?}");
            // Octants by the signs of x, y and |x| − |y|.
            let o = usize::from(v.x < 0.0)
                + 2 * usize::from(v.y < 0.0)
                + 4 * usize::from(v.x.abs() < v.y.abs());
            octants[o] += 1;
            if d < 1.5 * r {
                inner += 1;
            }
        }
        for o in octants {
            assert!((o as f64 / n as f64 - 0.125).abs() < 0.005, "{octants:?}");
        }
        // Uniform in area: (1.5² − 1) / (2² − 1) of the points lie within
        // 1.5 r.
        let inner = f64::from(inner) / n as f64;
        assert!((inner - 1.25 / 3.0).abs() < 0.005, "{inner}");
    }

    #[test]
    fn uniform_makes_exactly_count_points_spread_evenly() {
        let square = rect(0.0, 0.0, 10.0, 10.0);
        let points = uniform(&square, 4000, &mut stream(2)).unwrap();
        assert_eq!(points.len(), 4000);
        let mut quadrants = [0usize; 4];
        for p in &points {
            quadrants[usize::from(p.x >= 5.0) + 2 * usize::from(p.y >= 5.0)] += 1;
        }
        for q in quadrants {
            assert!((800..=1200).contains(&q), "{quadrants:?}");
        }
        assert!(uniform(&square, 0, &mut stream(2)).unwrap().is_empty());
        assert_eq!(uniform(&l_shape(), 777, &mut stream(2)).unwrap().len(), 777);
    }

    #[test]
    fn uniform_refuses_a_region_that_hardly_fills_its_bounds() {
        // A sliver along the diagonal: 0.5 mm² in a 100 × 100 mm box.
        let sliver = polygon(&[(0.0, 0.0), (100.0, 100.0), (100.0, 100.01)]);
        let e = uniform(&sliver, 10, &mut stream(3)).unwrap_err();
        assert!(
            matches!(&e, Error::Invalid { field, .. } if field == "region"),
            "{e}"
        );
        assert!(e.to_string().contains("of its bounds"), "{e}");
        let e = uniform(&Region::empty(), 1, &mut stream(3)).unwrap_err();
        assert!(matches!(e, Error::Invalid { .. }));
        let e = uniform(&l_shape(), MAX_POINTS + 1, &mut stream(3)).unwrap_err();
        assert!(
            matches!(&e, Error::Invalid { field, .. } if field == "count"),
            "{e}"
        );
    }

    #[test]
    fn jittered_grid_has_about_area_over_spacing_squared_points() {
        for (name, region, _) in shapes() {
            for (spacing, jitter) in [(1.0, 1.0), (2.0, 0.5), (0.7, 0.0)] {
                let n = jittered_grid(&region, spacing, jitter, &mut stream(4))
                    .unwrap()
                    .len() as f64;
                let expected = region.area() / (spacing * spacing);
                assert!(
                    (n - expected).abs() <= 0.1 * expected,
                    "{name}, spacing {spacing}: {n} points, expected {expected}"
                );
            }
        }
    }

    #[test]
    fn jitter_zero_gives_the_grid_nodes() {
        let region = rect(0.3, 0.3, 20.3, 10.3);
        let points = jittered_grid(&region, 1.0, 0.0, &mut stream(5)).unwrap();
        let expected: Vec<Point> = (1..=10)
            .flat_map(|j| (1..=20).map(move |i| Point::new(f64::from(i), f64::from(j))))
            .collect();
        assert_eq!(points, expected);
        // Jittered, no point stays on a node and none moves farther than
        // jitter × spacing / 2 in x or y.
        let points = jittered_grid(&region, 1.0, 0.5, &mut stream(5)).unwrap();
        for p in &points {
            let off = p.to_vec2() - p.to_vec2().round();
            assert!(off.x.abs() <= 0.25 && off.y.abs() <= 0.25, "{p:?}");
            assert!(off.x != 0.0 && off.y != 0.0, "{p:?}");
        }
    }

    #[test]
    fn poisson_disk_constant_radius_is_spaced_and_maximal() {
        let r = 1.5;
        for (name, region, _) in shapes() {
            let points = poisson_disk(&region, &|_| r, r..=r, &mut stream(6), 100_000).unwrap();
            check_spacing(&points, |_| r);
            check_coverage(name, &region, &points, 2.0 * r);
            // Bridson's sets hold about 0.6 / r² points per mm² (hexagonal
            // packing 1.15 / r²).
            let density = points.len() as f64 * r * r / region.area();
            assert!((0.5..0.9).contains(&density), "{name}: density {density}");
        }
    }

    #[test]
    fn poisson_disk_seeds_every_part() {
        // Islands 30 mm apart, and radius 1: growing from one cannot reach
        // the other.
        let region = two_islands();
        assert_eq!(region.components().len(), 2);
        for seed in 0..5 {
            let points =
                poisson_disk(&region, &|_| 1.0, 1.0..=1.0, &mut stream(seed), 10_000).unwrap();
            let left = points.iter().filter(|p| p.x < 35.0).count();
            assert!(
                left > 100 && points.len() - left > 100,
                "{left} of {}",
                points.len()
            );
            check_coverage("two islands", &region, &points, 2.0);
        }
        // A thin ring fills 8 % of its bounds: the seed must be drawn
        // inside it, and growth goes all the way round.
        let ring = circle(0.0, 0.0, 20.0).difference(&circle(0.0, 0.0, 19.0));
        for seed in 0..2 {
            let points =
                poisson_disk(&ring, &|_| 0.5, 0.5..=0.5, &mut stream(seed), 10_000).unwrap();
            check_inside("ring", &ring, |p| p.to_vec2().hypot() < 19.0, &points);
            check_coverage("ring", &ring, &points, 1.0);
        }
        // An island smaller than the radius gets its one point.
        let mut path = rect(0.0, 0.0, 20.0, 20.0).into_path();
        path.extend(rect(40.0, 40.0, 40.5, 40.5).path().iter());
        let region = Region::new(path, FillRule::NonZero).unwrap();
        let points = poisson_disk(&region, &|_| 2.0, 2.0..=2.0, &mut stream(7), 10_000).unwrap();
        assert_eq!(points.iter().filter(|p| p.x > 30.0).count(), 1);
    }

    #[test]
    fn poisson_disk_variable_radius_is_denser_where_the_radius_is_small() {
        let square = rect(0.0, 0.0, 60.0, 60.0);
        // 0.8 mm at the left edge to 2.4 mm at the right; the range clamps
        // it further to 1..2.
        let radius = |p: Point| 0.8 + p.x / 37.5;
        let clamped = |p: Point| radius(p).clamp(1.0, 2.0);
        let points = poisson_disk(&square, &radius, 1.0..=2.0, &mut stream(8), 100_000).unwrap();
        check_spacing(&points, clamped);
        let left = points.iter().filter(|p| p.x < 30.0).count();
        let right = points.len() - left;
        // About (1.6 / 1.15)² ≈ 2 to 1 in the mean radius squared.
        assert!(
            left as f64 > 1.5 * right as f64,
            "{left} left, {right} right"
        );
        check_coverage("variable", &square, &points, 4.0);
        // The rule is the radius at the later point, not the larger of the
        // two: some pair is closer than the larger radius.
        let mut index = PointIndex::new(&points);
        let closer_than_larger = (0..points.len()).rev().any(|j| {
            index.remove(j as u32);
            let (p, rp) = (points[j], clamped(points[j]));
            index
                .nearest_within(p, 4.0)
                .is_some_and(|(i, d2)| d2.sqrt() < clamped(points[i as usize]).max(rp))
        });
        assert!(closer_than_larger);
    }

    #[test]
    fn poisson_disk_grows_across_a_jump_in_radius() {
        // Radius 1 on the left half, 8 on the right: more than twice the
        // annulus, yet the right half is covered, sparsely. Seeded on the
        // left (the only dense part), so the front has to cross.
        let square = rect(0.0, 0.0, 100.0, 100.0);
        let radius = |p: Point| if p.x < 50.0 { 1.0 } else { 8.0 };
        for seed in 0..3 {
            let points =
                poisson_disk(&square, &radius, 1.0..=8.0, &mut stream(seed), 100_000).unwrap();
            let right = points.iter().filter(|p| p.x > 58.0).count();
            // A 42 × 100 mm strip at radius 8: about 0.63 × 4200 / 64 ≈ 41.
            assert!(right > 25, "seed {seed}: {right} points on the right");
            // And no gap wider than twice the radius there.
            for x in (60..100).step_by(4) {
                for y in (2..100).step_by(4) {
                    let probe = Point::new(x as f64, y as f64);
                    let near = points.iter().any(|p| p.distance(probe) < 16.0);
                    assert!(near, "seed {seed}: gap at {probe:?}");
                }
            }
        }
    }

    #[test]
    fn same_seed_same_points_other_seed_other_points() {
        let region = l_shape();
        let all = |seed| {
            let mut rng = stream(seed);
            (
                uniform(&region, 500, &mut rng).unwrap(),
                jittered_grid(&region, 2.0, 0.8, &mut rng).unwrap(),
                poisson_disk(&region, &|p| 1.0 + p.y / 60.0, 1.0..=2.0, &mut rng, 10_000).unwrap(),
            )
        };
        let (a, b) = (all(9), all(9));
        assert_eq!(a, b);
        let c = all(10);
        assert_ne!(a.0, c.0);
        assert_ne!(a.1, c.1);
        assert_ne!(a.2, c.2);
    }

    #[test]
    fn budget_stops_before_sampling() {
        // 1 m² at 0.01 mm: room for 1.2e10 points.
        let big = rect(0.0, 0.0, 1000.0, 1000.0);
        let e = poisson_disk(&big, &|_| 0.01, 0.01..=1.0, &mut stream(11), 200_000).unwrap_err();
        assert!(matches!(e, Error::Budget { limit: 200_000, .. }), "{e}");
        // 2 mm² at 0.01 mm fits the budget, but the bounds span 100 m: the
        // grid's index would not.
        let mut path = rect(0.0, 0.0, 1.0, 1.0).into_path();
        path.extend(rect(99_999.0, 99_999.0, 100_000.0, 100_000.0).path().iter());
        let far = Region::new(path, FillRule::NonZero).unwrap();
        let e = poisson_disk(&far, &|_| 0.01, 0.01..=0.01, &mut stream(11), 200_000).unwrap_err();
        assert!(matches!(e, Error::Budget { limit: 200_000, .. }), "{e}");
        // Just under and over the estimate of a small square.
        let small = rect(0.0, 0.0, 10.0, 10.0);
        let room = (100.0 * 2.0 / 3f64.sqrt()).ceil() as usize;
        assert!(poisson_disk(&small, &|_| 1.0, 1.0..=1.0, &mut stream(11), room).is_ok());
        let e = poisson_disk(&small, &|_| 1.0, 1.0..=1.0, &mut stream(11), room - 1);
        assert!(matches!(e, Err(Error::Budget { .. })));
    }

    #[test]
    fn bad_input_is_invalid() {
        let square = rect(0.0, 0.0, 10.0, 10.0);
        let mut rng = stream(12);
        let invalid = |r: Result<Vec<Point>>, field: &str| match r {
            Err(Error::Invalid { field: f, .. }) => assert_eq!(f, field),
            other => panic!("expected an invalid {field}, got {other:?}"),
        };
        for range in [
            f64::NAN..=1.0,
            0.0..=1.0,
            0.005..=1.0,
            -1.0..=1.0,
            1.0..=f64::NAN,
            1.0..=f64::INFINITY,
            2.0..=1.0,
            1.0..=101.0,
        ] {
            invalid(
                poisson_disk(&square, &|_| 1.0, range, &mut rng, 1000),
                "radius",
            );
        }
        invalid(
            poisson_disk(&square, &|_| f64::NAN, 1.0..=2.0, &mut rng, 1000),
            "radius",
        );
        // A range of one value is the radius: the function is not asked.
        assert!(poisson_disk(&square, &|_| f64::NAN, 1.0..=1.0, &mut rng, 1000).is_ok());
        for spacing in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-4] {
            invalid(jittered_grid(&square, spacing, 0.5, &mut rng), "spacing");
        }
        for jitter in [-0.1, 1.1, f64::NAN] {
            invalid(jittered_grid(&square, 1.0, jitter, &mut rng), "jitter");
        }
        // The empty region has no points, and that is no error.
        assert!(
            poisson_disk(&Region::empty(), &|_| 1.0, 1.0..=1.0, &mut rng, 10)
                .unwrap()
                .is_empty()
        );
        assert!(jittered_grid(&Region::empty(), 1.0, 1.0, &mut rng)
            .unwrap()
            .is_empty());
    }
}
