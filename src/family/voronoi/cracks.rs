//! Mud cracks (`draw = ["cracks"]`): the region split again and again,
//! the largest piece first, each time by one curved crack across it.
//!
//! Drying mud cracks in sequence: a crack opens across a piece of mud and
//! runs until it meets an older crack, so a newer crack ends on an older
//! one at a right-ish angle — a T-junction — and the pattern is
//! hierarchical: long first cracks, shorter ones between them, plates of
//! about one size at the end (Bohn, Pauchard and Couder 2005, "Hierarchical
//! crack pattern as formed by successive domain divisions"). A Voronoi
//! diagram instead meets three edges at 120°, which reads as paving.
//!
//! Each crack runs across its piece's short way (perpendicular to the
//! piece's long axis, give or take), wanders gently, is narrower than the
//! generation before it and tapers towards its ends. Cracks are drawn as
//! the outlines of the plates they leave: the region less the union of
//! the cracks' tapered outlines, so each crack is a closed outline of
//! varying width and no line is drawn twice.

use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::f64::consts::PI;

use kurbo::{BezPath, Point, Vec2};

use crate::error::{Error, Result};
use crate::geom::clip::clip_stroke;
use crate::geom::region::{FillRule, Region};
use crate::geom::{outline_with_widths, path_length, TOLERANCE};
use crate::rng::RandomStream;

/// Most plates one pattern may crack into.
pub(crate) const MAX_PLATES: usize = 20_000;

/// A piece larger than this many spacings squared cracks again: halves of
/// it are then about one spacing squared.
const SPLIT_AREA: f64 = 1.4;

/// Each generation of cracks is this much narrower than the one before:
/// the first cracks open widest, having dried longest.
const NARROWING: f64 = 0.8;

/// A crack's width at its ends, as a fraction of its width in the middle.
const END_WIDTH: f64 = 0.5;

/// Tries to find a crack that leaves two pieces of some size before a
/// piece is left whole.
const TRIES: usize = 4;

/// Neither side of a crack is smaller than this fraction of the piece.
const MIN_SIDE: f64 = 0.2;

/// Steps along a crack's centre line, mm.
const STEP: f64 = 0.8;

/// One crack: its centre line inside the piece it split, and its width in
/// the middle (mm).
#[derive(Debug, Clone)]
pub(crate) struct Crack {
    /// The centre line, a polyline ending on older cracks or the border.
    pub(crate) centre: BezPath,
    /// The width in the middle, mm; the ends are [`END_WIDTH`] of it.
    pub(crate) width: f64,
}

/// A region cracked: the cracks in the order they opened, and the plates.
#[derive(Debug, Clone)]
pub(crate) struct Cracked {
    /// The cracks, oldest first.
    pub(crate) cracks: Vec<Crack>,
    /// The plates of mud between the cracks, each a closed outline.
    pub(crate) plates: Vec<BezPath>,
}

/// `region` cracked into plates of about `spacing`² each; the first crack
/// `widths[0]` wide, each generation [`NARROWING`] of the one before, none
/// narrower than `widths[1]`.
///
/// # Errors
/// More plates than [`MAX_PLATES`] (field `spacing`).
pub(crate) fn crack(
    region: &Region,
    spacing: f64,
    widths: [f64; 2],
    rng: &mut RandomStream,
) -> Result<Cracked> {
    let plates = region.area() / (spacing * spacing);
    if plates > MAX_PLATES as f64 {
        // The family names the field in the description's terms.
        return Err(Error::invalid(
            "spacing",
            format!(
                "would crack a region of {:.0} mm² into about {plates:.0} plates, more than \
                 {MAX_PLATES}; widen the spacing",
                region.area()
            ),
        ));
    }
    let split_area = SPLIT_AREA * spacing * spacing;
    let mut pieces: Vec<(Region, u32)> = Vec::new();
    let mut queue = BinaryHeap::new();
    let push = |pieces: &mut Vec<(Region, u32)>, queue: &mut BinaryHeap<_>, r: Region, g| {
        // Areas are positive, so their bits order as they do.
        queue.push((r.area().to_bits(), Reverse(pieces.len())));
        pieces.push((r, g));
    };
    for part in region.components() {
        push(&mut pieces, &mut queue, part, 0);
    }
    let mut cracks = Vec::new();
    while let Some((area, Reverse(i))) = queue.pop() {
        if f64::from_bits(area) < split_area {
            break;
        }
        let (piece, generation) = pieces[i].clone();
        let Some((centres, sides)) = split(&piece, rng) else {
            continue;
        };
        let width = (widths[0] * NARROWING.powi(generation as i32)).max(widths[1]);
        cracks.extend(centres.into_iter().map(|centre| Crack { centre, width }));
        for side in sides {
            push(&mut pieces, &mut queue, side, generation + 1);
        }
    }
    let opened: Vec<Region> = cracks.iter().filter_map(outline).collect();
    let plates = region
        .difference(&Region::union_all(&opened))
        .components()
        .into_iter()
        .map(Region::into_path)
        .collect();
    Ok(Cracked { cracks, plates })
}

