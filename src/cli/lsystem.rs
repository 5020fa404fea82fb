//! `moyo lsystem`: an L-system from the command line, for exploring — the
//! same table a scene description's `[[layers.lsystem]]` holds, on one pen,
//! fitted to the page; or, with `--stroke`, the Sketching L-System grown
//! along the first path of an SVG, on that SVG's page.

use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};

use super::folders::MadeFolders;
use super::{check_outputs, identity, CliError, Named};
use moyo::output::Staged;
use moyo::project::{self, Rendered};
use moyo::spec::{
    Format, LSystemSpec, LimbStyle, NamedView, PaperSize, SceneSpec, SketchSpec, ValidSpec, View,
};

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum ViewArg {
    /// From the front: the turtle's x right, y up.
    Front,
    /// From the side: −z right, y up.
    Side,
    /// From above: x right, −z up the page.
    Top,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum StyleArg {
    /// Centre lines, one pen pass.
    Stroke,
    /// Closed outlines as wide as the turtle's width.
    Outline,
}

#[derive(Args)]
pub(crate) struct LSystemArgs {
    /// The start word (ABOP's axiom), e.g. F or "A(1, 10)".
    #[arg(
        long,
        allow_hyphen_values = true,
        required_unless_present = "stroke",
        conflicts_with = "stroke"
    )]
    axiom: Option<String>,
    /// A production, repeatable: 'F=F[+F]F[-F]F', 'F ->(0.5) F[+F]F',
    /// 'A(l) : l > 1 -> F(l)[+A(l*0.7)]'. With --stroke: the rule of a
    /// or c, e.g. 'a -> b(40) b(-40) c(30) a'.
    #[arg(long = "rule", value_name = "RULE", allow_hyphen_values = true)]
    rules: Vec<String>,
    /// The turning angle δ, degrees (0–360; default 25.7). Not with
    /// --stroke, whose rules give each branch its angle.
    #[arg(long, value_name = "DEG")]
    angle: Option<f64>,
    /// Rewriting steps (0–100; default 4). Not with --stroke, which takes
    /// one step per --module of stroke.
    #[arg(long, short = 'n', value_name = "N")]
    iterations: Option<u32>,
    /// A named constant for the rules, repeatable: --define r1=0.9.
    #[arg(long = "define", value_name = "NAME=VALUE", value_parser = parse_define, conflicts_with = "stroke")]
    defines: Vec<(String, f64)>,
    /// Symbols that context matching passes over, e.g. "+-F".
    #[arg(
        long,
        default_value = "",
        allow_hyphen_values = true,
        conflicts_with = "stroke"
    )]
    ignore: String,
    /// How limbs are drawn (a sketch is always outlined).
    #[arg(long, value_enum, default_value = "stroke", conflicts_with = "stroke")]
    style: StyleArg,
    /// Starting width of the turtle, in units of F (with --style outline).
    #[arg(
        long,
        default_value_t = 1.0,
        value_name = "W",
        conflicts_with = "stroke"
    )]
    width: f64,
    /// Smooth curves through the turtle's points instead of exact lines.
    #[arg(long)]
    smooth: bool,
    /// Where the 3D drawing is seen from.
    #[arg(long, value_enum, default_value = "front", conflicts_with = "stroke")]
    view: ViewArg,
    /// Seed of stochastic rules (0 – 9223372036854775807).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Page: A5, A4, A3, A2, letter, legal, tabloid. Not with --stroke,
    /// which draws on the stroke file's page.
    #[arg(long, default_value = "A4", conflicts_with = "stroke")]
    page: String,
    /// Grow the Sketching L-System along the first path of this SVG, on
    /// its page and in its coordinates (not fitted).
    #[arg(long, value_name = "SVG")]
    stroke: Option<PathBuf>,
    /// With --stroke: stroke length per rule application, mm (0.1–1000)
    /// [default: 8].
    #[arg(long, value_name = "MM")]
    module: Option<f64>,

    /// Output SVG file.
    #[arg(short, long, help_heading = "Output")]
    output: PathBuf,
    /// Also write a PNG preview.
    #[arg(long, help_heading = "Output")]
    png: Option<PathBuf>,
    /// Resolution of the PNG preview (1–2400).
    #[arg(long, default_value_t = 150.0, value_parser = super::parse_dpi, requires = "png", help_heading = "Output")]
    dpi: f64,
    /// Also write the drawing after every rewriting step (every module
    /// step with --stroke) into this folder: frame-000.svg, … (and .png
    /// with --png), and growth.svg, all of them in one loop (a browser
    /// plays it). Older frames there that this run does not write are
    /// removed; a file of this name is refused.
    #[arg(long, value_name = "DIR", help_heading = "Output")]
    frames: Option<PathBuf>,
}

