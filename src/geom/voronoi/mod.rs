//! Voronoi cells clipped exactly to a region, Delaunay edges inside a
//! region, and Lloyd relaxation (plain and density-weighted, for stippling).
//!
//! **What it owns.** A [`Domain`] is a [`Region`] prepared once for many
//! queries: its outline flattened within a tolerance, and a grid of tiles
//! over it that knows which tiles the outline crosses, which lie wholly
//! inside or outside, and the region cut into one piece per tile. A
//! [`Diagram`] is the Voronoi diagram of a set of sites clipped to a domain:
//! one [`Cell`] per input site. [`delaunay_edges`] and
//! [`constrained_delaunay`] give the triangulations, [`lloyd_step`] and
//! [`weighted_lloyd_step`] one step of relaxation, [`relax`] relaxation to
//! convergence (Lloyd or weighted Linde-Buzo-Gray).
//!
//! **Method.** Triangulations come from spade by *bulk load* (never point
//! by point: that is hundreds of times slower on large inputs). Voronoi
//! cells are the polygons of the circumcentres around each site; four far
//! "ghost" sites around everything close the cells of the hull sites
//! without changing any cell inside the region (they are farther from every
//! point of the region than any real site is). Each cell is then clipped to
//! the region *exactly* — holes stay empty, concave outlines are respected —
//! in three stages, cheapest first:
//! 1. tiles: a cell whose bounding box covers only tiles the outline does
//!    not cross is wholly inside or wholly outside, as those tiles are;
//! 2. edges: a cell that no outline edge in its tiles touches (an exact
//!    separating-axis test, with a margin that errs towards "touches") is
//!    wholly inside or outside, as one of its points is;
//! 3. otherwise the cell is intersected with the region's pieces in its
//!    tiles by i_overlay (integer, exact predicates).
//!
//! Nothing is skipped because a bounding box lies inside another one: that
//! shortcut (geo 0.33's `VoronoiClip`) fills holes and concave bays. Stage
//! 3 sees only the region near the cell, so its cost does not grow with the
//! length of the whole outline.
//!
//! **Choices.**
//! - *Duplicates.* Sites closer than [`MERGE_DISTANCE`] to an earlier site
//!   are merged into it: the earlier one owns the cell, the later one gets
//!   an empty cell and [`SiteStatus::MergedInto`]. So there is exactly one
//!   non-empty cell per distinct site (inside the region). In a Lloyd step a
//!   merged site stays where it is, so it separates from its owner as the
//!   owner moves. [`distinct`] leaves out the sites that would merge, for
//!   a caller whose sites come from a person (or a file) and may repeat.
//! - *Sites outside the region* follow [`OutsideSites`]: kept by default
//!   (the diagram of all sites, seen through the region: cells still tile
//!   the region, and an outside site's cell is the part of its cell that
//!   lies inside, often nothing), or dropped, or rejected as an error.
//!   "Outside" is decided on the flattened outline; sites on it may go
//!   either way.
//! - *Cells* are polygons ([`Cell::contours`]): one or more pieces (a
//!   concave region can cut a cell in two), each an outer contour with
//!   positive area (clockwise on the page, y down) followed by its holes
//!   (negative area). Contours thinner than
//!   [`SLIVER_WIDTH`] are dropped, as in
//!   every region operation.
//!
//! **Accuracy.** Cells tile the flattened region: their areas sum to
//! [`Domain::area`] up to i_overlay's integer grid (about 1e-9 of a cell's
//! size). The flattened outline is within the domain's tolerance of the
//! region's curves.
//!
//! ```
//! use kurbo::{Point, Rect};
//! use moyo::geom::region::Region;
//! use moyo::geom::voronoi::{CellOptions, Diagram, Domain};
//!
//! let square = Region::from_rect(Rect::new(0.0, 0.0, 10.0, 10.0))?;
//! let hole = Region::from_rect(Rect::new(3.0, 3.0, 7.0, 7.0))?;
//! let domain = Domain::new(&square.difference(&hole), moyo::geom::TOLERANCE)?;
//! let sites = [Point::new(1.0, 1.0), Point::new(9.0, 2.0), Point::new(5.0, 9.0)];
//! let diagram = Diagram::new(&sites, &domain, &CellOptions::DEFAULT)?;
//! let total: f64 = diagram.cells().iter().map(|c| c.area()).sum();
//! assert!((total - 84.0).abs() < 1e-6); // the hole is not covered
//! # Ok::<(), moyo::Error>(())
//! ```

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use i_overlay::core::fill_rule::FillRule as IFill;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::float::single::SingleFloatOverlay;
use i_overlay::float::slice::FloatSlice;
use kurbo::{BezPath, Line, Point, Rect, Vec2};
use spade::{
    ConstrainedDelaunayTriangulation, DelaunayTriangulation, HasPosition, Point2, Triangulation,
};

use super::region::{Region, SLIVER_WIDTH};
use super::TOLERANCE;
use crate::error::{Error, Result};
use crate::units::MAX_COORD;

mod density_grid;
mod network;
mod relax;

pub(crate) use network::{cell_network, chains};
use relax::Moments;
pub use relax::{
    lloyd_step, relax, weighted_lloyd_step, Lbg, LloydStep, Method, Relaxation, Relaxed, StepReport,
};

/// Sites closer than this (mm) to an earlier site are merged into it. Far
/// below what a pen shows, and far above the rounding noise that would make
/// the circumcentres of such near-coincident sites meaningless.
pub const MERGE_DISTANCE: f64 = 1e-6;

/// The ghost sites stand this many half-widths of the sites' and region's
/// box from its centre. Any factor above 3 keeps them farther from every
/// point of the box than the box's diagonal, hence than any real site.
const GHOST_FACTOR: f64 = 8.0;

/// At most this many tiles along each side of the grid.
const MAX_TILES_PER_SIDE: usize = 256;

/// Coordinates smaller than this (mm) are read as 0: spade refuses
/// non-zero values below about 1e-43, and they mean nothing on paper.
const FLUSH_TO_ZERO: f64 = 1e-30;

/// What to do with sites that lie outside the region.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum OutsideSites {
    /// Keep them in the diagram: the cells are those of all sites, seen
    /// through the region (they still tile it). An outside site's cell is
    /// the part of its cell inside the region, often empty.
    #[default]
    Keep,
    /// Leave them out of the diagram, as if they had not been given: their
    /// cells are empty, and the inside sites' cells tile the region.
    Drop,
    /// Refuse them with an [`Error::Invalid`] naming the first one.
    Reject,
}

