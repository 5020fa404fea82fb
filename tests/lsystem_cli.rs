//! `moyo lsystem` through the binary: rules from the command line give the
//! same drawing as the same table in a description; growth frames; the
//! sketch along the first path of an SVG, on its page; bad rules failing
//! with the option and the column, leaving no file behind.

use std::fs;

use predicates::prelude::*;

use crate::cli::{moyo, tempdir as dir};

/// A stroke: one cubic on a 150 mm square page, and a second path that the
/// sketch must not follow.
const STROKE: &str = r##"<svg xmlns="http://www.w3.org/2000/svg" width="150mm" height="150mm" viewBox="0 0 150 150">
    <path d="M 20 140 C 40 100, 110 110, 120 20" stroke="#000" fill="none"/>
    <path d="M 0 0 L 150 0" stroke="#000" fill="none"/>
</svg>"##;

/// The path data of every `<path>` in an SVG (the drawing, not the
/// embedded description).
fn path_data(svg: &str) -> Vec<&str> {
    svg.split("<path")
        .skip(1)
        .filter_map(|p| p.split(" d=\"").nth(1)?.split('"').next())
        .collect()
}

#[test]
fn the_command_line_draws_what_the_description_draws() {
    let d = dir();
    moyo(&d)
        .args([
            "lsystem",
            "--axiom",
            "X",
            "--rule",
            "X -> F[+X]F[-X]+X",
            "--rule",
            "F=FF",
            "--angle",
            "20",
            "-n",
            "4",
            "--page",
            "A5",
            "-o",
            "cli.svg",
        ])
        .assert()
        .success()
        .stderr(predicate::str::contains("wrote cli.svg"));
    let description = r#"version = 1
seed = 1
page = { size = "A5" }
limits = { max_paths = 1000000 }
[[layers]]
name = "lsystem"
[[layers.lsystem]]
axiom = "X"
rules = ["X -> F[+X]F[-X]+X", "F=FF"]
iterations = 4
angle = 20
"#;
    fs::write(d.path().join("plant.toml"), description).unwrap();
    moyo(&d)
        .args(["render", "plant.toml", "-o", "file.svg"])
        .assert()
        .success();
    let cli = fs::read_to_string(d.path().join("cli.svg")).unwrap();
    let file = fs::read_to_string(d.path().join("file.svg")).unwrap();
    assert!(!path_data(&cli).is_empty());
    assert_eq!(path_data(&cli), path_data(&file));
}