/// A crack's tapered outline, as a region.
fn outline(crack: &Crack) -> Option<Region> {
    let w = crack.width;
    let shape = outline_with_widths(&crack.centre, &|f| {
        w * (END_WIDTH + (1.0 - END_WIDTH) * (PI * f).sin())
    });
    Region::new(shape, FillRule::NonZero).ok()
}

/// One crack across `piece`: its centre lines inside the piece (more than
/// one where the piece is concave) and the pieces on either side; `None`
/// when no try leaves two sides of some size.
fn split(piece: &Region, rng: &mut RandomStream) -> Option<(Vec<BezPath>, Vec<Region>)> {
    let shape = Moments::of(piece)?;
    let area = piece.area();
    for _ in 0..TRIES {
        let line = wandering_line(piece, &shape, rng);
        let Some(side) = side_of(&line, &shape) else {
            continue;
        };
        let (a, b) = (piece.intersection(&side), piece.difference(&side));
        if a.area() < MIN_SIDE * area || b.area() < MIN_SIDE * area {
            continue;
        }
        let centres: Vec<BezPath> = clip_stroke(&line.path, piece, TOLERANCE)
            .inside
            .into_iter()
            .filter(|c| path_length(c) > STEP)
            .collect();
        let mut sides = a.components();
        sides.extend(b.components());
        return Some((centres, sides));
    }
    None
}

/// A crack's centre line across a piece and reaching past it, and the
/// direction that is its left.
struct Line {
    path: BezPath,
    points: Vec<Point>,
    left: Vec2,
}

/// A gently wandering line across `piece`'s short way through about its
/// centroid: two waves along it, one about as long as the piece and one a
/// third of that.
fn wandering_line(piece: &Region, shape: &Moments, rng: &mut RandomStream) -> Line {
    let b = piece.bounds();
    let reach = 0.5 * b.width().hypot(b.height()) + 1.0;
    let angle = shape.long_axis + 0.5 * PI + rng.symmetric(0.35);
    let along = Vec2::from_angle(angle);
    let left = Vec2::new(along.y, -along.x);
    let long = Vec2::from_angle(shape.long_axis);
    let centre = shape.centroid + long * rng.symmetric(0.3 * shape.long_spread);
    let waves = [
        (2.0 * reach * rng.range(0.8, 1.4), 0.05 * reach * rng.unit()),
        (0.6 * reach * rng.range(0.8, 1.2), 0.02 * reach * rng.unit()),
    ]
    .map(|(length, amplitude)| (length, amplitude, rng.range(0.0, 2.0 * PI)));
    let n = ((2.0 * reach / STEP).ceil() as usize).clamp(2, 4000);
    let points: Vec<Point> = (0..=n)
        .map(|k| {
            let t = -reach + 2.0 * reach * k as f64 / n as f64;
            let off: f64 = waves
                .iter()
                .map(|(l, a, phase)| a * (2.0 * PI * t / l + phase).sin())
                .sum();
            centre + along * t + left * off
        })
        .collect();
    let mut path = BezPath::new();
    path.move_to(points[0]);
    for p in &points[1..] {
        path.line_to(*p);
    }
    Line { path, points, left }
}

/// The half-plane left of `line`, as far as the piece reaches: the line
/// closed by a polygon beyond the piece on its left.
fn side_of(line: &Line, shape: &Moments) -> Option<Region> {
    let far = line.left * (4.0 * shape.reach);
    let (first, last) = (*line.points.first()?, *line.points.last()?);
    let mut polygon = line.points.clone();
    polygon.push(last + far);
    polygon.push(first + far);
    Region::polygon(&polygon).ok()
}

/// The area moments of a piece that say where to crack it.
struct Moments {
    centroid: Point,
    /// The direction (radians) the piece is longest in.
    long_axis: f64,
    /// The standard deviation of the piece along that axis, mm.
    long_spread: f64,
    /// Half the diagonal of the piece's bounds, mm.
    reach: f64,
}

impl Moments {
    /// Centroid and principal axes from the outline's polygons (holes
    /// count negative, by their orientation).
    fn of(piece: &Region) -> Option<Moments> {
        let (mut a, mut cx, mut cy, mut xx, mut yy, mut xy) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        for contour in piece.polygons(TOLERANCE) {
            for (k, p) in contour.iter().enumerate() {
                let q = contour[(k + 1) % contour.len()];
                let c = p.x * q.y - q.x * p.y;
                a += c / 2.0;
                cx += (p.x + q.x) * c / 6.0;
                cy += (p.y + q.y) * c / 6.0;
                xx += (p.x * p.x + p.x * q.x + q.x * q.x) * c / 12.0;
                yy += (p.y * p.y + p.y * q.y + q.y * q.y) * c / 12.0;
                xy += (p.x * q.y + 2.0 * p.x * p.y + 2.0 * q.x * q.y + q.x * p.y) * c / 24.0;
            }
        }
        if a.abs() < 1e-12 {
            return None;
        }
        let centroid = Point::new(cx / a, cy / a);
        let sxx = xx / a - centroid.x * centroid.x;
        let syy = yy / a - centroid.y * centroid.y;
        let sxy = xy / a - centroid.x * centroid.y;
        let long_axis = 0.5 * (2.0 * sxy).atan2(sxx - syy);
        let mean = 0.5 * (sxx + syy);
        let spread = (0.25 * (sxx - syy).powi(2) + sxy * sxy).sqrt();
        let b = piece.bounds();
        Some(Moments {
            centroid,
            long_axis,
            long_spread: (mean + spread).max(0.0).sqrt(),
            reach: 0.5 * b.width().hypot(b.height()) + 1.0,
        })
    }
}

