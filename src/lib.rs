//! moyo (模様, "pattern") generates ornamental line art — kimono plant
//! patterns, zentangle fills, Voronoi and Delaunay patterns and stipples,
//! stroke-guided L-systems, twining vines and wagara grounds — as Bézier
//! paths in a scene graph, and writes layered SVG that a pen plotter or
//! cutter can run as is, plus PNG previews, G-code and HPGL.
//!
//! Data flows one way:
//!
//! ```text
//! scene description (spec) → motif generators (motif) → scene graph (scene)
//!   → plot stages (plot: hatching, hidden lines, the pen stage)
//!   → outputs (output: SVG, PNG preview, G-code, HPGL, path dump)
//! ```
//!
//! [`project`] strings the stages together; its entry points are here at
//! the root, with the types they take and give:
//!
//! ```
//! use moyo::{Format, SceneSpec};
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
//! let rendered = moyo::render(&spec)?;
//! assert!(rendered.svg.contains(r#"inkscape:label="1 black""#));
//! assert_eq!(rendered.scene.path_count(), 2 * (1 + 4 * 5));
//!
//! // The same description and seed always give the same bytes.
//! assert_eq!(moyo::render(&spec)?.svg, rendered.svg);
//!
//! // One line per path, for snapshot tests of your own designs: what the
//! // pen draws (one layer per pen), in the order it draws it, each path
//! // with its id.
//! let dump = rendered.dump(2);
//! assert!(dump
//!     .lines()
//!     .all(|l| l.starts_with("pen-1.layer\tfront.trees-0.tree-")));
//! # Ok::<(), moyo::Error>(())
//! ```
//!
//! The modules hold the rest: [`spec`] every table of the description (to
//! build one in code), [`plot`] the plot stages and their options,
//! [`output`] the writers (SVG, PNG, G-code, HPGL, DXF, path dump),
//! [`stencil`] line art made into a cuttable stencil (bridges, blade
//! limits), [`input`]
//! SVG import, [`geom`] the geometry toolkit (regions, clipping, offsets,
//! splines), [`lsystem`] the L-system engine (rules, turtle, the
//! stroke-guided sketch), [`vine`] the twining-vine growth simulation (3D
//! stems and leaves round supports), [`motif`] the motif library,
//! [`templates`] the built-in scenes, [`text`] single-stroke lettering in
//! the built-in Hershey fonts, [`units`] paper sizes and lengths.
//! Without the default `cli` feature the crate is the library alone.

// Lints are set in Cargo.toml. Unit tests do not use every dev-dependency
// (those are the integration tests'), and the `cli` feature's crates are
// the `moyo` command's, not the library's.
#![cfg_attr(test, allow(unused_crate_dependencies))]
// The library never prints: the command and the examples talk to people.
#![warn(clippy::print_stdout, clippy::print_stderr)]
#![forbid(unsafe_code)]
#[cfg(all(feature = "cli", unix))]
use signal_hook as _;
#[cfg(feature = "cli")]
use {clap as _, indicatif as _};

mod cancel;
mod error;
mod family;
#[cfg(feature = "fuzzing")]
pub mod fuzz;
pub mod geom;
pub mod input;
pub mod motif;
pub mod output;
pub mod plot;
pub mod project;
mod rng;
mod scene;
pub mod spec;
pub mod stencil;
#[cfg(feature = "studio")]
pub mod studio;
pub mod templates;
pub mod text;
pub mod units;

// The chosen entry points, flat as kurbo's: a description becomes a
// `ValidSpec`, `render` makes the scene and its SVG, `plot_scene` runs a
// drawing through the plot stages into a plotter's format. The modules hold
// the rest (stage options, writers' options, the geometry toolkit).
pub use error::{Cause, Error, LineCol, Result, UserFile};
pub use input::{import_svg, ImportOptions, Imported};
pub use output::{render_png, to_svg, SvgOptions};
pub use project::{
    build_scene, fill_scene, load_motifs, plot_scene, read_svg, render, FillJob, FillPattern,
    FillRegion, Filled, PlotFormat, PlotJob, Plotted, Rendered,
};
pub use rng::{RandomStream, Seed};
pub use scene::traditional;
pub use scene::{
    embedded_description, Color, Group, Layer, LayerCodes, Model, ModelPart, Node, PathBudget, Pen,
    Scene, Stats, Style, StyledPath,
};
pub use spec::{Format, SceneSpec, ValidSpec};
pub use units::{Margins, Orientation, Page, PaperName};

pub use family::lsystem::engine as lsystem;
pub use family::vine::engine as vine;
