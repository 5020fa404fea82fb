//! One line through many points: the travelling-salesman path a stipple
//! drawing is plotted as (StippleGen's "TSP mode"), so the pen goes down
//! once for thousands of sites.
//!
//! A nearest-neighbour tour ([`PointIndex`]) improved by 2-opt restricted
//! to each point's candidate neighbours (the Delaunay neighbours are the
//! classic choice: they hold every point's nearest ones) with a work queue
//! of points whose edges changed ("don't-look bits"), so the cost grows
//! with the number of points times the candidates, not with its square.
//! The tour is improved as a closed loop and then opened at its longest
//! edge, the one a plotter need not draw.

use kurbo::Point;

use super::PointIndex;

/// The order in which to visit `points` (each index once), as an open
/// path; `neighbours[i]` are the candidates 2-opt tries as new neighbours
/// of point `i` (any order, indices into `points`; an empty list leaves
/// the nearest-neighbour tour as it is). Deterministic.
///
/// # Panics
/// When `neighbours` is not as long as `points` or names a point that does
/// not exist.
pub fn tour(points: &[Point], neighbours: &[Vec<u32>]) -> Vec<usize> {
    assert_eq!(points.len(), neighbours.len(), "one neighbour list a point");
    let n = points.len();
    if n < 4 {
        return (0..n).collect();
    }
    let mut loop_ = Loop::new(nearest_neighbour(points));
    // Candidates nearest first, so a search stops at the first one too far
    // away to gain.
    let candidates: Vec<Vec<u32>> = neighbours
        .iter()
        .enumerate()
        .map(|(i, list)| {
            let mut list: Vec<u32> = list.iter().copied().filter(|&c| c as usize != i).collect();
            list.sort_by(|&a, &b| {
                let da = points[i].distance_squared(points[a as usize]);
                let db = points[i].distance_squared(points[b as usize]);
                da.total_cmp(&db).then(a.cmp(&b))
            });
            list.dedup();
            list
        })
        .collect();
    two_opt(points, &candidates, &mut loop_);
    loop_.opened_at_longest_edge(points)
}

/// Length of a path through `points` in `order`.
pub fn tour_length(points: &[Point], order: &[usize]) -> f64 {
    order
        .windows(2)
        .map(|w| points[w[0]].distance(points[w[1]]))
        .sum()
}

/// Greedy tour: from the first point, always on to the nearest point not
/// yet visited.
fn nearest_neighbour(points: &[Point]) -> Vec<usize> {
    let mut index = PointIndex::new(points);
    let mut order = Vec::with_capacity(points.len());
    let mut at = 0u32;
    index.remove(at);
    order.push(0);
    while let Some((next, _)) = index.nearest_within(points[at as usize], f64::INFINITY) {
        index.remove(next);
        order.push(next as usize);
        at = next;
    }
    order
}

/// A closed tour: the order of points and each point's place in it.
struct Loop {
    order: Vec<usize>,
    place: Vec<usize>,
}

impl Loop {
    fn new(order: Vec<usize>) -> Loop {
        let mut place = vec![0; order.len()];
        for (i, &p) in order.iter().enumerate() {
            place[p] = i;
        }
        Loop { order, place }
    }

    fn next(&self, p: usize) -> usize {
        self.order[(self.place[p] + 1) % self.order.len()]
    }

    fn prev(&self, p: usize) -> usize {
        let n = self.order.len();
        self.order[(self.place[p] + n - 1) % n]
    }

    /// Reverses the stretch from `from` to `to` (inclusive, going forward).
    /// Reversing the rest of the loop instead gives the same loop, so the
    /// shorter of the two is turned.
    fn reverse(&mut self, from: usize, to: usize) {
        let n = self.order.len();
        let (mut i, mut j) = (self.place[from], self.place[to]);
        let mut len = (j + n - i) % n + 1;
        if 2 * len > n {
            (i, j) = ((j + 1) % n, (i + n - 1) % n);
            len = n - len;
        }
        for _ in 0..len / 2 {
            self.order.swap(i, j);
            self.place[self.order[i]] = i;
            self.place[self.order[j]] = j;
            i = (i + 1) % n;
            j = (j + n - 1) % n;
        }
    }

    /// The loop as a path that leaves out its longest edge.
    fn opened_at_longest_edge(self, points: &[Point]) -> Vec<usize> {
        let n = self.order.len();
        let edge = |i: usize| points[self.order[i]].distance(points[self.order[(i + 1) % n]]);
        let longest = (0..n)
            .max_by(|&a, &b| edge(a).total_cmp(&edge(b)).then(b.cmp(&a)))
            .unwrap_or(0);
        let start = (longest + 1) % n;
        self.order[start..]
            .iter()
            .chain(&self.order[..start])
            .copied()
            .collect()
    }
}

/// Smallest gain (mm) a 2-opt move must make: rounding noise never loops.
const MIN_GAIN: f64 = 1e-9;

