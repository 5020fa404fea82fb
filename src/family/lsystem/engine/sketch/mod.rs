//! The Sketching L-System (Ijiri and Igarashi; seed 003): an L-system
//! that grows along a stroke as it is drawn. This module owns the model:
//! the rules and their text ([`SketchRules`]), the growth step by step as
//! the stroke lengthens ([`Sketch`]) and its result as a [`Skeleton`].
//!
//! # The model
//!
//! The special branch `a` follows the stroke. Whenever the stroke has
//! grown by one module (measured along it), one step happens:
//!
//! 1. The pending `a` is drawn: a straight segment from the current
//!    a-node to the point one module further along the stroke, the next
//!    a-node. Every a-node lies on the stroke, a module apart in arc
//!    length (so the chord is at most a module).
//! 2. `a`'s rule is applied to that segment: its `b` and `c` branches
//!    leave it by their handles, and its one `a` becomes the next pending
//!    `a`, which waits for the stroke.
//! 3. Every `c` drawn before this step and not yet rewritten (a growing
//!    shoot) is rewritten once by `c`'s rule: it keeps its segment and its
//!    rule's branches leave it; its `c` branches are the new shoots.
//!
//! So a `c` born at step k has been rewritten n − k times after step n:
//! its recursion depth is n − k, and the oldest side branches, near the
//! stroke's start, are the deepest. A straight stroke gives the classic
//! self-similar L-system: every side branch is the same structure cut at
//! its own depth (mirrored where the sides alternate, and thinner by
//! `a`'s width ratio per step along the stroke).
//!
//! # Geometry
//!
//! Page millimetres: x right, y down, the stroke in the plane z = 0, z
//! towards the viewer; a top view (drop z) lies on the stroke.
//!
//! Every segment has a frame: its heading H and up U (unit, at right
//! angles), and its left L = H × U (on a y-down page seen from +z, the
//! viewer's left of someone walking along H). The k-th `a` (from step k)
//! heads along its chord; its up is the page normal +z rolled about H by
//! (k − 1) times the roll of `a`'s handle in `a`'s rule (0 by default: up
//! is +z and left is the page's left of the stroke; 180: the sides swap at
//! every step).
//!
//! A branch with handle (angle θ, roll φ, width ratio, length ratio, at)
//! leaves its parent at the fraction `at` of the parent's segment (1, its
//! tip, by default). Its frame is the parent's rolled by φ about H
//! (L′ = L cos φ + U sin φ, U′ = U cos φ − L sin φ) then turned by θ
//! towards L′ (heading H cos θ + L′ sin θ, up U′). So θ = 0 is collinear
//! with the parent, roll 0 leaves on the parent's left, 90 towards its up,
//! 180 on its right, and a child inherits its parent's roll: its own
//! children's rolls count from its frame. Its length and width are the
//! parent's times the ratios. An `a`'s length is the module (the stroke
//! it stands for, even where the stroke curves and its chord is shorter)
//! and `a`'s length ratio is 1, so the side branches of every step have
//! the same size, while the width multiplies by `a`'s width ratio at each
//! step.
//!
//! # The skeleton
//!
//! Every unbroken lineage is one limb, so that a drawing can smooth and
//! taper along it: the `a` chain along the stroke (limb 0, order 0), and
//! each `c` with the shoot that continues it — the first `c` of `c`'s rule
//! that leaves from the tip. Every `b` and every other `c` starts a limb of
//! its parent's order plus one. A limb's width at a point is the width of
//! the segment that starts there; at its last point, the width its lineage
//! goes on with (its segment's width times the continuing branch's width
//! ratio), or 0 where none goes on (a `b`, a `c` whose rule has no
//! continuation), so a `b` is a pointed leaflet. `tip` is true where no
//! branch leaves the limb's last point. [`Sketch::parents`] keeps the
//! tree: the limb each limb leaves from.
//!
//! # A plant, not a feather
//!
//! Three limits make the structure a plant drawn along a gesture (each
//! leaves the rewriting as it was where it does not apply):
//!
//! * **The minimum limb** ([`Sketch::with_pen`]): a branch shorter than
//!   [`MIN_LIMB_PENS`] pen widths is not drawn, and a shoot whose next
//!   segment would be shorter stops growing, so that tips never curl
//!   into scribble finer than the pen.
//! * **The trunk**: a branch segment that would come nearer the `a` chain
//!   than their half widths and the pen's width is not drawn (a shoot
//!   stops there); and where a new `a` segment comes that near an older
//!   branch, that branch is cut back to before the segment, with what
//!   grew beyond it. No branch crosses the trunk, however the stroke
//!   curves.
//! * **The page** ([`Sketch::within`]): a branch whose tip's outline
//!   would leave the page is not drawn; where the stroke itself leaves
//!   it, the sketch stops growing ([`Sketch::off_page`] says so).

