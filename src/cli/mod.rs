//! Command-line parsing and the commands. Uses only the public library API;
//! everything it prints goes through here (the library never prints).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

mod fill;
mod folders;
mod lsystem;
mod plot;
mod stencil;
#[cfg(feature = "studio")]
mod studio;

use moyo::output::write_all_atomic;
use moyo::project::{self, Progress};
use moyo::spec::{Format, SceneSpec, ValidSpec};
use moyo::templates;

/// moyo (模様): ornamental line art as layered, plottable SVG.
#[derive(Parser)]
#[command(name = "moyo", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene description to layered SVG (and optionally PNG).
    ///
    /// With no SCENE and no --template, renders the built-in default design.
    #[command(allow_negative_numbers = true)]
    Render(RenderArgs),
    /// List the built-in templates with a one-line description each.
    Templates,
    /// Run the plot pipeline on any SVG and write SVG, G-code, HPGL or DXF.
    ///
    /// Stages run in a fixed order: transform, hatch, occlude, then per pen
    /// dedupe, merge, debris, simplify, sort, multipass. Only the stages
    /// asked for run.
    #[command(allow_negative_numbers = true)]
    Plot(Box<plot::PlotArgs>),
    /// Make line art into a stencil that holds together: strokes cut out
    /// at their pen's width, islands held by bridges, blade limits
    /// reported; written as SVG, HPGL (cutter) or DXF, inside first.
    #[command(allow_negative_numbers = true)]
    Stencil(Box<stencil::StencilArgs>),
    /// Path count, pen-down and pen-up length and plot time of an SVG.
    #[command(allow_negative_numbers = true)]
    Stats(plot::StatsArgs),
    /// Fill the closed shapes of any SVG with a Voronoi-family pattern or a
    /// zentangle.
    ///
    /// The fill follows what is painted: filled shapes united (a shape
    /// painted over another covers it), and closed outlines of unfilled
    /// shapes, an outline inside an outline being a hole (--even-odd: every
    /// outline by the even-odd rule). Open strokes fill nothing. The
    /// pattern goes on a layer and pen of its own; the input's layers and
    /// pens are kept as they are.
    #[command(allow_negative_numbers = true)]
    Fill(fill::FillArgs),
    /// Draw an L-system: rules from the command line, fitted to the page;
    /// or the Sketching L-System grown along the first path of an SVG.
    ///
    /// The turtle starts heading up the page; `+` turns left. The same
    /// table in a scene description (`[[layers.lsystem]]`) draws the same.
    #[command(allow_negative_numbers = true)]
    Lsystem(lsystem::LSystemArgs),
    /// Open the live design page in the browser: edit a description and
    /// see the pattern change as you work.
    ///
    /// Serves on 127.0.0.1 and prints the address; reads and writes files
    /// only in the current folder.
    #[cfg(feature = "studio")]
    #[command(allow_negative_numbers = true)]
    Studio(studio::StudioArgs),
    /// List the built-in machine profiles, or print one (TOML, with its
    /// comments) to start your own from: `moyo devices grbl-z > my.toml`,
    /// then `moyo plot --device my.toml`.
    Devices {
        /// The profile to print.
        name: Option<String>,
    },
    /// Print a template's scene description to start a design from.
    New {
        /// Template name (see `moyo templates`).
        name: String,
        /// Write to this file instead of standard output.
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
}