/// Options for diagrams, triangulations and Lloyd steps.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellOptions {
    /// Most sites accepted (before merging duplicates); more is an
    /// [`Error::Budget`].
    pub max_sites: usize,
    /// What to do with sites outside the region.
    pub outside: OutsideSites,
    /// For [`weighted_lloyd_step`]: each triangle of a cell's fan is cut
    /// into `n²` smaller ones (`n` ≥ 1), and the density is sampled at
    /// three points in each. Raise it when the density varies on a scale
    /// finer than the cells.
    pub density_subdivisions: u32,
    /// The scale (mm) on which the density may change, such as an image's
    /// pixel. When it is above 0 the density is sampled once on a grid of
    /// this spacing and each cell's moments are integrated exactly over
    /// that grid, strip by strip — so a large cell reaching over an edge
    /// in the density (out over white next to a dark patch) weighs what
    /// it holds, not what a dozen samples happen to hit — instead of
    /// sampling each cell at `density_subdivisions` points. 0: sampling.
    pub density_detail: f64,
}

impl CellOptions {
    /// One million sites, outside sites kept, 2 subdivisions (12 density
    /// samples per fan triangle), no density detail.
    pub const DEFAULT: CellOptions = CellOptions {
        max_sites: 1_000_000,
        outside: OutsideSites::Keep,
        density_subdivisions: 2,
        density_detail: 0.0,
    };

    /// With another cap on the number of sites.
    pub fn with_max_sites(self, max_sites: usize) -> CellOptions {
        CellOptions { max_sites, ..self }
    }

    /// With another policy for sites outside the region.
    pub fn with_outside(self, outside: OutsideSites) -> CellOptions {
        CellOptions { outside, ..self }
    }

    /// With the scale on which the density changes (see
    /// [`CellOptions::density_detail`]).
    pub fn with_density_detail(self, mm: f64) -> CellOptions {
        CellOptions {
            density_detail: if mm.is_finite() { mm.max(0.0) } else { 0.0 },
            ..self
        }
    }

    /// With another number of density subdivisions (0 counts as 1).
    pub fn with_density_subdivisions(self, n: u32) -> CellOptions {
        CellOptions {
            density_subdivisions: n.max(1),
            ..self
        }
    }
}

impl Default for CellOptions {
    fn default() -> Self {
        CellOptions::DEFAULT
    }
}

// ---------------------------------------------------------------------------
// Domain: a region prepared for clipping and containment queries.

/// What a tile of the domain's grid holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum TileState {
    Inside,
    Outside,
    /// The flattened outline meets the tile.
    Boundary,
}

/// A uniform grid over the domain's bounds.
#[derive(Debug, Clone)]
struct Grid {
    x0: f64,
    y0: f64,
    sx: f64,
    sy: f64,
    nx: usize,
    ny: usize,
}

impl Grid {
    fn col(&self, x: f64) -> usize {
        // `as` saturates (and maps NaN to 0), so any input is a valid index.
        (((x - self.x0) / self.sx).floor().max(0.0) as usize).min(self.nx - 1)
    }

    fn row(&self, y: f64) -> usize {
        (((y - self.y0) / self.sy).floor().max(0.0) as usize).min(self.ny - 1)
    }

    /// Columns and rows of the tiles that `r` overlaps (clamped to the grid).
    fn span(
        &self,
        r: Rect,
    ) -> (
        std::ops::RangeInclusive<usize>,
        std::ops::RangeInclusive<usize>,
    ) {
        (
            self.col(r.x0)..=self.col(r.x1),
            self.row(r.y0)..=self.row(r.y1),
        )
    }

    fn tile_rect(&self, ix: usize, iy: usize) -> Rect {
        Rect::new(
            self.x0 + ix as f64 * self.sx,
            self.y0 + iy as f64 * self.sy,
            self.x0 + (ix + 1) as f64 * self.sx,
            self.y0 + (iy + 1) as f64 * self.sy,
        )
    }
}

/// A region prepared for Voronoi clipping, triangulation and containment:
/// its outline flattened within a tolerance, in a grid of tiles.
///
/// Make it once and reuse it for every Lloyd step on the same region.
/// Everything here works on the *flattened* region: [`Domain::area`] and
/// [`Domain::contains`] are those of the polygons, which lie within the
/// tolerance of the region's curves.
#[derive(Debug, Clone)]
pub struct Domain {
    tolerance: f64,
    polygons: Vec<Vec<Point>>,
    edges: Vec<[Point; 2]>,
    area: f64,
    bounds: Rect,
    /// The bounds grown a little: cells are cut to it first, so that the
    /// polygon engine never sees the huge cells of hull sites.
    frame: Rect,
    /// Margin (mm) of the "touches" tests: values this close count as
    /// touching, which only sends a cell to the exact stage.
    eps: f64,
    grid: Grid,
    tile_state: Vec<TileState>,
    tile_edges: Vec<Vec<u32>>,
    tile_pieces: Vec<Vec<u32>>,
    row_edges: Vec<Vec<u32>>,
    /// The region cut along the grid lines: shapes (outer contour, holes).
    pieces: Vec<Vec<Vec<[f64; 2]>>>,
    /// The number of points of each piece.
    piece_points: Vec<usize>,
    /// The whole flattened region, for cells so large that their pieces
    /// would hold more points.
    whole: Vec<Vec<[f64; 2]>>,
}

