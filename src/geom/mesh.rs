//! Triangle meshes: a closed mesh read from a Wavefront OBJ file (a
//! vine's support, loaded with the user's files), and the geometry of one
//! triangle (nearest point, ray crossing).

use std::collections::BTreeMap;

use glam::{DVec2, DVec3};

use crate::error::{Error, Result};

/// A triangle mesh. As a support it must be closed (a solid):
/// see [`TriMesh::check_closed`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions, mm.
    pub vertices: Vec<DVec3>,
    /// Triangles as indices into `vertices`, from 0.
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// Reads the vertices (`v x y z`) and faces (`f a b c …`) of a
    /// Wavefront OBJ text. A face of more than three corners is split into
    /// a fan of triangles; a corner may be written `a/t/n` (only `a` is
    /// read), and a negative index counts back from the last vertex read
    /// so far. Other lines (normals, groups, materials, …) are ignored.
    ///
    /// Errors name `field` and the line: a number that does not read or is
    /// not finite, a face with fewer than three corners, an index out of
    /// range, a file with no faces.
    pub fn parse_obj(text: &str, field: &str) -> Result<TriMesh> {
        let mut vertices = Vec::new();
        // Faces are checked at the end: a positive index may name a vertex
        // that comes later in the file.
        let mut faces: Vec<(usize, Vec<i64>)> = Vec::new();
        let at =
            |line: usize, message: String| Error::invalid(field, format!("line {line}: {message}"));
        for (i, raw) in text.lines().enumerate() {
            let line = i + 1;
            let mut words = raw.split_whitespace();
            match words.next() {
                Some("v") => {
                    let mut xyz = [0.0; 3];
                    for c in &mut xyz {
                        let word = words
                            .next()
                            .ok_or_else(|| at(line, "a vertex needs three coordinates".into()))?;
                        *c = match word.parse::<f64>() {
                            Ok(v) if v.is_finite() => v,
                            _ => {
                                return Err(at(
                                    line,
                                    format!("vertex coordinate '{word}' is not a finite number"),
                                ))
                            }
                        };
                    }
                    vertices.push(DVec3::from_array(xyz));
                }
                Some("f") => {
                    let mut corners = Vec::new();
                    for word in words {
                        let index = word.split('/').next().unwrap_or(word);
                        let n: i64 = index.parse().map_err(|_| {
                            at(line, format!("face index '{word}' is not a whole number"))
                        })?;
                        let resolved = match n {
                            0 => return Err(at(line, "face index 0: OBJ counts from 1".into())),
                            n if n < 0 => {
                                let back = vertices.len() as i64 + n;
                                if back < 0 {
                                    return Err(at(
                                        line,
                                        format!(
                                            "face index {n} but only {} vertices before it",
                                            vertices.len()
                                        ),
                                    ));
                                }
                                back + 1
                            }
                            n => n,
                        };
                        corners.push(resolved);
                    }
                    if corners.len() < 3 {
                        return Err(at(
                            line,
                            format!("a face needs at least 3 corners, got {}", corners.len()),
                        ));
                    }
                    faces.push((line, corners));
                }
                _ => {}
            }
        }
        if faces.is_empty() {
            return Err(Error::invalid(
                field,
                "has no faces (`f` lines): a support mesh must be a closed solid",
            ));
        }
        let count = vertices.len();
        let mut triangles = Vec::new();
        for (line, corners) in faces {
            let mut ids = Vec::with_capacity(corners.len());
            for n in corners {
                if n as usize > count {
                    return Err(at(
                        line,
                        format!("face index {n} but only {count} vertices"),
                    ));
                }
                ids.push((n - 1) as u32);
            }
            for w in 1..ids.len() - 1 {
                triangles.push([ids[0], ids[w], ids[w + 1]]);
            }
        }
        Ok(TriMesh {
            vertices,
            triangles,
        })
    }

    /// Checks that the mesh encloses a solid: every index names a vertex,
    /// and every edge is shared by exactly two triangles. Vertices in the
    /// message are numbered from 1, as in OBJ.
    pub fn check_closed(&self, field: &str) -> Result<()> {
        let count = self.vertices.len();
        if self.triangles.is_empty() {
            return Err(Error::invalid(
                field,
                "has no triangles; a support must be a solid",
            ));
        }
        if let Some(v) = self.vertices.iter().find(|v| !v.is_finite()) {
            return Err(Error::invalid(field, format!("vertex {v} is not finite")));
        }
        let mut edges: BTreeMap<(u32, u32), usize> = BTreeMap::new();
        for (t, tri) in self.triangles.iter().enumerate() {
            if let Some(&i) = tri.iter().find(|&&i| i as usize >= count) {
                return Err(Error::invalid(
                    field,
                    format!(
                        "triangle {} names vertex {} but there are {count}",
                        t + 1,
                        i + 1
                    ),
                ));
            }
            for e in 0..3 {
                let (a, b) = (tri[e], tri[(e + 1) % 3]);
                *edges.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        let mut bad = edges.iter().filter(|(_, &n)| n != 2);
        if let Some((&(a, b), &n)) = bad.next() {
            let others = bad.count();
            let faces = if n == 1 { "face" } else { "faces" };
            let more = match others {
                0 => "the only such edge".to_string(),
                1 => "and 1 more edge like it".to_string(),
                k => format!("and {k} more edges like it"),
            };
            return Err(Error::invalid(
                field,
                format!(
                    "is not a closed mesh: edge {}–{} has {n} {faces} ({more}; vertices \
                     numbered from 1); a support must be a solid",
                    a + 1,
                    b + 1
                ),
            ));
        }
        Ok(())
    }

    /// The mesh scaled about the origin by `scale`, then moved by `offset`.
    pub fn transformed(&self, scale: f64, offset: DVec3) -> TriMesh {
        TriMesh {
            vertices: self.vertices.iter().map(|&v| v * scale + offset).collect(),
            triangles: self.triangles.clone(),
        }
    }
}

/// The point of triangle `abc` nearest to `p` (Ericson, *Real-Time
/// Collision Detection*, 5.1.5: by the Voronoi regions of the corners,
/// edges and face).
pub(crate) fn nearest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// Whether the ray from `p` towards +x crosses triangle `abc`.
///
/// The test is done in the y–z plane with a symbolic perturbation of `p`
/// (by (ε, ε²) in y and z), so a ray through an edge or a corner counts
/// for exactly one of the triangles that share it: the parity of the
/// crossings of a closed mesh then says inside or outside without the
/// rounding cases of a plain test.
pub(crate) fn ray_crosses(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> bool {
    let q = DVec2::new(p.y, p.z);
    let (a2, b2, c2) = (
        DVec2::new(a.y, a.z),
        DVec2::new(b.y, b.z),
        DVec2::new(c.y, c.z),
    );
    let area = (b2 - a2).perp_dot(c2 - a2);
    if area == 0.0 {
        return false;
    }
    let s = [side(b2, c2, q), side(c2, a2, q), side(a2, b2, q)];
    if s.iter().any(|&(sign, _)| sign == 0.0) || !(s[0].0 == s[1].0 && s[1].0 == s[2].0) {
        return false;
    }
    // Barycentric weights give the x where the ray meets the plane.
    let x = (s[0].1 * a.x + s[1].1 * b.x + s[2].1 * c.x) / area;
    x > p.x
}

/// The sign of the turn u→v→q (perturbed as in [`ray_crosses`] when q lies
/// on the line) and the unperturbed signed area.
fn side(u: DVec2, v: DVec2, q: DVec2) -> (f64, f64) {
    let e = v - u;
    let area = e.perp_dot(q - u);
    let sign = if area != 0.0 {
        area.signum()
    } else if e.y != 0.0 {
        // e × (q + (ε, ε²) − u) = −ε·e.y + ε²·e.x: the first term that
        // is not zero decides.
        -e.y.signum()
    } else if e.x != 0.0 {
        e.x.signum()
    } else {
        0.0
    };
    (sign, area)
}
