//! Triangles covering a polygon, by ear clipping: how a flat shape (a
//! leaf's outline) becomes faces that can hide what lies behind it.
//!
//! O(n²) in the ring's points, which stay in the hundreds for a motif. A
//! ring that is not simple (it crosses itself) still gives triangles and
//! never loops: when no ear is left, the rest is fanned from its first
//! point.

use kurbo::Point;

/// Triangles (indices into `ring`) covering the polygon `ring` (closed
/// implicitly, either winding).
pub(super) fn ear_clip(ring: &[Point]) -> Vec<[usize; 3]> {
    let n = ring.len();
    if n < 3 {
        return Vec::new();
    }
    let area2: f64 = (0..n)
        .map(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % n]);
            a.x * b.y - b.x * a.y
        })
        .sum();
    let sign = if area2 < 0.0 { -1.0 } else { 1.0 };
    let mut left: Vec<usize> = (0..n).collect();
    let mut triangles = Vec::with_capacity(n - 2);
    while left.len() > 3 {
        let m = left.len();
        let ear = (0..m).find(|&i| {
            let (a, b, c) = (left[(i + m - 1) % m], left[i], left[(i + 1) % m]);
            let (pa, pb, pc) = (ring[a], ring[b], ring[c]);
            // Convex at b, and no other point inside the triangle.
            sign * cross(pa, pb, pc) > 0.0
                && left
                    .iter()
                    .all(|&k| k == a || k == b || k == c || !inside(ring[k], pa, pb, pc, sign))
        });
        let Some(i) = ear else { break };
        triangles.push([left[(i + m - 1) % m], left[i], left[(i + 1) % m]]);
        left.remove(i);
    }
    for k in 1..left.len().saturating_sub(1) {
        triangles.push([left[0], left[k], left[k + 1]]);
    }
    triangles
}

fn cross(a: Point, b: Point, c: Point) -> f64 {
    (b - a).cross(c - b)
}

/// Whether `p` lies inside or on the triangle `a b c` wound by `sign`.
fn inside(p: Point, a: Point, b: Point, c: Point, sign: f64) -> bool {
    sign * (b - a).cross(p - a) >= 0.0
        && sign * (c - b).cross(p - b) >= 0.0
        && sign * (a - c).cross(p - c) >= 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(ring: &[Point], t: &[[usize; 3]]) -> f64 {
        t.iter()
            .map(|&[a, b, c]| 0.5 * (ring[b] - ring[a]).cross(ring[c] - ring[a]).abs())
            .sum()
    }

    #[test]
    fn a_concave_polygon_is_covered_exactly() {
        // An L of area 3, both windings.
        let mut l = vec![
            Point::new(0.0, 0.0),
            Point::new(2.0, 0.0),
            Point::new(2.0, 1.0),
            Point::new(1.0, 1.0),
            Point::new(1.0, 2.0),
            Point::new(0.0, 2.0),
        ];
        for _ in 0..2 {
            let t = ear_clip(&l);
            assert_eq!(t.len(), 4);
            assert!((area(&l, &t) - 3.0).abs() < 1e-12);
            l.reverse();
        }
    }

    #[test]
    fn a_ring_that_crosses_itself_ends() {
        let bow = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(1.0, 0.0),
            Point::new(0.0, 1.0),
        ];
        assert_eq!(ear_clip(&bow).len(), 2);
        assert!(ear_clip(&bow[..2]).is_empty());
    }
}
