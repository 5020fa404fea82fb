//! G-code for GRBL-style pen plotters: pen up/down by commands, straight
//! `G1` moves, millimetres, absolute coordinates.
//!
//! [`to_gcode`] writes the scene as it is: pens in ascending number, within
//! a pen its layers back to front (as in the SVG), within a layer the paths
//! in scene order, each subpath one pen-down stroke. It never reorders or
//! merges strokes; that is the plot pipeline's job, done before writing.
//! Curves are flattened to polylines within [`GcodeOptions::tolerance`].
//! Layers that are not plotted (AxiDraw's `%` documentation layers,
//! [`Layer::is_plotted`](crate::scene::Layer::is_plotted)) are left out,
//! and a pen that draws only such layers gets no tool change.
//!
//! Shape of the program (with the default options; `;` comments are written
//! only when [`GcodeOptions::comments`] is on):
//!
//! ```text
//! ; moyo G-code: 100 x 80 mm page, origin bottom-left, Y up
//! G21 ; millimetres
//! G90 ; absolute coordinates
//! {header lines}
//! M5                        pen up
//! G4 P0.15                  let the servo settle
//! ; pen 1 black
//! M0 ; load pen 1 black     tool change, only when the program uses 2+ pens
//! ; path square
//! G1 X10 Y70 F4000          travel with the pen up (G0 without a travel feed)
//! M3 S1000                  pen down
//! G4 P0.15
//! G1 X30 Y70 F1500          draw
//! G1 X30 Y50
//! M5                        pen up
//! G4 P0.15
//! …
//! ; end
//! G1 X0 Y0 F4000            park
//! {footer lines}            M2 by default
//! ```
//!
//! Numbers go through [`write_number`] at [`GcodeOptions::precision`]
//! decimals, so equal scenes give equal bytes. `F` is modal and written only
//! when the feed changes.
//!
//! # Machine coordinates
//!
//! Page coordinates have their origin at the top-left corner of the sheet
//! with y pointing down (the SVG convention). [`GcodeOptions::origin`] says
//! which sheet corner is the machine's zero, and [`GcodeOptions::flip_y`]
//! whether the machine's Y runs the other way than "away from that corner".
//! With page height `H`:
//!
//! | origin | flip_y | machine Y | typical machine |
//! |---|---|---|---|
//! | `BottomLeft` (default) | `false` | `H − y` | Y up, zero at the bottom-left (most GRBL XY plotters) |
//! | `BottomLeft` | `true` | `y − H` | Y down, zero at the bottom-left (negative Y) |
//! | `TopLeft` | `false` | `y` | Y down, zero at the top-left (page coordinates as they are) |
//! | `TopLeft` | `true` | `−y` | Y up, zero at the top-left (homes at the far corner, negative Y) |
//!
//! X is always the page x. [`GcodeOptions::park`] is given in machine
//! coordinates.
//!
//! # Pen commands
//!
//! The defaults suit GRBL builds that drive a pen servo from the spindle PWM
//! (`M3 S1000` lowers the pen, `M5` lifts it); other machines use e.g.
//! `M3 S90`/`M3 S30`, `M280 P0 S…` (Marlin servo) or a Z move (`G1 Z0 F500`
//! / `G0 Z5`). GRBL finishes the buffered motion before it changes the
//! spindle state, and the `G4 P…` dwell (in seconds, GRBL's unit) after every
//! pen command gives the servo time to arrive.

use kurbo::Point;
use serde::{Deserialize, Serialize};

use super::arcs::{self, Move};
use super::number::write_number;
use super::runs::{self, RunOptions};
use super::strokes::{pen_blocks, positive, PenBlock, Stroke, ToMachine};
use super::template;
use crate::error::{Error, Result};
use crate::scene::{LayerCodes, Scene};

pub use super::strokes::MIN_TOLERANCE;

/// Which corner of the sheet is the machine's X0 Y0 (see the module
/// documentation for the full mapping).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Origin {
    /// The top-left corner; machine Y = page y (negated with `flip_y`).
    TopLeft,
    /// The bottom-left corner; machine Y = page height − page y (negated
    /// with `flip_y`).
    #[default]
    BottomLeft,
}

/// Placeholders of [`GcodeOptions::header`] and [`GcodeOptions::footer`].
pub const PAGE_PLACEHOLDERS: &[&str] = &["page_width", "page_height"];

/// Placeholders of [`GcodeOptions::tool_change`],
/// [`GcodeOptions::pen_start`] and [`GcodeOptions::pen_end`]: the pen's
/// number and name, its layer (the label AxiDraw reads, number and codes
/// included: [`LayerCodes::label`](crate::scene::LayerCodes::label)), and
/// where the machine is (the end of the last move; 0, 0 before the first).
pub const PEN_PLACEHOLDERS: &[&str] = &["pen", "name", "layer", "x", "y"];

/// Placeholders of [`GcodeOptions::pause`]: the pen and why the plot
/// stops (`pause before pen 2 red`, `refill pen 2 red`).
pub const PAUSE_PLACEHOLDERS: &[&str] = &["pen", "name", "message"];

/// Placeholders of [`GcodeOptions::pen_down`]: the pen-down height.
pub const PEN_DOWN_PLACEHOLDERS: &[&str] = &["height"];

/// Placeholders of [`GcodeOptions::dwell`]: the time in seconds and in
/// milliseconds.
pub const DWELL_PLACEHOLDERS: &[&str] = &["s", "ms"];

