//! Filling any drawing (`moyo fill`): a pattern of the Voronoi family or a
//! zentangle inside the closed shapes of a drawing, on a pen of its own,
//! the drawing's own lines kept as they are.
//!
//! [`fill_scene`] takes the region a viewer sees painted in the drawing's
//! plotted layers ([`FillRegion`]), describes one
//! `[[layers.voronoi]]` or `[[layers.zentangle]]` table over it in code, and
//! has the family's own generator build it — so a fill draws what that
//! table would in a scene description. The layer it makes is added to the
//! drawing with a pen.

use std::collections::BTreeSet;

use kurbo::{Affine, BezPath};

use super::render::build;
use super::Note;
use crate::error::{Error, Result};
use crate::geom::density::GreyImage;
use crate::geom::path_length;
use crate::geom::region::{FillRule, Region};
use crate::geom::subpath::subpaths;
use crate::motif::Library;
use crate::output::{render_png, to_svg, SvgOptions};
use crate::plot::PlotOptions;
use crate::scene::{Color, Group, Layer, Node, Pen, Scene, Stats};
use crate::spec::{
    Distribution, Draw, LayerSpec, LimitsSpec, Look, MarginSpec, OutputSpec, PageSpec, PaperSize,
    PenSpec, PlotSpec, RegionLinesSpec, RegionSpec, RelaxationMethod, SceneSpec, SitesSpec,
    ValidSpec, VoronoiSpec, ZentangleSpec, DEFAULT_CRACK, FORMAT_VERSION,
};

/// What a fill draws: one of the ways the Voronoi family draws its sites.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FillPattern {
    /// The cells: every edge between two cells once, and the outline of
    /// the region.
    Voronoi,
    /// The Delaunay edges between neighbouring sites inside the region,
    /// chained into long strokes.
    Delaunay,
    /// A dot of ink of radius [`FillJob::dot`] at each site: stippling (a
    /// tap of the pen, or a spiral filling the dot).
    /// Relaxed 10 times unless [`FillJob::relax`] says otherwise.
    Stipple,
    /// One pen-down line through the sites of each separate shape (the pen
    /// lifts between shapes). Relaxed 10 times unless
    /// [`FillJob::relax`] says otherwise.
    Tour,
    /// Each cell as its own closed shape, 0.8 mm in from its edges, corners
    /// rounded by 1 mm: stained glass.
    Glass,
    /// A zentangle: [`FillJob::steps`] steps of the zentangle family's
    /// filling loop (`[[layers.zentangle]]`) inside the shapes.
    Zentangle,
}

impl FillPattern {
    /// Every pattern.
    pub const ALL: [FillPattern; 6] = [
        FillPattern::Voronoi,
        FillPattern::Delaunay,
        FillPattern::Stipple,
        FillPattern::Tour,
        FillPattern::Glass,
        FillPattern::Zentangle,
    ];

    /// Its name on the command line (`glass`).
    pub fn name(self) -> &'static str {
        match self {
            FillPattern::Voronoi => "voronoi",
            FillPattern::Delaunay => "delaunay",
            FillPattern::Stipple => "stipple",
            FillPattern::Tour => "tour",
            FillPattern::Glass => "glass",
            FillPattern::Zentangle => "zentangle",
        }
    }

    /// Lloyd steps when the job does not say: 10 for the patterns drawn
    /// from the sites alone (stipple, tour), whose clumps would show;
    /// none for the others.
    pub fn default_relax(self) -> u32 {
        match self {
            FillPattern::Stipple | FillPattern::Tour => 10,
            FillPattern::Voronoi
            | FillPattern::Delaunay
            | FillPattern::Glass
            | FillPattern::Zentangle => 0,
        }
    }

    /// What the Voronoi family draws for it (`None`: not a Voronoi
    /// pattern).
    fn draw(self) -> Option<Draw> {
        match self {
            FillPattern::Voronoi => Some(Draw::Cells),
            FillPattern::Delaunay => Some(Draw::Delaunay),
            FillPattern::Stipple => Some(Draw::Sites),
            FillPattern::Tour => Some(Draw::Tour),
            FillPattern::Glass => Some(Draw::Inset),
            FillPattern::Zentangle => None,
        }
    }
}

