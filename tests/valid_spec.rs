//! Descriptions built in code, as a library user may: every one either
//! fails validation naming a field, or renders without a panic.
//!
//! A small scene with every family is the base; each case sets one to four
//! "knobs" (a field of the spec) to an arbitrary nasty value — NaN,
//! infinities, zero, huge counts, extreme seeds, empty lists — and then
//! validates and, if valid, renders under a small path budget.

use moyo::spec::{Format, MotifKind, MotifRef, SceneSpec};
use moyo::Error;
use proptest::prelude::*;

const BASE: &str = r#"
version = 1
seed = 3
[limits]
max_paths = 20000
[[layers]]
name = "front"
[[layers.trees]]
rule = "tree1"
count = 2
centre = [[20, 200], [150, 210]]
params = { generations = 3, trunk = 20 }
flowers = { motifs = ["ume", "kiku"], width = 8 }
leaves = { ring = { motifs = ["leaf"], count = 3, spacing = 5, width = 4 }, joints = { motifs = ["momiji"], width = 4 } }
[[layers.paths]]
d = "M 0 0 L 10 0 L 10 5 Z"
along = [[10, 20], [180, 30]]
count = 3
[[layers]]
name = "back"
[layers.background]
composite = 1
count = 2
centre = [[20, 240], [180, 240]]
params = { generations = 2, trunk = 15 }
pattern = 2
motifs = ["seigaiha"]
width = 12
"#;

/// A nasty number: what a careless caller might put in a field.
fn nasty() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(-1.0),
        Just(1e-300),
        Just(1e300),
        Just(f64::MAX),
        Just(u32::MAX as f64),
        -1e6f64..1e6,
        -2.0f64..2.0,
    ]
}

type Knob = fn(&mut SceneSpec, f64);

