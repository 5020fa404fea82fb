//! Path ordering: minimise the distance the pen travels *up*.
//!
//! Each layer of a flat scene (see [`super::flatten`]) is ordered on its
//! own; pens are never mixed. Multi-subpath paths are first split into one
//! path per subpath ([`super::flatten::split_subpaths`]), since the pen
//! lifts between subpaths anyway.
//!
//! The travel of an order is the sum of straight pen-up moves from the
//! origin (0, 0) — the plotter's home, the top-left corner of the sheet — to
//! the start of the first path, and from the end of each path to the start
//! of the next ([`super::stats::pen_up_length`]); the move home after the
//! last path is not counted.
//!
//! 1. **Greedy nearest neighbour.** Starting at the origin, repeatedly draw
//!    the path whose entry point is nearest to the pen. Entry points are
//!    kept in a static k-d tree with deletion ([`PointIndex`]), so this is
//!    O(n log n). An open path can be entered at its start, or — with
//!    [`SortOptions::reverse`] — at its end and drawn backwards. A closed
//!    path ([`Subpath::is_closed`]: ending in a close-path, or back at its
//!    first point) can be entered at its start, or — with
//!    [`SortOptions::rotate_closed`] — at any of its on-curve vertices; it
//!    then ends where it began.
//! 2. **Improvement** ([`SortOptions::two_opt`]): passes of windowed 2-opt
//!    (reverse a run of up to [`SortOptions::window`] consecutive paths,
//!    drawing each of them backwards; needs `reverse`), Or-opt (move a run
//!    of one to three paths about `window / 8` places away, possibly
//!    backwards), and re-choosing the entry vertex of every closed path
//!    for its new neighbours. A change is made only when it shortens the
//!    travel, so the result is never longer than the greedy order. Passes
//!    stop when one shortens the travel by less than 0.1 %, or after
//!    [`SortOptions::max_passes`]; each costs O(n · window), so the whole
//!    stage stays O(n log n + n · window · passes). Candidates are screened
//!    with squared distances against cached move lengths, so a pass costs
//!    little more than reading the order.
//!
//! On 100,000 short paths the improvement passes shorten the greedy travel
//! by 8–12 %; see `timing_100k` in the tests for the measurement.
//!
//! Ink is unchanged: every path is drawn with exactly the same segments
//! (reversing swaps the points of each segment, rotating a closed path
//! starts its cycle of segments elsewhere; one that stops short of its
//! start by rounding noise, within [`CLOSE_TOLERANCE`], gets a line across
//! that gap, as a close-path would draw). Closed paths are never drawn
//! backwards (a cutter may care about the direction of an outline). The
//! order changes the paint order, so run this stage after occlusion.
//! Everything is deterministic: ties go to the lower index.
//!
//! [`CLOSE_TOLERANCE`]: crate::geom::subpath::CLOSE_TOLERANCE

use kurbo::{BezPath, PathEl, Point};
use serde::{Deserialize, Serialize};

use super::flatten::{el_end, reverse_open_in_place, set_paths, split_subpaths, take_paths};
use crate::geom::subpath::{subpaths, Subpath};
use crate::geom::PointIndex;
use crate::scene::{Scene, StyledPath};

/// Options of [`run`] and [`order`].
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SortOptions {
    /// Open paths may be drawn backwards.
    pub reverse: bool,
    /// Closed paths may start at any on-curve vertex.
    pub rotate_closed: bool,
    /// Run the improvement passes after the greedy order (2-opt, Or-opt,
    /// closed-path re-rotation). Off gives the plain greedy order.
    pub two_opt: bool,
    /// How many places away 2-opt looks (at least 1); Or-opt looks an
    /// eighth as far (at least 2), since its moves cost more to try and
    /// gain less (measured on random drawings).
    pub window: u32,
    /// At most this many improvement passes.
    pub max_passes: u32,
}

impl SortOptions {
    /// Reversal, rotation and improvement on; window 64, at most 8 passes.
    pub const DEFAULT: SortOptions = SortOptions {
        reverse: true,
        rotate_closed: true,
        two_opt: true,
        window: 64,
        max_passes: 8,
    };

    /// These options with [`SortOptions::reverse`] set.
    pub const fn with_reverse(mut self, reverse: bool) -> SortOptions {
        self.reverse = reverse;
        self
    }

    /// These options with [`SortOptions::rotate_closed`] set.
    pub const fn with_rotate_closed(mut self, rotate_closed: bool) -> SortOptions {
        self.rotate_closed = rotate_closed;
        self
    }

    /// These options with [`SortOptions::two_opt`] set.
    pub const fn with_two_opt(mut self, two_opt: bool) -> SortOptions {
        self.two_opt = two_opt;
        self
    }

    /// These options with [`SortOptions::window`] set.
    pub const fn with_window(mut self, window: u32) -> SortOptions {
        self.window = window;
        self
    }

    /// These options with [`SortOptions::max_passes`] set.
    pub const fn with_max_passes(mut self, max_passes: u32) -> SortOptions {
        self.max_passes = max_passes;
        self
    }
}

impl Default for SortOptions {
    fn default() -> SortOptions {
        SortOptions::DEFAULT
    }
}

