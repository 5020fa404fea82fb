//! `moyo stencil`: line art (an SVG or a scene description) made into a
//! stencil that holds together, written for a cutter.

use std::path::{Path, PathBuf};

use clap::Args;

use super::{check_outputs, extension, parse_dpi, CliError, Named};
use moyo::output::dxf::DxfOptions;
use moyo::output::hpgl::{CutterOptions, HpglOptions};
use moyo::output::{render_png, to_svg, write_all_atomic, SvgOptions};
use moyo::plot::{PlotOptions, SortOptions};
use moyo::project::{self, PlotFormat, PlotJob};
use moyo::stencil::{self, StencilOptions};
use moyo::{Format, ImportOptions, SceneSpec};

#[derive(Args)]
pub(crate) struct StencilArgs {
    /// The line art: an SVG, or a scene description (.toml, .json).
    input: PathBuf,
    /// The cut: .svg, .hpgl (.plt, .hgl; cutter mode) or .dxf.
    #[arg(short, long)]
    output: PathBuf,
    /// Width of a bridge that holds an island, mm.
    #[arg(long, default_value_t = StencilOptions::DEFAULT.bridge)]
    bridge: f64,
    /// A bridge every this many mm along an island's outline (0: one per
    /// island, across its narrowest gap).
    #[arg(long, default_value_t = StencilOptions::DEFAULT.bridge_every)]
    bridge_every: f64,
    /// The narrowest paper or cut-out the blade leaves, mm: narrower
    /// places are reported.
    #[arg(long, default_value_t = StencilOptions::DEFAULT.min_feature)]
    min_feature: f64,
    /// Cut every stroke at least --min-feature wide.
    #[arg(long)]
    widen: bool,
    /// Corners of the cut sharper than this many degrees are reported.
    #[arg(long, default_value_t = StencilOptions::DEFAULT.min_corner_deg)]
    min_corner_deg: f64,
    /// Round the paper's sharp tips between cut-outs off, so that a drag
    /// knife follows them.
    #[arg(long)]
    round_corners: bool,
    /// HPGL: cut past the start of closed outlines, mm [default: 1].
    #[arg(long)]
    overcut: Option<f64>,
    /// HPGL: drag-knife blade offset, mm [default: 0.25].
    #[arg(long)]
    knife_offset: Option<f64>,
    /// Also write a PNG of the sheet with its bridges (in red).
    #[arg(long)]
    png: Option<PathBuf>,
    /// Also write a PNG of the print: what ink passes through.
    #[arg(long, value_name = "PNG")]
    print_png: Option<PathBuf>,
    /// Resolution of the PNGs (1–2400) [default: 150].
    #[arg(long, value_parser = parse_dpi)]
    dpi: Option<f64>,
}

impl StencilArgs {
    fn options(&self) -> StencilOptions {
        StencilOptions::DEFAULT
            .with_bridge(self.bridge)
            .with_bridge_every(self.bridge_every)
            .with_min_feature(self.min_feature)
            .with_widen(self.widen)
            .with_min_corner_deg(self.min_corner_deg)
            .with_round_corners(self.round_corners)
    }

    /// The output format, by the output's extension. The options of
    /// another output than the one chosen are refused, saying why: they
    /// would change nothing.
    fn format(&self) -> Result<PlotFormat, CliError> {
        let ext = extension(&self.output);
        let knife = [
            ("--overcut", self.overcut.is_some()),
            ("--knife-offset", self.knife_offset.is_some()),
        ];
        if let Some((option, _)) = knife.iter().find(|(_, given)| *given) {
            if matches!(ext.as_str(), "svg" | "dxf") {
                return Err(CliError::Message(format!(
                    "{option}: an HPGL cutter option, but the cut is written as {}, \
                     which it would not change; leave it out, or name the cut .hpgl",
                    ext.to_ascii_uppercase()
                )));
            }
        }
        if self.dpi.is_some() && self.png.is_none() && self.print_png.is_none() {
            return Err(CliError::Message(
                "--dpi: the resolution of --png and --print-png, and neither is asked for; \
                 leave it out, or give one"
                    .to_string(),
            ));
        }
        match ext.as_str() {
            "svg" => Ok(PlotFormat::Svg(SvgOptions::DEFAULT)),
            "dxf" => Ok(PlotFormat::Dxf(DxfOptions::DEFAULT)),
            "hpgl" | "plt" | "hgl" => {
                let mut c = CutterOptions::DEFAULT;
                if let Some(mm) = self.overcut {
                    c.overcut_mm = mm;
                }
                if let Some(mm) = self.knife_offset {
                    c.knife_offset_mm = mm;
                }
                Ok(PlotFormat::Hpgl(HpglOptions::DEFAULT.with_cutter(Some(c))))
            }
            _ => Err(CliError::Message(format!(
                "-o {}: name the cut .svg, .hpgl (.plt, .hgl) or .dxf",
                self.output.display()
            ))),
        }
    }
}