mod room;
mod rules;
#[cfg(test)]
mod tests;

pub use rules::{Branch, Handle, Kind, SketchRules};

use glam::{DVec2, DVec3};

use super::{Limb, Skeleton};
use crate::{Error, Result};
use room::{BranchSegment, Room};

/// The shortest limb a sketch draws, in pen widths: what a pen draws
/// shorter than this reads as a dot, not a twig.
pub const MIN_LIMB_PENS: f64 = 4.0;

/// Sine and cosine of `deg` degrees, exact at multiples of 90° (so that
/// branches in the page plane have z exactly 0).
fn sin_cos_deg(deg: f64) -> (f64, f64) {
    let d = deg.rem_euclid(360.0);
    if d == 0.0 {
        (0.0, 1.0)
    } else if d == 90.0 {
        (1.0, 0.0)
    } else if d == 180.0 {
        (0.0, -1.0)
    } else if d == 270.0 {
        (-1.0, 0.0)
    } else {
        d.to_radians().sin_cos()
    }
}

/// A segment's orientation: heading and up, unit and at right angles.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Frame {
    heading: DVec3,
    up: DVec3,
}

impl Frame {
    fn left(&self) -> DVec3 {
        self.heading.cross(self.up)
    }

    /// Rolled by `deg` about the heading, from left towards up.
    fn rolled(&self, deg: f64) -> Frame {
        let (s, c) = sin_cos_deg(deg);
        Frame {
            heading: self.heading,
            up: self.up * c - self.left() * s,
        }
    }

    /// The frame of a branch leaving by `handle`: rolled, then turned
    /// towards the rolled left. Renormalised, so that frames deep in a
    /// lineage stay orthonormal.
    fn child(&self, handle: &Handle) -> Frame {
        let rolled = self.rolled(handle.roll);
        let (s, c) = sin_cos_deg(handle.angle);
        let heading = (rolled.heading * c + rolled.left() * s).normalize();
        let up = (rolled.up - heading * heading.dot(rolled.up)).normalize();
        Frame { heading, up }
    }
}

/// A drawn segment that its rule's branches leave from.
#[derive(Debug, Clone, Copy)]
struct Segment {
    base: DVec3,
    tip: DVec3,
    frame: Frame,
    length: f64,
    width: f64,
    /// The limb the segment ends.
    limb: usize,
    /// The index of the segment's tip in its limb.
    end: usize,
    /// The trunk node the segment leaves from, if it does.
    root: Option<usize>,
    order: u32,
}

/// The Sketching L-System growing along a stroke: extend the stroke, and
/// the structure grows by one step per module of new stroke, never
/// recomputing what exists (a step costs in proportion to the growing
/// shoots).
#[derive(Debug, Clone)]
pub struct Sketch {
    rules: SketchRules,
    /// The index in `c`'s rule of the `c` that continues its parent's limb.
    continuation: Option<usize>,
    /// What a `c` limb's width at its last point is of its last segment's:
    /// the continuation's width ratio (0 without one: the limb ends).
    c_end_ratio: f64,
    /// The handle of the `a` in `a`'s rule.
    a_handle: Handle,
    max_segments: usize,
    segments: usize,
    skeleton: Skeleton,
    parents: Vec<Option<usize>>,
    /// For each limb, the index of the point of its parent it leaves at
    /// (the tip of the parent's segment it leaves from).
    attach: Vec<usize>,
    nodes: Vec<DVec3>,
    /// The `c` segments not yet rewritten.
    shoots: Vec<Segment>,
    /// The last point of the stroke so far.
    last: Option<DVec2>,
    /// Stroke length from the last a-node to `last`, mm.
    since: f64,
    /// Width of the pending `a`.
    a_width: f64,
    /// Roll of the pending `a`'s frame about the stroke, degrees.
    a_roll: f64,
    /// Set when a step would have exceeded the budget: the sketch stays
    /// as it was before that step.
    full: bool,
    /// The shortest branch segment drawn, mm.
    min_limb: f64,
    /// What is drawn so far, for keeping the branches clear of the trunk
    /// and on the page.
    room: Room,
    /// Set when the stroke has left the page: the sketch grows no more.
    off_page: bool,
}

