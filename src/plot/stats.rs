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
//! - **Plot time**, two figures with the [`Speeds`]. *At constant speed*
//!   ([`PlotStats::plot_time_s`]): `pen_down_mm / pen_down_mm_s +
//!   pen_up_mm / pen_up_mm_s + pen_lifts · pen_lift_s`, as if the pen
//!   moved at full speed from the first millimetre to the last. *With
//!   acceleration* ([`PlotStats::plot_time_accel_s`]): the same moves and
//!   lifts, the pen starting and stopping at every subpath and slowing
//!   down for corners, as a planner for the AxiDraw plans them (below).
//!   It is never less than the first, and is the one to believe for plots
//!   of many short strokes or sharp turns. Neither counts pen changes
//!   between layers.
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
//!
//! # Plot time with acceleration
//!
//! The motion model of saxi's planner (`src/planning.ts` in
//! github.com/nornagon/saxi, itself after Michael Fogleman's `axi`): a
//! constant-acceleration planner whose corners follow GRBL's junction
//! deviation. With `v` the maximum speed, `a` the acceleration and `δ`
//! the cornering distance ([`Speeds`]: `pen_down_mm_s`,
//! `pen_down_accel_mm_s2`, `cornering_mm` when drawing):
//!
//! - Every subpath that draws is one pen-down move along straight
//!   *pieces*: its lines as they are, its curves flattened within
//!   [`FLATNESS`] mm (the G-code writer's default), each curve's pieces
//!   stretched by one factor so that they add up to its arc length (the
//!   move is as long as the pen-down length). A piece shorter than
//!   [`MIN_PIECE`] has no direction of its own and lengthens its
//!   neighbour.
//! - The pen is at rest where a move starts and where it ends. Where a
//!   piece of unit direction `d₁` meets one of direction `d₂`, let
//!   `s = √((1 + d₁·d₂) / 2)`, the sine of half the angle between going
//!   back along `d₁` and going on along `d₂` (1 straight on, 0 turning
//!   back). The pen passes the junction at most at
//!   `min(v, √(a·δ·s / (1 − s)))` (`v` when `s = 1`): the speed at which
//!   it would follow, at centripetal acceleration `a`, the arc tangent to
//!   both pieces that passes `δ` from the corner.
//! - Those limits are lowered so that no piece asks for more than `a`:
//!   backwards, `vᵢ ≤ √(vᵢ₊₁² + 2·a·Lᵢ)`, then forwards,
//!   `vᵢ₊₁ ≤ √(vᵢ² + 2·a·Lᵢ)`, for the piece `i` of length `Lᵢ` between
//!   junctions `i` and `i + 1`. (saxi backtracks where this makes a
//!   backward pass; the limits are the same.)
//! - A piece of length `L` entered at `u` and left at `w` speeds up at
//!   `a`, runs at `v` if it gets there, and slows down at `a`. With
//!   `p² = a·L + (u² + w²) / 2`, it takes `(2p − u − w) / a` when `p ≤ v`
//!   (a triangle), else `(2v − u − w) / a + (L − (2v² − u² − w²) / (2a)) / v`
//!   (a trapezoid).
//! - A pen-up move is one straight piece from rest to rest at the pen-up
//!   speed and acceleration (`pen_up_mm_s`, `pen_up_accel_mm_s2`):
//!   `2·√(D / a)` for a distance `D ≤ v² / a`, else `D / v + v / a`.
//! - Every pen lift costs `pen_lift_s`, as at constant speed.
//!
//! Each junction, piece and move is looked at a fixed number of times: the
//! estimate is linear in the number of pieces. Left out: pen changes
//! between layers, the move home at the end, the servo's own motion (a
//! fixed time per lift, where saxi counts a drop and a lift duration),
//! the motors' step resolution and the time the plotter spends receiving
//! commands. Since no piece runs faster than at constant speed, the
//! figure is never below that one.
//!
//! The default accelerations and cornering distance are saxi's defaults
//! for the AxiDraw (its `defaultPlanOptions`): 200 mm/s² drawing with a
//! cornering factor of 0.127 mm (0.005 in), 400 mm/s² travelling. saxi's
//! maximum speeds there are 50 and 200 mm/s; moyo keeps its moderate 25
//! and 75 mm/s (see [`Speeds::DEFAULT`]).

