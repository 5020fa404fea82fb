//! `moyo plot` and `moyo stats`: the plot pipeline on any SVG.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};

use super::{
    as_typed, check_outputs, extension, stdout_error, warn_outside_page, CliError, Named, Typed,
};
use moyo::input::{ImportOptions, Imported, PenGrouping};
use moyo::output::device::{BuiltIn, Device, DeviceSpec, BUILT_IN};
use moyo::output::dxf::DxfOptions;
use moyo::output::gcode::{GcodeOptions, Origin};
use moyo::output::hpgl::{CutterOptions, HpglOptions};
use moyo::output::{write_all_atomic, RunOptions, SvgOptions};
use moyo::plot::{
    self, BlotOptions, DebrisOptions, DedupeOptions, HatchOptions, MergeOptions, MultipassOptions,
    OccludeOptions, PlotOptions, SimplifyOptions, SortOptions, Speeds, TransformOptions,
};
use moyo::project::{self, PlotFormat, PlotJob, Preview};

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum OutputFormat {
    Svg,
    Gcode,
    Hpgl,
    Dxf,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum OriginArg {
    BottomLeft,
    TopLeft,
}

#[derive(Args)]
pub(crate) struct PlotArgs {
    /// The SVG to plot (Inkscape layers, or stroke colours, become pens).
    input: PathBuf,
    /// Output file.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    pens: PenArgs,
    /// Output format; by default the device's (--device, or a moyo SVG's
    /// own), else from the output's extension (.svg; .gcode, .nc, .ngc, .g
    /// → gcode; .hpgl, .plt, .hgl → hpgl; .dxf). Another extension needs
    /// it. A cutter's output (HPGL with --cutter, DXF) is cut inside first.
    #[arg(long, value_enum)]
    format: Option<OutputFormat>,

    /// Remove strokes hidden behind closed shapes in front.
    #[arg(long, help_heading = "Stages")]
    occlude: bool,
    /// With --occlude: merge each group of closed shapes (a tree) into one
    /// silhouette first.
    #[arg(long, requires = "occlude", help_heading = "Stages")]
    silhouettes: bool,
    /// With --occlude: keep the visible colour of partly hidden filled
    /// shapes for the preview, in a `%` layer that is never plotted.
    #[arg(long, requires = "occlude", help_heading = "Stages")]
    preview_fills: bool,
    /// Hatch fills with lines this far apart (mm).
    #[arg(long, value_name = "SPACING", help_heading = "Stages")]
    hatch: Option<f64>,
    /// Hatch angle in degrees.
    #[arg(
        long,
        default_value_t = 45.0,
        requires = "hatch",
        help_heading = "Stages"
    )]
    hatch_angle: f64,
    /// Cross-hatch (a second set of lines at 90°).
    #[arg(long, requires = "hatch", help_heading = "Stages")]
    cross: bool,
    /// Keep hatch lines this far inside the outline (mm).
    #[arg(
        long,
        default_value_t = 0.0,
        requires = "hatch",
        help_heading = "Stages"
    )]
    hatch_inset: f64,
    /// Take out line work that lies on other line work of the same pen,
    /// within TOL mm (default: a quarter of the pen's width).
    #[arg(long, value_name = "TOL", num_args = 0..=1, help_heading = "Stages")]
    dedupe: Option<Option<f64>>,
    /// Trim line ends where a square millimetre of the paper would hold
    /// more than LIMIT times the ink that covers it solid (0.5–10,
    /// default 2): converging lines stop short instead of blotting.
    #[arg(long, value_name = "LIMIT", num_args = 0..=1, default_missing_value = "2", help_heading = "Stages")]
    blots: Option<f64>,
    /// Take out strokes shorter than LEN mm that touch other line work of
    /// the same pen (default: the pen's width); isolated dots stay.
    #[arg(long, value_name = "LEN", num_args = 0..=1, help_heading = "Stages")]
    debris: Option<Option<f64>>,
    /// Join paths whose ends are within TOL mm (default 0.05).
    #[arg(long, value_name = "TOL", num_args = 0..=1, default_missing_value = "0.05", help_heading = "Stages")]
    merge: Option<f64>,
    /// Order paths to shorten pen-up travel.
    #[arg(long, help_heading = "Stages")]
    sort: bool,
    /// Drop points within TOL mm.
    #[arg(long, value_name = "TOL", help_heading = "Stages")]
    simplify: Option<f64>,
    /// Draw every path N times (1–100).
    #[arg(long, value_name = "N", help_heading = "Stages")]
    multipass: Option<u32>,
    /// Scale the drawing to fit inside the page margins (mm, default 10).
    #[arg(long, help_heading = "Transform")]
    fit: bool,
    /// Margin for --fit, mm.
    #[arg(long, value_name = "MM", requires = "fit", help_heading = "Transform")]
    fit_margin: Option<f64>,
    /// Centre the drawing on the page.
    #[arg(long, help_heading = "Transform")]
    centre: bool,
    /// Scale the drawing about the page centre.
    #[arg(long, default_value_t = 1.0, help_heading = "Transform")]
    scale: f64,
    /// Rotate the drawing about the page centre, degrees clockwise.
    #[arg(long, default_value_t = 0.0, help_heading = "Transform")]
    rotate: f64,

    /// Decimals in SVG and G-code output and the --preview-svg (0–8)
    /// [default: 3].
    #[arg(long, value_parser = clap::value_parser!(u8).range(0..=8), help_heading = "Output")]
    precision: Option<u8>,
    /// Also write a PNG preview of the result, in colour (rendered from
    /// the SVG of --preview-svg).
    #[arg(long, help_heading = "Output")]
    png: Option<PathBuf>,
    /// Also write the colour preview as SVG: the result plus fill colours
    /// and `%` layers, for looking at, not for plotting.
    #[arg(long, value_name = "SVG", help_heading = "Output")]
    preview_svg: Option<PathBuf>,
    /// Resolution of the PNG preview (1–2400).
    #[arg(long, default_value_t = 150.0, value_parser = super::parse_dpi, requires = "png", help_heading = "Output")]
    dpi: f64,
    /// Draw pen-up travel in red on the PNG preview (not in the output).
    #[arg(long, requires = "png", help_heading = "Output")]
    show_travel: bool,

    /// The machine: a built-in profile (`moyo devices` lists them) or a
    /// profile file (TOML). It sets the format and every G-code or HPGL
    /// option below; the flags change what it says. Without it, a moyo
    /// SVG's own `[device]` counts, else the defaults.
    #[arg(long, value_name = "NAME|FILE", help_heading = "Machine")]
    device: Option<String>,
    /// Refill the pen after at most MM of drawing: runs end between
    /// strokes, a longer stroke is cut into whole runs.
    #[arg(long, value_name = "MM", help_heading = "Machine")]
    refill: Option<f64>,
    /// With --refill: dip the pen at machine X,Y mm (else pause there).
    #[arg(long, value_name = "X,Y", requires = "refill", value_parser = parse_point, allow_hyphen_values = true, help_heading = "Machine")]
    refill_at: Option<[f64; 2]>,
    /// Resume a failed plot: leave out its first MM of drawing.
    #[arg(long, value_name = "MM", help_heading = "Machine")]
    from_distance: Option<f64>,

    /// G-code: command that lifts the pen [default: M5].
    #[arg(long, help_heading = "G-code")]
    pen_up: Option<String>,
    /// G-code: command that lowers the pen [default: M3 S1000].
    #[arg(long, help_heading = "G-code")]
    pen_down: Option<String>,
    /// G-code: pause after each pen move, seconds [default: 0.15].
    #[arg(long, help_heading = "G-code")]
    pen_delay: Option<f64>,
    /// G-code: drawing feed rate, mm/min [default: 1500].
    #[arg(long, help_heading = "G-code")]
    feed: Option<f64>,
    /// G-code: travel feed rate, mm/min (0: rapid moves, G0) [default:
    /// 4000].
    #[arg(long, help_heading = "G-code")]
    travel_feed: Option<f64>,
    /// G-code: where the machine's origin is on the page [default:
    /// bottom-left].
    #[arg(long, value_enum, help_heading = "G-code")]
    origin: Option<OriginArg>,
    /// G-code: negate machine Y.
    #[arg(long, help_heading = "G-code")]
    flip_y: bool,
    /// G-code: write arcs (G2/G3) where strokes follow a circle within TOL
    /// mm (default 0.01).
    #[arg(long, value_name = "TOL", num_args = 0..=1, default_missing_value = "0.01", help_heading = "G-code")]
    arcs: Option<f64>,

    /// HPGL: cutter mode (closed outlines, overcut, drag-knife offset).
    #[arg(long, help_heading = "HPGL")]
    cutter: bool,
    /// HPGL cutter: cut past the start of closed outlines, mm [default: 1].
    #[arg(long, help_heading = "HPGL")]
    overcut: Option<f64>,
    /// HPGL cutter: drag-knife blade offset, mm [default: 0.25].
    #[arg(long, help_heading = "HPGL")]
    knife_offset: Option<f64>,
    /// HPGL: mirror left–right (cutting on the back of the media).
    #[arg(long, help_heading = "HPGL")]
    mirror: bool,
    /// HPGL: the coordinates the device accepts, in plotter units (default
    /// HP-GL's -32768,32767; HP-GL/2 devices take up to ±1073741823).
    #[arg(long, value_name = "MIN,MAX", value_parser = parse_range, allow_hyphen_values = true, help_heading = "HPGL")]
    device_range: Option<[i32; 2]>,
    /// HPGL: plotter units per millimetre [default: 40].
    #[arg(long, value_name = "UNITS", help_heading = "HPGL")]
    units_per_mm: Option<f64>,

    #[command(flatten)]
    speeds: SpeedArgs,
}

