//! A spatial index of points for "which point is nearest, among those not
//! taken yet": the question greedy path ordering ([`crate::plot::sort`])
//! asks of path ends once per path, and line merging
//! ([`crate::plot::merge`]) once per join.
//!
//! Both remove points as they go (a path drawn, an end joined), so the
//! index supports deletion and its queries skip what is gone; it never
//! inserts. Answers are exact (squared Euclidean distances in `f64`) and
//! deterministic: ties go to the lower index, whatever the tree's shape.

use std::cmp::Ordering;

use kurbo::Point;

/// A static 2-d tree over points with deletion, for nearest-neighbour
/// queries on a shrinking set. Points are identified by their index in the
/// slice given to [`PointIndex::new`].
///
/// A complete binary tree in arrays (node 1 is the root, the children of
/// node `k` are `2k` and `2k + 1`), built by median splits on the wider
/// side of each box, so every leaf holds at most `LEAF` points and the
/// range of slots under a node follows from its position. Per node only a
/// box (in `f32`, rounded outwards) and a count of points not removed are
/// stored: 20 bytes, so the upper levels stay in cache. Built in
/// O(n log n); a removal is O(log n); a query skips subtrees whose points
/// are all removed. Ties are broken towards the lower index, so answers do
/// not depend on the tree's shape. Points with a coordinate that is not
/// finite are never found.
pub struct PointIndex {
    /// Points in tree order; a removed point becomes NaN, which no
    /// distance comparison accepts.
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// The caller's index of each slot.
    ids: Vec<u32>,
    /// Caller's index → slot.
    slot_of: Vec<u32>,
    /// Node boxes `[min x, min y, max x, max y]`; index 0 is unused.
    boxes: Vec<[f32; 4]>,
    /// Points below each node not removed yet.
    alive: Vec<u32>,
    /// Depth of the leaves (the root has depth 0).
    depth: u32,
    /// Reused by queries: (node, first slot, end slot, squared distance).
    stack: Vec<(u32, u32, u32, f64)>,
}

/// Points per leaf, at most.
const LEAF: usize = 24;

/// The largest `f32` not above `x`.
fn f32_down(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) <= x || f.is_nan() || f == f32::NEG_INFINITY {
        f
    } else if f == 0.0 {
        -f32::from_bits(1)
    } else if f > 0.0 {
        f32::from_bits(f.to_bits() - 1)
    } else {
        f32::from_bits(f.to_bits() + 1)
    }
}

/// The smallest `f32` not below `x`.
fn f32_up(x: f64) -> f32 {
    -f32_down(-x)
}

/// Squared distance from `(x, y)` to a box (infinite for an empty box).
#[inline]
fn box_dist2(b: &[f32; 4], x: f64, y: f64) -> f64 {
    let dx = (f64::from(b[0]) - x).max(x - f64::from(b[2])).max(0.0);
    let dy = (f64::from(b[1]) - y).max(y - f64::from(b[3])).max(0.0);
    dx * dx + dy * dy
}

/// Where a node's range splits between its children.
#[inline]
fn split(lo: u32, hi: u32) -> u32 {
    lo + (hi - lo) / 2
}

