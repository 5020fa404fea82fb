//! Blots: square millimetres where a pen would lay down more ink than the
//! paper takes. Lines that converge on a point — leaves meeting at a node,
//! petals at a flower's centre, a whirl's last turns, strokes ending on one
//! another — stop short of it, as an illustrator leaves them, instead of
//! filling it with a puddle of ink that pills or tears the paper.
//!
//! A pen `w` mm wide covers paper solid with `1 / w` mm of line per mm².
//! Ink is counted as `moyo stats` counts its densest mm²
//! ([`super::stats::densest`]): line cut into pieces of at most 0.05 mm,
//! each in the 1 mm cell (aligned to the page origin) of its middle. In a
//! cell holding more than the *limit* (default twice solid), the line
//! ends there are trimmed back, a twentieth of a millimetre at a time and
//! each end in turn, so that converging lines stop short evenly, until the
//! cell holds no more than the limit less a margin of 5 % (for readers
//! that count cells otherwise); an end that stops less than a
//! millimetre short of the cell, its line passing through it, is trimmed
//! back into it too. No end goes back more than [`MAX_TRIM`]: more than
//! that would be needed where line work piles up or runs in a bundle, not
//! where it meets, and thinning that is the generator's (as the zentangle
//! loop's ink limit does).
//! A closed subpath with nothing else to trim is opened
//! there once (that costs no pen lift); line that only passes through a
//! cell is never cut, so this stage adds no pen lift.
//! An end trimmed into the next cell goes on being trimmed there if that
//! cell is over the limit too. What a trim leaves is an exact sub-curve;
//! untouched subpaths keep their elements, and paths with a fill are left
//! alone.
//!
//! Cost: linear in the length of the drawing.

use kurbo::{BezPath, Point};
use rustc_hash::FxHashMap;
use serde::{Deserialize, Serialize};

use super::cover::Pieces;
use super::flatten::{set_paths, take_paths};
use crate::geom::subpath::subpaths;
use crate::scene::{Scene, StyledPath};

/// Pieces of line are no longer than this (mm), as `moyo stats` counts.
const PIECE: f64 = 0.05;

/// An end this close to a crowded cell along its line (mm) is trimmed
/// back into it.
const REACH: f64 = 1.0;

/// No end is trimmed back by more than this (mm): converging lines stop
/// short by a little, as a hand leaves them; where more would be needed
/// the line work is a pile or a bundle, not a meeting point, and is the
/// generator's to thin.
pub const MAX_TRIM: f64 = 1.5;

/// Cells are thinned to this share under the limit. A reader that cuts
/// line into other pieces or lays its cells otherwise counts a crowded
/// cell a few percent higher or lower (bench/pen_metrics.py, with pieces
/// a quarter of a pen long, found 2.09× solid in katagami's cells this
/// stage had thinned to 2.0×), and a trimmed curve measured again is cut
/// into pieces from its new end, which may move a piece's middle across
/// a cell border.
const COUNT_MARGIN: f64 = 0.05;

/// Curves are measured on chords this close to them (mm).
const FLAT: f64 = 0.01;

/// Options of [`run`].
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BlotOptions {
    /// The most ink a square millimetre may hold, in multiples of what
    /// covers it solid for its pen (0.5 to 10, default 2).
    pub limit: f64,
}

impl BlotOptions {
    /// Twice solid ink.
    pub const DEFAULT: BlotOptions = BlotOptions { limit: 2.0 };

    /// These options with this limit (multiples of solid ink).
    pub const fn with_limit(mut self, limit: f64) -> BlotOptions {
        self.limit = limit;
        self
    }
}

impl Default for BlotOptions {
    fn default() -> Self {
        BlotOptions::DEFAULT
    }
}

/// Thins the blots of every layer of a flat scene (see the module
/// documentation), each with its pen's width.
pub fn run(scene: &mut Scene, options: &BlotOptions) {
    for i in 0..scene.layers.len() {
        let width = scene.pen_width(scene.layers[i].pen);
        let layer = &mut scene.layers[i];
        let paths = take_paths(layer);
        set_paths(
            layer,
            thin(paths, options.limit / width * (1.0 - COUNT_MARGIN)),
        );
    }
}