impl Sketch {
    /// A sketch with no stroke yet, that will refuse to grow past
    /// `max_segments` segments.
    ///
    /// # Errors
    /// [`Error::Invalid`] at `rules.field` (`.a`, `.c`, `.module`,
    /// `.width`) for rules out of range.
    pub fn new(rules: SketchRules, max_segments: usize) -> Result<Sketch> {
        rules.check()?;
        let continuation = rules
            .c
            .iter()
            .position(|b| b.kind == Kind::C && b.handle.at == 1.0);
        let a_handle = rules
            .a
            .iter()
            .find(|b| b.kind == Kind::A)
            .map(|b| b.handle)
            .ok_or_else(|| Error::invalid(&rules.field, "`a`'s rule has no `a`"))?;
        Ok(Sketch {
            c_end_ratio: continuation.map_or(0.0, |i| rules.c[i].handle.width),
            continuation,
            a_handle,
            max_segments,
            segments: 0,
            skeleton: Skeleton::default(),
            parents: Vec::new(),
            attach: Vec::new(),
            nodes: Vec::new(),
            shoots: Vec::new(),
            last: None,
            since: 0.0,
            a_width: rules.width,
            a_roll: 0.0,
            full: false,
            min_limb: 0.0,
            room: Room::new(rules.module),
            off_page: false,
            rules,
        })
    }

    /// This sketch drawn by a pen `pen_width` mm wide (0, the default:
    /// no limits from the pen): no limb shorter than [`MIN_LIMB_PENS`]
    /// pen widths, and a pen width kept clear between the trunk and the
    /// branches. Set before the stroke comes.
    pub fn with_pen(mut self, pen_width: f64) -> Sketch {
        let pen = if pen_width.is_finite() {
            pen_width.max(0.0)
        } else {
            0.0
        };
        self.min_limb = MIN_LIMB_PENS * pen;
        self.room.set_gap(pen);
        self
    }

    /// This sketch kept inside the box from `min` to `max` (page mm):
    /// every outline on it, the stroke followed only while it stays on it.
    /// Set before the stroke comes.
    pub fn within(mut self, min: DVec2, max: DVec2) -> Sketch {
        self.room.set_page(min, max);
        self
    }

    /// Whether the stroke has left the page (see [`within`](Self::within)):
    /// the sketch stopped growing at the last a-node on it.
    pub fn off_page(&self) -> bool {
        self.off_page
    }

    /// The shortest branch segment drawn, mm (see [`with_pen`](Self::with_pen)).
    pub fn min_limb(&self) -> f64 {
        self.min_limb
    }

    /// Appends `points` (page mm) to the stroke and takes a step for every
    /// module the stroke now reaches past the last a-node. The first point
    /// ever given is the first a-node; a point equal to the one before is
    /// skipped. Extending point by point gives exactly the sketch that
    /// extending with all the points at once does.
    ///
    /// Returns the number of steps taken.
    ///
    /// # Errors
    /// [`Error::Invalid`] at `rules.field` for a point that is not finite
    /// (the points before it are kept), or when a step would make the
    /// structure more than `max_segments` segments: the sketch then stays
    /// as it was after the steps before, and refuses to grow further.
    pub fn extend(&mut self, points: &[DVec2]) -> Result<usize> {
        let before = self.steps();
        let module = self.rules.module;
        for &p in points {
            if self.full {
                return Err(self.budget_error());
            }
            if self.off_page {
                break;
            }
            if !p.is_finite() {
                return Err(Error::invalid(
                    &self.rules.field,
                    format!("a point of the stroke is not finite: {p}"),
                ));
            }
            let Some(from) = self.last else {
                self.last = Some(p);
                self.nodes.push(p.extend(0.0));
                self.off_page = !self.room.on_page(p.extend(0.0), self.a_width);
                continue;
            };
            let length = from.distance(p);
            if length == 0.0 {
                continue;
            }
            let direction = (p - from) / length;
            // How far along this piece of stroke the last node stands.
            let mut along = 0.0;
            while self.since + (length - along) >= module {
                along += module - self.since;
                let node = if along >= length {
                    p
                } else {
                    from + direction * along
                };
                if !self.room.on_page(node.extend(0.0), self.a_width) {
                    self.off_page = true;
                    return Ok(self.steps() - before);
                }
                self.step(node.extend(0.0), direction.extend(0.0))?;
                self.since = 0.0;
            }
            // `along` may pass `length` by a rounding error.
            self.since += (length - along).max(0.0);
            self.last = Some(p);
        }
        Ok(self.steps() - before)
    }

