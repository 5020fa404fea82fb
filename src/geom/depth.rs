//! Depth composition: shapes stacked front to back, each hiding the lines
//! of the shapes behind it, drawn as a line drawing with one silhouette.
//!
//! A flower's petals lie over one another this way, and so will a vine's
//! stem winding round its support: in front of the pole on one side,
//! behind it on the other. Each is a list of [`Piece`]s: an area (a
//! [`Region`]), the line along its edge, lines drawn on it (veins,
//! creases), and a depth, larger in front. A [`DepthStack`] of them gives
//!
//! - [`DepthStack::visible_lines`]: every piece's edge where it lies over
//!   a piece further back, and its lines, each minus what hides it;
//! - [`DepthStack::silhouette`]: the union of the areas, whose outline is
//!   drawn on its own (an edge that lies over nothing is part of it, so
//!   it is not among the visible lines).
//!
//! **What hides what.** A piece hides the edges and lines of every piece
//! at a smaller depth wherever it covers them. Pieces at the *same* depth
//! make one layer: each hides the other's edge and lines where they
//! overlap, so together they draw the outline of their union over what
//! lies behind, and no line inside one another (a flower draws a seam
//! between such neighbours itself, with [`DepthStack::hide_on`]). An
//! optional *cover* lies in front of every piece: it hides their lines but
//! draws nothing (a flower's stamen cup). Order within a depth does not
//! matter; the order of the pieces is the order of the lines.
//!
//! ```
//! use kurbo::{Rect, Shape};
//! use moyo::geom::depth::{DepthStack, Piece};
//! use moyo::geom::region::Region;
//!
//! // A vine's stem crossing its pole twice: in front (depth 1), then
//! // behind (depth −1). Rectangles here; a real stem is cut into runs at
//! // alternating depths that overlap a little where they meet, each with
//! // only its two sides as its edge (`Piece::with_edge`), so that no cut
//! // end is drawn across the stem.
//! let pole = Region::from_rect(Rect::new(45.0, 0.0, 55.0, 100.0))?;
//! let front = Region::from_rect(Rect::new(30.0, 20.0, 70.0, 24.0))?;
//! let behind = Region::from_rect(Rect::new(30.0, 60.0, 70.0, 64.0))?;
//! let stack = DepthStack::new(
//!     vec![Piece::new(pole, 0), Piece::new(front, 1), Piece::new(behind, -1)],
//!     None,
//!     0.01,
//! );
//! let length: f64 = stack.visible_lines().iter().map(|l| l.perimeter(1e-6)).sum();
//! // The stem in front draws its sides across the pole (2 × 10 mm); behind
//! // it, the pole's sides cross the stem (2 × 4 mm).
//! assert!((length - 28.0).abs() < 1e-9);
//! assert!((stack.silhouette(&[]).area() - (1000.0 + 2.0 * 120.0)).abs() < 1e-6);
//! # Ok::<(), moyo::Error>(())
//! ```
//!
//! **Cost.** Making a stack prepares one [`StrokeClipper`] per piece, and
//! two per distinct depth (what lies behind it, what lies in front) made
//! with [`StrokeClipper::for_union`], which puts the outlines together
//! without a boolean sweep; so preparing is linear in the outlines times
//! the number of depths. A line is clipped by the clipper in front of its
//! depth and by the pieces at its depth whose boxes meet its piece's.
//! Only the silhouette takes a sweep.

use kurbo::{BezPath, Rect};

use super::clip::StrokeClipper;
use super::region::Region;

/// One shape of a [`DepthStack`].
#[derive(Debug, Clone)]
pub struct Piece {
    area: Region,
    edge: BezPath,
    lines: BezPath,
    depth: i32,
}

impl Piece {
    /// A piece covering `area` at `depth` (larger in front); its edge is
    /// the area's boundary, it has no lines.
    pub fn new(area: Region, depth: i32) -> Piece {
        Piece {
            edge: area.path().clone(),
            area,
            lines: BezPath::new(),
            depth,
        }
    }

    /// This piece with `edge` as the line along its edge: the shape as it
    /// was drawn (its direction and start kept), or only part of the
    /// boundary (a stem's sides without its cut ends).
    pub fn with_edge(mut self, edge: BezPath) -> Piece {
        self.edge = edge;
        self
    }

    /// This piece with `lines` drawn on it, hidden where it is covered.
    pub fn with_lines(mut self, lines: BezPath) -> Piece {
        self.lines = lines;
        self
    }
}

