//! From a 3D skeleton to page paths: the orthographic projection, and each
//! limb as an exact polyline, a smooth spline, or an outline as wide as
//! the turtle's width along it.

use glam::DVec3;
use kurbo::{BezPath, Point, Rect, Vec2};

use super::ornament::Site;

use crate::family::lsystem::engine::Skeleton;
use crate::geom::{natural_spline, outline_with_widths};

/// An orthographic view: page x along `right`, page y down along −`up`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Projection {
    right: DVec3,
    up: DVec3,
}

impl Projection {
    /// A sketch's own frame: page millimetres with y down, seen from +z.
    pub(super) const PAGE: Projection = Projection {
        right: DVec3::X,
        up: DVec3::NEG_Y,
    };

    /// Looking along `direction` with `up` up the page (validated: not
    /// parallel, not zero).
    pub(super) fn of((direction, up): ([f64; 3], [f64; 3])) -> Projection {
        let d = DVec3::from_array(direction).normalize();
        let right = d.cross(DVec3::from_array(up)).normalize();
        Projection {
            right,
            up: right.cross(d),
        }
    }

    /// Its right and up in the drawing's frame.
    pub(super) fn axes(&self) -> (DVec3, DVec3) {
        (self.right, self.up)
    }

    fn point(&self, p: DVec3) -> Point {
        Point::new(p.dot(self.right), -p.dot(self.up))
    }
}

/// A limb on the page: its points and the width at each.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct FlatLimb {
    pub(super) points: Vec<Point>,
    pub(super) widths: Vec<f64>,
}

/// A recorded symbol on the page: where, and where the turtle headed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct FlatMark {
    pub(super) symbol: char,
    pub(super) at: Point,
    pub(super) heading: Vec2,
}

impl FlatLimb {
    /// The polyline's length.
    pub(super) fn length(&self) -> f64 {
        self.points.windows(2).map(|w| w[0].distance(w[1])).sum()
    }
}

/// A skeleton on the page, in its own units.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Flat {
    pub(super) limbs: Vec<FlatLimb>,
    pub(super) polygons: Vec<Vec<Point>>,
    /// The ends of the limbs nothing grows on from, with their direction.
    pub(super) tips: Vec<Site>,
    pub(super) marks: Vec<FlatMark>,
}

impl Flat {
    /// The box of every point (empty at the origin for an empty drawing);
    /// with `outline`, of a disc as wide as the limb around each.
    pub(super) fn bounds(&self, outline: bool) -> Rect {
        let limbs = self.limbs.iter().flat_map(|l| {
            l.points.iter().zip(&l.widths).map(move |(&p, &w)| {
                let r = if outline { w.max(0.0) / 2.0 } else { 0.0 };
                Rect::from_center_size(p, (2.0 * r, 2.0 * r))
            })
        });
        let polygons = self
            .polygons
            .iter()
            .flatten()
            .map(|&p| Rect::from_points(p, p));
        limbs
            .chain(polygons)
            .reduce(|a, b| a.union(b))
            .unwrap_or_default()
    }
}

/// The skeleton seen through `view`. Limbs that collapse to a point in
/// this view (seen end on) are left out.
pub(super) fn flat(skeleton: &Skeleton, view: &Projection) -> Flat {
    let direction = |at: DVec3, heading: DVec3| view.point(at + heading) - view.point(at);
    let tips = skeleton
        .limbs
        .iter()
        .filter(|l| l.tip && l.points.len() >= 2)
        .map(|l| {
            let n = l.points.len();
            Site {
                at: view.point(l.points[n - 1]),
                heading: direction(l.points[n - 2], l.points[n - 1] - l.points[n - 2]),
            }
        })
        .collect();
    let marks = skeleton
        .marks
        .iter()
        .map(|m| FlatMark {
            symbol: m.symbol,
            at: view.point(m.at),
            heading: direction(m.at, m.heading),
        })
        .collect();
    let limbs = skeleton
        .limbs
        .iter()
        .map(|l| FlatLimb {
            points: l.points.iter().map(|&p| view.point(p)).collect(),
            widths: l.widths.clone(),
        })
        .filter(|l| l.points.windows(2).any(|w| w[0].distance(w[1]) > 1e-9))
        .collect();
    let polygons = skeleton
        .polygons
        .iter()
        .map(|poly| poly.iter().map(|&p| view.point(p)).collect::<Vec<_>>())
        .filter(|poly| poly.len() >= 3)
        .collect();
    Flat {
        limbs,
        polygons,
        tips,
        marks,
    }
}

/// A limb as a path in its drawing's units: the polyline, or a spline
/// through its points with `smooth`; with `outline`, a closed outline as
/// wide as the turtle's width (in the same units: placing the drawing
/// scales both alike).
pub(super) fn limb_path(limb: &FlatLimb, smooth: bool, outline: bool) -> BezPath {
    let centre = if smooth && limb.points.len() > 2 {
        natural_spline(&limb.points)
    } else {
        let mut line = BezPath::new();
        line.move_to(limb.points[0]);
        for &p in &limb.points[1..] {
            line.line_to(p);
        }
        line
    };
    if !outline {
        return centre;
    }
    // The width at a fraction of the limb's length, linear between its
    // points (measured along the polyline: close enough for a spline
    // through the same points).
    let mut along = Vec::with_capacity(limb.points.len());
    let mut total = 0.0;
    for (i, p) in limb.points.iter().enumerate() {
        if i > 0 {
            total += limb.points[i - 1].distance(*p);
        }
        along.push(total);
    }
    let width = |f: f64| {
        let s = f * total;
        let i = along.partition_point(|&a| a < s).clamp(1, along.len() - 1);
        let (a, b) = (along[i - 1], along[i]);
        let t = if b > a {
            ((s - a) / (b - a)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        limb.widths[i - 1] + (limb.widths[i] - limb.widths[i - 1]) * t
    };
    outline_with_widths(&centre, &width)
}

/// A `{ … }` polygon as a closed path.
pub(super) fn polygon_path(points: &[Point]) -> BezPath {
    let mut path = BezPath::new();
    path.move_to(points[0]);
    for &p in &points[1..] {
        path.line_to(p);
    }
    path.close_path();
    path
}
