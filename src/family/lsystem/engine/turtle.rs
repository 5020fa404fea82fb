//! The 3D turtle: reads a [`Word`] in ABOP's notation and draws it into a
//! [`Skeleton`].
//!
//! The turtle has a position, a frame of heading H, left L and up U
//! (H × L = U), a width, a colour index and a branch order. It starts at
//! the origin with H = +y, L = −x, U = +z. `+`, `&` and `\` turn by the
//! angle δ in the positive (right-hand) sense about U, L and H: `+` turns
//! left as seen from +z, `&` pitches the heading down (towards −U), `\`
//! rolls L towards U; `-`, `^` and `/` turn back. `|` turns around, `$`
//! rolls L level (at right angles to the vertical +y, up which plants
//! grow). A parameter, `+(30)`, is the angle in degrees; `F(l)` moves `l`
//! steps; `!(w)` sets the width and `'(c)` the colour index.
//!
//! Consecutive drawing steps make one [`Limb`]. A branch `[ … ]` starts
//! its own limb, and the limb it grew from goes on after the `]` where it
//! left off, so an axis with side branches stays one polyline (smooth
//! splines and outlines follow it whole). A limb ends where the pen lifts
//! (`f`), where the colour changes, where its branch ends and at the end
//! of the word. (`%` needs no drawing: derivation has already cut the rest
//! of its branch from the word.)
//!
//! Inside `{ … }` the turtle traces a polygon instead of drawing limbs: a
//! vertex at each `.`, and at the end of each `F` and `f` (the first also
//! at its start); `G` moves without a vertex.

use glam::{DQuat, DVec3};

use super::rewrite::Word;
use super::{Limb, Mark, Skeleton};
use crate::error::{Error, Result};

/// How the turtle draws.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq)]
pub struct TurtleOptions {
    /// The length of one step (`F`; `F(l)` moves `l` steps), > 0.
    pub step: f64,
    /// The turning angle δ of `+ - & ^ \ /` without a parameter, degrees.
    pub angle: f64,
    /// The width at the start.
    pub width: f64,
    /// What `!` without a parameter multiplies the width by (`!(w)` sets
    /// it to `w`).
    pub width_factor: f64,
    /// ABOP's tropism: after each drawing step (`F`, `G`) the heading
    /// turns towards this direction (normalised) by elasticity ×
    /// |H × T| radians. `None`: no tropism.
    pub tropism: Option<(DVec3, f64)>,
    /// The symbols to record as [`Mark`]s where the turtle meets them.
    pub marks: String,
    /// The most drawing steps, polygon vertices and marks together.
    pub max_segments: usize,
    /// Branches too small to be drawn, left out as the turtle meets
    /// them. `None`: every branch is drawn.
    pub prune: Option<Prune>,
}

/// Which branches the turtle leaves out: a branch `[ … ]` whose steps
/// (`F`, `G`, `f`) add up to less than `min_length` on the page, so
/// that every limb in it is shorter than that — provided it holds no
/// recorded symbol and no polygon, and the turtle is not tracing one.
/// Such a branch is skipped to its `]`; nothing of it is in the
/// skeleton (nor among the limbs it would have started, nor in the
/// drawing's extent).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prune {
    /// The view's right and up (page x along `right`, page y along −`up`).
    pub right: DVec3,
    /// See `right`.
    pub up: DVec3,
    /// The shortest limb drawn, on the page (mm).
    pub min_length: f64,
    /// How the drawing is scaled to the page: `Scale(s)` mm a unit, or
    /// `Fit(width, height)`: fitted into a frame this size, aspect kept
    /// (then the scale is not known until the drawing is done; the turtle
    /// prunes by the scale the drawing so far would have, which is never
    /// smaller).
    pub scale: PruneScale,
}

/// The modules of a word the turtle looked at (see
/// [`Turtle::interpret_counted`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Work {
    /// Interpreted: turned, moved, drew, …
    pub interpreted: usize,
    /// Read ahead from a `[` to learn whether its branch is too small to
    /// draw (see [`Prune`]): those left out are read once, those drawn up
    /// to where their steps reach the limit.
    pub read_ahead: usize,
}

/// How a pruned drawing is scaled to the page (see [`Prune`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PruneScale {
    /// Millimetres a unit.
    Scale(f64),
    /// Fitted into a frame this wide and high (mm).
    Fit(f64, f64),
}

