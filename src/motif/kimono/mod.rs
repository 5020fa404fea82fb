//! Kimono plant patterns (SPEC §1): the overall flow (upper and lower
//! region lines) and tree sets placed along their centre lines.
//!
//! A tree set puts `count` trees at even arc-length spacing along its centre
//! line (SPEC §1.4): tree `i` stands at arc length `L·(i + ½)/count`,
//! perpendicular to the line on its upper side or along it, then turned by
//! the set's and the tree's `rotate`. Every tree has the id `tree-N` inside
//! its set, and per-tree overrides (root, rotate, scale, parameters) are
//! addressed by that id.

pub mod adjust;
pub mod background;
pub mod bloom;

use kurbo::{BezPath, Point, Vec2};

pub use adjust::Adjustments;
pub use bloom::FloraContext;

use crate::error::Result;
use crate::geom::{natural_spline, PathWalker, Side, SideTest, TOLERANCE};
use crate::motif::tree::{self, Growth, LimbLook};
use crate::scene::{Color, Group, PathBudget, Style};
use crate::spec::{
    Growth as Orientation, LimbSpec, Points, RegionLinesSpec, TreeOverride, TreeSetSpec,
};

/// The overall flow: what stops trees from growing.
pub struct Flow {
    upper: Option<SideTest>,
    lower: Option<SideTest>,
}

/// Natural spline through control points given as `[x, y]` pairs.
pub fn flow_line(points: &Points) -> BezPath {
    let pts: Vec<Point> = points.iter().map(|[x, y]| Point::new(*x, *y)).collect();
    natural_spline(&pts)
}

/// A region line as a far-side test. The line is taken left to right (its
/// points are reversed when the last lies left of the first), so the far
/// side of the upper line is above it and that of the lower line below.
fn region_test(points: &Points, far: Side) -> SideTest {
    let mut pts = points.clone();
    if pts[pts.len() - 1][0] < pts[0][0] {
        pts.reverse();
    }
    SideTest::new(&flow_line(&pts), far)
}

impl Flow {
    /// The flow of a scene description's `[lines]`.
    pub fn new(lines: &RegionLinesSpec) -> Flow {
        Flow {
            upper: lines.upper.as_ref().map(|p| region_test(p, Side::Left)),
            lower: lines.lower.as_ref().map(|p| region_test(p, Side::Right)),
        }
    }

    /// True when `p` may not be part of a tree: beyond the upper line, or —
    /// for a tree growing downward — beyond the lower line.
    pub fn blocks(&self, p: Point, downward: bool) -> bool {
        self.upper.as_ref().is_some_and(|t| t.is_beyond(p))
            || (downward && self.lower.as_ref().is_some_and(|t| t.is_beyond(p)))
    }
}

/// Where one tree of a set stands and how it is scaled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
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
        let n =
            o.id.strip_prefix("tree-")
                .and_then(|n| n.parse::<usize>().ok());
        if let Some(slot) = n.and_then(|n| by_tree.get_mut(n)) {
            *slot = Some(o);
        }
    }
    by_tree
}

/// The placements of a set's trees, overrides applied.
pub fn placements(set: &TreeSetSpec) -> Vec<Placement> {
    let walker = PathWalker::new(&flow_line(&set.centre), TOLERANCE);
    let n = set.count as usize;
    overrides_by_tree(set)
        .into_iter()
        .enumerate()
        .map(|(i, o)| {
            let s = walker.length() * (i as f64 + 0.5) / n as f64;
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
            let rotate = set.rotate + o.and_then(|o| o.rotate).unwrap_or(0.0);
            Placement {
                root: o
                    .and_then(|o| o.root)
                    .map_or_else(|| walker.point_at(s), |[x, y]| Point::new(x, y)),
                direction: turn(base, rotate),
                scale: o.and_then(|o| o.scale).unwrap_or(1.0),
            }
        })
        .collect()
}

/// Grows and draws a tree set into a group with id `group_id`, calling
/// `tree_done` after each tree.
///
/// Each tree gets its own random stream, derived from the seed and its id,
/// so changing one set or tree leaves the others as they were. The final
/// adjustment of a tree (by its full id) hides it with its flowers and
/// leaves, or moves its root, turns and scales it before it grows, so the
/// region lines still hold. Each tree is a [solid](Group::solid) group of
/// limbs, followed by its leaves and flowers ([`bloom`]).
#[allow(clippy::too_many_arguments)]
pub fn tree_set(
    set: &TreeSetSpec,
    group_id: &str,
    limbs: &LimbSpec,
    flow: &Flow,
    cx: &FloraContext<'_>,
    adjust: &mut Adjustments<'_>,
    budget: &mut PathBudget,
    tree_done: &mut dyn FnMut(),
) -> Result<Group> {
    let mut group = Group::new(group_id);
    let style = Style {
        fill: limbs.fill.as_deref().and_then(Color::parse),
        ..Style::default()
    };
    let overrides = overrides_by_tree(set);
    for (i, mut place) in placements(set).into_iter().enumerate() {
        let full_id = format!("{group_id}.tree-{i}");
        let adjusted = adjust.take_tree(&full_id)?;
        if adjusted.is_some_and(|a| a.hide) {
            adjust.take_parts_of(&full_id);
            tree_done();
            continue;
        }
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
        p.trunk *= place.scale;
        let downward = place.direction.y > 0.0;
        let blocked = |q: Point| flow.blocks(q, downward);
        let skeleton = tree::grow(
            set.rule,
            &p,
            &Growth {
                root: place.root,
                direction: place.direction,
                blocked: &blocked,
            },
            cx.seed.derive(&full_id).stream(),
            budget,
            &format!("tree {full_id}"),
        )?;
        let look = LimbLook {
            style: limbs.style,
            width: limbs.width * place.scale,
            tip_width: limbs.tip_width * place.scale,
            bow: limbs.bow,
        };
        let mut tree_group = Group::solid(&full_id);
        for (k, path) in tree::limb_paths(&skeleton, &look).into_iter().enumerate() {
            tree_group.push_path(format!("{full_id}.limb-{k}"), path, style.clone());
        }
        group.push_group(tree_group);
        if let Some(flora) =
            bloom::tree_flora(set, &skeleton, i, &full_id, place.scale, cx, adjust, budget)?
        {
            group.push_group(flora.leaves);
            group.push_group(flora.flowers);
        }
        tree_done();
    }
    Ok(group)
}

/// The id of tree set `k` of a layer.
pub fn set_id(set: &TreeSetSpec, k: usize) -> String {
    set.id.clone().unwrap_or_else(|| format!("trees-{k}"))
}

#[cfg(test)]
mod tests;