/// Orders the paths of every layer of `scene` (see the module
/// documentation). Meant for a flat scene.
pub fn run(scene: &mut Scene, options: &SortOptions) {
    for layer in &mut scene.layers {
        let paths = take_paths(layer);
        set_paths(layer, order(paths, options));
    }
}

/// `paths` (split into single subpaths) in an order with little pen-up
/// travel from the origin; some reversed or rotated as the options allow.
pub fn order(paths: Vec<StyledPath>, options: &SortOptions) -> Vec<StyledPath> {
    let paths = split_subpaths(paths);
    if paths.is_empty() {
        return paths;
    }
    let cands = Candidates::new(&paths, options);
    let mut tour = cands.greedy();
    if options.two_opt {
        tour.improve(&cands, options);
    }
    tour.build(paths, &cands)
}

/// Where each path may be entered.
struct Candidates {
    /// Entry points, grouped by path.
    points: Vec<Point>,
    /// `points[first[p]..first[p + 1]]` belong to path `p`.
    first: Vec<u32>,
    /// Whether each path is a loop (closed or ending where it starts).
    looped: Vec<bool>,
    /// The end point of each open path.
    ends: Vec<Point>,
}

impl Candidates {
    fn new(paths: &[StyledPath], options: &SortOptions) -> Candidates {
        let mut c = Candidates {
            points: Vec::with_capacity(2 * paths.len()),
            first: Vec::with_capacity(paths.len() + 1),
            looped: Vec::with_capacity(paths.len()),
            ends: Vec::with_capacity(paths.len()),
        };
        for p in paths {
            c.first.push(c.points.len() as u32);
            // `split_subpaths` left one subpath in every path.
            let sub = subpaths(&p.path).next();
            let start = sub.map_or(Point::ZERO, |s| s.start());
            let end = sub.map_or(start, |s| s.end());
            let looped = sub.is_some_and(|s| s.is_closed());
            c.looped.push(looped);
            c.ends.push(end);
            if looped {
                match sub {
                    Some(sub) if options.rotate_closed => loop_vertices(sub, &mut c.points),
                    _ => c.points.push(start),
                }
            } else {
                // Entered at the start: candidate 0; at the end: candidate 1.
                c.points.push(start);
                if options.reverse {
                    c.points.push(end);
                }
            }
        }
        c.first.push(c.points.len() as u32);
        c
    }

    fn range(&self, path: usize) -> std::ops::Range<usize> {
        self.first[path] as usize..self.first[path + 1] as usize
    }

    /// The greedy nearest-neighbour order from the origin.
    fn greedy(&self) -> Tour {
        let n = self.looped.len();
        let mut index = PointIndex::new(&self.points);
        let mut owner = vec![0u32; self.points.len()];
        for p in 0..n {
            for c in self.range(p) {
                owner[c] = p as u32;
            }
        }
        let mut tour = Tour::with_capacity(n);
        let mut placed = vec![false; n];
        let mut pen = Point::ORIGIN;
        while let Some((c, _)) = index.nearest_within(pen, f64::INFINITY) {
            let p = owner[c as usize] as usize;
            let range = self.range(p);
            for cc in range.clone() {
                index.remove(cc as u32);
            }
            placed[p] = true;
            let k = c as usize - range.start;
            pen = self.push(&mut tour, p, k);
        }
        // Paths whose entry points the index cannot rank (not finite) go
        // last, in their original order: never lose a path.
        for (p, _) in placed.iter().enumerate().filter(|(_, &done)| !done) {
            self.push(&mut tour, p, 0);
        }
        tour
    }

    /// Appends path `p` entered at its candidate `k`; returns the exit.
    fn push(&self, tour: &mut Tour, p: usize, k: usize) -> Point {
        let entry = self.points[self.first[p] as usize + k];
        let (exit, rev, vert) = if self.looped[p] {
            (entry, false, k as u32)
        } else if k == 1 {
            (self.points[self.first[p] as usize], true, 0)
        } else {
            (self.ends[p], false, 0)
        };
        tour.path.push(p as u32);
        tour.a.push(entry);
        tour.b.push(exit);
        tour.rev.push(rev);
        tour.vert.push(vert);
        exit
    }
}

/// Pushes the on-curve vertices of a loop at which it may start: the start
/// of each segment (the closing line included).
fn loop_vertices(sub: Subpath, out: &mut Vec<Point>) {
    let start = sub.start();
    out.push(start);
    let Some((last, inner)) = sub.drawn().split_last() else {
        return; // `M p Z`: a dot.
    };
    // The end of each segment but the last is the start of the next; the
    // last one ends at the start, unless a closing line goes on from it.
    out.extend(inner.iter().map(|el| el_end(*el)));
    if el_end(*last) != start {
        out.push(el_end(*last));
    }
}

