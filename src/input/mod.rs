//! What moyo reads besides its own scene descriptions: SVG import
//! ([`import_svg`]: any SVG document into a [`Scene`](crate::Scene) in
//! millimetres, Inkscape layers or colours as pens), grey images as
//! density ([`decode_image`]: PNG or JPEG into a
//! [`GreyImage`](crate::geom::density::GreyImage), dark asks for more),
//! and every input file, read whole up to [`MAX_FILE_BYTES`]
//! ([`read_file`]). Readers only build scenes and maps; they never
//! generate motifs nor write files.

mod file;
mod image;
mod svg;

// For the studio, which opens a file its own way (regular files only).
#[cfg(feature = "studio")]
pub(crate) use file::utf8;
pub use file::{read_file, read_regular_file, read_text, MAX_FILE_BYTES};
pub use image::decode_image;
pub use svg::{import_svg, ImportOptions, Imported, PenGrouping, MAX_IMPORT_SEGMENTS};
