//! The elements of a tangle (docs/SPEC.md §2.1, the paper's 図4 basic shapes and
//! 図7 compound shapes) as exact vector geometry in the square [−1, 1]²,
//! y down as on the page, and their placement and hand-drawn deformation
//! (docs/SPEC.md §2.2).
//!
//! An element is a list of [`Mark`]s in painter's order: a later mark
//! paints over the earlier ones where its interior lies. A mark is a line
//! (drawn, encloses nothing) or a closed outline whose interior is painted
//! white or black ([`Paint`]); the outline itself is always drawn. What the
//! marks leave of a region is the business of the sibling module `compose`.
//!
//! Sizes are fixed so that elements tile: the square and the circle are
//! the square [−1, 1]² and the unit circle, the triangle is equilateral
//! with side 2 and its bounding box centred, and line-only elements reach
//! the sides of the square. Curves are kept as curves: circles and arcs
//! are kurbo arcs, spirals and the curves `c0`–`c4` are cubics fitted to
//! the exact parametric curve (Hermite interpolation of point and
//! tangent), within [`CURVE_TOLERANCE`] of it in unit coordinates.
//!
//! The design of each shape (the paper's figures are lost in the text we
//! have, so each follows its name and what a tangler draws):
//!
//! | name | design |
//! |---|---|
//! | `cr` | a plus sign, two strokes from side to side |
//! | `tr` | equilateral triangle, point up |
//! | `sq` | the square |
//! | `sp` | Archimedean spiral, three turns from the centre to radius 1 |
//! | `as` | a square whose four sides are arcs bulging *in* (sagitta 0.3): a cushion star, distinct from both square and circle |
//! | `cl` | the unit circle |
//! | `c0` | an ogee: one S-shaped cubic from lower left to upper right |
//! | `c1` | a wave, two periods of a sine across the square |
//! | `c2` | a fiddlehead: a stem rising from the bottom into a curl |
//! | `c3` | a loop: a prolate cycloid arch with one loop in the middle |
//! | `c4` | a double arch, two nested half-ellipses |
//! | `st` | the triangle cut into five strips parallel to its base (black: alternate strips white) |
//! | `ss` | the square cut into five horizontal strips (black: alternate strips white) |
//! | `le` | a pointed almond leaf, tip up, with a midrib (white only: black hides it) |
//! | `mtr0` | the triangle split into four: its midpoint triangle painted white |
//! | `mtr1` | the triangle and copies ×0.8, ×0.6, ×0.4 about its centre, paints alternating (the paper's tr white, ×0.8 black, …) |
//! | `mtr2` | `mtr0` once more in each corner triangle: the second Sierpiński step |
//! | `ptr` | paradox triangle: points 15 % along each side joined, repeated inwards (black: the nested triangles alternate white and black) |
//! | `msq0` | the square and copies ×0.75, ×0.5, ×0.25, paints alternating |
//! | `msq1` | squares and diamonds through each other's midpoints, four levels, paints alternating |
//! | `msq2` | a 2×2 grid of white squares inside the square |
//! | `msq3` | `msq2` with a black square in the middle of each white one |
//! | `psq` | paradox square, as `ptr` |
//! | `mcl0` | concentric circles ×1, ×0.75, ×0.5, ×0.25, paints alternating |
//! | `mcl1` | seven white circles (one in the middle, six round it) inside the circle |
//! | `scl` | a circle holding a spiral that ends on it (black: a white spiral band) |

use std::f64::consts::{PI, TAU};

use kurbo::{Affine, Arc, BezPath, Circle, CubicBez, ParamCurve, Point, Rect, Shape as _, Vec2};

use crate::error::Result;
use crate::family::zentangle::ffd::{deform, Lattice};
use crate::rng::RandomStream;

/// Curves are within this distance of the exact curve in unit
/// coordinates: an element 100 mm wide is then within 0.0005 mm.
pub(crate) const CURVE_TOLERANCE: f64 = 1e-5;

/// The square every element is drawn in, and the box the deformation
/// lattice is fitted to.
pub(crate) const UNIT: Rect = Rect::new(-1.0, -1.0, 1.0, 1.0);

/// Half the height of the equilateral triangle of side 2, `√3 / 2`.
const TRI_H: f64 = 0.866_025_403_784_438_6;

/// The fraction along each side at which a paradox polygon's next corner
/// lies: small enough for the twist to show, large enough that the
/// polygons shrink in a dozen steps.
const PARADOX_STEP: f64 = 0.15;

/// Paradox polygons stop once they are smaller than this share of the
/// outline: below it the lines run together at any pen width.
const PARADOX_MIN_SIZE: f64 = 0.08;

