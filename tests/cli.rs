//! The `moyo` command line, run as a separate process.
//!
//! Every test works in its own temporary directory (also the working
//! directory of the process, so a stray default `moyo.svg` cannot land in
//! the repository). Failure tests check three things: a non-zero exit, a
//! message on stderr that says what and where, and that no file at all was
//! created.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

use assert_cmd::Command;
use predicates::prelude::*;
use tempfile::TempDir;

use moyo::spec::{Format, SceneSpec};
use moyo::templates;

const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";

/// The `moyo` binary, run inside `dir`.
pub(crate) fn moyo(dir: &TempDir) -> Command {
    let mut cmd = Command::cargo_bin("moyo").expect("the moyo binary is built");
    cmd.current_dir(dir.path());
    cmd
}

pub(crate) fn tempdir() -> TempDir {
    tempfile::tempdir().expect("temporary directory")
}

/// Names of everything in `dir`.
pub(crate) fn entries(dir: &Path) -> BTreeSet<String> {
    fs::read_dir(dir)
        .expect("readable directory")
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

fn read_text(path: &Path) -> String {
    fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn path_count(svg: &str) -> usize {
    svg.matches("<path").count()
}

/// Width and height from a PNG's IHDR chunk.
fn png_size(png: &[u8]) -> (u32, u32) {
    assert!(png.starts_with(PNG_SIGNATURE), "not a PNG");
    let be = |i: usize| u32::from_be_bytes(png[i..i + 4].try_into().unwrap());
    (be(16), be(20))
}

/// A small valid scene: A5 portrait, one layer of two Tree2 trees.
const SMALL_TOML: &str = r##"version = 1
title = "small"
seed = 7

[page]
size = "A5"
margin = 10

[[pens]]
number = 3
name = "sepia"
color = "#704214"
width = 0.4

[[layers]]
name = "only"
pen = 3

[[layers.trees]]
id = "row"
rule = "tree2"
count = 2
centre = [[10, 150], [110, 160]]

[layers.trees.params]
generations = 5
trunk = 18
"##;

/// The same scene as [`SMALL_TOML`], as JSON.
const SMALL_JSON: &str = r##"{
  "version": 1,
  "title": "small",
  "seed": 7,
  "page": { "size": "A5", "margin": 10 },
  "pens": [ { "number": 3, "name": "sepia", "color": "#704214", "width": 0.4 } ],
  "layers": [
    {
      "name": "only",
      "pen": 3,
      "trees": [
        {
          "id": "row",
          "rule": "tree2",
          "count": 2,
          "centre": [[10, 150], [110, 160]],
          "params": { "generations": 5, "trunk": 18 }
        }
      ]
    }
  ]
}
"##;

/// Header shared by the broken scenes below: a valid start, so that the
/// line of the error is known.
fn scene_with_tree(extra_set_lines: &str, params: &str) -> String {
    format!(
        "version = 1\n\
         [[layers]]\n\
         name = \"a\"\n\
         [[layers.trees]]\n\
         rule = \"tree1\"\n\
         centre = [[10, 100], [100, 100]]\n\
         {extra_set_lines}\
         [layers.trees.params]\n\
         {params}"
    )
}

// ---------------------------------------------------------------- render

#[test]
fn render_without_scene_writes_the_default_design() {
    let dir = tempdir();
    let svg_path = dir.path().join("out.svg");
    let png_path = dir.path().join("out.png");
    let dump_path = dir.path().join("out.dump");
    moyo(&dir)
        .args([
            "render", "-o", "out.svg", "--png", "out.png", "--dump", "out.dump",
        ])
        .assert()
        .success()
        .stderr(predicate::str::contains("wrote out.svg"));

    let svg = read_text(&svg_path);
    assert!(svg.starts_with("<?xml"), "{}", &svg[..svg.len().min(200)]);
    assert!(svg.contains("inkscape:groupmode=\"layer\""));
    // The default template is A3 landscape.
    assert!(svg.contains("width=\"420mm\""));
    assert!(svg.contains("height=\"297mm\""));
    assert!(svg.trim_end().ends_with("</svg>"));
    let default = templates::get(templates::DEFAULT).unwrap().spec().unwrap();
    let embedded = moyo::embedded_description(&svg).expect("embedded description");
    assert_eq!(SceneSpec::parse(&embedded, Format::Toml).unwrap(), default);

    let png = fs::read(&png_path).unwrap();
    assert!(png.starts_with(PNG_SIGNATURE));
    // 420 × 297 mm at the default 150 dpi.
    assert_eq!(png_size(&png), (2480, 1754));

    let dump = read_text(&dump_path);
    let paths = path_count(&svg);
    assert!(paths > 20, "only {paths} paths in the default design");
    // The dump has every path of the scene; the SVG only what pens draw,
    // not the preview colour of partly hidden shapes.
    let fills = dump
        .lines()
        .filter(|l| l.starts_with("preview-fills\t"))
        .count();
    assert!(fills > 0 && !svg.contains("preview-fills"));
    assert_eq!(dump.lines().count(), paths + fills);
    assert!(dump.ends_with('\n'));
    for line in dump.lines() {
        assert_eq!(line.split('\t').count(), 3, "{line}");
    }

    // Nothing but the three requested files.
    assert_eq!(
        entries(dir.path()),
        ["out.dump", "out.png", "out.svg"].map(String::from).into()
    );
}

#[test]
fn render_default_output_name_is_moyo_svg() {
    let dir = tempdir();
    moyo(&dir).arg("render").assert().success();
    assert!(read_text(&dir.path().join("moyo.svg")).starts_with("<?xml"));
}

#[test]
fn preview_svg_is_a_separate_output_in_colour() {
    let dir = tempdir();
    moyo(&dir)
        .args(["render", "-o", "plot.svg", "--preview-svg", "preview.svg"])
        .assert()
        .success()
        .stderr(
            predicate::str::contains("wrote plot.svg (")
                .and(predicate::str::contains(") and preview.svg")),
        );
    let plot = read_text(&dir.path().join("plot.svg"));
    let preview = read_text(&dir.path().join("preview.svg"));
    // The preview adds the colour of cut shapes, in a `%` layer before the
    // pens; from the first pen on, it is the plot.
    assert!(!plot.contains("%preview fills"));
    assert!(preview.contains("inkscape:label=\"%preview fills\""));
    let pens = |s: &str| s[s.find("<g id=\"pen-").unwrap()..].to_string();
    assert!(pens(&plot) == pens(&preview));
    // It carries the description too: reopening it gives the plot again.
    moyo(&dir)
        .args(["render", "--from", "preview.svg", "-o", "again.svg"])
        .assert()
        .success();
    assert!(read_text(&dir.path().join("again.svg")) == plot);
}

#[test]
fn render_named_template() {
    let dir = tempdir();
    moyo(&dir)
        .args(["render", "-t", "tree-rules", "-o", "rules.svg"])
        .assert()
        .success();
    let svg = read_text(&dir.path().join("rules.svg"));
    for n in 1..=8 {
        assert!(
            svg.contains(&format!("id=\"rules.tree{n}.tree-0.silhouette\"")),
            "tree{n} missing"
        );
    }
    let expected = templates::get("tree-rules").unwrap().spec().unwrap();
    let embedded = moyo::embedded_description(&svg).unwrap();
    assert_eq!(SceneSpec::parse(&embedded, Format::Toml).unwrap(), expected);
}

#[test]
fn render_toml_scene_file() {
    let dir = tempdir();
    fs::write(dir.path().join("small.toml"), SMALL_TOML).unwrap();
    moyo(&dir)
        .args([
            "render",
            "small.toml",
            "-o",
            "small.svg",
            "--dump",
            "small.dump",
        ])
        .assert()
        .success();
    let svg = read_text(&dir.path().join("small.svg"));
    assert!(svg.contains("width=\"148mm\""), "A5 portrait expected");
    assert!(svg.contains("height=\"210mm\""));
    assert!(svg.contains("inkscape:label=\"3 sepia\""));
    assert!(svg.contains("id=\"only.row.tree-1.limb-0\""));
    assert!(!svg.contains("tree-2"), "count = 2 makes tree-0 and tree-1");
    let dump = read_text(&dir.path().join("small.dump"));
    assert_eq!(dump.lines().count(), path_count(&svg));
    // One pen's layer; every path keeps its id.
    assert!(dump
        .lines()
        .all(|l| l.starts_with("pen-3.layer\tonly.row.tree-")));
}

#[test]
fn render_json_scene_file_matches_the_same_scene_in_toml() {
    let dir = tempdir();
    fs::write(dir.path().join("small.toml"), SMALL_TOML).unwrap();
    fs::write(dir.path().join("small.json"), SMALL_JSON).unwrap();
    moyo(&dir)
        .args(["render", "small.json", "-o", "json.svg"])
        .assert()
        .success();
    moyo(&dir)
        .args(["render", "small.toml", "-o", "toml.svg"])
        .assert()
        .success();
    let json = fs::read(dir.path().join("json.svg")).unwrap();
    let toml = fs::read(dir.path().join("toml.svg")).unwrap();
    assert!(json.starts_with(b"<?xml"));
    assert!(
        json == toml,
        "the same scene as JSON and TOML renders differently"
    );
}

#[test]
fn different_seeds_give_different_drawings() {
    let dir = tempdir();
    for seed in ["1", "2"] {
        moyo(&dir)
            .args(["render", "--seed", seed])
            .args([
                "-o",
                &format!("s{seed}.svg"),
                "--dump",
                &format!("s{seed}.dump"),
            ])
            .assert()
            .success();
    }
    let svg = |n: u32| fs::read(dir.path().join(format!("s{n}.svg"))).unwrap();
    assert!(svg(1) != svg(2));
    // Not only the embedded seed: the geometry itself differs.
    let dump = |n: u32| read_text(&dir.path().join(format!("s{n}.dump")));
    assert_ne!(dump(1), dump(2));
    // The seed given on the command line is the one embedded.
    let embedded = moyo::embedded_description(&String::from_utf8(svg(2)).unwrap())
        .expect("embedded description");
    assert_eq!(SceneSpec::parse(&embedded, Format::Toml).unwrap().seed, 2);
}

#[test]
fn same_seed_gives_byte_identical_svg() {
    let dir = tempdir();
    for name in ["a.svg", "b.svg"] {
        moyo(&dir)
            .args(["render", "--seed", "1", "-o", name])
            .assert()
            .success();
    }
    let a = fs::read(dir.path().join("a.svg")).unwrap();
    let b = fs::read(dir.path().join("b.svg")).unwrap();
    assert!(!a.is_empty());
    assert!(a == b, "two renders with --seed 1 differ");
}

#[test]
fn precision_option_changes_the_numbers() {
    let dir = tempdir();
    moyo(&dir)
        .args([
            "render",
            "--precision",
            "0",
            "-o",
            "p0.svg",
            "--dump",
            "p0.dump",
        ])
        .assert()
        .success();
    let dump = read_text(&dir.path().join("p0.dump"));
    let data: String = dump
        .lines()
        .map(|l| l.rsplit('\t').next().unwrap())
        .collect();
    assert!(!data.is_empty());
    assert!(!data.contains('.'), "precision 0 still writes decimals");
}

#[test]
fn failed_render_leaves_an_existing_output_untouched() {
    let dir = tempdir();
    fs::write(dir.path().join("out.svg"), "old").unwrap();
    fs::write(dir.path().join("bad.toml"), "version = 1\n[page\n").unwrap();
    moyo(&dir)
        .args(["render", "bad.toml", "-o", "out.svg"])
        .assert()
        .failure();
    assert_eq!(read_text(&dir.path().join("out.svg")), "old");
    assert_eq!(
        entries(dir.path()),
        ["bad.toml", "out.svg"].map(String::from).into()
    );
}

// ------------------------------------------------------ templates and new

#[test]
fn templates_lists_every_template_with_its_description() {
    let dir = tempdir();
    let out = moyo(&dir).arg("templates").assert().success();
    let stdout = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    let names: Vec<&str> = templates::ALL.iter().map(|t| t.name).collect();
    assert!(names.contains(&"tomesode-hem") && names.contains(&"tree-rules"));
    assert_eq!(stdout.lines().count(), templates::ALL.len(), "{stdout}");
    for t in templates::ALL {
        let summary = t.summary();
        assert!(!summary.trim().is_empty(), "{} has no description", t.name);
        let line = stdout
            .lines()
            .find(|l| l.split_whitespace().next() == Some(t.name))
            .unwrap_or_else(|| panic!("{} not listed:\n{stdout}", t.name));
        assert!(line.contains(&summary), "{line}");
    }
}

#[test]
fn new_prints_the_template() {
    let dir = tempdir();
    let out = moyo(&dir).args(["new", "tree-rules"]).assert().success();
    let stdout = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    let template = templates::get("tree-rules").unwrap();
    assert_eq!(stdout, template.text);
    assert_eq!(
        SceneSpec::parse(&stdout, Format::Toml).unwrap(),
        template.spec().unwrap()
    );
    assert!(entries(dir.path()).is_empty());
}

#[test]
fn new_unknown_template_lists_the_available_ones() {
    let dir = tempdir();
    let mut assert = moyo(&dir)
        .args(["new", "nope"])
        .assert()
        .failure()
        .stdout(predicate::str::is_empty())
        .stderr(predicate::str::contains("nope"));
    for t in templates::ALL {
        assert = assert.stderr(predicate::str::contains(t.name));
    }
    assert!(entries(dir.path()).is_empty());
}

#[test]
fn new_writes_the_template_to_a_file() {
    let dir = tempdir();
    moyo(&dir)
        .args(["new", "tree-rules", "-o", "x.toml"])
        .assert()
        .success()
        .stdout(predicate::str::is_empty());
    let text = read_text(&dir.path().join("x.toml"));
    assert_eq!(text, templates::get("tree-rules").unwrap().text);
    // And the written file renders.
    moyo(&dir)
        .args(["render", "x.toml", "-o", "x.svg"])
        .assert()
        .success();
    assert!(dir.path().join("x.svg").exists());
}

#[test]
fn every_help_exits_zero() {
    let dir = tempdir();
    for args in [
        &["--help"][..],
        &["render", "--help"],
        &["templates", "--help"],
        &["new", "--help"],
        &["help", "render"],
    ] {
        moyo(&dir)
            .args(args)
            .assert()
            .success()
            .stdout(predicate::str::contains("Usage"));
    }
    assert!(entries(dir.path()).is_empty());
}

// ---------------------------------------------------------------- bad input

/// Runs `moyo render` with `args` in a directory holding `files`, and
/// checks that it fails, that stderr contains every one of `expected`, and
/// that no file was added to the directory.
fn render_fails(files: &[(&str, &str)], args: &[&str], expected: &[&str]) -> String {
    let dir = tempdir();
    for (name, text) in files {
        fs::write(dir.path().join(name), text).unwrap();
    }
    let before = entries(dir.path());
    let out = moyo(&dir)
        .arg("render")
        .args(args)
        .args(["-o", "out.svg", "--png", "out.png", "--dump", "out.dump"])
        .assert()
        .failure();
    let stderr = String::from_utf8(out.get_output().stderr.clone()).unwrap();
    assert!(stderr.starts_with("error: "), "{stderr}");
    for e in expected {
        assert!(stderr.contains(e), "stderr lacks {e:?}:\n{stderr}");
    }
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!dir.path().join("out.svg").exists(), "SVG written");
    assert_eq!(entries(dir.path()), before, "files were created");
    stderr
}