#[derive(Args)]
pub(crate) struct SpeedArgs {
    /// Drawing speed for the time estimates, mm/s (the most it reaches
    /// with acceleration).
    #[arg(long, default_value_t = Speeds::DEFAULT.pen_down_mm_s, help_heading = "Time estimate")]
    speed_down: f64,
    /// Travel speed for the time estimates, mm/s (likewise).
    #[arg(long, default_value_t = Speeds::DEFAULT.pen_up_mm_s, help_heading = "Time estimate")]
    speed_up: f64,
    /// Time of one pen lift and lowering, s.
    #[arg(long, default_value_t = Speeds::DEFAULT.pen_lift_s, help_heading = "Time estimate")]
    lift_time: f64,
    /// Acceleration while drawing, for the time with acceleration, mm/s².
    #[arg(long, value_name = "MM_S2", default_value_t = Speeds::DEFAULT.pen_down_accel_mm_s2, help_heading = "Time estimate")]
    accel_down: f64,
    /// Acceleration while travelling, for the time with acceleration,
    /// mm/s².
    #[arg(long, value_name = "MM_S2", default_value_t = Speeds::DEFAULT.pen_up_accel_mm_s2, help_heading = "Time estimate")]
    accel_up: f64,
    /// Cornering distance (junction deviation) for the time with
    /// acceleration, mm: 0 stops at every corner, more takes corners
    /// faster.
    #[arg(long, value_name = "MM", default_value_t = Speeds::DEFAULT.cornering_mm, help_heading = "Time estimate")]
    cornering: f64,
}