use std::borrow::Cow;

use kurbo::{Affine, BezPath, ParamCurve, ParamCurveArclen, PathEl, PathSeg, Point, Vec2};
use serde::{Deserialize, Serialize};

use super::cover::Pieces;
use super::flatten::by_pen;
use super::{debris, dedupe, DebrisOptions, DedupeOptions};
use crate::error::{Error, Result};
use crate::geom::subpath::{subpaths, Subpath};
use crate::geom::LENGTH_ACCURACY;
use crate::scene::Scene;

/// Curves are flattened within this distance (mm) for the time with
/// acceleration: the G-code writer's default tolerance, what a plotter
/// fed by moyo follows.
pub const FLATNESS: f64 = 0.02;

/// A piece of a pen-down move shorter than this (mm) is rounding noise
/// with no direction to speak of: it lengthens its neighbour instead of
/// making a corner.
pub const MIN_PIECE: f64 = 1e-6;

/// Plotter speeds for the time estimates of [`stats`]: maximum speeds,
/// accelerations, cornering and pen lifts.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Speeds {
    /// Drawing speed, mm/s: the speed of the whole pen-down length at
    /// constant speed, the most it reaches with acceleration.
    pub pen_down_mm_s: f64,
    /// Travel speed with the pen up, mm/s (likewise).
    pub pen_up_mm_s: f64,
    /// Time for one pen lift (raising and lowering once), s.
    pub pen_lift_s: f64,
    /// Acceleration and deceleration while drawing, mm/s².
    pub pen_down_accel_mm_s2: f64,
    /// Acceleration and deceleration while travelling, mm/s².
    pub pen_up_accel_mm_s2: f64,
    /// Cornering distance while drawing, mm: how far from a corner the
    /// arc the pen's speed there is reckoned on passes (GRBL's junction
    /// deviation, saxi's cornering factor). 0 stops the pen at every
    /// corner; larger values take corners faster.
    pub cornering_mm: f64,
}

