//! A vine along a line on the page (docs/SPEC.md §5, "2D vines"): grown round a
//! straight upright pole as long as the line, then bent onto the line, so
//! that it winds over and under a rod laid along it.
//!
//! The bend maps the model's height to the arc length along the line, its
//! x (away from the pole) to the line's left normal on the page, and keeps
//! its z as the depth towards the eye. The result lies on the page (x
//! right, y *up*, z towards the eye), for [`super::sight::page_camera`].
//! Lengths across the line are kept; along it they stretch or shrink with
//! the line's curvature, by the distance from the rod over the radius of
//! the bend (small for a vine that hugs its rod).

use glam::{DVec2, DVec3};

use crate::error::{Error, Result};
use crate::family::vine::engine::{Leaf, Plant};

/// Samples of the line are this far apart, mm.
const SPACING: f64 = 0.25;

/// The longest guide, mm: twice the longest side of the largest page.
/// The rod is drawn, and hidden where the stem passes over it, along all
/// of it, at about 30 KB and 0.1 ms a millimetre in release (a 280 m
/// guide aborted past 4 GB).
pub(super) const MAX_LENGTH: f64 = 20_000.0;

/// The length of `line` (page mm), refused (naming `field`) past
/// [`MAX_LENGTH`] before anything is grown along it.
pub(super) fn checked_length(line: &[DVec2], field: &str) -> Result<f64> {
    let total = length(line);
    if total > MAX_LENGTH {
        return Err(Error::invalid(
            field,
            format!("is {total:.0} mm long; a vine grows along at most {MAX_LENGTH:.0} mm"),
        ));
    }
    Ok(total)
}

/// The length of the polyline `line`.
fn length(line: &[DVec2]) -> f64 {
    line.windows(2).map(|w| w[0].distance(w[1])).sum()
}

/// A line on the page, sampled evenly by arc length.
#[derive(Debug, Clone)]
pub(super) struct Guide {
    /// The samples, page mm (y down).
    points: Vec<DVec2>,
    /// Arc length between samples.
    step: f64,
}

impl Guide {
    /// The line through `line` (page mm, ≥ 2 points, with length).
    pub(super) fn new(line: &[DVec2]) -> Guide {
        let total = length(line);
        let n = ((total / SPACING).ceil() as usize).clamp(1, 1_000_000);
        let step = total / n as f64;
        let mut points = Vec::with_capacity(n + 1);
        let (mut i, mut walked) = (0, 0.0);
        for k in 0..=n {
            let s = k as f64 * step;
            while i + 2 < line.len() && walked + line[i].distance(line[i + 1]) < s {
                walked += line[i].distance(line[i + 1]);
                i += 1;
            }
            let seg = line[i].distance(line[i + 1]);
            let t = if seg > 0.0 {
                ((s - walked) / seg).clamp(0.0, 1.0)
            } else {
                0.0
            };
            points.push(line[i].lerp(line[i + 1], t));
        }
        Guide { points, step }
    }

    /// Its length, mm.
    pub(super) fn length(&self) -> f64 {
        self.step * (self.points.len() - 1) as f64
    }

    /// The point at arc length `s` and the unit tangent there (page, y
    /// down); beyond the ends the line goes on straight.
    fn at(&self, s: f64) -> (DVec2, DVec2) {
        let last = self.points.len() - 1;
        let k = (s / self.step).floor().clamp(0.0, (last - 1) as f64) as usize;
        let tangent = (self.points[k + 1] - self.points[k]).normalize_or(DVec2::X);
        let t = s / self.step - k as f64;
        (self.points[k].lerp(self.points[k + 1], t), tangent)
    }

    /// A point of the model grown round the upright pole (its axis the y
    /// axis, y the arc length) on the page.
    pub(super) fn bend(&self, p: DVec3) -> DVec3 {
        let (on, tangent) = self.at(p.y);
        // The left of the direction of travel, with y down.
        let left = DVec2::new(tangent.y, -tangent.x);
        let q = on + left * p.x;
        DVec3::new(q.x, -q.y, p.z)
    }

    /// A direction at `p` after the bend.
    fn bend_direction(&self, p: DVec3, d: DVec3) -> DVec3 {
        let h = 1e-3;
        ((self.bend(p + d * h) - self.bend(p)) / h).normalize_or(d)
    }

    /// The rod along the line, as a 3D axis on the page.
    pub(super) fn rod(&self) -> Vec<DVec3> {
        self.points
            .iter()
            .map(|p| DVec3::new(p.x, -p.y, 0.0))
            .collect()
    }

    /// The plant bent onto the line.
    pub(super) fn bend_plant(&self, plant: &Plant) -> Plant {
        let mut bent = plant.clone();
        for stem in &mut bent.stems {
            for p in stem.points.iter_mut().chain(stem.raw.iter_mut()) {
                *p = self.bend(*p);
            }
        }
        for (leaf, old) in bent.leaves.iter_mut().zip(&plant.leaves) {
            *leaf = self.bend_leaf(old);
        }
        bent
    }

    fn bend_leaf(&self, leaf: &Leaf) -> Leaf {
        let start = leaf.stalk[1];
        let midrib = self.bend_direction(start, leaf.midrib);
        // Kept square to the midrib, as the blade was.
        let across = self.bend_direction(start, leaf.across);
        let across = (across - midrib * across.dot(midrib)).normalize_or(across);
        Leaf {
            stalk: leaf.stalk.map(|p| self.bend(p)),
            midrib,
            across,
            quad: leaf.quad.map(|p| self.bend(p)),
            ..leaf.clone()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bend_follows_the_line_and_keeps_the_distance_from_it() {
        // A quarter circle of radius 100 round (0, 0), from (100, 0) to
        // (0, 100) on the page.
        let line: Vec<DVec2> = (0..=200)
            .map(|k| {
                let a = std::f64::consts::FRAC_PI_2 * f64::from(k) / 200.0;
                DVec2::new(100.0 * a.cos(), 100.0 * a.sin())
            })
            .collect();
        let g = Guide::new(&line);
        assert!((g.length() - 50.0 * std::f64::consts::PI).abs() < 0.05);
        for s in [0.0, 40.0, 100.0, 150.0] {
            let on = g.bend(DVec3::new(0.0, s, 0.0));
            let off = g.bend(DVec3::new(3.0, s, 2.0));
            // On the line: at radius 100 on the page (y flipped back).
            assert!((DVec2::new(on.x, -on.y).length() - 100.0).abs() < 0.01);
            // Off it by 3 across, depth kept.
            assert!((off.truncate().distance(on.truncate()) - 3.0).abs() < 1e-6);
            assert_eq!(off.z, 2.0);
        }
        // Walking down the page from (100, 0), the left is +x: away from
        // the centre.
        let left = g.bend(DVec3::new(3.0, 10.0, 0.0));
        assert!((DVec2::new(left.x, -left.y).length() - 103.0).abs() < 0.01);
        // Beyond the end it goes on straight along the last tangent.
        let past = g.bend(DVec3::new(0.0, g.length() + 10.0, 0.0));
        assert!(
            (past.x - -10.0).abs() < 0.05 && (-past.y - 100.0).abs() < 0.05,
            "{past}"
        );
    }
}
