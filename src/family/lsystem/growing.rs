//! A sketch table's structure growing as its stroke comes in, point by
//! point: what the studio shows under the pen while a stroke is drawn,
//! and what a render grows along the whole stroke at once — the same
//! code, so that the picture drawn live is the one the render makes.

use glam::DVec2;
use kurbo::BezPath;

use super::draw::{flat, Projection};
use super::{drawn_limbs, strokes_first, MAX_SEGMENTS};
use crate::error::{Error, Result};
use crate::family::lsystem::engine::sketch::Sketch;
use crate::family::lsystem::engine::Skeleton;
use crate::spec::{LSystemSpec, LimbStyle};

/// See the module docs. The stroke is in scene millimetres (the corner
/// of the page's margins is the origin), as the table's `points` are.
#[derive(Debug, Clone)]
pub(crate) struct GrowingSketch {
    sketch: Sketch,
    /// Stroke length past which points are not taken: `steps` modules
    /// (infinite without `steps`).
    limit: f64,
    /// Stroke length taken so far.
    walked: f64,
    /// The last point taken.
    last: Option<DVec2>,
    /// How the studio's live drawing draws the limbs ([`Self::paths`]; a
    /// build without the studio only grows sketches).
    #[cfg_attr(not(feature = "studio"), allow(dead_code))]
    smooth: bool,
    #[cfg_attr(not(feature = "studio"), allow(dead_code))]
    outline: bool,
    /// The pen's width, mm (see [`GrowingSketch::with_pen_width`]).
    pen_width: f64,
}

impl GrowingSketch {
    /// The table's sketch with no stroke yet, growing to at most
    /// `max_segments` segments (and never past moyo's own limit).
    ///
    /// # Errors
    /// [`Error::Invalid`] at `field` when the table has no `sketch`, or at
    /// `field.sketch` for rules that do not parse.
    pub(crate) fn new(
        spec: &LSystemSpec,
        field: &str,
        max_segments: usize,
    ) -> Result<GrowingSketch> {
        let sketch = spec
            .sketch
            .as_ref()
            .ok_or_else(|| Error::invalid(field, "has no [sketch] to draw a stroke for"))?;
        let rules = sketch.rules(&format!("{field}.sketch"))?;
        Ok(GrowingSketch {
            sketch: Sketch::new(rules, MAX_SEGMENTS.min(max_segments))?,
            // A hair past `steps` modules, so that rounding cannot lose
            // the last.
            limit: sketch
                .steps
                .map_or(f64::INFINITY, |k| f64::from(k) * sketch.module + 1e-9),
            walked: 0.0,
            last: None,
            smooth: spec.smooth,
            outline: spec.style == LimbStyle::Outline,
            pen_width: 0.0,
        })
    }

    /// This sketch drawn by a pen `pen_width` mm wide: outlined limbs
    /// narrower than two pen widths are drawn as centre strokes, as the
    /// render draws them with the layer's pen. Default 0: every limb as
    /// the table's style asks.
    /// The pen also sets the sketch's shortest limb and the room kept
    /// between trunk and branches ([`Sketch::with_pen`]).
    pub(crate) fn with_pen_width(self, pen_width: f64) -> GrowingSketch {
        GrowingSketch {
            sketch: self.sketch.with_pen(pen_width),
            pen_width,
            ..self
        }
    }

    /// This sketch kept on a drawable area `size` mm (scene millimetres:
    /// from the margins' corner), see [`Sketch::within`].
    pub(crate) fn within(self, size: kurbo::Size) -> GrowingSketch {
        GrowingSketch {
            sketch: self
                .sketch
                .within(DVec2::ZERO, DVec2::new(size.width, size.height)),
            ..self
        }
    }

    /// Whether the stroke left the page, where the sketch stopped growing.
    pub(crate) fn off_page(&self) -> bool {
        self.sketch.off_page()
    }

    /// Appends `points` to the stroke, up to where `steps` modules end
    /// (the point there is taken, later ones are not), and grows one step
    /// per module the stroke now reaches. Extending point by point gives
    /// exactly what extending with every point at once does.
    ///
    /// Returns the number of steps taken.
    ///
    /// # Errors
    /// As [`Sketch::extend`]: a point that is not finite, or a structure
    /// that would grow past its segment limit.
    pub(crate) fn extend(&mut self, points: &[DVec2]) -> Result<usize> {
        let mut taken = Vec::with_capacity(points.len());
        for &p in points {
            if self.walked >= self.limit {
                break;
            }
            let Some(from) = self.last else {
                taken.push(p);
                self.last = Some(p);
                continue;
            };
            let step = from.distance(p);
            if self.walked + step >= self.limit {
                let t = if step > 0.0 {
                    (self.limit - self.walked) / step
                } else {
                    0.0
                };
                let end = from.lerp(p, t);
                taken.push(end);
                self.last = Some(end);
                self.walked = self.limit;
                break;
            }
            self.walked += step;
            taken.push(p);
            self.last = Some(p);
        }
        self.sketch.extend(&taken)
    }

    /// The steps taken so far.
    pub(crate) fn steps(&self) -> usize {
        self.sketch.steps()
    }

    /// The structure so far.
    pub(crate) fn skeleton(&self) -> Skeleton {
        self.sketch.skeleton()
    }

    /// The limbs so far as the table draws them (centre lines, splines
    /// or outlines), in scene millimetres; the flowers and leaves come
    /// with the render.
    #[cfg_attr(not(feature = "studio"), allow(dead_code))]
    pub(crate) fn paths(&self) -> Vec<BezPath> {
        let flat = flat(&self.sketch.skeleton(), &Projection::PAGE);
        strokes_first(drawn_limbs(
            &flat,
            self.smooth,
            self.outline,
            1.0,
            self.pen_width,
        ))
        .into_iter()
        .map(|(_, path)| path)
        .collect()
    }
}