impl Speeds {
    /// 25 mm/s drawing, 75 mm/s travel, 0.15 s per pen lift: an AxiDraw
    /// at moderate settings; with acceleration, saxi's defaults for the
    /// AxiDraw: 200 mm/s² drawing, 400 mm/s² travelling, cornering
    /// 0.127 mm (see the [module documentation](self)).
    pub const DEFAULT: Speeds = Speeds {
        pen_down_mm_s: 25.0,
        pen_up_mm_s: 75.0,
        pen_lift_s: 0.15,
        pen_down_accel_mm_s2: 200.0,
        pen_up_accel_mm_s2: 400.0,
        cornering_mm: 0.127,
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

    /// These speeds with [`Speeds::pen_down_accel_mm_s2`] set.
    pub const fn with_pen_down_accel_mm_s2(mut self, a: f64) -> Speeds {
        self.pen_down_accel_mm_s2 = a;
        self
    }

    /// These speeds with [`Speeds::pen_up_accel_mm_s2`] set.
    pub const fn with_pen_up_accel_mm_s2(mut self, a: f64) -> Speeds {
        self.pen_up_accel_mm_s2 = a;
        self
    }

    /// These speeds with [`Speeds::cornering_mm`] set.
    pub const fn with_cornering_mm(mut self, d: f64) -> Speeds {
        self.cornering_mm = d;
        self
    }

    /// Checks the values.
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the field (`pen_down_accel_mm_s2`, …) when
    /// a speed or an acceleration is not a finite number > 0, or the lift
    /// time or the cornering distance is not a finite number ≥ 0.
    pub fn validate(&self) -> Result<()> {
        for (field, value, unit) in [
            ("pen_down_mm_s", self.pen_down_mm_s, "mm/s"),
            ("pen_up_mm_s", self.pen_up_mm_s, "mm/s"),
            ("pen_down_accel_mm_s2", self.pen_down_accel_mm_s2, "mm/s²"),
            ("pen_up_accel_mm_s2", self.pen_up_accel_mm_s2, "mm/s²"),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(Error::invalid(
                    field,
                    format!("must be a finite number of {unit} > 0, got {value}"),
                ));
            }
        }
        for (field, value, unit) in [
            ("pen_lift_s", self.pen_lift_s, "s"),
            ("cornering_mm", self.cornering_mm, "mm"),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(Error::invalid(
                    field,
                    format!("must be a finite number of {unit} ≥ 0, got {value}"),
                ));
            }
        }
        Ok(())
    }

    /// Seconds to draw `down` mm, travel `up` mm and lift the pen `lifts`
    /// times, at constant speed.
    pub fn time(&self, down: f64, up: f64, lifts: usize) -> f64 {
        down / self.pen_down_mm_s + up / self.pen_up_mm_s + lifts as f64 * self.pen_lift_s
    }

    /// The limits of pen-down moves.
    fn drawing(&self) -> Motion {
        Motion {
            v: self.pen_down_mm_s,
            a: self.pen_down_accel_mm_s2,
            cornering: self.cornering_mm,
        }
    }

    /// The limits of pen-up moves (straight: they have no corners).
    fn travelling(&self) -> Motion {
        Motion {
            v: self.pen_up_mm_s,
            a: self.pen_up_accel_mm_s2,
            cornering: 0.0,
        }
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
    /// Estimated time at constant speed, s.
    pub plot_time_s: f64,
    /// Estimated time with acceleration and cornering, s (never less than
    /// [`LayerStats::plot_time_s`]).
    pub plot_time_accel_s: f64,
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
    /// Estimated time at constant speed, s (the sum over the layers).
    pub plot_time_s: f64,
    /// Estimated time with acceleration and cornering, s (the sum over the
    /// layers; never less than [`PlotStats::plot_time_s`]).
    pub plot_time_accel_s: f64,
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
///
/// The `speeds` are taken as they are: speeds or accelerations that
/// [`Speeds::validate`] refuses give meaningless times (infinite, not a
/// number or negative).
pub fn stats(scene: &Scene, speeds: &Speeds) -> PlotStats {
    let flat = by_pen(scene);
    let mut total = PlotStats {
        paths: 0,
        pen_lifts: 0,
        pen_down_mm: 0.0,
        pen_up_mm: 0.0,
        plot_time_s: 0.0,
        plot_time_accel_s: 0.0,
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
        let run = walk(paths.iter().map(|p| &**p), speeds);
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
            pen_lifts: run.pen_lifts,
            pen_down_mm: run.pen_down_mm,
            pen_up_mm: run.pen_up_mm,
            plot_time_s: speeds.time(run.pen_down_mm, run.pen_up_mm, run.pen_lifts),
            plot_time_accel_s: run.time_accel_s,
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
        total.plot_time_accel_s += s.plot_time_accel_s;
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
    lifts(paths).map(|(_, up)| up).sum()
}

/// Every subpath of `paths` (see [`subpaths`]), each with the length of
/// the pen-up move to its start from where the previous one ended (from
/// the origin for the first).
fn lifts<'a>(
    paths: impl IntoIterator<Item = &'a BezPath>,
) -> impl Iterator<Item = (Subpath<'a>, f64)> {
    let mut pen = Point::ORIGIN;
    paths.into_iter().flat_map(subpaths).map(move |sub| {
        let up = pen.distance(sub.start());
        pen = sub.end();
        (sub, up)
    })
}

/// What drawing some paths in order, from the origin, comes to.
#[derive(Debug, Default, Clone, Copy, PartialEq)]
struct Run {
    /// Arc length drawn, mm.
    pen_down_mm: f64,
    /// Length of the pen-up moves, mm.
    pen_up_mm: f64,
    /// Subpaths drawn.
    pen_lifts: usize,
    /// Time with acceleration, pen lifts included, s.
    time_accel_s: f64,
}

/// The lengths, lifts and time with acceleration of drawing `paths` in
/// this order from the origin (see the module documentation).
fn walk<'a>(paths: impl IntoIterator<Item = &'a BezPath>, speeds: &Speeds) -> Run {
    let (drawing, travelling) = (speeds.drawing(), speeds.travelling());
    let mut run = Run::default();
    // Reused from one subpath to the next.
    let (mut pieces, mut points, mut junctions) = (Vec::new(), Vec::new(), Vec::new());
    for (sub, up) in lifts(paths) {
        run.pen_up_mm += up;
        run.pen_lifts += 1;
        run.pen_down_mm += pieces_of(sub, &mut pieces, &mut points);
        run.time_accel_s += travelling.piece_s(up, 0.0, 0.0)
            + speeds.pen_lift_s
            + drawing.move_s(&pieces, &mut junctions);
    }
    run
}

