//! A description built into its scene and rendered: SVG, the colour
//! preview, PNG, the path dump; with progress, cancellation, or without
//! the pen stage for editing.

use std::path::Path;

use kurbo::Point;

use super::files::load_motifs;
use super::{Cancel, Note, Progress};
use crate::error::{Error, Result};
use crate::motif::{Context, Flow, Library};
use crate::output::{path_dump, render_png, to_svg, SvgOptions};
use crate::plot::{self, PlotOptions};
use crate::scene::{Color, Group, Layer, Model, Pen, Scene, Stats, UniqueIds};
use crate::spec::{LayerItem, LayerSpec, Points, Table, ValidSpec, VoronoiSpec};

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
    build(spec, library, progress, Cancel::never())
        .map(|(scene, _, _)| scene)
        .map_err(|e| spec.locate(e))
}

/// The scene, the generators' notes and their 3D models.
pub(super) fn build(
    spec: &ValidSpec,
    library: &Library,
    progress: &mut dyn FnMut(Progress),
    cancel: &Cancel,
) -> Result<(Scene, Vec<Note>, Vec<Model>)> {
    let flow = Flow::new(&spec.lines);
    let ids = layer_ids(spec)?;
    let mut cx = Context::new(spec, library, &flow, progress).with_cancel(cancel);
    let mut layers = Vec::with_capacity(spec.layers.len());
    for (index, (layer, id)) in spec.layers.iter().zip(&ids).enumerate() {
        layers.push(build_layer((index, layer), id, &mut cx, cancel)?);
    }
    cx.adjust().apply_to_groups(&mut layers)?;
    let (notes, models) = cx.finish()?;
    let mut pens: Vec<Pen> = spec
        .pens
        .iter()
        .map(|p| Pen {
            number: p.number,
            name: p.name.clone(),
            color: Color::parse_in(&p.color, spec.palette()).unwrap_or(Color::BLACK),
            width: p.width,
        })
        .collect();
    pens.sort_by_key(|p| p.number);
    let scene = Scene {
        page: spec.page(),
        pens,
        layers,
        description: Some(spec.to_toml()),
    };
    Ok((scene, notes, models))
}

/// Builds layer `index` of the description, with SVG id `id`.
fn build_layer<'a>(
    (index, layer): (usize, &'a LayerSpec),
    id: &'a str,
    cx: &mut Context<'a>,
    cancel: &Cancel,
) -> Result<Layer> {
    let depth = layer.depth.unwrap_or(index as i32);
    cx.enter_layer((index, layer), id, depth);
    let mut content = Group::new(format!("{id}.motifs"));
    for item in layer.items() {
        cancel.check()?;
        let group = crate::family::build(&item, cx)?;
        let segments = group.segment_count();
        cx.budget()
            .take_segments(segments, || format!("`{}`", group.id))?;
        content.push_group(group);
    }
    Ok(Layer {
        id: id.to_string(),
        name: layer.name.clone(),
        pen: layer.pen,
        depth,
        content,
    })
}

/// The sites the `[[layers.voronoi]]` table `layers[layer].voronoi[table]`
/// starts from, before relaxation: the sites it spreads, or the given
/// points it keeps (those inside its region, each once). Millimetres from
/// the top left corner inside the margins, as every point of a
/// description; in the order the dots' ids `site-<i>` count them.
///
/// Written back as the table's `sites.points` ([`VoronoiSpec::pinned`]),
/// they draw the same: the SVG is the same, byte for byte, but for the
/// description it embeds. So a designer can pin the sites a distribution
/// spread, then drag them one by one.
///
/// Only the table's sites are made, and the layers before it only when it
/// fills their regions (`region.layer`).
///
/// ```
/// let template = moyo::templates::get("voronoi-stained-glass")?;
/// let (spec, library) = (template.spec()?, template.library()?);
/// let sites = moyo::project::voronoi_sites(&spec, &library, 0, 0)?;
/// let pinned = spec.edit(|s| {
///     let table = &mut s.layers[0].voronoi[0];
///     *table = table.pinned(sites.clone());
/// })?;
/// assert_eq!(moyo::project::voronoi_sites(&pinned, &library, 0, 0)?, sites);
/// # Ok::<(), moyo::Error>(())
/// ```
///
/// # Errors
/// [`Error::Invalid`] naming `layers[layer].voronoi[table]` when the
/// description has no such table; otherwise what rendering reports up to
/// that table's sites (its region, its image, given points none of which
/// lies inside), with the line and column when the description came from
/// TOML.
pub fn voronoi_sites(
    spec: &ValidSpec,
    library: &Library,
    layer: usize,
    table: usize,
) -> Result<Points> {
    let field = format!("voronoi[{table}]");
    let found = spec.layers.get(layer).and_then(|l| {
        let item = l.items().into_iter().find(|item| item.field == field)?;
        match item.table {
            Table::Voronoi(v) => Some((l, item, v)),
            _ => None,
        }
    });
    let Some((layer_spec, item, voronoi)) = found else {
        return Err(Error::invalid(
            format!("layers[{layer}].{field}"),
            "the description has no such voronoi table",
        ));
    };
    let sites = table_sites(spec, library, (layer, layer_spec), &item, voronoi)
        .map_err(|e| spec.locate(e))?;
    Ok(sites.into_iter().map(|p| [p.x, p.y]).collect())
}