/// A loop drawn from its vertex `k` (as numbered by [`loop_vertices`]).
/// Its closing line becomes a line of its own: the one a close-path draws,
/// or the one across the gap (at most [`CLOSE_TOLERANCE`]) of a loop that
/// ends next to its start rather than on it.
///
/// [`CLOSE_TOLERANCE`]: crate::geom::subpath::CLOSE_TOLERANCE
fn rotate_loop(path: &BezPath, k: usize) -> BezPath {
    let Some(sub) = subpaths(path).next().filter(|_| k > 0) else {
        return path.clone();
    };
    let start = sub.start();
    let mut segs: Vec<PathEl> = sub.drawn().to_vec();
    if segs.last().map(|el| el_end(*el)) != Some(start) {
        segs.push(PathEl::LineTo(start));
    }
    let mut out = Vec::with_capacity(segs.len() + 2);
    out.push(PathEl::MoveTo(el_end(segs[k - 1])));
    out.extend_from_slice(&segs[k..]);
    out.extend_from_slice(&segs[..k]);
    if sub.ends_with_close() {
        out.push(PathEl::ClosePath);
    }
    BezPath::from_vec(out)
}

/// Improvements smaller than this (mm) are not worth a change; it also
/// keeps rounding from making a "shorter" order longer.
const EPS: f64 = 1e-9;

/// Straight distance (without `hypot`'s care for overflow, which page
/// coordinates do not need, and much faster).
#[inline]
fn dist(a: Point, b: Point) -> f64 {
    dist2(a, b).sqrt()
}

/// Squared distance.
#[inline]
fn dist2(a: Point, b: Point) -> f64 {
    let (dx, dy) = (a.x - b.x, a.y - b.y);
    dx * dx + dy * dy
}

/// Improvement passes stop once a pass shortens the travel by less than
/// this fraction (0.1 %).
const MIN_PASS_GAIN: f64 = 1e-3;

/// An order: position → path, with entry point `a`, exit point `b`,
/// whether an open path is drawn backwards, and where a loop starts; and,
/// during the improvement passes, the length of the pen-up move into each
/// position.
struct Tour {
    path: Vec<u32>,
    a: Vec<Point>,
    b: Vec<Point>,
    rev: Vec<bool>,
    vert: Vec<u32>,
    /// `edge[k]` = distance from `before(k)` to `a[k]`; kept up to date by
    /// every change once [`Tour::fix_edges`] has filled it.
    edge: Vec<f64>,
}

impl Tour {
    fn with_capacity(n: usize) -> Tour {
        Tour {
            path: Vec::with_capacity(n),
            a: Vec::with_capacity(n),
            b: Vec::with_capacity(n),
            rev: Vec::with_capacity(n),
            vert: Vec::with_capacity(n),
            edge: Vec::new(),
        }
    }

    fn len(&self) -> usize {
        self.path.len()
    }

    /// Where the pen is before drawing position `i`.
    fn before(&self, i: usize) -> Point {
        if i == 0 {
            Point::ORIGIN
        } else {
            self.b[i - 1]
        }
    }

    /// The pen-up travel of this order.
    fn travel(&self) -> f64 {
        (0..self.len())
            .map(|i| dist(self.before(i), self.a[i]))
            .sum()
    }

    /// Recomputes `edge[lo..=hi]` (clamped to the tour).
    fn fix_edges(&mut self, lo: usize, hi: usize) {
        let n = self.len();
        self.edge.resize(n, 0.0);
        for k in lo..=hi.min(n.saturating_sub(1)) {
            self.edge[k] = dist(self.before(k), self.a[k]);
        }
    }

    fn improve(&mut self, cands: &Candidates, options: &SortOptions) {
        let window = options.window.max(1) as usize;
        let or_window = (window / 8).max(2);
        self.fix_edges(0, self.len());
        let mut travel = self.travel();
        for _ in 0..options.max_passes {
            if options.reverse {
                self.two_opt_pass(window);
            }
            self.or_opt_pass(or_window, options.reverse);
            if options.rotate_closed {
                self.rotate_pass(cands);
            }
            let now = self.travel();
            if travel - now <= MIN_PASS_GAIN * travel {
                break;
            }
            travel = now;
        }
    }

    /// Draws positions `i..=j` in the opposite order, each backwards.
    fn reverse(&mut self, i: usize, j: usize) {
        self.path[i..=j].reverse();
        self.a[i..=j].reverse();
        self.b[i..=j].reverse();
        self.rev[i..=j].reverse();
        self.vert[i..=j].reverse();
        for k in i..=j {
            std::mem::swap(&mut self.a[k], &mut self.b[k]);
            // A loop's entry and exit are one point and `build` ignores
            // its flag: loops are never drawn backwards.
            self.rev[k] = !self.rev[k];
        }
        if !self.edge.is_empty() {
            // The moves inside the run are the same, in reverse order.
            self.edge[i + 1..=j].reverse();
            self.fix_edges(i, i);
            self.fix_edges(j + 1, j + 1);
        }
    }

    /// Rotates positions `lo..=hi` left (`left`) or right by `k`.
    fn rotate(&mut self, lo: usize, hi: usize, k: usize, left: bool) {
        fn rot<T>(v: &mut [T], k: usize, left: bool) {
            if left {
                v.rotate_left(k);
            } else {
                v.rotate_right(k);
            }
        }
        rot(&mut self.path[lo..=hi], k, left);
        rot(&mut self.a[lo..=hi], k, left);
        rot(&mut self.b[lo..=hi], k, left);
        rot(&mut self.rev[lo..=hi], k, left);
        rot(&mut self.vert[lo..=hi], k, left);
        if !self.edge.is_empty() {
            self.fix_edges(lo, hi + 1);
        }
    }

