//! The twenty drawing procedures of the paper's table 1 (docs/SPEC.md §2.3) and
//! their seed groups: what each draws into a region, with which elements
//! and template, and which procedure each white interior it paints may
//! call next (its seed).

use std::f64::consts::{PI, TAU};

use kurbo::{Affine, Point, Vec2};

use super::element::{self, marks, Mark, Paint, Shape};
use super::pattern;
use super::placement::{self, Lattice};
use super::tangle::{self, Tangle};
use crate::error::Result;
use crate::geom::region::Region;
use crate::geom::TOLERANCE;
use crate::rng::RandomStream;

/// `G1`: every procedure (the blank page's seed), the named tangles
/// after the paper's twenty (drawn only where a description allows them:
/// by default it allows the paper's).
pub(super) const G1: &[u32] = &[
    0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24,
    25, 26, 27, 28, 29, 30, 31,
];
/// `G2`: the region-dependent patterns.
const G2: &[u32] = &[14, 15, 16, 17, 18, 19];
/// `G3`: a circle (what a triangle holds).
const G3: &[u32] = &[2];
/// `G4`: a triangle (what a square holds).
const G4: &[u32] = &[0];
/// `G5`: a square (what a circle holds).
const G5: &[u32] = &[1];
/// `G6`: contour lines or cells (what a leaf holds).
const G6: &[u32] = &[16, 18];

/// `E1`: closed basic and compound shapes.
const E1: &[Shape] = &[
    Shape::Tr,
    Shape::Sq,
    Shape::Cl,
    Shape::St,
    Shape::Ss,
    Shape::Mtr0,
    Shape::Mtr1,
    Shape::Ptr,
    Shape::Msq0,
    Shape::Msq1,
    Shape::Msq2,
    Shape::Psq,
    Shape::Mcl0,
    Shape::Mcl1,
    Shape::Scl,
];
/// `E2`: triangles.
const E2: &[Shape] = &[Shape::Tr, Shape::St, Shape::Mtr0, Shape::Mtr1, Shape::Mtr2];
/// `E3`: squares and circles.
const E3: &[Shape] = &[
    Shape::Sq,
    Shape::Cl,
    Shape::Ss,
    Shape::Msq0,
    Shape::Msq1,
    Shape::Msq2,
    Shape::Msq3,
    Shape::Mcl0,
    Shape::Mcl1,
    Shape::Scl,
];
/// `E4`: the curves.
const E4: &[Shape] = &[Shape::C0, Shape::C1, Shape::C2, Shape::C3, Shape::C4];

/// The seed group of procedure `id`: what a white interior it paints may
/// call next (`None` for procedures that only draw lines).
pub(super) fn seed_group(id: u32) -> Option<&'static [u32]> {
    match id {
        0 => Some(G3),
        1 => Some(G4),
        2 => Some(G5),
        4 | 5 | 6 | 8 | 9 | 10 | 13 | 19 => Some(G2),
        7 => Some(G6),
        15 => Some(G1),
        _ => None,
    }
}

/// The elements procedure `id` draws with (table 1, column d).
pub(super) fn element_set(id: u32) -> &'static [Shape] {
    match id {
        0 => &[Shape::Tr],
        1 | 8 => &[Shape::Sq],
        2 => &[Shape::Cl],
        3 => &[Shape::Cr],
        4 | 10 | 13 | 19 => E1,
        5 => E2,
        6 | 9 => E3,
        7 => &[Shape::Le],
        11 | 12 => E4,
        15 => &[Shape::Sq, Shape::Cl],
        _ => &[],
    }
}

/// What the description allows.
#[derive(Debug, Clone)]
pub(super) struct Allowed {
    /// Procedure ids, ascending.
    pub(super) procedures: Vec<u32>,
    /// Elements.
    pub(super) elements: Vec<Shape>,
}

impl Allowed {
    /// A procedure of `group` that is allowed, at random; any allowed one
    /// when none of the group is.
    pub(super) fn pick(&self, group: &[u32], rng: &mut RandomStream) -> u32 {
        let both: Vec<u32> = group
            .iter()
            .copied()
            .filter(|p| self.procedures.contains(p))
            .collect();
        let from = if both.is_empty() {
            &self.procedures
        } else {
            &both
        };
        from[(rng.unit() * from.len() as f64) as usize % from.len()]
    }