impl Domain {
    /// Prepares `region`, its outline flattened within `tolerance` mm
    /// (non-finite or non-positive means [`TOLERANCE`]).
    ///
    /// # Errors
    /// [`Error::Invalid`] (field `region`) when the region is empty or its
    /// flattened outline encloses no area.
    pub fn new(region: &Region, tolerance: f64) -> Result<Domain> {
        let tolerance = if tolerance.is_finite() && tolerance > 0.0 {
            tolerance
        } else {
            TOLERANCE
        };
        let polygons: Vec<Vec<Point>> = region
            .polygons(tolerance)
            .into_iter()
            .filter(|c| shoelace(c) != 0.0)
            .collect();
        let area: f64 = polygons.iter().map(|c| shoelace(c)).sum();
        if polygons.is_empty() || area.is_nan() || area <= 0.0 {
            return Err(Error::invalid(
                "region",
                "the region is empty: there is no area to divide into cells",
            ));
        }
        let mut edges = Vec::new();
        let mut bounds = Rect::from_points(polygons[0][0], polygons[0][0]);
        for c in &polygons {
            for (i, &a) in c.iter().enumerate() {
                edges.push([a, c[(i + 1) % c.len()]]);
                bounds = bounds.union_pt(a);
            }
        }
        let (w, h) = (bounds.width(), bounds.height());
        let size = w.max(h);
        let eps = 1e-9
            * (1.0 + bounds.x0.abs().max(bounds.x1.abs()))
                .max(1.0 + bounds.y0.abs().max(bounds.y1.abs()));
        let frame = bounds.inflate(0.01 * size + 1e-6, 0.01 * size + 1e-6);

        // About √n tiles a side for n edges: an outline crosses some
        // multiple of √n tiles, so a tile it crosses holds a fraction of √n
        // edges (a few for a square with round holes, some dozens for a
        // detailed outline), and so does the region's piece in it.
        let per_side = ((edges.len() as f64).sqrt().ceil() as usize).clamp(1, MAX_TILES_PER_SIDE);
        let s = size / per_side as f64;
        let nx = ((w / s).ceil() as usize).clamp(1, MAX_TILES_PER_SIDE);
        let ny = ((h / s).ceil() as usize).clamp(1, MAX_TILES_PER_SIDE);
        let grid = Grid {
            x0: bounds.x0,
            y0: bounds.y0,
            sx: (w / nx as f64).max(f64::MIN_POSITIVE),
            sy: (h / ny as f64).max(f64::MIN_POSITIVE),
            nx,
            ny,
        };

        let mut tile_edges = vec![Vec::new(); nx * ny];
        let mut row_edges = vec![Vec::new(); ny];
        for (k, &[a, b]) in edges.iter().enumerate() {
            let r = Rect::from_points(a, b).inflate(eps, eps);
            let (cols, rows) = grid.span(r);
            for iy in rows {
                row_edges[iy].push(k as u32);
                for ix in cols.clone() {
                    if segment_meets_rect(a, b, grid.tile_rect(ix, iy).inflate(eps, eps)) {
                        tile_edges[iy * nx + ix].push(k as u32);
                    }
                }
            }
        }
        let tile_state = tile_states(&grid, &edges, &tile_edges, &row_edges);
        let mut domain = Domain {
            tolerance,
            polygons,
            edges,
            area,
            bounds,
            frame,
            eps,
            grid,
            tile_state,
            tile_edges,
            tile_pieces: vec![Vec::new(); nx * ny],
            row_edges,
            pieces: Vec::new(),
            piece_points: Vec::new(),
            whole: Vec::new(),
        };
        domain.cut_pieces();
        Ok(domain)
    }

    /// Cuts the region along the grid lines into one piece per tile, so that
    /// clipping a cell looks only at the region near it. If the cut does not
    /// add up (it should), the whole region is every tile's piece: slower,
    /// never wrong.
    fn cut_pieces(&mut self) {
        let subject: Vec<Vec<[f64; 2]>> = self
            .polygons
            .iter()
            .map(|c| c.iter().map(|p| [p.x, p.y]).collect())
            .collect();
        self.whole = subject.clone();
        let g = &self.grid;
        let whole = |d: &mut Domain, subject: Vec<Vec<[f64; 2]>>| {
            d.piece_points = vec![d.edges.len()];
            d.pieces = vec![subject];
            d.tile_pieces = vec![vec![0]; d.grid.nx * d.grid.ny];
        };
        if g.nx * g.ny == 1 {
            whole(self, subject);
            return;
        }
        let b = self.frame;
        let mut lines: Vec<Vec<[f64; 2]>> = Vec::new();
        for i in 1..g.nx {
            let x = g.x0 + i as f64 * g.sx;
            lines.push(vec![[x, b.y0], [x, b.y1]]);
        }
        for j in 1..g.ny {
            let y = g.y0 + j as f64 * g.sy;
            lines.push(vec![[b.x0, y], [b.x1, y]]);
        }
        let cut = super::engine_panic::catch(|| subject.slice_by(&lines, IFill::NonZero));
        let Some(shapes) = cut else {
            whole(self, subject);
            return;
        };
        let total: f64 = shapes
            .iter()
            .flatten()
            .map(|c| shoelace_arr(c))
            .sum::<f64>();
        if (total - self.area).abs() > 1e-6 * self.area + self.eps {
            whole(self, subject);
            return;
        }
        let shrink = 1e-7 * g.sx.max(g.sy);
        for shape in shapes {
            let Some(outer) = shape.first() else { continue };
            let Some(r) = bbox_arr(outer) else { continue };
            let r = Rect::new(
                r.x0 + shrink,
                r.y0 + shrink,
                (r.x1 - shrink).max(r.x0 + shrink),
                (r.y1 - shrink).max(r.y0 + shrink),
            );
            let id = self.pieces.len() as u32;
            let (cols, rows) = self.grid.span(r);
            for iy in rows {
                for ix in cols.clone() {
                    self.tile_pieces[iy * self.grid.nx + ix].push(id);
                }
            }
            self.piece_points.push(shape.iter().map(Vec::len).sum());
            self.pieces.push(shape);
        }
    }

    /// The flattening tolerance (mm) the domain was made with.
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// The region's outline flattened within [`Domain::tolerance`]: outer
    /// contours with positive area, holes negative, as
    /// [`Region::polygons`] gives them.
    pub fn polygons(&self) -> &[Vec<Point>] {
        &self.polygons
    }

    /// The area (mm²) of the flattened region: what the cells add up to.
    pub fn area(&self) -> f64 {
        self.area
    }

    /// The bounding box of the flattened region.
    pub fn bounds(&self) -> Rect {
        self.bounds
    }

    /// Whether `p` lies inside the flattened region (non-zero winding);
    /// points on the outline may go either way. Looks at `p`'s tile, and if
    /// the outline meets it, at the edges in `p`'s row of tiles.
    pub fn contains(&self, p: Point) -> bool {
        if !(p.x >= self.bounds.x0
            && p.x <= self.bounds.x1
            && p.y >= self.bounds.y0
            && p.y <= self.bounds.y1)
        {
            return false;
        }
        // A tile the outline does not meet answers for all its points.
        let (ix, iy) = (self.grid.col(p.x), self.grid.row(p.y));
        match self.tile_state[iy * self.grid.nx + ix] {
            TileState::Inside => return true,
            TileState::Outside => return false,
            TileState::Boundary => {}
        }
        let mut winding = 0i32;
        for &k in &self.row_edges[iy] {
            let [a, b] = self.edges[k as usize];
            // Sunday's winding number: edges crossing the ray to the right of
            // `p`, counted by direction, with half-open ends in y.
            if a.y <= p.y {
                if b.y > p.y && cross(a, b, p) > 0.0 {
                    winding += 1;
                }
            } else if b.y <= p.y && cross(a, b, p) < 0.0 {
                winding -= 1;
            }
        }
        winding != 0
    }

