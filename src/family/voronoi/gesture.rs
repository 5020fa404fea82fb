//! Pinning a Voronoi table: the sites it spreads written as its `points`,
//! exactly, so that the design does not change and every site becomes a
//! handle to drag; the keys that spread them go.

use serde_json::json;

use crate::error::{Error, Result};
use crate::family::gesture::{point_list, Change, Gesture, Gestures};
use crate::spec::VoronoiSpec;

/// The keys of `[sites]` that spread sites rather than give them.
const SPREADING: [&str; 7] = [
    "distribution",
    "count",
    "spacing",
    "jitter",
    "image",
    "density",
    "edges",
];

impl Gestures for VoronoiSpec {
    fn offers(&self) -> Vec<(Gesture, serde_json::Value)> {
        vec![(
            Gesture::Pin,
            json!({ "pinned": self.sites.points.is_some() }),
        )]
    }

    fn pin(&self, field: &str, sites: &[[f64; 2]]) -> Result<Vec<Change>> {
        let at = format!("{field}.sites");
        let pinned = self.pinned(sites.to_vec()).sites;
        // The sites' keys as they will be: each kept, set or removed.
        let now = toml::Value::try_from(&pinned).map_err(|e| Error::invalid(&at, e.to_string()))?;
        let mut changes = Vec::new();
        for key in SPREADING {
            let field = format!("{at}.{key}");
            changes.push(match now.get(key) {
                Some(v) => Change::Set(field, plain(v)?),
                None => Change::Remove(field),
            });
        }
        changes.push(Change::Set(
            format!("{at}.points"),
            point_list(sites).into(),
        ));
        Ok(changes)
    }

    fn pin_key(&self) -> Option<&str> {
        self.id.as_deref()
    }

    fn is_pinned(&self) -> bool {
        self.sites.points.is_some()
    }
}

/// A plain TOML value (a number, a string) as an editable one.
fn plain(v: &toml::Value) -> Result<toml_edit::Value> {
    v.to_string()
        .parse()
        .map_err(|e: toml_edit::TomlError| Error::invalid("studio", e.to_string()))
}
