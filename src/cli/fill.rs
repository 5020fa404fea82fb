//! `moyo fill`: a Voronoi-family pattern inside the closed shapes of any
//! SVG, on a pen of its own.

use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};

use super::plot::{load_svg, PenArgs};
use super::{check_outputs, warn_outside_page, CliError, Named};
use moyo::output::write_all_atomic;
use moyo::project::{self, FillJob, FillPattern};

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum PatternArg {
    /// The cells: each edge between two cells once, and the outline.
    Voronoi,
    /// The Delaunay triangulation of the sites and the outline, in long
    /// strokes.
    Delaunay,
    /// A dot at each site (--dot), relaxed 10 times by default.
    Stipple,
    /// One pen-down line through the sites of each separate shape, relaxed 10 times by default.
    Tour,
    /// Each cell shrunk and rounded, a closed shape each: stained glass.
    Glass,
    /// A zentangle, --steps filling steps (default 50).
    Zentangle,
}

impl PatternArg {
    fn pattern(self) -> FillPattern {
        match self {
            PatternArg::Voronoi => FillPattern::Voronoi,
            PatternArg::Delaunay => FillPattern::Delaunay,
            PatternArg::Stipple => FillPattern::Stipple,
            PatternArg::Tour => FillPattern::Tour,
            PatternArg::Glass => FillPattern::Glass,
            PatternArg::Zentangle => FillPattern::Zentangle,
        }
    }
}

#[derive(Args)]
pub(crate) struct FillArgs {
    /// The SVG whose closed shapes are filled; shapes inside shapes are
    /// holes, open strokes are kept but fill nothing.
    input: PathBuf,
    /// Output SVG: the input's layers as they were, plus the fill's.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    pens: PenArgs,
    /// What the fill draws.
    #[arg(long, value_enum, default_value = "voronoi")]
    pattern: PatternArg,
    /// Seed of the sites (0 – 9223372036854775807).
    #[arg(long, default_value_t = FillJob::DEFAULT.seed)]
    seed: u64,
    /// Poisson-disk sites this far apart, mm (0.1–10000; default 5).
    #[arg(long, value_name = "MM", conflicts_with = "points")]
    spacing: Option<f64>,
    /// This many sites spread uniformly at random instead (1–1000000).
    #[arg(long, value_name = "N")]
    points: Option<u32>,
    /// Relaxation steps, at most, evening out the sites (0–1000; default
    /// 10 for stipple and tour, 0 otherwise).
    #[arg(long, value_name = "N")]
    relax: Option<u32>,
    /// Relax by weighted Linde-Buzo-Gray: sites split and go until each
    /// holds one site's worth of density, --spacing apart where it is 1
    /// (the count follows the image; needs --relax).
    #[arg(long)]
    lbg: bool,
    /// Stop relaxing once a step moves the sites less than this on
    /// average, mm (0.00001–100).
    #[arg(long, value_name = "MM")]
    converge: Option<f64>,
    /// Density as a formula of the position: x, y in mm, u, v 0–1 across
    /// the shapes' bounding box, clamped to 0–1 (e.g. "1 - v"); times the
    /// image's when both are given.
    #[arg(long, value_name = "FORMULA", allow_hyphen_values = true)]
    density: Option<String>,
    /// Zentangle: filling steps (0–5000; default 50).
    #[arg(long, value_name = "N")]
    steps: Option<u32>,
    /// Pen of the fill (1–999); default the smallest number the input
    /// does not use.
    #[arg(long, value_name = "N")]
    pen: Option<u32>,
    /// Stipple: radius of the dots, mm (0.05–50; default 0.3).
    #[arg(long, value_name = "MM")]
    dot: Option<f64>,
    /// A PNG or JPEG whose dark parts get more sites (and weigh more when
    /// relaxing: weighted Voronoi stippling), fitted to the shapes'
    /// bounding box, aspect kept, centred.
    #[arg(long, value_name = "FILE")]
    image: Option<PathBuf>,