impl TurtleOptions {
    /// Step 1, δ = 25.7°, width 1 multiplied by 0.7 at each `!`, no
    /// tropism, no marks, at most 10 million segments.
    pub const DEFAULT: TurtleOptions = TurtleOptions {
        step: 1.0,
        angle: 25.7,
        width: 1.0,
        width_factor: 0.7,
        tropism: None,
        marks: String::new(),
        max_segments: 10_000_000,
        prune: None,
    };

    /// With this step length.
    pub fn with_step(mut self, step: f64) -> Self {
        self.step = step;
        self
    }

    /// With this turning angle (degrees).
    pub fn with_angle(mut self, angle: f64) -> Self {
        self.angle = angle;
        self
    }

    /// With this starting width.
    pub fn with_width(mut self, width: f64) -> Self {
        self.width = width;
        self
    }

    /// With this factor for `!`.
    pub fn with_width_factor(mut self, factor: f64) -> Self {
        self.width_factor = factor;
        self
    }

    /// With tropism towards `direction` (any length; zero turns it off)
    /// of this elasticity.
    pub fn with_tropism(mut self, direction: DVec3, elasticity: f64) -> Self {
        self.tropism = Some((direction, elasticity));
        self
    }

    /// Recording these symbols as marks.
    pub fn with_marks(mut self, symbols: &str) -> Self {
        self.marks = symbols.to_string();
        self
    }

    /// With at most this many drawing steps, vertices and marks.
    pub fn with_max_segments(mut self, max: usize) -> Self {
        self.max_segments = max;
        self
    }

    /// Leaving out the branches `prune` says no pen can draw.
    pub fn with_prune(mut self, prune: Prune) -> Self {
        self.prune = Some(prune);
        self
    }
}

impl Default for TurtleOptions {
    fn default() -> Self {
        TurtleOptions::DEFAULT
    }
}

/// The turtle that draws words.
#[derive(Debug, Clone, PartialEq)]
pub struct Turtle {
    options: TurtleOptions,
}

/// What a symbol makes the turtle do.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Command {
    Nothing,
    /// `F`: forward, drawing (a polygon vertex inside braces).
    Draw,
    /// `G`: forward, drawing, never a polygon vertex.
    DrawNoVertex,
    /// `f`: forward, pen up (a polygon vertex inside braces).
    Move,
    /// `.`: a polygon vertex.
    Vertex,
    /// `+ - & ^ \ /`: turn about U, L or H by ±δ.
    Turn(Axis, f64),
    /// `|`.
    TurnAround,
    /// `$`.
    Level,
    Push,
    Pop,
    PolygonStart,
    PolygonEnd,
    /// `!`.
    Width,
    /// `'`.
    Colour,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Axis {
    Up,
    Left,
    Heading,
}

fn command(c: char) -> Command {
    match c {
        'F' => Command::Draw,
        'G' => Command::DrawNoVertex,
        'f' => Command::Move,
        '.' => Command::Vertex,
        '+' => Command::Turn(Axis::Up, 1.0),
        '-' => Command::Turn(Axis::Up, -1.0),
        '&' => Command::Turn(Axis::Left, 1.0),
        '^' => Command::Turn(Axis::Left, -1.0),
        '\\' => Command::Turn(Axis::Heading, 1.0),
        '/' => Command::Turn(Axis::Heading, -1.0),
        '|' => Command::TurnAround,
        '$' => Command::Level,
        '[' => Command::Push,
        ']' => Command::Pop,
        '{' => Command::PolygonStart,
        '}' => Command::PolygonEnd,
        '!' => Command::Width,
        '\'' => Command::Colour,
        _ => Command::Nothing,
    }
}

/// The turtle's state, saved by `[` and restored by `]`.
#[derive(Debug, Clone, Copy)]
struct State {
    pos: DVec3,
    h: DVec3,
    l: DVec3,
    u: DVec3,
    width: f64,
    colour: u32,
    order: u32,
    /// The limb this state draws on (a slot of open limbs): only one
    /// state holds a limb at a time.
    open: Option<usize>,
    /// The limb whose last point is where the turtle stands, if any.
    attached: Option<Attached>,
}

/// A limb that ends where the turtle stands: a limb still being drawn
/// (held by this state or one it branched from), or one finished.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Attached {
    Open(usize),
    Closed(usize),
}

/// A limb being drawn: its index in the skeleton and its points so far.
#[derive(Debug, Default)]
struct OpenLimb {
    limb: usize,
    points: Vec<DVec3>,
    widths: Vec<f64>,
    /// Nothing has grown from its last point so far. (Kept here, not in
    /// the skeleton, while the limb grows: the skeleton's entry may be far
    /// away in memory.)
    tip: bool,
}

