//! Device profiles, AxiDraw's layer codes, refills and resuming, through
//! `moyo plot`, each output read by the program a machine's owner would
//! trust: pygcode (a G-code parser and machine model; Marlin's numbered,
//! checksummed lines are checked first, as a host does) and hp2xx.

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

/// Two pens on a 200 × 150 mm sheet: pen 1 a square and a circle, pen 2
/// (named with AxiDraw's pause, delay, height and speed codes) a wave of
/// curves. About 540 mm of line.
const TWO_PENS: &str = r#"<svg xmlns="http://www.w3.org/2000/svg"
    xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
    width="200mm" height="150mm" viewBox="0 0 200 150">
  <g inkscape:groupmode="layer" inkscape:label="1 black" stroke="black" fill="none">
    <path d="M 20 20 H 80 V 80 H 20 Z"/>
    <circle cx="130" cy="50" r="25"/>
  </g>
  <g inkscape:groupmode="layer" inkscape:label="!2+D300+H20+S40 red" stroke="red" fill="none">
    <path d="M 20 120 C 40 90 60 150 80 120 S 120 90 140 120 S 170 150 180 110"/>
  </g>
</svg>"#;

fn with_two_pens() -> TempDir {
    let dir = tempfile::tempdir().expect("temporary directory");
    fs::write(dir.path().join("in.svg"), TWO_PENS).unwrap();
    dir
}

/// Reads a G-code program as a machine would: when lines are numbered
/// (`N…`), each must follow the last and carry a right checksum (`*…`,
/// the XOR of its bytes); what is left must parse with pygcode, with no
/// stray words. The pen is down while the spindle turns (servo machines)
/// or Z is at most 0.6 (Z machines: `z` as the second argument). Prints
/// JSON: strokes, the length drawn (arcs along their circle), rapid moves
/// with the pen down, pauses (`M0`) and pauses with the pen down, the
/// pen-down length between pauses (`runs`), the box of the drawn moves'
/// ends (machine mm), and the pen at the end.
const READ_GCODE: &str = r#"
import json, math, re, sys
from pygcode import Line, Machine

path, pen = sys.argv[1], sys.argv[2]
machine = Machine()
def down():
    if pen == "z":
        return machine.pos.Z <= 0.6
    return str(machine.mode.spindle).startswith("M03")

strokes = drawn = rapid_down = pauses = pauses_down = arcs = 0
runs = [0.0]
box = None
expected = 0
for number, raw in enumerate(open(path, encoding="utf-8"), 1):
    text = raw.rstrip("\n")
    m = re.fullmatch(r"N(\d+) (.*?)(?:\*(\d+))?", text)
    if m:
        if int(m.group(1)) != expected:
            sys.exit("line %d: N%s, expected N%d" % (number, m.group(1), expected))
        expected += 1
        if m.group(3) is not None:
            body = text[:text.rindex("*")]
            xor = 0
            for b in body.encode():
                xor ^= b
            if xor != int(m.group(3)):
                sys.exit("line %d: checksum %s, expected %d" % (number, m.group(3), xor))
        text = m.group(2)
        if text.startswith("M110"):
            continue
    try:
        line = Line(text)
    except Exception as e:
        sys.exit("line %d %r: %s" % (number, text, e))
    if line.block.modal_params:
        sys.exit("line %d %r: words without a command: %s" % (number, text, line.block.modal_params))
    codes = [str(g) for g in line.block.gcodes]
    was_down = down()
    x0, y0 = machine.pos.X, machine.pos.Y
    if any(c.startswith("M00") for c in codes):
        pauses += 1
        pauses_down += was_down
        runs.append(0.0)
    machine.process_block(line.block)
    x1, y1 = machine.pos.X, machine.pos.Y
    if down() and not was_down:
        strokes += 1
    if was_down and down() and (x0, y0) != (x1, y1):
        if any(c.startswith("G00") for c in codes):
            rapid_down += 1
        arc = [g for g in line.block.gcodes if str(g).startswith(("G02", "G03"))]
        if arc:
            arcs += 1
            g = arc[0]
            cx, cy = x0 + (g.I or 0), y0 + (g.J or 0)
            a0, a1 = math.atan2(y0 - cy, x0 - cx), math.atan2(y1 - cy, x1 - cx)
            sweep = a1 - a0
            if str(g).startswith("G03") and sweep <= 0:
                sweep += 2 * math.pi
            if str(g).startswith("G02") and sweep >= 0:
                sweep -= 2 * math.pi
            step = math.hypot(x0 - cx, y0 - cy) * abs(sweep)
        else:
            step = math.hypot(x1 - x0, y1 - y0)
        drawn += step
        runs[-1] += step
        for x, y in ((x0, y0), (x1, y1)):
            box = [x, y, x, y] if box is None else [
                min(box[0], x), min(box[1], y), max(box[2], x), max(box[3], y)]
