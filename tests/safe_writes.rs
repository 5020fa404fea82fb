//! Writes are safe: an output is never one of the command's inputs nor
//! another of its outputs, and its folder is there (each refused before
//! anything is computed, naming the files or the folder); a place that
//! cannot be written fails with a message naming it and leaves nothing
//! behind; and two runs writing one file at once leave one whole file,
//! never a mix (every output goes to a temporary file that is renamed over
//! the target: `moyo::output::write_atomic`). Nothing is left behind: a
//! run with several outputs writes all of them or none, a signal removes
//! the temporary files, and a stale one from a killed run goes with the
//! next write into its folder.

use std::fs;
use std::os::unix::fs::PermissionsExt as _;
use std::path::{Path, PathBuf};
use std::process::Command as Process;

use predicates::prelude::*;

use crate::cli::{entries, moyo, tempdir};

/// A folder with a design (`a.toml`, rendered as `a.svg`), a drawing to
/// plot and fill (`in.svg`), an image (`photo.png`) and a stroke
/// (`stroke.svg`).
fn with_inputs() -> tempfile::TempDir {
    let dir = tempdir();
    moyo(&dir)
        .args(["new", "tree-rules", "-o", "a.toml"])
        .assert()
        .success();
    moyo(&dir)
        .args(["render", "a.toml", "-o", "a.svg"])
        .assert()
        .success();
    let square = r#"<svg xmlns="http://www.w3.org/2000/svg" width="40mm" height="40mm" viewBox="0 0 40 40"><rect x="5" y="5" width="30" height="30" stroke="black" fill="none"/></svg>"#;
    fs::write(dir.path().join("in.svg"), square).unwrap();
    fs::write(dir.path().join("stroke.svg"), square).unwrap();
    let png = moyo::output::render_png(square, 10.0).unwrap();
    fs::write(dir.path().join("photo.png"), png).unwrap();
    dir
}

#[test]
fn an_output_that_is_an_input_or_another_output_is_refused() {
    let dir = with_inputs();
    fs::create_dir(dir.path().join("sub")).unwrap();
    let lsystem = ["lsystem", "--axiom", "F", "--angle", "90"];
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["render", "a.toml", "-o", "a.toml"],
            "-o a.toml: the same file as the scene a.toml, which writing would replace",
        ),
        (
            vec!["render", "--from", "a.svg", "-o", "./a.svg"],
            "-o ./a.svg: the same file as --from a.svg",
        ),
        (
            vec!["render", "a.toml", "-o", "b.svg", "--png", "b.svg"],
            "--png b.svg: the same file as -o b.svg; give each output a file of its own",
        ),
        (
            vec![
                "render",
                "a.toml",
                "-o",
                "b.svg",
                "--preview-svg",
                "sub/../b.svg",
            ],
            "--preview-svg sub/../b.svg: the same file as -o b.svg",
        ),
        (
            vec![
                "render", "a.toml", "-o", "b.svg", "--dump", "d", "--obj", "d",
            ],
            "--obj d: the same file as --dump d",
        ),
        (
            vec!["plot", "in.svg", "-o", "in.svg"],
            "-o in.svg: the same file as the input in.svg",
        ),
        (
            vec![
                "plot",
                "in.svg",
                "-o",
                "out.svg",
                "--preview-svg",
                "out.svg",
            ],
            "--preview-svg out.svg: the same file as -o out.svg",
        ),
        (
            vec!["plot", "in.svg", "-o", "p.gcode", "--png", "p.gcode"],
            "--png p.gcode: the same file as -o p.gcode",
        ),
        (
            vec!["fill", "in.svg", "-o", "in.svg"],
            "-o in.svg: the same file as the input in.svg",
        ),
        (
            vec![
                "fill",
                "in.svg",
                "-o",
                "f.svg",
                "--image",
                "photo.png",
                "--png",
                "photo.png",
            ],
            "--png photo.png: the same file as --image photo.png",
        ),
        (
            vec!["fill", "in.svg", "-o", "f.svg", "--png", "f.svg"],
            "--png f.svg: the same file as -o f.svg",
        ),
        (
            vec!["lsystem", "--stroke", "stroke.svg", "-o", "stroke.svg"],
            "-o stroke.svg: the same file as --stroke stroke.svg",
        ),
        (
            [&lsystem[..], &["-o", "l.svg", "--png", "l.svg"]].concat(),
            "--png l.svg: the same file as -o l.svg",
        ),
        (
            [&lsystem[..], &["-o", "sub/growth.svg", "--frames", "sub"]].concat(),
            "-o sub/growth.svg: --frames sub writes a file of that name there",
        ),
        (
            [
                &lsystem[..],
                &[
                    "-o",
                    "l.svg",
                    "--png",
                    "./sub/frame-003.png",
                    "--frames",
                    "sub",
                ],
            ]
            .concat(),
            "--png ./sub/frame-003.png: --frames sub writes a file of that name there",
        ),
    ];
    let before = entries(dir.path());
    let a_toml = fs::read(dir.path().join("a.toml")).unwrap();
    let a_svg = fs::read(dir.path().join("a.svg")).unwrap();
    for (args, expected) in cases {
        let out = moyo(&dir)
            .args(&args)
            .assert()
            .failure()
            .get_output()
            .stderr
            .clone();
        let stderr = String::from_utf8_lossy(&out);
        assert!(
            stderr.starts_with(&format!("error: {expected}")),
            "{args:?}: {stderr}"
        );
        assert_eq!(entries(dir.path()), before, "{args:?}");
        assert!(entries(&dir.path().join("sub")).is_empty(), "{args:?}");
    }
    assert_eq!(fs::read(dir.path().join("a.toml")).unwrap(), a_toml);
    assert_eq!(fs::read(dir.path().join("a.svg")).unwrap(), a_svg);
    // Outputs of their own are fine, the same names in another folder too.
    moyo(&dir)
        .args(["plot", "in.svg", "-o", "sub/in.svg", "--png", "sub/in.png"])
        .assert()
        .success();
}

