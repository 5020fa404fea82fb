//! What marks do to a white region: the paper's filling step 3 (SPEC
//! §2.4, "draw the procedure only inside that region; the drawing splits
//! it") in vector form.
//!
//! [`compose`] takes a region and [`Mark`]s in painter's order (already
//! placed on the page) and returns
//! - the **visible lines**: each mark's path (a line, or a closed mark's
//!   outline) clipped to the region, minus the parts under the interior of
//!   a *later* white or black mark;
//! - the **white pieces** left: every point of the region whose topmost
//!   paint is white (a white mark, or the region's own background), minus
//!   the ink of the visible lines — each line buffered by half the pen
//!   width, as ink on paper, so a line across a region splits it in two.
//!   One [`Piece`] per connected part, holes kept, with the index of the
//!   white mark it lies in (the filling loop takes its next seed from
//!   that mark's procedure), or `None` for the region's background;
//!   pieces narrower than the pen cannot be drawn in and are dropped;
//! - the **black area**: where the topmost paint is black, one region per
//!   connected part. Nothing more is drawn there; the plot pipeline
//!   hatches it ([`crate::plot::hatch`]).
//!
//! So the region is partitioned: white pieces, black area and the ink of
//! the visible lines (which overlaps the black area along black outlines)
//! cover it, up to the dropped slivers and the flattening of the ink.
//!
//! **Why here and not in the plot pipeline.** [`crate::plot::occlude`]
//! hides lines under later fills for a whole scene, but the filling loop
//! needs the pieces *now*, to choose the next region; the strokes this
//! returns are final, and the family writes them as plain lines (black
//! areas as filled paths for hatching), so occlusion has nothing left to
//! hide among them.
//!
//! **Exact where it shows, polygons where it is ink.** Visible lines are
//! exact sub-curves of the marks ([`StrokeClipper`]). Black areas are
//! polygons within `tolerance` of the marks' curves (they are hatched, or
//! kept as fills that hide under the lines drawn on their edges): exact
//! curve booleans for them took two thirds of a tangle's time. The ink is
//! a polygon: lines flattened within `tolerance` and
//! stroked by i_overlay with round caps and joins (an exact integer sweep
//! that also unions the overlaps). kurbo's stroker keeps cubics, but its
//! outline folds over itself where the pen is wider than a curve's radius
//! and must be untangled by a boolean sweep; measured on a tangle's worth
//! of lines (the ignored test `ink_speed`: 98 lines, 2-core machine,
//! release) that costs about 4× the i_overlay stroke. A white piece is
//! bounded mostly by ink, so white pieces are cut by i_overlay on polygons
//! flattened within `tolerance` too: 4× faster than the same cuts by
//! [`Region::difference_all`] (whose sweep keeps curves there is no use
//! keeping), 54 ms instead of 215 ms for the 98 marks of `ink_speed`.
//!
//! **Cost.** Every fill mark's interior is made a [`Region`] once (one
//! sweep of its own curves), its outline a [`StrokeClipper`] once and its
//! polygon once; their boxes go into an R-tree, as do the inks' boxes. A
//! mark's path is clipped by the region and then by the later fills whose
//! boxes meet it, in turn (the outside of each is the outside of their
//! union, without building it). Its ink is one i_overlay stroke of its
//! visible lines. Each white area is one polygon cut of the mark's
//! interior by the later fills and the inks whose boxes meet it, each
//! black area one polygon cut by the later fills that meet it; a mark
//! inside the region (its outline does not leave it, no hole of the
//! region lies in it) needs no cut by the region. So the work is linear
//! in the marks times the number of marks stacked on one spot, plus the
//! region's own outline once per mark that crosses it; nothing is
//! compared with everything.

use i_overlay::core::fill_rule::FillRule as IFill;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::float::single::SingleFloatOverlay;
use i_overlay::mesh::float::stroke::offset::StrokeOffset;
use i_overlay::mesh::float::style::{LineCap, LineJoin, StrokeStyle};
use kurbo::{BezPath, ParamCurve, PathEl, Point, Rect, Shape as _};
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{RTree, AABB};

use super::element::{Mark, Paint};
use crate::error::{Error, Result};
use crate::geom::clip::StrokeClipper;
use crate::geom::region::{check_coordinates, path_from_shapes, FillRule, Region, SLIVER_WIDTH};
use crate::geom::subpath::subpaths;
use crate::geom::TOLERANCE;

/// Round caps and joins are made of steps of at most this angle (i_overlay
/// clamps it to [0.01π, 0.25π]); the sagitta `r·θ²/8` of a step is what
/// decides it (see [`ink`]).
const MAX_ARC_STEP: f64 = 0.25 * std::f64::consts::PI;