/// A subpath and which of its pieces are still drawn: `lo..hi`, indices
/// taken modulo the piece count once a closed subpath is opened.
struct Sub {
    /// Its path, and its place among the path's subpaths.
    path: usize,
    nth: usize,
    pieces: Pieces,
    lo: usize,
    hi: usize,
    /// How much has been trimmed off its start and its end (mm).
    trimmed: [f64; 2],
    /// A closed subpath not opened yet.
    whole_ring: bool,
    touched: bool,
}

impl Sub {
    fn n(&self) -> usize {
        self.pieces.pieces.len()
    }

    fn left(&self) -> usize {
        self.hi - self.lo
    }

    /// The piece at index `i`, which runs past the last piece on an
    /// opened ring.
    fn piece(&self, i: usize) -> usize {
        i % self.n()
    }
}

/// `paths` with no cell over `limit` mm of line per mm² where trimming
/// line ends can help (see the module documentation).
pub fn thin(paths: Vec<StyledPath>, limit: f64) -> Vec<StyledPath> {
    let mut subs = Vec::new();
    for (k, p) in paths.iter().enumerate() {
        if p.style.fill.is_some() {
            continue;
        }
        for (nth, s) in subpaths(&p.path).enumerate() {
            let pieces = Pieces::new(s.segments().collect(), s.is_closed(), PIECE, FLAT);
            let n = pieces.pieces.len();
            if n == 0 {
                continue;
            }
            subs.push(Sub {
                path: k,
                nth,
                whole_ring: pieces.closed,
                pieces,
                lo: 0,
                hi: n,
                trimmed: [0.0; 2],
                touched: false,
            });
        }
    }
    let mut ink: FxHashMap<(i64, i64), f64> = FxHashMap::default();
    let mut members: FxHashMap<(i64, i64), Vec<u32>> = FxHashMap::default();
    for (j, s) in subs.iter().enumerate() {
        for p in &s.pieces.pieces {
            let c = cell(p.a.midpoint(p.b));
            *ink.entry(c).or_default() += p.len();
            let m = members.entry(c).or_default();
            if m.last() != Some(&(j as u32)) {
                m.push(j as u32);
            }
        }
    }
    let mut over: Vec<(i64, i64)> = ink
        .iter()
        .filter(|(_, &v)| v > limit)
        .map(|(&c, _)| c)
        .collect();
    if over.is_empty() {
        return paths;
    }
    // Worst last, so that the worst is thinned first (a cell an end is
    // trimmed into is pushed and thinned next).
    over.sort_by(|a, b| ink[a].total_cmp(&ink[b]).then(b.cmp(a)));
    while let Some(c) = over.pop() {
        let Some(list) = members.get(&c) else {
            continue;
        };
        // A subpath that comes back into the cell is listed once.
        let mut list = list.clone();
        list.sort_unstable();
        list.dedup();
        let mut reached = Vec::new();
        thin_cell(c, &list, &mut subs, &mut ink, limit, &mut reached);
        for d in reached {
            if ink.get(&d).is_some_and(|&v| v > limit) {
                members.entry(d).or_default();
                over.push(d);
            }
        }
    }
    rebuild(paths, &subs)
}