/// A straight piece of a pen-down move.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Piece {
    /// Unit direction.
    dir: Vec2,
    /// Length, mm.
    len: f64,
}

/// Puts into `pieces` the straight pieces the pen runs along to draw `sub`
/// (see the module documentation), and returns its arc length. `points`
/// is room for one segment's flattening.
fn pieces_of(sub: Subpath<'_>, pieces: &mut Vec<Piece>, points: &mut Vec<Point>) -> f64 {
    pieces.clear();
    let mut length = 0.0;
    // Length of the pieces too short to have a direction before the first
    // that has one.
    let mut pending = 0.0;
    for seg in sub.segments() {
        let arc = seg.arclen(LENGTH_ACCURACY);
        length += arc;
        points.clear();
        match seg {
            PathSeg::Line(l) => points.extend([l.p0, l.p1]),
            _ => kurbo::flatten(
                [PathEl::MoveTo(seg.start()), seg.as_path_el()],
                FLATNESS,
                |el| {
                    if let PathEl::MoveTo(p) | PathEl::LineTo(p) = el {
                        points.push(p);
                    }
                },
            ),
        }
        let chords: f64 = points.windows(2).map(|w| w[0].distance(w[1])).sum();
        let stretch = if chords > 0.0 { arc / chords } else { 0.0 };
        for w in points.windows(2) {
            let chord = w[0].distance(w[1]);
            if chord >= MIN_PIECE {
                pieces.push(Piece {
                    dir: (w[1] - w[0]) / chord,
                    len: chord * stretch + std::mem::take(&mut pending),
                });
            } else if let Some(last) = pieces.last_mut() {
                last.len += chord * stretch;
            } else {
                pending += chord * stretch;
            }
        }
        if chords == 0.0 {
            // A curve that ends where it starts and never leaves: its
            // length (if any) has no direction.
            match pieces.last_mut() {
                Some(last) => last.len += arc,
                None => pending += arc,
            }
        }
    }
    if pending > 0.0 {
        // Nothing long enough to point anywhere: one piece, whose
        // direction does not matter.
        pieces.push(Piece {
            dir: Vec2::new(1.0, 0.0),
            len: pending,
        });
    }
    length
}

/// The limits of one kind of move.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Motion {
    /// Maximum speed, mm/s.
    v: f64,
    /// Acceleration, mm/s².
    a: f64,
    /// Cornering distance δ, mm.
    cornering: f64,
}

impl Motion {
    /// The most speed through the junction from a piece of unit direction
    /// `d1` into one of unit direction `d2`.
    fn junction(&self, d1: Vec2, d2: Vec2) -> f64 {
        // The sine of half the angle between going back along d1 and going
        // on along d2.
        let s = ((1.0 + d1.dot(d2)) / 2.0).clamp(0.0, 1.0).sqrt();
        if s >= 1.0 {
            return self.v;
        }
        (self.a * self.cornering * s / (1.0 - s)).sqrt().min(self.v)
    }

    /// Seconds to run `len` mm along a straight line, entering at `u` and
    /// leaving at `w` mm/s (reachable from each other within `len`).
    fn piece_s(&self, len: f64, u: f64, w: f64) -> f64 {
        let (v, a) = (self.v, self.a);
        // The speed reached by speeding up from u, then slowing down to w.
        let peak2 = a * len + (u * u + w * w) / 2.0;
        if peak2 <= v * v {
            (2.0 * peak2.sqrt() - u - w) / a
        } else {
            let ramps = (2.0 * v * v - u * u - w * w) / (2.0 * a);
            (2.0 * v - u - w) / a + (len - ramps) / v
        }
    }