impl PointIndex {
    /// An index over `points`, all present (but those with a coordinate
    /// that is not finite).
    ///
    /// # Panics
    /// With more than `u32::MAX / 2` points.
    pub fn new(points: &[Point]) -> PointIndex {
        let n = points.len();
        assert!(n < u32::MAX as usize / 2, "too many points for the index");
        let mut depth = 0u32;
        while n.div_ceil(1 << depth) > LEAF {
            depth += 1;
        }
        let nodes = 2usize << depth;
        let first_leaf = 1usize << depth;
        let mut boxes = vec![
            [
                f32::INFINITY,
                f32::INFINITY,
                f32::NEG_INFINITY,
                f32::NEG_INFINITY
            ];
            nodes
        ];
        let mut alive = vec![0u32; nodes];
        let mut ranges = vec![(0u32, 0u32); nodes];
        // Points that are not finite are put in a far corner to keep the
        // splits' ordering total, and removed below.
        let finite = |p: &Point| p.x.is_finite() && p.y.is_finite();
        let far = Point::new(f64::MAX, f64::MAX);
        let mut entries: Vec<(Point, u32)> = points
            .iter()
            .map(|p| if finite(p) { *p } else { far })
            .zip(0u32..)
            .collect();
        ranges[1] = (0, n as u32);
        // Top-down, level by level: each node's box, then its split.
        for k in 1..nodes {
            let (lo, hi) = ranges[k];
            let slice = &mut entries[lo as usize..hi as usize];
            alive[k] = hi - lo;
            let (mut x0, mut y0, mut x1, mut y1) = (
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            );
            for (p, _) in slice.iter() {
                x0 = x0.min(p.x);
                y0 = y0.min(p.y);
                x1 = x1.max(p.x);
                y1 = y1.max(p.y);
            }
            boxes[k] = [f32_down(x0), f32_down(y0), f32_up(x1), f32_up(y1)];
            if k >= first_leaf {
                continue;
            }
            let split_x = x1 - x0 >= y1 - y0;
            let m = split(lo, hi);
            // Coordinates are finite here (see `entries`), so `<` orders
            // them totally.
            let by = |a: f64, b: f64| {
                if a < b {
                    Ordering::Less
                } else if a > b {
                    Ordering::Greater
                } else {
                    Ordering::Equal
                }
            };
            let nth = (m - lo) as usize;
            if m > lo && split_x {
                slice.select_nth_unstable_by(nth, |p, q| by(p.0.x, q.0.x));
            } else if m > lo {
                slice.select_nth_unstable_by(nth, |p, q| by(p.0.y, q.0.y));
            }
            ranges[2 * k] = (lo, m);
            ranges[2 * k + 1] = (m, hi);
        }
        let mut slot_of = vec![0u32; n];
        for (slot, (_, id)) in entries.iter().enumerate() {
            slot_of[*id as usize] = slot as u32;
        }
        let mut index = PointIndex {
            xs: entries.iter().map(|e| e.0.x).collect(),
            ys: entries.iter().map(|e| e.0.y).collect(),
            ids: entries.iter().map(|e| e.1).collect(),
            slot_of,
            boxes,
            alive,
            depth,
            stack: Vec::new(),
        };
        // A point that is not finite is removed from the start.
        for (id, p) in points.iter().enumerate() {
            if !finite(p) {
                index.remove(id as u32);
            }
        }
        index
    }

    /// Removes point `id`; removing it again does nothing.
    pub fn remove(&mut self, id: u32) {
        let slot = self.slot_of[id as usize];
        let s = slot as usize;
        if self.xs[s].is_nan() && self.ys[s].is_nan() {
            return;
        }
        self.xs[s] = f64::NAN;
        self.ys[s] = f64::NAN;
        // Walk down from the root to the slot's leaf.
        let (mut k, mut lo, mut hi) = (1usize, 0u32, self.xs.len() as u32);
        for _ in 0..self.depth {
            self.alive[k] -= 1;
            let m = split(lo, hi);
            if slot < m {
                k *= 2;
                hi = m;
            } else {
                k = 2 * k + 1;
                lo = m;
            }
        }
        self.alive[k] -= 1;
    }