/// The drawing so far.
struct Canvas {
    skeleton: Skeleton,
    open: Vec<OpenLimb>,
    /// Slots of `open` free for reuse (their buffers keep their capacity).
    free: Vec<usize>,
    polygons: Vec<Vec<DVec3>>,
    used: usize,
    max: usize,
}

impl Canvas {
    fn count(&mut self, field: &str) -> Result<()> {
        self.used += 1;
        if self.used > self.max {
            return Err(Error::invalid(
                field,
                format!(
                    "the drawing has more than {} segments, vertices and marks (the limit): \
                     lower the iterations",
                    self.max
                ),
            ));
        }
        Ok(())
    }

    /// A new limb on `state`, from `from` to where the turtle stands.
    fn start(&mut self, state: &mut State, from: DVec3) {
        let to = state.pos;
        let limb = self.skeleton.limbs.len();
        self.skeleton.limbs.push(Limb {
            points: Vec::new(),
            widths: Vec::new(),
            order: state.order,
            tip: true,
            colour: state.colour,
        });
        match state.attached {
            Some(Attached::Open(slot)) => self.open[slot].tip = false,
            Some(Attached::Closed(limb)) => self.skeleton.limbs[limb].tip = false,
            None => {}
        }
        let slot = self.free.pop().unwrap_or_else(|| {
            self.open.push(OpenLimb::default());
            self.open.len() - 1
        });
        let o = &mut self.open[slot];
        o.limb = limb;
        o.points.extend([from, to]);
        o.widths.extend([state.width, state.width]);
        o.tip = true;
        state.open = Some(slot);
        state.attached = Some(Attached::Open(slot));
    }

    /// Hands the points of an open limb to the skeleton (allocated to
    /// size) and frees its slot; returns the limb's index.
    fn close(&mut self, slot: usize) -> usize {
        let o = &mut self.open[slot];
        let limb = &mut self.skeleton.limbs[o.limb];
        limb.points = o.points.clone();
        limb.widths = o.widths.clone();
        limb.tip = o.tip;
        o.points.clear();
        o.widths.clear();
        self.free.push(slot);
        o.limb
    }

    fn vertex(&mut self, at: DVec3, field: &str) -> Result<()> {
        let Some(poly) = self.polygons.last_mut() else {
            return Ok(());
        };
        if poly.last().is_some_and(|p| p.distance_squared(at) < 1e-24) {
            return Ok(());
        }
        poly.push(at);
        self.count(field)
    }
}

impl Turtle {
    /// A turtle drawing with `options`.
    pub fn new(options: TurtleOptions) -> Turtle {
        Turtle { options }
    }

    /// Draws a word.
    ///
    /// # Errors
    /// [`Error::Invalid`] at the system's field when the drawing would
    /// have more than `max_segments` steps, vertices and marks, or when
    /// the turtle leaves the finite numbers.
    pub fn interpret(&self, word: &Word) -> Result<Skeleton> {
        self.interpret_counted(word).map(|(skeleton, _)| skeleton)
    }

    /// Draws a word, and says how much work that took (see [`Work`]).
    ///
    /// # Errors
    /// As [`Turtle::interpret`].
    pub fn interpret_counted(&self, word: &Word) -> Result<(Skeleton, Work)> {
        let mut work = Work::default();
        let mut start = Extent::default();
        if let Some(Prune {
            scale: PruneScale::Fit(..),
            ..
        }) = self.options.prune
        {
            // First the main axis alone, every branch skipped: the drawing
            // spans at least that, so pruning starts near the scale the
            // drawing will have rather than at the first step's.
            let (_, axis, extent) = self.draw(word, true, start)?;
            work = axis;
            start = extent;
        }
        let (skeleton, all, _) = self.draw(word, false, start)?;
        work.interpreted += all.interpreted;
        work.read_ahead += all.read_ahead;
        Ok((skeleton, work))
    }