/// A zentangle element (docs/SPEC.md §2.1): the paper's 14 basic shapes (図4)
/// and 12 compound ones (図7 and the tables' `mtr2`, `msq3`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) enum Shape {
    /// Cross.
    Cr,
    /// Triangle.
    Tr,
    /// Square.
    Sq,
    /// Spiral.
    Sp,
    /// Arc-square.
    As,
    /// Circle.
    Cl,
    /// Curve 0 (ogee).
    C0,
    /// Curve 1 (wave).
    C1,
    /// Curve 2 (fiddlehead).
    C2,
    /// Curve 3 (loop).
    C3,
    /// Curve 4 (double arch).
    C4,
    /// Strip triangle.
    St,
    /// Strip square.
    Ss,
    /// Leaf.
    Le,
    /// Triangle split into four.
    Mtr0,
    /// Nested triangles, paints alternating.
    Mtr1,
    /// Triangle split twice (Sierpiński).
    Mtr2,
    /// Paradox triangle.
    Ptr,
    /// Nested squares, paints alternating.
    Msq0,
    /// Squares and diamonds through midpoints.
    Msq1,
    /// 2×2 squares in a square.
    Msq2,
    /// 2×2 squares, each with a square inside.
    Msq3,
    /// Paradox square.
    Psq,
    /// Concentric circles.
    Mcl0,
    /// Seven circles in a circle.
    Mcl1,
    /// Spiral in a circle.
    Scl,
}

impl Shape {
    /// Every shape: the basic ones in the paper's order, then the compound.
    pub(crate) const ALL: [Shape; 26] = [
        Shape::Cr,
        Shape::Tr,
        Shape::Sq,
        Shape::Sp,
        Shape::As,
        Shape::Cl,
        Shape::C0,
        Shape::C1,
        Shape::C2,
        Shape::C3,
        Shape::C4,
        Shape::St,
        Shape::Ss,
        Shape::Le,
        Shape::Mtr0,
        Shape::Mtr1,
        Shape::Mtr2,
        Shape::Ptr,
        Shape::Msq0,
        Shape::Msq1,
        Shape::Msq2,
        Shape::Msq3,
        Shape::Psq,
        Shape::Mcl0,
        Shape::Mcl1,
        Shape::Scl,
    ];

    /// The paper's short name (`"cr"`, `"mtr0"`, …).
    pub(crate) fn name(self) -> &'static str {
        match self {
            Shape::Cr => "cr",
            Shape::Tr => "tr",
            Shape::Sq => "sq",
            Shape::Sp => "sp",
            Shape::As => "as",
            Shape::Cl => "cl",
            Shape::C0 => "c0",
            Shape::C1 => "c1",
            Shape::C2 => "c2",
            Shape::C3 => "c3",
            Shape::C4 => "c4",
            Shape::St => "st",
            Shape::Ss => "ss",
            Shape::Le => "le",
            Shape::Mtr0 => "mtr0",
            Shape::Mtr1 => "mtr1",
            Shape::Mtr2 => "mtr2",
            Shape::Ptr => "ptr",
            Shape::Msq0 => "msq0",
            Shape::Msq1 => "msq1",
            Shape::Msq2 => "msq2",
            Shape::Msq3 => "msq3",
            Shape::Psq => "psq",
            Shape::Mcl0 => "mcl0",
            Shape::Mcl1 => "mcl1",
            Shape::Scl => "scl",
        }
    }

    /// The shape with this short name, if any.
    pub(crate) fn from_name(name: &str) -> Option<Shape> {
        Shape::ALL.into_iter().find(|s| s.name() == name)
    }

    /// Whether the shape has an outline enclosing an area (painted white
    /// or black); `cr`, `sp` and `c0`–`c4` are lines only.
    pub(crate) fn is_closed(self) -> bool {
        !matches!(
            self,
            Shape::Cr | Shape::Sp | Shape::C0 | Shape::C1 | Shape::C2 | Shape::C3 | Shape::C4
        )
    }
}

/// What a mark does to the paper.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) enum Paint {
    /// Drawn only: the path is a line, whether or not it is closed.
    Line,
    /// A closed outline, drawn, with its interior painted white.
    White,
    /// A closed outline, drawn, with its interior painted black.
    Black,
}

impl Paint {
    /// White for black and black for white (a line stays a line): the
    /// next paint of alternating nested shapes.
    fn opposite(self) -> Paint {
        match self {
            Paint::White => Paint::Black,
            Paint::Black => Paint::White,
            Paint::Line => Paint::Line,
        }
    }
}

/// One mark of an element: a path and what it paints.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Mark {
    /// The line drawn; for [`Paint::White`] and [`Paint::Black`] closed
    /// subpaths whose interior (non-zero rule) is painted.
    pub(crate) path: BezPath,
    /// What the mark paints.
    pub(crate) paint: Paint,
}

impl Mark {
    fn new(path: BezPath, paint: Paint) -> Mark {
        Mark { path, paint }
    }

