//! Stencils: line art turned into a sheet that holds together when cut,
//! as katagami, the paper stencils kimono are dyed through, are cut.
//!
//! [`make`] runs the steps in order:
//!
//! 1. [`cutouts`]: every stroke becomes the shape its pen draws (at least
//!    [`StencilOptions::min_feature`] wide when [`StencilOptions::widen`]
//!    is set), all unioned; the sheet (the page) minus them is the paper;
//! 2. [`bridges`]: islands narrower than the smallest feature are cut away
//!    whole (specks the blade cannot leave); every other *island* — a
//!    piece of paper that would fall out — gets bridges (*tsuri*) across
//!    the narrowest gap to the paper around it, more along long outlines,
//!    and long slits get one every [`StencilOptions::bridge_every`] mm;
//!    the bridges are taken out of the cut-outs;
//! 3. with [`StencilOptions::round_corners`], the paper's sharp tips
//!    between cut-outs are rounded off ([`blade`]);
//! 4. the sheet is checked: still one piece ([`Report::loose`] lists any
//!    part that would still fall out, never silently), and [`blade`]
//!    limits — paper and cut-outs narrower than the blade can leave,
//!    corners sharper than it can follow — are listed in the [`Report`].
//!
//! The booleans work on polygons in the boolean library's own form
//! (`shapes`), one integer sweep each: a full A3 kimono design becomes a
//! stencil in about two seconds of CPU (BENCHMARKS.md, section 14).
//!
//! The result's [`Stencil::cut_scene`] is what the knife cuts (every
//! boundary of the cut-outs, closed), to be written like any drawing, in
//! inside-first order ([`crate::plot::nest`]); [`Stencil::sheet_scene`] and
//! [`Stencil::print_scene`] are previews: the sheet with its bridges, and
//! what ink passes through.
//!
//! Everything is in page coordinates (mm from the sheet's top-left
//! corner); regions are flattened to polygons within
//! [`StencilOptions::tolerance`], which a cutter flattens to anyway.

pub mod blade;
pub mod bridges;
pub mod cutouts;
mod shapes;

use std::fmt;

use i_overlay::core::overlay_rule::OverlayRule;
use kurbo::{BezPath, Point, Rect};

use crate::error::{Error, Result};
use crate::geom::region::Region;
use crate::geom::subpath::subpaths;
use crate::scene::{Color, Group, Layer, Pen, Scene, Style};
use crate::units::{Margins, Page};

pub use bridges::{Bridge, Island};

/// Options of [`make`].
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StencilOptions {
    /// Width of a bridge, mm. Default 0.8.
    pub bridge: f64,
    /// Along an island's outline and along a long slit, a bridge every
    /// this many mm (0: only the one across an island's narrowest gap).
    /// Default 40.
    pub bridge_every: f64,
    /// The narrowest paper or cut-out the blade can leave, mm. Default 0.5.
    pub min_feature: f64,
    /// Cut every stroke at least [`StencilOptions::min_feature`] wide.
    /// Default off (narrow strokes are reported).
    pub widen: bool,
    /// Corners of the cut sharper than this (degrees) are reported.
    /// Default 30.
    pub min_corner_deg: f64,
    /// Round the paper's sharp tips between cut-outs off (to the blade's
    /// reach, [`blade::CORNER_REACH`], or less than half a bridge), so
    /// that a drag knife follows them. Default off (they are reported).
    pub round_corners: bool,
    /// Flattening tolerance, mm. Default 0.02.
    pub tolerance: f64,
}

impl StencilOptions {
    /// Bridges 0.8 mm wide, one every 40 mm of outline; features down to
    /// 0.5 mm, corners down to 30°; tolerance 0.02 mm.
    pub const DEFAULT: StencilOptions = StencilOptions {
        bridge: 0.8,
        bridge_every: 40.0,
        min_feature: 0.5,
        widen: false,
        min_corner_deg: 30.0,
        round_corners: false,
        tolerance: 0.02,
    };

    /// These options with [`StencilOptions::bridge`] set.
    pub const fn with_bridge(mut self, mm: f64) -> StencilOptions {
        self.bridge = mm;
        self
    }

