//! Text imported in single strokes: where it lands and at what size,
//! anchors, inherited sizes and units, white space, transforms and `use`,
//! the pen its paint chooses, and what is skipped or boxed, with its
//! warnings.

use kurbo::{BezPath, PathEl, Rect, Shape};

use super::super::test_support::{doc, import, paths};
use super::CAP_PER_EM;
use crate::scene::Color;

/// The one path of `body`'s document, with the warnings.
fn one_text(body: &str) -> (BezPath, Vec<String>) {
    let imported = import(&doc(body));
    let all = paths(&imported.scene);
    assert_eq!(all.len(), 1, "{body}: {all:?}");
    assert_eq!(all[0].2.fill, None, "glyphs are lines");
    (all[0].1.clone(), imported.warnings)
}

fn bounds(body: &str) -> Rect {
    one_text(body).0.bounding_box()
}

fn near(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn a_text_stands_on_its_baseline_at_its_x_with_the_cap_height_of_its_size() {
    let (path, warnings) = one_text(r#"<text x="10" y="50" font-size="10">HI</text>"#);
    let b = path.bounding_box();
    let cap = 10.0 * CAP_PER_EM;
    assert!(
        near(b.y1, 50.0, 1e-4) && near(b.y0, 50.0 - cap, 1e-4),
        "{b:?}"
    );
    assert!(b.x0 > 10.0 && b.x0 < 11.5, "{b:?}");
    // Each letter's strokes are subpaths: H three, I one.
    let moves = path
        .elements()
        .iter()
        .filter(|e| matches!(e, PathEl::MoveTo(_)))
        .count();
    assert_eq!(moves, 4);
    assert_eq!(
        warnings,
        ["1 text element drawn in moyo's single-stroke Hershey Sans in place of the document's font"]
    );
}

#[test]
fn text_anchor_sets_each_chunk_by_its_start_middle_or_end() {
    let middle = bounds(r#"<text x="100" y="50" font-size="10" text-anchor="middle">HOH</text>"#);
    assert!(near(middle.center().x, 100.0, 1e-4), "{middle:?}");
    let end = bounds(r#"<text x="100" y="50" style="font-size:10px;text-anchor:end">HOH</text>"#);
    assert!(end.x1 < 100.0 && end.x1 > 98.0, "{end:?}");
    assert!(near(end.width(), middle.width(), 1e-4));
    // An inherited anchor; a tspan with its own x starts a chunk of its own.
    let lines = bounds(
        r#"<g text-anchor="middle"><text font-size="10"><tspan x="100" y="20">HOH</tspan><tspan x="100" y="40">H</tspan></text></g>"#,
    );
    assert!(near(lines.center().x, 100.0, 1e-4), "{lines:?}");
    assert!(near(lines.y1, 40.0, 1e-4), "{lines:?}");
}

#[test]
fn sizes_are_inherited_and_read_in_any_unit() {
    let cap = |body: &str| bounds(body).height();
    let h = |size: &str| format!(r#"<text x="10" y="50" font-size="{size}">H</text>"#);
    assert!(near(cap(&h("10")), 7.0, 1e-4));
    assert!(near(cap(&h("10px")), 7.0, 1e-4));
    // 96 px to the inch: 72 pt is 96 user units, 25.4 mm as many.
    assert!(near(cap(&h("72pt")), 96.0 * CAP_PER_EM, 1e-3));
    assert!(near(cap(&h("25.4mm")), 96.0 * CAP_PER_EM, 1e-3));
    // No size anywhere: CSS's medium, 16 px.
    assert!(near(
        cap(r#"<text x="10" y="50">H</text>"#),
        16.0 * CAP_PER_EM,
        1e-4
    ));
    // From a group's style, relative in a tspan, and a bad value ignored.
    let nested = r#"<g style="font-size:20px"><text x="10" y="80" font-size="oops"><tspan font-size="50%">H</tspan></text></g>"#;
    assert!(near(cap(nested), 10.0 * CAP_PER_EM, 1e-4));
    let em =
        r#"<text x="10" y="80" font-size="20"><tspan style="font-size:1.5em">H</tspan></text>"#;
    assert!(near(cap(em), 30.0 * CAP_PER_EM, 1e-4));
}

#[test]
fn white_space_collapses_unless_preserved_and_dx_dy_shift_the_pen() {
    let plain = one_text(r#"<text x="10" y="50" font-size="10">a b</text>"#).0;
    let spaced = one_text("<text x=\"10\" y=\"50\" font-size=\"10\">\n   a \t\n   b   </text>").0;
    assert_eq!(plain, spaced);
    let preserved =
        bounds(r#"<text x="10" y="50" font-size="10" xml:space="preserve">  a   b</text>"#);
    assert!(preserved.x0 > plain.bounding_box().x0 + 3.0);
    assert!(preserved.width() > plain.bounding_box().width() + 3.0);
    let shifted = bounds(r#"<text x="10" y="50" dx="5" dy="-3" font-size="10">a b</text>"#);
    let b = plain.bounding_box();
    assert!(near(shifted.x0, b.x0 + 5.0, 1e-4) && near(shifted.y1, b.y1 - 3.0, 1e-4));
}

#[test]
fn transforms_of_the_text_and_its_groups_and_each_use_place_it() {
    // (0, 0) → rotate 90° → translate: the baseline runs down from (50, 20),
    // the letter's top to the right.
    let turned = bounds(
        r#"<g transform="translate(50 20)"><text transform="rotate(90)" font-size="10">H</text></g>"#,
    );
    assert!(
        turned.x0 > 50.0 - 1e-4 && near(turned.x1, 57.0, 1e-4),
        "{turned:?}"
    );
    assert!(turned.y0 > 20.0 && turned.y1 < 30.0, "{turned:?}");
    // Drawn once where it stands and once more where a use puts it; not
    // at all when hidden or only defined.
    let imported = import(&doc(r##"<text id="t" x="10" y="20" font-size="10">A</text>
           <use href="#t" x="100" y="50"/>
           <text x="10" y="60" font-size="10" display="none">hidden</text>
           <defs><text id="d" x="10" y="70">defined</text></defs>"##));
    let all = paths(&imported.scene);
    assert_eq!(all.len(), 2, "{all:?}");
    let (a, b) = (all[0].1.bounding_box(), all[1].1.bounding_box());
    assert!(near(b.x0 - a.x0, 100.0, 1e-4) && near(b.y1 - a.y1, 50.0, 1e-4));
    // Counted as drawn: twice.
    assert!(
        imported.warnings[0].starts_with("2 text elements drawn in "),
        "{:?}",
        imported.warnings
    );
    // The text's id is its path's.
    let mut ids = Vec::new();
    imported.scene.visit_paths(|_, p, _| ids.push(p.id.clone()));
    assert_eq!(ids[0], "t");
}

#[test]
fn the_fill_chooses_the_pen_as_a_filled_paths_does() {
    let imported = import(&doc(
        r##"<path d="M0 0 L50 50" stroke="#ff0000" fill="none"/>
           <text x="10" y="20" font-size="10" fill="#ff0000">red</text>
           <text x="10" y="40" font-size="10" style="fill:#0000ff">blue</text>
           <text x="10" y="60" font-size="10">black</text>"##,
    ));
    let all = paths(&imported.scene);
    let pens: Vec<u32> = all.iter().map(|(pen, _, _)| *pen).collect();
    assert_eq!(pens, [1, 1, 2, 3]);
    let colours: Vec<Color> = imported.scene.pens.iter().map(|p| p.color).collect();
    assert_eq!(
        colours,
        [
            Color::rgb(255, 0, 0),
            Color::rgb(0, 0, 255),
            Color::rgb(0, 0, 0)
        ]
    );
    assert!(all.iter().all(|(_, _, style)| style.fill.is_none()));
}

#[test]
fn inkscape_text_lands_on_its_layers_pen_with_missing_characters_named() {
    let imported = import(include_str!("../../../../tests/fixtures/import/text.svg"));
    let scene = &imported.scene;
    let pens: Vec<(u32, &str, String)> = scene
        .pens
        .iter()
        .map(|p| (p.number, p.name.as_str(), p.color.to_string()))
        .collect();
    assert_eq!(
        pens,
        [
            (1, "black", "#000000".to_string()),
            (2, "red", "#c00000".to_string())
        ]
    );
    let mut by_id = std::collections::BTreeMap::new();
    scene.visit_paths(|l, p, t| {
        by_id.insert(p.id.clone(), (l.pen, (t * p.path.clone()).bounding_box()));
    });
    // The title: two lines, each centred on x = 105, on baselines 20 and
    // 280, 14.1 and 7.1 px tall (a millimetre a px here).
    let (pen, title) = by_id["title"];
    assert_eq!(pen, 1);
    assert!(near(title.center().x, 105.0, 1.5), "{title:?}");
    assert!(
        near(title.y0, 20.0 - 14.1111 * CAP_PER_EM, 1e-3),
        "{title:?}"
    );
    // (Kana reach a little below the baseline.)
    assert!(title.y1 > 280.0 && title.y1 < 280.5, "{title:?}");
    // The signature ends at (180, 260) in its own frame, turned a quarter
    // anticlockwise and moved 10 mm right with its layer: it runs up to
    // y = 260 at x = 190, the letters' tops to the left.
    let (pen, signed) = by_id["signature"];
    assert_eq!(pen, 2);
    assert!(near(signed.x1, 190.0, 1e-3), "{signed:?}");
    assert!(
        near(signed.width(), 5.64444 * CAP_PER_EM, 1e-3),
        "{signed:?}"
    );
    assert!(signed.y0 > 260.0 && signed.y0 < 261.0, "{signed:?}");
    assert!(signed.height() > 15.0, "{signed:?}");
    assert_eq!(
        imported.warnings,
        [
            "2 text elements drawn in moyo's single-stroke Hershey Sans in place of \
             'DejaVu Sans'; Purisa",
            "no single-stroke glyph for '秋', '庭': drawn as boxes",
        ]
    );
}

#[test]
fn flowed_text_and_text_on_a_path_are_skipped_with_warnings() {
    let imported = import(&doc(
        r##"<flowRoot><flowRegion><rect width="50" height="50"/></flowRegion><flowPara>flowed</flowPara></flowRoot>
           <path id="p" d="M0 50 L100 50" stroke="black"/>
           <text font-size="10"><textPath href="#p">along</textPath></text>
           <text x="10" y="20" font-size="10">kept<textPath href="#p">along</textPath></text>"##,
    ));
    assert_eq!(imported.scene.path_count(), 2);
    assert_eq!(
        imported.warnings[1..],
        [
            "skipped 1 flowed text element: flowed text (flowRoot) is not imported \
             (convert it to text, Inkscape's Text > Convert to Text, or to paths)",
            "skipped 2 text paths: text along a path (textPath) is not imported \
             (convert it to paths first)",
        ]
    );
}

#[test]
fn text_past_the_character_limit_is_skipped_with_a_warning() {
    let half = "x".repeat(6_000);
    let imported = import(&doc(&format!(
        r#"<text x="1" y="10" font-size="1">{half}</text>
           <text x="1" y="20" font-size="1">{half}</text>
           <text x="1" y="30" font-size="1">last</text>"#
    )));
    // The first and the last fit in 10,000 characters.
    assert_eq!(imported.scene.path_count(), 2);
    assert!(
        imported.warnings.contains(
            &"skipped 1 text element: past the first 10,000 characters of text, \
              the most moyo draws from one file"
                .to_string()
        ),
        "{:?}",
        imported.warnings
    );
}

#[test]
fn odd_text_draws_what_it_can_and_never_panics() {
    let cases = [
        // Empty, only spaces, a zero size, a nested text, a percentage.
        r#"<text x="1" y="10"></text><text x="1" y="10">   </text>"#,
        r#"<text x="1" y="10" font-size="0">zero</text>"#,
        r#"<text x="1" y="10" font-size="-5">negative</text>"#,
        r#"<text x="1" y="10"><text x="5" y="5">inner</text><tspan><tspan><a>deep</a></tspan></tspan></text>"#,
        r#"<text x="10%" y="10" dx="NaN" font-size="1e30px">big</text>"#,
        r#"<text x="1" y="10" style="font-size:;text-anchor:;fill:" d="M0 0">attrs</text>"#,
        r#"<text x="1" y="10" class="a&amp;b" data-x="&quot;&lt;">escaped</text>"#,
        r#"<svg:text xmlns:svg="http://www.w3.org/2000/svg" x="1" y="10">prefixed</svg:text>"#,
        r#"<clipPath id="c"><text x="1" y="10">clip</text></clipPath><rect width="5" height="5" clip-path="url(#c)" fill="red"/>"#,
    ];
    for body in cases {
        let _ = crate::input::import_svg(&doc(body), &crate::input::ImportOptions::DEFAULT);
    }
    // A text from an entity cannot be replaced where it stands.
    let svg = format!(
        "<!DOCTYPE svg [<!ENTITY t \"<text x='1' y='10'>A</text>\">]>{}",
        doc("&t;&t;")
    );
    let _ = crate::input::import_svg(&svg, &crate::input::ImportOptions::DEFAULT);
    // The odd ones that draw: a zero size draws nothing.
    let imported = import(&doc(cases[1]));
    assert_eq!(imported.scene.path_count(), 0);
    let imported = import(&doc(cases[3]));
    assert_eq!(imported.scene.path_count(), 1);
    let imported = import(&doc(cases[7]));
    assert_eq!(imported.scene.path_count(), 1);
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

    /// Any characters, sizes, positions and anchors: drawn or refused,
    /// never a panic, and a drawn text stays one path.
    #[test]
    fn any_text_content_and_attributes_import_without_panic(
        content in "\\PC{0,80}",
        size in "[-0-9.eEm%px ]{0,8}",
        x in "[-0-9.eE%]{0,6}",
        anchor in "(start|middle|end|bogus)",
    ) {
        let escaped = content
            .replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;");
        let body = format!(
            r#"<text x="{x}" y="50" font-size="{size}" text-anchor="{anchor}">{escaped}<tspan dy="2">{escaped}</tspan></text>"#
        );
        if let Ok(imported) =
            crate::input::import_svg(&doc(&body), &crate::input::ImportOptions::DEFAULT)
        {
            proptest::prop_assert!(imported.scene.path_count() <= 1);
        }
    }
}
