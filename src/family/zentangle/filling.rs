//! The filling loop (docs/SPEC.md §2.4, the paper's §5.3) in vector form: the
//! white regions are exact regions, each with its seed and its largest
//! inscribed circle (found once, when the region is made); a step takes
//! the region whose circle is largest, draws the procedure its seed names
//! only inside it (`compose`), and puts back the white pieces left, each
//! with a seed — the one the mark it lies in was given, or its parent's.
//! Black is finished. A step touches one region and the pieces it makes,
//! whatever the number of regions (a heap keeps them by circle).
//!
//! Beyond the paper (which drew into a frame buffer, where more ink is
//! only more black), a pen has a limit: a mark that would take a square
//! millimetre past [`MAX_INK`] times solid ink is left out, so whirls stop
//! before they converge and small elements stop piling up (`ink`).

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use kurbo::{BezPath, Point, Shape as _};

use super::compose::compose;
use super::element::{Mark, Paint};
use super::choice::{choose, Choice};
use super::procedure::{draw, seed_group, Allowed, Drawn, Target, G1};
use super::tangle::Tangle;
use crate::error::{Error, Result};
use crate::family::zentangle::ffd::Lattice;
use crate::geom::polylabel::pole_of_inaccessibility;
use crate::geom::region::Region;
use crate::geom::TOLERANCE;
use super::ink::{Cells, Ink};
use crate::rng::RandomStream;

/// No square millimetre gets more than this many times the ink that
/// covers it solid (for the layer's pen), by the loop's count: a mark's
/// line, a black part's area over its hatch spacing. The plot draws up to
/// about a sixth more than that count where elements are a millimetre
/// across (the joins between hatch lines, outlines a little apart from
/// their neighbours'), so this stays that far under the 2× every template
/// is held to after the pen stage (`tests/pen_stage.rs`).
pub(super) const MAX_INK: f64 = 1.7;

/// How many steps drawing nothing a region is given before it is left
/// white. Among the templates a region that drew at all needed at most
/// 11 (a ring-shaped section of `zentangle-geometric`, where most
/// procedures place nothing); one that draws nothing under the ink limit
/// may never draw (`zentangle-1` at 1,000 steps tried one 135,000 times
/// before the loop gave up retrying).
pub(super) const TRIES: u32 = 16;

/// A white region waiting to be filled.
#[derive(Debug, Clone)]
struct Area {
    region: Region,
    /// The procedure it calls; `None`: any (the blank page's seed, G1).
    seed: Option<u32>,
    pole: Point,
    radius: f64,
    /// How much more (or less) black its procedure paints than the
    /// paper's (1 without tone control).
    black: f64,
    /// How deep it lies in tangles: 0 for a section, 1 inside an element
    /// of a section's tangle, …
    depth: u32,
    /// Its place in the queue (see [`Filling::queue`]).
    key: u64,
    /// The steps tried in it that drew nothing.
    failed: u32,
}

/// What one step drew.
#[derive(Debug, Clone, Default)]
pub(super) struct Step {
    /// The procedure drawn.
    pub(super) procedure: Option<u32>,
    /// The visible lines, inside the region drawn in.
    pub(super) strokes: Vec<BezPath>,
    /// The black parts, finished.
    pub(super) black: Vec<Region>,
}

/// How the loop draws.
#[derive(Clone, Copy)]
pub(super) struct Settings<'a> {
    /// Element size as a fraction of √(box area).
    pub(super) scale: f64,
    /// Regions narrower than this (inscribed radius, mm) are left white.
    pub(super) smallest: f64,
    /// Element deformation (1: the paper's).
    pub(super) wobble: f64,
    /// Per-stroke bending, mm (0: none).
    pub(super) hand: f64,
    /// Every line drawn a second time, bent by up to this, mm (0: once).
    pub(super) retrace: f64,
    /// The pen's width, mm.
    pub(super) pen: f64,
    /// Pieces of an element's line shorter than this (mm) are dropped
    /// where they end on the edge of the region drawn in.
    pub(super) fragment: f64,
    /// How far apart black parts are hatched, mm (`None`: filled, no
    /// lines).
    pub(super) hatch: Option<f64>,
    /// How often lattices follow the outline (0–1).
    pub(super) follow: f64,
    /// How deep ML plants branch (0: a single stem).
    pub(super) branching: u32,
    /// The target darkness (0–1) at a point, with how strongly it steers
    /// the loop (0–1); `None`: the paper's even tone.
    pub(super) tone: Option<(&'a dyn Fn(Point) -> f64, f64)>,
    /// One tangle a section, chosen so; `None`: the paper's sampler,
    /// a pattern in every white piece.
    pub(super) choice: Option<Choice<'a>>,
    /// The deepest nesting drawn in (`u32::MAX`: no limit).
    pub(super) depth: u32,
}

