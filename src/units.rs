//! Lengths and paper: named paper sizes, orientation, margins.
//!
//! All public lengths in moyo are millimetres. The SVG writer maps one user
//! unit to one millimetre (`viewBox` in mm, `width`/`height` with `mm`).

use kurbo::Rect;
use serde::{Deserialize, Serialize};

/// Millimetres per inch, for DPI conversions.
pub const MM_PER_INCH: f64 = 25.4;

/// Largest coordinate accepted anywhere, in mm (100 m): far beyond any
/// plotter, small enough that nothing overflows.
pub const MAX_COORD: f64 = 100_000.0;

/// A named paper size.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum PaperName {
    /// 148 × 210 mm.
    A5,
    /// 210 × 297 mm.
    A4,
    /// 297 × 420 mm.
    A3,
    /// 420 × 594 mm.
    A2,
    /// US letter, 8.5 × 11 in.
    #[serde(rename = "letter")]
    Letter,
    /// US legal, 8.5 × 14 in.
    #[serde(rename = "legal")]
    Legal,
    /// Tabloid, 11 × 17 in.
    #[serde(rename = "tabloid")]
    Tabloid,
}

impl PaperName {
    /// Every named size, for listings and error messages.
    pub const ALL: [PaperName; 7] = [
        PaperName::A5,
        PaperName::A4,
        PaperName::A3,
        PaperName::A2,
        PaperName::Letter,
        PaperName::Legal,
        PaperName::Tabloid,
    ];

    /// Portrait width and height in millimetres.
    pub fn portrait_mm(self) -> (f64, f64) {
        match self {
            PaperName::A5 => (148.0, 210.0),
            PaperName::A4 => (210.0, 297.0),
            PaperName::A3 => (297.0, 420.0),
            PaperName::A2 => (420.0, 594.0),
            PaperName::Letter => (215.9, 279.4),
            PaperName::Legal => (215.9, 355.6),
            PaperName::Tabloid => (279.4, 431.8),
        }
    }
}

/// Paper orientation. `Portrait` puts the shorter side horizontal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Orientation {
    /// Shorter side horizontal.
    #[default]
    Portrait,
    /// Longer side horizontal.
    Landscape,
}

/// Margins in millimetres.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Margins {
    /// Top margin.
    pub top: f64,
    /// Right margin.
    pub right: f64,
    /// Bottom margin.
    pub bottom: f64,
    /// Left margin.
    pub left: f64,
}

impl Margins {
    /// The same margin on all four sides.
    pub fn uniform(m: f64) -> Margins {
        Margins {
            top: m,
            right: m,
            bottom: m,
            left: m,
        }
    }
}

/// A resolved page: size in millimetres and the margins.
///
/// Scene coordinates are page coordinates: origin at the top-left corner of
/// the *drawable area* (inside the margins), x to the right, y down, in mm —
/// the SVG convention, so numbers in a scene file read like SVG numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Page {
    /// Page width in mm.
    pub width: f64,
    /// Page height in mm.
    pub height: f64,
    /// Margins in mm.
    pub margins: Margins,
}

impl Page {
    /// A page of a named size in the given orientation, with margins.
    pub fn named(name: PaperName, orientation: Orientation, margins: Margins) -> Page {
        let (w, h) = name.portrait_mm();
        Page::sized(w, h, orientation, margins)
    }

    /// A page of explicit size. `orientation` swaps the sides when they do
    /// not already match it.
    pub fn sized(w: f64, h: f64, orientation: Orientation, margins: Margins) -> Page {
        let (short, long) = if w <= h { (w, h) } else { (h, w) };
        let (width, height) = match orientation {
            Orientation::Portrait => (short, long),
            Orientation::Landscape => (long, short),
        };
        Page {
            width,
            height,
            margins,
        }
    }

    /// The drawable area in page coordinates (the sheet minus the margins).
    pub fn drawable(&self) -> Rect {
        Rect::new(
            self.margins.left,
            self.margins.top,
            self.width - self.margins.right,
            self.height - self.margins.bottom,
        )
    }

    /// Size in pixels of a raster preview at `dpi`, at least 1 × 1.
    pub fn pixels(&self, dpi: f64) -> (u32, u32) {
        let px = |mm: f64| ((mm / MM_PER_INCH * dpi).round() as u32).max(1);
        (px(self.width), px(self.height))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn landscape_swaps_sides() {
        let p = Page::named(PaperName::A4, Orientation::Landscape, Margins::default());
        assert_eq!((p.width, p.height), (297.0, 210.0));
        let p = Page::sized(300.0, 100.0, Orientation::Portrait, Margins::default());
        assert_eq!((p.width, p.height), (100.0, 300.0));
    }

    #[test]
    fn drawable_area_is_inside_margins() {
        let p = Page::named(PaperName::A5, Orientation::Portrait, Margins::uniform(10.0));
        assert_eq!(p.drawable(), Rect::new(10.0, 10.0, 138.0, 200.0));
    }

    #[test]
    fn a4_at_150_dpi() {
        let p = Page::named(PaperName::A4, Orientation::Portrait, Margins::default());
        assert_eq!(p.pixels(150.0), (1240, 1754));
    }
}
