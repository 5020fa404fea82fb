//! Reading PNG and JPEG files as darkness ([`GreyImage`]): PNG through
//! tiny-skia's decoder (already in the tree for previews), JPEG through
//! zune-jpeg. Colour is reduced to luminance (Rec. 709 weights);
//! transparent pixels count as white paper, so they ask for nothing.

use resvg::tiny_skia::Pixmap;
use zune_jpeg::zune_core::bytestream::ZCursor;
use zune_jpeg::zune_core::colorspace::ColorSpace;
use zune_jpeg::zune_core::options::DecoderOptions;
use zune_jpeg::JpegDecoder;

use crate::error::{Error, Result};
use crate::geom::density::{GreyImage, MAX_IMAGE_PIXELS};

/// Reads a PNG or JPEG file's bytes (told apart by their signature) as
/// darkness.
///
/// # Errors
/// [`Error::Invalid`] (field `image`) when the bytes are neither PNG nor
/// JPEG, do not decode, or the image is larger than [`MAX_IMAGE_PIXELS`]
/// or 32,768 pixels on a side.
pub fn decode_image(bytes: &[u8]) -> Result<GreyImage> {
    const PNG: &[u8] = b"\x89PNG\r\n\x1a\n";
    const JPEG: &[u8] = b"\xff\xd8\xff";
    if bytes.starts_with(PNG) {
        decode_png(bytes)
    } else if bytes.starts_with(JPEG) {
        decode_jpeg(bytes)
    } else {
        Err(Error::invalid(
            "image",
            "is not a PNG or JPEG image (its first bytes are neither signature)",
        ))
    }
}

fn decode_png(bytes: &[u8]) -> Result<GreyImage> {
    // The size from the header first: the decoder allocates for the size a
    // file claims before it finds the data missing (fuzzing found a
    // 47 × 452,984,879 header asking for 85 GB).
    let (width, height) = png_size(bytes)?;
    check_size(width, height)?;
    let pixmap = Pixmap::decode_png(bytes)
        .map_err(|e| Error::invalid("image", format!("is not a readable PNG: {e}")))?;
    let (width, height) = (pixmap.width() as usize, pixmap.height() as usize);
    check_size(width, height)?;
    let darkness = pixmap
        .pixels()
        .iter()
        .map(|p| {
            // Premultiplied: what alpha leaves is white paper.
            let white = 255.0 - f32::from(p.alpha());
            let luma = 0.2126 * (f32::from(p.red()) + white)
                + 0.7152 * (f32::from(p.green()) + white)
                + 0.0722 * (f32::from(p.blue()) + white);
            1.0 - luma / 255.0
        })
        .collect();
    GreyImage::new(width, height, darkness)
}

fn decode_jpeg(bytes: &[u8]) -> Result<GreyImage> {
    let bad =
        |e: &dyn std::fmt::Display| Error::invalid("image", format!("is not a readable JPEG: {e}"));
    let options = DecoderOptions::default()
        .jpeg_set_out_colorspace(ColorSpace::Luma)
        .set_max_width(MAX_SIDE)
        .set_max_height(MAX_SIDE);
    let mut decoder = JpegDecoder::new_with_options(ZCursor::new(bytes), options);
    decoder.decode_headers().map_err(|e| bad(&e))?;
    let info = decoder.info().ok_or_else(|| bad(&"no image header"))?;
    let (width, height) = (usize::from(info.width), usize::from(info.height));
    check_size(width, height)?;
    let luma = decoder.decode().map_err(|e| bad(&e))?;
    if luma.len() != width * height {
        return Err(bad(&format!(
            "{} values for {width} × {height} pixels",
            luma.len()
        )));
    }
    GreyImage::new(
        width,
        height,
        luma.into_iter()
            .map(|v| 1.0 - f32::from(v) / 255.0)
            .collect(),
    )
}

