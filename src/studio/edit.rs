//! Changes the page makes to a description, written into its TOML text
//! in place (`toml_edit`), so the designer's comments, order and layout
//! survive every drag of a slider.

use toml_edit::{DocumentMut, Item, Table, TableLike, Value};

use crate::error::{Error, Result};
use crate::spec::field::{steps, Step};

/// `text` with the number at `field` set to `value` (a whole number when
/// `integer`). Tables on the way that the text leaves out (`[limits]`)
/// are added; lists must be there.
///
/// # Errors
/// [`Error::Parse`] for text that is not TOML, [`Error::Invalid`] at
/// `field` for a path that does not lead to a number's place.
pub(crate) fn set_number(text: &str, field: &str, value: f64, integer: bool) -> Result<String> {
    let mut doc: DocumentMut = text
        .parse()
        .map_err(|e: toml_edit::TomlError| Error::Parse {
            at: None,
            field: None,
            message: e.message().to_string(),
        })?;
    let bad = |why: &str| Error::invalid(field, why.to_string());
    if !value.is_finite() {
        return Err(bad("the value must be a finite number"));
    }
    let steps = steps(field).ok_or_else(|| bad("not a field path"))?;
    let number = if integer {
        // Ranges of whole numbers in moyo are far inside i64.
        #[allow(clippy::cast_possible_truncation)]
        Value::from(value.round() as i64)
    } else {
        Value::from(value)
    };
    in_table(doc.as_table_mut(), &steps, number).map_err(bad)?;
    Ok(doc.to_string())
}

/// Sets the number at `steps` below a table (`[x]` or `{ … }`).
fn in_table(
    table: &mut dyn TableLike,
    steps: &[Step<'_>],
    number: Value,
) -> std::result::Result<(), &'static str> {
    let Some((Step::Key(key), rest)) = steps.split_first() else {
        return Err("an index where a table has names");
    };
    if rest.is_empty() {
        return match table.get_mut(key) {
            Some(Item::Value(v)) => replace(v, number),
            Some(_) => Err("it is a table or a list, not a number"),
            None => {
                table.insert(key, Item::Value(number));
                Ok(())
            }
        };
    }
    if table.get(key).is_none() {
        // A table the text leaves out (`[limits]`) is added; a list must
        // be there.
        if matches!(rest[0], Step::Index(_)) {
            return Err("a list in it is missing");
        }
        table.insert(key, Item::Table(Table::new()));
    }
    match table.get_mut(key) {
        Some(Item::Table(t)) => in_table(t, rest, number),
        Some(Item::Value(v)) => in_value(v, rest, number),
        Some(Item::ArrayOfTables(list)) => match rest.split_first() {
            Some((Step::Index(i), more)) if !more.is_empty() => match list.get_mut(*i) {
                Some(t) => in_table(t, more, number),
                None => Err("a list in it is shorter"),
            },
            Some((Step::Index(_), _)) => Err("it is a table, not a number"),
            _ => Err("a name where a list has indices"),
        },
        _ => Err("a part of it is not a table"),
    }
}

/// Sets the number at `steps` below an inline value (a list or `{ … }`).
fn in_value(
    value: &mut Value,
    steps: &[Step<'_>],
    number: Value,
) -> std::result::Result<(), &'static str> {
    match steps.split_first() {
        None => replace(value, number),
        Some((Step::Index(i), rest)) => {
            let list = value.as_array_mut().ok_or("a part of it is not a list")?;
            let item = list.get_mut(*i).ok_or("a list in it is shorter")?;
            in_value(item, rest, number)
        }
        Some((Step::Key(_), _)) => {
            let table = value
                .as_inline_table_mut()
                .ok_or("a part of it is not a table")?;
            in_table(table, steps, number)
        }
    }
}

/// Puts `number` in place of the number `old`, keeping the comment and
/// spacing around it.
fn replace(old: &mut Value, mut number: Value) -> std::result::Result<(), &'static str> {
    if !(old.is_integer() || old.is_float()) {
        return Err("it is not a number");
    }
    *number.decor_mut() = old.decor().clone();
    *old = number;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "# my design\nversion = 1\n\n[[layers]]\nname = \"a\"\n\n\
                        [[layers.trees]]\nrule = \"tree1\"\ncount = 3   # three pines\n\
                        centre = [[10, 100], [100, 100]]\n";

    #[test]
    fn a_number_is_set_in_place_keeping_comments() {
        let out = set_number(TEXT, "layers[0].trees[0].count", 7.0, true).unwrap();
        assert_eq!(out, TEXT.replace("count = 3 ", "count = 7 "));
        let out = set_number(TEXT, "layers[0].trees[0].centre[1][0]", 120.5, false).unwrap();
        assert!(out.contains("centre = [[10, 100], [120.5, 100]]"), "{out}");
        // A field the text leaves out is added, with its table.
        let out = set_number(TEXT, "limits.max_paths", 5000.0, true).unwrap();
        assert!(out.starts_with("# my design\n"), "{out}");
        assert!(out.contains("[limits]\nmax_paths = 5000"), "{out}");
        let out = set_number(TEXT, "layers[0].trees[0].rotate", 15.0, false).unwrap();
        assert!(out.contains("rotate = 15.0"), "{out}");
    }

    #[test]
    fn paths_that_lead_nowhere_are_refused() {
        for (field, why) in [
            ("layers[3].trees[0].count", "shorter"),
            ("layers[0].trees", "not a number"),
            ("layers[0]..x", "not a field path"),
            ("layers[0].name.x", "not a table"),
        ] {
            let e = set_number(TEXT, field, 1.0, true).unwrap_err().to_string();
            assert!(e.starts_with(field) && e.contains(why), "{field}: {e}");
        }
        assert!(set_number(TEXT, "version", f64::NAN, true).is_err());
        assert!(set_number("x = [", "x", 1.0, true).is_err());
    }
}
