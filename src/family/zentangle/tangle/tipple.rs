//! Tipple: small circles of many sizes packed together, none touching,
//! the big ones first and the little ones in the gaps.

use super::super::element::{Mark, Paint};
use super::shapes::{circle, mark, pack};
use super::Section;
use crate::rng::RandomStream;

/// The marks: the circles, white.
pub(super) fn draw(s: &Section<'_>, rng: &mut RandomStream) -> Vec<Mark> {
    let smallest = (0.1 * s.unit).max(2.0 * s.pen);
    let gap = (0.07 * s.unit).max(2.0 * s.pen);
    pack(s.region, (smallest, 0.4 * s.unit), gap, rng)
        .into_iter()
        .map(|(c, r)| mark(circle(c, r), Paint::White))
        .collect()
}