    /// One pass of windowed 2-opt: reverse `i..=j` (with `j - i < window`)
    /// wherever that shortens the travel. Returns whether anything changed.
    fn two_opt_pass(&mut self, window: usize) -> bool {
        let n = self.len();
        let mut improved = false;
        for i in 0..n {
            let prev = self.before(i);
            let last = (i + window - 1).min(n - 1);
            let mut j = i;
            while j <= last {
                // Now: prev → a[i] … b[j] → a[j + 1]; after: prev → b[j] …
                // a[i] → a[j + 1]. The new first move alone must already be
                // shorter than both old moves; most `j` fail that cheaply,
                // so find the next one that does not first.
                let old_i = self.edge[i];
                // Positions before `inner_end` have a next path.
                let inner_end = (last + 1).min(n - 1).max(j);
                let skip = self.b[j..inner_end]
                    .iter()
                    .zip(&self.edge[j + 1..inner_end + 1])
                    .position(|(&bj, &ej)| {
                        let old = old_i + ej;
                        dist2(prev, bj) < old * old
                    });
                j = match skip {
                    Some(k) => j + k,
                    None if inner_end <= last => inner_end,
                    None => break,
                };
                let old = old_i + self.edge.get(j + 1).copied().unwrap_or(0.0);
                let new = dist(prev, self.b[j])
                    + self.a.get(j + 1).map_or(0.0, |&next| dist(self.a[i], next));
                if new < old - EPS {
                    self.reverse(i, j);
                    improved = true;
                }
                j += 1;
            }
        }
        improved
    }

