//! What moyo reads besides its own scene descriptions: today SVG import
//! ([`import_svg`]: any SVG document into a [`Scene`](crate::scene::Scene)
//! in millimetres, Inkscape layers or colours as pens). Images, meshes and
//! strokes will join it. Readers only build scenes; they never generate
//! motifs nor write files.

mod svg;

pub use svg::{import_svg, ImportOptions, Imported, PenGrouping};
