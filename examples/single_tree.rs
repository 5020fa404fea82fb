//! Builds a scene description in code, renders it and prints the path dump.
//!
//! Run with `cargo run --example single_tree`.

// `unused_crate_dependencies` (Cargo.toml) is for the library: an example uses the library, not each of its dependencies.
#![allow(unused_crate_dependencies)]

use moyo::project;
use moyo::spec::{Format, SceneSpec};

fn main() -> Result<(), moyo::Error> {
    let spec = SceneSpec::parse(
        r#"
        version = 1
        seed = 3
        page = { size = "A5" }

        [[layers]]
        name = "tree"
        limbs = { style = "stroke" }

        [[layers.trees]]
        rule = "tree2"
        centre = [[40, 150], [90, 150]]
        params = { generations = 5, trunk = 25 }
        "#,
        Format::Toml,
    )?;
    let rendered = project::render(&spec)?;
    print!("{}", rendered.dump(2));
    eprintln!(
        "{} paths, {:.0} mm of line; SVG is {} bytes",
        rendered.scene.path_count(),
        rendered.scene.stats().pen_down_mm,
        rendered.svg.len()
    );
    Ok(())
}