    /// One pass of Or-opt: move a run of 1–3 paths (backwards too when
    /// `reverse`) before a position at most about `window` places away,
    /// wherever that shortens the travel.
    fn or_opt_pass(&mut self, window: usize, reverse: bool) -> bool {
        let n = self.len();
        let mut improved = false;
        for i in 0..n {
            let before = self.before(i);
            let ai = self.a[i];
            // What taking out the run i..i + len saves, for len 1, 2, 3.
            let mut gains = [0.0; 3];
            for (len, gain) in (1..=3).zip(&mut gains) {
                let e = i + len - 1;
                if e >= n {
                    break;
                }
                *gain = match self.a.get(e + 1) {
                    Some(&next) => self.edge[i] + self.edge[e + 1] - dist(before, next),
                    None => self.edge[i],
                };
            }
            if gains.iter().all(|g| *g <= EPS) {
                continue;
            }
            // Insert between x = before(q1) and y = a[q1] (q1 = 0: at the
            // very beginning; q1 = n: at the end).
            let lo = (i + 1).saturating_sub(window);
            let hi = (i + 3 + window).min(n);
            'q: for q1 in lo..=hi {
                if q1 == i {
                    continue;
                }
                let x = self.before(q1);
                let y = self.a.get(q1).copied();
                let d_xy = self.edge.get(q1).copied().unwrap_or(0.0);
                let d2_x_ai = dist2(x, ai);
                for (len, &gain) in (1..=3).zip(&gains) {
                    let e = i + len - 1;
                    if gain <= EPS || (q1 > i && q1 <= e + 1) {
                        continue;
                    }
                    // Entering the run costs at least the move to it, which
                    // must stay under what the move saves.
                    let bound = gain + d_xy - EPS;
                    if bound <= 0.0 {
                        continue;
                    }
                    let be = self.b[e];
                    let forward = if d2_x_ai < bound * bound {
                        d2_x_ai.sqrt() + y.map_or(0.0, |y| dist(be, y))
                    } else {
                        f64::INFINITY
                    };
                    let backward = match reverse {
                        true if dist2(x, be) < bound * bound => {
                            dist(x, be) + y.map_or(0.0, |y| dist(ai, y))
                        }
                        _ => f64::INFINITY,
                    };
                    if forward.min(backward) < bound {
                        // Move the run, then reverse it in place if needed.
                        let start = if q1 > e {
                            self.rotate(i, q1 - 1, len, true);
                            q1 - len
                        } else {
                            self.rotate(q1, e, len, false);
                            q1
                        };
                        if backward < forward {
                            self.reverse(start, start + len - 1);
                        }
                        improved = true;
                        break 'q;
                    }
                }
            }
        }
        improved
    }

    /// Re-chooses where each loop starts, for its current neighbours.
    fn rotate_pass(&mut self, cands: &Candidates) -> bool {
        let n = self.len();
        let mut improved = false;
        for i in 0..n {
            let p = self.path[i] as usize;
            if !cands.looped[p] {
                continue;
            }
            let prev = self.before(i);
            let next = (i + 1 < n).then(|| self.a[i + 1]);
            let cost = |v: Point| dist(prev, v) + next.map_or(0.0, |y| dist(v, y));
            let range = cands.range(p);
            let mut best = (cost(self.a[i]), self.vert[i] as usize);
            for (k, &v) in cands.points[range].iter().enumerate() {
                let c = cost(v);
                if c < best.0 - EPS {
                    best = (c, k);
                }
            }
            if best.1 != self.vert[i] as usize {
                let v = cands.points[cands.first[p] as usize + best.1];
                self.a[i] = v;
                self.b[i] = v;
                self.vert[i] = best.1 as u32;
                if !self.edge.is_empty() {
                    self.fix_edges(i, i + 1);
                }
                improved = true;
            }
        }
        improved
    }

    /// The paths in tour order, reversed or rotated as chosen.
    fn build(self, paths: Vec<StyledPath>, cands: &Candidates) -> Vec<StyledPath> {
        let mut slots: Vec<Option<StyledPath>> = paths.into_iter().map(Some).collect();
        let mut out = Vec::with_capacity(slots.len());
        for i in 0..self.len() {
            let p = self.path[i] as usize;
            let Some(mut sp) = slots[p].take() else {
                continue;
            };
            if cands.looped[p] {
                sp.path = rotate_loop(&sp.path, self.vert[i] as usize);
            } else if self.rev[i] {
                reverse_open_in_place(&mut sp.path);
            }
            out.push(sp);
        }
        out
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::geom::path_length;
    use crate::plot::stats::pen_up_length;
    use crate::scene::Style;
    use kurbo::{Line, PathSeg, Shape};
    use proptest::prelude::*;

    pub(crate) fn styled(id: impl Into<String>, path: BezPath) -> StyledPath {
        StyledPath {
            id: id.into(),
            path,
            style: Style::default(),
        }
    }

    pub(crate) fn line(a: (f64, f64), b: (f64, f64)) -> BezPath {
        Line::new(a, b).into_path(0.1)
    }

    /// A segment with its points in a canonical direction, as exact bits,
    /// so that multisets compare "up to reversal".
    pub(crate) fn seg_key(seg: PathSeg) -> Vec<u64> {
        let pts: Vec<Point> = match seg {
            PathSeg::Line(l) => vec![l.p0, l.p1],
            PathSeg::Quad(q) => vec![q.p0, q.p1, q.p2],
            PathSeg::Cubic(c) => vec![c.p0, c.p1, c.p2, c.p3],
        };
        let bits = |pts: &[Point]| -> Vec<u64> {
            pts.iter()
                .flat_map(|p| [p.x.to_bits(), p.y.to_bits()])
                .collect()
        };
        let fwd = bits(&pts);
        let mut rev_pts = pts.clone();
        rev_pts.reverse();
        let rev = bits(&rev_pts);
        fwd.min(rev)
    }

    pub(crate) fn seg_multiset<'a>(paths: impl IntoIterator<Item = &'a BezPath>) -> Vec<Vec<u64>> {
        let mut v: Vec<Vec<u64>> = paths
            .into_iter()
            .flat_map(|p| p.segments().map(seg_key).collect::<Vec<_>>())
            .collect();
        v.sort();
        v
    }

    /// A path's segments, canonical, as a sorted list: equal for a path and
    /// itself reversed or rotated.
    fn path_key(p: &BezPath) -> Vec<Vec<u64>> {
        seg_multiset([p])
    }

    fn point() -> impl Strategy<Value = (f64, f64)> {
        (0i32..200, 0i32..200).prop_map(|(x, y)| (x as f64 * 0.5, y as f64 * 0.5))
    }

    /// A short path of 1–3 lines or cubics.
    fn piece() -> impl Strategy<Value = BezPath> {
        (
            point(),
            prop::collection::vec((point(), point(), point(), any::<bool>()), 1..4),
        )
            .prop_map(|(start, segs)| {
                let mut p = BezPath::new();
                p.move_to(start);
                for (c1, c2, end, curve) in segs {
                    if curve {
                        p.curve_to(c1, c2, end);
                    } else {
                        p.line_to(end);
                    }
                }
                p
            })
    }

    /// Random sets of short paths, with some closed loops, some chains that
    /// share endpoints (some pieces reversed), some multi-subpath paths.
    pub(crate) fn path_set() -> impl Strategy<Value = Vec<BezPath>> {
        prop::collection::vec((piece(), 0u8..6), 0..40).prop_map(|items| {
            let mut out: Vec<BezPath> = Vec::new();
            for (p, kind) in items {
                match kind {
                    // Closed loop.
                    0 => {
                        let mut p = p;
                        p.close_path();
                        out.push(p);
                    }
                    // Continue the previous open path's chain (reversed
                    // half of the time).
                    1 | 2 => {
                        let prev_end = out
                            .last()
                            .and_then(|q| subpaths(q).next())
                            .filter(|s| !s.ends_with_close())
                            .map(|s| s.end());
                        let mut els = p.elements().to_vec();
                        if let Some(e) = prev_end {
                            els[0] = PathEl::MoveTo(e);
                        }
                        let q = BezPath::from_vec(els);
                        out.push(if kind == 2 {
                            super::super::flatten::reverse_open(&q)
                        } else {
                            q
                        });
                    }
                    // Two subpaths in one path.
                    3 => {
                        let mut q = p.clone();
                        q.move_to((1.0, 2.0));
                        q.line_to((3.0, 4.0));
                        out.push(q);
                    }
                    _ => out.push(p),
                }
            }
            out
        })
    }

    fn styled_all(paths: &[BezPath]) -> Vec<StyledPath> {
        paths
            .iter()
            .enumerate()
            .map(|(i, p)| styled(format!("p{i}"), p.clone()))
            .collect()
    }

    fn multiset_of_paths(paths: &[StyledPath]) -> Vec<Vec<Vec<u64>>> {
        let mut v: Vec<_> = paths.iter().map(|p| path_key(&p.path)).collect();
        v.sort();
        v
    }

    fn travel(paths: &[StyledPath]) -> f64 {
        pen_up_length(paths.iter().map(|p| &p.path))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]

        #[test]
        fn sort_keeps_paths_and_never_lengthens_greedy(paths in path_set()) {
            let input = split_subpaths(styled_all(&paths));
            let down: f64 = input.iter().map(|p| path_length(&p.path)).sum();
            let greedy = order(input.clone(), &SortOptions::DEFAULT.with_two_opt(false));
            let best = order(input.clone(), &SortOptions::DEFAULT);
            for out in [&greedy, &best] {
                prop_assert_eq!(multiset_of_paths(out), multiset_of_paths(&input));
                let mut ids: Vec<&str> = out.iter().map(|p| p.id.as_str()).collect();
                let mut want: Vec<&str> = input.iter().map(|p| p.id.as_str()).collect();
                ids.sort_unstable();
                want.sort_unstable();
                prop_assert_eq!(ids, want);
                let d: f64 = out.iter().map(|p| path_length(&p.path)).sum();
                prop_assert!((d - down).abs() <= 1e-6 * (1.0 + down));
                // Every path still starts with its move-to and is one subpath.
                prop_assert!(out.iter().all(|p| subpaths(&p.path).count() == 1));
            }
            prop_assert!(travel(&best) <= travel(&greedy) + 1e-9);
        }

        #[test]
        fn improvement_passes_never_lengthen(paths in path_set(), window in 1u32..6, reverse: bool, rotate: bool) {
            let input = split_subpaths(styled_all(&paths));
            if input.is_empty() {
                return Ok(());
            }
            let options = SortOptions::DEFAULT
                .with_window(window)
                .with_reverse(reverse)
                .with_rotate_closed(rotate);
            let cands = Candidates::new(&input, &options);
            let mut tour = cands.greedy();
            tour.fix_edges(0, tour.len());
            let mut before = tour.travel();
            let w = window as usize;
            for _ in 0..3 {
                if reverse {
                    tour.two_opt_pass(w);
                    let t = tour.travel();
                    prop_assert!(t <= before + 1e-9, "2-opt {} > {}", t, before);
                    before = t;
                }
                tour.or_opt_pass(w, reverse);
                let t = tour.travel();
                prop_assert!(t <= before + 1e-9, "or-opt {} > {}", t, before);
                before = t;
                if rotate {
                    tour.rotate_pass(&cands);
                    let t = tour.travel();
                    prop_assert!(t <= before + 1e-9, "rotate {} > {}", t, before);
                    before = t;
                }
            }
            // The tour's own bookkeeping matches the paths it builds.
            let built = tour.build(input, &cands);
            prop_assert!((travel(&built) - before).abs() < 1e-6);
        }
    }

    #[test]
    fn reverses_and_rotates_to_save_travel() {
        // A line whose end is near the origin, and a square whose corner
        // (10,10) is nearest to that line's far end.
        let mut square = BezPath::new();
        square.move_to((20.0, 20.0));
        square.line_to((10.0, 20.0));
        square.line_to((10.0, 10.0));
        square.line_to((20.0, 10.0));
        square.close_path();
        let paths = vec![
            styled("square", square.clone()),
            styled("line", line((10.0, 9.0), (1.0, 0.0))),
        ];
        let out = order(paths, &SortOptions::DEFAULT);
        assert_eq!(out[0].id, "line");
        assert_eq!(
            out[0].path.elements()[0],
            PathEl::MoveTo(Point::new(1.0, 0.0))
        );
        assert_eq!(out[1].id, "square");
        assert_eq!(
            out[1].path.elements()[0],
            PathEl::MoveTo(Point::new(10.0, 10.0))
        );
        assert!(crate::geom::subpath::is_closed(&out[1].path));
        assert_eq!(seg_multiset([&out[1].path]), seg_multiset([&square]));
        let t = travel(&out);
        assert!((t - (1.0 + 1.0)).abs() < 1e-12, "{t}");
    }

    #[test]
    fn options_off_keep_direction() {
        let paths = vec![
            styled("far", line((50.0, 50.0), (60.0, 60.0))),
            styled("near", line((5.0, 5.0), (0.0, 0.0))),
        ];
        let out = order(
            paths,
            &SortOptions::DEFAULT
                .with_reverse(false)
                .with_rotate_closed(false),
        );
        assert_eq!(out[0].id, "near");
        assert_eq!(
            out[0].path.elements()[0],
            PathEl::MoveTo(Point::new(5.0, 5.0))
        );
    }

    fn first(p: &BezPath) -> Subpath<'_> {
        subpaths(p).next().unwrap()
    }

    #[test]
    fn rotating_keeps_cubic_loops_exact() {
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.curve_to((1.0, 2.0), (3.0, 2.0), (4.0, 0.0));
        p.curve_to((3.0, -2.0), (1.0, -2.0), (0.0, 0.0));
        let mut verts = Vec::new();
        loop_vertices(first(&p), &mut verts);
        assert_eq!(verts, [Point::new(0.0, 0.0), Point::new(4.0, 0.0)]);
        let r = rotate_loop(&p, 1);
        assert_eq!(r.elements()[0], PathEl::MoveTo(Point::new(4.0, 0.0)));
        assert_eq!(seg_multiset([&r]), seg_multiset([&p]));
        // A dot has one vertex.
        let mut dot = BezPath::new();
        dot.move_to((3.0, 3.0));
        dot.close_path();
        verts.clear();
        loop_vertices(first(&dot), &mut verts);
        assert_eq!(verts, [Point::new(3.0, 3.0)]);
    }

    #[test]
    fn a_loop_closed_within_the_tolerance_rotates_across_its_gap() {
        use kurbo::Affine;
        // Back to 1e-10 mm from its start, without a close-path.
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.line_to((10.0, 0.0));
        p.line_to((10.0, 10.0));
        p.line_to((1e-10, 0.0));
        let mut verts = Vec::new();
        loop_vertices(subpaths(&p).next().unwrap(), &mut verts);
        assert_eq!(verts.len(), 4);
        let r = rotate_loop(&p, 1);
        assert_eq!(
            r.elements(),
            [
                PathEl::MoveTo(Point::new(10.0, 0.0)),
                PathEl::LineTo(Point::new(10.0, 10.0)),
                PathEl::LineTo(Point::new(1e-10, 0.0)),
                PathEl::LineTo(Point::new(0.0, 0.0)),
                PathEl::LineTo(Point::new(10.0, 0.0)),
            ]
        );
        // After a line that ends next to its far corner, it is drawn from
        // there round to there.
        let out = order(
            vec![
                styled("loop", Affine::translate((20.0, 20.0)) * p),
                styled("line", line((0.0, 0.0), (29.0, 29.0))),
            ],
            &SortOptions::DEFAULT,
        );
        assert_eq!(out[1].id, "loop");
        let els = out[1].path.elements();
        assert_eq!(els[0], PathEl::MoveTo(Point::new(30.0, 30.0)));
        assert_eq!(els.last(), Some(&PathEl::LineTo(Point::new(30.0, 30.0))));
        assert_eq!(els.len(), 5);
    }

    #[test]
    fn run_works_layer_by_layer_and_keeps_ink() {
        use crate::plot::flatten::by_pen;
        use crate::plot::merge::{self, MergeOptions};
        use crate::scene::{Group, Layer, Node};
        use crate::units::{Margins, Orientation, Page, PaperName};
        // Two pens whose paths would chain into each other if mixed.
        let mut g1 = Group::new("g1");
        let mut g2 = Group::new("g2");
        for i in 0..20 {
            let x = f64::from(i);
            g1.push_path(
                format!("a{i}"),
                line((x, 0.0), (x + 1.0, 0.0)),
                Style::default(),
            );
            g2.push_path(
                format!("b{i}"),
                line((x + 1.0, 0.0), (x, 5.0)),
                Style::default(),
            );
        }
        let layer = |id: &str, pen, content| Layer {
            id: id.into(),
            name: id.into(),
            pen,
            depth: 0,
            content,
        };
        let scene = Scene {
            page: Page::named(PaperName::A4, Orientation::Portrait, Margins::uniform(10.0)),
            pens: vec![],
            layers: vec![layer("one", 1, g1), layer("two", 2, g2)],
            description: None,
        };
        let mut flat = by_pen(&scene);
        merge::run(&mut flat, &MergeOptions::DEFAULT);
        run(&mut flat, &SortOptions::DEFAULT);
        for (l, prefix) in flat.layers.iter().zip(['a', 'b']) {
            assert!(l.content.children.iter().all(|n| match n {
                Node::Path(p) => p.id.starts_with(prefix),
                Node::Group(_) => false,
            }));
            let before = scene.pen_stats(l.pen).pen_down_mm;
            assert!((flat.pen_stats(l.pen).pen_down_mm - before).abs() < 1e-9);
        }
        // Pen 1's twenty pieces are one line now.
        assert_eq!(flat.layers[0].content.children.len(), 1);
    }

    #[test]
    fn options_read_from_partial_json_with_defaults() {
        let o: SortOptions = serde_json::from_str(r#"{"window": 8}"#).unwrap();
        assert_eq!(o, SortOptions::DEFAULT.with_window(8));
        assert!(serde_json::from_str::<SortOptions>(r#"{"windw": 8}"#).is_err());
        let m: crate::plot::merge::MergeOptions =
            serde_json::from_str(r#"{"tolerance": 0.1}"#).unwrap();
        assert_eq!(
            m,
            crate::plot::merge::MergeOptions::DEFAULT.with_tolerance(0.1)
        );
        let t: crate::plot::transform::TransformOptions =
            serde_json::from_str(r#"{"fit": true, "margin": 12.5}"#).unwrap();
        assert!(t.fit && t.margin == Some(12.5) && t.scale == 1.0);
    }

    #[test]
    fn non_finite_paths_are_kept() {
        let paths = vec![
            styled("nan", line((f64::NAN, 0.0), (1.0, 1.0))),
            styled("ok", line((1.0, 0.0), (2.0, 0.0))),
        ];
        let out = order(paths, &SortOptions::DEFAULT);
        let ids: Vec<&str> = out.iter().map(|p| p.id.as_str()).collect();
        assert_eq!(ids.len(), 2);
        assert!(ids.contains(&"nan") && ids.contains(&"ok"));
    }

    /// Release-mode timing of merge + sort on 100,000 short paths (not an
    /// assertion): `cargo test --release --lib plot::sort::tests::timing
    /// -- --ignored --nocapture`. Two drawings: random scattered strokes
    /// (lines and cubics up to ~3 mm, little to merge), and 1,000 random
    /// walks cut into 100 pieces each, shuffled, half of them reversed and
    /// a quarter moved by 0.03 mm (everything to merge).
    #[test]
    #[ignore]
    #[allow(clippy::print_stdout)]
    fn timing_100k() {
        use crate::plot::merge::{self, MergeOptions};
        let mut rng = crate::Seed(7).derive("sort-timing").stream();
        let mut scattered = Vec::new();
        for i in 0..100_000 {
            let x = rng.unit() * 400.0;
            let y = rng.unit() * 280.0;
            let dx = rng.unit() * 4.0 - 2.0;
            let dy = rng.unit() * 4.0 - 2.0;
            let mut p = BezPath::new();
            p.move_to((x, y));
            if i % 2 == 0 {
                p.line_to((x + dx, y + dy));
            } else {
                p.curve_to(
                    (x + dy, y - dx),
                    (x + dx + dy, y + dy - dx),
                    (x + dx, y + dy),
                );
            }
            scattered.push(styled(format!("p{i}"), p));
        }
        let mut walks = Vec::new();
        for w in 0..1000 {
            let mut at = Point::new(rng.unit() * 400.0, rng.unit() * 280.0);
            for k in 0..100 {
                let next = at + kurbo::Vec2::new(rng.symmetric(1.0), rng.symmetric(1.0));
                let start = if rng.below(4) == 0 {
                    at + kurbo::Vec2::new(0.03, 0.0)
                } else {
                    at
                };
                let mut p = BezPath::new();
                p.move_to(start);
                p.line_to(next);
                if rng.below(2) == 0 {
                    p = super::super::flatten::reverse_open(&p);
                }
                walks.push(styled(format!("w{w}.{k}"), p));
                at = next;
            }
        }
        for i in (1..walks.len()).rev() {
            walks.swap(i, rng.below(i + 1));
        }

        // CPU time of this thread (Linux), which a busy machine inflates
        // less than wall time; the best of three runs.
        fn cpu() -> std::time::Duration {
            std::fs::read_to_string("/proc/thread-self/schedstat")
                .ok()
                .and_then(|s| s.split_whitespace().next()?.parse().ok())
                .map_or(std::time::Duration::ZERO, std::time::Duration::from_nanos)
        }
        // Input copies are made and results dropped outside the timing.
        fn best_of<I: Clone, T>(input: &I, f: impl Fn(I) -> T) -> (T, std::time::Duration) {
            let mut best = std::time::Duration::MAX;
            let mut out = None;
            for _ in 0..3 {
                let copy = input.clone();
                drop(out.take());
                let t = cpu();
                let r = f(copy);
                best = best.min(cpu() - t);
                out = Some(r);
            }
            (out.unwrap(), best)
        }
        for (name, paths) in [("scattered", &scattered), ("walks", &walks)] {
            let (merged, t_merge) = best_of(paths, |p| merge::merge(p, &MergeOptions::DEFAULT));
            let greedy_options = SortOptions::DEFAULT.with_two_opt(false);
            let (greedy, t_greedy) = best_of(&merged, |p| order(p, &greedy_options));
            let (best, t_full) = best_of(&merged, |p| order(p, &SortOptions::DEFAULT));
            let (_, t_both) = best_of(paths, |p| {
                order(
                    merge::merge(p, &MergeOptions::DEFAULT),
                    &SortOptions::DEFAULT,
                )
            });
            println!(
                "{name}: {} → {} paths; merge {t_merge:?}, greedy sort {t_greedy:?}, \
                 full sort {t_full:?}, merge + full sort {t_both:?}",
                paths.len(),
                merged.len(),
            );
            println!(
                "{name}: travel as given {:.0} mm, greedy {:.0} mm, improved {:.0} mm \
                 ({:.1} % less than greedy)",
                travel(&merged),
                travel(&greedy),
                travel(&best),
                100.0 * (1.0 - travel(&best) / travel(&greedy))
            );
        }
        for w in [8, 16, 32, 64, 128] {
            let o = SortOptions::DEFAULT.with_window(w);
            let (r, t) = best_of(&scattered, |p| order(p, &o));
            println!(
                "scattered, window {w}: sort {t:?}, travel {:.0} mm",
                travel(&r)
            );
        }
    }
}
