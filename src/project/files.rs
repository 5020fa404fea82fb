//! The user files a description names — motifs, paths, density images,
//! meshes — read into the motif library, since generators never read
//! files.

use std::path::Path;

use kurbo::BezPath;

use crate::error::{Cause, Error, Result, UserFile};
use crate::geom::mesh::TriMesh;
use crate::input::{decode_image, import_svg, ImportOptions};
use crate::motif::{user_drawing, Library};
use crate::spec::{LayerSpec, MotifRef, ValidSpec};

/// Every user file a description names, in order of first appearance,
/// without repeats: user motifs (`{ svg = "…" }`) and the SVG files of
/// `[[layers.paths]]` tables.
pub fn user_files(spec: &ValidSpec) -> UserFiles {
    let mut files = UserFiles::default();
    let items: Vec<_> = spec.layers.iter().flat_map(LayerSpec::items).collect();
    let swaps = spec.adjust.iter().filter_map(|a| a.motif.as_ref());
    let refs = items
        .iter()
        .flat_map(|i| i.table.family().motifs())
        .chain(swaps);
    for r in refs {
        if let MotifRef::File(f) = r {
            push_new(&mut files.motifs, &f.svg);
        }
    }
    for name in items.iter().flat_map(|i| i.table.family().path_files()) {
        push_new(&mut files.paths, name);
    }
    for name in items.iter().flat_map(|i| i.table.family().image_files()) {
        push_new(&mut files.images, name);
    }
    for name in items.iter().flat_map(|i| i.table.family().mesh_files()) {
        push_new(&mut files.meshes, name);
    }
    files
}

/// The user files of a description (see [`user_files`]).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct UserFiles {
    /// SVG files drawn as motifs.
    pub motifs: Vec<String>,
    /// SVG files whose paths are placed as they are.
    pub paths: Vec<String>,
    /// PNG or JPEG files read as density.
    pub images: Vec<String>,
    /// Wavefront OBJ files read as closed meshes.
    pub meshes: Vec<String>,
}

fn push_new(list: &mut Vec<String>, name: &str) {
    if !list.iter().any(|n| n == name) {
        list.push(name.to_string());
    }
}

/// Reads the user files of a description into a library, their paths
/// taken relative to `base` (the directory of the description file).
///
/// # Errors
/// [`Error::Motif`] naming the file: unreadable, not an SVG (not a PNG or
/// JPEG for an image), or — for a motif — without a closed shape to serve
/// as its outline. The reason is kept as the error's source.
pub fn load_motifs(spec: &ValidSpec, base: &Path) -> Result<Library> {
    load_motifs_with(spec, &|name| {
        let path = base.join(name);
        // A description may come from anyone: what it names must be a
        // file, never a FIFO that would hang the render.
        (
            path.display().to_string(),
            crate::input::read_regular_file(&path),
        )
    })
}

/// [`load_motifs`] from anywhere: `read` gives the bytes of a file the
/// description names, with the name to show in messages (a path, or
/// where else it came from: a built-in template's files are compiled in).
///
/// # Errors
/// As [`load_motifs`].
pub fn load_motifs_with(spec: &ValidSpec, read: &FileReader<'_>) -> Result<Library> {
    let mut library = Library::new();
    let files = user_files(spec);
    let open = |kind: UserFile, name: &str| {
        let (shown, bytes) = read(name);
        match bytes {
            Ok(bytes) => Ok((shown, bytes)),
            Err(e) => Err(unusable(
                kind,
                name,
                format!("cannot read {shown}"),
                e.into(),
            )),
        }
    };
    for name in &files.motifs {
        let (shown, bytes) = open(UserFile::Motif, name)?;
        let paths = svg_paths(UserFile::Motif, name, &shown, &bytes)?;
        let drawing = user_drawing(&paths).map_err(|m| Error::Motif {
            kind: UserFile::Motif,
            name: name.clone(),
            message: format!("{shown}: {m}"),
            source: None,
        })?;
        library.add_user(name.clone(), drawing);
    }
    for name in &files.paths {
        let (shown, bytes) = open(UserFile::Paths, name)?;
        let mut joined = BezPath::new();
        for p in svg_paths(UserFile::Paths, name, &shown, &bytes)? {
            joined.extend(p.elements().iter().copied());
        }
        library.add_paths(name.clone(), joined);
    }
    for name in &files.images {
        let (shown, bytes) = open(UserFile::Image, name)?;
        let image =
            decode_image(&bytes).map_err(|e| unusable(UserFile::Image, name, shown, e.into()))?;
        library.add_image(name.clone(), image);
    }
    for name in &files.meshes {
        let (shown, bytes) = open(UserFile::Mesh, name)?;
        let text = std::str::from_utf8(&bytes).map_err(|e| {
            unusable(
                UserFile::Mesh,
                name,
                format!("{shown} is not UTF-8 text"),
                e.into(),
            )
        })?;
        let mesh = TriMesh::parse_obj(text, &shown)
            .and_then(|m| m.check_closed(&shown).map(|()| m))
            .map_err(|e| Error::Motif {
                kind: UserFile::Mesh,
                name: name.clone(),
                // The mesh's own error names the file (and the line).
                message: match e {
                    Error::Invalid { field, message, .. } => format!("{field}: {message}"),
                    e => e.to_string(),
                },
                source: None,
            })?;
        library.add_mesh(name.clone(), mesh);
    }
    Ok(library)
}

/// Where [`load_motifs_with`] gets a file: its name as the description
/// writes it → the name to show in messages (a path) and the file's bytes.
pub type FileReader<'a> = dyn Fn(&str) -> (String, std::io::Result<Vec<u8>>) + 'a;

/// A user file that could not be used: `message`, then the cause's own.
fn unusable(kind: UserFile, name: &str, message: String, cause: Cause) -> Error {
    Error::Motif {
        kind,
        name: name.to_string(),
        message: format!("{message}: {cause}"),
        source: Some(cause),
    }
}

/// The paths of the SVG file `name` (a `kind` of file, shown as `shown`), in its mm: the
/// lines it draws, not paint that no pen draws (a filled shape whose
/// stroke is transparent, such as a white page behind the drawing).
fn svg_paths(kind: UserFile, name: &str, shown: &str, bytes: &[u8]) -> Result<Vec<BezPath>> {
    let text = std::str::from_utf8(bytes)
        .map_err(|e| unusable(kind, name, format!("{shown} is not UTF-8 text"), e.into()))?;
    let imported = import_svg(text, &ImportOptions::DEFAULT)
        .map_err(|e| unusable(kind, name, shown.to_string(), e.into()))?;
    let mut paths: Vec<BezPath> = Vec::new();
    imported.scene.visit_paths(|_, p, t| {
        if p.style.is_drawn() {
            paths.push(t * p.path.clone());
        }
    });
    Ok(paths)
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_paths_of_a_file_are_the_lines_it_draws() {
        // A white page whose stroke is transparent behind a line: a motif,
        // a paths table or a sketch's stroke gets the line alone.
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="20mm" height="20mm" viewBox="0 0 20 20">
            <rect width="20" height="20" fill="white" stroke="transparent"/>
            <path d="M2 2 L18 18" stroke="black"/></svg>"#;
        let paths =
            super::svg_paths(super::UserFile::Paths, "a.svg", "a.svg", svg.as_bytes()).unwrap();
        assert_eq!(paths.len(), 1);
        assert_eq!(paths[0].elements().len(), 2);
    }
}
