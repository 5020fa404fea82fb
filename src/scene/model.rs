//! 3D models that generators make beside their drawings (a vine and its
//! supports), for export: each a list of named parts holding vertices,
//! polylines and faces in millimetres, right-handed with y up.
//!
//! The drawing is the scene's business; a model only rides along so that
//! an output ([`crate::output::to_obj`]) can write it.

/// A 3D model: one motif's parts.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Model {
    /// The id of the group that drew it (`front.vine-0`).
    pub id: String,
    /// Its parts in order.
    pub parts: Vec<ModelPart>,
}

/// One named part of a [`Model`]: a stem, a leaf, a support.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ModelPart {
    /// Its name, unique in the model (`stem-0`, `leaf-3`, `support-1`).
    pub name: String,
    /// Vertex positions, mm.
    pub vertices: Vec<[f64; 3]>,
    /// Polylines through vertices (indices into `vertices`).
    pub lines: Vec<Vec<u32>>,
    /// Faces, each ≥ 3 vertex indices counter-clockwise seen from outside.
    pub faces: Vec<Vec<u32>>,
}
