//! A grown vine as the camera sees it: the 3D lines to draw (stem
//! contours, leaf outlines and veins, support contours and rims), the
//! triangles that may hide them, and the camera.
//!
//! Lines lie *on* the surfaces they belong to; the triangles that hide
//! them are made a hair inside those surfaces (a stem's tube at 97 % of
//! its radius, a support shrunk by [`INSET`]), so no line is hidden by
//! its own surface, while anything truly behind a surface still is.

use glam::DVec3;
use kurbo::{BezPath, PathEl, Point, Rect};

use std::collections::BTreeMap;

use crate::family::vine::camera::Camera;
use crate::family::vine::ears::ear_clip;
use crate::family::vine::engine::{tube, Leaf, Plant, Shape, Supports, TriMesh};
use crate::family::vine::hidden::{tube_silhouette, Occluders};
use crate::motif::Drawing;
use crate::spec::{CameraPreset, CameraSpec, Orbit, Part};

/// How far (mm) a support's hiding triangles lie inside its surface.
const INSET: f64 = 0.05;

/// A hit closer than this (mm, along the ray) to the point looked at does
/// not hide it.
const EPS: f64 = 0.01;

/// Sides of a stem's hiding tube; its contour lines are exact either way.
const TUBE_SIDES: u32 = 12;

/// Sides of a pole's hiding cylinder and points of its rims.
const POLE_SIDES: u32 = 48;

/// Faces of a mesh support meeting at more than this many degrees draw
/// their shared edge.
const CREASE: f64 = 30.0;

/// Flattening tolerance of a leaf motif, in motif units (its box is 1).
const LEAF_FLATNESS: f64 = 0.002;

/// One 3D line of the drawing.
#[derive(Debug, Clone)]
pub(super) struct Line {
    /// What it belongs to.
    pub(super) part: Part,
    /// Which stem, leaf or support.
    pub(super) item: usize,
    /// Its points, mm.
    pub(super) points: Vec<DVec3>,
    /// A loop: its last point joins its first.
    pub(super) closed: bool,
}

/// The vine as the camera sees it.
pub(super) struct Sight {
    camera: Camera,
    occluders: Occluders,
    lines: Vec<Line>,
    /// Closed 3D loops whose pictures together cover the picture of the
    /// stems, leaves, poles and rod (not of boxes or meshes).
    loops: Vec<Vec<DVec3>>,
    /// The stems' smoothed axes, for the 3D export.
    pub(super) axes: Vec<Vec<DVec3>>,
    /// The rod's axis and radius, for the 3D export.
    pub(super) rod: Option<(Vec<DVec3>, f64)>,
}

/// A rod along a 3D line that a vine winds round (a guide on the page).
#[derive(Debug, Clone, Copy)]
pub(super) struct Rod<'a> {
    /// Its axis, mm.
    pub(super) axis: &'a [DVec3],
    /// Its radius, mm.
    pub(super) radius: f64,
}

impl Sight {
    /// The lines and the hiding triangles of `plant` (stems of `radius`)
    /// on `shapes` and `rod`, with `leaves[k]` the motif drawn on leaf k.
    pub(super) fn new(
        camera: Camera,
        radius: f64,
        plant: &Plant,
        shapes: &[Shape],
        rod: Option<Rod<'_>>,
        leaves: &[Drawing],
    ) -> Sight {
        let mut lines = Vec::new();
        let mut triangles: Vec<[DVec3; 3]> = Vec::new();
        let axes: Vec<Vec<DVec3>> = plant
            .stems
            .iter()
            .map(|s| smooth(&s.points, (0.5 * radius).max(0.25)))
            .collect();
        for (i, axis) in axes.iter().enumerate() {
            if axis.len() < 2 {
                continue;
            }
            lines.push(Line {
                part: Part::Stem,
                item: i,
                points: stem_outline(&camera, axis, radius),
                closed: true,
            });
            push_mesh(&mut triangles, tube(axis, 0.97 * radius, TUBE_SIDES));
        }
        for (k, (leaf, drawing)) in plant.leaves.iter().zip(leaves).enumerate() {
            leaf_lines(leaf, drawing, k, &mut lines, &mut triangles);
        }
        let mut loops = Vec::new();
        for (i, shape) in shapes.iter().enumerate() {
            support_lines(&camera, shape, i, &mut lines, &mut triangles, &mut loops);
        }
        if let Some(Rod { axis, radius }) = rod {
            let (left, right) = tube_silhouette(&camera, axis, radius);
            loops.push(tube_loop(&left, &right));
            for side in [left, right] {
                lines.push(Line {
                    part: Part::Supports,
                    item: shapes.len(),
                    points: side,
                    closed: false,
                });
            }
            let inset = INSET.min(0.25 * radius);
            push_mesh(&mut triangles, tube(axis, radius - inset, TUBE_SIDES));
        }
        // Stem outlines, leaf outlines and pole rims.
        loops.extend(lines.iter().filter(|l| l.closed).map(|l| l.points.clone()));
        Sight {
            camera,
            occluders: Occluders::new(triangles),
            lines,
            loops,
            axes,
            rod: rod.map(|r| (r.axis.to_vec(), r.radius)),
        }
    }