    /// The present point nearest to `p` within squared distance `max_d2`
    /// (inclusive), with its squared distance; ties go to the lower index.
    pub fn nearest_within(&mut self, p: Point, max_d2: f64) -> Option<(u32, f64)> {
        let (x, y) = (p.x, p.y);
        let mut best_d2 = max_d2;
        let mut best = u32::MAX;
        if self.alive[1] == 0 {
            return None;
        }
        let first_leaf = 1usize << self.depth;
        self.stack.clear();
        self.stack
            .push((1, 0, self.xs.len() as u32, box_dist2(&self.boxes[1], x, y)));
        while let Some((k, lo, hi, d2)) = self.stack.pop() {
            if d2 > best_d2 {
                continue;
            }
            let k = k as usize;
            if k >= first_leaf {
                for slot in lo as usize..hi as usize {
                    let dx = self.xs[slot] - x;
                    let dy = self.ys[slot] - y;
                    let d2 = dx * dx + dy * dy;
                    if d2 <= best_d2 && (d2 < best_d2 || self.ids[slot] < best) {
                        best_d2 = d2;
                        best = self.ids[slot];
                    }
                }
                continue;
            }
            // A child is worth a visit when it has points left, closer
            // than the best so far; the nearer one is popped first.
            let m = split(lo, hi);
            let (l, r) = (2 * k, 2 * k + 1);
            let near = |c: usize| {
                (self.alive[c] > 0)
                    .then(|| box_dist2(&self.boxes[c], x, y))
                    .filter(|d| *d <= best_d2)
            };
            match (near(l), near(r)) {
                (Some(dl), Some(dr)) => {
                    let left = (l as u32, lo, m, dl);
                    let right = (r as u32, m, hi, dr);
                    if dl <= dr {
                        self.stack.push(right);
                        self.stack.push(left);
                    } else {
                        self.stack.push(left);
                        self.stack.push(right);
                    }
                }
                (Some(d), None) => self.stack.push((l as u32, lo, m, d)),
                (None, Some(d)) => self.stack.push((r as u32, m, hi, d)),
                (None, None) => {}
            }
        }
        (best != u32::MAX).then_some((best, best_d2))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn point() -> impl Strategy<Value = (f64, f64)> {
        (0i32..200, 0i32..200).prop_map(|(x, y)| (x as f64 * 0.5, y as f64 * 0.5))
    }

    #[test]
    fn ties_go_to_the_lower_index_and_removed_points_are_gone() {
        let pts: Vec<Point> = (0..100)
            .map(|i| Point::new(f64::from(i % 10), f64::from(i / 10)))
            .chain([Point::new(5.0, 5.0), Point::new(5.0, 5.0)])
            .collect();
        let mut index = PointIndex::new(&pts);
        assert_eq!(
            index.nearest_within(Point::new(5.0, 5.0), 0.0),
            Some((55, 0.0))
        );
        index.remove(55);
        assert_eq!(
            index.nearest_within(Point::new(5.0, 5.0), 0.0),
            Some((100, 0.0))
        );
        index.remove(100);
        index.remove(100);
        assert_eq!(
            index.nearest_within(Point::new(5.0, 5.0), 0.0),
            Some((101, 0.0))
        );
        index.remove(101);
        // Four neighbours at distance 1: the lowest index, (5, 4).
        assert_eq!(
            index.nearest_within(Point::new(5.0, 5.0), 1.0),
            Some((45, 1.0))
        );
        assert_eq!(index.nearest_within(Point::new(5.0, 5.0), 0.5), None);
        for i in 0..102 {
            index.remove(i);
        }
        assert_eq!(index.nearest_within(Point::ORIGIN, f64::INFINITY), None);
    }

    #[test]
    fn points_that_are_not_finite_are_never_found() {
        let pts = [
            Point::new(f64::NAN, 0.0),
            Point::new(f64::INFINITY, 1.0),
            Point::new(3.0, 4.0),
        ];
        let mut index = PointIndex::new(&pts);
        assert_eq!(
            index.nearest_within(Point::ORIGIN, f64::INFINITY),
            Some((2, 25.0))
        );
        index.remove(2);
        assert_eq!(index.nearest_within(Point::ORIGIN, f64::INFINITY), None);
        assert_eq!(
            PointIndex::new(&[]).nearest_within(Point::ORIGIN, f64::INFINITY),
            None
        );
    }

    proptest! {
        #[test]
        fn index_nearest_matches_brute_force(
            pts in prop::collection::vec(point(), 1..200),
            queries in prop::collection::vec(point(), 1..20),
            removed in prop::collection::vec(any::<prop::sample::Index>(), 0..100),
        ) {
            let pts: Vec<Point> = pts.into_iter().map(Point::from).collect();
            let mut index = PointIndex::new(&pts);
            let mut alive = vec![true; pts.len()];
            for r in removed {
                let i = r.index(pts.len());
                index.remove(i as u32);
                alive[i] = false;
            }
            for q in queries {
                let q = Point::from(q);
                let brute = (0..pts.len())
                    .filter(|&i| alive[i])
                    .map(|i| ((pts[i] - q).hypot2(), i as u32))
                    .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
                let got = index.nearest_within(q, f64::INFINITY).map(|(i, d)| (d, i));
                prop_assert_eq!(got, brute);
                let within = index.nearest_within(q, 4.0).map(|(i, d)| (d, i));
                prop_assert_eq!(within, brute.filter(|b| b.0 <= 4.0));
            }
        }
    }
}
