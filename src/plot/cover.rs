//! Which line work lies on which: the straight pieces a pen draws, kept
//! in a grid, and the part of a piece that another piece covers. Shared by
//! the pen stages that remove doubled line work ([`super::dedupe`]) and
//! debris ([`super::debris`]), and by the figures of [`super::stats()`].
//!
//! A subpath is cut into [`Piece`]s: chords of its segments no longer than
//! the grid's cell, each remembering the segment and the parameter range
//! it stands for, so that a decision made on the pieces can be carried
//! back to the exact curves ([`Pieces::cut`]).
//!
//! A piece *covers* part of another when the two run the same way (the
//! angle between them under 20°, either direction) and that part lies
//! within the tolerance of it, beside it rather than beyond its ends
//! ([`covered`]). Crossing lines cover nothing of each other; a line that
//! ends on another, or continues it end to end, neither.

use kurbo::{ParamCurve, PathSeg, Point, Vec2};
use rustc_hash::FxHashMap;

/// Two pieces run the same way when the cosine of the angle between them
/// (either direction) is at least this: 20° and a hundredth, so that a
/// fork of exactly 20° (ABOP's plants branch at that angle) counts however
/// its coordinates round. Chords of two copies of one curve cut at
/// different places differ by a few degrees; lines that cross at a
/// shallow angle share ink only near the crossing, over a length the
/// stages weigh ([`super::dedupe`]).
pub(crate) const SAME_WAY_COS: f64 = 0.9396;

/// A straight piece of a subpath.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Piece {
    /// Where it starts and ends.
    pub(crate) a: Point,
    pub(crate) b: Point,
    /// The segment of the subpath (in [`kurbo::segments`] order) and the
    /// parameter range on it that this piece stands for.
    pub(crate) seg: u32,
    pub(crate) t0: f64,
    pub(crate) t1: f64,
    /// Length of the pieces before it in the subpath.
    pub(crate) s: f64,
}

impl Piece {
    /// Its length.
    pub(crate) fn len(&self) -> f64 {
        self.a.distance(self.b)
    }
}

/// A subpath's segments and their pieces.
#[derive(Debug, Clone, Default)]
pub(crate) struct Pieces {
    pub(crate) segs: Vec<PathSeg>,
    pub(crate) pieces: Vec<Piece>,
    /// Whether the subpath is closed (so a kept run may wrap round its
    /// start).
    pub(crate) closed: bool,
}

impl Pieces {
    /// The pieces of `segs`: each line split into equal pieces no longer
    /// than `max_len`, each curve into chords that stray at most about
    /// `flat` from it and are no longer than `max_len`.
    pub(crate) fn new(segs: Vec<PathSeg>, closed: bool, max_len: f64, flat: f64) -> Pieces {
        let mut pieces = Vec::new();
        let mut s = 0.0;
        for (k, seg) in segs.iter().enumerate() {
            let n = piece_count(seg, max_len, flat);
            let mut a = seg.start();
            for i in 1..=n {
                let t1 = i as f64 / n as f64;
                let b = if i == n { seg.end() } else { seg.eval(t1) };
                let piece = Piece {
                    a,
                    b,
                    seg: k as u32,
                    t0: (i - 1) as f64 / n as f64,
                    t1,
                    s,
                };
                s += piece.len();
                pieces.push(piece);
                a = b;
            }
        }
        Pieces {
            segs,
            pieces,
            closed,
        }
    }

    /// Length of the subpath along its pieces.
    pub(crate) fn len(&self) -> f64 {
        self.pieces.last().map_or(0.0, |p| p.s + p.len())
    }

    /// The segment and parameter at length `s` along the pieces.
    fn at(&self, s: f64) -> (usize, f64) {
        let i = self.pieces.partition_point(|p| p.s <= s).saturating_sub(1);
        let p = &self.pieces[i];
        let len = p.len();
        let f = if len > 0.0 {
            ((s - p.s) / len).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p.seg as usize, p.t0 + f * (p.t1 - p.t0))
    }

