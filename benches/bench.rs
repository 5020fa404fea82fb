//! Wall-clock benchmark of the render pipeline, through the public API only.
//!
//! Measures, with [`std::time::Instant`], the median of several runs (after
//! warm-up runs that are not counted):
//!
//! 1. **The `tomesode-hem` design** (the default before the kimono templates): parsing the
//!    description, building the scene, writing the SVG string, rendering the
//!    PNG preview at 150 dpi (the CLI default), and the whole chain end to
//!    end; for attribution also `write_number` alone on every path
//!    coordinate, and the PNG of an empty page of the same size.
//! 2. **Scaling with tree count**: a scene written in code — one layer, one
//!    tree set of rule `tree1`, `generations = 6`, along a straight
//!    horizontal centre line on a 4000 × 1000 mm page without region lines —
//!    with `count` = 10, 30, 100, 300, 1000, once with `outline` limbs and
//!    once with `stroke` limbs. Reports scene-build time, SVG time, paths,
//!    SVG bytes, time per tree, and the local growth exponent
//!    `k = ln(t₂/t₁) / ln(n₂/n₁)` against the previous row (1 is linear,
//!    2 quadratic); also the PNG at 25 dpi.
//! 3. **Per-tree overrides**: scene-build time of 100 … 10,000 small trees
//!    (`tree2`, 2 generations, `stroke`) without overrides and with one
//!    override per tree, plus the parse time of the latter.
//!
//! 4. **Voronoi cells**: one `[[layers.voronoi]]` table of `uniform` sites
//!    (1,000 … 100,000) on a 400 × 400 mm page with two round holes,
//!    drawing the cell network: scene build (sampling, diagram, exact
//!    clipping, network) and SVG, and the same with 5 Lloyd steps.
//!
//! Everything goes to standard output as Markdown tables, ready to paste into
//! `BENCHMARKS.md`.
//!
//! Run it with `cargo bench`, which builds it with the release settings
//! (debug timings mean nothing):
//!
//! ```text
//! cargo bench --bench bench             # 5 runs, 1 warm-up
//! cargo bench --bench bench -- --quick  # 3 runs, counts up to 300
//! cargo bench --bench bench -- --runs 11 --warmup 2
//! cargo bench --bench bench -- --only outline --counts 300,1000,3000
//! ```
//!
//! `--only` (repeatable) picks sections: `default`, `outline`, `stroke`,
//! `overrides`, `voronoi`. `--counts` and `--override-counts` replace the tree counts of
//! the scaling and override sections.

// `unused_crate_dependencies` (Cargo.toml) is for the library: a benchmark uses the library, not each of its dependencies.
#![allow(unused_crate_dependencies)]

use std::hint::black_box;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use kurbo::{PathEl, Point};
use moyo::output::{grouped, render_png, to_svg, write_number};
use moyo::project::{build_scene, render, svg_options};
use moyo::spec::{Format, SceneSpec};
use moyo::templates;

/// The CLI's default preview resolution.
const PNG_DPI: f64 = 150.0;

/// Preview resolution of the tree-count scaling scenes: their 4000 × 1000 mm
/// page at 25 dpi is 3937 × 984 px, about the pixel count of A3 at 150 dpi.
const SCALING_DPI: f64 = 25.0;

/// How the bench is run.
struct Config {
    runs: usize,
    warmup: usize,
    counts: Vec<u32>,
    override_counts: Vec<u32>,
    /// Sections to run; empty means all.
    only: Vec<String>,
}