/// Trims the ends of `list`'s subpaths in cell `c` in turn until it holds
/// no more than `limit`; the cells ends were trimmed into go to `reached`.
fn thin_cell(
    c: (i64, i64),
    list: &[u32],
    subs: &mut [Sub],
    ink: &mut FxHashMap<(i64, i64), f64>,
    limit: f64,
    reached: &mut Vec<(i64, i64)>,
) {
    let in_cell = |s: &Sub, i: usize| {
        let p = &s.pieces.pieces[s.piece(i)];
        cell(p.a.midpoint(p.b)) == c
    };
    loop {
        let mut trimmed = false;
        for &j in list {
            if ink[&c] <= limit {
                return;
            }
            let s = &mut subs[j as usize];
            if s.whole_ring || s.left() == 0 {
                continue;
            }
            for at_start in [true, false] {
                if s.left() == 0 || ink[&c] <= limit {
                    break;
                }
                let Some(outside) = approach(s, at_start, c) else {
                    continue;
                };
                // The pieces up to the cell, then one in it, if the end
                // may go back that far.
                let side = usize::from(!at_start);
                let cut: f64 = (0..=outside)
                    .map(|n| {
                        let i = if at_start { s.lo + n } else { s.hi - 1 - n };
                        s.pieces.pieces[s.piece(i)].len()
                    })
                    .sum();
                if s.trimmed[side] + cut > MAX_TRIM {
                    continue;
                }
                s.trimmed[side] += cut;
                for _ in 0..=outside {
                    let i = if at_start { s.lo } else { s.hi - 1 };
                    let p = &s.pieces.pieces[s.piece(i)];
                    *ink.get_mut(&cell(p.a.midpoint(p.b))).expect("counted") -= p.len();
                    if at_start {
                        s.lo += 1;
                    } else {
                        s.hi -= 1;
                    }
                }
                s.touched = true;
                trimmed = true;
                if s.left() > 0 {
                    let next = if at_start { s.lo } else { s.hi - 1 };
                    if !in_cell(s, next) {
                        let p = &s.pieces.pieces[s.piece(next)];
                        reached.push(cell(p.a.midpoint(p.b)));
                    }
                }
            }
        }
        if trimmed {
            continue;
        }
        // No end left here: open a closed subpath at one of its pieces in
        // the cell (its two new ends are trimmed on the next round).
        let Some(j) = list.iter().copied().find(|&j| subs[j as usize].whole_ring) else {
            return;
        };
        let s = &mut subs[j as usize];
        let Some(i) = (0..s.n()).find(|&i| in_cell(s, i)) else {
            s.whole_ring = false;
            continue;
        };
        *ink.get_mut(&c).expect("counted") -= s.pieces.pieces[i].len();
        s.whole_ring = false;
        s.touched = true;
        s.lo = i + 1;
        s.hi = i + s.n();
    }
}

/// How many pieces lie between the end of `s` (its start with
/// `at_start`) and its first piece in cell `c`, when they are at most
/// [`REACH`] long: an end that stopped just short of a crowded cell, its
/// line passing through it, is trimmed back into it too.
fn approach(s: &Sub, at_start: bool, c: (i64, i64)) -> Option<usize> {
    let mut outside = 0.0;
    for n in 0..s.left() {
        let i = if at_start { s.lo + n } else { s.hi - 1 - n };
        let p = &s.pieces.pieces[s.piece(i)];
        if cell(p.a.midpoint(p.b)) == c {
            return Some(n);
        }
        outside += p.len();
        if outside > REACH {
            return None;
        }
    }
    None
}

/// `paths` with every touched subpath replaced by what is left of it.
fn rebuild(paths: Vec<StyledPath>, subs: &[Sub]) -> Vec<StyledPath> {
    let mut touched: FxHashMap<usize, FxHashMap<usize, &Sub>> = FxHashMap::default();
    for s in subs.iter().filter(|s| s.touched) {
        touched.entry(s.path).or_default().insert(s.nth, s);
    }
    paths
        .into_iter()
        .enumerate()
        .filter_map(|(k, mut p)| {
            let Some(cut) = touched.get(&k) else {
                return Some(p);
            };
            let mut out = BezPath::new();
            for (nth, sub) in subpaths(&p.path).enumerate() {
                match cut.get(&nth) {
                    None => out.extend(sub.elements()),
                    Some(s) if s.left() > 0 => s.pieces.cut(&runs(s), &mut out),
                    Some(_) => {}
                }
            }
            if out.elements().is_empty() {
                return None;
            }
            p.path = out;
            Some(p)
        })
        .collect()
}

/// The lengths along `s` of the pieces left, as runs for [`Pieces::cut`].
fn runs(s: &Sub) -> Vec<(f64, f64)> {
    let pieces = &s.pieces.pieces;
    let n = s.n();
    let start = |i: usize| pieces[i].s;
    let end = |i: usize| pieces[i].s + pieces[i].len();
    // An opened ring's indices may run past its last piece.
    let (lo, hi) = if s.lo >= n {
        (s.lo - n, s.hi - n)
    } else {
        (s.lo, s.hi)
    };
    if hi <= n {
        vec![(start(lo), end(hi - 1))]
    } else {
        // Through the start of a closed subpath.
        vec![(0.0, end(hi - 1 - n)), (start(lo), s.pieces.len())]
    }
}