impl SpeedArgs {
    /// The option that sets each field of [`Speeds`], for errors.
    const OPTIONS: Typed<'static> = &[
        ("pen_down_mm_s", "--speed-down"),
        ("pen_up_mm_s", "--speed-up"),
        ("pen_lift_s", "--lift-time"),
        ("pen_down_accel_mm_s2", "--accel-down"),
        ("pen_up_accel_mm_s2", "--accel-up"),
        ("cornering_mm", "--cornering"),
    ];

    fn speeds(&self) -> Result<Speeds, CliError> {
        let s = Speeds::DEFAULT
            .with_pen_down_mm_s(self.speed_down)
            .with_pen_up_mm_s(self.speed_up)
            .with_pen_lift_s(self.lift_time)
            .with_pen_down_accel_mm_s2(self.accel_down)
            .with_pen_up_accel_mm_s2(self.accel_up)
            .with_cornering_mm(self.cornering);
        s.validate().map_err(|e| as_typed(e, Self::OPTIONS))?;
        Ok(s)
    }
}

#[derive(Args)]
pub(crate) struct StatsArgs {
    /// The SVG to measure.
    input: PathBuf,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    pens: PenArgs,
    #[command(flatten)]
    speeds: SpeedArgs,
}

/// How an SVG's paths become pens: `--pens`, `--single-layer`.
#[derive(Args)]
pub(crate) struct PenArgs {
    /// Without Inkscape layers, pens come from colours: at most N (0–999),
    /// colours beyond merged by nearest colour; 0 for one pen per colour.
    /// A file with layers keeps its layers as pens [default: 8]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(0..=999))]
    pens: Option<u32>,
    /// Everything on one pen (pen 1), layers and colours ignored;
    /// documentation (%) layers stay apart.
    #[arg(long, conflicts_with = "pens")]
    single_layer: bool,
}

