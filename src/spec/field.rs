//! Field paths as errors and [`super::FieldRange`] write them
//! (`layers[0].trees[1].count`), read back: to find a field's value in a
//! description, or to change it (the studio's form, the structured
//! fuzzer).

/// One step of a field path: a key, or an index into a list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Step<'a> {
    /// A table's key.
    Key(&'a str),
    /// A list's index.
    Index(usize),
}

/// The steps of `field`, or `None` when it is not a field path.
///
/// ```
/// use moyo::spec::field::{steps, Step};
/// assert_eq!(
///     steps("layers[0].centre[1][0]"),
///     Some(vec![Step::Key("layers"), Step::Index(0), Step::Key("centre"), Step::Index(1), Step::Index(0)])
/// );
/// assert_eq!(steps("a..b"), None);
/// ```
pub fn steps(field: &str) -> Option<Vec<Step<'_>>> {
    let mut out = Vec::new();
    for part in field.split('.') {
        let split = part.find('[').unwrap_or(part.len());
        let (key, mut rest) = part.split_at(split);
        if key.is_empty() || key.contains(']') {
            return None;
        }
        out.push(Step::Key(key));
        while !rest.is_empty() {
            let inner = rest.strip_prefix('[')?;
            let end = inner.find(']')?;
            out.push(Step::Index(inner[..end].parse().ok()?));
            rest = &inner[end + 1..];
        }
    }
    Some(out)
}

/// The value at `field` in a description read as a TOML value.
pub fn value_at_mut<'v>(value: &'v mut toml::Value, field: &str) -> Option<&'v mut toml::Value> {
    let mut here = value;
    for step in steps(field)? {
        here = match step {
            Step::Key(key) => here.get_mut(key)?,
            Step::Index(i) => here.get_mut(i)?,
        };
    }
    Some(here)
}

/// The value at `field`, if there is one.
pub fn value_at<'v>(value: &'v toml::Value, field: &str) -> Option<&'v toml::Value> {
    let mut here = value;
    for step in steps(field)? {
        here = match step {
            Step::Key(key) => here.get(key)?,
            Step::Index(i) => here.get(i)?,
        };
    }
    Some(here)
}

/// The number at `field`, if there is one.
pub fn number_at(value: &toml::Value, field: &str) -> Option<f64> {
    number(value_at(value, field)?)
}

/// `value` as a number, whether written as an integer or a float.
pub fn number(value: &toml::Value) -> Option<f64> {
    // Numbers in a description are far below 2⁵³.
    #[allow(clippy::cast_precision_loss)]
    value
        .as_float()
        .or_else(|| value.as_integer().map(|i| i as f64))
}

/// Calls `visit` with the path and value of every table entry and list
/// item below `value`, parents first, tables' keys in alphabetical order;
/// `visit` returns whether to go into what it was given.
fn walk(value: &toml::Value, visit: &mut dyn FnMut(&str, &toml::Value) -> bool) {
    fn go(v: &toml::Value, path: &str, visit: &mut dyn FnMut(&str, &toml::Value) -> bool) {
        match v {
            toml::Value::Table(t) => {
                for (k, v) in t {
                    let next = if path.is_empty() {
                        k.clone()
                    } else {
                        format!("{path}.{k}")
                    };
                    if visit(&next, v) {
                        go(v, &next, visit);
                    }
                }
            }
            toml::Value::Array(a) => {
                for (i, v) in a.iter().enumerate() {
                    let next = format!("{path}[{i}]");
                    if visit(&next, v) {
                        go(v, &next, visit);
                    }
                }
            }
            _ => {}
        }
    }
    go(value, "", visit);
}

/// The paths of every list of two or more `[x, y]` points in `value`,
/// tables' keys in alphabetical order.
pub fn point_lists(value: &toml::Value) -> Vec<String> {
    let mut out = Vec::new();
    walk(value, &mut |path, v| match v.as_array() {
        Some(a) if a.len() >= 2 && a.iter().all(|p| xy(p).is_some()) => {
            out.push(path.to_string());
            false
        }
        _ => true,
    });
    out
}