/// What [`fill_scene`] draws and with which pen.
///
/// Errors name the option at fault by these fields' names (`spacing`,
/// `points`, `relax`, `converge`, `density`, `pen`, `dot`, `seed`), and
/// the drawing as `input`.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq)]
pub struct FillJob {
    /// The pattern. Default [`FillPattern::Voronoi`].
    pub pattern: FillPattern,
    /// The seed of the sites (0 – 2^63−1). Default 1.
    pub seed: u64,
    /// Poisson-disk sites this far apart, mm (0.1–10,000). Default
    /// [`FillJob::DEFAULT_SPACING`] unless `points` is given; not both.
    pub spacing: Option<f64>,
    /// This many sites spread uniformly at random (1–1,000,000) instead
    /// of Poisson-disk ones.
    pub points: Option<u32>,
    /// Relaxation steps, at most (0–1000). Default the pattern's
    /// ([`FillPattern::default_relax`]).
    pub relax: Option<u32>,
    /// Relax by weighted Linde-Buzo-Gray instead of Lloyd: sites split
    /// and go until each cell holds one site's worth of density, `spacing`
    /// apart where it is 1 (the count follows the image). Default false.
    pub lbg: bool,
    /// Stop relaxing once a step moves the sites less than this on
    /// average, mm (0.00001–100). Default: every step.
    pub converge: Option<f64>,
    /// Density as a formula of the position (`x`, `y` mm, `u`, `v` 0–1
    /// across the shapes' bounding box; see
    /// [`crate::geom::density::Formula`]), times the image's if both.
    pub density: Option<String>,
    /// With [`FillPattern::Zentangle`] only: filling steps (0–5,000,
    /// default 50).
    pub steps: Option<u32>,
    /// The pen (1–999). Default: the smallest number the drawing does not
    /// use.
    pub pen: Option<u32>,
    /// With [`FillPattern::Stipple`] only: the radius of the dots, mm
    /// (0.05–50, default 0.3).
    pub dot: Option<f64>,
    /// Density: dark parts of the image get more sites and weigh more in
    /// relaxation (weighted Voronoi stippling), the image fitted to the
    /// shapes' bounding box, aspect kept, centred. Default none.
    pub image: Option<GreyImage>,
    /// With [`FillPattern::Voronoi`] and [`FillPattern::Delaunay`]: the
    /// fill's pen draws the shapes' outlines too. Default off: the
    /// drawing's own pen draws them, and a second pen going over them
    /// would draw them twice.
    pub outline: bool,
    /// Run the pen stage ([`PlotOptions::pen_ready`]: no line twice, no
    /// debris, merged and sorted) on the whole drawing for
    /// [`Filled::plotted`]. Default on.
    pub pen_stage: bool,
    /// How the drawing's shapes make the region filled. Default
    /// [`FillRegion::Painted`].
    pub region: FillRegion,
}

/// How [`fill_scene`] reads the drawing's shapes into the region it fills.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FillRegion {
    /// What a viewer sees painted: the filled shapes united, in any paint
    /// order — a shape painted over another covers it, and a shape's hole
    /// is a hole only where nothing else is painted — together with the
    /// closed outlines of unfilled shapes, which are line art: among
    /// themselves an outline inside an outline is a hole (even-odd).
    #[default]
    Painted,
    /// Every closed outline, filled or not, with the even-odd rule: a shape
    /// inside a shape is a hole, so stacked filled shapes cancel.
    EvenOdd,
}

