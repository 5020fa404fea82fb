//! Geometry helpers on top of kurbo that more than one stage or family
//! uses: natural splines, walking a path by arc length, the "far side of
//! a line" test, tapered outlines, a nearest-point index, the reading of a
//! path's subpaths that every stage shares, shapes stacked in depth that
//! hide one another, points spread inside a region (uniform, jittered
//! grid, Poisson-disk), Voronoi cells, Delaunay triangulations and Lloyd
//! relaxation inside a region, and one tour through many points. Geometry
//! only one family uses lives in that family's folder (`crate::family`).
//!
//! Coordinates are page coordinates in millimetres with y pointing *down*
//! (the SVG convention). "Left" and "right" are as seen by someone walking
//! along a direction on the page: for a direction pointing up the page,
//! left is towards smaller x.

pub mod clip;
pub mod density;
pub mod depth;
pub(crate) mod engine_panic;
pub(crate) mod mesh;
pub mod offset;
pub mod polylabel;
pub mod region;
pub mod sample;
pub mod subpath;
pub mod trace;
pub mod voronoi;

mod point_index;
mod segments;
mod side;
pub(crate) mod simplify;
mod spline;
mod taper;
mod tour;
mod walk;

pub use point_index::PointIndex;
pub(crate) use segments::segment_distance_3d;
pub use side::SideTest;
pub use spline::{natural_spline, natural_spline_cubics};
pub use taper::{outline_with_widths, tapered_outline};
pub use tour::{tour, tour_length};
pub use walk::PathWalker;

use kurbo::{BezPath, ParamCurveArclen, Vec2};

/// Default geometric tolerance in millimetres: flattening, nearest-point
/// searches and curve fitting stay within this distance of the exact curve.
/// A 0.3 mm pen cannot show an error of 0.01 mm.
pub const TOLERANCE: f64 = 0.01;

/// Accuracy in mm used for arc-length queries (pen-down length).
pub const LENGTH_ACCURACY: f64 = 1e-3;

/// Arc length of a path in its own units, summing every segment (the pen
/// is down along all of them; move-tos lift it).
pub fn path_length(path: &BezPath) -> f64 {
    path.segments().map(|s| s.arclen(LENGTH_ACCURACY)).sum()
}

/// A side of a direction of travel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Side {
    /// To the left of the direction of travel.
    Left,
    /// To the right of the direction of travel.
    Right,
}

impl Side {
    /// The unit normal of the unit direction `d` that points to this side.
    ///
    /// With y down, the left of `d = (dx, dy)` is `(dy, -dx)`.
    pub fn normal(self, d: Vec2) -> Vec2 {
        match self {
            Side::Left => Vec2::new(d.y, -d.x),
            Side::Right => Vec2::new(-d.y, d.x),
        }
    }

    /// The other side.
    pub fn opposite(self) -> Side {
        match self {
            Side::Left => Side::Right,
            Side::Right => Side::Left,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn left_of_up_is_towards_smaller_x() {
        let up = Vec2::new(0.0, -1.0);
        assert_eq!(Side::Left.normal(up), Vec2::new(-1.0, 0.0));
        assert_eq!(Side::Right.normal(up), Vec2::new(1.0, 0.0));
    }
}
