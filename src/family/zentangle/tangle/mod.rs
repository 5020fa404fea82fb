//! Named tangles: twelve of the official Zentangle patterns, each drawn
//! the way its step-out teaches — the strokes a pen makes, in the order a
//! tangler makes them — into one section (any white region the loop or a
//! manual step gives it). Beyond the paper's twenty procedures, whose
//! drawings are built from its elements; a description names a tangle
//! where it names a procedure (`procedures = ["printemps", 5]`,
//! `manual = [{ at = […], procedure = "tipple" }]`), and the tangle's id
//! is [`crate::spec::PROCEDURES`] plus its place in [`crate::spec::TANGLES`].
//!
//! Each tangle gives marks in painter's order over the section's bounding
//! box; `compose` clips them to the section and hides what lies under a
//! later fill (so a Hollibaugh band drawn later passes behind the earlier
//! ones), and black parts are finished as the family finishes black:
//! hatched or filled as the description's `black` says. A tangle fills
//! its section: the white it leaves is not filled again.

mod betweed;
mod cadent;
mod crescent_moon;
mod florz;
mod hollibaugh;
mod knightsbridge;
mod mooka;
mod nzeppel;
mod printemps;
mod shapes;
mod shattuck;
mod stat;
mod tipple;

#[cfg(test)]
mod tests;

use kurbo::{BezPath, Shape as _};

use super::element::Mark;
use super::procedure::Target;
use crate::error::Result;
use crate::geom::clip::StrokeClipper;
use crate::geom::offset::offset;
use crate::geom::region::{FillRule, Region};
use crate::geom::TOLERANCE;
use crate::rng::RandomStream;
use crate::spec::{PROCEDURES, TANGLES};

/// A named tangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Tangle {
    /// Tight spirals, rolled circles packed on black.
    Printemps,
    /// Black half-moons along the border, echoed inwards.
    CrescentMoon,
    /// Bands of parallel pairs, each new one passing behind the others.
    Hollibaugh,
    /// A diagonal grid, diamonds at its crossings, alternate cells black.
    Florz,
    /// A checkerboard.
    Knightsbridge,
    /// A grid cut into rounded pebbles.
    Nzeppel,
    /// Zig-zag lightning bands.
    Static,
    /// Packed small circles of many sizes.
    Tipple,
    /// A grid of dots joined by S-curves along rows and columns.
    Cadent,
    /// Concentric pods growing from the edges and between each other.
    Betweed,
    /// Bands of tight lines alternating with black.
    Shattuck,
    /// Stems curling into teardrop loops.
    Mooka,
}

impl Tangle {
    /// Every tangle, in the order of [`TANGLES`].
    pub(super) const ALL: [Tangle; 12] = [
        Tangle::Printemps,
        Tangle::CrescentMoon,
        Tangle::Hollibaugh,
        Tangle::Florz,
        Tangle::Knightsbridge,
        Tangle::Nzeppel,
        Tangle::Static,
        Tangle::Tipple,
        Tangle::Cadent,
        Tangle::Betweed,
        Tangle::Shattuck,
        Tangle::Mooka,
    ];

    /// The tangle with procedure id `id`, if `id` names one.
    pub(super) fn from_id(id: u32) -> Option<Tangle> {
        let k = id.checked_sub(PROCEDURES)?;
        Tangle::ALL.get(k as usize).copied()
    }

    /// Its procedure id.
    #[cfg(test)]
    pub(super) fn id(self) -> u32 {
        PROCEDURES + self as u32
    }

    /// Its name, as a description writes it and as its steps' group ids
    /// end (`step-3-crescent-moon`).
    pub(super) fn name(self) -> &'static str {
        TANGLES[self as usize]
    }
}

/// The section a tangle fills and the sizes it draws at.
pub(super) struct Section<'a> {
    /// The white region.
    pub(super) region: &'a Region,
    /// The tangle's grid spacing, mm: a fraction of the loop's element
    /// size, never less than a few pen widths.
    pub(super) unit: f64,
    /// The pen's width, mm.
    pub(super) pen: f64,
}

/// A tangle's grid spacing is this fraction of the loop's element size:
/// about ten cells across a section.
const UNIT_OF_SIZE: f64 = 0.3;

/// …and at least this many pen widths, so its finest lines stay apart.
const MIN_UNIT_PENS: f64 = 10.0;

/// Marks reach at most this many units past the section.
const MARGIN_UNITS: f64 = 0.5;

/// Draws `tangle` into `t`'s region: marks in painter's order, none
/// reaching more than half a unit past the region.
///
/// # Errors
/// From the region machinery on degenerate geometry.
pub(super) fn draw(tangle: Tangle, t: &Target<'_>, rng: &mut RandomStream) -> Result<Vec<Mark>> {
    let s = Section {
        region: t.region,
        unit: (UNIT_OF_SIZE * t.size).max(MIN_UNIT_PENS * t.pen),
        pen: t.pen,
    };
    let marks = match tangle {
        Tangle::Printemps => Ok(printemps::draw(&s, rng)),
        Tangle::CrescentMoon => crescent_moon::draw(&s),
        Tangle::Hollibaugh => Ok(hollibaugh::draw(&s, rng)),
        Tangle::Florz => Ok(florz::draw(&s, rng)),
        Tangle::Knightsbridge => Ok(knightsbridge::draw(&s, rng)),
        Tangle::Nzeppel => Ok(nzeppel::draw(&s, rng)),
        Tangle::Static => Ok(stat::draw(&s, rng)),
        Tangle::Tipple => Ok(tipple::draw(&s, rng)),
        Tangle::Cadent => Ok(cadent::draw(&s, rng)),
        Tangle::Betweed => Ok(betweed::draw(&s, rng)),
        Tangle::Shattuck => Ok(shattuck::draw(&s, rng)),
        Tangle::Mooka => Ok(mooka::draw(&s, rng)),
    }?;
    trimmed(marks, s.region, MARGIN_UNITS * s.unit)
}

/// `marks` cut back to within `margin` of `region`. A tangle lays its
/// grids and bands over the region's whole box, as a pencil guide runs
/// off the section; compose clips them to the region, but the loop's ink
/// limit weighs a mark as a whole before that, and a band reaching into
/// a neighbouring section full of ink would be left out. Marks within
/// `margin` of the box and no more than `3 · margin` across are kept as
/// they are (a cell beyond the region is all a lattice leaves there).
fn trimmed(marks: Vec<Mark>, region: &Region, margin: f64) -> Result<Vec<Mark>> {
    let reach = region.bounds().inflate(margin, margin);
    let near = offset(region, margin, TOLERANCE)?;
    let clipper = StrokeClipper::new(&near, TOLERANCE);
    let mut out = Vec::with_capacity(marks.len());
    for m in marks {
        let b = m.path.bounding_box();
        if reach.contains_rect(b) && b.width().max(b.height()) <= 3.0 * margin {
            out.push(m);
        } else if m.fills() {
            if let Ok(area) = Region::new(m.path, FillRule::NonZero) {
                let cut = area.intersection(&near);
                if !cut.is_empty() {
                    out.push(Mark {
                        path: cut.into_path(),
                        paint: m.paint,
                    });
                }
            }
        } else {
            let mut path = BezPath::new();
            for piece in clipper.clip(&m.path).inside {
                path.extend(piece.iter());
            }
            if !path.elements().is_empty() {
                out.push(Mark {
                    path,
                    paint: m.paint,
                });
            }
        }
    }
    Ok(out)
}
