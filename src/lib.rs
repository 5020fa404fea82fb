//! moyo (模様, "pattern") generates ornamental line art as Bézier paths in a
//! scene graph and writes layered SVG that a pen plotter or cutter can run as
//! is, plus PNG previews.
//!
//! Data flows one way: scene description → motif generators → scene graph →
//! outputs.

#![warn(missing_docs)]
#![warn(clippy::print_stdout, clippy::print_stderr)]

pub mod error;
pub mod geom;
pub mod motif;
pub mod output;
pub mod project;
pub mod rng;
pub mod scene;
pub mod spec;
pub mod templates;
pub mod units;

pub use error::{Error, LineCol, Result};
pub use rng::{RandomStream, Seed};
pub use scene::{Color, Group, Layer, Node, PathBudget, Pen, Scene, Stats, Style, StyledPath};
pub use units::{Margins, Orientation, Page, PaperName};