/// The width and height in a PNG's header chunk (IHDR), which must come
/// first after the signature.
fn png_size(bytes: &[u8]) -> Result<(usize, usize)> {
    let header = bytes
        .get(8..24)
        .filter(|h| &h[4..8] == b"IHDR")
        .ok_or_else(|| Error::invalid("image", "is not a readable PNG: no header chunk"))?;
    let be = |b: &[u8]| u32::from_be_bytes([b[0], b[1], b[2], b[3]]) as usize;
    Ok((be(&header[8..12]), be(&header[12..16])))
}

/// Longest side read, in pixels. Below 2¹⁶ with room to spare: zune-jpeg
/// rounds a width up to whole blocks in 16 bits and overflowed on a
/// 65,535-pixel header (found by fuzzing).
const MAX_SIDE: usize = 32_768;

fn check_size(width: usize, height: usize) -> Result<()> {
    if width > MAX_SIDE || height > MAX_SIDE {
        return Err(Error::invalid(
            "image",
            format!("{width} × {height} pixels: a side is longer than the {MAX_SIDE} read"),
        ));
    }
    if width.saturating_mul(height) > MAX_IMAGE_PIXELS {
        return Err(Error::invalid(
            "image",
            format!("{width} × {height} pixels is more than the {MAX_IMAGE_PIXELS} read"),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_and_jpeg_read_as_darkness() {
        // A PNG made by the preview renderer: black square on white.
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="8" height="4">
            <rect width="8" height="4" fill="white"/><rect width="4" height="4" fill="black"/></svg>"#;
        let png = crate::output::render_png(svg, 96.0).unwrap();
        let img = decode_image(&png).unwrap();
        assert_eq!((img.width(), img.height()), (8, 4));
        assert!(img.at(1, 1) > 0.99 && img.at(6, 1) < 0.01);
        // A JPEG: the fixture is a 16 × 8 grey ramp, dark on the left.
        let jpeg = include_bytes!("../../tests/fixtures/ramp.jpg");
        let img = decode_image(jpeg).unwrap();
        assert_eq!((img.width(), img.height()), (16, 8));
        assert!(img.at(0, 4) > img.at(15, 4) + 0.5);
    }

    /// A header that claims a huge image is refused before anything is
    /// decoded (found by fuzzing: the decoder asked for 85 GB).
    #[test]
    fn a_huge_png_header_is_refused_before_decoding() {
        let case = include_bytes!("../../fuzz/crashers/image/png-huge-header.png");
        let e = decode_image(case).unwrap_err().to_string();
        assert!(e.contains("47 × 452984879 pixels: a side is longer"), "{e}");
        // The real size of a small PNG passes the check.
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="3" height="2"/>"#;
        let png = crate::output::render_png(svg, 96.0).unwrap();
        assert_eq!(png_size(&png).unwrap(), (3, 2));
    }

    /// JPEG headers 65,535 pixels wide are refused before decoding (found
    /// by fuzzing: the decoder's block count overflowed).
    #[test]
    fn a_jpeg_wider_than_the_largest_side_is_refused() {
        for case in [
            &include_bytes!("../../fuzz/crashers/image/jpeg-width-overflow-1.jpg")[..],
            include_bytes!("../../fuzz/crashers/image/jpeg-width-overflow-4.jpg"),
        ] {
            let e = decode_image(case).unwrap_err().to_string();
            assert!(
                e.contains("not a readable JPEG") || e.contains("longer than"),
                "{e}"
            );
        }
        assert!(check_size(MAX_SIDE, 1).is_ok());
        assert!(check_size(MAX_SIDE + 1, 1).is_err());
    }

    #[test]
    fn what_is_not_an_image_is_refused() {
        for bytes in [
            &b""[..],
            b"GIF89a",
            b"\x89PNG\r\n\x1a\nbroken",
            b"\xff\xd8\xffbroken",
        ] {
            let e = decode_image(bytes).unwrap_err().to_string();
            assert!(e.starts_with("image: is not a"), "{e}");
        }
    }
}
