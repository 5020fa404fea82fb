//! Fills the closed shapes of any drawing with a pattern on a pen of its
//! own — here a leaf outline with stained-glass cells — and writes the
//! result, the drawing's own lines untouched.
//!
//! Run with `cargo run --example fill_outline -- [OUT.svg]` (default:
//! `filled.svg` in the system's temporary folder).

// `unused_crate_dependencies` (Cargo.toml) is for the library: an example uses the library, not each of its dependencies.
#![allow(unused_crate_dependencies)]

use std::path::PathBuf;

use moyo::output::write_atomic;
use moyo::{fill_scene, import_svg, FillJob, FillPattern, ImportOptions};

/// A leaf (one closed path) on an A6 card.
const LEAF: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" width="105mm" height="148mm" viewBox="0 0 105 148">
  <path d="M 52 10 C 95 40 95 100 52 138 C 10 100 10 40 52 10 Z"
        stroke="black" stroke-width="0.5" fill="none"/>
</svg>"#;

fn main() -> Result<(), moyo::Error> {
    let out = std::env::args()
        .nth(1)
        .map_or_else(|| std::env::temp_dir().join("filled.svg"), PathBuf::from);
    let drawing = import_svg(LEAF, &ImportOptions::DEFAULT)?.scene;

    // Cells 6 mm apart, relaxed three times, each shrunk inside its
    // neighbours (stained glass); seed 4 picks the sites.
    let job = FillJob::new(FillPattern::Glass)
        .with_spacing(6.0)
        .with_relax(3)
        .with_seed(4);
    let filled = fill_scene(drawing, &job)?;

    // What the pen draws: the pen stage has run (nothing drawn twice, no
    // crumbs, sorted); `filled.scene` keeps the groups for editing.
    write_atomic(&out, filled.svg(2).as_bytes())?;
    println!(
        "layer {} on pen {}{}: {} paths, {:.0} mm → {}",
        filled.layer,
        filled.pen,
        if filled.new_pen { " (new)" } else { "" },
        filled.fill.paths,
        filled.fill.pen_down_mm,
        out.display()
    );
    Ok(())
}