#[test]
fn missing_scene_file_is_named() {
    render_fails(&[], &["missing-scene.toml"], &["missing-scene.toml"]);
}

#[test]
fn broken_toml_reports_file_line_and_column() {
    let stderr = render_fails(
        &[("broken.toml", "version = 1\n[page\nsize = \"A4\"\n")],
        &["broken.toml"],
        &[],
    );
    let re = predicate::str::is_match(r"broken\.toml:2:\d+: ").unwrap();
    assert!(re.eval(&stderr), "{stderr}");
}

#[test]
fn broken_json_reports_file_line_and_column() {
    let stderr = render_fails(
        &[("broken.json", "{\n  \"version\": 1,\n  \"seed\": \n}\n")],
        &["broken.json"],
        &[],
    );
    let re = predicate::str::is_match(r"broken\.json:4:\d+: ").unwrap();
    assert!(re.eval(&stderr), "{stderr}");
}

#[test]
fn unknown_key_is_named_with_its_line() {
    render_fails(
        &[("top.toml", "version = 1\ncolour = 3\n")],
        &["top.toml"],
        &["top.toml:2:", "colour", "unknown field"],
    );
    let text = scene_with_tree("", "generations = 3\nratio9 = 2\n");
    render_fails(
        &[("deep.toml", &text)],
        &["deep.toml"],
        &[
            "deep.toml:9:",
            "layers[0].trees[0].params.ratio9",
            "unknown field",
        ],
    );
}

