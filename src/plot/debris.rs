//! Debris: strokes shorter than the pen is wide that touch other line
//! work of the same pen.
//!
//! Such a stroke adds nothing a person sees — the pen's own width already
//! covers it where it meets the line beside it — yet costs a pen lift, and
//! a heap of them (the ends hidden-line removal leaves, a circle cut into
//! slivers) blots. A subpath is debris when its whole length is under the
//! *length* (default: the pen's width) and some other, longer subpath of
//! the layer comes within the pen's width of it (their inks touch). A
//! short stroke that touches nothing — a dot of a stipple, a tap — is
//! drawing, not debris, and stays; so do short strokes that touch only
//! each other (a dot drawn as a few slivers), and anything with a fill.
//!
//! Run it after merging, so that pieces that join into a longer stroke
//! are not taken for debris.

use kurbo::BezPath;
use serde::{Deserialize, Serialize};

use super::cover::{segment_distance, LineIndex, Pieces};
use super::flatten::{set_paths, take_paths};
use crate::geom::subpath::subpaths;
use crate::scene::{Scene, StyledPath};

/// Options of [`run`].
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DebrisOptions {
    /// Strokes shorter than this, mm, that touch other line work go (0 to
    /// 10). Default: each pen's width.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
}

impl DebrisOptions {
    /// Each pen's width.
    pub const DEFAULT: DebrisOptions = DebrisOptions { length: None };

    /// These options with a length in mm (`None`: the pen's width).
    pub const fn with_length(mut self, length: Option<f64>) -> DebrisOptions {
        self.length = length;
        self
    }

    /// The length for a pen `width` mm wide.
    pub fn length_for(&self, width: f64) -> f64 {
        self.length.unwrap_or(width)
    }
}

/// Removes the debris of every layer of a flat scene (see the module
/// documentation), each with its pen's width.
pub fn run(scene: &mut Scene, options: &DebrisOptions) {
    for i in 0..scene.layers.len() {
        let width = scene.pen_width(scene.layers[i].pen);
        let layer = &mut scene.layers[i];
        let paths = take_paths(layer);
        set_paths(layer, remove(paths, options.length_for(width), width));
    }
}

/// `paths` without their debris: subpaths shorter than `length` within
/// `reach` of a subpath that is not (see the module documentation).
pub fn remove(paths: Vec<StyledPath>, length: f64, reach: f64) -> Vec<StyledPath> {
    let debris = find(
        paths.iter().map(|p| (&p.path, p.style.fill.is_some())),
        length,
        reach,
    );
    let mut k = 0;
    paths
        .into_iter()
        .filter_map(|mut p| {
            let subs: Vec<bool> = subpaths(&p.path)
                .map(|_| {
                    k += 1;
                    debris[k - 1]
                })
                .collect();
            if !subs.iter().any(|&d| d) {
                return Some(p);
            }
            let mut out = BezPath::new();
            for (sub, _) in subpaths(&p.path).zip(&subs).filter(|(_, &d)| !d) {
                out.extend(sub.elements());
            }
            if out.elements().is_empty() {
                return None;
            }
            p.path = out;
            Some(p)
        })
        .collect()
}

/// How many subpaths of `paths` are debris.
pub fn count<'a>(paths: impl IntoIterator<Item = &'a BezPath>, length: f64, reach: f64) -> usize {
    find(paths.into_iter().map(|p| (p, false)), length, reach)
        .into_iter()
        .filter(|&d| d)
        .count()
}

/// For every subpath of `paths` (each with whether it has a fill), in
/// order, whether it is debris.
fn find<'a>(
    paths: impl Iterator<Item = (&'a BezPath, bool)>,
    length: f64,
    reach: f64,
) -> Vec<bool> {
    let reach = reach.max(0.0);
    let cell = (2.0 * reach).max(1.0);
    let subs: Vec<(Pieces, bool)> = paths
        .flat_map(|(path, filled)| {
            subpaths(path).map(move |s| {
                (
                    Pieces::new(s.segments().collect(), s.is_closed(), cell, reach / 4.0),
                    filled,
                )
            })
        })
        .collect();
    let short: Vec<bool> = subs
        .iter()
        .map(|(pieces, filled)| !filled && pieces.len() < length)
        .collect();
    let mut index = LineIndex::new(cell);
    for (j, (pieces, _)) in subs.iter().enumerate() {
        if !short[j] {
            for p in &pieces.pieces {
                index.insert(p.a, p.b, j as u32, p.s);
            }
        }
    }
    subs.iter()
        .zip(&short)
        .map(|((pieces, _), &short)| {
            if !short {
                return false;
            }
            let mut touches = false;
            let mut probe = |a, b| {
                index.near(a, b, reach, |l| {
                    touches = touches || segment_distance(a, b, l.a, l.b) <= reach;
                });
            };
            match pieces.pieces.as_slice() {
                // A dot: where it is.
                [] => {
                    let at = pieces.segs.first().map(kurbo::ParamCurve::start);
                    if let Some(at) = at {
                        probe(at, at);
                    }
                }
                all => all.iter().for_each(|p| probe(p.a, p.b)),
            }
            touches
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Style;

    fn line(id: &str, from: (f64, f64), to: (f64, f64)) -> StyledPath {
        let mut path = BezPath::new();
        path.move_to(from);
        path.line_to(to);
        StyledPath {
            id: id.into(),
            path,
            style: Style::default(),
        }
    }

    #[test]
    fn a_sliver_touching_a_line_goes_and_an_isolated_dot_stays() {
        let long = line("long", (0.0, 0.0), (50.0, 0.0));
        let sliver = line("sliver", (10.0, 0.1), (10.1, 0.2));
        let dot = line("dot", (10.0, 5.0), (10.0, 5.0));
        let tap = line("tap", (20.0, 5.0), (20.1, 5.0));
        let out = remove(
            vec![long.clone(), sliver, dot.clone(), tap.clone()],
            0.3,
            0.3,
        );
        assert_eq!(out, [long, dot, tap]);
    }

    #[test]
    fn slivers_touching_only_each_other_stay() {
        // A small circle drawn as three slivers, alone on the page.
        let a = line("a", (0.0, 0.0), (0.1, 0.0));
        let b = line("b", (0.1, 0.0), (0.05, 0.1));
        let c = line("c", (0.05, 0.1), (0.0, 0.0));
        let paths = vec![a, b, c];
        assert_eq!(remove(paths.clone(), 0.3, 0.3), paths);
    }

    #[test]
    fn debris_inside_a_path_of_several_strokes_goes_alone() {
        let mut both = line("both", (0.0, 0.0), (30.0, 0.0));
        both.path.move_to((5.0, 0.1));
        both.path.line_to((5.1, 0.1));
        let out = remove(vec![both], 0.3, 0.3);
        assert_eq!(out[0].path.elements().len(), 2);
        assert_eq!(count([&out[0].path], 0.3, 0.3), 0);
    }
}
