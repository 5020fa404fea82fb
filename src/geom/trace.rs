//! Tracing a grey image into a region: the outlines of its light parts
//! (darkness below one half), by marching squares with the crossing
//! placed linearly between pixel centres, as closed polygons. Beyond the
//! image everything counts as dark, so a light part that reaches the
//! image's edge is closed along it. The zentangle paper's tool starts
//! from a monochrome picture whose white parts are the regions to fill;
//! this is that, as vectors.

use std::collections::HashMap;

use kurbo::{BezPath, Point, Rect};

use super::density::GreyImage;
use super::region::{FillRule, Region};
use crate::error::Result;

/// Darkness below this is light.
const THRESHOLD: f32 = 0.5;

/// The light parts of `image` as a region, the image fitted to `frame`
/// (page mm), aspect kept, centred. Light parts inside dark ones inside
/// light ones are nested as they are in the picture (even-odd).
///
/// # Errors
/// As [`Region::new`] when the outlines enclose nothing (an image dark
/// all over gives the empty region, not an error).
pub fn light_parts(image: &GreyImage, frame: Rect) -> Result<Region> {
    let (w, h) = (image.width(), image.height());
    let mm_per_px = (frame.width() / w as f64).min(frame.height() / h as f64);
    let origin = Point::new(
        frame.center().x - w as f64 * mm_per_px / 2.0,
        frame.center().y - h as f64 * mm_per_px / 2.0,
    );
    // Pixel (i, j) has its centre at grid point (i + 1, j + 1); the grid
    // has a ring of dark points round the image.
    let value = |i: i64, j: i64| -> f32 {
        if i < 1 || j < 1 || i > w as i64 || j > h as i64 {
            1.0
        } else {
            image.at(i as usize - 1, j as usize - 1)
        }
    };
    let to_page = |x: f64, y: f64| {
        Point::new(
            origin.x + (x - 0.5) * mm_per_px,
            origin.y + (y - 0.5) * mm_per_px,
        )
    };
    // Edges of the grid's cells, keyed by the grid edge a point lies on:
    // (x, y, horizontal?) of its lower-left end.
    type Key = (i64, i64, bool);
    let crossing = |a: (i64, i64), b: (i64, i64)| -> (f64, f64) {
        let (va, vb) = (value(a.0, a.1), value(b.0, b.1));
        let t = f64::from((THRESHOLD - va) / (vb - va)).clamp(0.0, 1.0);
        (
            a.0 as f64 + t * (b.0 - a.0) as f64,
            a.1 as f64 + t * (b.1 - a.1) as f64,
        )
    };
    let mut next: HashMap<Key, Key> = HashMap::new();
    let mut point: HashMap<Key, (f64, f64)> = HashMap::new();
    for j in 0..=h as i64 {
        for i in 0..=w as i64 {
            // Corners anticlockwise in y-down terms: top-left, top-right,
            // bottom-right, bottom-left.
            let c = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
            let light = c.map(|(x, y)| value(x, y) < THRESHOLD);
            let edges: [Key; 4] = [
                (i, j, true),
                (i + 1, j, false),
                (i, j + 1, true),
                (i, j, false),
            ];
            let ends = |e: usize| (c[e], c[(e + 1) % 4]);
            // Walk the cell's boundary: each edge where light turns to
            // dark starts a segment that ends where dark turns to light,
            // keeping the light on one side.
            let mut starts = Vec::new();
            let mut stops = Vec::new();
            for e in 0..4 {
                let (a, b) = (light[e], light[(e + 1) % 4]);
                if a && !b {
                    starts.push(e);
                } else if !a && b {
                    stops.push(e);
                }
            }
            // A saddle (two of each) pairs each start with the next stop
            // going round, which cuts off the dark corner between them:
            // the light joins across the saddle.
            for &s in &starts {
                let t = (1..4)
                    .map(|k| (s + k) % 4)
                    .find(|e| stops.contains(e))
                    .expect("a cell has as many stops as starts");
                for e in [s, t] {
                    let (a, b) = ends(e);
                    point.entry(edges[e]).or_insert_with(|| crossing(a, b));
                }
                next.insert(edges[s], edges[t]);
            }
        }
    }
    let mut path = BezPath::new();
    let mut keys: Vec<Key> = next.keys().copied().collect();
    keys.sort_unstable();
    let mut seen: HashMap<Key, ()> = HashMap::new();
    for start in keys {
        if seen.contains_key(&start) {
            continue;
        }
        let mut k = start;
        let mut first = true;
        loop {
            seen.insert(k, ());
            let (x, y) = point[&k];
            let p = to_page(x, y);
            if first {
                path.move_to(p);
                first = false;
            } else {
                path.line_to(p);
            }
            match next.get(&k) {
                Some(&n) if n != start && !seen.contains_key(&n) => k = n,
                _ => break,
            }
        }
        path.close_path();
    }
    if path.elements().is_empty() {
        return Ok(Region::empty());
    }
    Region::new(path, FillRule::EvenOdd)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `w × h` image, dark where `dark(i, j)`.
    fn image(w: usize, h: usize, dark: impl Fn(usize, usize) -> bool) -> GreyImage {
        let d = (0..h)
            .flat_map(|j| (0..w).map(move |i| (i, j)))
            .map(|(i, j)| if dark(i, j) { 1.0 } else { 0.0 })
            .collect();
        GreyImage::new(w, h, d).unwrap()
    }

    #[test]
    fn a_light_square_in_a_dark_frame_is_one_square() {
        // 10 × 10 px, light in the middle 6 × 6, on a 10 mm frame.
        let img = image(10, 10, |i, j| !(2..8).contains(&i) || !(2..8).contains(&j));
        let r = light_parts(&img, Rect::new(0.0, 0.0, 10.0, 10.0)).unwrap();
        // The outline runs halfway between light and dark pixel centres:
        // 6 mm wide, corners cut by the interpolation (½ px² each).
        assert!(
            (r.area() - (36.0 - 4.0 * 0.125)).abs() < 1e-6,
            "{}",
            r.area()
        );
        assert!(r.contains(Point::new(5.0, 5.0)));
        assert!(!r.contains(Point::new(1.0, 1.0)));
        assert_eq!(r.components().len(), 1);
    }

    #[test]
    fn holes_and_islands_are_kept_and_the_edge_closes_light_parts() {
        // Light all over but a dark ring; light inside the ring again.
        let img = image(20, 20, |i, j| {
            let d = ((i as f64 - 9.5).powi(2) + (j as f64 - 9.5).powi(2)).sqrt();
            (4.0..7.0).contains(&d)
        });
        let r = light_parts(&img, Rect::new(0.0, 0.0, 20.0, 20.0)).unwrap();
        assert!(r.contains(Point::new(10.0, 10.0)), "the island");
        assert!(!r.contains(Point::new(10.0, 4.5)), "the ring");
        assert!(r.contains(Point::new(1.0, 1.0)), "light up to the edge");
        assert_eq!(r.components().len(), 2);
        // Dark all over: nothing.
        let dark = image(4, 4, |_, _| true);
        assert!(light_parts(&dark, Rect::new(0.0, 0.0, 4.0, 4.0))
            .unwrap()
            .is_empty());
    }

    #[test]
    fn the_image_is_fitted_to_the_frame() {
        // 4 × 2 px all light, into a 40 × 40 mm frame: 40 × 20 mm, centred.
        let img = image(4, 2, |_, _| false);
        let r = light_parts(&img, Rect::new(0.0, 0.0, 40.0, 40.0)).unwrap();
        let b = r.bounds();
        assert!(
            (b.width() - 40.0).abs() < 1e-9 && (b.height() - 20.0).abs() < 1e-9,
            "{b:?}"
        );
        assert!((b.y0 - 10.0).abs() < 1e-9, "{b:?}");
    }
}
