//! Plotting any SVG (`moyo plot` and `moyo stats`): a drawing read in,
//! run through the plot stages and written in a plotter's format.

use std::path::Path;

use kurbo::{BezPath, Point};

use crate::error::{Error, Result};
use crate::input::{import_svg, ImportOptions, Imported};
use crate::output::dxf::{to_dxf, DxfOptions};
use crate::output::gcode::{self, to_gcode, GcodeOptions};
use crate::output::hpgl::{self, to_hpgl, HpglOptions};
use crate::output::{render_png, to_svg, SvgOptions};
use crate::plot::{self, PlotOptions};
use crate::scene::{Color, Group, Layer, Pen, Scene, Style};

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
// One per job: the size of the G-code variant costs nothing, a box would
// cost every caller a `Box::new`.
#[allow(clippy::large_enum_variant)]
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq)]
pub enum PlotFormat {
    /// Layered SVG ([`to_svg`]).
    Svg(SvgOptions),
    /// A G-code program ([`to_gcode`]).
    Gcode(GcodeOptions),
    /// HPGL ([`to_hpgl`]).
    Hpgl(HpglOptions),
    /// DXF for cutting programs and CAD ([`to_dxf`]).
    Dxf(DxfOptions),
}

impl PlotFormat {
    /// The format's name as people say it: `SVG`, `G-code`, `HPGL`, `DXF`.
    pub fn name(&self) -> &'static str {
        match self {
            PlotFormat::Svg(_) => "SVG",
            PlotFormat::Gcode(_) => "G-code",
            PlotFormat::Hpgl(_) => "HPGL",
            PlotFormat::Dxf(_) => "DXF",
        }
    }

    /// Whether the output is for a knife: HPGL in cutter mode, or DXF
    /// (what cutting programs import). A cutter's output is always cut
    /// inside first ([`PlotOptions::inside_first`]).
    pub fn cuts(&self) -> bool {
        match self {
            PlotFormat::Hpgl(o) => o.cutter.is_some(),
            PlotFormat::Dxf(_) => true,
            PlotFormat::Svg(_) | PlotFormat::Gcode(_) => false,
        }
    }
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

    /// Checks every option of the job before any work: the stages
    /// (fields `plot.…`), the format's options (`gcode.…`, `hpgl.…`,
    /// `dxf.…`) and the preview's resolution.
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the first field out of range;
    /// [`Error::Preview`] for a resolution outside 1–2400 dpi.
    pub fn validate(&self) -> Result<()> {
        self.stages.validate("plot")?;
        match &self.format {
            PlotFormat::Svg(_) => {}
            PlotFormat::Gcode(o) => o.validate()?,
            PlotFormat::Hpgl(o) => o.validate()?,
            PlotFormat::Dxf(o) => o.validate()?,
        }
        if let Some(p) = &self.preview {
            crate::output::check_dpi(p.dpi)?;
        }
        Ok(())
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
    /// What the output could not do of what the drawing asks (a pen's
    /// AxiDraw code the machine has no way to carry out), one line each.
    pub warnings: Vec<String>,
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
/// silhouettes when asked, runs the plot stages (inside first for a
/// cutter's output, [`PlotFormat::cuts`]), writes the output and renders
/// the preview.
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
    job.validate()?;
    if job.silhouettes {
        plot::occlude::mark_path_groups_solid(&mut scene);
    }
    let stages = PlotOptions {
        inside_first: job.stages.inside_first || job.format.cuts(),
        ..job.stages.clone()
    };
    let mut scene = plot::run(scene, &stages)?;
    if stages.occlude.is_some() && !stages.per_pen() {
        // Hiding took the fill off every partly hidden shape (its outline
        // is open pieces now); the whole ones lose theirs too, to the
        // preview's fill layer, so that the plot carries no fill at all
        // rather than some (the per-pen stages do this themselves).
        plot::occlude::fills_behind(&mut scene);
    }
    let (bytes, warnings) = match &job.format {
        PlotFormat::Svg(o) => (to_svg(&scene, o), Vec::new()),
        PlotFormat::Gcode(o) => (to_gcode(&scene, o)?, gcode::unsupported(&scene, o)),
        PlotFormat::Hpgl(o) => (to_hpgl(&scene, o)?, hpgl::unsupported(&scene, o)),
        PlotFormat::Dxf(o) => (to_dxf(&scene, o), Vec::new()),
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
    Ok(Plotted {
        scene,
        bytes,
        png,
        warnings,
    })
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
        let formats = [
            PlotFormat::Svg(SvgOptions::DEFAULT.with_precision(2)),
            PlotFormat::Gcode(GcodeOptions::default()),
            PlotFormat::Hpgl(HpglOptions::DEFAULT),
            PlotFormat::Hpgl(HpglOptions::CUTTER),
            PlotFormat::Dxf(DxfOptions::DEFAULT),
        ];
        for format in formats {
            let job = PlotJob::new(format.clone()).with_stages(stages.clone());
            let plotted = plot_scene(drawing(), &job).unwrap();
            // A cutter's output is cut inside first.
            let cutting = PlotOptions {
                inside_first: format.cuts(),
                ..stages.clone()
            };
            let plotted_scene = plot::run(drawing(), &cutting).unwrap();
            let expected = match &format {
                PlotFormat::Svg(o) => to_svg(&plotted_scene, o),
                PlotFormat::Gcode(o) => to_gcode(&plotted_scene, o).unwrap(),
                PlotFormat::Hpgl(o) => to_hpgl(&plotted_scene, o).unwrap(),
                PlotFormat::Dxf(o) => to_dxf(&plotted_scene, o),
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