    /// Every line, drawn or not: stems, then leaves, then supports.
    pub(super) fn lines(&self) -> &[Line] {
        &self.lines
    }

    /// Where the camera draws the model point `p`, if it can.
    pub(super) fn project(&self, p: DVec3) -> Option<Point> {
        self.camera.project(p).map(|(q, _)| q)
    }

    /// The picture's bounds: every line's points as projected, hidden or
    /// not (so that tables drawing different parts of one vine line up).
    pub(super) fn bounds(&self) -> Rect {
        let mut points = self
            .lines
            .iter()
            .flat_map(|l| &l.points)
            .filter_map(|p| self.camera.project(*p))
            .map(|(q, _)| q);
        let Some(first) = points.next() else {
            return Rect::ZERO;
        };
        points.fold(Rect::from_points(first, first), |r, p| r.union_pt(p))
    }

    /// The picture of the vine's solid parts as closed polygons, hidden or
    /// not: together they cover what the stems, leaves, poles and rod hide
    /// (boxes and meshes are left out).
    pub(super) fn silhouette(&self) -> Vec<Vec<Point>> {
        self.loops
            .iter()
            .filter_map(|l| match &self.picture(l)[..] {
                [whole] if whole.len() == l.len() && whole.len() > 2 => Some(whole.clone()),
                // Cut by a perspective eye: no closed picture.
                _ => None,
            })
            .collect()
    }

    /// The visible pieces of `line`, found every `step` and cut exactly
    /// to `tolerance` (picture units).
    pub(super) fn visible(&self, line: &Line, step: f64, tolerance: f64) -> Vec<Vec<DVec3>> {
        if line.closed {
            self.occluders
                .visible_loop_runs(&self.camera, &line.points, step, tolerance, EPS)
        } else {
            self.occluders
                .visible_runs(&self.camera, &line.points, step, tolerance, EPS)
        }
    }

    /// A 3D run in picture coordinates: a point behind a perspective eye
    /// has no picture, so it cuts the run.
    pub(super) fn picture(&self, run: &[DVec3]) -> Vec<Vec<Point>> {
        let mut out = Vec::new();
        let mut piece = Vec::new();
        for p in run {
            match self.camera.project(*p) {
                Some((q, _)) => piece.push(q),
                None if piece.len() > 1 => out.push(std::mem::take(&mut piece)),
                None => piece.clear(),
            }
        }
        if piece.len() > 1 {
            out.push(piece);
        }
        out
    }
}

/// The camera a spec asks for: presets look at the middle of the plant and
/// its supports.
pub(super) fn camera_for(spec: &CameraSpec, plant: &Plant, supports: &Supports) -> Camera {
    camera(spec, &bounds3(plant, supports))
}

/// The camera that sees a model laid on the page (x right, y up, z towards
/// the eye) as the page itself: x right, y down, 1:1.
pub(super) fn page_camera() -> Camera {
    Camera::orthographic(DVec3::Z, DVec3::ZERO, DVec3::Y)
}