    /// The parts of the subpath between lengths `runs` (sorted, apart),
    /// as subpaths of exact curves: whole segments as they were, the
    /// segments at a run's ends cut at their parameter. On a closed
    /// subpath a run ending at its end and one starting at its start are
    /// one run through the start.
    pub(crate) fn cut(&self, runs: &[(f64, f64)], out: &mut kurbo::BezPath) {
        let total = self.len();
        let eps = 1e-9 * (1.0 + total);
        let wraps = self.closed
            && runs.len() > 1
            && runs[0].0 <= eps
            && runs[runs.len() - 1].1 >= total - eps;
        if wraps {
            let (last, first) = (runs[runs.len() - 1], runs[0]);
            self.draw(last, out, true);
            self.draw(first, out, false);
            for &run in &runs[1..runs.len() - 1] {
                self.draw(run, out, true);
            }
        } else {
            for &run in runs {
                self.draw(run, out, true);
            }
        }
    }

    /// Draws the part between lengths `from` and `to`, starting with a
    /// move when `moving` (else continuing from where `out` is).
    fn draw(&self, (from, to): (f64, f64), out: &mut kurbo::BezPath, moving: bool) {
        let (k0, t0) = self.at(from);
        let (k1, t1) = self.at(to);
        if moving {
            out.move_to(self.segs[k0].eval(t0));
        }
        for k in k0..=k1 {
            let ta = if k == k0 { t0 } else { 0.0 };
            let tb = if k == k1 { t1 } else { 1.0 };
            if tb <= ta {
                // Nothing of this segment (a run starting at its very end):
                // a curve of no length would be a degenerate one.
                continue;
            }
            let seg = if ta == 0.0 && tb == 1.0 {
                self.segs[k]
            } else {
                self.segs[k].subsegment(ta..tb)
            };
            match seg {
                PathSeg::Line(l) => out.line_to(l.p1),
                PathSeg::Quad(q) => out.quad_to(q.p1, q.p2),
                PathSeg::Cubic(c) => out.curve_to(c.p1, c.p2, c.p3),
            }
        }
    }
}

/// How many pieces `seg` is cut into (see [`Pieces::new`]).
fn piece_count(seg: &PathSeg, max_len: f64, flat: f64) -> usize {
    // A chord strays from a curve by about |B''| / (8 n²); the second
    // differences of the control points bound |B''|.
    let (bend, hull) = match seg {
        PathSeg::Line(l) => (0.0, l.p0.distance(l.p1)),
        PathSeg::Quad(q) => (
            0.25 * (q.p0.to_vec2() - 2.0 * q.p1.to_vec2() + q.p2.to_vec2()).hypot(),
            q.p0.distance(q.p1) + q.p1.distance(q.p2),
        ),
        PathSeg::Cubic(c) => {
            let d1 = c.p0.to_vec2() - 2.0 * c.p1.to_vec2() + c.p2.to_vec2();
            let d2 = c.p1.to_vec2() - 2.0 * c.p2.to_vec2() + c.p3.to_vec2();
            (
                0.75 * d1.hypot().max(d2.hypot()),
                c.p0.distance(c.p1) + c.p1.distance(c.p2) + c.p2.distance(c.p3),
            )
        }
    };
    let by_bend = if flat > 0.0 {
        (bend / flat).sqrt().ceil()
    } else {
        1.0
    };
    let by_len = if max_len > 0.0 {
        (hull / max_len).ceil()
    } else {
        1.0
    };
    // NaN (a broken coordinate) and absurd counts end as one piece or the
    // cap: pieces cost memory, and a curve that needs more is drawn long
    // before it matters here.
    (by_bend.max(by_len) as usize).clamp(1, MAX_PIECES_PER_SEGMENT)
}

/// At most this many pieces stand for one segment.
const MAX_PIECES_PER_SEGMENT: usize = 4096;

