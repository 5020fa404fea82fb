//! Makes any SVG ready for a pen: a careless drawing — a line drawn
//! twice, a stroke in two halves drawn in the wrong order, a crumb of a
//! stroke — through the pen stage (dedupe, merge, debris, sort), written
//! as G-code for a GRBL plotter.
//!
//! Run with `cargo run --example plot_svg -- [OUT.gcode]` (default: the
//! G-code goes to standard output).

// `unused_crate_dependencies` (Cargo.toml) is for the library: an example uses the library, not each of its dependencies.
#![allow(unused_crate_dependencies)]

use moyo::output::gcode::GcodeOptions;
use moyo::output::write_atomic;
use moyo::plot::stats::{stats, Speeds};
use moyo::plot::PlotOptions;
use moyo::{import_svg, plot_scene, ImportOptions, PlotFormat, PlotJob};

/// A drawing as a careless program writes it (mm, 0.3 mm pen).
const DRAWING: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" width="120mm" height="80mm" viewBox="0 0 120 80">
  <g stroke="black" stroke-width="0.3" fill="none">
    <path d="M 100 60 L 60 60"/>
    <rect x="10" y="10" width="40" height="30"/>
    <path d="M 10 10 L 50 10"/>
    <path d="M 20 60 L 60 60"/>
    <path d="M 50 25 L 50.1 25"/>
    <circle cx="90" cy="25" r="12"/>
  </g>
</svg>"#;

fn main() -> Result<(), moyo::Error> {
    let out = std::env::args().nth(1);
    let drawing = import_svg(DRAWING, &ImportOptions::DEFAULT)?.scene;
    let before = stats(&drawing, &Speeds::DEFAULT);

    // The pen stage with every step's defaults, the scene's pens kept.
    let job = PlotJob::new(PlotFormat::Gcode(GcodeOptions::default()))
        .with_stages(PlotOptions::pen_ready());
    let plotted = plot_scene(drawing, &job)?;
    let after = stats(&plotted.scene, &Speeds::DEFAULT);

    eprintln!(
        "as written: {} strokes, {:.1} mm drawn twice, {} crumbs, {:.0} mm pen-up",
        before.paths, before.doubled_mm, before.debris, before.pen_up_mm
    );
    eprintln!(
        "pen-ready:  {} strokes, {:.1} mm drawn twice, {} crumbs, {:.0} mm pen-up",
        after.paths, after.doubled_mm, after.debris, after.pen_up_mm
    );
    match out {
        Some(path) => write_atomic(std::path::Path::new(&path), plotted.bytes.as_bytes())?,
        None => print!("{}", plotted.bytes),
    }
    Ok(())
}
