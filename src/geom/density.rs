//! Density over the page, 0–1: how much of something (stipples, sites,
//! cells) a place asks for. It comes from a grey image — darkness values
//! on a pixel grid, sampled bilinearly, fitted to a frame (the region's
//! bounding box), aspect kept, centred; dark asks for more — or from a
//! [`Formula`] of the position, or both multiplied. Reading image files is
//! [`crate::input::decode_image`]'s job.

use exmex::{Express, FlatEx};
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

/// Density over the page: a fitted image's darkness, a formula's value,
/// both multiplied, or 1 everywhere.
#[derive(Debug, Clone)]
pub struct Density<'a> {
    frame: Rect,
    image: Option<Fitted<'a>>,
    formula: Option<&'a Formula>,
}

/// An image laid over a rectangle of the page: scaled to fit inside it
/// with its aspect kept and centred (as a picture in a frame), white
/// beyond its edges.
#[derive(Debug, Clone)]
struct Fitted<'a> {
    image: &'a GreyImage,
    origin: Point,
    px_per_mm: f64,
}

impl<'a> Density<'a> {
    /// Density 1 everywhere; `frame` (page mm) is what images are fitted
    /// to and what a formula's `u`, `v` span.
    pub fn new(frame: Rect) -> Density<'a> {
        Density {
            frame,
            image: None,
            formula: None,
        }
    }

    /// `image` fitted to `frame` (page mm).
    pub fn fitted(image: &'a GreyImage, frame: Rect) -> Density<'a> {
        Density::new(frame).with_image(image)
    }

    /// This density times the darkness of `image`, fitted to the frame.
    pub fn with_image(mut self, image: &'a GreyImage) -> Density<'a> {
        let frame = self.frame;
        let (w, h) = (image.width as f64, image.height as f64);
        let mm_per_px = (frame.width() / w).min(frame.height() / h);
        let size = (w * mm_per_px, h * mm_per_px);
        let origin = Point::new(
            frame.center().x - size.0 / 2.0,
            frame.center().y - size.1 / 2.0,
        );
        self.image = Some(Fitted {
            image,
            origin,
            px_per_mm: 1.0 / mm_per_px,
        });
        self
    }

    /// This density times the value of `formula`.
    pub fn with_formula(mut self, formula: &'a Formula) -> Density<'a> {
        self.formula = Some(formula);
        self
    }

    /// The size of the image's pixels on the page (mm), the finest scale
    /// on which it changes; `None` without an image.
    pub fn pixel(&self) -> Option<f64> {
        self.image.as_ref().map(|f| 1.0 / f.px_per_mm)
    }

    /// Density at a page point (0–1).
    pub fn at(&self, p: Point) -> f64 {
        let mut d = 1.0;
        if let Some(f) = &self.image {
            let v = (p - f.origin) * f.px_per_mm;
            d *= f.image.sample(v.x, v.y);
        }
        if let Some(formula) = self.formula {
            let r = self.frame;
            let (u, v) = ((p.x - r.x0) / r.width(), (p.y - r.y0) / r.height());
            d *= formula.value(p.x, p.y, u, v);
        }
        d
    }
}

/// A density given as a formula of the position, such as
/// `"1 - v"` (dark at the top, white at the bottom) or
/// `"0.5 + 0.5 * sin(x / 10)"` (bands 63 mm apart).
///
/// Names: `x`, `y` — the point in mm (as every position in a description,
/// from the top left inside the margins); `u`, `v` — the same point across
/// the frame (the region's bounding box), 0 at its left/top, 1 at its
/// right/bottom. Operators `+ - * / ^`, the functions `sin cos tan asin
/// acos atan sinh cosh tanh exp ln log2 log10 sqrt cbrt abs signum floor
/// ceil round trunc fract`, and the constants `PI`/`π`, `TAU`/`τ`, `E`. The
/// value is clamped to 0–1; where it is not a number it counts as 0.
#[derive(Debug, Clone)]
pub struct Formula {
    text: String,
    expr: FlatEx<f64>,
    /// Which of x, y, u, v each of the formula's names is, in the order
    /// its evaluation takes them.
    names: Vec<usize>,
}

impl PartialEq for Formula {
    fn eq(&self, other: &Formula) -> bool {
        self.text == other.text
    }
}

/// The longest formula, in characters. A formula is evaluated at every
/// point a density is read (millions when a million sites are spread by
/// it), its cost growing with its length, and parsed into about 1 KB a
/// term: a 4 MB formula took gigabytes, and 999 characters spreading
/// Poisson sites 0.3 mm apart over A4 took 81 s (one name: 3.5 s). A
/// drawing's formula is a line (`"0.5 + 0.5 * sin(x / 10)"`).
pub const MAX_FORMULA_CHARS: usize = 200;

/// The deepest brackets may nest in a formula: the parser descends once
/// a level.
pub const MAX_FORMULA_DEPTH: usize = 32;

/// Refuses a formula past [`MAX_FORMULA_CHARS`] or [`MAX_FORMULA_DEPTH`]
/// before any of it is parsed.
fn check_size(text: &str) -> Result<()> {
    let chars = text.chars().count();
    if chars > MAX_FORMULA_CHARS {
        return Err(Error::invalid(
            "density",
            format!("is {chars} characters long; a formula may be at most {MAX_FORMULA_CHARS}"),
        ));
    }
    let (mut depth, mut deepest) = (0usize, 0usize);
    for c in text.chars() {
        match c {
            '(' => {
                depth += 1;
                deepest = deepest.max(depth);
            }
            ')' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    if deepest > MAX_FORMULA_DEPTH {
        return Err(Error::invalid(
            "density",
            format!(
                "nests brackets {deepest} deep; a formula may nest them at most \
                 {MAX_FORMULA_DEPTH} deep"
            ),
        ));
    }
    Ok(())
}

/// The names a formula may use, in the order [`Formula::value`] takes them.
const NAMES: [&str; 4] = ["x", "y", "u", "v"];

impl Formula {
    /// Parses `text`.
    ///
    /// # Errors
    /// [`Error::Invalid`] (field `density`) for text that is not a formula
    /// or uses a name other than `x`, `y`, `u`, `v`; for one longer than
    /// [`MAX_FORMULA_CHARS`] or with brackets nested deeper than
    /// [`MAX_FORMULA_DEPTH`], before it is parsed.
    pub fn parse(text: &str) -> Result<Formula> {
        check_size(text)?;
        let expr = exmex::parse::<f64>(text).map_err(|e| {
            Error::invalid(
                "density",
                format!("is not a formula of x, y, u, v: {}", e.msg()),
            )
        })?;
        let names = expr
            .var_names()
            .iter()
            .map(|name| {
                NAMES.iter().position(|n| n == name).ok_or_else(|| {
                    Error::invalid(
                        "density",
                        format!(
                            "uses the unknown name `{name}`: a formula may use x, y (mm) \
                             and u, v (0–1 across the region)"
                        ),
                    )
                })
            })
            .collect::<Result<Vec<usize>>>()?;
        Ok(Formula {
            text: text.to_string(),
            expr,
            names,
        })
    }

    /// The formula as written.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The value at `x`, `y` (mm) and `u`, `v` (0–1 across the frame),
    /// clamped to 0–1; 0 where it is not a number.
    pub fn value(&self, x: f64, y: f64, u: f64, v: f64) -> f64 {
        let all = [x, y, u, v];
        let mut args = [0.0; 4];
        for (arg, &i) in args.iter_mut().zip(&self.names) {
            *arg = all[i];
        }
        match self.expr.eval(&args[..self.names.len()]) {
            Ok(d) if d.is_nan() => 0.0,
            Ok(d) => d.clamp(0.0, 1.0),
            Err(_) => 0.0,
        }
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

    #[test]
    fn a_formula_past_its_length_or_depth_is_refused_before_it_is_parsed() {
        // The longest allowed parses; one character more is refused,
        // naming its length and the limit.
        let terms = "u+".repeat(MAX_FORMULA_CHARS / 2 - 1) + "u";
        assert_eq!(terms.len(), MAX_FORMULA_CHARS - 1);
        assert!(Formula::parse(&terms).is_ok());
        let long = "u+".repeat(2_000_000) + "u";
        let e = Formula::parse(&long).unwrap_err().to_string();
        assert_eq!(
            e,
            "density: is 4000001 characters long; a formula may be at most 200"
        );
        let deep = |n: usize| "(".repeat(n) + "u" + &")".repeat(n);
        assert!(Formula::parse(&deep(MAX_FORMULA_DEPTH)).is_ok());
        let e = Formula::parse(&deep(MAX_FORMULA_DEPTH + 1))
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "density: nests brackets 33 deep; a formula may nest them at most 32 deep"
        );
        // The longest chains of operators and functions within the limit
        // parse (or are refused) without exhausting a test thread's stack.
        for text in [
            "-".repeat(MAX_FORMULA_CHARS - 1) + "u",
            "sin(".repeat(MAX_FORMULA_DEPTH) + "u" + &")".repeat(MAX_FORMULA_DEPTH),
            "u^".repeat(MAX_FORMULA_CHARS / 2 - 1) + "u",
        ] {
            let _ = Formula::parse(&text);
        }
    }

    #[test]
    fn a_formula_reads_x_y_in_mm_and_u_v_across_the_frame() {
        let frame = Rect::new(10.0, 20.0, 110.0, 220.0);
        let f = Formula::parse("1 - v").unwrap();
        let d = Density::new(frame).with_formula(&f);
        assert!((d.at(Point::new(50.0, 20.0)) - 1.0).abs() < 1e-12);
        assert!((d.at(Point::new(50.0, 120.0)) - 0.5).abs() < 1e-12);
        assert!(d.at(Point::new(50.0, 220.0)).abs() < 1e-12);
        // Names in any order map to the right values.
        let f = Formula::parse("y / 1000 + x / 100 + 0 * u").unwrap();
        assert!((f.value(30.0, 200.0, 0.3, 0.9) - 0.5).abs() < 1e-12);
        // Clamped to 0–1, and not-a-number is 0.
        let f = Formula::parse("x").unwrap();
        assert_eq!(f.value(7.0, 0.0, 0.0, 0.0), 1.0);
        assert_eq!(f.value(-7.0, 0.0, 0.0, 0.0), 0.0);
        let f = Formula::parse("sqrt(x)").unwrap();
        assert_eq!(f.value(-1.0, 0.0, 0.0, 0.0), 0.0);
        // The guide's vignette (docs/guide/voronoi.md): 1 in the middle, 0 at the corners.
        let f = Formula::parse("1 - ((u - 0.5)^2 + (v - 0.5)^2) * 4").unwrap();
        assert_eq!(f.value(0.0, 0.0, 0.5, 0.5), 1.0);
        assert_eq!(f.value(0.0, 0.0, 0.0, 0.0), 0.0);
        let bands = Formula::parse("0.5 + 0.5 * sin(x / 6)").unwrap();
        assert!(
            (bands.value(6.0 * std::f64::consts::FRAC_PI_2, 0.0, 0.0, 0.0) - 1.0).abs() < 1e-12
        );
        // A constant needs no names.
        assert_eq!(
            Formula::parse("0.25").unwrap().value(1.0, 2.0, 3.0, 4.0),
            0.25
        );
    }

    #[test]
    fn an_image_and_a_formula_multiply() {
        let img = ramp(11, 3);
        let frame = Rect::new(0.0, 0.0, 110.0, 30.0);
        let f = Formula::parse("0.5").unwrap();
        let d = Density::fitted(&img, frame).with_formula(&f);
        assert!((d.at(Point::new(105.0, 15.0)) - 0.5).abs() < 1e-6);
        assert!(d.at(Point::new(5.0, 15.0)).abs() < 1e-6);
        assert_eq!(Density::new(frame).at(Point::new(1.0, 1.0)), 1.0);
    }

    #[test]
    fn bad_formulas_are_refused_with_the_reason() {
        for (text, wanted) in [
            ("1 +", "is not a formula"),
            ("", "is not a formula"),
            ("x * z", "unknown name `z`"),
            ("sin(", "is not a formula"),
        ] {
            let e = Formula::parse(text).unwrap_err();
            assert!(
                matches!(&e, Error::Invalid { field, message, .. }
                    if field == "density" && message.contains(wanted)),
                "{text}: {e}"
            );
        }
    }
}