/// A white part of a composed region.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Piece {
    /// The part: connected, holes kept.
    pub(crate) region: Region,
    /// The index of the topmost white mark whose interior holds the part,
    /// or `None` for the background of the region itself.
    pub(crate) inside: Option<usize>,
}

/// What [`compose`] leaves of a region.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Composed {
    /// The visible lines, mark by mark in painter's order, each inside
    /// the region.
    pub(crate) strokes: Vec<BezPath>,
    /// The white area left, one piece per connected part: the background
    /// first, then the pieces of each white mark in order.
    pub(crate) white: Vec<Piece>,
    /// The black area inside the region, one region per connected part.
    pub(crate) black: Vec<Region>,
}

/// Draws `marks` (painter's order, page coordinates) into `region` with a
/// pen `pen_width` mm wide; lines and outlines are flattened within
/// `tolerance` mm for clipping and for their ink (non-finite or
/// non-positive means [`TOLERANCE`]). See the [module docs](self).
///
/// A mark that crosses the region's edge leaves pieces of its line that
/// end on the edge; those shorter than `fragment` mm (after later fills
/// hid what they hide) are dropped, and take no ink: the stubs and
/// corner brackets of an element clipped to a sliver are debris to the
/// eye, not part of a tangle.
///
/// A fill mark whose path encloses no area (a degenerate outline) paints
/// nothing; its path is still drawn.
///
/// # Errors
/// When `pen_width` is not a finite positive number, or a mark has a
/// coordinate that is not finite or lies beyond the page limit.
pub(crate) fn compose(
    region: &Region,
    marks: &[Mark],
    pen_width: f64,
    tolerance: f64,
    fragment: f64,
) -> Result<Composed> {
    if !(pen_width.is_finite() && pen_width > 0.0) {
        return Err(Error::invalid(
            "compose.pen_width",
            format!("must be a finite number of mm > 0, got {pen_width}"),
        ));
    }
    let tolerance = if tolerance.is_finite() && tolerance > 0.0 {
        tolerance
    } else {
        TOLERANCE
    };
    for (i, m) in marks.iter().enumerate() {
        check_coordinates(&m.path)
            .map_err(|e| Error::invalid(format!("compose.marks[{i}]"), e.to_string()))?;
    }
    if region.is_empty() {
        return Ok(Composed::default());
    }

    // Interiors of the fill marks; a path that encloses nothing paints
    // nothing (its coordinates were checked, so that is the only failure).
    let areas: Vec<Option<Region>> = marks
        .iter()
        .map(|m| {
            m.fills()
                .then(|| Region::new(m.path.clone(), FillRule::NonZero).ok())
                .flatten()
        })
        .collect();
    let fills = BoxIndex::new(areas.iter().map(|a| a.as_ref().map(Region::bounds)));
    let fill_clippers: Vec<Option<StrokeClipper>> = areas
        .iter()
        .map(|a| a.as_ref().map(|r| StrokeClipper::new(r, tolerance)))
        .collect();

    // Visible lines of each mark, and their ink.
    let inside_region = StrokeClipper::new(region, tolerance);
    let mut strokes = Vec::new();
    let mut inks: Vec<Option<Region>> = Vec::with_capacity(marks.len());
    for (i, m) in marks.iter().enumerate() {
        let cut = inside_region.clip(&m.path);
        // Where the mark crosses the edge: the ends its inside and outside
        // pieces share.
        let on_edge: Vec<Point> = ends(&cut.outside)
            .filter(|p| ends(&cut.inside).any(|q| q.distance(*p) < EDGE_EPS))
            .collect();
        let mut visible = cut.inside;
        if !visible.is_empty() {
            for j in fills.meeting(m.path.bounding_box()) {
                if j <= i {
                    continue;
                }
                if let Some(c) = &fill_clippers[j] {
                    visible = visible.iter().flat_map(|l| c.clip(l).outside).collect();
                }
            }
            visible.retain(|l| {
                let length = l.perimeter(tolerance);
                length >= tolerance
                    && (length >= fragment
                        || !ends(std::slice::from_ref(l))
                            .any(|p| on_edge.iter().any(|q| q.distance(p) < EDGE_EPS)))
            });
        }
        let ink = ink(&visible, pen_width / 2.0, tolerance);
        inks.push((!ink.is_empty()).then_some(ink));
        strokes.extend(visible);
    }
    let ink_index = BoxIndex::new(inks.iter().map(|a| a.as_ref().map(Region::bounds)));

    // White areas are cut by polygons (see the module docs): every fill's
    // interior and every ink flattened once.
    let flatten = |regions: &[Option<Region>]| -> Vec<Polygons> {
        regions
            .iter()
            .map(|a| {
                a.as_ref()
                    .map(|r| polygons(r, tolerance))
                    .unwrap_or_default()
            })
            .collect()
    };
    let fill_polygons = flatten(&areas);
    let ink_polygons = flatten(&inks);
    // Everything painted or inked over a box after mark `after` (after
    // nothing for `None`): later fills and all the ink.
    let cover = |bounds: Rect, after: Option<usize>| -> Polygons {
        let later = fills
            .meeting(bounds)
            .into_iter()
            .filter(|&j| after.is_none_or(|i| j > i))
            .flat_map(|j| fill_polygons[j].iter().cloned());
        let inked = ink_index
            .meeting(bounds)
            .into_iter()
            .flat_map(|j| ink_polygons[j].iter().cloned());
        later.chain(inked).collect()
    };
    // Each contour of the region: its box and a point on it.
    let region_contours: Vec<(Rect, Point)> = subpaths(region.path())
        .map(|c| (c.to_path().bounding_box(), c.start()))
        .collect();
    let mut white = Vec::new();
    let background = overlay(
        &polygons(region, tolerance),
        &cover(region.bounds(), None),
        OverlayRule::Difference,
    );
    push_pieces(&mut white, &background, None, pen_width, tolerance);
    let region_polygons = polygons(region, tolerance);
    let mut black: Polygons = Vec::new();
    for (i, (m, area)) in marks.iter().zip(&areas).enumerate() {
        let Some(area) = area else { continue };
        // Most marks lie inside the region: their outline does not leave
        // it and no contour of the region (a hole) lies inside them. Then
        // there is nothing to cut.
        let within = inside_region.clip(area.path()).outside.is_empty()
            && fill_clippers[i].as_ref().is_some_and(|c| {
                let b = area.bounds();
                !region_contours
                    .iter()
                    .any(|(cb, p)| cb.overlaps(b) && c.contains(*p))
            });
        let base = if within {
            fill_polygons[i].clone()
        } else {
            // Only the part of the region near the mark takes part: a
            // long outline would otherwise be swept again for every mark
            // that crosses it.
            let near = within_rect(&region_polygons, area.bounds().inflate(1.0, 1.0));
            cut(&fill_polygons[i], &near, OverlayRule::Intersect)
        };
        if base.is_empty() {
            continue;
        }
        if m.paint == Paint::White {
            let shown = overlay(
                &base,
                &cover(area.bounds(), Some(i)),
                OverlayRule::Difference,
            );
            push_pieces(&mut white, &shown, Some(i), pen_width, tolerance);
        } else {
            let later: Polygons = fills
                .meeting(area.bounds())
                .into_iter()
                .filter(|&j| j > i)
                .flat_map(|j| fill_polygons[j].iter().cloned())
                .collect();
            black.extend(cut(&base, &later, OverlayRule::Difference));
        }
    }
    let black = overlay(&black, &Vec::new(), OverlayRule::Union).components();
    Ok(Composed {
        strokes,
        white,
        black,
    })
}