    /// The outline edges registered in the tiles that `r` overlaps (with
    /// repeats when an edge spans several tiles).
    fn edges_near(&self, r: Rect) -> impl Iterator<Item = [Point; 2]> + '_ {
        let (cols, rows) = self.grid.span(r);
        rows.flat_map(move |iy| {
            cols.clone()
                .flat_map(move |ix| self.tile_edges[iy * self.grid.nx + ix].iter())
        })
        .map(|&k| self.edges[k as usize])
    }

    /// The part of a convex cell (positive area) inside the region, as
    /// contours (see [`Cell::contours`]).
    fn clip_convex(&self, cell: &[Point]) -> Vec<Vec<Point>> {
        let Some(mut bb) = bbox(cell) else {
            return Vec::new();
        };
        if !bb.overlaps(self.bounds) {
            return Vec::new();
        }
        // Cut huge cells to the frame first (convex by convex: exact enough,
        // and the region lies inside the frame, so nothing of it is lost).
        let framed;
        let cell = if self.frame.contains_rect(bb) {
            cell
        } else {
            framed = clip_to_rect(cell, self.frame);
            match bbox(&framed) {
                Some(r) if framed.len() >= 3 => bb = r,
                _ => return Vec::new(),
            }
            &framed[..]
        };
        let within = self.bounds.contains_rect(bb);

        // Stage 1: the tiles.
        let (cols, rows) = self.grid.span(bb);
        let mut seen: Option<TileState> = None;
        let mut plain = true;
        for iy in rows {
            for ix in cols.clone() {
                let s = self.tile_state[iy * self.grid.nx + ix];
                if s == TileState::Boundary || seen.is_some_and(|t| t != s) {
                    plain = false;
                }
                seen = Some(s);
            }
        }
        if plain {
            match seen {
                Some(TileState::Inside) if within => return vec![cell.to_vec()],
                Some(TileState::Outside) => return Vec::new(),
                // An inside tile at the edge of the bounds cannot be (the
                // region touches every side of its box); let stage 2 decide.
                _ => {}
            }
        }

        // Stage 2: the edges.
        let touches = self
            .edges_near(bb)
            .any(|[a, b]| segment_meets_convex(a, b, cell, self.eps));
        if !touches {
            // Wholly on one side: a cell reaching out of the bounds is
            // outside, else ask one of its points (its vertex mean, inside
            // a convex cell).
            let mean = cell.iter().fold(Vec2::ZERO, |s, p| s + p.to_vec2()) / cell.len() as f64;
            return if within && self.contains(mean.to_point()) {
                vec![cell.to_vec()]
            } else {
                Vec::new()
            };
        }

        // Stage 3: the polygon engine, against the region's pieces nearby.
        let (cols, rows) = self.grid.span(bb);
        let mut ids: Vec<u32> = Vec::new();
        for iy in rows {
            for ix in cols.clone() {
                ids.extend_from_slice(&self.tile_pieces[iy * self.grid.nx + ix]);
            }
        }
        ids.sort_unstable();
        ids.dedup();
        let points: usize = ids.iter().map(|&i| self.piece_points[i as usize]).sum();
        let subject: Vec<[f64; 2]> = cell.iter().map(|p| [p.x, p.y]).collect();
        let shapes = if points > self.edges.len() {
            // A cell spanning many tiles: the whole region is smaller.
            subject.overlay(&self.whole, OverlayRule::Intersect, IFill::NonZero)
        } else {
            let clip: Vec<Vec<[f64; 2]>> = ids
                .iter()
                .flat_map(|&i| self.pieces[i as usize].iter().cloned())
                .collect();
            subject.overlay(&clip, OverlayRule::Intersect, IFill::NonZero)
        };
        contours_from_shapes(&shapes)
    }

    /// Whether the segment `a`–`b` crosses the flattened outline properly
    /// (touching at an end or a vertex does not count).
    fn crosses_outline(&self, a: Point, b: Point) -> bool {
        let r = Rect::from_points(a, b).inflate(self.eps, self.eps);
        if !r.overlaps(self.bounds) {
            return false;
        }
        self.edges_near(r)
            .any(|[p, q]| segments_cross_properly(a, b, p, q))
    }

    /// Whether the segment `a`–`b` lies in the region: its middle inside
    /// and no proper crossing of the outline.
    fn holds_segment(&self, a: Point, b: Point) -> bool {
        self.contains(a.midpoint(b)) && !self.crosses_outline(a, b)
    }
}

/// Inside/outside for the tiles the outline does not meet, from the
/// crossings of each row's centre line (one sort per row).
fn tile_states(
    grid: &Grid,
    edges: &[[Point; 2]],
    tile_edges: &[Vec<u32>],
    row_edges: &[Vec<u32>],
) -> Vec<TileState> {
    let mut state = vec![TileState::Boundary; grid.nx * grid.ny];
    let mut crossings: Vec<(f64, i32)> = Vec::new();
    for (iy, row) in row_edges.iter().enumerate() {
        let y = grid.y0 + (iy as f64 + 0.5) * grid.sy;
        crossings.clear();
        for &k in row {
            let [a, b] = edges[k as usize];
            if (a.y <= y) != (b.y <= y) {
                let x = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
                crossings.push((x, if b.y > a.y { 1 } else { -1 }));
            }
        }
        crossings.sort_by(|p, q| p.0.total_cmp(&q.0));
        // Winding to the right of a point: the sum over crossings beyond it.
        let mut right: i32 = crossings.iter().map(|c| c.1).sum();
        let mut next = 0;
        for ix in 0..grid.nx {
            let x = grid.x0 + (ix as f64 + 0.5) * grid.sx;
            while next < crossings.len() && crossings[next].0 <= x {
                right -= crossings[next].1;
                next += 1;
            }
            let t = iy * grid.nx + ix;
            if tile_edges[t].is_empty() {
                state[t] = if right != 0 {
                    TileState::Inside
                } else {
                    TileState::Outside
                };
            }
        }
    }
    state
}

// ---------------------------------------------------------------------------
// Cells and diagrams.