/// `--module` unless given: the paper's step, mm.
const DEFAULT_MODULE: f64 = 8.0;

/// `--angle` unless given: ABOP's δ for the plants of its fig. 1.24.
const DEFAULT_ANGLE: f64 = 25.7;

/// `--iterations` unless given.
const DEFAULT_ITERATIONS: u32 = 4;

/// Refuses the options that a sketch has no use for, saying why: its
/// angles are its rules' handles and its steps come from the stroke's
/// length, so either would be silently ignored.
fn refuse_with_stroke(args: &LSystemArgs) -> Result<(), CliError> {
    if args.angle.is_some() {
        return Err(CliError::Message(
            "--angle: with --stroke, each branch has its own angle in its rule, \
             e.g. --rule 'a -> b(40) b(-40) c(55) a(roll=180)'; leave --angle out"
                .to_string(),
        ));
    }
    if args.iterations.is_some() {
        return Err(CliError::Message(
            "--iterations: with --stroke, the sketch takes one step per --module mm \
             of stroke, so the stroke's length sets the steps; leave -n out \
             (or use a shorter stroke or a longer --module)"
                .to_string(),
        ));
    }
    Ok(())
}

fn parse_define(s: &str) -> Result<(String, f64), String> {
    let (name, value) = s
        .split_once('=')
        .ok_or_else(|| format!("`{s}` is not NAME=VALUE"))?;
    let value: f64 = value
        .trim()
        .parse()
        .map_err(|e| format!("`{value}` is not a number: {e}"))?;
    Ok((name.trim().to_string(), value))
}

impl LSystemArgs {
    /// The table the options describe.
    fn table(&self) -> Result<LSystemSpec, CliError> {
        let mut t = LSystemSpec {
            angle: self.angle.unwrap_or(DEFAULT_ANGLE),
            style: match self.style {
                StyleArg::Stroke => LimbStyle::Stroke,
                StyleArg::Outline => LimbStyle::Outline,
            },
            width: self.width,
            smooth: self.smooth,
            view: View::Named(match self.view {
                ViewArg::Front => NamedView::Front,
                ViewArg::Side => NamedView::Side,
                ViewArg::Top => NamedView::Top,
            }),
            ..LSystemSpec::default()
        };
        match &self.stroke {
            Some(path) => {
                refuse_with_stroke(self)?;
                let name = path.file_name().map_or_else(
                    || Err(CliError::Message(format!("{}: not a file", path.display()))),
                    |n| Ok(n.to_string_lossy().into_owned()),
                )?;
                let rule = |kind: &str| {
                    self.rules
                        .iter()
                        .find(|r| r.trim_start().starts_with(kind))
                        .cloned()
                };
                t.style = LimbStyle::Outline;
                t.width = 1.0;
                t.sketch = Some(SketchSpec {
                    points: None,
                    smooth: true,
                    svg: Some(name),
                    line: None,
                    module: self.module(),
                    a: rule("a"),
                    c: rule("c"),
                    width: 1.5,
                    steps: None,
                });
                if let Some(other) = self
                    .rules
                    .iter()
                    .find(|r| !r.trim_start().starts_with(['a', 'c']))
                {
                    return Err(CliError::Message(format!(
                        "--rule `{other}`: with --stroke, rules are for `a` or `c`"
                    )));
                }
            }
            None => {
                if self.module.is_some() {
                    return Err(CliError::Message(
                        "--module: the step of a sketch along --stroke; without --stroke \
                         the rules take --iterations steps; leave --module out"
                            .to_string(),
                    ));
                }
                t.axiom = self.axiom.clone().unwrap_or_default();
                t.rules = self.rules.clone();
                t.iterations = self.iterations.unwrap_or(DEFAULT_ITERATIONS);
                t.constants = self.defines.iter().cloned().collect();
                t.ignore = self.ignore.clone();
            }
        }
        Ok(t)
    }