#[test]
fn frames_show_every_rewriting_step() {
    let d = dir();
    moyo(&d)
        .args([
            "lsystem", "--axiom", "F", "--rule", "F=F[+F]F", "-n", "3", "-o", "out.svg", "--png",
            "out.png", "--dpi", "20", "--frames", "steps",
        ])
        .assert()
        .success()
        .stderr(predicate::str::contains("4 frames in steps"));
    let mut names: Vec<String> = fs::read_dir(d.path().join("steps"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    let mut want: Vec<String> = (0..4)
        .flat_map(|k| [format!("frame-{k:03}.png"), format!("frame-{k:03}.svg")])
        .collect();
    want.push("growth.svg".into());
    assert_eq!(names, want);
    // The growth in one loop: every frame, taking turns.
    let growth = fs::read_to_string(d.path().join("steps/growth.svg")).unwrap();
    assert_eq!(growth.matches("<animate ").count(), 4);
    // Each step draws more: F has 1, 3, 9, 27 segments in 1, 2, 4, 8 limbs.
    let limbs = |k: usize| {
        let svg = fs::read_to_string(d.path().join(format!("steps/frame-{k:03}.svg"))).unwrap();
        path_data(&svg).len()
    };
    assert!(limbs(0) < limbs(1) && limbs(1) < limbs(2) && limbs(2) < limbs(3));
    // The last frame is the drawing.
    let last = fs::read_to_string(d.path().join("steps/frame-003.svg")).unwrap();
    let out = fs::read_to_string(d.path().join("out.svg")).unwrap();
    assert_eq!(path_data(&last), path_data(&out));
}

#[test]
fn a_sketch_grows_along_the_first_path_on_its_page() {
    let d = dir();
    fs::write(d.path().join("stroke.svg"), STROKE).unwrap();
    moyo(&d)
        .args([
            "lsystem",
            "--stroke",
            "stroke.svg",
            "--module",
            "7",
            "-o",
            "s.svg",
            "--frames",
            "grow",
        ])
        .assert()
        .success();
    let svg = fs::read_to_string(d.path().join("s.svg")).unwrap();
    // On the stroke file's page.
    assert!(svg.contains("width=\"150mm\"") && svg.contains("height=\"150mm\""));
    // Fewer frames than module steps would be wrong: the stroke is about
    // 170 mm long, so some 24 steps of 7 mm.
    let frames = fs::read_dir(d.path().join("grow")).unwrap().count();
    assert!((20..=30).contains(&frames), "{frames} frames");
    // A rule of its own for `a`.
    moyo(&d)
        .args([
            "lsystem",
            "--stroke",
            "stroke.svg",
            "--rule",
            "a -> b(50) c(30) a",
            "-o",
            "own.svg",
        ])
        .assert()
        .success();
    let own = fs::read_to_string(d.path().join("own.svg")).unwrap();
    assert_ne!(path_data(&own), path_data(&svg));
}

#[test]
fn bad_rules_name_the_option_and_the_column_and_write_nothing() {
    for (args, expected) in [
        (
            vec!["--axiom", "F", "--rule", "F=F[+F"],
            "--rule (rules[0]): column 4",
        ),
        (vec!["--axiom", "F", "--angle", "400"], "--angle"),
        // A negative number is a value (refused by its range), not an
        // option clap does not know.
        (
            vec!["--axiom", "F", "--angle", "-90"],
            "--angle: must be between 0 and 360, got -90",
        ),
        (
            vec!["--axiom", "F", "--width", "-1", "--style", "outline"],
            "--width",
        ),
        (
            vec!["--axiom", "F", "--rule", "F=FFFFFFFFFF", "-n", "12"],
            "--iterations: iteration 8 would make 100000000 modules",
        ),
        (
            vec!["--stroke", "stroke.svg", "--rule", "a -> b(50 c(30) a"],
            "--rule (sketch.a): column",
        ),
        (
            vec!["--stroke", "stroke.svg", "--rule", "F=FF"],
            "with --stroke, rules are for `a` or `c`",
        ),
        (vec!["--stroke", "missing.svg"], "missing.svg"),
        // What a sketch would silently ignore is refused, saying why.
        (
            vec!["--stroke", "stroke.svg", "--angle", "30"],
            "--angle: with --stroke, each branch has its own angle in its rule",
        ),
        (
            vec!["--stroke", "stroke.svg", "-n", "3"],
            "--iterations: with --stroke, the sketch takes one step per --module mm",
        ),
        (
            vec!["--stroke", "stroke.svg", "--page", "A3"],
            "'--page <PAGE>'",
        ),
        (
            vec!["--stroke", "stroke.svg", "--axiom", "F"],
            "'--axiom <AXIOM>'",
        ),
        (
            vec!["--axiom", "F", "--module", "3"],
            "--module: the step of a sketch along --stroke",
        ),
        // Nothing to draw is an error, not an empty file.
        (
            vec!["--stroke", "stroke.svg", "--module", "1000"],
            "--stroke stroke.svg: nothing grew",
        ),
        (
            vec!["--stroke", "empty.svg"],
            "--stroke empty.svg: has no path",
        ),
        (
            vec!["--axiom", "X", "--rule", "X=+X"],
            "nothing drawn: the rules' word has no symbol that draws a line",
        ),
    ] {
        let d = dir();
        fs::write(d.path().join("stroke.svg"), STROKE).unwrap();
        fs::write(
            d.path().join("empty.svg"),
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="50mm" height="50mm"/>"#,
        )
        .unwrap();
        moyo(&d)
            .arg("lsystem")
            .args(&args)
            .args(["-o", "out.svg", "--png", "out.png", "--frames", "f"])
            .assert()
            .failure()
            .stderr(predicate::str::starts_with("error: ").and(predicate::str::contains(expected)));
        for name in ["out.svg", "out.png", "f"] {
            assert!(!d.path().join(name).exists(), "{args:?} left {name}");
        }
    }
}

#[test]
fn frames_are_the_drawings_of_each_step_and_a_failed_run_leaves_no_folder() {
    let d = dir();
    let args = ["lsystem", "--axiom", "F", "--rule", "F=F[+F]F"];
    moyo(&d)
        .args(args)
        .args(["-n", "3", "-o", "out.svg", "--frames", "steps"])
        .assert()
        .success();
    // Each frame, written as it was made, is what that many steps draw.
    for k in 0..=3 {
        let alone = format!("alone-{k}.svg");
        moyo(&d)
            .args(args)
            .args(["-n", &k.to_string(), "-o", &alone])
            .assert()
            .success();
        assert_eq!(
            fs::read(d.path().join(format!("steps/frame-{k:03}.svg"))).unwrap(),
            fs::read(d.path().join(&alone)).unwrap(),
            "frame {k}"
        );
    }
    // An output that cannot be written (a folder stands there): the
    // folders made for the frames go again, nothing is written.
    fs::create_dir(d.path().join("taken")).unwrap();
    moyo(&d)
        .args(args)
        .args(["-n", "3", "-o", "taken", "--frames", "new/frames"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("taken: a folder, not a file"));
    assert!(!d.path().join("new").exists());
    assert!(fs::read_dir(d.path().join("taken"))
        .unwrap()
        .next()
        .is_none());
}
