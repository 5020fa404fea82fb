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
//! [`weighted_lloyd_step`] one step of relaxation.
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
//!   owner moves.
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
use std::panic::AssertUnwindSafe;

use i_overlay::core::fill_rule::FillRule as IFill;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::float::single::SingleFloatOverlay;
use i_overlay::float::slice::FloatSlice;
use kurbo::{BezPath, Line, Point, Rect, Vec2};
use spade::{
    ConstrainedDelaunayTriangulation, DelaunayTriangulation, HasPosition, Point2, Triangulation,
};

use super::polylabel::pole_of_inaccessibility;
use super::region::{Region, SLIVER_WIDTH};
use super::TOLERANCE;
use crate::error::{Error, Result};
use crate::units::MAX_COORD;

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
}

impl CellOptions {
    /// One million sites, outside sites kept, 2 subdivisions (12 density
    /// samples per fan triangle).
    pub const DEFAULT: CellOptions = CellOptions {
        max_sites: 1_000_000,
        outside: OutsideSites::Keep,
        density_subdivisions: 2,
    };

    /// With another cap on the number of sites.
    pub fn with_max_sites(self, max_sites: usize) -> CellOptions {
        CellOptions { max_sites, ..self }
    }

    /// With another policy for sites outside the region.
    pub fn with_outside(self, outside: OutsideSites) -> CellOptions {
        CellOptions { outside, ..self }
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
        let cut = std::panic::catch_unwind(AssertUnwindSafe(|| {
            subject.slice_by(&lines, IFill::NonZero)
        }));
        let Ok(shapes) = cut else {
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
        // Near-duplicates: owners hashed by their MERGE_DISTANCE square (a
        // list per square, chained through `next`), looked up only, never
        // iterated, so the outcome depends on the input order alone.
        let mut heads: HashMap<(i64, i64), u32, BuildHasherDefault<SquareHasher>> =
            HashMap::with_capacity_and_hasher(points.len(), Default::default());
        let mut next = vec![u32::MAX; points.len()];
        let key = |p: Point| {
            (
                (p.x / MERGE_DISTANCE).floor() as i64,
                (p.y / MERGE_DISTANCE).floor() as i64,
            )
        };
        let mut owners = Vec::with_capacity(sites.len());
        for (i, &p) in points.iter().enumerate() {
            if status[i] == SiteStatus::Dropped {
                continue;
            }
            let (kx, ky) = key(p);
            let mut owner = None;
            'search: for dx in -1..=1 {
                for dy in -1..=1 {
                    let mut j = heads.get(&(kx + dx, ky + dy)).copied().unwrap_or(u32::MAX);
                    while j != u32::MAX {
                        if points[j as usize].distance(p) < MERGE_DISTANCE {
                            owner = Some(j as usize);
                            break 'search;
                        }
                        j = next[j as usize];
                    }
                }
            }
            match owner {
                Some(j) => status[i] = SiteStatus::MergedInto(j),
                None => {
                    let head = heads.entry((kx, ky)).or_insert(u32::MAX);
                    next[i] = *head;
                    *head = i as u32;
                    owners.push(i);
                }
            }
        }
        Ok(Prepared {
            status,
            owners,
            points,
        })
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
    std::panic::catch_unwind(AssertUnwindSafe(f)).map_err(|_| Error::Geometry {
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
        if closed && polygon.len() >= 3 {
            cells[tag as usize] = Cell {
                contours: domain.clip_convex(&polygon),
            };
        }
    }
    cells
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
// Lloyd relaxation.

/// The outcome of one Lloyd step.
#[derive(Debug, Clone, PartialEq)]
pub struct LloydStep {
    /// The moved sites, in input order.
    pub sites: Vec<Point>,
    /// The centroidal energy of the *input* sites, `Σᵢ ∫_{cellᵢ} ρ(x)·|x −
    /// siteᵢ|² dx` (mm⁴ times density; ρ = 1 for [`lloyd_step`]). It never
    /// increases from one step to the next, and falls as the sites
    /// converge: the figure to report.
    pub energy: f64,
    /// Mean distance (mm) the sites moved, over all input sites.
    pub mean_movement: f64,
    /// Largest distance (mm) a site moved.
    pub max_movement: f64,
}

/// One step of Lloyd relaxation: each site moves to the area centroid of
/// its cell clipped to the region (for a cell of several pieces, the
/// area-weighted centroid of all of them).
///
/// Where that centroid falls outside the region (a cell cut by a bay or a
/// hole), the site goes to whichever of the largest piece's centroid, that
/// piece's pole of inaccessibility and the site's old place lies inside and
/// nearest to the centroid, which keeps the energy from rising. Sites with
/// an empty cell (merged, dropped, or outside sites whose cell misses the
/// region) stay where they are.
///
/// # Errors
/// As [`Diagram::new`].
pub fn lloyd_step(sites: &[Point], domain: &Domain, options: &CellOptions) -> Result<LloydStep> {
    relax(sites, domain, options, None)
}

/// One step of density-weighted Lloyd relaxation (weighted Voronoi
/// stippling, Secord 2002): each site moves to the centroid of its cell
/// weighted by `density`, `∫ρx / ∫ρ`.
///
/// The integrals are taken over a fan of triangles per contour, each cut
/// into `n²` triangles (`n` = [`CellOptions::density_subdivisions`]) with
/// `density` sampled at three interior points of each (a rule exact for
/// quadratic functions): linear in the number of cells. Negative or
/// non-finite density values count as 0. A site whose cell has no mass
/// stays where it is: nothing pulls it anywhere, and moving it to its
/// cell's area centroid would walk it out into the blank parts (a white
/// margin of an image) step by step. A centroid outside the region is
/// handled as in [`lloyd_step`].
///
/// # Errors
/// As [`Diagram::new`].
pub fn weighted_lloyd_step(
    sites: &[Point],
    domain: &Domain,
    options: &CellOptions,
    density: &dyn Fn(Point) -> f64,
) -> Result<LloydStep> {
    relax(sites, domain, options, Some(density))
}

fn relax(
    sites: &[Point],
    domain: &Domain,
    options: &CellOptions,
    density: Option<&dyn Fn(Point) -> f64>,
) -> Result<LloydStep> {
    let diagram = Diagram::new(sites, domain, options)?;
    let n = options.density_subdivisions.max(1);
    let mut moved = sites.to_vec();
    let (mut energy, mut total, mut max) = (0.0, 0.0, 0.0f64);
    for (i, cell) in diagram.cells.iter().enumerate() {
        if cell.is_empty() {
            continue;
        }
        let site = sites[i];
        let origin = site.to_vec2();
        let area_moments = Moments::of(&cell.contours, origin);
        let (moments, target) = match density {
            None => (area_moments, area_moments.centroid(origin)),
            Some(rho) => {
                let m = Moments::weighted(&cell.contours, origin, rho, n);
                (m, m.centroid(origin))
            }
        };
        energy += moments.second;
        let Some(c) = target else { continue };
        let next = settle(c, site, cell, domain);
        let d = next.distance(site);
        moved[i] = next;
        total += d;
        max = max.max(d);
    }
    Ok(LloydStep {
        sites: moved,
        energy,
        mean_movement: total / sites.len() as f64,
        max_movement: max,
    })
}

/// Where a site whose cell has centroid `c` goes: `c` if inside the region,
/// else the candidate inside nearest to `c`. For a fixed cell the energy of
/// a site at `p` is the energy at the centroid plus mass × |p − c|², so the
/// nearest candidate is the best, and the old site is always a candidate.
fn settle(c: Point, site: Point, cell: &Cell, domain: &Domain) -> Point {
    if domain.contains(c) {
        return c;
    }
    let mut candidates = vec![site];
    if let Some(largest) = cell.pieces().max_by(|a, b| {
        let area = |p: &[Vec<Point>]| p.iter().map(|c| shoelace(c)).sum::<f64>();
        area(a).total_cmp(&area(b))
    }) {
        let origin = largest[0][0].to_vec2();
        if let Some(pc) = Moments::of(largest, origin).centroid(origin) {
            candidates.push(pc);
        }
        let piece = Cell {
            contours: largest.to_vec(),
        };
        if let Some((pole, _)) = pole_of_inaccessibility(&piece.to_region(), domain.tolerance) {
            candidates.push(pole);
        }
    }
    candidates
        .into_iter()
        .filter(|&p| domain.contains(p))
        .min_by(|a, b| a.distance_squared(c).total_cmp(&b.distance_squared(c)))
        .unwrap_or(site)
}

/// Mass, first and second moments of a set of contours about `origin`.
#[derive(Debug, Clone, Copy, Default)]
struct Moments {
    /// ∫ρ
    mass: f64,
    /// ∫ρ(x − origin)
    first: Vec2,
    /// ∫ρ|x − origin|²
    second: f64,
}

impl Moments {
    /// Exact moments of the polygons (ρ = 1), by Green's theorem.
    fn of(contours: &[Vec<Point>], origin: Vec2) -> Moments {
        let mut m = Moments::default();
        for c in contours {
            for (k, p) in c.iter().enumerate() {
                let a = p.to_vec2() - origin;
                let b = c[(k + 1) % c.len()].to_vec2() - origin;
                let w = a.cross(b);
                m.mass += w / 2.0;
                m.first += (a + b) * (w / 6.0);
                m.second += w
                    * (a.x * a.x + a.x * b.x + b.x * b.x + a.y * a.y + a.y * b.y + b.y * b.y)
                    / 12.0;
            }
        }
        m
    }

    /// Moments weighted by `rho`: a fan of signed triangles per contour
    /// (right for any simple contour and for holes: the signed parts cancel
    /// where they overlap), each cut into n² triangles sampled at three
    /// points.
    fn weighted(
        contours: &[Vec<Point>],
        origin: Vec2,
        rho: &dyn Fn(Point) -> f64,
        n: u32,
    ) -> Moments {
        let mut m = Moments::default();
        let step = 1.0 / n as f64;
        let mut sample = |d: Vec2, area: f64| {
            let r = rho((origin + d).to_point());
            let r = if r.is_finite() && r > 0.0 { r } else { 0.0 };
            let w = r * area / 3.0;
            m.mass += w;
            m.first += d * w;
            m.second += w * d.hypot2();
        };
        for c in contours {
            let apex = c[0].to_vec2() - origin;
            for k in 1..c.len().saturating_sub(1) {
                let (u, v) = (c[k] - c[0], c[k + 1] - c[0]);
                let area = u.cross(v) / 2.0 * step * step;
                // The barycentric grid in steps of 1/n: "up" triangles with
                // corners (i, j), (i+1, j), (i, j+1), and "down" ones with
                // (i+1, j), (i+1, j+1), (i, j+1).
                let at = |i: u32, j: u32| apex + u * (i as f64 * step) + v * (j as f64 * step);
                for i in 0..n {
                    for j in 0..n - i {
                        for q in quadrature_points([at(i, j), at(i + 1, j), at(i, j + 1)]) {
                            sample(q, area);
                        }
                        if i + j + 1 < n {
                            let down = [at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                            for q in quadrature_points(down) {
                                sample(q, area);
                            }
                        }
                    }
                }
            }
        }
        m
    }

    fn centroid(&self, origin: Vec2) -> Option<Point> {
        let c = origin + self.first / self.mass;
        (self.mass > 0.0 && c.is_finite()).then_some(c.to_point())
    }
}

/// The three points of the degree-2 rule on a triangle (barycentric
/// (2/3, 1/6, 1/6) and its permutations, equal weights).
fn quadrature_points([a, b, c]: [Vec2; 3]) -> [Vec2; 3] {
    let p = |x: Vec2, y: Vec2, z: Vec2| x * (2.0 / 3.0) + (y + z) * (1.0 / 6.0);
    [p(a, b, c), p(b, c, a), p(c, a, b)]
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
mod tests {
    use super::*;
    use crate::geom::region::FillRule;
    use crate::rng::Seed;
    use kurbo::{Circle, Shape};
    use proptest::prelude::*;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Region {
        Region::from_rect(Rect::new(x0, y0, x1, y1)).unwrap()
    }

    fn polygon_region(points: &[(f64, f64)]) -> Region {
        let points: Vec<Point> = points.iter().map(|&p| p.into()).collect();
        Region::polygon(&points).unwrap()
    }

    /// An L: the 10×10 square without its top-right 5×5 quarter (y down).
    fn l_shape() -> Region {
        polygon_region(&[
            (0.0, 0.0),
            (5.0, 0.0),
            (5.0, 5.0),
            (10.0, 5.0),
            (10.0, 10.0),
            (0.0, 10.0),
        ])
    }

    /// The 10×10 square with a 4×4 square hole in the middle: area 84.
    fn square_with_hole() -> Region {
        rect(0.0, 0.0, 10.0, 10.0).difference(&rect(3.0, 3.0, 7.0, 7.0))
    }

    fn circle(x: f64, y: f64, r: f64) -> Region {
        Region::new(Circle::new((x, y), r).to_path(1e-9), FillRule::NonZero).unwrap()
    }

    /// `n` random points inside `domain`, by rejection in its bounds.
    fn random_sites(domain: &Domain, n: usize, seed: u64) -> Vec<Point> {
        let b = domain.bounds();
        let mut s = Seed(seed).stream();
        let mut out = Vec::with_capacity(n);
        while out.len() < n {
            let p = Point::new(s.range(b.x0, b.x1), s.range(b.y0, b.y1));
            if domain.contains(p) {
                out.push(p);
            }
        }
        out
    }

    fn domain(region: &Region) -> Domain {
        Domain::new(region, TOLERANCE).unwrap()
    }

    fn diagram(sites: &[Point], d: &Domain) -> Diagram {
        Diagram::new(sites, d, &CellOptions::DEFAULT).unwrap()
    }

    fn total_area(d: &Diagram) -> f64 {
        d.cells().iter().map(Cell::area).sum()
    }

    fn distance_to_outline(d: &Domain, p: Point) -> f64 {
        d.edges
            .iter()
            .map(|&[a, b]| {
                let ab = b - a;
                let t = ((p - a).dot(ab) / ab.hypot2()).clamp(0.0, 1.0);
                p.distance(a + ab * t)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Winding of a set of contours around `p` (by kurbo on the path).
    fn cell_contains(cell: &Cell, p: Point) -> bool {
        cell.to_path().winding(p) != 0
    }

    /// The invariants every diagram must keep: cells tile the domain, lie
    /// in it, and contain their own (inside) sites.
    fn check_tiling(d: &Domain, diagram: &Diagram) {
        let total = total_area(diagram);
        assert!(
            (total - d.area()).abs() <= 1e-6 * d.area(),
            "cells cover {total}, the region {}",
            d.area()
        );
        for (i, cell) in diagram.cells().iter().enumerate() {
            assert!(cell.area() >= 0.0);
            for c in cell.contours() {
                for &v in c {
                    assert!(
                        d.contains(v) || distance_to_outline(d, v) < 1e-6,
                        "cell {i} has a vertex {v:?} outside the region"
                    );
                }
            }
            let site = diagram.sites()[i];
            if diagram.status()[i] == SiteStatus::Own
                && d.contains(site)
                && distance_to_outline(d, site) > 1e-6
            {
                assert!(
                    cell_contains(cell, site),
                    "cell {i} misses its site {site:?}"
                );
            }
        }
    }

    /// No overlaps: the area of the union of the cells is their sum.
    fn check_no_overlap(diagram: &Diagram) {
        let regions: Vec<Region> = diagram.cells().iter().map(Cell::to_region).collect();
        let union = Region::union_all(&regions).area();
        let total = total_area(diagram);
        assert!(
            (union - total).abs() <= 1e-6 * total,
            "union {union} vs sum {total}: cells overlap"
        );
    }

    #[test]
    fn cells_tile_a_square() {
        let d = domain(&rect(0.0, 0.0, 10.0, 10.0));
        let sites = random_sites(&d, 50, 1);
        let v = diagram(&sites, &d);
        assert!((total_area(&v) - 100.0).abs() < 1e-6 * 100.0);
        check_tiling(&d, &v);
        check_no_overlap(&v);
    }

    #[test]
    fn cells_tile_a_concave_l() {
        let d = domain(&l_shape());
        assert!((d.area() - 75.0).abs() < 1e-12);
        let sites = random_sites(&d, 40, 2);
        let v = diagram(&sites, &d);
        check_tiling(&d, &v);
        check_no_overlap(&v);
        // The bay is left empty: no cell reaches into the missing quarter.
        for cell in v.cells() {
            for c in cell.contours() {
                for p in c {
                    assert!(!(p.x > 5.0 + 1e-9 && p.y < 5.0 - 1e-9), "{p:?} in the bay");
                }
            }
        }
    }

    #[test]
    fn cells_do_not_cover_a_hole() {
        // geo's VoronoiClip gives 100 here: it skips clipping cells whose
        // box lies inside the region's box, filling the hole.
        let d = domain(&square_with_hole());
        assert!((d.area() - 84.0).abs() < 1e-12);
        let sites = random_sites(&d, 30, 3);
        let v = diagram(&sites, &d);
        assert!(
            (total_area(&v) - 84.0).abs() < 1e-6 * 84.0,
            "{}",
            total_area(&v)
        );
        check_tiling(&d, &v);
        check_no_overlap(&v);
        // Nothing of any cell inside the hole.
        let hole = rect(3.0, 3.0, 7.0, 7.0);
        for cell in v.cells() {
            assert!(cell.to_region().intersection(&hole).area() < 1e-9);
        }
    }

    #[test]
    fn a_cell_around_a_hole_keeps_it_as_a_hole() {
        // One site: its cell is the whole square, the hole a hole in it.
        let d = domain(&square_with_hole());
        let v = diagram(&[Point::new(1.0, 1.0)], &d);
        assert_eq!(v.cells()[0].contours().len(), 2);
        assert!((v.cells()[0].area() - 84.0).abs() < 1e-9);
        assert_eq!(v.cells()[0].piece_count(), 1);
    }

    #[test]
    fn a_concave_region_can_cut_a_cell_in_two() {
        // A U: two arms joined at the bottom. A site in the middle of the
        // gap, above the base, owns the top of both arms.
        let u = polygon_region(&[
            (0.0, 0.0),
            (3.0, 0.0),
            (3.0, 7.0),
            (7.0, 7.0),
            (7.0, 0.0),
            (10.0, 0.0),
            (10.0, 10.0),
            (0.0, 10.0),
        ]);
        let d = domain(&u);
        let sites = [Point::new(5.0, 0.5), Point::new(5.0, 9.0)];
        let v = Diagram::new(&sites, &d, &CellOptions::DEFAULT).unwrap();
        assert_eq!(v.cells()[0].piece_count(), 2);
        check_tiling(&d, &v);
        // Its centroid is in the gap, outside the region: Lloyd moves the
        // site elsewhere, inside.
        let step = lloyd_step(&sites, &d, &CellOptions::DEFAULT).unwrap();
        assert!(d.contains(step.sites[0]));
    }

    #[test]
    fn cells_tile_a_region_with_round_holes_and_many_tiles() {
        let region = rect(0.0, 0.0, 60.0, 40.0)
            .difference(&circle(20.0, 20.0, 8.0))
            .difference(&circle(42.0, 18.0, 6.0));
        let d = domain(&region);
        assert!(d.grid.nx * d.grid.ny > 1, "the test wants several tiles");
        assert!(d.pieces.len() > 1, "the region was not cut into pieces");
        let sites = random_sites(&d, 2000, 4);
        let v = diagram(&sites, &d);
        check_tiling(&d, &v);
    }

    /// A wavy disc: `n` vertices on a circle of radius `r` modulated by
    /// `waves` bumps, with a wavy hole.
    fn wavy(n: usize, r: f64, waves: f64) -> Region {
        let ring = |scale: f64, reverse: bool| -> Vec<(f64, f64)> {
            let mut pts: Vec<(f64, f64)> = (0..n)
                .map(|i| {
                    let a = std::f64::consts::TAU * i as f64 / n as f64;
                    let rr = scale * r * (1.0 + 0.08 * (waves * a).sin());
                    (100.0 + rr * a.cos(), 100.0 + rr * a.sin())
                })
                .collect();
            if reverse {
                pts.reverse();
            }
            pts
        };
        let mut path = BezPath::new();
        for pts in [ring(1.0, false), ring(0.3, true)] {
            path.move_to(pts[0]);
            for &p in &pts[1..] {
                path.line_to(p);
            }
            path.close_path();
        }
        Region::new(path, FillRule::NonZero).unwrap()
    }

    #[test]
    fn cells_tile_a_detailed_outline() {
        // 6 000 outline edges: a 78×78 grid of tiles, and cells clipped
        // against the pieces near them only.
        let d = domain(&wavy(3000, 90.0, 150.0));
        assert!(d.grid.nx > 50 && d.pieces.len() > 1000);
        let sites = random_sites(&d, 3000, 17);
        let v = diagram(&sites, &d);
        check_tiling(&d, &v);
        // A few huge cells, each spanning hundreds of tiles: clipped against
        // the whole region instead of its pieces.
        let v = diagram(&sites[..5], &d);
        check_tiling(&d, &v);
    }

    #[test]
    fn pieces_add_up_to_the_region() {
        let region = rect(0.0, 0.0, 50.0, 50.0).difference(&circle(25.0, 25.0, 10.0));
        let d = domain(&region);
        let total: f64 = d.pieces.iter().flatten().map(|c| shoelace_arr(c)).sum();
        assert!((total - d.area()).abs() < 1e-6 * d.area());
    }

    #[test]
    fn domain_contains_agrees_with_the_polygons() {
        let d = domain(&square_with_hole());
        let path = {
            let mut p = BezPath::new();
            for c in d.polygons() {
                p.move_to(c[0]);
                for &q in &c[1..] {
                    p.line_to(q);
                }
                p.close_path();
            }
            p
        };
        let mut s = Seed(5).stream();
        for _ in 0..2000 {
            let p = Point::new(s.range(-2.0, 12.0), s.range(-2.0, 12.0));
            assert_eq!(d.contains(p), path.winding(p) != 0, "{p:?}");
        }
    }

    #[test]
    fn one_cell_per_distinct_site() {
        let d = domain(&rect(0.0, 0.0, 10.0, 10.0));
        let mut sites = random_sites(&d, 20, 6);
        sites.push(sites[3]); // exact duplicate
        sites.push(sites[7] + Vec2::new(1e-8, -1e-8)); // near-duplicate
        sites.push(sites[7] + Vec2::new(1e-3, 0.0)); // distinct, close
        let v = diagram(&sites, &d);
        assert_eq!(v.status()[20], SiteStatus::MergedInto(3));
        assert_eq!(v.status()[21], SiteStatus::MergedInto(7));
        assert_eq!(v.status()[22], SiteStatus::Own);
        assert!(v.cells()[20].is_empty() && v.cells()[21].is_empty());
        let non_empty = v.cells().iter().filter(|c| !c.is_empty()).count();
        assert_eq!(non_empty, 21);
        check_tiling(&d, &v);
    }

    #[test]
    fn outside_sites_kept_dropped_or_rejected() {
        let d = domain(&l_shape());
        let sites = [
            Point::new(2.0, 2.0),
            Point::new(8.0, 4.0), // in the bay, outside
            Point::new(8.0, 8.0),
            Point::new(30.0, 30.0), // far outside
        ];
        let keep = diagram(&sites, &d);
        check_tiling(&d, &keep);
        assert!(!keep.cells()[1].is_empty(), "its cell reaches into the L");
        assert!(keep.cells()[3].is_empty());
        let drop_opts = CellOptions::DEFAULT.with_outside(OutsideSites::Drop);
        let dropped = Diagram::new(&sites, &d, &drop_opts).unwrap();
        assert_eq!(dropped.status()[1], SiteStatus::Dropped);
        assert_eq!(dropped.status()[3], SiteStatus::Dropped);
        assert!(dropped.cells()[1].is_empty());
        check_tiling(&d, &dropped);
        let reject = CellOptions::DEFAULT.with_outside(OutsideSites::Reject);
        let err = Diagram::new(&sites, &d, &reject).unwrap_err();
        assert!(
            matches!(&err, Error::Invalid { field, .. } if field == "sites[1]"),
            "{err}"
        );
    }

    #[test]
    fn single_and_collinear_sites() {
        let d = domain(&l_shape());
        let one = diagram(&[Point::new(1.0, 9.0)], &d);
        assert!((one.cells()[0].area() - 75.0).abs() < 1e-9);
        let line: Vec<Point> = (0..10).map(|i| Point::new(0.5 + i as f64, 9.0)).collect();
        let v = diagram(&line, &d);
        check_tiling(&d, &v);
        check_no_overlap(&v);
    }

    #[test]
    fn deterministic() {
        let region = rect(0.0, 0.0, 30.0, 30.0).difference(&circle(15.0, 15.0, 5.0));
        let d = domain(&region);
        let sites = random_sites(&d, 500, 7);
        assert_eq!(diagram(&sites, &d), diagram(&sites, &domain(&region)));
        let opts = CellOptions::DEFAULT;
        assert_eq!(
            lloyd_step(&sites, &d, &opts).unwrap(),
            lloyd_step(&sites, &d, &opts).unwrap()
        );
        assert_eq!(
            constrained_delaunay(&sites, &d, &opts).unwrap(),
            constrained_delaunay(&sites, &d, &opts).unwrap()
        );
        assert_eq!(
            delaunay_edges(&sites, &d, &opts).unwrap(),
            delaunay_edges(&sites, &d, &opts).unwrap()
        );
    }

    /// The triangles of a set of edges: triples of sites joined pairwise
    /// with no site strictly inside (faces of a planar triangulation).
    fn faces(sites: &[Point], edges: &[[usize; 2]]) -> Vec<[usize; 3]> {
        let mut adjacent = vec![std::collections::BTreeSet::new(); sites.len()];
        for &[i, j] in edges {
            adjacent[i].insert(j);
            adjacent[j].insert(i);
        }
        let mut out = Vec::new();
        for &[i, j] in edges {
            for &k in adjacent[i].intersection(&adjacent[j]) {
                if k <= j {
                    continue;
                }
                let (a, b, c) = (sites[i], sites[j], sites[k]);
                let s = cross(a, b, c).signum();
                let strictly_inside = |p: Point| {
                    cross(a, b, p) * s > 0.0 && cross(b, c, p) * s > 0.0 && cross(c, a, p) * s > 0.0
                };
                if !sites.iter().any(|&p| strictly_inside(p)) {
                    out.push([i, j, k]);
                }
            }
        }
        out
    }

    fn empty_circumcircle(sites: &[Point], [a, b, c]: [Point; 3]) -> bool {
        let centre = circumcentre(a, b, c);
        let r = centre.distance(a);
        sites
            .iter()
            .all(|&p| p.distance(centre) >= r * (1.0 - 1e-9))
    }

    /// Hull size by Andrew's monotone chain (strict turns only).
    fn hull_size(points: &[Point]) -> usize {
        let mut p = points.to_vec();
        p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        let mut hull: Vec<Point> = Vec::new();
        for pass in 0..2 {
            let start = hull.len();
            let iter: Box<dyn Iterator<Item = &Point>> = if pass == 0 {
                Box::new(p.iter())
            } else {
                Box::new(p.iter().rev())
            };
            for &q in iter {
                while hull.len() >= start + 2
                    && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
                {
                    hull.pop();
                }
                hull.push(q);
            }
            hull.pop();
        }
        hull.len()
    }

    #[test]
    fn delaunay_edges_are_delaunay_in_a_square() {
        let d = domain(&rect(0.0, 0.0, 100.0, 100.0));
        let sites = random_sites(&d, 200, 8);
        let edges = delaunay_edges(&sites, &d, &CellOptions::DEFAULT).unwrap();
        let tris = faces(&sites, &edges);
        // A full triangulation of n points with h on the hull has 2n − 2 − h
        // triangles and 3n − 3 − h edges: nothing is missing.
        let h = hull_size(&sites);
        assert_eq!(tris.len(), 2 * sites.len() - 2 - h);
        assert_eq!(edges.len(), 3 * sites.len() - 3 - h);
        for t in tris {
            assert!(
                empty_circumcircle(&sites, t.map(|i| sites[i])),
                "a site inside the circumcircle of {t:?}"
            );
        }
        // The constrained one, in a convex region: triangles between sites
        // are Delaunay too, and all triangles cover the square.
        let cdt = constrained_delaunay(&sites, &d, &CellOptions::DEFAULT).unwrap();
        let area: f64 = cdt.triangles.iter().map(|t| shoelace(t).abs()).sum();
        assert!((area - 10_000.0).abs() < 1e-6);
        for t in faces(&sites, &cdt.between_sites) {
            assert!(empty_circumcircle(&sites, t.map(|i| sites[i])));
        }
    }

    /// Brute-force: the segment stays in the region (middle inside, no
    /// proper crossing with any edge of the flattened outline).
    fn segment_in_region(region: &Region, d: &Domain, a: Point, b: Point) -> bool {
        region.contains(a.midpoint(b))
            && !d
                .polygons()
                .iter()
                .flat_map(|c| (0..c.len()).map(move |k| (c[k], c[(k + 1) % c.len()])))
                .any(|(p, q)| segments_cross_properly(a, b, p, q))
    }

    #[test]
    fn delaunay_edges_stay_inside_an_l() {
        let region = l_shape();
        let d = domain(&region);
        let sites = random_sites(&d, 150, 9);
        let edges = delaunay_edges(&sites, &d, &CellOptions::DEFAULT).unwrap();
        assert!(edges.len() > 300);
        for &[i, j] in &edges {
            assert!(segment_in_region(&region, &d, sites[i], sites[j]));
        }
        // And the edges across the bay were there to be removed.
        let all = delaunay_edges(
            &sites,
            &domain(&rect(0.0, 0.0, 10.0, 10.0)),
            &CellOptions::DEFAULT,
        )
        .unwrap();
        assert!(all.len() > edges.len());
        let cdt = constrained_delaunay(&sites, &d, &CellOptions::DEFAULT).unwrap();
        for &[i, j] in &cdt.between_sites {
            assert!(segment_in_region(&region, &d, sites[i], sites[j]));
        }
        for l in cdt.to_outline.iter().chain(&cdt.outline) {
            assert!(!d
                .polygons()
                .iter()
                .flat_map(|c| (0..c.len()).map(move |k| (c[k], c[(k + 1) % c.len()])))
                .any(|(p, q)| segments_cross_properly(l.p0, l.p1, p, q)));
        }
        let area: f64 = cdt.triangles.iter().map(|t| shoelace(t).abs()).sum();
        assert!((area - 75.0).abs() < 1e-9, "{area}");
        assert_eq!(cdt.outline.len(), 6);
    }

    #[test]
    fn constrained_delaunay_leaves_holes_empty() {
        let region = square_with_hole();
        let d = domain(&region);
        let sites = random_sites(&d, 60, 10);
        let cdt = constrained_delaunay(&sites, &d, &CellOptions::DEFAULT).unwrap();
        let area: f64 = cdt.triangles.iter().map(|t| shoelace(t).abs()).sum();
        assert!((area - 84.0).abs() < 1e-9, "{area}");
        assert_eq!(cdt.outline.len(), 8);
        for &[i, j] in &delaunay_edges(&sites, &d, &CellOptions::DEFAULT).unwrap() {
            assert!(segment_in_region(&region, &d, sites[i], sites[j]));
        }
    }

    #[test]
    fn lloyd_energy_falls() {
        let d = domain(&rect(0.0, 0.0, 100.0, 100.0));
        let mut sites = random_sites(&d, 100, 11);
        let opts = CellOptions::DEFAULT;
        let mut energies = Vec::new();
        for _ in 0..10 {
            let step = lloyd_step(&sites, &d, &opts).unwrap();
            energies.push(step.energy);
            sites = step.sites;
        }
        assert!(energies[1] < energies[0], "{energies:?}");
        for w in energies.windows(2) {
            assert!(w[1] <= w[0] * (1.0 + 1e-12), "{energies:?}");
        }
        // Sites stay inside.
        assert!(sites.iter().all(|&p| d.contains(p)));
    }

    #[test]
    fn lloyd_energy_falls_around_holes() {
        let region = rect(0.0, 0.0, 40.0, 40.0)
            .difference(&circle(15.0, 15.0, 6.0))
            .difference(&rect(25.0, 5.0, 35.0, 30.0));
        let d = domain(&region);
        let mut sites = random_sites(&d, 150, 12);
        let mut energies = Vec::new();
        for _ in 0..10 {
            let step = lloyd_step(&sites, &d, &CellOptions::DEFAULT).unwrap();
            energies.push(step.energy);
            assert!(step.sites.iter().all(|&p| d.contains(p)));
            sites = step.sites;
        }
        for w in energies.windows(2) {
            assert!(w[1] <= w[0] * (1.0 + 1e-12), "{energies:?}");
        }
    }

    #[test]
    fn unit_density_is_plain_lloyd() {
        let d = domain(&l_shape());
        let sites = random_sites(&d, 60, 13);
        let opts = CellOptions::DEFAULT;
        let plain = lloyd_step(&sites, &d, &opts).unwrap();
        let weighted = weighted_lloyd_step(&sites, &d, &opts, &|_| 1.0).unwrap();
        for (a, b) in plain.sites.iter().zip(&weighted.sites) {
            assert!(a.distance(*b) < 1e-9, "{a:?} {b:?}");
        }
        assert!((plain.energy - weighted.energy).abs() < 1e-9 * plain.energy);
        // A density that is linear is integrated exactly too: compare with
        // a finer subdivision.
        let rho = |p: Point| 1.0 + p.x + 0.5 * p.y;
        let coarse = weighted_lloyd_step(&sites, &d, &opts, &rho).unwrap();
        let fine =
            weighted_lloyd_step(&sites, &d, &opts.with_density_subdivisions(6), &rho).unwrap();
        for (a, b) in coarse.sites.iter().zip(&fine.sites) {
            assert!(a.distance(*b) < 1e-9);
        }
    }

    #[test]
    fn weighted_lloyd_moves_towards_density() {
        let d = domain(&rect(0.0, 0.0, 100.0, 100.0));
        let sites = random_sites(&d, 100, 14);
        let step =
            weighted_lloyd_step(&sites, &d, &CellOptions::DEFAULT, &|p: Point| p.x * p.x).unwrap();
        let mean_dx: f64 = sites
            .iter()
            .zip(&step.sites)
            .map(|(a, b)| b.x - a.x)
            .sum::<f64>()
            / sites.len() as f64;
        assert!(mean_dx > 0.1, "{mean_dx}");
        // Energies computed with density still fall over steps.
        let next = weighted_lloyd_step(&step.sites, &d, &CellOptions::DEFAULT, &|p: Point| {
            p.x * p.x
        })
        .unwrap();
        assert!(next.energy < step.energy);
        // Where the density is zero (or NaN) nothing pulls a site: it
        // stays, rather than drifting into the blank part.
        let nan = weighted_lloyd_step(&sites, &d, &CellOptions::DEFAULT, &|_| f64::NAN).unwrap();
        assert_eq!(nan.sites, sites);
        let left = |p: Point| if p.x < 50.0 { 1.0 } else { 0.0 };
        let half = weighted_lloyd_step(&sites, &d, &CellOptions::DEFAULT, &left).unwrap();
        let plain = lloyd_step(&sites, &d, &CellOptions::DEFAULT).unwrap();
        let diagram = Diagram::new(&sites, &d, &CellOptions::DEFAULT).unwrap();
        for (i, cell) in diagram.cells().iter().enumerate() {
            let b = cell.to_path().bounding_box();
            if b.x0 > 50.0 {
                assert_eq!(half.sites[i], sites[i], "a site on the blank side moved");
            } else if b.x1 < 50.0 {
                // Uniform density there: the area centroid, up to the
                // quadrature's rounding.
                assert!(half.sites[i].distance(plain.sites[i]) < 1e-9);
            }
        }
    }

    #[test]
    fn bad_input_is_an_error() {
        let d = domain(&rect(0.0, 0.0, 10.0, 10.0));
        let opts = CellOptions::DEFAULT;
        let invalid = |r: Result<Diagram>| matches!(r, Err(Error::Invalid { .. }));
        assert!(invalid(Diagram::new(&[], &d, &opts)));
        assert!(invalid(Diagram::new(
            &[Point::new(f64::NAN, 1.0)],
            &d,
            &opts
        )));
        assert!(invalid(Diagram::new(
            &[Point::new(1.0, 1.0), Point::new(1.0, f64::INFINITY)],
            &d,
            &opts
        )));
        assert!(invalid(Diagram::new(&[Point::new(1e9, 1.0)], &d, &opts)));
        let err = Diagram::new(
            &[Point::new(1.0, 1.0), Point::new(2.0, 2.0)],
            &d,
            &opts.with_max_sites(1),
        )
        .unwrap_err();
        assert!(matches!(err, Error::Budget { limit: 1, .. }), "{err}");
        assert!(matches!(
            lloyd_step(&[], &d, &opts),
            Err(Error::Invalid { .. })
        ));
        assert!(matches!(
            delaunay_edges(&[Point::new(f64::NAN, 0.0)], &d, &opts),
            Err(Error::Invalid { .. })
        ));
        assert!(matches!(
            Domain::new(&Region::empty(), TOLERANCE),
            Err(Error::Invalid { .. })
        ));
    }

    /// Finite but awkward coordinates: on the outline (0, 3, 7, 10), at the
    /// range limit, tiny, and clusters of near-duplicates.
    fn wild() -> impl Strategy<Value = f64> {
        prop_oneof![
            4 => -20.0..20.0f64,
            1 => Just(0.0),
            1 => Just(3.0),
            1 => Just(7.0),
            1 => Just(10.0),
            1 => Just(1e-300),
            1 => Just(-1e5),
            1 => Just(1e5),
            2 => (-1.0..1.0f64).prop_map(|v| 5.0 + v * 1e-6),
            1 => (-1.0..1.0f64).prop_map(|v| 1.0 + v * 1e-12),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        #[test]
        fn wild_sites_never_panic(
            points in prop::collection::vec((wild(), wild()), 0..40),
            poison in prop::option::weighted(
                0.2,
                (0..40usize, prop_oneof![
                    Just(f64::NAN),
                    Just(f64::INFINITY),
                    Just(-f64::INFINITY),
                    Just(1e9),
                ]),
            ),
            outside in prop_oneof![
                Just(OutsideSites::Keep),
                Just(OutsideSites::Drop),
                Just(OutsideSites::Reject)
            ],
        ) {
            let d = domain(&square_with_hole());
            let mut sites: Vec<Point> = points.iter().map(|&(x, y)| Point::new(x, y)).collect();
            if let Some((i, v)) = poison {
                if let Some(p) = sites.get_mut(i) {
                    p.y = v;
                }
            }
            let opts = CellOptions::DEFAULT.with_outside(outside);
            match Diagram::new(&sites, &d, &opts) {
                Ok(v) => {
                    // With every site dropped, nothing owns a cell.
                    if v.status().contains(&SiteStatus::Own) {
                        let total = total_area(&v);
                        prop_assert!((total - 84.0).abs() < 1e-6 * 84.0, "{}", total);
                    }
                    let step = lloyd_step(&sites, &d, &opts).unwrap();
                    prop_assert!(step.energy.is_finite() && step.mean_movement.is_finite());
                    prop_assert!(step.sites.iter().all(|p| p.is_finite()));
                    for [i, j] in delaunay_edges(&sites, &d, &opts).unwrap() {
                        prop_assert!(d.contains(sites[i].midpoint(sites[j])));
                    }
                    let cdt = constrained_delaunay(&sites, &d, &opts).unwrap();
                    let area: f64 = cdt.triangles.iter().map(|t| shoelace(t).abs()).sum();
                    prop_assert!((area - 84.0).abs() < 1e-6, "{}", area);
                }
                Err(e) => {
                    prop_assert!(matches!(e, Error::Invalid { .. }), "unexpected error: {}", e);
                    prop_assert!(lloyd_step(&sites, &d, &opts).is_err());
                    prop_assert!(delaunay_edges(&sites, &d, &opts).is_err());
                    prop_assert!(constrained_delaunay(&sites, &d, &opts).is_err());
                }
            }
        }
    }

    /// Timing on the measurement in the module's brief; asserts only the
    /// tiling. `cargo test --release --lib geom::voronoi -- --ignored
    /// --nocapture`.
    #[test]
    #[ignore]
    #[allow(clippy::print_stderr)]
    fn timing_large() {
        use std::time::Instant;
        let region = rect(0.0, 0.0, 200.0, 200.0)
            .difference(&circle(60.0, 70.0, 30.0))
            .difference(&circle(140.0, 130.0, 40.0));
        let t = Instant::now();
        let d = domain(&region);
        eprintln!(
            "domain: {:?} ({} edges, {}×{} tiles, {} pieces)",
            t.elapsed(),
            d.edges.len(),
            d.grid.nx,
            d.grid.ny,
            d.pieces.len()
        );
        let sites = random_sites(&d, 100_000, 15);
        let t = Instant::now();
        let v = diagram(&sites, &d);
        eprintln!("100 000 cells: {:?}", t.elapsed());
        let total = total_area(&v);
        assert!((total - d.area()).abs() < 1e-6 * d.area());
        let t = Instant::now();
        let edges = delaunay_edges(&sites, &d, &CellOptions::DEFAULT).unwrap();
        eprintln!(
            "100 000 sites, Delaunay edges: {:?} ({})",
            t.elapsed(),
            edges.len()
        );
        let t = Instant::now();
        let cdt = constrained_delaunay(&sites, &d, &CellOptions::DEFAULT).unwrap();
        eprintln!(
            "100 000 sites, constrained: {:?} ({} triangles)",
            t.elapsed(),
            cdt.triangles.len()
        );

        let t = Instant::now();
        let detailed = domain(&wavy(20_000, 90.0, 400.0));
        eprintln!(
            "domain of {} edges: {:?} ({}×{} tiles, {} pieces)",
            detailed.edges.len(),
            t.elapsed(),
            detailed.grid.nx,
            detailed.grid.ny,
            detailed.pieces.len()
        );
        let many = random_sites(&detailed, 100_000, 18);
        let t = Instant::now();
        let v = diagram(&many, &detailed);
        eprintln!(
            "100 000 cells in an outline of {} edges: {:?}",
            detailed.edges.len(),
            t.elapsed()
        );
        assert!((total_area(&v) - detailed.area()).abs() < 1e-6 * detailed.area());

        let small = random_sites(&d, 10_000, 16);
        let t = Instant::now();
        let step = lloyd_step(&small, &d, &CellOptions::DEFAULT).unwrap();
        eprintln!("Lloyd step, 10 000 sites: {:?}", t.elapsed());
        let t = Instant::now();
        let w = weighted_lloyd_step(&small, &d, &CellOptions::DEFAULT, &|p: Point| {
            1.0 + (p.x * 0.1).sin() * (p.y * 0.1).cos()
        })
        .unwrap();
        eprintln!("weighted Lloyd step, 10 000 sites: {:?}", t.elapsed());
        let t = Instant::now();
        let mut s = small.clone();
        for _ in 0..10 {
            s = lloyd_step(&s, &d, &CellOptions::DEFAULT).unwrap().sites;
        }
        eprintln!("10 Lloyd steps, 10 000 sites: {:?}", t.elapsed());
        assert!(step.energy > 0.0 && w.energy > 0.0);
    }
}
