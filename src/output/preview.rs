//! PNG previews, rendered by resvg from SVG text: the colour preview
//! document ([`SvgOptions::preview`](super::SvgOptions::preview)), whose pen
//! layers are those of the plot SVG byte for byte.
//!
//! Rendering written text rather than the scene means the preview shows
//! exactly what a plotter program will read, including any rounding of
//! coordinates, plus the colours only a person needs.

use resvg::tiny_skia::{Color, Pixmap, Transform};
use resvg::usvg;

use crate::error::{Error, Result};

/// CSS pixels per inch: usvg reports sizes in px at this resolution.
const CSS_DPI: f64 = 96.0;

/// Accepted preview resolutions, in dots per inch.
const DPI_RANGE: std::ops::RangeInclusive<f64> = 1.0..=2400.0;

/// Largest preview in pixels (400 megapixels, 1.6 GB of RGBA): beyond it a
/// mistyped dpi would exhaust memory instead of failing with a message.
const MAX_PIXELS: f64 = 400e6;

/// Renders `svg` to a PNG at `dpi` on a white background.
///
/// The image is the SVG's size (its `width`/`height`, e.g. in mm) at `dpi`,
/// each side rounded and at least one pixel. Errors: [`Error::Invalid`] for a
/// dpi outside 1–2400, [`Error::Preview`] when the SVG cannot be parsed, the
/// image would exceed 400 megapixels, or encoding fails.
pub fn render_png(svg: &str, dpi: f64) -> Result<Vec<u8>> {
    render_pixmap(svg, dpi)?
        .encode_png()
        .map_err(|e| Error::preview("cannot encode PNG", e))
}

/// Checks a preview resolution: 1–2400 dpi. Callers that take a dpi from a
/// user check it up front, so a bad value fails before any work is done.
pub fn check_dpi(dpi: f64) -> Result<()> {
    // `contains` is false for NaN, so this also rejects it.
    if DPI_RANGE.contains(&dpi) {
        Ok(())
    } else {
        Err(Error::invalid(
            "dpi",
            format!("must be between 1 and 2400, got {dpi}"),
        ))
    }
}

fn render_pixmap(svg: &str, dpi: f64) -> Result<Pixmap> {
    check_dpi(dpi)?;
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default())
        .map_err(|e| Error::preview("cannot read SVG", e))?;
    let scale = dpi / CSS_DPI;
    let size = tree.size();
    let side = |px: f32| (f64::from(px) * scale).round().max(1.0);
    let (width, height) = (side(size.width()), side(size.height()));
    // Checked in f64, before any cast to u32 could saturate.
    if width * height > MAX_PIXELS {
        return Err(Error::Preview {
            message: format!(
                "a {width}×{height} pixel image at {dpi} dpi is larger than the \
                 limit of 400 megapixels; lower the dpi"
            ),
            source: None,
        });
    }
    let mut pixmap = Pixmap::new(width as u32, height as u32).ok_or_else(|| Error::Preview {
        message: format!("cannot allocate a {width}×{height} pixel image"),
        source: None,
    })?;
    pixmap.fill(Color::WHITE);
    let scale = scale as f32;
    resvg::render(
        &tree,
        Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    Ok(pixmap)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::{to_svg, SvgOptions};
    use crate::scene::{Group, Layer, Pen, Scene, Style};
    use crate::units::{Margins, Orientation, Page, PaperName};
    use kurbo::{Line, Shape};

    fn a5_svg() -> String {
        let mut g = Group::new("g");
        // A thick black diagonal across the whole drawable area.
        g.push_path(
            "diagonal",
            Line::new((0.0, 0.0), (128.0, 190.0)).into_path(0.1),
            Style::default(),
        );
        let scene = Scene {
            page: Page::named(PaperName::A5, Orientation::Portrait, Margins::uniform(10.0)),
            pens: vec![Pen {
                number: 1,
                name: "black".into(),
                color: crate::scene::Color::BLACK,
                width: 2.0,
            }],
            layers: vec![Layer {
                id: "l".into(),
                name: "l".into(),
                pen: 1,
                depth: 0,
                content: g,
            }],
            description: None,
        };
        to_svg(&scene, &SvgOptions::DEFAULT)
    }

    fn png_size(png: &[u8]) -> (u32, u32) {
        // The IHDR chunk follows the 8-byte signature and 8 bytes of chunk
        // length and type: width and height are big-endian u32s.
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        let be = |i: usize| u32::from_be_bytes(png[i..i + 4].try_into().unwrap());
        (be(16), be(20))
    }

    #[test]
    fn a5_at_150_dpi() {
        let png = render_png(&a5_svg(), 150.0).unwrap();
        assert_eq!(png_size(&png), (874, 1240));
        let pixmap = Pixmap::decode_png(&png).unwrap();
        let white = Color::WHITE.premultiply().to_color_u8();
        assert_eq!(pixmap.pixel(0, 0), Some(white));
        assert_eq!(pixmap.pixel(873, 1239), Some(white));
        // The stroke is drawn: the middle of the diagonal is dark.
        let mid = pixmap.pixel(437, 620).unwrap();
        assert!(mid.red() < 64 && mid.alpha() == 255, "{mid:?}");
    }

    #[test]
    fn tiny_dpi_gives_at_least_one_pixel() {
        let svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"0.1mm\" height=\"0.1mm\"/>";
        let png = render_png(svg, 1.0).unwrap();
        assert_eq!(png_size(&png), (1, 1));
    }

    #[test]
    fn dpi_out_of_range_is_invalid() {
        for dpi in [0.0, 0.5, 2400.5, f64::NAN, f64::INFINITY] {
            let err = render_png(&a5_svg(), dpi).unwrap_err();
            assert!(
                matches!(&err, Error::Invalid { field, .. } if field == "dpi"),
                "{err}"
            );
        }
    }

    #[test]
    fn huge_images_are_refused() {
        // A5 at 2400 dpi is about 14,000 × 20,000 px = 280 MP (allowed);
        // 2 m × 2 m at 2400 dpi is 35 gigapixels.
        let svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"2000mm\" height=\"2000mm\"/>";
        let err = render_png(svg, 2400.0).unwrap_err();
        assert!(
            matches!(&err, Error::Preview { message, .. } if message.contains("400 megapixels")),
            "{err}"
        );
    }

    #[test]
    fn unreadable_svg_is_a_preview_error() {
        let err = render_png("not svg", 96.0).unwrap_err();
        assert!(matches!(err, Error::Preview { .. }), "{err}");
        // The parser's error is kept as the source, and its text is in the
        // message.
        let cause = std::error::Error::source(&err).expect("a source");
        assert!(err.to_string().ends_with(&cause.to_string()), "{err}");
    }
}