impl FillJob {
    /// Distance between sites when neither `spacing` nor `points` is
    /// given, mm.
    pub const DEFAULT_SPACING: f64 = 5.0;

    /// Voronoi cells, seed 1, everything else by default.
    pub const DEFAULT: FillJob = FillJob {
        pattern: FillPattern::Voronoi,
        seed: 1,
        spacing: None,
        points: None,
        relax: None,
        lbg: false,
        converge: None,
        density: None,
        steps: None,
        pen: None,
        dot: None,
        image: None,
        outline: false,
        pen_stage: true,
        region: FillRegion::Painted,
    };

    /// This job reading the drawing's shapes as `region` says.
    pub const fn with_region(mut self, region: FillRegion) -> FillJob {
        self.region = region;
        self
    }

    /// This job with sites denser where `image` is dark.
    pub fn with_image(mut self, image: GreyImage) -> FillJob {
        self.image = Some(image);
        self
    }

    /// The default job drawing `pattern`.
    pub const fn new(pattern: FillPattern) -> FillJob {
        let mut job = FillJob::DEFAULT;
        job.pattern = pattern;
        job
    }

    /// This job with another seed.
    pub const fn with_seed(mut self, seed: u64) -> FillJob {
        self.seed = seed;
        self
    }

    /// This job with Poisson-disk sites `mm` apart.
    pub const fn with_spacing(mut self, mm: f64) -> FillJob {
        self.spacing = Some(mm);
        self
    }

    /// This job with `n` sites spread uniformly.
    pub const fn with_points(mut self, n: u32) -> FillJob {
        self.points = Some(n);
        self
    }

    /// This job with `steps` Lloyd steps.
    pub const fn with_relax(mut self, steps: u32) -> FillJob {
        self.relax = Some(steps);
        self
    }

    /// This job relaxing by weighted Linde-Buzo-Gray.
    pub const fn with_lbg(mut self) -> FillJob {
        self.lbg = true;
        self
    }

    /// This job stopping relaxation once the sites move less than `mm`.
    pub const fn with_converge(mut self, mm: f64) -> FillJob {
        self.converge = Some(mm);
        self
    }

    /// This job with sites denser where `formula` is high.
    pub fn with_density(mut self, formula: impl Into<String>) -> FillJob {
        self.density = Some(formula.into());
        self
    }

    /// This job's zentangle running `steps` steps.
    pub const fn with_steps(mut self, steps: u32) -> FillJob {
        self.steps = Some(steps);
        self
    }

    /// This job drawing with pen `number`.
    pub const fn with_pen(mut self, number: u32) -> FillJob {
        self.pen = Some(number);
        self
    }

    /// This job's stipple dots with radius `mm`.
    pub const fn with_dot(mut self, mm: f64) -> FillJob {
        self.dot = Some(mm);
        self
    }
}

impl Default for FillJob {
    fn default() -> FillJob {
        FillJob::DEFAULT
    }
}

/// What [`fill_scene`] makes.
#[non_exhaustive]
#[derive(Debug, Clone)]
pub struct Filled {
    /// The drawing, unchanged, plus the fill's layer (the last one).
    pub scene: Scene,
    /// What a pen should draw: [`Filled::scene`] through the pen stage
    /// (one layer per pen) when [`FillJob::pen_stage`] is on, else the same.
    pub plotted: Scene,
    /// The id of the fill's layer.
    pub layer: String,
    /// The pen that draws the fill.
    pub pen: u32,
    /// Whether that pen was added to the drawing's (false: the drawing
    /// had it, and keeps its name, colour and width).
    pub new_pen: bool,
    /// Paths and pen-down length of the fill alone.
    pub fill: Stats,
    /// What the fill's generator noted (how a relaxation converged, how
    /// many zentangle steps ran).
    pub notes: Vec<Note>,
}

