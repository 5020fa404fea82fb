//! Text on a layer: where it stands, its size, turn and alignment, the
//! note for missing characters, the path budget and the table's ranges.

use std::collections::BTreeMap;

use kurbo::{Affine, BezPath, Rect, Shape};

use crate::project::{build_scene, render};
use crate::spec::{Format, SceneSpec};

fn spec(body: &str) -> crate::error::Result<crate::spec::ValidSpec> {
    let text = format!("version = 1\nseed = 2\n[[layers]]\nname = \"l\"\n{body}");
    SceneSpec::parse(&text, Format::Toml)
}

/// The paths of a one-layer scene whose layer body is `body`, by id.
fn placed(body: &str) -> BTreeMap<String, BezPath> {
    let scene = build_scene(&spec(body).unwrap()).unwrap();
    let mut out = BTreeMap::new();
    for layer in &scene.layers {
        layer.content.visit_paths(Affine::IDENTITY, &mut |p, t| {
            assert_eq!(p.style.fill, None, "{}", p.id);
            out.insert(p.id.clone(), t * p.path.clone());
        });
    }
    out
}

fn bounds(paths: &BTreeMap<String, BezPath>) -> Rect {
    paths
        .values()
        .map(Shape::bounding_box)
        .reduce(|a, b| a.union(b))
        .unwrap()
}

#[test]
fn a_title_stands_on_its_baseline_at_its_size_one_path_per_letter() {
    let paths = placed("[[layers.text]]\ntext = \"HI moyo\"\nat = [20, 280]\nsize = 6\n");
    assert_eq!(
        paths.keys().collect::<Vec<_>>(),
        (0..6)
            .map(|i| format!("l.text-0.glyph-{i}"))
            .collect::<Vec<_>>()
            .iter()
            .collect::<Vec<_>>()
    );
    let h = paths["l.text-0.glyph-0"].bounding_box();
    assert!((h.y1 - 280.0).abs() < 1e-9 && (h.y0 - 274.0).abs() < 1e-9, "{h:?}");
    assert!(h.x0 > 20.0 && h.x0 < 21.5, "{h:?}");
}

#[test]
fn middle_alignment_centres_the_line_on_at_and_rotate_turns_it_about_at() {
    let body = "[[layers.text]]\ntext = \"HOH\"\nat = [100, 50]\nsize = 10\nalign = \"middle\"\n";
    let b = bounds(&placed(body));
    assert!((b.center().x - 100.0).abs() < 1e-9, "{b:?}");
    // Turned a quarter clockwise: the line runs down the page, centred on
    // y = 50, the letters' tops to the right of x = 100.
    let turned = bounds(&placed(&format!("{body}rotate = 90\n")));
    assert!((turned.center().y - 50.0).abs() < 1e-9, "{turned:?}");
    assert!(turned.x0 > 100.0 - 1e-9 && turned.x1 > 105.0, "{turned:?}");
    assert!((turned.height() - b.width()).abs() < 1e-9);
}

#[test]
fn missing_characters_are_drawn_as_boxes_and_noted() {
    let spec = spec("[[layers.text]]\ntext = \"秋の庭 — M.K. 2026\"\nat = [20, 280]\n").unwrap();
    let rendered = render(&spec).unwrap();
    let notes: Vec<&str> = rendered.notes.iter().map(|n| n.text.as_str()).collect();
    assert_eq!(
        notes,
        ["no single-stroke glyph for '秋', '庭': drawn as boxes"]
    );
    assert_eq!(rendered.notes[0].motif, "l.text-0");
}

#[test]
fn the_path_budget_counts_every_letter() {
    let body = "limits = { max_paths = 5 }\n";
    let text = format!(
        "version = 1\nseed = 2\n{body}[[layers]]\nname = \"l\"\n[[layers.text]]\ntext = \"abcdef\"\nat = [10, 10]\n"
    );
    let spec = SceneSpec::parse(&text, Format::Toml).unwrap();
    let e = build_scene(&spec).unwrap_err().to_string();
    assert!(e.contains("text l.text-0"), "{e}");
}

#[test]
fn the_table_is_checked_with_its_field_names() {
    let cases = [
        ("text = \"\"\nat = [0, 0]", "layers[0].text[0].text", "says nothing"),
        ("text = \"a\"\nat = [0, 0]\nsize = 0", "layers[0].text[0].size", "between 0.5 and 500"),
        ("text = \"a\"\nat = [0, 0]\nsize = 501", "layers[0].text[0].size", "between 0.5 and 500"),
        ("text = \"a\"\nat = [0, 1e9]", "layers[0].text[0].at", "within"),
        ("text = \"a\"\nat = [0, 0]\nrotate = 400", "layers[0].text[0].rotate", "between"),
        ("text = \"a\"\nat = [0, 0]\nline_height = 0", "layers[0].text[0].line_height", "between"),
        ("text = \"a\"\nat = [0, 0]\nletter_spacing = -11", "layers[0].text[0].letter_spacing", "between"),
        ("text = \"a\"\nat = [0, 0]\nfont = \"gothic\"", "font", "unknown variant"),
        ("text = \"a\"", "at", "missing field"),
    ];
    for (table, field, message) in cases {
        let e = spec(&format!("[[layers.text]]\n{table}\n")).unwrap_err().to_string();
        assert!(e.contains(field) && e.contains(message), "{table}: {e}");
    }
    let long = "a".repeat(crate::text::MAX_CHARS + 1);
    let e = spec(&format!("[[layers.text]]\ntext = \"{long}\"\nat = [0, 0]\n"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("layers[0].text[0].text") && e.contains("at most 10000"),
        "{e}"
    );
}
