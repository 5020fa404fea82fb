//! Trees: the eight recursive rules of the kimono source (`skeleton`) and
//! their smoothing and taper (`draw`).

mod bow;
mod draw;
mod skeleton;

#[cfg(test)]
mod tests;

pub(crate) use draw::{limb_paths, LimbLook};
pub(crate) use skeleton::{grow, Growth, Skeleton};
