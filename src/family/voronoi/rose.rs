//! Rose-window sites (`sites.distribution = "rose"`): rings of sites
//! about the centre of the region's bounds, `petals` of them in the first
//! ring and a multiple of `petals` in every other, so the cells are
//! ordered ring by ring and the whole is unchanged by a turn of 360° ÷
//! `petals`, as a rose window is.
//!
//! The rings are conformal: each ring is farther from the last in
//! proportion to the width of its cells, so a cell keeps its shape while
//! it grows outwards, and alternate rings are turned by half a cell, so
//! the cells interlock like a window's lights. Where cells grow wider
//! than twice `spacing` the count doubles, and there a ring of stone
//! tracery (`sites.tracery` mm wide) is cut from the region: a circle of
//! lead on either side of it.

use std::f64::consts::TAU;

use kurbo::{Circle, Point, Rect, Shape};

use crate::error::Result;
use crate::geom::region::{FillRule, Region};
use crate::geom::TOLERANCE;

/// A ring's distance from the last, as a fraction of its cells' width.
const ASPECT: f64 = 0.75;

/// Cells wider than this many spacings double the count.
const WIDEST: f64 = 2.0;

/// Most rings a window has.
const MAX_RINGS: usize = 200;

/// A rose window's plan: the sites, ring by ring, and the radii of its
/// tracery rings.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Rose {
    /// The sites, the innermost ring first, each ring anticlockwise from
    /// the right on the page.
    pub(crate) sites: Vec<Point>,
    /// The centre of the window.
    pub(crate) centre: Point,
    /// The radii where the count of cells doubles.
    pub(crate) tracery: Vec<f64>,
}

/// The window that fills `bounds` (its inscribed circle), `petals` cells
/// in the first ring, the first ring's cells about `spacing` wide.
pub(crate) fn plan(bounds: Rect, petals: u32, spacing: f64) -> Rose {
    let centre = bounds.center();
    let outer = 0.5 * bounds.width().min(bounds.height());
    let mut count = petals.max(1) as usize;
    let mut radius = count as f64 * spacing / TAU;
    let mut rose = Rose {
        sites: Vec::new(),
        centre,
        tracery: Vec::new(),
    };
    for ring in 0..MAX_RINGS {
        if radius > outer {
            break;
        }
        let step = TAU / count as f64;
        let turn = if ring % 2 == 1 { 0.5 } else { 0.0 };
        rose.sites.extend((0..count).map(|j| {
            let angle = (j as f64 + turn) * step;
            centre + radius * kurbo::Vec2::from_angle(angle)
        }));
        let mut next = radius * (1.0 + ASPECT * step);
        if TAU * next / count as f64 > WIDEST * spacing {
            let ring = (radius * next).sqrt();
            rose.tracery.push(ring);
            count *= 2;
            // The ring past the tracery is twice as far from it as the
            // ring inside, so the cells of the two meet beyond the
            // tracery and it cuts no slivers off either.
            next = ring + 2.0 * (ring - radius);
        }
        radius = next;
    }
    rose
}

impl Rose {
    /// `region` less the tracery rings, each `width` mm wide.
    ///
    /// # Errors
    /// Should the region ops fail on their input (they do not on circles).
    pub(crate) fn cut(&self, region: &Region, width: f64) -> Result<Region> {
        if width <= 0.0 || self.tracery.is_empty() {
            return Ok(region.clone());
        }
        let mut rings = Vec::new();
        for r in &self.tracery {
            let mut path = Circle::new(self.centre, r + 0.5 * width).to_path(TOLERANCE);
            path.extend(Circle::new(self.centre, (r - 0.5 * width).max(0.0)).to_path(TOLERANCE));
            rings.push(Region::new(path, FillRule::EvenOdd)?);
        }
        Ok(region.difference(&Region::union_all(&rings)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn window() -> Rose {
        plan(Rect::new(0.0, 0.0, 176.0, 176.0), 12, 8.0)
    }

    #[test]
    fn rings_hold_multiples_of_the_petals_and_turn_into_themselves() {
        let rose = window();
        assert!(!rose.tracery.is_empty());
        assert_eq!(rose.sites.len() % 12, 0);
        let turn = kurbo::Affine::rotate_about(TAU / 12.0, rose.centre);
        for &p in &rose.sites {
            let q = turn * p;
            let nearest = rose
                .sites
                .iter()
                .map(|s| s.distance(q))
                .fold(f64::INFINITY, f64::min);
            assert!(nearest < 1e-9, "{p:?} turns to {q:?}, {nearest} from a site");
        }
        // Ordered by ring: distances from the centre never fall.
        let radii: Vec<f64> = rose.sites.iter().map(|p| p.distance(rose.centre)).collect();
        assert!(radii.windows(2).all(|w| w[1] >= w[0] - 1e-9));
        assert!(*radii.last().unwrap() <= 88.0);
    }

    #[test]
    fn tracery_lies_between_rings_and_is_cut_from_the_region() {
        let rose = window();
        for &t in &rose.tracery {
            let gap = rose
                .sites
                .iter()
                .map(|p| (p.distance(rose.centre) - t).abs())
                .fold(f64::INFINITY, f64::min);
            assert!(gap > 1.0, "a site {gap} mm from the tracery at {t}");
        }
        let disc = Region::new(
            Circle::new(rose.centre, 88.0).to_path(TOLERANCE),
            FillRule::NonZero,
        )
        .unwrap();
        let cut = rose.cut(&disc, 1.5).unwrap();
        let t = rose.tracery[0];
        assert!(!cut.contains(rose.centre + kurbo::Vec2::new(t, 0.0)));
        assert!(cut.contains(rose.centre + kurbo::Vec2::new(t + 1.0, 0.0)));
        let lost = disc.area() - cut.area();
        let expected: f64 = rose.tracery.iter().map(|r| TAU * r * 1.5).sum();
        assert!((lost - expected).abs() < 0.01 * expected, "{lost} vs {expected}");
    }
}
