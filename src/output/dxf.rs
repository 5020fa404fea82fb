//! DXF for cutters and CAD: AutoCAD R12 (`AC1009`) text, the version every
//! cutting program imports (Silhouette Studio's basic edition reads DXF,
//! not SVG).
//!
//! Millimetres, y up from the bottom edge of the sheet (DXF's convention),
//! the sheet's bottom-left corner at the origin. One layer per pen, named
//! `PEN-N` (R12 names: capitals, digits, `-` and `_`, at most 31
//! characters), listed in the `LAYER` table. Every stroke of the stroke
//! model (`output::strokes`) is one `POLYLINE` (closed flag for a closed
//! outline, its first point not repeated) with its `VERTEX`es and a
//! `SEQEND`; a dot is a `POINT`. Entities come in the order the pens draw
//! them, so a cutting program that keeps file order keeps the plot order
//! (inside first, for a cutter). Numbers go through [`write_number`]: same
//! scene, same bytes.

use super::strokes::{pen_blocks, positive, ToMachine};
use super::write_number;
use crate::error::Result;
use crate::scene::Scene;

/// Options of [`to_dxf`].
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DxfOptions {
    /// Flattening tolerance in mm. Default 0.01 mm.
    pub tolerance: f64,
    /// Decimals of a millimetre written. Default 4.
    pub precision: u8,
}

impl DxfOptions {
    /// Tolerance 0.01 mm, four decimals.
    pub const DEFAULT: DxfOptions = DxfOptions {
        tolerance: 0.01,
        precision: 4,
    };

    /// These options with [`DxfOptions::tolerance`] set.
    pub const fn with_tolerance(mut self, mm: f64) -> DxfOptions {
        self.tolerance = mm;
        self
    }

    /// These options with [`DxfOptions::precision`] set.
    pub const fn with_precision(mut self, decimals: u8) -> DxfOptions {
        self.precision = decimals;
        self
    }

    /// Checks the tolerance.
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] (field `dxf.tolerance`) unless it is a
    /// number above zero.
    pub fn validate(&self) -> Result<()> {
        positive("dxf.tolerance", self.tolerance)
    }
}

impl Default for DxfOptions {
    fn default() -> DxfOptions {
        DxfOptions::DEFAULT
    }
}

/// The R12 DXF text of the plotted layers of `scene` (see the module
/// documentation).
pub fn to_dxf(scene: &Scene, options: &DxfOptions) -> String {
    let to_machine = ToMachine {
        page: (scene.page.width, scene.page.height),
        mirror_x: false,
        from_bottom: true,
        negate_y: false,
    };
    let blocks = pen_blocks(scene, options.tolerance);
    let mut w = Writer {
        out: String::new(),
        precision: options.precision,
    };
    w.pair(
        999,
        "moyo: millimetres, y up from the bottom edge of the sheet",
    );
    w.section("HEADER");
    w.pair(9, "$ACADVER");
    w.pair(1, "AC1009");
    w.pair(9, "$EXTMIN");
    w.point(10, 0.0, 0.0);
    w.pair(9, "$EXTMAX");
    w.point(10, scene.page.width, scene.page.height);
    w.pair(0, "ENDSEC");
    w.section("TABLES");
    w.pair(0, "TABLE");
    w.pair(2, "LAYER");
    w.pair(70, &blocks.len().to_string());
    for block in &blocks {
        w.pair(0, "LAYER");
        w.pair(2, &layer_name(block.number));
        w.pair(70, "0");
        // AutoCAD's colour index: pens 1–7 in its seven basic colours.
        w.pair(62, &((block.number.saturating_sub(1) % 7) + 1).to_string());
        w.pair(6, "CONTINUOUS");
    }
    w.pair(0, "ENDTAB");
    w.pair(0, "ENDSEC");
    w.section("ENTITIES");
    for block in &blocks {
        let layer = layer_name(block.number);
        for stroke in block.paths.iter().flat_map(|p| &p.strokes) {
            let machine = to_machine.stroke(stroke);
            let points = match machine.points.as_slice() {
                [p] => {
                    w.pair(0, "POINT");
                    w.pair(8, &layer);
                    w.point(10, p.x, p.y);
                    continue;
                }
                // A closed stroke ends on its first point; the flag closes it.
                [rest @ .., _] if machine.closed => rest,
                all => all,
            };
            w.pair(0, "POLYLINE");
            w.pair(8, &layer);
            w.pair(66, "1");
            w.point(10, 0.0, 0.0);
            w.pair(70, if machine.closed { "1" } else { "0" });
            for p in points {
                w.pair(0, "VERTEX");
                w.pair(8, &layer);
                w.point(10, p.x, p.y);
            }
            w.pair(0, "SEQEND");
            w.pair(8, &layer);
        }
    }
    w.pair(0, "ENDSEC");
    w.pair(0, "EOF");
    w.out
}