/// Options of [`to_gcode`]: one machine's dialect and habits. The
/// built-in device profiles ([`crate::output::device`]) are sets of them.
///
/// Check them with [`GcodeOptions::validate`] where they enter the program
/// (a scene description, the command line, a profile). [`to_gcode`]
/// itself fails only for a drawing outside [`GcodeOptions::area`]: a
/// tolerance below [`MIN_TOLERANCE`] is raised to it, and other
/// out-of-range values are written as given.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GcodeOptions {
    /// Flattening tolerance in mm: the written polylines stay about this
    /// close to the curves (kurbo's `flatten` estimates the subdivision and
    /// may exceed it by a fraction). Default 0.02 mm, invisible under a
    /// 0.3 mm pen.
    pub tolerance: f64,
    /// Decimals of coordinates (at most 8). Default 3 (a micrometre).
    pub precision: u8,
    /// Command(s) that lift the pen; several lines are separated by `\n`.
    /// Default `M5`.
    pub pen_up: String,
    /// Command(s) that lower the pen; `{height}` is the pen-down height
    /// ([`GcodeOptions::pen_down_height`], or a pen's `+H` code mapped
    /// through [`GcodeOptions::height_range`]). Default `M3 S1000`.
    pub pen_down: String,
    /// What `{height}` is in [`GcodeOptions::pen_down`] when the pen's name
    /// has no `+H` code, in the machine's own unit (a Z in mm, a servo
    /// value). Default 0.
    pub pen_down_height: f64,
    /// The heights of AxiDraw's `+H0` and `+H100`, in the machine's unit: a
    /// pen named `+H30 …` goes down to `h0 + 0.3 · (h100 − h0)`. `None`:
    /// this machine cannot set a height, and `+H` is reported, not acted
    /// on. Default `None`.
    pub height_range: Option<[f64; 2]>,
    /// Dwell after every pen command, in seconds; 0 writes none. Default
    /// 0.15 s.
    pub pen_delay_s: f64,
    /// How a dwell is written; `{s}` is seconds, `{ms}` milliseconds.
    /// Default `G4 P{s}` (GRBL reads `P` in seconds; Marlin in
    /// milliseconds, `G4 P{ms}`).
    pub dwell: String,
    /// Feed rate while drawing, mm/min. Default 1500.
    pub feed_down_mm_min: f64,
    /// The drawing feed of AxiDraw's `+S100`: a pen named `+S40 …` draws at
    /// 40 % of it. Default 6000 mm/min.
    pub feed_max_mm_min: f64,
    /// Feed rate of pen-up travel, mm/min, written as `G1 … F…`; `None`
    /// (0 in a file) travels with `G0` at the machine's maximum rates
    /// (`$110`, `$111`). Default 4000.
    #[serde(with = "zero_is_rapid")]
    pub feed_up_mm_min: Option<f64>,
    /// The sheet corner that is the machine's zero. Default bottom-left.
    pub origin: Origin,
    /// Run machine Y the other way (see the module documentation).
    /// Default `false`.
    pub flip_y: bool,
    /// The machine's travel, `[x_min, y_min, x_max, y_max]` in machine mm:
    /// a program that would leave it is refused ([`Error::MachineArea`])
    /// and nothing is written. `None`: not checked. Default `None`.
    pub area: Option<[f64; 4]>,
    /// Write runs of a stroke that lie on a circle within this many mm as
    /// `G2`/`G3` arcs (see `output::arcs`); `None` writes lines only.
    /// Default `None`.
    pub arcs: Option<f64>,
    /// Number every line (`N1 G21`), as Marlin hosts do; comments are then
    /// left out, and the program starts by setting the line number
    /// (`N0 M110 N0`). Default off.
    pub line_numbers: bool,
    /// End every numbered line with `*` and its checksum (the XOR of its
    /// bytes, RepRap's rule); implies line numbers. Default off.
    pub checksums: bool,
    /// Lines written after `G21`/`G90`, before the pen is first lifted
    /// (e.g. `$H` to home, `G92 X0 Y0`); placeholders
    /// [`PAGE_PLACEHOLDERS`]. Default none.
    pub header: Vec<String>,
    /// Lines written at the very end, after the pen is lifted and parked;
    /// placeholders [`PAGE_PLACEHOLDERS`]. Default `M2` (end of program).
    pub footer: Vec<String>,
    /// Where to travel after the last stroke, in machine coordinates;
    /// `None` stays where the drawing ends. Default `[0, 0]`.
    pub park: Option<[f64; 2]>,
    /// Written before each pen's strokes when the program uses more than one
    /// pen; placeholders [`PEN_PLACEHOLDERS`]. The pen is up when it runs.
    /// Default `M0 ; load pen {pen} {name}` (GRBL pauses until cycle
    /// start). `None` writes nothing.
    pub tool_change: Option<String>,
    /// Written before each pen's strokes, after any tool change, pause or
    /// delay; placeholders [`PEN_PLACEHOLDERS`]. Default none.
    pub pen_start: Option<String>,
    /// Written after each pen's last stroke, the pen up; placeholders
    /// [`PEN_PLACEHOLDERS`]. Default none.
    pub pen_end: Option<String>,
    /// How the program stops for the operator: before a pen whose name
    /// starts with AxiDraw's `!`, and to refill a pen without a refill
    /// place ([`RunOptions`]); placeholders [`PAUSE_PLACEHOLDERS`].
    /// Default `M0 ; {message}`.
    pub pause: String,
    /// Refills and resuming ([`RunOptions`]). Default neither.
    pub runs: RunOptions,
    /// Write `;` comments (program summary, pen and path ids). Default on.
    pub comments: bool,
}

impl Default for GcodeOptions {
    fn default() -> GcodeOptions {
        GcodeOptions {
            tolerance: 0.02,
            precision: 3,
            pen_up: "M5".into(),
            pen_down: "M3 S1000".into(),
            pen_down_height: 0.0,
            height_range: None,
            pen_delay_s: 0.15,
            dwell: "G4 P{s}".into(),
            feed_down_mm_min: 1500.0,
            feed_max_mm_min: 6000.0,
            feed_up_mm_min: Some(4000.0),
            origin: Origin::BottomLeft,
            flip_y: false,
            area: None,
            arcs: None,
            line_numbers: false,
            checksums: false,
            header: Vec::new(),
            footer: vec!["M2".into()],
            park: Some([0.0, 0.0]),
            tool_change: Some("M0 ; load pen {pen} {name}".into()),
            pen_start: None,
            pen_end: None,
            pause: "M0 ; {message}".into(),
            runs: RunOptions::default(),
            comments: true,
        }
    }
}

impl GcodeOptions {
    /// These options with flattening tolerance `tolerance` mm.
    pub fn with_tolerance(mut self, tolerance: f64) -> GcodeOptions {
        self.tolerance = tolerance;
        self
    }

    /// These options with `precision` decimals (clamped to 8).
    pub fn with_precision(mut self, precision: u8) -> GcodeOptions {
        self.precision = precision.min(super::number::MAX_PRECISION);
        self
    }

    /// These options with other pen commands.
    pub fn with_pen_commands(
        mut self,
        up: impl Into<String>,
        down: impl Into<String>,
    ) -> GcodeOptions {
        self.pen_up = up.into();
        self.pen_down = down.into();
        self
    }

    /// These options with a pen-down height and the heights of `+H0` and
    /// `+H100` (`None`: no heights).
    pub fn with_heights(mut self, down: f64, range: Option<[f64; 2]>) -> GcodeOptions {
        self.pen_down_height = down;
        self.height_range = range;
        self
    }

    /// These options with a dwell of `seconds` after each pen command.
    pub fn with_pen_delay_s(mut self, seconds: f64) -> GcodeOptions {
        self.pen_delay_s = seconds;
        self
    }