    /// Whether the mark paints an interior (white or black).
    pub(crate) fn fills(&self) -> bool {
        self.paint != Paint::Line
    }

    /// The mark mapped by `affine` (the placement `[m p]`).
    pub(crate) fn transformed(&self, affine: Affine) -> Mark {
        Mark::new(affine * self.path.clone(), self.paint)
    }

    /// The mark deformed by `lattice` within `tolerance` (the `[f p]` of
    /// docs/SPEC.md §2.2; see [`deform`]).
    pub(crate) fn deformed(&self, lattice: &Lattice, tolerance: f64) -> Mark {
        Mark::new(deform(&self.path, lattice, tolerance), self.paint)
    }
}

/// `marks` deformed by one lattice fitted to [`UNIT`] whose control points
/// are jittered by up to `rx/2`, `ry/2` lattice spacings (docs/SPEC.md §2.2; the
/// paper's `F` with `rx = ry = 1` moves a point up to half a cell), within
/// `tolerance` in unit coordinates (an element drawn `s` mm wide wants the
/// output tolerance divided by `s/2`).
///
/// # Errors
/// When `rx` or `ry` is negative or not finite.
pub(crate) fn wobble(
    marks: &[Mark],
    rx: f64,
    ry: f64,
    rng: &mut RandomStream,
    tolerance: f64,
) -> Result<Vec<Mark>> {
    let lattice = Lattice::jittered(UNIT, rx, ry, rng)?;
    Ok(marks
        .iter()
        .map(|m| m.deformed(&lattice, tolerance))
        .collect())
}

/// The marks of `shape` in painter's order, in [`UNIT`].
///
/// `fill` is the paint of the outermost closed outline; compound shapes
/// paint their inner shapes themselves (see the [module docs](self)).
/// [`Paint::Line`] as `fill` asks for the element's line drawing: the
/// marks of the white element, every one a line, nothing painted. The
/// marks of line-only shapes are lines whatever `fill` says.
pub(crate) fn marks(shape: Shape, fill: Paint) -> Vec<Mark> {
    if fill == Paint::Line && shape.is_closed() {
        return marks(shape, Paint::White)
            .into_iter()
            .map(|m| Mark::new(m.path, Paint::Line))
            .collect();
    }
    let f = fill;
    let line = |p: BezPath| Mark::new(p, Paint::Line);
    match shape {
        Shape::Cr => vec![
            line(segment((-1.0, 0.0), (1.0, 0.0))),
            line(segment((0.0, -1.0), (0.0, 1.0))),
        ],
        Shape::Tr => vec![Mark::new(polygon(&triangle()), f)],
        Shape::Sq => vec![Mark::new(polygon(&square(1.0)), f)],
        Shape::Sp => vec![line(spiral(Point::ORIGIN, 1.0, 3.0, 0.0))],
        Shape::As => vec![Mark::new(arc_square(0.3), f)],
        Shape::Cl => vec![Mark::new(circle(Point::ORIGIN, 1.0), f)],
        Shape::C0 => vec![line(ogee())],
        Shape::C1 => vec![line(wave())],
        Shape::C2 => vec![line(fiddlehead())],
        Shape::C3 => vec![line(cycloid_loop())],
        Shape::C4 => double_arch().into_iter().map(line).collect(),
        Shape::St => strips(&triangle(), f),
        Shape::Ss => strips(&square(1.0), f),
        Shape::Le => leaf(f),
        Shape::Mtr0 => sierpinski(f, 1),
        Shape::Mtr1 => nested(
            &polygon(&triangle()),
            centroid(&triangle()),
            &[0.8, 0.6, 0.4],
            f,
        ),
        Shape::Mtr2 => sierpinski(f, 2),
        Shape::Ptr => paradox(&triangle(), f),
        Shape::Msq0 => nested(&polygon(&square(1.0)), Point::ORIGIN, &[0.75, 0.5, 0.25], f),
        Shape::Msq1 => squares_and_diamonds(f),
        Shape::Msq2 => square_grid(f, None),
        Shape::Msq3 => square_grid(f, Some(Paint::Black)),
        Shape::Psq => paradox(&square(1.0), f),
        Shape::Mcl0 => nested(
            &circle(Point::ORIGIN, 1.0),
            Point::ORIGIN,
            &[0.75, 0.5, 0.25],
            f,
        ),
        Shape::Mcl1 => seven_circles(f),
        Shape::Scl => spiral_circle(f),
    }
}

// ---- building blocks ------------------------------------------------------

/// The equilateral triangle of side 2, point up, its box centred.
fn triangle() -> [Point; 3] {
    [
        Point::new(0.0, -TRI_H),
        Point::new(1.0, TRI_H),
        Point::new(-1.0, TRI_H),
    ]
}

/// The square of half-side `h` about the origin, clockwise on the page.
fn square(h: f64) -> [Point; 4] {
    [
        Point::new(-h, -h),
        Point::new(h, -h),
        Point::new(h, h),
        Point::new(-h, h),
    ]
}

