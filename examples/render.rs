//! Renders a built-in template — the SVG a pen plotter runs as is, and a
//! PNG preview — and writes both atomically.
//!
//! Run with `cargo run --example render -- [TEMPLATE] [OUT_DIR]`
//! (default `kimono-2` into the system's temporary folder).

// `unused_crate_dependencies` (Cargo.toml) is for the library: an example uses the library, not each of its dependencies.
#![allow(unused_crate_dependencies)]

use std::path::PathBuf;

use moyo::output::write_atomic;
use moyo::plot::stats::{stats, Speeds};
use moyo::spec::{Format, SceneSpec};

fn main() -> Result<(), moyo::Error> {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "kimono-2".into());
    let dir = args.next().map_or_else(std::env::temp_dir, PathBuf::from);

    let template = moyo::templates::get(&name)?;
    let spec = SceneSpec::parse(template.text, Format::Toml)?;
    let rendered = moyo::render(&spec)?;

    // The SVG: one Inkscape layer per pen, in plotting order, the
    // description embedded so `moyo render --from-svg` can reopen it.
    let svg = dir.join(format!("{name}.svg"));
    write_atomic(&svg, rendered.svg.as_bytes())?;
    // The PNG: the colour preview (fills, `%` layers) at 96 dpi.
    let png = dir.join(format!("{name}.png"));
    write_atomic(&png, &rendered.png(96.0)?)?;

    // What a plotter will do with it: an AxiDraw at moderate speeds.
    let stats = stats(&rendered.scene, &Speeds::DEFAULT);
    println!(
        "{name}: {} paths, {:.0} mm pen-down, {:.0} mm pen-up, {:.0} min to plot → {} and {}",
        stats.paths,
        stats.pen_down_mm,
        stats.pen_up_mm,
        stats.plot_time_s / 60.0,
        svg.display(),
        png.display()
    );
    Ok(())
}
