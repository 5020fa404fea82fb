//! Laying text out: advances, the size of a capital, line breaks,
//! alignment, letter spacing, strokes as subpaths, Japanese and the
//! boxes that stand for missing characters.

use kurbo::{BezPath, PathEl, Rect, Shape};

use super::{layout, Align, Font, TextStyle};

fn style(size: f64) -> TextStyle {
    TextStyle::new(size)
}

fn bounds(paths: &[BezPath]) -> Rect {
    paths
        .iter()
        .map(Shape::bounding_box)
        .reduce(|a, b| a.union(b))
        .unwrap_or_default()
}

fn moves(path: &BezPath) -> usize {
    path.elements()
        .iter()
        .filter(|e| matches!(e, PathEl::MoveTo(_)))
        .count()
}

#[test]
fn wide_letters_advance_further_than_narrow_ones() {
    for font in [Font::Sans, Font::Script] {
        let s = TextStyle { font, ..style(5.0) };
        let mm = layout("MM", &s);
        let ii = layout("ii", &s);
        assert!(
            mm.width > 2.0 * ii.width,
            "{font:?}: {} vs {}",
            mm.width,
            ii.width
        );
        assert!(bounds(&mm.glyphs).width() > 2.0 * bounds(&ii.glyphs).width());
    }
}

#[test]
fn an_l_is_one_vertical_stroke_a_cap_height_long() {
    let l = layout("l", &style(7.0));
    assert_eq!(l.glyphs.len(), 1);
    let els = l.glyphs[0].elements();
    assert_eq!(els.len(), 2, "{els:?}");
    let (PathEl::MoveTo(a), PathEl::LineTo(b)) = (els[0], els[1]) else {
        panic!("{els:?}")
    };
    assert!((a.x - b.x).abs() < 1e-12, "vertical: {a:?} {b:?}");
    assert!(((a.y - b.y).abs() - 7.0).abs() < 1e-12, "{a:?} {b:?}");
    // From the cap line down to the baseline.
    assert!((a.y.min(b.y) + 7.0).abs() < 1e-12 && a.y.max(b.y).abs() < 1e-12);
}

#[test]
fn each_stroke_is_a_subpath_of_its_characters_path() {
    let h = layout("H", &style(5.0));
    assert_eq!(moves(&h.glyphs[0]), 3);
    let word = layout("Hi there", &style(5.0));
    // Seven letters, the space draws nothing.
    assert_eq!(word.glyphs.len(), 7);
    assert_eq!(
        moves(&word.path()),
        word.glyphs.iter().map(moves).sum::<usize>()
    );
}

#[test]
fn a_line_break_moves_the_baseline_down_by_the_line_height() {
    let s = TextStyle {
        line_height: 1.5,
        ..style(4.0)
    };
    let two = layout("H\nH", &s);
    assert_eq!(two.lines, 2);
    let (first, second) = (two.glyphs[0].bounding_box(), two.glyphs[1].bounding_box());
    assert!(
        (second.y1 - first.y1 - 6.0).abs() < 1e-12,
        "{first:?} {second:?}"
    );
    // The next line starts again at the anchor.
    assert!((second.x0 - first.x0).abs() < 1e-12);
    // A carriage return before the break draws nothing.
    assert_eq!(layout("H\r\nH", &s), two);
}

#[test]
fn alignment_puts_the_start_middle_or_end_of_each_line_on_the_anchor() {
    let at = |align| {
        let s = TextStyle {
            align,
            ..style(10.0)
        };
        layout("MOM\nH", &s)
    };
    let start = at(Align::Start);
    assert!(bounds(&start.glyphs).x0 > 0.0 && bounds(&start.glyphs).x0 < 3.0);
    let middle = at(Align::Middle);
    // Symmetric letters: each line's ink is centred on x = 0.
    let top = bounds(&middle.glyphs[..3]);
    let bottom = bounds(&middle.glyphs[3..]);
    assert!(top.center().x.abs() < 1e-9, "{top:?}");
    assert!(bottom.center().x.abs() < 1e-9, "{bottom:?}");
    let end = at(Align::End);
    let last = bounds(&end.glyphs[..3]);
    assert!(last.x1 < 0.0 && last.x1 > -3.0, "{last:?}");
    // Moved, not changed.
    assert_eq!(start.width, end.width);
    assert!((top.width() - bounds(&start.glyphs[..3]).width()).abs() < 1e-9);
}

#[test]
fn letter_spacing_adds_between_characters_only() {
    let plain = layout("abc", &style(5.0));
    let spaced = layout(
        "abc",
        &TextStyle {
            letter_spacing: 1.5,
            ..style(5.0)
        },
    );
    assert!((spaced.width - plain.width - 3.0).abs() < 1e-12);
}

#[test]
fn missing_characters_are_boxes_and_are_listed_once() {
    let text = layout("秋a秋\u{1F600}", &style(5.0));
    assert_eq!(text.missing, vec!['秋', '\u{1F600}']);
    assert_eq!(text.glyphs.len(), 4);
    let boxed = text.glyphs[0].bounding_box();
    assert!((boxed.height() - 5.0).abs() < 1e-12 && boxed.y1.abs() < 1e-12);
    assert!(boxed.width() > 2.0);
    assert_eq!(text.missing_list(), "'秋', '\u{1F600}'");
    let many: String = ('\u{9F00}'..'\u{9F10}').collect();
    assert!(layout(&many, &style(5.0))
        .missing_list()
        .ends_with(", and 6 more"));
}

#[test]
fn kana_and_the_kanji_there_are_are_drawn_at_the_size_of_capitals() {
    let text = layout("あア日本ー。", &style(10.0));
    assert!(text.missing.is_empty(), "{:?}", text.missing);
    assert_eq!(text.glyphs.len(), 6);
    let kana = text.glyphs[0].bounding_box();
    // About as tall as a capital, standing on the baseline.
    assert!(kana.height() > 8.0 && kana.height() < 12.0, "{kana:?}");
    assert!(kana.y1 > -1.0 && kana.y1 < 1.5, "{kana:?}");
    // A small kana is drawn smaller, on the same line.
    let small = layout("っ", &style(10.0)).glyphs[0].bounding_box();
    let big = layout("つ", &style(10.0)).glyphs[0].bounding_box();
    assert!(small.width() < 0.8 * big.width() && small.height() < 0.8 * big.height());
    assert!((small.y1 - big.y1).abs() < 1.0);
}

#[test]
fn typographic_forms_are_drawn_with_plain_glyphs() {
    assert_eq!(
        layout("“Ａ” – ’", &style(5.0)).glyphs,
        layout("\"A\" - '", &style(5.0)).glyphs
    );
    let dash = layout("—", &style(5.0));
    assert!(dash.missing.is_empty());
    assert!(dash.glyphs[0].bounding_box().width() > layout("-", &style(5.0)).width);
}

#[test]
fn nothing_to_draw_is_one_empty_line() {
    for text in ["", "   "] {
        let laid = layout(text, &style(5.0));
        assert!(laid.glyphs.is_empty() && laid.missing.is_empty());
        assert_eq!(laid.lines, 1);
    }
    assert!(layout("   ", &style(5.0)).width > 0.0);
}
