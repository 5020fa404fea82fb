//! Bokashi (暈し) in line: the dyer's shading of a flower, a leaf or a
//! background, drawn with the same pen as its outline.
//!
//! The source shows its flowers and leaves flat and names shading
//! ("gradation", bokashi) as what they lack beside real kimono
//! [000 §7.2.1]. A plotter has one colour per pen, so the shade is line
//! density: lines inside the shape, the first `spacing` mm from the side
//! the shading comes from, each further gap `growth` times the one before,
//! until they have crossed `reach` of the shape. The eye reads close lines
//! as dark, so the shape darkens towards that side.
//!
//! * `edge`: the lines are the shape's contours (its outline shrunk by the
//!   distance), the way dye gathers at a petal's rim; the distance runs
//!   from the outline to the shape's deepest point (the centre of its
//!   largest inscribed circle).
//! * `centre`: the outline scaled about the shape's deepest point, counted
//!   from it outwards: rings of the shape's own form round its heart.
//! * `top`, `bottom`, `left`, `right`: straight lines across the page,
//!   counted from the shape's top (bottom, …) to its far side.
//!
//! Every island of a shape (the parts of a background mask) is shaded on
//! its own, so a small island is shaded as fully as a large one. The lines
//! are returned for the caller to append to the shape's own path: its
//! closed contours lie inside the outline and are wound like it, so they
//! neither change the fill nor hide the shape's own details.

use kurbo::{Affine, BezPath, Line, Shape};

use crate::error::Result;
use crate::geom::clip::StrokeClipper;
use crate::geom::offset::offset;
use crate::geom::polylabel::pole_of_inaccessibility;
use crate::geom::region::{FillRule, Region};
use crate::geom::subpath::subpaths;
use crate::geom::TOLERANCE;
use crate::spec::{BokashiSpec, ShadeFrom};

/// Most lines in one island: more would be a grey fill, not a shade, and
/// a 0.1 mm spacing with growth 1 across a page would otherwise be
/// thousands of offsets.
pub(crate) const MAX_LINES: usize = 64;

/// How close the deepest point is found, mm.
const POLE_PRECISION: f64 = 0.05;

/// The shading lines of the area that the closed subpaths of `outline`
/// enclose (non-zero rule), in the outline's coordinates (mm).
///
/// # Errors
/// Only for an outline with coordinates no region can hold.
pub(crate) fn shade(outline: &BezPath, spec: &BokashiSpec) -> Result<BezPath> {
    let mut closed = BezPath::new();
    for sub in subpaths(outline).filter(|s| s.is_closed()) {
        closed.extend(sub.elements());
    }
    let mut lines = BezPath::new();
    if closed.elements().is_empty() {
        return Ok(lines);
    }
    let region = Region::new(closed.clone(), FillRule::NonZero)?;
    for island in region.components() {
        match spec.from {
            ShadeFrom::Edge | ShadeFrom::Centre => contours(&island, spec, &mut lines)?,
            _ => across(&island, spec, &mut lines),
        }
    }
    // Contours come wound as regions are; turned, if need be, the way the
    // outline runs, so that they add to its fill instead of cutting holes.
    if closed.area() * region.path().area() < 0.0 {
        lines = lines.reverse_subpaths();
    }
    Ok(lines)
}

/// The distances of the lines from the dense side: `spacing`, then gaps
/// growing by `growth`, up to `limit` and [`MAX_LINES`] of them.
pub(crate) fn distances(spec: &BokashiSpec, limit: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let (mut at, mut gap) = (0.0, spec.spacing);
    while out.len() < MAX_LINES {
        at += gap;
        if at > limit {
            break;
        }
        out.push(at);
        gap *= spec.growth;
    }
    out
}

