//! Placing the drawing on the sheet: rotate, scale, fit to the page,
//! centre.
//!
//! All of it happens in page coordinates (mm, origin at the sheet's
//! top-left corner, y down) and works on any scene, flat or not. [`apply`]
//! runs the steps of [`TransformOptions`] in this order:
//!
//! 1. **rotate** by [`TransformOptions::rotate_deg`] about the centre of
//!    the sheet (positive is clockwise as seen on the page, since y points
//!    down);
//! 2. **scale** by [`TransformOptions::scale`] about the centre of the
//!    sheet;
//! 3. **fit**: scale uniformly (up or down, keeping the aspect ratio) so
//!    the bounding box of the drawing just fits the drawable area, and
//!    centre it there;
//! 4. **centre**: move the drawing so its bounding box is centred in the
//!    drawable area, without scaling.
//!
//! The drawable area is the sheet minus [`TransformOptions::margin`] on
//! every side, or minus the scene's own page margins when that is `None`.
//! A flat scene (see [`super::flatten`]) has zero margins, so fitting it
//! fills the whole sheet unless a margin is given — or transform before
//! flattening. Bounding boxes are those of the path geometry (curves
//! included, stroke width not).
//!
//! A flat layer gets the transform applied to its path coordinates (so it
//! stays flat); any other layer gets it composed into its content group's
//! transform. Affine maps take Bézier curves to Bézier curves exactly, so
//! nothing is approximated.

use kurbo::{Affine, Point, Rect};
use serde::{Deserialize, Serialize};

use super::flatten::is_flat;
use crate::scene::{Node, Scene};

/// Options of [`apply`].
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TransformOptions {
    /// Rotation in degrees about the sheet's centre, clockwise on the page.
    pub rotate_deg: f64,
    /// Scale factor about the sheet's centre.
    pub scale: f64,
    /// Scale the drawing to fit the drawable area and centre it there.
    pub fit: bool,
    /// Centre the drawing in the drawable area.
    pub centre: bool,
    /// Margin in mm on every side of the drawable area used by `fit` and
    /// `centre`; `None` uses the scene's page margins.
    pub margin: Option<f64>,
}

impl TransformOptions {
    /// Nothing changes: no rotation, scale 1, no fitting, no centring.
    pub const DEFAULT: TransformOptions = TransformOptions {
        rotate_deg: 0.0,
        scale: 1.0,
        fit: false,
        centre: false,
        margin: None,
    };

    /// These options with [`TransformOptions::rotate_deg`] set.
    pub const fn with_rotate_deg(mut self, degrees: f64) -> TransformOptions {
        self.rotate_deg = degrees;
        self
    }

    /// These options with [`TransformOptions::scale`] set.
    pub const fn with_scale(mut self, scale: f64) -> TransformOptions {
        self.scale = scale;
        self
    }

    /// These options with [`TransformOptions::fit`] set.
    pub const fn with_fit(mut self, fit: bool) -> TransformOptions {
        self.fit = fit;
        self
    }

    /// These options with [`TransformOptions::centre`] set.
    pub const fn with_centre(mut self, centre: bool) -> TransformOptions {
        self.centre = centre;
        self
    }

    /// These options with [`TransformOptions::margin`] set.
    pub const fn with_margin(mut self, margin: Option<f64>) -> TransformOptions {
        self.margin = margin;
        self
    }
}

impl Default for TransformOptions {
    fn default() -> TransformOptions {
        TransformOptions::DEFAULT
    }
}

/// Rotates, scales, fits and centres the drawing (see the module
/// documentation).
pub fn apply(scene: &mut Scene, options: &TransformOptions) {
    let sheet_centre = Point::new(scene.page.width / 2.0, scene.page.height / 2.0);
    let first = Affine::scale_about(options.scale, sheet_centre)
        * Affine::rotate_about(options.rotate_deg.to_radians(), sheet_centre);
    if first != Affine::IDENTITY {
        transform_scene(scene, first);
    }
    if !(options.fit || options.centre) {
        return;
    }
    let Some(bounds) = scene.bounds() else {
        return;
    };
    let area = match options.margin {
        Some(m) => Rect::new(m, m, scene.page.width - m, scene.page.height - m),
        None => scene.page.drawable(),
    };
    let mut placed = Affine::IDENTITY;
    if options.fit {
        placed = fit(bounds, area);
    }
    if options.centre {
        let b = placed.transform_rect_bbox(bounds);
        placed = Affine::translate(area.center() - b.center()) * placed;
    }
    if placed != Affine::IDENTITY {
        transform_scene(scene, placed);
    }
}

/// The uniform scale and move that fits `bounds` into `area`, centred.
/// Only the move when either has no extent to compare.
fn fit(bounds: Rect, area: Rect) -> Affine {
    let ratio = |have: f64, room: f64| (have > 0.0 && room > 0.0).then(|| room / have);
    let s = match (
        ratio(bounds.width(), area.width()),
        ratio(bounds.height(), area.height()),
    ) {
        (Some(x), Some(y)) => x.min(y),
        (x, y) => x.or(y).unwrap_or(1.0),
    };
    if !s.is_finite() {
        return Affine::translate(area.center() - bounds.center());
    }
    Affine::translate(area.center().to_vec2())
        * Affine::scale(s)
        * Affine::translate(-bounds.center().to_vec2())
}