impl Filled {
    /// The SVG to plot, numbers written with `precision` decimals (see
    /// [`to_svg`]).
    pub fn svg(&self, precision: u8) -> String {
        to_svg(
            &self.plotted,
            &SvgOptions::DEFAULT.with_precision(precision),
        )
    }

    /// The colour preview SVG: [`Filled::svg`] plus the drawing's fills
    /// and `%` layers, for looking at, not for plotting.
    pub fn preview_svg(&self, precision: u8) -> String {
        to_svg(
            &self.plotted,
            &SvgOptions::PREVIEW.with_precision(precision),
        )
    }

    /// PNG preview at `dpi`, rendered from [`Filled::preview_svg`].
    ///
    /// # Errors
    /// [`Error::Preview`] when it cannot be rendered (see
    /// [`render_png`]).
    pub fn png(&self, dpi: f64) -> Result<Vec<u8>> {
        render_png(&self.preview_svg(SvgOptions::PREVIEW.precision), dpi)
    }
}

/// The name the drawing's closed shapes go by in the library, the
/// description's `region.svg`.
const INPUT: &str = "input";

/// The name the density image goes by in the fill's description.
const IMAGE: &str = "image";

/// The field paths of the description's one table (whichever family).
const TABLES: [&str; 2] = ["layers[0].voronoi[0]", "layers[0].zentangle[0]"];

/// The fill's colour when its pen is new: a blue-green that stands apart
/// from black lines.
const FILL_COLOR: Color = Color::rgb(0x1f, 0x6f, 0x8b);

/// Fills the closed shapes of `drawing` as `job` says, on a new layer.
///
/// The region is what the plotted layers paint (transforms applied; open
/// strokes, fill-only paths and `%` layers left out), as
/// [`FillJob::region`] says: by default the filled shapes united with the
/// closed outlines of unfilled ones, or every closed outline with the
/// even-odd rule.
/// The drawing's layers and pens come back as they were, the fill's
/// layer after them, behind them in depth, with an id none of the
/// drawing's ids starts with; its pen is added (named `fill`, blue-green,
/// 0.3 mm) unless the drawing has it.
///
/// ```
/// use moyo::{fill_scene, import_svg, FillJob, FillPattern, ImportOptions};
///
/// // A frame: a square with a square hole.
/// let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm"
///     viewBox="0 0 100 100">
///   <path d="M 10 10 H 90 V 90 H 10 Z M 30 30 H 70 V 70 H 30 Z" stroke="black" fill="none"/>
/// </svg>"#;
/// let drawing = import_svg(svg, &ImportOptions::DEFAULT)?.scene;
/// let job = FillJob::new(FillPattern::Glass).with_spacing(8.0);
/// let filled = fill_scene(drawing, &job)?;
/// assert_eq!((filled.pen, filled.new_pen), (2, true));
/// assert!(filled.fill.paths > 20);
/// assert!(filled.svg(3).contains(r#"inkscape:label="2 fill""#));
/// # Ok::<(), moyo::Error>(())
/// ```
///
/// # Errors
/// [`Error::Invalid`] with field `input` when the drawing has no closed
/// shape or its closed shapes enclose no area, and with field `pattern`
/// when the pattern draws nothing inside them; with the option's name
/// (`spacing`, `points`, `relax`, `pen`, `dot`, `seed`) for a bad option,
/// both `spacing` and `points`, or a `dot` for another pattern than
/// stipple.
pub fn fill_scene(mut drawing: Scene, job: &FillJob) -> Result<Filled> {
    check_options(job)?;
    if job.spacing.is_some() && job.points.is_some() {
        return Err(Error::invalid(
            "points",
            "give either spacing (Poisson-disk sites) or points (uniform sites), not both",
        ));
    }
    if job.dot.is_some() && job.pattern != FillPattern::Stipple {
        return Err(Error::invalid(
            "dot",
            format!(
                "sizes stipple dots; the {} pattern draws none",
                job.pattern.name()
            ),
        ));
    }
    let pen = job.pen.unwrap_or_else(|| free_pen(&drawing));
    let id = free_layer_id(&drawing);
    let spec = ValidSpec::new(description(&drawing, job, pen, &id)).map_err(by_option)?;
    let outline = region_to_fill(&drawing, job.region)?;
    let mut library = Library::new();
    library.add_paths(INPUT, outline);
    if let Some(image) = &job.image {
        library.add_image(IMAGE, image.clone());
    }
    let (mut built, notes, _) = build(&spec, &library, &mut |_| {}, super::Cancel::never())
        .map_err(|e| spec.locate(e))
        .map_err(by_option)?;
    // Black parts of a zentangle are hatched by its own pen, as in a
    // render: a fill a pen cannot draw would be lost on the plotter.
    crate::plot::hatch::run_own(&mut built)?;
    let mut layers = built.layers;
    let mut layer = layers.pop().ok_or_else(|| Error::Geometry {
        operation: "filling: the description built no layer".into(),
    })?;
    layer.depth = drawing.layers.iter().map(|l| l.depth).max().unwrap_or(0) + 1;
    let fill = stats(&layer);
    if fill.paths == 0 {
        return Err(Error::invalid(
            "pattern",
            format!(
                "the {} pattern drew nothing inside the shapes; a smaller spacing \
                 or more points give it room",
                job.pattern.name()
            ),
        ));
    }
    let new_pen = drawing.pen(pen).is_none();
    if new_pen {
        let at = drawing.pens.partition_point(|p| p.number < pen);
        drawing.pens.insert(
            at,
            Pen {
                number: pen,
                name: "fill".into(),
                color: FILL_COLOR,
                width: 0.3,
            },
        );
    }
    drawing.layers.push(layer);
    let plotted = if job.pen_stage {
        crate::plot::run(drawing.clone(), &PlotOptions::pen_ready())?
    } else {
        drawing.clone()
    };
    Ok(Filled {
        scene: drawing,
        plotted,
        layer: id,
        pen,
        new_pen,
        fill,
        notes,
    })
}