/// The part of piece `a`–`b`, as lengths from `a`, that lies within `tol`
/// of the piece `c`–`d` running the same way (see the module docs), when
/// it has any length.
pub(crate) fn covered(a: Point, b: Point, c: Point, d: Point, tol: f64) -> Option<(f64, f64)> {
    let len = a.distance(b);
    let lc = c.distance(d);
    if len <= 0.0 || lc <= 0.0 {
        return None;
    }
    let u = (b - a) / len;
    let v = (d - c) / lc;
    let cos = u.dot(v);
    if cos.abs() < SAME_WAY_COS {
        return None;
    }
    let n = Vec2::new(-v.y, v.x);
    let from = a - c;
    // Beside it: |n·(p - c)| ≤ tol; along it: 0 ≤ v·(p - c) ≤ lc.
    let (s0, s1) = linear_within(n.dot(from), n.dot(u), -tol, tol)?;
    let (s2, s3) = linear_within(v.dot(from), cos, 0.0, lc)?;
    let lo = s0.max(s2).max(0.0);
    let hi = s1.min(s3).min(len);
    (hi > lo).then_some((lo, hi))
}

/// The `s` where `lo ≤ h0 + s·h1 ≤ hi`, as an interval (unbounded when
/// `h1` is zero and `h0` lies within).
fn linear_within(h0: f64, h1: f64, lo: f64, hi: f64) -> Option<(f64, f64)> {
    if h1.abs() < 1e-12 {
        return (lo <= h0 && h0 <= hi).then_some((f64::NEG_INFINITY, f64::INFINITY));
    }
    let (x, y) = ((lo - h0) / h1, (hi - h0) / h1);
    Some((x.min(y), x.max(y)))
}

/// Distance between the segments `a`–`b` and `c`–`d`.
pub(crate) fn segment_distance(a: Point, b: Point, c: Point, d: Point) -> f64 {
    if segments_cross(a, b, c, d) {
        return 0.0;
    }
    point_segment(a, c, d)
        .min(point_segment(b, c, d))
        .min(point_segment(c, a, b))
        .min(point_segment(d, a, b))
}

