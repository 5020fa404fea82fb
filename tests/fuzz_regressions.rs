//! What the fuzzers found stays fixed: every input under
//! `fuzz/crashers/<target>/` (minimised cases that once panicked or hung)
//! runs through the same entry point the fuzz binary calls
//! ([`moyo::fuzz::Target::run`]) and must come back, as an answer or an
//! error. The seed corpus runs too, and every seed must still be a usable
//! input (its file name says `broken` when it is meant not to be), so the
//! corpus does not rot as the formats change.

use std::fs;
use std::path::{Path, PathBuf};

use moyo::fuzz::Target;

fn fuzz_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz")
}

/// The files of `fuzz/<kind>/<target>/`, sorted (none if it is missing).
fn cases(kind: &str, target: Target) -> Vec<PathBuf> {
    let dir = fuzz_dir().join(kind).join(target.name());
    let mut files: Vec<PathBuf> = fs::read_dir(&dir)
        .map(|entries| {
            entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.is_file() && p.file_name().is_some_and(|n| n != "README.md"))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
}

#[test]
fn every_crasher_ever_found_comes_back() {
    for target in Target::ALL {
        for case in cases("crashers", target) {
            let bytes = fs::read(&case).unwrap();
            // An error is a fine answer; a panic fails the test here.
            let _ = target.run(&bytes);
        }
    }
}

#[test]
fn every_seed_is_a_usable_input() {
    let mut seen = 0;
    for target in Target::ALL {
        let seeds = cases("corpus", target);
        assert!(!seeds.is_empty(), "{}: no seeds", target.name());
        for seed in seeds {
            let bytes = fs::read(&seed).unwrap();
            let result = target.run(&bytes);
            let broken = seed.to_string_lossy().contains("broken");
            assert_eq!(result.is_err(), broken, "{}: {result:?}", seed.display());
            seen += 1;
        }
    }
    assert!(seen >= 20, "{seen} seeds");
}

/// Each slow case the fuzzers kept (`fuzz/slow/<target>/`) is now refused
/// before its work, by a budget or a limit it passes (the message names
/// it), never run.
#[test]
fn every_slow_case_is_refused_before_its_work() {
    let mut seen = 0;
    for target in Target::ALL {
        for case in cases("slow", target) {
            let bytes = fs::read(&case).unwrap();
            let e = target.run(&bytes).unwrap_err().to_string();
            assert!(
                e.contains("site-steps") || e.contains("limits.max_paths"),
                "{}: {e}",
                case.display()
            );
            seen += 1;
        }
    }
    assert!(seen >= 1);
}