/// Options that do not apply to the job's pattern are refused by name:
/// the sites' options for a zentangle, `steps` for the others.
fn check_options(job: &FillJob) -> Result<()> {
    let zentangle = job.pattern == FillPattern::Zentangle;
    let sites = [
        ("spacing", job.spacing.is_some()),
        ("points", job.points.is_some()),
        ("relax", job.relax.is_some()),
        ("lbg", job.lbg),
        ("converge", job.converge.is_some()),
        ("density", job.density.is_some()),
        ("image", job.image.is_some()),
    ];
    if zentangle {
        if let Some((option, _)) = sites.iter().find(|(_, set)| *set) {
            return Err(Error::invalid(
                *option,
                "places the sites of the Voronoi patterns; the zentangle pattern has none",
            ));
        }
    } else if job.steps.is_some() {
        return Err(Error::invalid(
            "steps",
            format!(
                "counts zentangle steps; the {} pattern has none",
                job.pattern.name()
            ),
        ));
    }
    Ok(())
}

/// The description of the fill: the drawing's page (margins 0, so the
/// layer's coordinates are the drawing's), one layer with one table whose
/// region is the drawing's closed shapes.
fn description(drawing: &Scene, job: &FillJob, pen: u32, layer: &str) -> SceneSpec {
    // Only a description's own region depends on its page; this one's is
    // the drawing's shapes, so a page outside what a description allows
    // is brought inside rather than refused.
    let size = |mm: f64| mm.clamp(10.0, 10_000.0);
    let sites = match job.points {
        Some(n) => SitesSpec {
            distribution: Some(Distribution::Uniform),
            count: Some(n),
            ..SitesSpec::default()
        },
        None => SitesSpec {
            distribution: Some(Distribution::Poisson),
            spacing: Some(job.spacing.unwrap_or(FillJob::DEFAULT_SPACING)),
            ..SitesSpec::default()
        },
    };
    let sites = SitesSpec {
        image: job.image.as_ref().map(|_| IMAGE.to_string()),
        density: job.density.clone(),
        // With LBG the spacing is the target, whatever the start.
        spacing: sites.spacing.or(job.spacing),
        ..sites
    };
    let region = RegionSpec {
        svg: Some(INPUT.into()),
        ..RegionSpec::default()
    };
    let glass = job.pattern == FillPattern::Glass;
    let voronoi = job.pattern.draw().map(|draw| VoronoiSpec {
        // One id for every pattern: the same seed and spacing give the
        // same sites, whichever pattern draws them.
        id: Some("pattern".into()),
        region: region.clone(),
        sites,
        relax: job.relax.unwrap_or(job.pattern.default_relax()),
        relaxation: if job.lbg {
            RelaxationMethod::Lbg
        } else {
            RelaxationMethod::Lloyd
        },
        converge: job.converge,
        draw: vec![draw],
        inset: if glass { 0.8 } else { 1.0 },
        round: if glass { 1.0 } else { 0.0 },
        dot: job.dot.unwrap_or(0.3),
        // The drawing's own pen draws the shapes' outlines.
        outline: job.outline,
        dot_range: None,
        crack: DEFAULT_CRACK,
    });
    let zentangle = (job.pattern == FillPattern::Zentangle).then(|| ZentangleSpec {
        id: Some("pattern".into()),
        region,
        steps: job.steps.unwrap_or(50),
        // Steps, not sections: an outline has no string to split it, and
        // the paper's loop fills its pieces as the steps go.
        look: Look::Sampler,
        ..ZentangleSpec::default()
    });
    SceneSpec {
        palette: None,
        version: FORMAT_VERSION,
        title: None,
        description: None,
        seed: job.seed,
        page: PageSpec {
            size: PaperSize::Custom([size(drawing.page.width), size(drawing.page.height)]),
            orientation: None,
            margin: MarginSpec::Uniform(0.0),
        },
        output: OutputSpec::default(),
        // The family's own limit on sites (a million) is the one that
        // counts here.
        limits: LimitsSpec {
            max_paths: crate::spec::MAX_PATHS,
            ..LimitsSpec::default()
        },
        pens: vec![PenSpec {
            number: pen,
            name: "fill".into(),
            color: FILL_COLOR.to_string(),
            width: 0.3,
        }],
        lines: RegionLinesSpec::default(),
        layers: vec![LayerSpec {
            voronoi: voronoi.into_iter().collect(),
            zentangle: zentangle.into_iter().collect(),
            ..LayerSpec::new(layer, pen)
        }],
        plot: PlotSpec::default(),
        adjust: Vec::new(),
        device: None,
    }
}

