//! Numbers that become geometry, checked before usvg sees them. usvg
//! drops an element whose path data or length holds NaN or an infinity
//! without a word, and turns a number beyond `f32` into an infinite
//! coordinate; either way the drawing would silently change. Each geometry
//! attribute is read here with the svgtypes parser usvg itself reads it
//! with (path data, transform lists, number lists, lengths), so that the
//! numbers checked are the numbers usvg would use.

use std::str::FromStr;

use kurbo::Affine;
use resvg::usvg::roxmltree;
use svgtypes::{
    LengthListParser, NumberListParser, PathParser, PathSegment, TransformListParser,
    TransformListToken,
};

use crate::error::{Error, LineCol, Result};

/// The largest magnitude usvg can hold (it computes in `f32`).
const LARGEST: f64 = f32::MAX as f64;

/// A longer run of number characters at a parse error is not quoted whole
/// (it bounds the search for the number the run starts with).
const MAX_QUOTED: usize = 1000;

/// How the value of a geometry attribute is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Grammar {
    /// `d`: path data.
    PathData,
    /// `transform`: a transform list.
    Transform,
    /// `points`, `viewBox`: a list of plain numbers.
    Numbers,
    /// Coordinates and sizes: lengths (a list of them on text).
    Lengths,
}

/// The grammar of the geometry attribute `name`; `None` for attributes
/// whose numbers never become geometry.
fn grammar(name: &str) -> Option<Grammar> {
    Some(match name {
        "d" => Grammar::PathData,
        "transform" => Grammar::Transform,
        "points" | "viewBox" => Grammar::Numbers,
        "x" | "y" | "x1" | "y1" | "x2" | "y2" | "cx" | "cy" | "r" | "rx" | "ry" | "width"
        | "height" => Grammar::Lengths,
        _ => return None,
    })
}

/// Rejects NaN, infinities and numbers beyond `f32` in the geometry
/// attributes of `node` (an element of `text`).
///
/// # Errors
/// [`Error::Invalid`] naming the element, the attribute and the number, at
/// the attribute's value.
pub(super) fn check_numbers(text: &str, node: roxmltree::Node<'_, '_>) -> Result<()> {
    for attr in node.attributes() {
        let Some(grammar) = grammar(attr.name()).filter(|_| attr.namespace().is_none()) else {
            continue;
        };
        if let Some(bad) = bad_number(attr.value(), grammar) {
            return Err(Error::Invalid {
                at: Some(LineCol::of_offset(text, attr.range_value().start)),
                field: format!("{} {}", element_name(node), attr.name()),
                message: format!(
                    "'{bad}' is not a plottable number (NaN, infinite, or beyond \
                     ±{:e})",
                    f32::MAX
                ),
            });
        }
    }
    Ok(())
}

/// Rejects an element whose `transform`, composed with the transforms of
/// the elements around it, scales or moves the drawing beyond what usvg
/// can hold: each number may be fine (`scale(10)`) and 400 nested ones
/// overflow, and usvg then drops the element without a word.
///
/// # Errors
/// [`Error::Invalid`] naming the element, its transform and the scale it
/// comes to, at the transform's value.
pub(super) fn check_composed_transforms(text: &str, doc: &roxmltree::Document<'_>) -> Result<()> {
    let mut stack = vec![(doc.root_element(), Affine::IDENTITY)];
    while let Some((node, outer)) = stack.pop() {
        let mut composed = outer;
        let own = node
            .attributes()
            .find(|a| a.name() == "transform" && a.namespace().is_none());
        if let Some(attr) = own {
            // A transform svgtypes cannot read is usvg's to refuse.
            if let Ok(t) = svgtypes::Transform::from_str(attr.value()) {
                composed = outer * Affine::new([t.a, t.b, t.c, t.d, t.e, t.f]);
                let largest = composed.as_coeffs().into_iter().fold(0.0f64, |m, c| {
                    if c.is_nan() {
                        f64::INFINITY
                    } else {
                        m.max(c.abs())
                    }
                });
                if largest > LARGEST {
                    return Err(Error::Invalid {
                        at: Some(LineCol::of_offset(text, attr.range_value().start)),
                        field: format!("{} transform", element_name(node)),
                        message: format!(
                            "'{}' with the transforms of the elements around it comes to \
                             {largest:.1e}, beyond ±{:e}, the most moyo can plot (the element \
                             would be lost)",
                            attr.value(),
                            f32::MAX
                        ),
                    });
                }
            }
        }
        stack.extend(
            node.children()
                .filter(|n| n.is_element())
                .map(|n| (n, composed)),
        );
    }
    Ok(())
}