/// Pieces prepared for hiding one another (see the [module docs](self)).
#[derive(Debug, Clone)]
pub struct DepthStack {
    pieces: Vec<Piece>,
    cover: Option<Region>,
    /// Each piece's area, prepared.
    clippers: Vec<StrokeClipper>,
    bounds: Vec<Rect>,
    /// The distinct depths, ascending.
    levels: Vec<i32>,
    /// Per level: the pieces behind it, put together.
    behind: Vec<StrokeClipper>,
    /// Per level: the pieces in front of it and the cover, put together.
    in_front: Vec<StrokeClipper>,
}

impl DepthStack {
    /// Prepares `pieces`, with `cover` in front of all of them (hiding,
    /// never drawn); outlines are flattened within `tolerance` (as
    /// [`StrokeClipper::new`] takes it).
    pub fn new(pieces: Vec<Piece>, cover: Option<Region>, tolerance: f64) -> DepthStack {
        let clippers = pieces
            .iter()
            .map(|p| StrokeClipper::new(&p.area, tolerance))
            .collect();
        let bounds = pieces.iter().map(|p| p.area.bounds()).collect();
        let mut levels: Vec<i32> = pieces.iter().map(|p| p.depth).collect();
        levels.sort_unstable();
        levels.dedup();
        let union_of = |keep: &dyn Fn(i32) -> bool, cover: Option<&Region>| {
            let areas = pieces.iter().filter(|p| keep(p.depth)).map(|p| &p.area);
            StrokeClipper::for_union(areas.chain(cover), tolerance)
        };
        let behind = levels
            .iter()
            .map(|&d| union_of(&|depth| depth < d, None))
            .collect();
        let in_front = levels
            .iter()
            .map(|&d| union_of(&|depth| depth > d, cover.as_ref()))
            .collect();
        DepthStack {
            pieces,
            cover,
            clippers,
            bounds,
            levels,
            behind,
            in_front,
        }
    }

    /// The visible lines of every piece in order: the parts of its edge
    /// over a piece further back, then its lines, each without the parts
    /// that something in front of it hides (see [`DepthStack::hide_on`]).
    pub fn visible_lines(&self) -> Vec<BezPath> {
        let mut out = Vec::new();
        for (i, piece) in self.pieces.iter().enumerate() {
            let over_behind = self.behind[self.level_of(piece.depth)]
                .clip(&piece.edge)
                .inside;
            out.extend(self.hide_on(i, &[], over_behind));
            if !piece.lines.elements().is_empty() {
                out.extend(self.hide_on(i, &[], vec![piece.lines.clone()]));
            }
        }
        out
    }

    /// The parts of `lines`, drawn on piece `i`, that nothing hides: not
    /// the pieces in front of it, nor the cover, nor the other pieces at
    /// its depth but those listed in `except`.
    ///
    /// # Panics
    /// When `i` is not the index of a piece.
    pub fn hide_on(&self, i: usize, except: &[usize], lines: Vec<BezPath>) -> Vec<BezPath> {
        let depth = self.pieces[i].depth;
        let mut lines = outside(&self.in_front[self.level_of(depth)], lines);
        for (k, p) in self.pieces.iter().enumerate() {
            if k != i
                && !except.contains(&k)
                && p.depth == depth
                && self.bounds[i].overlaps(self.bounds[k])
            {
                lines = outside(&self.clippers[k], lines);
            }
        }
        lines
    }

    /// Piece `i`'s area, prepared for clipping.
    ///
    /// # Panics
    /// When `i` is not the index of a piece.
    pub fn clipper(&self, i: usize) -> &StrokeClipper {
        &self.clippers[i]
    }

    /// The union of the pieces' areas, the regions `fill` (shapes that only
    /// fill the silhouette, such as a gap the pieces enclose) and the
    /// cover, in one sweep.
    pub fn silhouette(&self, fill: &[Region]) -> Region {
        let mut all: Vec<Region> = self.pieces.iter().map(|p| p.area.clone()).collect();
        all.extend(fill.iter().cloned());
        all.extend(self.cover.iter().cloned());
        Region::union_all(&all)
    }

    fn level_of(&self, depth: i32) -> usize {
        self.levels.binary_search(&depth).unwrap_or(0)
    }
}

