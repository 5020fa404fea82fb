//! Inside-first order for cutters: every closed path is cut after every
//! path inside it.
//!
//! A knife that cuts an outline before the holes inside it frees the piece,
//! which then shifts on the mat while the holes are cut. So each path gets
//! its *nesting depth* — how many closed paths of its layer enclose it —
//! and the deepest paths are cut first, level by level; inside a level the
//! travel sort ([`super::sort::order`]) orders the paths, when it runs.
//! A path inside a closed outline is at least one level deeper than that
//! outline, so it always comes first.
//!
//! "Inside" is tested at one point of the path (its start): outlines of a
//! drawing that is to be cut do not cross, so a path lies either wholly
//! inside a closed outline or wholly outside it. Candidates are found in a
//! grid of the outlines' bounding boxes, so a sheet of many small shapes
//! costs about one winding test per shape and per outline around it.

use kurbo::{BezPath, ParamCurve, PathSeg, Point, Rect, Shape};

use super::flatten::{set_paths, split_subpaths, take_paths};
use super::sort::{self, SortOptions};
use crate::geom::subpath::subpaths;
use crate::scene::{Scene, StyledPath};

/// Puts the paths of every layer of `scene` in inside-first order (see the
/// module documentation), each level ordered by `sort` when given, else
/// kept in scene order. Meant for a flat scene.
pub fn run(scene: &mut Scene, sort: Option<&SortOptions>) {
    for layer in &mut scene.layers {
        let paths = take_paths(layer);
        set_paths(layer, order(paths, sort));
    }
}

/// `paths`, split into single subpaths, deepest nesting level first; each
/// level ordered by `sort` when given, else kept in the given order.
pub fn order(paths: Vec<StyledPath>, sort: Option<&SortOptions>) -> Vec<StyledPath> {
    let paths = split_subpaths(paths);
    let depth = depths(&paths);
    let deepest = depth.iter().copied().max().unwrap_or(0);
    let mut levels: Vec<Vec<StyledPath>> = (0..=deepest).map(|_| Vec::new()).collect();
    for (p, d) in paths.into_iter().zip(depth) {
        levels[deepest - d].push(p);
    }
    levels
        .into_iter()
        .flat_map(|level| match sort {
            Some(s) => sort::order(level, s),
            None => level,
        })
        .collect()
}

/// The nesting depth of every path (each a single subpath): the number of
/// *other* closed paths that enclose its start. Of two closed paths with
/// the same bounding box only the earlier may enclose the later, so that
/// duplicated outlines do not enclose each other.
pub fn depths(paths: &[StyledPath]) -> Vec<usize> {
    let outlines: Vec<(usize, Rect)> = paths
        .iter()
        .enumerate()
        .filter(|(_, p)| subpaths(&p.path).next().is_some_and(|s| s.is_closed()))
        .map(|(i, p)| (i, p.path.bounding_box()))
        .collect();
    let grid = Grid::new(&outlines);
    let bands: Vec<Bands> = outlines
        .iter()
        .map(|&(j, _)| Bands::new(&paths[j].path))
        .collect();
    paths
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let Some(probe) = subpaths(&p.path).next().map(|s| s.start()) else {
                return 0;
            };
            let own = p.path.bounding_box();
            grid.at(probe)
                .iter()
                .filter(|&&k| {
                    let (j, b) = outlines[k];
                    j != i && encloses(b, j, own, i) && bands[k].winds(probe)
                })
                .count()
        })
        .collect()
}

/// Whether an outline with bounding box `outer` (path `j`) may enclose a
/// path with bounding box `inner` (path `i`): its box holds the other's,
/// and is larger or, when equal, belongs to the earlier path.
fn encloses(outer: Rect, j: usize, inner: Rect, i: usize) -> bool {
    let holds = outer.x0 <= inner.x0
        && outer.y0 <= inner.y0
        && outer.x1 >= inner.x1
        && outer.y1 >= inner.y1;
    holds && (outer != inner || j < i)
}

/// A closed outline's segments in horizontal bands, so that a winding
/// test meets only the segments that reach the probe's height: a
/// stencil's large outlines (thousands of vertices, round most of the
/// other cuts) would otherwise cost a pass over all their vertices for
/// every path inside them. A segment goes into every band its control
/// points reach, so that the band of a point holds every segment a ray
/// from it can cross: the winding number is the same as the whole path's.
struct Bands {
    y0: f64,
    step: f64,
    /// Each band's segments, each its own subpath (a path's winding
    /// number is the sum of its segments').
    bands: Vec<BezPath>,
}