    /// Seconds to run along `pieces`, from rest to rest. `junctions` is
    /// room for the speeds at their ends.
    fn move_s(&self, pieces: &[Piece], junctions: &mut Vec<f64>) -> f64 {
        if pieces.is_empty() {
            return 0.0;
        }
        let v = junctions;
        v.clear();
        v.push(0.0);
        v.extend(pieces.windows(2).map(|w| self.junction(w[0].dir, w[1].dir)));
        v.push(0.0);
        let reach = |from: f64, len: f64| (from * from + 2.0 * self.a * len).sqrt();
        for (i, p) in pieces.iter().enumerate().rev() {
            v[i] = v[i].min(reach(v[i + 1], p.len));
        }
        for (i, p) in pieces.iter().enumerate() {
            v[i + 1] = v[i + 1].min(reach(v[i], p.len));
        }
        pieces
            .iter()
            .zip(v.windows(2))
            .map(|(p, ends)| self.piece_s(p.len, ends[0], ends[1]))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::path_length;
    use crate::scene::{Color, Group, Layer, Pen, Style};
    use crate::units::{Margins, Orientation, Page, PaperName};
    use kurbo::{Affine, Line, Shape};
    use proptest::prelude::*;

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
        let run = walk([&p], &Speeds::DEFAULT);
        assert!((run.pen_up_mm - 8.0).abs() < 1e-12, "{run:?}");
        assert_eq!(run.pen_lifts, 3);
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
        // With acceleration, every move here is long enough to reach full
        // speed: each costs v/a more (10/200 drawing, 20/400 travelling).
        assert!(
            (l2.plot_time_accel_s - (l2.plot_time_s + 0.05 + 0.05)).abs() < 1e-9,
            "{l2:?}"
        );
        assert!(l1.plot_time_accel_s > l1.plot_time_s);
        assert!((s.plot_time_accel_s - (l1.plot_time_accel_s + l2.plot_time_accel_s)).abs() < 1e-9);

        let json = serde_json::to_value(&s).unwrap();
        for key in [
            "paths",
            "pen_down_mm",
            "pen_up_mm",
            "plot_time_s",
            "plot_time_accel_s",
        ] {
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
            (
                s.pen_down_mm,
                s.pen_up_mm,
                s.plot_time_s,
                s.plot_time_accel_s
            ),
            (
                p.pen_down_mm,
                p.pen_up_mm,
                p.plot_time_s,
                p.plot_time_accel_s
            )
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
            (
                s.paths,
                s.pen_down_mm,
                s.pen_up_mm,
                s.plot_time_s,
                s.plot_time_accel_s
            ),
            (0, 0.0, 0.0, 0.0, 0.0)
        );
        assert!(s.layers.is_empty());
    }

    /// A polyline through `points`.
    fn polyline(points: &[(f64, f64)]) -> BezPath {
        let mut path = BezPath::new();
        path.move_to(points[0]);
        for &p in &points[1..] {
            path.line_to(p);
        }
        path
    }

    /// The default speeds without lift time: what a move from the origin
    /// costs with acceleration is then the move alone.
    const NO_LIFT: Speeds = Speeds::DEFAULT.with_pen_lift_s(0.0);

    /// Seconds with acceleration to draw `paths` from the origin.
    fn accel_s(paths: &[BezPath], speeds: &Speeds) -> f64 {
        walk(paths, speeds).time_accel_s
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-9 * (1.0 + b.abs())
    }