/// The part of one site's Voronoi cell that lies in the region.
///
/// Contours are closed polygons (the first point is not repeated): each
/// outer contour, with positive area (clockwise on the page, y down), is
/// followed by its holes, with negative area. Empty when the cell misses
/// the region, or when the site was merged or dropped (see
/// [`SiteStatus`]).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Cell {
    contours: Vec<Vec<Point>>,
}

impl Cell {
    /// The contours: each outer contour followed by its holes.
    pub fn contours(&self) -> &[Vec<Point>] {
        &self.contours
    }

    /// Whether the cell has no area.
    pub fn is_empty(&self) -> bool {
        self.contours.is_empty()
    }

    /// The area (mm²), holes subtracted.
    pub fn area(&self) -> f64 {
        self.contours.iter().map(|c| shoelace(c)).sum()
    }

    /// The area centroid of all pieces together (each weighted by its
    /// area); `None` for an empty cell. It may lie outside the cell when the
    /// cell is not convex or has several pieces.
    pub fn centroid(&self) -> Option<Point> {
        let origin = self.contours.first()?.first()?.to_vec2();
        let m = Moments::of(&self.contours, origin);
        m.centroid(origin)
    }

    /// The number of pieces (outer contours).
    pub fn piece_count(&self) -> usize {
        self.contours.iter().filter(|c| shoelace(c) > 0.0).count()
    }

    /// The cell as a path of closed polygons.
    pub fn to_path(&self) -> BezPath {
        let mut path = BezPath::new();
        for c in &self.contours {
            path.move_to(c[0]);
            for &p in &c[1..] {
                path.line_to(p);
            }
            path.close_path();
        }
        path
    }

    /// The cell as a [`Region`] (already normalised: simple contours,
    /// outer ones positive, holes negative), ready for other families to
    /// fill.
    pub fn to_region(&self) -> Region {
        Region::from_normalised(self.to_path())
    }

    /// The pieces, each an outer contour followed by its holes.
    fn pieces(&self) -> impl Iterator<Item = &[Vec<Point>]> {
        let mut starts: Vec<usize> = (0..self.contours.len())
            .filter(|&i| shoelace(&self.contours[i]) > 0.0)
            .collect();
        starts.push(self.contours.len());
        let (contours, n) = (&self.contours, starts.len());
        (0..n - 1).map(move |k| &contours[starts[k]..starts[k + 1]])
    }
}

/// What became of an input site.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SiteStatus {
    /// The site owns its cell.
    Own,
    /// The site lies within [`MERGE_DISTANCE`] of the earlier site with this
    /// index, which owns the cell; its own cell is empty.
    MergedInto(usize),
    /// The site lies outside the region and [`OutsideSites::Drop`] left it
    /// out; its cell is empty.
    Dropped,
}

/// The Voronoi diagram of a set of sites, clipped to a [`Domain`]: one
/// [`Cell`] per input site, in input order. The non-empty cells tile the
/// region (no overlaps, no gaps, holes left empty).
#[derive(Debug, Clone, PartialEq)]
pub struct Diagram {
    sites: Vec<Point>,
    status: Vec<SiteStatus>,
    cells: Vec<Cell>,
}

impl Diagram {
    /// The diagram of `sites` clipped to `domain`.
    ///
    /// # Errors
    /// - [`Error::Invalid`] (field `sites`, or `sites[i]` for the site at
    ///   fault) for no sites, a coordinate that
    ///   is not finite or beyond ±[`MAX_COORD`] mm, or (with
    ///   [`OutsideSites::Reject`]) a site outside the region;
    /// - [`Error::Budget`] for more than [`CellOptions::max_sites`] sites;
    /// - [`Error::Geometry`] if a geometry engine fails.
    pub fn new(sites: &[Point], domain: &Domain, options: &CellOptions) -> Result<Diagram> {
        let prepared = Prepared::new(sites, domain, options)?;
        guard("computing Voronoi cells", || {
            let cells = voronoi_cells(&prepared, domain);
            Diagram {
                sites: sites.to_vec(),
                status: prepared.status,
                cells,
            }
        })
    }

    /// The input sites, as given.
    pub fn sites(&self) -> &[Point] {
        &self.sites
    }

    /// One cell per input site, in input order.
    pub fn cells(&self) -> &[Cell] {
        &self.cells
    }

    /// What became of each input site, in input order.
    pub fn status(&self) -> &[SiteStatus] {
        &self.status
    }
}

/// Sites checked, merged and sorted out: the ones that own a cell.
struct Prepared {
    status: Vec<SiteStatus>,
    /// Indices of the sites that own a cell, ascending.
    owners: Vec<usize>,
    /// The sites, flushed to zero where tiny.
    points: Vec<Point>,
}

impl Prepared {
    fn new(sites: &[Point], domain: &Domain, options: &CellOptions) -> Result<Prepared> {
        if sites.is_empty() {
            return Err(Error::invalid("sites", "at least one site is needed"));
        }
        if sites.len() > options.max_sites {
            return Err(Error::Budget {
                limit: options.max_sites,
                what: format!("{} Voronoi sites (one cell each)", sites.len()),
            });
        }
        let mut points = Vec::with_capacity(sites.len());
        for (i, p) in sites.iter().enumerate() {
            if !(p.x.is_finite()
                && p.y.is_finite()
                && p.x.abs() <= MAX_COORD
                && p.y.abs() <= MAX_COORD)
            {
                return Err(Error::invalid(
                    format!("sites[{i}]"),
                    format!(
                        "coordinates must be finite numbers within ±{MAX_COORD} mm, got ({}, {})",
                        p.x, p.y
                    ),
                ));
            }
            let flush = |v: f64| if v.abs() < FLUSH_TO_ZERO { 0.0 } else { v };
            points.push(Point::new(flush(p.x), flush(p.y)));
        }
        let mut status = vec![SiteStatus::Own; sites.len()];
        if options.outside != OutsideSites::Keep {
            for (i, &p) in points.iter().enumerate() {
                if !domain.contains(p) {
                    if options.outside == OutsideSites::Reject {
                        return Err(Error::invalid(
                            format!("sites[{i}]"),
                            format!("the site ({}, {}) lies outside the region", p.x, p.y),
                        ));
                    }
                    status[i] = SiteStatus::Dropped;
                }
            }
        }
        let mut merger = Merger::new(points.len());
        let mut owners = Vec::with_capacity(sites.len());
        for (i, status) in status.iter_mut().enumerate() {
            if *status == SiteStatus::Dropped {
                continue;
            }
            match merger.owner(&points, i) {
                Some(j) => *status = SiteStatus::MergedInto(j),
                None => owners.push(i),
            }
        }
        Ok(Prepared {
            status,
            owners,
            points,
        })
    }
}

