//! Plot statistics: how much the pen draws, how far it travels lifted, and
//! how long the plot takes.
//!
//! The figures are those of the plot the SVG describes, in the file's
//! order: [`stats`] looks at the scene as the SVG writer lays it out, one
//! layer per pen in ascending pen number with its scene layers back to
//! front (exactly [`super::flatten::by_pen`]), and at the paths in that
//! order, in page coordinates.
//!
//! - **Pen-down length**: the arc length of every segment (move-tos lift
//!   the pen), as [`crate::geom::path_length`].
//! - **Pen-up length**: straight moves from the origin (0, 0), the
//!   plotter's home at the top-left corner of the sheet, to the start of
//!   the first subpath, and from the end of each subpath to the start of
//!   the next ([`pen_up_length`]). Each layer starts from the origin: a
//!   plotter runs the layers one after another with a pause for a pen
//!   change in between, returning home (as the AxiDraw does with layer
//!   pauses). The move home at the end of a layer is not counted.
//! - **Pen lifts**: one per subpath that draws something (a path with two
//!   subpaths lifts the pen twice).
//! - **Plot time**, with the [`Speeds`]:
//!   `pen_down_mm / pen_down_mm_s + pen_up_mm / pen_up_mm_s + pen_lifts ·
//!   pen_lift_s`. Acceleration is ignored, so real plots of many tiny paths
//!   take longer; pen changes between layers are not counted.
//! - **Doubled length**: line work that lies on other line work of the
//!   same pen, within a quarter of the pen's width, running the same way,
//!   over runs of at least two pen widths
//!   ([`super::dedupe::doubled_length`]: shorter shared runs are what
//!   lines crossing at a shallow angle share).
//! - **Debris**: strokes shorter than the pen's width that touch other
//!   line work of the pen ([`super::debris::count`]): what the debris stage
//!   would take out.
//! - **Densest**: the most ink in any square millimetre of the sheet (a
//!   grid aligned to the page), as a multiple of what covers it solid —
//!   the line length there times the pen's width ([`densest`]). Past about
//!   2, a felt tip pills or tears the paper.
//!
//! **Layers that are not plotted** (AxiDraw's `%` documentation layers,
//! [`Layer::is_plotted`](crate::scene::Layer::is_plotted) false) are listed
//! like the others, first (where the SVG writer puts them), with
//! [`LayerStats::plotted`] false and figures computed as if that layer were
//! plotted on its own; they count in none of the totals of [`PlotStats`].

use std::borrow::Cow;

use kurbo::{Affine, BezPath, Point};
use serde::{Deserialize, Serialize};

use super::cover::Pieces;
use super::flatten::by_pen;
use super::{debris, dedupe, DebrisOptions, DedupeOptions};
use crate::geom::path_length;
use crate::geom::subpath::subpaths;
use crate::scene::Scene;

/// Plotter speeds for the time estimate of [`stats`].
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Speeds {
    /// Drawing speed, mm/s.
    pub pen_down_mm_s: f64,
    /// Travel speed with the pen up, mm/s.
    pub pen_up_mm_s: f64,
    /// Time for one pen lift (raising and lowering once), s.
    pub pen_lift_s: f64,
}

impl Speeds {
    /// 25 mm/s drawing, 75 mm/s travel, 0.15 s per pen lift: an AxiDraw
    /// at moderate settings.
    pub const DEFAULT: Speeds = Speeds {
        pen_down_mm_s: 25.0,
        pen_up_mm_s: 75.0,
        pen_lift_s: 0.15,
    };

    /// These speeds with [`Speeds::pen_down_mm_s`] set.
    pub const fn with_pen_down_mm_s(mut self, v: f64) -> Speeds {
        self.pen_down_mm_s = v;
        self
    }

    /// These speeds with [`Speeds::pen_up_mm_s`] set.
    pub const fn with_pen_up_mm_s(mut self, v: f64) -> Speeds {
        self.pen_up_mm_s = v;
        self
    }