    /// These options with [`StencilOptions::bridge_every`] set.
    pub const fn with_bridge_every(mut self, mm: f64) -> StencilOptions {
        self.bridge_every = mm;
        self
    }

    /// These options with [`StencilOptions::min_feature`] set.
    pub const fn with_min_feature(mut self, mm: f64) -> StencilOptions {
        self.min_feature = mm;
        self
    }

    /// These options with [`StencilOptions::widen`] set.
    pub const fn with_widen(mut self, widen: bool) -> StencilOptions {
        self.widen = widen;
        self
    }

    /// These options with [`StencilOptions::round_corners`] set.
    pub const fn with_round_corners(mut self, round: bool) -> StencilOptions {
        self.round_corners = round;
        self
    }

    /// These options with [`StencilOptions::min_corner_deg`] set.
    pub const fn with_min_corner_deg(mut self, degrees: f64) -> StencilOptions {
        self.min_corner_deg = degrees;
        self
    }

    /// Checks every range.
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the field (`bridge`, `bridge_every`,
    /// `min_feature`, `min_corner_deg`, `tolerance`) and its range.
    pub fn validate(&self) -> Result<()> {
        let check = |field: &str, v: f64, lo: f64, hi: f64, open_low: bool| {
            let above = if open_low { v > lo } else { v >= lo };
            if above && v <= hi {
                Ok(())
            } else {
                let low = if open_low { "above" } else { "at least" };
                Err(Error::invalid(
                    field,
                    format!("must be {low} {lo} and at most {hi}, got {v}"),
                ))
            }
        };
        check("bridge", self.bridge, 0.0, 20.0, true)?;
        check("bridge_every", self.bridge_every, 0.0, 1000.0, false)?;
        check("min_feature", self.min_feature, 0.0, 20.0, false)?;
        check("min_corner_deg", self.min_corner_deg, 0.0, 180.0, false)?;
        check("tolerance", self.tolerance, 1e-3, 1.0, false)
    }
}

impl Default for StencilOptions {
    fn default() -> StencilOptions {
        StencilOptions::DEFAULT
    }
}

/// What [`make`] found and did.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Report {
    /// Every island, bridged or not.
    pub islands: Vec<Island>,
    /// Every bridge.
    pub bridges: Vec<Bridge>,
    /// Islands narrower than the smallest feature, cut away whole.
    pub specks: Vec<Point>,
    /// A point inside every part that still falls out after bridging
    /// (empty when the sheet is one piece).
    pub loose: Vec<Point>,
    /// Places where the paper is narrower than the smallest feature.
    pub narrow_paper: Vec<Point>,
    /// Places where a cut-out is narrower than the smallest feature.
    pub narrow_cuts: Vec<Point>,
    /// Corners sharper than the blade follows.
    pub sharp_corners: Vec<Point>,
    /// The narrowest feature checked for, mm ([`StencilOptions::min_feature`]).
    pub min_feature: f64,
    /// The sharpest corner checked for, degrees
    /// ([`StencilOptions::min_corner_deg`]).
    pub min_corner_deg: f64,
    /// The width of the thinnest stroke cut, mm.
    pub thinnest_stroke: f64,
}