    /// Decimals in the SVG (0–8).
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u8).range(0..=8), help_heading = "Output")]
    precision: u8,
    /// voronoi, delaunay: the fill's pen draws the shapes' outlines as
    /// well (by default only the input's own pen draws them).
    #[arg(long)]
    outline: bool,
    /// Fill every closed outline with the even-odd rule, fills ignored (a
    /// shape inside a shape is a hole, stacked shapes cancel). By default
    /// the fill follows what is painted: filled shapes united, a shape
    /// painted over another covering it, with the closed outlines of
    /// unfilled shapes (an outline inside an outline is a hole).
    #[arg(long)]
    even_odd: bool,
    /// Write the drawing and the fill as built: without the pen stage
    /// (doubled line work and debris taken out, strokes merged and sorted
    /// for little pen-up travel), which runs by default.
    #[arg(long, help_heading = "Output")]
    no_pen_stage: bool,
    /// Also write a PNG preview, in colour.
    #[arg(long, help_heading = "Output")]
    png: Option<PathBuf>,
    /// Resolution of the PNG preview (1–2400).
    #[arg(long, default_value_t = 150.0, value_parser = super::parse_dpi, requires = "png", help_heading = "Output")]
    dpi: f64,
}

impl FillArgs {
    /// What `moyo fill` asks of the library (reads the density image).
    fn job(&self) -> Result<FillJob, CliError> {
        let mut job = FillJob::new(self.pattern.pattern()).with_seed(self.seed);
        job.spacing = self.spacing;
        job.points = self.points;
        job.relax = self.relax;
        job.lbg = self.lbg;
        job.converge = self.converge;
        job.density = self.density.clone();
        job.steps = self.steps;
        job.pen = self.pen;
        job.dot = self.dot;
        job.pen_stage = !self.no_pen_stage;
        job.outline = self.outline;
        if self.even_odd {
            job = job.with_region(moyo::FillRegion::EvenOdd);
        }
        if let Some(path) = &self.image {
            let fail =
                |e: &dyn std::fmt::Display| CliError::Message(format!("{}: {e}", path.display()));
            let bytes = moyo::input::read_file(path).map_err(|e| fail(&e))?;
            job = job.with_image(moyo::input::decode_image(&bytes).map_err(|e| fail(&e))?);
        }
        Ok(job)
    }
}

/// The library names a bad option by its field and the drawing `input`;
/// here they are the command's option and the input file.
fn on_the_command_line(e: moyo::Error, input: &Path) -> CliError {
    const OPTIONS: [&str; 11] = [
        "seed", "spacing", "points", "relax", "converge", "density", "pen", "dot", "steps", "lbg",
        "image",
    ];
    CliError::Message(match e {
        moyo::Error::Invalid { field, message, .. } if field == "input" => {
            format!("{}: {message}", input.display())
        }
        moyo::Error::Invalid { field, message, .. } if OPTIONS.contains(&field.as_str()) => {
            format!("--{field}: {message}")
        }
        e => e.to_string(),
    })
}

/// `moyo fill`.
pub(crate) fn fill(args: &FillArgs) -> Result<(), CliError> {
    let mut inputs: Vec<Named<'_>> = vec![("the input", &args.input)];
    inputs.extend(args.image.as_deref().map(|p| ("--image", p)));
    let mut outputs: Vec<Named<'_>> = vec![("-o", &args.output)];
    outputs.extend(args.png.as_deref().map(|p| ("--png", p)));
    check_outputs(&inputs, &outputs)?;
    let imported = load_svg(&args.input, &args.pens)?;
    let job = args.job()?;
    // Everything is computed before anything is written.
    let filled = project::fill_scene(imported.scene, &job)
        .map_err(|e| on_the_command_line(e, &args.input))?;
    let svg = filled.svg(args.precision);
    let png = match &args.png {
        Some(_) => Some(filled.png(args.dpi)?),
        None => None,
    };
    // All or none: a failed output leaves every old file.
    let mut files: Vec<(&Path, &[u8])> = vec![(&args.output, svg.as_bytes())];
    if let (Some(path), Some(bytes)) = (&args.png, &png) {
        files.push((path, bytes));
    }
    write_all_atomic(&files)?;
    let all = filled.plotted.stats();
    // On a pen of its own the fill is counted as plotted, like the total
    // (the pen stage joins its lines); on the input's pen, as drawn.
    let fill = if filled.new_pen {
        filled.plotted.pen_stats(filled.pen)
    } else {
        filled.fill
    };
    eprintln!(
        "wrote {}{} ({} paths, {:.0} mm pen-down; the {} fill: {} paths, {:.0} mm, on {} pen {})",
        args.output.display(),
        args.png
            .as_ref()
            .map(|p| format!(" and {}", p.display()))
            .unwrap_or_default(),
        all.paths,
        all.pen_down_mm,
        job.pattern.name(),
        fill.paths,
        fill.pen_down_mm,
        if filled.new_pen { "new" } else { "the input's" },
        filled.pen,
    );
    for note in &filled.notes {
        eprintln!("{}: {}", note.motif, note.text);
    }
    warn_outside_page(&filled.plotted);
    Ok(())
}