/// Ends closer than this (mm) are the same cut point of a mark's line.
const EDGE_EPS: f64 = 1e-6;

/// The first and last points of each line.
fn ends(lines: &[BezPath]) -> impl Iterator<Item = Point> + '_ {
    lines.iter().flat_map(|l| {
        let first = match l.elements().first() {
            Some(PathEl::MoveTo(p)) => Some(*p),
            _ => None,
        };
        first.into_iter().chain(l.segments().last().map(|s| s.eval(1.0)))
    })
}

/// The white parts of `region` left when `lines` are inked over it whole
/// (each part at least `pen_width` wide): for lines drawn as they are,
/// such as a border on the region's own edge, which [`compose`] would
/// clip to pieces.
pub(crate) fn uninked(
    region: &Region,
    lines: &[BezPath],
    pen_width: f64,
    tolerance: f64,
) -> Vec<Region> {
    let ink = ink(lines, pen_width / 2.0, tolerance);
    let left = overlay(
        &polygons(region, tolerance),
        &polygons(&ink, tolerance),
        OverlayRule::Difference,
    );
    let mut pieces = Vec::new();
    push_pieces(&mut pieces, &left, None, pen_width, tolerance);
    pieces.into_iter().map(|p| p.region).collect()
}

/// Closed polygons as i_overlay takes them.
type Polygons = Vec<Vec<[f64; 2]>>;

/// The boundary of `region` flattened within `tolerance`.
fn polygons(region: &Region, tolerance: f64) -> Polygons {
    region
        .polygons(tolerance)
        .into_iter()
        .map(|c| c.into_iter().map(|p| [p.x, p.y]).collect())
        .collect()
}

