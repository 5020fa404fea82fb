//! `moyo plot` and `moyo stats` through the binary: formats, stages, stats
//! JSON, and bad input leaving no output file; AxiDraw documentation layers
//! (`%` names) kept in the colour preview and left out of everything
//! plotted, the SVG included; pens from many colours merged (`--pens`,
//! `--single-layer`); and real
//! interpreters (pygcode, hp2xx) reading our G-code and HPGL, when
//! `MOYO_PYTHON` and `MOYO_HP2XX` name them (`.ci/run` sets both).

use std::fs;
use std::path::Path;

use assert_cmd::Command;
use predicates::prelude::*;
use tempfile::TempDir;

use crate::devices::read_gcode;

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

/// What `moyo stats --json` says of `file` in `dir`.
pub(crate) fn stats_json(dir: &TempDir, file: &str) -> serde_json::Value {
    let out = moyo(dir)
        .args(["stats", file, "--json"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    serde_json::from_slice(&out).expect("stats --json prints JSON")
}

/// The numbers of the pens an SVG written by moyo draws with (its
/// `pen-N` Inkscape layers), in document order.
fn pen_numbers(svg: &str) -> Vec<f64> {
    svg.split("<g id=\"pen-")
        .skip(1)
        .map(|rest| &rest[..rest.find('"').unwrap()])
        // `pen-N.layer` is the pen's group inside its Inkscape layer.
        .filter(|id| !id.contains('.'))
        .map(|id| id.parse().unwrap())
        .collect()
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
    // The default design keeps preview fills in a `%` layer, which only
    // the colour preview holds: the SVG has the plotted layers alone.
    let all = s["layers"].as_array().expect("layers");
    let layers: Vec<_> = all.iter().filter(|l| l["plotted"] == true).collect();
    assert_eq!(all.len(), layers.len(), "no `%preview fills` layer");
    let svg = fs::read_to_string(dir.path().join("hem.svg")).unwrap();
    assert!(layers.len() >= 2);
    assert_eq!(layers.len(), pen_numbers(&svg).len(), "one per pen");
    let sum: f64 = layers.iter().map(|l| number(l, "paths")).sum();
    assert_eq!(sum, number(&s, "paths"));
}

#[test]
fn stats_give_the_time_at_constant_speed_and_with_acceleration() {
    let dir = with_default_design();
    let s = stats_json(&dir, "hem.svg");
    let (constant, accel) = (number(&s, "plot_time_s"), number(&s, "plot_time_accel_s"));
    // Thousands of strokes, each starting and stopping: a good deal more.
    assert!(accel > 1.1 * constant && constant > 0.0, "{s}");
    let layers = s["layers"].as_array().expect("layers");
    for l in layers {
        assert!(
            number(l, "plot_time_accel_s") >= number(l, "plot_time_s"),
            "{l}"
        );
    }
    let sum: f64 = layers.iter().map(|l| number(l, "plot_time_accel_s")).sum();
    assert!((sum - accel).abs() < 1e-6 * accel, "{sum} vs {accel}");

    // The table has both, the total row last.
    let out = moyo(&dir).args(["stats", "hem.svg"]).assert().success();
    let table = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    let header = table.lines().next().unwrap();
    assert!(header.contains("   time accel time  doubled mm"), "{table}");
    let total: Vec<&str> = table.lines().last().unwrap().split_whitespace().collect();
    let seconds = |d: &str| -> f64 {
        // 1h02m, 5m07s or 42s.
        let (h, rest) = d.split_once('h').unwrap_or(("0", d));
        let (m, rest) = rest.split_once('m').unwrap_or(("0", rest));
        let s = rest.trim_end_matches('s');
        let n = |t: &str| {
            if t.is_empty() {
                0.0
            } else {
                t.parse::<f64>().unwrap()
            }
        };
        3600.0 * n(h) + 60.0 * n(m) + n(s)
    };
    assert_eq!(total[0], "total", "{table}");
    // Rounded to the minute past an hour.
    assert!((seconds(total[4]) - constant).abs() <= 60.0, "{table}");
    assert!((seconds(total[5]) - accel).abs() <= 60.0, "{table}");

    // With all but instant acceleration, the two figures meet: the
    // flags reach the model.
    let out = moyo(&dir)
        .args(["stats", "hem.svg", "--json"])
        .args([
            "--accel-down",
            "1e9",
            "--accel-up",
            "1e9",
            "--cornering",
            "1e3",
        ])
        .assert()
        .success();
    let quick: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    let t = number(&quick, "plot_time_accel_s");
    assert!(t >= constant && t < 1.001 * constant, "{t} vs {constant}");
    moyo(&dir)
        .args(["stats", "hem.svg", "--cornering=-1"])
        .assert()
        .failure()
        .stderr(predicate::str::starts_with("error: --cornering: "));
}

#[test]
fn merge_and_sort_keep_ink_and_shorten_travel() {
    let dir = tempfile::tempdir().unwrap();
    // The default design in the order its generators drew it.
    let text = moyo::templates::get(moyo::templates::DEFAULT).unwrap().text;
    fs::write(
        dir.path().join("hem.toml"),
        format!("{text}\n[plot]\nmerge = false\nsort = false\n"),
    )
    .unwrap();
    moyo(&dir)
        .args(["render", "hem.toml", "-o", "hem.svg"])
        .assert()
        .success();
    moyo(&dir)
        .args(["plot", "hem.svg", "--merge", "--sort", "-o", "sorted.svg"])
        .assert()
        .success();
    let before = stats_json(&dir, "hem.svg");
    let after = stats_json(&dir, "sorted.svg");
    let ink = |v: &serde_json::Value| number(v, "pen_down_mm");
    assert!((ink(&before) - ink(&after)).abs() < 0.01 * ink(&before));
    assert!(number(&after, "pen_up_mm") < 0.5 * number(&before, "pen_up_mm"));
    // What a render writes is sorted already: sorting it again gains at
    // most a few percent.
    moyo(&dir)
        .args(["render", "-o", "default.svg"])
        .assert()
        .success();
    moyo(&dir)
        .args([
            "plot",
            "default.svg",
            "--merge",
            "--sort",
            "-o",
            "again.svg",
        ])
        .assert()
        .success();
    let rendered = number(&stats_json(&dir, "default.svg"), "pen_up_mm");
    let again = number(&stats_json(&dir, "again.svg"), "pen_up_mm");
    assert!(rendered <= 1.05 * again, "{rendered} vs {again}");
}

/// An SVG drawn carelessly: a line drawn twice, another lying on half of
/// it, a sliver touching it, and an isolated dot.
const CARELESS: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="50mm" viewBox="0 0 100 50">
  <path id="a" d="M 10 10 L 90 10" stroke="black" stroke-width="0.3" fill="none"/>
  <path id="b" d="M 10 10 L 90 10" stroke="black" stroke-width="0.3" fill="none"/>
  <path id="c" d="M 50 10.02 L 90 10.02 L 90 40" stroke="black" stroke-width="0.3" fill="none"/>
  <path id="sliver" d="M 30 10.1 L 30.1 10.2" stroke="black" stroke-width="0.3" fill="none"/>
  <path id="dot" d="M 30 30 L 30 30" stroke="black" stroke-width="0.3" fill="none"/>
</svg>"#;

#[test]
fn stats_show_doubled_line_work_and_debris_that_dedupe_and_debris_take_out() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("careless.svg"), CARELESS).unwrap();
    let before = stats_json(&dir, "careless.svg");
    // b on a (80 mm), c's first 40 mm on a: 120 mm drawn twice.
    assert!(
        (number(&before, "doubled_mm") - 120.0).abs() < 0.5,
        "{before}"
    );
    assert_eq!(number(&before, "debris"), 1.0, "the sliver, not the dot");
    // Three lines on one another: a 1 mm cell holds 3 mm of 0.3 mm line.
    assert!((number(&before, "densest") - 0.9).abs() < 0.1, "{before}");
    let table = moyo(&dir)
        .args(["stats", "careless.svg"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let table = String::from_utf8(table).unwrap();
    assert!(
        table
            .lines()
            .next()
            .unwrap()
            .ends_with("doubled mm  debris  densest"),
        "{table}"
    );

    moyo(&dir)
        .args([
            "plot",
            "careless.svg",
            "-o",
            "clean.svg",
            "--dedupe",
            "--debris",
        ])
        .assert()
        .success();
    let after = stats_json(&dir, "clean.svg");
    assert!(number(&after, "doubled_mm") < 0.01, "{after}");
    assert_eq!(number(&after, "debris"), 0.0);
    // Ink: a once, the 30 mm of c that do not lie on it, and the dot.
    assert!(
        (number(&after, "pen_down_mm") - 110.0).abs() < 0.1,
        "{after}"
    );
    let clean = fs::read_to_string(dir.path().join("clean.svg")).unwrap();
    assert!(clean.contains("id=\"dot\""), "the isolated dot stays");
    assert!(!clean.contains("id=\"sliver\"") && !clean.contains("id=\"b\""));
    // A tolerance in mm: 0.01 mm does not see c as lying on a (only b
    // goes; the sliver stays without --debris).
    moyo(&dir)
        .args([
            "plot",
            "careless.svg",
            "-o",
            "tight.svg",
            "--dedupe",
            "0.01",
        ])
        .assert()
        .success();
    let tight = stats_json(&dir, "tight.svg");
    assert!(
        (number(&tight, "pen_down_mm") - 150.14).abs() < 0.05,
        "{tight}"
    );
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

/// A directory holding `forty.svg`: 40 strokes in 40 colours, no layers.
fn with_forty_colours() -> TempDir {
    let dir = tempfile::tempdir().expect("temporary directory");
    fs::copy(
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/fixtures/import/forty_colours.svg"
        ),
        dir.path().join("forty.svg"),
    )
    .unwrap();
    dir
}

#[test]
fn many_colours_merge_into_at_most_eight_pens_unless_told() {
    let dir = with_forty_colours();
    moyo(&dir)
        .args(["plot", "forty.svg", "-o", "out.hpgl"])
        .assert()
        .success()
        .stderr(predicate::str::contains(
            "warning: forty.svg: 40 colours merged into 8 pens by nearest colour (OKLab); \
             --pens N to choose, --pens 0 for one pen per colour up to 999",
        ));
    let h = fs::read_to_string(dir.path().join("out.hpgl")).unwrap();
    let mut pens: Vec<u32> = h
        .split(';')
        .filter_map(|c| c.trim().strip_prefix("SP")?.parse().ok())
        .filter(|&n| n > 0)
        .collect();
    pens.sort_unstable();
    pens.dedup();
    assert_eq!(pens, (1..=8).collect::<Vec<_>>(), "{h}");

    let layers = |args: &[&str]| {
        let out = moyo(&dir)
            .args(["stats", "forty.svg", "--json"])
            .args(args)
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        let s: serde_json::Value = serde_json::from_slice(&out).unwrap();
        assert_eq!(number(&s, "paths"), 40.0);
        s["layers"].as_array().expect("layers").len()
    };
    assert_eq!(layers(&["--pens", "3"]), 3);
    assert_eq!(layers(&["--single-layer"]), 1);
    assert_eq!(layers(&["--pens", "0"]), 40);
    moyo(&dir)
        .args(["stats", "forty.svg", "--pens", "3", "--single-layer"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("cannot be used with"));
    moyo(&dir)
        .args(["stats", "forty.svg", "--pens", "1000"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("1000 is not in 0..=999"));
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

/// A bad value is refused before any work, named by the option as it was
/// typed (not by the library's field), and nothing is written.
#[test]
fn bad_options_are_refused_by_the_name_typed() {
    let dir = with_default_design();
    for (output, args, named) in [
        ("out.svg", &["--hatch", "0"][..], "--hatch"),
        (
            "out.svg",
            &["--hatch", "1", "--hatch-inset", "-1"],
            "--hatch-inset",
        ),
        ("out.svg", &["--multipass", "0"], "--multipass"),
        ("out.svg", &["--merge", "-1"], "--merge"),
        ("out.svg", &["--rotate", "400"], "--rotate"),
        ("out.svg", &["--scale", "0"], "--scale"),
        ("out.svg", &["--speed-down", "0"], "--speed-down"),
        ("out.svg", &["--accel-up", "0"], "--accel-up"),
        ("out.svg", &["--accel-down", "inf"], "--accel-down"),
        ("out.svg", &["--cornering", "NaN"], "--cornering"),
        ("out.svg", &["--dedupe=-0.1"], "--dedupe"),
        ("out.svg", &["--dedupe", "NaN"], "--dedupe"),
        ("out.svg", &["--dedupe", "400"], "--dedupe"),
        ("out.svg", &["--debris=-1"], "--debris"),
        ("out.svg", &["--blots", "0.2"], "--blots"),
        ("out.svg", &["--blots", "NaN"], "--blots"),
        ("out.gcode", &["--feed", "0"], "--feed"),
        ("out.gcode", &["--travel-feed", "-5"], "--travel-feed"),
        ("out.gcode", &["--pen-delay", "-1"], "--pen-delay"),
        ("out.gcode", &["--refill", "0.01"], "--refill"),
        ("out.gcode", &["--from-distance", "-3"], "--from-distance"),
        ("out.hpgl", &["--units-per-mm", "0"], "--units-per-mm"),
        ("out.hpgl", &["--device-range", "5,4"], "--device-range"),
        (
            "out.hpgl",
            &["--cutter", "--knife-offset", "-1"],
            "--knife-offset",
        ),
    ] {
        let out = moyo(&dir)
            .args(["plot", "hem.svg", "-o", output])
            .args(args)
            .assert()
            .failure();
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
        let error = stderr
            .lines()
            .find(|l| l.starts_with("error: "))
            .unwrap_or("");
        assert!(
            error.starts_with(&format!("error: {named}: ")),
            "{args:?}: {stderr}"
        );
        assert!(!dir.path().join(output).exists(), "{args:?}");
    }
}

/// An option that the chosen output would not change is refused, saying
/// which output it belongs to; nothing is written.
#[test]
fn an_option_the_output_ignores_is_refused_with_why() {
    let dir = with_default_design();
    for (output, args, why) in [
        (
            "out.svg",
            &["--feed", "1000"][..],
            "a G-code option, but the output is SVG",
        ),
        (
            "out.svg",
            &["--cutter"],
            "an HPGL option, but the output is SVG",
        ),
        (
            "out.svg",
            &["--mirror"],
            "an HPGL option, but the output is SVG",
        ),
        (
            "out.gcode",
            &["--cutter"],
            "an HPGL option, but the output is G-code",
        ),
        (
            "out.hpgl",
            &["--flip-y"],
            "a G-code option, but the output is HPGL",
        ),
        (
            "out.hpgl",
            &["--arcs"],
            "a G-code option, but the output is HPGL",
        ),
        ("out.dxf", &["--refill", "500"], "a machine option"),
        ("out.hpgl", &["--precision", "2"], "the output is HPGL"),
        ("out.svg", &["--dpi", "300"], "--png"),
        // A file with layers has its pens: --pens would group nothing.
        ("out.svg", &["--pens", "3"], "its layers are its pens"),
    ] {
        let out = moyo(&dir)
            .args(["plot", "hem.svg", "-o", output])
            .args(args)
            .assert()
            .failure();
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
        assert!(stderr.contains(why), "{args:?}: {stderr}");
        assert!(!dir.path().join(output).exists(), "{args:?}");
    }
    // What does apply still works: --precision sets G-code's decimals.
    moyo(&dir)
        .args(["plot", "hem.svg", "-o", "out.gcode", "--precision", "1"])
        .assert()
        .success();
    let gcode = std::fs::read_to_string(dir.path().join("out.gcode")).unwrap();
    let moves = gcode.lines().filter(|l| l.starts_with("G1 X")).take(50);
    for line in moves {
        for word in line.split_whitespace().skip(1) {
            let decimals = word.split_once('.').map_or(0, |(_, d)| d.len());
            assert!(decimals <= 1, "{line}");
        }
    }
}

/// Forty strokes converging on one point: a puddle of ink where they meet.
fn converging_strokes() -> String {
    let mut paths = String::new();
    for k in 0..40 {
        let a = std::f64::consts::TAU * f64::from(k) / 40.0;
        paths.push_str(&format!(
            "<path id=\"ray-{k}\" d=\"M {:.3} {:.3} L 50.5 25.5\" stroke=\"black\" stroke-width=\"0.3\" fill=\"none\"/>\n",
            50.5 + 20.0 * a.cos(),
            25.5 + 20.0 * a.sin()
        ));
    }
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" height=\"50mm\" viewBox=\"0 0 100 50\">\n{paths}</svg>"
    )
}

#[test]
fn blots_trims_converging_strokes_until_no_square_millimetre_passes_its_limit() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("rays.svg"), converging_strokes()).unwrap();
    let before = stats_json(&dir, "rays.svg");
    // 40 strokes ending in one cell: about 20 mm of a 0.3 mm line.
    assert!(number(&before, "densest") > 5.0, "{before}");
    for (args, limit) in [(&["--blots"][..], 2.0), (&["--blots", "1.5"], 1.5)] {
        moyo(&dir)
            .args(["plot", "rays.svg", "-o", "thin.svg"])
            .args(args)
            .assert()
            .success();
        let after = stats_json(&dir, "thin.svg");
        assert!(number(&after, "densest") <= limit, "{args:?}: {after}");
        // Every stroke is still there, a little shorter, none cut in two.
        assert_eq!(number(&after, "paths"), 40.0, "{after}");
        assert_eq!(number(&after, "pen_lifts"), 40.0, "{after}");
        let lost = number(&before, "pen_down_mm") - number(&after, "pen_down_mm");
        assert!(lost > 0.0 && lost < 40.0 * 1.0, "{lost} mm");
    }
}

#[test]
fn hpgl_beyond_the_device_range_fails_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let svg = r##"<svg xmlns="http://www.w3.org/2000/svg" width="2000mm" height="100mm" viewBox="0 0 2000 100">
        <path id="long" d="M 10 50 L 1500 50" stroke="#000" fill="none"/>
    </svg>"##;
    fs::write(dir.path().join("big.svg"), svg).unwrap();
    // 1500 mm is 60000 plotter units: beyond HP-GL's 32767.
    moyo(&dir)
        .args(["plot", "big.svg", "-o", "out.hpgl"])
        .assert()
        .failure()
        .stderr(predicate::str::starts_with(
            "error: hpgl: path long reaches (1500.000, 50.000) mm on the device, \
             (60000, 2000) plotter units: outside the device range -32768…32767 units",
        ));
    assert!(!dir.path().join("out.hpgl").exists());
    // An HP-GL/2 device takes it.
    moyo(&dir)
        .args(["plot", "big.svg", "-o", "out.hpgl"])
        .args(["--device-range", "-1073741824,1073741823"])
        .assert()
        .success();
    let h = fs::read_to_string(dir.path().join("out.hpgl")).unwrap();
    assert!(h.contains("PU400,2000;\nPD60000,2000;\n"), "{h}");
    // A range that is no range is refused.
    for range in ["5,1", "0,2000000000", "5"] {
        moyo(&dir)
            .args(["plot", "big.svg", "-o", "x.hpgl", "--device-range", range])
            .assert()
            .failure()
            .stderr(
                predicate::str::contains("device-range")
                    .or(predicate::str::contains("device_range")),
            );
        assert!(!dir.path().join("x.hpgl").exists());
    }
}

// ---------------------------------------------------------------------------
// AxiDraw documentation layers (`%` names): kept in the colour preview,
// never plotted.

/// Two documentation layers, `%guides` and `  % 2 notes`, beside pens 1 and
/// 2 (see the comment at the top of the file).
const AXIDRAW_LAYERS: &str = include_str!("fixtures/import/axidraw_layers.svg");

/// Everything the fixture plots lies in this box, on the page (mm, y down):
/// `[x0, y0, x1, y1]`; every point of its documentation layers lies outside.
const PLOTTED_BOX: [f64; 4] = [20.0, 20.0, 160.0, 70.0];

/// Pen-down length of the fixture's plotted paths: 40 + 40 + 20 + 2π·20 mm.
fn plotted_ink() -> f64 {
    100.0 + 2.0 * std::f64::consts::PI * 20.0
}

/// A directory holding the fixture as `in.svg`.
fn with_axidraw_layers() -> TempDir {
    let dir = tempfile::tempdir().expect("temporary directory");
    fs::write(dir.path().join("in.svg"), AXIDRAW_LAYERS).unwrap();
    dir
}

/// The documentation layers of an SVG, in document order: each one's name
/// and its paths' points on the page.
fn unplotted_layers(svg: &str) -> Vec<(String, Vec<Vec<kurbo::Point>>)> {
    use moyo::input::{import_svg, ImportOptions};
    let scene = import_svg(svg, &ImportOptions::DEFAULT)
        .expect("moyo reads the SVG")
        .scene;
    let mut out: Vec<(String, Vec<Vec<kurbo::Point>>)> = Vec::new();
    for layer in scene.layers.iter().filter(|l| !l.is_plotted()) {
        let mut paths = Vec::new();
        layer
            .content
            .visit_paths(scene.page_transform(), &mut |p, t| {
                let path = t * p.path.clone();
                let mut points = Vec::new();
                for el in path.elements() {
                    use kurbo::PathEl::*;
                    match *el {
                        MoveTo(a) | LineTo(a) => points.push(a),
                        QuadTo(a, b) => points.extend([a, b]),
                        CurveTo(a, b, c) => points.extend([a, b, c]),
                        ClosePath => {}
                    }
                }
                paths.push(points);
            });
        out.push((layer.name.clone(), paths));
    }
    out
}

fn assert_same_unplotted_layers(before: &str, after: &str) {
    let (a, b) = (unplotted_layers(before), unplotted_layers(after));
    let names = |v: &[(String, Vec<Vec<kurbo::Point>>)]| -> Vec<String> {
        v.iter().map(|(n, _)| n.clone()).collect()
    };
    assert_eq!(names(&a), ["%guides", "% 2 notes"]);
    assert_eq!(names(&a), names(&b));
    for ((name, pa), (_, pb)) in a.iter().zip(&b) {
        assert_eq!(pa.len(), pb.len(), "{name}: number of paths");
        for (x, y) in pa.iter().zip(pb) {
            assert_eq!(x.len(), y.len(), "{name}: {x:?} vs {y:?}");
            for (p, q) in x.iter().zip(y) {
                assert!((*p - *q).hypot() < 1e-3, "{name}: {p:?} vs {q:?}");
            }
        }
    }
}

/// Whether page point `(x, y)` is in [`PLOTTED_BOX`], give or take `slack`.
fn in_plotted_box(x: f64, y: f64, slack: f64) -> bool {
    let [x0, y0, x1, y1] = PLOTTED_BOX;
    x0 - slack <= x && x <= x1 + slack && y0 - slack <= y && y <= y1 + slack
}

#[test]
fn documentation_layers_survive_merge_and_sort_unchanged_in_the_preview() {
    let dir = with_axidraw_layers();
    moyo(&dir)
        .args(["plot", "in.svg", "--merge", "--sort", "-o", "out.svg"])
        .args(["--png", "out.png", "--preview-svg", "preview.svg"])
        .assert()
        .success()
        // The summary counts what is plotted, 3 paths after merging, and
        // what was read.
        .stderr(predicate::str::contains(
            "(3 paths from the input's 4, 226 mm pen-down",
        ));
    // The plot holds only what pens draw: vpype and cutters would draw
    // the guides.
    let out = fs::read_to_string(dir.path().join("out.svg")).unwrap();
    assert!(!out.contains("inkscape:label=\"%"), "{out}");
    assert!(unplotted_layers(&out).is_empty());
    let preview = fs::read_to_string(dir.path().join("preview.svg")).unwrap();
    for label in ["%guides", "% 2 notes"] {
        assert!(
            preview.contains(&format!("inkscape:label=\"{label}\"")),
            "{label} is a layer of its own:\n{preview}"
        );
    }
    assert_same_unplotted_layers(AXIDRAW_LAYERS, &preview);
    assert!(dir.path().join("out.png").exists());

    // Stats: the documentation layers are listed, flagged, and not counted.
    for (file, plotted_paths, documented) in [
        ("in.svg", 4.0, true),
        ("preview.svg", 3.0, true),
        ("out.svg", 3.0, false),
    ] {
        let s = stats_json(&dir, file);
        let layers = s["layers"].as_array().expect("layers");
        let flags: Vec<(&str, bool)> = layers
            .iter()
            .map(|l| (l["name"].as_str().unwrap(), l["plotted"].as_bool().unwrap()))
            .collect();
        let pens = [("black", true), ("red", true)];
        let expected = if documented {
            [&[("%guides", false), ("% 2 notes", false)][..], &pens].concat()
        } else {
            pens.to_vec()
        };
        assert_eq!(flags, expected, "{file}");
        assert_eq!(number(&s, "paths"), plotted_paths, "{file}");
        // usvg's circle (four cubics) is a little longer than 2πr.
        let ink = number(&s, "pen_down_mm");
        assert!((ink - plotted_ink()).abs() < 0.05, "{file}: {ink}");
        for key in [
            "paths",
            "pen_lifts",
            "pen_down_mm",
            "pen_up_mm",
            "plot_time_s",
            "plot_time_accel_s",
        ] {
            let plotted: f64 = layers
                .iter()
                .filter(|l| l["plotted"] == true)
                .map(|l| number(l, key))
                .sum();
            assert!((plotted - number(&s, key)).abs() < 1e-9, "{file}: {key}");
        }
        if documented {
            // The guides' own figures: a 560 mm frame and a 90 mm line.
            assert_eq!(number(&layers[0], "paths"), 2.0);
            assert!((number(&layers[0], "pen_down_mm") - 650.0).abs() < 0.01);
        }
    }
}

#[test]
fn gcode_and_hpgl_leave_documentation_layers_out() {
    let dir = with_axidraw_layers();
    moyo(&dir)
        .args(["plot", "in.svg", "-o", "out.gcode"])
        .assert()
        .success();
    let g = fs::read_to_string(dir.path().join("out.gcode")).unwrap();
    let mut moves = 0;
    for line in g
        .lines()
        .filter(|l| l.starts_with("G0") || l.starts_with("G1"))
    {
        let word = |c: char| -> f64 {
            let w = line.split(' ').find(|w| w.starts_with(c)).unwrap();
            w[1..].parse().unwrap()
        };
        // Origin bottom-left, Y up, on a 100 mm high page.
        let (x, y) = (word('X'), 100.0 - word('Y'));
        assert!(
            in_plotted_box(x, y, 1e-9) || (x, y) == (0.0, 100.0),
            "{line}"
        );
        moves += 1;
    }
    assert!(moves > 20, "{g}");
    assert!(!g.contains("note") && !g.contains("frame") && !g.contains("pen 3"));

    for args in [&[][..], &["--cutter"]] {
        moyo(&dir)
            .args(["plot", "in.svg", "-o", "out.plt"])
            .args(args)
            .assert()
            .success();
        let h = fs::read_to_string(dir.path().join("out.plt")).unwrap();
        assert!(h.contains("SP1;") && h.contains("SP2;"), "{h}");
        assert!(!h.contains("SP3;") && !h.contains("SP4;"), "{h}");
        // The knife offset and the overcut reach a little past a shape.
        let slack = if args.is_empty() { 1e-9 } else { 1.3 };
        for ins in h.split(';').map(str::trim) {
            let Some(rest) = ins.strip_prefix("PU").or_else(|| ins.strip_prefix("PD")) else {
                continue;
            };
            // The pen parks at the device's origin before it is put away.
            if ins == "PU0,0" && h.ends_with("PU0,0;\nSP0;\n") {
                continue;
            }
            let n: Vec<f64> = rest
                .split(',')
                .filter(|t| !t.is_empty())
                .map(|t| t.parse::<f64>().unwrap() / 40.0)
                .collect();
            for c in n.chunks(2) {
                assert!(in_plotted_box(c[0], 100.0 - c[1], slack), "{ins}");
            }
        }
    }
}

#[test]
fn documentation_layers_are_neither_hatched_nor_occluded() {
    let dir = with_axidraw_layers();
    moyo(&dir)
        .args([
            "plot",
            "in.svg",
            "--hatch",
            "2",
            "--occlude",
            "-o",
            "out.svg",
            "--preview-svg",
            "preview.svg",
        ])
        .assert()
        .success();
    let preview = fs::read_to_string(dir.path().join("preview.svg")).unwrap();
    assert_same_unplotted_layers(AXIDRAW_LAYERS, &preview);
    let s = stats_json(&dir, "out.svg");
    assert!((number(&s, "pen_down_mm") - plotted_ink()).abs() < 0.05);
}

// ---------------------------------------------------------------------------
// Real interpreters read our G-code and HPGL.
//
// Each test runs when its variable names the program (`tools/test-env.sh`
// installs both); without it, see `readers.rs`.

pub(crate) use crate::readers::reader as interpreter;

#[test]
fn pygcode_reads_our_gcode_and_draws_the_plotted_paths() {
    let Some(python) = interpreter("MOYO_PYTHON") else {
        return;
    };
    let dir = with_axidraw_layers();
    moyo(&dir)
        .args(["plot", "in.svg", "-o", "out.gcode"])
        .assert()
        .success();
    let r = read_gcode(&python, &dir.path().join("out.gcode"), "spindle");
    assert_eq!(r["strokes"], 4, "{r}");
    assert_eq!(r["rapid_down"], 0, "{r}");
    assert_eq!(r["pen_up_at_end"], true, "{r}");
    // Flattening within 0.02 mm shortens the circle a little.
    let drawn = number(&r, "drawn_mm");
    assert!((drawn - plotted_ink()).abs() < 0.1, "{drawn}");
    // Machine Y = 100 − page y: the plotted box, and nothing of the guides.
    let b: Vec<f64> = r["box"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let [x0, y0, x1, y1] = PLOTTED_BOX;
    let expected = [x0, 100.0 - y1, x1, 100.0 - y0];
    for (got, want) in b.iter().zip(expected) {
        assert!((got - want).abs() < 1e-3, "{b:?} vs {expected:?}");
    }

    // The default design, sorted, with travel at G0 and several pens.
    let dir = with_default_design();
    moyo(&dir)
        .args(["plot", "hem.svg", "--sort", "--travel-feed", "0"])
        .args(["-o", "hem.gcode"])
        .assert()
        .success();
    let r = read_gcode(&python, &dir.path().join("hem.gcode"), "spindle");
    let s = stats_json(&dir, "hem.svg");
    assert!(number(&r, "strokes") >= number(&s, "paths"), "{r}");
    assert_eq!(r["rapid_down"], 0, "{r}");
    let (drawn, ink) = (number(&r, "drawn_mm"), number(&s, "pen_down_mm"));
    assert!((drawn - ink).abs() < 0.01 * ink, "{drawn} vs {ink}");
}

/// The number after `key` on hp2xx's report line that starts with it.
fn hp2xx_figure(report: &str, key: &str) -> f64 {
    report
        .lines()
        .find_map(|l| l.trim().strip_prefix(key))
        .unwrap_or_else(|| panic!("no '{key}' in:\n{report}"))
        .trim()
        .parse()
        .unwrap_or_else(|e| panic!("{key}: {e}\n{report}"))
}

/// Every number on hp2xx's report line that starts with `key`.
fn hp2xx_numbers(report: &str, key: &str) -> Vec<f64> {
    let line = report
        .lines()
        .find_map(|l| l.trim().strip_prefix(key))
        .unwrap_or_else(|| panic!("no '{key}' in:\n{report}"));
    line.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
        .filter(|t| !t.is_empty() && *t != "." && *t != "...")
        .map(|t| t.parse().unwrap())
        .collect()
}

#[test]
fn hp2xx_draws_our_hpgl() {
    let Some(hp2xx) = interpreter("MOYO_HP2XX") else {
        return;
    };
    let dir = with_axidraw_layers();
    for args in [&[][..], &["--cutter"]] {
        moyo(&dir)
            .args(["plot", "in.svg", "-o", "out.plt"])
            .args(args)
            .assert()
            .success();
        let _ = fs::remove_file(dir.path().join("hp2xx.svg"));
        let out = std::process::Command::new(&hp2xx)
            .current_dir(dir.path())
            .args(["-m", "svg", "-f", "hp2xx.svg", "out.plt"])
            .output()
            .expect("hp2xx runs");
        let report = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{args:?}: {report}");
        let drawing = fs::read_to_string(dir.path().join("hp2xx.svg")).unwrap();
        assert!(drawing.contains("<path"), "{drawing}");
        // Every instruction understood; the documentation layers' pens
        // (3 and 4) are never selected.
        assert_eq!(hp2xx_figure(&report, "HPGL command(s) ignored:"), 0.0);
        assert_eq!(hp2xx_figure(&report, "Unexpected event(s):"), 0.0);
        assert_eq!(hp2xx_numbers(&report, "Pens used:"), [1.0, 2.0], "{report}");
        // The drawing's extent in plotter units (40 per mm, Y up): the
        // plotted box, a knife offset and overcut past it when cutting.
        let range = hp2xx_numbers(&report, "Coordinate range:");
        let [x0, y0, x1, y1] = PLOTTED_BOX.map(|v| v * 40.0);
        let expected = [x0, 4000.0 - y1, x1, 4000.0 - y0];
        let slack = if args.is_empty() { 0.5 } else { 1.3 * 40.0 };
        assert_eq!(range.len(), 4, "{report}");
        for (got, want) in range.iter().zip(expected) {
            assert!((got - want).abs() <= slack, "{range:?} vs {expected:?}");
        }
    }

    // The default design: several pens, curves, long strokes in PD chunks.
    let dir = with_default_design();
    let pens = pen_numbers(&fs::read_to_string(dir.path().join("hem.svg")).unwrap());
    moyo(&dir)
        .args(["plot", "hem.svg", "--sort", "-o", "hem.plt"])
        .assert()
        .success();
    let out = std::process::Command::new(&hp2xx)
        .current_dir(dir.path())
        .args(["-m", "pbm", "-f", "hem.pbm", "hem.plt"])
        .output()
        .expect("hp2xx runs");
    let report = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{report}");
    assert!(fs::metadata(dir.path().join("hem.pbm")).unwrap().len() > 0);
    assert_eq!(hp2xx_figure(&report, "HPGL command(s) ignored:"), 0.0);
    assert_eq!(hp2xx_figure(&report, "Unexpected event(s):"), 0.0);
    assert_eq!(hp2xx_numbers(&report, "Pens used:"), pens, "{report}");
}

/// A graph as graphviz draws it: a white page polygon with a transparent
/// stroke behind three nodes (one a filled box), three edges with
/// arrowheads and three labels.
pub(crate) const GRAPHVIZ: &str = include_str!("fixtures/import/graphviz_like.svg");

/// A directory holding `graph.svg`.
pub(crate) fn with_graph() -> TempDir {
    let dir = tempfile::tempdir().expect("temporary directory");
    fs::write(dir.path().join("graph.svg"), GRAPHVIZ).unwrap();
    dir
}

/// The bounds, on the page, of what an SVG draws (mm).
pub(crate) fn drawn_bounds(svg: &str) -> kurbo::Rect {
    use moyo::input::{import_svg, ImportOptions};
    let scene = import_svg(svg, &ImportOptions::DEFAULT)
        .expect("moyo reads the SVG")
        .scene;
    scene.bounds().expect("something is drawn")
}

#[test]
fn a_graphviz_page_is_neither_plotted_nor_counted() {
    let dir = with_graph();
    // Three nodes, three edges and their arrowheads, three labels; no
    // page border, and no pen for the page's white.
    let s = stats_json(&dir, "graph.svg");
    assert_eq!(number(&s, "paths"), 12.0, "{s}");
    assert_eq!(s["layers"].as_array().unwrap().len(), 1, "{s}");
    // Less than the border alone would be: 2 × (134 + 188) pt = 227 mm.
    let ink = number(&s, "pen_down_mm");
    assert!(ink > 250.0 && ink < 300.0, "{ink}");
    // The page is 134 × 188 pt; the graph keeps 4 pt (1.41 mm) from its
    // edges, and so does the plot, with or without hidden-line removal
    // (the white page lies behind the graph and hides none of it), and
    // through the pen stage (which counts a glyph's strokes apart).
    let page = kurbo::Rect::new(0.0, 0.0, 134.0, 188.0).scale_from_origin(25.4 / 72.0);
    for stages in [&[][..], &["--occlude"], &["--occlude", "--merge", "--sort"]] {
        moyo(&dir)
            .args(["plot", "graph.svg", "-o", "out.svg", "--png", "out.png"])
            .args(stages)
            .assert()
            .success();
        let b = drawn_bounds(&fs::read_to_string(dir.path().join("out.svg")).unwrap());
        let inset = page.inset(-1.3);
        assert!(
            b.x0 > inset.x0 && b.y0 > inset.y0 && b.x1 < inset.x1 && b.y1 < inset.y1,
            "{stages:?}: {b:?} reaches the page's edge {page:?}"
        );
        let out = stats_json(&dir, "out.svg");
        let drawn = number(&out, "pen_down_mm");
        assert!(
            (drawn - ink).abs() < 0.01 * ink,
            "{stages:?}: {drawn} vs {ink}"
        );
        assert_eq!(
            out["layers"].as_array().unwrap().len(),
            1,
            "{stages:?}: {out}"
        );
    }
    // G-code draws with pen 1 alone.
    moyo(&dir)
        .args(["plot", "graph.svg", "-o", "out.gcode"])
        .assert()
        .success();
    let g = fs::read_to_string(dir.path().join("out.gcode")).unwrap();
    assert!(g.contains("; pen 1 ") && !g.contains("; pen 2"), "{g}");
}

/// The stderr of a `moyo` run that fails, with nothing written: the
/// folder holds what it held before.
fn fails(dir: &TempDir, args: &[&str]) -> String {
    let before = crate::cli::entries(dir.path());
    let out = moyo(dir)
        .args(args)
        .assert()
        .failure()
        .get_output()
        .stderr
        .clone();
    assert_eq!(crate::cli::entries(dir.path()), before, "{args:?}");
    let stderr = String::from_utf8_lossy(&out).into_owned();
    assert!(stderr.starts_with("error: "), "{args:?}: {stderr}");
    stderr
}

#[test]
fn negative_numbers_need_no_equals_sign() {
    let dir = with_graph();
    // The same drawing with a space as with `=`.
    for (flag, value, extra) in [
        ("--rotate", "-30", &["--format", "svg"][..]),
        (
            "--hatch-angle",
            "-45",
            &["--hatch", "2", "--format", "svg"][..],
        ),
        (
            "--refill-at",
            "-15,20",
            &["--refill", "60", "--format", "gcode"][..],
        ),
        (
            "--device-range",
            "-100000,100000",
            &["--format", "hpgl"][..],
        ),
    ] {
        moyo(&dir)
            .args(["plot", "graph.svg", "-o", "spaced", flag, value])
            .args(extra)
            .assert()
            .success();
        moyo(&dir)
            .args(["plot", "graph.svg", "-o", "joined"])
            .arg(format!("{flag}={value}"))
            .args(extra)
            .assert()
            .success();
        let read = |name: &str| fs::read(dir.path().join(name)).unwrap();
        assert_eq!(read("spaced"), read("joined"), "{flag} {value}");
    }
    // A negative value out of range is refused by the option's own check,
    // not taken for an unknown option.
    for (args, expected) in [
        (&["--scale", "-2"][..], "scale: must be between"),
        (&["--speed-down", "-5"], "--speed-down: "),
        (&["--dpi", "-5", "--png", "x.png"], "-5"),
    ] {
        let stderr = fails(
            &dir,
            &[&["plot", "graph.svg", "-o", "out.svg"][..], args].concat(),
        );
        assert!(
            stderr.contains(expected) && !stderr.contains("unexpected argument"),
            "{args:?}: {stderr}"
        );
    }
}

#[test]
fn an_output_extension_that_names_no_format_is_refused() {
    let dir = with_graph();
    for (out, expected) in [
        (
            "out.txt",
            "-o out.txt: the extension .txt names no output format",
        ),
        ("out", "-o out: no extension to tell the output format by"),
    ] {
        let stderr = fails(&dir, &["plot", "graph.svg", "-o", out]);
        assert!(stderr.contains(expected), "{stderr}");
        assert!(
            stderr.contains(
                ".svg, .gcode, .nc, .ngc, .g, .hpgl, .plt, .hgl or .dxf, or give --format"
            ),
            "{stderr}"
        );
    }
    // --format says what to write; so does a device.
    moyo(&dir)
        .args(["plot", "graph.svg", "-o", "out.txt", "--format", "svg"])
        .assert()
        .success();
    assert!(fs::read_to_string(dir.path().join("out.txt"))
        .unwrap()
        .contains("<svg"));
    moyo(&dir)
        .args([
            "plot",
            "graph.svg",
            "-o",
            "out.nc2",
            "--device",
            "grbl-servo",
        ])
        .assert()
        .success();
    assert!(fs::read_to_string(dir.path().join("out.nc2"))
        .unwrap()
        .contains("G21"));
}

/// A directory holding the real-world drawing `name` of tests/data/.
fn with_real_world(name: &str) -> TempDir {
    let dir = tempfile::tempdir().expect("temporary directory");
    let from = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name);
    fs::copy(from, dir.path().join(name)).expect("tests/data holds it");
    dir
}

/// The pen numbers an HPGL program selects, `SP0` (put the pen away) left
/// out.
fn hpgl_pens(hpgl: &str) -> std::collections::BTreeSet<u32> {
    hpgl.split(';')
        .filter_map(|c| c.trim().strip_prefix("SP")?.parse().ok())
        .filter(|&n| n != 0)
        .collect()
}

/// The `requests` logo (tests/data/): an Illustrator export of 3,683 paths
/// in 1,978 colours, which once became 1,977 pens (`SP1`…`SP1977`). Pens
/// come from colours by a policy with a cap, and the merge is said.
#[test]
fn a_logo_of_two_thousand_colours_plots_with_a_handful_of_pens() {
    let logo = "requests-logo.svg";
    let dir = with_real_world(logo);
    for (args, most) in [
        (&[][..], 8),
        (&["--pens", "3"], 3),
        (&["--single-layer"], 1),
    ] {
        let out = moyo(&dir)
            .args(["plot", logo, "-o", "out.hpgl"])
            .args(args)
            .assert()
            .success();
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
        let pens = hpgl_pens(&fs::read_to_string(dir.path().join("out.hpgl")).unwrap());
        assert!(
            !pens.is_empty() && pens.iter().all(|&p| p <= most),
            "{args:?}: pens {pens:?}"
        );
        if args.is_empty() {
            assert!(
                stderr.contains("1,978 colours merged into 8 pens"),
                "{stderr}"
            );
            assert_eq!(pens.len(), 8, "the cap is used: {pens:?}");
        }
    }
    // One pen a colour would pass the 999 a plot allows: refused, saying
    // how to merge, and nothing written.
    fs::remove_file(dir.path().join("out.hpgl")).unwrap();
    moyo(&dir)
        .args(["plot", logo, "-o", "out.hpgl", "--pens", "0"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("1,978 pens").and(predicate::str::contains("--pens N")));
    assert!(!dir.path().join("out.hpgl").exists());
}

/// A graph from graphviz (tests/data/, from the Rust book): graphviz puts a
/// white page with `stroke="transparent"` behind every graph. It is paint,
/// not line work: no pen draws a border round the page, and `moyo fill`
/// fills the graph's boxes, not the page (it once stippled the whole page:
/// 84,942 dots).
#[test]
fn graphviz_s_page_behind_the_graph_is_neither_plotted_nor_filled() {
    let graph = "graphviz-trpl04-01.svg";
    let dir = with_real_world(graph);
    moyo(&dir)
        .args(["plot", graph, "-o", "out.svg"])
        .assert()
        .success();
    let out = fs::read_to_string(dir.path().join("out.svg")).unwrap();
    let plotted = moyo::import_svg(&out, &moyo::ImportOptions::DEFAULT)
        .unwrap()
        .scene;
    let page = kurbo::Rect::new(0.0, 0.0, plotted.page.width, plotted.page.height);
    let mut paths = 0;
    plotted.visit_paths(|_, p, t| {
        paths += 1;
        let b = kurbo::Shape::bounding_box(&(t * p.path.clone()));
        assert!(
            b.width() < 0.9 * page.width() || b.height() < 0.9 * page.height(),
            "a path round the page: {b:?} on {page:?}"
        );
    });
    assert!(paths > 20, "the graph is drawn: {paths} paths");
    let out = moyo(&dir)
        .args(["fill", graph, "-o", "filled.svg", "--pattern", "stipple"])
        .assert()
        .success();
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    let dots: usize = stderr
        .split("the stipple fill: ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{stderr}"));
    assert!(
        (100..2_000).contains(&dots),
        "{dots} dots: the boxes, not the page"
    );
}

/// Hiding lines takes the fill off every partly hidden shape (its outline
/// is open pieces now). The plot then carries no fill at all — not the
/// fills of the shapes nothing hides and none of the others, which looked
/// like a fault in Inkscape — and the colours of the whole shapes go to
/// the preview's fill layer. Ferris (tests/data/) has both kinds.
#[test]
fn a_plot_with_hidden_lines_carries_no_fill_and_its_preview_keeps_the_colours() {
    let ferris = "ferris-panics.svg";
    let dir = with_real_world(ferris);
    moyo(&dir)
        .args(["plot", ferris, "--occlude", "-o", "out.svg"])
        .args(["--preview-svg", "preview.svg"])
        .assert()
        .success();
    let out = fs::read_to_string(dir.path().join("out.svg")).unwrap();
    let filled = out
        .split("<path")
        .skip(1)
        .filter(|p| p.split('>').next().unwrap_or("").contains("fill:#"))
        .count();
    assert_eq!(filled, 0, "filled paths in the plot");
    let preview = fs::read_to_string(dir.path().join("preview.svg")).unwrap();
    let fills_layer = preview
        .split("inkscape:label=\"%preview fills\"")
        .nth(1)
        .expect("the preview has a fill layer");
    assert!(fills_layer.matches("fill:#").count() >= 5, "{fills_layer}");
}