    /// Draws `word` — with `axis`, its main axis only — pruning by the
    /// extent of what is drawn and `start`.
    fn draw(&self, word: &Word, axis: bool, start: Extent) -> Result<(Skeleton, Work, Extent)> {
        let o = &self.options;
        let field = word.shared.field.as_str();
        let alphabet = &word.shared.alphabet;
        let mut commands = Vec::with_capacity(alphabet.len());
        let mut marks = Vec::with_capacity(alphabet.len());
        let mut arity = Vec::with_capacity(alphabet.len());
        for &(c, a) in &alphabet.letters {
            commands.push(command(c));
            marks.push(o.marks.contains(c));
            arity.push(usize::from(a));
        }
        let (sin, cos) = o.angle.to_radians().sin_cos();
        let tropism = o.tropism.and_then(|(t, e)| {
            let t = t.normalize_or_zero();
            (t != DVec3::ZERO && e != 0.0).then_some((t, e))
        });

        let mut state = State {
            pos: DVec3::ZERO,
            h: DVec3::Y,
            l: DVec3::NEG_X,
            u: DVec3::Z,
            width: o.width,
            colour: 0,
            order: 0,
            open: None,
            attached: None,
        };
        let mut stack: Vec<State> = Vec::new();
        // Room for the limbs up front (growing a vector of millions of
        // limbs would copy it again and again): a limb starts at a drawing
        // step after a branch, a pen-up step or a colour change, or at the
        // first step.
        let mut counts = [0usize; 256];
        for &s in &word.syms {
            counts[usize::from(s)] += 1;
        }
        let (mut steps, mut starts) = (0, 1);
        for (id, &c) in counts.iter().take(alphabet.len()).enumerate() {
            match commands[id] {
                Command::Draw | Command::DrawNoVertex => steps += c,
                Command::Push | Command::Move | Command::Colour => starts += c,
                _ => {}
            }
        }
        let limbs = steps.min(starts).min(o.max_segments);
        let mut canvas = Canvas {
            skeleton: Skeleton {
                limbs: Vec::with_capacity(limbs),
                ..Skeleton::default()
            },
            open: Vec::new(),
            free: Vec::new(),
            polygons: Vec::new(),
            used: 0,
            max: o.max_segments,
        };
        let lost = |i: usize| {
            let (c, p) = word.modules().nth(i).unwrap_or(('?', &[]));
            let p: Vec<String> = p.iter().map(f64::to_string).collect();
            Error::invalid(
                field,
                format!(
                    "the turtle's position is no longer a finite number at module {} ({c}{})",
                    i + 1,
                    if p.is_empty() {
                        String::new()
                    } else {
                        format!("({})", p.join(","))
                    }
                ),
            )
        };

        let syms = &word.syms;
        let params = &word.params;
        let mut at = 0;
        let mut work = Work::default();
        let mut extent = start;
        let mut i = 0;
        while i < syms.len() {
            if i % 4096 == 0 {
                // Millions of modules: a newer edit stops the drawing.
                crate::cancel::checkpoint()?;
            }
            let sym = syms[i];
            work.interpreted += 1;
            let s = usize::from(sym);
            let a = arity[s];
            let first = (a > 0).then(|| params[at]);
            at += a;
            if let (Some(prune), Command::Push, true) =
                (o.prune, commands[s], canvas.polygons.is_empty())
            {
                let branch = Branch {
                    word,
                    commands: &commands,
                    marks: &marks,
                    arity: &arity,
                    step: o.step,
                };
                let min = if axis {
                    Some(f64::INFINITY)
                } else {
                    extent.below(&prune)
                };
                if let Some((end, after)) =
                    min.and_then(|min| branch.small(i, at, min, axis, &mut work.read_ahead))
                {
                    // Left out whole: the turtle goes on after its `]`
                    // in the state it had before its `[`.
                    i = end + 1;
                    at = after;
                    continue;
                }
            }
            if marks[s] {
                canvas.skeleton.marks.push(Mark {
                    symbol: alphabet.letters[s].0,
                    at: state.pos,
                    heading: state.h,
                    up: state.u,
                    width: state.width,
                    order: state.order,
                });
                canvas.count(field)?;
            }
            match commands[s] {
                Command::Nothing => {}
                cmd @ (Command::Draw | Command::DrawNoVertex | Command::Move) => {
                    let from = state.pos;
                    state.pos += state.h * (first.unwrap_or(1.0) * o.step);
                    if !state.pos.is_finite() {
                        return Err(lost(i));
                    }
                    if !canvas.polygons.is_empty() || cmd == Command::Move {
                        if let Some(slot) = state.open.take() {
                            canvas.close(slot);
                        }
                        state.attached = None;
                        if cmd != Command::DrawNoVertex {
                            // A polygon traced by steps starts where the
                            // turtle stood at its first step.
                            if canvas.polygons.last().is_some_and(Vec::is_empty) {
                                canvas.vertex(from, field)?;
                            }
                            canvas.vertex(state.pos, field)?;
                        }
                    } else {
                        canvas.count(field)?;
                        if let Some(prune) = &o.prune {
                            extent.add(prune, from, state.pos);
                        }
                        match state.open {
                            Some(slot) => {
                                let limb = &mut canvas.open[slot];
                                limb.points.push(state.pos);
                                limb.widths.push(state.width);
                                // The end moved on: nothing grows from it yet.
                                limb.tip = true;
                            }
                            None => canvas.start(&mut state, from),
                        }
                    }
                    if cmd != Command::Move {
                        if let Some((t, e)) = tropism {
                            bend(&mut state, t, e);
                        }
                    }
                }
                Command::Vertex => canvas.vertex(state.pos, field)?,
                Command::Turn(axis, sign) => {
                    let (s, c) = match first {
                        Some(deg) => deg.to_radians().sin_cos(),
                        None => (sin, cos),
                    };
                    let s = s * sign;
                    match axis {
                        Axis::Up => rotate(&mut state.h, &mut state.l, s, c),
                        Axis::Left => rotate(&mut state.u, &mut state.h, s, c),
                        Axis::Heading => rotate(&mut state.l, &mut state.u, s, c),
                    }
                }
                Command::TurnAround => {
                    state.h = -state.h;
                    state.l = -state.l;
                }
                Command::Level => {
                    // ABOP: L = V × H / |V × H|, U = H × L, V pointing up.
                    let l = DVec3::Y.cross(state.h);
                    if l.length_squared() > 1e-24 {
                        state.l = l.normalize();
                        state.u = state.h.cross(state.l);
                    }
                }
                Command::Push => {
                    stack.push(state);
                    state.open = None;
                    state.order += 1;
                }
                Command::Pop => {
                    if let Some(saved) = stack.pop() {
                        if let Some(slot) = state.open {
                            canvas.close(slot);
                        }
                        state = saved;
                    }
                }
                Command::PolygonStart => canvas.polygons.push(Vec::new()),
                Command::PolygonEnd => {
                    if let Some(mut poly) = canvas.polygons.pop() {
                        if poly.len() > 1 && poly[0].distance_squared(poly[poly.len() - 1]) < 1e-24
                        {
                            poly.pop();
                        }
                        if poly.len() >= 3 {
                            canvas.skeleton.polygons.push(poly);
                        }
                    }
                }
                Command::Width => {
                    state.width = match first {
                        Some(w) => w.max(0.0),
                        None => state.width * o.width_factor,
                    };
                }
                Command::Colour => {
                    let colour = match first {
                        // Saturating: a colour index is small and ≥ 0.
                        Some(c) => c.round().clamp(0.0, f64::from(u32::MAX)) as u32,
                        None => state.colour.saturating_add(1),
                    };
                    if colour != state.colour {
                        if let Some(slot) = state.open.take() {
                            // The next limb starts where this one ends.
                            state.attached = Some(Attached::Closed(canvas.close(slot)));
                        }
                        state.colour = colour;
                    }
                }
            }
            i += 1;
        }
        if let Some(slot) = state.open {
            canvas.close(slot);
        }
        for saved in stack {
            if let Some(slot) = saved.open {
                canvas.close(slot);
            }
        }
        Ok((canvas.skeleton, work, extent))
    }
}

