//! The facade: scene description → scene → SVG / PNG / path dump.
//!
//! This is the one place that knows the order of the stages; the CLI calls
//! only these functions. It is also where user motifs are read from their
//! SVG files ([`load_motifs`]), since generators never touch files.

use std::path::Path;

use kurbo::BezPath;

use crate::error::{Error, Result};
use crate::motif::flora::{user_drawing, Library};
use crate::motif::kimono::{self, Adjustments, FloraContext, Flow};
use crate::output::import::{import_svg, ImportOptions};
use crate::output::{path_dump, render_png, to_svg, SvgOptions};
use crate::plot;
use crate::rng::Seed;
use crate::scene::{Color, Group, Layer, PathBudget, Pen, Scene};
use crate::spec::{MotifRef, SceneSpec};

/// How far generation has come, for progress bars.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Progress {
    /// Trees grown so far.
    pub done: usize,
    /// Trees in the scene.
    pub total: usize,
}

/// Every user motif a description names (`{ svg = "…" }`), in order of
/// first appearance, without repeats.
pub fn user_motif_files(spec: &SceneSpec) -> Vec<String> {
    let mut refs: Vec<&MotifRef> = Vec::new();
    for layer in &spec.layers {
        for set in &layer.trees {
            if let Some(f) = &set.flowers {
                refs.extend(&f.motifs);
            }
            if let Some(r) = &set.leaves.ring {
                refs.extend(&r.motifs);
            }
            if let Some(j) = &set.leaves.joints {
                refs.extend(&j.motifs);
            }
        }
        if let Some(bg) = &layer.background {
            refs.push(&bg.stamp);
            refs.extend(&bg.motifs);
        }
    }
    refs.extend(spec.adjust.iter().filter_map(|a| a.motif.as_ref()));
    let mut files: Vec<String> = Vec::new();
    for r in refs {
        if let MotifRef::File(f) = r {
            if !files.contains(&f.svg) {
                files.push(f.svg.clone());
            }
        }
    }
    files
}

/// Reads the user motifs of a description, their paths taken relative to
/// `base` (the directory of the description file).
///
/// # Errors
/// [`Error::Motif`] naming the file: unreadable, not an SVG, or without a
/// closed shape to serve as the motif's outline.
pub fn load_motifs(spec: &SceneSpec, base: &Path) -> Result<Library> {
    let mut library = Library::new();
    for name in user_motif_files(spec) {
        let path = base.join(&name);
        let fail = |message: String| Error::Motif {
            name: name.clone(),
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
        let drawing = user_drawing(&paths).map_err(|m| fail(format!("{}: {m}", path.display())))?;
        library.add_user(name.clone(), drawing);
    }
    Ok(library)
}

/// Builds the scene of a validated description, reading user motifs
/// relative to the current directory.
pub fn build_scene(spec: &SceneSpec) -> Result<Scene> {
    build_scene_with_progress(spec, &load_motifs(spec, Path::new("."))?, &mut |_| {})
}

/// [`build_scene`] with the motifs given, reporting progress after every
/// tree.
pub fn build_scene_with_progress(
    spec: &SceneSpec,
    library: &Library,
    progress: &mut dyn FnMut(Progress),
) -> Result<Scene> {
    let seed = Seed(spec.seed);
    let flow = Flow::new(&spec.lines);
    let mut budget = PathBudget::new(spec.limits.max_paths);
    let mut adjust = Adjustments::new(&spec.adjust);
    let total = spec
        .layers
        .iter()
        .flat_map(|l| &l.trees)
        .map(|s| s.count as usize)
        .sum();
    let mut done = 0;
    let ids = layer_ids(spec);
    let mut layers = Vec::with_capacity(spec.layers.len());
    for (index, (layer, id)) in spec.layers.iter().zip(ids).enumerate() {
        let depth = layer.depth.unwrap_or(index as i32);
        let cx = FloraContext {
            library,
            seed,
            depth,
        };
        let mut content = Group::new(format!("{id}.motifs"));
        if let Some(bg) = &layer.background {
            let group = kimono::background::background(
                bg,
                &format!("{id}.background"),
                &flow,
                &cx,
                &mut budget,
            )?;
            content.push_group(group);
        }
        for (k, set) in layer.trees.iter().enumerate() {
            let set_id = format!("{id}.{}", kimono::set_id(set, k));
            let mut tree_done = || {
                done += 1;
                progress(Progress { done, total });
            };
            let group = kimono::tree_set(
                set,
                &set_id,
                &layer.limbs,
                &flow,
                &cx,
                &mut adjust,
                &mut budget,
                &mut tree_done,
            )?;
            content.push_group(group);
        }
        layers.push(Layer {
            id,
            name: layer.name.clone(),
            pen: layer.pen,
            depth,
            content,
        });
    }
    adjust.finish()?;
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
fn layer_ids(spec: &SceneSpec) -> Vec<String> {
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
pub fn svg_options(spec: &SceneSpec) -> SvgOptions {
    SvgOptions::DEFAULT.with_precision(spec.output.precision)
}

/// Everything a render produces, in memory.
#[derive(Debug, Clone)]
pub struct Rendered {
    /// The scene.
    pub scene: Scene,
    /// The SVG to plot: only what pens draw (see [`crate::output::to_svg`]);
    /// the colour preview is [`Rendered::preview_svg`].
    pub svg: String,
    /// The options `svg` was written with.
    options: SvgOptions,
}

/// Builds the scene, runs the plot stages the description asks for and
/// writes its SVG; user motifs are read relative to the current directory.
pub fn render(spec: &SceneSpec) -> Result<Rendered> {
    render_with_progress(spec, &load_motifs(spec, Path::new("."))?, &mut |_| {})
}

/// [`render`] with the motifs given and progress reports.
pub fn render_with_progress(
    spec: &SceneSpec,
    library: &Library,
    progress: &mut dyn FnMut(Progress),
) -> Result<Rendered> {
    let scene = plot::run(
        build_scene_with_progress(spec, library, progress)?,
        &spec.plot,
    )?;
    let options = svg_options(spec);
    let svg = to_svg(&scene, &options);
    Ok(Rendered {
        scene,
        svg,
        options,
    })
}

impl Rendered {
    /// The colour preview SVG: the plot's pen layers as they are in
    /// [`Rendered::svg`], plus the preview colour of partly hidden shapes
    /// and the layers that are not plotted.
    pub fn preview_svg(&self) -> String {
        to_svg(&self.scene, &self.options.with_preview(true))
    }

    /// PNG preview, rendered from [`Rendered::preview_svg`].
    pub fn png(&self, dpi: f64) -> Result<Vec<u8>> {
        render_png(&self.preview_svg(), dpi)
    }

    /// The line-oriented path dump (see [`crate::output::path_dump`]).
    pub fn dump(&self, precision: u8) -> String {
        path_dump(&self.scene, precision)
    }
}