/// `sites` less those within [`MERGE_DISTANCE`] of an earlier one, in
/// order: the sites that own a cell of their diagram (when all lie
/// inside), each once. A diagram, a triangulation or a tour of these has
/// no empty cell, no coincident vertices, no step of length 0.
///
/// ```
/// use kurbo::Point;
/// use moyo::geom::voronoi::distinct;
///
/// let sites = [Point::new(1.0, 1.0), Point::new(2.0, 2.0), Point::new(1.0, 1.0 + 1e-9)];
/// assert_eq!(distinct(&sites), vec![sites[0], sites[1]]);
/// ```
pub fn distinct(sites: &[Point]) -> Vec<Point> {
    let mut merger = Merger::new(sites.len());
    (0..sites.len())
        .filter(|&i| merger.owner(sites, i).is_none())
        .map(|i| sites[i])
        .collect()
}

/// The search for near-duplicates: the sites that own a cell so far,
/// hashed by their [`MERGE_DISTANCE`] square (a list per square, chained
/// through `next`), looked up only, never iterated, so the outcome
/// depends on the input order alone.
struct Merger {
    heads: HashMap<(i64, i64), u32, BuildHasherDefault<SquareHasher>>,
    next: Vec<u32>,
}

impl Merger {
    /// A search over at most `n` sites (indices below `n`, at most
    /// `u32::MAX`: the callers cap the sites far below).
    fn new(n: usize) -> Merger {
        Merger {
            heads: HashMap::with_capacity_and_hasher(n, Default::default()),
            next: vec![u32::MAX; n],
        }
    }

    /// The earlier owner within [`MERGE_DISTANCE`] of `points[i]`, or
    /// `None` after making site `i` an owner itself. Sites are asked in
    /// increasing order.
    fn owner(&mut self, points: &[Point], i: usize) -> Option<usize> {
        let p = points[i];
        let (kx, ky) = (
            (p.x / MERGE_DISTANCE).floor() as i64,
            (p.y / MERGE_DISTANCE).floor() as i64,
        );
        for dx in -1..=1 {
            for dy in -1..=1 {
                let mut j = self
                    .heads
                    .get(&(kx + dx, ky + dy))
                    .copied()
                    .unwrap_or(u32::MAX);
                while j != u32::MAX {
                    if points[j as usize].distance(p) < MERGE_DISTANCE {
                        return Some(j as usize);
                    }
                    j = self.next[j as usize];
                }
            }
        }
        let head = self.heads.entry((kx, ky)).or_insert(u32::MAX);
        self.next[i] = *head;
        *head = i as u32;
        None
    }
}

/// A small multiplicative hasher for the integer keys of the duplicate
/// search (the default SipHash took a third of a 100 000-site diagram's
/// preparation). Keys come from the input, but a collision only costs
/// time.
#[derive(Default)]
struct SquareHasher(u64);

impl Hasher for SquareHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }

    fn write_i64(&mut self, v: i64) {
        self.write_u64(v as u64);
    }

    fn write_u64(&mut self, v: u64) {
        self.0 = (self.0.rotate_left(5) ^ v).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

/// Runs `f`, turning a panic of a geometry engine into [`Error::Geometry`].
fn guard<T>(operation: &str, f: impl FnOnce() -> T) -> Result<T> {
    super::engine_panic::catch(f).ok_or_else(|| Error::Geometry {
        operation: operation.into(),
    })
}

/// A triangulation vertex: a position and a tag (a site index, or
/// `u32::MAX` for ghosts and outline vertices).
#[derive(Debug, Clone, Copy)]
struct Vertex {
    position: Point2<f64>,
    tag: u32,
}

const NO_SITE: u32 = u32::MAX;

impl HasPosition for Vertex {
    type Scalar = f64;

    fn position(&self) -> Point2<f64> {
        self.position
    }
}

fn vertex(p: Point, tag: u32) -> Vertex {
    Vertex {
        position: Point2::new(p.x, p.y),
        tag,
    }
}

fn to_point(p: Point2<f64>) -> Point {
    Point::new(p.x, p.y)
}

/// The cells of the prepared sites, one per input site.
fn voronoi_cells(prepared: &Prepared, domain: &Domain) -> Vec<Cell> {
    let mut box_ = domain.bounds;
    for &i in &prepared.owners {
        box_ = box_.union_pt(prepared.points[i]);
    }
    let centre = box_.center();
    let half = 0.5 * box_.width().max(box_.height()) + 1.0;
    let mut vertices: Vec<Vertex> = prepared
        .owners
        .iter()
        .map(|&i| vertex(prepared.points[i], i as u32))
        .collect();
    for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        let g = centre + Vec2::new(sx, sy) * (GHOST_FACTOR * half);
        vertices.push(vertex(g, NO_SITE));
    }
    let dt: DelaunayTriangulation<Vertex> =
        DelaunayTriangulation::bulk_load(vertices).expect("coordinates were validated");

    // One circumcentre per face, shared by the cells around it, so that
    // neighbouring cells have exactly the same vertices.
    let mut centres = vec![Point::ZERO; dt.num_all_faces()];
    for face in dt.inner_faces() {
        let [a, b, c] = face.positions().map(to_point);
        centres[face.fix().index()] = circumcentre(a, b, c);
    }

    let mut cells = vec![Cell::default(); prepared.points.len()];
    let mut polygon: Vec<Point> = Vec::new();
    for v in dt.vertices() {
        let tag = v.data().tag;
        if tag == NO_SITE {
            continue;
        }
        polygon.clear();
        // Out-edges turn anticlockwise (spade's y-up sense: positive area);
        // the face left of each is the next corner of the cell.
        let mut closed = true;
        for e in v.out_edges() {
            let face = e.face();
            // The ghosts enclose every real site, so this does not happen.
            closed &= !face.is_outer();
            let c = centres[face.fix().index()];
            if polygon.last() != Some(&c) {
                polygon.push(c);
            }
        }
        if polygon.len() > 1 && polygon.first() == polygon.last() {
            polygon.pop();
        }
        // Sites on one circle (a ring of a rose window with nothing inside
        // it) share a circumcentre, computed a hair apart for each face:
        // the corners there turn any way, and a side whose direction is
        // noise would cut the cell away. The cell is convex in exact
        // arithmetic, so its hull is the cell.
        if !is_convex(&polygon) {
            polygon = convex_hull(&polygon);
        }
        if closed && polygon.len() >= 3 {
            cells[tag as usize] = Cell {
                contours: domain.clip_convex(&polygon),
            };
        }
    }
    cells
}

