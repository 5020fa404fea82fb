//! moyo (模様, "pattern") generates ornamental line art — kimono plant
//! patterns first — as Bézier paths in a scene graph, and writes layered SVG
//! that a pen plotter or cutter can run as is, plus PNG previews.
//!
//! Data flows one way:
//!
//! ```text
//! scene description (spec) → motif generators (motif) → scene graph (scene)
//!                          → outputs (output: SVG, PNG preview, path dump)
//! ```
//!
//! [`project`] strings the stages together:
//!
//! ```
//! use moyo::spec::{Format, SceneSpec};
//!
//! let spec = SceneSpec::parse(
//!     r#"
//!     version = 1
//!     seed = 7
//!     page = { size = "A5", margin = 10 }
//!
//!     [[layers]]
//!     name = "front"
//!
//!     [[layers.trees]]
//!     rule = "tree1"
//!     count = 2
//!     centre = [[10, 170], [120, 180]]
//!     params = { generations = 5, trunk = 22 }
//!     "#,
//!     Format::Toml,
//! )?;
//! let rendered = moyo::project::render(&spec)?;
//! assert!(rendered.svg.contains(r#"inkscape:label="1 black""#));
//! assert_eq!(rendered.scene.path_count(), 2 * (1 + 4 * 5));
//!
//! // The same description and seed always give the same bytes.
//! assert_eq!(moyo::project::render(&spec)?.svg, rendered.svg);
//!
//! // One line per path, for snapshot tests of your own designs.
//! let dump = rendered.dump(2);
//! assert!(dump.starts_with("front\tfront.trees-0.tree-0.limb-0\tM "));
//! # Ok::<(), moyo::Error>(())
//! ```

#![warn(missing_docs)]
#![warn(clippy::print_stdout, clippy::print_stderr)]

pub mod error;
pub mod geom;
pub mod input;
pub mod motif;
pub mod output;
pub mod plot;
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