/// The parts of `polygons` inside `rect` (Sutherland-Hodgman on each
/// contour that meets it: a concave contour may come back with zero-width
/// runs along the rectangle's edges, which add nothing under the non-zero
/// rule). Contours wholly inside are kept as they are.
fn within_rect(polygons: &Polygons, rect: Rect) -> Polygons {
    let mut out = Vec::new();
    for contour in polygons {
        let Some(b) = contour_bounds(contour) else {
            continue;
        };
        if !b.overlaps(rect) {
            continue;
        }
        if rect.contains_rect(b) {
            out.push(contour.clone());
            continue;
        }
        let mut c = contour.clone();
        // Keep the side of each edge of the rectangle that holds it.
        let sides: [(usize, f64, bool); 4] = [
            (0, rect.x0, true),
            (0, rect.x1, false),
            (1, rect.y0, true),
            (1, rect.y1, false),
        ];
        for (axis, at, above) in sides {
            let inside = |p: &[f64; 2]| if above { p[axis] >= at } else { p[axis] <= at };
            let mut next = Vec::with_capacity(c.len() + 4);
            for (k, p) in c.iter().enumerate() {
                let q = &c[(k + 1) % c.len()];
                if inside(p) {
                    next.push(*p);
                }
                if inside(p) != inside(q) {
                    let t = (at - p[axis]) / (q[axis] - p[axis]);
                    next.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
                }
            }
            c = next;
            if c.len() < 3 {
                break;
            }
        }
        if c.len() >= 3 {
            out.push(c);
        }
    }
    out
}

fn contour_bounds(c: &[[f64; 2]]) -> Option<Rect> {
    let first = c.first()?;
    Some(
        c.iter()
            .fold(Rect::new(first[0], first[1], first[0], first[1]), |r, p| {
                r.union_pt(Point::new(p[0], p[1]))
            }),
    )
}

/// `subject` combined with `clip` by i_overlay, as contours (outer ones
/// and holes wound oppositely, so the non-zero rule reads them back).
fn cut(subject: &Polygons, clip: &Polygons, rule: OverlayRule) -> Polygons {
    if subject.is_empty() {
        return Vec::new();
    }
    subject
        .overlay(clip, rule, IFill::NonZero)
        .into_iter()
        .flatten()
        .collect()
}

/// `subject` combined with `clip` by i_overlay (non-zero rule: normalised
/// regions put together wind once per region holding a point).
fn overlay(subject: &Polygons, clip: &Polygons, rule: OverlayRule) -> Region {
    if subject.is_empty() {
        return Region::empty();
    }
    let shapes = subject.overlay(clip, rule, IFill::NonZero);
    Region::from_normalised(path_from_shapes(&shapes, SLIVER_WIDTH))
}

/// Appends the connected parts of `area` to `out` as pieces inside
/// `inside`, except those whose mean width `2·area / perimeter` is below
/// `min_width` (strips narrower than the pen, discs of a smaller radius:
/// nothing can be drawn in them).
fn push_pieces(
    out: &mut Vec<Piece>,
    area: &Region,
    inside: Option<usize>,
    min_width: f64,
    tolerance: f64,
) {
    for part in area.components() {
        if 2.0 * part.area() >= min_width * part.perimeter(tolerance) {
            out.push(Piece {
                region: part,
                inside,
            });
        }
    }
}

/// The ink of `lines` drawn with a pen of radius `half_width`: the lines
/// flattened within `tolerance` and stroked with round caps and joins, as
/// one normalised region.
fn ink(lines: &[BezPath], half_width: f64, tolerance: f64) -> Region {
    let mut polylines: Vec<Vec<[f64; 2]>> = Vec::new();
    for line in lines {
        let mut current: Vec<[f64; 2]> = Vec::new();
        let mut start = Point::ORIGIN;
        let mut finish = |c: &mut Vec<[f64; 2]>| {
            if c.len() >= 2 {
                polylines.push(std::mem::take(c));
            } else {
                c.clear();
            }
        };
        kurbo::flatten(line, tolerance, |el| match el {
            PathEl::MoveTo(p) => {
                finish(&mut current);
                start = p;
                current.push([p.x, p.y]);
            }
            PathEl::LineTo(p) | PathEl::QuadTo(_, p) | PathEl::CurveTo(_, _, p) => {
                if current.last() != Some(&[p.x, p.y]) {
                    current.push([p.x, p.y]);
                }
            }
            // An open polyline back to its start with round caps covers
            // the same ink as a closed one: the cap fills the join.
            PathEl::ClosePath => {
                if current.last() != Some(&[start.x, start.y]) {
                    current.push([start.x, start.y]);
                }
            }
        });
        finish(&mut current);
    }
    if polylines.is_empty() || half_width.is_nan() || half_width <= 0.0 {
        return Region::empty();
    }
    // Sagitta of a step θ on radius r: r·θ²/8 ≤ tolerance.
    let step = (8.0 * tolerance / half_width).sqrt().min(MAX_ARC_STEP);
    let style = StrokeStyle::new(2.0 * half_width)
        .start_cap(LineCap::Round(step))
        .end_cap(LineCap::Round(step))
        .line_join(LineJoin::Round(step));
    let shapes = polylines.stroke(style, false);
    Region::from_normalised(path_from_shapes(&shapes, SLIVER_WIDTH))
}

