//! Writes are safe: an output may replace its own input, a place that
//! cannot be written fails with a message naming it and leaves nothing
//! behind, and two runs writing one file at once leave one whole file,
//! never a mix (every output goes to a temporary file that is renamed
//! over the target: `moyo::output::write_atomic`).

use std::fs;
use std::os::unix::fs::PermissionsExt as _;
use std::path::{Path, PathBuf};
use std::process::Command as Process;

use predicates::prelude::*;

use crate::cli::{entries, moyo, tempdir};

#[test]
fn plot_can_write_over_its_own_input() {
    let dir = tempdir();
    moyo(&dir)
        .args(["render", "-t", "tree-rules", "-o", "a.svg"])
        .assert()
        .success();
    fs::copy(dir.path().join("a.svg"), dir.path().join("copy.svg")).unwrap();
    moyo(&dir)
        .args([
            "plot",
            "copy.svg",
            "-o",
            "expected.svg",
            "--merge",
            "--sort",
        ])
        .assert()
        .success();
    moyo(&dir)
        .args(["plot", "a.svg", "-o", "a.svg", "--merge", "--sort"])
        .assert()
        .success();
    let read = |name: &str| fs::read_to_string(dir.path().join(name)).unwrap();
    assert_eq!(read("a.svg"), read("expected.svg"));
    assert_eq!(entries(dir.path()).len(), 3, "{:?}", entries(dir.path()));
}

/// A directory this process cannot write in: one without write
/// permission, or, for root (whom permissions do not stop), `/sys`.
fn unwritable(dir: &Path) -> Option<PathBuf> {
    let locked = dir.join("locked");
    fs::create_dir(&locked).unwrap();
    fs::set_permissions(&locked, fs::Permissions::from_mode(0o555)).unwrap();
    [locked, PathBuf::from("/sys")]
        .into_iter()
        .find(|d| d.is_dir() && fs::write(d.join(".moyo-probe"), b"").is_err())
}

#[test]
fn a_place_that_cannot_be_written_fails_with_its_name() {
    let dir = tempdir();
    let Some(place) = unwritable(dir.path()) else {
        eprintln!("every directory is writable here; nothing to test");
        return;
    };
    let target = place.join("out.svg");
    for args in [
        vec!["render", "-t", "tree-rules", "-o"],
        vec!["plot", "in.svg", "-o"],
    ] {
        fs::write(dir.path().join("in.svg"), r#"<svg xmlns="http://www.w3.org/2000/svg" width="10mm" height="10mm"><path d="M1 1 L9 9" stroke="black"/></svg>"#).unwrap();
        moyo(&dir)
            .args(&args)
            .arg(&target)
            .assert()
            .failure()
            .stderr(predicate::str::contains(target.display().to_string()))
            .stderr(predicate::str::contains("denied").or(predicate::str::contains("ermission")));
        assert!(!target.exists());
    }
    if place.starts_with(dir.path()) {
        assert!(fs::read_dir(&place).unwrap().next().is_none());
    }
}

#[test]
fn two_runs_writing_one_file_leave_one_whole_file() {
    let dir = tempdir();
    let bin = assert_cmd::cargo::cargo_bin("moyo");
    let render = |template: &str, out: &str| {
        Process::new(&bin)
            .current_dir(dir.path())
            .args(["render", "-t", template, "-o", out])
            .spawn()
            .unwrap()
    };
    for (template, name) in [("kimono-1", "a.svg"), ("tree-rules", "b.svg")] {
        assert!(render(template, name).wait().unwrap().success());
    }
    let a = fs::read(dir.path().join("a.svg")).unwrap();
    let b = fs::read(dir.path().join("b.svg")).unwrap();
    for _ in 0..4 {
        let mut first = render("kimono-1", "out.svg");
        let mut second = render("tree-rules", "out.svg");
        assert!(first.wait().unwrap().success() && second.wait().unwrap().success());
        let out = fs::read(dir.path().join("out.svg")).unwrap();
        assert!(out == a || out == b, "a mix of {} bytes", out.len());
        let names = entries(dir.path());
        assert!(names.iter().all(|n| !n.ends_with(".tmp")), "{names:?}");
    }
}
