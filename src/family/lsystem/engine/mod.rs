//! L-systems: the engine of *The Algorithmic Beauty of Plants* (grammar,
//! rewriting, 3D turtle) and the stroke-guided Sketching L-System (source 003).
//!
//! Pure: this module turns rule text and strokes into a [`Skeleton`] of 3D
//! limbs, and knows nothing of scenes, pens or pages. Projecting a skeleton
//! to the page, tapering limbs into outlines and placing it in a layer is
//! the `lsystem` family's work (`motif::lsystem`).
//!
//! Coordinates: a skeleton is in millimetres in its own right-handed frame.
//! The general turtle starts at the origin heading up (+y), its left is −x
//! and its up (towards the viewer) is +z, as in ABOP's plant figures, so
//! `+` turns left as seen from the viewer. A sketch works in the stroke's
//! own coordinates (page millimetres, y down, the page at z = 0).

use glam::DVec3;

mod expr;
mod grammar;
mod rewrite;
pub mod sketch;
#[cfg(test)]
mod tests;
mod turtle;

pub use rewrite::{LSystem, Word};
pub use turtle::{Prune, PruneScale, Turtle, TurtleOptions, Work};

/// A drawing in 3D: the limbs (pen-down runs of the turtle), the filled
/// polygons of `{ … }`, and the marks the caller asked to record.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Skeleton {
    /// Pen-down runs, in the order the turtle drew them.
    pub limbs: Vec<Limb>,
    /// Closed polygons traced between `{` and `}`.
    pub polygons: Vec<Vec<DVec3>>,
    /// Where the turtle met a symbol it was asked to record (leaves,
    /// flowers, …), in the order met.
    pub marks: Vec<Mark>,
}

/// One continuous pen-down run: a polyline with a width at every point.
/// A run ends where the pen lifts (`f`), at a branch (`[` starts a new
/// limb, `]` ends one) or at the end of the word.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Limb {
    /// At least two points.
    pub points: Vec<DVec3>,
    /// The width at each point, mm (as many as `points`).
    pub widths: Vec<f64>,
    /// Branch order: 0 for the main axis, one more per bracket (or, in a
    /// sketch, per branching off the parent).
    pub order: u32,
    /// Whether the run ends a branch: nothing grows on from its last point
    /// (where a flower or a leaf may go).
    pub tip: bool,
    /// The turtle's colour index (`'` counts it up from 0), for mapping
    /// runs to pens.
    pub colour: u32,
}

/// A recorded symbol with the turtle's state where it was met.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mark {
    /// The symbol.
    pub symbol: char,
    /// Where.
    pub at: DVec3,
    /// The turtle's heading (unit).
    pub heading: DVec3,
    /// The turtle's up (unit, at right angles to the heading).
    pub up: DVec3,
    /// The width then, mm.
    pub width: f64,
    /// Branch order then.
    pub order: u32,
}
