//! The 3D model of a vine table for the OBJ export: the parts it draws,
//! in millimetres with y up, as the simulation made them.
//!
//! A stem is its smoothed axis as a polyline and the tube swept along it
//! (the thesis' eq. 3.4–3.5, [`tube`]); a leaf is the thesis' square quad
//! (eq. 3.6–3.8) on its blade; a support is its surface.

use glam::DVec3;

use super::sight::Sight;
use crate::family::vine::engine::{tube, Plant, Shape};
use crate::scene::{Model, ModelPart};
use crate::spec::{Part, VineSpec};

/// Sides of an exported stem tube (the thesis' M).
const SIDES: u32 = 12;

/// Sides of an exported pole.
const POLE_SIDES: u32 = 32;

/// The model of the parts `spec` draws.
pub(super) fn model(
    id: &str,
    spec: &VineSpec,
    plant: &Plant,
    supports: &[Shape],
    sight: &Sight,
) -> Model {
    let mut parts = Vec::new();
    if spec.draw.contains(&Part::Stem) {
        for (i, axis) in sight.axes.iter().enumerate().filter(|(_, a)| a.len() > 1) {
            let (vertices, faces) = tube(axis, spec.radius, SIDES);
            let mut part = mesh(format!("stem-{i}"), &vertices, &faces);
            let start = part.vertices.len() as u32;
            part.vertices.extend(axis.iter().map(|p| p.to_array()));
            part.lines
                .push((start..start + axis.len() as u32).collect());
            parts.push(part);
        }
    }
    if spec.draw.contains(&Part::Leaves) {
        for (k, leaf) in plant.leaves.iter().enumerate() {
            parts.push(ModelPart {
                name: format!("leaf-{k}"),
                vertices: leaf.quad.iter().map(|p| p.to_array()).collect(),
                lines: Vec::new(),
                faces: vec![vec![0, 1, 2, 3]],
            });
        }
    }
    if spec.draw.contains(&Part::Supports) {
        for (i, shape) in supports.iter().enumerate() {
            let name = format!("support-{i}");
            parts.push(match shape {
                Shape::Pole { base, top, radius } => {
                    let (v, f) = tube(&[*base, *top], *radius, POLE_SIDES);
                    mesh(name, &v, &f)
                }
                Shape::Block { min, max } => block(name, *min, *max),
                Shape::Mesh(m) => mesh(name, &m.vertices, &m.triangles),
            });
        }
        if let Some((axis, radius)) = &sight.rod {
            let (v, f) = tube(axis, *radius, SIDES);
            parts.push(mesh(format!("support-{}", supports.len()), &v, &f));
        }
    }
    Model {
        id: id.to_string(),
        parts,
    }
}

/// A triangle mesh as a part.
fn mesh(name: String, vertices: &[DVec3], faces: &[[u32; 3]]) -> ModelPart {
    ModelPart {
        name,
        vertices: vertices.iter().map(|p| p.to_array()).collect(),
        lines: Vec::new(),
        faces: faces.iter().map(|f| f.to_vec()).collect(),
    }
}

/// A box as six quads wound outwards.
fn block(name: String, min: DVec3, max: DVec3) -> ModelPart {
    let vertices = (0..8)
        .map(|k| {
            [
                if k & 1 == 0 { min.x } else { max.x },
                if k & 2 == 0 { min.y } else { max.y },
                if k & 4 == 0 { min.z } else { max.z },
            ]
        })
        .collect();
    ModelPart {
        name,
        vertices,
        lines: Vec::new(),
        faces: vec![
            vec![0, 4, 6, 2], // x = min
            vec![1, 3, 7, 5], // x = max
            vec![0, 1, 5, 4], // y = min
            vec![2, 6, 7, 3], // y = max
            vec![0, 2, 3, 1], // z = min
            vec![4, 5, 7, 6], // z = max
        ],
    }
}