#[derive(clap::Args)]
struct RenderArgs {
    /// Scene description file (.toml, or .json).
    scene: Option<PathBuf>,
    /// Render a built-in template instead of a file.
    #[arg(short, long, conflicts_with = "scene")]
    template: Option<String>,
    /// Reopen a design: render the description embedded in an SVG that
    /// moyo wrote (byte-identical output when nothing is changed).
    #[arg(long, value_name = "SVG", conflicts_with_all = ["scene", "template"])]
    from: Option<PathBuf>,
    /// Output SVG file.
    #[arg(short, long, default_value = "moyo.svg")]
    output: PathBuf,
    /// Also write a PNG preview, in colour: rendered from the SVG of
    /// --preview-svg.
    #[arg(long)]
    png: Option<PathBuf>,
    /// Also write the colour preview as SVG: the plot plus fill colours
    /// and `%` layers, for looking at, not for plotting.
    #[arg(long, value_name = "SVG")]
    preview_svg: Option<PathBuf>,
    /// Resolution of the PNG preview (1–2400).
    #[arg(long, default_value_t = 150.0, value_parser = parse_dpi, requires = "png")]
    dpi: f64,
    /// Override the description's seed (0 – 9223372036854775807).
    #[arg(long)]
    seed: Option<u64>,
    /// Override the number of decimals in the SVG (0–8).
    #[arg(long)]
    precision: Option<u8>,
    /// Also write the line-oriented path dump (for snapshot tests).
    #[arg(long)]
    dump: Option<PathBuf>,
    /// Also write the 3D model (vines and their supports) as Wavefront
    /// OBJ, in millimetres, y up.
    #[arg(long, value_name = "OBJ")]
    obj: Option<PathBuf>,
}

/// A file named on the command line: how the command line names it (the
/// option, or what the argument is) and the path.
pub(crate) type Named<'a> = (&'a str, &'a Path);

/// What a path stands for when comparing files: the file itself when it
/// exists (links and `..` resolved), else the resolved folder and the
/// name, else the path as written.
pub(crate) fn identity(path: &Path) -> PathBuf {
    if let Ok(real) = std::fs::canonicalize(path) {
        return real;
    }
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    match (path.file_name(), std::fs::canonicalize(dir)) {
        (Some(name), Ok(dir)) => dir.join(name),
        _ => path.to_path_buf(),
    }
}

/// Refuses, before anything is computed, outputs that would destroy what
/// the command reads or what it writes: an output that is also one of the
/// `inputs`, two `outputs` that are one file, and an output whose folder
/// is missing.
pub(crate) fn check_outputs(inputs: &[Named<'_>], outputs: &[Named<'_>]) -> Result<(), CliError> {
    let inputs: Vec<(Named<'_>, PathBuf)> = inputs.iter().map(|&n| (n, identity(n.1))).collect();
    let mut seen: Vec<(Named<'_>, PathBuf)> = Vec::new();
    for &(flag, path) in outputs {
        moyo::output::check_output_folder(path)?;
        let id = identity(path);
        if let Some(((what, input), _)) = inputs.iter().find(|(_, i)| *i == id) {
            return Err(CliError::Message(format!(
                "{flag} {}: the same file as {what} {}, which writing would replace; \
                 choose another output",
                path.display(),
                input.display()
            )));
        }
        if let Some(((other, first), _)) = seen.iter().find(|(_, o)| *o == id) {
            return Err(CliError::Message(format!(
                "{flag} {}: the same file as {other} {}; give each output a file of its own",
                path.display(),
                first.display()
            )));
        }
        seen.push(((flag, path), id));
    }
    Ok(())
}

/// The extension of an output's name, lower-cased (empty when it has
/// none): what names its format.
pub(crate) fn extension(output: &Path) -> String {
    output
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// Rejects a bad `--dpi` while parsing, whether or not `--png` is given.
pub(crate) fn parse_dpi(s: &str) -> Result<f64, String> {
    let dpi: f64 = s.parse().map_err(|e| format!("{e}"))?;
    moyo::output::check_dpi(dpi).map_err(|e| e.to_string())?;
    Ok(dpi)
}

/// Parses the command line and runs it.
pub(crate) fn run() -> ExitCode {
    let cli = Cli::parse();
    remove_temporaries_on_signal();
    let result = match cli.command {
        Command::Render(args) => render(&args),
        Command::Templates => list_templates(),
        Command::Devices { name } => plot::devices(name.as_deref()),
        Command::Plot(args) => plot::plot(&args),
        Command::Stats(args) => plot::stats(&args),
        Command::Stencil(args) => stencil::stencil(&args),
        Command::Fill(args) => fill::fill(&args),
        Command::Lsystem(args) => lsystem::lsystem(&args),
        #[cfg(feature = "studio")]
        Command::Studio(args) => studio::studio(&args),
        Command::New { name, output } => new(&name, output.as_deref()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(CliError::BrokenPipe) => ExitCode::SUCCESS,
        Err(CliError::Message(msg)) => {
            eprintln!("error: {msg}");
            ExitCode::FAILURE
        }
    }
}

/// On SIGINT (Ctrl-C) or SIGTERM, removes the temporary files of the
/// writes under way and exits as a shell reports a death by that signal
/// (130, 143): a stopped run leaves no `.moyo-*.tmp` beside its outputs.
/// The handler runs on a thread of its own, so it may take the lock the
/// writes register their files under. The library installs no handler
/// (a process's signals are its program's business).
#[cfg(unix)]
fn remove_temporaries_on_signal() {
    use signal_hook::consts::{SIGINT, SIGTERM};
    // Without the handler (it cannot be installed, which does not happen
    // in practice) a signal kills the run as before, and the next write
    // into the folder removes what it left once stale: no reason to stop.
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM]) else {
        return;
    };
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            moyo::output::remove_temporaries();
            std::process::exit(128 + signal);
        }
    });
}