impl fmt::Display for Report {
    /// A line per finding; places listed by their first five, findings
    /// with none left out (a kimono has thousands of each).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // `what` is the finding said of one place and of several.
        let places = |f: &mut fmt::Formatter<'_>, what: (&str, &str), ps: &[Point]| {
            if ps.is_empty() {
                return Ok(());
            }
            write!(f, "{}, at", counted(ps.len(), what.0, what.1))?;
            for p in ps.iter().take(5) {
                write!(f, " ({:.1}, {:.1})", p.x, p.y)?;
            }
            if ps.len() > 5 {
                write!(f, " …")?;
            }
            writeln!(f)
        };
        let across_slits = self.bridges.iter().filter(|b| b.island.is_none()).count();
        writeln!(
            f,
            "{}, {} ({across_slits} across long slits)",
            counted(self.islands.len(), "island", "islands"),
            counted(self.bridges.len(), "bridge", "bridges")
        )?;
        // The largest islands first; a kimono has thousands.
        let mut order: Vec<usize> = (0..self.islands.len()).collect();
        order.sort_by(|&a, &b| self.islands[b].across.total_cmp(&self.islands[a].across));
        for &k in order.iter().take(LISTED) {
            let island = &self.islands[k];
            let held = self.bridges.iter().filter(|b| b.island == Some(k)).count();
            writeln!(
                f,
                "  island {} at ({:.1}, {:.1}) mm, {:.2} mm across: {}",
                k + 1,
                island.centre.x,
                island.centre.y,
                island.across,
                counted(held, "bridge", "bridges")
            )?;
        }
        if self.islands.len() > LISTED {
            let rest = self.islands.len() - LISTED;
            writeln!(
                f,
                "  … and {}",
                counted(rest, "smaller island", "smaller islands")
            )?;
        }
        if self.loose.is_empty() {
            writeln!(f, "the sheet is one piece")?;
        } else {
            places(
                f,
                ("part still falls out", "parts still fall out"),
                &self.loose,
            )?;
        }
        let mm = self.min_feature;
        places(
            f,
            (
                &format!("speck of paper narrower than {mm} mm cut away whole"),
                &format!("specks of paper narrower than {mm} mm cut away whole"),
            ),
            &self.specks,
        )?;
        let narrow = format!("the paper between cut-outs is narrower than {mm} mm and may tear");
        places(
            f,
            (
                &format!("place where {narrow}"),
                &format!("places where {narrow}"),
            ),
            &self.narrow_paper,
        )?;
        // Most narrow cut-outs are strokes drawn thinner than the blade
        // leaves: say how thin, once, rather than where each one is.
        let thin = if self.thinnest_stroke < mm {
            format!(" (strokes down to {} mm wide)", self.thinnest_stroke)
        } else {
            String::new()
        };
        let narrow = format!("a cut-out is narrower than {mm} mm{thin}");
        places(
            f,
            (
                &format!("place where {narrow}"),
                &format!("places where {narrow}"),
            ),
            &self.narrow_cuts,
        )?;
        let sharp = format!(
            "sharper than {}° (a drag knife tears the paper's tip there)",
            self.min_corner_deg
        );
        places(
            f,
            (&format!("corner {sharp}"), &format!("corners {sharp}")),
            &self.sharp_corners,
        )
    }
}

