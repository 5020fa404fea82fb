//! Flowers and leaves on a grown tree (docs/SPEC.md §1.5, [000 §4.6–4.8]).
//!
//! * **Flowers** sit at the tips of the limbs (trunk first, then in the
//!   order the limbs grew) or at every vertex but the root. Type 1 gives
//!   the i-th flower of every tree motif `i mod n`; type 2 gives every
//!   flower of tree k motif `k mod n` (n ≤ 5 motifs; the source's "(i mod
//!   5) + 1" with five images). Flowers stand upright, turned by at most
//!   `turn` degrees at random.
//! * **Leaf 1** puts a ring of `count` leaves around each flower, evenly
//!   spaced with the first pointing up, each leaf's stem end `spacing` mm
//!   from the flower's centre and the leaf pointing away from it.
//! * **Leaf 2** puts a leaf at every branch joint, pointing along the
//!   branch and turned `angle` degrees further to the branch's side.
//! * Leaves follow the set's flower type: type 1 uses the first leaf motif
//!   everywhere, type 2 gives tree k leaf motif `k mod n`.
//!
//! Sizes scale with the tree (a tree scaled by an override carries larger
//! flowers); with `main_largest` they also fall along each tree or with
//! the layer's depth.
//!
//! Ids: `<tree>.flower-<i>`, `<tree>.flower-<i>.leaf-<j>` (ring leaves
//! belong to their flower: adjusting a flower moves, turns, scales or hides
//! its ring with it), `<tree>.joint-<j>`. Each motif is one path (outline,
//! then details), so its id is the path's id in the SVG. Each flower and
//! leaf draws its jitter from its own stream, derived from its id.

use kurbo::{Affine, Point, Vec2};

use super::GrownTree;
use crate::error::Result;
use crate::family::kimono::tree::Skeleton;
use crate::geom::Side;
use crate::motif::adjust::about;
use crate::motif::place::{angle_from_up, put, sized, Put};
use crate::motif::Context;
use crate::scene::Group;
use crate::spec::{Assign, FlowerSites, FlowerSpec, MainLargest, MotifRef, TreeSetSpec};

/// One tree's leaves and flowers, as two groups `<tree>.leaves` and
/// `<tree>.flowers` (leaves painted first, so flowers are in front).
pub(crate) struct TreeFlora {
    /// Ring and joint leaves.
    pub leaves: Group,
    /// Flowers.
    pub flowers: Group,
}

/// The motif of the `i`-th item of tree `k` under an assignment type.
fn assigned(motifs: &[MotifRef], assign: Assign, i: usize, k: usize) -> &MotifRef {
    let n = motifs.len();
    match assign {
        Assign::Type1 => &motifs[i % n],
        Assign::Type2 => &motifs[k % n],
    }
}

/// The leaf motif of tree `k`: type 1 uses the first only.
fn leaf_motif(motifs: &[MotifRef], assign: Assign, k: usize) -> &MotifRef {
    assigned(motifs, assign, 0, k)
}

/// The flower sites of a skeleton, in order.
fn flower_sites(skeleton: &Skeleton, at: FlowerSites) -> Vec<Point> {
    match at {
        FlowerSites::Tips => skeleton
            .limbs
            .iter()
            .filter_map(|l| l.points.last().copied())
            .collect(),
        FlowerSites::Vertices => skeleton
            .limbs
            .iter()
            .flat_map(|l| l.points.iter().skip(1).copied())
            .collect(),
    }
}

/// Size factor of flower `i` of `n` (see [`MainLargest`]).
fn size_factor(f: &FlowerSpec, i: usize, n: usize, depth: i32) -> f64 {
    match f.main_largest {
        MainLargest::None => 1.0,
        MainLargest::Order if n > 1 => 1.0 - (1.0 - f.smallest) * i as f64 / (n - 1) as f64,
        MainLargest::Order => 1.0,
        MainLargest::Depth => f.smallest.powi(depth.max(0)),
    }
}

