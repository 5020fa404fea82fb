//! Turning a skeleton into paths (docs/SPEC.md §1.3): smooth centre curves, then
//! either a tapered closed outline per limb or a single centre stroke.
//!
//! * A limb of two points becomes a cubic Bézier bowed towards the limb's
//!   own side by `bow` × its length ([000] eqs. 5–7); trunks have no side
//!   and stay straight.
//! * A limb of three or more points becomes a natural cubic spline through
//!   them.
//! * Widths fall linearly along each limb from its base width to the tip
//!   width; a limb starts at 85% of its parent's width where it leaves it,
//!   so branches are never thicker than what carries them.

use kurbo::BezPath;

use super::bow::bowed_cubic;
use super::skeleton::{Limb, Skeleton};
use crate::geom::{natural_spline, tapered_outline};
use crate::motif::limb::THIN;
use crate::spec::LimbStyle;

/// How limbs are drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LimbLook {
    /// Outline or centre stroke.
    pub style: LimbStyle,
    /// Width at the root of the trunk, mm.
    pub width: f64,
    /// Width at every tip, mm.
    pub tip_width: f64,
    /// Bow of two-point limbs, fraction of their length.
    pub bow: f64,
    /// Width of the pen that draws the tree, mm: an outline narrower than
    /// [`THIN`] of it at its base is drawn as the limb's centre curve (its
    /// two sides would run into one blot). 0: always as asked.
    pub pen_width: f64,
}

/// How much thinner a limb starts than its parent at the junction.
const CHILD_WIDTH: f64 = 0.85;

/// The smooth centre curve of a limb.
pub(super) fn centre_curve(limb: &Limb, bow: f64) -> BezPath {
    match (limb.points.as_slice(), limb.side) {
        ([a, b], Some(side)) => {
            let mut p = BezPath::new();
            p.move_to(*a);
            let c = bowed_cubic(*a, *b, bow, side);
            p.curve_to(c.p1, c.p2, c.p3);
            p
        }
        (pts, _) => natural_spline(pts),
    }
}

/// One path per limb, in skeleton order: closed outlines, or open centre
/// curves (every limb with [`LimbStyle::Stroke`], the thin ones with
/// [`LimbStyle::Outline`]).
pub(crate) fn limb_paths(skeleton: &Skeleton, look: &LimbLook) -> Vec<BezPath> {
    let widths = base_widths(skeleton, look);
    skeleton
        .limbs
        .iter()
        .zip(widths)
        .map(|(limb, base)| {
            let centre = centre_curve(limb, look.bow);
            match look.style {
                LimbStyle::Stroke => centre,
                LimbStyle::Outline if base < THIN * look.pen_width => centre,
                LimbStyle::Outline => tapered_outline(&centre, base, look.tip_width.min(base)),
            }
        })
        .collect()
}

/// Base width of every limb: the trunk's is `look.width`; a child's is
/// `CHILD_WIDTH` × its parent's width at the junction vertex (measured by
/// polyline length along the parent).
fn base_widths(skeleton: &Skeleton, look: &LimbLook) -> Vec<f64> {
    let mut widths: Vec<f64> = Vec::with_capacity(skeleton.limbs.len());
    for limb in &skeleton.limbs {
        let w = match limb.parent {
            None => look.width,
            Some(at) => {
                let parent = &skeleton.limbs[at.limb];
                let pw = widths[at.limb];
                let f = length_fraction(&parent.points, at.vertex);
                let here = pw + (look.tip_width.min(pw) - pw) * f;
                (here * CHILD_WIDTH).max(look.tip_width.min(look.width))
            }
        };
        widths.push(w);
    }
    widths
}

/// Fraction of a polyline's length that lies before vertex `k`.
fn length_fraction(points: &[kurbo::Point], k: usize) -> f64 {
    let seg = |i: usize| (points[i + 1] - points[i]).hypot();
    let total: f64 = (0..points.len() - 1).map(seg).sum();
    if total <= 0.0 {
        return 0.0;
    }
    (0..k.min(points.len() - 1)).map(seg).sum::<f64>() / total
}
