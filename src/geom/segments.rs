//! Distances between straight segments in 3D: what keeps one stem or
//! branch clear of another (the sketch's trunk, the vine's stems).

use glam::DVec3;

/// The least distance between the segments `p0`–`p1` and `q0`–`q1`.
pub(crate) fn segment_distance_3d(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3) -> f64 {
    let (d1, d2, r) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, e, f) = (d1.length_squared(), d2.length_squared(), d2.dot(r));
    let tiny = 1e-18;
    let (s, t) = if a <= tiny && e <= tiny {
        (0.0, 0.0)
    } else if a <= tiny {
        (0.0, (f / e).clamp(0.0, 1.0))
    } else {
        let c = d1.dot(r);
        if e <= tiny {
            ((-c / a).clamp(0.0, 1.0), 0.0)
        } else {
            let b = d1.dot(d2);
            let denom = a * e - b * b;
            let mut s = if denom > tiny {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let mut t = (b * s + f) / e;
            if t < 0.0 {
                t = 0.0;
                s = (-c / a).clamp(0.0, 1.0);
            } else if t > 1.0 {
                t = 1.0;
                s = ((b - c) / a).clamp(0.0, 1.0);
            }
            (s, t)
        }
    };
    (p0 + d1 * s).distance(q0 + d2 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_distance_is_the_least_distance() {
        let d = |p0: [f64; 3], p1: [f64; 3], q0: [f64; 3], q1: [f64; 3]| {
            segment_distance_3d(
                DVec3::from(p0),
                DVec3::from(p1),
                DVec3::from(q0),
                DVec3::from(q1),
            )
        };
        // Crossing, parallel, end to end, skew in 3D, a point.
        assert!(d([0., 0., 0.], [2., 2., 0.], [0., 2., 0.], [2., 0., 0.]) < 1e-12);
        assert!((d([0., 0., 0.], [4., 0., 0.], [1., 3., 0.], [2., 3., 0.]) - 3.0).abs() < 1e-12);
        assert!((d([0., 0., 0.], [1., 0., 0.], [4., 4., 0.], [9., 4., 0.]) - 5.0).abs() < 1e-12);
        assert!((d([0., 0., 0.], [2., 0., 0.], [1., -1., 2.], [1., 1., 2.]) - 2.0).abs() < 1e-12);
        assert!((d([1., 1., 0.], [1., 1., 0.], [0., 0., 0.], [2., 0., 0.]) - 1.0).abs() < 1e-12);
    }
}
