//! Islands and bridges (katagami's *tsuri*): the pieces of a stencil sheet
//! that would fall out, and the strips of paper left uncut that hold them.
//!
//! An *island* is paper enclosed by one cut-out: a hole of a part of the
//! cut-out region. The paper just outside that part's outer contour is
//! its *holder*, which may be an island itself (rings inside rings), so
//! bridging every island to its holder ties every piece to the sheet.
//!
//! A bridge crosses the cut-out between an island and its holder where
//! that gap is narrowest: from the island's boundary point nearest to the
//! cut-out's outer contour, across to that nearest point, reaching half
//! its width into the paper at both ends so that it joins it whatever the
//! curvature.
//! An island whose outline is longer than the spacing gets more bridges,
//! spread evenly along its outline from the first, each to the nearest
//! point of the holder, so that a long slit does not flap.
//!
//! Nearest points are searched among the boundaries flattened within the
//! tolerance and resampled every [`SAMPLE_SPACING`], with a k-d tree
//! ([`PointIndex`]) over the holder's points: a bridge lands within that
//! spacing of the narrowest place.

use kurbo::{BezPath, PathEl, Point, Shape, Vec2};

use crate::error::{Error, Result};
use crate::geom::polylabel::pole_of_inaccessibility;
use crate::geom::region::Region;
use crate::geom::subpath::subpaths;
use crate::geom::PointIndex;

/// Boundaries are resampled this often (mm) for the nearest-point search.
pub const SAMPLE_SPACING: f64 = 0.1;

/// One bridge: a strip of paper `width` mm wide from `from`, on an
/// island's boundary, to `to`, on its holder's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bridge {
    /// Where it leaves the island.
    pub from: Point,
    /// Where it reaches the holder.
    pub to: Point,
    /// Its width, mm.
    pub width: f64,
    /// The island it holds (index into the islands found with it).
    pub island: usize,
}

impl Bridge {
    /// The strip as a region: the segment from `from` to `to`, lengthened
    /// by half the width at both ends, `width` wide.
    pub fn region(&self) -> Result<Region> {
        Region::polygon(&self.corners(self.width / 2.0))
    }

    /// The corners of the strip from `from` to `to` lengthened by `reach`
    /// mm at both ends.
    pub fn corners(&self, reach: f64) -> [Point; 4] {
        let along = self.to - self.from;
        let length = along.hypot();
        let u = if length > 0.0 {
            along / length
        } else {
            Vec2::new(1.0, 0.0)
        };
        let n = Vec2::new(-u.y, u.x) * (self.width / 2.0);
        let (a, b) = (self.from - u * reach, self.to + u * reach);
        [a + n, b + n, b - n, a - n]
    }

    /// The length of the gap it crosses, mm.
    pub fn span(&self) -> f64 {
        self.from.distance(self.to)
    }
}

/// An island of the sheet and where it is held.
#[derive(Debug, Clone, PartialEq)]
pub struct Island {
    /// The island's outline (outer contour).
    pub outline: BezPath,
    /// A point well inside it (its pole of inaccessibility), for reports.
    pub centre: Point,
    /// The widest circle inside it, diameter in mm.
    pub across: f64,
}

/// The islands that the cut-outs `cut` free, with the bridges that tie
/// each to the paper around it: one across the narrowest gap, and more
/// along outlines longer than `every` mm (0: no more).
///
/// No sweep is needed: `cut` is normalised, so every hole of one of its
/// parts is an island's outline, and the paper around it (the holder)
/// begins at that part's outer contour.
///
/// # Errors
/// [`Error::Invalid`] (field `bridge`) when `width` is wider than an
/// island it must hold; the message names the island's place.
pub fn bridge(
    cut: &Region,
    width: f64,
    every: f64,
    tolerance: f64,
) -> Result<(Vec<Island>, Vec<Bridge>)> {
    let mut islands = Vec::new();
    let mut bridges = Vec::new();
    for part in cut.components() {
        let contours: Vec<BezPath> = subpaths(part.path()).map(|s| s.to_path()).collect();
        let Some(wall) = contours.iter().find(|c| c.area() > 0.0) else {
            continue;
        };
        for hole in contours.iter().filter(|c| c.area() < 0.0) {
            // The island's outline, turned to enclose it.
            let outline = hole.reverse_subpaths();
            let (centre, radius) =
                pole_of_inaccessibility(&Region::from_normalised(outline.clone()), tolerance)
                    .unwrap_or((outline.bounding_box().center(), 0.0));
            if width >= 2.0 * radius {
                return Err(Error::invalid(
                    "bridge",
                    format!(
                        "a bridge {width} mm wide is wider than the island at ({:.1}, {:.1}) mm \
                         it must hold ({:.2} mm across); give a narrower bridge",
                        centre.x,
                        centre.y,
                        2.0 * radius
                    ),
                ));
            }
            let island = islands.len();
            bridges.extend(
                island_bridges(&outline, wall, every, tolerance)
                    .into_iter()
                    .map(|(from, to)| Bridge {
                        from,
                        to,
                        width,
                        island,
                    }),
            );
            islands.push(Island {
                outline,
                centre,
                across: 2.0 * radius,
            });
        }
    }
    Ok((islands, bridges))
}

