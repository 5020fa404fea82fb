//! What the families' tables offer the studio's gestures. The studio
//! finds the table a gesture names and hands it the gesture; what the
//! gesture writes into the description is the family's: a zentangle
//! takes a click as a manual step, a Voronoi table's sites are pinned as
//! its points, a vine's camera turns, a sketch takes a stroke as its
//! points. A table answers in [`Change`]s of the description, addressed
//! by field path, which the studio applies as one edit.

use toml_edit::{Array, Table, Value};

use crate::error::{Error, Result};

/// A gesture the page can make on a table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Gesture {
    /// A stroke drawn with the pen (a sketch's points).
    Stroke,
    /// A click choosing one of a list (a zentangle region's procedure).
    Fill,
    /// The table's sites written as points, to drag as handles.
    Pin,
    /// The view turned round what is drawn (a vine's camera).
    Orbit,
}

impl Gesture {
    /// Every gesture, in the order `GET /api/targets` lists them.
    pub(crate) const ALL: [Gesture; 4] =
        [Gesture::Stroke, Gesture::Fill, Gesture::Pin, Gesture::Orbit];

    /// Its name in the studio's API (`"sketch"`, `"zentangle"`, …: what
    /// the page's lists are called).
    pub(crate) fn list(self) -> &'static str {
        match self {
            Gesture::Stroke => "sketch",
            Gesture::Fill => "zentangle",
            Gesture::Pin => "voronoi",
            Gesture::Orbit => "vine",
        }
    }
}

/// A change of the description, addressed by field path
/// (`layers[0].zentangle[1].manual`).
#[derive(Debug, Clone)]
pub(crate) enum Change {
    /// The key set to the value (made when missing).
    Set(String, Value),
    /// The key removed (nothing when missing).
    Remove(String),
    /// A table appended to an array of tables; `inline` writes it as
    /// `{ … }` in an inline array rather than as `[[…]]`.
    Push {
        /// The array's field path.
        field: String,
        /// The new table.
        table: Table,
        /// Whether it is written inline.
        inline: bool,
    },
}

/// A table's answers to the gestures it offers; the others are refused.
pub(crate) trait Gestures {
    /// The gestures the table takes, each with the facts the page shows
    /// of it (a JSON object: `{"pinned": true}`, `{"orbits": false}`).
    fn offers(&self) -> Vec<(Gesture, serde_json::Value)>;

    /// A click at `at` (scene mm) choosing `choice`.
    ///
    /// # Errors
    /// [`Error::Invalid`] at `field` when the table takes no click.
    fn click(&self, field: &str, _at: [f64; 2], _choice: u32) -> Result<Vec<Change>> {
        Err(refused(field, "a click"))
    }

    /// The sites the table spreads, `sites` (scene mm), written as its
    /// points, the keys that spread them gone.
    ///
    /// # Errors
    /// [`Error::Invalid`] at `field` when the table has no sites.
    fn pin(&self, field: &str, _sites: &[[f64; 2]]) -> Result<Vec<Change>> {
        Err(refused(field, "pinned sites"))
    }

    /// Which tables are pinned together with this one: those with the
    /// same key that spread the very same sites (one pattern drawn with
    /// two pens). `None`: pinned alone.
    fn pin_key(&self) -> Option<&str> {
        None
    }

    /// Whether its sites are given as points already.
    fn is_pinned(&self) -> bool {
        false
    }

    /// The view turned by `turn` degrees about the vertical and `tilt`
    /// above the horizontal.
    ///
    /// # Errors
    /// [`Error::Invalid`] at `field` when the view does not turn.
    fn turn(&self, field: &str, _turn: f64, _tilt: f64) -> Result<Vec<Change>> {
        Err(refused(field, "a turn"))
    }

    /// The stroke `points` (scene mm, to a tenth) written as the table's
    /// stroke.
    ///
    /// # Errors
    /// [`Error::Invalid`] at `field` when the table follows no stroke.
    fn stroke(&self, field: &str, _points: &[[f64; 2]]) -> Result<Vec<Change>> {
        Err(refused(field, "a stroke"))
    }
}

fn refused(field: &str, what: &str) -> Error {
    Error::invalid(field, format!("this table takes no {what}"))
}

/// `v` to a tenth (of a millimetre, of a degree): what a gesture writes,
/// finer than a hand places anything.
pub(crate) fn tenth(v: f64) -> f64 {
    (v * 10.0).round() / 10.0
}

/// Points as a TOML list, a few to a line when there are many (a stroke,
/// a table's sites), so that the description stays readable.
pub(crate) fn point_list(points: &[[f64; 2]]) -> Array {
    const PER_LINE: usize = 6;
    let mut list = Array::new();
    for (i, &[x, y]) in points.iter().enumerate() {
        let mut pair = Array::new();
        pair.push(x);
        pair.push(y);
        let mut pair = Value::Array(pair);
        if points.len() > PER_LINE {
            let prefix = if i % PER_LINE == 0 { "\n  " } else { " " };
            pair.decor_mut().set_prefix(prefix);
        }
        list.push_formatted(pair);
    }
    if points.len() > PER_LINE {
        list.set_trailing_comma(true);
        list.set_trailing("\n");
    }
    list
}
