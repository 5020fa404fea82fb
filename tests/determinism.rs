//! Determinism: the same description and seed give the same bytes; the
//! seed matters; each tree draws from its own random stream, so editing one
//! part of a design leaves the rest exactly as it was; and the description
//! embedded in the SVG reopens as the design that was rendered.

use std::collections::BTreeMap;

use proptest::prelude::*;

use moyo::embedded_description;
use moyo::motif::Library;
use moyo::project::{self, Rendered};
use moyo::spec::{Format, SceneSpec, TreeOverride, TreeParams, ValidSpec};
use moyo::templates;

use crate::rendered;

/// A template without its plot stages: these tests are about generation
/// (per-layer random streams), and hidden-line removal rightly lets a
/// change in a front layer change what shows of the layers behind it.
/// The CLI tests cover determinism of the full pipeline.
fn template(name: &str) -> SceneSpec {
    let mut spec = templates::get(name).unwrap().spec().unwrap().into_inner();
    spec.plot = moyo::spec::PlotSpec::none();
    spec
}

/// Validates and renders a description built or changed in code.
fn render(spec: &SceneSpec) -> Rendered {
    let spec = spec.clone().validate().unwrap_or_else(|e| panic!("{e}"));
    project::render(&spec).unwrap_or_else(|e| panic!("{e}"))
}

/// Dump lines grouped by layer id, in order.
fn lines_by_layer(dump: &str) -> BTreeMap<String, Vec<String>> {
    let mut map: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for line in dump.lines() {
        let layer = line.split('\t').next().unwrap().to_string();
        map.entry(layer).or_default().push(line.to_string());
    }
    map
}

/// Dump lines whose path id does not start with `prefix`.
fn lines_outside(dump: &str, prefix: &str) -> Vec<String> {
    dump.lines()
        .filter(|l| !l.split('\t').nth(1).unwrap().starts_with(prefix))
        .map(str::to_string)
        .collect()
}

#[test]
fn default_template_renders_byte_identical_twice() {
    let a = render(&template(templates::DEFAULT));
    // A fresh parse, so nothing is shared between the two renders.
    let b = render(&template(templates::DEFAULT));
    assert!(a.svg.len() > 1000);
    assert!(a.svg == b.svg, "two renders of the default template differ");
    assert_eq!(a.dump(3), b.dump(3));
}

#[test]
fn different_seeds_give_different_svg_in_every_layer() {
    let mut spec = template(templates::DEFAULT);
    spec.seed = 1;
    let one = render(&spec);
    spec.seed = 2;
    let two = render(&spec);
    assert!(one.svg != two.svg);
    // Every layer of the template has jitter, so every layer must change,
    // not only the embedded seed.
    let (a, b) = (lines_by_layer(&one.dump(3)), lines_by_layer(&two.dump(3)));
    assert_eq!(a.keys().collect::<Vec<_>>(), b.keys().collect::<Vec<_>>());
    assert!(a.len() >= 3, "{:?}", a.keys());
    for (layer, lines) in &a {
        assert_ne!(lines, &b[layer], "layer {layer} ignores the seed");
    }
}

#[test]
fn changing_the_last_layer_leaves_the_other_layers_unchanged() {
    let spec = template("tomesode-hem");
    let before = render(&spec);
    let last_id = before.scene.layers.last().unwrap().id.clone();

    let mut changed = spec.clone();
    let last = changed.layers.last_mut().unwrap();
    for set in &mut last.trees {
        set.params.generations = Some(set.params.generations.unwrap_or(6) - 1);
        set.params.ang1 = Some(set.params.ang1.unwrap_or(8.0) + 5.0);
        set.count += 1;
    }
    let after = render(&changed);

    let (a, b) = (
        lines_by_layer(&before.dump(3)),
        lines_by_layer(&after.dump(3)),
    );
    assert!(a.len() >= 3, "{:?}", a.keys());
    // The change is real...
    assert_ne!(a[&last_id], b[&last_id], "the last layer did not change");
    // ...and reaches nothing else, path for path.
    for (layer, lines) in a.iter().filter(|(id, _)| **id != last_id) {
        assert_eq!(lines, &b[layer], "layer {layer} changed");
    }
}

