//! Flower motifs: ume, sakura, kiku, tsubaki, kikyo, botan.

use super::{tiles::circle, Drawing, MotifParams};
use crate::rng::RandomStream;

pub(super) fn ume(_p: &MotifParams, _rng: &mut RandomStream) -> Drawing {
    circle()
}
pub(super) fn sakura(_p: &MotifParams, _rng: &mut RandomStream) -> Drawing {
    circle()
}
pub(super) fn kiku(_p: &MotifParams, _rng: &mut RandomStream) -> Drawing {
    circle()
}
pub(super) fn tsubaki(_p: &MotifParams, _rng: &mut RandomStream) -> Drawing {
    circle()
}
pub(super) fn kikyo(_p: &MotifParams, _rng: &mut RandomStream) -> Drawing {
    circle()
}
pub(super) fn botan(_p: &MotifParams, _rng: &mut RandomStream) -> Drawing {
    circle()
}