/// `<tag id="…">`, or `<tag>` without an id: how an error names an element.
fn element_name(node: roxmltree::Node<'_, '_>) -> String {
    match node.attribute("id") {
        Some(id) => format!("<{} id=\"{id}\">", node.tag_name().name()),
        None => format!("<{}>", node.tag_name().name()),
    }
}

/// The first number of `value` that usvg could not hold: one svgtypes
/// read beyond `f32` (written as `-1e39`), or, where svgtypes stopped at
/// an error, a NaN, an infinity or a number beyond `f64` standing there,
/// as written.
fn bad_number(value: &str, grammar: Grammar) -> Option<String> {
    let mut numbers = Vec::new();
    let error = match grammar {
        Grammar::PathData => read(PathParser::from(value), &mut numbers, segment_numbers),
        Grammar::Transform => read(
            TransformListParser::from(value),
            &mut numbers,
            transform_numbers,
        ),
        Grammar::Numbers => read(NumberListParser::from(value), &mut numbers, |n, out| {
            out.push(n)
        }),
        Grammar::Lengths => read(LengthListParser::from(value), &mut numbers, |l, out| {
            out.push(l.number)
        }),
    };
    if let Some(v) = numbers.into_iter().find(|v| v.abs() > LARGEST) {
        return Some(format!("{v:e}"));
    }
    let (token, v) = number_at(value, error_position(&error?)?)?;
    (!v.is_finite() || v.abs() > LARGEST).then(|| token.to_string())
}

/// Collects the numbers of `items` up to the first error, which it returns.
fn read<T>(
    items: impl Iterator<Item = Result<T, svgtypes::Error>>,
    numbers: &mut Vec<f64>,
    numbers_of: impl Fn(T, &mut Vec<f64>),
) -> Option<svgtypes::Error> {
    for item in items {
        match item {
            Ok(item) => numbers_of(item, numbers),
            Err(e) => return Some(e),
        }
    }
    None
}

fn segment_numbers(segment: PathSegment, out: &mut Vec<f64>) {
    use PathSegment::*;
    match segment {
        MoveTo { x, y, .. } | LineTo { x, y, .. } | SmoothQuadratic { x, y, .. } => {
            out.extend([x, y])
        }
        HorizontalLineTo { x, .. } => out.push(x),
        VerticalLineTo { y, .. } => out.push(y),
        CurveTo {
            x1,
            y1,
            x2,
            y2,
            x,
            y,
            ..
        } => out.extend([x1, y1, x2, y2, x, y]),
        SmoothCurveTo { x2, y2, x, y, .. } => out.extend([x2, y2, x, y]),
        Quadratic { x1, y1, x, y, .. } => out.extend([x1, y1, x, y]),
        EllipticalArc {
            rx,
            ry,
            x_axis_rotation,
            x,
            y,
            ..
        } => out.extend([rx, ry, x_axis_rotation, x, y]),
        ClosePath { .. } => {}
    }
}

fn transform_numbers(token: TransformListToken, out: &mut Vec<f64>) {
    use TransformListToken::*;
    match token {
        Matrix { a, b, c, d, e, f } => out.extend([a, b, c, d, e, f]),
        Translate { tx, ty } => out.extend([tx, ty]),
        Scale { sx, sy } => out.extend([sx, sy]),
        Rotate { angle } | SkewX { angle } | SkewY { angle } => out.push(angle),
    }
}

/// Where svgtypes stopped: a character position counted from 1.
fn error_position(e: &svgtypes::Error) -> Option<usize> {
    match *e {
        svgtypes::Error::UnexpectedData(at)
        | svgtypes::Error::InvalidNumber(at)
        | svgtypes::Error::InvalidChar(_, at)
        | svgtypes::Error::InvalidString(_, at) => Some(at),
        _ => None,
    }
}