fn centroid(points: &[Point]) -> Point {
    let sum = points.iter().fold(Vec2::ZERO, |s, p| s + p.to_vec2());
    (sum / points.len() as f64).to_point()
}

/// `path` with every subpath turned to positive area (kurbo's sign: the
/// orientation a [`crate::geom::region::Region`] keeps for outer contours).
fn positive(path: BezPath) -> BezPath {
    if path.area() < 0.0 {
        path.reverse_subpaths()
    } else {
        path
    }
}

/// The closed polygon through `points`, positive area.
fn polygon(points: &[Point]) -> BezPath {
    let mut p = BezPath::new();
    for (i, q) in points.iter().enumerate() {
        if i == 0 {
            p.move_to(*q);
        } else {
            p.line_to(*q);
        }
    }
    p.close_path();
    positive(p)
}

fn segment(a: (f64, f64), b: (f64, f64)) -> BezPath {
    let mut p = BezPath::new();
    p.move_to(a);
    p.line_to(b);
    p
}

/// The circle about `c` of radius `r` as arcs, positive area.
fn circle(c: Point, r: f64) -> BezPath {
    positive(Circle::new(c, r).to_path(CURVE_TOLERANCE))
}

/// `path` scaled by `k` about `c`.
fn scaled(path: &BezPath, c: Point, k: f64) -> BezPath {
    Affine::scale_about(k, c) * path.clone()
}

/// The points at fraction `t` along each side of the closed polygon
/// `points` (`t = 0.5`: the midpoint polygon).
fn along_sides(points: &[Point], t: f64) -> Vec<Point> {
    (0..points.len())
        .map(|i| points[i].lerp(points[(i + 1) % points.len()], t))
        .collect()
}

/// Cubics through the parametric curve `f(t) = (point, derivative)` for
/// `t` from `t0` to `t1`: equal steps in `t`, each the Hermite cubic of its
/// end points and tangents (tangent-continuous, exact at the joins). The
/// steps are halved until every cubic is within [`CURVE_TOLERANCE`] of
/// the curve at the same parameters, at a quarter, half and three
/// quarters of its step (a bound on the distance between the two curves
/// there), up to [`MAX_FIT_PIECES`].
fn fit(f: impl Fn(f64) -> (Point, Vec2), t0: f64, t1: f64) -> BezPath {
    let mut pieces = 4;
    loop {
        let dt = (t1 - t0) / pieces as f64;
        let mut path = BezPath::new();
        let (mut p, mut d) = f(t0);
        path.move_to(p);
        let mut good = true;
        for k in 1..=pieces {
            let ta = t0 + dt * (k - 1) as f64;
            let (q, e) = f(t0 + dt * k as f64);
            let c = CubicBez::new(p, p + d * (dt / 3.0), q - e * (dt / 3.0), q);
            good = good
                && [0.25, 0.5, 0.75]
                    .iter()
                    .all(|&u| (c.eval(u) - f(ta + u * dt).0).hypot() <= CURVE_TOLERANCE);
            path.curve_to(c.p1, c.p2, c.p3);
            (p, d) = (q, e);
        }
        if good || pieces >= MAX_FIT_PIECES {
            return path;
        }
        pieces *= 2;
    }
}

/// [`fit`] stops halving here: the curves of this module need far fewer.
const MAX_FIT_PIECES: usize = 1024;

/// The Archimedean spiral `r = a·θ` about `c`, from the centre out to
/// radius `r_max` in `turns` turns, rotated by `phase`.
fn spiral(c: Point, r_max: f64, turns: f64, phase: f64) -> BezPath {
    let theta_max = turns * TAU;
    let a = r_max / theta_max;
    fit(|t| archimedes(c, a, 0.0, phase, t), 0.0, theta_max)
}

/// The point of `r = a·(θ + lag)` at angle `θ + phase` about `c`, and its
/// derivative in `θ`.
fn archimedes(c: Point, a: f64, lag: f64, phase: f64, t: f64) -> (Point, Vec2) {
    let r = a * (t + lag);
    let (s, co) = (t + phase).sin_cos();
    (
        c + Vec2::new(r * co, r * s),
        Vec2::new(a * co - r * s, a * s + r * co),
    )
}

// ---- basic shapes -------------------------------------------------------

