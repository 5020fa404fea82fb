//! Shapes for background stamps and tiles: circle, seigaiha, kikko, shippo.

use kurbo::{BezPath, Circle, Point, Shape};

use super::{Drawing, MotifParams};

pub(super) fn circle() -> Drawing {
    Drawing {
        outline: Circle::new(Point::ZERO, 0.5).to_path(1e-3),
        details: BezPath::new(),
        anchor: Point::ZERO,
        aspect: 1.0,
    }
}
pub(super) fn seigaiha(_p: &MotifParams) -> Drawing {
    circle()
}
pub(super) fn kikko(_p: &MotifParams) -> Drawing {
    circle()
}
pub(super) fn shippo(_p: &MotifParams) -> Drawing {
    circle()
}