    /// These speeds with [`Speeds::pen_lift_s`] set.
    pub const fn with_pen_lift_s(mut self, v: f64) -> Speeds {
        self.pen_lift_s = v;
        self
    }

    /// Seconds to draw `down` mm, travel `up` mm and lift the pen `lifts`
    /// times.
    pub fn time(&self, down: f64, up: f64, lifts: usize) -> f64 {
        down / self.pen_down_mm_s + up / self.pen_up_mm_s + lifts as f64 * self.pen_lift_s
    }
}

impl Default for Speeds {
    fn default() -> Speeds {
        Speeds::DEFAULT
    }
}

/// Figures of one layer of the plot: one pen's layer, or a layer that is
/// not plotted.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LayerStats {
    /// Layer id: `pen-N.layer` for a pen's layer, the scene layer's own id
    /// for a layer that is not plotted.
    pub id: String,
    /// The pen's name (the layer's name, `%…`, for a layer that is not
    /// plotted).
    pub name: String,
    /// Pen number.
    pub pen: u32,
    /// Whether the plotter draws this layer. When false (a `%`
    /// documentation layer), its figures are not part of the totals.
    pub plotted: bool,
    /// Number of paths.
    pub paths: usize,
    /// Number of pen lifts (subpaths that draw).
    pub pen_lifts: usize,
    /// Length drawn, mm.
    pub pen_down_mm: f64,
    /// Length travelled with the pen up, from the origin, mm.
    pub pen_up_mm: f64,
    /// Estimated time, s.
    pub plot_time_s: f64,
    /// Length drawn over line work the pen already draws, mm.
    pub doubled_mm: f64,
    /// Strokes shorter than the pen's width touching other line work.
    pub debris: usize,
    /// The most ink in any mm² of the sheet, in multiples of solid.
    pub densest: f64,
}

/// Figures of a whole plot: totals over the plotted layers, and each layer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlotStats {
    /// Number of paths.
    pub paths: usize,
    /// Number of pen lifts.
    pub pen_lifts: usize,
    /// Length drawn, mm.
    pub pen_down_mm: f64,
    /// Length travelled with the pen up, mm (the sum over the layers).
    pub pen_up_mm: f64,
    /// Estimated time, s (the sum over the layers).
    pub plot_time_s: f64,
    /// Length drawn twice, mm (the sum over the layers).
    pub doubled_mm: f64,
    /// Debris strokes (the sum over the layers).
    pub debris: usize,
    /// The most ink in any mm² of the sheet, in multiples of solid (the
    /// largest over the layers).
    pub densest: f64,
    /// Per layer, in the order of the file: layers that are not plotted
    /// first, then the pens in plotting order.
    pub layers: Vec<LayerStats>,
}