/// The cell holding `p`.
fn cell(p: Point) -> (i64, i64) {
    (p.x.floor() as i64, p.y.floor() as i64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::stats::densest;
    use crate::scene::Style;
    use kurbo::{Circle, Shape};
    use std::f64::consts::TAU;

    fn styled(id: &str, path: BezPath) -> StyledPath {
        StyledPath {
            id: id.into(),
            path,
            style: Style::default(),
        }
    }

    /// `n` lines of length 5 mm converging on `centre` from every side.
    fn star(centre: Point, n: usize) -> Vec<StyledPath> {
        (0..n)
            .map(|k| {
                let a = TAU * k as f64 / n as f64;
                let mut p = BezPath::new();
                p.move_to(centre + 5.0 * kurbo::Vec2::from_angle(a));
                p.line_to(centre);
                styled(&format!("ray-{k}"), p)
            })
            .collect()
    }

    fn total_length(paths: &[StyledPath]) -> f64 {
        paths.iter().map(|p| p.path.perimeter(1e-6)).sum()
    }

    #[test]
    fn converging_lines_stop_short_evenly_and_the_cell_holds_the_limit() {
        let pen = 0.3;
        let paths = star(Point::new(20.5, 20.5), 24);
        assert!(densest(paths.iter().map(|p| &p.path), pen) > 4.0);
        let thinned = thin(paths.clone(), 2.0 / pen);
        assert!(densest(thinned.iter().map(|p| &p.path), pen) <= 2.0 + 1e-9);
        // Every ray is still there, each shortened by about as much.
        assert_eq!(thinned.len(), 24);
        let cuts: Vec<f64> = thinned
            .iter()
            .map(|p| 5.0 - p.path.perimeter(1e-6))
            .collect();
        let (lo, hi) = cuts
            .iter()
            .fold((f64::INFINITY, 0.0_f64), |(l, h), &c| (l.min(c), h.max(c)));
        assert!(lo > 0.0 && hi - lo <= 2.0 * PIECE + 1e-9, "{cuts:?}");
        // Only the converging ends: the outer ends are where they were.
        for (a, b) in paths.iter().zip(&thinned) {
            assert_eq!(a.id, b.id);
            let (pa, pb) = (a.path.elements()[0], b.path.elements()[0]);
            assert_eq!(pa, pb);
        }
    }

    #[test]
    fn lines_that_only_pass_through_are_not_cut() {
        // Twenty parallel lines 0.05 mm apart, 30 mm long: every cell
        // along them is far past the limit, but only their ends can be
        // trimmed, by MAX_TRIM at most; in between no line is cut (a cut
        // would cost a pen lift).
        let paths: Vec<StyledPath> = (0..20)
            .map(|k| {
                let mut p = BezPath::new();
                let y = 10.02 + 0.05 * f64::from(k);
                p.move_to((0.0, y));
                p.line_to((30.0, y));
                styled(&format!("l{k}"), p)
            })
            .collect();
        let thinned = thin(paths, 2.0 / 0.3);
        assert_eq!(thinned.len(), 20);
        for p in &thinned {
            assert_eq!(subpaths(&p.path).count(), 1);
            let b = p.path.bounding_box();
            assert!(
                b.x0 >= 0.0 && b.x1 <= 30.0 && b.width() >= 30.0 - 2.0 * MAX_TRIM - 1e-9,
                "{b:?}"
            );
        }
    }

    #[test]
    fn a_ring_in_a_blot_is_opened_once_and_stays_one_stroke() {
        // Small circles piled on one point: each is opened at most once and
        // stays one subpath.
        let paths: Vec<StyledPath> = (0..12)
            .map(|k| {
                styled(
                    &format!("c{k}"),
                    Circle::new((40.5, 40.5), 0.3).to_path(1e-3),
                )
            })
            .collect();
        let before = total_length(&paths);
        let thinned = thin(paths, 2.0 / 0.3);
        assert!(densest(thinned.iter().map(|p| &p.path), 0.3) <= 2.0 + 1e-9);
        for p in &thinned {
            assert_eq!(subpaths(&p.path).count(), 1, "{}", p.id);
        }
        assert!(total_length(&thinned) < before);
    }

    #[test]
    fn paths_under_the_limit_are_returned_as_they_were() {
        let paths = star(Point::new(20.5, 20.5), 6);
        assert_eq!(thin(paths.clone(), 2.0 / 0.3), paths);
    }
}