    /// These options writing dwells with `template`.
    pub fn with_dwell(mut self, template: impl Into<String>) -> GcodeOptions {
        self.dwell = template.into();
        self
    }

    /// These options with a drawing feed of `mm_min`.
    pub fn with_feed_down_mm_min(mut self, mm_min: f64) -> GcodeOptions {
        self.feed_down_mm_min = mm_min;
        self
    }

    /// These options with `mm_min` as the feed of `+S100`.
    pub fn with_feed_max_mm_min(mut self, mm_min: f64) -> GcodeOptions {
        self.feed_max_mm_min = mm_min;
        self
    }

    /// These options with a travel feed (`None`: travel with `G0`).
    pub fn with_feed_up_mm_min(mut self, mm_min: Option<f64>) -> GcodeOptions {
        self.feed_up_mm_min = mm_min;
        self
    }

    /// These options with the machine zero at `origin`.
    pub fn with_origin(mut self, origin: Origin) -> GcodeOptions {
        self.origin = origin;
        self
    }

    /// These options with machine Y flipped or not.
    pub fn with_flip_y(mut self, flip_y: bool) -> GcodeOptions {
        self.flip_y = flip_y;
        self
    }

    /// These options with the machine's travel `[x_min, y_min, x_max,
    /// y_max]` (`None`: unchecked).
    pub fn with_area(mut self, area: Option<[f64; 4]>) -> GcodeOptions {
        self.area = area;
        self
    }

    /// These options with arcs fitted within `tolerance` mm (`None`: lines
    /// only).
    pub fn with_arcs(mut self, tolerance: Option<f64>) -> GcodeOptions {
        self.arcs = tolerance;
        self
    }

    /// These options with line numbers and checksums on or off.
    pub fn with_line_numbers(mut self, numbers: bool, checksums: bool) -> GcodeOptions {
        self.line_numbers = numbers;
        self.checksums = checksums;
        self
    }

    /// These options with these header lines.
    pub fn with_header(mut self, lines: Vec<String>) -> GcodeOptions {
        self.header = lines;
        self
    }

    /// These options with these footer lines.
    pub fn with_footer(mut self, lines: Vec<String>) -> GcodeOptions {
        self.footer = lines;
        self
    }

    /// These options with another park position (`None`: do not park).
    pub fn with_park(mut self, park: Option<[f64; 2]>) -> GcodeOptions {
        self.park = park;
        self
    }

    /// These options with another tool-change template (`None`: none).
    pub fn with_tool_change(mut self, template: Option<String>) -> GcodeOptions {
        self.tool_change = template;
        self
    }

    /// These options with templates around each pen's strokes.
    pub fn with_pen_templates(
        mut self,
        start: Option<String>,
        end: Option<String>,
    ) -> GcodeOptions {
        self.pen_start = start;
        self.pen_end = end;
        self
    }

    /// These options pausing with `template`.
    pub fn with_pause(mut self, template: impl Into<String>) -> GcodeOptions {
        self.pause = template.into();
        self
    }

    /// These options with refills and resuming.
    pub fn with_runs(mut self, runs: RunOptions) -> GcodeOptions {
        self.runs = runs;
        self
    }

    /// These options with comments on or off.
    pub fn with_comments(mut self, comments: bool) -> GcodeOptions {
        self.comments = comments;
        self
    }

    /// Checks the options; field names in errors are prefixed `gcode.`.
    pub fn validate(&self) -> Result<()> {
        positive("gcode.tolerance", self.tolerance)?;
        positive("gcode.feed_down_mm_min", self.feed_down_mm_min)?;
        positive("gcode.feed_max_mm_min", self.feed_max_mm_min)?;
        if let Some(f) = self.feed_up_mm_min {
            positive("gcode.feed_up_mm_min", f)?;
        }
        if let Some(t) = self.arcs {
            positive("gcode.arcs", t)?;
        }
        if !(self.pen_delay_s.is_finite() && (0.0..=3600.0).contains(&self.pen_delay_s)) {
            return Err(Error::invalid(
                "gcode.pen_delay_s",
                format!("must be 0 to 3600 seconds, got {}", self.pen_delay_s),
            ));
        }
        if self.precision > super::number::MAX_PRECISION {
            return Err(Error::invalid(
                "gcode.precision",
                format!(
                    "must be at most {}, got {}",
                    super::number::MAX_PRECISION,
                    self.precision
                ),
            ));
        }
        finite("gcode.pen_down_height", &[self.pen_down_height])?;
        if let Some(range) = self.height_range {
            finite("gcode.height_range", &range)?;
        }
        if let Some(park) = self.park {
            finite("gcode.park", &park)?;
        }
        if let Some(area) = self.area {
            finite("gcode.area", &area)?;
            let [x0, y0, x1, y1] = area;
            if !(x0 < x1 && y0 < y1) {
                return Err(Error::invalid(
                    "gcode.area",
                    format!("must be [x_min, y_min, x_max, y_max] with min < max, got {area:?}"),
                ));
            }
        }
        template::check("gcode.pen_up", &self.pen_up, &[])?;
        template::check("gcode.pen_down", &self.pen_down, PEN_DOWN_PLACEHOLDERS)?;
        template::check("gcode.dwell", &self.dwell, DWELL_PLACEHOLDERS)?;
        template::check("gcode.pause", &self.pause, PAUSE_PLACEHOLDERS)?;
        for (field, lines) in [
            ("gcode.header", &self.header),
            ("gcode.footer", &self.footer),
        ] {
            for line in lines {
                template::check(field, line, PAGE_PLACEHOLDERS)?;
            }
        }
        for (field, text) in [
            ("gcode.tool_change", &self.tool_change),
            ("gcode.pen_start", &self.pen_start),
            ("gcode.pen_end", &self.pen_end),
        ] {
            if let Some(text) = text {
                template::check(field, text, PEN_PLACEHOLDERS)?;
            }
        }
        self.runs.validate("gcode")
    }
}

/// [`GcodeOptions::feed_up_mm_min`] in a file: 0 for `None` (travel with
/// `G0`), which a TOML table could not say otherwise.
mod zero_is_rapid {
    use serde::{Deserialize, Deserializer, Serializer};

    pub(super) fn serialize<S: Serializer>(feed: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_f64(feed.unwrap_or(0.0))
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
        let feed = f64::deserialize(d)?;
        Ok((feed != 0.0).then_some(feed))
    }
}

/// `Err` naming `field` unless every value is finite.
fn finite(field: &str, values: &[f64]) -> Result<()> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(Error::invalid(field, "must be finite numbers"))
    }
}

