//! Line merging: join paths whose ends meet, so the pen stays down.
//!
//! Each layer of a flat scene (see [`super::flatten`]) is merged on its
//! own; pens are never mixed. Paths are first split into one path per
//! subpath ([`super::flatten::split_subpaths`]).
//!
//! Greedy, in path order: the first path not yet used starts a chain; the
//! chain grows at its end, then at its start, each time by the unused path
//! with an end point nearest to the chain's free end, as long as that end
//! lies within [`MergeOptions::tolerance`]. With
//! [`MergeOptions::reverse`] a path may join back to front (end to end,
//! start to start); otherwise only end to start. Ends with another end in
//! their neighbourhood (found by sorting ends into grid cells of the
//! tolerance's size) are looked up in a k-d tree with deletion; the others
//! cannot join anything and cost nothing more. Merging is O(n log n). Ties
//! go to a start before an end, then to the lower path index, so the
//! result is deterministic.
//!
//! A chain becomes one path with the id and style of the path that started
//! it (the first in the original order), at that path's place in the
//! order. Where two ends do not coincide exactly, a straight line joins
//! them: every original segment is kept exactly (reversed pieces have their
//! points in reverse order), and the pen-down length grows by at most
//! `tolerance` per join.
//!
//! Not merged: paths that end with a close-path (joining would drop it;
//! a loop drawn back to its start without one may be joined, which
//! changes no ink) and filled paths (the fill would change); they are kept
//! as they are, at their place in the order.

use kurbo::{BezPath, PathEl, Point};
use serde::{Deserialize, Serialize};

use super::flatten::{el_end, reverse_open_in_place, set_paths, split_subpaths, take_paths};
use crate::geom::subpath::subpaths;
use crate::geom::PointIndex;
use crate::scene::{Scene, StyledPath};

/// Options of [`run`] and [`merge`].
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MergeOptions {
    /// Largest distance, in mm, between two ends that are joined. Zero
    /// joins only ends that coincide exactly; a negative or NaN value
    /// counts as zero.
    pub tolerance: f64,
    /// Paths may be drawn backwards to join them.
    pub reverse: bool,
}

impl MergeOptions {
    /// Tolerance 0.05 mm (vpype's `linemerge` default), reversal on.
    pub const DEFAULT: MergeOptions = MergeOptions {
        tolerance: 0.05,
        reverse: true,
    };

    /// These options with [`MergeOptions::tolerance`] set.
    pub const fn with_tolerance(mut self, tolerance: f64) -> MergeOptions {
        self.tolerance = tolerance;
        self
    }

    /// These options with [`MergeOptions::reverse`] set.
    pub const fn with_reverse(mut self, reverse: bool) -> MergeOptions {
        self.reverse = reverse;
        self
    }
}

impl Default for MergeOptions {
    fn default() -> MergeOptions {
        MergeOptions::DEFAULT
    }
}

/// Merges the paths of every layer of `scene` (see the module
/// documentation). Meant for a flat scene.
pub fn run(scene: &mut Scene, options: &MergeOptions) {
    for layer in &mut scene.layers {
        let paths = take_paths(layer);
        set_paths(layer, merge(paths, options));
    }
}

/// `paths`, split into single subpaths, with chains of paths whose ends
/// meet joined into one path each.
pub fn merge(paths: Vec<StyledPath>, options: &MergeOptions) -> Vec<StyledPath> {
    let paths = split_subpaths(paths);
    let n = paths.len();
    let tolerance = if options.tolerance >= 0.0 {
        options.tolerance
    } else {
        0.0
    };
    let tol2 = tolerance * tolerance;
    let mergeable: Vec<bool> = paths
        .iter()
        .map(|p| subpaths(&p.path).all(|s| !s.ends_with_close()) && p.style.fill.is_none())
        .collect();
    // `split_subpaths` left one subpath in every path.
    let (starts, ends): (Vec<Point>, Vec<Point>) = paths
        .iter()
        .map(|p| {
            subpaths(&p.path)
                .next()
                .map_or((Point::ZERO, Point::ZERO), |s| (s.start(), s.end()))
        })
        .unzip();
    let mut free = FreeEnds::new(&starts, &ends, tol2, options.reverse);
    for (i, _) in mergeable.iter().enumerate().filter(|(_, &m)| !m) {
        free.take(i);
    }

    let mut slots: Vec<Option<StyledPath>> = paths.into_iter().map(Some).collect();
    let mut used = vec![false; n];
    let mut out = Vec::with_capacity(n);
    // Pieces of the chain being built: (path, drawn backwards).
    let mut chain: std::collections::VecDeque<(usize, bool)> = Default::default();
    for seed in 0..n {
        if used[seed] {
            continue;
        }
        used[seed] = true;
        let Some(mut first) = slots[seed].take() else {
            continue;
        };
        if !mergeable[seed] {
            out.push(first);
            continue;
        }
        free.take(seed);
        chain.clear();
        chain.push_back((seed, false));
        // Grow at the end (ends are named by codes: path i's start is i,
        // its end n + i): a start there continues forwards, an end
        // continues backwards.
        let mut tail = n + seed;
        while let Some((j, via_start)) = free.next(tail, true) {
            used[j] = true;
            let backwards = !via_start;
            chain.push_back((j, backwards));
            tail = if backwards { j } else { n + j };
        }
        // Grow at the start: an end there comes before forwards, a start
        // comes before backwards.
        let mut head = seed;
        while let Some((j, via_start)) = free.next(head, false) {
            used[j] = true;
            let backwards = via_start;
            chain.push_front((j, backwards));
            head = if backwards { n + j } else { j };
        }
        if chain.len() > 1 {
            let mut joined = BezPath::new();
            for &(j, backwards) in &chain {
                let piece = if j == seed {
                    std::mem::take(&mut first.path)
                } else {
                    slots[j].take().map(|p| p.path).unwrap_or_default()
                };
                let mut piece = piece;
                if backwards {
                    reverse_open_in_place(&mut piece);
                }
                append(&mut joined, &piece);
            }
            first.path = joined;
        }
        out.push(first);
    }
    out
}

