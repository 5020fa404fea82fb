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

/// The number at `field`, if there is one.
pub fn number_at(value: &toml::Value, field: &str) -> Option<f64> {
    let mut here = value;
    for step in steps(field)? {
        here = match step {
            Step::Key(key) => here.get(key)?,
            Step::Index(i) => here.get(i)?,
        };
    }
    number(here)
}

/// `value` as a number, whether written as an integer or a float.
pub fn number(value: &toml::Value) -> Option<f64> {
    // Numbers in a description are far below 2⁵³.
    #[allow(clippy::cast_precision_loss)]
    value
        .as_float()
        .or_else(|| value.as_integer().map(|i| i as f64))
}

#[cfg(test)]
mod tests {
    use super::*;

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
