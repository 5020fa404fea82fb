//! Line work drawn twice: the parts of a pen's paths that lie on line work
//! the same pen already draws are taken out, partial overlaps included.
//!
//! Two strokes of one pen whose centre lines run the same way within the
//! *tolerance* of each other put down the same ink: the second adds a
//! little width at most, and a felt tip going over wet ink blots and wears
//! the paper. The default tolerance is a quarter of the pen's width
//! ([`PEN_SHARE`]): two strokes that close look like one line, and
//! dropping one of them changes the ink by at most that quarter of a width
//! along them. Lines that cross, end on one another or continue one
//! another end to end are never cut: two pieces share ink only where they
//! run within 20° of each other and lie beside each other, not beyond
//! each other's ends.
//!
//! Which copy stays: paths with a fill first (they are never cut, so a
//! flower keeps its outline whole), then the longest paths, then the
//! earlier; each path keeps what no path before it in that order covers.
//! Within one subpath, a part that runs back over its own earlier part
//! (more than a few millimetres away along it) is doubled too.
//!
//! What is cut: a covered run at the free end of an open subpath as soon
//! as it is longer than the tolerance (it costs no pen lift); a covered
//! run inside a subpath only when it is at least two pen widths long (a
//! cut there costs a pen lift, and lines crossing at a shallow angle share
//! less than that); a subpath covered whole disappears, and a path with
//! nothing left goes. Covered runs less than two tolerances apart count as
//! one (a copy that turns a corner beside the original leaves that much
//! beyond the original's pieces), and so does a run that close to a free
//! end with the end: no crumbs of line are left between cuts. Cuts are made on the exact curves, at the parameter
//! the cover was found at; untouched subpaths keep their elements, and a
//! path that loses nothing stays exactly as it was. Ids are kept: the
//! pieces of a cut path stay one path, with its id and style.
//!
//! Cost: every segment is cut into pieces no longer than a grid cell, and
//! each piece looks only at the pieces in the cells around it, so the stage
//! is linear in the length of the drawing for drawings of bounded density.

use kurbo::BezPath;
use serde::{Deserialize, Serialize};

use super::cover::{covered, union, LineIndex, Pieces};
use super::flatten::{set_paths, take_paths};
use crate::geom::subpath::subpaths;
use crate::scene::{Scene, StyledPath};

/// The default tolerance, as a share of the pen's width.
pub const PEN_SHARE: f64 = 0.25;

/// Options of [`run`].
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DedupeOptions {
    /// Largest distance, mm, between two strokes that run the same way and
    /// count as one line (0 to 10). Default: [`PEN_SHARE`] of each pen's
    /// width.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
}

impl DedupeOptions {
    /// A quarter of each pen's width.
    pub const DEFAULT: DedupeOptions = DedupeOptions { tolerance: None };

    /// These options with a tolerance in mm (`None`: from the pen).
    pub const fn with_tolerance(mut self, tolerance: Option<f64>) -> DedupeOptions {
        self.tolerance = tolerance;
        self
    }

    /// The tolerance for a pen `width` mm wide.
    pub fn tolerance_for(&self, width: f64) -> f64 {
        self.tolerance.unwrap_or(PEN_SHARE * width)
    }
}

/// Takes doubled line work out of every layer of a flat scene (see the
/// module documentation), each with its pen's width.
pub fn run(scene: &mut Scene, options: &DedupeOptions) {
    for i in 0..scene.layers.len() {
        let width = scene.pen_width(scene.layers[i].pen);
        let layer = &mut scene.layers[i];
        let paths = take_paths(layer);
        set_paths(layer, dedupe(paths, options.tolerance_for(width), width));
    }
}

/// `paths` without the line work that lies on other line work of theirs,
/// within `tolerance`, for a pen `width` wide (see the module
/// documentation).
pub fn dedupe(paths: Vec<StyledPath>, tolerance: f64, width: f64) -> Vec<StyledPath> {
    let found = find(
        paths.iter().map(|p| (&p.path, p.style.fill.is_some())),
        Rules::for_pen(tolerance, width),
    );
    paths
        .into_iter()
        .enumerate()
        .filter_map(|(i, mut p)| {
            p.path = found.kept(i, p.path, 0.0)?;
            Some(p)
        })
        .collect()
}

