//! Supports: the solids a vine twines round, their ready-made shapes
//! (cross, T, fence), and distance queries through an R-tree.

use glam::DVec3;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{RTree, AABB};

use crate::geom::mesh::{nearest_on_triangle, ray_crosses, TriMesh};

/// One solid support.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A cylinder from `base` to `top` (any direction) with flat caps.
    Pole {
        /// The centre of one cap.
        base: DVec3,
        /// The centre of the other cap.
        top: DVec3,
        /// Radius, mm.
        radius: f64,
    },
    /// An axis-aligned box.
    Block {
        /// The corner with the smallest coordinates.
        min: DVec3,
        /// The corner with the largest coordinates.
        max: DVec3,
    },
    /// A closed triangle mesh, the solid it encloses (see
    /// [`TriMesh::check_closed`]).
    Mesh(TriMesh),
}

/// A cross: a vertical pole of `height` standing on `centre_base`, and a
/// bar along x of total length `arm_span`, centred on the pole at
/// `arm_height` above its base; both of `radius`.
pub fn cross(
    centre_base: DVec3,
    height: f64,
    arm_height: f64,
    arm_span: f64,
    radius: f64,
) -> Vec<Shape> {
    let arm = centre_base + DVec3::Y * arm_height;
    let half = DVec3::X * (arm_span / 2.0);
    vec![
        Shape::Pole {
            base: centre_base,
            top: centre_base + DVec3::Y * height,
            radius,
        },
        Shape::Pole {
            base: arm - half,
            top: arm + half,
            radius,
        },
    ]
}

/// A T: a vertical pole of `height` standing on `base`, and a bar along x
/// of total length `span` centred on its top; both of `radius`.
pub fn tee(base: DVec3, height: f64, span: f64, radius: f64) -> Vec<Shape> {
    cross(base, height, height, span, radius)
}

/// A lattice fence in the x–y plane at z = `base.z`, from `base` along +x
/// for `width` and up for `height`: `posts` vertical poles spaced evenly
/// from one end to the other (a single post stands at the middle), and
/// `rails` horizontal bars the whole width, spaced evenly up to the top
/// (the top rail at `height`, none at the ground); all of `radius`.
pub fn fence(
    base: DVec3,
    width: f64,
    height: f64,
    posts: u32,
    rails: u32,
    radius: f64,
) -> Vec<Shape> {
    let post_x = |i: u32| {
        if posts <= 1 {
            width / 2.0
        } else {
            width * f64::from(i) / f64::from(posts - 1)
        }
    };
    let mut shapes: Vec<Shape> = (0..posts)
        .map(|i| {
            let foot = base + DVec3::X * post_x(i);
            Shape::Pole {
                base: foot,
                top: foot + DVec3::Y * height,
                radius,
            }
        })
        .collect();
    shapes.extend((1..=rails).map(|j| {
        let left = base + DVec3::Y * (height * f64::from(j) / f64::from(rails));
        Shape::Pole {
            base: left,
            top: left + DVec3::X * width,
            radius,
        }
    }));
    shapes
}

/// One entry of the R-tree: a whole pole or block, or one triangle of a
/// mesh (with the mesh's index among the meshes).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Part {
    Pole {
        base: DVec3,
        top: DVec3,
        radius: f64,
    },
    Block {
        min: DVec3,
        max: DVec3,
    },
    Triangle {
        corners: [DVec3; 3],
        mesh: usize,
    },
}

type Entry = GeomWithData<Rectangle<[f64; 3]>, Part>;

/// The surface point of a support nearest to a query point.
struct Nearest {
    /// Distance to the surface (≥ 0).
    distance: f64,
    /// The query point is inside a support.
    inside: bool,
    /// The nearest surface point.
    point: DVec3,
    /// The outward normal there (used when the query point is on it).
    normal: DVec3,
}

/// The supports of a vine with a spatial index, for the nearest-surface
/// queries of the simulation.
///
/// The R-tree holds the bounding box of every pole and block, and of each
/// triangle of a mesh separately, so a query near a large mesh looks at a
/// few triangles only.
#[derive(Debug, Clone)]
pub struct Supports {
    shapes: Vec<Shape>,
    tree: RTree<Entry>,
    /// The bounding box of each mesh: its inside test runs only within it.
    mesh_boxes: Vec<(DVec3, DVec3)>,
}