/// The paths and values of every `true`/`false` in `value`.
pub fn booleans(value: &toml::Value) -> Vec<(String, bool)> {
    let mut out = Vec::new();
    walk(value, &mut |path, v| {
        if let Some(b) = v.as_bool() {
            out.push((path.to_string(), b));
        }
        true
    });
    out
}

/// A text field of a description that takes one of a few words.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Choice {
    /// Its path.
    pub field: String,
    /// The word it has.
    pub value: String,
    /// The words it may take.
    pub options: Vec<String>,
}

/// Every text field of the description `value` that takes one of a few
/// words (`style`, `distribution`, `black` …), with them. The words are
/// the ones the description's own reader names when given another (each
/// text is tried with a word no field takes), so the list cannot drift
/// from what is accepted.
pub fn choices(value: &toml::Value) -> Vec<Choice> {
    const PROBE: &str = "\u{1}";
    let mut texts = Vec::new();
    walk(value, &mut |path, v| {
        if let Some(s) = v.as_str() {
            texts.push((path.to_string(), s.to_string()));
        }
        true
    });
    let mut probe = value.clone();
    let mut out = Vec::new();
    for (field, now) in texts {
        let Some(slot) = value_at_mut(&mut probe, &field) else {
            continue;
        };
        *slot = toml::Value::String(PROBE.into());
        let refused = probe.clone().try_into::<super::SceneSpec>().err();
        if let Some(slot) = value_at_mut(&mut probe, &field) {
            *slot = toml::Value::String(now.clone());
        }
        let message = refused.map(|e| e.message().to_string()).unwrap_or_default();
        let Some((_, named)) = message
            .strip_prefix("unknown variant")
            .and_then(|m| m.split_once("expected "))
        else {
            continue;
        };
        let options: Vec<String> = named
            .split('`')
            .skip(1)
            .step_by(2)
            .map(str::to_string)
            .collect();
        if !options.is_empty() {
            out.push(Choice {
                field,
                value: now,
                options,
            });
        }
    }
    out
}

/// A point `[x, y]`.
pub fn xy(value: &toml::Value) -> Option<[f64; 2]> {
    match value.as_array()?.as_slice() {
        [x, y] => Some([number(x)?, number(y)?]),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn switches_and_words_are_found_with_what_they_take() {
        let text = "version = 1\n[plot.occlude]\nsilhouettes = true\n[[layers]]\nname = \"a\"\n\
                    [[layers.voronoi]]\nid = \"v\"\nsites = { distribution = \"grid\" }\n";
        let v: toml::Value = toml::from_str(text).unwrap();
        assert_eq!(
            booleans(&v),
            [("plot.occlude.silhouettes".to_string(), true)]
        );
        let found = choices(&v);
        // Names and ids are free text; the distribution takes four words.
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].field, "layers[0].voronoi[0].sites.distribution");
        assert_eq!(found[0].value, "grid");
        assert_eq!(found[0].options, ["uniform", "grid", "poisson", "rose"]);
    }

    #[test]
    fn lines_of_points_are_found_by_their_paths() {
        let v: toml::Value =
            toml::from_str("a = [{ b = [[1, 2], [3, 4.5]] }]\nc = { d = [[5, 6]] }").unwrap();
        assert_eq!(point_lists(&v), vec!["a[0].b".to_string()]);
        assert_eq!(xy(&v["a"][0]["b"][1]), Some([3.0, 4.5]));
    }

    #[test]
    fn paths_reach_into_tables_and_lists() {
        let mut v: toml::Value =
            toml::from_str("a = [{ b = [[1, 2], [3, 4.5]] }]\nc = { d = 5 }").unwrap();
        assert_eq!(number_at(&v, "a[0].b[1][1]"), Some(4.5));
        assert_eq!(number_at(&v, "c.d"), Some(5.0));
        assert_eq!(number_at(&v, "a[0].b"), None);
        assert!(value_at_mut(&mut v, "a[3].b").is_none() && value_at_mut(&mut v, "c.e").is_none());
        *value_at_mut(&mut v, "c.d").unwrap() = toml::Value::Integer(6);
        assert_eq!(number_at(&v, "c.d"), Some(6.0));
        for bad in ["", "a[", "a[x]", "a]0[", ".a", "a[0]b", "a[0"] {
            assert!(steps(bad).is_none(), "{bad}");
        }
    }
}