/// The parts of `paths` that do not lie on the line work of `drawn`,
/// which is never cut, nor on each other's, by the rules of [`dedupe`],
/// less pieces left between cuts shorter than the pen is wide (the ink
/// of the lines they lie between already covers them):
/// the line a generator still has to draw along an edge that its other
/// lines draw in places (a zentangle's black part), in the order of
/// `paths`; `None` where nothing is left.
pub(crate) fn beside(
    drawn: &[BezPath],
    paths: Vec<BezPath>,
    tolerance: f64,
    width: f64,
) -> Vec<Option<BezPath>> {
    let found = find(
        drawn
            .iter()
            .map(|p| (p, true))
            .chain(paths.iter().map(|p| (p, false))),
        Rules::for_pen(tolerance, width),
    );
    paths
        .into_iter()
        .enumerate()
        .map(|(i, p)| {
            found
                .kept(drawn.len() + i, p, width)
                .filter(|p| !p.elements().is_empty())
        })
        .collect()
}

/// Length of the line work of `paths` that lies on other line work of
/// theirs, within `tolerance`, over runs at least `min_run` long (for a
/// pen `w` wide, `2 w`: two lines crossing at 30° share that much ink, and
/// nobody calls a crossing a line drawn twice).
pub fn doubled_length<'a>(
    paths: impl IntoIterator<Item = &'a BezPath>,
    tolerance: f64,
    min_run: f64,
) -> f64 {
    let rules = Rules {
        tolerance,
        inside: min_run,
        at_end: min_run,
    };
    let found = find(paths.into_iter().map(|p| (p, false)), rules);
    // Folded from +0: a sum of nothing is -0 in Rust, which prints as "-0.0".
    found
        .cuts
        .iter()
        .flatten()
        .fold(0.0, |sum, (lo, hi)| sum + (hi - lo))
}

/// When a covered run is cut.
#[derive(Debug, Clone, Copy)]
struct Rules {
    tolerance: f64,
    /// Shortest run cut inside a subpath.
    inside: f64,
    /// Shortest run cut at the free end of an open subpath.
    at_end: f64,
}

/// A subpath of the drawing.
struct Sub {
    path: usize,
    pieces: Pieces,
}

/// The subpaths of a drawing and the runs (lengths along each) to cut.
struct Found {
    subs: Vec<Sub>,
    /// Per subpath, sorted and apart.
    cuts: Vec<Vec<(f64, f64)>>,
    /// Per path, its first subpath (and one past the last path's last).
    first: Vec<usize>,
}

impl Found {
    /// What is left of path `i`, `path`, once its cuts are made, less the
    /// pieces left between cuts that are shorter than `shortest`: the
    /// path itself when nothing is cut, `None` when everything is.
    fn kept(&self, i: usize, path: BezPath, shortest: f64) -> Option<BezPath> {
        let subs = self.first[i]..self.first[i + 1];
        if subs.clone().all(|s| self.cuts[s].is_empty()) {
            return Some(path);
        }
        let mut out = BezPath::new();
        for (sub, j) in subpaths(&path).zip(subs) {
            let cuts = &self.cuts[j];
            if cuts.is_empty() {
                out.extend(sub.elements());
                continue;
            }
            let pieces = &self.subs[j].pieces;
            let mut kept = complement(cuts, pieces.len());
            drop_short(&mut kept, pieces.len(), pieces.closed, shortest);
            pieces.cut(&kept, &mut out);
        }
        (!out.elements().is_empty()).then_some(out)
    }
}

