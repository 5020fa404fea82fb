//! Lines on the page that motifs follow or stop at: control points made
//! into natural splines, and the overall flow of a scene (docs/SPEC.md §1.1): the
//! upper and lower region lines that stop growth.

use kurbo::{BezPath, Point};

use crate::geom::{natural_spline, Side, SideTest};
use crate::spec::{Points, RegionLinesSpec};

/// Natural spline through control points given as `[x, y]` pairs.
pub(crate) fn flow_line(points: &Points) -> BezPath {
    let pts: Vec<Point> = points.iter().map(|[x, y]| Point::new(*x, *y)).collect();
    natural_spline(&pts)
}

/// The overall flow: what stops growth, and the region lines themselves
/// (strokes for a sketch to grow along).
#[derive(Debug)]
pub(crate) struct Flow {
    upper: Option<SideTest>,
    lower: Option<SideTest>,
    lines: [Option<BezPath>; 2],
}

/// A region line as a far-side test. The line is taken left to right (its
/// points are reversed when the last lies left of the first), so the far
/// side of the upper line is above it and that of the lower line below.
fn region_test(points: &Points, far: Side) -> Option<SideTest> {
    Some(SideTest::new(&left_to_right(points)?, far))
}

/// A region line as a spline taken left to right.
fn left_to_right(points: &Points) -> Option<BezPath> {
    let mut pts = points.clone();
    if pts.first()?[0] > pts.last()?[0] {
        pts.reverse();
    }
    Some(flow_line(&pts))
}

impl Flow {
    /// The flow of a scene description's `[lines]`.
    pub(crate) fn new(lines: &RegionLinesSpec) -> Flow {
        Flow {
            upper: lines
                .upper
                .as_ref()
                .and_then(|p| region_test(p, Side::Left)),
            lower: lines
                .lower
                .as_ref()
                .and_then(|p| region_test(p, Side::Right)),
            lines: [
                lines.upper.as_ref().and_then(left_to_right),
                lines.lower.as_ref().and_then(left_to_right),
            ],
        }
    }

    /// The upper (`upper`) or the lower region line, left to right.
    pub(crate) fn line(&self, upper: bool) -> Option<&BezPath> {
        self.lines[usize::from(!upper)].as_ref()
    }

    /// How far `p` lies below the upper region line, in mm along the
    /// line's normal (negative beyond it); `None` without an upper line.
    pub(crate) fn headroom(&self, p: Point) -> Option<f64> {
        self.upper.as_ref().map(|t| -t.signed_distance(p))
    }

    /// True when `p` may not be part of a plant: beyond the upper line, or
    /// — for one growing downward — beyond the lower line.
    pub(crate) fn blocks(&self, p: Point, downward: bool) -> bool {
        self.upper.as_ref().is_some_and(|t| t.is_beyond(p))
            || (downward && self.lower.as_ref().is_some_and(|t| t.is_beyond(p)))
    }
}
