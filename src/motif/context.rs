//! [`Context`]: what every generator is handed, whatever its family.
//!
//! It carries the scene's seed (each motif derives its own stream from its
//! id, so editing one part leaves the others as they were), the motif
//! library, the overall flow, the layer being built (its description, id
//! and depth), the path budget, the final adjustments by id, progress,
//! and the regions earlier layers drew for later ones to fill.
//! With it no generator needs more than a handful of arguments, and a new
//! family gets all of this by taking a `&mut Context`.

use std::collections::{BTreeMap, BTreeSet};

use super::adjust::Adjustments;
use super::flora::Library;
use super::flow::Flow;
use crate::error::Result;
use crate::geom::region::Region;
use crate::rng::{RandomStream, Seed};
use crate::scene::traditional::Palette;
use crate::scene::{Model, PathBudget};
use crate::spec::{LayerSpec, PenSpec, ValidSpec};
use crate::units::Page;

/// How far generation has come, in work units of any family (a tree, a
/// cell, a plant; see `Family::work`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Progress {
    /// Units done so far.
    pub done: usize,
    /// Units in the scene.
    pub total: usize,
}

/// Something a generator found worth telling the user that is not part
/// of the drawing: how a relaxation converged, say.
#[derive(Debug, Clone, PartialEq)]
pub struct Note {
    /// Id of the motif's group (`<layer>.<table>`).
    pub motif: String,
    /// What it says, one line.
    pub text: String,
}

/// The layer being built.
#[derive(Debug, Clone, Copy)]
struct Frame<'a> {
    spec: &'a LayerSpec,
    id: &'a str,
    depth: i32,
    index: usize,
}

/// What every generator needs (see the module docs).
pub(crate) struct Context<'a> {
    seed: Seed,
    page: Page,
    library: &'a Library,
    flow: &'a Flow,
    layer: Option<Frame<'a>>,
    /// The field path of the table being built, below its layer.
    item: String,
    budget: PathBudget,
    cancel: &'a crate::cancel::Cancel,
    adjust: Adjustments<'a>,
    progress: Progress,
    report: &'a mut dyn FnMut(Progress),
    notes: Vec<Note>,
    models: Vec<Model>,
    pens: &'a [PenSpec],
    palette: &'static Palette,
    /// The names of the layers whose regions a later table fills.
    read: BTreeSet<&'a str>,
    /// The regions those layers drew, by layer name, as they were built.
    offered: BTreeMap<&'a str, Vec<Region>>,
}