#[test]
fn changing_the_first_layer_leaves_the_other_layers_unchanged() {
    let spec = template("tomesode-hem");
    let before = render(&spec);
    let first_id = before.scene.layers[0].id.clone();

    let mut changed = spec.clone();
    changed.layers[0].trees[0].count += 2;
    changed.layers[0].trees[0].params.ratio2 = Some(0.3);
    let after = render(&changed);

    let (a, b) = (
        lines_by_layer(&before.dump(3)),
        lines_by_layer(&after.dump(3)),
    );
    assert_ne!(a[&first_id], b[&first_id]);
    for (layer, lines) in a.iter().filter(|(id, _)| **id != first_id) {
        assert_eq!(lines, &b[layer], "layer {layer} changed");
    }
}

#[test]
fn removing_a_layer_leaves_the_other_layers_unchanged() {
    let spec = template("tomesode-hem");
    let before = render(&spec);
    let mut changed = spec.clone();
    let removed = changed.layers.remove(1);
    let after = render(&changed);
    let removed_id = before.scene.layers[1].id.clone();
    assert_eq!(before.scene.layers[1].name, removed.name);

    let (a, b) = (
        lines_by_layer(&before.dump(3)),
        lines_by_layer(&after.dump(3)),
    );
    assert!(!b.contains_key(&removed_id));
    for (layer, lines) in a.iter().filter(|(id, _)| **id != removed_id) {
        assert_eq!(lines, &b[layer], "layer {layer} changed");
    }
}

#[test]
fn changing_one_tree_set_leaves_its_neighbours_unchanged() {
    // The middle layer of tomesode-hem holds two sets, `pine` and `twin`.
    let spec = template("tomesode-hem");
    let (li, set) = spec
        .layers
        .iter()
        .enumerate()
        .find_map(|(i, l)| (l.trees.len() >= 2).then_some((i, l.trees.len() - 1)))
        .expect("a layer with two tree sets");
    let before = render(&spec);
    let prefix = format!(
        "{}.{}.",
        before.scene.layers[li].id,
        spec.layers[li].trees[set]
            .id
            .clone()
            .unwrap_or_else(|| format!("trees-{set}"))
    );

    let mut changed = spec.clone();
    changed.layers[li].trees[set].params.ang2 = Some(20.0);
    changed.layers[li].trees[set].params.trunk = Some(30.0);
    let after = render(&changed);

    let (a, b) = (before.dump(3), after.dump(3));
    assert_ne!(a, b, "the change did not show");
    assert_eq!(lines_outside(&a, &prefix), lines_outside(&b, &prefix));
}

#[test]
fn overriding_one_tree_leaves_its_siblings_unchanged() {
    let mut spec = template("tomesode-hem");
    // The front layer's first set, with at least three trees.
    let set = &mut spec.layers[0].trees[0];
    set.count = set.count.max(3);
    set.overrides.retain(|o| o.id != "tree-1");
    let set_name = set.id.clone().unwrap_or_else(|| "trees-0".into());
    let before = render(&spec);

    let mut changed = spec.clone();
    changed.layers[0].trees[0].overrides.push(TreeOverride {
        id: "tree-1".into(),
        root: None,
        rotate: Some(10.0),
        scale: None,
        params: TreeParams {
            generations: Some(3),
            ..TreeParams::default()
        },
    });
    let after = render(&changed);

    let tree = format!("{}.{set_name}.tree-1.", before.scene.layers[0].id);
    let (a, b) = (before.dump(3), after.dump(3));
    assert!(a.contains(&tree), "no paths with ids {tree}*");
    assert_ne!(a, b);
    assert_eq!(lines_outside(&a, &tree), lines_outside(&b, &tree));
}

/// Renders `spec` with `library`.
fn render_with(spec: &SceneSpec, library: &Library) -> Rendered {
    let spec = spec.clone().validate().unwrap_or_else(|e| panic!("{e}"));
    project::render_with_progress(&spec, library, &mut |_| {}).unwrap_or_else(|e| panic!("{e}"))
}

/// The description embedded in the SVG of `spec` parses back to `spec`,
/// and renders to the same SVG.
fn assert_embedded_round_trip(spec: &SceneSpec, library: &Library) {
    assert_reopens_as_rendered(spec, library, &render_with(spec, library));
}

/// The description embedded in `rendered`, the SVG of `spec`, parses back
/// to `spec`, and renders afresh to the same SVG.
fn assert_reopens_as_rendered(spec: &SceneSpec, library: &Library, rendered: &Rendered) {
    let text = embedded_description(&rendered.svg).expect("the SVG embeds its description");
    let back = SceneSpec::parse(&text, Format::Toml).unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert_eq!(&back, spec, "{text}");
    assert!(
        render_with(&back, library).svg == rendered.svg,
        "the reopened design renders differently"
    );
}

