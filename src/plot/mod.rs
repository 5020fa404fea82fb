//! The plot pipeline: stages that turn a scene into one a plotter runs well
//! (hidden lines, hatching, doubled line work, merging, blots, debris,
//! simplifying, ordering, inside-first order for cutters), usable on
//! generated scenes and on imported SVGs alike. Each stage reads and writes
//! a [`crate::scene::Scene`]; none generates motifs or writes files.

pub mod blots;
mod cover;
pub mod debris;
pub mod dedupe;
pub mod flatten;
pub mod hatch;
pub mod merge;
pub mod multipass;
pub mod nest;
pub mod occlude;
pub mod pipeline;
pub mod simplify;
pub mod sort;
pub mod stats;
pub mod transform;

pub use blots::BlotOptions;
pub use debris::DebrisOptions;
pub use dedupe::DedupeOptions;
pub use hatch::HatchOptions;
pub use merge::MergeOptions;
pub use multipass::MultipassOptions;
pub use occlude::OccludeOptions;
pub use pipeline::{run, run_cancellable, PlotOptions};
pub use simplify::SimplifyOptions;
pub use sort::SortOptions;
pub use stats::{stats, PlotStats, Speeds};
pub use transform::TransformOptions;
