//! The facade: scene description → scene → SVG / PNG / path dump; and any
//! SVG through the plot stages ([`plot_scene`]) or filled with a pattern
//! ([`fill_scene`]).
//!
//! This is the one place that knows the order of the stages; the CLI calls
//! only these functions. It is also where user motifs are read from their
//! SVG files ([`load_motifs`]), since generators never touch files.

//!
//! `files` reads what a description names (user motifs, paths, images,
//! meshes), `render` builds and renders a description, `plot` runs any
//! drawing through the plot stages into a plotter's format, `fill` fills
//! any drawing's shapes with a pattern.

mod files;
mod fill;
mod plot;
mod render;

pub use crate::cancel::Cancel;
pub use crate::motif::{Note, Progress};
pub use files::{load_motifs, load_motifs_with, user_files, FileReader, UserFiles};
pub use fill::{fill_scene, FillJob, FillPattern, FillRegion, Filled};
pub use plot::{plot_scene, read_svg, PlotFormat, PlotJob, Plotted, Preview};
pub use render::{
    build_scene, build_scene_with_progress, render, render_cancellable, render_for_editing,
    render_with_progress, svg_options, voronoi_sites, Rendered,
};