impl Supports {
    /// Indexes `shapes`. A block's corners may be given in any order; a
    /// mesh should have passed [`TriMesh::check_closed`] (triangles that
    /// name a missing vertex are left out).
    pub fn new(shapes: Vec<Shape>) -> Supports {
        let mut entries = Vec::new();
        let mut mesh_boxes = Vec::new();
        let mut shapes = shapes;
        for shape in &mut shapes {
            match shape {
                Shape::Pole { base, top, radius } => {
                    *radius = radius.abs();
                    let (base, top, radius) = (*base, *top, *radius);
                    let pad = DVec3::splat(radius);
                    let part = Part::Pole { base, top, radius };
                    entries.push(entry(base.min(top) - pad, base.max(top) + pad, part));
                }
                Shape::Block { min, max } => {
                    (*min, *max) = (min.min(*max), min.max(*max));
                    let part = Part::Block {
                        min: *min,
                        max: *max,
                    };
                    entries.push(entry(*min, *max, part));
                }
                Shape::Mesh(mesh) => {
                    let n = mesh.vertices.len();
                    mesh.triangles
                        .retain(|t| t.iter().all(|&v| (v as usize) < n));
                    if mesh.triangles.is_empty() {
                        continue;
                    }
                    let id = mesh_boxes.len();
                    let mut lo = DVec3::INFINITY;
                    let mut hi = DVec3::NEG_INFINITY;
                    for tri in &mesh.triangles {
                        let corners = tri.map(|v| mesh.vertices[v as usize]);
                        let [a, b, c] = corners;
                        let (tlo, thi) = (a.min(b).min(c), a.max(b).max(c));
                        lo = lo.min(tlo);
                        hi = hi.max(thi);
                        entries.push(entry(tlo, thi, Part::Triangle { corners, mesh: id }));
                    }
                    mesh_boxes.push((lo, hi));
                }
            }
        }
        Supports {
            shapes,
            tree: RTree::bulk_load(entries),
            mesh_boxes,
        }
    }

    /// The shapes, as given (blocks with ordered corners).
    pub fn shapes(&self) -> &[Shape] {
        &self.shapes
    }

    /// The distance from `p` to the nearest support surface, mm: positive
    /// outside every support, negative (or 0) inside one, infinite when
    /// there are no supports.
    pub fn distance(&self, p: DVec3) -> f64 {
        match self.nearest(p) {
            None => f64::INFINITY,
            Some(n) if n.inside => -n.distance,
            Some(n) => n.distance,
        }
    }

    /// The unit direction from the nearest surface point towards `p`
    /// (outwards, also when `p` is inside: then away from `p`); the
    /// surface's normal when `p` is on it. `None` without supports.
    pub fn outward(&self, p: DVec3) -> Option<DVec3> {
        let n = self.nearest(p)?;
        let away = p - n.point;
        Some(if n.distance > 1e-12 {
            if n.inside {
                -away / n.distance
            } else {
                away / n.distance
            }
        } else {
            n.normal
        })
    }

    fn nearest(&self, p: DVec3) -> Option<Nearest> {
        let mut best: Option<Nearest> = None;
        let mut inside = false;
        // Entries come in order of the distance to their boxes, a lower
        // bound of the distance to what they hold: stop once it passes the
        // best surface distance found. Every solid that holds p has a box
        // at distance 0, so it is met before the loop stops.
        for (e, box_d2) in self
            .tree
            .nearest_neighbor_iter_with_distance_2(&p.to_array())
        {
            if best
                .as_ref()
                .is_some_and(|b| box_d2 > b.distance * b.distance)
            {
                break;
            }
            let (point, normal, holds) = match e.data {
                Part::Pole { base, top, radius } => nearest_on_pole(p, base, top, radius),
                Part::Block { min, max } => nearest_on_block(p, min, max),
                Part::Triangle {
                    corners: [a, b, c], ..
                } => {
                    let q = nearest_on_triangle(p, a, b, c);
                    (q, (b - a).cross(c - a).normalize_or(DVec3::Y), false)
                }
            };
            inside |= holds;
            let distance = p.distance(point);
            if best.as_ref().is_none_or(|b| distance < b.distance) {
                best = Some(Nearest {
                    distance,
                    inside: false,
                    point,
                    normal,
                });
            }
        }
        let mut best = best?;
        best.inside = inside || self.inside_mesh(p);
        Some(best)
    }

