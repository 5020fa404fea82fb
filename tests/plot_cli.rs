//! `moyo plot` and `moyo stats` through the binary: formats, stages, stats
//! JSON, and bad input leaving no output file.

use std::fs;
use std::path::Path;

use assert_cmd::Command;
use predicates::prelude::*;
use tempfile::TempDir;

fn moyo(dir: &TempDir) -> Command {
    let mut cmd = Command::cargo_bin("moyo").expect("the moyo binary is built");
    cmd.current_dir(dir.path());
    cmd
}

/// A directory holding the default design as `hem.svg`.
fn with_default_design() -> TempDir {
    let dir = tempfile::tempdir().expect("temporary directory");
    moyo(&dir)
        .args(["render", "-o", "hem.svg"])
        .assert()
        .success();
    dir
}

fn stats_json(dir: &TempDir, file: &str) -> serde_json::Value {
    let out = moyo(dir)
        .args(["stats", file, "--json"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    serde_json::from_slice(&out).expect("stats --json prints JSON")
}

fn number(v: &serde_json::Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} missing in {v}"))
}

#[test]
fn stats_json_has_totals_and_layers() {
    let dir = with_default_design();
    let s = stats_json(&dir, "hem.svg");
    assert!(number(&s, "paths") > 50.0);
    assert!(number(&s, "pen_down_mm") > 1000.0);
    assert!(number(&s, "pen_up_mm") > 0.0);
    assert!(number(&s, "plot_time_s") > 0.0);
    let layers = s["layers"].as_array().expect("layers");
    assert_eq!(layers.len(), 2, "one per pen");
    let sum: f64 = layers.iter().map(|l| number(l, "paths")).sum();
    assert_eq!(sum, number(&s, "paths"));
}

#[test]
fn merge_and_sort_keep_ink_and_shorten_travel() {
    let dir = with_default_design();
    moyo(&dir)
        .args(["plot", "hem.svg", "--merge", "--sort", "-o", "sorted.svg"])
        .assert()
        .success();
    let before = stats_json(&dir, "hem.svg");
    let after = stats_json(&dir, "sorted.svg");
    let ink = |v: &serde_json::Value| number(v, "pen_down_mm");
    assert!((ink(&before) - ink(&after)).abs() < 0.01 * ink(&before));
    assert!(number(&after, "pen_up_mm") < number(&before, "pen_up_mm"));
}

#[test]
fn output_format_follows_the_extension() {
    let dir = with_default_design();
    moyo(&dir)
        .args(["plot", "hem.svg", "--sort", "-o", "hem.gcode"])
        .assert()
        .success();
    let g = fs::read_to_string(dir.path().join("hem.gcode")).unwrap();
    assert!(g.contains("G21") && g.contains("M3 S1000"), "{}", &g[..200]);
    moyo(&dir)
        .args(["plot", "hem.svg", "-o", "hem.plt", "--cutter"])
        .assert()
        .success();
    let h = fs::read_to_string(dir.path().join("hem.plt")).unwrap();
    assert!(h.starts_with("IN;") && h.contains("SP2;") && h.contains("PD"));
}

#[test]
fn hatch_and_occlude_run_on_an_imported_svg() {
    let dir = tempfile::tempdir().unwrap();
    let svg = r##"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100">
        <path d="M 0 50 L 100 50" stroke="#000" fill="none"/>
        <rect x="20" y="20" width="60" height="60" fill="#888" stroke="#000"/>
    </svg>"##;
    fs::write(dir.path().join("in.svg"), svg).unwrap();
    moyo(&dir)
        .args([
            "plot",
            "in.svg",
            "--hatch",
            "2",
            "--occlude",
            "-o",
            "out.svg",
        ])
        .args(["--png", "out.png", "--show-travel"])
        .assert()
        .success();
    let s = stats_json(&dir, "out.svg");
    // The line is hidden where the square covers it (60 of 100 mm), and
    // the square's fill became hatch lines.
    let ink = number(&s, "pen_down_mm");
    assert!(ink > 40.0 + 240.0 + 60.0 * 60.0 / 2.0 * 0.9, "{ink}");
    assert!(dir.path().join("out.png").exists());
}

#[test]
fn bad_svg_fails_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in [("empty.svg", ""), ("broken.svg", "<svg><g></svg")] {
        fs::write(dir.path().join(name), text).unwrap();
        moyo(&dir)
            .args(["plot", name, "--sort", "-o", "out.svg"])
            .assert()
            .failure()
            .stderr(predicate::str::starts_with("error: ").and(predicate::str::contains(name)));
        assert!(!Path::new(&dir.path().join("out.svg")).exists());
        moyo(&dir).args(["stats", name]).assert().failure();
    }
    moyo(&dir)
        .args(["plot", "missing.svg", "-o", "out.svg"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("missing.svg"));
}

#[test]
fn bad_stage_options_are_refused() {
    let dir = with_default_design();
    for args in [
        &["--hatch", "0"][..],
        &["--multipass", "0"],
        &["--merge", "-1"],
        &["--speed-down", "0"],
    ] {
        moyo(&dir)
            .args(["plot", "hem.svg", "-o", "out.svg"])
            .args(args)
            .assert()
            .failure()
            .stderr(predicate::str::starts_with("error: "));
        assert!(!dir.path().join("out.svg").exists(), "{args:?}");
    }
}