    /// An element of `set` that is allowed, at random; with none of them
    /// allowed, an allowed one of the same kind (closed or line-only), or
    /// any allowed.
    fn element(&self, set: &[Shape], rng: &mut RandomStream) -> Shape {
        let closed = set.first().is_some_and(|s| s.is_closed());
        let pool: Vec<Shape> = {
            let both: Vec<Shape> = set
                .iter()
                .copied()
                .filter(|s| self.elements.contains(s))
                .collect();
            if !both.is_empty() {
                both
            } else {
                let kind: Vec<Shape> = self
                    .elements
                    .iter()
                    .copied()
                    .filter(|s| s.is_closed() == closed)
                    .collect();
                if kind.is_empty() {
                    self.elements.clone()
                } else {
                    kind
                }
            }
        };
        pool[(rng.unit() * pool.len() as f64) as usize % pool.len()]
    }
}

/// Where a procedure draws.
#[derive(Clone, Copy)]
pub(super) struct Target<'a> {
    /// The white region.
    pub(super) region: &'a Region,
    /// The centre of its largest inscribed circle.
    pub(super) pole: Point,
    /// That circle's radius, mm.
    pub(super) radius: f64,
    /// Half the width of a basic element here: the description's `scale`
    /// times the square root of the region's bounding-box area.
    pub(super) size: f64,
    /// The deformation amount (1: the paper's).
    pub(super) wobble: f64,
    /// The pen's width, mm.
    pub(super) pen: f64,
    /// How often the lattices MT, MS and MA lay their rows along the
    /// region's outline instead (0–1).
    pub(super) follow: f64,
    /// How deep ML plants branch (0: the paper's single stem).
    pub(super) branching: u32,
    /// How many times the paper's chance of black elements and black
    /// grounds (tone control, at the region's widest point; 1: the
    /// paper's).
    pub(super) black: f64,
    /// The target darkness (0–1) at a point and how strongly it steers
    /// (tone control; `None`: the paper's even tone).
    pub(super) tone: Option<(&'a dyn Fn(Point) -> f64, f64)>,
}

impl Target<'_> {
    /// Whether an element at `at` is drawn: always without tone control;
    /// with it, where the target is lighter than mid-grey elements thin
    /// out (to `1 − contrast` of them on white), so a lattice fades.
    fn keeps(&self, at: Point, rng: &mut RandomStream) -> bool {
        match self.tone {
            None => true,
            Some((tone, contrast)) => {
                let dark = tone(at).clamp(0.0, 1.0);
                rng.unit() < 1.0 - contrast + contrast * (2.0 * dark).min(1.0)
            }
        }
    }

    /// The paint of an element at `at` whose slot says `paint`: the
    /// slot's without tone control; with it, a black one turns white
    /// where the target is lighter than mid-grey (always on white, at full
    /// contrast) and a white one black where it is darker (half of them
    /// on black).
    fn paint_at(&self, at: Point, paint: Paint, rng: &mut RandomStream) -> Paint {
        let Some((tone, contrast)) = self.tone else {
            return paint;
        };
        let dark = tone(at).clamp(0.0, 1.0);
        match paint {
            Paint::Black if rng.unit() < contrast * (1.0 - 2.0 * dark).max(0.0) => Paint::White,
            Paint::White if rng.unit() < contrast * (dark - 0.5).max(0.0) => Paint::Black,
            other => other,
        }
    }
}

/// What a procedure drew: marks in painter's order (page mm) and, for
/// each, the seed its white interior gets.
#[derive(Debug, Clone, Default)]
pub(super) struct Drawn {
    /// The marks.
    pub(super) marks: Vec<Mark>,
    /// For each mark, the seed of its white interior.
    pub(super) seeds: Vec<Option<u32>>,
}

impl Drawn {
    /// Adds `marks`; their white ones get seeds from `group`.
    fn add(
        &mut self,
        marks: Vec<Mark>,
        group: Option<&[u32]>,
        allowed: &Allowed,
        rng: &mut RandomStream,
    ) {
        for m in marks {
            let seed = match (m.paint, group) {
                (Paint::White, Some(g)) => Some(allowed.pick(g, rng)),
                _ => None,
            };
            self.marks.push(m);
            self.seeds.push(seed);
        }
    }
}

