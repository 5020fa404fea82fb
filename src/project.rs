//! The facade: scene description → scene → SVG / PNG / path dump.
//!
//! This is the one place that knows the order of the stages; the CLI calls
//! only these functions. It is also where user motifs are read from their
//! SVG files ([`load_motifs`]), since generators never touch files.

use std::path::Path;

use kurbo::BezPath;

use crate::error::{Error, Result};
use crate::motif::flora::{user_drawing, Library};
use crate::motif::{self, Context, Flow};
use crate::output::import::{import_svg, ImportOptions};
use crate::output::{path_dump, render_png, to_svg, SvgOptions};
use crate::plot;
use crate::scene::{Color, Group, Layer, Pen, Scene};
use crate::spec::{LayerSpec, MotifRef, ValidSpec};

pub use crate::motif::Progress;

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
    files
}

/// The user files of a description (see [`user_files`]).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct UserFiles {
    /// SVG files drawn as motifs.
    pub motifs: Vec<String>,
    /// SVG files whose paths are placed as they are.
    pub paths: Vec<String>,
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
/// [`Error::Motif`] naming the file: unreadable, not an SVG, or — for a
/// motif — without a closed shape to serve as its outline. The reason is
/// kept as the error's source.
pub fn load_motifs(spec: &ValidSpec, base: &Path) -> Result<Library> {
    let mut library = Library::new();
    let files = user_files(spec);
    for name in &files.motifs {
        let (path, paths) = read_paths(base, name)?;
        let drawing = user_drawing(&paths).map_err(|m| Error::Motif {
            name: name.clone(),
            message: format!("{}: {m}", path.display()),
        })?;
        library.add_user(name.clone(), drawing);
    }
    for name in &files.paths {
        let (_, paths) = read_paths(base, name)?;
        let mut joined = BezPath::new();
        for p in paths {
            joined.extend(p.elements().iter().copied());
        }
        library.add_paths(name.clone(), joined);
    }
    Ok(library)
}

/// The paths of the SVG file `name` (relative to `base`), in its mm.
fn read_paths(base: &Path, name: &str) -> Result<(std::path::PathBuf, Vec<BezPath>)> {
    let path = base.join(name);
    let fail = |message: String| Error::Motif {
        name: name.to_string(),
        message,
    };
    let text = std::fs::read_to_string(&path)
        .map_err(|e| fail(format!("cannot read {}: {e}", path.display())))?;
    let imported = import_svg(&text, &ImportOptions::DEFAULT)
        .map_err(|e| fail(format!("{}: {e}", path.display())))?;
    let mut paths: Vec<BezPath> = Vec::new();
    imported
        .scene
        .visit_paths(|_, p, t| paths.push(t * p.path.clone()));
    Ok((path, paths))
}

/// Builds the scene of a description, reading user files relative to the
/// current directory.
///
/// # Errors
/// See [`build_scene_with_progress`].
pub fn build_scene(spec: &ValidSpec) -> Result<Scene> {
    build_scene_with_progress(spec, &load_motifs(spec, Path::new("."))?, &mut |_| {})
}

/// [`build_scene`] with the library given, reporting progress in work
/// units of any family.
///
/// # Errors
/// The path budget running out ([`Error::Budget`]), an `[[adjust]]` that
/// matches nothing or does not fit what it matches ([`Error::Invalid`]
/// with its line and column when the description came from TOML), a user
/// file missing from the library ([`Error::Motif`]).
pub fn build_scene_with_progress(
    spec: &ValidSpec,
    library: &Library,
    progress: &mut dyn FnMut(Progress),
) -> Result<Scene> {
    build(spec, library, progress).map_err(|e| spec.locate(e))
}

fn build(spec: &ValidSpec, library: &Library, progress: &mut dyn FnMut(Progress)) -> Result<Scene> {
    let flow = Flow::new(&spec.lines);
    let ids = layer_ids(spec);
    let mut cx = Context::new(spec, library, &flow, progress);
    let mut layers = Vec::with_capacity(spec.layers.len());
    for (index, (layer, id)) in spec.layers.iter().zip(&ids).enumerate() {
        let depth = layer.depth.unwrap_or(index as i32);
        cx.enter_layer((index, layer), id, depth);
        let mut content = Group::new(format!("{id}.motifs"));
        for item in layer.items() {
            content.push_group(motif::build(&item, &mut cx)?);
        }
        layers.push(Layer {
            id: id.clone(),
            name: layer.name.clone(),
            pen: layer.pen,
            depth,
            content,
        });
    }
    cx.finish()?;
    let mut pens: Vec<Pen> = spec
        .pens
        .iter()
        .map(|p| Pen {
            number: p.number,
            name: p.name.clone(),
            color: Color::parse(&p.color).unwrap_or(Color::BLACK),
            width: p.width,
        })
        .collect();
    pens.sort_by_key(|p| p.number);
    Ok(Scene {
        page: spec.page(),
        pens,
        layers,
        description: Some(spec.to_toml()),
    })
}

/// Stable, unique, SVG-safe ids for the layers, made from their names.
fn layer_ids(spec: &ValidSpec) -> Vec<String> {
    let mut ids: Vec<String> = Vec::new();
    for layer in &spec.layers {
        let mut slug: String = layer
            .name
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() {
                    c.to_ascii_lowercase()
                } else {
                    '-'
                }
            })
            .collect();
        if !slug.starts_with(|c: char| c.is_ascii_alphabetic()) {
            slug.insert_str(0, "layer-");
        }
        let mut id = slug.clone();
        let mut n = 2;
        while ids.contains(&id) {
            id = format!("{slug}-{n}");
            n += 1;
        }
        ids.push(id);
    }
    ids
}

/// The SVG options a description asks for.
pub fn svg_options(spec: &ValidSpec) -> SvgOptions {
    SvgOptions::DEFAULT.with_precision(spec.output.precision)
}

/// Everything a render produces, in memory.
#[derive(Debug, Clone)]
pub struct Rendered {
    /// The scene.
    pub scene: Scene,
    /// The SVG text.
    pub svg: String,
}

/// Builds the scene, runs the plot stages the description asks for and
/// writes its SVG; user motifs are read relative to the current directory.
pub fn render(spec: &ValidSpec) -> Result<Rendered> {
    render_with_progress(spec, &load_motifs(spec, Path::new("."))?, &mut |_| {})
}

/// [`render`] with the motifs given and progress reports.
pub fn render_with_progress(
    spec: &ValidSpec,
    library: &Library,
    progress: &mut dyn FnMut(Progress),
) -> Result<Rendered> {
    let scene = plot::run(
        build_scene_with_progress(spec, library, progress)?,
        &spec.plot,
    )?;
    let svg = to_svg(&scene, &svg_options(spec));
    Ok(Rendered { scene, svg })
}

impl Rendered {
    /// PNG preview of exactly this SVG.
    pub fn png(&self, dpi: f64) -> Result<Vec<u8>> {
        render_png(&self.svg, dpi)
    }

    /// The line-oriented path dump (see [`crate::output::path_dump`]).
    pub fn dump(&self, precision: u8) -> String {
        path_dump(&self.scene, precision)
    }
}