    /// The steps taken so far: the number of `a` segments.
    pub fn steps(&self) -> usize {
        self.nodes.len().saturating_sub(1)
    }

    /// The structure so far (see the [module documentation](self)).
    pub fn skeleton(&self) -> Skeleton {
        self.skeleton.clone()
    }

    /// For each limb of [`skeleton`](Self::skeleton), the limb it leaves
    /// from (`None` for the `a` chain): the branching structure that the
    /// skeleton's flat list of limbs leaves out.
    pub fn parents(&self) -> &[Option<usize>] {
        &self.parents
    }

    /// The a-nodes: the stroke's first point, then one per step, each a
    /// module further along the stroke (z = 0).
    pub fn a_nodes(&self) -> &[DVec3] {
        &self.nodes
    }

    /// The segments drawn so far.
    pub fn segments(&self) -> usize {
        self.segments
    }

    fn budget_error(&self) -> Error {
        Error::invalid(
            &self.rules.field,
            format!(
                "the sketch would have more than {} segments (the limit) after {} steps: \
                 use a shorter stroke, a longer module, or rules that branch less",
                self.max_segments,
                self.steps()
            ),
        )
    }

    /// One step: the pending `a` drawn up to `node` (reached along the
    /// stroke's `direction`), `a`'s rule applied to it and every shoot
    /// rewritten.
    fn step(&mut self, node: DVec3, direction: DVec3) -> Result<()> {
        let new = (self.shoots.len())
            .saturating_mul(self.rules.c.len())
            .saturating_add(self.rules.a.len());
        if self.segments.saturating_add(new) > self.max_segments {
            self.full = true;
            return Err(self.budget_error());
        }
        let from = self.nodes[self.nodes.len() - 1];
        let chord = node - from;
        // A stroke that doubles back may bring the node onto the last: then
        // the stroke's own direction stands in for the chord's.
        let heading = if chord.length() > 1e-9 * self.rules.module {
            chord.normalize()
        } else {
            direction
        };
        let a = Segment {
            base: from,
            tip: node,
            frame: Frame {
                heading,
                up: DVec3::Z,
            }
            .rolled(self.a_roll),
            length: self.rules.module,
            width: self.a_width,
            limb: 0,
            end: self.nodes.len(),
            root: Some(self.nodes.len()),
            order: 0,
        };
        let next_width = self.a_width * self.a_handle.width;
        if self.nodes.len() == 1 {
            let at_tip = self
                .rules
                .a
                .iter()
                .any(|b| b.kind != Kind::A && b.handle.at == 1.0);
            self.new_limb(vec![from, node], vec![self.a_width, next_width], 0, None, 0);
            self.skeleton.limbs[0].tip = !at_tip;
        } else {
            let chain = &mut self.skeleton.limbs[0];
            chain.points.push(node);
            chain.widths.push(next_width);
        }
        self.segments += 1;
        self.nodes.push(node);
        let crossed = self.room.add_trunk(from, node, a.width, a.end);
        self.cut(&crossed);
        self.a_width = next_width;
        self.a_roll = (self.a_roll + self.a_handle.roll).rem_euclid(360.0);

        let old = std::mem::take(&mut self.shoots);
        let rules = std::mem::take(&mut self.rules.a);
        self.sprout(&a, &rules, false);
        self.rules.a = rules;
        let rules = std::mem::take(&mut self.rules.c);
        for shoot in &old {
            self.sprout(shoot, &rules, true);
        }
        self.rules.c = rules;
        Ok(())
    }