/// Runs procedure `id` in `t`: 0–19 the paper's, from 20 the named
/// tangles ([`Tangle`]).
///
/// # Errors
/// From the region machinery on degenerate geometry.
pub(super) fn draw(
    id: u32,
    t: &Target<'_>,
    allowed: &Allowed,
    rng: &mut RandomStream,
) -> Result<Drawn> {
    let mut out = Drawn::default();
    let group = seed_group(id);
    let set = element_set(id);
    // Basic and symmetric patterns sit at the widest point of the region,
    // a little off it (the paper jitters the bounding box's centre; the
    // widest point keeps a ring's pattern out of its hole).
    let jitter = Vec2::from_angle(rng.unit() * TAU) * (rng.unit() * 0.15 * t.radius);
    let centre = t.pole + jitter;
    match id {
        0..=2 => {
            let shape = allowed.element(set, rng);
            let angle = (rng.unit() - 0.5) * PI / 6.0;
            let at = about(centre, angle, 2.0 * t.size);
            let m = placed(shape, Paint::White, at, 2.0 * t.size, t, rng)?;
            out.add(m, group, allowed, rng);
        }
        3 | 11 => {
            let shape = allowed.element(set, rng);
            let angle = rng.unit() * TAU;
            let at = about(centre, angle, 2.0 * t.size);
            let m = placed(shape, Paint::Line, at, 2.0 * t.size, t, rng)?;
            out.add(m, group, allowed, rng);
        }
        4 | 5 | 6 | 8 | 9 | 10 | 12 | 13 => {
            // (¹) With probability 1/3 the region is painted black first.
            if matches!(id, 4 | 8) && rng.unit() < t.black / 3.0 {
                let all = Mark {
                    path: t.region.path().clone(),
                    paint: Paint::Black,
                };
                out.add(vec![all], None, allowed, rng);
            }
            let step = 0.6 * t.size;
            let b = t.region.bounds();
            // Beyond the paper: a lattice bent along the outline. The
            // stream is drawn from only when it may be, so `follow = 0`
            // draws the paper's patterns number for number.
            let follow = matches!(id, 5 | 6 | 9 | 10) && t.follow > 0.0 && rng.unit() < t.follow;
            let instances = match id {
                5 if follow => placement::along_contours(t.region, step, Lattice::Triangles)?,
                6 if follow => placement::along_contours(t.region, step, Lattice::Squares)?,
                9 | 10 if follow => placement::along_contours(t.region, step, Lattice::Rows)?,
                4 | 8 | 12 => placement::scatter(t.region, step, rng)?,
                5 => placement::triangles(b, centre, step)?,
                6 => placement::squares(b, centre, step)?,
                9 | 10 => placement::rows(b, centre, step)?,
                _ => placement::rotational(b, centre, step, 3 + (rng.unit() * 6.0) as usize)?,
            };
            // Slots a, b, c: one element and paint each.
            let slots: Vec<(Shape, Paint)> = (0..3)
                .map(|_| {
                    let shape = allowed.element(set, rng);
                    let paint = if !shape.is_closed() {
                        Paint::Line
                    } else if rng.unit() < 1.0 - 0.25 * t.black {
                        Paint::White
                    } else {
                        Paint::Black
                    };
                    (shape, paint)
                })
                .collect();
            // Lattices cover the region's box; only the elements near the
            // region itself can show (its widest reach is a cell away).
            let near = |c: Point| {
                t.region.contains(c)
                    || [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                        .iter()
                        .any(|&(x, y)| t.region.contains(c + Vec2::new(x, y) * (step / 2.0)))
            };
            for p in instances.into_iter().filter(|p| near(p.centre())) {
                if !t.keeps(p.centre(), rng) {
                    continue;
                }
                let (shape, paint) = if id == 12 {
                    // E4 with repetition: any curve in any slot.
                    (allowed.element(set, rng), Paint::Line)
                } else {
                    slots[p.slot as usize]
                };
                let paint = t.paint_at(p.centre(), paint, rng);
                // A little apart, as a hand leaves them.
                let mut at = p.at * Affine::scale(GAP);
                match id {
                    // (³) Turned at random before placement; by quarter
                    // turns in a row along the outline, which it keeps.
                    10 if follow => at *= Affine::rotate((rng.unit() * 4.0).floor() * PI / 2.0),
                    10 | 12 => at *= Affine::rotate(rng.unit() * TAU),
                    // (²) Stretched across and turned.
                    8 => {
                        at *= Affine::rotate(rng.unit() * TAU)
                            * Affine::scale_non_uniform(1.5 + rng.unit(), 1.0)
                    }
                    _ => {}
                }
                let m = placed(shape, paint, at, step, t, rng)?;
                out.add(m, group, allowed, rng);
            }
        }
        7 => {
            let leaf = 0.3 * t.size;
            let plant = placement::plant(t.region.bounds(), leaf, t.branching, rng)?;
            let lines = plant
                .stems
                .into_iter()
                .map(|path| Mark {
                    path,
                    paint: Paint::Line,
                })
                .collect();
            out.add(lines, None, allowed, rng);
            for p in plant.leaves {
                let shape = allowed.element(set, rng);
                let m = placed(shape, Paint::White, p.at, leaf, t, rng)?;
                out.add(m, group, allowed, rng);
            }
        }
        14 | 18 => {
            let spacing = (0.45 * t.size).max(4.0 * t.pen);
            let m = pattern::cells_or_triangles(t.region, spacing, id == 14, rng)?;
            out.add(m, None, allowed, rng);
        }
        15 => {
            let shape = allowed.element(set, rng);
            let paint = if rng.unit() < 0.5 {
                Paint::Line
            } else {
                Paint::White
            };
            let tile = (0.35 * t.size).max(4.0 * t.pen);
            out.add(
                pattern::tiled(t.region, shape, tile, paint),
                group,
                allowed,
                rng,
            );
        }
        16 => {
            let gap = (t.radius / 5.0).max(3.0 * t.pen);
            out.add(pattern::contour_lines(t.region, gap)?, None, allowed, rng);
        }
        17 => {
            let corners = 3 + (rng.unit() * 4.0) as usize;
            out.add(
                pattern::paradox_whirl(t.region, corners),
                None,
                allowed,
                rng,
            );
        }
        19 => {
            let width = (0.35 * t.size).min(t.radius).max(4.0 * t.pen);
            let a = (allowed.element(set, rng), Paint::White);
            let b = (allowed.element(set, rng), Paint::Black);
            let m = pattern::along_border(t.region, width, &mut |k| if k % 2 == 0 { a } else { b });
            out.add(m, group, allowed, rng);
        }
        _ => {
            if let Some(named) = Tangle::from_id(id) {
                out.add(tangle::draw(named, t, rng)?, None, allowed, rng);
            }
        }
    }
    Ok(out)
}

/// Elements of symmetric patterns fill this share of their lattice cell.
const GAP: f64 = 0.87;

/// The placement of an element `width` mm across, centred at `centre`,
/// turned by `angle`.
fn about(centre: Point, angle: f64, width: f64) -> Affine {
    Affine::translate(centre.to_vec2()) * Affine::rotate(angle) * Affine::scale(width / 2.0)
}

/// `shape` painted `paint`, deformed by hand (as much as `t.wobble`
/// says) and placed by `at` (from the element square to the page; about
/// `width` mm across).
fn placed(
    shape: Shape,
    paint: Paint,
    at: Affine,
    width: f64,
    t: &Target<'_>,
    rng: &mut RandomStream,
) -> Result<Vec<Mark>> {
    let unit = marks(shape, paint);
    let unit = if t.wobble > 0.0 {
        element::wobble(&unit, t.wobble, t.wobble, rng, TOLERANCE / (width / 2.0))?
    } else {
        unit
    };
    Ok(unit.iter().map(|m| m.transformed(at)).collect())
}

#[cfg(test)]
mod tests {
    use kurbo::{Circle, Shape as _};

    use super::*;
    use crate::geom::region::FillRule;
    use crate::rng::Seed;

    /// Procedure 6 (MS) with plain squares in a disc of radius 40, with
    /// `follow` as given.
    fn squares_in_a_disc(follow: f64) -> (Vec<Mark>, f64) {
        let c = Point::new(50.0, 50.0);
        let disc = Region::new(Circle::new(c, 40.0).to_path(1e-4), FillRule::NonZero).unwrap();
        let size = 0.35 * disc.bounds().area().sqrt();
        let t = Target {
            region: &disc,
            pole: c,
            radius: 40.0,
            size,
            wobble: 0.0,
            pen: 0.3,
            follow,
            branching: 2,
            black: 1.0,
            tone: None,
        };
        let allowed = Allowed {
            procedures: vec![6],
            elements: vec![Shape::Sq],
        };
        let mut rng = Seed(2).derive("p6").stream();
        (draw(6, &t, &allowed, &mut rng).unwrap().marks, 0.6 * size)
    }

    #[test]
    fn lattices_follow_the_outline_when_asked() {
        let c = Point::new(50.0, 50.0);
        // On the lattice, squares stand upright wherever they are.
        let (marks, _) = squares_in_a_disc(0.0);
        assert!(marks.iter().all(|m| {
            let b = m.path.bounding_box();
            (b.width() - b.height()).abs() < 1e-6 && m.path.elements().len() <= 6
        }));
        let upright = |m: &Mark| {
            let b = m.path.bounding_box();
            let area = m.path.area().abs();
            (area - b.area()).abs() < 1e-6 * b.area()
        };
        assert!(marks.iter().all(upright));
        // Along the outline: on rings half a step, one and a half … in,
        // turned to face it (so most are not upright).
        let (marks, step) = squares_in_a_disc(1.0);
        assert!(marks.len() >= 12, "{}", marks.len());
        let mut turned = 0;
        for m in &marks {
            let centre = m.path.bounding_box().center();
            let depth = 40.0 - centre.distance(c);
            let k = (depth / step - 0.5).round();
            assert!(
                (depth - (k + 0.5) * step).abs() < 0.01 * step || centre.distance(c) < step,
                "a square {depth} mm in, rings are {step} mm apart"
            );
            turned += usize::from(!upright(m));
        }
        assert!(
            turned > marks.len() / 2,
            "{turned} of {} turned",
            marks.len()
        );
    }

    /// Ink in the left and right thirds of an A5 page: the length of the
    /// lines plus the black area (as the pen would hatch it, 0.3 mm
    /// apart).
    fn ink_by_side(table: &str) -> (f64, f64) {
        let table = format!("look = \"sampler\"\n{table}");
        let scene = crate::motif::test_scene::scene("zentangle", &table);
        let width = scene.page.drawable().width();
        let (mut left, mut right) = (0.0, 0.0);
        scene.layers[0]
            .content
            .visit_paths(kurbo::Affine::IDENTITY, &mut |p, t| {
                let path = t * p.path.clone();
                let x = path.bounding_box().center().x;
                let ink = if p.style.fill.is_some() {
                    path.area().abs() / 0.3
                } else {
                    path.perimeter(0.01)
                };
                if x < width / 3.0 {
                    left += ink;
                } else if x > 2.0 * width / 3.0 {
                    right += ink;
                }
            });
        (left, right)
    }

    #[test]
    fn a_tone_map_puts_more_ink_where_it_is_dark() {
        // Without tone the two sides get about the same; with the
        // target dark on the right, the right gets far more.
        let (l0, r0) = ink_by_side("steps = 80\n");
        assert!(
            r0 < 2.0 * l0 && l0 < 2.0 * r0,
            "untoned: {l0:.0} left, {r0:.0} right"
        );
        let (l1, r1) = ink_by_side("steps = 80\ntone = { formula = \"u\" }\n");
        assert!(r1 > 4.0 * l1, "toned: {l1:.0} left, {r1:.0} right");
        // Full contrast leaves the white end of the page all but empty
        // (the dark end is as dark as the ink limit lets it be).
        let (l2, r2) = ink_by_side("steps = 80\ntone = { formula = \"u\", contrast = 1 }\n");
        assert!(r2 > 4.0 * l2, "full contrast: {l2:.0} left, {r2:.0} right");
    }
}
