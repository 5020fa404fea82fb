//! Vines through the binary: `--obj` writes the plant and its supports as
//! Wavefront OBJ that a real reader (trimesh, as Blender does: one object
//! per `o`) takes apart into watertight stems, quad leaves and supports in
//! millimetres with y up; `--obj` on a scene without a vine fails and
//! writes nothing; a broken vine table names its field.

use std::fs;

use predicates::prelude::*;

use crate::cli::{moyo, tempdir as dir};
use crate::plot_cli::interpreter;

/// Reads an OBJ with trimesh, one geometry per object, and prints JSON:
/// for each object its vertex and face counts, whether it is watertight,
/// its volume and its box.
const TRIMESH_CHECK: &str = r#"
import json, sys, trimesh
scene = trimesh.load(sys.argv[1], force="scene", split_objects=True, group_material=False)
out = {}
for name, g in scene.geometry.items():
    out[name] = {
        "vertices": int(len(g.vertices)),
        "faces": int(len(g.faces)),
        "watertight": bool(g.is_watertight),
        "volume": float(abs(g.volume)) if g.is_watertight else 0.0,
        "box": [float(v) for v in g.bounds.flatten()],
    }
print(json.dumps(out))
"#;

#[test]
fn the_obj_is_read_back_as_stems_leaves_and_supports() {
    let d = dir();
    moyo(&d)
        .args([
            "render",
            "-t",
            "vine-basic",
            "-o",
            "v.svg",
            "--obj",
            "v.obj",
        ])
        .assert()
        .success()
        .stderr(predicate::str::contains("v.obj"));
    let obj = fs::read_to_string(d.path().join("v.obj")).unwrap();
    assert!(obj.starts_with("# moyo: millimetres, right-handed, y up\n"));
    assert!(obj.contains("\ng stem-0\n") && obj.contains("\ng support-0\n"));
    assert!(obj.contains("\nl "), "stem axes as polylines");
    let Some(python) = interpreter("MOYO_PYTHON") else {
        return;
    };
    let out = std::process::Command::new(python)
        .arg("-c")
        .arg(TRIMESH_CHECK)
        .arg(d.path().join("v.obj"))
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "trimesh rejects the OBJ:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let parts: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let parts = parts.as_object().unwrap();
    let named = |p: &str| -> Vec<(&String, &serde_json::Value)> {
        parts.iter().filter(|(k, _)| k.starts_with(p)).collect()
    };
    assert!(!named("vine.vine.stem-").is_empty(), "{parts:?}");
    for (name, stem) in named("vine.vine.stem-") {
        assert_eq!(stem["watertight"], true, "{name} is a closed tube");
        // A tube of radius 2 (4π mm² across) at least one internode long.
        assert!(
            stem["volume"].as_f64().unwrap() > 60.0 * 4.0 * 3.1,
            "{name}"
        );
    }
    let leaves = named("vine.vine.leaf-").len();
    assert!(leaves > 5, "{leaves} leaves");
    for (_, leaf) in named("vine.vine.leaf-") {
        // A quad: four corners, two triangles.
        assert_eq!(
            (leaf["vertices"].as_u64(), leaf["faces"].as_u64()),
            (Some(4), Some(2))
        );
    }
    // The pole: radius 6 from y = 0 to 560 (mm, y up), watertight.
    let pole = &parts["vine.vine.support-0"];
    assert_eq!(pole["watertight"], true);
    let b: Vec<f64> = pole["box"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!(
        (b[1] - 0.0).abs() < 1e-6 && (b[4] - 560.0).abs() < 1e-6,
        "{b:?}"
    );
    assert!((b[3] - b[0] - 12.0).abs() < 0.1, "{b:?}");
    let volume = pole["volume"].as_f64().unwrap();
    assert!((volume / (std::f64::consts::PI * 36.0 * 560.0) - 1.0).abs() < 0.02);
}

#[test]
fn obj_needs_a_vine_and_writes_nothing_without_one() {
    let d = dir();
    moyo(&d)
        .args([
            "render",
            "-t",
            "lsystem-koch",
            "-o",
            "k.svg",
            "--obj",
            "k.obj",
        ])
        .assert()
        .failure()
        .stderr(predicate::str::starts_with("error: --obj"));
    assert!(!d.path().join("k.svg").exists() && !d.path().join("k.obj").exists());
}

#[test]
fn a_broken_vine_names_its_field_and_line() {
    let d = dir();
    fs::write(
        d.path().join("v.toml"),
        "version = 1\n[[layers]]\nname = \"v\"\n[[layers.vine]]\nangle = 95\n",
    )
    .unwrap();
    moyo(&d)
        .args(["render", "v.toml", "-o", "v.svg", "--obj", "v.obj"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("5:9: layers[0].vine[0].angle"))
        .stderr(predicate::str::contains("between 1 and 80"));
    assert!(!d.path().join("v.svg").exists() && !d.path().join("v.obj").exists());
}

/// A closed box 12 × 300 × 12 mm standing at x = 20, as an OBJ of quads.
const PILLAR: &str = "v 14 0 -6\nv 26 0 -6\nv 26 0 6\nv 14 0 6\n\
    v 14 300 -6\nv 26 300 -6\nv 26 300 6\nv 14 300 6\n\
    f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n";

fn scene_with_mesh(obj: &str) -> String {
    format!(
        "version = 1\n[[layers]]\nname = \"v\"\n[[layers.vine]]\ninternodes = 8\n\
         supports = [{{ kind = \"mesh\", obj = \"{obj}\" }}]\n"
    )
}

#[test]
fn a_vine_climbs_a_mesh_read_from_an_obj_file() {
    let d = dir();
    fs::write(d.path().join("pillar.obj"), PILLAR).unwrap();
    fs::write(d.path().join("v.toml"), scene_with_mesh("pillar.obj")).unwrap();
    moyo(&d)
        .args(["render", "v.toml", "-o", "v.svg", "--obj", "v.obj"])
        .assert()
        .success();
    let svg = fs::read_to_string(d.path().join("v.svg")).unwrap();
    assert!(
        svg.contains("id=\"v.vine-0.support-0\""),
        "the pillar is drawn"
    );
    let obj = fs::read_to_string(d.path().join("v.obj")).unwrap();
    // The pillar goes out as its 12 triangles.
    let support = obj.split("g support-0\n").nth(1).unwrap();
    assert_eq!(support.lines().filter(|l| l.starts_with("f ")).count(), 12);

    // A mesh with a hole is not a solid; a broken file names its line.
    let open = PILLAR.replace("f 4 8 5 1\n", "");
    fs::write(d.path().join("open.obj"), open).unwrap();
    fs::write(d.path().join("o.toml"), scene_with_mesh("open.obj")).unwrap();
    moyo(&d)
        .args(["render", "o.toml", "-o", "o.svg"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("error: mesh open.obj: "))
        .stderr(predicate::str::contains("not a closed mesh"))
        .stderr(predicate::str::contains("motif").not());
    fs::write(
        d.path().join("bad.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
    )
    .unwrap();
    fs::write(d.path().join("b.toml"), scene_with_mesh("bad.obj")).unwrap();
    moyo(&d)
        .args(["render", "b.toml", "-o", "b.svg"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("error: mesh bad.obj: "))
        .stderr(predicate::str::contains("line 4"));
    for f in ["o.svg", "b.svg"] {
        assert!(!d.path().join(f).exists());
    }
}