    #[test]
    fn a_long_stroke_is_a_trapezoid_and_a_short_one_a_triangle() {
        // v = 25 mm/s, a = 200 mm/s²: full speed after v²/(2a) = 1.5625 mm.
        let t = accel_s(&[polyline(&[(0.0, 0.0), (100.0, 0.0)])], &NO_LIFT);
        assert!(close(t, 100.0 / 25.0 + 25.0 / 200.0), "{t}");
        // Points on the way that do not turn slow nothing down.
        let steps: Vec<(f64, f64)> = (0..=10).map(|k| (10.0 * f64::from(k), 0.0)).collect();
        let stepped = accel_s(&[polyline(&steps)], &NO_LIFT);
        assert!(close(stepped, t), "{stepped} vs {t}");
        // Nor do points closer to the ends than the pen needs to get up
        // to speed or to stop.
        let fake = [(0.0, 0.0), (0.5, 0.0), (99.5, 0.0), (100.0, 0.0)];
        let fake = accel_s(&[polyline(&fake)], &NO_LIFT);
        assert!(close(fake, t), "{fake} vs {t}");
        // Shorter than v²/a: speed up half way, slow down the other half.
        let t = accel_s(&[polyline(&[(0.0, 0.0), (2.0, 0.0)])], &NO_LIFT);
        assert!(close(t, 2.0 * (2.0_f64 / 200.0).sqrt()), "{t}");
        // At v²/a exactly, both are 2v/a.
        let t = accel_s(&[polyline(&[(0.0, 0.0), (3.125, 0.0)])], &NO_LIFT);
        assert!(close(t, 0.25), "{t}");
    }

    #[test]
    fn travel_between_strokes_is_included() {
        let a = polyline(&[(0.0, 0.0), (10.0, 0.0)]);
        let far = polyline(&[(110.0, 0.0), (120.0, 0.0)]);
        let near = polyline(&[(12.0, 0.0), (22.0, 0.0)]);
        // Each 10 mm stroke: 10/25 + 25/200 s; each lift 0.15 s.
        let strokes = 2.0 * (10.0 / 25.0 + 25.0 / 200.0) + 2.0 * 0.15;
        // 100 mm up at 75 mm/s, 400 mm/s²: past v²/a = 14.06 mm.
        let t = accel_s(&[a.clone(), far], &Speeds::DEFAULT);
        assert!(close(t, strokes + 100.0 / 75.0 + 75.0 / 400.0), "{t}");
        // 2 mm up: a triangle.
        let t = accel_s(&[a, near], &Speeds::DEFAULT);
        assert!(close(t, strokes + 2.0 * (2.0_f64 / 400.0).sqrt()), "{t}");
    }

    #[test]
    fn a_right_angle_costs_more_than_going_straight_on() {
        let straight = accel_s(
            &[polyline(&[(0.0, 0.0), (50.0, 0.0), (100.0, 0.0)])],
            &NO_LIFT,
        );
        let turn = |deg: f64| {
            let (sin, cos) = deg.to_radians().sin_cos();
            accel_s(
                &[polyline(&[
                    (0.0, 0.0),
                    (50.0, 0.0),
                    (50.0 + 50.0 * cos, 50.0 * sin),
                ])],
                &NO_LIFT,
            )
        };
        // Turning 30°, the arc 0.127 mm from the corner has a radius of
        // 3.6 mm: at 200 mm/s², taken at 27 mm/s, past full speed.
        assert!(close(turn(30.0), straight), "{}", turn(30.0));
        // Turning 60°: 12.8 mm/s.
        let gentle = turn(60.0);
        let square = [polyline(&[(0.0, 0.0), (50.0, 0.0), (50.0, 50.0)])];
        let right = accel_s(&square, &NO_LIFT);
        let back = accel_s(
            &[polyline(&[(0.0, 0.0), (50.0, 0.0), (0.0, 0.0)])],
            &NO_LIFT,
        );
        // Two 50 mm moves from rest to rest.
        let stopped = 2.0 * (50.0 / 25.0 + 25.0 / 200.0);
        assert!(close(straight, 100.0 / 25.0 + 25.0 / 200.0), "{straight}");
        assert!(straight < gentle, "{straight} {gentle}");
        assert!(gentle < right, "{gentle} {right}");
        assert!(right < stopped, "{right} {stopped}");
        // Turning back stops the pen, whatever the cornering.
        assert!(close(back, stopped), "{back} {stopped}");
        // Without cornering, every corner stops it.
        let sharp = accel_s(&square, &NO_LIFT.with_cornering_mm(0.0));
        assert!(close(sharp, stopped), "{sharp} {stopped}");
        // More cornering, faster corners.
        let wide = accel_s(&square, &NO_LIFT.with_cornering_mm(1.0));
        assert!(straight < wide && wide < right, "{wide} {right}");
    }