/// The ends of the paths not used yet. An end is named by a code: the
/// start of path `i` is `i`, its end `n + i`.
///
/// Only *crowded* ends — with another end in the same or a neighbouring
/// grid cell of the tolerance's size — go into the k-d trees: an end alone
/// in its neighbourhood can neither be found nor find anything, and in
/// most drawings most ends are alone, so this saves most of the work.
struct FreeEnds {
    n: usize,
    points: Vec<Point>,
    crowded: Vec<bool>,
    tol2: f64,
    /// With reversal one tree for all ends; without, starts and ends apart.
    trees: Vec<PointIndex>,
    /// Tree point → code, per tree.
    codes: Vec<Vec<u32>>,
    /// Code → (tree, point in it), for crowded ends.
    place: Vec<(u8, u32)>,
}

impl FreeEnds {
    fn new(starts: &[Point], ends: &[Point], tol2: f64, reverse: bool) -> FreeEnds {
        let n = starts.len();
        let points: Vec<Point> = starts.iter().chain(ends).copied().collect();
        let crowded = crowded(&points, tol2.sqrt());
        let tree_of = |code: usize| usize::from(!reverse && code >= n);
        let mut members: Vec<Vec<u32>> = vec![Vec::new(); if reverse { 1 } else { 2 }];
        let mut place = vec![(0u8, u32::MAX); 2 * n];
        for code in (0..2 * n).filter(|&c| crowded[c]) {
            let t = tree_of(code);
            place[code] = (t as u8, members[t].len() as u32);
            members[t].push(code as u32);
        }
        let trees = members
            .iter()
            .map(|m| {
                let pts: Vec<Point> = m.iter().map(|&c| points[c as usize]).collect();
                PointIndex::new(&pts)
            })
            .collect();
        FreeEnds {
            n,
            points,
            crowded,
            tol2,
            trees,
            codes: members,
            place,
        }
    }

    /// Marks path `i` as used.
    fn take(&mut self, i: usize) {
        for code in [i, self.n + i] {
            let (t, id) = self.place[code];
            if id != u32::MAX {
                self.trees[t as usize].remove(id);
            }
        }
    }

    /// Takes the unused path with an end nearest to the end `from` within
    /// the tolerance — its start when `want_start` is true, else its end;
    /// or either end with reversal — and returns it with whether the end
    /// found is its start. Ties go to the lower code (a start before an
    /// end, then the lower path index).
    fn next(&mut self, from: usize, want_start: bool) -> Option<(usize, bool)> {
        if !self.crowded[from] {
            return None;
        }
        let t = usize::from(self.trees.len() == 2 && !want_start);
        let (id, _) = self.trees[t].nearest_within(self.points[from], self.tol2)?;
        let code = self.codes[t][id as usize] as usize;
        let (i, at_start) = if code < self.n {
            (code, true)
        } else {
            (code - self.n, false)
        };
        self.take(i);
        Some((i, at_start))
    }
}