impl Config {
    fn from_args() -> Result<Config, String> {
        let mut c = Config {
            runs: 5,
            warmup: 1,
            counts: vec![10, 30, 100, 300, 1000],
            override_counts: vec![100, 300, 1000, 3000, 10_000],
            only: Vec::new(),
        };
        let mut args = std::env::args().skip(1);
        while let Some(arg) = args.next() {
            match arg.as_str() {
                "--quick" => {
                    c.runs = 3;
                    c.counts = vec![10, 30, 100, 300];
                    c.override_counts = vec![100, 300, 1000, 3000];
                }
                "--runs" => c.runs = number(&arg, args.next())?,
                "--warmup" => c.warmup = number(&arg, args.next())?,
                "--counts" => c.counts = list(&arg, args.next())?,
                "--override-counts" => c.override_counts = list(&arg, args.next())?,
                "--only" => match args.next() {
                    Some(s) if SECTIONS.contains(&s.as_str()) => c.only.push(s),
                    _ => return Err(format!("--only needs one of {}", SECTIONS.join(", "))),
                },
                // Passed by `cargo bench` (see `main`).
                "--bench" => {}
                "-h" | "--help" => {
                    println!("{USAGE}");
                    std::process::exit(0);
                }
                other => return Err(format!("unknown argument '{other}'\n{USAGE}")),
            }
        }
        if c.runs == 0 {
            return Err("--runs must be at least 1".into());
        }
        Ok(c)
    }
}

const USAGE: &str = "usage: cargo bench --bench bench -- [--quick] \
    [--runs N] [--warmup N] [--counts N,N,…] [--override-counts N,N,…] \
    [--only default|outline|stroke|overrides|voronoi]…";

/// The sections of the report, in order.
const SECTIONS: [&str; 5] = ["default", "outline", "stroke", "overrides", "voronoi"];

impl Config {
    fn runs_section(&self, name: &str) -> bool {
        self.only.is_empty() || self.only.iter().any(|s| s == name)
    }
}

fn list(flag: &str, value: Option<String>) -> Result<Vec<u32>, String> {
    let bad = || format!("{flag} needs a comma-separated list of tree counts ≥ 1");
    let v = value.ok_or_else(bad)?;
    let counts: Vec<u32> = v
        .split(',')
        .map(|n| n.trim().parse().ok().filter(|n| *n >= 1))
        .collect::<Option<_>>()
        .ok_or_else(bad)?;
    if counts.is_empty() {
        return Err(bad());
    }
    Ok(counts)
}

fn number(flag: &str, value: Option<String>) -> Result<usize, String> {
    value
        .as_deref()
        .and_then(|v| v.parse().ok())
        .ok_or_else(|| format!("{flag} needs a whole number"))
}

/// Median, min and max of the timed runs.
#[derive(Clone, Copy)]
struct Timing {
    median: Duration,
    min: Duration,
    max: Duration,
}

/// Runs `f` `warmup` times untimed, then `runs` times timed; returns the
/// timing and the result of the last run.
fn measure<T>(cfg: &Config, mut f: impl FnMut() -> T) -> (Timing, T) {
    for _ in 0..cfg.warmup {
        black_box(f());
    }
    let mut times = Vec::with_capacity(cfg.runs);
    let mut last = None;
    for _ in 0..cfg.runs {
        let start = Instant::now();
        let out = black_box(f());
        times.push(start.elapsed());
        last = Some(out);
    }
    times.sort();
    let n = times.len();
    // Even counts: the mean of the middle two.
    let median = if n % 2 == 1 {
        times[n / 2]
    } else {
        (times[n / 2 - 1] + times[n / 2]) / 2
    };
    let timing = Timing {
        median,
        min: times[0],
        max: times[n - 1],
    };
    (timing, last.expect("runs >= 1"))
}

fn ms(d: Duration) -> String {
    let v = d.as_secs_f64() * 1e3;
    if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else if v >= 1.0 {
        format!("{v:.2}")
    } else {
        format!("{v:.3}")
    }
}

fn us(v: f64) -> String {
    if v >= 100.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.1}")
    }
}