/// An error of the description, on the option it came from.
fn by_option(e: Error) -> Error {
    let Error::Invalid { at, field, message } = e else {
        return e;
    };
    let table = TABLES
        .iter()
        .find_map(|t| field.strip_prefix(t))
        .and_then(|f| f.strip_prefix('.'));
    let option = match (field.as_str(), table) {
        ("seed", _) => "seed",
        (f, _) if f.starts_with("pens[") => "pen",
        (_, Some("sites.spacing")) => "spacing",
        (_, Some("sites.count")) => "points",
        (_, Some("relax")) => "relax",
        (_, Some("steps")) => "steps",
        (_, Some("converge")) => "converge",
        (_, Some("sites.density")) => "density",
        (_, Some("dot")) => "dot",
        (_, Some(f)) if f.starts_with("region") => {
            let message = message
                .strip_prefix(&format!("{INPUT}: "))
                .unwrap_or(&message)
                .to_string();
            return Error::invalid("input", message);
        }
        _ => return Error::Invalid { at, field, message },
    };
    Error::invalid(option, message)
}

/// The boundary of the region `mode` makes of the drawing's plotted
/// layers, in the layers' coordinates: simple contours that paint it under
/// either fill rule.
///
/// # Errors
/// [`Error::Invalid`] (field `input`) when there is no closed shape, or
/// when the closed shapes enclose no area.
fn region_to_fill(drawing: &Scene, mode: FillRegion) -> Result<BezPath> {
    let mut painted = Vec::new();
    let mut outlines = BezPath::new();
    for layer in drawing.layers.iter().filter(|l| l.is_plotted()) {
        layer.content.visit_paths(Affine::IDENTITY, &mut |p, t| {
            // Fill-only paths are colour a pen does not draw.
            if !p.style.is_drawn() {
                return;
            }
            let path = t * p.path.clone();
            if mode == FillRegion::Painted && p.style.fill.is_some() {
                // The import has made every fill non-zero already. A shape
                // that encloses nothing paints nothing.
                if let Ok(region) = Region::new(path, FillRule::NonZero) {
                    painted.push(region);
                }
                return;
            }
            for sub in subpaths(&path).filter(|s| s.is_closed()) {
                outlines.extend(sub.elements());
                if !sub.ends_with_close() {
                    outlines.close_path();
                }
            }
        });
    }
    if painted.is_empty() && outlines.elements().is_empty() {
        return Err(Error::invalid(
            "input",
            "has no closed shape to fill (only open strokes, or nothing a pen draws)",
        ));
    }
    if !outlines.elements().is_empty() {
        if let Ok(region) = Region::new(outlines, FillRule::EvenOdd) {
            painted.push(region);
        }
    }
    let region = Region::union_all(&painted);
    if region.is_empty() {
        return Err(Error::invalid(
            "input",
            "its closed shapes enclose no area (each is degenerate, retraced, \
             or cancelled by another with the even-odd rule)",
        ));
    }
    Ok(region.into_path())
}