/// For each point, whether another point lies in the same or a
/// neighbouring cell of a grid of side `tol` (so every point within `tol`
/// of it, and some a little further). Sorting by cell makes this
/// O(n log n) whatever the tolerance.
fn crowded(points: &[Point], tol: f64) -> Vec<bool> {
    if !tol.is_finite() {
        return vec![true; points.len()];
    }
    let cell = if tol > 0.0 { tol } else { 1.0 };
    // Saturating casts: huge or NaN coordinates share edge cells, which
    // only errs towards "crowded".
    let mut keys: Vec<(i64, i64, u32)> = points
        .iter()
        .zip(0u32..)
        .map(|(p, i)| ((p.x / cell).floor() as i64, (p.y / cell).floor() as i64, i))
        .collect();
    keys.sort_unstable();
    let mut out = vec![false; points.len()];
    // One cursor per neighbouring column: the first key not below
    // (column, cy - 1). Targets only grow along the sorted keys, so the
    // cursors only move forwards: O(n) after the sort.
    let mut cursors = [0usize; 3];
    for (k, &(cx, cy, i)) in keys.iter().enumerate() {
        let same_cell =
            |o: Option<&(i64, i64, u32)>| o.is_some_and(|&(x, y, _)| (x, y) == (cx, cy));
        if same_cell(keys.get(k + 1)) || (k > 0 && same_cell(keys.get(k - 1))) {
            out[i as usize] = true;
            continue;
        }
        let (y0, y1) = (cy.saturating_sub(1), cy.saturating_add(1));
        for (cursor, dx) in cursors.iter_mut().zip([-1i64, 0, 1]) {
            let x = cx.saturating_add(dx);
            while keys
                .get(*cursor)
                .is_some_and(|&(kx, ky, _)| (kx, ky) < (x, y0))
            {
                *cursor += 1;
            }
            let found = keys[*cursor..]
                .iter()
                .take_while(|&&(kx, ky, _)| kx == x && ky <= y1)
                .any(|&(_, _, j)| j != i);
            if found {
                out[i as usize] = true;
                break;
            }
        }
    }
    out
}