/// The statistics of `scene` as plotted (see the module documentation).
pub fn stats(scene: &Scene, speeds: &Speeds) -> PlotStats {
    let flat = by_pen(scene);
    let mut total = PlotStats {
        paths: 0,
        pen_lifts: 0,
        pen_down_mm: 0.0,
        pen_up_mm: 0.0,
        plot_time_s: 0.0,
        doubled_mm: 0.0,
        debris: 0,
        densest: 0.0,
        layers: Vec::with_capacity(flat.layers.len()),
    };
    for layer in &flat.layers {
        // A pen's layer is flat; a layer that is not plotted keeps its
        // groups (see `by_pen`).
        let mut paths: Vec<Cow<'_, BezPath>> = Vec::new();
        layer.content.visit_paths(Affine::IDENTITY, &mut |p, t| {
            paths.push(if t == Affine::IDENTITY {
                Cow::Borrowed(&p.path)
            } else {
                Cow::Owned(t * p.path.clone())
            });
        });
        let pen_down_mm: f64 = paths.iter().map(|p| path_length(p)).sum();
        let (pen_up_mm, pen_lifts) = travel(paths.iter().map(|p| &**p));
        let width = scene.pen_width(layer.pen);
        let doubled_mm = dedupe::doubled_length(
            paths.iter().map(|p| &**p),
            DedupeOptions::DEFAULT.tolerance_for(width),
            2.0 * width,
        );
        let debris = debris::count(
            paths.iter().map(|p| &**p),
            DebrisOptions::DEFAULT.length_for(width),
            width,
        );
        let s = LayerStats {
            id: layer.id.clone(),
            name: layer.name.clone(),
            pen: layer.pen,
            plotted: layer.is_plotted(),
            paths: paths.len(),
            pen_lifts,
            pen_down_mm,
            pen_up_mm,
            plot_time_s: speeds.time(pen_down_mm, pen_up_mm, pen_lifts),
            doubled_mm,
            debris,
            densest: densest(paths.iter().map(|p| &**p), width),
        };
        if !s.plotted {
            total.layers.push(s);
            continue;
        }
        total.paths += s.paths;
        total.pen_lifts += s.pen_lifts;
        total.pen_down_mm += s.pen_down_mm;
        total.pen_up_mm += s.pen_up_mm;
        total.plot_time_s += s.plot_time_s;
        total.doubled_mm += s.doubled_mm;
        total.debris += s.debris;
        total.densest = total.densest.max(s.densest);
        total.layers.push(s);
    }
    total
}

/// Pieces of line [`densest`] puts in the cell of their middle are no
/// longer than this (mm): a cell's length is right within a twentieth of a
/// millimetre for every line through it.
const PIECE: f64 = 0.05;

/// The most ink a pen `width` mm wide lays into one square millimetre of
/// a grid aligned to the page, in multiples of solid: the length of line
/// whose pieces' middles fall in the cell, times the width.
pub fn densest<'a>(paths: impl IntoIterator<Item = &'a BezPath>, width: f64) -> f64 {
    let mut cells: rustc_hash::FxHashMap<(i64, i64), f64> = Default::default();
    for path in paths {
        for sub in subpaths(path) {
            let pieces = Pieces::new(sub.segments().collect(), false, PIECE, 0.01);
            for p in &pieces.pieces {
                let mid = p.a.midpoint(p.b);
                *cells
                    .entry((mid.x.floor() as i64, mid.y.floor() as i64))
                    .or_default() += p.len();
            }
        }
    }
    cells.values().copied().fold(0.0_f64, f64::max) * width
}

/// Pen-up travel of drawing `paths` in this order, starting from the
/// origin: straight moves to the start of every subpath that draws, from
/// where the previous one ended (a subpath that ends with a close-path ends
/// at its start; see [`crate::geom::subpath`]).
pub fn pen_up_length<'a>(paths: impl IntoIterator<Item = &'a BezPath>) -> f64 {
    travel(paths).0
}