/// About this many segments to a band; an outline with fewer than two
/// bands' worth is tested whole.
const BAND_SEGMENTS: usize = 16;

impl Bands {
    fn new(path: &BezPath) -> Bands {
        let segments: Vec<PathSeg> = path.segments().collect();
        let n = (segments.len() / BAND_SEGMENTS).clamp(1, 4096);
        let reach = |seg: &PathSeg| {
            let ys = match *seg {
                PathSeg::Line(l) => [l.p0.y, l.p1.y, l.p1.y, l.p1.y],
                PathSeg::Quad(q) => [q.p0.y, q.p1.y, q.p2.y, q.p2.y],
                PathSeg::Cubic(c) => [c.p0.y, c.p1.y, c.p2.y, c.p3.y],
            };
            ys.iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &y| {
                    (lo.min(y), hi.max(y))
                })
        };
        let (y0, y1) = segments
            .iter()
            .map(reach)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (a, b)| {
                (lo.min(a), hi.max(b))
            });
        let step = (y1 - y0) / n as f64;
        let mut bands = Bands {
            y0,
            step,
            bands: vec![BezPath::new(); if step > 0.0 { n } else { 1 }],
        };
        for seg in &segments {
            let (lo, hi) = reach(seg);
            for k in bands.band(lo)..=bands.band(hi) {
                let band = &mut bands.bands[k];
                band.move_to(seg.start());
                band.push(seg.as_path_el());
            }
        }
        bands
    }

    /// The band of height `y`: the bands' order is the heights' order,
    /// those beyond the ends clamped to them.
    fn band(&self, y: f64) -> usize {
        if self.bands.len() == 1 {
            return 0;
        }
        (((y - self.y0) / self.step).floor().max(0.0) as usize).min(self.bands.len() - 1)
    }

    /// Whether the outline goes round `p`.
    fn winds(&self, p: Point) -> bool {
        self.bands[self.band(p.y)].winding(p) != 0
    }
}

/// Bounding boxes of outlines by grid cell: about one cell per outline.
struct Grid {
    bounds: Rect,
    side: usize,
    cells: Vec<Vec<usize>>,
}

impl Grid {
    fn new(outlines: &[(usize, Rect)]) -> Grid {
        let bounds = outlines
            .iter()
            .map(|(_, b)| *b)
            .reduce(|a, b| a.union(b))
            .unwrap_or(Rect::ZERO);
        // Capped so that a few outlines as large as the sheet cost little.
        let side = ((outlines.len() as f64).sqrt().ceil() as usize).clamp(1, 256);
        let mut grid = Grid {
            bounds,
            side,
            cells: vec![Vec::new(); side * side],
        };
        for (k, (_, b)) in outlines.iter().enumerate() {
            let (x0, y0) = grid.cell(Point::new(b.x0, b.y0));
            let (x1, y1) = grid.cell(Point::new(b.x1, b.y1));
            for y in y0..=y1 {
                for x in x0..=x1 {
                    grid.cells[y * side + x].push(k);
                }
            }
        }
        grid
    }

    /// The cell holding `p`, clamped to the grid.
    fn cell(&self, p: Point) -> (usize, usize) {
        let along = |v: f64, lo: f64, hi: f64| {
            let t = if hi > lo { (v - lo) / (hi - lo) } else { 0.0 };
            ((t * self.side as f64).floor().max(0.0) as usize).min(self.side - 1)
        };
        (
            along(p.x, self.bounds.x0, self.bounds.x1),
            along(p.y, self.bounds.y0, self.bounds.y1),
        )
    }

    /// The outlines whose bounding box may hold `p`.
    fn at(&self, p: Point) -> &[usize] {
        if !self.bounds.contains(p) {
            return &[];
        }
        let (x, y) = self.cell(p);
        &self.cells[y * self.side + x]
    }
}

#[cfg(test)]
mod tests {
    use kurbo::Circle;

    use super::*;
    use crate::rng::Seed;
    use crate::scene::Style;

    fn path(id: &str, path: BezPath) -> StyledPath {
        StyledPath {
            id: id.into(),
            path,
            style: Style::default(),
        }
    }

    fn square(id: &str, x: f64, y: f64, size: f64) -> StyledPath {
        path(id, Rect::new(x, y, x + size, y + size).to_path(0.0))
    }