/// Boxes by index, for the question "which of them meet this box?".
struct BoxIndex {
    tree: RTree<GeomWithData<Rectangle<[f64; 2]>, usize>>,
}

impl BoxIndex {
    /// The index of `boxes` (`None`: nothing at that index).
    fn new(boxes: impl Iterator<Item = Option<Rect>>) -> BoxIndex {
        let entries = boxes
            .enumerate()
            .filter_map(|(k, b)| {
                b.map(|b| GeomWithData::new(Rectangle::from_corners([b.x0, b.y0], [b.x1, b.y1]), k))
            })
            .collect();
        BoxIndex {
            tree: RTree::bulk_load(entries),
        }
    }

    /// The indices of the boxes meeting `r`, ascending.
    fn meeting(&self, r: Rect) -> Vec<usize> {
        let env = AABB::from_corners([r.x0, r.y0], [r.x1, r.y1]);
        let mut found: Vec<usize> = self
            .tree
            .locate_in_envelope_intersecting(&env)
            .map(|e| e.data)
            .collect();
        found.sort_unstable();
        found
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::family::zentangle::element::tests::{distance_to, samples};
    use crate::family::zentangle::element::{marks, wobble, Shape};
    use crate::rng::Seed;
    use kurbo::{Affine, Circle, Line};

    const PEN: f64 = 0.3;
    const TOL: f64 = 0.01;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Region {
        Region::from_rect(Rect::new(x0, y0, x1, y1)).unwrap()
    }

    fn line(a: (f64, f64), b: (f64, f64)) -> Mark {
        Mark {
            path: Line::new(a, b).to_path(0.0),
            paint: Paint::Line,
        }
    }

    fn filled(path: BezPath, paint: Paint) -> Mark {
        Mark { path, paint }
    }

    fn length(lines: &[BezPath]) -> f64 {
        lines.iter().map(|l| l.perimeter(1e-9)).sum()
    }

    fn white_area(c: &Composed) -> f64 {
        c.white.iter().map(|p| p.region.area()).sum()
    }

    /// An element `shape` with `fill`, wobbled by `seed`, placed at
    /// `centre` with half-size `half`.
    fn element(shape: Shape, fill: Paint, seed: u64, centre: (f64, f64), half: f64) -> Vec<Mark> {
        let m = wobble(
            &marks(shape, fill),
            1.0,
            1.0,
            &mut Seed(seed).stream(),
            1e-4,
        )
        .unwrap();
        let at = Affine::translate(centre) * Affine::scale(half);
        m.iter().map(|k| k.transformed(at)).collect()
    }

    /// The region's area is white + ink ∪ black, up to what flattening
    /// the ink within TOL can move (TOL along both sides of every visible
    /// line: 2·TOL·length, plus the round ends) and the slivers dropped
    /// (none in these drawings: checked by the piece counts elsewhere).
    fn check_partition(region: &Region, c: &Composed) {
        let ink = ink(&c.strokes, PEN / 2.0, TOL);
        let mut dark = c.black.clone();
        dark.push(ink);
        let dark = Region::union_all(&dark).intersection(region);
        let total = white_area(c) + dark.area();
        let slack = 2.0 * TOL * length(&c.strokes) + 1e-6 * region.area();
        assert!(
            (total - region.area()).abs() <= slack,
            "white {} + dark {} = {total} vs {} (slack {slack})",
            white_area(c),
            dark.area(),
            region.area()
        );
        // No white piece overlaps the ink or the black area.
        for p in &c.white {
            assert!(p.region.intersection(&dark).area() <= slack);
        }
    }

    fn check_strokes_inside(region: &Region, c: &Composed) {
        for s in &c.strokes {
            for p in samples(s) {
                let d = distance_to(region.path(), p);
                assert!(region.contains(p) || d <= 2.0 * TOL, "{p:?} is {d} outside");
            }
        }
    }

    #[test]
    fn a_line_across_a_square_splits_it_in_two() {
        let sq = rect(0.0, 0.0, 10.0, 10.0);
        // Longer than the square: clipped to it.
        let c = compose(&sq, &[line((-5.0, 4.0), (15.0, 4.0))], PEN, TOL, 0.0).unwrap();
        assert_eq!(c.white.len(), 2);
        assert!(c.white.iter().all(|p| p.inside.is_none()));
        assert!((length(&c.strokes) - 10.0).abs() < 1e-9);
        let mut areas: Vec<f64> = c.white.iter().map(|p| p.region.area()).collect();
        areas.sort_by(f64::total_cmp);
        // 10 × (4 − 0.15) and 10 × (6 − 0.15).
        assert!((areas[0] - 38.5).abs() < 1e-3, "{areas:?}");
        assert!((areas[1] - 58.5).abs() < 1e-3, "{areas:?}");
        assert!(c.black.is_empty());
        check_partition(&sq, &c);
    }

    #[test]
    fn a_white_square_makes_a_piece_of_its_own_and_a_hole() {
        let sq = rect(0.0, 0.0, 20.0, 20.0);
        let inner = Rect::new(5.0, 5.0, 15.0, 15.0).to_path(0.0);
        let c = compose(&sq, &[filled(inner, Paint::White)], PEN, TOL, 0.0).unwrap();
        assert_eq!(c.white.len(), 2);
        let bg = &c.white[0];
        assert_eq!(bg.inside, None);
        // One outer contour and one hole.
        assert_eq!(crate::geom::subpath::subpaths(bg.region.path()).count(), 2);
        assert!(!bg.region.contains(Point::new(10.0, 10.0)));
        assert!(
            (bg.region.area()
                - (400.0 - (10.3 * 10.3 - (PEN * PEN - std::f64::consts::PI * 0.0225))))
                .abs()
                < 0.01,
            "{}",
            bg.region.area()
        );
        let own = &c.white[1];
        assert_eq!(own.inside, Some(0));
        assert!((own.region.area() - 9.7 * 9.7).abs() < 1e-3);
        assert!(own.region.contains(Point::new(10.0, 10.0)));
        check_partition(&sq, &c);
    }

    #[test]
    fn a_black_square_is_finished_and_hides_what_lies_under_it() {
        let sq = rect(0.0, 0.0, 20.0, 20.0);
        let marks = [
            line((0.0, 10.0), (20.0, 10.0)),
            filled(Rect::new(5.0, 5.0, 15.0, 15.0).to_path(0.0), Paint::Black),
        ];
        let c = compose(&sq, &marks, PEN, TOL, 0.0).unwrap();
        assert_eq!(c.black.len(), 1);
        assert!((c.black[0].area() - 100.0).abs() < 1e-6);
        // The line shows only outside the square: 2 × 5, plus the outline.
        assert!((length(&c.strokes) - (10.0 + 40.0)).abs() < 1e-6);
        // The line cuts the white ring into two pieces, none inside black.
        assert_eq!(c.white.len(), 2);
        assert!(c
            .white
            .iter()
            .all(|p| !p.region.contains(Point::new(10.0, 12.0))));
        check_partition(&sq, &c);
        // Drawn the other way round, the line lies over the square.
        let c = compose(&sq, &[marks[1].clone(), marks[0].clone()], PEN, TOL, 0.0).unwrap();
        assert!((length(&c.strokes) - (20.0 + 40.0)).abs() < 1e-6);
    }

    #[test]
    fn later_white_covers_earlier_black() {
        // mtr1-like: black disc, white disc in it, black dot in that.
        let sq = rect(-20.0, -20.0, 20.0, 20.0);
        let disc = |r: f64| Circle::new((0.0, 0.0), r).to_path(1e-4);
        let marks = [
            filled(disc(15.0), Paint::Black),
            filled(disc(10.0), Paint::White),
            filled(disc(5.0), Paint::Black),
        ];
        let c = compose(&sq, &marks, PEN, TOL, 0.0).unwrap();
        assert_eq!(c.black.len(), 2);
        let black: f64 = c.black.iter().map(Region::area).sum();
        let pi = std::f64::consts::PI;
        // Black is a polygon within TOL of the circles: off by at most
        // their length × TOL.
        let slack = 2.0 * pi * (15.0 + 10.0 + 5.0) * TOL;
        assert!(
            (black - pi * (225.0 - 100.0 + 25.0)).abs() < slack,
            "{black}"
        );
        let ring: Vec<&Piece> = c.white.iter().filter(|p| p.inside == Some(1)).collect();
        assert_eq!(ring.len(), 1);
        let want = pi * ((10.0 - 0.15f64).powi(2) - (5.0 + 0.15f64).powi(2));
        // The ink follows the circles flattened within TOL: the ring's
        // edges move by less than TOL all along them.
        let slack = TOL * 2.0 * pi * (10.0 + 5.0);
        let got = ring[0].region.area();
        assert!((got - want).abs() < slack, "{got} vs {want}");
        check_partition(&sq, &c);
    }

    #[test]
    fn elements_partition_the_region_and_stay_inside_it() {
        // A disc cutting through a few wobbled elements of every kind.
        let disc = Region::new(
            Circle::new((0.0, 0.0), 24.0).to_path(1e-4),
            FillRule::NonZero,
        )
        .unwrap();
        let mut all = Vec::new();
        for (k, s) in [
            Shape::Mtr1,
            Shape::Scl,
            Shape::C3,
            Shape::St,
            Shape::Msq3,
            Shape::Ptr,
        ]
        .into_iter()
        .enumerate()
        {
            let fill = if k % 2 == 0 {
                Paint::White
            } else {
                Paint::Black
            };
            let (x, y) = ((k % 3) as f64 * 16.0 - 16.0, (k / 3) as f64 * 18.0 - 9.0);
            all.extend(element(s, fill, k as u64, (x, y), 9.0));
        }
        let c = compose(&disc, &all, PEN, TOL, 0.0).unwrap();
        assert!(c.white.len() > 10 && !c.black.is_empty());
        check_partition(&disc, &c);
        check_strokes_inside(&disc, &c);
        // Deterministic.
        assert_eq!(compose(&disc, &all, PEN, TOL, 0.0).unwrap(), c);
    }

    /// The visible lines with an end on the region's edge that are
    /// shorter than `min`.
    fn stubs(region: &Region, c: &Composed, min: f64) -> usize {
        c.strokes
            .iter()
            .filter(|s| {
                s.perimeter(1e-6) < min
                    && ends(std::slice::from_ref(*s)).any(|p| distance_to(region.path(), p) < 0.05)
            })
            .count()
    }

    #[test]
    fn no_short_piece_of_a_clipped_element_is_left_on_the_edge() {
        // Small elements all over a disc's rim: clipped, some leave stubs
        // and corner brackets shorter than four pen widths.
        let disc = Region::new(
            Circle::new((0.0, 0.0), 20.0).to_path(1e-4),
            FillRule::NonZero,
        )
        .unwrap();
        let mut all = Vec::new();
        for k in 0..40 {
            let a = f64::from(k) * 0.157;
            let shape = [Shape::Sq, Shape::Tr, Shape::Msq1, Shape::C2][k as usize % 4];
            let fill = if k % 3 == 0 { Paint::Black } else { Paint::White };
            let centre = (20.6 * a.cos(), 20.6 * a.sin());
            all.extend(element(shape, fill, k as u64, centre, 1.5));
        }
        let min = 4.0 * PEN;
        let kept = compose(&disc, &all, PEN, TOL, 0.0).unwrap();
        assert!(stubs(&disc, &kept, min) > 5, "{}", stubs(&disc, &kept, min));
        let trimmed = compose(&disc, &all, PEN, TOL, min).unwrap();
        assert_eq!(stubs(&disc, &trimmed, min), 0);
        // Longer pieces on the edge, and short lines inside, stay.
        assert!(length(&trimmed.strokes) > 0.5 * length(&kept.strokes));
        let inside = [line((0.0, 0.0), (0.5, 0.0))];
        assert_eq!(compose(&disc, &inside, PEN, TOL, min).unwrap().strokes.len(), 1);
        // What is dropped takes no ink: the white left is as if never drawn.
        assert!(white_area(&trimmed) > white_area(&kept));
    }

    #[test]
    fn a_hole_of_the_region_under_a_mark_stays_a_hole() {
        // The white square's outline lies wholly inside the region, but the
        // region's hole lies inside the square.
        let ring = rect(0.0, 0.0, 30.0, 30.0).difference(&rect(12.0, 12.0, 18.0, 18.0));
        let sq = filled(Rect::new(5.0, 5.0, 25.0, 25.0).to_path(0.0), Paint::White);
        let c = compose(&ring, &[sq], PEN, TOL, 0.0).unwrap();
        let own: Vec<&Piece> = c.white.iter().filter(|p| p.inside == Some(0)).collect();
        assert_eq!(own.len(), 1);
        assert!(!own[0].region.contains(Point::new(15.0, 15.0)));
        assert!((own[0].region.area() - (19.7 * 19.7 - 36.0)).abs() < 1e-3);
        check_partition(&ring, &c);
    }

    #[test]
    fn marks_outside_the_region_draw_nothing() {
        let sq = rect(0.0, 0.0, 10.0, 10.0);
        let far = element(Shape::Msq2, Paint::Black, 1, (50.0, 50.0), 5.0);
        let c = compose(&sq, &far, PEN, TOL, 0.0).unwrap();
        assert!(c.strokes.is_empty() && c.black.is_empty());
        assert_eq!(c.white.len(), 1);
        assert_eq!(c.white[0].inside, None);
        assert!((c.white[0].region.area() - 100.0).abs() < 1e-9);
        // Nothing at all, and an empty region.
        assert_eq!(compose(&sq, &[], PEN, TOL, 0.0).unwrap().white.len(), 1);
        assert_eq!(
            compose(&Region::empty(), &far, PEN, TOL, 0.0).unwrap(),
            Composed::default()
        );
    }

    #[test]
    fn slivers_narrower_than_the_pen_are_dropped() {
        // Two lines 0.5 mm apart leave a 0.2 mm strip between their inks.
        let sq = rect(0.0, 0.0, 10.0, 10.0);
        let c = compose(
            &sq,
            &[line((0.0, 5.0), (10.0, 5.0)), line((0.0, 5.5), (10.0, 5.5))],
            PEN,
            TOL,
            0.0,
        )
        .unwrap();
        assert_eq!(c.white.len(), 2);
        // A little wider than the pen, it stays.
        let c = compose(
            &sq,
            &[line((0.0, 5.0), (10.0, 5.0)), line((0.0, 5.7), (10.0, 5.7))],
            PEN,
            TOL,
            0.0,
        )
        .unwrap();
        assert_eq!(c.white.len(), 3);
    }

    #[test]
    fn bad_input_is_an_error() {
        let sq = rect(0.0, 0.0, 10.0, 10.0);
        for w in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(compose(&sq, &[], w, TOL, 0.0).is_err());
        }
        let bad = line((0.0, 0.0), (f64::NAN, 1.0));
        let e = compose(&sq, &[bad], PEN, TOL, 0.0).unwrap_err().to_string();
        assert!(e.contains("marks[0]"), "{e}");
        // A fill that encloses nothing still draws its line.
        let flat = filled(
            Line::new((-1.0, -1.0), (11.0, 11.0)).to_path(0.0),
            Paint::Black,
        );
        let c = compose(&sq, &[flat], PEN, 0.0, 0.0).unwrap();
        assert!(c.black.is_empty() && c.white.len() == 2);
    }