/// The square with corners (±1, ±1) whose sides are arcs bulging in by
/// `sagitta`.
fn arc_square(sagitta: f64) -> BezPath {
    let corners = square(1.0);
    // Radius of the arc over a chord of 2 with this sagitta.
    let r = (1.0 + sagitta * sagitta) / (2.0 * sagitta);
    let mut path = BezPath::new();
    path.move_to(corners[0]);
    for i in 0..4 {
        let (a, b) = (corners[i], corners[(i + 1) % 4]);
        let mid = a.midpoint(b);
        // The outward normal of the side is the direction from the origin
        // to its middle; the centre lies outside, so the arc bulges in.
        let out = mid.to_vec2().normalize();
        let centre = mid + out * (r - sagitta);
        let start = (a - centre).atan2();
        let mut sweep = (b - centre).atan2() - start;
        if sweep > PI {
            sweep -= TAU;
        } else if sweep < -PI {
            sweep += TAU;
        }
        let arc = Arc::new(centre, (r, r), start, sweep, 0.0);
        path.extend(arc.append_iter(CURVE_TOLERANCE));
    }
    path.close_path();
    positive(path)
}

/// `c0`: one S-shaped cubic across the square.
fn ogee() -> BezPath {
    let mut p = BezPath::new();
    p.move_to((-1.0, 0.85));
    p.curve_to((0.55, 1.1), (-0.55, -1.1), (1.0, -0.85));
    p
}

/// `c1`: two periods of a sine, amplitude 0.45, across the square.
fn wave() -> BezPath {
    let (amp, k) = (0.45, TAU);
    fit(
        |x| {
            (
                Point::new(x, -amp * (k * x).sin()),
                Vec2::new(1.0, -amp * k * (k * x).cos()),
            )
        },
        -1.0,
        1.0,
    )
}

/// `c2`: a stem rising from the bottom and rolling into a curl, one
/// smooth stroke: an Archimedean spiral wound inwards, continued at its
/// outer end by a cubic down to the bottom of the square.
fn fiddlehead() -> BezPath {
    let centre = Point::new(0.05, -0.3);
    let (r0, turns) = (0.68, 1.5);
    let theta_max = turns * TAU;
    let a = r0 / theta_max;
    // The curl from its outer end inwards, `r = a·(θmax − t)` at angle
    // `−t`: it starts right of the centre heading up and rolls over the
    // top to the left, as a fern's crozier does.
    let curl = fit(
        |t| {
            let r = a * (theta_max - t);
            let (s, c) = (-t).sin_cos();
            (
                centre + Vec2::new(r * c, r * s),
                Vec2::new(-a * c + r * s, -a * s - r * c),
            )
        },
        0.0,
        theta_max * 0.92,
    );
    // The stem rises from the bottom, sweeping right, and meets the curl
    // with its tangent there (the derivative above at t = 0).
    let start = centre + Vec2::new(r0, 0.0);
    let heading = Vec2::new(-a, -r0).normalize();
    let mut path = BezPath::new();
    path.move_to((-0.55, 1.0));
    path.curve_to(Point::new(-0.35, 0.35), start - heading * 0.55, start);
    path.extend(curl.elements().iter().skip(1).copied());
    path
}

/// `c3`: a prolate cycloid arch, `x = 0.32·t − 0.7·sin t`, over one period:
/// a line that makes one loop in the middle.
fn cycloid_loop() -> BezPath {
    let (a, b, h) = (1.0 / PI, 0.7, 0.85);
    fit(
        |t| {
            (
                Point::new(a * t - b * t.sin(), -h * t.cos()),
                Vec2::new(a - b * t.cos(), h * t.sin()),
            )
        },
        -PI,
        PI,
    )
}

/// `c4`: two nested half-ellipses standing on the bottom of the square.
fn double_arch() -> [BezPath; 2] {
    let base = Point::new(0.0, 1.0);
    [(1.0, 1.9), (0.55, 1.15)].map(|(rx, ry)| {
        let arc = Arc::new(base, (rx, ry), PI, PI, 0.0);
        let mut p = BezPath::new();
        p.move_to(base + Vec2::new(-rx, 0.0));
        p.extend(arc.append_iter(CURVE_TOLERANCE));
        p
    })
}

/// `st` and `ss`: the polygon `outline` (a triangle point up or the
/// square) cut into five strips parallel to its bottom side. White: the
/// cuts are lines. Black: strips two and four are painted white.
fn strips(outline: &[Point], fill: Paint) -> Vec<Mark> {
    const N: usize = 5;
    let (top, bottom) = outline
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(t, b), p| {
            (t.min(p.y), b.max(p.y))
        });
    // Half-width of the outline at height y: linear from the top (a point
    // for the triangle) to the bottom.
    let top_w = outline
        .iter()
        .filter(|p| p.y == top)
        .map(|p| p.x.abs())
        .fold(0.0, f64::max);
    let half = |y: f64| top_w + (1.0 - top_w) * (y - top) / (bottom - top);
    let cut = |k: usize| top + (bottom - top) * k as f64 / N as f64;
    let mut marks = vec![Mark::new(polygon(outline), fill)];
    match fill {
        Paint::Black => {
            for k in [1, 3] {
                let (y0, y1) = (cut(k), cut(k + 1));
                let band = [
                    Point::new(-half(y0), y0),
                    Point::new(half(y0), y0),
                    Point::new(half(y1), y1),
                    Point::new(-half(y1), y1),
                ];
                marks.push(Mark::new(polygon(&band), Paint::White));
            }
        }
        _ => {
            for k in 1..N {
                let y = cut(k);
                marks.push(Mark::new(segment((-half(y), y), (half(y), y)), Paint::Line));
            }
        }
    }
    marks
}

