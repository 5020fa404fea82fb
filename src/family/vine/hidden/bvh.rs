//! A bounding-volume hierarchy over triangles, answering one question:
//! does any triangle cross this stretch of a ray?

use glam::DVec3;

/// Triangles per leaf, at most.
const LEAF: usize = 4;

/// How far past its edges a triangle still stops a ray, as a fraction of
/// its size (in barycentric coordinates): a billionth, so that a ray
/// through the shared edge of two triangles of a mesh hits one of them
/// despite rounding, and no line shows through the seams of a surface.
const SLACK: f64 = 1e-9;

/// How oblique a ray may meet a triangle's plane and still be stopped:
/// below this (relative to the triangle's edges) the ray grazes the
/// plane, where the triangle covers nothing.
const GRAZING: f64 = 1e-12;

/// A triangle, prepared for Möller–Trumbore.
#[derive(Debug, Clone, Copy)]
struct Triangle {
    a: DVec3,
    /// `b − a`.
    e1: DVec3,
    /// `c − a`.
    e2: DVec3,
    /// `GRAZING · |e1| · |e2|`: smaller determinants are rays along the
    /// plane (or a triangle without area).
    flat: f64,
}

impl Triangle {
    fn new([a, b, c]: [DVec3; 3]) -> Triangle {
        let (e1, e2) = (b - a, c - a);
        Triangle {
            a,
            e1,
            e2,
            flat: GRAZING * e1.length() * e2.length(),
        }
    }

    /// Whether the ray `origin + t · direction` meets this triangle (either
    /// side) at some `t` strictly between `t_min` and `t_max`.
    fn hit(&self, origin: DVec3, direction: DVec3, t_min: f64, t_max: f64) -> bool {
        let p = direction.cross(self.e2);
        let det = self.e1.dot(p);
        if det.abs() <= self.flat {
            return false;
        }
        let inv = 1.0 / det;
        let s = origin - self.a;
        let u = s.dot(p) * inv;
        if !(-SLACK..=1.0 + SLACK).contains(&u) {
            return false;
        }
        let q = s.cross(self.e1);
        let v = direction.dot(q) * inv;
        if v < -SLACK || u + v > 1.0 + SLACK {
            return false;
        }
        let t = self.e2.dot(q) * inv;
        t > t_min && t < t_max
    }
}

/// A node: its box and either two children or a run of triangles.
#[derive(Debug, Clone, Copy)]
struct Node {
    lo: DVec3,
    hi: DVec3,
    /// A leaf's first triangle; an inner node's second child (its first
    /// child is the next node).
    index: usize,
    /// A leaf's number of triangles; 0 for an inner node.
    count: usize,
}

/// Triangles in a tree of boxes, split at the median of the longest axis
/// of their centroids, so the tree is balanced: building takes
/// O(n log n), a ray visits O(log n) nodes when the triangles are spread
/// out (more when many of them lie along it).
#[derive(Debug, Clone, Default)]
pub(super) struct Bvh {
    /// Depth first: the root, then its first subtree, then its second.
    nodes: Vec<Node>,
    /// In the order of the leaves.
    triangles: Vec<Triangle>,
}

impl Bvh {
    /// The tree over `triangles`, whose corners must be finite.
    pub(super) fn new(triangles: Vec<[DVec3; 3]>) -> Bvh {
        let mut items: Vec<(DVec3, [DVec3; 3])> = triangles
            .into_iter()
            .map(|t| ((t[0] + t[1] + t[2]) / 3.0, t))
            .collect();
        let mut nodes = Vec::with_capacity(2 * items.len().div_ceil(LEAF));
        if !items.is_empty() {
            build(&mut items, 0, &mut nodes);
        }
        Bvh {
            nodes,
            triangles: items.into_iter().map(|(_, t)| Triangle::new(t)).collect(),
        }
    }

    /// The number of triangles.
    #[cfg(test)]
    pub(super) fn len(&self) -> usize {
        self.triangles.len()
    }