/// Appends the single subpath `piece` to `joined`, with a line across the
/// gap if its start is not where `joined` ends.
fn append(joined: &mut BezPath, piece: &BezPath) {
    let Some(sub) = subpaths(piece).next() else {
        return;
    };
    match joined.elements().last() {
        None => joined.extend(sub.elements()),
        Some(&last) => {
            if el_end(last) != sub.start() {
                joined.push(PathEl::LineTo(sub.start()));
            }
            joined.extend(sub.body().iter().copied());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::path_length;
    use crate::plot::sort::tests::{line, path_set, seg_key, seg_multiset, styled};
    use crate::scene::{Color, Style};
    use proptest::prelude::*;

    fn lengths(paths: &[StyledPath]) -> f64 {
        paths.iter().map(|p| path_length(&p.path)).sum()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(192))]

        #[test]
        fn merge_keeps_every_segment_once(paths in path_set(), reverse: bool, tol_i in 0u8..3) {
            let tolerance = [0.0, 0.05, 0.6][tol_i as usize];
            let options = MergeOptions::DEFAULT.with_tolerance(tolerance).with_reverse(reverse);
            let input = split_subpaths(
                paths.iter().enumerate().map(|(i, p)| styled(format!("p{i}"), p.clone())).collect(),
            );
            let out = merge(input.clone(), &options);

            // Every output path is one subpath, ids are the input's, once each.
            prop_assert!(out.iter().all(|p| subpaths(&p.path).count() == 1));
            let mut ids: Vec<&str> = out.iter().map(|p| p.id.as_str()).collect();
            ids.sort_unstable();
            ids.dedup();
            prop_assert_eq!(ids.len(), out.len());
            prop_assert!(out.iter().all(|o| input.iter().any(|p| p.id == o.id)));

            // Output segments = input segments (up to reversal) + gap lines.
            let mut bag = seg_multiset(input.iter().map(|p| &p.path));
            let mut gaps = 0usize;
            for p in &out {
                for seg in p.path.segments() {
                    let key = seg_key(seg);
                    match bag.binary_search(&key) {
                        Ok(k) => {
                            bag.remove(k);
                        }
                        Err(_) => {
                            let kurbo::PathSeg::Line(l) = seg else {
                                return Err(TestCaseError::fail("extra curve"));
                            };
                            prop_assert!(l.length() <= tolerance + 1e-12);
                            gaps += 1;
                        }
                    }
                }
            }
            prop_assert!(bag.is_empty(), "segments lost: {:?}", bag.len());
            prop_assert!(gaps <= input.len() - out.len());

            // Ink grows by the gaps at most.
            let (a, b) = (lengths(&input), lengths(&out));
            prop_assert!(b >= a - 1e-6 && b <= a + gaps as f64 * tolerance + 1e-6, "{} vs {}", a, b);

            // Merging again with the same options finds nothing more that
            // the first run could have joined from its seeds' ends... but
            // it never loses anything either.
            let again = merge(out.clone(), &options);
            prop_assert!(again.len() <= out.len());
        }
    }

    proptest! {
        #[test]
        fn crowded_finds_every_close_pair(
            pts in prop::collection::vec((-20i32..20, -20i32..20), 0..80),
            tol_i in 0usize..4,
        ) {
            let tol = [0.0, 0.05, 0.3, 1.0][tol_i];
            let pts: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x as f64 * 0.1, y as f64 * 0.1)).collect();
            let flags = crowded(&pts, tol);
            for (i, p) in pts.iter().enumerate() {
                let close = pts.iter().enumerate().any(|(j, q)| j != i && p.distance(*q) <= tol);
                prop_assert!(!close || flags[i], "point {} has a neighbour within {}", i, tol);
            }
        }
    }

    fn ids(paths: &[StyledPath]) -> Vec<&str> {
        paths.iter().map(|p| p.id.as_str()).collect()
    }

    #[test]
    fn joins_in_every_direction() {
        // c (reversed) ← a → b (reversed), plus an unrelated d.
        let paths = vec![
            styled("a", line((10.0, 0.0), (20.0, 0.0))),
            styled("d", line((50.0, 50.0), (60.0, 50.0))),
            styled("b", line((30.0, 0.0), (20.0, 0.0))),
            styled("c", line((10.0, 0.0), (0.0, 0.0))),
        ];
        let out = merge(paths, &MergeOptions::DEFAULT);
        assert_eq!(ids(&out), ["a", "d"]);
        let pts: Vec<PathEl> = out[0].path.elements().to_vec();
        assert_eq!(
            pts,
            [
                PathEl::MoveTo(Point::new(0.0, 0.0)),
                PathEl::LineTo(Point::new(10.0, 0.0)),
                PathEl::LineTo(Point::new(20.0, 0.0)),
                PathEl::LineTo(Point::new(30.0, 0.0)),
            ]
        );
    }

    #[test]
    fn gap_within_tolerance_is_bridged_and_beyond_is_not() {
        let paths = vec![
            styled("a", line((0.0, 0.0), (10.0, 0.0))),
            styled("b", line((10.04, 0.0), (20.0, 0.0))),
            styled("c", line((20.1, 0.0), (30.0, 0.0))),
        ];
        let out = merge(paths, &MergeOptions::DEFAULT);
        assert_eq!(ids(&out), ["a", "c"]);
        assert_eq!(out[0].path.elements().len(), 4);
        assert!((path_length(&out[0].path) - 20.0).abs() < 1e-9);
    }

    #[test]
    fn without_reverse_only_end_to_start() {
        let paths = vec![
            styled("a", line((0.0, 0.0), (10.0, 0.0))),
            styled("b", line((20.0, 0.0), (10.0, 0.0))),
            styled("c", line((10.0, 0.0), (10.0, 5.0))),
        ];
        let out = merge(paths, &MergeOptions::DEFAULT.with_reverse(false));
        assert_eq!(ids(&out), ["a", "b"]);
        assert_eq!(
            out[0].path.elements().last(),
            Some(&PathEl::LineTo(Point::new(10.0, 5.0)))
        );
    }

    #[test]
    fn closed_and_filled_paths_stay_alone() {
        let mut square = line((0.0, 0.0), (10.0, 0.0));
        square.line_to((10.0, 10.0));
        square.close_path();
        let filled = StyledPath {
            id: "filled".into(),
            path: line((10.0, 10.0), (0.0, 10.0)),
            style: Style {
                fill: Some(Color::BLACK),
                ..Style::default()
            },
        };
        let paths = vec![
            styled("square", square.clone()),
            filled,
            styled("open", line((10.0, 0.0), (20.0, 0.0))),
        ];
        let out = merge(paths, &MergeOptions::DEFAULT);
        assert_eq!(ids(&out), ["square", "filled", "open"]);
        assert_eq!(out[0].path, square);
    }

    #[test]
    fn long_chain_in_random_order_becomes_one_path() {
        // 1,000 unit pieces of one polyline, shuffled and half reversed.
        let mut rng = crate::Seed(3).derive("chain").stream();
        let mut pieces: Vec<StyledPath> = (0..1000)
            .map(|i| {
                let (a, b) = ((i as f64, 0.0), (i as f64 + 1.0, 0.0));
                let p = if rng.below(2) == 0 {
                    line(a, b)
                } else {
                    line(b, a)
                };
                styled(format!("p{i}"), p)
            })
            .collect();
        for i in (1..pieces.len()).rev() {
            pieces.swap(i, rng.below(i + 1));
        }
        let first = pieces[0].id.clone();
        let out = merge(pieces, &MergeOptions::DEFAULT);
        assert_eq!(out.len(), 1);
        assert_eq!(out[0].id, first);
        assert!((path_length(&out[0].path) - 1000.0).abs() < 1e-9);
    }
}
