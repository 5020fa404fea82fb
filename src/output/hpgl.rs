//! HPGL for pen plotters and cutters: `PU`/`PD` moves in integer plotter
//! units, one `SP` pen selection per pen.
//!
//! [`to_hpgl`] writes the scene as it is, in the same order as the SVG and
//! G-code writers: pens in ascending number, within a pen its layers back to
//! front, within a layer the paths in scene order, each subpath one pen-down
//! stroke. It never reorders or merges strokes (the plot pipeline does that
//! before writing). Curves are flattened to polylines within
//! [`HpglOptions::tolerance`]. Layers that are not plotted (AxiDraw's `%`
//! documentation layers,
//! [`Layer::is_plotted`](crate::scene::Layer::is_plotted)) are left out, and
//! a pen that draws only such layers is never selected.
//!
//! Shape of the output, one instruction per line:
//!
//! ```text
//! IN;
//! PA;                       absolute coordinates
//! VS20;                     only with a velocity, cm/s
//! SP1;                      pen 1
//! PU400,2800;               travel to a stroke's start
//! PD1200,2800,1200,2000,…;  draw, at most 32 points per PD
//! …
//! PU;                       the pen up before another is chosen
//! SP2;
//! …
//! PU;
//! SP0;                      put the pen away
//! ```
//!
//! # Coordinates
//!
//! Plotter units are [`HpglOptions::units_per_mm`] per millimetre (40, i.e.
//! 0.025 mm, the HP-GL standard), rounded to integers, from the bottom-left
//! corner of the sheet with Y up: HPGL's Y runs the other way from the
//! page's, so [`HpglOptions::flip_y`] (on by default) writes
//! `Y = (page height − y) · units`. Turning it off keeps page y, for devices
//! whose Y points down. [`HpglOptions::mirror_x`] and
//! [`HpglOptions::mirror_y`] mirror the drawing on the sheet, for cutting
//! from the back of the material: `X = (page width − x) · units`, and
//! mirror_y flips Y once more. Consecutive points that round to the same unit
//! are written once. Nothing is clipped: a scene inside its page stays
//! inside, and in cutter mode the overcut and the knife offset may reach a
//! few tenths of a millimetre past a shape.
//!
//! # Device range
//!
//! A plotter takes coordinates only within a range, and what it does with
//! others differs (HP's own discard the instruction, others clamp, wrap
//! around or crash the carriage), so nothing outside
//! [`HpglOptions::device_range`] is written: [`to_hpgl`] fails with
//! [`Error::DeviceRange`], which names the path and the point in
//! millimetres and plotter units, and writes nothing. The default,
//! [`HPGL_RANGE`], is HP-GL's: 16-bit coordinates, −32768…32767 units, the
//! range the HP 7470A and 7475A accept and the one a cutter that emulates
//! them can be relied on for. At 40 units per mm that is ±819 mm from the
//! origin, enough for every named paper size up to A2 (594 mm). Devices
//! that speak HP-GL/2 accept integers within ±2³⁰ ([`HPGL2_RANGE`]); a
//! larger sheet or a roll cutter needs that, or the device's own limit,
//! through [`HpglOptions::with_device_range`].
//!
//! # Cutter mode
//!
//! With [`HpglOptions::cutter`] set, every stroke goes through two steps
//! (after the coordinate mapping, so they are the same for mirrored output):
//!
//! 1. **Closing and overcut.** A closed outline (a subpath that ends with a
//!    close, or on its own start point) ends exactly on its start; it then
//!    continues along its own first segments for
//!    [`CutterOptions::overcut_mm`] (at most once around), so the cut
//!    overlaps where it began and the shape drops out of the sheet. Open
//!    strokes are cut as they are.
//! 2. **Drag-knife offset.** A drag knife's tip trails the axis of its
//!    holder by [`CutterOptions::knife_offset_mm`] `d`, and the machine
//!    moves the axis. To make the tip follow a polyline, the axis is kept
//!    `d` ahead of the tip along the direction of travel `u`: each segment
//!    from `A` to `B` becomes `A + d·u → B + d·u` (parallel, same length,
//!    its end pushed past the corner by `d`). At a corner `B` where the
//!    direction turns from `u` to `v` by more than
//!    [`CutterOptions::swivel_threshold_deg`], the axis then swivels on a
//!    circle of radius `d` around `B` from `B + d·u` to `B + d·v`, which
//!    turns the blade in place while its tip rests at `B`; the circle is
//!    followed in steps of at most the threshold angle (fewer degrees when
//!    needed to stay within the tolerance). Gentler turns, such as the
//!    vertices of a flattened curve, are passed once at `B + d·w`, with `w`
//!    the mean of `u` and `v`: the blade follows by itself, and a smooth
//!    curve is simply shifted forward along its tangent. A closed outline
//!    starts with the corner from its last direction to its first, so the
//!    blade is aligned before the first side; an open stroke starts at
//!    `A + d·u`.

use kurbo::{Point, Vec2};
use serde::{Deserialize, Serialize};

use super::runs::{self, RunOptions};
use super::strokes::{pen_blocks, positive, Stroke, ToMachine, MIN_TOLERANCE};
use crate::error::{Error, Result};
use crate::scene::Scene;

/// HP-GL's coordinate range in plotter units (16-bit integers, as the HP
/// 7470A and 7475A take them): the default device range.
pub const HPGL_RANGE: [i32; 2] = [-32_768, 32_767];

/// HP-GL/2's integer range in plotter units, −2³⁰…2³⁰ − 1: the widest
/// device range allowed.
pub const HPGL2_RANGE: [i32; 2] = [-(1 << 30), (1 << 30) - 1];

