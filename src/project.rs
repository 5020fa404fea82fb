//! The facade: scene description → scene → SVG / PNG / path dump; and any
//! SVG through the plot stages ([`plot_scene`]) or filled with a pattern
//! ([`fill_scene`]).
//!
//! This is the one place that knows the order of the stages; the CLI calls
//! only these functions. It is also where user motifs are read from their
//! SVG files ([`load_motifs`]), since generators never touch files.

use std::path::Path;

use kurbo::BezPath;

use crate::error::{Cause, Error, Result};
use crate::geom::mesh::TriMesh;
use crate::input::{decode_image, import_svg, ImportOptions};
use crate::motif::{user_drawing, Library};
use crate::motif::{Context, Flow};
use crate::output::{path_dump, render_png, to_svg, SvgOptions};
use crate::plot;
use crate::scene::{Color, Group, Layer, Model, Pen, Scene};
use crate::spec::{LayerItem, LayerSpec, MotifRef, Points, Table, ValidSpec, VoronoiSpec};

pub use crate::cancel::Cancel;
pub use crate::motif::{Note, Progress};

mod fill;

pub use fill::{fill_scene, FillJob, FillPattern, Filled};

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
        (path.display().to_string(), crate::input::read_file(&path))
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
    let open = |name: &str| {
        let (shown, bytes) = read(name);
        match bytes {
            Ok(bytes) => Ok((shown, bytes)),
            Err(e) => Err(unusable(name, format!("cannot read {shown}"), e.into())),
        }
    };
    for name in &files.motifs {
        let (shown, bytes) = open(name)?;
        let paths = svg_paths(name, &shown, &bytes)?;
        let drawing = user_drawing(&paths).map_err(|m| Error::Motif {
            name: name.clone(),
            message: format!("{shown}: {m}"),
            source: None,
        })?;
        library.add_user(name.clone(), drawing);
    }
    for name in &files.paths {
        let (shown, bytes) = open(name)?;
        let mut joined = BezPath::new();
        for p in svg_paths(name, &shown, &bytes)? {
            joined.extend(p.elements().iter().copied());
        }
        library.add_paths(name.clone(), joined);
    }
    for name in &files.images {
        let (shown, bytes) = open(name)?;
        let image = decode_image(&bytes).map_err(|e| unusable(name, shown, e.into()))?;
        library.add_image(name.clone(), image);
    }
    for name in &files.meshes {
        let (shown, bytes) = open(name)?;
        let text = std::str::from_utf8(&bytes)
            .map_err(|e| unusable(name, format!("{shown} is not UTF-8 text"), e.into()))?;
        let mesh = TriMesh::parse_obj(text, &shown)
            .and_then(|m| m.check_closed(&shown).map(|()| m))
            .map_err(|e| Error::Motif {
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
fn unusable(name: &str, message: String, cause: Cause) -> Error {
    Error::Motif {
        name: name.to_string(),
        message: format!("{message}: {cause}"),
        source: Some(cause),
    }
}

/// The paths of the SVG file `name` (shown as `shown`), in its mm.
fn svg_paths(name: &str, shown: &str, bytes: &[u8]) -> Result<Vec<BezPath>> {
    let text = std::str::from_utf8(bytes)
        .map_err(|e| unusable(name, format!("{shown} is not UTF-8 text"), e.into()))?;
    let imported = import_svg(text, &ImportOptions::DEFAULT)
        .map_err(|e| unusable(name, shown.to_string(), e.into()))?;
    let mut paths: Vec<BezPath> = Vec::new();
    imported
        .scene
        .visit_paths(|_, p, t| paths.push(t * p.path.clone()));
    Ok(paths)
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
    build(spec, library, progress, Cancel::never())
        .map(|(scene, _, _)| scene)
        .map_err(|e| spec.locate(e))
}

/// The scene, the generators' notes and their 3D models.
fn build(
    spec: &ValidSpec,
    library: &Library,
    progress: &mut dyn FnMut(Progress),
    cancel: &Cancel,
) -> Result<(Scene, Vec<Note>, Vec<Model>)> {
    let flow = Flow::new(&spec.lines);
    let ids = layer_ids(spec);
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
    let ids = layer_ids(spec);
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
/// paths from the budget, between the plot stages and inside hidden-line
/// removal, and before the SVG.
///
/// # Errors
/// As [`render_with_progress`], and [`Error::Cancelled`].
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
    let (scene, notes, models) =
        build(spec, library, progress, cancel).map_err(|e| spec.locate(e))?;
    cancel.check()?;
    let scene = plot::run_cancellable(scene, stages, cancel)?;
    cancel.check()?;
    let options = svg_options(spec);
    let svg = to_svg(&scene, &options);
    Ok(Rendered {
        scene,
        svg,
        notes,
        models,
        options,
    })
}

impl Rendered {
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

// ---------------------------------------------------------------------------
// Plotting any SVG: `moyo plot` and `moyo stats`. (Its imports are kept with
// it, apart from the ones above, while the rest of this file is rewritten.)

use kurbo::Point;

use crate::input::Imported;
use crate::output::gcode::{to_gcode, GcodeOptions};
use crate::output::hpgl::{to_hpgl, HpglOptions};
use crate::plot::PlotOptions;
use crate::scene::Style;

/// Reads the SVG file at `path` into a scene (see
/// [`import_svg`] for the mapping), with the warnings of the import.
///
/// # Errors
/// [`Error::Io`] when the file cannot be read; [`Error::File`] naming the
/// file around the import's error.
pub fn read_svg(path: &Path, options: &ImportOptions) -> Result<Imported> {
    let text = crate::input::read_text(path).map_err(|e| Error::io(path, e))?;
    import_svg(&text, options).map_err(|e| Error::File {
        path: path.to_path_buf(),
        source: Box::new(e),
    })
}

/// The output of [`plot_scene`], with its options.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq)]
pub enum PlotFormat {
    /// Layered SVG ([`to_svg`]).
    Svg(SvgOptions),
    /// A G-code program ([`to_gcode`]).
    Gcode(GcodeOptions),
    /// HPGL ([`to_hpgl`]).
    Hpgl(HpglOptions),
}

/// A PNG preview of a plotted scene.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Preview {
    /// Resolution, dots per inch (see [`render_png`]).
    pub dpi: f64,
    /// Draw every pen-up move as a red line over the drawing, in the order
    /// [`plot::stats()`] counts them (each pen from the origin). The output
    /// itself never has them.
    pub show_travel: bool,
}

impl Preview {
    /// 150 dpi, without travel.
    pub const DEFAULT: Preview = Preview {
        dpi: 150.0,
        show_travel: false,
    };

    /// This preview at `dpi` dots per inch.
    pub const fn with_dpi(mut self, dpi: f64) -> Preview {
        self.dpi = dpi;
        self
    }

    /// This preview with pen-up travel drawn or not.
    pub const fn with_show_travel(mut self, show_travel: bool) -> Preview {
        self.show_travel = show_travel;
        self
    }
}

impl Default for Preview {
    fn default() -> Preview {
        Preview::DEFAULT
    }
}

/// What [`plot_scene`] does with a drawing: the plot stages, the output
/// format and an optional preview.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq)]
pub struct PlotJob {
    /// How the SVG is read ([`read_svg`]). Default [`ImportOptions::DEFAULT`].
    pub import: ImportOptions,
    /// The plot stages. Default none.
    pub stages: PlotOptions,
    /// Before the stages, take every group of paths as one solid shape
    /// ([`plot::occlude::mark_path_groups_solid`]): an imported drawing
    /// carries no solid marks, so this is how occlusion sees whole trees
    /// as silhouettes. Default off.
    pub silhouettes: bool,
    /// The output.
    pub format: PlotFormat,
    /// A PNG preview of the result. Default none.
    pub preview: Option<Preview>,
}

impl PlotJob {
    /// A job that writes `format` with no stages and no preview.
    pub fn new(format: PlotFormat) -> PlotJob {
        PlotJob {
            import: ImportOptions::DEFAULT,
            stages: PlotOptions::default(),
            silhouettes: false,
            format,
            preview: None,
        }
    }

    /// This job reading SVG with `import`.
    pub fn with_import(mut self, import: ImportOptions) -> PlotJob {
        self.import = import;
        self
    }

    /// This job with these plot stages.
    pub fn with_stages(mut self, stages: PlotOptions) -> PlotJob {
        self.stages = stages;
        self
    }

    /// This job with silhouettes marked or not.
    pub fn with_silhouettes(mut self, silhouettes: bool) -> PlotJob {
        self.silhouettes = silhouettes;
        self
    }

    /// This job with a preview (`None`: none).
    pub fn with_preview(mut self, preview: Option<Preview>) -> PlotJob {
        self.preview = preview;
        self
    }
}

/// Everything [`plot_scene`] produces, in memory: nothing is written
/// before all of it is computed.
#[non_exhaustive]
#[derive(Debug, Clone)]
pub struct Plotted {
    /// The scene after the plot stages.
    pub scene: Scene,
    /// The output in the job's format.
    pub bytes: String,
    /// The PNG preview, when the job asks for one.
    pub png: Option<Vec<u8>>,
}

impl Plotted {
    /// The colour preview SVG of the result, numbers written with
    /// `precision` decimals: the plotted pens plus preview fills and `%`
    /// layers, for looking at, not for plotting.
    pub fn preview_svg(&self, precision: u8) -> String {
        to_svg(&self.scene, &SvgOptions::PREVIEW.with_precision(precision))
    }
}

/// Runs a drawing (typically from [`read_svg`]) through the job: marks
/// silhouettes when asked, runs the plot stages, writes the output and
/// renders the preview.
///
/// ```
/// use moyo::output::hpgl::HpglOptions;
/// use moyo::plot::{MergeOptions, PlotOptions, SortOptions};
/// use moyo::{import_svg, plot_scene, ImportOptions, PlotFormat, PlotJob};
///
/// // Two strokes that meet end to end, drawn in the wrong order.
/// let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="50mm"
///     viewBox="0 0 100 50">
///   <path d="M 90 10 L 50 10" stroke="black" fill="none"/>
///   <path d="M 10 10 L 50 10" stroke="black" fill="none"/>
/// </svg>"#;
/// let drawing = import_svg(svg, &ImportOptions::DEFAULT)?.scene;
/// let stages = PlotOptions {
///     merge: Some(MergeOptions::DEFAULT),
///     sort: Some(SortOptions::DEFAULT),
///     ..PlotOptions::default()
/// };
/// let job = PlotJob::new(PlotFormat::Hpgl(HpglOptions::DEFAULT)).with_stages(stages);
/// let plotted = plot_scene(drawing, &job)?;
/// // Merged into one stroke: the pen goes down once.
/// assert_eq!(plotted.scene.path_count(), 1);
/// assert_eq!(plotted.bytes.matches("PD").count(), 1);
/// # Ok::<(), moyo::Error>(())
/// ```
///
/// # Errors
/// [`Error::Invalid`] for bad stage or format options; the stages' errors
/// (see [`plot::run`]); [`Error::DeviceRange`] for HPGL beyond the device;
/// [`Error::Preview`] when the preview cannot be rendered.
pub fn plot_scene(mut scene: Scene, job: &PlotJob) -> Result<Plotted> {
    if job.silhouettes {
        plot::occlude::mark_path_groups_solid(&mut scene);
    }
    let scene = plot::run(scene, &job.stages)?;
    let bytes = match &job.format {
        PlotFormat::Svg(o) => to_svg(&scene, o),
        PlotFormat::Gcode(o) => {
            o.validate()?;
            to_gcode(&scene, o)
        }
        PlotFormat::Hpgl(o) => {
            o.validate()?;
            to_hpgl(&scene, o)?
        }
    };
    let png = match job.preview {
        Some(p) => {
            let svg = if p.show_travel {
                to_svg(&with_travel(&scene), &SvgOptions::PREVIEW)
            } else {
                to_svg(&scene, &SvgOptions::PREVIEW)
            };
            Some(render_png(&svg, p.dpi)?)
        }
        None => None,
    };
    Ok(Plotted { scene, bytes, png })
}

/// The scene with one more layer: red lines along every pen-up move, in
/// the order [`plot::stats()`] counts them (each pen from the origin).
fn with_travel(scene: &Scene) -> Scene {
    let flat = plot::flatten::by_pen(scene);
    let mut travel = BezPath::new();
    for layer in flat.layers.iter().filter(|l| l.is_plotted()) {
        let mut at = Point::ZERO;
        layer
            .content
            .visit_paths(kurbo::Affine::IDENTITY, &mut |p, t| {
                let path = t * p.path.clone();
                for sub in crate::geom::subpath::subpaths(&path) {
                    travel.move_to(at);
                    travel.line_to(sub.start());
                    at = sub.end();
                }
            });
    }
    let number = flat.pens.iter().map(|p| p.number).max().unwrap_or(0) + 1;
    let mut out = flat;
    out.pens.push(Pen {
        number,
        name: "travel".into(),
        color: Color::rgb(230, 40, 40),
        width: 0.15,
    });
    let mut content = Group::new("travel.paths");
    content.push_path("travel", travel, Style::default());
    out.layers.push(Layer {
        id: "travel".into(),
        name: "travel".into(),
        pen: number,
        depth: -1,
        content,
    });
    out
}

#[cfg(test)]
mod plot_tests {
    use super::*;
    use crate::output::hpgl::HPGL2_RANGE;

    const SVG: &str = r##"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="50mm" viewBox="0 0 100 50">
        <path id="line" d="M 10 25 L 90 25" stroke="#000" fill="none"/>
        <rect id="box" x="40" y="10" width="20" height="30" fill="#888" stroke="#000"/>
    </svg>"##;

    fn drawing() -> Scene {
        import_svg(SVG, &ImportOptions::DEFAULT).unwrap().scene
    }

    #[test]
    fn read_svg_names_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("missing.svg");
        let e = read_svg(&missing, &ImportOptions::DEFAULT).unwrap_err();
        assert!(matches!(e, Error::Io { .. }), "{e:?}");
        let broken = dir.path().join("broken.svg");
        std::fs::write(&broken, "<svg><g></svg").unwrap();
        let e = read_svg(&broken, &ImportOptions::DEFAULT).unwrap_err();
        assert!(
            matches!(&e, Error::File { source, .. } if matches!(**source, Error::Parse { .. }))
        );
        assert!(
            e.to_string()
                .starts_with(&format!("{}: 1:", broken.display())),
            "{e}"
        );
        let good = dir.path().join("good.svg");
        std::fs::write(&good, SVG).unwrap();
        let imported = read_svg(&good, &ImportOptions::DEFAULT).unwrap();
        assert_eq!(imported.scene.path_count(), 2);
    }

    #[test]
    fn plot_scene_writes_what_the_writers_write() {
        let stages = PlotOptions {
            sort: Some(plot::SortOptions::DEFAULT),
            ..PlotOptions::default()
        };
        let plotted_scene = plot::run(drawing(), &stages).unwrap();
        let formats = [
            PlotFormat::Svg(SvgOptions::DEFAULT.with_precision(2)),
            PlotFormat::Gcode(GcodeOptions::default()),
            PlotFormat::Hpgl(HpglOptions::CUTTER),
        ];
        for format in formats {
            let job = PlotJob::new(format.clone()).with_stages(stages.clone());
            let plotted = plot_scene(drawing(), &job).unwrap();
            let expected = match &format {
                PlotFormat::Svg(o) => to_svg(&plotted_scene, o),
                PlotFormat::Gcode(o) => to_gcode(&plotted_scene, o),
                PlotFormat::Hpgl(o) => to_hpgl(&plotted_scene, o).unwrap(),
            };
            assert_eq!(plotted.bytes, expected);
            assert!(plotted.png.is_none());
        }
    }

    #[test]
    fn plot_scene_previews_and_checks_the_format() {
        let job = PlotJob::new(PlotFormat::Svg(SvgOptions::DEFAULT))
            .with_preview(Some(Preview::DEFAULT.with_dpi(20.0).with_show_travel(true)));
        let png = plot_scene(drawing(), &job).unwrap().png.unwrap();
        assert!(png.starts_with(b"\x89PNG"));
        // Travel is drawn on the preview only: one more pen there.
        let travel = with_travel(&drawing());
        assert_eq!(travel.pens.len(), drawing().pens.len() + 1);
        assert_eq!(travel.layers.last().unwrap().name, "travel");

        let bad = PlotJob::new(PlotFormat::Gcode(
            GcodeOptions::default().with_feed_down_mm_min(0.0),
        ));
        let e = plot_scene(drawing(), &bad).unwrap_err();
        assert!(e.to_string().starts_with("gcode.feed_down_mm_min"), "{e}");
        let narrow = PlotJob::new(PlotFormat::Hpgl(
            HpglOptions::DEFAULT.with_device_range(0, 1000),
        ));
        let e = plot_scene(drawing(), &narrow).unwrap_err();
        assert!(matches!(e, Error::DeviceRange { .. }), "{e:?}");
        let wide = PlotJob::new(PlotFormat::Hpgl(
            HpglOptions::DEFAULT.with_device_range(HPGL2_RANGE[0], HPGL2_RANGE[1]),
        ));
        assert!(plot_scene(drawing(), &wide).is_ok());
    }

    #[test]
    fn silhouettes_mark_groups_of_paths_solid() {
        let mut scene = drawing();
        let mut tree = Group::new("tree");
        tree.push_path(
            "leaf",
            kurbo::Shape::to_path(&kurbo::Rect::new(1.0, 1.0, 5.0, 5.0), 0.1),
            Style::default(),
        );
        scene.layers[0].content.push_group(tree);
        let solid = |silhouettes| {
            let job =
                PlotJob::new(PlotFormat::Svg(SvgOptions::DEFAULT)).with_silhouettes(silhouettes);
            let plotted = plot_scene(scene.clone(), &job).unwrap().scene;
            plotted.layers[0]
                .content
                .children
                .iter()
                .any(|n| matches!(n, crate::scene::Node::Group(g) if g.solid))
        };
        assert!(solid(true));
        assert!(!solid(false));
    }
}
