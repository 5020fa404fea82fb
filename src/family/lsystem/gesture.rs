//! A stroke drawn with the studio's pen, written as a sketch's stroke:
//! the table's `points` replaced by it (its `svg` or `line` gone), or a
//! new sketch table for a stroke that starts one.

use serde_json::json;
use toml_edit::{Array, Table};

use crate::error::Result;
use crate::family::gesture::{point_list, Change, Gesture, Gestures};
use crate::spec::LSystemSpec;

impl Gestures for LSystemSpec {
    fn offers(&self) -> Vec<(Gesture, serde_json::Value)> {
        if self.sketch.is_some() {
            vec![(Gesture::Stroke, json!({}))]
        } else {
            Vec::new()
        }
    }

    fn stroke(&self, field: &str, points: &[[f64; 2]]) -> Result<Vec<Change>> {
        let sketch = format!("{field}.sketch");
        Ok(vec![
            Change::Remove(format!("{sketch}.svg")),
            Change::Remove(format!("{sketch}.line")),
            Change::Set(format!("{sketch}.smooth"), false.into()),
            Change::Set(format!("{sketch}.points"), point_list(points).into()),
        ])
    }
}

/// The table a stroke that starts a sketch of its own writes (in the
/// layer it was drawn for): the stroke as straight lines, grown by the
/// paper's rules and drawn as one outline, as the sketch templates are.
pub(crate) fn new_sketch(id: &str, points: Array) -> Table {
    let mut sketch = Table::new();
    sketch.insert("points", toml_edit::value(points));
    sketch.insert("smooth", toml_edit::value(false));
    sketch.insert("module", toml_edit::value(8));
    sketch.insert("width", toml_edit::value(2));
    let mut table = Table::new();
    table.insert("id", toml_edit::value(id));
    table.insert("style", toml_edit::value("outline"));
    table.insert("sketch", toml_edit::Item::Table(sketch));
    table
}