#[test]
fn out_of_range_value_names_field_range_and_place() {
    let text = scene_with_tree("", "generations = 500\n");
    render_fails(
        &[("range.toml", &text)],
        &["range.toml"],
        &[
            "range.toml:8:15: ",
            "layers[0].trees[0].params.generations",
            "must be between 0 and 64",
            "500",
        ],
    );
}

#[test]
fn wrong_type_names_field_and_place() {
    let text = "version = 1\n[[layers]]\nname = \"a\"\npen = \"one\"\n";
    render_fails(
        &[("type.toml", text)],
        &["type.toml"],
        &["type.toml:4:", "layers[0].pen", "invalid type"],
    );
}

#[test]
fn non_finite_coordinates_are_refused() {
    for (name, value) in [
        ("nan.toml", "nan"),
        ("inf.toml", "inf"),
        ("ninf.toml", "-inf"),
    ] {
        let text = format!(
            "version = 1\n[[layers]]\nname = \"a\"\n[[layers.trees]]\nrule = \"tree1\"\n\
             centre = [[10, 100], [100, {value}]]\n"
        );
        render_fails(
            &[(name, &text)],
            &[name],
            &[
                &format!("{name}:6:"),
                "layers[0].trees[0].centre[1]",
                "finite",
            ],
        );
    }
    // Also in the region lines.
    render_fails(
        &[(
            "upper.toml",
            "version = 1\n[lines]\nupper = [[0, 0], [nan, 5]]\n",
        )],
        &["upper.toml"],
        &["upper.toml:3:", "lines.upper[1]", "finite"],
    );
}

