//! What moyo reads besides its own scene descriptions: SVG import
//! ([`import_svg`]: any SVG document into a [`Scene`](crate::Scene) in
//! millimetres, Inkscape layers or colours as pens) and grey images as
//! density ([`decode_image`]: PNG or JPEG into a
//! [`GreyImage`](crate::geom::density::GreyImage), dark asks for more). Meshes and strokes will join them. Readers only build scenes and
//! maps; they never generate motifs nor write files.

mod image;
mod svg;

pub use image::decode_image;
pub use svg::{import_svg, ImportOptions, Imported, PenGrouping};