/// Finds the covered runs of every subpath of `paths` (each with whether
/// it is an anchor, never cut), in the order the module documentation
/// gives, and which of them `rules` cut.
fn find<'a>(paths: impl Iterator<Item = (&'a BezPath, bool)>, rules: Rules) -> Found {
    let tol = rules.tolerance.max(0.0);
    // Cells several tolerances wide keep the neighbourhood of a piece in
    // few cells; a millimetre at least keeps their number reasonable.
    let cell = (8.0 * tol).max(1.0);
    let flat = (tol / 4.0).max(1e-4);
    let mut subs = Vec::new();
    let mut first = Vec::new();
    let mut anchors = Vec::new();
    for (i, (path, anchor)) in paths.enumerate() {
        first.push(subs.len());
        anchors.push(anchor);
        for sub in subpaths(path) {
            subs.push(Sub {
                path: i,
                pieces: Pieces::new(sub.segments().collect(), sub.is_closed(), cell, flat),
            });
        }
    }
    first.push(subs.len());
    let lengths: Vec<f64> = (0..anchors.len())
        .map(|i| {
            subs[first[i]..first[i + 1]]
                .iter()
                .map(|s| s.pieces.len())
                .sum()
        })
        .collect();
    let mut order: Vec<usize> = (0..anchors.len()).collect();
    order.sort_by(|&x, &y| {
        anchors[y]
            .cmp(&anchors[x])
            .then(lengths[y].total_cmp(&lengths[x]))
            .then(x.cmp(&y))
    });

    // A subpath's own pieces this close along it are its neighbours, not
    // a second pass over the same place.
    let self_gap = 2.0 * cell + tol;
    let mut index = LineIndex::new(cell);
    let mut cuts = vec![Vec::new(); subs.len()];
    let mut runs = Vec::new();
    let mut own = Vec::new();
    let mut ids = Vec::new();
    for i in order {
        for j in first[i]..first[i + 1] {
            let pieces = &subs[j].pieces;
            debug_assert_eq!(subs[j].path, i);
            // What the subpaths decided before cover; they are final, so
            // what is cut here lies on line work that stays.
            runs.clear();
            if !anchors[i] {
                for piece in &pieces.pieces {
                    index.near(piece.a, piece.b, tol, |l| {
                        if let Some((lo, hi)) = covered(piece.a, piece.b, l.a, l.b, tol) {
                            runs.push((piece.s + lo, piece.s + hi));
                        }
                    });
                }
            }
            let mut cut = rules.cut(&mut runs, pieces);
            // Then the subpath against itself: a piece goes into the index
            // only when nothing of it lies on its own earlier line work, so
            // what is cut here too lies on line work that stays.
            own.clear();
            ids.clear();
            let may_cross_itself = !anchors[i] && pieces.len() > self_gap;
            for piece in &pieces.pieces {
                let mid = piece.s + piece.len() / 2.0;
                if inside(&cut, mid) {
                    continue;
                }
                let before = own.len();
                if may_cross_itself {
                    index.near(piece.a, piece.b, tol, |l| {
                        if l.owner != j as u32 || (l.s - piece.s).abs() < self_gap {
                            return;
                        }
                        if let Some((lo, hi)) = covered(piece.a, piece.b, l.a, l.b, tol) {
                            own.push((piece.s + lo, piece.s + hi));
                        }
                    });
                }
                if own.len() == before {
                    ids.push((mid, index.insert(piece.a, piece.b, j as u32, piece.s)));
                }
            }
            let again = rules.cut(&mut own, pieces);
            if !again.is_empty() {
                for &(mid, id) in &ids {
                    if inside(&again, mid) {
                        index.remove(id);
                    }
                }
                cut.extend(again);
                union(&mut cut);
            }
            cuts[j] = cut;
        }
    }
    Found { subs, cuts, first }
}

impl Rules {
    /// The rules of [`dedupe`] for a pen `width` wide.
    fn for_pen(tolerance: f64, width: f64) -> Rules {
        Rules {
            tolerance,
            inside: 2.0 * width,
            at_end: tolerance,
        }
    }