/// The box on the page of the limbs drawn so far (in the drawing's
/// units), for pruning a fitted drawing.
#[derive(Debug, Clone, Copy)]
struct Extent {
    min: (f64, f64),
    max: (f64, f64),
}

impl Default for Extent {
    fn default() -> Self {
        Extent {
            min: (f64::INFINITY, f64::INFINITY),
            max: (f64::NEG_INFINITY, f64::NEG_INFINITY),
        }
    }
}

impl Extent {
    /// Takes in the step from `a` to `b`, unless it is seen end on (a
    /// limb of such steps only is not drawn, so its points are not in
    /// the drawing's box).
    fn add(&mut self, prune: &Prune, a: DVec3, b: DVec3) {
        let flat = |p: DVec3| (p.dot(prune.right), -p.dot(prune.up));
        let (a, b) = (flat(a), flat(b));
        if (a.0 - b.0).hypot(a.1 - b.1) <= 1e-9 {
            return;
        }
        for (x, y) in [a, b] {
            self.min = (self.min.0.min(x), self.min.1.min(y));
            self.max = (self.max.0.max(x), self.max.1.max(y));
        }
    }

    /// The length (in the drawing's units) under which a branch is too
    /// small to draw: `min_length` over the scale, which for a fitted
    /// drawing is the one the drawing so far would be fitted at (as the
    /// drawing grows its scale only shrinks and this only grows, so no
    /// branch is left out that the finished drawing would draw). `None`
    /// while that scale is not known (nothing drawn yet, or a point).
    fn below(&self, prune: &Prune) -> Option<f64> {
        let scale = match prune.scale {
            PruneScale::Scale(s) => s,
            PruneScale::Fit(width, height) => {
                // As `motif::fitted` scales a drawing's box.
                let (w, h) = (self.max.0 - self.min.0, self.max.1 - self.min.1);
                match (w > 1e-12, h > 1e-12) {
                    (true, true) => (width / w).min(height / h),
                    (true, false) => width / w,
                    (false, true) => height / h,
                    (false, false) => return None,
                }
            }
        };
        (scale > 0.0 && scale.is_finite()).then(|| prune.min_length / scale)
    }
}

