//! Kimono plant patterns (docs/SPEC.md §1): the overall flow (upper and lower
//! region lines) and tree sets placed along their centre lines.
//!
//! A tree set puts `count` trees at even arc-length spacing along its centre
//! line (docs/SPEC.md §1.4): tree `i` stands at arc length `L·(i + ½)/count`,
//! perpendicular to the line on its upper side or along it, then turned by
//! the set's and the tree's `rotate`. Every tree has the id `tree-N` inside
//! its set, and per-tree overrides (root, rotate, scale, parameters) are
//! addressed by that id.

pub(crate) mod description;
pub(crate) mod background;
pub(crate) mod bloom;
pub(crate) mod tree;

use kurbo::{Point, Vec2};

use crate::error::Result;
use crate::family::kimono::tree::{Growth, LimbLook, Skeleton};
use crate::geom::{PathWalker, Side, TOLERANCE};
use crate::motif::{flow_line, Context};
use crate::rng::RandomStream;
use crate::scene::{Color, Group, PathBudget, Style};
use crate::spec::{Growth as Orientation, TreeOverride, TreeSetSpec};

/// Where one tree of a set stands and how it is scaled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Placement {
    /// Root point (mm).
    pub root: Point,
    /// Unit growth direction.
    pub direction: Vec2,
    /// Length and width scale.
    pub scale: f64,
}

/// Rotates a unit vector clockwise on the page by `deg` degrees.
fn turn(v: Vec2, deg: f64) -> Vec2 {
    let (s, c) = deg.to_radians().sin_cos();
    Vec2::new(v.x * c - v.y * s, v.x * s + v.y * c)
}

/// The override of each tree of a set, indexed by tree number: one pass
/// over the overrides, so lookups stay O(1) however many there are.
/// Validation guarantees ids are unique `tree-N` with `N < count`.
fn overrides_by_tree(set: &TreeSetSpec) -> Vec<Option<&TreeOverride>> {
    let mut by_tree = vec![None; set.count as usize];
    for o in &set.overrides {
        if let Some(slot) = set.tree_of(o).and_then(|n| by_tree.get_mut(n)) {
            *slot = Some(o);
        }
    }
    by_tree
}

/// The placements of a set's trees, overrides applied.
pub(super) fn placements(set: &TreeSetSpec) -> Vec<Placement> {
    let walker = PathWalker::new(&flow_line(&set.centre), TOLERANCE);
    let places = set.rhythm.places(set.count as usize);
    overrides_by_tree(set)
        .into_iter()
        .zip(places)
        .map(|(o, (along, size, fan))| {
            let s = walker.length() * along;
            let tangent = walker.tangent_at(s);
            let base = match set.growth {
                Orientation::Perpendicular => {
                    let left = Side::Left.normal(tangent);
                    if left.y > 0.0 {
                        -left
                    } else {
                        left
                    }
                }
                Orientation::Parallel => tangent,
            };
            let rotate = set.rotate + fan + o.and_then(|o| o.rotate).unwrap_or(0.0);
            Placement {
                root: o
                    .and_then(|o| o.root)
                    .map_or_else(|| walker.point_at(s), |[x, y]| Point::new(x, y)),
                direction: turn(base, rotate),
                scale: size * o.and_then(|o| o.scale).unwrap_or(1.0),
            }
        })
        .collect()
}

/// A grown tree, for its flowers and leaves.
pub(crate) struct GrownTree<'s> {
    /// Its limbs.
    pub skeleton: &'s Skeleton,
    /// Its number in the set (for type 2 motif assignment).
    pub index: usize,
    /// Its full id (`<layer>.<set>.tree-<index>`).
    pub id: &'s str,
    /// Its placement scale (flowers and leaves scale with it).
    pub scale: f64,
}

/// How one tree of a set differs from the set as written: the main tree
/// and its companions of [`VarySpec`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Variation {
    /// Size factor.
    pub scale: f64,
    /// Extra turn, degrees clockwise.
    pub turn: f64,
    /// Generations fewer than the set's.
    pub fewer: u32,
    /// Grown mirrored.
    pub mirror: bool,
}

impl Variation {
    const NONE: Variation = Variation {
        scale: 1.0,
        turn: 0.0,
        fewer: 0,
        mirror: false,
    };

    /// Tree `i`'s variation; a companion draws it from `rng`. With
    /// `reach` the trees are sized to the line, the main tree reaching it
    /// and the companions falling short by up to the size spread; without,
    /// the main tree is `main_scale` times the companions' size.
    pub(super) fn of(set: &TreeSetSpec, i: usize, rng: &mut RandomStream) -> Variation {
        let Some(v) = &set.vary else {
            return Variation::NONE;
        };
        let main = v.main as usize;
        if i == main {
            let scale = if set.reach.is_some() { 1.0 } else { v.main_scale };
            return Variation { scale, ..Variation::NONE };
        }
        let scale = if set.reach.is_some() {
            1.0 - v.size * rng.unit()
        } else {
            1.0 + rng.symmetric(v.size)
        };
        Variation {
            scale,
            turn: rng.symmetric(v.turn),
            fewer: rng.below(v.generations as usize + 1) as u32,
            mirror: v.mirror && i.abs_diff(main) % 2 == 1,
        }
    }
}

/// The order the trees of a set are painted in: by number, the main tree
/// last so that it stands in front of its companions.
fn paint_order(set: &TreeSetSpec) -> Vec<usize> {
    let main = set.vary.as_ref().map(|v| v.main as usize);
    let mut order: Vec<usize> = (0..set.count as usize).filter(|i| Some(*i) != main).collect();
    order.extend(main.filter(|m| *m < set.count as usize));
    order
}