    /// Of the covered `runs` of the subpath `pieces` (any order, joined
    /// here), the ones to cut. Runs less than two tolerances apart are one
    /// run (where a copy turns a corner beside the original, the bit of it
    /// beyond both of the original's pieces is that short), and a run that
    /// short of a free end reaches the end.
    fn cut(&self, runs: &mut Vec<(f64, f64)>, pieces: &Pieces) -> Vec<(f64, f64)> {
        union(runs);
        let total = pieces.len();
        let eps = 1e-9 * (1.0 + total);
        let bridge = 2.0 * self.tolerance;
        let mut joined: Vec<(f64, f64)> = Vec::with_capacity(runs.len());
        for &(lo, hi) in runs.iter() {
            match joined.last_mut() {
                Some(last) if lo - last.1 <= bridge => last.1 = last.1.max(hi),
                _ => joined.push((lo, hi)),
            }
        }
        if !pieces.closed {
            if let Some(first) = joined.first_mut().filter(|r| r.0 <= bridge) {
                first.0 = 0.0;
            }
            if let Some(last) = joined.last_mut().filter(|r| r.1 >= total - bridge) {
                last.1 = total;
            }
        }
        joined
            .into_iter()
            .filter(|&(lo, hi)| {
                let whole = lo <= eps && hi >= total - eps;
                let at_end = !pieces.closed && (lo <= eps || hi >= total - eps);
                whole
                    || (hi - lo > 0.0 && hi - lo >= self.inside)
                    || (at_end && hi - lo >= self.at_end)
            })
            .collect()
    }
}

/// `runs` (sorted, apart, along a subpath `total` long) without those
/// shorter than `shortest`; on a `closed` subpath a run through its start
/// counts whole.
fn drop_short(runs: &mut Vec<(f64, f64)>, total: f64, closed: bool, shortest: f64) {
    if shortest <= 0.0 || runs.is_empty() {
        return;
    }
    let eps = 1e-9 * (1.0 + total);
    let n = runs.len();
    let wraps = closed && n > 1 && runs[0].0 <= eps && runs[n - 1].1 >= total - eps;
    let through_start = if wraps {
        (runs[n - 1].1 - runs[n - 1].0) + (runs[0].1 - runs[0].0)
    } else {
        0.0
    };
    let mut k = 0;
    runs.retain(|&(lo, hi)| {
        let end = k == 0 || k == n - 1;
        k += 1;
        let length = if wraps && end { through_start } else { hi - lo };
        length >= shortest
    });
}

/// Whether `s` lies in one of `runs`.
///
/// `runs` are sorted and apart, so the one run that may hold `s` is the
/// last starting at or before it: a binary search. A long subpath has
/// thousands of runs and each of its pieces asks, and a scan of them all
/// made the stage quadratic (the dragon curve at 21 iterations, one path
/// of two million segments, spent all its time here; issue 36).
fn inside(runs: &[(f64, f64)], s: f64) -> bool {
    let i = runs.partition_point(|&(lo, _)| lo <= s);
    i > 0 && s <= runs[i - 1].1
}

/// The runs of `0..total` outside `cuts` (sorted, apart), each longer
/// than rounding noise.
fn complement(cuts: &[(f64, f64)], total: f64) -> Vec<(f64, f64)> {
    let eps = 1e-9 * (1.0 + total);
    let mut kept = Vec::new();
    let mut at = 0.0;
    for &(lo, hi) in cuts {
        if lo > at + eps {
            kept.push((at, lo));
        }
        at = at.max(hi);
    }
    if total > at + eps {
        kept.push((at, total));
    }
    kept
}

#[cfg(test)]
mod tests {
    use kurbo::{Circle, ParamCurveNearest, Point, Rect, Shape};
    use proptest::prelude::*;

    use super::*;
    use crate::scene::{Color, Style};

    #[test]
    fn a_length_is_inside_the_sorted_runs_that_hold_it_ends_included() {
        let runs = [(1.0, 2.0), (3.0, 3.0), (5.0, 8.0)];
        for (s, want) in [
            (0.5, false),
            (1.0, true),
            (1.5, true),
            (2.0, true),
            (2.5, false),
            (3.0, true),
            (4.0, false),
            (8.0, true),
            (9.0, false),
            (f64::NAN, false),
        ] {
            assert_eq!(inside(&runs, s), want, "{s}");
            assert_eq!(runs.iter().any(|&(lo, hi)| lo <= s && s <= hi), want, "{s}");
        }
        assert!(!inside(&[], 1.0));
    }

