//! What the families share to draw with: the motif library (built-in
//! flowers, leaves and tile shapes, and user motifs: [`Library`],
//! [`draw`]), the `Context` every generator draws in (seed, library,
//! flow, layer, budget, adjustments, progress), final adjustment by id
//! (`adjust`), the overall flow (`flow`), `[region]` tables as regions
//! (`region`), shading in line (`bokashi`), strokes to follow
//! (`stroke`), putting a motif on the page (`place`), limbs drawn
//! for the pen (`limb`), dots that are dots, not rings (`dot`), and the
//! traditional grounds as seamless repeats (`ground`: the wagara family's
//! and kimono backgrounds').
//!
//! The families themselves live in `crate::family`; what a library user
//! reaches here is the motif [`Library`], [`draw`] for one motif on its
//! own and [`Progress`].

pub(crate) mod adjust;
pub(crate) mod bokashi;
mod context;
pub(crate) mod dot;
pub(crate) mod flora;
mod flow;
pub(crate) mod ground;
pub(crate) mod limb;
pub(crate) mod place;
pub(crate) mod region;
mod stroke;
#[cfg(test)]
pub(crate) mod test_scene;

pub(crate) use context::Context;
pub use context::{Note, Progress};
pub(crate) use flora::user_drawing;
pub use flora::{draw, Drawing, Library, MotifParams};
pub(crate) use flow::{flow_line, Flow};
pub(crate) use stroke::{stroke_points, Stroke};

use kurbo::{Affine, Rect};

/// The map that puts `drawn` (a drawing's own units, already y down) into
/// the middle of `frame`, as large as fits with the aspect kept.
pub(crate) fn fitted(drawn: Rect, frame: Rect) -> Affine {
    let (w, h) = (drawn.width(), drawn.height());
    let scale = match (w > 1e-12, h > 1e-12) {
        (true, true) => (frame.width() / w).min(frame.height() / h),
        (true, false) => frame.width() / w,
        (false, true) => frame.height() / h,
        // A single point: nothing to size.
        (false, false) => 1.0,
    };
    Affine::translate(frame.center().to_vec2())
        * Affine::scale(scale)
        * Affine::translate(-drawn.center().to_vec2())
}