/// Pen-up length and number of pen lifts: one lift to the start of every
/// subpath (see [`subpaths`]), from where the previous one ended.
fn travel<'a>(paths: impl IntoIterator<Item = &'a BezPath>) -> (f64, usize) {
    let mut pen = Point::ORIGIN;
    let mut up = 0.0;
    let mut lifts = 0;
    for sub in paths.into_iter().flat_map(subpaths) {
        up += pen.distance(sub.start());
        lifts += 1;
        pen = sub.end();
    }
    (up, lifts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Color, Group, Layer, Pen, Style};
    use crate::units::{Margins, Orientation, Page, PaperName};
    use kurbo::{Affine, Line, Shape};

    fn line(a: (f64, f64), b: (f64, f64)) -> BezPath {
        Line::new(a, b).into_path(0.1)
    }

    #[test]
    fn travel_counts_subpaths_and_closes() {
        let mut p = BezPath::new();
        p.move_to((3.0, 4.0)); // 5 from the origin
        p.line_to((13.0, 4.0));
        p.line_to((13.0, 14.0));
        p.close_path(); // back at (3,4)
        p.close_path(); // nothing
        p.line_to((3.0, 10.0)); // new subpath from (3,4): no travel
        p.move_to((100.0, 100.0)); // lone move-to: nothing
        p.move_to((3.0, 13.0)); // 3 from (3,10)
        p.line_to((0.0, 13.0));
        let (up, lifts) = travel([&p]);
        assert!((up - 8.0).abs() < 1e-12, "{up}");
        assert_eq!(lifts, 3);
        let q = line((0.0, 17.0), (0.0, 20.0)); // 4 from (0,13)
        assert!((pen_up_length([&p, &q]) - 12.0).abs() < 1e-12);
    }

    #[test]
    fn stats_of_a_small_scene() {
        // Pen 1: two layers; the back one (depth 2) is plotted first.
        let mut back = Group::new("back");
        back.push_path("b", line((0.0, 0.0), (30.0, 0.0)), Style::default());
        let mut front = Group::new("front");
        front.transform = Affine::scale(2.0);
        front.push_path("f", line((15.0, 20.0), (15.0, 25.0)), Style::default());
        // Pen 2: one path.
        let mut other = Group::new("other");
        other.push_path("o", line((0.0, 10.0), (0.0, 0.0)), Style::default());
        let scene = Scene {
            page: Page::named(PaperName::A4, Orientation::Portrait, Margins::uniform(10.0)),
            pens: vec![Pen {
                number: 1,
                name: "black".into(),
                color: Color::BLACK,
                width: 0.3,
            }],
            layers: vec![
                Layer {
                    id: "front".into(),
                    name: "front".into(),
                    pen: 1,
                    depth: 0,
                    content: front,
                },
                Layer {
                    id: "other".into(),
                    name: "other".into(),
                    pen: 2,
                    depth: 0,
                    content: other,
                },
                Layer {
                    id: "back".into(),
                    name: "back".into(),
                    pen: 1,
                    depth: 2,
                    content: back,
                },
            ],
            description: None,
        };
        let speeds = Speeds::DEFAULT
            .with_pen_down_mm_s(10.0)
            .with_pen_up_mm_s(20.0)
            .with_pen_lift_s(1.0);
        let s = stats(&scene, &speeds);
        // Page coordinates: b (10,10)→(40,10); f (40,50)→(40,60); o (10,20)→(10,10).
        let l1 = &s.layers[0];
        assert_eq!(
            (l1.id.as_str(), l1.name.as_str(), l1.pen),
            ("pen-1.layer", "black", 1)
        );
        assert_eq!((l1.paths, l1.pen_lifts), (2, 2));
        assert!((l1.pen_down_mm - 40.0).abs() < 1e-9);
        let up1 = 200f64.sqrt() + 40.0;
        assert!((l1.pen_up_mm - up1).abs() < 1e-9);
        assert!((l1.plot_time_s - (4.0 + up1 / 20.0 + 2.0)).abs() < 1e-9);
        let l2 = &s.layers[1];
        assert_eq!(
            (l2.id.as_str(), l2.name.as_str(), l2.pen),
            ("pen-2.layer", "", 2)
        );
        let up2 = 500f64.sqrt();
        assert!((l2.pen_up_mm - up2).abs() < 1e-9);
        assert_eq!(s.paths, 3);
        assert_eq!(s.pen_lifts, 3);
        assert!((s.pen_down_mm - 50.0).abs() < 1e-9);
        assert!((s.pen_up_mm - (up1 + up2)).abs() < 1e-9);
        assert!((s.plot_time_s - (l1.plot_time_s + l2.plot_time_s)).abs() < 1e-9);

        let json = serde_json::to_value(&s).unwrap();
        for key in ["paths", "pen_down_mm", "pen_up_mm", "plot_time_s"] {
            assert!(json[key].is_number(), "{key}");
        }
        assert_eq!(json["layers"][1]["id"], "pen-2.layer");
    }

    #[test]
    fn unplotted_layers_are_listed_but_not_counted() {
        let mut plotted = Group::new("plotted");
        plotted.push_path("p", line((0.0, 0.0), (30.0, 0.0)), Style::default());
        let mut guides = Group::new("guides");
        let mut inner = Group::new("inner");
        inner.transform = Affine::scale(2.0);
        inner.push_path("g", line((0.0, 10.0), (0.0, 60.0)), Style::default());
        guides.push_group(inner);
        guides.push_path("h", line((5.0, 0.0), (5.0, 1.0)), Style::default());
        let layer = |id: &str, name: &str, pen, content| Layer {
            id: id.into(),
            name: name.into(),
            pen,
            depth: 0,
            content,
        };
        let mut scene = Scene {
            page: Page::named(PaperName::A4, Orientation::Portrait, Margins::default()),
            pens: vec![],
            layers: vec![
                layer("drawing", "drawing", 1, plotted),
                layer("guides", "%guides", 1, guides),
            ],
            description: None,
        };
        let s = stats(&scene, &Speeds::DEFAULT);
        assert_eq!(s.layers.len(), 2);
        let g = &s.layers[0];
        assert_eq!(
            (g.id.as_str(), g.name.as_str(), g.pen, g.plotted),
            ("guides", "%guides", 1, false)
        );
        // Its own figures, groups and transforms included: 100 + 1 mm.
        assert_eq!((g.paths, g.pen_lifts), (2, 2));
        assert!((g.pen_down_mm - 101.0).abs() < 1e-9, "{}", g.pen_down_mm);
        assert!(g.pen_up_mm > 0.0 && g.plot_time_s > 0.0);
        let p = &s.layers[1];
        assert!(p.plotted);
        // The totals are the plotted layer's alone.
        assert_eq!((s.paths, s.pen_lifts), (p.paths, p.pen_lifts));
        assert_eq!(
            (s.pen_down_mm, s.pen_up_mm, s.plot_time_s),
            (p.pen_down_mm, p.pen_up_mm, p.plot_time_s)
        );
        assert_eq!(s.pen_down_mm, 30.0);
        let json = serde_json::to_value(&s).unwrap();
        assert_eq!(json["layers"][0]["plotted"], false);
        assert_eq!(json["layers"][1]["plotted"], true);

        // Without the plotted layer, nothing is plotted at all.
        scene.layers.remove(0);
        let s = stats(&scene, &Speeds::DEFAULT);
        assert_eq!(
            (s.paths, s.pen_down_mm, s.pen_up_mm, s.plot_time_s),
            (0, 0.0, 0.0, 0.0)
        );
        assert_eq!(s.layers.len(), 1);
    }

    #[test]
    fn densest_is_the_most_ink_in_a_square_millimetre() {
        // Ten lines 0.1 mm apart across one millimetre, and a long line
        // elsewhere: 10 mm of a 0.3 mm line in one mm², three times solid.
        let mut path = BezPath::new();
        for k in 0..10 {
            let y = 5.05 + 0.09 * f64::from(k);
            path.move_to((20.0, y));
            path.line_to((21.0, y));
        }
        path.move_to((40.0, 40.5));
        path.line_to((80.0, 40.5));
        let d = densest([&path], 0.3);
        assert!((d - 3.0).abs() < 0.01, "{d}");
        assert_eq!(densest([&BezPath::new()], 0.3), 0.0);
    }

    #[test]
    fn empty_scene_has_zero_stats() {
        let scene = Scene {
            page: Page::named(PaperName::A5, Orientation::Portrait, Margins::default()),
            pens: vec![],
            layers: vec![],
            description: None,
        };
        let s = stats(&scene, &Speeds::default());
        assert_eq!(
            (s.paths, s.pen_down_mm, s.pen_up_mm, s.plot_time_s),
            (0, 0.0, 0.0, 0.0)
        );
        assert!(s.layers.is_empty());
    }
}
