//! Crescent Moon: half-moons along the section's border, their straight
//! side on it, filled black; then auras — lines echoing the moons' outline
//! — one beside the other, growing inwards until the section is full.

use super::super::element::{Mark, Paint};
use super::shapes::{along_outline, circle, mark};
use super::Section;
use crate::error::Result;
use crate::geom::offset::offset;
use crate::geom::region::{FillRule, Region};
use crate::geom::TOLERANCE;

/// Most auras around the moons.
const MAX_AURAS: usize = 60;

/// The marks: the moons (black discs centred on the border, so half of
/// each shows), then the auras as lines.
pub(super) fn draw(s: &Section<'_>) -> Result<Vec<Mark>> {
    let r = 0.42 * s.unit;
    let mut moons = kurbo::BezPath::new();
    let mut out = Vec::new();
    for (at, _) in along_outline(s.region, 2.0 * r + 0.45 * s.unit) {
        let disc = circle(at, r);
        moons.extend(disc.iter());
        out.push(mark(disc, Paint::Black));
    }
    if out.is_empty() {
        return Ok(out);
    }
    let moons = Region::new(moons, FillRule::NonZero)?;
    let gap = (0.3 * s.unit).max(4.0 * s.pen);
    let reach = s.region.bounds().width().hypot(s.region.bounds().height());
    for k in 1..=MAX_AURAS {
        let d = k as f64 * gap;
        if d > reach {
            break;
        }
        let aura = offset(&moons, d, TOLERANCE)?;
        // Once an aura holds the whole section, the ones after it
        // would draw nothing.
        if s.region.difference(&aura).area() < 1e-6 * s.region.area() {
            break;
        }
        out.push(mark(aura.into_path(), Paint::Line));
    }
    Ok(out)
}