/// What the G-code writer cannot do of what the scene's pens ask
/// (AxiDraw's `+H` without [`GcodeOptions::height_range`], or with a
/// [`GcodeOptions::pen_down`] that has no `{height}`), one line each, for
/// the caller to show.
pub fn unsupported(scene: &Scene, options: &GcodeOptions) -> Vec<String> {
    let mut out = Vec::new();
    for block in pen_blocks(scene, options.tolerance) {
        if let Some(h) = block.codes.height {
            if options.height_range.is_none() || !options.pen_down.contains("{height}") {
                out.push(format!(
                    "pen {} asks for pen height +H{h}, but this machine's pen_down has no \
                     {{height}} or it has no height_range: drawn at the usual height",
                    block.number
                ));
            }
        }
    }
    out
}

/// Writes `scene` as a G-code program (see the module documentation).
///
/// # Errors
/// [`Error::MachineArea`] for the first point outside
/// [`GcodeOptions::area`].
pub fn to_gcode(scene: &Scene, options: &GcodeOptions) -> Result<String> {
    let mut blocks = pen_blocks(scene, options.tolerance);
    runs::apply(&mut blocks, &options.runs);
    let mut w = Writer {
        out: String::new(),
        o: options,
        precision: options.precision.min(super::number::MAX_PRECISION),
        to_machine: ToMachine {
            page: (scene.page.width, scene.page.height),
            mirror_x: false,
            from_bottom: options.origin == Origin::BottomLeft,
            negate_y: options.flip_y,
        },
        feed: None,
        at: Point::ZERO,
        comments: options.comments && !(options.line_numbers || options.checksums),
    };
    w.program(scene, &blocks)?;
    if options.line_numbers || options.checksums {
        Ok(numbered(&w.out, options.checksums))
    } else {
        Ok(w.out)
    }
}

/// `program` with every line numbered (and checksummed), from `N0 M110 N0`
/// which tells the machine where counting starts.
fn numbered(program: &str, checksums: bool) -> String {
    let mut out = String::with_capacity(program.len() * 5 / 4);
    let lines = std::iter::once("M110 N0").chain(program.lines());
    for (n, line) in lines.enumerate() {
        let mut numbered = format!("N{n} {line}");
        if checksums {
            let sum = numbered.bytes().fold(0u8, |a, b| a ^ b);
            numbered.push('*');
            numbered.push_str(&sum.to_string());
        }
        out.push_str(&numbered);
        out.push('\n');
    }
    out
}

struct Writer<'a> {
    out: String,
    o: &'a GcodeOptions,
    precision: u8,
    /// Page millimetres to machine coordinates (module documentation).
    to_machine: ToMachine,
    /// The last `F` written (G-code feed is modal).
    feed: Option<f64>,
    /// Where the last move ended, machine mm.
    at: Point,
    /// Write moyo's own comments (not with line numbers).
    comments: bool,
}

/// What a pen's block draws with: its feed and its pen-down command.
struct PenSettings {
    feed: f64,
    pen_down: String,
}