fn default_design(cfg: &Config) -> Result<(), moyo::Error> {
    let template = templates::get("tomesode-hem")?;
    let (t_parse, spec) = measure(cfg, || template.spec().expect("template parses"));
    let (t_scene, scene) = measure(cfg, || build_scene(&spec).expect("scene builds"));
    let options = svg_options(&spec);
    let (t_svg, svg) = measure(cfg, || to_svg(&scene, &options));
    let (t_png, png) = measure(cfg, || render_png(&svg, PNG_DPI).expect("PNG renders"));
    let (t_total, _) = measure(cfg, || {
        let spec = template.spec().expect("template parses");
        let rendered = render(&spec).expect("render succeeds");
        let png = rendered.png(PNG_DPI).expect("PNG renders");
        (rendered, png)
    });

    // Attribution, not part of the pipeline: the coordinates of every path
    // through the SVG writer's number formatter alone, and a PNG of an empty
    // page of the same size (allocation, fill and encoding, no paths).
    let mut coords = Vec::new();
    scene.visit_paths(|_, p, _| {
        for el in p.path.elements() {
            let pts: &[Point] = match el {
                PathEl::MoveTo(a) | PathEl::LineTo(a) => std::slice::from_ref(a),
                PathEl::QuadTo(a, b) => &[*a, *b],
                PathEl::CurveTo(a, b, c) => &[*a, *b, *c],
                PathEl::ClosePath => &[],
            };
            for q in pts {
                coords.extend([q.x, q.y]);
            }
        }
    });
    let (t_numbers, _) = measure(cfg, || {
        let mut out = String::with_capacity(coords.len() * 8);
        for &v in &coords {
            write_number(&mut out, v, spec.output.precision);
            out.push(' ');
        }
        out
    });
    let blank = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}mm\" height=\"{h}mm\" \
         viewBox=\"0 0 {w} {h}\"/>",
        w = scene.page.width,
        h = scene.page.height
    );
    let (t_blank, _) = measure(cfg, || render_png(&blank, PNG_DPI).expect("PNG renders"));

    let stats = scene.stats();
    println!(
        "### Default design `{}` ({} runs, {} warm-up)\n",
        template.name, cfg.runs, cfg.warmup
    );
    println!(
        "{} paths, {:.0} mm pen-down, SVG {} bytes, PNG {} bytes at {PNG_DPI} dpi.\n",
        grouped(stats.paths),
        stats.pen_down_mm,
        grouped(svg.len()),
        grouped(png.len())
    );
    println!("| stage | median ms | min ms | max ms | share of stages |");
    println!("|---|---:|---:|---:|---:|");
    let stages = [
        ("parse + validate description", t_parse),
        ("build scene", t_scene),
        ("write SVG string", t_svg),
        ("PNG at 150 dpi (usvg parse + raster + encode)", t_png),
    ];
    let sum: f64 = stages.iter().map(|(_, t)| t.median.as_secs_f64()).sum();
    let row = |name: &str, t: Timing, share: String| {
        println!(
            "| {name} | {} | {} | {} | {share} |",
            ms(t.median),
            ms(t.min),
            ms(t.max)
        );
    };
    for (name, t) in stages {
        row(
            name,
            t,
            format!("{:.1} %", 100.0 * t.median.as_secs_f64() / sum),
        );
    }
    row(
        "**total**, measured as one chain (parse → scene → SVG → PNG)",
        t_total,
        String::new(),
    );
    row(
        &format!(
            "for comparison: `write_number` alone on the {} path coordinates",
            grouped(coords.len())
        ),
        t_numbers,
        String::new(),
    );
    row(
        &format!(
            "for comparison: PNG of an empty {} × {} mm page at 150 dpi",
            scene.page.width, scene.page.height
        ),
        t_blank,
        String::new(),
    );
    println!();
    Ok(())
}

/// One layer, one `tree1` set of `count` trees along a horizontal line.
fn row_of_trees(count: u32, style: &str) -> String {
    row_scene(count, "tree1", style, 6)
}