/// [`voronoi_sites`] of the table `item`, `voronoi`, of layer `index`.
fn table_sites(
    spec: &ValidSpec,
    library: &Library,
    (index, layer): (usize, &LayerSpec),
    item: &LayerItem<'_>,
    voronoi: &VoronoiSpec,
) -> Result<Vec<Point>> {
    let flow = Flow::new(&spec.lines);
    let ids = layer_ids(spec)?;
    let mut quiet = |_| {};
    let mut cx = Context::new(spec, library, &flow, &mut quiet);
    // The regions a table fills come from the layers built before it.
    if !item.table.family().layers_read().is_empty() {
        for (i, (earlier, id)) in spec.layers.iter().zip(&ids).enumerate().take(index) {
            build_layer((i, earlier), id, &mut cx, Cancel::never())?;
        }
    }
    let depth = layer.depth.unwrap_or(index as i32);
    cx.enter_layer((index, layer), &ids[index], depth);
    crate::family::voronoi_sites(item, voronoi, &mut cx)
}

/// Stable, unique, SVG-safe ids for the layers, made from their names: a
/// slug, and when it is taken, the slug with the first free `-2`, `-3`, …
/// ([`UniqueIds`]).
fn layer_ids(spec: &ValidSpec) -> Result<Vec<String>> {
    ids_of(spec.layers.iter().map(|l| l.name.as_str()))
}

/// [`layer_ids`] of these names.
fn ids_of<'a>(names: impl Iterator<Item = &'a str>) -> Result<Vec<String>> {
    let mut ids = UniqueIds::default();
    names
        .map(|name| {
            crate::cancel::checkpoint()?;
            let mut slug: String = name
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
            Ok(ids.unique(&slug))
        })
        .collect()
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
    /// The SVG to plot: only what pens draw (see [`crate::output::to_svg`]);
    /// the colour preview is [`Rendered::preview_svg`].
    pub svg: String,
    /// What the generators noted (how relaxations converged…), in scene
    /// order.
    pub notes: Vec<Note>,
    /// The 3D models the generators made (a vine and its supports), for
    /// [`crate::output::to_obj`]; empty for a flat scene.
    pub models: Vec<Model>,
    /// The options `svg` was written with.
    options: SvgOptions,
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
    render_cancellable(spec, library, progress, Cancel::never())
}

/// [`render_with_progress`] that stops with [`Error::Cancelled`] soon
/// after `cancel` is raised: between tables, whenever a generator takes
/// paths from the budget, inside the long loops (layer ids, rewriting an
/// L-system word, placing and relaxing sites and the density formulas
/// they evaluate, zentangle steps), between the plot stages and inside
/// hidden-line removal, and before the SVG. A flag with a memory budget
/// ([`Cancel::with_memory_limit`]) stops it at the same places with
/// [`Error::MemoryBudget`].
///
/// # Errors
/// As [`render_with_progress`], [`Error::Cancelled`] and
/// [`Error::MemoryBudget`].
pub fn render_cancellable(
    spec: &ValidSpec,
    library: &Library,
    progress: &mut dyn FnMut(Progress),
    cancel: &Cancel,
) -> Result<Rendered> {
    render_through(spec, library, progress, cancel, &spec.plot.options())
}