    fn line(id: &str, points: &[(f64, f64)]) -> StyledPath {
        let mut path = BezPath::new();
        path.move_to(points[0]);
        for &p in &points[1..] {
            path.line_to(p);
        }
        StyledPath {
            id: id.into(),
            path,
            style: Style::default(),
        }
    }

    fn length(paths: &[StyledPath]) -> f64 {
        paths
            .iter()
            .map(|p| {
                p.path
                    .segments()
                    .map(|s| kurbo::ParamCurve::end(&s).distance(kurbo::ParamCurve::start(&s)))
                    .sum::<f64>()
            })
            .sum()
    }

    #[test]
    fn an_identical_path_is_drawn_once() {
        let a = line("a", &[(0.0, 0.0), (50.0, 0.0)]);
        let mut b = a.clone();
        b.id = "b".into();
        let out = dedupe(vec![a.clone(), b], 0.075, 0.3);
        assert_eq!(out, [a]);
    }

    #[test]
    fn a_partial_overlap_is_cut_at_the_free_end() {
        // A stem, and a branch that starts along it for 5 mm, 0.02 mm off.
        let stem = line("stem", &[(0.0, 0.0), (0.0, -40.0)]);
        let branch = line("branch", &[(0.02, -10.0), (0.02, -15.0), (10.0, -25.0)]);
        let out = dedupe(vec![stem.clone(), branch], 0.075, 0.3);
        assert_eq!(out[0], stem);
        assert_eq!(out[1].id, "branch");
        let start = out[1].path.elements()[0].end_point().unwrap();
        assert!((start.y - -15.0).abs() < 0.05, "{start:?}");
        assert!((length(&out) - (40.0 + (200.0f64).sqrt())).abs() < 0.05);
    }

    #[test]
    fn crossing_lines_and_lines_meeting_end_to_end_are_kept() {
        let paths = vec![
            line("h", &[(0.0, 0.0), (20.0, 0.0)]),
            line("v", &[(10.0, -10.0), (10.0, 10.0)]),
            line("on", &[(20.0, 0.0), (40.0, 0.0)]),
            // Crossing at 25°: ink shared only where lines cross.
            line("shallow", &[(0.0, -4.66), (20.0, 4.66)]),
        ];
        assert_eq!(dedupe(paths.clone(), 0.075, 0.3), paths);
    }

    #[test]
    fn a_covered_run_inside_a_path_is_cut_when_long_enough() {
        let long = line("long", &[(0.0, 0.0), (100.0, 0.0)]);
        // Runs along `long` for 30 mm in its middle, away at both ends.
        let detour = line(
            "detour",
            &[(20.0, 10.0), (30.0, 0.01), (60.0, 0.01), (70.0, 10.0)],
        );
        let out = dedupe(vec![long.clone(), detour.clone()], 0.075, 0.3);
        assert_eq!(out[0], long);
        assert_eq!(
            out[1]
                .path
                .elements()
                .iter()
                .filter(|e| matches!(e, kurbo::PathEl::MoveTo(_)))
                .count(),
            2
        );
        assert!(
            (length(&out) - (100.0 + 2.0 * (200.0f64 - 2.0 * 0.01 * 10.0 + 0.0001).sqrt())).abs()
                < 0.1
        );
        // A shorter run inside costs a pen lift for less than two pen
        // widths of ink: kept.
        let blip = line(
            "blip",
            &[(20.0, 10.0), (30.0, 0.01), (30.4, 0.01), (40.0, 10.0)],
        );
        assert_eq!(
            dedupe(vec![long.clone(), blip.clone()], 0.075, 0.3),
            [long, blip]
        );
    }

