//! The studio's pen: a stroke drawn on the page grows a sketch L-system
//! as it comes in — one [`GrowingSketch`] extended by every batch of
//! points, never grown again from the start — and when the pen lifts,
//! the stroke becomes the sketch table's `points` (a new table when the
//! stroke starts one), so nothing of it lives only in the page.
//!
//! The points are kept as the description will hold them (a tenth of a
//! millimetre, at least [`MIN_GAP`] apart, joined by straight lines), so
//! that the render after the stroke draws exactly what grew under the
//! pen.

use glam::DVec2;
use kurbo::BezPath;
use toml_edit::Array;

use super::edit::{table_index, Edit};
use super::session::Good;
use crate::error::{Error, Result};
use crate::family::gesture::{point_list, tenth, Change, Gestures};
use crate::family::lsystem::gesture::new_sketch;
use crate::family::lsystem::GrowingSketch;
use crate::output::write_path_data;
use crate::spec::validate::{point, MAX_POINTS};
use crate::spec::LSystemSpec;

/// Points of a stroke closer than this to the last one kept (mm) are
/// left out: finer than a pen draws, and they would only lengthen the
/// description.
pub(crate) const MIN_GAP: f64 = 0.5;

/// The most points a stroke keeps: as many as a line of points in a
/// description may have, so a stroke that would not be written is
/// refused as it comes in rather than grown without end.
pub const MAX_STROKE_POINTS: usize = MAX_POINTS;

/// Decimals of the live drawing's path data.
const PRECISION: u8 = 2;

/// Where a stroke goes: a sketch table already there, or a new one at
/// the end of a layer's L-systems.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Target {
    /// The field path of an `lsystem` table with a `[sketch]`.
    Table(String),
    /// A new sketch table in the layer with this index.
    New(usize),
}

/// A stroke being drawn.
pub(crate) struct Stroke {
    target: Target,
    /// The sketch table it goes into (as it will be, for a new one).
    table: LSystemSpec,
    growing: GrowingSketch,
    points: Vec<[f64; 2]>,
    /// The colour and width of the pen that will draw it.
    pen: (String, f64),
    outline: bool,
}

/// What the page draws while the stroke comes in.
#[derive(Debug, Clone, serde::Serialize)]
pub(crate) struct Growth {
    /// Steps of the sketch so far.
    pub steps: usize,
    /// The limbs as SVG path data (scene mm), or `None` when no step was
    /// taken since the last answer (the drawing is as it was).
    pub paths: Option<Vec<String>>,
    /// Outlines (drawn as one silhouette) rather than centre lines.
    pub outline: bool,
    /// The pen's colour.
    pub color: String,
    /// The pen's width, mm.
    pub width: f64,
}

impl Stroke {
    /// Starts a stroke at `at` (scene mm) for `target` in the design
    /// `good`.
    ///
    /// # Errors
    /// [`Error::Invalid`] at `target` when it is not a sketch table of
    /// the design or not a layer of it, at `at` for a point past
    /// ±[`crate::units::MAX_COORD`] mm.
    pub(crate) fn begin(good: &Good, target: Target, at: [f64; 2]) -> Result<(Stroke, Growth)> {
        point("at", at)?;
        let spec = good.spec.spec();
        let (table, layer, field) = match &target {
            Target::Table(field) => {
                let place = table_index(field, "lsystem")
                    .and_then(|(l, t)| Some((spec.layers.get(l)?.lsystem.get(t)?, l)));
                let Some((table, layer)) = place.filter(|(t, _)| t.sketch.is_some()) else {
                    return Err(Error::invalid(field, "is not a sketch table of the design"));
                };
                (table.clone(), layer, field.clone())
            }
            Target::New(layer) => {
                if *layer >= spec.layers.len() {
                    return Err(Error::invalid(
                        format!("layers[{layer}]"),
                        "the design has no such layer",
                    ));
                }
                let text =
                    toml_edit::DocumentMut::from(new_sketch("new", Array::new())).to_string();
                let table: LSystemSpec =
                    toml::from_str(&text).map_err(|e| Error::invalid("studio", e.to_string()))?;
                (table, *layer, format!("layers[{layer}].lsystem[new]"))
            }
        };
        let scene = &good.rendered.scene;
        let pen = scene
            .layers
            .get(layer)
            .and_then(|l| scene.pens.iter().find(|p| p.number == l.pen))
            .map_or_else(
                || ("#1d1d1f".to_string(), 0.3),
                |p| (p.color.to_string(), p.width),
            );
        // Kept on the page as the render keeps it.
        let growing = GrowingSketch::new(&table, &field, spec.limits.max_segments)?
            .with_pen_width(pen.1)
            .within(scene.page.drawable().size());
        let mut stroke = Stroke {
            target,
            growing,
            points: Vec::new(),
            pen,
            outline: table.style == crate::spec::LimbStyle::Outline,
            table,
        };
        let mut growth = stroke.extend(&[at])?;
        // The page clears what an earlier stroke left.
        growth.paths = Some(Vec::new());
        Ok((stroke, growth))
    }