/// The box holding the plant and its supports.
fn bounds3(plant: &Plant, supports: &Supports) -> (DVec3, DVec3) {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    let mut add = |p: DVec3, pad: f64| {
        lo = lo.min(p - pad);
        hi = hi.max(p + pad);
    };
    for s in &plant.stems {
        for p in &s.points {
            add(*p, 0.0);
        }
    }
    for l in &plant.leaves {
        for p in &l.quad {
            add(*p, 0.0);
        }
    }
    for shape in supports.shapes() {
        match shape {
            Shape::Pole { base, top, radius } => {
                add(*base, *radius);
                add(*top, *radius);
            }
            Shape::Block { min, max } => {
                add(*min, 0.0);
                add(*max, 0.0);
            }
            Shape::Mesh(m) => {
                for p in &m.vertices {
                    add(*p, 0.0);
                }
            }
        }
    }
    if lo.x > hi.x {
        return (DVec3::ZERO, DVec3::ZERO);
    }
    (lo, hi)
}

/// The camera a spec asks for; presets and orbits look at the middle of
/// `bounds`.
fn camera(spec: &CameraSpec, (lo, hi): &(DVec3, DVec3)) -> Camera {
    let centre = 0.5 * (*lo + *hi);
    let size = (*hi - *lo).length().max(1.0);
    let (from, perspective) = match *spec {
        CameraSpec::Preset(CameraPreset::Front) => (Orbit::FRONT.direction(), None),
        // The preset keeps its own direction, so that drawings made with
        // it stay as they were: its angles (`Orbit::THREE_QUARTER`) give
        // it only to the last bit, which can move a point the
        // simplification keeps.
        CameraSpec::Preset(CameraPreset::ThreeQuarter) => {
            (DVec3::new(0.8, 0.45, 1.0).normalize(), None)
        }
        CameraSpec::Orbit(orbit) => (orbit.direction(), orbit.perspective),
        CameraSpec::Preset(CameraPreset::Below) => {
            let height = hi.y - lo.y;
            let eye = DVec3::new(
                centre.x,
                lo.y + 0.02 * height,
                hi.z + 0.45 * height.max(hi.x - lo.x),
            );
            let target = DVec3::new(centre.x, lo.y + 0.6 * height, centre.z);
            return Camera::perspective(eye, target, DVec3::Y, 60.0);
        }
        CameraSpec::Placed {
            eye,
            target,
            up,
            perspective,
        } => {
            let (eye, target, up) = (
                DVec3::from_array(eye),
                DVec3::from_array(target),
                DVec3::from_array(up),
            );
            return match perspective {
                Some(fov) => Camera::perspective(eye, target, up, fov),
                None => Camera::orthographic(eye, target, up),
            };
        }
    };
    match perspective {
        // The sphere round the box (diameter `size`) just fits the field
        // of view.
        Some(fov) => {
            let distance = 0.5 * size / (0.5 * fov.to_radians()).sin();
            Camera::perspective(centre + from * distance, centre, DVec3::Y, fov)
        }
        None => Camera::orthographic(centre + from * 2.0 * size, centre, DVec3::Y),
    }
}

/// A centripetal Catmull–Rom curve through `points`, sampled at most
/// `spacing` mm apart: the stem as a smooth axis, through every point the
/// simulation made.
fn smooth(points: &[DVec3], spacing: f64) -> Vec<DVec3> {
    let n = points.len();
    if n < 3 {
        return points.to_vec();
    }
    let mut out = Vec::with_capacity(n * 4);
    for i in 0..n - 1 {
        let p0 = points[i.saturating_sub(1)];
        let (p1, p2) = (points[i], points[i + 1]);
        let p3 = points[(i + 2).min(n - 1)];
        let pieces = ((p2 - p1).length() / spacing).ceil().clamp(1.0, 1000.0) as usize;
        for k in 0..pieces {
            out.push(catmull_rom(p0, p1, p2, p3, k as f64 / pieces as f64));
        }
    }
    out.push(points[n - 1]);
    out
}

/// The point at `t` ∈ [0, 1] between `p1` and `p2` of a centripetal
/// Catmull–Rom segment (Barry–Goldman's pyramid).
fn catmull_rom(p0: DVec3, p1: DVec3, p2: DVec3, p3: DVec3, t: f64) -> DVec3 {
    let knot = |a: DVec3, b: DVec3| a.distance(b).sqrt().max(1e-9);
    let t0 = 0.0;
    let t1 = t0 + knot(p0, p1);
    let t2 = t1 + knot(p1, p2);
    let t3 = t2 + knot(p2, p3);
    let t = t1 + (t2 - t1) * t;
    let lerp = |a: DVec3, b: DVec3, ta: f64, tb: f64| a + (b - a) * ((t - ta) / (tb - ta));
    let a1 = lerp(p0, p1, t0, t1);
    let a2 = lerp(p1, p2, t1, t2);
    let a3 = lerp(p2, p3, t2, t3);
    let b1 = lerp(a1, a2, t0, t2);
    let b2 = lerp(a2, a3, t1, t3);
    lerp(b1, b2, t1, t2)
}