    /// Whether a triangle meets the ray `origin + t · direction` at some
    /// `t` strictly between `t_min` and `t_max`.
    pub(super) fn any_hit(&self, origin: DVec3, direction: DVec3, t_min: f64, t_max: f64) -> bool {
        if self.nodes.is_empty() || t_min >= t_max {
            return false;
        }
        let inverse = direction.recip();
        // Median splits keep the tree balanced whatever the geometry: its
        // depth is log2(n / LEAF) rounded up, and at most depth + 1 nodes
        // are pending, far fewer than 64 for any n that fits in memory.
        let mut stack = [0usize; 64];
        let mut pending = 1;
        while pending > 0 {
            pending -= 1;
            let at = stack[pending];
            let node = &self.nodes[at];
            if !meets_box(node, origin, inverse, t_min, t_max) {
                continue;
            }
            if node.count > 0 {
                let leaf = &self.triangles[node.index..node.index + node.count];
                if leaf.iter().any(|t| t.hit(origin, direction, t_min, t_max)) {
                    return true;
                }
            } else {
                // Depth first: the first child follows its parent.
                stack[pending] = node.index;
                stack[pending + 1] = at + 1;
                pending += 2;
            }
        }
        false
    }

    /// The number of inner nodes on the longest path from the root to a
    /// leaf.
    #[cfg(test)]
    pub(super) fn depth(&self) -> usize {
        fn below(nodes: &[Node], at: usize) -> usize {
            let node = nodes[at];
            if node.count > 0 {
                0
            } else {
                1 + below(nodes, at + 1).max(below(nodes, node.index))
            }
        }
        if self.nodes.is_empty() {
            0
        } else {
            below(&self.nodes, 0)
        }
    }

    /// Every triangle tested one by one: what [`Bvh::any_hit`] must agree
    /// with.
    #[cfg(test)]
    pub(super) fn brute_force(
        &self,
        origin: DVec3,
        direction: DVec3,
        t_min: f64,
        t_max: f64,
    ) -> bool {
        self.triangles
            .iter()
            .any(|t| t.hit(origin, direction, t_min, t_max))
    }
}

/// Appends the subtree over `items` (triangles `first..` in the final
/// order) to `nodes`, depth first.
fn build(items: &mut [(DVec3, [DVec3; 3])], first: usize, nodes: &mut Vec<Node>) {
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    let (mut c_lo, mut c_hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    for (centroid, corners) in items.iter() {
        for &c in corners {
            lo = lo.min(c);
            hi = hi.max(c);
        }
        c_lo = c_lo.min(*centroid);
        c_hi = c_hi.max(*centroid);
    }
    // Rounding in the slab test must not miss a triangle touching its box.
    let pad = 1e-9 * (1.0 + lo.abs().max(hi.abs()).max_element());
    let me = nodes.len();
    nodes.push(Node {
        lo: lo - pad,
        hi: hi + pad,
        index: first,
        count: items.len(),
    });
    if items.len() <= LEAF {
        return;
    }
    let extent = c_hi - c_lo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |a, b| a.0[axis].total_cmp(&b.0[axis]));
    let (left, right) = items.split_at_mut(mid);
    build(left, first, nodes);
    nodes[me].index = nodes.len();
    nodes[me].count = 0;
    build(right, first + mid, nodes);
}

/// Whether the ray meets the box of `node` for some `t` in
/// `[t_min, t_max]` (slab test; `inverse` is 1 / direction).
fn meets_box(node: &Node, origin: DVec3, inverse: DVec3, t_min: f64, t_max: f64) -> bool {
    let (mut near, mut far) = (t_min, t_max);
    for axis in 0..3 {
        let (o, lo, hi) = (origin[axis], node.lo[axis], node.hi[axis]);
        if inverse[axis].is_infinite() {
            // Parallel to this slab: inside it everywhere or nowhere (the
            // products below would be 0 · ∞).
            if o < lo || o > hi {
                return false;
            }
            continue;
        }
        let t1 = (lo - o) * inverse[axis];
        let t2 = (hi - o) * inverse[axis];
        near = near.max(t1.min(t2));
        far = far.min(t1.max(t2));
    }
    near <= far
}