    /// The sketch's step along the stroke, mm.
    fn module(&self) -> f64 {
        self.module.unwrap_or(DEFAULT_MODULE)
    }

    /// The scene: one layer on pen 1 holding the table.
    fn scene(&self) -> Result<ValidSpec, CliError> {
        let table = self.table()?;
        let page = match &self.stroke {
            Some(path) => {
                let drawing = project::read_svg(path, &moyo::ImportOptions::DEFAULT)?;
                if drawing.scene.path_count() == 0 {
                    return Err(CliError::Message(format!(
                        "--stroke {}: has no path for the sketch to grow along \
                         (it grows along the SVG's first path; text and images are not paths)",
                        path.display()
                    )));
                }
                let page = drawing.scene.page;
                Some(PaperSize::Custom([page.width, page.height]))
            }
            None => None,
        };
        let base = "version = 1\n[[layers]]\nname = \"lsystem\"\n";
        let spec = SceneSpec::parse(base, Format::Toml)?;
        let paper = self.page.clone();
        spec.edit(|s| {
            s.seed = self.seed;
            s.title = Some("moyo lsystem".into());
            match page {
                Some(size) => {
                    s.page.size = size;
                    s.page.margin = moyo::spec::MarginSpec::Uniform(0.0);
                }
                None => {
                    if let Ok(size) = toml::Value::String(paper).try_into::<PaperSize>() {
                        s.page.size = size;
                    }
                }
            }
            s.limits.max_paths = moyo::spec::MAX_PATHS;
            if table.style == LimbStyle::Outline {
                // Limb outlines merge into one silhouette, as a person
                // draws a plant: no line inside it.
                s.plot.occlude =
                    Some(moyo::plot::occlude::OccludeOptions::DEFAULT.with_silhouettes(true));
            }
            s.layers[0].lsystem = vec![table];
        })
        .map_err(|e| CliError::Message(on_the_command_line(e)))
    }
}

/// The library names a bad value by its field in the table (and its place
/// in a description the command wrote itself); here it is the command's
/// option.
fn on_the_command_line(e: moyo::Error) -> String {
    let moyo::Error::Invalid { field, message, .. } = &e else {
        return e.to_string();
    };
    let Some(rest) = field.strip_prefix("layers[0].lsystem[0]") else {
        return e.to_string();
    };
    let rest = rest.trim_start_matches('.');
    let option = match rest.split(['[', '.']).next().unwrap_or(rest) {
        // The table as a whole: its growth ran over a budget.
        "" => "--iterations",
        "rules" => "--rule",
        "constants" => "--define",
        "sketch" if rest.starts_with("sketch.a") || rest.starts_with("sketch.c") => "--rule",
        "sketch" => "--module",
        "axiom" => "--axiom",
        "iterations" => "--iterations",
        "angle" => "--angle",
        "width" => "--width",
        "ignore" => "--ignore",
        _ => return format!("{rest}: {message}"),
    };
    if rest.is_empty() || rest == &option[2..] {
        format!("{option}: {message}")
    } else {
        format!("{option} ({rest}): {message}")
    }
}

/// Renders `spec` with the files beside `base`.
fn render(spec: &ValidSpec, base: &Path) -> Result<Rendered, CliError> {
    let library = project::load_motifs(spec, base)?;
    project::render_with_progress(spec, &library, &mut |_| {})
        .map_err(|e| CliError::Message(on_the_command_line(e)))
}