/// Whether every corner of `polygon` turns left (anticlockwise, positive
/// area).
fn is_convex(polygon: &[Point]) -> bool {
    let n = polygon.len();
    (0..n).all(|k| {
        let (a, b, c) = (polygon[k], polygon[(k + 1) % n], polygon[(k + 2) % n]);
        (b - a).cross(c - b) > 0.0
    })
}

/// The convex hull of `points`, anticlockwise (Andrew's monotone chain),
/// without collinear corners.
fn convex_hull(points: &[Point]) -> Vec<Point> {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    sorted.dedup();
    if sorted.len() < 3 {
        return sorted;
    }
    let mut hull: Vec<Point> = Vec::with_capacity(2 * sorted.len());
    for pass in [
        &sorted[..],
        &sorted.iter().rev().copied().collect::<Vec<_>>()[..],
    ] {
        let floor = hull.len();
        for &p in pass {
            while hull.len() >= floor + 2 {
                let (a, b) = (hull[hull.len() - 2], hull[hull.len() - 1]);
                if (b - a).cross(p - b) > 0.0 {
                    break;
                }
                hull.pop();
            }
            hull.push(p);
        }
        // Each chain's last point starts the other.
        hull.pop();
    }
    hull
}

/// The circumcentre of a triangle, computed relative to its first corner
/// for accuracy; the vertex mean if the triangle is flat in floating point.
fn circumcentre(a: Point, b: Point, c: Point) -> Point {
    let (b, c) = (b - a, c - a);
    let d = 2.0 * (b.x * c.y - b.y * c.x);
    let (bb, cc) = (b.hypot2(), c.hypot2());
    let u = Vec2::new(c.y * bb - b.y * cc, b.x * cc - c.x * bb) / d;
    if d == 0.0 || !u.is_finite() {
        return a + (b + c) / 3.0;
    }
    a + u
}

// ---------------------------------------------------------------------------
// Delaunay edges.

/// The edges of the Delaunay triangulation of the sites that lie in the
/// region, as pairs of site indices `[i, j]` (`i < j`, into `sites`),
/// sorted.
///
/// This is the *unconstrained* triangulation of the sites (merged and
/// dropped sites take no part), restricted to the region: an edge is kept
/// when its middle is inside and it crosses the flattened outline nowhere.
/// In a convex region holding all sites that is the whole triangulation;
/// in a concave one or one with holes, edges across bays and holes are
/// gone (edges that only graze the outline at a vertex may go either way).
/// For a triangulation that also follows the outline, see
/// [`constrained_delaunay`].
///
/// # Errors
/// As [`Diagram::new`].
pub fn delaunay_edges(
    sites: &[Point],
    domain: &Domain,
    options: &CellOptions,
) -> Result<Vec<[usize; 2]>> {
    let prepared = Prepared::new(sites, domain, options)?;
    guard("triangulating sites", || {
        let vertices: Vec<Vertex> = prepared
            .owners
            .iter()
            .map(|&i| vertex(prepared.points[i], i as u32))
            .collect();
        let dt: DelaunayTriangulation<Vertex> =
            DelaunayTriangulation::bulk_load(vertices).expect("coordinates were validated");
        let mut out: Vec<[usize; 2]> = dt
            .undirected_edges()
            .filter_map(|e| {
                let [a, b] = e.vertices();
                let (pa, pb) = (to_point(a.position()), to_point(b.position()));
                domain.holds_segment(pa, pb).then(|| {
                    let (i, j) = (a.data().tag as usize, b.data().tag as usize);
                    [i.min(j), i.max(j)]
                })
            })
            .collect();
        out.sort_unstable();
        out
    })
}

/// A constrained Delaunay triangulation of the sites and the region's
/// flattened outline, cut to the region.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ConstrainedDelaunay {
    /// Edges between two sites, as sorted pairs of site indices `[i, j]`
    /// (`i < j`).
    pub between_sites: Vec<[usize; 2]>,
    /// Edges from a site to a vertex of the outline, and diagonals between
    /// outline vertices.
    pub to_outline: Vec<Line>,
    /// Edges of the flattened outline (pieces of it, where a site lies on
    /// it).
    pub outline: Vec<Line>,
    /// The triangles inside the region; together they cover it.
    pub triangles: Vec<[Point; 3]>,
}

/// The constrained Delaunay triangulation of the sites (merged and dropped
/// ones take no part) together with the vertices of the region's flattened
/// outline, whose edges are constraints: no edge crosses the outline. Only
/// triangles whose centroid lies in the region are kept (the hull of the
/// vertices also holds triangles in bays and holes), and the edges come out
/// sorted into three kinds (see [`ConstrainedDelaunay`]).
///
/// Near the outline the sites connect to outline vertices rather than to
/// one another, so `between_sites` has fewer edges there than
/// [`delaunay_edges`]; together with `to_outline` and `outline` the edges
/// are a triangulation of the region.
///
/// # Errors
/// As [`Diagram::new`].
pub fn constrained_delaunay(
    sites: &[Point],
    domain: &Domain,
    options: &CellOptions,
) -> Result<ConstrainedDelaunay> {
    let prepared = Prepared::new(sites, domain, options)?;
    guard("triangulating sites and outline", || {
        let mut vertices: Vec<Vertex> = prepared
            .owners
            .iter()
            .map(|&i| vertex(prepared.points[i], i as u32))
            .collect();
        let mut constraints: Vec<[usize; 2]> = Vec::new();
        for c in &domain.polygons {
            let first = vertices.len();
            vertices.extend(c.iter().map(|&p| vertex(p, NO_SITE)));
            for k in 0..c.len() {
                constraints.push([first + k, first + (k + 1) % c.len()]);
            }
        }
        // Overlapping constraints (outline contours touching along an edge
        // after flattening) are skipped rather than fatal.
        let cdt: ConstrainedDelaunayTriangulation<Vertex> =
            ConstrainedDelaunayTriangulation::try_bulk_load_cdt(vertices, constraints, |_| {})
                .expect("coordinates were validated");
        let mut out = ConstrainedDelaunay::default();
        let mut done = vec![false; cdt.num_undirected_edges()];
        for face in cdt.inner_faces() {
            let [a, b, c] = face.positions().map(to_point);
            let centroid = ((a.to_vec2() + b.to_vec2() + c.to_vec2()) / 3.0).to_point();
            if !domain.contains(centroid) {
                continue;
            }
            out.triangles.push([a, b, c]);
            for e in face.adjacent_edges() {
                let u = e.as_undirected();
                if std::mem::replace(&mut done[u.fix().index()], true) {
                    continue;
                }
                let [from, to] = e.vertices();
                let (i, j) = (from.data().tag, to.data().tag);
                let line = Line::new(to_point(from.position()), to_point(to.position()));
                if cdt.is_constraint_edge(u.fix()) {
                    out.outline.push(line);
                } else if i != NO_SITE && j != NO_SITE {
                    let (i, j) = (i as usize, j as usize);
                    out.between_sites.push([i.min(j), i.max(j)]);
                } else {
                    out.to_outline.push(line);
                }
            }
        }
        out.between_sites.sort_unstable();
        out
    })
}