fn point_segment(p: Point, a: Point, b: Point) -> f64 {
    let ab = b - a;
    let l2 = ab.hypot2();
    let t = if l2 > 0.0 {
        ((p - a).dot(ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + t * ab)
}

fn segments_cross(a: Point, b: Point, c: Point, d: Point) -> bool {
    let side = |p: Point, q: Point, r: Point| (q - p).cross(r - p);
    let (d1, d2) = (side(c, d, a), side(c, d, b));
    let (d3, d4) = (side(a, b, c), side(a, b, d));
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

/// Straight pieces in a grid of square cells, each piece in every cell its
/// bounding box touches; a piece is no longer than a cell, so it sits in
/// at most four.
#[derive(Debug, Default)]
pub(crate) struct LineIndex {
    cell: f64,
    cells: FxHashMap<(i32, i32), Vec<u32>>,
    lines: Vec<Indexed>,
}

/// A piece in the index.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Indexed {
    pub(crate) a: Point,
    pub(crate) b: Point,
    /// Whose it is (a subpath's number, the caller's choice).
    pub(crate) owner: u32,
    /// Where it starts along its owner.
    pub(crate) s: f64,
    /// Taken back ([`LineIndex::remove`]): no longer found.
    alive: bool,
}

impl LineIndex {
    /// An empty index of cells `cell` wide (pieces must be no longer).
    pub(crate) fn new(cell: f64) -> LineIndex {
        LineIndex {
            cell,
            cells: FxHashMap::default(),
            lines: Vec::new(),
        }
    }

    fn key(&self, p: Point) -> (i32, i32) {
        // `as` saturates: coordinates beyond i32 cells share the edge cells.
        (
            (p.x / self.cell).floor() as i32,
            (p.y / self.cell).floor() as i32,
        )
    }

    /// Adds a piece; gives its number.
    pub(crate) fn insert(&mut self, a: Point, b: Point, owner: u32, s: f64) -> u32 {
        let id = self.lines.len() as u32;
        self.lines.push(Indexed {
            a,
            b,
            owner,
            s,
            alive: true,
        });
        let (lo, hi) = (
            self.key(corner(a, b, f64::min)),
            self.key(corner(a, b, f64::max)),
        );
        for x in lo.0..=hi.0.max(lo.0) {
            for y in lo.1..=hi.1.max(lo.1) {
                self.cells.entry((x, y)).or_default().push(id);
            }
        }
        id
    }

    /// Takes piece `id` back: searches no longer find it.
    pub(crate) fn remove(&mut self, id: u32) {
        self.lines[id as usize].alive = false;
    }

    /// Calls `f` with every piece whose bounding box comes within `reach`
    /// of the bounding box of `a`–`b` (some more than once).
    pub(crate) fn near(&self, a: Point, b: Point, reach: f64, mut f: impl FnMut(&Indexed)) {
        let r = Vec2::new(reach, reach);
        let (lo, hi) = (
            self.key(corner(a, b, f64::min) - r),
            self.key(corner(a, b, f64::max) + r),
        );
        // Far more cells than pieces (a reach as wide as the page): the
        // pieces themselves are fewer to look at.
        let span =
            (i64::from(hi.0) - i64::from(lo.0) + 1) * (i64::from(hi.1) - i64::from(lo.1) + 1);
        if span as u64 > self.lines.len() as u64 {
            self.lines.iter().filter(|l| l.alive).for_each(f);
            return;
        }
        for x in lo.0..=hi.0 {
            for y in lo.1..=hi.1 {
                if let Some(ids) = self.cells.get(&(x, y)) {
                    for &id in ids {
                        let line = &self.lines[id as usize];
                        if line.alive {
                            f(line);
                        }
                    }
                }
            }
        }
    }
}

/// The corner of the bounding box of `a` and `b` that `pick` chooses.
fn corner(a: Point, b: Point, pick: fn(f64, f64) -> f64) -> Point {
    Point::new(pick(a.x, b.x), pick(a.y, b.y))
}

/// Sorts `runs` and joins those that overlap or touch.
pub(crate) fn union(runs: &mut Vec<(f64, f64)>) {
    runs.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.total_cmp(&y.1)));
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(runs.len());
    for &(lo, hi) in runs.iter() {
        match out.last_mut() {
            Some(last) if lo <= last.1 + 1e-9 => last.1 = last.1.max(hi),
            _ => out.push((lo, hi)),
        }
    }
    *runs = out;
}

#[cfg(test)]
mod tests {
    use kurbo::{CubicBez, Line, ParamCurveArclen};

    use super::*;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    #[test]
    fn a_line_beside_another_is_covered_where_they_overlap() {
        let got = covered(p(0.0, 0.0), p(10.0, 0.0), p(4.0, 0.05), p(20.0, 0.05), 0.1);
        let (lo, hi) = got.unwrap();
        assert!((lo - 4.0).abs() < 1e-9 && (hi - 10.0).abs() < 1e-9);
        // Either direction.
        assert_eq!(
            covered(p(0.0, 0.0), p(10.0, 0.0), p(20.0, 0.05), p(4.0, 0.05), 0.1),
            got
        );
    }

    #[test]
    fn a_fork_of_twenty_degrees_shares_its_start_and_a_wider_one_does_not() {
        // ABOP's plants branch at 20°: the branch's first tenths of a
        // millimetre lie on its parent, within a quarter of a 0.3 mm pen.
        let branch = |deg: f64| {
            let d = Vec2::from_angle(deg.to_radians()) * 5.0;
            covered(p(0.0, 0.0), d.to_point(), p(-5.0, 0.0), p(10.0, 0.0), 0.075)
        };
        let (lo, hi) = branch(20.0).expect("a 20° fork shares its start");
        assert!(lo.abs() < 1e-9 && (hi - 0.075 / 20f64.to_radians().sin()).abs() < 1e-6);
        assert!(branch(20.1).is_none());
    }