/// The loop's state.
pub(super) struct Filling<'a> {
    areas: Vec<Option<Area>>,
    /// By inscribed radius times the tone's weight (as ordered bits, both
    /// being ≥ 0), the oldest first among equals.
    queue: BinaryHeap<(u64, Reverse<usize>)>,
    allowed: Allowed,
    settings: Settings<'a>,
    /// The per-stroke bending's own numbers, so that turning it on
    /// changes how the lines are drawn, not what is drawn.
    hand: RandomStream,
    /// The ink drawn so far.
    ink: Ink,
    /// How many times a region was drawn in, whether or not the step
    /// kept a mark (the loop's work, as a count).
    attempts: usize,
}

impl<'a> Filling<'a> {
    /// The blank `regions` (each a white region of its own, as the
    /// sections a string makes), split by `lines` (drawn as the first
    /// step); `hand` draws the per-stroke bending.
    pub(super) fn new(
        regions: &[Region],
        lines: Vec<BezPath>,
        allowed: Allowed,
        settings: Settings<'a>,
        hand: RandomStream,
    ) -> Result<(Filling<'a>, Step)> {
        let pen = settings.pen;
        let mut filling = Filling {
            areas: Vec::new(),
            queue: BinaryHeap::new(),
            allowed,
            settings,
            hand,
            ink: Ink::new(pen, MAX_INK, settings.hatch),
            attempts: 0,
        };
        let marks: Vec<Mark> = lines
            .into_iter()
            .map(|path| Mark {
                path,
                paint: Paint::Line,
            })
            .collect();
        let mut step = Step::default();
        for region in regions {
            // The user's lines are drawn whatever is left of them.
            let composed = compose(region, &marks, pen, flattening(pen), 0.0)?;
            for piece in composed.white {
                filling.push(piece.region, None, 0);
            }
            step.strokes.extend(composed.strokes);
            step.black.extend(composed.black);
        }

        // The lines are the user's: drawn whatever their ink.
        let drawn = ink_of(&step.strokes, &step.black);
        filling.ink.add(&drawn);
        Ok((filling, step))
    }

    /// With one tangle a section: gives each section waiting (all are,
    /// before the first step) the tangle the settings' choice picks for
    /// it.
    pub(super) fn choose_tangles(&mut self, rng: &mut RandomStream) {
        let Some(choice) = self.settings.choice else {
            return;
        };
        let waiting: Vec<usize> = (0..self.areas.len())
            .filter(|&i| self.areas[i].is_some())
            .collect();
        let sections: Vec<Region> = waiting
            .iter()
            .filter_map(|&i| self.areas[i].as_ref().map(|a| a.region.clone()))
            .collect();
        let poles: Vec<Point> = waiting
            .iter()
            .filter_map(|&i| self.areas[i].as_ref().map(|a| a.pole))
            .collect();
        let tone = self.settings.tone.map(|(t, _)| t);
        let tangles = choose(
            &sections,
            &poles,
            &self.allowed,
            &choice,
            tone,
            self.settings.pen,
            rng,
        );
        for (&i, p) in waiting.iter().zip(tangles) {
            if let Some(a) = &mut self.areas[i] {
                a.seed = Some(p);
            }
        }
    }

    fn push(&mut self, region: Region, seed: Option<u32>, depth: u32) {
        if depth > self.settings.depth {
            return;
        }
        let precision = precision(&region, self.settings.pen);
        let Some((pole, radius)) = pole_of_inaccessibility(&region, precision) else {
            return;
        };
        // Tone control: a region counts as narrower where the target is
        // light, so it waits, and stays white once it counts as too
        // narrow; where it is dark, black is likelier.
        let (weight, black) = match self.settings.tone {
            None => (1.0, 1.0),
            Some((tone, contrast)) => {
                let dark = tone(pole).clamp(0.0, 1.0);
                (
                    1.0 - contrast + contrast * dark,
                    1.0 - contrast + contrast * 2.0 * dark,
                )
            }
        };
        if radius * weight < self.settings.smallest {
            return;
        }
        let id = self.areas.len();
        let key = (radius * weight).to_bits();
        self.areas.push(Some(Area {
            region,
            seed,
            pole,
            radius,
            black,
            depth,
            key,
            failed: 0,
        }));
        self.queue.push((key, Reverse(id)));
    }

    /// The region the next automatic step will draw in, and the radius
    /// of its largest inscribed circle (the widest region, without tone
    /// control).
    #[cfg(test)]
    pub(super) fn widest(&self) -> Option<(Region, f64)> {
        let mut queue = self.queue.clone();
        while let Some((_, Reverse(id))) = queue.pop() {
            if let Some(a) = &self.areas[id] {
                return Some((a.region.clone(), a.radius));
            }
        }
        None
    }

