//! Cutter outputs through the command: DXF read back by ezdxf (the DXF
//! library CAD scripts use), inside-first order of `moyo plot --cutter`
//! and of DXF, and `moyo stencil` (issue 32): islands held by bridges, a
//! report that says so, bad options refused by name with nothing written.

use std::fs;
use std::path::Path;

use assert_cmd::Command;
use tempfile::TempDir;

use crate::plot_cli::{interpreter, stats_json};

fn moyo(dir: &TempDir) -> Command {
    let mut cmd = Command::cargo_bin("moyo").expect("the moyo binary is built");
    cmd.current_dir(dir.path());
    cmd
}

fn with(svg: &str) -> TempDir {
    let dir = tempfile::tempdir().expect("temporary directory");
    fs::write(dir.path().join("in.svg"), svg).unwrap();
    dir
}

/// Two pens on a 200 × 150 mm sheet: pen 1 an outline with a hole and a
/// circle in the hole, written outside first; pen 2 an open wave.
const NESTED: &str = r#"<svg xmlns="http://www.w3.org/2000/svg"
    xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
    width="200mm" height="150mm" viewBox="0 0 200 150">
  <g inkscape:groupmode="layer" inkscape:label="1 black" stroke="black" fill="none">
    <path d="M 20 20 H 120 V 120 H 20 Z"/>
    <path d="M 40 40 H 100 V 100 H 40 Z"/>
    <circle cx="70" cy="70" r="15"/>
  </g>
  <g inkscape:groupmode="layer" inkscape:label="2 red" stroke="red" fill="none">
    <path d="M 140 120 C 150 90 170 150 190 110"/>
  </g>
</svg>"#;

/// Reads a DXF with ezdxf and prints JSON: the version, the layers, and
/// every polyline (layer, closed, points) in file order.
const READ_DXF: &str = r#"
import json, sys
import ezdxf
doc = ezdxf.readfile(sys.argv[1])
out = {"version": doc.dxfversion, "layers": [l.dxf.name for l in doc.layers], "polylines": []}
for e in doc.modelspace():
    if e.dxftype() != "POLYLINE":
        sys.exit("unexpected entity %s" % e.dxftype())
    pts = [[v.dxf.location[0], v.dxf.location[1]] for v in e.vertices]
    out["polylines"].append({"layer": e.dxf.layer, "closed": e.is_closed, "points": pts})
print(json.dumps(out))
"#;

fn read_dxf(python: &std::ffi::OsStr, dxf: &Path) -> serde_json::Value {
    let out = std::process::Command::new(python)
        .arg("-c")
        .arg(READ_DXF)
        .arg(dxf)
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "{} is refused:\n{}",
        dxf.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("the reader prints JSON")
}

/// The polylines of a read DXF: (layer, closed, points).
fn polylines(r: &serde_json::Value) -> Vec<(String, bool, Vec<[f64; 2]>)> {
    r["polylines"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let points = p["points"]
                .as_array()
                .unwrap()
                .iter()
                .map(|q| [q[0].as_f64().unwrap(), q[1].as_f64().unwrap()])
                .collect();
            (
                p["layer"].as_str().unwrap().to_string(),
                p["closed"].as_bool().unwrap(),
                points,
            )
        })
        .collect()
}

fn length(closed: bool, points: &[[f64; 2]]) -> f64 {
    let mut l: f64 = points
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .sum();
    if closed {
        let (a, b) = (points[0], points[points.len() - 1]);
        l += (a[0] - b[0]).hypot(a[1] - b[1]);
    }
    l
}