impl Writer<'_> {
    fn program(&mut self, scene: &Scene, blocks: &[PenBlock<'_>]) -> Result<()> {
        if self.comments {
            self.out.push_str("; moyo G-code: ");
            self.number_exact(scene.page.width);
            self.out.push_str(" x ");
            self.number_exact(scene.page.height);
            self.out.push_str(" mm page, origin ");
            self.out.push_str(match self.o.origin {
                Origin::TopLeft => "top-left",
                Origin::BottomLeft => "bottom-left",
            });
            let y_up = (self.o.origin == Origin::BottomLeft) != self.o.flip_y;
            self.out
                .push_str(if y_up { ", Y up\n" } else { ", Y down\n" });
        }
        self.command("G21", "millimetres");
        self.command("G90", "absolute coordinates");
        let page = [
            ("page_width", number_text(scene.page.width)),
            ("page_height", number_text(scene.page.height)),
        ];
        let page: Vec<(&str, &str)> = page.iter().map(|(k, v)| (*k, v.as_str())).collect();
        for line in &self.o.header {
            self.lines(&template::fill(line, &page));
        }
        self.pen_up();

        let tool_change = self.o.tool_change.as_deref().filter(|_| blocks.len() > 1);
        for block in blocks {
            self.block(block, tool_change)?;
        }

        if self.comments {
            self.out.push_str("; end\n");
        }
        if let Some([x, y]) = self.o.park {
            self.travel(x, y, "park")?;
        }
        for line in &self.o.footer {
            self.lines(&template::fill(line, &page));
        }
        Ok(())
    }

    /// One pen's strokes, with what its name asks for before them.
    fn block(&mut self, block: &PenBlock<'_>, tool_change: Option<&str>) -> Result<()> {
        let name = comment_text(block.name);
        if self.comments {
            self.out.push_str("; pen ");
            self.out.push_str(&block.number.to_string());
            if !name.is_empty() {
                self.out.push(' ');
                self.out.push_str(&name);
            }
            self.out.push('\n');
        }
        if let Some(template) = tool_change {
            self.pen_template(template, block);
        }
        let codes = block.codes;
        if codes.pause {
            self.pause(block.number, &name, "pause before pen");
        }
        if let Some(ms) = codes.delay_ms {
            self.dwell(f64::from(ms) / 1000.0);
        }
        if let Some(template) = &self.o.pen_start {
            self.pen_template(template, block);
        }
        let settings = PenSettings {
            feed: match codes.speed {
                Some(percent) => self.o.feed_max_mm_min * f64::from(percent) / 100.0,
                None => self.o.feed_down_mm_min,
            },
            pen_down: {
                let height = match (codes.height, self.o.height_range) {
                    (Some(h), Some([h0, h100])) => h0 + f64::from(h) / 100.0 * (h100 - h0),
                    _ => self.o.pen_down_height,
                };
                template::fill(&self.o.pen_down, &[("height", &number_text(height))])
            },
        };
        for path in &block.paths {
            if self.comments {
                self.out.push_str("; path ");
                push_comment_text(&mut self.out, path.id);
                self.out.push('\n');
            }
            for stroke in &path.strokes {
                if stroke.refill_before {
                    self.refill(block.number, &name, &settings)?;
                }
                self.stroke(stroke, &settings, path.id)?;
            }
        }
        if let Some(template) = &self.o.pen_end {
            self.pen_template(template, block);
        }
        Ok(())
    }

    /// A refill: dip the pen at the refill place, or pause.
    fn refill(&mut self, pen: u32, name: &str, settings: &PenSettings) -> Result<()> {
        match self.o.runs.refill_at {
            Some([x, y]) => {
                if self.comments {
                    self.out.push_str("; refill\n");
                }
                self.travel(x, y, "refill")?;
                self.pen_down(settings);
                self.pen_up();
            }
            None => self.pause(pen, name, "refill pen"),
        }
        Ok(())
    }

    /// One pen-down stroke: travel, pen down, draw, pen up.
    fn stroke(&mut self, stroke: &Stroke, settings: &PenSettings, path: &str) -> Result<()> {
        let machine = self.to_machine.stroke(stroke);
        let Some((&Point { x: x0, y: y0 }, _)) = machine.points.split_first() else {
            return Ok(());
        };
        for &p in &machine.points {
            self.check_area(p, path)?;
        }
        self.travel(x0, y0, path)?;
        self.pen_down(settings);
        let moves = match self.o.arcs {
            Some(tolerance) => arcs::fit(&machine.points, tolerance, self.o.tolerance),
            None => machine.points[1..].iter().map(|&p| Move::Line(p)).collect(),
        };
        // Moves that print like the previous position are left out.
        let mut last = self.xy(x0, y0);
        for m in moves {
            let (to, arc) = match m {
                Move::Line(to) => (to, None),
                Move::Arc { to, center, ccw } => (to, Some((center, ccw))),
            };
            let xy = self.xy(to.x, to.y);
            if xy == last {
                continue;
            }
            match arc {
                Some((center, ccw)) => {
                    let from = self.at;
                    self.out.push_str(if ccw { "G3 " } else { "G2 " });
                    self.out.push_str(&xy);
                    self.out.push_str(" I");
                    write_number(&mut self.out, center.x - from.x, self.precision);
                    self.out.push_str(" J");
                    write_number(&mut self.out, center.y - from.y, self.precision);
                }
                None => {
                    self.out.push_str("G1 ");
                    self.out.push_str(&xy);
                }
            }
            self.feed(Some(settings.feed));
            self.out.push('\n');
            self.at = to;
            last = xy;
        }
        self.pen_up();
        Ok(())
    }

    /// A pen-up move to machine `(x, y)`; `what` names it in an area error.
    fn travel(&mut self, x: f64, y: f64, what: &str) -> Result<()> {
        self.check_area(Point::new(x, y), what)?;
        let xy = self.xy(x, y);
        match self.o.feed_up_mm_min {
            Some(f) => {
                self.out.push_str("G1 ");
                self.out.push_str(&xy);
                self.feed(Some(f));
            }
            None => {
                self.out.push_str("G0 ");
                self.out.push_str(&xy);
            }
        }
        self.out.push('\n');
        self.at = Point::new(x, y);
        Ok(())
    }

    /// `Err` when machine point `p` is outside [`GcodeOptions::area`].
    fn check_area(&self, p: Point, what: &str) -> Result<()> {
        match self.o.area {
            Some(area @ [x0, y0, x1, y1])
                if !((x0..=x1).contains(&p.x) && (y0..=y1).contains(&p.y)) =>
            {
                Err(Error::MachineArea {
                    what: what.to_string(),
                    x_mm: p.x,
                    y_mm: p.y,
                    area,
                })
            }
            _ => Ok(()),
        }
    }

    /// ` F…` when `feed` differs from the modal feed.
    fn feed(&mut self, feed: Option<f64>) {
        if feed != self.feed {
            if let Some(f) = feed {
                self.out.push_str(" F");
                write_number(&mut self.out, f, self.precision);
            }
            self.feed = feed;
        }
    }

    /// `X… Y…` at the coordinate precision.
    fn xy(&self, x: f64, y: f64) -> String {
        let mut s = String::from("X");
        write_number(&mut s, x, self.precision);
        s.push_str(" Y");
        write_number(&mut s, y, self.precision);
        s
    }

    /// The pen-up command and its dwell.
    fn pen_up(&mut self) {
        let command = self.o.pen_up.clone();
        self.lines(&command);
        self.dwell(self.o.pen_delay_s);
    }

    /// The pen's pen-down command and its dwell.
    fn pen_down(&mut self, settings: &PenSettings) {
        self.lines(&settings.pen_down);
        self.dwell(self.o.pen_delay_s);
    }

    /// A dwell of `seconds`, none for 0.
    fn dwell(&mut self, seconds: f64) {
        if seconds > 0.0 {
            let s = number_text(seconds);
            let ms = number_text(seconds * 1000.0);
            let text = template::fill(&self.o.dwell, &[("s", &s), ("ms", &ms)]);
            self.lines(&text);
        }
    }

    /// The pause template, for `why` (`pause before pen`, `refill pen`).
    fn pause(&mut self, pen: u32, name: &str, why: &str) {
        let pen = pen.to_string();
        let message = if name.is_empty() {
            format!("{why} {pen}")
        } else {
            format!("{why} {pen} {name}")
        };
        let text = template::fill(
            &self.o.pause,
            &[("pen", &pen), ("name", name), ("message", &message)],
        );
        self.lines(&text);
    }

    /// A per-pen template.
    fn pen_template(&mut self, template: &str, block: &PenBlock<'_>) {
        let pen = block.number.to_string();
        let name = comment_text(block.name);
        let layer = comment_text(&LayerCodes::label(block.number, block.name));
        let (x, y) = (number_text(self.at.x), number_text(self.at.y));
        let text = template::fill(
            template,
            &[
                ("pen", &pen),
                ("name", &name),
                ("layer", &layer),
                ("x", &x),
                ("y", &y),
            ],
        );
        self.lines(text.trim_end());
    }

    fn command(&mut self, code: &str, comment: &str) {
        self.out.push_str(code);
        if self.comments {
            self.out.push_str(" ; ");
            self.out.push_str(comment);
        }
        self.out.push('\n');
    }

    /// User-supplied text, one output line per line, without empty lines;
    /// with line numbers, without comments.
    fn lines(&mut self, text: &str) {
        for line in text.lines() {
            let line = if self.comments || !(self.o.line_numbers || self.o.checksums) {
                line
            } else {
                line.split(';').next().unwrap_or("")
            };
            let line = line.trim_end();
            if !line.is_empty() {
                self.out.push_str(line);
                self.out.push('\n');
            }
        }
    }

    fn number_exact(&mut self, v: f64) {
        write_number(&mut self.out, v, super::number::MAX_PRECISION);
    }
}

/// `v` as the writers write numbers, at three decimals.
fn number_text(v: f64) -> String {
    let mut s = String::new();
    write_number(&mut s, v, 3);
    s
}