/// Lines following the shape of `island`, dense at its outline (`edge`:
/// the outline shrunk by each distance) or at its deepest point
/// (`centre`: the outline scaled about that point, so a flower is ringed
/// by smaller flowers of its own shape, clipped to the island where a
/// scaled copy would leave it).
fn contours(island: &Region, spec: &BokashiSpec, lines: &mut BezPath) -> Result<()> {
    let Some((pole, depth)) = pole_of_inaccessibility(island, POLE_PRECISION) else {
        return Ok(());
    };
    if spec.from == ShadeFrom::Centre {
        let clipper = StrokeClipper::new(island, TOLERANCE);
        for d in distances(spec, spec.reach * depth) {
            let scaled = Affine::scale_about(d / depth, pole) * island.path().clone();
            for piece in clipper.clip(&scaled).inside {
                lines.extend(piece.elements().iter().copied());
            }
        }
        return Ok(());
    }
    for d in distances(spec, spec.reach * depth) {
        let contour = offset(island, -d, TOLERANCE)?;
        lines.extend(contour.path().elements().iter().copied());
    }
    Ok(())
}

/// Straight lines across `island`, dense at the side of the page that
/// `spec.from` names.
fn across(island: &Region, spec: &BokashiSpec, lines: &mut BezPath) {
    let b = island.bounds();
    let (extent, line_at): (f64, Box<dyn Fn(f64) -> Line>) = match spec.from {
        ShadeFrom::Top => (b.height(), Box::new(|d| row(b, b.y0 + d))),
        ShadeFrom::Bottom => (b.height(), Box::new(|d| row(b, b.y1 - d))),
        ShadeFrom::Left => (b.width(), Box::new(|d| column(b, b.x0 + d))),
        _ => (b.width(), Box::new(|d| column(b, b.x1 - d))),
    };
    let clipper = StrokeClipper::new(island, TOLERANCE);
    for d in distances(spec, spec.reach * extent) {
        for piece in clipper.clip(&line_at(d).to_path(0.0)).inside {
            lines.extend(piece.elements().iter().copied());
        }
    }
}

/// A level line across `b` (and a little beyond it) at height `y`.
fn row(b: kurbo::Rect, y: f64) -> Line {
    Line::new((b.x0 - 1.0, y), (b.x1 + 1.0, y))
}

/// An upright line across `b` (and a little beyond it) at `x`.
fn column(b: kurbo::Rect, x: f64) -> Line {
    Line::new((x, b.y0 - 1.0), (x, b.y1 + 1.0))
}

#[cfg(test)]
mod tests {
    use kurbo::{Circle, ParamCurve, Point, Rect};

    use super::*;

    fn spec(from: ShadeFrom) -> BokashiSpec {
        BokashiSpec {
            from,
            ..BokashiSpec::default()
        }
    }

    /// Where the lines of `lines` cross the segment `a`–`b`, as distances
    /// from `a`, nearest first.
    fn crossings(lines: &BezPath, a: Point, b: Point) -> Vec<f64> {
        let probe = Line::new(a, b);
        let mut out: Vec<f64> = lines
            .segments()
            .flat_map(|s| s.intersect_line(probe))
            .map(|i| i.line_t * a.distance(b))
            .collect();
        out.sort_by(f64::total_cmp);
        out.dedup_by(|x, y| (*x - *y).abs() < 1e-6);
        out
    }

    /// The gaps between successive positions, starting from 0.
    fn gaps(at: &[f64]) -> Vec<f64> {
        let mut prev = 0.0;
        at.iter()
            .map(|x| {
                let g = x - prev;
                prev = *x;
                g
            })
            .collect()
    }

    fn assert_growing(g: &[f64], growth: f64, what: &str) {
        assert!(g.len() >= 3, "{what}: {g:?}");
        for w in g.windows(2) {
            assert!(w[1] > w[0], "{what}: gaps do not grow: {g:?}");
            assert!((w[1] / w[0] - growth).abs() < 0.02, "{what}: {g:?}");
        }
    }

    #[test]
    fn distances_start_at_the_spacing_and_grow_by_the_ratio() {
        let s = BokashiSpec {
            spacing: 0.5,
            growth: 2.0,
            ..BokashiSpec::default()
        };
        assert_eq!(distances(&s, 8.0), vec![0.5, 1.5, 3.5, 7.5]);
        let even = BokashiSpec {
            growth: 1.0,
            spacing: 0.1,
            ..s
        };
        assert_eq!(distances(&even, 1e9).len(), MAX_LINES);
        assert!(distances(&s, 0.4).is_empty());
    }

