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

use super::number::write_number;
use super::strokes::{pen_blocks, positive, PenBlock, Stroke, ToMachine};
use crate::error::{Error, Result};
use crate::scene::Scene;

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

/// Options of [`to_gcode`].
///
/// Check them with [`GcodeOptions::validate`] where they enter the program
/// (a scene description, the command line). [`to_gcode`] itself never
/// fails: a tolerance below [`MIN_TOLERANCE`] is raised to it, and other
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
    /// Command(s) that lower the pen. Default `M3 S1000`.
    pub pen_down: String,
    /// Dwell after every pen command, in seconds (`G4 P…`); 0 writes none.
    /// Default 0.15 s.
    pub pen_delay_s: f64,
    /// Feed rate while drawing, mm/min. Default 1500.
    pub feed_down_mm_min: f64,
    /// Feed rate of pen-up travel, mm/min, written as `G1 … F…`; `None`
    /// travels with `G0` at the machine's maximum rates (`$110`, `$111`).
    /// Default 4000.
    pub feed_up_mm_min: Option<f64>,
    /// The sheet corner that is the machine's zero. Default bottom-left.
    pub origin: Origin,
    /// Run machine Y the other way (see the module documentation).
    /// Default `false`.
    pub flip_y: bool,
    /// Lines written after `G21`/`G90`, before the pen is first lifted
    /// (e.g. `$H` to home, `G92 X0 Y0`). Default none.
    pub header: Vec<String>,
    /// Lines written at the very end, after the pen is lifted and parked.
    /// Default `M2` (end of program).
    pub footer: Vec<String>,
    /// Where to travel after the last stroke, in machine coordinates;
    /// `None` stays where the drawing ends. Default `[0, 0]`.
    pub park: Option<[f64; 2]>,
    /// Written before each pen's strokes when the program uses more than one
    /// pen; `{pen}` becomes the pen number and `{name}` its name. The pen is
    /// up when it runs. Default `M0 ; load pen {pen} {name}` (GRBL pauses
    /// until cycle start). `None` writes nothing.
    pub tool_change: Option<String>,
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
            pen_delay_s: 0.15,
            feed_down_mm_min: 1500.0,
            feed_up_mm_min: Some(4000.0),
            origin: Origin::BottomLeft,
            flip_y: false,
            header: Vec::new(),
            footer: vec!["M2".into()],
            park: Some([0.0, 0.0]),
            tool_change: Some("M0 ; load pen {pen} {name}".into()),
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

    /// These options with a dwell of `seconds` after each pen command.
    pub fn with_pen_delay_s(mut self, seconds: f64) -> GcodeOptions {
        self.pen_delay_s = seconds;
        self
    }

    /// These options with a drawing feed of `mm_min`.
    pub fn with_feed_down_mm_min(mut self, mm_min: f64) -> GcodeOptions {
        self.feed_down_mm_min = mm_min;
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

    /// These options with comments on or off.
    pub fn with_comments(mut self, comments: bool) -> GcodeOptions {
        self.comments = comments;
        self
    }

    /// Checks the options; field names in errors are prefixed `gcode.`.
    pub fn validate(&self) -> Result<()> {
        positive("gcode.tolerance", self.tolerance)?;
        positive("gcode.feed_down_mm_min", self.feed_down_mm_min)?;
        if let Some(f) = self.feed_up_mm_min {
            positive("gcode.feed_up_mm_min", f)?;
        }
        if !(self.pen_delay_s.is_finite() && self.pen_delay_s >= 0.0) {
            return Err(Error::invalid(
                "gcode.pen_delay_s",
                format!("must be 0 or more seconds, got {}", self.pen_delay_s),
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
        if let Some([x, y]) = self.park {
            if !(x.is_finite() && y.is_finite()) {
                return Err(Error::invalid("gcode.park", "must be finite"));
            }
        }
        Ok(())
    }
}

/// Writes `scene` as a G-code program (see the module documentation).
pub fn to_gcode(scene: &Scene, options: &GcodeOptions) -> String {
    let blocks = pen_blocks(scene, options.tolerance);
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
    };
    w.program(scene, &blocks);
    w.out
}

struct Writer<'a> {
    out: String,
    o: &'a GcodeOptions,
    precision: u8,
    /// Page millimetres to machine coordinates (module documentation).
    to_machine: ToMachine,
    /// The last `F` written (G-code feed is modal).
    feed: Option<f64>,
}

impl Writer<'_> {
    fn program(&mut self, scene: &Scene, blocks: &[PenBlock<'_>]) {
        if self.o.comments {
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
        for line in &self.o.header {
            self.lines(line);
        }
        self.pen(false);

        let tool_change = self.o.tool_change.as_deref().filter(|_| blocks.len() > 1);
        for block in blocks {
            if self.o.comments {
                self.out.push_str("; pen ");
                self.out.push_str(&block.number.to_string());
                if !block.name.is_empty() {
                    self.out.push(' ');
                    push_comment_text(&mut self.out, block.name);
                }
                self.out.push('\n');
            }
            if let Some(template) = tool_change {
                let text = template
                    .replace("{pen}", &block.number.to_string())
                    .replace("{name}", &comment_text(block.name));
                self.lines(text.trim_end());
            }
            for path in &block.paths {
                if self.o.comments {
                    self.out.push_str("; path ");
                    push_comment_text(&mut self.out, path.id);
                    self.out.push('\n');
                }
                for stroke in &path.strokes {
                    self.stroke(stroke);
                }
            }
        }

        if self.o.comments {
            self.out.push_str("; end\n");
        }
        if let Some([x, y]) = self.o.park {
            self.travel(x, y);
        }
        for line in &self.o.footer {
            self.lines(line);
        }
    }

    /// One pen-down stroke: travel, pen down, draw, pen up.
    fn stroke(&mut self, stroke: &Stroke) {
        let machine = self.to_machine.stroke(stroke);
        let Some((&Point { x: x0, y: y0 }, rest)) = machine.points.split_first() else {
            return;
        };
        self.travel(x0, y0);
        self.pen(true);
        // Moves that print like the previous position are left out.
        let mut last = self.xy(x0, y0);
        for &Point { x, y } in rest {
            let xy = self.xy(x, y);
            if xy == last {
                continue;
            }
            self.out.push_str("G1 ");
            self.out.push_str(&xy);
            self.feed(Some(self.o.feed_down_mm_min));
            self.out.push('\n');
            last = xy;
        }
        self.pen(false);
    }

    /// A pen-up move to machine `(x, y)`.
    fn travel(&mut self, x: f64, y: f64) {
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

    /// Pen command and dwell.
    fn pen(&mut self, down: bool) {
        let command = if down {
            &self.o.pen_down
        } else {
            &self.o.pen_up
        };
        self.lines(command);
        if self.o.pen_delay_s > 0.0 {
            self.out.push_str("G4 P");
            write_number(&mut self.out, self.o.pen_delay_s, 3);
            self.out.push('\n');
        }
    }

    fn command(&mut self, code: &str, comment: &str) {
        self.out.push_str(code);
        if self.o.comments {
            self.out.push_str(" ; ");
            self.out.push_str(comment);
        }
        self.out.push('\n');
    }

    /// User-supplied text, one output line per line, without empty lines.
    fn lines(&mut self, text: &str) {
        for line in text.lines() {
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
        insta::assert_snapshot!(to_gcode(&two_pen_scene(), &GcodeOptions::default()));
    }

    #[test]
    fn deterministic() {
        let o = GcodeOptions::default();
        assert_eq!(
            to_gcode(&two_pen_scene(), &o),
            to_gcode(&two_pen_scene().clone(), &o.clone())
        );
    }

    #[test]
    fn unplotted_layers_are_left_out() {
        let o = GcodeOptions::default();
        let plain = to_gcode(&two_pen_scene(), &o);
        let with = to_gcode(&with_unplotted_layers(two_pen_scene()), &o);
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
        let empty = to_gcode(&only, &o);
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
        let g = to_gcode(&two_pen_scene(), &o);
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
        let d = to_gcode(&two_pen_scene(), &GcodeOptions::default());
        assert!(d.ends_with("G1 X0 Y0 F4000\nM2\n"), "{d}");
    }

    #[test]
    fn every_stroke_is_framed_by_pen_commands() {
        let g = to_gcode(
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
            let g = to_gcode(&scene, &o.with_park(None));
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
            let g = to_gcode(
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
        let g = to_gcode(&two_pen_scene(), &o);
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
        let g = to_gcode(&scene, &GcodeOptions::default().with_precision(2));
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
        let g = to_gcode(&two_pen_scene(), &GcodeOptions::default());
        assert!(g.contains("M0 ; load pen 1 black\n"));
        assert!(g.contains("M0 ; load pen 2 red\n"));
        // It comes after the pen comment and before the pen's first travel.
        let change2 = g.find("M0 ; load pen 2").unwrap();
        assert!(g.find("; pen 2 red").unwrap() < change2);
        assert!(change2 < g.find("; path circle").unwrap());

        let mut one = two_pen_scene();
        one.layers.retain(|l| l.pen == 1);
        assert!(!to_gcode(&one, &GcodeOptions::default()).contains("M0"));

        let custom = GcodeOptions::default()
            .with_tool_change(Some("G0 X0 Y0\nM0 ; pen {pen}".into()))
            .with_comments(false);
        let g = to_gcode(&two_pen_scene(), &custom);
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
        let g = to_gcode(&scene, &GcodeOptions::default());
        assert!(g.lines().all(|l| !l.starts_with("G0 X999") && l != "M3"));
        assert!(g.contains("; pen 1 evil G0 X999\n"));
    }

    #[test]
    fn closed_paths_return_to_their_start() {
        let mut scene = two_pen_scene();
        scene.layers.retain(|l| l.id == "square-layer");
        let g = to_gcode(&scene, &GcodeOptions::default().with_park(None));
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
}