/// `n` and the noun for that many: "1 island", "2 islands".
fn counted(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// How many islands the report lists one by one.
const LISTED: usize = 10;

/// A stencil: the paper that stays and what is cut out of it.
#[derive(Debug, Clone)]
pub struct Stencil {
    /// The sheet (the page, from its top-left corner).
    pub page: Page,
    /// The paper that stays, bridges included.
    pub sheet: Region,
    /// The cut-outs, bridges taken out: where ink passes.
    pub holes: Region,
    /// What was found and done.
    pub report: Report,
}

/// The stencil of the line art of `scene` (see the module documentation).
///
/// # Errors
/// [`Error::Invalid`] for options out of range (naming the option), a
/// drawing without strokes (`input`), or a bridge as wide as a whole
/// cut-out it must cross (`bridge`, naming the place).
pub fn make(scene: &Scene, options: &StencilOptions) -> Result<Stencil> {
    options.validate()?;
    let tolerance = options.tolerance;
    let min_width = if options.widen {
        options.min_feature
    } else {
        0.0
    };
    let page = Page {
        margins: Margins::uniform(0.0),
        ..scene.page
    };
    let paper = vec![shapes::rect(Rect::new(0.0, 0.0, page.width, page.height))];
    let (cut, thinnest_stroke) = cutouts::cutout_shapes(scene, min_width, tolerance)?;
    let found = bridges::bridge(
        cut,
        options.bridge,
        options.bridge_every,
        options.min_feature,
        tolerance,
    )?;
    let mut holes = found.holes;
    if options.round_corners {
        // Less than half a bridge, so that every bridge stays.
        let radius = blade::CORNER_REACH.min(0.45 * options.bridge);
        holes = blade::rounded(&holes, radius, tolerance);
    }
    let mut sheet = shapes::overlay(&paper, &holes, OverlayRule::Difference);
    sheet.sort_by(|a, b| shapes::shape_area(b).total_cmp(&shapes::shape_area(a)));
    let loose = sheet
        .iter()
        .skip(1)
        .map(|s| {
            let part = shapes::to_region(std::slice::from_ref(s));
            crate::geom::polylabel::pole_of_inaccessibility(&part, tolerance)
                .map_or(part.bounds().center(), |(c, _)| c)
        })
        .collect();
    // The blade's checks of paper and of cut-outs are independent and
    // cost most of the time: one on a thread of its own.
    let (narrow_paper, (narrow_cuts, sharp_corners)) = std::thread::scope(|scope| {
        let paper = scope.spawn(|| blade::narrow_places(&sheet, options.min_feature, tolerance));
        let cuts = (
            blade::narrow_places(&holes, options.min_feature, tolerance),
            blade::sharp_corners(&holes, options.min_corner_deg),
        );
        let paper = paper
            .join()
            .unwrap_or_else(|e| std::panic::resume_unwind(e));
        (paper, cuts)
    });
    let report = Report {
        islands: found.islands,
        bridges: found.bridges,
        specks: found.specks,
        loose,
        narrow_paper,
        narrow_cuts,
        sharp_corners,
        min_feature: options.min_feature,
        min_corner_deg: options.min_corner_deg,
        thinnest_stroke,
    };
    Ok(Stencil {
        page,
        sheet: shapes::to_region(&sheet),
        holes: shapes::to_region(&holes),
        report,
    })
}

/// Colour of the paper in the previews: persimmon-tanned katagami paper.
const PAPER: Color = Color::rgb(0x9a, 0x5b, 0x2e);
/// Colour of the bridges in the sheet preview.
const BRIDGE: Color = Color::rgb(0xd8, 0x2a, 0x20);
/// Colour of the ink in the print preview: indigo.
const INDIGO: Color = Color::rgb(0x1f, 0x2f, 0x5c);

impl Stencil {
    /// What the knife cuts: every contour of the cut-outs as a closed path
    /// (`cut-N`), on pen 1 (`knife`).
    pub fn cut_scene(&self) -> Scene {
        let mut group = Group::new("cuts");
        for (k, contour) in subpaths(self.holes.path()).enumerate() {
            group.push_path(format!("cut-{k}"), contour.to_path(), Style::default());
        }
        self.scene(vec![(pen(1, "knife", Color::BLACK, 0.1), group)])
    }

    /// The sheet as it comes off the cutter: the paper, with the bridges
    /// drawn over it in red.
    pub fn sheet_scene(&self) -> Scene {
        let mut paper = Group::new("paper");
        paper.push_path("sheet", self.sheet.path().clone(), filled(PAPER));
        let mut strips = Group::new("bridges");
        for (k, b) in self.report.bridges.iter().enumerate() {
            // The part across the gap: the rest lies on paper anyway.
            let [a, b, c, d] = b.corners(0.0);
            let mut strip = BezPath::new();
            strip.move_to(a);
            strip.line_to(b);
            strip.line_to(c);
            strip.line_to(d);
            strip.close_path();
            strips.push_path(format!("bridge-{k}"), strip, filled(BRIDGE));
        }
        self.scene(vec![
            (pen(1, "paper", PAPER, 0.05), paper),
            (pen(2, "bridges", BRIDGE, 0.05), strips),
        ])
    }

    /// A preview of the print: the ink that passes through the cut-outs.
    pub fn print_scene(&self) -> Scene {
        let mut ink = Group::new("ink");
        ink.push_path("print", self.holes.path().clone(), filled(INDIGO));
        self.scene(vec![(pen(1, "indigo", INDIGO, 0.05), ink)])
    }

    fn scene(&self, layers: Vec<(Pen, Group)>) -> Scene {
        Scene {
            page: self.page,
            pens: layers.iter().map(|(p, _)| p.clone()).collect(),
            layers: layers
                .into_iter()
                .map(|(p, content)| Layer {
                    id: format!("{}-layer", p.name),
                    name: p.name.clone(),
                    pen: p.number,
                    depth: 0,
                    content,
                })
                .collect(),
            description: None,
        }
    }
}

fn pen(number: u32, name: &str, color: Color, width: f64) -> Pen {
    Pen {
        number,
        name: name.into(),
        color,
        width,
    }
}

fn filled(color: Color) -> Style {
    Style {
        fill: Some(color),
        ..Style::default()
    }
}

#[cfg(test)]
mod tests {
    use kurbo::{Circle, Shape};

    use super::*;
    use crate::units::Orientation;

    fn drawing(paths: Vec<BezPath>) -> Scene {
        let mut g = Group::new("g");
        for (k, p) in paths.into_iter().enumerate() {
            g.push_path(format!("p{k}"), p, Style::default());
        }
        Scene::one_pen(
            Page::sized(100.0, 100.0, Orientation::Portrait, Margins::uniform(5.0)),
            g,
        )
    }

    /// Circles in circles and a crossing of lines: islands in islands.
    fn rings() -> Vec<BezPath> {
        let mut paths: Vec<BezPath> = [30.0, 20.0, 10.0]
            .into_iter()
            .map(|r| Circle::new((45.0, 45.0), r).to_path(0.01))
            .collect();
        let mut line = BezPath::new();
        line.move_to((0.0, 85.0));
        line.line_to((90.0, 85.0));
        paths.push(line);
        paths
    }

    #[test]
    fn after_bridging_the_sheet_is_one_piece() {
        let s = make(&drawing(rings()), &StencilOptions::DEFAULT).unwrap();
        // A disc and two rings fall out without bridges.
        assert_eq!(s.report.islands.len(), 3);
        assert!(s.report.loose.is_empty(), "{}", s.report);
        assert_eq!(s.sheet.components().len(), 1);
    }

    #[test]
    fn without_bridges_the_islands_would_fall_out() {
        // The connectivity check has something to find: without bridges
        // the drawing falls apart into four pieces.
        let paper = Region::from_rect(Rect::new(0.0, 0.0, 100.0, 100.0)).unwrap();
        let cut = cutouts::cutouts(&drawing(rings()), 0.0, 0.02).unwrap();
        assert_eq!(paper.difference(&cut).components().len(), 4);
    }

    #[test]
    fn every_bridge_is_at_least_its_width() {
        let options = StencilOptions::DEFAULT.with_bridge(1.2);
        let s = make(&drawing(rings()), &options).unwrap();
        assert!(!s.report.bridges.is_empty());
        for b in &s.report.bridges {
            // Across the middle of the gap, the paper spans the width.
            let mid = b.from.midpoint(b.to);
            let along = (b.to - b.from).normalize();
            let across = kurbo::Vec2::new(-along.y, along.x);
            for k in -5..=5 {
                let p = mid + across * (0.999 * 1.2 / 2.0 * f64::from(k) / 5.0);
                assert!(s.sheet.contains(p), "bridge {b:?} is narrower at {p:?}");
            }
        }
    }

    #[test]
    fn a_design_with_no_islands_and_no_long_slits_gets_no_bridges() {
        let mut wave = BezPath::new();
        wave.move_to((10.0, 50.0));
        wave.curve_to((20.0, 40.0), (30.0, 60.0), (40.0, 50.0));
        let s = make(&drawing(vec![wave]), &StencilOptions::DEFAULT).unwrap();
        assert!(s.report.islands.is_empty());
        assert!(s.report.bridges.is_empty(), "{}", s.report);
        assert_eq!(s.cut_scene().path_count(), 1);
    }

    #[test]
    fn a_long_slit_gets_a_bridge_every_spacing() {
        // About 80 mm of slit, no island.
        let mut wave = BezPath::new();
        wave.move_to((10.0, 50.0));
        wave.curve_to((30.0, 20.0), (60.0, 80.0), (85.0, 50.0));
        let options = StencilOptions::DEFAULT.with_bridge_every(20.0);
        let s = make(&drawing(vec![wave.clone()]), &options).unwrap();
        assert!(s.report.islands.is_empty());
        let n = s.report.bridges.len();
        assert!((3..=5).contains(&n), "{}", s.report);
        // Each crosses the 0.3 mm cut, and the cut falls apart in pieces
        // between them.
        for b in &s.report.bridges {
            assert!(b.island.is_none() && (b.span() - 0.3).abs() < 0.05, "{b:?}");
        }
        assert_eq!(s.holes.components().len(), n + 1);
        assert_eq!(s.sheet.components().len(), 1);
        // Spaced out: no two nearer than ¾ of the spacing.
        for (i, a) in s.report.bridges.iter().enumerate() {
            for b in &s.report.bridges[i + 1..] {
                assert!(a.from.distance(b.from) > 14.9, "{a:?} {b:?}");
            }
        }
        // A longer spacing, fewer bridges; none when spacing is off.
        let fewer = make(
            &drawing(vec![wave.clone()]),
            &options.with_bridge_every(40.0),
        )
        .unwrap();
        assert!(fewer.report.bridges.len() < n, "{}", fewer.report);
        let none = make(&drawing(vec![wave]), &options.with_bridge_every(0.0)).unwrap();
        assert!(none.report.bridges.is_empty());
    }

    #[test]
    fn sharp_tips_of_paper_are_reported_and_rounded_on_request() {
        // Two strokes from one point, 15° apart.
        let stroke = |deg: f64| {
            let mut p = BezPath::new();
            p.move_to((10.0, 50.0));
            p.line_to(Point::new(10.0, 50.0) + kurbo::Vec2::from_angle(deg.to_radians()) * 30.0);
            p
        };
        let options = StencilOptions::DEFAULT.with_widen(true);
        let v = drawing(vec![stroke(0.0), stroke(15.0)]);
        let sharp = make(&v, &options).unwrap();
        assert!(!sharp.report.sharp_corners.is_empty(), "{}", sharp.report);
        let round = make(&v, &options.with_round_corners(true)).unwrap();
        assert!(round.report.sharp_corners.is_empty(), "{}", round.report);
        // The cut grew into the tip only: a little more cut, the sheet whole.
        let more = round.holes.area() - sharp.holes.area();
        assert!(more > 0.0 && more < 1.0, "{more}");
        assert_eq!(round.sheet.components().len(), 1);
    }

    #[test]
    fn narrow_strokes_are_reported_unless_widened() {
        let mut line = BezPath::new();
        line.move_to((10.0, 50.0));
        line.line_to((80.0, 50.0));
        // No bridges along it, which would cut it in pieces.
        let options = StencilOptions::DEFAULT
            .with_min_feature(0.5)
            .with_bridge_every(0.0);
        let s = make(&drawing(vec![line.clone()]), &options).unwrap();
        assert_eq!(s.report.narrow_cuts.len(), 1, "{}", s.report);
        // Said once, with how thin the strokes are.
        let text = s.report.to_string();
        let line_of =
            "1 place where a cut-out is narrower than 0.5 mm (strokes down to 0.3 mm wide), at (";
        assert!(text.contains(line_of), "{text}");
        let s = make(&drawing(vec![line]), &options.with_widen(true)).unwrap();
        assert!(s.report.narrow_cuts.is_empty(), "{}", s.report);
        // A finding with no place is left out of the report.
        assert!(
            !s.report.to_string().contains("narrower than"),
            "{}",
            s.report
        );
    }

    #[test]
    fn bad_options_are_named() {
        for (options, field) in [
            (StencilOptions::DEFAULT.with_bridge(-1.0), "bridge: "),
            (
                StencilOptions::DEFAULT.with_bridge_every(-1.0),
                "bridge_every: ",
            ),
            (
                StencilOptions::DEFAULT.with_min_feature(f64::NAN),
                "min_feature: ",
            ),
        ] {
            let e = make(&drawing(rings()), &options).unwrap_err().to_string();
            assert!(e.starts_with(field), "{e}");
        }
    }
}