    /// Each mark followed by its line drawn again, bent by up to
    /// `retrace` mm: a pen going over its line a second time, which
    /// thickens it unevenly (line weight by hand). The copies paint
    /// nothing and call nothing.
    fn retraced(&mut self, drawn: Drawn) -> Result<Drawn> {
        let mut out = Drawn::default();
        for (m, seed) in drawn.marks.into_iter().zip(drawn.seeds) {
            let again = Mark {
                path: m.path.clone(),
                paint: Paint::Line,
            };
            let again = by_hand(&again, self.settings.retrace, &mut self.hand)?;
            out.marks.extend([m, again]);
            out.seeds.extend([seed, None]);
        }
        Ok(out)
    }

    /// The marks of `drawn` that fit under the ink limit, in order, each
    /// counted with all its line (and hatch) as if nothing covered it: a
    /// mark that would take a cell past the limit is left out, with its
    /// seed.
    fn within_ink(&mut self, drawn: Drawn) -> Drawn {
        let mut kept = Drawn::default();
        let mut pending = Cells::default();
        for (m, seed) in drawn.marks.into_iter().zip(drawn.seeds) {
            let mut cells = Cells::default();
            cells.line(&m.path);
            if m.paint == Paint::Black {
                cells.black(&m.path);
            }
            if self.ink.fits(&cells) {
                self.ink.add(&cells);
                pending.merge(cells);
                kept.marks.push(m);
                kept.seeds.push(seed);
            }
        }
        // What is drawn of them is counted once composed.
        self.ink.remove(&pending);
        kept
    }

    /// Whether `piece` is open as wide as half a region of inscribed
    /// radius `radius`.
    fn is_open(&self, piece: &Region, radius: f64) -> bool {
        pole_of_inaccessibility(piece, precision(piece, self.settings.pen))
            .is_some_and(|(_, r)| r >= 0.5 * radius)
    }

    /// The white regions left that are wide enough to draw in.
    pub(super) fn open(&self) -> usize {
        self.areas.iter().flatten().count()
    }

    /// How many times a region was drawn in so far, by the loop or by
    /// hand, counting the tries that drew nothing.
    #[cfg(test)]
    pub(super) fn attempts(&self) -> usize {
        self.attempts
    }

    /// How many white regions wide enough to draw in were made so far.
    #[cfg(test)]
    pub(super) fn made(&self) -> usize {
        self.areas.len()
    }

    /// One automatic step: the widest region that can take one gets the
    /// procedure its seed names. A step that draws nothing (every mark
    /// over the ink limit, or none the procedure can place there) is not
    /// a step: the region is tried again — the procedure, its elements
    /// and their sizes are drawn anew — up to [`TRIES`] times, then
    /// retired white, so that a region no procedure fits cannot hold the
    /// loop. `None` when no region is left that can take a step.
    pub(super) fn step(&mut self, rng: &mut RandomStream) -> Result<Option<Step>> {
        while let Some((_, Reverse(id))) = self.queue.pop() {
            if let Some(mut area) = self.areas[id].take() {
                let procedure = match area.seed {
                    Some(p) if self.allowed.procedures.contains(&p) => p,
                    // A seed left out: an allowed one of the same group.
                    Some(p) => self.allowed.pick(&[p], rng),
                    None => self.allowed.pick(G1, rng),
                };
                if let Some(step) = self.draw_in(&area, procedure, rng)? {
                    return Ok(Some(step));
                }
                area.failed += 1;
                if area.failed < TRIES {
                    self.queue.push((area.key, Reverse(id)));
                    self.areas[id] = Some(area);
                }
            }
        }
        Ok(None)
    }

    /// A manual step: the region holding `at` gets `procedure`.
    ///
    /// # Errors
    /// [`Error::Invalid`] (field `at`) when no white region holds the
    /// point.
    pub(super) fn step_at(
        &mut self,
        at: Point,
        procedure: u32,
        rng: &mut RandomStream,
    ) -> Result<Step> {
        let id = self
            .areas
            .iter()
            .position(|a| a.as_ref().is_some_and(|a| a.region.contains(at)))
            .ok_or_else(|| {
                Error::invalid(
                    "at",
                    format!(
                        "({}, {}) lies in no white region wide enough to draw in (it may be \
                         on a line, in black, or in a region narrower than `smallest`)",
                        at.x, at.y
                    ),
                )
            })?;
        let area = self.areas[id].take().expect("found alive");
        // A manual step is the user's: drawn even when it draws nothing.
        Ok(self.draw_in(&area, procedure, rng)?.unwrap_or(Step {
            procedure: Some(procedure),
            ..Step::default()
        }))
    }

