//! Motif generators: each family in its own folder. Generators read a
//! validated description and write [`crate::scene::Group`]s; they never
//! write files.

pub mod flora;
pub mod kimono;
pub mod tree;
