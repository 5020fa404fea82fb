//! Micro-benchmark of the number formatter of every text output
//! ([`moyo::output::write_number`]) against the way it used to write
//! numbers: Rust's `{:.p}` and trimming, which defines the bytes.
//!
//! For each precision it writes the same 200,000 numbers both ways (drawing
//! coordinates: uniform in ±300 mm, from a fixed xorshift sequence), checks
//! that the bytes are identical, and reports the median over several runs
//! of the time per number and the speed-up. Timed with
//! [`std::time::Instant`], like the other benchmarks here (a loop of
//! 200,000 calls, far above the timer's resolution).
//!
//! ```text
//! cargo bench --bench number_bench            # 9 runs
//! cargo bench --bench number_bench -- --runs 21
//! ```

// `unused_crate_dependencies` (Cargo.toml) is for the library: a benchmark uses the library, not each of its dependencies.
#![allow(unused_crate_dependencies)]

use std::fmt::Write as _;
use std::hint::black_box;
use std::process::ExitCode;
use std::time::Instant;

use moyo::output::write_number;

/// Numbers written per timed run.
const COUNT: usize = 200_000;

/// The way numbers were written before the fixed-point formatter: the
/// reference the bytes are checked against.
fn write_formatted(out: &mut String, v: f64, precision: u8) {
    let start = out.len();
    let precision = usize::from(precision);
    write!(out, "{v:.precision$}").expect("writing to a String cannot fail");
    if out[start..].contains('.') {
        let kept = out[start..]
            .trim_end_matches('0')
            .trim_end_matches('.')
            .len();
        out.truncate(start + kept);
    }
    if &out[start..] == "-0" {
        out.truncate(start);
        out.push('0');
    }
}

/// `COUNT` coordinates in ±300 mm from a fixed xorshift64 sequence.
fn coordinates() -> Vec<f64> {
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    (0..COUNT)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 600.0 - 300.0
        })
        .collect()
}

/// The median time of `runs` runs of writing every value of `values`
/// with `write`, in nanoseconds a number; and the text written.
fn time(
    values: &[f64],
    precision: u8,
    runs: usize,
    write: fn(&mut String, f64, u8),
) -> (f64, String) {
    let mut out = String::with_capacity(values.len() * 16);
    let mut times = Vec::with_capacity(runs);
    for _ in 0..=runs {
        out.clear();
        let start = Instant::now();
        for &v in values {
            write(&mut out, black_box(v), precision);
            out.push(' ');
        }
        times.push(start.elapsed().as_secs_f64() * 1e9 / values.len() as f64);
    }
    // The first run warms the caches and is not counted.
    times.remove(0);
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], out)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    // `cargo bench` passes `--bench`; `cargo test --benches` (and
    // `--all-targets`) runs a benchmark without it, in a test build.
    if !args.iter().any(|a| a == "--bench") {
        eprintln!("nothing timed: run `cargo bench --bench number_bench`");
        return ExitCode::SUCCESS;
    }
    let runs = match args.iter().position(|a| a == "--runs") {
        Some(i) => match args.get(i + 1).and_then(|n| n.parse().ok()) {
            Some(n) if n > 0 => n,
            _ => {
                eprintln!("--runs needs a whole number ≥ 1");
                return ExitCode::FAILURE;
            }
        },
        None => 9,
    };
    let values = coordinates();
    println!("| precision | `{{:.p}}` + trim, ns | fixed point, ns | speed-up |");
    println!("|---:|---:|---:|---:|");
    for precision in 0..=8 {
        let (before, reference) = time(&values, precision, runs, write_formatted);
        let (after, written) = time(&values, precision, runs, write_number);
        if written != reference {
            eprintln!("precision {precision}: the bytes differ from `{{:.p}}` + trim");
            return ExitCode::FAILURE;
        }
        println!(
            "| {precision} | {before:.1} | {after:.1} | {:.1}× |",
            before / after
        );
    }
    ExitCode::SUCCESS
}
