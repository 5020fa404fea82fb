//! Wall-clock benchmark of `moyo stencil` (issue 32), through the public
//! API.
//!
//! Measures, with [`std::time::Instant`], the median of several runs
//! (after one warm-up run that is not counted) of, for each template:
//!
//! - **render**: the template to its scene ([`moyo::templates::Template::render`]);
//! - **stencil**: the scene to a stencil ([`moyo::stencil::make`]: the
//!   cut-outs, islands, bridges, specks, the sheet and the blade checks);
//! - **cut**: the cut to DXF in inside-first order, as `moyo stencil -o
//!   OUT.dxf` writes it ([`moyo::project::plot_scene`]);
//!
//! and the total, which is what `moyo stencil templates/NAME.toml -o
//! OUT.dxf` spends (but reading the file and writing the result).
//!
//! Everything goes to standard output as a Markdown table. Run it with
//! `cargo bench`, which builds it with the release settings (debug
//! timings mean nothing):
//!
//! ```text
//! cargo bench --bench stencil_bench            # 5 runs
//! cargo bench --bench stencil_bench -- --runs 3
//! ```

// `unused_crate_dependencies` (Cargo.toml) is for the library: a benchmark uses the library, not each of its dependencies.
#![allow(unused_crate_dependencies)]

use std::time::{Duration, Instant};

use moyo::output::dxf::DxfOptions;
use moyo::plot::{PlotOptions, SortOptions};
use moyo::project::{plot_scene, PlotFormat, PlotJob};
use moyo::stencil::{make, StencilOptions};

/// The largest A3 kimono templates (by the size of their SVG), and the
/// stencil design.
const TEMPLATES: &[&str] = &["kimono-1", "kimono-egasumi", "kimono-tangles", "katagami"];

fn main() -> Result<(), moyo::Error> {
    // `cargo bench` passes `--bench`; `cargo test --benches` (and
    // `--all-targets`) runs a benchmark without it, in a test build.
    if !std::env::args().any(|a| a == "--bench") {
        eprintln!("nothing timed: run `cargo bench --bench stencil_bench`");
        return Ok(());
    }
    let runs = runs();
    println!("| template | strokes | islands | bridges | cuts | render ms | stencil ms | cut ms | total ms |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for name in TEMPLATES {
        let template = moyo::templates::get(name)?;
        let job = PlotJob::new(PlotFormat::Dxf(DxfOptions::DEFAULT)).with_stages(PlotOptions {
            sort: Some(SortOptions::DEFAULT),
            inside_first: true,
            ..PlotOptions::default()
        });
        let mut times: [Vec<Duration>; 3] = Default::default();
        let mut row = String::new();
        for run in 0..=runs {
            let t0 = Instant::now();
            let scene = template.render()?.scene;
            let t1 = Instant::now();
            let stencil = make(&scene, &StencilOptions::DEFAULT)?;
            let t2 = Instant::now();
            let cut = plot_scene(stencil.cut_scene(), &job)?;
            let t3 = Instant::now();
            if run == 0 {
                row = format!(
                    "| {name} | {} | {} | {} | {} |",
                    scene.path_count(),
                    stencil.report.islands.len(),
                    stencil.report.bridges.len(),
                    cut.scene.path_count()
                );
                continue;
            }
            times[0].push(t1 - t0);
            times[1].push(t2 - t1);
            times[2].push(t3 - t2);
        }
        let ms: Vec<f64> = times.iter_mut().map(|t| median(t)).collect();
        println!(
            "{row} {:.0} | {:.0} | {:.0} | {:.0} |",
            ms[0],
            ms[1],
            ms[2],
            ms.iter().sum::<f64>()
        );
    }
    Ok(())
}

/// The median, in milliseconds.
fn median(times: &mut [Duration]) -> f64 {
    times.sort();
    times[times.len() / 2].as_secs_f64() * 1000.0
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