/// Largest number of points in one `PD` instruction; longer strokes are
/// split into several `PD`s (older plotters have small instruction buffers).
pub const MAX_POINTS_PER_PD: usize = 32;

/// Drag-knife cutting options (see the module documentation).
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CutterOptions {
    /// How far a closed outline is cut again past its start, in mm.
    /// Default 1 mm.
    pub overcut_mm: f64,
    /// Distance from the holder axis to the blade tip, in mm; 0 turns the
    /// compensation off. Default 0.25 mm (a common 45° blade).
    pub knife_offset_mm: f64,
    /// Direction changes up to this angle, in degrees, are not swivelled
    /// explicitly. Default 30°.
    pub swivel_threshold_deg: f64,
}

impl CutterOptions {
    /// 1 mm overcut, 0.25 mm knife offset, swivel above 30°.
    pub const DEFAULT: CutterOptions = CutterOptions {
        overcut_mm: 1.0,
        knife_offset_mm: 0.25,
        swivel_threshold_deg: 30.0,
    };

    /// These options with an overcut of `mm`.
    pub const fn with_overcut_mm(mut self, mm: f64) -> CutterOptions {
        self.overcut_mm = mm;
        self
    }

    /// These options with a knife offset of `mm`.
    pub const fn with_knife_offset_mm(mut self, mm: f64) -> CutterOptions {
        self.knife_offset_mm = mm;
        self
    }

    /// These options with another swivel threshold, in degrees.
    pub const fn with_swivel_threshold_deg(mut self, degrees: f64) -> CutterOptions {
        self.swivel_threshold_deg = degrees;
        self
    }
}

impl Default for CutterOptions {
    fn default() -> CutterOptions {
        CutterOptions::DEFAULT
    }
}

/// Options of [`to_hpgl`].
///
/// Check them with [`HpglOptions::validate`] where they enter the program.
/// [`to_hpgl`] itself fails only for a point outside the device range.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HpglOptions {
    /// Flattening tolerance in mm. Default 0.02 mm (below one plotter unit).
    pub tolerance: f64,
    /// Plotter units per millimetre. Default 40.
    pub units_per_mm: f64,
    /// Write Y up from the bottom edge (HPGL's convention). Default on.
    pub flip_y: bool,
    /// Mirror left to right. Default off.
    pub mirror_x: bool,
    /// Mirror top to bottom. Default off.
    pub mirror_y: bool,
    /// Pen or knife speed in cm/s (`VS`); `None` keeps the device's.
    /// Default `None`.
    pub velocity_cm_s: Option<f64>,
    /// Drag-knife cutting; `None` plots. Default `None`.
    pub cutter: Option<CutterOptions>,
    /// The smallest and largest coordinate the device accepts, in plotter
    /// units, for X and Y alike (see "Device range" in the module
    /// documentation). Default [`HPGL_RANGE`].
    pub device_range: [i32; 2],
    /// The `VS` of AxiDraw's `+S100`, cm/s: a pen named `+S40 …` is
    /// selected with `VS` at 40 % of it. Default 38.1 cm/s (the HP 7475A's
    /// fastest).
    pub velocity_max_cm_s: f64,
    /// Where the pen goes after the last stroke, in device millimetres
    /// (after mirroring and the Y flip, like every written point), before
    /// it is put away; `None` stays. Default `[0, 0]`, the device's origin.
    pub park: Option<[f64; 2]>,
    /// Refills and resuming ([`RunOptions`]); the refill place is in
    /// device millimetres. Default neither.
    pub runs: RunOptions,
}

impl HpglOptions {
    /// Plotting: 40 units per mm, Y up, no mirror, no velocity, no cutter,
    /// HP-GL's device range.
    pub const DEFAULT: HpglOptions = HpglOptions {
        tolerance: 0.02,
        units_per_mm: 40.0,
        flip_y: true,
        mirror_x: false,
        mirror_y: false,
        velocity_cm_s: None,
        cutter: None,
        device_range: HPGL_RANGE,
        velocity_max_cm_s: 38.1,
        park: Some([0.0, 0.0]),
        runs: RunOptions::NONE,
    };

    /// [`HpglOptions::DEFAULT`] with [`CutterOptions::DEFAULT`].
    pub const CUTTER: HpglOptions = HpglOptions::DEFAULT.with_cutter(Some(CutterOptions::DEFAULT));

    /// These options with flattening tolerance `tolerance` mm.
    pub const fn with_tolerance(mut self, tolerance: f64) -> HpglOptions {
        self.tolerance = tolerance;
        self
    }

    /// These options with `units` plotter units per mm.
    pub const fn with_units_per_mm(mut self, units: f64) -> HpglOptions {
        self.units_per_mm = units;
        self
    }

    /// These options with Y flipped (HPGL convention) or not.
    pub const fn with_flip_y(mut self, flip_y: bool) -> HpglOptions {
        self.flip_y = flip_y;
        self
    }

    /// These options mirrored left to right, top to bottom, or neither.
    pub const fn with_mirror(mut self, mirror_x: bool, mirror_y: bool) -> HpglOptions {
        self.mirror_x = mirror_x;
        self.mirror_y = mirror_y;
        self
    }

    /// These options with a `VS` velocity in cm/s (`None`: none).
    pub const fn with_velocity_cm_s(mut self, velocity: Option<f64>) -> HpglOptions {
        self.velocity_cm_s = velocity;
        self
    }

    /// These options in cutter mode (`Some`) or plotter mode (`None`).
    pub const fn with_cutter(mut self, cutter: Option<CutterOptions>) -> HpglOptions {
        self.cutter = cutter;
        self
    }