/// `text` with control characters (line breaks above all) made spaces, so
/// that it cannot end a `;` comment early.
fn comment_text(text: &str) -> String {
    text.chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect()
}

fn push_comment_text(out: &mut String, text: &str) {
    out.push_str(&comment_text(text));
}

#[cfg(test)]
mod tests {
    use super::super::strokes::tests::{two_pen_scene, with_unplotted_layers};
    use super::*;
    use kurbo::Affine;

    fn gcode(scene: &Scene, options: &GcodeOptions) -> String {
        to_gcode(scene, options).unwrap()
    }

    /// The `(x, y)` of every `G0`/`G1` line, in order.
    fn moves(gcode: &str) -> Vec<(String, f64, f64)> {
        gcode
            .lines()
            .filter(|l| l.starts_with("G0 ") || l.starts_with("G1 "))
            .map(|l| {
                let word = |c: char| -> f64 {
                    let w = l.split(' ').find(|w| w.starts_with(c)).unwrap();
                    w[1..].parse().unwrap()
                };
                (l[..2].to_string(), word('X'), word('Y'))
            })
            .collect()
    }

    #[test]
    fn snapshot_of_two_pen_scene() {
        insta::assert_snapshot!(gcode(&two_pen_scene(), &GcodeOptions::default()));
    }

    #[test]
    fn deterministic() {
        let o = GcodeOptions::default();
        assert_eq!(
            gcode(&two_pen_scene(), &o),
            gcode(&two_pen_scene().clone(), &o.clone())
        );
    }

    #[test]
    fn unplotted_layers_are_left_out() {
        let o = GcodeOptions::default();
        let plain = gcode(&two_pen_scene(), &o);
        let with = gcode(&with_unplotted_layers(two_pen_scene()), &o);
        // Not a move, not a path comment, not a tool change for pen 3.
        assert_eq!(with, plain);
        assert!(!with.contains("frame-outline") && !with.contains("pen 3"));
        // The frame's corners (1, 1) and (99, 79) on the page would be
        // X1 Y79 and X99 Y1 on the machine.
        for (_, x, y) in moves(&with) {
            assert!((6.0..=94.0).contains(&x) || (x, y) == (0.0, 0.0), "{x} {y}");
        }
        // A scene of nothing but unplotted layers is an empty program.
        let mut only = with_unplotted_layers(two_pen_scene());
        only.layers.retain(|l| !l.is_plotted());
        let empty = gcode(&only, &o);
        assert!(
            !empty.contains("M3 S1000") && !empty.contains("M0"),
            "{empty}"
        );
    }

    #[test]
    fn header_and_footer_frame_the_program() {
        let o = GcodeOptions::default()
            .with_header(vec!["$H".into(), "G92 X0 Y0".into()])
            .with_footer(vec!["M30".into()])
            .with_comments(false);
        let g = gcode(&two_pen_scene(), &o);
        let lines: Vec<&str> = g.lines().collect();
        assert_eq!(
            lines[..6],
            ["G21", "G90", "$H", "G92 X0 Y0", "M5", "G4 P0.15"]
        );
        assert_eq!(
            lines[lines.len() - 4..],
            ["M5", "G4 P0.15", "G1 X0 Y0 F4000", "M30"]
        );
        assert!(
            g.lines().all(|l| !l.starts_with(';')),
            "no comments when off"
        );
        // The default footer ends the program.
        let d = gcode(&two_pen_scene(), &GcodeOptions::default());
        assert!(d.ends_with("G1 X0 Y0 F4000\nM2\n"), "{d}");
    }

    #[test]
    fn every_stroke_is_framed_by_pen_commands() {
        let g = gcode(
            &two_pen_scene(),
            &GcodeOptions::default().with_comments(false),
        );
        let downs = g.lines().filter(|l| *l == "M3 S1000").count();
        let ups = g.lines().filter(|l| *l == "M5").count();
        // square, curve, circle; plus the initial lift.
        assert_eq!(downs, 3);
        assert_eq!(ups, 4);
        // The pen is never down during a travel, and always down for a draw.
        let mut down = false;
        let mut draws = 0;
        for l in g.lines() {
            match l {
                "M3 S1000" => down = true,
                "M5" => down = false,
                _ if l.contains(" F4000") => assert!(!down, "travel with the pen down: {l}"),
                _ if l.starts_with("G1 ") => {
                    assert!(down, "draw with the pen up: {l}");
                    draws += 1;
                }
                _ => {}
            }
        }
        assert!(draws > 20);
        // Dwell after each pen command.
        assert_eq!(g.matches("G4 P0.15\n").count(), downs + ups);
    }

    #[test]
    fn y_mapping_follows_origin_and_flip() {
        // The square spans page x 10..30, y 10..30 on an 80 mm high page.
        let mut scene = two_pen_scene();
        scene.layers.retain(|l| l.id == "square-layer");
        let first_draw = |o: GcodeOptions| {
            let g = gcode(&scene, &o.with_park(None));
            let m = moves(&g);
            // The travel to the start, then the first drawn corner.
            (m[0].1, m[0].2, m[1].1, m[1].2)
        };
        let d = GcodeOptions::default();
        // kurbo's rectangle path goes (x0,y0) → (x1,y0) → (x1,y1) → (x0,y1).
        assert_eq!(first_draw(d.clone()), (10.0, 70.0, 30.0, 70.0));
        assert_eq!(
            first_draw(d.clone().with_flip_y(true)),
            (10.0, -70.0, 30.0, -70.0)
        );
        assert_eq!(
            first_draw(d.clone().with_origin(Origin::TopLeft)),
            (10.0, 10.0, 30.0, 10.0)
        );
        assert_eq!(
            first_draw(d.with_origin(Origin::TopLeft).with_flip_y(true)),
            (10.0, -10.0, 30.0, -10.0)
        );
    }

    #[test]
    fn every_coordinate_is_on_the_page() {
        for origin in [Origin::TopLeft, Origin::BottomLeft] {
            let g = gcode(
                &two_pen_scene(),
                &GcodeOptions::default().with_origin(origin),
            );
            for (_, x, y) in moves(&g) {
                assert!((0.0..=100.0).contains(&x) && (0.0..=80.0).contains(&y));
            }
        }
    }

    #[test]
    fn travel_uses_g0_without_a_travel_feed() {
        let o = GcodeOptions::default()
            .with_feed_up_mm_min(None)
            .with_comments(false);
        let g = gcode(&two_pen_scene(), &o);
        let m = moves(&g);
        assert_eq!(m.iter().filter(|m| m.0 == "G0").count(), 3 + 1);
        // Feed is modal and G0 does not use it: written once.
        assert_eq!(g.matches("F1500").count(), 1);
        assert!(!g.contains("F4000"));
        assert!(g.ends_with("G0 X0 Y0\nM2\n"));
    }