/// Elsewhere the platform's default stands; a stale temporary file is
/// removed by the next write into its folder.
#[cfg(not(unix))]
fn remove_temporaries_on_signal() {}

pub(crate) enum CliError {
    /// The reader of standard output went away: not an error for a filter.
    BrokenPipe,
    Message(String),
}

impl From<moyo::Error> for CliError {
    fn from(e: moyo::Error) -> Self {
        CliError::Message(e.to_string())
    }
}

/// How the command line types the options the library names by field:
/// (field path, option), e.g. `("gcode.feed_down_mm_min", "--feed")`.
pub(crate) type Typed<'a> = &'a [(&'a str, &'a str)];

/// `e` as the command line words it: an invalid field that an option of
/// `typed` sets is named by that option (`--feed: must be …`), any other
/// error is the library's own.
pub(crate) fn as_typed(e: moyo::Error, typed: Typed<'_>) -> CliError {
    match e {
        moyo::Error::Invalid { field, message, .. } if typed.iter().any(|(f, _)| *f == field) => {
            let (_, option) = typed
                .iter()
                .find(|(f, _)| *f == field)
                .expect("found above");
            CliError::Message(format!("{option}: {message}"))
        }
        e => e.into(),
    }
}

pub(crate) fn stdout_error(e: std::io::Error) -> CliError {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        CliError::BrokenPipe
    } else {
        CliError::Message(format!("standard output: {e}"))
    }
}

/// Loads the scene to render — a file, the description embedded in an SVG,
/// a named template or the default — with the directory its user motifs
/// are read from.
fn load(args: &RenderArgs) -> Result<(ValidSpec, Files), CliError> {
    let read = |path: &Path| {
        moyo::input::read_text(path)
            .map_err(|e| CliError::Message(format!("{}: {e}", path.display())))
    };
    let base = |path: &Path| {
        path.parent()
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
    };
    match (&args.scene, &args.from, &args.template) {
        (Some(path), _, _) => {
            let spec = SceneSpec::parse(&read(path)?, Format::from_path(path))
                .map_err(|e| CliError::Message(format!("{}:{e}", path.display())))?;
            Ok((spec, Files::Dir(base(path))))
        }
        (None, Some(svg), _) => {
            let text = moyo::embedded_description(&read(svg)?).ok_or_else(|| {
                CliError::Message(format!(
                    "{}: carries no scene description (only SVGs written by moyo render can be reopened)",
                    svg.display()
                ))
            })?;
            let spec = SceneSpec::parse(&text, Format::Toml).map_err(|e| {
                CliError::Message(format!("{} (embedded description):{e}", svg.display()))
            })?;
            Ok((spec, Files::Dir(base(svg))))
        }
        (None, None, name) => {
            let template = templates::get(name.as_deref().unwrap_or(templates::DEFAULT))?;
            Ok((template.spec()?, Files::Template(template)))
        }
    }
}