print(json.dumps({
    "strokes": strokes, "drawn_mm": drawn, "rapid_down": rapid_down,
    "pauses": pauses, "pauses_down": pauses_down, "arcs": arcs,
    "runs": runs, "box": box, "pen_up_at_end": not down(),
}))
"#;

pub(crate) fn read_gcode(python: &std::ffi::OsStr, gcode: &Path, pen: &str) -> serde_json::Value {
    let out = std::process::Command::new(python)
        .arg("-c")
        .arg(READ_GCODE)
        .arg(gcode)
        .arg(pen)
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "{} is refused:\n{}",
        gcode.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("the reader prints JSON")
}

fn number(v: &serde_json::Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} missing in {v}"))
}

/// What hp2xx says of an HPGL file: (instructions ignored, unexpected
/// events, pens used).
fn read_hpgl(hp2xx: &std::ffi::OsStr, dir: &TempDir, file: &str) -> (f64, f64, Vec<f64>) {
    let out = std::process::Command::new(hp2xx)
        .current_dir(dir.path())
        .args(["-m", "svg", "-f", "hp2xx.svg", file])
        .output()
        .expect("hp2xx runs");
    let report = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(out.status.success(), "{report}");
    let line = |key: &str| -> Vec<f64> {
        report
            .lines()
            .find_map(|l| l.trim().strip_prefix(key))
            .unwrap_or_else(|| panic!("no '{key}' in:\n{report}"))
            .split(|c: char| !(c.is_ascii_digit() || c == '.'))
            .filter(|t| !t.is_empty() && *t != ".")
            .map(|t| t.parse().unwrap())
            .collect()
    };
    (
        line("HPGL command(s) ignored:")[0],
        line("Unexpected event(s):")[0],
        line("Pens used:"),
    )
}

#[test]
fn every_built_in_device_is_read_by_its_reader() {
    let dir = with_two_pens();
    let ink = number(&stats_json(&dir, "in.svg"), "pen_down_mm");
    if let Some(python) = interpreter("MOYO_PYTHON") {
        for (device, pen) in [("grbl-servo", "spindle"), ("grbl-z", "z"), ("marlin", "z")] {
            let file = format!("{device}.gcode");
            moyo(&dir)
                .args(["plot", "in.svg", "--device", device, "-o", &file])
                .assert()
                .success();
            let r = read_gcode(&python, &dir.path().join(&file), pen);
            assert_eq!(r["strokes"], 3, "{device}: {r}");
            assert_eq!(r["rapid_down"], 0, "{device}: {r}");
            assert_eq!(r["pauses_down"], 0, "{device}: {r}");
            assert_eq!(r["pen_up_at_end"], true, "{device}: {r}");
            // Two tool changes and pen 2's `!`: three stops.
            assert_eq!(r["pauses"], 3, "{device}: {r}");
            let drawn = number(&r, "drawn_mm");
            assert!(
                (drawn - ink).abs() < 0.005 * ink,
                "{device}: {drawn} vs {ink}"
            );
            let text = fs::read_to_string(dir.path().join(&file)).unwrap();
            match device {
                // Arcs: the circle in a few moves.
                "grbl-z" => {
                    assert!(number(&r, "arcs") >= 2.0, "{r}");
                    // Pen 2 down at +H20 of −0.5…0.5, drawing at 40 % of 8000.
                    assert!(text.contains("G1 Z-0.3 F600\n") && text.contains(" F3200\n"));
                    // +D300 is a 0.3 s dwell before pen 2.
                    assert!(text.contains("G4 P0.3\n"), "{text}");
                }
                "marlin" => assert!(text.contains(" G4 P300*"), "{text}"),
                _ => {}
            }
            insta::assert_snapshot!(format!("device_{device}"), text);
        }
    }
    if let Some(hp2xx) = interpreter("MOYO_HP2XX") {
        for device in ["hp7475a", "roland-dxy", "drag-knife"] {
            let file = format!("{device}.plt");
            moyo(&dir)
                .args(["plot", "in.svg", "--device", device, "-o", &file])
                .assert()
                .success();
            let (ignored, unexpected, pens) = read_hpgl(&hp2xx, &dir, &file);
            assert_eq!((ignored, unexpected), (0.0, 0.0), "{device}");
            assert_eq!(pens, [1.0, 2.0], "{device}");
            let text = fs::read_to_string(dir.path().join(&file)).unwrap();
            // Pen 2 after its pause, at 40 % of the device's velocity.
            assert!(
                text.contains("CO\"pause before pen 2\";\nSP2;\nVS"),
                "{text}"
            );
            assert!(text.ends_with("PU0,0;\nSP0;\n"), "{device}");
            insta::assert_snapshot!(format!("device_{device}"), text);
        }
    }
}