#[test]
fn embedded_description_of_every_template_parses_back() {
    // The template's render (with its built-in files, as `Template::render`
    // renders it) comes from the cache; its reopened description is
    // rendered here.
    for (t, r) in rendered::plotted() {
        assert_reopens_as_rendered(&t.spec().unwrap(), &t.library().unwrap(), r);
    }
}

#[test]
fn embedded_description_survives_awkward_text() {
    // "]]>" would end a CDATA section; "<", "&" and quotes are XML-special;
    // the floats are not exactly representable in decimal.
    let text = r##"version = 1
title = "a ]]> b <g> & \"quoted\" ]]]]>> 模様"
description = """two
lines ]]>"""
seed = 9223372036854775807

[page]
size = [123.456, 98.7654321]
margin = [1.1, 2.2, 3.3, 4.4]

[[pens]]
number = 999
name = "pen ]]> & <"
color = "#abc"
width = 0.1

[[layers]]
name = "layer ]]> one"
pen = 999
depth = -3

[layers.limbs]
fill = "red"
bow = -0.3333333333333333

[[layers.trees]]
rule = "tree6"
count = 2
centre = [[10.1, 80.3], [100.00000000000001, 0.30000000000000004]]
rotate = 1e-7

[layers.trees.params]
generations = 3
ratio1 = 0.1
base = [[0, 0], [0.1, 0.2], [-0.3, 0.4], [0.5, 3.0]]

[[layers.trees.overrides]]
id = "tree-1"
root = [50.5, 60.25]
rotate = -0.0
"##;
    let spec = SceneSpec::parse(text, Format::Toml).unwrap_or_else(|e| panic!("{e}"));
    assert_embedded_round_trip(&spec, &Library::new());
}

#[test]
fn embedded_description_of_a_json_scene_parses_back() {
    let json = r#"{"version": 1, "seed": 42,
        "layers": [{"name": "j", "trees": [{"rule": "tree3", "count": 3,
            "centre": [[20, 200], [100, 180], [190, 210]],
            "params": {"generations": 4, "jitter_angle": 12.5}}]}]}"#;
    let spec = SceneSpec::parse(json, Format::Json).unwrap();
    assert_embedded_round_trip(&spec, &Library::new());
}

/// A small scene with arbitrary (valid) numbers.
fn arbitrary_scene() -> impl Strategy<Value = ValidSpec> {
    (
        0..=i64::MAX as u64,
        0u32..=8,
        1u32..=4,
        0usize..8,
        -180.0f64..=180.0,
        0.05f64..=1.5,
        0.0f64..=45.0,
        prop::array::uniform4((-200.0f64..=200.0, 0.0f64..=300.0)),
    )
        .prop_map(
            |(seed, precision, count, rule, ang1, ratio1, jitter, centre)| {
                let rule = format!("tree{}", rule + 1);
                let centre: Vec<String> = centre
                    .iter()
                    .map(|(x, y)| format!("[{x:?}, {y:?}]"))
                    .collect();
                let text = format!(
                    "version = 1\nseed = {seed}\n[output]\nprecision = {precision}\n\
                     [[layers]]\nname = \"p\"\n[[layers.trees]]\nrule = \"{rule}\"\n\
                     count = {count}\ncentre = [{}]\n[layers.trees.params]\n\
                     generations = 4\nang1 = {ang1:?}\nratio1 = {ratio1:?}\n\
                     jitter_angle = {jitter:?}\n",
                    centre.join(", ")
                );
                SceneSpec::parse(&text, Format::Toml).unwrap_or_else(|e| panic!("{e}\n{text}"))
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn embedded_description_round_trips(spec in arbitrary_scene()) {
        let rendered = render(&spec);
        let text = embedded_description(&rendered.svg).expect("embedded description");
        let back = SceneSpec::parse(&text, Format::Toml).unwrap();
        prop_assert_eq!(&back, &spec);
        // Rendering is a function of the description: again, and from the
        // reopened description, the bytes are the same.
        prop_assert!(render(&spec).svg == rendered.svg);
        prop_assert!(render(&back).svg == rendered.svg);
    }
}
