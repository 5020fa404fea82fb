//! Trees: the eight recursive rules of the kimono source ([`skeleton`]) and
//! their smoothing and taper ([`draw`]).

pub mod draw;
pub mod skeleton;

#[cfg(test)]
mod tests;

pub use draw::{centre_curve, limb_paths, LimbLook};
pub use skeleton::{grow, Attach, Growth, Limb, LimbKind, Skeleton};