/// A word as the turtle reads it, for looking ahead through a branch.
struct Branch<'w> {
    word: &'w Word,
    commands: &'w [Command],
    marks: &'w [bool],
    arity: &'w [usize],
    step: f64,
}

impl Branch<'_> {
    /// Whether the branch whose `[` is module `open` (its parameters
    /// ending at `at`) can be left out: each pen-down run in it (a limb,
    /// at most: nested branches do not break their parent's) is shorter
    /// than `min` units, all its steps together shorter than [`SPAN`] ×
    /// `min` (so that what is left out reaches less than that past what
    /// is drawn), and it records no symbol and traces no polygon. If so,
    /// its `]` and where the parameters after it start. Reads up to where
    /// it knows, counting each module read in `read`. With `whole`, any
    /// branch can (to draw the main axis alone).
    fn small(
        &self,
        open: usize,
        mut at: usize,
        min: f64,
        whole: bool,
        read: &mut usize,
    ) -> Option<(usize, usize)> {
        let (syms, params) = (&self.word.syms, &self.word.params);
        // The pen-down run at each depth of the branch, and all its steps.
        let mut runs = vec![0.0];
        let mut travel = 0.0;
        for (j, &sym) in syms.iter().enumerate().skip(open + 1) {
            *read += 1;
            let s = usize::from(sym);
            let a = self.arity[s];
            if self.marks[s] && !whole {
                return None;
            }
            match self.commands[s] {
                Command::Push => runs.push(0.0),
                Command::Pop => {
                    runs.pop();
                    if runs.is_empty() {
                        return Some((j, at + a));
                    }
                }
                cmd @ (Command::Draw | Command::DrawNoVertex | Command::Move) => {
                    let steps = if a > 0 { params[at].abs() } else { 1.0 };
                    let length = steps * self.step;
                    travel += length;
                    let run = runs.last_mut().expect("inside the branch");
                    *run = if cmd == Command::Move { 0.0 } else { *run + length };
                    if *run >= min || travel >= SPAN * min || travel.is_nan() {
                        return None;
                    }
                }
                Command::PolygonStart | Command::PolygonEnd if !whole => return None,
                _ => {}
            }
            at += a;
        }
        // Never closed: the branch runs to the end of the word.
        None
    }
}

/// How far a branch left out may reach, in limb limits (see
/// [`Branch::small`]): ABOP 1.24a's two-level branches (`[+F[+F]F[-F]F]`
/// at n − 2, 25 steps reaching 9 apart) are left out once a limb of
/// 3 steps is too short, and a fitted drawing's scale moves by less than
/// four limb limits over its size.
const SPAN: f64 = 4.0;

/// Turns the pair `(a, b)` so that `a` moves towards `b` by the angle of
/// this sine and cosine.
fn rotate(a: &mut DVec3, b: &mut DVec3, sin: f64, cos: f64) {
    let (x, y) = (*a, *b);
    *a = x * cos + y * sin;
    *b = y * cos - x * sin;
}

/// ABOP's tropism: the frame turns about H × T by e·|H × T|, moving the
/// heading towards T.
fn bend(state: &mut State, t: DVec3, e: f64) {
    let axis = state.h.cross(t);
    let len = axis.length();
    if len < 1e-12 {
        return;
    }
    let q = DQuat::from_axis_angle(axis / len, e * len);
    // Renormalised: rotations pile up over a long branch.
    let h = (q * state.h).normalize();
    let l = (q * state.l - h * h.dot(q * state.l)).normalize();
    state.h = h;
    state.l = l;
    state.u = h.cross(l);
}