    /// Draws `procedure` in `area` and puts back the white pieces left;
    /// `None` when the step drew nothing.
    fn draw_in(
        &mut self,
        area: &Area,
        procedure: u32,
        rng: &mut RandomStream,
    ) -> Result<Option<Step>> {
        // Each try draws a tangle and composes it with the region: the
        // unit of work a newer edit waits for.
        crate::cancel::checkpoint()?;
        self.attempts += 1;
        let b = area.region.bounds();
        let Settings {
            scale,
            wobble,
            hand,
            pen,
            follow,
            branching,
            ..
        } = self.settings;
        let target = Target {
            region: &area.region,
            pole: area.pole,
            radius: area.radius,
            size: scale * b.area().sqrt(),
            wobble,
            pen,
            follow,
            branching,
            black: area.black,
            tone: self.settings.tone,
        };
        let mut drawn = draw(procedure, &target, &self.allowed, rng)?;
        if hand > 0.0 {
            for m in &mut drawn.marks {
                *m = by_hand(m, hand, &mut self.hand)?;
            }
        }
        if self.settings.retrace > 0.0 {
            drawn = self.retraced(drawn)?;
        }
        let drawn = self.within_ink(drawn);
        crate::cancel::checkpoint()?;
        let composed = compose(
            &area.region,
            &drawn.marks,
            pen,
            flattening(pen),
            self.settings.fragment,
        )?;
        if composed.strokes.is_empty() && composed.black.is_empty() {
            return Ok(None);
        }
        let ink = ink_of(&composed.strokes, &composed.black);
        self.ink.add(&ink);
        // A named tangle fills its section: what it leaves white stays so.
        let white = if Tangle::from_id(procedure).is_some() {
            Vec::new()
        } else {
            composed.white
        };
        // One tangle a section: all its elements hold the same nested
        // tangle, of the seed group the procedure names.
        let nested = match (&self.settings.choice, seed_group(procedure)) {
            (Some(_), Some(group)) => Some(self.allowed.pick(group, rng)),
            _ => None,
        };
        for piece in white {
            let own = piece.inside.and_then(|i| drawn.seeds[i]);
            if self.settings.choice.is_some() {
                // The tangle's own white, between and inside its elements,
                // stays white; only what they nest is drawn in, and what
                // it left open as wide as half the section, where the
                // same tangle goes on (a band along the edge goes round
                // again inside).
                if own.is_some() {
                    self.push(piece.region, nested, area.depth + 1);
                } else if piece.inside.is_none() && self.is_open(&piece.region, area.radius) {
                    self.push(piece.region, Some(procedure), area.depth);
                }
                continue;
            }
            // Inside a white mark: the seed the mark was given. Elsewhere
            // the piece keeps its region's seed, as its pixels would in the
            // paper's frame buffer (the blank page's stays "any").
            let depth = area.depth + u32::from(own.is_some());
            self.push(piece.region, own.or(area.seed), depth);
        }
        Ok(Some(Step {
            procedure: Some(procedure),
            strokes: composed.strokes,
            black: composed.black,
        }))
    }
}

/// The ink of `strokes` and of hatching `black` (whose outlines are
/// strokes of their own marks, or of the lines around the region).
fn ink_of(strokes: &[BezPath], black: &[Region]) -> Cells {
    let mut cells = Cells::default();
    for s in strokes {
        cells.line(s);
    }
    for b in black {
        cells.black(b.path());
    }
    cells
}

/// `mark` bent by a deformation of its own that moves no point more than
/// about `amount` mm: a 4×4 lattice over its box (grown by `amount`, so a
/// straight line has a box to bend in) whose control points move up to
/// `amount`.
pub(super) fn by_hand(mark: &Mark, amount: f64, rng: &mut RandomStream) -> Result<Mark> {
    let b = mark.path.bounding_box().inflate(amount, amount);
    // A control point moves up to rx/2 lattice cells of width/3.
    let lattice = Lattice::jittered(b, 6.0 * amount / b.width(), 6.0 * amount / b.height(), rng)?;
    Ok(mark.deformed(&lattice, TOLERANCE))
}

/// How closely white pieces, black parts and ink follow the curves (mm):
/// an eighth of the pen's width, far inside the line that covers the
/// edge, and a quarter of the vertices the output tolerance would take.
fn flattening(pen: f64) -> f64 {
    pen / 8.0
}

/// How exactly a region's widest inscribed circle is found (mm): to a
/// quarter of the pen, or 0.5 % of the region's smaller side when that is
/// more — enough to tell which region is widest, and the search costs
/// grow with the inverse square of it.
pub(super) fn precision(region: &Region, pen: f64) -> f64 {
    let b = region.bounds();
    (pen / 4.0).max(0.005 * b.width().min(b.height()))
}