    /// Whether `p` is inside one of the meshes: an odd number of its
    /// triangles cross the ray from `p` towards +x.
    fn inside_mesh(&self, p: DVec3) -> bool {
        self.mesh_boxes.iter().enumerate().any(|(id, &(lo, hi))| {
            if p.cmplt(lo).any() || p.cmpgt(hi).any() {
                return false;
            }
            let ray = AABB::from_corners(p.to_array(), [hi.x, p.y, p.z]);
            let crossings = self
                .tree
                .locate_in_envelope_intersecting(&ray)
                .filter(|e| match e.data {
                    Part::Triangle {
                        corners: [a, b, c],
                        mesh,
                    } => mesh == id && ray_crosses(p, a, b, c),
                    _ => false,
                })
                .count();
            crossings % 2 == 1
        })
    }
}

fn entry(lo: DVec3, hi: DVec3, part: Part) -> Entry {
    GeomWithData::new(Rectangle::from_corners(lo.to_array(), hi.to_array()), part)
}

/// The nearest surface point of a capped cylinder, its outward normal, and
/// whether `p` is inside.
fn nearest_on_pole(p: DVec3, base: DVec3, top: DVec3, radius: f64) -> (DVec3, DVec3, bool) {
    let axis = top - base;
    let length = axis.length();
    // A pole of no length is a flat disc facing up.
    let u = if length > 0.0 {
        axis / length
    } else {
        DVec3::Y
    };
    let t = (p - base).dot(u);
    let radial = p - base - u * t;
    let rho = radial.length();
    let out = if rho > 1e-12 {
        radial / rho
    } else {
        u.any_orthonormal_vector()
    };
    let (cap_t, cap_normal) = if t < length / 2.0 {
        (0.0, -u)
    } else {
        (length, u)
    };
    let inside = rho < radius && t > 0.0 && t < length;
    if inside {
        // To the side or to the nearer cap, whichever is closer.
        if radius - rho < (t - cap_t).abs() {
            (base + u * t + out * radius, out, true)
        } else {
            (base + u * cap_t + radial, cap_normal, true)
        }
    } else {
        let tc = t.clamp(0.0, length);
        let point = base + u * tc + out * rho.min(radius);
        let normal = if rho > radius { out } else { cap_normal };
        (point, normal, false)
    }
}

/// The nearest surface point of an axis-aligned box, its outward normal,
/// and whether `p` is inside.
fn nearest_on_block(p: DVec3, min: DVec3, max: DVec3) -> (DVec3, DVec3, bool) {
    let inside = p.cmpgt(min).all() && p.cmplt(max).all();
    if inside {
        // Out through the nearest face.
        let mut best = (f64::INFINITY, p, DVec3::ZERO);
        for axis in 0..3 {
            for (face, sign) in [(min[axis], -1.0), (max[axis], 1.0)] {
                let d = (p[axis] - face).abs();
                if d < best.0 {
                    let mut q = p;
                    q[axis] = face;
                    let mut n = DVec3::ZERO;
                    n[axis] = sign;
                    best = (d, q, n);
                }
            }
        }
        (best.1, best.2, true)
    } else {
        let q = p.clamp(min, max);
        let away = p - q;
        let normal = if away.length_squared() > 0.0 {
            away.normalize()
        } else {
            // On a face: the axis where p sits at a bound.
            let mut n = DVec3::Y;
            for axis in 0..3 {
                if p[axis] <= min[axis] {
                    n = DVec3::ZERO;
                    n[axis] = -1.0;
                } else if p[axis] >= max[axis] {
                    n = DVec3::ZERO;
                    n[axis] = 1.0;
                }
            }
            n
        };
        (q, normal, false)
    }
}