#[test]
fn refill_runs_never_exceed_their_length_and_never_stop_with_the_pen_down() {
    let Some(python) = interpreter("MOYO_PYTHON") else {
        return;
    };
    let dir = with_two_pens();
    let ink = number(&stats_json(&dir, "in.svg"), "pen_down_mm");
    moyo(&dir)
        .args(["plot", "in.svg", "--refill", "60", "-o", "refill.gcode"])
        .assert()
        .success();
    let r = read_gcode(&python, &dir.path().join("refill.gcode"), "spindle");
    let runs: Vec<f64> = r["runs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!(runs.iter().all(|&run| run <= 60.0 + 0.01), "{runs:?}");
    assert!(runs.len() >= (ink / 60.0).ceil() as usize, "{runs:?}");
    assert_eq!(r["pauses_down"], 0, "{r}");
    assert!((number(&r, "drawn_mm") - ink).abs() < 0.005 * ink, "{r}");

    // With a refill place: the pen dips there instead of stopping.
    moyo(&dir)
        .args(["plot", "in.svg", "--refill", "60", "--refill-at", "-15,20"])
        .args(["-o", "dip.gcode"])
        .assert()
        .success();
    let dip = fs::read_to_string(dir.path().join("dip.gcode")).unwrap();
    let paused = fs::read_to_string(dir.path().join("refill.gcode")).unwrap();
    let refills = paused.matches("M0 ; refill pen").count();
    assert!(refills >= 8, "{runs:?}");
    // Each a travel to the well (its feed written when it changes), the
    // pen down and up.
    let dips: Vec<&str> = dip.split("; refill\nG1 X-15 Y20").skip(1).collect();
    assert_eq!(dips.len(), refills, "{dip}");
    for d in dips {
        assert!(d.starts_with(" F4000\nM3 S1000\nG4 P0.15\nM5\n"), "{d}");
    }
    assert!(!dip.contains("M0 ; refill"));
}

#[test]
fn a_resumed_plot_and_what_it_skips_make_the_whole() {
    let Some(python) = interpreter("MOYO_PYTHON") else {
        return;
    };
    let dir = with_two_pens();
    moyo(&dir)
        .args(["plot", "in.svg", "-o", "whole.gcode"])
        .assert()
        .success();
    let whole = number(
        &read_gcode(&python, &dir.path().join("whole.gcode"), "spindle"),
        "drawn_mm",
    );
    for from in [0.5, 100.0, 240.0, 300.0] {
        moyo(&dir)
            .args(["plot", "in.svg", "--from-distance", &from.to_string()])
            .args(["-o", "rest.gcode"])
            .assert()
            .success();
        let rest = read_gcode(&python, &dir.path().join("rest.gcode"), "spindle");
        let drawn = number(&rest, "drawn_mm");
        assert!(
            (drawn + from - whole).abs() < 0.01,
            "{from}: {drawn} + {from} vs {whole}"
        );
    }
}

#[test]
fn a_scene_carries_its_device_into_the_plot() {
    let dir = tempfile::tempdir().unwrap();
    let scene = r#"
version = 1
[page]
size = "A5"
[[pens]]
number = 1
name = "+S50 fine"
color = "black"
[[layers]]
name = "ring"
[[layers.paths]]
points = [[20, 20], [80, 20], [80, 80], [20, 80], [20, 20]]
[device]
profile = "grbl-z"
[device.gcode]
header = ["; my router"]
"#;
    fs::write(dir.path().join("design.toml"), scene).unwrap();
    moyo(&dir)
        .args(["render", "design.toml", "-o", "design.svg"])
        .assert()
        .success();
    // The label carries the code where AxiDraw reads it.
    let svg = fs::read_to_string(dir.path().join("design.svg")).unwrap();
    assert!(svg.contains("inkscape:label=\"1+S50 fine\""), "{svg}");
    moyo(&dir)
        .args(["plot", "design.svg", "-o", "design.gcode"])
        .assert()
        .success();
    let g = fs::read_to_string(dir.path().join("design.gcode")).unwrap();
    assert!(g.contains("; my router\nG0 Z3\n"), "{g}");
    assert!(g.contains(" F4000\n"), "+S50 of grbl-z's 8000: {g}");
    // An SVG written from it, or HPGL, takes nothing from a G-code device.
    moyo(&dir)
        .args(["plot", "design.svg", "--sort", "-o", "sorted.svg"])
        .assert()
        .success();
    let out = moyo(&dir)
        .args(["plot", "design.svg", "-o", "design.plt"])
        .assert()
        .success()
        .get_output()
        .stderr
        .clone();
    assert!(String::from_utf8_lossy(&out).contains("its [device] is for another language"));
    // --device wins over the scene's.
    moyo(&dir)
        .args([
            "plot",
            "design.svg",
            "--device",
            "grbl-servo",
            "-o",
            "servo.gcode",
        ])
        .assert()
        .success();
    let g = fs::read_to_string(dir.path().join("servo.gcode")).unwrap();
    assert!(g.contains("M3 S1000") && !g.contains("my router"));
}

#[test]
fn bad_devices_are_refused_and_nothing_is_written() {
    let dir = with_two_pens();
    fs::write(
        dir.path().join("typo.toml"),
        "profile = \"grbl-servo\"\n[gcode]\ntool_change = \"M0 ; pen {pne}\"\n",
    )
    .unwrap();
    let cases: [(&[&str], &str); 5] = [
        (
            &["--device", "grbl"],
            "--device: 'grbl' is neither a built-in profile (grbl-servo",
        ),
        (
            &["--device", "typo.toml"],
            "device.gcode.tool_change: unknown placeholder {pne}; allowed here: {pen}, {name}, {layer}, {x}, {y}",
        ),
        (
            &["--device", "hp7475a", "--format", "gcode"],
            "the output is G-code, but the device is an HPGL machine",
        ),
        (&["--device", "drag-knife", "--format", "svg"], "--device: writes G-code or HPGL"),
        (&["--refill", "0"], "--refill: must be at least 0.1 mm"),
    ];
    for (args, message) in cases {
        let out = moyo(&dir)
            .args(["plot", "in.svg", "-o", "out.gcode"])
            .args(args)
            .assert()
            .failure()
            .get_output()
            .stderr
            .clone();
        let stderr = String::from_utf8_lossy(&out);
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert!(!dir.path().join("out.gcode").exists(), "{args:?}");
    }

    // A drawing larger than the machine's travel (the HP 7475A takes
    // 0…16158 units; a 500 mm wide line needs 20000).
    fs::write(
        dir.path().join("wide.svg"),
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="520mm" height="100mm"
            viewBox="0 0 520 100"><path d="M 10 50 H 510" stroke="black"/></svg>"#,
    )
    .unwrap();
    let out = moyo(&dir)
        .args(["plot", "wide.svg", "--device", "hp7475a", "-o", "wide.plt"])
        .assert()
        .failure()
        .get_output()
        .stderr
        .clone();
    assert!(String::from_utf8_lossy(&out).contains("outside the device range 0…16158"));
    assert!(!dir.path().join("wide.plt").exists());
}

#[test]
fn devices_lists_and_prints_the_profiles() {
    let dir = tempfile::tempdir().unwrap();
    let out = moyo(&dir)
        .arg("devices")
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let list = String::from_utf8_lossy(&out);
    for name in [
        "grbl-servo",
        "grbl-z",
        "marlin",
        "hp7475a",
        "roland-dxy",
        "drag-knife",
    ] {
        assert!(list.lines().any(|l| l.starts_with(name)), "{list}");
    }
    // A printed profile is one to start from: it resolves as it is.
    let out = moyo(&dir)
        .args(["devices", "marlin"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    fs::write(dir.path().join("mine.toml"), &out).unwrap();
    fs::write(dir.path().join("in.svg"), TWO_PENS).unwrap();
    moyo(&dir)
        .args(["plot", "in.svg", "--device", "mine.toml", "-o", "out.gcode"])
        .assert()
        .success();
    assert!(fs::read_to_string(dir.path().join("out.gcode"))
        .unwrap()
        .starts_with("N0 M110 N0*"));
}