    /// These options with a device range of `min`…`max` plotter units.
    pub const fn with_device_range(mut self, min: i32, max: i32) -> HpglOptions {
        self.device_range = [min, max];
        self
    }

    /// These options with `cm_s` as the velocity of `+S100`.
    pub const fn with_velocity_max_cm_s(mut self, cm_s: f64) -> HpglOptions {
        self.velocity_max_cm_s = cm_s;
        self
    }

    /// These options parking at device `(x, y)` mm (`None`: not at all).
    pub const fn with_park(mut self, park: Option<[f64; 2]>) -> HpglOptions {
        self.park = park;
        self
    }

    /// These options with refills and resuming.
    pub const fn with_runs(mut self, runs: RunOptions) -> HpglOptions {
        self.runs = runs;
        self
    }

    /// Checks the options; field names in errors are prefixed `hpgl.`.
    pub fn validate(&self) -> Result<()> {
        positive("hpgl.tolerance", self.tolerance)?;
        positive("hpgl.units_per_mm", self.units_per_mm)?;
        let [min, max] = self.device_range;
        let [lowest, highest] = HPGL2_RANGE;
        if !(lowest <= min && min < max && max <= highest) {
            return Err(Error::invalid(
                "hpgl.device_range",
                format!(
                    "must be [min, max] with min < max, within HP-GL/2's \
                     {lowest}…{highest} units; got [{min}, {max}]"
                ),
            ));
        }
        if let Some(v) = self.velocity_cm_s {
            positive("hpgl.velocity_cm_s", v)?;
        }
        positive("hpgl.velocity_max_cm_s", self.velocity_max_cm_s)?;
        if let Some([x, y]) = self.park {
            if !(x.is_finite() && y.is_finite()) {
                return Err(Error::invalid("hpgl.park", "must be finite"));
            }
        }
        self.runs.validate("hpgl")?;
        if let Some(c) = self.cutter {
            for (field, v) in [
                ("hpgl.cutter.overcut_mm", c.overcut_mm),
                ("hpgl.cutter.knife_offset_mm", c.knife_offset_mm),
            ] {
                if !(v.is_finite() && v >= 0.0) {
                    return Err(Error::invalid(
                        field,
                        format!("must be 0 or more mm, got {v}"),
                    ));
                }
            }
            let t = c.swivel_threshold_deg;
            if !(t.is_finite() && t > 0.0 && t <= 180.0) {
                return Err(Error::invalid(
                    "hpgl.cutter.swivel_threshold_deg",
                    format!("must be more than 0 and at most 180 degrees, got {t}"),
                ));
            }
        }
        Ok(())
    }
}

impl Default for HpglOptions {
    fn default() -> HpglOptions {
        HpglOptions::DEFAULT
    }
}

/// What the HPGL writer cannot do of what the scene's pens ask (AxiDraw's
/// `+H` pen height and `+D` delay: HP-GL has no instruction for either),
/// one line each, for the caller to show.
pub fn unsupported(scene: &Scene, options: &HpglOptions) -> Vec<String> {
    let mut out = Vec::new();
    for block in pen_blocks(scene, options.tolerance) {
        let codes = block.codes;
        if let Some(h) = codes.height {
            out.push(format!(
                "pen {} asks for pen height +H{h}: HPGL sets no pen height; set it on the device",
                block.number
            ));
        }
        if let Some(d) = codes.delay_ms {
            out.push(format!(
                "pen {} asks for a delay +D{d}: HPGL has no delay; not written",
                block.number
            ));
        }
    }
    out
}

/// Writes `scene` as HPGL (see the module documentation).
///
/// # Errors
/// [`Error::DeviceRange`] for the first point outside
/// [`HpglOptions::device_range`].
pub fn to_hpgl(scene: &Scene, options: &HpglOptions) -> Result<String> {
    let mut out = String::from("IN;\nPA;\n");
    if let Some(v) = options.velocity_cm_s {
        velocity(&mut out, v);
    }
    let to_machine = ToMachine {
        page: (scene.page.width, scene.page.height),
        mirror_x: options.mirror_x,
        from_bottom: options.flip_y != options.mirror_y,
        negate_y: false,
    };
    let mut blocks = pen_blocks(scene, options.tolerance);
    runs::apply(&mut blocks, &options.runs);
    for (k, block) in blocks.iter().enumerate() {
        // The pen comes up before it is put away: a pen selected while
        // the last one is down dots the end of its line (HP plotters;
        // vpype and Inkscape write the same `PU;`).
        if block.codes.pause {
            pause(&mut out, &format!("pause before pen {}", block.number));
        } else if k > 0 {
            out.push_str("PU;\n");
        }
        out.push_str("SP");
        out.push_str(&block.number.to_string());
        out.push_str(";\n");
        if let Some(percent) = block.codes.speed {
            velocity(
                &mut out,
                options.velocity_max_cm_s * f64::from(percent) / 100.0,
            );
        } else if k > 0 && blocks[k - 1].codes.speed.is_some() {
            // Back to the plot's own speed after a pen of its own.
            match options.velocity_cm_s {
                Some(v) => velocity(&mut out, v),
                None => out.push_str("VS;\n"),
            }
        }
        for path in &block.paths {
            for stroke in &path.strokes {
                if stroke.refill_before {
                    match options.runs.refill_at {
                        Some([x, y]) => {
                            let dip = Point::new(x, y);
                            write_stroke(&mut out, &[dip], options, "refill")?;
                        }
                        None => pause(&mut out, &format!("refill pen {}", block.number)),
                    }
                }
                let machine = to_machine.stroke(stroke);
                let points = match &options.cutter {
                    Some(c) => cut(&machine, c, options.tolerance),
                    None => machine.points,
                };
                write_stroke(&mut out, &points, options, path.id)?;
            }
        }
    }
    // The pen up (and parked), then put away.
    match options.park {
        Some([x, y]) => {
            let (x, y) = units(Point::new(x, y), options, "park")?;
            out.push_str(&format!("PU{x},{y};\n"));
        }
        None => out.push_str("PU;\n"),
    }
    out.push_str("SP0;\n");
    Ok(out)
}