    #[test]
    fn numbers_have_fixed_precision() {
        let mut scene = two_pen_scene();
        let ring = &mut scene.layers[0].content;
        ring.transform = Affine::translate((1.0 / 3.0, 0.0)) * ring.transform;
        let g = gcode(&scene, &GcodeOptions::default().with_precision(2));
        for (_, x, y) in moves(&g) {
            for v in [x, y] {
                assert_eq!((v * 100.0).round() / 100.0, v, "{v}");
            }
        }
        // The circle starts at page (65⅓ + 8, 35).
        assert!(g.contains("X73.33 Y45"), "{g}");
        assert!(!g.contains("-0 ") && !g.contains("-0\n"));
    }

    #[test]
    fn tool_change_only_with_several_pens() {
        let g = gcode(&two_pen_scene(), &GcodeOptions::default());
        assert!(g.contains("M0 ; load pen 1 black\n"));
        assert!(g.contains("M0 ; load pen 2 red\n"));
        // It comes after the pen comment and before the pen's first travel.
        let change2 = g.find("M0 ; load pen 2").unwrap();
        assert!(g.find("; pen 2 red").unwrap() < change2);
        assert!(change2 < g.find("; path circle").unwrap());

        let mut one = two_pen_scene();
        one.layers.retain(|l| l.pen == 1);
        assert!(!gcode(&one, &GcodeOptions::default()).contains("M0"));

        let custom = GcodeOptions::default()
            .with_tool_change(Some("G0 X0 Y0\nM0 ; pen {pen}".into()))
            .with_comments(false);
        let g = gcode(&two_pen_scene(), &custom);
        assert!(g.contains("M5\nG4 P0.15\nG0 X0 Y0\nM0 ; pen 2\nG1 "), "{g}");
    }

    #[test]
    fn names_cannot_break_out_of_comments() {
        let mut scene = two_pen_scene();
        scene.pens[0].name = "evil\nG0 X999".into();
        scene.layers[1].content.children.iter_mut().for_each(|n| {
            if let crate::scene::Node::Path(p) = n {
                p.id = "sq\r\nM3".into();
            }
        });
        let g = gcode(&scene, &GcodeOptions::default());
        assert!(g.lines().all(|l| !l.starts_with("G0 X999") && l != "M3"));
        assert!(g.contains("; pen 1 evil G0 X999\n"));
    }

    #[test]
    fn closed_paths_return_to_their_start() {
        let mut scene = two_pen_scene();
        scene.layers.retain(|l| l.id == "square-layer");
        let g = gcode(&scene, &GcodeOptions::default().with_park(None));
        let m = moves(&g);
        assert_eq!(m.len(), 1 + 4);
        assert_eq!((m[0].1, m[0].2), (m[4].1, m[4].2));
    }

    #[test]
    fn validate_names_the_field() {
        assert!(GcodeOptions::default().validate().is_ok());
        let e = GcodeOptions::default()
            .with_feed_down_mm_min(0.0)
            .validate()
            .unwrap_err();
        assert!(e.to_string().starts_with("gcode.feed_down_mm_min: "), "{e}");
        let e = GcodeOptions::default()
            .with_pen_delay_s(f64::NAN)
            .validate()
            .unwrap_err();
        assert!(e.to_string().starts_with("gcode.pen_delay_s: "), "{e}");
        assert!(GcodeOptions::default()
            .with_tolerance(0.0)
            .validate()
            .is_err());
    }

    #[test]
    fn options_deserialize_with_defaults() {
        let o: GcodeOptions =
            toml::from_str("pen_down = \"M3 S90\"\norigin = \"top_left\"\nfeed_up_mm_min = 3000")
                .unwrap();
        assert_eq!(o.pen_down, "M3 S90");
        assert_eq!(o.origin, Origin::TopLeft);
        assert_eq!(o.feed_up_mm_min, Some(3000.0));
        assert_eq!(o.pen_up, "M5");
        assert!(toml::from_str::<GcodeOptions>("pen_dwn = \"x\"").is_err());
        let back: GcodeOptions = toml::from_str(&toml::to_string(&o).unwrap()).unwrap();
        assert_eq!(back, o);
    }

    /// [`two_pen_scene`] with pen 2 named `name`.
    fn pen_2_named(name: &str) -> Scene {
        let mut scene = two_pen_scene();
        scene.pens[1].name = name.into();
        scene
    }

    #[test]
    fn layer_codes_are_acted_on() {
        let z = GcodeOptions::default()
            .with_pen_commands("G0 Z3", "G1 Z{height} F600")
            .with_heights(0.0, Some([-0.5, 0.5]))
            .with_comments(false);
        let g = gcode(&pen_2_named("!+D500+H30+S40 fine"), &z);
        // Pen 2: the tool change, then exactly one pause, the delay, and
        // its strokes drawn at 40 % of the maximum feed, pen at +H30.
        let pen2 = &g[g.find("M0 ; load pen 2").unwrap()..];
        assert!(
            pen2.starts_with(
                "M0 ; load pen 2 !+D500+H30+S40 fine\nM0 ; pause before pen 2 !+D500+H30+S40 fine\nG4 P0.5\n"
            ),
            "{pen2}"
        );
        assert_eq!(g.matches("pause before pen").count(), 1);
        assert!(pen2.contains("G1 Z-0.2 F600\n"), "{pen2}");
        assert!(pen2.contains(" F2400\n"), "{pen2}");
        // Pen 1 draws as usual.
        let pen1 = &g[..g.find("M0 ; load pen 2").unwrap()];
        assert!(
            pen1.contains("G1 Z0 F600\n") && pen1.contains(" F1500\n"),
            "{pen1}"
        );
        assert!(unsupported(&pen_2_named("+H30"), &z).is_empty());
        // Without a height range, +H is reported, not acted on.
        let servo = GcodeOptions::default();
        assert!(!gcode(&pen_2_named("+H30"), &servo).contains("{height}"));
        let w = unsupported(&pen_2_named("+H30"), &servo);
        assert!(
            w.len() == 1 && w[0].starts_with("pen 2 asks for pen height +H30"),
            "{w:?}"
        );
    }