/// Whether `--frames dir` writes a file at `path`: its `growth.svg`, or
/// a frame (`frame-000.svg`, `frame-000.png`, …).
fn frames_write(dir: &Path, path: &Path) -> bool {
    let Some(name) = path.file_name().and_then(|n| n.to_str()) else {
        return false;
    };
    let frame = is_frame(name);
    let folder = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    (frame || name == "growth.svg") && identity(folder) == identity(dir)
}

/// Whether `name` is the name of a frame `--frames` writes
/// (`frame-000.svg`, `frame-000.png`, …).
fn is_frame(name: &str) -> bool {
    name.strip_prefix("frame-")
        .and_then(|rest| rest.strip_suffix(".svg").or(rest.strip_suffix(".png")))
        .is_some_and(|k| k.len() >= 3 && k.bytes().all(|b| b.is_ascii_digit()))
}

/// Removes the frames in `dir` that this run did not write (`written`):
/// those of an earlier, longer growth, which would play on after this
/// one's. Only names `--frames` writes are touched.
fn remove_old_frames(dir: &Path, written: &[PathBuf]) -> Result<(), CliError> {
    let io = |path: &Path, e: std::io::Error| CliError::Message(format!("{}: {e}", path.display()));
    let entries = std::fs::read_dir(dir).map_err(|e| io(dir, e))?;
    for entry in entries {
        let entry = entry.map_err(|e| io(dir, e))?;
        let path = entry.path();
        let old = entry.file_name().to_str().is_some_and(is_frame)
            && entry.file_type().is_ok_and(|t| t.is_file())
            && !written.contains(&path);
        if old {
            std::fs::remove_file(&path).map_err(|e| {
                CliError::Message(format!("{}: an old frame not removed: {e}", path.display()))
            })?;
        }
    }
    Ok(())
}

/// `moyo lsystem`.
pub(crate) fn lsystem(args: &LSystemArgs) -> Result<(), CliError> {
    let inputs: Vec<Named<'_>> = args
        .stroke
        .iter()
        .map(|p| ("--stroke", p.as_path()))
        .collect();
    let mut outputs: Vec<Named<'_>> = vec![("-o", &args.output)];
    outputs.extend(args.png.as_deref().map(|p| ("--png", p)));
    check_outputs(&inputs, &outputs)?;
    if let Some(dir) = &args.frames {
        if std::fs::metadata(dir).is_ok_and(|m| !m.is_dir()) {
            return Err(CliError::Message(format!(
                "--frames {}: not a folder; name a folder for the frames",
                dir.display()
            )));
        }
        let named = inputs.iter().chain(&outputs);
        if let Some((flag, path)) = named.into_iter().find(|(_, p)| frames_write(dir, p)) {
            return Err(CliError::Message(format!(
                "{flag} {}: --frames {} writes a file of that name there; \
                 choose another name or folder",
                path.display(),
                dir.display()
            )));
        }
    }
    let spec = args.scene()?;
    let base = args
        .stroke
        .as_deref()
        .and_then(Path::parent)
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    // Everything is computed before anything is written.
    let rendered = render(&spec, &base)?;
    if rendered.scene.path_count() == 0 {
        return Err(CliError::Message(match &args.stroke {
            Some(path) => format!(
                "--stroke {}: nothing grew: the sketch takes one step per --module \
                 ({} mm) of stroke, and the stroke is shorter than that or leaves the page at once",
                path.display(),
                args.module()
            ),
            None => "nothing drawn: the rules' word has no symbol that draws a line \
                     (F, G or a motif) after the rewriting steps; check --axiom and --rule"
                .to_string(),
        }));
    }
    let png = match &args.png {
        Some(_) => Some(moyo::output::render_png(&rendered.preview_svg(), args.dpi)?),
        None => None,
    };
    // A folder for the frames that this run made is taken away again if
    // it writes nothing.
    let mut made = MadeFolders::default();
    let frames = match write_outputs(&spec, &base, &rendered, png.as_deref(), args, &mut made) {
        Ok(frames) => frames,
        Err(e) => {
            made.remove();
            return Err(e);
        }
    };
    let stats = rendered.stats();
    eprintln!(
        "wrote {}{} ({} paths, {:.0} mm pen-down){}",
        args.output.display(),
        args.png
            .as_ref()
            .map(|p| format!(" and {}", p.display()))
            .unwrap_or_default(),
        stats.paths,
        stats.pen_down_mm,
        args.frames
            .as_ref()
            .map(|d| format!(", and {frames} frames in {}", d.display()))
            .unwrap_or_default(),
    );
    for note in &rendered.notes {
        eprintln!("{}: {}", note.motif, note.text);
    }
    Ok(())
}