/// The parts of `lines` outside `clipper`.
fn outside(clipper: &StrokeClipper, lines: Vec<BezPath>) -> Vec<BezPath> {
    lines.iter().flat_map(|l| clipper.clip(l).outside).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{Line, Shape};

    fn square(x0: f64, y0: f64, x1: f64, y1: f64) -> Region {
        Region::from_rect(Rect::new(x0, y0, x1, y1)).unwrap()
    }

    fn length(lines: &[BezPath]) -> f64 {
        lines.iter().map(|l| l.perimeter(1e-9)).sum()
    }

    fn diagonal(a: (f64, f64), b: (f64, f64)) -> BezPath {
        Line::new(a, b).to_path(0.0)
    }

    /// `a` = [0, 10]² with its diagonal, `b` = [5, 15]² with its diagonal.
    fn two_squares(depth_a: i32, depth_b: i32) -> Vec<Piece> {
        vec![
            Piece::new(square(0.0, 0.0, 10.0, 10.0), depth_a)
                .with_lines(diagonal((0.0, 0.0), (10.0, 10.0))),
            Piece::new(square(5.0, 5.0, 15.0, 15.0), depth_b)
                .with_lines(diagonal((5.0, 5.0), (15.0, 15.0))),
        ]
    }

    #[test]
    fn a_square_in_front_hides_the_square_behind() {
        let stack = DepthStack::new(two_squares(0, 1), None, 0.01);
        let lines = stack.visible_lines();
        // The back square draws no edge (it lies over nothing) and the half
        // of its diagonal outside the front one; the front one its edge
        // over the back one (2 × 5) and its whole diagonal.
        let half = 50f64.sqrt();
        assert!((length(&lines) - (half + 10.0 + 2.0 * half)).abs() < 1e-9);
        assert!((stack.silhouette(&[]).area() - 175.0).abs() < 1e-6);
        // Swapped: the other way round.
        let swapped = DepthStack::new(two_squares(1, 0), None, 0.01).visible_lines();
        assert!((length(&swapped) - (10.0 + 2.0 * half + half)).abs() < 1e-9);
    }

    #[test]
    fn pieces_at_one_depth_draw_the_outline_of_their_union() {
        // Nothing behind: no edges, and each hides the other's diagonal.
        let alone = DepthStack::new(two_squares(0, 0), None, 0.01).visible_lines();
        assert!((length(&alone) - 2.0 * 50f64.sqrt()).abs() < 1e-9);
        // Over a large square: the outline of the union, 60 mm, and the
        // same diagonals.
        let mut pieces = two_squares(0, 0);
        pieces.push(Piece::new(square(-10.0, -10.0, 30.0, 30.0), -1));
        let stack = DepthStack::new(pieces, None, 0.01);
        let lines = stack.visible_lines();
        assert!((length(&lines) - (60.0 + 2.0 * 50f64.sqrt())).abs() < 1e-9);
        // What `hide_on` leaves of a line on `a`, when `b` may show it.
        let across = diagonal((0.0, 8.0), (15.0, 8.0));
        assert!((length(&stack.hide_on(0, &[], vec![across.clone()])) - 15.0).abs() > 1.0);
        assert!((length(&stack.hide_on(0, &[1], vec![across])) - 15.0).abs() < 1e-9);
    }

    #[test]
    fn three_depths() {
        // a = [0, 10]² at 0, b = [5, 15]² at 1, and a strip c = [7, 9] ×
        // [−5, 20] at 2 in front of both.
        let mut pieces = two_squares(0, 1);
        pieces.push(Piece::new(square(7.0, -5.0, 9.0, 20.0), 2));
        let stack = DepthStack::new(pieces, None, 0.01);
        let lines = stack.visible_lines();
        let half = 50f64.sqrt();
        // a: its diagonal up to b, less the strip: (0,0)–(5,5).
        // b: its edge over a (10) less the strip across y = 5 (2), and its
        //    diagonal less the strip: (5,5)–(7,7) and (9,9)–(15,15).
        // c: its sides over a and b, y from 0 to 15: 2 × 15.
        let diag = |a: f64, b: f64| (b - a) * 2f64.sqrt();
        let want = half + 8.0 + diag(5.0, 7.0) + diag(9.0, 15.0) + 30.0;
        assert!((length(&lines) - want).abs() < 1e-9, "{}", length(&lines));
    }

    #[test]
    fn a_cover_hides_and_draws_nothing() {
        let cover = square(-1.0, 4.0, 16.0, 6.0);
        let stack = DepthStack::new(two_squares(0, 1), Some(cover), 0.01);
        let lines = stack.visible_lines();
        let half = 50f64.sqrt();
        // As in front of one another, less the band 4 < y < 6: a's
        // diagonal loses (4,4)–(5,5), b's edge x = 5 loses y 5–6 and its
        // edge y = 5 all of it, b's diagonal loses (5,5)–(6,6).
        let want = (half - 2f64.sqrt()) + 4.0 + (2.0 * half - 2f64.sqrt());
        assert!((length(&lines) - want).abs() < 1e-9, "{}", length(&lines));
        // The band adds what sticks out of the squares: 34 − (10 + 15).
        assert!((stack.silhouette(&[]).area() - (175.0 + 9.0)).abs() < 1e-6);
    }
}
