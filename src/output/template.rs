//! The text templates of the plotter writers: user lines (a header, a tool
//! change, a pen command) with `{name}` placeholders that the writer fills
//! in (`M0 ; load pen {pen} {name}`).
//!
//! Each template field allows its own placeholders; [`check`] refuses any
//! other, naming the field and what it allows, so a typo is caught before
//! anything is written rather than sent to the machine. `{{` and `}}` are
//! literal braces.

use crate::error::{Error, Result};

/// `Err` naming `field` when `text` has a placeholder outside `allowed` or
/// an unmatched brace.
pub(super) fn check(field: &str, text: &str, allowed: &[&str]) -> Result<()> {
    let allowed_list = || {
        if allowed.is_empty() {
            "none".to_string()
        } else {
            allowed
                .iter()
                .map(|a| format!("{{{a}}}"))
                .collect::<Vec<_>>()
                .join(", ")
        }
    };
    for piece in pieces(text) {
        match piece {
            Piece::Text(_) => {}
            Piece::Placeholder(name) if allowed.contains(&name) => {}
            Piece::Placeholder(name) => {
                return Err(Error::invalid(
                    field,
                    format!(
                        "unknown placeholder {{{name}}}; allowed here: {}",
                        allowed_list()
                    ),
                ))
            }
            Piece::Unmatched => {
                return Err(Error::invalid(
                    field,
                    format!(
                        "an unmatched brace in '{text}' (write {{{{ or }}}} for a brace); \
                         placeholders allowed here: {}",
                        allowed_list()
                    ),
                ))
            }
        }
    }
    Ok(())
}

/// `text` with its placeholders replaced by `values` (a placeholder without
/// a value, which [`check`] refuses, is written as it is).
pub(super) fn fill(text: &str, values: &[(&str, &str)]) -> String {
    let mut out = String::with_capacity(text.len());
    for piece in pieces(text) {
        match piece {
            Piece::Text(t) => out.push_str(t),
            Piece::Placeholder(name) => match values.iter().find(|(k, _)| *k == name) {
                Some((_, v)) => out.push_str(v),
                None => {
                    out.push('{');
                    out.push_str(name);
                    out.push('}');
                }
            },
            Piece::Unmatched => {}
        }
    }
    out
}

enum Piece<'a> {
    Text(&'a str),
    Placeholder(&'a str),
    Unmatched,
}

/// Splits a template into text, placeholders and unmatched braces.
fn pieces(text: &str) -> Vec<Piece<'_>> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find(['{', '}']) {
        out.push(Piece::Text(&rest[..i]));
        let tail = &rest[i..];
        if let Some(after) = tail.strip_prefix("{{") {
            out.push(Piece::Text("{"));
            rest = after;
        } else if let Some(after) = tail.strip_prefix("}}") {
            out.push(Piece::Text("}"));
            rest = after;
        } else if let Some(after) = tail.strip_prefix('}') {
            out.push(Piece::Unmatched);
            rest = after;
        } else {
            match tail[1..].find(['{', '}']) {
                Some(j) if tail.as_bytes()[1 + j] == b'}' => {
                    out.push(Piece::Placeholder(&tail[1..1 + j]));
                    rest = &tail[2 + j..];
                }
                _ => {
                    out.push(Piece::Unmatched);
                    rest = &tail[1..];
                }
            }
        }
    }
    out.push(Piece::Text(rest));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placeholders_are_filled() {
        let values = [("pen", "2"), ("name", "red")];
        assert_eq!(fill("M0 ; pen {pen} {name}", &values), "M0 ; pen 2 red");
        assert_eq!(fill("{{pen}} {pen}", &values), "{pen} 2");
        assert_eq!(fill("no placeholder", &values), "no placeholder");
    }

    #[test]
    fn check_names_the_field_and_what_is_allowed() {
        assert!(check("gcode.tool_change", "M0 {pen} {name}", &["pen", "name"]).is_ok());
        assert!(check("gcode.header", "{{literal}}", &[]).is_ok());
        let e = check("gcode.tool_change", "M0 {pne}", &["pen", "name"])
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("gcode.tool_change: unknown placeholder {pne}")
                && e.contains("{pen}, {name}"),
            "{e}"
        );
        for bad in ["{pen", "pen}", "{a{b}"] {
            let e = check("gcode.header", bad, &["pen"])
                .unwrap_err()
                .to_string();
            assert!(e.contains("unmatched brace"), "{bad}: {e}");
        }
        let e = check("gcode.pen_up", "{x}", &[]).unwrap_err().to_string();
        assert!(e.contains("allowed here: none"), "{e}");
    }
}
