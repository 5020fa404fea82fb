//! Wall-clock benchmark of the vine family, through the public API.
//!
//! Measures, with [`std::time::Instant`], the median of several runs (after
//! one warm-up run that is not counted) of:
//!
//! - **grow**: the 3D simulation alone ([`moyo::vine::grow`]);
//! - **render**: the whole description to SVG — the growth again, the
//!   camera, hidden-line removal of every stem, leaf and support line, the
//!   plot stages and the SVG text ([`moyo::project::render_with_progress`]);
//! - **png**: the PNG preview of that SVG at 150 dpi, as `moyo render
//!   --png` writes it.
//!
//! Two series: a vine of 25 to 400 internodes round a pole tall enough
//! for all of them (A4, front view); and a vine of 50 internodes round a closed mesh pillar of
//! about 1,000 to 100,000 triangles (a faceted cylinder read from OBJ text,
//! as `supports = [{ kind = "mesh", obj = … }]` reads it), seen from three
//! quarters, so that every line is tested against every triangle in front
//! of it.
//!
//! Everything goes to standard output as a Markdown table. Run it
//! with `cargo bench`, which builds it with the release settings (debug
//! timings mean nothing):
//!
//! ```text
//! cargo bench --bench vine_bench            # 5 runs
//! cargo bench --bench vine_bench -- --runs 3
//! ```

// `unused_crate_dependencies` (Cargo.toml) is for the library: a benchmark uses the library, not each of its dependencies.
#![allow(unused_crate_dependencies)]

use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;

use moyo::project::{load_motifs_with, render_with_progress};
use moyo::spec::{Format, ValidSpec};
use moyo::vine::{grow, Supports};

/// The OBJ file name the mesh series' descriptions refer to.
const PILLAR: &str = "pillar.obj";

fn main() -> Result<(), moyo::Error> {
    // `cargo bench` passes `--bench`; `cargo test --benches` (and
    // `--all-targets`) runs a benchmark without it, in a test build.
    if !std::env::args().any(|a| a == "--bench") {
        eprintln!("nothing timed: run `cargo bench --bench vine_bench`");
        return Ok(());
    }
    let runs = runs();
    println!("| support | internodes | triangles | stems | leaves | paths | grow ms | render ms | png ms |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for internodes in [25, 50, 100, 200, 400] {
        // Tall enough that the apex never runs out of pole: every
        // internode is grown.
        let pole = format!(
            "supports = [{{ kind = \"pole\", from = [20, 0, 0], to = [20, {}, 0], radius = 6 }}]\n",
            60 * internodes
        );
        let scene = description(internodes, &pole, "");
        measure("pole", &scene, "", 0, runs)?;
    }
    for sides in [8, 25, 80, 250] {
        let (obj, triangles) = pillar(sides);
        let supports = format!(
            "supports = [{{ kind = \"mesh\", obj = \"{PILLAR}\" }}]\nroots = [[0, 0, 16]]\n"
        );
        let scene = description(50, &supports, "camera = \"three-quarter\"\n");
        measure("mesh pillar", &scene, &obj, triangles, runs)?;
    }
    Ok(())
}

/// `--runs N` (default 5).
fn runs() -> usize {
    let args: Vec<String> = std::env::args().collect();
    args.iter()
        .position(|a| a == "--runs")
        .and_then(|i| args.get(i + 1))
        .and_then(|n| n.parse().ok())
        .unwrap_or(5)
        .max(1)
}

/// A description of one vine on A4 with `internodes`, its supports and
/// camera lines given (the front view when `camera` is empty).
fn description(internodes: u32, supports: &str, camera: &str) -> String {
    format!(
        "version = 1\nseed = 1\n[page]\nsize = \"A4\"\nmargin = 12\n[[layers]]\nname = \"vine\"\n\
         [[layers.vine]]\nid = \"vine\"\ninternodes = {internodes}\n{supports}{camera}"
    )
}