    /// The branches `rule` sends from `parent` (but its `a`, which waits
    /// for the stroke); `rewriting_c` says whether the parent is a `c`,
    /// whose continuation extends its limb.
    fn sprout(&mut self, parent: &Segment, rule: &[Branch], rewriting_c: bool) {
        let continuation = self.continuation.filter(|_| rewriting_c);
        for (i, b) in rule.iter().enumerate() {
            if b.kind == Kind::A {
                continue;
            }
            let h = &b.handle;
            let base = if h.at == 1.0 {
                parent.tip
            } else {
                parent.base.lerp(parent.tip, h.at)
            };
            let frame = parent.frame.child(h);
            let length = parent.length * h.length;
            let width = parent.width * h.width;
            let tip = base + frame.heading * length;
            // A branch on the trunk leaves from the node it stands by; one
            // at the base of a parent that leaves the trunk, from its node.
            let root = if !rewriting_c || h.at == 0.0 {
                parent.root
            } else {
                None
            };
            let room = length >= self.min_limb
                && self.room.on_page(tip, width)
                && self.room.clear_of_trunk(base, tip, width, root);
            if !room {
                continue;
            }
            let end_width = match b.kind {
                Kind::C => width * self.c_end_ratio,
                _ => 0.0,
            };
            let (limb, end) = if continuation == Some(i) {
                let limb = &mut self.skeleton.limbs[parent.limb];
                limb.points.push(tip);
                limb.widths.push(end_width);
                (parent.limb, parent.end + 1)
            } else {
                let limb = self.new_limb(
                    vec![base, tip],
                    vec![width, end_width],
                    parent.order + 1,
                    Some(parent.limb),
                    parent.end,
                );
                (limb, 1)
            };
            self.room
                .add_branch(base, tip, width, BranchSegment { limb, end, root });
            if h.at == 1.0 && continuation.is_none() {
                self.skeleton.limbs[parent.limb].tip = false;
            }
            if b.kind == Kind::C {
                self.shoots.push(Segment {
                    base,
                    tip,
                    frame,
                    length,
                    width,
                    limb,
                    end,
                    root,
                    order: if limb == parent.limb {
                        parent.order
                    } else {
                        parent.order + 1
                    },
                });
            }
            self.segments += 1;
        }
    }

    fn new_limb(
        &mut self,
        points: Vec<DVec3>,
        widths: Vec<f64>,
        order: u32,
        parent: Option<usize>,
        attach: usize,
    ) -> usize {
        self.skeleton.limbs.push(Limb {
            points,
            widths,
            order,
            tip: true,
            ..Limb::default()
        });
        self.parents.push(parent);
        self.attach.push(attach);
        self.skeleton.limbs.len() - 1
    }

    /// Cuts each branch segment in `crossed` off its limb, with the rest
    /// of the limb beyond it and every branch that grew from what is cut:
    /// a limb keeps its points before the cut (none: it is gone), and
    /// the shoots on what is cut stop growing.
    fn cut(&mut self, crossed: &[BranchSegment]) {
        if crossed.is_empty() {
            return;
        }
        let limbs = self.skeleton.limbs.len();
        // How many points each limb keeps (all where it is not cut).
        let mut kept: Vec<Option<usize>> = vec![None; limbs];
        // What an earlier cut took is gone already.
        let standing = crossed
            .iter()
            .filter(|c| self.skeleton.limbs[c.limb].points.len() > c.end);
        for c in standing {
            let k = kept[c.limb].get_or_insert(c.end);
            *k = (*k).min(c.end);
        }
        // A limb comes after its parent, so one pass carries a cut on to
        // the branches beyond it, and to theirs.
        let first = crossed.iter().map(|c| c.limb).min().unwrap_or(limbs);
        for i in first..limbs {
            if let Some(p) = self.parents[i] {
                if kept[p].is_some_and(|k| self.attach[i] >= k) {
                    kept[i] = Some(0);
                }
            }
            if let Some(k) = kept[i] {
                let limb = &mut self.skeleton.limbs[i];
                limb.points.truncate(k);
                limb.widths.truncate(k);
                // A cut end is no tip for a flower.
                limb.tip = false;
            }
        }
        let limbs = &self.skeleton.limbs;
        self.shoots
            .retain(|s| limbs[s.limb].points.len() > s.end);
    }
}
