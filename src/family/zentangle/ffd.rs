//! Free-form deformation by a 4×4 control lattice (docs/SPEC.md §2.2, the
//! zentangle hand-drawn wobble `[f p]`).
//!
//! The lattice is fitted to a box; control point `(i, j)` starts at
//! `origin + (i·w/3, j·h/3)`. The deformation is the bicubic tensor-product
//! Bézier map of the control points over the box's normalised coordinates
//! `(u, v) ∈ [0, 1]²`:
//!
//! ```text
//! f(x, y) = Σᵢ Σⱼ Bᵢ(u) Bⱼ(v) · control[j][i],   u = (x − x0)/w,  v = (y − y0)/h
//! ```
//!
//! with the cubic Bernstein polynomials `Bᵢ`. Because those reproduce
//! linear functions, the undisturbed lattice is exactly the identity.
//! Points outside the box follow the same polynomial (a smooth
//! extrapolation).
//!
//! Curves are deformed as the SPEC decides, through their control points,
//! after subdividing enough: each segment becomes a cubic whose end points
//! are mapped and whose inner control points are the end tangents mapped by
//! the Jacobian of `f` (the limit of mapping control points as the pieces
//! shrink, and tangent-continuous across joins); a piece is halved until
//! the cubic stays within `tolerance` of the exactly mapped curve at
//! sample points.

use kurbo::{BezPath, CubicBez, Line, ParamCurve, PathEl, PathSeg, Point, QuadBez, Rect, Vec2};

use crate::error::{Error, Result};
use crate::rng::RandomStream;

use crate::geom::TOLERANCE;

/// A piece of a segment is halved at most this many times (2¹⁰ pieces).
const MAX_DEPTH: u32 = 10;

/// Parameters at which a mapped piece is compared with the exact image.
const SAMPLES: [f64; 5] = [0.1, 0.3, 0.5, 0.7, 0.9];

/// A 4×4 control lattice over a box.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Lattice {
    origin: Point,
    size: Vec2,
    /// `control[j][i]`: row `j` (along y), column `i` (along x).
    control: [[Point; 4]; 4],
}

impl Lattice {
    /// The undisturbed lattice over `bounds`: it maps every point to itself.
    ///
    /// # Errors
    /// When `bounds` is not finite or has zero width or height (give a
    /// line-like element a nominal square box instead).
    pub(crate) fn identity(bounds: Rect) -> Result<Lattice> {
        let bounds = bounds.abs();
        let ok = [bounds.x0, bounds.y0, bounds.x1, bounds.y1]
            .iter()
            .all(|v| v.is_finite())
            && bounds.width() > 0.0
            && bounds.height() > 0.0;
        if !ok {
            return Err(Error::invalid(
                "lattice.bounds",
                format!("the box must be finite with a positive width and height, got {bounds:?}"),
            ));
        }
        let origin = bounds.origin();
        let size = Vec2::new(bounds.width(), bounds.height());
        let mut control = [[Point::ORIGIN; 4]; 4];
        for (j, row) in control.iter_mut().enumerate() {
            for (i, c) in row.iter_mut().enumerate() {
                *c = origin + Vec2::new(size.x * i as f64 / 3.0, size.y * j as f64 / 3.0);
            }
        }
        Ok(Lattice {
            origin,
            size,
            control,
        })
    }

