//! Ramer–Douglas–Peucker: the points of a polyline that keep it within
//! a tolerance of itself. The plot pipeline simplifies strokes with it;
//! the zentangle paradox pattern finds a region's few main corners.

use kurbo::Point;

/// Ramer–Douglas–Peucker: marks in `keep` the points of `pts` to keep (the
/// ends always). Iterative, so long runs cannot overflow the stack.
pub(crate) fn rdp(pts: &[Point], tolerance: f64, keep: &mut Vec<bool>) {
    keep.clear();
    keep.resize(pts.len(), false);
    let last = pts.len() - 1;
    keep[0] = true;
    keep[last] = true;
    let mut stack = vec![(0, last)];
    while let Some((i, j)) = stack.pop() {
        if j <= i + 1 {
            continue;
        }
        let mut far = (0.0, i);
        for (k, &p) in pts.iter().enumerate().take(j).skip(i + 1) {
            // A NaN distance is never "within": such a point is kept.
            let d2 = segment_dist2(pts[i], pts[j], p);
            let d2 = if d2.is_nan() { f64::INFINITY } else { d2 };
            if d2 > far.0 {
                far = (d2, k);
            }
        }
        if far.0 > tolerance * tolerance {
            let k = far.1;
            keep[k] = true;
            stack.push((i, k));
            stack.push((k, j));
        }
    }
}

/// Squared distance from `p` to the segment `a`–`b` (a point when `a ==
/// b`).
fn segment_dist2(a: Point, b: Point, p: Point) -> f64 {
    let ab = b - a;
    let l2 = ab.hypot2();
    if l2 == 0.0 {
        return (p - a).hypot2();
    }
    let t = ((p - a).dot(ab) / l2).clamp(0.0, 1.0);
    (p - (a + ab * t)).hypot2()
}