    /// The measurement behind the choice of i_overlay for the ink (module
    /// docs): `cargo test --release --lib ink_speed -- --ignored
    /// --nocapture`.
    #[test]
    #[ignore]
    #[allow(clippy::print_stderr)]
    fn ink_speed() {
        let mut all = Vec::new();
        for (k, s) in Shape::ALL.into_iter().enumerate() {
            let centre = ((k % 6) as f64 * 22.0, (k / 6) as f64 * 22.0);
            let fill = if k % 2 == 0 {
                Paint::White
            } else {
                Paint::Black
            };
            all.extend(element(s, fill, k as u64, centre, 10.0));
        }
        let lines: Vec<BezPath> = all.iter().map(|m| m.path.clone()).collect();
        let t = std::time::Instant::now();
        let ours = ink(&lines, PEN / 2.0, TOL);
        let t_ours = t.elapsed();
        let t = std::time::Instant::now();
        let style = kurbo::Stroke::new(PEN)
            .with_caps(kurbo::Cap::Round)
            .with_join(kurbo::Join::Round);
        let mut outline = BezPath::new();
        for l in &lines {
            outline
                .extend(kurbo::stroke(l.iter(), &style, &kurbo::StrokeOpts::default(), TOL).iter());
        }
        let t_stroke = t.elapsed();
        let theirs = Region::new(outline, FillRule::NonZero).unwrap();
        let t_kurbo = t.elapsed();
        eprintln!(
            "{} lines: i_overlay ink {t_ours:?} (area {:.3}); kurbo stroke {t_stroke:?}, \
             + untangling sweep {t_kurbo:?} (area {:.3})",
            lines.len(),
            ours.area(),
            theirs.area()
        );
        let page = rect(-15.0, -15.0, 130.0, 110.0);
        let t = std::time::Instant::now();
        let c = compose(&page, &all, PEN, TOL, 0.0).unwrap();
        eprintln!(
            "compose({} marks): {:?}, {} white pieces, {} black parts",
            all.len(),
            t.elapsed(),
            c.white.len(),
            c.black.len()
        );
    }
}