impl PenArgs {
    /// The import options these flags ask for.
    pub(crate) fn import_options(&self) -> ImportOptions {
        let options = ImportOptions::DEFAULT
            .with_max_pens(self.pens.unwrap_or(ImportOptions::DEFAULT_MAX_PENS));
        if self.single_layer {
            options.with_pens(PenGrouping::Single)
        } else {
            options
        }
    }
}

/// Reads the SVG at `path` with the pens `pens` asks for, telling what
/// its import left out. `--pens` on a file whose Inkscape layers are its
/// pens would change nothing: refused.
pub(crate) fn load_svg(path: &Path, pens: &PenArgs) -> Result<Imported, CliError> {
    let imported = project::read_svg(path, &pens.import_options())?;
    if let (Some(n), true) = (pens.pens, imported.pens_from_layers) {
        return Err(CliError::Message(format!(
            "--pens {n}: {} has Inkscape layers, and its layers are its pens ({}); \
             --pens groups the colours of a file without layers. Leave it out, \
             or give --single-layer for one pen",
            path.display(),
            imported.scene.pens.len()
        )));
    }
    for w in &imported.warnings {
        eprintln!("warning: {}: {w}", path.display());
    }
    Ok(imported)
}

impl PlotArgs {
    fn plot_options(&self) -> PlotOptions {
        let transform =
            (self.fit || self.centre || self.scale != 1.0 || self.rotate != 0.0).then(|| {
                let mut t = TransformOptions::DEFAULT;
                t.fit = self.fit;
                t.centre = self.centre;
                t.scale = self.scale;
                t.rotate_deg = self.rotate;
                t.margin = self.fit_margin;
                t
            });
        PlotOptions {
            transform,
            occlude: self.occlude.then(|| {
                let mut o = OccludeOptions::default();
                o.silhouettes = self.silhouettes;
                o.preview_fills = self.preview_fills;
                o
            }),
            hatch: self.hatch.map(|spacing| {
                HatchOptions::DEFAULT
                    .with_spacing(spacing)
                    .with_angle_deg(self.hatch_angle)
                    .with_cross(self.cross)
                    .with_inset(self.hatch_inset)
            }),
            dedupe: self
                .dedupe
                .map(|tolerance| DedupeOptions::DEFAULT.with_tolerance(tolerance)),
            blots: self
                .blots
                .map(|limit| BlotOptions::DEFAULT.with_limit(limit)),
            debris: self
                .debris
                .map(|length| DebrisOptions::DEFAULT.with_length(length)),
            merge: self.merge.map(|tolerance| {
                let mut m = MergeOptions::DEFAULT;
                m.tolerance = tolerance;
                m
            }),
            simplify: self.simplify.map(|tolerance| {
                let mut s = SimplifyOptions::DEFAULT;
                s.tolerance = tolerance;
                s
            }),
            sort: self.sort.then_some(SortOptions::DEFAULT),
            multipass: self.multipass.map(|passes| {
                let mut m = MultipassOptions::DEFAULT;
                m.passes = passes;
                m
            }),
            // The job turns it on for a cutter's output.
            inside_first: false,
        }
    }

    /// What `moyo plot` asks of the library, for `device` (from
    /// --device, or the drawing's own `[device]`).
    fn job(&self, device: Option<Device>) -> Result<PlotJob, CliError> {
        let format = match (self.format(), device) {
            (Some(OutputFormat::Svg), Some(_)) => {
                return Err(CliError::Message(
                    "--device: writes G-code or HPGL, but the output is SVG (name it .gcode or .hpgl, or give --format)"
                        .into(),
                ))
            }
            (Some(OutputFormat::Svg), None) => {
                PlotFormat::Svg(SvgOptions::DEFAULT.with_precision(self.precision()))
            }
            (Some(OutputFormat::Dxf), Some(_)) => {
                return Err(CliError::Message(
                    "--device: writes G-code or HPGL, but the output is DXF (name it .gcode or .hpgl, or give --format)"
                        .into(),
                ))
            }
            (Some(OutputFormat::Dxf), None) => PlotFormat::Dxf(DxfOptions::DEFAULT),
            (Some(OutputFormat::Gcode) | None, Some(Device::Gcode(o))) => {
                PlotFormat::Gcode(self.gcode_options(o))
            }
            (Some(OutputFormat::Hpgl) | None, Some(Device::Hpgl(o))) => {
                PlotFormat::Hpgl(self.hpgl_options(o))
            }
            (Some(asked), Some(_)) => {
                let (asked, device) = match asked {
                    OutputFormat::Gcode => ("G-code", "an HPGL"),
                    _ => ("HPGL", "a G-code"),
                };
                return Err(CliError::Message(format!(
                    "--device: the output is {asked}, but the device is {device} machine"
                )));
            }
            (Some(OutputFormat::Gcode), None) => {
                PlotFormat::Gcode(self.gcode_options(GcodeOptions::default()))
            }
            (Some(OutputFormat::Hpgl), None) => {
                PlotFormat::Hpgl(self.hpgl_options(HpglOptions::DEFAULT))
            }
            (None, None) => return Err(CliError::Message(self.unknown_extension())),
        };
        let preview = self.png.as_ref().map(|_| {
            Preview::DEFAULT
                .with_dpi(self.dpi)
                .with_show_travel(self.show_travel)
        });
        Ok(PlotJob::new(format)
            .with_stages(self.plot_options())
            .with_silhouettes(self.silhouettes)
            .with_preview(preview)
            .with_import(self.pens.import_options()))
    }