    /// A lattice over `bounds` whose control points are each moved by
    /// `s·u + t·v`, where `u = (w/3, 0)` and `v = (0, h/3)` are the lattice
    /// spacings and `s`, `t` are uniform in `[−rx/2, rx/2)` and
    /// `[−ry/2, ry/2)` (docs/SPEC.md §2.2). `rx = ry = 1` lets a control point move
    /// up to half a cell each way.
    ///
    /// Numbers are drawn row by row (`j` = 0..4 along y, `i` = 0..4 along x),
    /// `s` then `t` for each point; a zero amplitude draws nothing.
    ///
    /// # Errors
    /// As [`Lattice::identity`], and when `rx` or `ry` is negative or not
    /// finite.
    pub(crate) fn jittered(
        bounds: Rect,
        rx: f64,
        ry: f64,
        rng: &mut RandomStream,
    ) -> Result<Lattice> {
        for (name, v) in [("rx", rx), ("ry", ry)] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::invalid(
                    format!("lattice.{name}"),
                    format!("must be a finite number ≥ 0, got {v}"),
                ));
            }
        }
        let mut lattice = Lattice::identity(bounds)?;
        let u = Vec2::new(lattice.size.x / 3.0, 0.0);
        let v = Vec2::new(0.0, lattice.size.y / 3.0);
        for row in lattice.control.iter_mut() {
            for c in row.iter_mut() {
                let s = rng.symmetric(rx / 2.0);
                let t = rng.symmetric(ry / 2.0);
                *c += u * s + v * t;
            }
        }
        Ok(lattice)
    }

    /// A lattice over `bounds` with the given control points
    /// (`control[j][i]`, row `j` along y).
    ///
    /// # Errors
    /// As [`Lattice::identity`], and when a control point is not finite.
    #[cfg(test)]
    pub(crate) fn with_control(bounds: Rect, control: [[Point; 4]; 4]) -> Result<Lattice> {
        let mut lattice = Lattice::identity(bounds)?;
        if control.iter().flatten().any(|p| !p.is_finite()) {
            return Err(Error::invalid(
                "lattice.control",
                "control points must be finite",
            ));
        }
        lattice.control = control;
        Ok(lattice)
    }

    /// The control points, `control[j][i]` (row `j` along y).
    #[cfg(test)]
    pub(crate) fn control(&self) -> &[[Point; 4]; 4] {
        &self.control
    }

    /// The deformed position of `p`.
    pub(crate) fn map(&self, p: Point) -> Point {
        let (bu, _) = bernstein(self.u(p.x));
        let (bv, _) = bernstein(self.v(p.y));
        let mut acc = Vec2::ZERO;
        for (j, row) in self.control.iter().enumerate() {
            for (i, c) in row.iter().enumerate() {
                acc += c.to_vec2() * (bu[i] * bv[j]);
            }
        }
        acc.to_point()
    }

    /// The Jacobian of the map at `p`: the images of the unit vectors
    /// along x and along y.
    fn jacobian(&self, p: Point) -> (Vec2, Vec2) {
        let (bu, du) = bernstein(self.u(p.x));
        let (bv, dv) = bernstein(self.v(p.y));
        let (mut fx, mut fy) = (Vec2::ZERO, Vec2::ZERO);
        for (j, row) in self.control.iter().enumerate() {
            for (i, c) in row.iter().enumerate() {
                fx += c.to_vec2() * (du[i] * bv[j]);
                fy += c.to_vec2() * (bu[i] * dv[j]);
            }
        }
        (fx / self.size.x, fy / self.size.y)
    }

    /// The image of the direction `d` at `p`.
    fn map_vector(&self, p: Point, d: Vec2) -> Vec2 {
        let (fx, fy) = self.jacobian(p);
        fx * d.x + fy * d.y
    }

    fn u(&self, x: f64) -> f64 {
        (x - self.origin.x) / self.size.x
    }

    fn v(&self, y: f64) -> f64 {
        (y - self.origin.y) / self.size.y
    }
}

/// The cubic Bernstein polynomials at `t` and their derivatives.
fn bernstein(t: f64) -> ([f64; 4], [f64; 4]) {
    let s = 1.0 - t;
    (
        [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t],
        [
            -3.0 * s * s,
            3.0 * s * s - 6.0 * t * s,
            6.0 * t * s - 3.0 * t * t,
            3.0 * t * t,
        ],
    )
}