#[test]
fn ezdxf_reads_our_dxf_with_the_same_paths() {
    let Some(python) = interpreter("MOYO_PYTHON") else {
        return;
    };
    let dir = with(NESTED);
    moyo(&dir)
        .args(["plot", "in.svg", "-o", "out.dxf"])
        .assert()
        .success();
    let r = read_dxf(&python, &dir.path().join("out.dxf"));
    assert_eq!(r["version"], "AC1009", "{r}");
    let layers: Vec<&str> = r["layers"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|l| l.as_str())
        .filter(|l| l.starts_with("PEN-"))
        .collect();
    assert_eq!(layers, ["PEN-1", "PEN-2"]);
    let lines = polylines(&r);
    let shape: Vec<(&str, bool)> = lines.iter().map(|(l, c, _)| (l.as_str(), *c)).collect();
    // Inside first: the circle, the hole, the outline; then pen 2's wave.
    assert_eq!(
        shape,
        [
            ("PEN-1", true),
            ("PEN-1", true),
            ("PEN-1", true),
            ("PEN-2", false)
        ]
    );
    // The outline's corners, y up from the bottom of the 150 mm sheet.
    let mut outline = lines[2].2.clone();
    outline.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(
        outline,
        [[20.0, 30.0], [20.0, 130.0], [120.0, 30.0], [120.0, 130.0]]
    );
    // The same line work as the drawing: the pen-down length matches.
    let drawn: f64 = lines.iter().map(|(_, c, p)| length(*c, p)).sum();
    let ink = stats_json(&dir, "in.svg")["pen_down_mm"].as_f64().unwrap();
    assert!((drawn - ink).abs() < 0.002 * ink, "{drawn} vs {ink}");
}

/// The points a cutter's HPGL puts the knife down on, stroke by stroke
/// (`PD` after a `PU` starts a stroke).
fn hpgl_strokes(hpgl: &str) -> Vec<Vec<[f64; 2]>> {
    let mut strokes: Vec<Vec<[f64; 2]>> = Vec::new();
    let mut down = false;
    for cmd in hpgl.split(';') {
        let cmd = cmd.trim();
        let (op, args) = cmd.split_at(cmd.len().min(2));
        let nums: Vec<f64> = args
            .split(',')
            .filter_map(|n| n.trim().parse().ok())
            .collect();
        match op {
            "PU" => down = false,
            "PD" => {
                if !down {
                    strokes.push(Vec::new());
                }
                down = true;
                let s = strokes.last_mut().unwrap();
                s.extend(nums.chunks(2).map(|c| [c[0], c[1]]));
            }
            _ => {}
        }
    }
    strokes
}

#[test]
fn the_cutter_cuts_every_outline_after_what_lies_inside_it() {
    let dir = with(NESTED);
    moyo(&dir)
        .args(["plot", "in.svg", "--cutter", "--sort", "-o", "cut.hpgl"])
        .assert()
        .success();
    let hpgl = fs::read_to_string(dir.path().join("cut.hpgl")).unwrap();
    // The three strokes of pen 1, by the width of what they cut (40
    // units per mm): the circle (30 mm), the hole (60), the outline (100).
    let widths: Vec<f64> = hpgl_strokes(&hpgl)
        .iter()
        .take(3)
        .map(|s| {
            let xs = s.iter().map(|p| p[0]);
            let max = xs.clone().fold(f64::MIN, f64::max);
            let min = xs.fold(f64::MAX, f64::min);
            (max - min) / 40.0
        })
        .collect();
    assert!(
        widths[0] < widths[1] && widths[1] < widths[2],
        "cut widths in order {widths:?}"
    );
    // A pen plotter keeps the travel sort's own order: the outline,
    // nearest the origin, comes first.
    moyo(&dir)
        .args(["plot", "in.svg", "--sort", "-o", "pen.hpgl"])
        .assert()
        .success();
    let pen = fs::read_to_string(dir.path().join("pen.hpgl")).unwrap();
    let first = &hpgl_strokes(&pen)[0];
    let xs = first.iter().map(|p| p[0]);
    let span = xs.clone().fold(f64::MIN, f64::max) - xs.fold(f64::MAX, f64::min);
    assert!((span / 40.0 - 100.0).abs() < 0.1, "{span}");
}

/// A disc in a ring in a ring (three islands), a small ring round a 3.5
/// mm disc (one more) and a wave (none), 0.5 mm pens on a 120 mm square
/// sheet.
const RINGS: &str = r#"<svg xmlns="http://www.w3.org/2000/svg"
    xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
    width="120mm" height="120mm" viewBox="0 0 120 120">
  <g inkscape:groupmode="layer" inkscape:label="1 black" stroke="black" fill="none" stroke-width="0.5">
    <circle cx="60" cy="60" r="40"/>
    <circle cx="60" cy="60" r="25"/>
    <circle cx="60" cy="60" r="10"/>
    <circle cx="10" cy="10" r="2"/>
    <path d="M 10 112 C 30 100 60 120 110 108"/>
  </g>
</svg>"#;