    /// The decimals asked for, else the default.
    fn precision(&self) -> u8 {
        self.precision.unwrap_or(SvgOptions::DEFAULT.precision)
    }

    /// Refuses the options that `format` would ignore, saying which
    /// output they belong to: a flag that changes nothing is a surprise.
    fn refuse_unused(&self, format: &PlotFormat) -> Result<(), CliError> {
        let output = format.name();
        let gcode = matches!(format, PlotFormat::Gcode(_));
        let hpgl = matches!(format, PlotFormat::Hpgl(_));
        let groups: [OptionGroup<'_>; 3] = [
            (
                "a G-code option",
                ".gcode",
                gcode,
                &[
                    ("--pen-up", self.pen_up.is_some()),
                    ("--pen-down", self.pen_down.is_some()),
                    ("--pen-delay", self.pen_delay.is_some()),
                    ("--feed", self.feed.is_some()),
                    ("--travel-feed", self.travel_feed.is_some()),
                    ("--origin", self.origin.is_some()),
                    ("--flip-y", self.flip_y),
                    ("--arcs", self.arcs.is_some()),
                ],
            ),
            (
                "an HPGL option",
                ".hpgl",
                hpgl,
                &[
                    ("--cutter", self.cutter),
                    ("--overcut", self.overcut.is_some()),
                    ("--knife-offset", self.knife_offset.is_some()),
                    ("--mirror", self.mirror),
                    ("--device-range", self.device_range.is_some()),
                    ("--units-per-mm", self.units_per_mm.is_some()),
                ],
            ),
            (
                "a machine option",
                ".gcode or .hpgl",
                gcode || hpgl,
                &[
                    ("--refill", self.refill.is_some()),
                    ("--from-distance", self.from_distance.is_some()),
                ],
            ),
        ];
        for (what, needs, chosen, options) in groups {
            if let Some((option, _)) = options.iter().find(|(_, given)| *given && !chosen) {
                return Err(CliError::Message(format!(
                    "{option}: {what}, but the output is {output}, which it would not change; \
                     leave it out, or write {needs} (by the output's extension or --format)"
                )));
            }
        }
        let decimals = matches!(format, PlotFormat::Svg(_)) || gcode || self.preview_svg.is_some();
        if self.precision.is_some() && !decimals {
            return Err(CliError::Message(format!(
                "--precision: sets the decimals of SVG and G-code, but the output is {output} \
                 (and no --preview-svg is asked for); leave it out"
            )));
        }
        Ok(())
    }

    /// The format asked for: --format, else the output's extension when
    /// it names one (.gcode, .nc, .ngc, .g; .hpgl, .plt, .hgl, .svg, .dxf).
    fn format(&self) -> Option<OutputFormat> {
        self.format
            .or_else(|| match extension(&self.output).as_str() {
                "gcode" | "nc" | "ngc" | "g" => Some(OutputFormat::Gcode),
                "hpgl" | "plt" | "hgl" => Some(OutputFormat::Hpgl),
                "svg" => Some(OutputFormat::Svg),
                "dxf" => Some(OutputFormat::Dxf),
                _ => None,
            })
    }

    /// Why an output that names no format by its extension is refused
    /// (when neither --format nor a device chooses one).
    fn unknown_extension(&self) -> String {
        let output = self.output.display();
        let allowed = ".svg, .gcode, .nc, .ngc, .g, .hpgl, .plt, .hgl or .dxf";
        match self.output.extension() {
            Some(ext) => format!(
                "-o {output}: the extension .{} names no output format; \
                 use {allowed}, or give --format",
                ext.to_string_lossy()
            ),
            None => format!(
                "-o {output}: no extension to tell the output format by; \
                 use {allowed}, or give --format"
            ),
        }
    }

