//! The twenty drawing procedures of the paper's table 1 (SPEC §2.3) and
//! their seed groups: what each draws into a region, with which elements
//! and template, and which procedure each white interior it paints may
//! call next (its seed).

use std::f64::consts::{PI, TAU};

use kurbo::{Affine, Point, Vec2};

use super::element::{self, marks, Mark, Paint, Shape};
use super::pattern;
use super::placement;
use crate::error::Result;
use crate::geom::region::Region;
use crate::geom::TOLERANCE;
use crate::rng::RandomStream;

/// `G1`: every procedure (the blank page's seed).
pub(super) const G1: &[u32] = &[
    0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19,
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
#[derive(Debug, Clone, Copy)]
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

/// Runs procedure `id` (0–19) in `t`.
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
            if matches!(id, 4 | 8) && rng.unit() < 1.0 / 3.0 {
                let all = Mark {
                    path: t.region.path().clone(),
                    paint: Paint::Black,
                };
                out.add(vec![all], None, allowed, rng);
            }
            let step = 0.6 * t.size;
            let b = t.region.bounds();
            let instances = match id {
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
                    } else if rng.unit() < 0.75 {
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
                let (shape, paint) = if id == 12 {
                    // E4 with repetition: any curve in any slot.
                    (allowed.element(set, rng), Paint::Line)
                } else {
                    slots[p.slot as usize]
                };
                // A little apart, as a hand leaves them.
                let mut at = p.at * Affine::scale(GAP);
                match id {
                    // (³) Turned at random before placement.
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
            let plant = placement::plant(t.region.bounds(), leaf, rng)?;
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
        _ => {}
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