/// [`render_cancellable`] without the stages that make one flat layer per
/// pen (the pen stage among them: [`PlotOptions::keeping_groups`]): the
/// scene keeps the description's layers, every table's group and every
/// id, so that each part of the drawing can be found and pointed at, as the
/// studio does. Its SVG is a preview of the design, not what a pen should
/// draw: [`Rendered::pen_ready`] makes that.
///
/// # Errors
/// As [`render_cancellable`].
pub fn render_for_editing(
    spec: &ValidSpec,
    library: &Library,
    progress: &mut dyn FnMut(Progress),
    cancel: &Cancel,
) -> Result<Rendered> {
    let stages = spec.plot.options().keeping_groups();
    render_through(spec, library, progress, cancel, &stages)
}

/// Builds the scene and runs `stages` on it.
fn render_through(
    spec: &ValidSpec,
    library: &Library,
    progress: &mut dyn FnMut(Progress),
    cancel: &Cancel,
    stages: &PlotOptions,
) -> Result<Rendered> {
    // The loops deep inside (site placement, relaxation, rewriting…)
    // check this flag, and the memory budget, through
    // `crate::cancel::checkpoint`.
    let _entered = cancel.enter();
    let (scene, notes, models) =
        build(spec, library, progress, cancel).map_err(|e| spec.locate(e))?;
    cancel.check()?;
    let scene = plot::run_cancellable(scene, stages, cancel)?;
    cancel.check()?;
    let options = svg_options(spec);
    let svg = to_svg(&scene, &options);
    // Written in full unless the render was called off meanwhile; and the
    // memory's peak so far read, whenever it was last.
    cancel.check_now()?;
    Ok(Rendered {
        scene,
        svg,
        notes,
        models,
        options,
    })
}

impl Rendered {
    /// Path count and pen-down length of [`Rendered::svg`] as written: the
    /// coordinates rounded to its precision, as a program reading the SVG
    /// (`moyo stats`, vpype) measures them.
    pub fn stats(&self) -> Stats {
        self.scene.stats_at_precision(self.options.precision)
    }

    /// What [`render_cancellable`] makes of `spec`, from this render of
    /// it by [`render_for_editing`]: the stages that render left out (the
    /// pen stage) run on its scene.
    ///
    /// # Errors
    /// As [`plot::run`].
    pub fn pen_ready(&self, spec: &ValidSpec) -> Result<Rendered> {
        let all = spec.plot.options();
        let rest = PlotOptions {
            transform: None,
            occlude: None,
            hatch: None,
            ..all
        };
        let scene = plot::run(self.scene.clone(), &rest)?;
        let svg = to_svg(&scene, &self.options);
        Ok(Rendered {
            scene,
            svg,
            notes: self.notes.clone(),
            models: self.models.clone(),
            options: self.options,
        })
    }

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layer_ids_are_unique_slugs_numbered_in_order() {
        let names = ["Front", "front", "front-2", "2nd", "front", "桜", "梅"];
        assert_eq!(
            ids_of(names.into_iter()).unwrap(),
            [
                "front",
                "front-2",
                "front-2-2",
                "layer-2nd",
                "front-3",
                "layer--",
                "layer---2"
            ]
        );
    }

    /// 40,000 names that make one slug (they differ only in characters
    /// that are not ASCII): ten times the count that took 77 s when every
    /// id was searched for in a list from `-2` up.
    #[test]
    fn many_names_of_one_slug_stay_linear() {
        let names: Vec<String> = (0..40_000u32)
            .map(|i| char::from_u32(0x4E00 + i % 20_000).unwrap().to_string() + "葉")
            .collect();
        let ids = ids_of(names.iter().map(String::as_str)).unwrap();
        let unique: std::collections::HashSet<&String> = ids.iter().collect();
        assert_eq!(unique.len(), ids.len());
        assert_eq!(ids[39_999], "layer----40000");
    }

    #[test]
    fn layer_ids_stop_when_the_render_is_called_off() {
        let cancel = Cancel::default();
        cancel.raise();
        let _entered = cancel.enter();
        let names = ["a"; 10];
        assert!(matches!(ids_of(names.into_iter()), Err(Error::Cancelled)));
    }
}