#[test]
fn override_of_a_missing_tree_is_refused() {
    let text = scene_with_tree(
        "count = 2\n[[layers.trees.overrides]]\nid = \"tree-5\"\nscale = 2\n",
        "generations = 3\n",
    );
    render_fails(
        &[("ov.toml", &text)],
        &["ov.toml"],
        &[
            "ov.toml:9:",
            "layers[0].trees[0].overrides[0].id",
            "tree-5",
            "matches no tree",
        ],
    );
}

#[test]
fn path_budget_exceeded_is_refused() {
    let text = "version = 1\n[limits]\nmax_paths = 50\n[[layers]]\nname = \"a\"\n\
                [[layers.trees]]\nrule = \"tree5\"\ncount = 40\n\
                centre = [[10, 100], [190, 100]]\n";
    render_fails(
        &[("budget.toml", text)],
        &["budget.toml"],
        &["path budget", "50", "limits.max_paths"],
    );
}

#[test]
fn seed_above_i64_max_is_refused() {
    render_fails(
        &[],
        &["--seed", "9223372036854775808"],
        &["seed", "9223372036854775807"],
    );
    // The largest allowed seed works.
    let dir = tempdir();
    moyo(&dir)
        .args(["render", "--seed", "9223372036854775807", "-o", "max.svg"])
        .assert()
        .success();
}

