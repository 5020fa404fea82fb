//! The image a table's sites are weighed by: its darkness, and with
//! `sites.edges` its edges mixed in — where the image changes, as at an
//! eye, a mouth or the outline of a face. Darkness alone spreads sites
//! evenly over a dark area and leaves a light feature on a light face
//! without any, so a mesh through them loses the feature.

use std::borrow::Cow;

use crate::error::Result;
use crate::geom::density::GreyImage;

/// The edge strength counted as full: a change of darkness this large
/// from one pixel to the next (Sobel, normalised). Weaker edges weigh in
/// proportion; a 256-level image's noise stays well below it.
const FULL_EDGE: f64 = 0.12;

/// `image` with `edges` (0–1) of its weight taken from its edge strength
/// and the rest from its darkness; the image itself when `edges` is 0.
///
/// # Errors
/// None in practice: the mixed image has the size of the given one.
pub(crate) fn weighed(image: &GreyImage, edges: f64) -> Result<Cow<'_, GreyImage>> {
    if edges <= 0.0 {
        return Ok(Cow::Borrowed(image));
    }
    let (w, h) = (image.width(), image.height());
    let at = |x: isize, y: isize| {
        let x = x.clamp(0, w as isize - 1) as usize;
        let y = y.clamp(0, h as isize - 1) as usize;
        f64::from(image.at(x, y))
    };
    let strength = |x: isize, y: isize| {
        let gx = at(x + 1, y - 1) + 2.0 * at(x + 1, y) + at(x + 1, y + 1)
            - at(x - 1, y - 1)
            - 2.0 * at(x - 1, y)
            - at(x - 1, y + 1);
        let gy = at(x - 1, y + 1) + 2.0 * at(x, y + 1) + at(x + 1, y + 1)
            - at(x - 1, y - 1)
            - 2.0 * at(x, y - 1)
            - at(x + 1, y - 1);
        (gx.hypot(gy) / 8.0 / FULL_EDGE).min(1.0)
    };
    let mut mixed = Vec::with_capacity(w * h);
    for y in 0..h as isize {
        for x in 0..w as isize {
            let v = (1.0 - edges) * at(x, y) + edges * strength(x, y);
            mixed.push(v as f32);
        }
    }
    Ok(Cow::Owned(GreyImage::new(w, h, mixed)?))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A light square on a white ground: little darkness, a sharp edge.
    fn square() -> GreyImage {
        let (w, h) = (40, 40);
        let darkness = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                if (10..30).contains(&x) && (10..30).contains(&y) {
                    0.3
                } else {
                    0.0
                }
            })
            .collect();
        GreyImage::new(w, h, darkness).unwrap()
    }

    #[test]
    fn edges_weigh_where_the_image_changes() {
        let image = square();
        let mixed = weighed(&image, 1.0).unwrap();
        assert_eq!(mixed.at(10, 20), 1.0, "on the edge");
        assert_eq!(mixed.at(20, 20), 0.0, "inside the square");
        assert_eq!(mixed.at(2, 2), 0.0, "on the ground");
        let half = weighed(&image, 0.5).unwrap();
        assert!((half.at(20, 20) - 0.15).abs() < 1e-6);
        assert!(matches!(weighed(&image, 0.0).unwrap(), Cow::Borrowed(_)));
    }
}
