//! Wall-clock benchmark of the L-system engine, through the public API.
//!
//! Measures, with [`std::time::Instant`], the median of several runs (after
//! one warm-up run that is not counted), each in a fresh process, for each
//! system:
//!
//! - **derive**: parsing and rewriting from the axiom (`LSystem::derive`);
//! - **draw**: the turtle's interpretation into a skeleton
//!   (`Turtle::interpret`).
//!
//! The systems: ABOP fig. 1.24a (`F → F[+F]F[-F]F`, n = 10: about 24.4
//! million modules, 9.8 million segments; the non-parametric fast path),
//! the same rule as two stochastic alternatives (ABOP fig. 1.27's kind),
//! the same rule with a length parameter (every module through the
//! expression evaluator; n = 9: about 4.9 million modules), a parametric
//! tree with conditions and constants, and ABOP fig. 1.31a
//! (context-sensitive, with ignored symbols).
//!
//! Everything goes to standard output as a Markdown table. Run it
//! with `cargo bench`, which builds it with the release settings (debug
//! timings mean nothing):
//!
//! ```text
//! cargo bench --bench lsystem_bench            # 5 runs
//! cargo bench --bench lsystem_bench -- --runs 3
//! ```

// `unused_crate_dependencies` (Cargo.toml) is for the library: a benchmark uses the library, not each of its dependencies.
#![allow(unused_crate_dependencies)]

use std::collections::BTreeMap;
use std::hint::black_box;
use std::process::Command;
use std::time::Instant;

use moyo::lsystem::{LSystem, Turtle, TurtleOptions};
use moyo::Seed;

struct Case {
    name: &'static str,
    axiom: &'static str,
    rules: &'static [&'static str],
    constants: &'static [(&'static str, f64)],
    ignore: &'static str,
    n: usize,
    angle: f64,
}

const CASES: &[Case] = &[
    Case {
        name: "ABOP 1.24a, n = 10",
        axiom: "F",
        rules: &["F -> F[+F]F[-F]F"],
        constants: &[],
        ignore: "",
        n: 10,
        angle: 25.7,
    },
    Case {
        name: "stochastic 1.24a, n = 10",
        axiom: "F",
        rules: &["F ->(1) F[+F]F[-F]F", "F ->(1) F[-F]F[+F]F"],
        constants: &[],
        ignore: "",
        n: 10,
        angle: 25.7,
    },
    Case {
        name: "parametric 1.24a, n = 9",
        axiom: "F(1)",
        rules: &["F(l) -> F(l/3)[+F(l/3)]F(l/3)[-F(l/3)]F(l/3)"],
        constants: &[],
        ignore: "",
        n: 9,
        angle: 25.7,
    },
    Case {
        name: "parametric tree, n = 18",
        axiom: "A(L0, W0)",
        rules: &[
            "A(l, w) : l > 0.05 -> !(w)F(l)[&(30)/(137)A(l*R1, w*0.7)][^(20)\\(90)A(l*R2, w*0.7)]",
            "A(l, w) : l <= 0.05 -> L",
        ],
        constants: &[("L0", 1.0), ("W0", 0.1), ("R1", 0.75), ("R2", 0.68)],
        ignore: "",
        n: 18,
        angle: 25.7,
    },
    Case {
        // ABOP fig. 1.31a (its `* < + > *` rules are context-free).
        name: "ABOP 1.31a context, n = 30",
        axiom: "F1F1F1",
        rules: &[
            "0 < 0 > 0 -> 0",
            "0 < 0 > 1 -> 1[+F1F1]",
            "0 < 1 > 0 -> 1",
            "0 < 1 > 1 -> 1",
            "1 < 0 > 0 -> 0",
            "1 < 0 > 1 -> 1F1",
            "1 < 1 > 0 -> 0",
            "1 < 1 > 1 -> 0",
            "+ -> -",
            "- -> +",
        ],
        constants: &[],
        ignore: "+-F",
        n: 30,
        angle: 22.5,
    },
];

fn median(mut t: Vec<f64>) -> f64 {
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

/// One measurement in this process: prints "derive-ms draw-ms modules
/// segments limbs".
fn measure(case: &Case) {
    let constants: BTreeMap<String, f64> = case
        .constants
        .iter()
        .map(|(k, v)| (k.to_string(), *v))
        .collect();
    let options = TurtleOptions::DEFAULT
        .with_angle(case.angle)
        .with_max_segments(50_000_000);
    let t = Instant::now();
    let system = LSystem::parse(case.axiom, case.rules, &constants, case.ignore, "bench")
        .expect("the benchmark's systems parse");
    let word = system
        .derive(case.n, &mut Seed(1).stream(), 100_000_000)
        .expect("within the budget");
    let t_derive = t.elapsed();
    let t = Instant::now();
    let skeleton = Turtle::new(options)
        .interpret(&word)
        .expect("within the budget");
    let t_draw = t.elapsed();
    let segments: usize = skeleton.limbs.iter().map(|l| l.points.len() - 1).sum();
    println!(
        "{} {} {} {} {}",
        t_derive.as_secs_f64() * 1000.0,
        t_draw.as_secs_f64() * 1000.0,
        word.len(),
        segments,
        skeleton.limbs.len()
    );
    black_box((word, skeleton));
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .and_then(|r| r.parse::<usize>().ok())
    };
    if let Some(k) = value("--case") {
        measure(&CASES[k.min(CASES.len() - 1)]);
        return;
    }
    // `cargo bench` passes `--bench`; `cargo test --benches` (and
    // `--all-targets`) runs a benchmark without it, in a test build.
    if !std::env::args().any(|a| a == "--bench") {
        eprintln!("nothing timed: run `cargo bench --bench lsystem_bench`");
        return;
    }
    let runs = value("--runs").unwrap_or(5).max(1);
    let me = std::env::current_exe().expect("the benchmark knows where it is");

    println!("| system | modules | segments | limbs | derive ms | draw ms |");
    println!("|---|---:|---:|---:|---:|---:|");
    for (k, case) in CASES.iter().enumerate() {
        let (mut derive, mut draw) = (Vec::new(), Vec::new());
        let mut sizes = String::new();
        // Each run in a fresh process: the allocator starts clean, as it
        // does for a real program (freeing millions of limbs of one run
        // would otherwise slow the next one's allocations).
        for run in 0..=runs {
            let out = Command::new(&me)
                .args(["--case", &k.to_string()])
                .output()
                .expect("the benchmark runs itself");
            let line = String::from_utf8_lossy(&out.stdout).to_string();
            let f: Vec<&str> = line.split_whitespace().collect();
            assert_eq!(f.len(), 5, "unexpected output: {line}");
            if run > 0 {
                derive.push(f[0].parse().expect("a number"));
                draw.push(f[1].parse().expect("a number"));
            }
            sizes = format!("{} | {} | {}", f[2], f[3], f[4]);
        }
        println!(
            "| {} | {sizes} | {:.1} | {:.1} |",
            case.name,
            median(derive),
            median(draw)
        );
    }
}