/// Where the files a description names are read from.
enum Files {
    /// Beside the description (or the SVG it came from).
    Dir(PathBuf),
    /// A built-in template's own files.
    Template(&'static templates::Template),
}

fn render(args: &RenderArgs) -> Result<(), CliError> {
    let (spec, files) = load(args)?;
    // The files the description reads (motifs, paths, images, meshes)
    // are inputs too.
    let read: Vec<PathBuf> = match &files {
        Files::Dir(base) => {
            let named = project::user_files(&spec);
            named
                .motifs
                .iter()
                .chain(&named.paths)
                .chain(&named.images)
                .chain(&named.meshes)
                .map(|name| base.join(name))
                .collect()
        }
        Files::Template(_) => Vec::new(),
    };
    let mut inputs: Vec<Named<'_>> = Vec::new();
    inputs.extend(args.scene.as_deref().map(|p| ("the scene", p)));
    inputs.extend(args.from.as_deref().map(|p| ("--from", p)));
    inputs.extend(read.iter().map(|p| ("the scene's file", p.as_path())));
    let mut outputs: Vec<Named<'_>> = vec![("-o", &args.output)];
    outputs.extend(args.png.as_deref().map(|p| ("--png", p)));
    outputs.extend(args.preview_svg.as_deref().map(|p| ("--preview-svg", p)));
    outputs.extend(args.dump.as_deref().map(|p| ("--dump", p)));
    outputs.extend(args.obj.as_deref().map(|p| ("--obj", p)));
    check_outputs(&inputs, &outputs)?;
    // The overrides go through the same validation as the file.
    let spec = spec
        .edit(|s| {
            if let Some(seed) = args.seed {
                s.seed = seed;
            }
            if let Some(p) = args.precision {
                s.output.precision = p;
            }
        })
        .map_err(|e| {
            as_typed(
                e,
                &[("seed", "--seed"), ("output.precision", "--precision")],
            )
        })?;

    let bar = DelayedBar::new();
    let library = match &files {
        Files::Dir(base) => project::load_motifs(&spec, base)?,
        // Overrides (seed, precision) name no files: the template's own.
        Files::Template(t) => t.library()?,
    };
    let rendered = project::render_with_progress(&spec, &library, &mut |p| bar.update(p))?;
    bar.finish();

    // Everything is computed before anything is written, so a failure
    // leaves no output file behind.
    let preview =
        (args.png.is_some() || args.preview_svg.is_some()).then(|| rendered.preview_svg());
    let png = match (&args.png, &preview) {
        (Some(_), Some(svg)) => Some(moyo::output::render_png(svg, args.dpi)?),
        _ => None,
    };
    let dump = args
        .dump
        .as_ref()
        .map(|_| rendered.dump(spec.output.precision));
    let obj = match &args.obj {
        Some(_) if rendered.models.is_empty() => {
            return Err(CliError::Message(
                "--obj: the scene has no 3D model (a `[[layers.vine]]` makes one)".into(),
            ));
        }
        Some(_) => Some(moyo::output::to_obj(
            &rendered.models,
            spec.output.precision,
        )),
        None => None,
    };

    // All or none: a failed output leaves every old file.
    let mut files: Vec<(&Path, &[u8])> = vec![(&args.output, rendered.svg.as_bytes())];
    if let (Some(path), Some(svg)) = (&args.preview_svg, &preview) {
        files.push((path, svg.as_bytes()));
    }
    if let (Some(path), Some(bytes)) = (&args.png, &png) {
        files.push((path, bytes));
    }
    if let (Some(path), Some(text)) = (&args.dump, &dump) {
        files.push((path, text.as_bytes()));
    }
    if let (Some(path), Some(text)) = (&args.obj, &obj) {
        files.push((path, text.as_bytes()));
    }
    moyo::output::write_all_atomic(&files)?;

    let stats = rendered.stats();
    let also: Vec<String> = [&args.preview_svg, &args.png, &args.obj]
        .into_iter()
        .flatten()
        .map(|p| p.display().to_string())
        .collect();
    eprintln!(
        "wrote {} ({} paths, {:.0} mm pen-down){}",
        args.output.display(),
        stats.paths,
        stats.pen_down_mm,
        if also.is_empty() {
            String::new()
        } else {
            format!(" and {}", also.join(" and "))
        }
    );
    for note in &rendered.notes {
        eprintln!("{}: {}", note.motif, note.text);
    }
    warn_outside_page(&rendered.scene);
    Ok(())
}

/// Plotters clip or crash at the page edge; say so before the plot does.
pub(crate) fn warn_outside_page(scene: &moyo::Scene) {
    let Some(b) = scene.bounds() else { return };
    let area = scene.page.drawable();
    let slack = 0.01;
    if b.x0 < area.x0 - slack
        || b.y0 < area.y0 - slack
        || b.x1 > area.x1 + slack
        || b.y1 > area.y1 + slack
    {
        eprintln!(
            "warning: the drawing ({:.1}, {:.1}) – ({:.1}, {:.1}) mm reaches beyond the area inside the margins ({:.1}, {:.1}) – ({:.1}, {:.1}) mm",
            b.x0, b.y0, b.x1, b.y1, area.x0, area.y0, area.x1, area.y1
        );
    }
}

fn list_templates() -> Result<(), CliError> {
    let width = templates::ALL
        .iter()
        .map(|t| t.name.len())
        .max()
        .unwrap_or(0);
    let mut out = std::io::stdout().lock();
    for t in templates::ALL {
        let mark = if t.name == templates::DEFAULT {
            " (default)"
        } else {
            ""
        };
        writeln!(out, "{:width$}  {}{mark}", t.name, t.summary()).map_err(stdout_error)?;
    }
    Ok(())
}

fn new(name: &str, output: Option<&Path>) -> Result<(), CliError> {
    let t = templates::get(name)?;
    // The files the template reads (images) go beside the description, so
    // it renders from there as it is.
    let files = project::user_files(&t.spec()?);
    let names: Vec<&String> = files
        .motifs
        .iter()
        .chain(&files.paths)
        .chain(&files.images)
        .collect();
    match output {
        Some(path) => {
            let dir = path.parent().unwrap_or(Path::new("."));
            let mut files: Vec<(PathBuf, &[u8])> = vec![(path.to_path_buf(), t.text.as_bytes())];
            for name in names {
                let target = dir.join(name);
                if target.exists() {
                    eprintln!("kept {} (already there)", target.display());
                    continue;
                }
                let bytes = templates::file(name).ok_or_else(|| {
                    CliError::Message(format!("template {}: {name} is not built in", t.name))
                })?;
                files.push((target, bytes));
            }
            // All or none: the folders the images go in are made first,
            // and taken away again with the files when one cannot be
            // written (a description without its images does not render).
            let mut made = folders::MadeFolders::default();
            let written = files
                .iter()
                .skip(1)
                .filter_map(|(target, _)| target.parent())
                .try_for_each(|parent| made.make(parent))
                .and_then(|()| {
                    let all: Vec<(&Path, &[u8])> =
                        files.iter().map(|(p, b)| (p.as_path(), *b)).collect();
                    write_all_atomic(&all).map_err(CliError::from)
                });
            if let Err(e) = written {
                made.remove();
                return Err(e);
            }
            for (target, _) in &files {
                eprintln!("wrote {}", target.display());
            }
            Ok(())
        }
        None => {
            for name in names {
                eprintln!("note: this template reads {name}; `moyo new {} -o FILE` writes it beside the description", t.name);
            }
            std::io::stdout()
                .lock()
                .write_all(t.text.as_bytes())
                .map_err(stdout_error)
        }
    }
}

/// A progress bar on stderr that appears only once work has taken more
/// than a second, and only when stderr is a terminal (indicatif hides it
/// otherwise).
struct DelayedBar {
    bar: ProgressBar,
    start: Instant,
}

impl DelayedBar {
    const DELAY: Duration = Duration::from_secs(1);

    fn new() -> DelayedBar {
        let bar = ProgressBar::hidden();
        bar.set_style(
            ProgressStyle::with_template("{spinner} generating {pos}/{len} [{elapsed}]")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        DelayedBar {
            bar,
            start: Instant::now(),
        }
    }

    fn update(&self, p: Progress) {
        if self.bar.is_hidden() && self.start.elapsed() > Self::DELAY {
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        self.bar.set_length(p.total as u64);
        self.bar.set_position(p.done as u64);
    }

    fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