#[cfg(test)]
mod tests {
    use kurbo::{ParamCurve, ParamCurveArclen, ParamCurveNearest, Rect, Shape};

    use super::*;
    use crate::rng::Seed;

    fn page() -> Region {
        Region::from_rect(Rect::new(0.0, 0.0, 190.0, 128.0)).unwrap()
    }

    fn cracked(seed: u64) -> Cracked {
        crack(&page(), 11.0, [1.6, 0.7], &mut Seed(seed).stream()).unwrap()
    }

    /// How far `p` is from the polyline, and whether the nearest point is
    /// within `margin` of one of its ends.
    fn distance(p: Point, path: &BezPath, margin: f64) -> (f64, bool) {
        let mut best = (f64::INFINITY, false);
        let mut walked = 0.0;
        let length = path_length(path);
        for seg in path.segments() {
            let n = seg.nearest(p, 1e-9);
            let d = n.distance_sq.sqrt();
            if d < best.0 {
                let at = walked + seg.subsegment(0.0..n.t).arclen(1e-9);
                best = (d, at < margin || at > length - margin);
            }
            walked += seg.arclen(1e-9);
        }
        best
    }

    /// Junctions where a crack ends on another: T when it ends on the
    /// other's run (away from its ends), else Y or X.
    fn junctions(c: &Cracked) -> (usize, usize) {
        let border = page();
        let (mut t, mut other) = (0, 0);
        for (i, crack) in c.cracks.iter().enumerate() {
            let ends = [crack.centre.segments().next(), crack.centre.segments().last()];
            for end in ends.into_iter().flatten().zip([0.0, 1.0]) {
                let p = end.0.eval(end.1);
                let b = border.bounds();
                let on_border = [p.x - b.x0, b.x1 - p.x, p.y - b.y0, b.y1 - p.y]
                    .iter()
                    .any(|d| d.abs() < 1e-3);
                if on_border {
                    continue;
                }
                let host = c
                    .cracks
                    .iter()
                    .enumerate()
                    .filter(|(j, _)| *j != i)
                    .map(|(_, h)| distance(p, &h.centre, 1.0))
                    .filter(|(d, _)| *d < 1e-3)
                    .collect::<Vec<_>>();
                if host.len() == 1 && !host[0].1 {
                    t += 1;
                } else {
                    other += 1;
                }
            }
        }
        (t, other)
    }

    #[test]
    fn most_junctions_are_t_junctions() {
        for seed in [1, 8] {
            let c = cracked(seed);
            let (t, other) = junctions(&c);
            assert!(t + other > 50, "{t} + {other} junctions");
            let share = t as f64 / (t + other) as f64;
            assert!(share > 0.5, "T-junctions {t} of {}", t + other);
        }
    }

    #[test]
    fn plates_are_about_a_spacing_squared_and_cracks_narrow_with_generations() {
        let c = cracked(8);
        let areas: Vec<f64> = c.plates.iter().map(|p| p.area().abs()).collect();
        let mean = areas.iter().sum::<f64>() / areas.len() as f64;
        assert!((50.0..150.0).contains(&mean), "mean plate {mean} mm²");
        // The plates and the cracks between them tile the page.
        let cracked_area = 190.0 * 128.0 - areas.iter().sum::<f64>();
        assert!(cracked_area > 0.02 * 190.0 * 128.0, "{cracked_area}");
        let first = &c.cracks[0];
        let last = c.cracks.last().unwrap();
        assert_eq!(first.width, 1.6);
        assert!(last.width < first.width && last.width >= 0.7);
        // The first crack crosses the page; the last ones are plate-sized.
        assert!(path_length(&first.centre) > 100.0);
        assert!(path_length(&last.centre) < 30.0);
    }

    #[test]
    fn the_same_seed_cracks_the_same_way() {
        let (a, b) = (cracked(3), cracked(3));
        assert_eq!(a.plates, b.plates);
        assert_ne!(a.plates, cracked(4).plates);
    }

    #[test]
    fn too_fine_a_spacing_is_refused() {
        let e = crack(&page(), 0.1, [1.0, 0.5], &mut Seed(1).stream()).unwrap_err();
        assert!(e.to_string().contains("spacing"), "{e}");
    }
}
