//! Leaf motifs: momiji, matsu, take, leaf.

use super::{tiles::circle, Drawing, MotifParams};
use crate::rng::RandomStream;

pub(super) fn momiji(_p: &MotifParams, _rng: &mut RandomStream) -> Drawing {
    circle()
}
pub(super) fn matsu(_p: &MotifParams, _rng: &mut RandomStream) -> Drawing {
    circle()
}
pub(super) fn take(_p: &MotifParams, _rng: &mut RandomStream) -> Drawing {
    circle()
}
pub(super) fn leaf(_p: &MotifParams, _rng: &mut RandomStream) -> Drawing {
    let mut d = circle();
    d.anchor = kurbo::Point::new(0.0, 0.5);
    d
}