// ---------------------------------------------------------------------------
// Small polygon helpers.

/// Twice the cross product `(b − a) × (p − a)`: positive when `p` is left
/// of `a → b` in y-up terms (anticlockwise).
fn cross(a: Point, b: Point, p: Point) -> f64 {
    (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)
}

/// Signed area of a closed polygon (positive: clockwise on the page).
fn shoelace(c: &[Point]) -> f64 {
    let mut s = 0.0;
    for (k, a) in c.iter().enumerate() {
        let b = c[(k + 1) % c.len()];
        s += a.x * b.y - b.x * a.y;
    }
    s / 2.0
}

fn shoelace_arr(c: &[[f64; 2]]) -> f64 {
    let mut s = 0.0;
    for (k, a) in c.iter().enumerate() {
        let b = c[(k + 1) % c.len()];
        s += a[0] * b[1] - b[0] * a[1];
    }
    s / 2.0
}

fn bbox(c: &[Point]) -> Option<Rect> {
    let first = *c.first()?;
    Some(
        c.iter()
            .fold(Rect::from_points(first, first), |r, &p| r.union_pt(p)),
    )
}

fn bbox_arr(c: &[[f64; 2]]) -> Option<Rect> {
    let f = c.first()?;
    let first = Point::new(f[0], f[1]);
    Some(c.iter().fold(Rect::from_points(first, first), |r, p| {
        r.union_pt(Point::new(p[0], p[1]))
    }))
}

/// Whether the segment meets the (closed) rectangle.
fn segment_meets_rect(a: Point, b: Point, r: Rect) -> bool {
    if !Rect::from_points(a, b).overlaps(r) {
        return false;
    }
    let corners = [
        Point::new(r.x0, r.y0),
        Point::new(r.x1, r.y0),
        Point::new(r.x1, r.y1),
        Point::new(r.x0, r.y1),
    ];
    let sides = corners.map(|c| cross(a, b, c));
    !(sides.iter().all(|&s| s > 0.0) || sides.iter().all(|&s| s < 0.0))
}

/// Whether the segment comes within about `eps` of a convex polygon with
/// positive area (separating axes: the polygon's edge normals and the
/// segment's normal; in doubt, "yes").
fn segment_meets_convex(a: Point, b: Point, poly: &[Point], eps: f64) -> bool {
    for (k, &p) in poly.iter().enumerate() {
        let q = poly[(k + 1) % poly.len()];
        let margin = eps * p.distance(q);
        // Outside this edge's half-plane: right of p → q.
        if cross(p, q, a) < -margin && cross(p, q, b) < -margin {
            return false;
        }
    }
    let margin = eps * a.distance(b);
    let sides = poly.iter().map(|&v| cross(a, b, v));
    let (mut left, mut right) = (true, true);
    for s in sides {
        left &= s > margin;
        right &= s < -margin;
    }
    !(left || right)
}

/// Whether two segments cross at a single point inside both (strictly on
/// both sides of each other).
fn segments_cross_properly(a: Point, b: Point, p: Point, q: Point) -> bool {
    let (d1, d2) = (cross(p, q, a), cross(p, q, b));
    let (d3, d4) = (cross(a, b, p), cross(a, b, q));
    ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
}

/// A convex polygon cut to a rectangle (Sutherland–Hodgman: exact for a
/// convex subject; the cut points are put exactly on the rectangle).
fn clip_to_rect(poly: &[Point], r: Rect) -> Vec<Point> {
    let mut out: Vec<Point> = poly.to_vec();
    // Each side: whether it is vertical (a limit on x), the limit, and
    // whether the inside lies below it.
    for (vertical, limit, below) in [
        (true, r.x0, false),
        (true, r.x1, true),
        (false, r.y0, false),
        (false, r.y1, true),
    ] {
        let input = std::mem::take(&mut out);
        let coord = |p: Point| if vertical { p.x } else { p.y };
        let inside = |p: Point| {
            if below {
                coord(p) <= limit
            } else {
                coord(p) >= limit
            }
        };
        for (k, &p) in input.iter().enumerate() {
            let q = input[(k + 1) % input.len()];
            let (ip, iq) = (inside(p), inside(q));
            if ip {
                out.push(p);
            }
            if ip != iq {
                let t = (limit - coord(p)) / (coord(q) - coord(p));
                let mut x = p.lerp(q, t);
                if vertical {
                    x.x = limit;
                } else {
                    x.y = limit;
                }
                out.push(x);
            }
        }
        if out.is_empty() {
            break;
        }
    }
    out
}

/// i_overlay shapes as cell contours: each outer contour (made positive)
/// followed by its holes (made negative); slivers dropped, an outer contour
/// with its holes.
fn contours_from_shapes(shapes: &[Vec<Vec<[f64; 2]>>]) -> Vec<Vec<Point>> {
    let mut out = Vec::new();
    for shape in shapes {
        for (k, contour) in shape.iter().enumerate() {
            if contour.len() < 3 {
                continue;
            }
            let mut c: Vec<Point> = contour.iter().map(|p| Point::new(p[0], p[1])).collect();
            let area = shoelace(&c);
            let perimeter: f64 = (0..c.len())
                .map(|i| c[i].distance(c[(i + 1) % c.len()]))
                .sum();
            if area == 0.0 || 2.0 * area.abs() < SLIVER_WIDTH * perimeter {
                if k == 0 {
                    break;
                }
                continue;
            }
            if (area > 0.0) != (k == 0) {
                c.reverse();
            }
            out.push(c);
        }
    }
    out
}

#[cfg(test)]
mod tests;