/// Factors tried when sizing a tree to the upper line: from a third to
/// four times its size, in steps of 8 %, then halved between the last two.
const REACH_SMALLEST: f64 = 0.3;
const REACH_LARGEST: f64 = 4.0;
const REACH_STEP: f64 = 1.08;
const REACH_HALVINGS: u32 = 10;

/// The size factor that brings a tree within `reach` mm of the upper line:
/// the smallest tried whose highest limb is that close. `headroom(k)` is
/// the least distance below the line of the tree grown `k` times its size
/// (`None` when it has no limbs or there is no line). A tree that comes no
/// closer keeps the factor that came closest.
fn fit_to_line(
    reach: f64,
    mut headroom: impl FnMut(f64) -> Result<Option<f64>>,
) -> Result<f64> {
    let mut best = (f64::INFINITY, 1.0);
    let mut below = REACH_SMALLEST;
    let mut k = REACH_SMALLEST;
    while k <= REACH_LARGEST {
        match headroom(k)? {
            Some(h) if h <= reach => {
                let mut above = k;
                for _ in 0..REACH_HALVINGS {
                    let mid = 0.5 * (below + above);
                    if headroom(mid)?.is_some_and(|h| h <= reach) {
                        above = mid;
                    } else {
                        below = mid;
                    }
                }
                return Ok(above);
            }
            Some(h) if h < best.0 => best = (h, k),
            _ => {}
        }
        below = k;
        k *= REACH_STEP;
    }
    Ok(best.1)
}

/// Grows and draws a tree set into a group with id `group_id`, one unit
/// of progress per tree.
///
/// Each tree gets its own random stream, derived from the seed and its id,
/// so changing one set or tree leaves the others as they were. The final
/// adjustment of a tree (by its full id) hides it with its flowers and
/// leaves, or moves its root, turns and scales it before it grows, so the
/// region lines still hold. A set with `reach` sizes each upward tree to
/// the upper line; one with `vary` makes a main tree and companions
/// ([`Variation`]). Each tree is a [solid](Group::solid) group of limbs,
/// followed by its leaves and flowers ([`bloom`]).
pub(super) fn tree_set(set: &TreeSetSpec, group_id: &str, cx: &mut Context<'_>) -> Result<Group> {
    let mut group = Group::new(group_id);
    let limbs = &cx.layer().limbs;
    let style = Style {
        fill: limbs
            .fill
            .as_deref()
            .and_then(|f| Color::parse_in(f, cx.palette())),
        ..Style::default()
    };
    let overrides = overrides_by_tree(set);
    let mut places = placements(set);
    for i in paint_order(set) {
        let place = &mut places[i];
        let full_id = format!("{group_id}.tree-{i}");
        let adjusted = cx.adjust().take_without_motif(&full_id, "a tree")?;
        if adjusted.is_some_and(|a| a.hide) {
            cx.adjust().take_parts_of(&full_id);
            cx.advance(1);
            continue;
        }
        let variation = Variation::of(set, i, &mut cx.stream(&format!("{full_id}.vary")));
        place.direction = turn(place.direction, variation.turn);
        if let Some(a) = adjusted {
            let [dx, dy] = a.offset.unwrap_or([0.0, 0.0]);
            place.root += Vec2::new(dx, dy);
            place.direction = turn(place.direction, a.rotate.unwrap_or(0.0));
            place.scale *= a.scale.unwrap_or(1.0);
        }
        let params = match overrides[i] {
            Some(o) => o.params.over(&set.params),
            None => set.params.clone(),
        };
        let mut p = params.resolve();
        p.generations = p.generations.saturating_sub(variation.fewer);
        let downward = place.direction.y > 0.0;
        let flow = cx.flow();
        let blocked = |q: Point| flow.blocks(q, downward);
        let growth = Growth {
            root: place.root,
            direction: place.direction,
            blocked: &blocked,
            mirror: variation.mirror,
        };
        let what = format!("tree {full_id}");
        let stream = cx.stream(&full_id);
        let grow_at = |k: f64, budget: &mut PathBudget| {
            let mut q = p;
            q.trunk *= k;
            tree::grow(set.rule, &q, &growth, stream.clone(), budget, &what)
        };
        let fitted = match set.reach {
            Some(reach) if !downward => {
                let trial = cx.budget().clone();
                fit_to_line(reach, |k| {
                    let skeleton = grow_at(place.scale * k, &mut trial.clone())?;
                    Ok(skeleton
                        .vertices()
                        .filter_map(|v| flow.headroom(v))
                        .min_by(f64::total_cmp))
                })?
            }
            _ => 1.0,
        };
        place.scale *= fitted * variation.scale;
        let skeleton = grow_at(place.scale, cx.budget())?;
        let look = LimbLook {
            style: limbs.style,
            width: limbs.width * place.scale,
            tip_width: limbs.tip_width * place.scale,
            bow: limbs.bow,
            pen_width: cx.pen_width(),
        };
        let mut tree_group = Group::solid(&full_id);
        for (k, path) in crate::motif::limb::strokes_first(
            tree::limb_paths(&skeleton, &look).into_iter().enumerate(),
        ) {
            tree_group.push_path(format!("{full_id}.limb-{k}"), path, style.clone());
        }
        group.push_group(tree_group);
        let grown = GrownTree {
            skeleton: &skeleton,
            index: i,
            id: &full_id,
            scale: place.scale,
        };
        if let Some(flora) = bloom::tree_flora(set, &grown, cx)? {
            group.push_group(flora.leaves);
            group.push_group(flora.flowers);
        }
        cx.advance(1);
    }
    Ok(group)
}

#[cfg(test)]
mod tests;