/// Flowers and leaves of a grown tree of `set`. `None` when the set has
/// neither.
pub(crate) fn tree_flora(
    set: &TreeSetSpec,
    tree: &GrownTree<'_>,
    cx: &mut Context<'_>,
) -> Result<Option<TreeFlora>> {
    let GrownTree {
        skeleton,
        index: k,
        id: tree_id,
        scale,
    } = *tree;
    if set.flowers.is_none() && set.leaves.is_empty() {
        return Ok(None);
    }
    let assign = set.flowers.as_ref().map_or(Assign::Type1, |f| f.assign);
    let mut leaves = Group::new(format!("{tree_id}.leaves"));
    let mut flowers = Group::new(format!("{tree_id}.flowers"));

    if let Some(j) = &set.leaves.joints {
        let motif = leaf_motif(&j.motifs, assign, k);
        let joints = skeleton.limbs.iter().filter(|l| l.parent.is_some());
        for (n, limb) in joints.enumerate() {
            let id = format!("{tree_id}.joint-{n}");
            let a = cx.adjust().take(&id);
            if a.is_some_and(|a| a.hide) {
                continue;
            }
            let base = limb.points[0];
            let along = limb.points[1] - base;
            if along.hypot() == 0.0 {
                continue;
            }
            let dir = along / along.hypot();
            let lean = match limb.side {
                Some(Side::Left) => -j.angle,
                Some(Side::Right) => j.angle,
                None => 0.0,
            };
            let mut rng = cx.stream(&id);
            let item = Put {
                id,
                motif,
                adjust: a,
                paint: &j.paint,
            };
            put(&mut leaves, item, cx, &mut rng, |d| {
                about(a, base)
                    * Affine::translate(base.to_vec2())
                    * Affine::rotate(angle_from_up(dir) + lean.to_radians())
                    * sized(d, j.width * scale, j.height.map(|h| h * scale))
            })?;
        }
    }

    let Some(f) = &set.flowers else {
        return Ok(Some(TreeFlora { leaves, flowers }));
    };
    let sites = flower_sites(skeleton, f.at);
    for (i, site) in sites.iter().enumerate() {
        let id = format!("{tree_id}.flower-{i}");
        let a = cx.adjust().take(&id);
        let hidden = a.is_some_and(|a| a.hide);
        let factor = scale * size_factor(f, i, sites.len(), cx.depth());
        let mut rng = cx.stream(&id);
        let turn = rng.symmetric(f.turn).to_radians();
        let flower_map = about(a, *site) * Affine::translate(site.to_vec2()) * Affine::rotate(turn);

        if let Some(ring) = &set.leaves.ring {
            let motif = leaf_motif(&ring.motifs, assign, k);
            for j in 0..ring.count {
                let leaf_id = format!("{id}.leaf-{j}");
                let la = cx.adjust().take(&leaf_id);
                if hidden || la.is_some_and(|a| a.hide) {
                    continue;
                }
                let theta = (360.0 * f64::from(j) / f64::from(ring.count)).to_radians();
                let out = Vec2::new(theta.sin(), -theta.cos());
                let stem = flower_map * (out * ring.spacing * factor).to_point();
                let mut leaf_rng = cx.stream(&leaf_id);
                let item = Put {
                    id: leaf_id,
                    motif,
                    adjust: la,
                    paint: &ring.paint,
                };
                put(&mut leaves, item, cx, &mut leaf_rng, |d| {
                    about(la, stem)
                        * flower_map
                        * Affine::translate(out * ring.spacing * factor)
                        * Affine::rotate(theta)
                        * sized(d, ring.width * factor, ring.height.map(|h| h * factor))
                })?;
            }
        }

        if hidden {
            continue;
        }
        let item = Put {
            id,
            motif: assigned(&f.motifs, f.assign, i, k),
            adjust: a,
            paint: &f.paint,
        };
        put(&mut flowers, item, cx, &mut rng, |d| {
            flower_map * sized(d, f.width * factor, f.height.map(|h| h * factor))
        })?;
    }
    Ok(Some(TreeFlora { leaves, flowers }))
}