    /// Whether closed path `outer` goes round the whole of `inner` (every
    /// on-curve point of it): the relation the order must respect.
    fn inside(inner: &BezPath, outer: &BezPath) -> bool {
        inner
            .elements()
            .iter()
            .filter_map(|el| el.end_point())
            .all(|p| outer.winding(p) != 0)
    }

    #[test]
    fn an_outline_in_bands_winds_round_the_same_points_as_whole() {
        // A wavy ring of 400 sides with a curved notch: 25 bands.
        let mut outline = BezPath::new();
        for k in 0..400 {
            let a = std::f64::consts::TAU * f64::from(k) / 400.0;
            let r = 40.0 + 6.0 * (9.0 * a).sin();
            let p = Point::new(50.0 + r * a.cos(), 50.0 + r * a.sin());
            if k == 0 {
                outline.move_to(p);
            } else {
                outline.line_to(p);
            }
        }
        outline.curve_to((60.0, 40.0), (40.0, 60.0), (90.0, 50.0));
        outline.close_path();
        let bands = Bands::new(&outline);
        assert!(bands.bands.len() > 20, "{}", bands.bands.len());
        let mut inside = 0;
        for i in 0..=120 {
            for j in 0..=120 {
                let p = Point::new(f64::from(i) * 0.85 - 1.0, f64::from(j) * 0.85 - 1.0);
                let whole = outline.winding(p) != 0;
                assert_eq!(bands.winds(p), whole, "{p:?}");
                inside += usize::from(whole);
            }
        }
        assert!(inside > 1000 && inside < 121 * 121 - 1000, "{inside}");
    }

    #[test]
    fn every_path_comes_before_the_outlines_around_it() {
        // Nested squares, circles in some of them, open strokes inside.
        let mut rng = Seed(32).stream();
        let mut paths = Vec::new();
        for k in 0..40 {
            let x = 100.0 * rng.unit();
            let y = 100.0 * rng.unit();
            for (d, size) in [30.0, 20.0, 10.0].into_iter().enumerate() {
                let o = (30.0 - size) / 2.0;
                paths.push(square(&format!("s{k}.{d}"), x + o, y + o, size));
            }
            let mut line = BezPath::new();
            line.move_to((x + 14.0, y + 15.0));
            line.line_to((x + 16.0, y + 15.0));
            paths.push(path(&format!("l{k}"), line));
            paths.push(path(
                &format!("c{k}"),
                Circle::new((x + 15.0, y + 15.0), 7.0).to_path(0.1),
            ));
        }
        // Scrambled, so that scene order alone does not pass.
        paths.reverse();
        for sort in [None, Some(&SortOptions::DEFAULT)] {
            let ordered = order(paths.clone(), sort);
            assert_eq!(ordered.len(), paths.len());
            let mut pairs = 0;
            for (a, inner) in ordered.iter().enumerate() {
                for (b, outer) in ordered.iter().enumerate() {
                    if a != b
                        && subpaths(&outer.path).next().unwrap().is_closed()
                        && inside(&inner.path, &outer.path)
                    {
                        pairs += 1;
                        assert!(a < b, "{} is cut after {} around it", inner.id, outer.id);
                    }
                }
            }
            assert!(pairs > 200, "only {pairs} nested pairs tested");
        }
    }

    #[test]
    fn depth_counts_the_outlines_around_a_path() {
        let paths = vec![
            square("outer", 0.0, 0.0, 30.0),
            square("middle", 5.0, 5.0, 20.0),
            square("inner", 10.0, 10.0, 10.0),
            square("beside", 40.0, 0.0, 10.0),
            square("copy", 40.0, 0.0, 10.0),
        ];
        assert_eq!(depths(&paths), [0, 1, 2, 0, 1]);
    }

    #[test]
    fn without_nesting_the_sort_alone_decides() {
        let paths: Vec<StyledPath> = (0..10)
            .map(|k| square(&format!("s{k}"), 50.0 - 5.0 * k as f64, 0.0, 4.0))
            .collect();
        let ids = |ps: Vec<StyledPath>| ps.into_iter().map(|p| p.id).collect::<Vec<_>>();
        assert_eq!(
            ids(order(paths.clone(), Some(&SortOptions::DEFAULT))),
            ids(sort::order(paths.clone(), &SortOptions::DEFAULT))
        );
        assert_eq!(ids(order(paths.clone(), None)), ids(paths));
    }
}