    #[test]
    fn filled_paths_keep_their_outline_and_the_longer_path_wins() {
        let mut flower = StyledPath {
            id: "flower".into(),
            path: Circle::new((0.0, 0.0), 5.0).to_path(0.01),
            style: Style {
                fill: Some(Color::rgb(255, 255, 255)),
                ..Style::default()
            },
        };
        let ring = StyledPath {
            id: "ring".into(),
            path: Circle::new((0.0, 0.0), 5.0).to_path(0.01),
            style: Style::default(),
        };
        let out = dedupe(vec![ring.clone(), flower.clone()], 0.075, 0.3);
        assert_eq!(out, [flower.clone()]);
        flower.style.fill = None;
        let short = line("short", &[(-10.0, 5.0), (0.0, 5.0)]);
        let long = line("long", &[(-20.0, 5.0), (20.0, 5.0)]);
        let out = dedupe(vec![short, long.clone()], 0.075, 0.3);
        assert_eq!(out, [long]);
    }

    #[test]
    fn a_copy_turning_corners_beside_the_original_goes_whole() {
        // Short segments and bends, the copy 0.02 mm beside: the bits of
        // the copy past the original's corners must not stay as crumbs.
        let a = line(
            "a",
            &[
                (39.0, 20.0),
                (39.083, 19.561),
                (39.099, 19.361),
                (39.152, 19.082),
            ],
        );
        let b = line(
            "b",
            &[
                (39.01, 20.017),
                (39.094, 19.578),
                (39.109, 19.378),
                (39.162, 19.099),
            ],
        );
        // The longer of the two stays, whole; the other goes, whole.
        assert_eq!(dedupe(vec![a, b.clone()], 0.075, 0.3), [b]);
        let bend = line("bend", &[(10.0, 10.0), (10.5, 10.0), (11.0, 10.3)]);
        let mut moved = bend.clone();
        moved.id = "moved".into();
        moved
            .path
            .apply_affine(kurbo::Affine::translate((0.02, 0.0)));
        let out = dedupe(vec![bend, moved], 0.075, 0.3);
        assert_eq!(out.len(), 1, "{out:?}");
    }

    #[test]
    fn a_path_running_back_over_itself_is_drawn_once() {
        let there_and_back = line("t", &[(0.0, 0.0), (30.0, 0.0), (0.0, 0.01)]);
        let out = dedupe(vec![there_and_back], 0.075, 0.3);
        // All of the way back but its first millimetre or two: what lies
        // that close along a path to a piece is its neighbour, not a
        // second pass.
        let left = length(&out) - 30.0;
        assert!((0.0..2.1).contains(&left), "{left}");
    }

    #[test]
    fn a_closed_path_cut_once_stays_one_stroke() {
        let square = line(
            "sq",
            &[
                (0.0, 0.0),
                (10.0, 0.0),
                (10.0, 10.0),
                (0.0, 10.0),
                (0.0, 0.0),
            ],
        );
        let side = line("side", &[(2.0, -5.0), (2.0, 0.0), (8.0, 0.0), (8.0, -5.0)]);
        let mut long_side = side.clone();
        long_side.path = BezPath::new();
        // Make `side` the longer one, so the square is the one cut.
        long_side.path.move_to((-20.0, 0.0));
        long_side.path.line_to((-20.0, -30.0));
        long_side.path.line_to((-20.0, 0.0));
        let lead = line(
            "lead",
            &[
                (-40.0, 0.0),
                (3.0, 0.0),
                (7.0, 0.0),
                (40.0, 0.0),
                (40.0, -30.0),
                (-40.0, -30.0),
            ],
        );
        let out = dedupe(vec![square, lead], 0.075, 0.3);
        let sq = out.iter().find(|p| p.id == "sq").unwrap();
        let moves = sq
            .path
            .elements()
            .iter()
            .filter(|e| matches!(e, kurbo::PathEl::MoveTo(_)))
            .count();
        assert_eq!(moves, 1, "{:?}", sq.path);
        assert!((length(std::slice::from_ref(sq)) - 30.0).abs() < 0.01);
    }