#[test]
fn a_missing_folder_is_named_before_anything_is_computed() {
    let dir = with_inputs();
    let lsystem = ["lsystem", "--axiom", "F", "--angle", "90"];
    for args in [
        vec!["render", "a.toml", "-o", "nodir/out.svg"],
        vec![
            "render",
            "a.toml",
            "-o",
            "out.svg",
            "--png",
            "nodir/out.png",
        ],
        vec!["plot", "in.svg", "-o", "nodir/out.svg"],
        vec![
            "plot",
            "in.svg",
            "-o",
            "out.svg",
            "--preview-svg",
            "nodir/p.svg",
        ],
        vec!["fill", "in.svg", "-o", "nodir/out.svg"],
        [&lsystem[..], &["-o", "nodir/out.svg"]].concat(),
        vec!["new", "tree-rules", "-o", "nodir/out.toml"],
    ] {
        let before = entries(dir.path());
        moyo(&dir)
            .args(&args)
            .assert()
            .failure()
            .stderr(predicate::eq("error: nodir: no such folder\n"));
        assert_eq!(entries(dir.path()), before, "{args:?}");
    }
    // A file where a folder should be.
    moyo(&dir)
        .args(["plot", "in.svg", "-o", "in.svg/out.svg"])
        .assert()
        .failure()
        .stderr(predicate::eq("error: in.svg: not a folder\n"));
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

/// The names of the temporary files in `dir`.
fn temporaries(dir: &Path) -> Vec<String> {
    entries(dir)
        .into_iter()
        .filter(|n| n.starts_with(".moyo-") && n.ends_with(".tmp"))
        .collect()
}

#[test]
fn several_outputs_are_written_all_or_none() {
    let dir = with_inputs();
    let Some(place) = unwritable(dir.path()) else {
        eprintln!("every directory is writable here; nothing to test");
        return;
    };
    let blocked = place.join("b.png");
    let before = fs::read(dir.path().join("a.svg")).unwrap();
    // The PNG cannot be written: the SVG written first is not renamed.
    for args in [
        vec!["render", "-t", "tree-rules", "-o", "a.svg", "--png"],
        vec!["render", "-t", "tree-rules", "-o", "new.svg", "--png"],
        vec!["plot", "in.svg", "-o", "new.svg", "--png"],
        vec!["fill", "in.svg", "-o", "new.svg", "--png"],
    ] {
        moyo(&dir)
            .args(&args)
            .arg(&blocked)
            .assert()
            .failure()
            .stderr(predicate::str::contains(blocked.display().to_string()));
        assert!(!dir.path().join("new.svg").exists(), "{args:?}");
        assert_eq!(fs::read(dir.path().join("a.svg")).unwrap(), before);
        assert!(temporaries(dir.path()).is_empty());
    }
    // A PNG that would replace a folder is refused before anything is
    // written.
    fs::create_dir(dir.path().join("taken.png")).unwrap();
    moyo(&dir)
        .args([
            "render",
            "-t",
            "tree-rules",
            "-o",
            "new.svg",
            "--png",
            "taken.png",
        ])
        .assert()
        .failure()
        .stderr(predicate::str::contains("taken.png: a folder, not a file"));
    assert!(!dir.path().join("new.svg").exists());
}

#[test]
fn a_stale_temporary_file_is_removed_by_the_next_write_a_fresh_one_kept() {
    let dir = tempdir();
    let long_ago = std::time::SystemTime::now() - moyo::output::STALE_AFTER;
    let stale = dir.path().join(".moyo-killed.tmp");
    fs::File::create(&stale)
        .unwrap()
        .set_modified(long_ago)
        .unwrap();
    // Another run's, writing now.
    fs::write(dir.path().join(".moyo-running.tmp"), b"").unwrap();
    moyo(&dir)
        .args(["render", "-t", "tree-rules", "-o", "out.svg"])
        .assert()
        .success();
    let names: Vec<String> = entries(dir.path()).into_iter().collect();
    assert_eq!(names, [".moyo-running.tmp", "out.svg"]);
}

/// A signal stops a run with the shell's code for it, and leaves no file:
/// neither the output nor a temporary file. (A temporary file exists for
/// milliseconds, too short to aim a signal at from here; that the handler
/// removes the registered temporary files, and that none is created after
/// it ran, is tested in `output::atomic`.)
#[test]
fn a_signal_stops_a_run_and_leaves_nothing_behind() {
    let dir = tempdir();
    let bin = assert_cmd::cargo::cargo_bin("moyo");
    for (signal, code) in [("TERM", 143), ("INT", 130)] {
        // Seconds of work in a test build.
        let mut run = Process::new(&bin)
            .current_dir(dir.path())
            .args([
                "render",
                "-t",
                "stipple-lbg",
                "-o",
                "out.svg",
                "--png",
                "out.png",
            ])
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        // Past the start, where the handler is installed.
        std::thread::sleep(std::time::Duration::from_millis(700));
        let sent = Process::new("kill")
            .args([format!("-{signal}"), run.id().to_string()])
            .status()
            .unwrap();
        assert!(sent.success());
        let status = run.wait().unwrap();
        assert_eq!(status.code(), Some(code), "SIG{signal}: {status}");
        assert!(entries(dir.path()).is_empty(), "{:?}", entries(dir.path()));
    }
}

#[test]
fn frames_refuse_a_file_and_replace_their_own_old_frames() {
    let dir = with_inputs();
    let lsystem = ["lsystem", "--axiom", "F", "--angle", "90", "-o", "l.svg"];
    // A file where the frames folder should be: refused before any work.
    moyo(&dir)
        .args(lsystem)
        .args(["--frames", "in.svg"])
        .assert()
        .failure()
        .stderr(predicate::eq(
            "error: --frames in.svg: not a folder; name a folder for the frames\n",
        ));
    assert!(!dir.path().join("l.svg").exists());

    // An earlier, longer growth with PNGs; and a file of the user's.
    let frames = dir.path().join("f");
    fs::create_dir(&frames).unwrap();
    for k in 0..40 {
        fs::write(frames.join(format!("frame-{k:03}.svg")), b"old").unwrap();
        fs::write(frames.join(format!("frame-{k:03}.png")), b"old").unwrap();
    }
    fs::write(frames.join("notes.txt"), b"mine").unwrap();
    moyo(&dir)
        .args(lsystem)
        .args(["--frames", "f"])
        .assert()
        .success();
    let names = entries(&frames);
    assert!(names.contains("notes.txt") && names.contains("growth.svg"));
    let written: Vec<&String> = names.iter().filter(|n| n.starts_with("frame-")).collect();
    assert!(!written.is_empty() && written.len() < 40, "{names:?}");
    assert!(written.iter().all(|n| n.ends_with(".svg")), "{names:?}");
    for name in written {
        assert_ne!(fs::read(frames.join(name)).unwrap(), b"old", "{name}");
    }
}