/// `VS` with a velocity in cm/s; `VS;` alone restores the device's.
fn velocity(out: &mut String, cm_s: f64) {
    out.push_str("VS");
    super::number::write_number(out, cm_s, 2);
    out.push_str(";\n");
}

/// The pen up, and a comment (HP-GL/2's `CO`) saying why the operator
/// should stop the plot here: HP-GL has no pause of its own.
fn pause(out: &mut String, why: &str) {
    out.push_str("PU;\nCO\"");
    out.push_str(&why.replace(|c: char| c == '"' || c.is_control(), " "));
    out.push_str("\";\n");
}

/// Device point `p` (mm) in plotter units; an error naming `what` when it
/// is outside the device range.
fn units(p: Point, o: &HpglOptions, what: &str) -> Result<(i64, i64)> {
    let [min, max] = o.device_range;
    let in_range = |v: f64| f64::from(min) <= v && v <= f64::from(max);
    let (x, y) = (
        (p.x * o.units_per_mm).round(),
        (p.y * o.units_per_mm).round(),
    );
    if !(in_range(x) && in_range(y)) {
        return Err(Error::DeviceRange {
            path: what.to_string(),
            x_mm: p.x,
            y_mm: p.y,
            x_units: x,
            y_units: y,
            min_units: min,
            max_units: max,
            min_mm: f64::from(min) / o.units_per_mm,
            max_mm: f64::from(max) / o.units_per_mm,
        });
    }
    // Within the range, so integers that `as` keeps exactly.
    Ok((x as i64, y as i64))
}

/// `PU` to the first point, then `PD` through the rest, in rounded units;
/// an error for a point outside the device range (`path` names the scene
/// path the stroke comes from).
fn write_stroke(out: &mut String, points: &[Point], o: &HpglOptions, path: &str) -> Result<()> {
    let mut units_of: Vec<(i64, i64)> = Vec::with_capacity(points.len());
    for &p in points {
        let u = units(p, o, path)?;
        if units_of.last() != Some(&u) {
            units_of.push(u);
        }
    }
    let units = units_of;
    let Some(&(x0, y0)) = units.first() else {
        return Ok(());
    };
    out.push_str(&format!("PU{x0},{y0};\n"));
    // A one-point stroke is a dot: lower the pen where it is.
    let rest = if units.len() == 1 {
        &units[..]
    } else {
        &units[1..]
    };
    for chunk in rest.chunks(MAX_POINTS_PER_PD) {
        out.push_str("PD");
        for (i, (x, y)) in chunk.iter().enumerate() {
            if i > 0 {
                out.push(',');
            }
            out.push_str(&format!("{x},{y}"));
        }
        out.push_str(";\n");
    }
    Ok(())
}

/// The path of the knife holder's axis that cuts `stroke` (machine mm):
/// closing and overcut, then the drag-knife offset.
fn cut(stroke: &Stroke, c: &CutterOptions, tolerance: f64) -> Vec<Point> {
    let tip = dedup(&stroke.points);
    if tip.len() < 2 {
        return tip;
    }
    let closed = stroke.closed && tip.len() >= 3;
    let lead_in = if closed {
        // Flattening closed it exactly; the last segment arrives at the start.
        (tip[tip.len() - 1] - tip[tip.len() - 2]).normalize()
    } else {
        Vec2::ZERO
    };
    let tip = if closed {
        overcut(&tip, c.overcut_mm)
    } else {
        tip
    };
    let d = c.knife_offset_mm;
    if d.is_nan() || d <= 0.0 {
        return tip;
    }
    let threshold = c.swivel_threshold_deg.to_radians();
    knife_offset(&tip, closed.then_some(lead_in), d, threshold, tolerance)
}

/// Segments shorter than this (mm) have no reliable direction.
const MIN_SEGMENT: f64 = 1e-9;

fn dedup(points: &[Point]) -> Vec<Point> {
    let mut v: Vec<Point> = Vec::with_capacity(points.len());
    for &p in points {
        if v.last().is_none_or(|q| q.distance(p) > MIN_SEGMENT) {
            v.push(p);
        }
    }
    v
}

/// `closed` (first point = last point) continued along its own segments
/// for `length` mm, at most once around.
fn overcut(closed: &[Point], length: f64) -> Vec<Point> {
    let mut out = closed.to_vec();
    let mut remaining = length;
    for pair in closed.windows(2) {
        if remaining.is_nan() || remaining <= MIN_SEGMENT {
            break;
        }
        let (a, b) = (pair[0], pair[1]);
        let len = a.distance(b);
        if remaining >= len {
            out.push(b);
            remaining -= len;
        } else {
            out.push(a.lerp(b, remaining / len));
            remaining = 0.0;
        }
    }
    out
}