    #[test]
    fn pen_changes_and_pauses_happen_with_the_pen_up() {
        let o = GcodeOptions::default()
            .with_runs(RunOptions::default().with_refill_mm(Some(30.0)))
            .with_comments(false);
        let g = gcode(&pen_2_named("!red"), &o);
        let mut down = false;
        let mut pauses = 0;
        for l in g.lines() {
            match l {
                "M3 S1000" => down = true,
                "M5" => down = false,
                _ if l.starts_with("M0") => {
                    assert!(!down, "a pause with the pen down:\n{g}");
                    pauses += 1;
                }
                _ => {}
            }
        }
        // Two tool changes, one `!`, and refills every 30 mm.
        assert!(g.contains("M0 ; refill pen 1 black"), "{g}");
        assert!(pauses >= 4, "{g}");
    }

    #[test]
    fn refills_dip_at_the_refill_place() {
        let runs = RunOptions::default()
            .with_refill_mm(Some(30.0))
            .with_refill_at(Some([-20.0, 5.0]));
        let g = gcode(
            &two_pen_scene(),
            &GcodeOptions::default().with_runs(runs).with_comments(false),
        );
        let dips = g
            .matches("G1 X-20 Y5 F4000\nM3 S1000\nG4 P0.15\nM5\n")
            .count();
        assert!(dips >= 2, "{g}");
        assert!(!g.contains("refill pen"));
    }

    #[test]
    fn resuming_writes_only_the_rest() {
        let whole = two_pen_scene();
        let o = GcodeOptions::default().with_comments(false);
        let all = moves(&gcode(&whole, &o));
        let resumed = gcode(
            &whole,
            &o.clone()
                .with_runs(RunOptions::default().with_from_distance_mm(90.0)),
        );
        let rest = moves(&resumed);
        assert!(rest.len() < all.len());
        // Pen 1 draws about 80 mm (the square) and 70 mm (the curve):
        // resuming at 90 mm starts inside pen 1's second stroke, and what
        // follows is the whole program's tail.
        let tail = &all[all.len() - (rest.len() - 2)..];
        assert_eq!(&rest[2..], tail);
    }

    #[test]
    fn a_drawing_outside_the_machine_is_refused() {
        let small = GcodeOptions::default().with_area(Some([0.0, 0.0, 50.0, 50.0]));
        let e = to_gcode(&two_pen_scene(), &small).unwrap_err().to_string();
        assert!(
            e.starts_with("gcode: ") && e.contains("outside the machine's travel X 0…50, Y 0…50"),
            "{e}"
        );
        let fits = GcodeOptions::default().with_area(Some([0.0, 0.0, 100.0, 80.0]));
        assert!(to_gcode(&two_pen_scene(), &fits).is_ok());
        // The park counts too.
        let e = to_gcode(&two_pen_scene(), &fits.with_park(Some([120.0, 0.0])))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("gcode: park reaches (120.000, 0.000)"), "{e}");
        assert!(GcodeOptions::default()
            .with_area(Some([10.0, 0.0, 5.0, 50.0]))
            .validate()
            .is_err());
    }

    #[test]
    fn numbered_lines_carry_their_checksum() {
        let o = GcodeOptions::default().with_line_numbers(true, true);
        let g = gcode(&two_pen_scene(), &o);
        assert!(g.starts_with("N0 M110 N0*"), "{g}");
        for (n, line) in g.lines().enumerate() {
            let (body, sum) = line.rsplit_once('*').unwrap();
            assert!(body.starts_with(&format!("N{n} ")), "{line}");
            let xor = body.bytes().fold(0u8, |a, b| a ^ b);
            assert_eq!(sum, xor.to_string(), "{line}");
            assert!(!body.contains(';'), "no comments: {line}");
        }
        // The first line after the counter's reset.
        let one = numbered("G21\n", true);
        assert_eq!(
            one.lines().nth(1).unwrap(),
            format!("N1 G21*{}", b"N1 G21".iter().fold(0, |a, b| a ^ b))
        );
    }

    #[test]
    fn arcs_draw_the_circle_in_a_few_moves() {
        let mut scene = two_pen_scene();
        scene.layers.retain(|l| l.id == "circle-layer");
        // A circle drawn true to 0.1 µm (the scene's own is a rough one).
        if let crate::scene::Node::Path(p) = &mut scene.layers[0].content.children[0] {
            p.path = kurbo::Shape::to_path(&kurbo::Circle::new((0.0, 0.0), 4.0), 1e-4);
        }
        let lines = gcode(&scene, &GcodeOptions::default().with_comments(false));
        let arcs = gcode(
            &scene,
            &GcodeOptions::default()
                .with_arcs(Some(0.01))
                .with_comments(false),
        );
        let count = |g: &str, p: &str| g.lines().filter(|l| l.starts_with(p)).count();
        assert!(count(&arcs, "G2 ") + count(&arcs, "G3 ") >= 1, "{arcs}");
        assert!(arcs.lines().count() * 4 < lines.lines().count(), "{arcs}");
        // The circle (radius 8 about machine (65, 45)): every arc ends on
        // it.
        for l in arcs
            .lines()
            .filter(|l| l.starts_with("G2 ") || l.starts_with("G3 "))
        {
            let word = |c: char| -> f64 {
                l.split(' ').find(|w| w.starts_with(c)).unwrap()[1..]
                    .parse()
                    .unwrap()
            };
            let (x, y) = (word('X'), word('Y'));
            let r = ((x - 65.0).powi(2) + (y - 45.0).powi(2)).sqrt();
            assert!((r - 8.0).abs() < 0.03, "{l}: {r}");
        }
    }

    #[test]
    fn templates_fill_their_placeholders_and_refuse_others() {
        let o = GcodeOptions::default()
            .with_header(vec!["; page {page_width} x {page_height}".into()])
            .with_pen_templates(
                Some("; start {pen} at {x},{y}".into()),
                Some("; end {name}".into()),
            );
        let g = gcode(&two_pen_scene(), &o);
        assert!(g.contains("; page 100 x 80\n"), "{g}");
        assert!(
            g.contains("; start 1 at 0,0\n") && g.contains("; end red\n"),
            "{g}"
        );
        for (o, field) in [
            (
                GcodeOptions::default().with_header(vec!["{pen}".into()]),
                "gcode.header",
            ),
            (
                GcodeOptions::default().with_pause("M0 {why}"),
                "gcode.pause",
            ),
            (
                GcodeOptions::default().with_pen_commands("M5 {height}", "M3"),
                "gcode.pen_up",
            ),
            (
                GcodeOptions::default().with_dwell("G4 P{sec}"),
                "gcode.dwell",
            ),
        ] {
            let e = o.validate().unwrap_err().to_string();
            assert!(
                e.starts_with(&format!("{field}: unknown placeholder")),
                "{e}"
            );
        }
    }
}