/// A stem's outline as one loop: one contour line of its tube up to the
/// tip, round the tip, the other contour back down, across the foot.
fn stem_outline(camera: &Camera, axis: &[DVec3], radius: f64) -> Vec<DVec3> {
    let (left, right) = tube_silhouette(camera, axis, radius);
    let n = axis.len();
    let tip = axis[n - 1];
    let heading = (tip - axis[n - 2]).normalize_or_zero();
    let side = left[n - 1] - tip;
    let mut outline = left;
    // Round the tip: a half circle from the left contour to the right.
    for k in 1..8 {
        let a = std::f64::consts::PI * f64::from(k) / 8.0;
        outline.push(tip + side * a.cos() + heading * radius * a.sin());
    }
    outline.extend(right.into_iter().rev());
    outline
}

/// Appends a mesh's triangles.
fn push_mesh(triangles: &mut Vec<[DVec3; 3]>, (vertices, faces): (Vec<DVec3>, Vec<[u32; 3]>)) {
    triangles.extend(faces.iter().map(|f| f.map(|i| vertices[i as usize])));
}

/// A leaf: the motif laid on its blade (outline and veins), its stalk, and
/// the blade's triangles.
fn leaf_lines(
    leaf: &Leaf,
    drawing: &Drawing,
    k: usize,
    lines: &mut Vec<Line>,
    triangles: &mut Vec<[DVec3; 3]>,
) {
    let height = leaf.length;
    let width = height / drawing.aspect.max(1e-6);
    let origin = leaf.stalk[1];
    // Motif units: the box [-0.5, 0.5]², tip up (−y), stem end at (0, 0.5).
    let lay = |p: Point| origin + leaf.midrib * (0.5 - p.y) * height + leaf.across * p.x * width;
    lines.push(Line {
        part: Part::Leaves,
        item: k,
        points: leaf.stalk.to_vec(),
        closed: false,
    });
    for (ring, closed) in polylines(&drawing.outline) {
        for [a, b, c] in ear_clip(&ring) {
            triangles.push([lay(ring[a]), lay(ring[b]), lay(ring[c])]);
        }
        lines.push(Line {
            part: Part::Leaves,
            item: k,
            points: ring.iter().map(|p| lay(*p)).collect(),
            closed,
        });
    }
    for (vein, closed) in polylines(&drawing.details) {
        lines.push(Line {
            part: Part::Leaves,
            item: k,
            points: vein.iter().map(|p| lay(*p)).collect(),
            closed,
        });
    }
}

/// The subpaths of a motif path flattened, each with whether it closes.
fn polylines(path: &BezPath) -> Vec<(Vec<Point>, bool)> {
    let mut out: Vec<(Vec<Point>, bool)> = Vec::new();
    kurbo::flatten(path, LEAF_FLATNESS, |el| match el {
        PathEl::MoveTo(p) => out.push((vec![p], false)),
        PathEl::LineTo(p) => {
            if let Some((line, _)) = out.last_mut() {
                line.push(p);
            }
        }
        PathEl::ClosePath => {
            if let Some((line, closed)) = out.last_mut() {
                *closed = true;
                if line.len() > 1 && line.first() == line.last() {
                    line.pop();
                }
            }
        }
        _ => {}
    });
    out.retain(|(l, _)| l.len() > 1);
    out
}