    #[test]
    fn crossing_touching_and_distant_lines_cover_nothing() {
        let a = (p(0.0, 0.0), p(10.0, 0.0));
        // Crossing square on.
        assert!(covered(a.0, a.1, p(5.0, -5.0), p(5.0, 5.0), 0.1).is_none());
        // Continuing it end to end.
        assert!(covered(a.0, a.1, p(10.0, 0.0), p(20.0, 0.0), 0.1).is_none());
        // Parallel, further than the tolerance.
        assert!(covered(a.0, a.1, p(0.0, 0.2), p(10.0, 0.2), 0.1).is_none());
    }

    #[test]
    fn a_tilted_line_is_covered_only_where_it_is_near() {
        // 0.1 mm of rise over 10 mm: within 0.05 of the x axis for x < 5.
        let (lo, hi) = covered(p(0.0, 0.0), p(10.0, 0.1), p(0.0, 0.0), p(10.0, 0.0), 0.05).unwrap();
        assert!(lo.abs() < 1e-9);
        assert!((hi - 5.0).abs() < 0.01, "{hi}");
    }

    #[test]
    fn pieces_stand_for_their_segments() {
        let curve = PathSeg::Cubic(CubicBez::new(
            p(0.0, 0.0),
            p(10.0, 20.0),
            p(30.0, -20.0),
            p(40.0, 0.0),
        ));
        let line = PathSeg::Line(Line::new(p(40.0, 0.0), p(40.0, 30.0)));
        let pieces = Pieces::new(vec![curve, line], false, 1.0, 0.01);
        for piece in &pieces.pieces {
            assert!(piece.len() <= 1.0 + 1e-9);
            let seg = pieces.segs[piece.seg as usize];
            assert!(seg.eval(piece.t0).distance(piece.a) < 1e-9);
            assert!(seg.eval(piece.t1).distance(piece.b) < 1e-9);
            // The chord stays near the curve.
            let mid = seg.eval((piece.t0 + piece.t1) / 2.0);
            assert!(point_segment(mid, piece.a, piece.b) < 0.02);
        }
        assert!((pieces.len() - (curve.arclen(1e-6) + 30.0)).abs() < 0.01);
        // Cutting out the whole length gives the segments back as they were.
        let mut out = kurbo::BezPath::new();
        pieces.cut(&[(0.0, pieces.len())], &mut out);
        let back: Vec<PathSeg> = out.segments().collect();
        assert_eq!(back, pieces.segs);
        // A run from the very end of a segment starts with the next one:
        // no curve of no length.
        let first = pieces.pieces.iter().rfind(|p| p.seg == 0).unwrap();
        let from = first.s + first.len();
        let mut out = kurbo::BezPath::new();
        pieces.cut(&[(from, pieces.len())], &mut out);
        let back: Vec<PathSeg> = out.segments().collect();
        assert_eq!(back, pieces.segs[1..]);
    }

    #[test]
    fn the_index_finds_what_is_near_and_forgets_what_is_removed() {
        let mut index = LineIndex::new(1.0);
        let id = index.insert(p(0.5, 0.5), p(1.2, 0.5), 7, 0.0);
        index.insert(p(50.0, 50.0), p(50.5, 50.0), 8, 0.0);
        let mut owners = Vec::new();
        index.near(p(1.5, 0.6), p(1.6, 0.6), 0.1, |l| owners.push(l.owner));
        owners.dedup();
        assert_eq!(owners, [7]);
        index.remove(id);
        let mut found = 0;
        index.near(p(1.5, 0.6), p(1.6, 0.6), 0.1, |_| found += 1);
        assert_eq!(found, 0);
    }

    #[test]
    fn segment_distance_is_zero_when_crossing() {
        assert_eq!(
            segment_distance(p(0.0, 0.0), p(2.0, 2.0), p(0.0, 2.0), p(2.0, 0.0)),
            0.0
        );
        assert!(
            (segment_distance(p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0), p(1.0, 1.0)) - 1.0).abs()
                < 1e-12
        );
    }
}
