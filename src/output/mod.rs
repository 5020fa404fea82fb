//! Writers: everything that turns a finished [`Scene`](crate::scene::Scene)
//! into bytes. Writers only read the scene; they never generate geometry.
//!
//! - [`to_svg`]: layered SVG, one Inkscape layer per pen, page size in mm,
//!   with the scene description embedded
//!   ([`embedded_description`](crate::scene::embedded_description) reads it
//!   back): the plot, only what pens draw, or the colour preview, which
//!   adds preview fills and `%` layers ([`SvgOptions::preview`]);
//! - [`render_png`]: a PNG rendered from SVG text (the colour preview's,
//!   for a preview);
//! - [`gcode`] and [`hpgl`], set for a machine by a [`device`] profile:
//!   programs for pen plotters and cutters, both
//!   written from one stroke model (pens in order, flattened strokes,
//!   closed or open, page to machine coordinates), cut into runs between
//!   refills or resumed part way ([`RunOptions`]);
//! - [`dxf`]: AutoCAD R12 DXF for cutting programs and CAD, one layer
//!   per pen, from the same stroke model;
//! - [`path_dump`]: a stable one-line-per-path text for snapshot tests;
//! - [`to_obj`]: the 3D models beside a drawing (a vine and its supports)
//!   as Wavefront OBJ;
//! - [`animated_svg`]: frames of a growth in one looping SVG, to watch;
//! - [`write_atomic`]: puts any of these on disk without half-written files
//!   ([`check_output_folder`]: whether the folder is there, asked first;
//!   [`write_all_atomic`]: several files, all or none; [`Staged`]: the
//!   same, written one at a time as they are made;
//!   [`remove_temporaries`]: for a signal handler, nothing left behind);
//! - [`write_number`]: the single number formatter behind all text outputs.

pub mod device;
pub mod dxf;
pub mod gcode;
pub mod hpgl;

mod animate;
mod arcs;
mod atomic;
mod dump;
mod number;
mod obj;
mod preview;
mod runs;
mod strokes;
mod svg;
mod template;

pub use animate::{animated_svg, FRAME_SECONDS};
pub use atomic::{
    check_output_folder, remove_temporaries, write_all_atomic, write_atomic, Staged, STALE_AFTER,
};
pub use dump::path_dump;
pub use number::{grouped, write_number};
pub use obj::to_obj;
pub use preview::{check_dpi, render_png};
pub use runs::RunOptions;
#[cfg(feature = "studio")]
pub(crate) use svg::write_path_data;
pub use svg::{to_svg, SvgOptions};