/// The DXF layer of pen `number`.
fn layer_name(number: u32) -> String {
    format!("PEN-{number}")
}

/// Group codes and values, one per line.
struct Writer {
    out: String,
    precision: u8,
}

impl Writer {
    fn pair(&mut self, code: u16, value: &str) {
        self.out.push_str(&code.to_string());
        self.out.push('\n');
        self.out.push_str(value);
        self.out.push('\n');
    }

    fn number(&mut self, code: u16, v: f64) {
        self.out.push_str(&code.to_string());
        self.out.push('\n');
        write_number(&mut self.out, v, self.precision);
        self.out.push('\n');
    }

    /// A point: x under `code`, y under `code + 10`, z 0 under `code + 20`.
    fn point(&mut self, code: u16, x: f64, y: f64) {
        self.number(code, x);
        self.number(code + 10, y);
        self.number(code + 20, 0.0);
    }

    fn section(&mut self, name: &str) {
        self.pair(0, "SECTION");
        self.pair(2, name);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::strokes::tests::two_pen_scene;

    /// The (code, value) pairs of a DXF text.
    fn pairs(dxf: &str) -> Vec<(u16, &str)> {
        let lines: Vec<&str> = dxf.lines().collect();
        assert_eq!(lines.len() % 2, 0, "group codes and values pair up");
        lines
            .chunks(2)
            .map(|c| (c[0].trim().parse().expect("a group code"), c[1]))
            .collect()
    }

    #[test]
    fn one_layer_per_pen_and_one_polyline_per_stroke() {
        let scene = two_pen_scene();
        let dxf = to_dxf(&scene, &DxfOptions::DEFAULT);
        let pairs = pairs(&dxf);
        assert_eq!(pairs.last(), Some(&(0, "EOF")));
        let layers: Vec<&str> = pairs
            .windows(2)
            .filter(|w| w[0] == (0, "LAYER"))
            .map(|w| w[1].1)
            .collect();
        assert_eq!(layers, ["PEN-1", "PEN-2"]);
        // Pen 1: the open curve and the square; pen 2: the circle.
        let polylines: Vec<(&str, &str)> = pairs
            .iter()
            .enumerate()
            .filter(|(_, p)| **p == (0, "POLYLINE"))
            .map(|(i, _)| (pairs[i + 1].1, pairs[i + 6].1))
            .collect();
        assert_eq!(
            polylines,
            [("PEN-1", "0"), ("PEN-1", "1"), ("PEN-2", "1")],
            "(layer, closed flag) of each polyline"
        );
        assert_eq!(
            pairs.iter().filter(|p| **p == (0, "SEQEND")).count(),
            polylines.len()
        );
    }

    #[test]
    fn y_runs_up_from_the_bottom_edge() {
        let scene = two_pen_scene();
        let dxf = to_dxf(&scene, &DxfOptions::DEFAULT);
        let pairs = pairs(&dxf);
        // The square's corners are 5 to 25 mm below the top margin of
        // 5 mm on an 80 mm high page: 70 to 50 mm up.
        let ys: Vec<f64> = pairs
            .iter()
            .enumerate()
            .filter(|(_, p)| **p == (0, "VERTEX"))
            .map(|(i, _)| {
                assert_eq!(pairs[i + 3].0, 20);
                pairs[i + 3].1.parse().unwrap()
            })
            .collect();
        assert!(ys.iter().all(|y| (0.0..=80.0).contains(y)), "{ys:?}");
        assert!(ys.iter().any(|&y| (y - 70.0).abs() < 1e-9), "{ys:?}");
        assert!(ys.iter().any(|&y| (y - 50.0).abs() < 1e-9), "{ys:?}");
    }

    #[test]
    fn the_same_scene_gives_the_same_bytes_and_a_bad_tolerance_is_named() {
        let scene = two_pen_scene();
        assert_eq!(
            to_dxf(&scene, &DxfOptions::DEFAULT),
            to_dxf(&scene, &DxfOptions::DEFAULT)
        );
        let e = DxfOptions::DEFAULT
            .with_tolerance(-1.0)
            .validate()
            .unwrap_err();
        assert!(e.to_string().contains("dxf.tolerance"), "{e}");
    }
}