/// `path` deformed by `lattice`, within `tolerance` (mm) of the exact image
/// at the sample points of every piece. Straight segments whose image stays
/// within `tolerance` of a straight line stay lines; every other segment
/// becomes one or more cubics. Closed subpaths stay closed (a straight
/// closing segment is deformed like any other). A non-finite or
/// non-positive `tolerance` means [`TOLERANCE`].
pub(crate) fn deform(path: &BezPath, lattice: &Lattice, tolerance: f64) -> BezPath {
    let tolerance = if tolerance.is_finite() && tolerance > 0.0 {
        tolerance
    } else {
        TOLERANCE
    };
    let mut out = BezPath::new();
    let mut start = Point::ORIGIN;
    let mut current = Point::ORIGIN;
    let mut open = false;
    for el in path.elements() {
        let seg = match *el {
            PathEl::MoveTo(p) => {
                out.move_to(lattice.map(p));
                start = p;
                current = p;
                open = true;
                continue;
            }
            PathEl::ClosePath => {
                if current != start {
                    push_line(&mut out, Line::new(current, start), lattice, tolerance);
                }
                out.close_path();
                current = start;
                continue;
            }
            PathEl::LineTo(p) => PathSeg::Line(Line::new(current, p)),
            PathEl::QuadTo(a, p) => PathSeg::Quad(QuadBez::new(current, a, p)),
            PathEl::CurveTo(a, b, p) => PathSeg::Cubic(CubicBez::new(current, a, b, p)),
        };
        if !open {
            // A segment after a close (or at the very start) begins at the
            // subpath's start point without a move-to of its own.
            out.move_to(lattice.map(current));
            open = true;
        }
        match seg {
            PathSeg::Line(l) => push_line(&mut out, l, lattice, tolerance),
            PathSeg::Quad(q) => push_cubic(&mut out, q.raise(), lattice, tolerance, 0),
            PathSeg::Cubic(c) => push_cubic(&mut out, c, lattice, tolerance, 0),
        }
        current = seg.end();
    }
    out
}

fn push_line(out: &mut BezPath, l: Line, lattice: &Lattice, tolerance: f64) {
    let (a, b) = (lattice.map(l.p0), lattice.map(l.p1));
    let chord = Line::new(a, b);
    let straight = SAMPLES
        .iter()
        .all(|&t| (lattice.map(l.eval(t)) - chord.eval(t)).hypot() <= tolerance);
    if straight {
        out.line_to(b);
    } else {
        let c = CubicBez::new(l.p0, l.eval(1.0 / 3.0), l.eval(2.0 / 3.0), l.p1);
        push_cubic(out, c, lattice, tolerance, 0);
    }
}

