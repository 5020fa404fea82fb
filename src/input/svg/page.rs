//! The page of an imported document: its size in millimetres, from usvg's
//! `f32` size, replaced by the same size computed in `f64` from the
//! source's `width`, `height` and `viewBox` where the two agree.

use std::str::FromStr;

use resvg::usvg::{self, roxmltree};
use svgtypes::{Length, LengthUnit, ViewBox};

use crate::error::{Error, Result};
use crate::units::{Margins, Page, MAX_COORD, MM_PER_INCH};

/// Page sizes and pen widths are rounded to 1/this mm (a nanometre), which
/// removes usvg's `f32` noise (`420.00001`) without changing anything a
/// plotter could draw.
const SIZE_STEPS_PER_MM: f64 = 1e6;

/// An absolute length (`12`, `12px`, `210mm`, `8.5in`…) in mm; `None` for
/// percentages, font-relative units and anything malformed.
fn length_mm(value: &str, mm_per_px: f64) -> Option<f64> {
    let length = Length::from_str(value.trim()).ok()?;
    let mm_per_unit = match length.unit {
        LengthUnit::None | LengthUnit::Px => mm_per_px,
        LengthUnit::Mm => 1.0,
        LengthUnit::Cm => 10.0,
        LengthUnit::In => MM_PER_INCH,
        LengthUnit::Pt => MM_PER_INCH / 72.0,
        LengthUnit::Pc => MM_PER_INCH / 6.0,
        LengthUnit::Em | LengthUnit::Ex | LengthUnit::Percent => return None,
    };
    Some(length.number * mm_per_unit)
}

/// The page size in mm computed in `f64` from the root's `width`,
/// `height` and `viewBox`, following usvg's rules; `None` where usvg would
/// need more (percentages, font units).
pub(super) fn exact_size(root: roxmltree::Node<'_, '_>, mm_per_px: f64) -> Option<(f64, f64)> {
    let side = |name| root.attribute(name).map(|v| length_mm(v, mm_per_px));
    let view_box = root
        .attribute("viewBox")
        .and_then(|v| ViewBox::from_str(v).ok())
        .map(|b| (b.w, b.h));
    match (side("width"), side("height"), view_box) {
        (Some(Some(w)), Some(Some(h)), _) => Some((w, h)),
        (Some(Some(w)), None, Some((vw, vh))) => Some((w, w * vh / vw)),
        (None, Some(Some(h)), Some((vw, vh))) => Some((h * vw / vh, h)),
        (None, None, Some((vw, vh))) => Some((vw * mm_per_px, vh * mm_per_px)),
        _ => None,
    }
}

/// The page: the document's size in mm, no margins. usvg's size is `f32`;
/// the same size computed in `f64` from the source replaces it when the
/// two agree, so that `width="148mm"` is exactly 148.
pub(super) fn page_of(
    tree: &usvg::Tree,
    exact: Option<(f64, f64)>,
    mm_per_px: f64,
) -> Result<Page> {
    let size = tree.size();
    let mut mm = [0.0; 2];
    for (i, (px, name)) in [(size.width(), "width"), (size.height(), "height")]
        .into_iter()
        .enumerate()
    {
        let approx = f64::from(px) * mm_per_px;
        let v = match exact.map(|(w, h)| if i == 0 { w } else { h }) {
            Some(v) if (v - approx).abs() <= 1e-5 * approx.abs() => v,
            _ => round_size(approx),
        };
        if !(v.is_finite() && v > 0.0 && v <= MAX_COORD) {
            return Err(Error::invalid(
                format!("svg {name}"),
                format!("the page {name} must be within 0–{MAX_COORD} mm, got {v} mm"),
            ));
        }
        mm[i] = v;
    }
    Ok(Page {
        width: mm[0],
        height: mm[1],
        margins: Margins::default(),
    })
}

/// `v` mm rounded to a nanometre. Dividing by the exact `1e6` gives the
/// double nearest to the decimal, so `0.30000001` becomes exactly `0.3`.
pub(super) fn round_size(v: f64) -> f64 {
    (v * SIZE_STEPS_PER_MM).round() / SIZE_STEPS_PER_MM
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{import, near, paths};
    use super::super::{import_svg, ImportOptions};
    use crate::units::Margins;
    use kurbo::PathEl;

    #[test]
    fn px_and_mm_documents_scale_right() {
        let px = import(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="50">
               <line x1="0" y1="0" x2="96" y2="0" stroke="black"/></svg>"#,
        );
        let page = px.scene.page;
        assert!((page.width - 26.458_333).abs() < 1e-6, "{page:?}");
        assert!((page.height - 13.229_167).abs() < 1e-6, "{page:?}");
        assert_eq!(page.margins, Margins::default());
        assert!((px.scene.stats().pen_down_mm - 25.4).abs() < 1e-4);

        let scaled = import(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="50mm" viewBox="0 0 1000 500">
               <line x1="0" y1="0" x2="1000" y2="0" stroke="black" stroke-width="10"/></svg>"#,
        );
        assert_eq!(
            (scaled.scene.page.width, scaled.scene.page.height),
            (100.0, 50.0)
        );
        assert!((scaled.scene.stats().pen_down_mm - 100.0).abs() < 1e-4);
        assert_eq!(scaled.scene.pens[0].width, 1.0);

        let inches = import(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="4in" height="2in">
               <line x1="0" y1="0" x2="96" y2="0" stroke="black"/></svg>"#,
        );
        assert_eq!(
            (inches.scene.page.width, inches.scene.page.height),
            (101.6, 50.8)
        );
        assert!((inches.scene.stats().pen_down_mm - 25.4).abs() < 1e-4);

        // moyo's own page: one user unit is one millimetre.
        let a3 = import(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="420mm" height="297mm" viewBox="0 0 420 297">
               <path d="M 0 0 L 420 297" stroke="black"/></svg>"#,
        );
        assert_eq!((a3.scene.page.width, a3.scene.page.height), (420.0, 297.0));
        let els = paths(&a3.scene)[0].1.elements().to_vec();
        assert!(matches!(els[1], PathEl::LineTo(p) if near(p, (420.0, 297.0).into(), 1e-4)));

        // An old Illustrator file at 72 px per inch.
        let options = ImportOptions::DEFAULT.with_px_per_inch(72.0);
        let old = import_svg(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="72" height="144"/>"#,
            &options,
        )
        .unwrap();
        assert_eq!((old.scene.page.width, old.scene.page.height), (25.4, 50.8));
        assert_eq!(old.scene.path_count(), 0);
    }
}
