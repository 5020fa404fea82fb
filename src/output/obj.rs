//! Wavefront OBJ: the 3D models a scene's generators made (a vine and its
//! supports), as text that Blender, MeshLab and most 3D tools import.
//!
//! Millimetres, right-handed with y up, as the models are. Each part of a
//! model is an object named after the model and the part (`o
//! front.vine-0.stem-0`: Blender and trimesh make one object of each) and
//! a group named after the part alone (`g stem-0`, `g leaf-3`, `g
//! support-1`), holding its vertices, its polylines (`l`) and its faces
//! (`f`). Indices are 1-based and count from the top of the file. Numbers
//! go through [`write_number`] at a fixed precision: same models, same
//! bytes.

use std::fmt::Write as _;

use super::write_number;
use crate::scene::Model;

/// The OBJ text of `models`, numbers rounded to `precision` decimals.
pub fn to_obj(models: &[Model], precision: u8) -> String {
    let mut out = String::new();
    out.push_str("# moyo: millimetres, right-handed, y up\n");
    let mut base = 1u64;
    for model in models {
        for part in &model.parts {
            let _ = writeln!(out, "o {}.{}", name(&model.id), name(&part.name));
            let _ = writeln!(out, "g {}", name(&part.name));
            for v in &part.vertices {
                out.push('v');
                for c in v {
                    out.push(' ');
                    write_number(&mut out, *c, precision);
                }
                out.push('\n');
            }
            for (tag, lists) in [('l', &part.lines), ('f', &part.faces)] {
                for list in lists {
                    out.push(tag);
                    for i in list {
                        let _ = write!(out, " {}", base + u64::from(*i));
                    }
                    out.push('\n');
                }
            }
            base += part.vertices.len() as u64;
        }
    }
    out
}

/// An OBJ name: no whitespace (a name ends at the first blank).
fn name(s: &str) -> String {
    s.chars()
        .map(|c| if c.is_whitespace() { '_' } else { c })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::ModelPart;

    fn part(name: &str, at: f64) -> ModelPart {
        ModelPart {
            name: name.into(),
            vertices: vec![[at, 0.0, 0.0], [at, 1.5, 0.0], [at, 0.0, 2.0]],
            lines: vec![vec![0, 1]],
            faces: vec![vec![0, 1, 2]],
        }
    }

    #[test]
    fn indices_count_from_the_top_of_the_file() {
        let model = Model {
            id: "front.vine 0".into(),
            parts: vec![part("stem-0", 0.0), part("leaf-0", 1.0 / 3.0)],
        };
        let obj = to_obj(&[model], 3);
        assert_eq!(
            obj,
            "# moyo: millimetres, right-handed, y up\n\
             o front.vine_0.stem-0\ng stem-0\n\
             v 0 0 0\nv 0 1.5 0\nv 0 0 2\nl 1 2\nf 1 2 3\n\
             o front.vine_0.leaf-0\ng leaf-0\n\
             v 0.333 0 0\nv 0.333 1.5 0\nv 0.333 0 2\nl 4 5\nf 4 5 6\n"
        );
    }

    #[test]
    fn no_models_is_a_header_alone() {
        assert_eq!(to_obj(&[], 3).lines().count(), 1);
    }
}