/// `--dpi` unless given.
const DEFAULT_DPI: f64 = 150.0;

/// The drawing in `path`: an SVG as it is, a scene description rendered.
fn read_drawing(path: &Path) -> Result<moyo::Scene, CliError> {
    let is_svg = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
    if is_svg {
        return Ok(project::read_svg(path, &ImportOptions::DEFAULT)?.scene);
    }
    let text = moyo::input::read_text(path)
        .map_err(|e| CliError::Message(format!("{}: {e}", path.display())))?;
    let spec = SceneSpec::parse(&text, Format::from_path(path))
        .map_err(|e| CliError::Message(format!("{}:{e}", path.display())))?;
    Ok(moyo::render(&spec)?.scene)
}

/// A library error in the command's words: an option's field becomes its
/// flag (`bridge_every` → `--bridge-every`), `input` the input file.
fn in_flags(e: moyo::Error, input: &Path) -> CliError {
    match e {
        moyo::Error::Invalid { field, message, .. } => {
            let what = if field == "input" {
                input.display().to_string()
            } else {
                format!("--{}", field.replace('_', "-"))
            };
            CliError::Message(format!("{what}: {message}"))
        }
        e => e.into(),
    }
}

/// `moyo stencil`.
pub(crate) fn stencil(args: &StencilArgs) -> Result<(), CliError> {
    let inputs: Vec<Named<'_>> = vec![("the input", &args.input)];
    let mut outputs: Vec<Named<'_>> = vec![("-o", &args.output)];
    outputs.extend(args.png.as_deref().map(|p| ("--png", p)));
    outputs.extend(args.print_png.as_deref().map(|p| ("--print-png", p)));
    check_outputs(&inputs, &outputs)?;
    let format = args.format()?;
    let options = args.options();
    options.validate().map_err(|e| in_flags(e, &args.input))?;
    let drawing = read_drawing(&args.input)?;
    let made = stencil::make(&drawing, &options).map_err(|e| in_flags(e, &args.input))?;
    // Cut inside first, each level in a short tour, whatever the format.
    let stages = PlotOptions {
        sort: Some(SortOptions::DEFAULT),
        inside_first: true,
        ..PlotOptions::default()
    };
    let cut = project::plot_scene(made.cut_scene(), &PlotJob::new(format).with_stages(stages))?;
    // Everything is computed before anything is written.
    let png = |scene: moyo::Scene| {
        render_png(
            &to_svg(&scene, &SvgOptions::PREVIEW),
            args.dpi.unwrap_or(DEFAULT_DPI),
        )
    };
    let sheet_png = args
        .png
        .as_ref()
        .map(|_| png(made.sheet_scene()))
        .transpose()?;
    let print_png = args
        .print_png
        .as_ref()
        .map(|_| png(made.print_scene()))
        .transpose()?;
    let mut files: Vec<(&Path, &[u8])> = vec![(&args.output, cut.bytes.as_bytes())];
    if let (Some(path), Some(bytes)) = (&args.png, &sheet_png) {
        files.push((path, bytes));
    }
    if let (Some(path), Some(bytes)) = (&args.print_png, &print_png) {
        files.push((path, bytes));
    }
    write_all_atomic(&files)?;
    eprint!("{}", made.report);
    eprintln!(
        "wrote {} ({} cuts)",
        args.output.display(),
        cut.scene.path_count()
    );
    // What the command can do about the blade's findings.
    if !made.report.narrow_cuts.is_empty() && !args.widen {
        eprintln!(
            "hint: --widen cuts every stroke at least --min-feature ({} mm) wide",
            args.min_feature
        );
    }
    if !made.report.sharp_corners.is_empty() && !args.round_corners {
        eprintln!("hint: --round-corners rounds the paper's sharp tips off");
    }
    if !made.report.loose.is_empty() {
        eprintln!(
            "warning: {} parts of the sheet still fall out (see above); \
             widen --bridge or cut them apart",
            made.report.loose.len()
        );
    }
    Ok(())
}