    #[test]
    fn a_finely_flattened_circle_is_not_slowed_like_sharp_corners() {
        // A 720-gon of radius 20 from the origin: 720 pieces of 0.17 mm,
        // turning half a degree at each junction.
        let n: u32 = 720;
        let ring: Vec<(f64, f64)> = (0..=n)
            .map(|k| {
                let t = std::f64::consts::TAU * f64::from(k) / f64::from(n);
                (20.0 * t.cos() - 20.0, 20.0 * t.sin())
            })
            .collect();
        let ring = polyline(&ring);
        let length = path_length(&ring);
        let full_speed = length / 25.0 + 25.0 / 200.0;
        let t = accel_s(std::slice::from_ref(&ring), &NO_LIFT);
        assert!(close(t, full_speed), "{t} vs {full_speed}");
        // The same circle as kurbo's four cubics, flattened by the model.
        let circle = kurbo::Circle::new((-20.0, 0.0), 20.0).to_path(1e-6);
        let length = path_length(&circle);
        let t = accel_s(&[circle], &NO_LIFT);
        assert!(close(t, length / 25.0 + 25.0 / 200.0), "{t}");
        // A staircase of as many pieces, as long, turning 90° at each.
        let step = ring.segments().next().unwrap().arclen(1e-9);
        let stairs: Vec<(f64, f64)> = (0..=n)
            .map(|k| {
                let (x, y) = (k.div_ceil(2), k / 2);
                (step * f64::from(x), step * f64::from(y))
            })
            .collect();
        let stairs = accel_s(&[polyline(&stairs)], &NO_LIFT);
        assert!(stairs > 2.0 * full_speed, "{stairs} vs {full_speed}");
    }

    #[test]
    fn curves_are_drawn_at_their_arc_length() {
        let mut wave = BezPath::new();
        wave.move_to((0.0, 0.0));
        wave.curve_to((20.0, -30.0), (40.0, 30.0), (60.0, 0.0));
        wave.quad_to((70.0, -10.0), (80.0, 0.0));
        let arc = path_length(&wave);
        let run = walk([&wave], &NO_LIFT);
        assert!(close(run.pen_down_mm, arc), "{run:?} vs {arc}");
        // Accelerating and cornering all but instantly: the pen draws the
        // arc length at full speed, not the shorter flattened polyline.
        let quick = NO_LIFT
            .with_pen_down_accel_mm_s2(1e9)
            .with_cornering_mm(1e3);
        let t = accel_s(std::slice::from_ref(&wave), &quick);
        assert!(t >= arc / 25.0 && t < arc / 25.0 * (1.0 + 1e-6), "{t}");
    }

    #[test]
    fn rounding_noise_is_no_corner() {
        // A 1e-7 mm jog sideways halfway: not two right angles.
        let jog = polyline(&[(0.0, 0.0), (10.0, 0.0), (10.0, 1e-7), (20.0, 1e-7)]);
        let t = accel_s(&[jog], &NO_LIFT);
        assert!(close(t, (20.0 + 1e-7) / 25.0 + 25.0 / 200.0), "{t}");
        // A dot takes its lift and its travel, nothing else.
        let dot = polyline(&[(30.0, 40.0), (30.0, 40.0)]);
        let t = accel_s(&[dot], &Speeds::DEFAULT);
        assert!(close(t, 50.0 / 75.0 + 75.0 / 400.0 + 0.15), "{t}");
    }