#[test]
fn a_stencil_holds_its_islands_and_says_so() {
    let dir = with(RINGS);
    let out = moyo(&dir)
        .args(["stencil", "in.svg", "-o", "cut.svg", "--bridge-every", "0"])
        .args(["--png", "sheet.png", "--print-png", "print.png"])
        .assert()
        .success();
    let report = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(report.contains("4 islands, 4 bridges"), "{report}");
    assert!(report.contains("the sheet is one piece"), "{report}");
    for file in ["cut.svg", "sheet.png", "print.png"] {
        assert!(dir.path().join(file).exists(), "{file}");
    }
    // More bridges along long outlines.
    let out = moyo(&dir)
        .args(["stencil", "in.svg", "-o", "cut.dxf", "--bridge-every", "30"])
        .assert()
        .success();
    let report = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(report.contains("4 islands, "), "{report}");
    assert!(!report.contains("4 islands, 4 bridges"), "{report}");
    if let Some(python) = interpreter("MOYO_PYTHON") {
        let r = read_dxf(&python, &dir.path().join("cut.dxf"));
        let lines = polylines(&r);
        // Every cut is a closed outline.
        assert!(lines.iter().all(|(_, closed, _)| *closed), "{r}");
        assert!(lines.len() >= 4, "{r}");
    }
}

#[test]
fn bad_stencil_input_is_refused_by_name_and_nothing_is_written() {
    let dir = with(RINGS);
    fs::write(
        dir.path().join("empty.svg"),
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="50mm" height="50mm" viewBox="0 0 50 50"/>"#,
    )
    .unwrap();
    for (args, expected) in [
        (&["in.svg", "--bridge", "-1"][..], "--bridge: "),
        (&["in.svg", "--bridge-every", "-5"][..], "--bridge-every: "),
        (&["in.svg", "--min-feature", "-0.1"][..], "--min-feature: "),
        // As wide as the whole small ring (4.5 mm across) it must cross.
        (
            &["in.svg", "--bridge", "5"][..],
            "--bridge: a bridge 5 mm wide is wider than the gap it must cross at (",
        ),
        (&["empty.svg"][..], "empty.svg: "),
    ] {
        let out = moyo(&dir)
            .arg("stencil")
            .args(args)
            .args(["-o", "cut.dxf", "--png", "sheet.png"])
            .assert()
            .failure();
        let err = String::from_utf8_lossy(&out.get_output().stderr).to_string();
        assert!(err.contains(expected), "{args:?}: {err}");
        assert!(!dir.path().join("cut.dxf").exists(), "{args:?}");
        assert!(!dir.path().join("sheet.png").exists(), "{args:?}");
    }
}

/// Options that the chosen cut would not use are refused, saying why;
/// nothing is written.
#[test]
fn options_the_cut_would_ignore_are_refused_with_why() {
    let dir = with(RINGS);
    for (output, args, expected) in [
        (
            "cut.svg",
            &["--overcut", "2"][..],
            "--overcut: an HPGL cutter option, but the cut is written as SVG",
        ),
        (
            "cut.dxf",
            &["--knife-offset", "0.3"],
            "--knife-offset: an HPGL cutter option, but the cut is written as DXF",
        ),
        (
            "cut.hpgl",
            &["--dpi", "300"],
            "--dpi: the resolution of --png and --print-png",
        ),
    ] {
        let out = moyo(&dir)
            .args(["stencil", "in.svg", "-o", output])
            .args(args)
            .assert()
            .failure();
        let err = String::from_utf8_lossy(&out.get_output().stderr).to_string();
        assert!(err.contains(expected), "{args:?}: {err}");
        assert!(!dir.path().join(output).exists(), "{args:?}");
    }
}

#[test]
fn the_katagami_template_cut_as_a_stencil_is_one_piece() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let template = Path::new(env!("CARGO_MANIFEST_DIR")).join("templates/katagami.toml");
    let out = moyo(&dir)
        .arg("stencil")
        .arg(&template)
        .args(["-o", "katagami.dxf"])
        .assert()
        .success();
    let report = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(report.contains("the sheet is one piece"), "{report}");
    assert!(!report.contains("fall out"), "{report}");
    // A web of waves and blossoms: hundreds of islands, each held.
    let counts: Vec<usize> = report
        .lines()
        .next()
        .unwrap()
        .split(|c: char| !c.is_ascii_digit())
        .filter_map(|n| n.parse().ok())
        .collect();
    assert!(counts[0] > 500 && counts[1] >= counts[0], "{report}");
    assert!(dir.path().join("katagami.dxf").exists());
}
