//! Grey images as density: darkness values on a pixel grid, sampled
//! bilinearly, and laid over a region of the page — fitted to a frame (the
//! region's bounding box), aspect kept, centred. Dark asks for more
//! (stipples, sites, cells). Reading image files is
//! [`crate::input::decode_image`]'s job.

use kurbo::{Point, Rect};

use crate::error::{Error, Result};

/// Largest image, in pixels (64 megapixels, 256 MB of darkness
/// values): a density map needs no more, and a larger one is more likely a
/// mistake than a wish.
pub const MAX_IMAGE_PIXELS: usize = 64_000_000;

/// An image as darkness: 0 for white, 1 for black, row by row from the
/// top left.
#[derive(Debug, Clone, PartialEq)]
pub struct GreyImage {
    width: usize,
    height: usize,
    darkness: Vec<f32>,
}

impl GreyImage {
    /// An image of `width × height` darkness values (each clamped to
    /// 0–1), row by row from the top left.
    ///
    /// # Errors
    /// [`Error::Invalid`] (field `image`) when the sizes do not match the
    /// values or the image is empty or larger than [`MAX_IMAGE_PIXELS`].
    pub fn new(width: usize, height: usize, darkness: Vec<f32>) -> Result<GreyImage> {
        let n = width.saturating_mul(height);
        if n == 0 || n > MAX_IMAGE_PIXELS || darkness.len() != n {
            return Err(Error::invalid(
                "image",
                format!(
                    "a {width} × {height} image with {} values: needs 1 to {MAX_IMAGE_PIXELS} pixels, one value each",
                    darkness.len()
                ),
            ));
        }
        let darkness = darkness
            .into_iter()
            .map(|d| if d.is_nan() { 0.0 } else { d.clamp(0.0, 1.0) })
            .collect();
        Ok(GreyImage {
            width,
            height,
            darkness,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Darkness of pixel `(x, y)` (0 white – 1 black).
    pub fn at(&self, x: usize, y: usize) -> f32 {
        self.darkness[y * self.width + x]
    }

    /// Darkness at a point of the image in pixel units (pixel `(i, j)`
    /// covers `[i, i + 1) × [j, j + 1)`), bilinear between pixel centres;
    /// outside the image, white.
    pub fn sample(&self, x: f64, y: f64) -> f64 {
        if !(x >= 0.0 && y >= 0.0 && x <= self.width as f64 && y <= self.height as f64) {
            return 0.0;
        }
        let fx = (x - 0.5).clamp(0.0, (self.width - 1) as f64);
        let fy = (y - 0.5).clamp(0.0, (self.height - 1) as f64);
        let (x0, y0) = (fx.floor() as usize, fy.floor() as usize);
        let (x1, y1) = ((x0 + 1).min(self.width - 1), (y0 + 1).min(self.height - 1));
        let (tx, ty) = (fx - x0 as f64, fy - y0 as f64);
        let v = |x, y| f64::from(self.at(x, y));
        let top = v(x0, y0) * (1.0 - tx) + v(x1, y0) * tx;
        let bottom = v(x0, y1) * (1.0 - tx) + v(x1, y1) * tx;
        top * (1.0 - ty) + bottom * ty
    }
}

/// An image laid over a rectangle of the page: scaled to fit inside it
/// with its aspect kept and centred (as a picture in a frame), white
/// beyond its edges.
#[derive(Debug, Clone)]
pub struct Density<'a> {
    image: &'a GreyImage,
    origin: Point,
    px_per_mm: f64,
}

impl<'a> Density<'a> {
    /// `image` fitted to `frame` (page mm).
    pub fn fitted(image: &'a GreyImage, frame: Rect) -> Density<'a> {
        let (w, h) = (image.width as f64, image.height as f64);
        let mm_per_px = (frame.width() / w).min(frame.height() / h);
        let size = (w * mm_per_px, h * mm_per_px);
        let origin = Point::new(
            frame.center().x - size.0 / 2.0,
            frame.center().y - size.1 / 2.0,
        );
        Density {
            image,
            origin,
            px_per_mm: 1.0 / mm_per_px,
        }
    }

    /// Darkness at a page point (0 white – 1 black).
    pub fn at(&self, p: Point) -> f64 {
        let v = (p - self.origin) * self.px_per_mm;
        self.image.sample(v.x, v.y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A left-to-right ramp, white to black.
    fn ramp(width: usize, height: usize) -> GreyImage {
        let d = (0..height)
            .flat_map(|_| (0..width).map(move |x| x as f32 / (width - 1) as f32))
            .collect();
        GreyImage::new(width, height, d).unwrap()
    }

    #[test]
    fn sizes_must_match_the_values() {
        assert!(GreyImage::new(0, 5, vec![]).is_err());
        assert!(GreyImage::new(2, 2, vec![0.0; 3]).is_err());
        // Values are clamped; NaN is white.
        let img = GreyImage::new(3, 1, vec![-1.0, f32::NAN, 7.0]).unwrap();
        assert_eq!([img.at(0, 0), img.at(1, 0), img.at(2, 0)], [0.0, 0.0, 1.0]);
    }

    #[test]
    fn sampling_is_bilinear_and_white_outside() {
        let img = ramp(11, 3);
        assert!((img.sample(0.5, 1.5) - 0.0).abs() < 1e-6);
        assert!((img.sample(10.5, 1.5) - 1.0).abs() < 1e-6);
        assert!((img.sample(5.5, 1.5) - 0.5).abs() < 1e-6);
        assert!((img.sample(3.0, 1.5) - 0.25).abs() < 1e-6);
        assert_eq!(img.sample(-0.1, 1.0), 0.0);
        assert_eq!(img.sample(11.1, 1.0), 0.0);
        assert_eq!(img.sample(f64::NAN, 1.0), 0.0);
    }

    #[test]
    fn an_image_is_fitted_to_its_frame_centred_with_its_aspect() {
        // 11 × 3 px into a 110 × 90 mm frame: 10 mm a pixel, 30 mm tall,
        // centred vertically (30 mm of white above and below).
        let img = ramp(11, 3);
        let d = Density::fitted(&img, Rect::new(0.0, 0.0, 110.0, 90.0));
        assert!((d.at(Point::new(105.0, 45.0)) - 1.0).abs() < 1e-6);
        assert!(d.at(Point::new(5.0, 45.0)).abs() < 1e-6);
        assert_eq!(d.at(Point::new(105.0, 20.0)), 0.0);
        assert!(d.at(Point::new(105.0, 35.0)) > 0.99);
    }
}