/// 2-opt on the neighbour candidates until no move gains.
fn two_opt(points: &[Point], candidates: &[Vec<u32>], tour: &mut Loop) {
    let d = |a: usize, b: usize| points[a].distance(points[b]);
    let n = points.len();
    let mut queued = vec![true; n];
    let mut queue: std::collections::VecDeque<usize> = (0..n).collect();
    while let Some(a) = queue.pop_front() {
        queued[a] = false;
        let mut changed = None;
        'search: for forward in [true, false] {
            let b = if forward { tour.next(a) } else { tour.prev(a) };
            let ab = d(a, b);
            for &c in &candidates[a] {
                let c = c as usize;
                let ac = d(a, c);
                if ac >= ab {
                    break;
                }
                let e = if forward { tour.next(c) } else { tour.prev(c) };
                if c == b || e == a {
                    continue;
                }
                let gain = ab + d(c, e) - ac - d(b, e);
                if gain > MIN_GAIN {
                    // Forward: a b … c e becomes a c … b e. Backward:
                    // e c … b a becomes e b … c a.
                    if forward {
                        tour.reverse(b, c);
                    } else {
                        tour.reverse(c, b);
                    }
                    changed = Some([a, b, c, e]);
                    break 'search;
                }
            }
        }
        for p in changed.into_iter().flatten() {
            if !queued[p] {
                queued[p] = true;
                queue.push_back(p);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Seed;

    fn random_points(n: usize, seed: u64) -> Vec<Point> {
        let mut rng = Seed(seed).stream();
        (0..n)
            .map(|_| Point::new(rng.range(0.0, 100.0), rng.range(0.0, 100.0)))
            .collect()
    }

    /// The k nearest other points of each, by brute force.
    fn nearest(points: &[Point], k: usize) -> Vec<Vec<u32>> {
        points
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let mut others: Vec<u32> = (0..points.len() as u32)
                    .filter(|&j| j as usize != i)
                    .collect();
                others.sort_by(|&a, &b| {
                    p.distance_squared(points[a as usize])
                        .total_cmp(&p.distance_squared(points[b as usize]))
                });
                others.truncate(k);
                others
            })
            .collect()
    }

    fn is_permutation(order: &[usize], n: usize) -> bool {
        let mut seen = vec![false; n];
        order.len() == n
            && order
                .iter()
                .all(|&i| !std::mem::replace(&mut seen[i], true))
    }

    fn segments_cross(a: Point, b: Point, c: Point, d: Point) -> bool {
        let side = |p: Point, q: Point, r: Point| (q - p).cross(r - p);
        let (d1, d2) = (side(a, b, c), side(a, b, d));
        let (d3, d4) = (side(c, d, a), side(c, d, b));
        d1 * d2 < 0.0 && d3 * d4 < 0.0
    }

    #[test]
    fn every_point_is_visited_once() {
        for n in [0, 1, 2, 3, 4, 5, 50, 500] {
            let pts = random_points(n, n as u64);
            let order = tour(&pts, &nearest(&pts, 8));
            assert!(is_permutation(&order, n), "n = {n}");
        }
    }

    #[test]
    fn two_opt_shortens_the_greedy_tour_and_untangles_it() {
        let pts = random_points(400, 7);
        let greedy = nearest_neighbour(&pts);
        let order = tour(&pts, &nearest(&pts, 10));
        let (g, t) = (tour_length(&pts, &greedy), tour_length(&pts, &order));
        // Greedy tours are typically 25 % above optimal, 2-opt about 5 %.
        assert!(t < 0.92 * g, "2-opt {t:.1} mm, greedy {g:.1} mm");
        // A 2-opt optimum has no two crossing edges among neighbours; with
        // candidate lists a rare crossing of far edges may stay.
        let mut crossings = 0;
        for i in 0..order.len() - 1 {
            for j in i + 2..order.len() - 1 {
                let (a, b) = (pts[order[i]], pts[order[i + 1]]);
                let (c, d) = (pts[order[j]], pts[order[j + 1]]);
                crossings += usize::from(segments_cross(a, b, c, d));
            }
        }
        assert!(crossings <= 2, "{crossings} crossings");
    }

    #[test]
    fn points_on_a_circle_are_visited_in_circle_order() {
        let n = 60;
        // Shuffled order of points on a circle.
        let pts: Vec<Point> = (0..n)
            .map(|i| {
                let k = (i * 37) % n;
                let a = k as f64 / n as f64 * std::f64::consts::TAU;
                Point::new(50.0 + 40.0 * a.cos(), 50.0 + 40.0 * a.sin())
            })
            .collect();
        let order = tour(&pts, &nearest(&pts, 6));
        let chord = pts[0].distance(pts[(0..n).find(|&i| (i * 37) % n == 1).unwrap()]);
        // Each step goes to a neighbour on the circle.
        for w in order.windows(2) {
            let step = pts[w[0]].distance(pts[w[1]]);
            assert!((step - chord).abs() < 1e-9, "step {step} vs chord {chord}");
        }
    }

    #[test]
    fn the_same_points_give_the_same_tour() {
        let pts = random_points(300, 3);
        let nb = nearest(&pts, 8);
        assert_eq!(tour(&pts, &nb), tour(&pts, &nb));
    }

    #[test]
    fn coincident_points_are_all_visited() {
        let mut pts = random_points(50, 1);
        pts.extend(pts.clone());
        let order = tour(&pts, &nearest(&pts, 8));
        assert!(is_permutation(&order, 100));
    }
}