/// A support's lines and hiding triangles, and the loops round its picture.
fn support_lines(
    camera: &Camera,
    shape: &Shape,
    i: usize,
    lines: &mut Vec<Line>,
    triangles: &mut Vec<[DVec3; 3]>,
    loops: &mut Vec<Vec<DVec3>>,
) {
    let mut line = |points: Vec<DVec3>, closed: bool| {
        lines.push(Line {
            part: Part::Supports,
            item: i,
            points,
            closed,
        });
    };
    match shape {
        Shape::Pole { base, top, radius } => {
            let along = (*top - *base).normalize();
            // Contours sampled along the pole: a perspective camera sees
            // them converge.
            let samples = 64;
            let axis: Vec<DVec3> = (0..=samples)
                .map(|k| base.lerp(*top, f64::from(k) / f64::from(samples)))
                .collect();
            let (left, right) = tube_silhouette(camera, &axis, *radius);
            loops.push(tube_loop(&left, &right));
            line(left, false);
            line(right, false);
            for end in [*base, *top] {
                line(ring(end, along, *radius, POLE_SIDES), true);
            }
            let inset = INSET.min(0.25 * radius);
            push_mesh(
                triangles,
                tube(
                    &[*base + along * inset, *top - along * inset],
                    radius - inset,
                    POLE_SIDES,
                ),
            );
        }
        Shape::Block { min, max } => {
            let corner = |lo: DVec3, hi: DVec3, k: usize| {
                DVec3::new(
                    if k & 1 == 0 { lo.x } else { hi.x },
                    if k & 2 == 0 { lo.y } else { hi.y },
                    if k & 4 == 0 { lo.z } else { hi.z },
                )
            };
            for a in 0..8 {
                for bit in [1, 2, 4] {
                    if a & bit == 0 {
                        line(
                            vec![corner(*min, *max, a), corner(*min, *max, a | bit)],
                            false,
                        );
                    }
                }
            }
            let (lo, hi) = (*min + INSET, *max - INSET);
            // Two triangles on each face: corners differing in the two
            // axes other than the face's.
            for (axis, others) in [(1, [2, 4]), (2, [1, 4]), (4, [1, 2])] {
                for side in [0, axis] {
                    let [a, b] = others;
                    let c = |k: usize| corner(lo, hi, side | k);
                    triangles.push([c(0), c(a), c(a | b)]);
                    triangles.push([c(0), c(a | b), c(b)]);
                }
            }
        }
        Shape::Mesh(mesh) => {
            for (a, b) in mesh_edges(camera, mesh) {
                line(vec![a, b], false);
            }
            // Lines on a mesh lie on its own triangles' edges: the ray to
            // them meets those triangles at the point itself, which the
            // hiding test's margin lets through, so no inset is needed.
            triangles.extend(
                mesh.triangles
                    .iter()
                    .map(|t| t.map(|i| mesh.vertices[i as usize])),
            );
        }
    }
}

/// The edges a pen draws of a closed mesh: its creases (faces meeting at
/// more than [`CREASE`] degrees, either winding) and its contour as the
/// camera sees it (one face turned towards the eye, the other away).
fn mesh_edges(camera: &Camera, mesh: &TriMesh) -> Vec<(DVec3, DVec3)> {
    let v = |i: u32| mesh.vertices[i as usize];
    let normals: Vec<DVec3> = mesh
        .triangles
        .iter()
        .map(|&[a, b, c]| (v(b) - v(a)).cross(v(c) - v(a)).normalize_or_zero())
        .collect();
    let mut faces: BTreeMap<(u32, u32), Vec<usize>> = BTreeMap::new();
    for (f, t) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            faces.entry((a.min(b), a.max(b))).or_default().push(f);
        }
    }
    let crease = CREASE.to_radians().cos();
    faces
        .into_iter()
        .filter(|((a, b), fs)| {
            let [f, g] = fs[..] else { return true };
            let (n, m) = (normals[f], normals[g]);
            let towards = camera.looking_at(0.5 * (v(*a) + v(*b)));
            n.dot(m).abs() < crease || (n.dot(towards) < 0.0) != (m.dot(towards) < 0.0)
        })
        .map(|((a, b), _)| (v(a), v(b)))
        .collect()
}

/// The loop round a tube's picture: along one contour line and back along
/// the other.
fn tube_loop(left: &[DVec3], right: &[DVec3]) -> Vec<DVec3> {
    left.iter().chain(right.iter().rev()).copied().collect()
}

/// A circle of `n` points round `centre` in the plane across `normal`.
fn ring(centre: DVec3, normal: DVec3, radius: f64, n: u32) -> Vec<DVec3> {
    let (u, v) = normal.any_orthonormal_pair();
    (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * f64::from(k) / f64::from(n);
            centre + (u * a.cos() + v * a.sin()) * radius
        })
        .collect()
}