/// Maps the whole drawing by `t`, given in page coordinates.
pub fn transform_scene(scene: &mut Scene, t: Affine) {
    let page = scene.page_transform();
    let local = page.inverse() * t * page;
    for layer in &mut scene.layers {
        if is_flat(layer) {
            for node in &mut layer.content.children {
                if let Node::Path(p) = node {
                    p.path.apply_affine(local);
                }
            }
        } else {
            layer.content.transform = local * layer.content.transform;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::flatten::by_pen;
    use crate::scene::{Group, Layer, Style};
    use crate::units::{Margins, Orientation, Page, PaperName};
    use kurbo::{BezPath, Line, Shape};

    fn scene(content: Group) -> Scene {
        Scene {
            // A5 portrait: 148 × 210.
            page: Page::named(PaperName::A5, Orientation::Portrait, Margins::uniform(10.0)),
            pens: vec![],
            layers: vec![Layer {
                id: "l".into(),
                name: "l".into(),
                pen: 1,
                depth: 0,
                content,
            }],
            description: None,
        }
    }

    fn rect_scene() -> Scene {
        let mut g = Group::new("g");
        let mut inner = Group::new("inner");
        inner.transform = Affine::scale(2.0);
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.line_to((10.0, 0.0));
        p.line_to((10.0, 5.0));
        inner.push_path("r", p, Style::default());
        g.push_group(inner);
        scene(g)
    }

    fn close(a: Rect, b: Rect) -> bool {
        (a.x0 - b.x0).abs() < 1e-9
            && (a.y0 - b.y0).abs() < 1e-9
            && (a.x1 - b.x1).abs() < 1e-9
            && (a.y1 - b.y1).abs() < 1e-9
    }

    #[test]
    fn default_changes_nothing() {
        let mut s = rect_scene();
        apply(&mut s, &TransformOptions::DEFAULT);
        assert_eq!(s, rect_scene());
    }

    #[test]
    fn fit_fills_the_drawable_area_keeping_aspect() {
        // Bounds in page coordinates: (10,10)–(30,20), 2:1.
        for flat in [false, true] {
            let mut s = rect_scene();
            if flat {
                s = by_pen(&s);
            }
            let margin = flat.then_some(10.0);
            apply(
                &mut s,
                &TransformOptions::DEFAULT.with_fit(true).with_margin(margin),
            );
            // Area 128 × 190: width limits, scale 6.4 → 128 × 64, centred.
            let want = Rect::new(10.0, 105.0 - 32.0, 138.0, 105.0 + 32.0);
            assert!(close(s.bounds().unwrap(), want), "{flat}: {:?}", s.bounds());
            assert_eq!(s.layers[0].content.children.len(), 1);
        }
    }

    #[test]
    fn centre_moves_without_scaling() {
        let mut s = rect_scene();
        apply(&mut s, &TransformOptions::DEFAULT.with_centre(true));
        let want = Rect::new(74.0 - 10.0, 105.0 - 5.0, 74.0 + 10.0, 105.0 + 5.0);
        assert!(close(s.bounds().unwrap(), want), "{:?}", s.bounds());
    }

    #[test]
    fn rotate_and_scale_about_the_sheet_centre() {
        let mut g = Group::new("g");
        let mut inner = Group::new("inner");
        // In page coordinates (margin 10): from the centre (74,105) to the right.
        inner.push_path(
            "a",
            Line::new((64.0, 95.0), (74.0, 95.0)).into_path(0.1),
            Style::default(),
        );
        g.push_group(inner);
        let mut s = scene(g);
        apply(
            &mut s,
            &TransformOptions::DEFAULT
                .with_rotate_deg(90.0)
                .with_scale(2.0),
        );
        // Clockwise on the page: right turns into down; doubled.
        let want = Rect::new(74.0, 105.0, 74.0, 125.0);
        assert!(close(s.bounds().unwrap(), want), "{:?}", s.bounds());
        // Still a nested-transform layer: the transform went on the group.
        assert_ne!(s.layers[0].content.transform, Affine::IDENTITY);

        let mut flat = by_pen(&scene({
            let mut g = Group::new("g");
            g.push_path(
                "a",
                Line::new((64.0, 95.0), (74.0, 95.0)).into_path(0.1),
                Style::default(),
            );
            g
        }));
        apply(
            &mut flat,
            &TransformOptions::DEFAULT
                .with_rotate_deg(90.0)
                .with_scale(2.0),
        );
        assert!(close(flat.bounds().unwrap(), want), "{:?}", flat.bounds());
        assert!(is_flat(&flat.layers[0]));
    }

    #[test]
    fn fit_of_a_straight_line_uses_its_one_extent() {
        let mut g = Group::new("g");
        g.push_path(
            "a",
            Line::new((0.0, 0.0), (10.0, 0.0)).into_path(0.1),
            Style::default(),
        );
        let mut s = scene(g);
        apply(&mut s, &TransformOptions::DEFAULT.with_fit(true));
        let want = Rect::new(10.0, 105.0, 138.0, 105.0);
        assert!(close(s.bounds().unwrap(), want), "{:?}", s.bounds());
    }
}