    fn runs(&self, runs: RunOptions) -> RunOptions {
        let runs = match self.refill {
            Some(mm) => runs.with_refill_mm(Some(mm)).with_refill_at(self.refill_at),
            None => runs,
        };
        match self.from_distance {
            Some(mm) => runs.with_from_distance_mm(mm),
            None => runs,
        }
    }

    /// `base` (the device's, or the defaults) with the flags given.
    fn gcode_options(&self, base: GcodeOptions) -> GcodeOptions {
        let mut o = base;
        if let Some(up) = &self.pen_up {
            o.pen_up = up.clone();
        }
        if let Some(down) = &self.pen_down {
            o.pen_down = down.clone();
        }
        if let Some(delay) = self.pen_delay {
            o = o.with_pen_delay_s(delay);
        }
        if let Some(feed) = self.feed {
            o = o.with_feed_down_mm_min(feed);
        }
        if let Some(travel) = self.travel_feed {
            o = o.with_feed_up_mm_min((travel != 0.0).then_some(travel));
        }
        if let Some(origin) = self.origin {
            o = o.with_origin(match origin {
                OriginArg::BottomLeft => Origin::BottomLeft,
                OriginArg::TopLeft => Origin::TopLeft,
            });
        }
        if self.flip_y {
            o = o.with_flip_y(true);
        }
        if self.arcs.is_some() {
            o = o.with_arcs(self.arcs);
        }
        if let Some(p) = self.precision {
            o = o.with_precision(p);
        }
        let runs = self.runs(o.runs);
        o.with_runs(runs)
    }

    /// `base` (the device's, or the defaults) with the flags given.
    fn hpgl_options(&self, base: HpglOptions) -> HpglOptions {
        let mut o = base;
        if self.cutter || self.overcut.is_some() || self.knife_offset.is_some() {
            let mut c = o.cutter.unwrap_or(CutterOptions::DEFAULT);
            if let Some(mm) = self.overcut {
                c.overcut_mm = mm;
            }
            if let Some(mm) = self.knife_offset {
                c.knife_offset_mm = mm;
            }
            o = o.with_cutter(Some(c));
        }
        if self.mirror {
            o = o.with_mirror(true, o.mirror_y);
        }
        if let Some([min, max]) = self.device_range {
            o = o.with_device_range(min, max);
        }
        if let Some(units) = self.units_per_mm {
            o = o.with_units_per_mm(units);
        }
        o.with_runs(self.runs(o.runs))
    }
}