/// The most growth frames written.
const MAX_FRAMES: u32 = 1000;

/// Writes the drawing (`rendered`, and its `png`) and, with `--frames`,
/// the frames of its growth and `growth.svg`, all or none: each goes to
/// its temporary file as soon as it is made, and all are renamed at the
/// end, so no frame's drawing is held longer than it takes to write it
/// (only each frame's SVG, for `growth.svg`). Frames of an earlier run
/// this one did not write are then removed. Returns the number of frames.
fn write_outputs(
    spec: &ValidSpec,
    base: &Path,
    rendered: &Rendered,
    png: Option<&[u8]>,
    args: &LSystemArgs,
    made: &mut MadeFolders,
) -> Result<usize, CliError> {
    if let Some(dir) = &args.frames {
        made.make(dir)?;
    }
    let mut staged = Staged::default();
    staged.stage(&args.output, rendered.svg.as_bytes())?;
    if let (Some(path), Some(bytes)) = (&args.png, png) {
        staged.stage(path, bytes)?;
    }
    let Some(dir) = &args.frames else {
        staged.commit()?;
        return Ok(0);
    };
    let mut written = Vec::new();
    let mut svgs = Vec::new();
    each_frame(spec, base, rendered, args, |k, frame, png| {
        let path = dir.join(format!("frame-{k:03}.svg"));
        staged.stage(&path, frame.svg.as_bytes())?;
        written.push(path);
        if let Some(bytes) = png {
            let path = dir.join(format!("frame-{k:03}.png"));
            staged.stage(&path, bytes)?;
            written.push(path);
        }
        svgs.push(frame.svg);
        Ok(())
    })?;
    let growth = {
        let svgs: Vec<&str> = svgs.iter().map(String::as_str).collect();
        moyo::output::animated_svg(&svgs)?
    };
    staged.stage(&dir.join("growth.svg"), growth.as_bytes())?;
    staged.commit()?;
    remove_old_frames(dir, &written)?;
    Ok(svgs.len())
}

/// Hands `write` each frame of the growth in turn — the drawing after
/// each rewriting step (or module step of a sketch), up to the whole of
/// `full` — with its PNG when `--png` asks for one.
fn each_frame<W>(
    spec: &ValidSpec,
    base: &Path,
    full: &Rendered,
    args: &LSystemArgs,
    mut write: W,
) -> Result<(), CliError>
where
    W: FnMut(usize, Rendered, Option<&[u8]>) -> Result<(), CliError>,
{
    let precision = spec.output.precision;
    let whole = full.dump(precision);
    for k in 0..=MAX_FRAMES {
        let step = spec
            .edit(|s| {
                let t = &mut s.layers[0].lsystem[0];
                match &mut t.sketch {
                    Some(sketch) => sketch.steps = Some(k),
                    None => t.iterations = k,
                }
            })
            .map_err(|e| CliError::Message(on_the_command_line(e)))?;
        let r = render(&step, base)?;
        let png = match &args.png {
            Some(_) => Some(moyo::output::render_png(&r.preview_svg(), args.dpi)?),
            None => None,
        };
        let last = r.dump(precision) == whole;
        write(k as usize, r, png.as_deref())?;
        if last {
            break;
        }
    }
    Ok(())
}