/// The holder-axis path for a blade tip that must follow `tip` (distinct
/// consecutive points, at least two): see "Drag-knife offset" in the module
/// documentation. `lead_in` is the blade direction to swivel from at the
/// start (closed outlines).
fn knife_offset(
    tip: &[Point],
    lead_in: Option<Vec2>,
    d: f64,
    threshold: f64,
    tolerance: f64,
) -> Vec<Point> {
    // Largest swivel step whose chords stay within the tolerance of the
    // circle, and never more than the threshold.
    let tolerance = tolerance.max(MIN_TOLERANCE);
    let tolerance_step = if tolerance < d {
        2.0 * (1.0 - tolerance / d).acos()
    } else {
        std::f64::consts::PI
    };
    let step = threshold.min(tolerance_step);
    // The axis positions for a blade tip resting at `b` while the direction
    // of travel turns from `u` to `v`.
    let corner = |out: &mut Vec<Point>, b: Point, u: Vec2, v: Vec2| {
        let turn = u.cross(v).atan2(u.dot(v));
        if turn.abs() <= threshold {
            // Gentle turn (or none): pass once, along the mean tangent.
            out.push(b + d * (u + v).normalize());
            return;
        }
        // Swivel: from `b + d·u` around `b` to `b + d·v`.
        out.push(b + d * u);
        let n = (turn.abs() / step).ceil() as usize;
        for k in 1..=n {
            let (sin, cos) = (turn * k as f64 / n as f64).sin_cos();
            let r = Vec2::new(u.x * cos - u.y * sin, u.x * sin + u.y * cos);
            out.push(b + d * r);
        }
    };

    let dirs: Vec<Vec2> = tip.windows(2).map(|w| (w[1] - w[0]).normalize()).collect();
    let mut out = Vec::with_capacity(tip.len() + 8);
    match lead_in {
        Some(w) => corner(&mut out, tip[0], w, dirs[0]),
        None => out.push(tip[0] + d * dirs[0]),
    }
    for (i, &u) in dirs.iter().enumerate() {
        let b = tip[i + 1];
        match dirs.get(i + 1) {
            Some(&v) => corner(&mut out, b, u, v),
            None => out.push(b + d * u),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::strokes::tests::{two_pen_scene, with_unplotted_layers};

    /// A point in plotter units.
    type Unit = (i64, i64);

    /// The points of every `PD`, with the `PU` that starts each stroke:
    /// `(pu, pds)` per stroke.
    fn strokes(hpgl: &str) -> Vec<(Unit, Vec<Unit>)> {
        let pairs = |s: &str| -> Vec<Unit> {
            let n: Vec<i64> = s
                .split(',')
                .filter(|t| !t.is_empty())
                .map(|t| t.parse().unwrap())
                .collect();
            assert_eq!(n.len() % 2, 0, "{s}");
            n.chunks(2).map(|c| (c[0], c[1])).collect()
        };
        let mut out: Vec<(Unit, Vec<Unit>)> = Vec::new();
        for ins in hpgl.split(';').map(str::trim) {
            if let Some(rest) = ins.strip_prefix("PU") {
                if let Some(&p) = pairs(rest).first() {
                    out.push((p, Vec::new()));
                }
            } else if let Some(rest) = ins.strip_prefix("PD") {
                out.last_mut().unwrap().1.extend(pairs(rest));
            }
        }
        // The park is a move, not a stroke.
        out.retain(|(_, pd)| !pd.is_empty());
        out
    }

    fn square_only() -> Scene {
        let mut s = two_pen_scene();
        s.layers.retain(|l| l.id == "square-layer");
        s
    }

    fn dist(a: Unit, b: Unit) -> f64 {
        (((a.0 - b.0).pow(2) + (a.1 - b.1).pow(2)) as f64).sqrt()
    }

    #[test]
    fn snapshot_of_two_pen_scene() {
        insta::assert_snapshot!(to_hpgl(&two_pen_scene(), &HpglOptions::DEFAULT).unwrap());
    }

    #[test]
    fn snapshot_of_two_pen_scene_cut() {
        insta::assert_snapshot!(to_hpgl(
            &two_pen_scene(),
            &HpglOptions::CUTTER.with_velocity_cm_s(Some(10.0))
        )
        .unwrap());
    }

    #[test]
    fn frame_and_pens_in_order() {
        let h = to_hpgl(&two_pen_scene(), &HpglOptions::DEFAULT).unwrap();
        assert!(h.starts_with("IN;\nPA;\nSP1;\nPU"), "{h}");
        assert!(h.ends_with(";\nPU0,0;\nSP0;\n"), "{h}");
        let sp1 = h.find("SP1;").unwrap();
        let sp2 = h.find("SP2;").unwrap();
        assert!(sp1 < sp2);
        assert_eq!(h.matches("SP").count(), 3);
        // No pen is chosen or put away while one is down.
        let lines: Vec<&str> = h.lines().collect();
        for (i, line) in lines.iter().enumerate().skip(1) {
            if line.starts_with("SP") && !line.starts_with("SP1") {
                assert!(lines[i - 1].starts_with("PU"), "{h}");
                assert!(!lines[i - 1].contains(',') || *line == "SP0;", "{h}");
            }
        }
        // Pen 1: the back layer's curve, then the square; pen 2: the circle.
        assert_eq!(strokes(&h).len(), 3);
        let v = to_hpgl(
            &two_pen_scene(),
            &HpglOptions::DEFAULT.with_velocity_cm_s(Some(12.5)),
        )
        .unwrap();
        assert!(v.starts_with("IN;\nPA;\nVS12.5;\nSP1;"));
    }

    #[test]
    fn unplotted_layers_are_left_out() {
        let scene = with_unplotted_layers(two_pen_scene());
        for options in [HpglOptions::DEFAULT, HpglOptions::CUTTER] {
            let with = to_hpgl(&scene, &options).unwrap();
            assert_eq!(with, to_hpgl(&two_pen_scene(), &options).unwrap());
            assert!(!with.contains("SP3;"), "pen 3 draws only notes");
            // The frame's corners would be at 40 and 3960 units.
            for (pu, pds) in strokes(&with) {
                for (x, _) in std::iter::once(pu).chain(pds) {
                    assert!((200..=3800).contains(&x), "{x}");
                }
            }
        }
    }

    #[test]
    fn every_coordinate_is_on_the_page_in_plotter_units() {
        let (w, h) = (100 * 40, 80 * 40);
        for o in [
            HpglOptions::DEFAULT,
            HpglOptions::DEFAULT.with_mirror(true, false),
            HpglOptions::DEFAULT.with_mirror(true, true),
            HpglOptions::DEFAULT.with_flip_y(false),
            HpglOptions::CUTTER,
            HpglOptions::CUTTER.with_mirror(true, false),
        ] {
            let out = to_hpgl(&two_pen_scene(), &o).unwrap();
            let all = strokes(&out);
            assert_eq!(all.len(), 3);
            for (pu, pd) in all {
                assert!(!pd.is_empty());
                for (x, y) in std::iter::once(pu).chain(pd) {
                    assert!(
                        (0..=w).contains(&x) && (0..=h).contains(&y),
                        "{x},{y} {o:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn y_flip_and_mirrors() {
        // The square's first corner is page (10, 10), its second (30, 10).
        let first = |o: HpglOptions| {
            let s = strokes(&to_hpgl(&square_only(), &o).unwrap());
            (s[0].0, s[0].1[0])
        };
        let d = HpglOptions::DEFAULT;
        assert_eq!(first(d), ((400, 2800), (1200, 2800)));
        assert_eq!(first(d.with_flip_y(false)), ((400, 400), (1200, 400)));
        assert_eq!(
            first(d.with_mirror(true, false)),
            ((3600, 2800), (2800, 2800))
        );
        assert_eq!(first(d.with_mirror(false, true)), ((400, 400), (1200, 400)));
        assert_eq!(
            first(d.with_mirror(true, true).with_flip_y(false)),
            ((3600, 2800), (2800, 2800))
        );
        assert_eq!(
            first(d.with_units_per_mm(39.37)),
            ((394, 2756), (1181, 2756))
        );
    }

    #[test]
    fn long_strokes_are_split_into_pd_chunks() {
        let h = to_hpgl(
            &two_pen_scene(),
            &HpglOptions::DEFAULT.with_tolerance(0.001),
        )
        .unwrap();
        let circle = &strokes(&h)[2];
        assert!(circle.1.len() > MAX_POINTS_PER_PD * 2, "{}", circle.1.len());
        for line in h.lines().filter(|l| l.starts_with("PD")) {
            assert!(line.matches(',').count() < MAX_POINTS_PER_PD * 2);
        }
        // Closed in plotter mode too.
        assert_eq!(circle.0, *circle.1.last().unwrap());
    }

    #[test]
    fn cutter_closes_outlines_and_overcuts_by_the_given_length() {
        let o =
            HpglOptions::CUTTER.with_cutter(Some(CutterOptions::DEFAULT.with_knife_offset_mm(0.0)));
        let s = strokes(&to_hpgl(&square_only(), &o).unwrap());
        assert_eq!(s.len(), 1);
        let (pu, pd) = &s[0];
        // Around the square, back to the start, then 1 mm = 40 units on.
        assert_eq!(
            pd[..],
            [
                (1200, 2800),
                (1200, 2000),
                (400, 2000),
                (400, 2800),
                (440, 2800)
            ]
        );
        assert_eq!(*pu, (400, 2800));

        // On a curve the overcut follows the outline for its length.
        for overcut in [0.5, 1.0, 3.0] {
            let mut circle = two_pen_scene();
            circle.layers.retain(|l| l.id == "circle-layer");
            let o = HpglOptions::CUTTER.with_cutter(Some(
                CutterOptions::DEFAULT
                    .with_knife_offset_mm(0.0)
                    .with_overcut_mm(overcut),
            ));
            let s = strokes(&to_hpgl(&circle, &o).unwrap());
            let (pu, pd) = &s[0];
            let back = pd
                .iter()
                .position(|p| p == pu)
                .expect("returns to the start");
            let mut len = 0.0;
            let mut prev = *pu;
            for &p in &pd[back + 1..] {
                len += dist(prev, p);
                prev = p;
            }
            // Rounding to units moves each point by at most half a unit·√2.
            assert!((len / 40.0 - overcut).abs() < 0.05, "{overcut}: {len}");
        }

        // Open strokes are neither closed nor overcut.
        let mut open = two_pen_scene();
        open.layers.retain(|l| l.id == "vine-layer");
        let o =
            HpglOptions::CUTTER.with_cutter(Some(CutterOptions::DEFAULT.with_knife_offset_mm(0.0)));
        assert_eq!(
            to_hpgl(&open, &o).unwrap(),
            to_hpgl(&open, &HpglOptions::DEFAULT).unwrap()
        );
    }

    #[test]
    fn overcut_is_at_most_once_around() {
        let sq = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(0.0, 0.0),
        ];
        assert_eq!(overcut(&sq, 100.0).len(), 7);
        assert_eq!(overcut(&sq, 0.0).len(), 4);
        assert_eq!(
            overcut(&sq, 1.5)[4..],
            [Point::new(1.0, 0.0), Point::new(1.0, 0.5)]
        );
    }

    #[test]
    fn knife_offset_swivels_at_corners_and_keeps_sides_straight() {
        let o = HpglOptions::CUTTER.with_cutter(Some(CutterOptions::DEFAULT.with_overcut_mm(0.0)));
        let s = strokes(&to_hpgl(&square_only(), &o).unwrap());
        let (pu, pd) = &s[0];
        let mut path = vec![*pu];
        path.extend(pd);
        let corners = [(400, 2800), (1200, 2800), (1200, 2000), (400, 2000)];
        // Every axis position is the knife offset (10 units) from a corner
        // of the square, or on a side.
        for &p in &path {
            let near_corner = corners.iter().any(|&c| (dist(p, c) - 10.0).abs() <= 0.8);
            assert!(near_corner, "{p:?}");
        }
        // The long moves are the four sides: same direction and length as
        // the square's, shifted forward by the offset.
        let sides: Vec<(Unit, Unit)> = path
            .windows(2)
            .map(|w| (w[0], w[1]))
            .filter(|(a, b)| dist(*a, *b) > 100.0)
            .collect();
        assert_eq!(
            sides,
            [
                ((410, 2800), (1210, 2800)),
                ((1200, 2790), (1200, 1990)),
                ((1190, 2000), (390, 2000)),
                ((400, 2010), (400, 2810)),
            ]
        );
        // Each 90° corner is swivelled in three 30° steps, and the start
        // too (the blade is turned from the last side to the first).
        assert_eq!(path.len(), 1 + 3 + 4 + 3 * 3);
        assert_eq!(path[0], (400, 2810));

        // A straight open line only moves forward by the offset.
        let tip = [
            Point::new(0.0, 0.0),
            Point::new(5.0, 0.0),
            Point::new(10.0, 0.0),
        ];
        let axis = knife_offset(&tip, None, 0.25, 30f64.to_radians(), 0.02);
        assert_eq!(
            axis,
            [
                Point::new(0.25, 0.0),
                Point::new(5.25, 0.0),
                Point::new(10.25, 0.0)
            ]
        );
    }

    #[test]
    fn gentle_turns_are_not_swivelled() {
        let tip = [
            Point::new(0.0, 0.0),
            Point::new(10.0, 0.0),
            Point::new(20.0, 1.0),
        ];
        let axis = knife_offset(&tip, None, 0.25, 30f64.to_radians(), 0.02);
        // Start, the corner once along the mean direction, end.
        assert_eq!(axis.len(), 3);
        let w = (Vec2::new(1.0, 0.0) + Vec2::new(10.0, 1.0).normalize()).normalize();
        assert!((axis[1] - (Point::new(10.0, 0.0) + 0.25 * w)).hypot() < 1e-12);
        let sharp = [
            Point::new(0.0, 0.0),
            Point::new(10.0, 0.0),
            Point::new(0.0, 1.0),
        ];
        let axis = knife_offset(&sharp, None, 0.25, 30f64.to_radians(), 0.02);
        // A near reversal (≈ 174°) needs six 30° steps: start, corner, six
        // swivel points, end.
        assert_eq!(axis.len(), 9);
        for p in &axis[1..axis.len() - 1] {
            assert!((p.distance(Point::new(10.0, 0.0)) - 0.25).abs() < 1e-12);
        }
    }

    #[test]
    fn validate_names_the_field() {
        assert!(HpglOptions::DEFAULT.validate().is_ok());
        assert!(HpglOptions::CUTTER.validate().is_ok());
        let e = HpglOptions::DEFAULT
            .with_units_per_mm(0.0)
            .validate()
            .unwrap_err();
        assert!(e.to_string().starts_with("hpgl.units_per_mm: "), "{e}");
        let e = HpglOptions::DEFAULT
            .with_cutter(Some(CutterOptions::DEFAULT.with_overcut_mm(-1.0)))
            .validate()
            .unwrap_err();
        assert!(e.to_string().starts_with("hpgl.cutter.overcut_mm: "), "{e}");
        let e = HpglOptions::CUTTER
            .with_cutter(Some(CutterOptions::DEFAULT.with_swivel_threshold_deg(0.0)))
            .validate()
            .unwrap_err();
        assert!(e.to_string().contains("swivel_threshold_deg"), "{e}");
    }

    #[test]
    fn options_deserialize_with_defaults() {
        let o: HpglOptions = toml::from_str("mirror_x = true\n[cutter]\novercut_mm = 2").unwrap();
        assert!(o.mirror_x && o.flip_y);
        assert_eq!(o.cutter, Some(CutterOptions::DEFAULT.with_overcut_mm(2.0)));
        assert!(toml::from_str::<HpglOptions>("mirror = true").is_err());
    }

    #[test]
    fn a_dot_lowers_the_pen_in_place() {
        let mut s = square_only();
        let mut dot = kurbo::BezPath::new();
        dot.move_to((1.0, 2.0));
        dot.line_to((1.0, 2.0));
        s.layers[0]
            .content
            .push_path("dot", dot, crate::scene::Style::default());
        for o in [HpglOptions::DEFAULT, HpglOptions::CUTTER] {
            let h = to_hpgl(&s, &o).unwrap();
            // Page (6, 7) after the 5 mm margin; y = 80 − 7 = 73 mm.
            assert!(h.contains("PU240,2920;\nPD240,2920;\n"), "{h}");
        }
    }

    #[test]
    fn points_outside_the_device_range_are_an_error() {
        // The square spans 400…1200 units: a range ending at 1000 cuts it.
        let o = HpglOptions::DEFAULT.with_device_range(0, 1000);
        let e = to_hpgl(&square_only(), &o).unwrap_err();
        let Error::DeviceRange {
            path,
            x_mm,
            y_mm,
            x_units,
            y_units,
            min_units,
            max_units,
            max_mm,
            ..
        } = &e
        else {
            panic!("{e:?}")
        };
        // Pages y 10 → 80 − 10 = 70 mm from the bottom, 2800 units.
        assert_eq!(path, "square");
        assert_eq!((*x_mm, *y_mm), (10.0, 70.0));
        assert_eq!((*x_units, *y_units), (400.0, 2800.0));
        assert_eq!((*min_units, *max_units, *max_mm), (0, 1000, 25.0));
        assert_eq!(
            e.to_string(),
            "hpgl: path square reaches (10.000, 70.000) mm on the device, \
             (400, 2800) plotter units: outside the device range 0…1000 units \
             (0.000…25.000 mm); shrink or move the drawing, or widen the range"
        );

        // HP-GL's range holds about ±819 mm at 40 units per mm.
        let mut far = square_only();
        far.page.width = 2000.0;
        far.layers[0].content.transform = kurbo::Affine::translate((900.0, 0.0));
        let e = to_hpgl(&far, &HpglOptions::DEFAULT).unwrap_err();
        assert!(e.to_string().contains("(36400, 2800) plotter units"), "{e}");
        // A wider range takes it, with the same bytes as before the check.
        let wide = HpglOptions::DEFAULT.with_device_range(HPGL2_RANGE[0], HPGL2_RANGE[1]);
        assert!(to_hpgl(&far, &wide).unwrap().contains("PU36400,2800;"));
        // Mirrored and cut, the point the device is sent to is checked.
        let cut = HpglOptions::CUTTER.with_mirror(true, false);
        assert!(to_hpgl(&far, &cut.with_device_range(0, 1_000_000)).is_ok());
        let e = to_hpgl(&square_only(), &cut.with_device_range(0, 3605)).unwrap_err();
        assert!(
            matches!(e, Error::DeviceRange { x_units, .. } if x_units > 3605.0),
            "{e}"
        );

        // Huge coordinates never wrap around into nonsense units.
        far.layers[0].content.transform = kurbo::Affine::translate((1e15, 0.0));
        let e = to_hpgl(&far, &wide).unwrap_err();
        assert!(
            matches!(e, Error::DeviceRange { x_units, .. } if x_units > 1e16),
            "{e}"
        );
    }

    #[test]
    fn device_range_is_validated() {
        assert_eq!(HpglOptions::DEFAULT.device_range, HPGL_RANGE);
        for [min, max] in [[0, 0], [10, -10], [HPGL2_RANGE[0] - 1, 0], [0, i32::MAX]] {
            let e = HpglOptions::DEFAULT
                .with_device_range(min, max)
                .validate()
                .unwrap_err();
            assert!(e.to_string().starts_with("hpgl.device_range: "), "{e}");
        }
        let o: HpglOptions = toml::from_str("device_range = [0, 100000]").unwrap();
        assert_eq!(o.device_range, [0, 100_000]);
        assert!(o.validate().is_ok());
    }

    #[test]
    fn empty_scene_is_a_valid_program() {
        let mut s = two_pen_scene();
        s.layers.clear();
        assert_eq!(
            to_hpgl(&s, &HpglOptions::DEFAULT).unwrap(),
            "IN;\nPA;\nPU0,0;\nSP0;\n"
        );
    }

    #[test]
    fn pens_take_their_speed_and_pause_from_their_names() {
        let mut scene = two_pen_scene();
        scene.pens[1].name = "!+S50+D200+H10 red".into();
        let h = to_hpgl(&scene, &HpglOptions::DEFAULT).unwrap();
        // Pen 2 at half the maximum velocity, after a pause comment, with
        // the pen up.
        assert!(
            h.contains(";\nPU;\nCO\"pause before pen 2\";\nSP2;\nVS19.05;\n"),
            "{h}"
        );
        assert_eq!(h.matches("CO\"").count(), 1);
        let w = unsupported(&scene, &HpglOptions::DEFAULT);
        assert_eq!(w.len(), 2, "+H and +D: {w:?}");
        // A pen of its own speed, then one without: back to the plot's.
        scene.pens.swap(0, 1);
        scene.pens[0].number = 1;
        scene.pens[1].number = 2;
        let h = to_hpgl(&scene, &HpglOptions::DEFAULT).unwrap();
        assert!(
            h.contains("SP1;\nVS19.05;\n") && h.contains("SP2;\nVS;\n"),
            "{h}"
        );
        let h = to_hpgl(&scene, &HpglOptions::DEFAULT.with_velocity_cm_s(Some(8.0))).unwrap();
        assert!(h.contains("SP2;\nVS8;\n"), "{h}");
    }

    #[test]
    fn refills_dip_or_pause_and_resuming_draws_the_rest() {
        let runs = RunOptions::default().with_refill_mm(Some(30.0));
        let paused = to_hpgl(&two_pen_scene(), &HpglOptions::DEFAULT.with_runs(runs)).unwrap();
        assert!(paused.contains("PU;\nCO\"refill pen 1\";\n"), "{paused}");
        let dipped = to_hpgl(
            &two_pen_scene(),
            &HpglOptions::DEFAULT.with_runs(runs.with_refill_at(Some([-5.0, 10.0]))),
        );
        // A dot at the ink well, 5 mm left of the sheet.
        let dipped = dipped.unwrap();
        assert!(dipped.contains("PU-200,400;\nPD-200,400;\n"), "{dipped}");
        assert!(!dipped.contains("CO\""));

        let whole = strokes(&to_hpgl(&two_pen_scene(), &HpglOptions::DEFAULT).unwrap());
        let rest = strokes(
            &to_hpgl(
                &two_pen_scene(),
                &HpglOptions::DEFAULT.with_runs(RunOptions::default().with_from_distance_mm(90.0)),
            )
            .unwrap(),
        );
        assert_eq!(rest.len(), 2);
        assert_eq!(rest[1], whole[2]);
        assert_eq!(rest[0].1.last(), whole[1].1.last());
    }
}