impl<'a> Context<'a> {
    /// The context of a whole scene: `report` hears of every unit of work
    /// done, out of the total the description's tables declare.
    pub(crate) fn new(
        spec: &'a ValidSpec,
        library: &'a Library,
        flow: &'a Flow,
        report: &'a mut dyn FnMut(Progress),
    ) -> Context<'a> {
        let total = spec
            .layers
            .iter()
            .flat_map(LayerSpec::items)
            .map(|item| item.table.family().work())
            .sum();
        Context {
            seed: Seed(spec.seed),
            page: spec.page(),
            library,
            flow,
            layer: None,
            item: String::new(),
            budget: PathBudget::new(spec.limits.max_paths).with_segments(spec.limits.max_segments),
            cancel: crate::cancel::Cancel::never(),
            adjust: Adjustments::new(&spec.adjust),
            progress: Progress { done: 0, total },
            report,
            notes: Vec::new(),
            models: Vec::new(),
            pens: &spec.pens,
            palette: spec.palette(),
            read: spec
                .layers
                .iter()
                .flat_map(LayerSpec::items)
                .flat_map(|item| item.table.family().layers_read())
                .map(|(_, name)| name)
                .collect(),
            offered: BTreeMap::new(),
        }
    }

    /// Starts building layer `index` of the description, with SVG id `id`
    /// at `depth`.
    pub(crate) fn enter_layer(
        &mut self,
        (index, spec): (usize, &'a LayerSpec),
        id: &'a str,
        depth: i32,
    ) {
        self.layer = Some(Frame {
            spec,
            id,
            depth,
            index,
        });
    }

    /// Starts building the table at field path `field` of the layer
    /// (`trees[0]`).
    pub(crate) fn enter_item(&mut self, field: &str) {
        self.item = field.to_string();
    }

    /// The full field path of `name` in the table being built
    /// (`layers[1].paths[0].width`), for errors found while generating.
    pub(crate) fn field(&self, name: &str) -> String {
        format!("{}.{name}", self.item_field())
    }

    /// The full field path of the table being built (`layers[1].paths[0]`).
    pub(crate) fn item_field(&self) -> String {
        format!("layers[{}].{}", self.frame().index, self.item)
    }

    /// The page the scene is drawn on (its drawable area is inside the
    /// margins).
    pub(crate) fn page(&self) -> Page {
        self.page
    }

    /// The random stream of the motif with id `id` (a full SVG id): the
    /// same id always gets the same stream.
    pub(crate) fn stream(&self, id: &str) -> RandomStream {
        self.seed.derive(id).stream()
    }

    /// The width (mm) of the pen the current layer draws with (0.3 when
    /// the description names no such pen).
    pub(crate) fn pen_width(&self) -> f64 {
        let number = self.layer.map(|f| f.spec.pen);
        self.pens
            .iter()
            .find(|p| Some(p.number) == number)
            .map_or(0.3, |p| p.width)
    }

    /// The palette whose colours `@1`–`@5` name.
    pub(crate) fn palette(&self) -> &'static Palette {
        self.palette
    }

    /// Built-in and loaded user motifs and paths.
    pub(crate) fn library(&self) -> &'a Library {
        self.library
    }

    /// The overall flow (region lines).
    pub(crate) fn flow(&self) -> &'a Flow {
        self.flow
    }

    /// The description of the layer being built.
    ///
    pub(crate) fn layer(&self) -> &'a LayerSpec {
        self.frame().spec
    }

    /// The SVG id of the layer being built.
    pub(crate) fn layer_id(&self) -> &'a str {
        self.frame().id
    }

    /// The depth of the layer being built (0 front, larger further back).
    pub(crate) fn depth(&self) -> i32 {
        self.frame().depth
    }

    fn frame(&self) -> Frame<'a> {
        self.layer
            .expect("Context::enter_layer is called before any layer is built")
    }

    /// The scene's path budget.
    pub(crate) fn budget(&mut self) -> &mut PathBudget {
        &mut self.budget
    }

    /// Takes `n` paths from the budget; `what` names them in the error.
    ///
    /// # Errors
    /// [`crate::Error::Budget`] when the scene would exceed its limit.
    pub(crate) fn take_paths(&mut self, n: usize, what: impl FnOnce() -> String) -> Result<()> {
        // Generators take paths often and before their work: the place to
        // notice that the render was called off.
        self.cancel.check()?;
        self.budget.take(n, what)
    }

    /// The same context, called off when `cancel` is raised.
    pub(crate) fn with_cancel(self, cancel: &'a crate::cancel::Cancel) -> Context<'a> {
        Context { cancel, ..self }
    }

    /// The final adjustments by id.
    pub(crate) fn adjust(&mut self) -> &mut Adjustments<'a> {
        &mut self.adjust
    }

    /// Reports `units` more units of work done.
    pub(crate) fn advance(&mut self, units: usize) {
        if units > 0 {
            self.progress.done = (self.progress.done + units).min(self.progress.total);
            (self.report)(self.progress);
        }
    }

    /// Units done so far.
    pub(crate) fn done(&self) -> usize {
        self.progress.done
    }

    /// Brings the count to `done` when a generator reported fewer units
    /// than its table declared (work it skipped).
    pub(crate) fn advance_to(&mut self, done: usize) {
        if done > self.progress.done {
            self.advance(done - self.progress.done);
        }
    }

    /// Whether a later table fills the regions this layer draws: a
    /// family that offers regions hands them to [`Context::offer`] only
    /// then, as finding them may cost work its drawing does not need.
    pub(crate) fn regions_wanted(&self) -> bool {
        self.read.contains(self.frame().spec.name.as_str())
    }

    /// Adds regions the current layer drew (cells, a mask) for later
    /// layers to fill.
    pub(crate) fn offer(&mut self, regions: impl IntoIterator<Item = Region>) {
        let name = self.frame().spec.name.as_str();
        self.offered.entry(name).or_default().extend(regions);
    }

    /// The regions the layer named `layer` offered (none when it has not
    /// been built yet).
    pub(crate) fn offered(&self, layer: &str) -> &[Region] {
        self.offered.get(layer).map_or(&[], Vec::as_slice)
    }

    /// Tells the user `text` about the motif `motif` (its group id).
    pub(crate) fn note(&mut self, motif: &str, text: impl Into<String>) {
        self.notes.push(Note {
            motif: motif.to_string(),
            text: text.into(),
        });
    }

    /// Hands on the 3D model a generator made beside its drawing (for
    /// the OBJ export).
    pub(crate) fn model(&mut self, model: Model) {
        self.models.push(model);
    }

    /// Ends the scene: every adjustment must have found its target. Gives
    /// the notes and the 3D models, in the order they were made.
    ///
    /// # Errors
    /// [`crate::Error::Invalid`] naming the first `adjust[i].id` that
    /// matched nothing.
    pub(crate) fn finish(self) -> Result<(Vec<Note>, Vec<Model>)> {
        self.adjust.finish()?;
        Ok((self.notes, self.models))
    }
}