/// `le`: a pointed almond, tip up, with a midrib when white (on a black
/// leaf it would not show).
fn leaf(fill: Paint) -> Vec<Mark> {
    let mut outline = BezPath::new();
    outline.move_to((0.0, 1.0));
    outline.curve_to((0.72, 0.45), (0.5, -0.55), (0.0, -1.0));
    outline.curve_to((-0.5, -0.55), (-0.72, 0.45), (0.0, 1.0));
    outline.close_path();
    let mut marks = vec![Mark::new(positive(outline), fill)];
    if fill == Paint::White {
        let mut rib = BezPath::new();
        rib.move_to((0.0, 1.0));
        rib.curve_to((0.06, 0.35), (0.06, -0.3), (0.0, -0.78));
        marks.push(Mark::new(rib, Paint::Line));
    }
    marks
}

// ---- compound shapes ------------------------------------------------------

/// `outline` and copies of it scaled by each of `scales` about `centre`,
/// paints alternating from `fill`.
fn nested(outline: &BezPath, centre: Point, scales: &[f64], fill: Paint) -> Vec<Mark> {
    let mut marks = vec![Mark::new(outline.clone(), fill)];
    let mut paint = fill;
    for &k in scales {
        paint = paint.opposite();
        marks.push(Mark::new(scaled(outline, centre, k), paint));
    }
    marks
}

/// `mtr0` (`depth` 1) and `mtr2` (`depth` 2): the triangle, its midpoint
/// triangle painted white, and at depth 2 the same in each of the three
/// corner triangles.
fn sierpinski(fill: Paint, depth: u32) -> Vec<Mark> {
    fn split(tri: [Point; 3], depth: u32, marks: &mut Vec<Mark>) {
        let m = along_sides(&tri, 0.5);
        marks.push(Mark::new(polygon(&m), Paint::White));
        if depth > 1 {
            // Corner k lies between the midpoints of the sides that meet
            // there: side k−1 (ending at it) and side k (starting at it).
            for k in 0..3 {
                split([tri[k], m[k], m[(k + 2) % 3]], depth - 1, marks);
            }
        }
    }
    let tri = triangle();
    let mut marks = vec![Mark::new(polygon(&tri), fill)];
    split(tri, depth, &mut marks);
    marks
}

/// `ptr` and `psq`: the polygon, then the polygon through the points
/// [`PARADOX_STEP`] along each side of the previous one, until they are
/// smaller than [`PARADOX_MIN_SIZE`] of the outline. White: the inner
/// polygons are lines. Black: they are painted white and black in turn,
/// so the twist shows as bands.
pub(super) fn paradox(outline: &[Point], fill: Paint) -> Vec<Mark> {
    let size = |p: &[Point]| (p[1] - p[0]).hypot();
    let first = size(outline);
    let mut marks = vec![Mark::new(polygon(outline), fill)];
    let mut current = outline.to_vec();
    let mut paint = fill;
    loop {
        current = along_sides(&current, PARADOX_STEP);
        if size(&current) < PARADOX_MIN_SIZE * first {
            break;
        }
        let p = if fill == Paint::Black {
            paint = paint.opposite();
            paint
        } else {
            Paint::Line
        };
        marks.push(Mark::new(polygon(&current), p));
    }
    marks
}

/// `msq1`: the square, the diamond through its midpoints, the square
/// through the diamond's midpoints, and one more diamond; paints
/// alternating.
fn squares_and_diamonds(fill: Paint) -> Vec<Mark> {
    let mut current = square(1.0).to_vec();
    let mut marks = vec![Mark::new(polygon(&current), fill)];
    let mut paint = fill;
    for _ in 0..3 {
        current = along_sides(&current, 0.5);
        paint = paint.opposite();
        marks.push(Mark::new(polygon(&current), paint));
    }
    marks
}

/// `msq2` and `msq3`: the square holding a 2×2 grid of white squares,
/// each with a square of paint `inner` in its middle (`msq3`).
fn square_grid(fill: Paint, inner: Option<Paint>) -> Vec<Mark> {
    let mut marks = vec![Mark::new(polygon(&square(1.0)), fill)];
    for (cx, cy) in [(-0.5, -0.5), (0.5, -0.5), (-0.5, 0.5), (0.5, 0.5)] {
        let at = Affine::translate((cx, cy));
        marks.push(Mark::new(at * polygon(&square(0.36)), Paint::White));
        if let Some(p) = inner {
            marks.push(Mark::new(at * polygon(&square(0.17)), p));
        }
    }
    marks
}