#[test]
fn seed_above_i64_max_in_the_file_is_refused() {
    let text = "version = 1\nseed = 9223372036854775808\n";
    render_fails(
        &[("seed.toml", text)],
        &["seed.toml"],
        &["seed.toml:2:", "seed"],
    );
}

#[test]
fn precision_above_eight_is_refused() {
    render_fails(
        &[],
        &["--precision", "9"],
        &["precision", "between 0 and 8"],
    );
}

#[test]
fn dpi_zero_is_refused() {
    render_fails(&[], &["--dpi", "0"], &["dpi", "between 1 and 2400"]);
}

#[test]
fn dpi_zero_without_png_is_refused() {
    let dir = tempdir();
    moyo(&dir)
        .args(["render", "--dpi", "0", "-o", "out.svg"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("dpi"));
    assert!(!dir.path().join("out.svg").exists());
}

#[test]
fn unknown_template_lists_the_available_ones() {
    let mut expected = vec!["nope"];
    expected.extend(templates::ALL.iter().map(|t| t.name));
    render_fails(&[], &["-t", "nope"], &expected);
}

#[test]
fn failed_png_writes_no_svg_either() {
    // A valid dpi on a huge page: the preview is refused only after the
    // scene and its SVG exist in memory, and then nothing may be written.
    let huge = "version = 1\npage = { size = [10000, 10000] }\n";
    render_fails(
        &[("huge.toml", huge)],
        &["huge.toml", "--dpi", "2400"],
        &["megapixels"],
    );
}

#[test]
fn scene_and_template_together_are_refused() {
    let dir = tempdir();
    fs::write(dir.path().join("small.toml"), SMALL_TOML).unwrap();
    moyo(&dir)
        .args(["render", "small.toml", "-t", "tree-rules", "-o", "out.svg"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("--template"));
    assert!(!dir.path().join("out.svg").exists());
}

#[test]
fn output_into_a_missing_directory_fails_cleanly() {
    let dir = tempdir();
    let target: PathBuf = ["no-such-dir", "out.svg"].iter().collect();
    moyo(&dir)
        .arg("render")
        .arg("-o")
        .arg(&target)
        .assert()
        .failure()
        // The folder is named, not the output's temporary file.
        .stderr(predicate::eq("error: no-such-dir: no such folder\n"));
    assert!(entries(dir.path()).is_empty());
}

/// A template that reads an image renders anywhere (its files are built
/// in), and `moyo new` writes them beside the description it writes.
#[test]
fn templates_bring_their_own_files() {
    let dir = tempdir();
    moyo(&dir)
        .args(["render", "-t", "stipple-portrait", "-o", "a.svg"])
        .assert()
        .success();
    fs::create_dir(dir.path().join("mine")).unwrap();
    moyo(&dir)
        .args(["new", "stipple-portrait", "-o", "mine/p.toml"])
        .assert()
        .success()
        .stderr(predicate::str::contains("images/portrait.jpg"));
    assert_eq!(
        fs::read(dir.path().join("mine/images/portrait.jpg")).unwrap(),
        moyo::templates::file("images/portrait.jpg").unwrap()
    );
    moyo(&dir)
        .args(["render", "mine/p.toml", "-o", "b.svg"])
        .assert()
        .success();
    // The same drawing either way.
    let a = fs::read_to_string(dir.path().join("a.svg")).unwrap();
    let b = fs::read_to_string(dir.path().join("b.svg")).unwrap();
    assert_eq!(a, b);
    // An image that is not there is named, with no output left behind.
    fs::remove_file(dir.path().join("mine/images/portrait.jpg")).unwrap();
    moyo(&dir)
        .args(["render", "mine/p.toml", "-o", "c.svg"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("images/portrait.jpg"));
    assert!(!dir.path().join("c.svg").exists());
}

// ----------------------------------------------------- voronoi sites by hand

/// A voronoi table's sites given by hand, in TOML.
fn voronoi_with_points(sites: &str) -> String {
    format!(
        "version = 1\npage = {{ size = \"A5\", margin = 10 }}\n[[layers]]\nname = \"l\"\n\
         [[layers.voronoi]]\ndraw = [\"sites\", \"cells\"]\n[layers.voronoi.sites]\n{sites}"
    )
}

#[test]
fn voronoi_sites_given_by_hand_are_drawn_and_bad_ones_named() {
    let dir = tempdir();
    // The last point lies off the page's drawable area (128 × 190 mm).
    let text =
        voronoi_with_points("points = [[10, 10], [60, 90], [60, 90], [100, 150], [300, 10]]\n");
    fs::write(dir.path().join("v.toml"), text).unwrap();
    moyo(&dir)
        .args([
            "render", "v.toml", "-o", "v.svg", "--png", "v.png", "--dpi", "30",
        ])
        .assert()
        .success();
    let svg = read_text(&dir.path().join("v.svg"));
    for i in 0..3 {
        assert!(
            svg.contains(&format!("id=\"l.voronoi-0.sites.site-{i}\"")),
            "site {i}"
        );
    }
    assert!(
        !svg.contains("site-3"),
        "a repeated or outside point drew a site"
    );
    png_size(&fs::read(dir.path().join("v.png")).unwrap());
    // A distribution beside the points, none inside: named with their place.
    let text = voronoi_with_points("points = [[10, 10]]\ndistribution = \"grid\"\n");
    render_fails(
        &[("both.toml", &text)],
        &["both.toml"],
        &[
            "both.toml:9:",
            "layers[0].voronoi[0].sites.distribution: does not apply to given points",
        ],
    );
    // (Found while rendering: the place has no file name.)
    let text = voronoi_with_points("points = [[-10, 10], [10, 500]]\n");
    render_fails(
        &[("out.toml", &text)],
        &["out.toml"],
        &["8:10: layers[0].voronoi[0].sites.points: none of the 2 points lies inside the region"],
    );
}

/// An SVG less the description it embeds.
fn without_description(svg: &str) -> String {
    let (head, rest) = svg
        .split_once("<metadata>")
        .expect("an embedded description");
    let (_, tail) = rest.split_once("</metadata>").expect("its end");
    format!("{head}{tail}")
}

#[test]
fn voronoi_sites_pinned_as_points_draw_the_same_svg() {
    // The stained-glass window: two tables (lead and glass) share their
    // rose-window sites. Pinned as a designer would, in the text: the
    // distribution gives way to the points; petals, spacing and tracery
    // stay, as they place the tracery rings.
    let template = templates::get("voronoi-stained-glass").unwrap();
    let (spec, library) = (template.spec().unwrap(), template.library().unwrap());
    let lead = moyo::project::voronoi_sites(&spec, &library, 0, 0).unwrap();
    let glass = moyo::project::voronoi_sites(&spec, &library, 1, 0).unwrap();
    assert_eq!(lead, glass);
    assert!(lead.len() > 50, "{} sites", lead.len());
    let points: Vec<String> = lead.iter().map(|[x, y]| format!("[{x}, {y}]")).collect();
    let generated = "distribution = \"rose\"\n";
    assert_eq!(template.text.matches(generated).count(), 2);
    let pinned = template
        .text
        .replace(generated, &format!("points = [{}]\n", points.join(", ")));
    let dir = tempdir();
    fs::write(dir.path().join("pinned.toml"), pinned).unwrap();
    moyo(&dir)
        .args(["render", "-t", "voronoi-stained-glass", "-o", "spread.svg"])
        .assert()
        .success();
    moyo(&dir)
        .args(["render", "pinned.toml", "-o", "pinned.svg"])
        .assert()
        .success();
    let spread = read_text(&dir.path().join("spread.svg"));
    let pinned = read_text(&dir.path().join("pinned.svg"));
    assert_ne!(spread, pinned, "the embedded descriptions differ");
    assert!(
        without_description(&spread) == without_description(&pinned),
        "the pinned sites draw another window"
    );
    assert!(path_count(&spread) > 50);
}

#[test]
fn a_negative_number_is_a_value_to_check_not_an_unknown_option() {
    for (args, expected) in [
        (
            &["-t", "tree-rules", "--seed", "-1"][..],
            "'-1' for '--seed",
        ),
        (&["-t", "tree-rules", "--dpi", "-5"], "'-5' for '--dpi"),
        (
            &["-t", "tree-rules", "--precision", "-2"],
            "'-2' for '--precision",
        ),
    ] {
        let stderr = render_fails(&[], args, &[expected]);
        assert!(!stderr.contains("unexpected argument"), "{stderr}");
    }
}

/// `render` reports what `stats` then reads in the SVG: the same path
/// count and the same pen-down length to the millimetre it prints.
#[test]
fn render_and_stats_agree_on_what_was_written() {
    let dir = tempdir();
    for (template, precision) in [("kimono-1", "3"), ("zentangle-10", "1")] {
        let out = moyo(&dir)
            .args([
                "render",
                "-t",
                template,
                "-o",
                "x.svg",
                "--precision",
                precision,
            ])
            .assert()
            .success()
            .get_output()
            .stderr
            .clone();
        let said = String::from_utf8(out).unwrap();
        let inside = said.split_once(" (").unwrap().1;
        let (paths, rest) = inside.split_once(" paths, ").unwrap();
        let mm = rest.split_once(" mm pen-down").unwrap().0;
        let stats = crate::plot_cli::stats_json(&dir, "x.svg");
        assert_eq!(paths, stats["paths"].to_string(), "{template}: {said}");
        let read = stats["pen_down_mm"].as_f64().unwrap();
        assert_eq!(mm, format!("{read:.0}"), "{template}: {said}, stats {read}");
    }
}

/// `moyo new` writes a description and the images it reads all or none:
/// where an image cannot go, the description is not written either, and
/// the folders made for the images go again.
#[test]
fn new_writes_all_its_files_or_none() {
    let dir = tempdir();
    // An image's folder taken by a file; the description's own name taken
    // by a folder (the images folder made for it goes again).
    for (folder, taken, a_folder, message) in [
        ("mine", "images", false, "images"),
        ("other", "p.toml", true, "a folder, not a file"),
    ] {
        let place = dir.path().join(folder);
        fs::create_dir(&place).unwrap();
        if a_folder {
            fs::create_dir(place.join(taken)).unwrap();
        } else {
            fs::write(place.join(taken), "a file, not a folder").unwrap();
        }
        moyo(&dir)
            .args(["new", "stipple-portrait", "-o", &format!("{folder}/p.toml")])
            .assert()
            .failure()
            .stderr(predicate::str::contains(message));
        assert_eq!(
            entries(&place),
            BTreeSet::from([taken.to_string()]),
            "{folder}"
        );
    }
}
