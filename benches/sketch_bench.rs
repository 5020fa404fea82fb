//! Wall-clock benchmark of the Sketching L-System, through the public API.
//!
//! Grows the paper's rules (`SketchRules::paper()`) with a 5 mm module
//! along a gently curving stroke, sampled about every 0.5 mm, until it has
//! taken 100 steps (500 mm). Measures, with [`std::time::Instant`], the
//! median of several runs (after one warm-up run that is not counted):
//!
//! - **grow**: `Sketch::new` and `extend` with the whole stroke (100 steps);
//! - **one more step**: `extend` of the grown sketch by one more module
//!   of stroke (step 101, which rewrites the 100 growing shoots), on a
//!   sketch grown afresh for each run;
//! - **skeleton**: `Sketch::skeleton`, the copy of the structure handed out.
//!
//! and, for the cost of a step against the shoots it rewrites, the time of
//! the step after 25, 50 and 100 steps.
//!
//! Everything goes to standard output as a Markdown table. Run it
//! with `cargo bench`, which builds it with the release settings (debug
//! timings mean nothing):
//!
//! ```text
//! cargo bench --bench sketch_bench            # 11 runs
//! cargo bench --bench sketch_bench -- --runs 5
//! ```

// `unused_crate_dependencies` (Cargo.toml) is for the library: a benchmark uses the library, not each of its dependencies.
#![allow(unused_crate_dependencies)]

use std::hint::black_box;
use std::time::{Duration, Instant};

use glam::DVec2;
use moyo::lsystem::sketch::{Sketch, SketchRules};

const MODULE: f64 = 5.0;
const SAMPLE: f64 = 0.5;

/// The point at parameter `s` of a stroke that climbs the page in a slow
/// S (its arc length a little more than `s`).
fn stroke_point(s: f64) -> DVec2 {
    DVec2::new(150.0 + 20.0 * (s / 80.0).sin(), 600.0 - s)
}

/// The stroke up to parameter `end`, a point every `SAMPLE`.
fn stroke(end: f64) -> Vec<DVec2> {
    let n = (end / SAMPLE).ceil() as usize;
    (0..=n)
        .map(|i| stroke_point((i as f64 * SAMPLE).min(end)))
        .collect()
}

fn median(mut t: Vec<Duration>) -> Duration {
    t.sort();
    t[t.len() / 2]
}

fn us(d: Duration) -> String {
    format!("{:.1}", d.as_secs_f64() * 1e6)
}

fn rules() -> SketchRules {
    SketchRules {
        module: MODULE,
        ..SketchRules::paper()
    }
}

/// The sketch grown along the stroke until it has taken `steps` steps.
fn grown(steps: usize, points: &[DVec2]) -> (Sketch, usize) {
    let mut sketch = Sketch::new(rules(), 10_000_000).expect("the paper's rules are valid");
    let mut used = 0;
    while sketch.steps() < steps {
        sketch
            .extend(&points[used..used + 1])
            .expect("within the budget");
        used += 1;
    }
    (sketch, used)
}

/// The median time of step `steps + 1`, on a sketch grown afresh each run
/// (a clone would have its vectors' capacities cut to their lengths, and
/// its first pushes would copy them).
fn next_step(steps: usize, points: &[DVec2], runs: usize) -> Duration {
    let mut times = Vec::new();
    for run in 0..=runs {
        let (mut s, mut used) = grown(steps, points);
        let t = Instant::now();
        while s.steps() == steps {
            s.extend(&points[used..used + 1])
                .expect("within the budget");
            used += 1;
        }
        let elapsed = t.elapsed();
        black_box(&s);
        if run > 0 {
            times.push(elapsed);
        }
    }
    median(times)
}

fn main() {
    // `cargo bench` passes `--bench`; `cargo test --benches` (and
    // `--all-targets`) runs a benchmark without it, in a test build.
    if !std::env::args().any(|a| a == "--bench") {
        eprintln!("nothing timed: run `cargo bench --bench sketch_bench`");
        return;
    }
    let args: Vec<String> = std::env::args().collect();
    let runs = args
        .iter()
        .position(|a| a == "--runs")
        .and_then(|i| args.get(i + 1))
        .and_then(|r| r.parse().ok())
        .unwrap_or(11usize)
        .max(1);

    // Enough stroke for 101 modules and a little more.
    let points = stroke(560.0);
    let (hundred, used) = grown(100, &points);
    let whole = &points[..used];
    let length: f64 = whole.windows(2).map(|w| w[0].distance(w[1])).sum();

    let mut grow = Vec::new();
    let mut copy = Vec::new();
    for run in 0..=runs {
        let t = Instant::now();
        let mut s = Sketch::new(rules(), 10_000_000).expect("valid");
        s.extend(whole).expect("within the budget");
        let t_grow = t.elapsed();
        let t = Instant::now();
        let skeleton = black_box(s.skeleton());
        let t_copy = t.elapsed();
        assert_eq!(s.steps(), 100);
        black_box((s, skeleton));
        if run > 0 {
            grow.push(t_grow);
            copy.push(t_copy);
        }
    }
    let skeleton = hundred.skeleton();
    println!(
        "Paper's rules, module {MODULE} mm, {} stroke points ({:.0} mm): {} steps, \
         {} segments, {} limbs",
        whole.len(),
        length,
        hundred.steps(),
        hundred.segments(),
        skeleton.limbs.len()
    );
    println!();
    println!("| what | µs (median of {runs}) |");
    println!("|---|---:|");
    println!("| grow 100 steps | {} |", us(median(grow)));
    println!(
        "| one more step (step 101) | {} |",
        us(next_step(100, &points, runs))
    );
    println!("| skeleton() copy | {} |", us(median(copy)));
    println!();
    println!("| step | growing shoots | µs (median of {runs}) |");
    println!("|---:|---:|---:|");
    for steps in [25, 50, 100] {
        println!(
            "| {} | {} | {} |",
            steps + 1,
            steps,
            us(next_step(steps, &points, runs))
        );
    }
}