/// Options that only one kind of output uses: what they are, the output
/// they need, whether it is chosen, and each option with whether it was
/// given.
type OptionGroup<'a> = (&'a str, &'a str, bool, &'a [(&'a str, bool)]);

/// The option that sets each field `moyo plot` checks, for errors.
const PLOT_OPTIONS: Typed<'static> = &[
    ("plot.transform.rotate_deg", "--rotate"),
    ("plot.transform.scale", "--scale"),
    ("plot.transform.margin", "--fit-margin"),
    ("plot.hatch.spacing", "--hatch"),
    ("plot.hatch.angle_deg", "--hatch-angle"),
    ("plot.hatch.inset", "--hatch-inset"),
    ("plot.dedupe.tolerance", "--dedupe"),
    ("plot.merge.tolerance", "--merge"),
    ("plot.blots.limit", "--blots"),
    ("plot.debris.length", "--debris"),
    ("plot.simplify.tolerance", "--simplify"),
    ("plot.multipass.passes", "--multipass"),
    ("gcode.feed_down_mm_min", "--feed"),
    ("gcode.feed_up_mm_min", "--travel-feed"),
    ("gcode.arcs", "--arcs"),
    ("gcode.pen_delay_s", "--pen-delay"),
    ("gcode.runs.refill_mm", "--refill"),
    ("gcode.runs.refill_at", "--refill-at"),
    ("gcode.runs.from_distance_mm", "--from-distance"),
    ("hpgl.units_per_mm", "--units-per-mm"),
    ("hpgl.device_range", "--device-range"),
    ("hpgl.cutter.overcut_mm", "--overcut"),
    ("hpgl.cutter.knife_offset_mm", "--knife-offset"),
    ("hpgl.runs.refill_mm", "--refill"),
    ("hpgl.runs.refill_at", "--refill-at"),
    ("hpgl.runs.from_distance_mm", "--from-distance"),
];

/// `X,Y`: two numbers.
fn parse_point(s: &str) -> Result<[f64; 2], String> {
    let (x, y) = s
        .split_once(',')
        .ok_or_else(|| format!("expected X,Y, got '{s}'"))?;
    let number = |t: &str| t.trim().parse::<f64>().map_err(|e| format!("'{t}': {e}"));
    Ok([number(x)?, number(y)?])
}

/// The device `--device` names: a built-in profile, else a profile file.
fn device_arg(arg: &str) -> Result<Device, CliError> {
    let spec = match BuiltIn::get(arg) {
        Some(b) => DeviceSpec::parse(b.text)?,
        None => {
            let path = Path::new(arg);
            if !path.is_file() {
                return Err(CliError::Message(format!(
                    "--device: '{arg}' is neither a built-in profile ({}) nor a profile file",
                    BuiltIn::names()
                )));
            }
            let text = moyo::input::read_text(path)
                .map_err(|e| CliError::Message(format!("{arg}: {e}")))?;
            DeviceSpec::parse(&text).map_err(|e| CliError::Message(format!("{arg}: {e}")))?
        }
    };
    spec.resolve()
        .map_err(|e| CliError::Message(format!("--device {arg}: {e}")))
}

/// The `[device]` of the scene description a moyo SVG carries, if any.
fn embedded_device(path: &Path) -> Result<Option<Device>, CliError> {
    let Ok(text) = moyo::input::read_text(path) else {
        // The import reports an unreadable file.
        return Ok(None);
    };
    let Some(description) = moyo::embedded_description(&text) else {
        return Ok(None);
    };
    let Ok(spec) = moyo::SceneSpec::parse(&description, moyo::Format::Toml) else {
        return Ok(None);
    };
    match &spec.device {
        Some(device) => device.resolve().map(Some).map_err(|e| {
            CliError::Message(format!("{} (embedded description): {e}", path.display()))
        }),
        None => Ok(None),
    }
}

/// `MIN,MAX`: two integers.
fn parse_range(s: &str) -> Result<[i32; 2], String> {
    let (min, max) = s
        .split_once(',')
        .ok_or_else(|| format!("expected MIN,MAX, got '{s}'"))?;
    let number = |t: &str| t.trim().parse::<i32>().map_err(|e| format!("'{t}': {e}"));
    Ok([number(min)?, number(max)?])
}

/// `moyo plot`.
pub(crate) fn plot(args: &PlotArgs) -> Result<(), CliError> {
    let mut inputs: Vec<Named<'_>> = vec![("the input", &args.input)];
    // A profile file is read too (a built-in name is no file).
    inputs.extend(
        args.device
            .as_deref()
            .filter(|arg| BuiltIn::get(arg).is_none())
            .map(|arg| ("--device", Path::new(arg))),
    );
    let mut outputs: Vec<Named<'_>> = vec![("-o", &args.output)];
    outputs.extend(args.png.as_deref().map(|p| ("--png", p)));
    outputs.extend(args.preview_svg.as_deref().map(|p| ("--preview-svg", p)));
    check_outputs(&inputs, &outputs)?;
    let speeds = args.speeds.speeds()?;
    let device = match &args.device {
        Some(arg) => Some(device_arg(arg)?),
        // The drawing's own machine counts only for the language it
        // speaks: an SVG written from it, or the other language asked
        // for, takes no device from it.
        None => embedded_device(&args.input)?.filter(|d| {
            let fits = matches!(
                (args.format(), d),
                (None, _)
                    | (Some(OutputFormat::Gcode), Device::Gcode(_))
                    | (Some(OutputFormat::Hpgl), Device::Hpgl(_))
            );
            if !fits && !matches!(args.format(), Some(OutputFormat::Svg | OutputFormat::Dxf)) {
                eprintln!(
                    "warning: {}: its [device] is for another language than the output's; \
                     the output's defaults are used",
                    args.input.display()
                );
            }
            fits
        }),
    };
    let job = args.job(device)?;
    args.refuse_unused(&job.format)?;
    job.validate().map_err(|e| as_typed(e, PLOT_OPTIONS))?;
    let imported = load_svg(&args.input, &args.pens)?;
    // The stages join, split and drop paths: say what came in too.
    let read = plot::stats(&imported.scene, &speeds).paths;
    // Everything is computed before anything is written.
    let plotted = project::plot_scene(imported.scene, &job)?;
    let preview_svg = args
        .preview_svg
        .as_ref()
        .map(|path| (path, plotted.preview_svg(args.precision())));
    // All or none: a failed output leaves every old file.
    let mut files: Vec<(&Path, &[u8])> = vec![(&args.output, plotted.bytes.as_bytes())];
    if let Some((path, svg)) = &preview_svg {
        files.push((path, svg.as_bytes()));
    }
    if let (Some(path), Some(png)) = (&args.png, &plotted.png) {
        files.push((path, png));
    }
    write_all_atomic(&files)?;
    let s = plot::stats(&plotted.scene, &speeds);
    eprintln!(
        "wrote {} ({} paths from the input's {read}, {:.0} mm pen-down, {:.0} mm pen-up, about {} at constant speed, {} with acceleration)",
        args.output.display(),
        s.paths,
        s.pen_down_mm,
        s.pen_up_mm,
        duration(s.plot_time_s),
        duration(s.plot_time_accel_s)
    );
    for w in &plotted.warnings {
        eprintln!("warning: {w}");
    }
    warn_outside_page(&plotted.scene);
    Ok(())
}

fn duration(seconds: f64) -> String {
    let s = seconds.round() as u64;
    if s >= 3600 {
        format!("{}h{:02}m", s / 3600, (s % 3600) / 60)
    } else if s >= 60 {
        format!("{}m{:02}s", s / 60, s % 60)
    } else {
        format!("{s}s")
    }
}

/// One row of `moyo stats`.
struct Figures {
    paths: usize,
    down: f64,
    up: f64,
    time: f64,
    time_accel: f64,
    doubled: f64,
    debris: usize,
    densest: f64,
}

/// `moyo stats`.
pub(crate) fn stats(args: &StatsArgs) -> Result<(), CliError> {
    let speeds = args.speeds.speeds()?;
    let imported = load_svg(&args.input, &args.pens)?;
    let s = plot::stats(&imported.scene, &speeds);
    let mut out = std::io::stdout().lock();
    if args.json {
        let text = serde_json::to_string_pretty(&s)
            .map_err(|e| CliError::Message(format!("JSON: {e}")))?;
        writeln!(out, "{text}").map_err(stdout_error)?;
        return Ok(());
    }
    let row = |out: &mut dyn Write, name: &str, f: Figures| {
        writeln!(
            out,
            "{name:<24} {:>8} {:>14.1} {:>14.1} {:>10} {:>10} {:>11.1} {:>7} {:>8.1}",
            f.paths,
            f.down,
            f.up,
            duration(f.time),
            duration(f.time_accel),
            f.doubled,
            f.debris,
            f.densest
        )
    };
    writeln!(
        out,
        "{:<24} {:>8} {:>14} {:>14} {:>10} {:>10} {:>11} {:>7} {:>8}",
        "layer",
        "paths",
        "pen-down mm",
        "pen-up mm",
        "time",
        "accel time",
        "doubled mm",
        "debris",
        "densest"
    )
    .map_err(stdout_error)?;
    for l in &s.layers {
        let figures = Figures {
            paths: l.paths,
            down: l.pen_down_mm,
            up: l.pen_up_mm,
            time: l.plot_time_s,
            time_accel: l.plot_time_accel_s,
            doubled: l.doubled_mm,
            debris: l.debris,
            densest: l.densest,
        };
        row(&mut out, &l.name, figures).map_err(stdout_error)?;
    }
    let total = Figures {
        paths: s.paths,
        down: s.pen_down_mm,
        up: s.pen_up_mm,
        time: s.plot_time_s,
        time_accel: s.plot_time_accel_s,
        doubled: s.doubled_mm,
        debris: s.debris,
        densest: s.densest,
    };
    row(&mut out, "total", total).map_err(stdout_error)?;
    Ok(())
}

/// `moyo devices [NAME]`.
pub(crate) fn devices(name: Option<&str>) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    match name {
        Some(name) => {
            let b = BuiltIn::get(name).ok_or_else(|| {
                CliError::Message(format!(
                    "no device profile '{name}'; built in: {}",
                    BuiltIn::names()
                ))
            })?;
            write!(out, "{}", b.text).map_err(stdout_error)
        }
        None => {
            let width = BUILT_IN.iter().map(|b| b.name.len()).max().unwrap_or(0);
            for b in BUILT_IN {
                writeln!(out, "{:width$}  {}", b.name, b.about()).map_err(stdout_error)?;
            }
            Ok(())
        }
    }
}
