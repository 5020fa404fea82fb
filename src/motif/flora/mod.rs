//! Flowers, leaves and background tiles as vector motifs (SPEC §1.5, §1.6).
//!
//! The source pasted bitmap images; moyo draws every motif as Bézier paths
//! so a plotter can draw it and a cutter can cut it. A motif is drawn once
//! in *motif units* and then placed with an affine map:
//!
//! * the drawing fills the box `[-0.5, 0.5] × [-0.5, 0.5]` (width and height
//!   1), so a placement scales it straight to its width and height in mm;
//! * it is **upright**: its top is towards −y (up the page, y points down);
//! * its [`Drawing::anchor`] is the point that sits on the tree: the centre
//!   of a flower, the stem end of a leaf (bottom centre, `(0, 0.5)`).
//!
//! A drawing has a closed **outline** — the shape that hides what lies
//! behind it and the line a cutter cuts — and **details**: inner lines
//! (petal edges, veins, stamens) drawn on top. [`Drawing::to_path`] joins
//! them into one path, outline first, with every closed subpath wound like
//! the outline, so the non-zero area of the whole path is exactly the area
//! of the outline: details never punch holes into what the motif hides.
//!
//! Randomness (`jitter`) comes from the caller's stream, so each placed
//! motif varies a little and the same seed gives the same drawing.

mod flowers;
mod leaves;
mod tiles;

use kurbo::{Affine, BezPath, PathEl, Point, Shape};

use crate::rng::RandomStream;
use crate::spec::MotifKind;

/// A motif drawn in motif units (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Drawing {
    /// Closed subpaths bounding the motif.
    pub outline: BezPath,
    /// Inner lines, open or closed, inside the outline.
    pub details: BezPath,
    /// The point placed on the tree (flower centre, leaf stem end).
    pub anchor: Point,
    /// The motif's natural height divided by its width: a placement given
    /// only a width gets height `width × aspect`.
    pub aspect: f64,
}

/// How one motif instance is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotifParams {
    /// Petal (or lobe, needle, leaf) count; `None` is the kind's default.
    pub petals: Option<u32>,
    /// Random variation, 0 (none) – 1 (strong): petal lengths, angles.
    pub jitter: f64,
}

impl MotifParams {
    /// The kind's default count, no jitter.
    pub const DEFAULT: MotifParams = MotifParams {
        petals: None,
        jitter: 0.0,
    };
}

impl Default for MotifParams {
    fn default() -> Self {
        MotifParams::DEFAULT
    }
}

/// Draws a built-in motif. Draws numbers from `rng` only when
/// `params.jitter > 0`.
pub fn draw(kind: MotifKind, params: &MotifParams, rng: &mut RandomStream) -> Drawing {
    let d = match kind {
        MotifKind::Ume => flowers::ume(params, rng),
        MotifKind::Sakura => flowers::sakura(params, rng),
        MotifKind::Kiku => flowers::kiku(params, rng),
        MotifKind::Tsubaki => flowers::tsubaki(params, rng),
        MotifKind::Kikyo => flowers::kikyo(params, rng),
        MotifKind::Botan => flowers::botan(params, rng),
        MotifKind::Momiji => leaves::momiji(params, rng),
        MotifKind::Matsu => leaves::matsu(params, rng),
        MotifKind::Take => leaves::take(params, rng),
        MotifKind::Leaf => leaves::leaf(params, rng),
        MotifKind::Circle => tiles::circle(),
        MotifKind::Seigaiha => tiles::seigaiha(params),
        MotifKind::Kikko => tiles::kikko(params),
        MotifKind::Shippo => tiles::shippo(params),
    };
    d.normalised()
}

impl Drawing {
    /// The motif as one path mapped by `placement`: the outline's
    /// subpaths, then the details (see the module docs for the winding).
    pub fn to_path(&self, placement: Affine) -> BezPath {
        let mut out = placement * self.outline.clone();
        for el in (placement * self.details.clone()).elements() {
            out.push(*el);
        }
        out
    }

    /// Winds every closed subpath like the first outline subpath (see the
    /// module docs).
    fn normalised(self) -> Drawing {
        let sign = subpaths(&self.outline)
            .first()
            .map_or(1.0, |s| s.area().signum());
        Drawing {
            outline: wound(&self.outline, sign),
            details: wound(&self.details, sign),
            anchor: self.anchor,
            aspect: self.aspect,
        }
    }
}

/// The subpaths of a path.
fn subpaths(path: &BezPath) -> Vec<BezPath> {
    let mut out: Vec<BezPath> = Vec::new();
    for el in path.elements() {
        if matches!(el, PathEl::MoveTo(_)) || out.is_empty() {
            out.push(BezPath::new());
        }
        if let Some(last) = out.last_mut() {
            last.push(*el);
        }
    }
    out
}

/// True when a subpath ends with a close-path or where it started.
fn is_closed(sub: &BezPath) -> bool {
    let els = sub.elements();
    if matches!(els.last(), Some(PathEl::ClosePath)) {
        return true;
    }
    match (els.first(), els.last().and_then(PathEl::end_point)) {
        (Some(PathEl::MoveTo(a)), Some(b)) => a.distance(b) < 1e-9,
        _ => false,
    }
}

/// `path` with every closed subpath whose signed area has the other sign
/// than `sign` reversed.
fn wound(path: &BezPath, sign: f64) -> BezPath {
    let mut out = BezPath::new();
    for sub in subpaths(path) {
        let sub = if is_closed(&sub) && sub.area() * sign < 0.0 {
            sub.reverse_subpaths()
        } else {
            sub
        };
        out.extend(sub.elements().iter().copied());
    }
    out
}

#[cfg(test)]
mod tests;