/// One layer with one set of `count` trees of `rule` along a 4 m line.
fn row_scene(count: u32, rule: &str, style: &str, generations: u32) -> String {
    format!(
        r#"version = 1
title = "bench: {count} {rule} trees, {style}"
seed = 1

[page]
size = [4000, 1000]
orientation = "landscape"
margin = 10

[limits]
max_paths = 1000000

[[layers]]
name = "row"

[layers.limbs]
style = "{style}"

[[layers.trees]]
id = "row"
rule = "{rule}"
count = {count}
centre = [[10, 900], [3970, 900]]

[layers.trees.params]
generations = {generations}
"#
    )
}

/// Local growth exponent of `t` from `(n0, t0)` to `(n1, t1)`.
fn exponent(n0: u32, t0: Duration, n1: u32, t1: Duration) -> f64 {
    (t1.as_secs_f64() / t0.as_secs_f64()).ln() / (f64::from(n1) / f64::from(n0)).ln()
}

fn scaling(cfg: &Config, style: &str) -> Result<(), moyo::Error> {
    println!(
        "### Tree count scaling, `tree1`, generations 6, limbs `{style}` ({} runs, {} warm-up)\n",
        cfg.runs, cfg.warmup
    );
    println!(
        "| trees | paths | SVG bytes | scene ms | SVG ms | PNG ms at {SCALING_DPI} dpi \
         | scene µs/tree | SVG µs/tree | k scene | k SVG | k PNG |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut prev: Option<(u32, [Duration; 3])> = None;
    for &count in &cfg.counts {
        let spec = SceneSpec::parse(&row_of_trees(count, style), Format::Toml)?;
        let (t_scene, scene) = measure(cfg, || build_scene(&spec).expect("scene builds"));
        let options = svg_options(&spec);
        let (t_svg, svg) = measure(cfg, || to_svg(&scene, &options));
        let (t_png, _) = measure(cfg, || render_png(&svg, SCALING_DPI).expect("PNG renders"));
        let now = [t_scene.median, t_svg.median, t_png.median];
        let per_tree = |t: Duration| us(t.as_secs_f64() * 1e6 / f64::from(count));
        let k = |i: usize| match prev {
            Some((n0, before)) => format!("{:.2}", exponent(n0, before[i], count, now[i])),
            None => "–".into(),
        };
        println!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            grouped(count as usize),
            grouped(scene.path_count()),
            grouped(svg.len()),
            ms(t_scene.median),
            ms(t_svg.median),
            ms(t_png.median),
            per_tree(t_scene.median),
            per_tree(t_svg.median),
            k(0),
            k(1),
            k(2),
        );
        prev = Some((count, now));
    }
    println!();
    Ok(())
}

/// One set of `count` small trees (`tree2`, 2 generations, stroke limbs),
/// each tree with an override when `overridden`.
fn overridden_trees(count: u32, overridden: bool) -> String {
    let mut s = row_scene(count, "tree2", "stroke", 2);
    if overridden {
        for i in 0..count {
            s.push_str(&format!(
                "\n[[layers.trees.overrides]]\nid = \"tree-{i}\"\nscale = 1.0\n"
            ));
        }
    }
    s
}

/// Tree sets where every tree has an override: the lookup of a tree's
/// override is a linear search of the set's override list.
fn overrides(cfg: &Config) -> Result<(), moyo::Error> {
    println!(
        "### Per-tree overrides, `tree2`, generations 2, `stroke` ({} runs, {} warm-up)\n",
        cfg.runs, cfg.warmup
    );
    println!(
        "| trees | paths | scene ms, no overrides | scene ms, every tree overridden \
         | µs/tree, no overrides | µs/tree, overridden | k, no overrides | k, overridden \
         | parse + validate ms, overridden |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut prev: Option<(u32, [Duration; 2])> = None;
    for &count in &cfg.override_counts {
        let plain = SceneSpec::parse(&overridden_trees(count, false), Format::Toml)?;
        let every_text = overridden_trees(count, true);
        let every = SceneSpec::parse(&every_text, Format::Toml)?;
        let (t_parse, _) = measure(cfg, || {
            SceneSpec::parse(&every_text, Format::Toml).expect("description parses")
        });
        let (t_plain, scene) = measure(cfg, || build_scene(&plain).expect("scene builds"));
        let (t_every, _) = measure(cfg, || build_scene(&every).expect("scene builds"));
        let now = [t_plain.median, t_every.median];
        let per_tree = |t: Duration| us(t.as_secs_f64() * 1e6 / f64::from(count));
        let k = |i: usize| match prev {
            Some((n0, before)) => format!("{:.2}", exponent(n0, before[i], count, now[i])),
            None => "–".into(),
        };
        println!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            grouped(count as usize),
            grouped(scene.path_count()),
            ms(t_plain.median),
            ms(t_every.median),
            per_tree(t_plain.median),
            per_tree(t_every.median),
            k(0),
            k(1),
            ms(t_parse.median),
        );
        prev = Some((count, now));
    }
    println!();
    Ok(())
}

