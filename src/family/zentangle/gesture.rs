//! A click in a zentangle fill: the white region under it gets the
//! chosen procedure as a manual step — after the table's automatic steps
//! when it has any (a touch-up of the tile the designer sees), from the
//! blank tile on when it has none.

use serde_json::json;
use toml_edit::{Array, Table};

use crate::error::Result;
use crate::family::gesture::{tenth, Change, Gesture, Gestures};
use crate::spec::ZentangleSpec;

impl Gestures for ZentangleSpec {
    fn offers(&self) -> Vec<(Gesture, serde_json::Value)> {
        vec![(Gesture::Fill, json!({}))]
    }

    fn click(&self, field: &str, at: [f64; 2], procedure: u32) -> Result<Vec<Change>> {
        let mut step = Table::new();
        let mut point = Array::new();
        point.push(tenth(at[0]));
        point.push(tenth(at[1]));
        step.insert("at", toml_edit::value(point));
        step.insert("procedure", toml_edit::value(i64::from(procedure)));
        if self.steps > 0 {
            step.insert("after", toml_edit::value(true));
        }
        Ok(vec![Change::Push {
            field: format!("{field}.manual"),
            table: step,
            inline: true,
        }])
    }
}