/// `mcl1`: the circle holding seven white circles, one in the middle and
/// six round it.
fn seven_circles(fill: Paint) -> Vec<Mark> {
    let r = 0.28;
    let mut marks = vec![
        Mark::new(circle(Point::ORIGIN, 1.0), fill),
        Mark::new(circle(Point::ORIGIN, r), Paint::White),
    ];
    for k in 0..6 {
        let (s, c) = (k as f64 * TAU / 6.0 - PI / 2.0).sin_cos();
        marks.push(Mark::new(
            circle(Point::new(0.62 * c, 0.62 * s), r),
            Paint::White,
        ));
    }
    marks
}

/// `scl`: the circle with a spiral inside. White: a three-turn spiral line
/// from the centre that ends on the circle. Black: a white band between
/// the spiral `r = a·θ` and the same spiral half a turn further out, so
/// band and gap are equally wide.
fn spiral_circle(fill: Paint) -> Vec<Mark> {
    let mut marks = vec![Mark::new(circle(Point::ORIGIN, 1.0), fill)];
    if fill != Paint::Black {
        marks.push(Mark::new(spiral(Point::ORIGIN, 1.0, 3.0, 0.0), Paint::Line));
        return marks;
    }
    let turns = 2.0;
    let theta_max = turns * TAU;
    // The outer edge reaches a·(θmax + π) = 0.9.
    let a = 0.9 / (theta_max + PI);
    let inner = fit(
        |t| archimedes(Point::ORIGIN, a, 0.0, 0.0, t),
        0.0,
        theta_max,
    );
    let outer = fit(|t| archimedes(Point::ORIGIN, a, PI, 0.0, t), 0.0, theta_max);
    let mut band = inner;
    let back = outer.reverse_subpaths();
    let mut els = back.elements().iter().copied();
    if let Some(kurbo::PathEl::MoveTo(p)) = els.next() {
        band.line_to(p);
    }
    band.extend(els);
    band.close_path();
    marks.push(Mark::new(positive(band), Paint::White));
    marks
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::rng::Seed;
    use kurbo::{ParamCurveNearest, PathEl};

    fn all_fills() -> [Paint; 3] {
        [Paint::White, Paint::Black, Paint::Line]
    }

    /// Points along every segment of `path`.
    pub(in crate::family::zentangle) fn samples(path: &BezPath) -> Vec<Point> {
        path.segments()
            .flat_map(|s| (0..=8).map(move |k| s.eval(k as f64 / 8.0)))
            .collect()
    }

    /// The distance from `p` to the nearest point of `path`.
    pub(in crate::family::zentangle) fn distance_to(path: &BezPath, p: Point) -> f64 {
        path.segments()
            .map(|s| s.nearest(p, 1e-9).distance_sq)
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    }

    /// Inside the closed `outline` or on it.
    fn within(outline: &BezPath, p: Point) -> bool {
        outline.winding(p) != 0 || distance_to(outline, p) < 1e-6
    }

    #[test]
    fn names_round_trip_and_are_distinct() {
        let mut names: Vec<&str> = Shape::ALL.iter().map(|s| s.name()).collect();
        for s in Shape::ALL {
            assert_eq!(Shape::from_name(s.name()), Some(s));
        }
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), 26);
        assert_eq!(Shape::from_name("mtr3"), None);
        let open: Vec<&str> = Shape::ALL
            .iter()
            .filter(|s| !s.is_closed())
            .map(|s| s.name())
            .collect();
        assert_eq!(open, ["cr", "sp", "c0", "c1", "c2", "c3", "c4"]);
    }

    #[test]
    fn every_element_stays_in_the_unit_square() {
        for s in Shape::ALL {
            for f in all_fills() {
                let marks = marks(s, f);
                assert!(!marks.is_empty(), "{}", s.name());
                for m in &marks {
                    let b = m.path.bounding_box();
                    // Arcs are cubics within CURVE_TOLERANCE of the circle.
                    let lim = 1.0 + CURVE_TOLERANCE;
                    assert!(
                        b.x0 >= -lim && b.y0 >= -lim && b.x1 <= lim && b.y1 <= lim,
                        "{} {b:?}",
                        s.name()
                    );
                    assert!(m.path.elements().iter().all(|e| match e {
                        PathEl::MoveTo(p) | PathEl::LineTo(p) => p.is_finite(),
                        PathEl::QuadTo(a, p) => a.is_finite() && p.is_finite(),
                        PathEl::CurveTo(a, b, p) => a.is_finite() && b.is_finite() && p.is_finite(),
                        PathEl::ClosePath => true,
                    }));
                }
            }
        }
    }

    #[test]
    fn paints_follow_the_fill() {
        for s in Shape::ALL {
            for f in all_fills() {
                let marks = marks(s, f);
                if !s.is_closed() || f == Paint::Line {
                    assert!(marks.iter().all(|m| m.paint == Paint::Line), "{}", s.name());
                } else {
                    assert_eq!(marks[0].paint, f, "{}", s.name());
                }
            }
        }
        // The paper's mtr1: tr white, ×0.8 black, then ×0.6, ×0.4 alternating.
        let paints: Vec<Paint> = marks(Shape::Mtr1, Paint::White)
            .iter()
            .map(|m| m.paint)
            .collect();
        assert_eq!(
            paints,
            [Paint::White, Paint::Black, Paint::White, Paint::Black]
        );
    }

    #[test]
    fn closed_outlines_are_closed_with_positive_area_and_hold_the_rest() {
        for s in Shape::ALL.into_iter().filter(|s| s.is_closed()) {
            for f in [Paint::White, Paint::Black] {
                let marks = marks(s, f);
                let outline = &marks[0].path;
                for m in marks.iter().filter(|m| m.fills()) {
                    assert!(m.path.area() > 1e-3, "{} {:?}", s.name(), m.paint);
                    for sub in crate::geom::subpath::subpaths(&m.path) {
                        assert!(sub.ends_with_close(), "{}", s.name());
                    }
                }
                for m in &marks[1..] {
                    for p in samples(&m.path) {
                        assert!(within(outline, p), "{} {:?} at {p:?}", s.name(), m.paint);
                    }
                }
            }
        }
    }

    #[test]
    fn curves_are_curves_and_fill_the_square() {
        for s in [
            Shape::Sp,
            Shape::C0,
            Shape::C1,
            Shape::C2,
            Shape::C3,
            Shape::C4,
        ] {
            let marks = marks(s, Paint::White);
            let mut b = Rect::ZERO;
            for (i, m) in marks.iter().enumerate() {
                assert!(m
                    .path
                    .elements()
                    .iter()
                    .all(|e| !matches!(e, PathEl::LineTo(_))));
                let mb = m.path.bounding_box();
                b = if i == 0 { mb } else { b.union(mb) };
            }
            // Across the square one way, most of it the other.
            let (long, short) = (b.width().max(b.height()), b.width().min(b.height()));
            assert!(long > 1.8 && short > 0.85, "{} {b:?}", s.name());
        }
        // Each curve is its own: no two share their start and end.
        let ends: Vec<(Point, Point)> = [Shape::C0, Shape::C1, Shape::C2, Shape::C3, Shape::C4]
            .iter()
            .map(|s| {
                let p = &marks(*s, Paint::Line)[0].path;
                let segs: Vec<_> = p.segments().collect();
                (segs[0].start(), segs[segs.len() - 1].end())
            })
            .collect();
        for i in 0..ends.len() {
            for j in 0..i {
                assert!(ends[i] != ends[j]);
            }
        }
    }

    #[test]
    fn spirals_follow_the_exact_curve() {
        let a = 1.0 / (3.0 * TAU);
        let sp = spiral(Point::ORIGIN, 1.0, 3.0, 0.0);
        for k in 0..=600 {
            let t = 3.0 * TAU * k as f64 / 600.0;
            let (p, _) = archimedes(Point::ORIGIN, a, 0.0, 0.0, t);
            assert!(distance_to(&sp, p) < CURVE_TOLERANCE, "{t}");
        }
        // It starts at the centre and ends on the unit circle.
        let segs: Vec<_> = sp.segments().collect();
        assert!(segs[0].start().distance(Point::ORIGIN) < 1e-12);
        assert!((segs[segs.len() - 1].end().distance(Point::ORIGIN) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn wobble_is_bounded_and_reproducible() {
        let m = marks(Shape::Msq1, Paint::White);
        let a = wobble(&m, 1.0, 1.0, &mut Seed(4).stream(), 1e-4).unwrap();
        let b = wobble(&m, 1.0, 1.0, &mut Seed(4).stream(), 1e-4).unwrap();
        assert_eq!(a, b);
        assert_ne!(a, m);
        let none = wobble(&m, 0.0, 0.0, &mut Seed(4).stream(), 1e-4).unwrap();
        for (x, y) in none.iter().zip(&m) {
            for p in samples(&y.path) {
                assert!(distance_to(&x.path, p) < 1e-9);
            }
        }
        // A control point moves at most half a cell (1/3), and the map is
        // a convex combination of them.
        for mk in &a {
            let bb = mk.path.bounding_box();
            assert!(bb.x0 > -1.34 && bb.x1 < 1.34 && bb.y0 > -1.34 && bb.y1 < 1.34);
            assert_eq!(mk.paint, m[a.iter().position(|x| x == mk).unwrap()].paint);
        }
        assert!(wobble(&m, -1.0, 0.0, &mut Seed(4).stream(), 1e-4).is_err());
    }
}