/// `cut` with every island narrower than `min_width` mm (its widest
/// inscribed circle) cut away whole, and the places of those specks:
/// paper the blade cannot leave, too small to hold with a bridge.
pub fn cut_specks(cut: &Region, min_width: f64, tolerance: f64) -> (Region, Vec<Point>) {
    let mut kept = BezPath::new();
    let mut specks = Vec::new();
    for contour in subpaths(cut.path()).map(|s| s.to_path()) {
        if contour.area() < 0.0 {
            let island = Region::from_normalised(contour.reverse_subpaths());
            let (centre, radius) = pole_of_inaccessibility(&island, tolerance)
                .unwrap_or((contour.bounding_box().center(), 0.0));
            if 2.0 * radius < min_width {
                specks.push(centre);
                continue;
            }
        }
        kept.extend(contour.iter());
    }
    if specks.is_empty() {
        (cut.clone(), specks)
    } else {
        (Region::from_normalised(kept), specks)
    }
}

/// The ends of the bridges from the island bounded by `outline` to the
/// outer contour `wall` of the cut-out around it.
fn island_bridges(
    outline: &BezPath,
    wall: &BezPath,
    every: f64,
    tolerance: f64,
) -> Vec<(Point, Point)> {
    let island = resample(outline, tolerance);
    let wall = resample(wall, tolerance);
    if island.is_empty() || wall.is_empty() {
        return Vec::new();
    }
    let mut index = PointIndex::new(&wall);
    let mut nearest = |p: Point| {
        index
            .nearest_within(p, f64::INFINITY)
            .map(|(i, d2)| (wall[i as usize], d2))
    };
    // The narrowest gap.
    let mut first = 0;
    let mut best = f64::INFINITY;
    for (i, &p) in island.iter().enumerate() {
        if let Some((_, d2)) = nearest(p) {
            if d2 < best {
                best = d2;
                first = i;
            }
        }
    }
    let perimeter = island.len() as f64 * SAMPLE_SPACING;
    let count = if every > 0.0 {
        ((perimeter / every).floor() as usize).max(1)
    } else {
        1
    };
    (0..count)
        .filter_map(|m| {
            let at = island[(first + m * island.len() / count) % island.len()];
            nearest(at).map(|(to, _)| (at, to))
        })
        .collect()
}

/// Points along the closed contour `path`, about [`SAMPLE_SPACING`] apart
/// (the contour flattened within `tolerance`, long lines split).
fn resample(path: &BezPath, tolerance: f64) -> Vec<Point> {
    let mut corners: Vec<Point> = Vec::new();
    kurbo::flatten(path.iter(), tolerance, |el| {
        if let PathEl::MoveTo(p) | PathEl::LineTo(p) = el {
            corners.push(p);
        }
    });
    if let Some(&first) = corners.first() {
        corners.push(first);
    }
    let mut out = Vec::new();
    let mut carry = 0.0;
    for w in corners.windows(2) {
        let (a, b) = (w[0], w[1]);
        let length = a.distance(b);
        let mut s = carry;
        while s < length {
            out.push(a.lerp(b, s / length));
            s += SAMPLE_SPACING;
        }
        carry = s - length;
    }
    out
}

#[cfg(test)]
mod tests {
    use kurbo::{Circle, Rect};

    use super::*;

    /// A ring 1 mm wide cut out round a disc island of radius 10.
    fn ring_cut() -> Region {
        let outer = Region::new(
            Circle::new((50.0, 50.0), 11.0).to_path(0.01),
            crate::geom::region::FillRule::NonZero,
        )
        .unwrap();
        let inner = Region::new(
            Circle::new((50.0, 50.0), 10.0).to_path(0.01),
            crate::geom::region::FillRule::NonZero,
        )
        .unwrap();
        outer.difference(&inner)
    }

    #[test]
    fn a_disc_in_a_ring_is_an_island_held_across_the_ring() {
        let (islands, bridges) = bridge(&ring_cut(), 0.8, 0.0, 0.01).unwrap();
        assert_eq!(islands.len(), 1);
        assert!((islands[0].across - 20.0).abs() < 0.1);
        assert_eq!(bridges.len(), 1);
        assert!((bridges[0].span() - 1.0).abs() < 0.05, "{:?}", bridges[0]);
    }

    #[test]
    fn bridges_are_spread_along_long_outlines() {
        // The disc's outline is about 63 mm long.
        let (_, bridges) = bridge(&ring_cut(), 0.8, 20.0, 0.01).unwrap();
        assert_eq!(bridges.len(), 3);
        for (a, b) in bridges.iter().zip(bridges.iter().skip(1)) {
            assert!(a.from.distance(b.from) > 15.0, "{a:?} {b:?}");
        }
    }

    #[test]
    fn a_bridge_wider_than_its_island_is_refused_with_the_place() {
        let e = bridge(&ring_cut(), 25.0, 0.0, 0.01).unwrap_err();
        let text = e.to_string();
        assert!(text.starts_with("bridge: "), "{text}");
        assert!(text.contains("(50.0, 50.0)"), "{text}");
    }

    #[test]
    fn a_slot_frees_no_island_and_gets_no_bridges() {
        let slot = Region::from_rect(Rect::new(10.0, 10.0, 60.0, 12.0)).unwrap();
        let (islands, bridges) = bridge(&slot, 0.8, 10.0, 0.01).unwrap();
        assert!(islands.is_empty() && bridges.is_empty());
    }
}