fn push_cubic(out: &mut BezPath, c: CubicBez, lattice: &Lattice, tolerance: f64, depth: u32) {
    let p0 = lattice.map(c.p0);
    let p3 = lattice.map(c.p3);
    let q1 = p0 + lattice.map_vector(c.p0, c.p1 - c.p0);
    let q2 = p3 - lattice.map_vector(c.p3, c.p3 - c.p2);
    let approx = CubicBez::new(p0, q1, q2, p3);
    let good = SAMPLES
        .iter()
        .all(|&t| (lattice.map(c.eval(t)) - approx.eval(t)).hypot() <= tolerance);
    if good || depth >= MAX_DEPTH {
        out.curve_to(q1, q2, p3);
    } else {
        let (a, b) = c.subdivide();
        push_cubic(out, a, lattice, tolerance, depth + 1);
        push_cubic(out, b, lattice, tolerance, depth + 1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Seed;
    use kurbo::{Circle, ParamCurveNearest, Shape};

    fn max_distance(a: &BezPath, b: &BezPath) -> f64 {
        // Sample a; distance to the nearest point of b.
        let mut worst: f64 = 0.0;
        for seg in a.segments() {
            for k in 0..=8 {
                let p = seg.eval(k as f64 / 8.0);
                let d = b
                    .segments()
                    .map(|s| s.nearest(p, 1e-9).distance_sq)
                    .fold(f64::INFINITY, f64::min)
                    .sqrt();
                worst = worst.max(d);
            }
        }
        worst
    }

    #[test]
    fn identity_maps_a_path_onto_itself() {
        let mut p = Circle::new((3.0, 4.0), 2.0).to_path(1e-6);
        p.move_to((0.0, 0.0));
        p.line_to((6.0, 1.0));
        p.quad_to((7.0, 7.0), (1.0, 6.0));
        p.close_path();
        let lat = Lattice::identity(Rect::new(0.0, 0.0, 8.0, 8.0)).unwrap();
        let q = deform(&p, &lat, 1e-3);
        assert!(max_distance(&p, &q) < 1e-9);
        assert!(max_distance(&q, &p) < 1e-9);
        // Lines stay lines, the circle keeps its four cubics.
        assert_eq!(
            q.elements()
                .iter()
                .filter(|e| matches!(e, PathEl::LineTo(_)))
                .count(),
            2
        );
        assert_eq!(
            q.elements()
                .iter()
                .filter(|e| matches!(e, PathEl::ClosePath))
                .count(),
            2
        );
        let m = lat.map(Point::new(1.25, 7.5));
        assert!((m - Point::new(1.25, 7.5)).hypot() < 1e-12);
    }

    #[test]
    fn jitter_is_bounded_reproducible_and_optional() {
        let b = Rect::new(-1.0, -1.0, 1.0, 1.0);
        let id = Lattice::identity(b).unwrap();
        let a = Lattice::jittered(b, 0.5, 0.25, &mut Seed(3).stream()).unwrap();
        let again = Lattice::jittered(b, 0.5, 0.25, &mut Seed(3).stream()).unwrap();
        assert_eq!(a, again);
        let spacing = 2.0 / 3.0;
        for (ra, ri) in a.control().iter().zip(id.control()) {
            for (pa, pi) in ra.iter().zip(ri) {
                let d = *pa - *pi;
                assert!(d.x.abs() <= 0.25 * spacing && d.y.abs() <= 0.125 * spacing);
            }
        }
        assert_ne!(a, id);
        let none = Lattice::jittered(b, 0.0, 0.0, &mut Seed(3).stream()).unwrap();
        assert_eq!(none, id);
    }

    #[test]
    fn deformed_curve_follows_the_exact_map() {
        let b = Rect::new(0.0, 0.0, 10.0, 10.0);
        let lat = Lattice::jittered(b, 1.0, 1.0, &mut Seed(9).stream()).unwrap();
        let p = Circle::new((5.0, 5.0), 4.0).to_path(1e-6);
        let tol = 1e-3;
        let q = deform(&p, &lat, tol);
        // Every exactly mapped point of the input lies near the output.
        for seg in p.segments() {
            for k in 0..=20 {
                let exact = lat.map(seg.eval(k as f64 / 20.0));
                let d = q
                    .segments()
                    .map(|s| s.nearest(exact, 1e-9).distance_sq)
                    .fold(f64::INFINITY, f64::min)
                    .sqrt();
                assert!(d < 2.0 * tol, "{d}");
            }
        }
        assert!(q.segments().count() >= 4);
        // A straight line through a wobbly lattice becomes curves.
        let mut l = BezPath::new();
        l.move_to((0.0, 5.0));
        l.line_to((10.0, 5.0));
        let dl = deform(&l, &lat, tol);
        assert!(dl
            .elements()
            .iter()
            .any(|e| matches!(e, PathEl::CurveTo(..))));
    }

    #[test]
    fn bad_lattices_are_errors() {
        let mut s = Seed(1).stream();
        assert!(Lattice::identity(Rect::new(0.0, 0.0, 0.0, 1.0)).is_err());
        assert!(Lattice::identity(Rect::new(0.0, 0.0, f64::NAN, 1.0)).is_err());
        let b = Rect::new(0.0, 0.0, 1.0, 1.0);
        assert!(Lattice::jittered(b, -1.0, 0.0, &mut s).is_err());
        assert!(Lattice::jittered(b, 0.0, f64::INFINITY, &mut s).is_err());
        let mut c = *Lattice::identity(b).unwrap().control();
        c[1][2] = Point::new(f64::NAN, 0.0);
        assert!(Lattice::with_control(b, c).is_err());
        // Silly tolerances fall back to the default instead of looping.
        let lat = Lattice::jittered(b, 1.0, 1.0, &mut s).unwrap();
        let p = Circle::new((0.5, 0.5), 0.4).to_path(1e-6);
        for t in [0.0, -1.0, f64::NAN] {
            assert!(!deform(&p, &lat, t).elements().is_empty());
        }
    }
}