/// The smallest pen number the drawing does not use, whose SVG layer id
/// (`pen-N`) no element of the drawing has either.
fn free_pen(drawing: &Scene) -> u32 {
    let ids = ids(drawing);
    (1..)
        .find(|&n| {
            drawing.pen(n).is_none()
                && drawing.layers.iter().all(|l| l.pen != n)
                && !ids.contains(format!("pen-{n}").as_str())
        })
        .unwrap_or(u32::MAX)
}

/// `fill`, or `fill-2`, `fill-3` …: the first that no id of the drawing
/// is or starts with (the fill's group and path ids start `<layer>.`).
fn free_layer_id(drawing: &Scene) -> String {
    let ids = ids(drawing);
    let taken = |c: &str| {
        ids.iter()
            .any(|id| *id == c || id.strip_prefix(c).is_some_and(|r| r.starts_with('.')))
    };
    std::iter::once("fill".to_string())
        .chain((2..).map(|n| format!("fill-{n}")))
        .find(|c| !taken(c))
        .unwrap_or_default()
}

/// Every id in the drawing: layers, groups and paths.
fn ids(drawing: &Scene) -> BTreeSet<&str> {
    fn walk<'a>(group: &'a Group, out: &mut BTreeSet<&'a str>) {
        out.insert(&group.id);
        for child in &group.children {
            match child {
                Node::Group(g) => walk(g, out),
                Node::Path(p) => {
                    out.insert(&p.id);
                }
            }
        }
    }
    let mut out = BTreeSet::new();
    for layer in &drawing.layers {
        out.insert(layer.id.as_str());
        walk(&layer.content, &mut out);
    }
    out
}

/// Path count and pen-down length of one layer.
fn stats(layer: &Layer) -> Stats {
    let mut s = Stats::default();
    layer.content.visit_paths(Affine::IDENTITY, &mut |p, t| {
        s.paths += 1;
        s.pen_down_mm += path_length(&(t * p.path.clone()));
    });
    s
}

#[cfg(test)]
mod tests;