    #[test]
    fn speeds_are_validated_by_field() {
        assert!(Speeds::DEFAULT.validate().is_ok());
        assert!(NO_LIFT.with_cornering_mm(0.0).validate().is_ok());
        for (speeds, field) in [
            (Speeds::DEFAULT.with_pen_down_mm_s(0.0), "pen_down_mm_s"),
            (Speeds::DEFAULT.with_pen_up_mm_s(f64::NAN), "pen_up_mm_s"),
            (Speeds::DEFAULT.with_pen_lift_s(-1.0), "pen_lift_s"),
            (
                Speeds::DEFAULT.with_pen_down_accel_mm_s2(0.0),
                "pen_down_accel_mm_s2",
            ),
            (
                Speeds::DEFAULT.with_pen_up_accel_mm_s2(f64::INFINITY),
                "pen_up_accel_mm_s2",
            ),
            (Speeds::DEFAULT.with_cornering_mm(-0.1), "cornering_mm"),
        ] {
            match speeds.validate() {
                Err(Error::Invalid { field: f, .. }) => assert_eq!(f, field),
                other => panic!("{field}: {other:?}"),
            }
        }
        // Read from JSON, what is not said keeps its default.
        let s: Speeds = serde_json::from_str(r#"{"cornering_mm": 0.5}"#).unwrap();
        assert_eq!(s, Speeds::DEFAULT.with_cornering_mm(0.5));
    }

    fn arb_polylines() -> impl Strategy<Value = Vec<BezPath>> {
        let point = (0.0..200.0_f64, 0.0..200.0_f64);
        let line = prop::collection::vec(point, 2..30);
        prop::collection::vec(line, 1..6)
            .prop_map(|lines| lines.iter().map(|l| polyline(l)).collect())
    }

    fn arb_speeds() -> impl Strategy<Value = Speeds> {
        (
            1.0..100.0_f64,
            1.0..300.0_f64,
            0.0..1.0_f64,
            10.0..2000.0_f64,
            10.0..4000.0_f64,
            0.0..1.0_f64,
        )
            .prop_map(|(down, up, lift, a_down, a_up, cornering)| {
                Speeds::DEFAULT
                    .with_pen_down_mm_s(down)
                    .with_pen_up_mm_s(up)
                    .with_pen_lift_s(lift)
                    .with_pen_down_accel_mm_s2(a_down)
                    .with_pen_up_accel_mm_s2(a_up)
                    .with_cornering_mm(cornering)
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn acceleration_never_makes_a_plot_faster(
            paths in arb_polylines(),
            speeds in arb_speeds(),
            f in 0.01..0.99_f64,
        ) {
            let run = walk(&paths, &speeds);
            let constant = speeds.time(run.pen_down_mm, run.pen_up_mm, run.pen_lifts);
            prop_assert!(run.time_accel_s.is_finite());
            prop_assert!(
                run.time_accel_s >= constant * (1.0 - 1e-12),
                "{} < {constant}", run.time_accel_s
            );
            // More acceleration or wider corners never slow the plot down.
            let t = run.time_accel_s * (1.0 + 1e-12);
            let quicker = speeds
                .with_pen_down_accel_mm_s2(2.0 * speeds.pen_down_accel_mm_s2)
                .with_pen_up_accel_mm_s2(2.0 * speeds.pen_up_accel_mm_s2);
            prop_assert!(accel_s(&paths, &quicker) <= t);
            let wider = speeds.with_cornering_mm(speeds.cornering_mm + 0.5);
            prop_assert!(accel_s(&paths, &wider) <= t);
            // All but instant acceleration: the two figures meet.
            let instant = speeds
                .with_pen_down_accel_mm_s2(1e12)
                .with_pen_up_accel_mm_s2(1e12);
            let t = accel_s(&paths, &instant);
            prop_assert!(t <= constant * (1.0 + 1e-4), "{t} vs {constant}");
            // A point on a piece, however near its ends, changes nothing.
            let split: Vec<BezPath> = paths
                .iter()
                .map(|p| {
                    let mut out = BezPath::new();
                    for (k, seg) in p.segments().enumerate() {
                        if k == 0 {
                            out.move_to(seg.start());
                        }
                        out.line_to(seg.eval(f));
                        out.line_to(seg.end());
                    }
                    out
                })
                .collect();
            let t = accel_s(&split, &speeds);
            prop_assert!(close(t, run.time_accel_s), "{t} vs {}", run.time_accel_s);
        }
    }
}
