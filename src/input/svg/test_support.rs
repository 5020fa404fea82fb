//! Helpers shared by the import tests: a document around a body, importing
//! it, and reading the paths back.

use kurbo::{BezPath, Point, Rect};

use super::{import_svg, ImportOptions, Imported};
use crate::error::Error;
use crate::scene::{Scene, Style};

const OPEN: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" width="200mm" height="100mm" viewBox="0 0 200 100">"#;

/// A 200 × 100 mm document, one user unit per mm, around `body`.
pub(super) fn doc(body: &str) -> String {
    format!("{OPEN}\n{body}\n</svg>\n")
}

pub(super) fn import(text: &str) -> Imported {
    import_svg(text, &ImportOptions::DEFAULT).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

pub(super) fn import_err(text: &str) -> Error {
    match import_svg(text, &ImportOptions::DEFAULT) {
        Ok(imported) => panic!("expected an error, got {imported:?}"),
        Err(e) => e,
    }
}

/// Every path in page coordinates with its pen number and style, in
/// scene order.
pub(super) fn paths(scene: &Scene) -> Vec<(u32, BezPath, Style)> {
    let mut v = Vec::new();
    scene.visit_paths(|l, p, t| v.push((l.pen, t * p.path.clone(), p.style.clone())));
    v
}

/// The one path of a document made of `body`.
pub(super) fn only_path(body: &str) -> BezPath {
    let imported = import(&doc(body));
    let all = paths(&imported.scene);
    assert_eq!(all.len(), 1, "{body}: {all:?}");
    all[0].1.clone()
}

pub(super) fn near(a: Point, b: Point, tol: f64) -> bool {
    (a - b).hypot() <= tol
}

pub(super) fn assert_rect_near(a: Rect, b: Rect, tol: f64) {
    assert!(
        near(a.origin(), b.origin(), tol) && near((a.x1, a.y1).into(), (b.x1, b.y1).into(), tol),
        "{a:?} != {b:?}"
    );
}