/// `count` uniform sites in a 400 mm square with two round holes, the cell
/// network drawn, relaxed `relax` times.
fn voronoi_scene(count: u32, relax: u32) -> String {
    format!(
        "version = 1\nseed = 1\npage = {{ size = [400, 400], margin = 0 }}\n\
         limits = {{ max_paths = 1000000 }}\n\
         [[layers]]\nname = \"cells\"\n[[layers.voronoi]]\nrelax = {relax}\n\
         sites = {{ distribution = \"uniform\", count = {count} }}\n\
         [layers.voronoi.region]\npolygon = [[0, 0], [400, 0], [400, 400], [0, 400]]\n\
         holes = [{{ circle = {{ centre = [130, 200], radius = 60 }} }}, \
                  {{ circle = {{ centre = [280, 200], radius = 80 }} }}]\n"
    )
}

fn voronoi(cfg: &Config) -> Result<(), moyo::Error> {
    println!(
        "### Voronoi cells clipped to a square with two holes ({} runs, {} warm-up)\n",
        cfg.runs, cfg.warmup
    );
    println!("| sites | Lloyd steps | paths | scene ms | SVG ms | scene + SVG ms |");
    println!("|---:|---:|---:|---:|---:|---:|");
    for (count, relax) in [(1_000, 0), (10_000, 0), (100_000, 0), (10_000, 5)] {
        let spec = SceneSpec::parse(&voronoi_scene(count, relax), Format::Toml)?;
        let (t_scene, scene) = measure(cfg, || build_scene(&spec).expect("scene builds"));
        let options = svg_options(&spec);
        let (t_svg, _) = measure(cfg, || to_svg(&scene, &options));
        println!(
            "| {} | {relax} | {} | {} | {} | {} |",
            grouped(count as usize),
            grouped(scene.path_count()),
            ms(t_scene.median),
            ms(t_svg.median),
            ms(t_scene.median + t_svg.median),
        );
    }
    println!();
    Ok(())
}

fn main() -> ExitCode {
    // `cargo bench` passes `--bench`; `cargo test --benches` (and
    // `--all-targets`) runs a benchmark without it, in a test build.
    if !std::env::args().any(|a| a == "--bench") {
        eprintln!("nothing timed: run `cargo bench --bench bench`");
        return ExitCode::SUCCESS;
    }
    let cfg = match Config::from_args() {
        Ok(c) => c,
        Err(msg) => {
            eprintln!("{msg}");
            return ExitCode::from(2);
        }
    };
    if cfg!(debug_assertions) {
        eprintln!("warning: debug build; run with `cargo bench` for meaningful figures");
    }
    let result = (|| {
        if cfg.runs_section("default") {
            default_design(&cfg)?;
        }
        for style in ["outline", "stroke"] {
            if cfg.runs_section(style) {
                scaling(&cfg, style)?;
            }
        }
        if cfg.runs_section("overrides") {
            overrides(&cfg)?;
        }
        if cfg.runs_section("voronoi") {
            voronoi(&cfg)?;
        }
        Ok::<(), moyo::Error>(())
    })();
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
