//! Trees: the eight recursive rules of the kimono source (`skeleton`) and
//! their smoothing and taper (`draw`).

mod draw;
mod skeleton;

#[cfg(test)]
mod tests;

pub(crate) use draw::{limb_paths, strokes_first, LimbLook, THIN};
pub(crate) use skeleton::{grow, Growth, Skeleton};