    #[test]
    fn beside_drawn_lines_only_the_bare_stretches_are_left() {
        // A 10 mm square whose top and right sides are lines already
        // drawn (the right one in two, 0.2 mm apart: a gap the lines' ink
        // covers): what is left of the square is its bottom and left
        // sides, one stroke round the corner.
        let square = Rect::new(0.0, 0.0, 10.0, 10.0).to_path(0.0);
        let drawn = [
            line("t", &[(0.0, 0.0), (10.0, 0.0)]).path,
            line("r", &[(10.0, 0.0), (10.0, 4.9)]).path,
            line("r", &[(10.0, 5.1), (10.0, 10.0)]).path,
        ];
        let left = beside(&drawn, vec![square, BezPath::new()], 0.075, 0.3);
        assert_eq!(left.len(), 2);
        assert!(left[1].is_none());
        let bare = left[0].as_ref().unwrap();
        assert_eq!(subpaths(bare).count(), 1);
        assert!(
            (bare.perimeter(0.01) - 20.0).abs() < 1e-6,
            "{}",
            bare.perimeter(0.01)
        );
        for p in [
            Point::new(0.0, 5.0),
            Point::new(5.0, 10.0),
            Point::new(0.0, 10.0),
        ] {
            let d = bare
                .segments()
                .map(|s| s.nearest(p, 1e-9).distance_sq)
                .fold(f64::MAX, f64::min);
            assert!(d < 1e-12, "{p:?} not on what is left");
        }
    }

    #[test]
    fn the_doubled_length_counts_every_covered_run() {
        let a = line("a", &[(0.0, 0.0), (50.0, 0.0)]);
        let b = line("b", &[(25.0, 0.0), (75.0, 0.0)]);
        let d = doubled_length([&a.path, &b.path], 0.075, 0.6);
        assert!((d - 25.0).abs() < 1e-6, "{d}");
        // A shared run shorter than the least counted is a crossing's.
        let c = line("c", &[(10.0, 5.0), (20.0, 0.01), (20.5, 0.01), (30.0, 5.0)]);
        assert_eq!(doubled_length([&a.path, &c.path], 0.075, 0.6), 0.0);
    }

    /// The distance from `p` to the nearest line work of `paths`.
    fn distance_to(paths: &[StyledPath], p: Point) -> f64 {
        paths
            .iter()
            .flat_map(|q| q.path.segments())
            .map(|s| {
                let l = kurbo::Line::new(kurbo::ParamCurve::start(&s), kurbo::ParamCurve::end(&s));
                let n = kurbo::ParamCurveNearest::nearest(&l, p, 1e-9);
                n.distance_sq.sqrt()
            })
            .fold(f64::INFINITY, f64::min)
    }

    fn polyline() -> impl Strategy<Value = Vec<(f64, f64)>> {
        // Points on a coarse lattice so that segments often lie on each
        // other, partly or whole.
        prop::collection::vec((0..6i32, 0..6i32), 2..6).prop_map(|v| {
            v.into_iter()
                .map(|(x, y)| (f64::from(x) * 2.0, f64::from(y) * 2.0))
                .collect()
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        /// Nothing that no other line covers is removed: every point of
        /// the drawing before lies within two tolerances of the drawing
        /// after (one, but for the short gaps a cut bridges); and nothing
        /// is added: every point after lies on the drawing before.
        #[test]
        fn dedupe_removes_only_covered_line_work(lines in prop::collection::vec(polyline(), 1..6)) {
            let tol = 0.075;
            let paths: Vec<StyledPath> = lines
                .iter()
                .enumerate()
                .map(|(i, l)| line(&format!("p{i}"), l))
                .collect();
            let out = dedupe(paths.clone(), tol, 0.3);
            for p in &paths {
                for seg in p.path.segments() {
                    for k in 0..=20 {
                        let at = kurbo::ParamCurve::eval(&seg, f64::from(k) / 20.0);
                        let d = distance_to(&out, at);
                        prop_assert!(d <= 2.0 * tol + 1e-6, "{at:?} is {d} from what is left");
                    }
                }
            }
            for p in &out {
                for seg in p.path.segments() {
                    for k in 0..=20 {
                        let at = kurbo::ParamCurve::eval(&seg, f64::from(k) / 20.0);
                        prop_assert!(distance_to(&paths, at) <= 1e-6);
                    }
                }
            }
        }
    }
}