/// The number written at character `position` (from 1) of `value`, as
/// written, with its value: the longest run of number characters there
/// that Rust's `f64` parser reads (which also reads `NaN`, `inf` and
/// `Infinity`, in any case, and gives infinity beyond `f64`). A word is
/// not cut: `information` holds no `inf`.
fn number_at(value: &str, position: usize) -> Option<(&str, f64)> {
    let start = value.char_indices().nth(position.checked_sub(1)?)?.0;
    let rest = &value[start..];
    let run = rest
        .find(|c: char| !(c.is_ascii_alphanumeric() || matches!(c, '.' | '+' | '-')))
        .unwrap_or(rest.len())
        .min(MAX_QUOTED);
    (1..=run).rev().find_map(|n| {
        // The run is ASCII, so every `n` is a character boundary.
        let token = &rest[..n];
        let v = token.parse::<f64>().ok()?;
        let letter = |c: char| c.is_ascii_alphabetic();
        let cuts_a_word = token.ends_with(letter) && rest[n..].starts_with(letter);
        (!cuts_a_word).then_some((token, v))
    })
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{doc, import, import_err};
    use super::*;

    #[test]
    fn huge_and_nan_coordinates_are_rejected() {
        for (body, expected) in [
            (
                r#"<path id="p" d="M 0 0 L NaN 5" stroke="black"/>"#,
                "<path id=\"p\"> d",
            ),
            (r#"<path d="M0-1e39L5 5" stroke="black"/>"#, "'-1e39'"),
            (r#"<circle r="inf" stroke="black"/>"#, "<circle> r"),
            (
                r#"<g transform="scale(1e400)"><path d="M0 0L1 1" stroke="black"/></g>"#,
                "'1e400'",
            ),
            (
                r#"<path id="far" d="M 0 0 L 1e9 0" stroke="black"/>"#,
                "path far: point (1000000",
            ),
            (
                r#"<g transform="scale(1e6)"><path d="M0 0L1 1" stroke="black"/></g>"#,
                "outside",
            ),
        ] {
            let e = import_err(&doc(body));
            assert!(matches!(e, Error::Invalid { .. }), "{body}: {e:?}");
            assert!(e.to_string().contains(expected), "{body}: {e}");
        }
        let bad = |value: &str, grammar| bad_number(value, grammar);
        assert_eq!(bad("M.5.5 1e5-2E+3", Grammar::PathData), None);
        assert_eq!(bad("translate(1,2) scale(-1e38)", Grammar::Transform), None);
        assert_eq!(bad("1-1e39", Grammar::Lengths).as_deref(), Some("-1e39"));
        assert_eq!(
            bad("M 0 0 L Infinity 3", Grammar::PathData).as_deref(),
            Some("Infinity")
        );
    }

    /// Issue 36, item 7: each `scale(10)` is a fine number, 400 nested
    /// come to 1e400, and usvg dropped the path without a word.
    #[test]
    fn transforms_nested_past_what_usvg_holds_are_refused_naming_the_element() {
        let nested = |n: usize| {
            format!(
                "{}<path d=\"M0 0L1 1\" stroke=\"black\"/>{}",
                r#"<g transform="scale(10)">"#.repeat(n),
                "</g>".repeat(n)
            )
        };
        let e = import_err(&doc(&nested(400))).to_string();
        assert!(
            e.contains("<g> transform: 'scale(10)' with the transforms of the elements around it comes to 1.0e39"),
            "{e}"
        );
        assert!(e.contains("beyond ±3.4028235e38"), "{e}");
        // Scales that undo each other are as small as they come to.
        let undone = r#"<g transform="scale(1e3)"><g transform="scale(1e-3)"><path d="M0 0L1 1" stroke="black"/></g></g>"#;
        assert_eq!(import(&doc(undone)).scene.path_count(), 1);
    }

    #[test]
    fn only_numbers_usvg_would_use_are_checked() {
        let bad = |value: &str, grammar| bad_number(value, grammar);
        // Words that are not numbers are left to usvg.
        assert_eq!(bad("auto", Grammar::Lengths), None);
        assert_eq!(bad("information", Grammar::Lengths), None);
        assert_eq!(bad("M 0 0 L 5", Grammar::PathData), None);
        // Wherever svgtypes stops, what stands there is quoted as written.
        assert_eq!(
            bad("M0 0 L1 1 nan", Grammar::PathData).as_deref(),
            Some("nan")
        );
        assert_eq!(
            bad("0 0 1e999 1", Grammar::Numbers).as_deref(),
            Some("1e999")
        );
        assert_eq!(
            bad("rotate(NaN)", Grammar::Transform).as_deref(),
            Some("NaN")
        );
        assert_eq!(bad("10 20 1e39", Grammar::Lengths).as_deref(), Some("1e39"));
        assert_eq!(bad("1e39mm", Grammar::Lengths).as_deref(), Some("1e39"));
        // Arc radii and flags are numbers too.
        assert_eq!(
            bad("M0 0 A 1e39 1 0 0 1 5 5", Grammar::PathData).as_deref(),
            Some("1e39")
        );
        assert_eq!(grammar("style"), None);
    }
}
