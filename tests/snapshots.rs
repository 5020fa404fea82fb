//! Snapshot tests of the geometry, through the library and the path dump
//! (`Rendered::dump`): one per tree rule, one outline-style tree, one per
//! built-in motif, one per built-in template. Snapshots live in `tests/snapshots/`; see
//! tests/README.md for how to review a change.

use moyo::project::{self, Rendered};
use moyo::spec::{Format, SceneSpec};
use moyo::templates;

/// Decimals of the rule snapshots: 0.01 mm, enough to see any real change,
/// coarse enough to keep the files small.
const PRECISION: u8 = 2;

/// One tree of `rule`, upright in the middle of an A4 page: no jitter, no
/// region lines, every parameter given so that changed defaults do not
/// change these snapshots.
fn one_tree_scene(rule: &str, style: &str) -> String {
    // Tree8 bends by Ang1 between base-curve samples: a larger angle shows
    // its sprays the way the source uses it.
    let ang1 = if rule == "tree8" { 40 } else { 8 };
    format!(
        r#"version = 1
seed = 1

[page]
size = "A4"
margin = 10

[output]
precision = {PRECISION}

[[layers]]
name = "rule"

[layers.limbs]
style = "{style}"
width = 2
tip_width = 0.3
bow = 0.08

[[layers.trees]]
id = "{rule}"
rule = "{rule}"
count = 1
centre = [[40, 220], [150, 220]]

[layers.trees.params]
generations = 6
trunk = 20
ang1 = {ang1}
ang2 = 55
ang3 = 35
ratio1 = 0.85
ratio2 = 0.6
ratio3 = 0.6
sub_generations = 3
jitter_angle = 0
jitter_length = 0
"#
    )
}

fn render(text: &str) -> Rendered {
    let spec = SceneSpec::parse(text, Format::Toml).unwrap_or_else(|e| panic!("{e}\n{text}"));
    project::render(&spec).unwrap_or_else(|e| panic!("{e}"))
}

/// Structural checks that hold whatever the exact numbers: every line is
/// `layer<TAB>id<TAB>data`, every path starts with a move, stroke paths
/// are open and outline paths closed.
fn check_dump(dump: &str, style: &str) {
    assert!(!dump.is_empty());
    for line in dump.lines() {
        let fields: Vec<&str> = line.split('\t').collect();
        assert_eq!(fields.len(), 3, "{line}");
        let data = fields[2];
        assert!(data.starts_with("M "), "{line}");
        assert_eq!(data.matches('M').count(), 1, "one subpath per limb: {line}");
        match style {
            "stroke" => assert!(!data.contains('Z'), "stroke limb is closed: {line}"),
            "outline" => assert!(data.ends_with(" Z"), "outline limb is open: {line}"),
            _ => unreachable!(),
        }
    }
}

#[test]
fn every_tree_rule() {
    for n in 1..=8 {
        let rule = format!("tree{n}");
        let rendered = render(&one_tree_scene(&rule, "stroke"));
        let dump = rendered.dump(PRECISION);
        check_dump(&dump, "stroke");
        assert!(
            dump.lines()
                .all(|l| l.starts_with(&format!("rule\trule.{rule}.tree-0.limb-"))),
            "{dump}"
        );
        // A trunk and at least one branch.
        assert!(dump.lines().count() >= 2, "{rule}: {dump}");
        insta::assert_snapshot!(format!("tree{n}"), dump);
    }
}

#[test]
fn tree1_outline() {
    let rendered = render(&one_tree_scene("tree1", "outline"));
    let dump = rendered.dump(PRECISION);
    check_dump(&dump, "outline");
    // Same skeleton, other drawing: as many limbs as the stroke version.
    let strokes = render(&one_tree_scene("tree1", "stroke")).dump(PRECISION);
    assert_eq!(dump.lines().count(), strokes.lines().count());
    insta::assert_snapshot!("tree1-outline", dump);
}

#[test]
fn every_template() {
    for t in templates::ALL {
        let spec = t.spec().unwrap_or_else(|e| panic!("{}: {e}", t.name));
        let rendered = project::render(&spec).unwrap_or_else(|e| panic!("{}: {e}", t.name));
        let dump = rendered.dump(spec.output.precision);
        assert!(!dump.is_empty(), "{} draws nothing", t.name);
        assert_eq!(dump.lines().count(), rendered.scene.path_count());
        insta::assert_snapshot!(format!("template-{}", t.name), dump);
    }
}

/// Every built-in motif at its defaults, 20 mm wide, one path each.
#[test]
fn every_motif() {
    use kurbo::Affine;
    use moyo::motif::flora::{draw, MotifParams};
    use moyo::spec::MotifKind;
    use moyo::{Group, Layer, Margins, Page, PaperName, Scene, Seed, Style};

    let mut group = Group::new("motifs");
    for (i, kind) in MotifKind::ALL.into_iter().enumerate() {
        let d = draw(kind, &MotifParams::DEFAULT, &mut Seed(1).stream());
        let at = Affine::translate((25.0 + 25.0 * (i % 7) as f64, 25.0 + 40.0 * (i / 7) as f64));
        let path = d.to_path(at * Affine::scale_non_uniform(20.0, 20.0 * d.aspect));
        group.push_path(format!("{kind:?}").to_lowercase(), path, Style::default());
    }
    let scene = Scene {
        page: Page::named(
            PaperName::A4,
            moyo::Orientation::Landscape,
            Margins::uniform(10.0),
        ),
        pens: Vec::new(),
        layers: vec![Layer {
            id: "motifs".into(),
            name: "motifs".into(),
            pen: 1,
            depth: 0,
            content: group,
        }],
        description: None,
    };
    let dump = moyo::output::path_dump(&scene, PRECISION);
    assert_eq!(dump.lines().count(), MotifKind::ALL.len());
    insta::assert_snapshot!("motifs", dump);
}