/// A closed faceted cylinder of radius 12 and height 600 mm at the origin,
/// as OBJ text: `sides` round, as many rings as make its facets about
/// square, capped at both ends; and its triangle count.
fn pillar(sides: usize) -> (String, usize) {
    let (radius, height) = (12.0_f64, 600.0_f64);
    let facet = std::f64::consts::TAU * radius / sides as f64;
    let rings = ((height / facet).round() as usize).max(1);
    let mut obj = String::new();
    for ring in 0..=rings {
        let y = height * ring as f64 / rings as f64;
        for side in 0..sides {
            let a = std::f64::consts::TAU * side as f64 / sides as f64;
            writeln!(obj, "v {} {y} {}", radius * a.cos(), radius * a.sin()).expect("to a string");
        }
    }
    // Cap centres, after the rings: bottom, then top.
    writeln!(obj, "v 0 0 0\nv 0 {height} 0").expect("to a string");
    let at = |ring: usize, side: usize| ring * sides + side % sides + 1;
    let (bottom, top) = ((rings + 1) * sides + 1, (rings + 1) * sides + 2);
    let mut triangles = 0;
    for ring in 0..rings {
        for side in 0..sides {
            let (a, b) = (at(ring, side), at(ring, side + 1));
            let (c, d) = (at(ring + 1, side + 1), at(ring + 1, side));
            writeln!(obj, "f {a} {d} {c}\nf {a} {c} {b}").expect("to a string");
            triangles += 2;
        }
    }
    for side in 0..sides {
        let (a, b) = (at(0, side), at(0, side + 1));
        let (c, d) = (at(rings, side), at(rings, side + 1));
        writeln!(obj, "f {bottom} {a} {b}\nf {top} {d} {c}").expect("to a string");
        triangles += 2;
    }
    (obj, triangles)
}

/// Times one description and prints its row.
fn measure(
    support: &str,
    text: &str,
    obj: &str,
    triangles: usize,
    runs: usize,
) -> Result<(), moyo::Error> {
    let spec = ValidSpec::parse(text, Format::Toml)?;
    let library = load_motifs_with(&spec, &|name| {
        (name.to_string(), Ok(obj.as_bytes().to_vec()))
    })?;
    let table = spec.layers[0].vine.first().expect("one vine");
    let shapes = table.shapes("vine", &|name| library.mesh(name).cloned())?;
    let supports = Supports::new(shapes);
    let params = table.params(table.roots[0]);
    let mut grow_ms = Vec::new();
    let mut render_ms = Vec::new();
    let mut png_ms = Vec::new();
    let mut counts = (0, 0, 0);
    for run in 0..=runs {
        let t = Instant::now();
        let plant = grow(
            &params,
            &supports,
            &mut moyo::Seed(1).derive("bench").stream(),
        )?;
        let grown = t.elapsed();
        let t = Instant::now();
        let rendered = render_with_progress(&spec, &library, &mut |_| {})?;
        let drawn = t.elapsed();
        let t = Instant::now();
        black_box(rendered.png(150.0)?);
        let pictured = t.elapsed();
        counts = (
            plant.stems.len(),
            plant.leaves.len(),
            rendered.scene.path_count(),
        );
        if run > 0 {
            grow_ms.push(grown.as_secs_f64() * 1e3);
            render_ms.push(drawn.as_secs_f64() * 1e3);
            png_ms.push(pictured.as_secs_f64() * 1e3);
        }
    }
    let internodes = params.internodes;
    let (stems, leaves, paths) = counts;
    let shown = if triangles > 0 {
        triangles.to_string()
    } else {
        "—".into()
    };
    println!(
        "| {support} | {internodes} | {shown} | {stems} | {leaves} | {paths} | {:.1} | {:.1} | {:.1} |",
        median(&mut grow_ms),
        median(&mut render_ms),
        median(&mut png_ms)
    );
    Ok(())
}

fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}
