//! The stem as a closed tube mesh (thesis §3.3.2, eq. 3.4/3.5).

use std::f64::consts::TAU;

use glam::{DQuat, DVec3};

/// A tube of `radius` swept along `points`: a ring of `sides` vertices
/// (at least 3) round each point, at right angles to the axis, joined by
/// two triangles per side between consecutive rings, and closed by a fan
/// at each end about an extra centre vertex. Returns the vertices and the
/// triangles (indices into them, counter-clockwise seen from outside):
/// `points.len()·sides + 2` vertices and `2·sides·(points.len() − 1) +
/// 2·sides` triangles; nothing for fewer than two points.
///
/// Unlike the thesis' frames from rotations about x and z (eq. 3.5), the
/// rings' frames are carried along the axis by parallel transport (each
/// turned by the smallest rotation from one tangent to the next), so the
/// rings neither twist nor flip where the stem turns past the horizontal.
pub fn tube(points: &[DVec3], radius: f64, sides: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let n = points.len();
    if n < 2 {
        return (Vec::new(), Vec::new());
    }
    let sides = sides.max(3) as usize;
    let mut tangents = Vec::with_capacity(n);
    let mut last = DVec3::Y;
    for i in 0..n {
        let a = points[i.saturating_sub(1)];
        let b = points[(i + 1).min(n - 1)];
        // A repeated point keeps the previous direction.
        last = (b - a).try_normalize().unwrap_or(last);
        tangents.push(last);
    }
    let mut vertices = Vec::with_capacity(n * sides + 2);
    let mut normal = tangents[0].any_orthonormal_vector();
    for i in 0..n {
        let t = tangents[i];
        if i > 0 {
            normal = DQuat::from_rotation_arc(tangents[i - 1], t) * normal;
            // Keep it exactly at right angles despite rounding.
            normal = (normal - t * normal.dot(t))
                .try_normalize()
                .unwrap_or_else(|| t.any_orthonormal_vector());
        }
        let binormal = t.cross(normal);
        for a in 0..sides {
            let phi = TAU * a as f64 / sides as f64;
            vertices.push(points[i] + (normal * phi.cos() + binormal * phi.sin()) * radius);
        }
    }
    let ring = |i: usize, a: usize| (i * sides + a % sides) as u32;
    let mut triangles = Vec::with_capacity(2 * sides * n);
    for i in 0..n - 1 {
        for a in 0..sides {
            let (v00, v01, v10, v11) = (
                ring(i, a),
                ring(i, a + 1),
                ring(i + 1, a),
                ring(i + 1, a + 1),
            );
            triangles.push([v00, v01, v11]);
            triangles.push([v00, v11, v10]);
        }
    }
    let (first, end) = ((n * sides) as u32, (n * sides + 1) as u32);
    vertices.push(points[0]);
    vertices.push(points[n - 1]);
    for a in 0..sides {
        triangles.push([first, ring(0, a + 1), ring(0, a)]);
        triangles.push([end, ring(n - 1, a), ring(n - 1, a + 1)]);
    }
    (vertices, triangles)
}