    /// Adds `points` (scene mm) to the stroke and grows the sketch. A
    /// batch with a point out of range, or one too many, adds nothing:
    /// the stroke is as it was, and the pen can still lift.
    ///
    /// # Errors
    /// [`Error::Invalid`] at `points[i]` for a point that is not finite or
    /// lies past ±[`crate::units::MAX_COORD`] mm, at `points` when the
    /// stroke would keep more than [`MAX_STROKE_POINTS`], or when the
    /// sketch would grow past the design's segment limit.
    pub(crate) fn extend(&mut self, points: &[[f64; 2]]) -> Result<Growth> {
        let before = self.growing.steps();
        let mut kept: Vec<[f64; 2]> = Vec::new();
        for (i, &p) in points.iter().enumerate() {
            point(&format!("points[{i}]"), p)?;
            let p = p.map(tenth);
            let far = kept
                .last()
                .or(self.points.last())
                .is_none_or(|q| (p[0] - q[0]).hypot(p[1] - q[1]) >= MIN_GAP);
            if far {
                kept.push(p);
            }
            if self.points.len() + kept.len() > MAX_STROKE_POINTS {
                return Err(Error::invalid(
                    "points",
                    format!(
                        "a stroke has at most {MAX_STROKE_POINTS} points (at least \
                         {MIN_GAP} mm apart): lift the pen and draw on in a new stroke"
                    ),
                ));
            }
        }
        self.points.extend_from_slice(&kept);
        let taken: Vec<DVec2> = kept.into_iter().map(DVec2::from_array).collect();
        self.growing.extend(&taken)?;
        let grew = self.growing.steps() != before;
        Ok(Growth {
            steps: self.growing.steps(),
            paths: grew.then(|| self.growing.paths().iter().map(path_data).collect()),
            outline: self.outline,
            color: self.pen.0.clone(),
            width: self.pen.1,
        })
    }

    /// The description `text` with the stroke written into it: the
    /// table's stroke replaced by these points, or a new sketch table.
    ///
    /// # Errors
    /// [`Error::Invalid`] at `points` for a stroke with no length, or
    /// what the edit of the text reports.
    pub(crate) fn finish(&self, text: &str) -> Result<String> {
        if self.points.len() < 2 {
            return Err(Error::invalid(
                "points",
                format!("the stroke has no length: draw further than {MIN_GAP} mm"),
            ));
        }
        let changes = match &self.target {
            Target::Table(field) => self.table.stroke(field, &self.points)?,
            Target::New(layer) => vec![Change::Push {
                field: format!("layers[{layer}].lsystem"),
                table: new_sketch(&self.new_id(text, *layer), point_list(&self.points)),
                inline: false,
            }],
        };
        Edit::with_changes(text, changes)
    }

    /// An id for a new sketch that no table of the layer has.
    fn new_id(&self, text: &str, layer: usize) -> String {
        let taken: Vec<String> = toml::from_str::<toml::Value>(text)
            .ok()
            .and_then(|v| {
                let tables = v
                    .get("layers")?
                    .get(layer)?
                    .get("lsystem")?
                    .as_array()?
                    .clone();
                Some(
                    tables
                        .iter()
                        .filter_map(|t| Some(t.get("id")?.as_str()?.to_string()))
                        .collect(),
                )
            })
            .unwrap_or_default();
        (1..)
            .map(|k| format!("sketch-{k}"))
            .find(|id| !taken.contains(id))
            .unwrap_or_default()
    }
}

fn path_data(path: &BezPath) -> String {
    let mut d = String::new();
    write_path_data(&mut d, path, PRECISION);
    d
}
