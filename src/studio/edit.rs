//! Changes the page makes to a description, written into its TOML text
//! in place (`toml_edit`), so the designer's comments, order and layout
//! survive every drag of a slider and every gesture.

use toml_edit::{Array, ArrayOfTables, DocumentMut, Item, Table, TableLike, Value};

use crate::error::{Error, Result};
use crate::family::gesture::Change;
use crate::spec::field::{steps, Step};

/// A description's TOML being changed in place: values set, removed and
/// tables appended at field paths (`layers[0].trees[1].count`), the rest
/// of the text as it was.
pub(crate) struct Edit {
    doc: DocumentMut,
}

/// Where a path ends: a key of a table, or an index of a list.
enum Slot<'a> {
    Key(&'a mut dyn TableLike, &'a str),
    Index(&'a mut Array, usize),
}

/// What to do where a path ends.
type Op<'o> = &'o mut dyn FnMut(Slot<'_>) -> std::result::Result<(), &'static str>;

impl Edit {
    /// # Errors
    /// [`Error::Parse`] for text that is not TOML.
    pub(crate) fn parse(text: &str) -> Result<Edit> {
        let doc = text
            .parse()
            .map_err(|e: toml_edit::TomlError| Error::Parse {
                at: None,
                field: None,
                message: e.message().to_string(),
            })?;
        Ok(Edit { doc })
    }

    /// The text as changed.
    pub(crate) fn text(&self) -> String {
        self.doc.to_string()
    }

    /// The description `text` with a gesture's `changes` made, as one
    /// edit.
    ///
    /// # Errors
    /// As [`Edit::parse`], and a change whose field does not lead to a
    /// place in the text.
    pub(crate) fn with_changes(text: &str, changes: Vec<Change>) -> Result<String> {
        let mut edit = Edit::parse(text)?;
        for change in changes {
            match change {
                Change::Set(field, value) => edit.set(&field, value)?,
                Change::Remove(field) => edit.remove(&field)?,
                Change::Push {
                    field,
                    table,
                    inline,
                } => {
                    edit.push_table(&field, table, inline)?;
                }
            }
        }
        Ok(edit.text())
    }

    /// Runs `op` where `field` leads. Tables on the way that the text
    /// leaves out (`[limits]`) are added; lists must be there.
    fn at(&mut self, field: &str, op: Op<'_>) -> Result<()> {
        let bad = |why: &str| Error::invalid(field, why.to_string());
        let steps = steps(field).ok_or_else(|| bad("not a field path"))?;
        in_table(self.doc.as_table_mut(), &steps, op).map_err(bad)
    }

    /// Sets the number at `field` (a whole number when `integer`), keeping
    /// the comment and spacing around the old one.
    ///
    /// # Errors
    /// [`Error::Invalid`] at `field` for a value that is not finite or a
    /// path that does not lead to a number's place.
    pub(crate) fn set_number(&mut self, field: &str, value: f64, integer: bool) -> Result<()> {
        if !value.is_finite() {
            return Err(Error::invalid(field, "the value must be a finite number"));
        }
        let number = if integer {
            // Ranges of whole numbers in moyo are far inside i64.
            #[allow(clippy::cast_possible_truncation)]
            Value::from(value.round() as i64)
        } else {
            Value::from(value)
        };
        self.at(field, &mut |slot| {
            let old = match slot {
                Slot::Key(table, key) => match table.get_mut(key) {
                    Some(Item::Value(v)) => v,
                    Some(_) => return Err("it is a table or a list, not a number"),
                    None => {
                        table.insert(key, Item::Value(number.clone()));
                        return Ok(());
                    }
                },
                Slot::Index(list, i) => list.get_mut(i).ok_or("a list in it is shorter")?,
            };
            if !(old.is_integer() || old.is_float()) {
                return Err("it is not a number");
            }
            replace(old, number.clone());
            Ok(())
        })
    }

    /// Sets the value at `field`, whatever was there.
    ///
    /// # Errors
    /// [`Error::Invalid`] at `field` for a path that leads nowhere.
    pub(crate) fn set(&mut self, field: &str, value: impl Into<Value>) -> Result<()> {
        let value = value.into();
        self.at(field, &mut |slot| {
            match slot {
                Slot::Key(table, key) => match table.get_mut(key) {
                    Some(Item::Value(old)) => replace(old, value.clone()),
                    _ => {
                        table.insert(key, Item::Value(value.clone()));
                    }
                },
                Slot::Index(list, i) => replace(
                    list.get_mut(i).ok_or("a list in it is shorter")?,
                    value.clone(),
                ),
            }
            Ok(())
        })
    }

    /// Removes the key at `field`, if it is there.
    ///
    /// # Errors
    /// [`Error::Invalid`] at `field` for a path that leads nowhere.
    pub(crate) fn remove(&mut self, field: &str) -> Result<()> {
        self.at(field, &mut |slot| match slot {
            Slot::Key(table, key) => {
                table.remove(key);
                Ok(())
            }
            Slot::Index(..) => Err("an index where a table has names"),
        })
    }

    /// Appends `table` to the list of tables at `field` (`[[…]]` tables or
    /// a list of `{ … }`), and returns its index in the list. Where there
    /// is no list yet, one is started: `[[…]]` tables, or with `inline` a
    /// list of `{ … }` (for short tables, as a manual step is).
    ///
    /// # Errors
    /// [`Error::Invalid`] at `field` for a path that leads nowhere or to
    /// something other than a list of tables.
    pub(crate) fn push_table(&mut self, field: &str, table: Table, inline: bool) -> Result<usize> {
        let mut index = 0;
        self.at(field, &mut |slot| {
            let Slot::Key(parent, key) = slot else {
                return Err("an index where a table has names");
            };
            match parent.get_mut(key) {
                None if inline => {
                    let mut list = Array::new();
                    list.push(table.clone().into_inline_table());
                    parent.insert(key, Item::Value(Value::Array(list)));
                }
                None => {
                    let mut list = ArrayOfTables::new();
                    list.push(table.clone());
                    parent.insert(key, Item::ArrayOfTables(list));
                }
                Some(Item::ArrayOfTables(list)) => {
                    index = list.len();
                    list.push(table.clone());
                }
                Some(Item::Value(Value::Array(list))) => {
                    index = list.len();
                    list.push(table.clone().into_inline_table());
                }
                Some(_) => return Err("it is not a list of tables"),
            }
            Ok(())
        })?;
        Ok(index)
    }
}

/// The layer and table indices of a family's table from its field path:
/// `(L, T)` for `layers[L].<family>[T]`.
pub(crate) fn table_index(field: &str, family: &str) -> Option<(usize, usize)> {
    match steps(field)?.as_slice() {
        [Step::Key("layers"), Step::Index(l), Step::Key(f), Step::Index(t)] if *f == family => {
            Some((*l, *t))
        }
        _ => None,
    }
}

/// Runs `op` where `steps` lead below a table (`[x]` or `{ … }`).
fn in_table(
    table: &mut dyn TableLike,
    steps: &[Step<'_>],
    op: Op<'_>,
) -> std::result::Result<(), &'static str> {
    let Some((Step::Key(key), rest)) = steps.split_first() else {
        return Err("an index where a table has names");
    };
    if rest.is_empty() {
        return op(Slot::Key(table, key));
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
        Some(Item::Table(t)) => in_table(t, rest, op),
        Some(Item::Value(v)) => in_value(v, rest, op),
        Some(Item::ArrayOfTables(list)) => match rest.split_first() {
            Some((Step::Index(i), more)) if !more.is_empty() => match list.get_mut(*i) {
                Some(t) => in_table(t, more, op),
                None => Err("a list in it is shorter"),
            },
            Some((Step::Index(_), _)) => Err("it is a table, not a value"),
            _ => Err("a name where a list has indices"),
        },
        _ => Err("a part of it is not a table"),
    }
}

/// Runs `op` where `steps` lead below an inline value (a list or
/// `{ … }`).
fn in_value(
    value: &mut Value,
    steps: &[Step<'_>],
    op: Op<'_>,
) -> std::result::Result<(), &'static str> {
    match steps.split_first() {
        None => Err("it is not a table"),
        Some((Step::Index(i), rest)) => {
            let list = value.as_array_mut().ok_or("a part of it is not a list")?;
            if rest.is_empty() {
                return op(Slot::Index(list, *i));
            }
            let item = list.get_mut(*i).ok_or("a list in it is shorter")?;
            in_value(item, rest, op)
        }
        Some((Step::Key(_), _)) => {
            let table = value
                .as_inline_table_mut()
                .ok_or("a part of it is not a table")?;
            in_table(table, steps, op)
        }
    }
}

/// Puts `value` in place of `old`, keeping the comment and spacing
/// around it.
fn replace(old: &mut Value, mut value: Value) {
    *value.decor_mut() = old.decor().clone();
    *old = value;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn set_number(text: &str, field: &str, value: f64, integer: bool) -> Result<String> {
        let mut edit = Edit::parse(text)?;
        edit.set_number(field, value, integer)?;
        Ok(edit.text())
    }
    use toml_edit::{Array, Item, Table};

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
    fn values_are_set_and_removed_and_tables_appended_where_they_belong() {
        let two = format!("{TEXT}\n[[layers]]\nname = \"b\"\n[[layers.trees]]\nrule = \"tree2\"\n");
        let mut edit = Edit::parse(&two).unwrap();
        let mut points = Array::new();
        points.push(Array::from_iter([1.5, 2.0]));
        edit.set("layers[0].trees[0].centre", points).unwrap();
        edit.set("layers[0].trees[0].smooth", false).unwrap();
        edit.remove("layers[0].trees[0].count").unwrap();
        edit.remove("layers[0].trees[0].nothing").unwrap();
        // A new table in the first layer, with a table of its own: it is
        // written inside that layer, not after the last one.
        let mut inner = Table::new();
        inner.insert("module", toml_edit::value(8));
        let mut table = Table::new();
        table.insert("id", toml_edit::value("s"));
        table.insert("sketch", Item::Table(inner));
        assert_eq!(
            edit.push_table("layers[0].lsystem", table.clone(), false)
                .unwrap(),
            0
        );
        assert_eq!(
            edit.push_table("layers[1].trees", table.clone(), true)
                .unwrap(),
            1
        );
        let out = edit.text();
        assert!(out.starts_with("# my design\n"), "{out}");
        let v: toml::Value = toml::from_str(&out).unwrap();
        let first = &v["layers"][0];
        assert_eq!(
            first["trees"][0]["centre"],
            toml::Value::try_from([[1.5, 2.0]]).unwrap()
        );
        assert_eq!(first["trees"][0]["smooth"], toml::Value::Boolean(false));
        assert!(first["trees"][0].get("count").is_none());
        assert_eq!(
            first["lsystem"][0]["sketch"]["module"].as_integer(),
            Some(8)
        );
        assert_eq!(v["layers"][1]["trees"][1]["id"].as_str(), Some("s"));
        assert_eq!(v["layers"].as_array().unwrap().len(), 2);
        // Not a list of tables.
        assert!(edit
            .push_table("layers[0].name", table.clone(), true)
            .is_err());
        // A short list starts inline.
        edit.push_table("layers[1].trees[0].manual", table, true)
            .unwrap();
        assert!(
            edit.text()
                .contains("manual = [{ id = \"s\", sketch = { module = 8 } }]"),
            "{}",
            edit.text()
        );
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
