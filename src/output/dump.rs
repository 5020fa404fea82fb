//! A stable, line-oriented dump of every path, for snapshot tests.
//!
//! [`path_dump`] writes one line per path, in scene order (layers as listed
//! in the scene, then depth-first through groups in child order):
//!
//! ```text
//! {layer id}<TAB>{path id}<TAB>{path data}<LF>
//! ```
//!
//! - The path data is in **page coordinates** (mm from the top-left corner
//!   of the sheet): every group transform and the margin offset are applied.
//! - It uses the SVG writer's path syntax: absolute commands `M`, `L`, `Q`,
//!   `C`, `Z`, each command and number separated by one space, numbers
//!   rounded to `precision` decimals (at most 8) with trailing zeros removed
//!   and no negative zero. An empty path has empty path data.
//! - In ids, `\` is written `\\`, tab `\t`, line feed `\n` and carriage
//!   return `\r`, so every path is exactly one line with three fields.
//! - Every line, the last included, ends with a line feed; a scene without
//!   paths gives the empty string.
//!
//! This format is stable: changing any of the above (field order, separator,
//! coordinate space, number or command syntax, escaping) is a breaking
//! change. Styles and pens are deliberately not part of it, so a dump only
//! changes when geometry or ids change.

use super::svg::write_path_data;
use crate::scene::Scene;

/// The path dump of `scene` with coordinates at `precision` decimals (see
/// the module documentation for the exact, stable format).
pub fn path_dump(scene: &Scene, precision: u8) -> String {
    let mut out = String::new();
    scene.visit_paths(|layer, path, transform| {
        write_field(&mut out, &layer.id);
        out.push('\t');
        write_field(&mut out, &path.id);
        out.push('\t');
        write_path_data(&mut out, &(transform * path.path.clone()), precision);
        out.push('\n');
    });
    out
}

/// Appends an id with the characters that would break the line format
/// escaped.
fn write_field(out: &mut String, id: &str) {
    for c in id.chars() {
        match c {
            '\\' => out.push_str("\\\\"),
            '\t' => out.push_str("\\t"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            c => out.push(c),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Color, Group, Layer, Pen, Style};
    use crate::units::{Margins, Orientation, Page, PaperName};
    use kurbo::{Affine, BezPath, Line, Shape};

    fn scene() -> Scene {
        let mut trunk = Group::new("trunk");
        trunk.push_path(
            "base",
            Line::new((0.0, 0.0), (0.0, -10.0)).into_path(0.1),
            Style::default(),
        );
        let mut twig = Group::new("twig");
        twig.transform = Affine::translate((5.0, 5.0)) * Affine::scale(2.0);
        let mut curl = BezPath::new();
        curl.move_to((0.0, 0.0));
        curl.curve_to((1.0, 0.0), (1.0, 1.0 / 3.0), (0.0, 1.0));
        curl.close_path();
        twig.push_path(
            "curl",
            curl,
            Style {
                fill: Some(Color::BLACK),
                ..Style::default()
            },
        );
        trunk.push_group(twig);

        let mut odd = Group::new("odd");
        odd.push_path("tab\there\\", BezPath::new(), Style::default());

        let layer = |id: &str, depth: i32, content: Group| Layer {
            id: id.into(),
            name: id.into(),
            pen: 1,
            depth,
            content,
        };
        Scene {
            page: Page::named(PaperName::A4, Orientation::Portrait, Margins::uniform(20.0)),
            pens: vec![Pen {
                number: 1,
                name: "black".into(),
                color: Color::BLACK,
                width: 0.3,
            }],
            // The back layer comes second in the description: the dump
            // follows the description, not the paint order.
            layers: vec![layer("tree", 0, trunk), layer("line\nbreak", 5, odd)],
            description: None,
        }
    }

    #[test]
    fn one_line_per_path_in_page_coordinates() {
        assert_eq!(
            path_dump(&scene(), 3),
            "tree\tbase\tM 20 20 L 20 10\n\
             tree\tcurl\tM 25 25 C 27 25 27 25.667 25 27 Z\n\
             line\\nbreak\ttab\\there\\\\\t\n"
        );
    }

    #[test]
    fn precision_applies_after_transforms() {
        let dump = path_dump(&scene(), 1);
        assert!(dump.contains("C 27 25 27 25.7 25 27 Z"), "{dump}");
    }

    #[test]
    fn empty_scene_gives_empty_dump() {
        let mut s = scene();
        s.layers.clear();
        assert_eq!(path_dump(&s, 3), "");
    }
}
