//! Motif generators: one folder per family, one seam.
//!
//! A layer's tables come from [`crate::spec::LayerSpec::items`]; `build`
//! hands each to its family's generator with the shared `Context` (seed,
//! library, flow, layer, budget, adjustments, progress) and gets back one
//! [`Group`] with ids `<layer>.<item>…`. Generators read a validated
//! description and write groups; they never read or write files.
//!
//! Families: `kimono` (tree sets with flowers and leaves, backgrounds),
//! built on `tree` (the eight rules) and `flora` (vector motifs),
//! `paths` (user paths placed and repeated), `voronoi` (cells, Delaunay
//! edges, inset cells, stipples and tours inside a region), `zentangle`
//! (the filling process) and `lsystem` (an L-system or a sketch along a
//! stroke, seen from its view, with flowers and leaves). docs/ARCHITECTURE.md says
//! how to add one. The generators are the crate's own; what a library user
//! reaches here is the motif [`Library`] (built-in and user motifs),
//! [`draw`] for one motif on its own, and [`Progress`].

mod adjust;
mod bokashi;
mod context;
mod flora;
mod flow;
mod kimono;
mod lsystem;
mod paths;
mod region;
mod stroke;
#[cfg(test)]
mod test_scene;
mod tree;
mod vine;
mod voronoi;
mod zentangle;

pub(crate) use context::Context;
pub use context::{Note, Progress};
pub(crate) use flora::user_drawing;
pub use flora::{draw, Drawing, Library, MotifParams};
pub(crate) use flow::{flow_line, Flow};
pub use lsystem::GrowingSketch;
pub(crate) use stroke::{stroke_points, Stroke};

use kurbo::{Affine, Point, Rect};

use crate::error::Result;
use crate::scene::Group;
use crate::spec::{LayerItem, Table, VoronoiSpec};

/// Builds one table of the layer being built into a group with id
/// `<layer>.<item id>`, and counts its declared work as done.
///
/// # Errors
/// What the family's generator reports: the path budget running out, an
/// adjustment that does not fit what it addresses, a user motif missing
/// from the library.
pub fn build(item: &LayerItem<'_>, cx: &mut Context<'_>) -> Result<Group> {
    let id = format!("{}.{}", cx.layer_id(), item.id);
    let done = cx.done() + item.table.family().work();
    cx.enter_item(&item.field);
    let group = match item.table {
        Table::Background(t) => kimono::background::background(t, &id, cx),
        Table::Trees(t) => kimono::tree_set(t, &id, cx),
        Table::Paths(t) => paths::build(t, &id, cx),
        Table::Voronoi(t) => voronoi::build(t, &id, cx),
        Table::Zentangle(t) => zentangle::build(t, &id, cx),
        Table::LSystem(t) => lsystem::build(t, &id, cx),
        Table::Vine(t) => vine::build(t, &id, cx),
    }?;
    cx.advance_to(done);
    Ok(group)
}

/// The sites the voronoi table `item` (`spec`) of the layer being built
/// starts from, before relaxation (see [`crate::project::voronoi_sites`]).
///
/// # Errors
/// As [`build`], up to the sites.
pub(crate) fn voronoi_sites(
    item: &LayerItem<'_>,
    spec: &VoronoiSpec,
    cx: &mut Context<'_>,
) -> Result<Vec<Point>> {
    let id = format!("{}.{}", cx.layer_id(), item.id);
    cx.enter_item(&item.field);
    voronoi::starting_sites(spec, &id, cx)
}

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