    /// From the edge of a disc: rings whose gaps grow towards the middle,
    /// reaching `reach` of the radius; from the centre the other way.
    #[test]
    fn contours_thin_out_away_from_the_dense_side() {
        let disc = Circle::new((50.0, 50.0), 20.0).to_path(1e-3);
        let along =
            |lines: &BezPath| crossings(lines, Point::new(30.0, 50.0), Point::new(50.0, 50.0));
        let edge = shade(&disc, &spec(ShadeFrom::Edge)).unwrap();
        let at = along(&edge);
        assert_growing(&gaps(&at), 1.4, "edge");
        assert!((at[0] - 0.4).abs() < 0.02, "{at:?}");
        assert!(*at.last().unwrap() <= 0.6 * 20.0 + 0.02, "{at:?}");
        assert!(*at.last().unwrap() > 0.6 * 20.0 / 1.4, "{at:?}");

        let centre = shade(&disc, &spec(ShadeFrom::Centre)).unwrap();
        let mut from_middle: Vec<f64> = along(&centre).iter().map(|x| 20.0 - x).collect();
        from_middle.reverse();
        assert_growing(&gaps(&from_middle), 1.4, "centre");
        assert!((from_middle[0] - 0.4).abs() < 0.02, "{from_middle:?}");
    }

    /// From a side of the page: level or upright lines whose gaps grow away
    /// from that side, inside the shape only.
    #[test]
    fn lines_across_thin_out_away_from_their_side() {
        let r = Rect::new(10.0, 20.0, 70.0, 60.0);
        let shape = r.to_path(0.0);
        let region = Region::new(shape.clone(), FillRule::NonZero).unwrap();
        for (from, a, b) in [
            (
                ShadeFrom::Top,
                Point::new(40.0, 20.0),
                Point::new(40.0, 60.0),
            ),
            (
                ShadeFrom::Bottom,
                Point::new(40.0, 60.0),
                Point::new(40.0, 20.0),
            ),
            (
                ShadeFrom::Left,
                Point::new(10.0, 40.0),
                Point::new(70.0, 40.0),
            ),
            (
                ShadeFrom::Right,
                Point::new(70.0, 40.0),
                Point::new(10.0, 40.0),
            ),
        ] {
            let lines = shade(&shape, &spec(from)).unwrap();
            assert_growing(&gaps(&crossings(&lines, a, b)), 1.4, &format!("{from:?}"));
            for seg in lines.segments() {
                for p in [seg.start(), seg.end()] {
                    assert!(
                        region.contains(p) || r.inflate(1e-6, 1e-6).contains(p),
                        "{p:?}"
                    );
                }
            }
        }
    }

    /// Each island is shaded on its own: a small one as deep as a large one
    /// relative to its size.
    #[test]
    fn every_island_is_shaded_on_its_own() {
        let mut two = Circle::new((20.0, 20.0), 15.0).to_path(1e-3);
        two.extend(Circle::new((80.0, 20.0), 5.0).to_path(1e-3));
        let lines = shade(&two, &spec(ShadeFrom::Edge)).unwrap();
        let big = crossings(&lines, Point::new(5.0, 20.0), Point::new(20.0, 20.0));
        let small = crossings(&lines, Point::new(75.0, 20.0), Point::new(80.0, 20.0));
        assert!(*big.last().unwrap() > 0.5 * 15.0 / 1.4, "{big:?}");
        assert!(*small.last().unwrap() > 0.5 * 5.0 / 1.4, "{small:?}");
        // The contours keep the outline's fill whichever way it runs.
        for outline in [two.clone(), two.reverse_subpaths()] {
            let mut whole = outline.clone();
            whole.extend(
                shade(&outline, &spec(ShadeFrom::Edge))
                    .unwrap()
                    .elements()
                    .iter()
                    .copied(),
            );
            for x in (6..=34).chain(76..=84) {
                let p = Point::new(f64::from(x) + 0.05, 20.3);
                assert_eq!(whole.winding(p).signum(), outline.winding(p), "{p:?}");
            }
        }
        // Open lines enclose nothing to shade.
        let open = Line::new((0.0, 0.0), (10.0, 10.0)).to_path(0.0);
        assert!(shade(&open, &spec(ShadeFrom::Edge))
            .unwrap()
            .elements()
            .is_empty());
    }
}