/// Fields to set, as a user of the library can.
fn knobs() -> Vec<Knob> {
    vec![
        |s, v| s.seed = v.abs().min(u64::MAX as f64) as u64,
        |s, _| s.seed = u64::MAX,
        |s, v| s.limits.max_paths = v.abs().min(usize::MAX as f64) as usize,
        |s, v| s.output.precision = v.abs().min(255.0) as u8,
        |s, v| s.pens[0].width = v,
        |s, _| s.pens.clear(),
        |s, v| s.lines.upper = Some(vec![[0.0, v], [100.0, v]]),
        |s, _| s.lines.upper = Some(Vec::new()),
        |s, v| s.lines.lower = Some(vec![[v, v]]),
        |s, v| s.layers[0].depth = Some(v as i32),
        |s, v| s.layers[0].limbs.width = v,
        |s, v| s.layers[0].limbs.bow = v,
        |s, v| s.layers[0].trees[0].count = v.abs().min(u32::MAX as f64) as u32,
        |s, _| s.layers[0].trees[0].centre.clear(),
        |s, v| s.layers[0].trees[0].centre[1] = [v, v],
        |s, v| s.layers[0].trees[0].rotate = v,
        |s, v| s.layers[0].trees[0].params.generations = Some(v.abs().min(1e9) as u32),
        |s, v| s.layers[0].trees[0].params.trunk = Some(v),
        |s, v| s.layers[0].trees[0].params.ratio1 = Some(v),
        |s, v| s.layers[0].trees[0].params.ang2 = Some(v),
        |s, v| s.layers[0].trees[0].params.sub_generations = Some(v.abs().min(1e9) as u32),
        |s, v| {
            s.layers[0].trees[0].params.base = Some([[0.0, 0.0], [v, v], [0.0, 1.0], [1.0, 1.0]])
        },
        |s, _| {
            if let Some(f) = s.layers[0].trees[0].flowers.as_mut() {
                f.motifs.clear();
            }
        },
        |s, v| {
            if let Some(f) = s.layers[0].trees[0].flowers.as_mut() {
                f.width = v;
                f.motifs.push(MotifRef::Built(moyo::spec::BuiltMotif {
                    kind: MotifKind::Botan,
                    petals: Some(v.abs().min(1e9) as u32),
                    jitter: v,
                }));
            }
        },
        |s, v| {
            if let Some(r) = s.layers[0].trees[0].leaves.ring.as_mut() {
                r.count = v.abs().min(1e9) as u32;
                r.spacing = v;
            }
        },
        |s, _| {
            if let Some(j) = s.layers[0].trees[0].leaves.joints.as_mut() {
                j.motifs.clear();
            }
        },
        |s, v| s.layers[0].paths[0].count = Some(v.abs().min(u32::MAX as f64) as u32),
        |s, v| s.layers[0].paths[0].spacing = Some(v),
        |s, v| s.layers[0].paths[0].scale = v,
        |s, v| s.layers[0].paths[0].width = Some(v),
        |s, v| s.layers[0].paths[0].along = Some(vec![[v, 0.0], [0.0, v]]),
        |s, v| s.layers[0].paths[0].d = Some(format!("M 0 0 L {v} {v}")),
        |s, _| s.layers[0].paths[0].d = Some(String::new()),
        |s, v| {
            if let Some(b) = s.layers[1].background.as_mut() {
                b.width = v;
            }
        },
        |s, v| {
            if let Some(b) = s.layers[1].background.as_mut() {
                b.stamp_width = v;
                b.count = v.abs().min(u32::MAX as f64) as u32;
            }
        },
        |s, _| {
            if let Some(b) = s.layers[1].background.as_mut() {
                b.motifs.clear();
            }
        },
        |s, v| {
            if let Some(b) = s.layers[1].background.as_mut() {
                b.composite = v.abs().min(255.0) as u8;
                b.pattern = (v.abs() * 7.0).min(255.0) as u8;
            }
        },
        |s, _| s.layers.clear(),
        |s, _| {
            let copy = s.layers[0].clone();
            s.layers.push(copy);
        },
        |s, v| {
            s.adjust.push(moyo::spec::AdjustSpec {
                id: "front.trees-0.tree-0".into(),
                offset: Some([v, v]),
                rotate: Some(v),
                scale: Some(v),
                hide: false,
                motif: None,
            })
        },
        |s, _| {
            s.adjust.push(moyo::spec::AdjustSpec {
                id: "nothing".into(),
                offset: None,
                rotate: None,
                scale: None,
                hide: true,
                motif: None,
            })
        },
    ]
}

fn base() -> SceneSpec {
    SceneSpec::parse(BASE, Format::Toml)
        .unwrap_or_else(|e| panic!("{e}"))
        .into_inner()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn every_spec_is_refused_with_a_field_or_renders(
        edits in prop::collection::vec((0usize..1000, nasty()), 1..=4)
    ) {
        let knobs = knobs();
        let mut spec = base();
        for (k, v) in &edits {
            // Knobs index into layers that an earlier knob may have removed.
            let knob = knobs[k % knobs.len()];
            let mut trial = spec.clone();
            if std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| knob(&mut trial, *v))).is_ok() {
                spec = trial;
            }
        }
        match spec.validate() {
            Err(Error::Invalid { field, message, .. }) => {
                prop_assert!(!field.is_empty(), "no field: {message}");
            }
            Err(e) => prop_assert!(false, "validation failed without a field: {e}"),
            Ok(valid) => match moyo::project::render(&valid) {
                Ok(r) => prop_assert!(r.svg.starts_with("<?xml")),
                // Found while generating: still named.
                Err(Error::Budget { .. }) | Err(Error::Invalid { .. }) => {}
                Err(e) => prop_assert!(false, "render failed unexpectedly: {e}"),
            },
        }
    }
}

#[test]
fn the_base_scene_renders() {
    let spec = base().validate().unwrap();
    let r = moyo::project::render(&spec).unwrap();
    assert!(r.scene.path_count() > 20);
}
