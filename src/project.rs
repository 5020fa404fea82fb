//! The facade: scene description → scene → SVG / PNG / path dump.
//!
//! This is the one place that knows the order of the stages; the CLI calls
//! only these functions.

use crate::error::Result;
use crate::motif::kimono::{self, Flow};
use crate::output::{path_dump, render_png, to_svg, SvgOptions};
use crate::plot;
use crate::rng::Seed;
use crate::scene::{Color, Group, Layer, PathBudget, Pen, Scene};
use crate::spec::SceneSpec;

/// How far generation has come, for progress bars.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Progress {
    /// Trees grown so far.
    pub done: usize,
    /// Trees in the scene.
    pub total: usize,
}

/// Builds the scene of a validated description.
pub fn build_scene(spec: &SceneSpec) -> Result<Scene> {
    build_scene_with_progress(spec, &mut |_| {})
}

/// [`build_scene`], reporting progress after every tree.
pub fn build_scene_with_progress(
    spec: &SceneSpec,
    progress: &mut dyn FnMut(Progress),
) -> Result<Scene> {
    let seed = Seed(spec.seed);
    let flow = Flow::new(&spec.lines);
    let mut budget = PathBudget::new(spec.limits.max_paths);
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
        let mut content = Group::new(format!("{id}.motifs"));
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
                seed,
                &mut budget,
                &mut tree_done,
            )?;
            content.push_group(group);
        }
        layers.push(Layer {
            id,
            name: layer.name.clone(),
            pen: layer.pen,
            depth: layer.depth.unwrap_or(index as i32),
            content,
        });
    }
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
    /// The SVG text.
    pub svg: String,
}

/// Builds the scene, runs the plot stages the description asks for and
/// writes its SVG.
pub fn render(spec: &SceneSpec) -> Result<Rendered> {
    render_with_progress(spec, &mut |_| {})
}

/// [`render`] with progress reports.
pub fn render_with_progress(
    spec: &SceneSpec,
    progress: &mut dyn FnMut(Progress),
) -> Result<Rendered> {
    let scene = plot::run(build_scene_with_progress(spec, progress)?, &spec.plot)?;
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
