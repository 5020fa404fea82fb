//! Entry points for fuzzing: each reads arbitrary bytes the way one of
//! moyo's commands reads a file, then runs what that command runs after
//! it, within a small path budget. None may panic, hang or run out of
//! memory; an input it cannot use is an `Err`, which is a fine answer.
//!
//! One target is structured: [`Target::SceneExtremes`] does not parse
//! its bytes but takes them as choices (`arbitrary`'s [`Unstructured`])
//! that edit a valid description at its limits — each numeric field set
//! to the ends of the range validation allows it
//! ([`crate::spec::ValidSpec::ranges`]), points made to coincide, lines
//! made zero-length, tables repeated — so that the generators themselves
//! meet trees of 64 generations and counts at their maximum, not only
//! the parsers' refusals.
//!
//! The coverage-guided targets in `fuzz/` (cargo-afl, see
//! `fuzz/README.md`) call [`Target::run`], and so does the regression test
//! `tests/fuzz_regressions.rs`, on every input a fuzzer ever found that
//! panicked or hung (`fuzz/crashers/<target>/`), so a fixed finding stays
//! fixed in plain `cargo test`.

use std::collections::BTreeMap;

use arbitrary::Unstructured;

use crate::error::{Error, Result};
use crate::family::lsystem::engine::LSystem;
use crate::geom::mesh::TriMesh;
use crate::input::{decode_image, import_svg, ImportOptions};
use crate::output::to_obj;
use crate::plot::{
    DebrisOptions, DedupeOptions, HatchOptions, MergeOptions, OccludeOptions, PlotOptions,
    SortOptions,
};
use crate::project::{self, plot_scene, PlotFormat, PlotJob};
use crate::rng::Seed;
use crate::scene::embedded_description;
use crate::spec::field::{point_lists, value_at_mut as at, xy};
use crate::spec::{Format, SceneSpec};

/// The path budget of a fuzzed description: its own `limits.max_paths`,
/// but at most this many, so one case cannot take long.
pub const MAX_PATHS: usize = 2_000;

/// The segment budget of a fuzzed description, likewise: one path may
/// hold millions of segments (an L-system's), and drawing them is slow
/// without being wrong.
pub const MAX_SEGMENTS: usize = 200_000;

/// Longest input a target reads, in bytes (a fuzzer's inputs are small;
/// the resource bounds of large inputs are tested on their own).
pub const MAX_INPUT: usize = 256 * 1024;

/// Most modules an L-system rule text may derive.
const MAX_MODULES: usize = 200_000;

/// Derivation steps of an L-system rule text.
const LSYSTEM_STEPS: usize = 6;

/// What a fuzz target reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// A scene description in TOML, validated and rendered with every
    /// plot output.
    SceneToml,
    /// The same in JSON.
    SceneJson,
    /// An SVG imported and run through every plot stage (occlude, hatch,
    /// merge, sort) and every plot output.
    Svg,
    /// An SVG written by `moyo render`, reopened (`render --from`) from
    /// its embedded description.
    RenderFrom,
    /// An OBJ mesh, as a vine's support.
    Obj,
    /// An image (PNG or JPEG), as a density for stippling.
    Image,
    /// L-system rule text: the first line the axiom, every other line a
    /// production, derived a few steps.
    LsystemRules,
    /// A stroke file: an SVG whose paths, joined, are the stroke a sketch
    /// L-system grows along.
    Stroke,
    /// Choices that edit a built-in description at its limits (see the
    /// module docs).
    SceneExtremes,
    /// Bytes read as a few small closed paths (see [`regions`]): their
    /// regions combined every way, then drawn filled over lines through
    /// the occlude and hatch stages. No path or segment cap stops them
    /// before the booleans; their size is small by construction.
    Regions,
}

impl Target {
    /// Every target.
    pub const ALL: [Target; 10] = [
        Target::SceneToml,
        Target::SceneJson,
        Target::Svg,
        Target::RenderFrom,
        Target::Obj,
        Target::Image,
        Target::LsystemRules,
        Target::Stroke,
        Target::SceneExtremes,
        Target::Regions,
    ];

    /// Its name: the fuzz binary's and its corpus folder's.
    pub fn name(self) -> &'static str {
        match self {
            Target::SceneToml => "scene_toml",
            Target::SceneJson => "scene_json",
            Target::Svg => "svg",
            Target::RenderFrom => "render_from",
            Target::Obj => "obj",
            Target::Image => "image",
            Target::LsystemRules => "lsystem_rules",
            Target::Stroke => "stroke",
            Target::SceneExtremes => "scene_extremes",
            Target::Regions => "regions",
        }
    }

    /// The target named `name`.
    pub fn from_name(name: &str) -> Option<Target> {
        Target::ALL.into_iter().find(|t| t.name() == name)
    }

    /// Runs the target on `bytes`.
    ///
    /// # Errors
    /// Whatever moyo says of an input it cannot use; never a panic.
    pub fn run(self, bytes: &[u8]) -> Result<()> {
        if bytes.len() > MAX_INPUT {
            return Err(Error::invalid("input", "longer than a fuzz case may be"));
        }
        match self {
            Target::SceneToml => scene(text(bytes)?, Format::Toml),
            Target::SceneJson => scene(text(bytes)?, Format::Json),
            Target::Svg => svg(text(bytes)?),
            Target::RenderFrom => {
                let description = embedded_description(text(bytes)?)
                    .ok_or_else(|| Error::invalid("input", "carries no scene description"))?;
                scene(&description, Format::Toml)
            }
            Target::Obj => TriMesh::parse_obj(text(bytes)?, "obj").map(|_| ()),
            Target::Image => decode_image(bytes).map(|_| ()),
            Target::LsystemRules => lsystem_rules(text(bytes)?),
            Target::Stroke => stroke(bytes),
            Target::SceneExtremes => extremes(bytes),
            Target::Regions => regions(bytes),
        }
    }
}

fn text(bytes: &[u8]) -> Result<&str> {
    std::str::from_utf8(bytes).map_err(|e| Error::invalid("input", format!("not UTF-8: {e}")))
}

/// Validates a description and renders it, with every plot output, its
/// budgets capped at [`MAX_PATHS`] and [`MAX_SEGMENTS`]. The files it
/// names are not there.
fn scene(text: &str, format: Format) -> Result<()> {
    scene_with(text, format, &|_| None)
}

/// As [`scene`], with the files `file` gives by name.
fn scene_with(text: &str, format: Format, file: &dyn Fn(&str) -> Option<Vec<u8>>) -> Result<()> {
    let mut spec = SceneSpec::parse(text, format)?.into_inner();
    spec.limits.max_paths = spec.limits.max_paths.min(MAX_PATHS);
    spec.limits.max_segments = spec.limits.max_segments.min(MAX_SEGMENTS);
    let spec = spec.validate()?;
    let library = project::load_motifs_with(&spec, &|name: &str| {
        let bytes = file(name)
            .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::NotFound, "not in a fuzz case"));
        (name.to_string(), bytes)
    })?;
    let rendered = project::render_with_progress(&spec, &library, &mut |_| {})?;
    to_obj(&rendered.models, spec.output.precision);
    outputs(rendered.scene)
}

/// Imports an SVG and runs every plot stage and output on it.
fn svg(text: &str) -> Result<()> {
    svg_with(text, false)
}

/// As [`svg`], the occlude stage merging closed shapes into
/// `silhouettes` first when asked.
fn svg_with(text: &str, silhouettes: bool) -> Result<()> {
    let imported = import_svg(text, &ImportOptions::DEFAULT)?;
    let stages = PlotOptions {
        occlude: Some(OccludeOptions {
            silhouettes,
            ..OccludeOptions::default()
        }),
        hatch: Some(HatchOptions::default()),
        dedupe: Some(DedupeOptions::default()),
        merge: Some(MergeOptions::default()),
        debris: Some(DebrisOptions::default()),
        sort: Some(SortOptions::default()),
        ..PlotOptions::default()
    };
    let job = PlotJob::new(PlotFormat::Svg(Default::default())).with_stages(stages);
    let plotted = plot_scene(imported.scene, &job)?;
    outputs(plotted.scene)
}

/// Writes `scene` as G-code and HPGL.
fn outputs(scene: crate::Scene) -> Result<()> {
    for format in [
        PlotFormat::Gcode(Default::default()),
        PlotFormat::Hpgl(Default::default()),
    ] {
        plot_scene(scene.clone(), &PlotJob::new(format))?;
    }
    Ok(())
}

/// Parses rule text (first line the axiom, then one production a line)
/// and derives it [`LSYSTEM_STEPS`] steps.
fn lsystem_rules(text: &str) -> Result<()> {
    let mut lines = text.lines();
    let axiom = lines.next().unwrap_or_default();
    let productions: Vec<&str> = lines.collect();
    let system = LSystem::parse(axiom, &productions, &BTreeMap::new(), "", "lsystem")?;
    system.derive(LSYSTEM_STEPS, &mut Seed(1).stream(), MAX_MODULES)?;
    Ok(())
}

/// The description a stroke file is grown in: the sketch L-system of the
/// source, with the stroke read from `stroke.svg`.
const STROKE_SCENE: &str = "version = 1\n\
    [page]\nsize = \"A5\"\n\
    [[layers]]\nname = \"sketch\"\n\
    [[layers.lsystem]]\nid = \"sketch\"\nstyle = \"outline\"\n\
    [layers.lsystem.sketch]\nsvg = \"stroke.svg\"\nmodule = 6\n";

/// Grows the sketch L-system along the stroke in `bytes` (an SVG).
fn stroke(bytes: &[u8]) -> Result<()> {
    scene_with(STROKE_SCENE, Format::Toml, &|name| {
        (name == "stroke.svg").then(|| bytes.to_vec())
    })
}

/// Most paths, subpaths a path and points a subpath of a
/// [`Target::Regions`] case: small, so that a case runs in milliseconds
/// and the fuzzer's time goes to the shapes, not their number.
const REGION_PATHS: u8 = 4;
const REGION_SUBPATHS: u8 = 3;
const REGION_POINTS: u8 = 12;

/// Reads up to [`REGION_PATHS`] closed paths from `bytes`, each with its
/// fill rule; makes their regions and combines them every way
/// (union, intersection, difference, xor, of two and of all); then draws
/// them filled, in front of lines crossing the page, through the occlude
/// (with silhouettes), hatch and pen stages, as the `svg` target does.
/// The shapes the property tests found hard are easy to reach: points
/// read as raw numbers, a hair from zero, repeated, and cubics that run
/// out and back over themselves (see [`region_path`]).
fn regions(bytes: &[u8]) -> Result<()> {
    use crate::geom::region::{FillRule, Region};
    let mut u = Unstructured::new(bytes);
    let count = 1 + byte(&mut u)? % REGION_PATHS;
    let mut made = Vec::new();
    let mut body = String::new();
    for k in 0..count {
        let even_odd = byte(&mut u)? % 2 == 1;
        let path = region_path(&mut u)?;
        let rule = if even_odd {
            FillRule::EvenOdd
        } else {
            FillRule::NonZero
        };
        body.push_str(&format!(
            "<path d=\"M-200 {y} L300 {y}\" stroke=\"blue\" fill=\"none\"/>\
             <path d=\"{}\" fill=\"#{:02x}0000\" fill-rule=\"{}\" stroke=\"black\"/>",
            path.to_svg(),
            40 * k + 60,
            if even_odd { "evenodd" } else { "nonzero" },
            y = 25 * k,
        ));
        if let Ok(region) = Region::new(path, rule) {
            made.push(region);
        }
    }
    if let [a, b, ..] = &made[..] {
        for combined in [a.union(b), a.intersection(b), a.difference(b), a.xor(b)] {
            let _ = combined.components();
        }
    }
    let _ = Region::union_all(&made);
    let _ = Region::intersection_all(&made);
    if let Some((first, rest)) = made.split_first() {
        let _ = first.difference_all(rest);
    }
    let svg_text = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="-50 -50 100 100">{body}</svg>"#
    );
    svg_with(&svg_text, true)
}

/// One closed path of a [`Target::Regions`] case: up to
/// [`REGION_SUBPATHS`] subpaths of up to [`REGION_POINTS`] points, each
/// reached by a line, a quadratic, a cubic, or a cubic that runs out and
/// back over itself (its second control point the point it ends on).
fn region_path(u: &mut Unstructured<'_>) -> Result<kurbo::BezPath> {
    let mut path = kurbo::BezPath::new();
    for _ in 0..=byte(u)? % REGION_SUBPATHS {
        let mut last = region_point(u, kurbo::Point::ZERO)?;
        path.move_to(last);
        for _ in 1..=byte(u)? % REGION_POINTS {
            let kind = byte(u)? % 4;
            let to = region_point(u, last)?;
            match kind {
                0 => path.line_to(to),
                1 => path.quad_to(region_point(u, last)?, to),
                2 => path.curve_to(region_point(u, last)?, region_point(u, to)?, to),
                _ => path.curve_to(to, last, to),
            }
            last = to;
        }
        path.close_path();
    }
    Ok(path)
}

/// A point of a [`Target::Regions`] path: each coordinate a small number
/// (hundredths of a millimetre), 0, 10, a raw `f64` (any value a file
/// could hold, within the largest coordinate moyo takes), a hair from
/// zero, or the coordinate of `near`.
fn region_point(u: &mut Unstructured<'_>, near: kurbo::Point) -> Result<kurbo::Point> {
    let mut coordinate = |near: f64| -> Result<f64> {
        let pair = |u: &mut Unstructured<'_>| -> Result<i16> {
            Ok(i16::from_le_bytes([byte(u)?, byte(u)?]))
        };
        Ok(match byte(u)? % 6 {
            0 => f64::from(pair(u)?) / 100.0,
            1 => 0.0,
            2 => 10.0,
            3 => {
                let mut raw = [0u8; 8];
                for b in &mut raw {
                    *b = byte(u)?;
                }
                let v = f64::from_le_bytes(raw);
                if v.is_finite() {
                    v.clamp(-crate::units::MAX_COORD, crate::units::MAX_COORD)
                } else {
                    0.0
                }
            }
            4 => f64::from(pair(u)?) * 1e-7,
            _ => near,
        })
    };
    let x = coordinate(near.x)?;
    let y = coordinate(near.y)?;
    Ok(kurbo::Point::new(x, y))
}

/// The next byte of the choices.
fn byte(u: &mut Unstructured<'_>) -> Result<u8> {
    u.arbitrary::<u8>().map_err(choices)
}

/// The built-in descriptions [`Target::SceneExtremes`] starts from: one
/// or more of every family, each rendering in well under 100 ms, so that
/// the fuzzer's time goes to the edits.
pub const EXTREMES_BASES: &[&str] = &[
    "tree-rules",
    "tomesode-hem",
    "kimono-2",
    "lsystem-koch",
    "lsystem-plant-a",
    "lsystem-bush",
    "lsystem-sketch-straight",
    "zentangle-2",
    "zentangle-10",
    "voronoi-stained-glass",
    "delaunay-lowpoly",
    "cracked-earth",
    "vine-basic",
    "vine-opposite",
    "vine-cross",
    "vine-fence",
];

/// Most edits one case makes.
const MAX_EDITS: u32 = 8;

/// Edits a built-in description by the choices in `bytes` and renders it.
fn extremes(bytes: &[u8]) -> Result<()> {
    let text = extreme_description(bytes)?;
    scene_with(&text, Format::Toml, &|name| {
        crate::templates::file(name).map(<[u8]>::to_vec)
    })
}

/// The description a [`Target::SceneExtremes`] case renders: a built-in
/// one (of [`EXTREMES_BASES`]) with the edits the choices in `bytes`
/// make, as TOML — to read a finding, or to render it with `moyo render`.
///
/// # Errors
/// When `bytes` run out before a template is chosen.
pub fn extreme_description(bytes: &[u8]) -> Result<String> {
    let mut u = Unstructured::new(bytes);
    let name = *u.choose(EXTREMES_BASES).map_err(choices)?;
    let template = crate::templates::get(name)?;
    let spec = template.spec()?;
    let ranges = spec.ranges();
    let mut value: toml::Value = toml::from_str(&spec.to_toml())
        .map_err(|e| Error::invalid("input", format!("a template did not read back: {e}")))?;
    let edits = u.int_in_range(1..=MAX_EDITS).map_err(choices)?;
    for _ in 0..edits {
        if u.is_empty() {
            break;
        }
        edit(&mut u, &mut value, &ranges).map_err(choices)?;
    }
    toml::to_string(&value)
        .map_err(|e| Error::invalid("input", format!("the edit cannot be written: {e}")))
}

fn choices(e: arbitrary::Error) -> Error {
    Error::invalid("input", format!("not enough choices: {e}"))
}

/// One edit of the description `value`.
fn edit(
    u: &mut Unstructured<'_>,
    value: &mut toml::Value,
    ranges: &[crate::spec::FieldRange],
) -> arbitrary::Result<()> {
    match u.int_in_range(0..=9)? {
        // Most edits put a number at the end of its range.
        0..=5 if !ranges.is_empty() => {
            let r = u.choose(ranges)?;
            let v = extreme(u, r.lo, r.hi)?;
            // Only a number is replaced: some ranges bound a list's length.
            if let Some(slot) = at(value, &r.field).filter(|v| v.is_integer() || v.is_float()) {
                *slot = if r.integer {
                    // Within i64 for every integer range moyo checks.
                    #[allow(clippy::cast_possible_truncation)]
                    toml::Value::Integer(v.round().clamp(-9.2e18, 9.2e18) as i64)
                } else {
                    toml::Value::Float(v)
                };
            }
        }
        // Two neighbouring points of a line made one.
        6 => {
            let lines = point_lists(value);
            if !lines.is_empty() {
                let path = u.choose(&lines)?.clone();
                if let Some(toml::Value::Array(points)) = at(value, &path) {
                    if points.len() >= 2 {
                        let i = u.choose_index(points.len() - 1)?;
                        points[i + 1] = points[i].clone();
                    }
                }
            }
        }
        // A line of two points a hair apart (zero length to a plotter).
        7 => {
            let lines = point_lists(value);
            if !lines.is_empty() {
                let path = u.choose(&lines)?.clone();
                if let Some(toml::Value::Array(points)) = at(value, &path) {
                    if let Some([x, y]) = points.first().and_then(xy) {
                        let n = points.len();
                        for (i, p) in points.iter_mut().enumerate() {
                            *p = pair(if i + 1 == n { x + 1e-9 } else { x }, y);
                        }
                    }
                }
            }
        }
        // A table repeated: every layer's tables twice.
        _ => {
            if let Some(toml::Value::Array(layers)) = value.get_mut("layers") {
                if !layers.is_empty() {
                    let i = u.choose_index(layers.len())?;
                    if let Some(toml::Value::Table(layer)) = layers.get_mut(i) {
                        for (_, table) in layer.iter_mut() {
                            if let toml::Value::Array(items) = table {
                                let copies = items.clone();
                                let n = items.len();
                                items.extend(copies.into_iter().map(|c| renamed(c, n)));
                            }
                        }
                    }
                }
            }
        }
    }
    Ok(())
}

/// A value in `lo..=hi`, most often one of its ends or a hair inside.
fn extreme(u: &mut Unstructured<'_>, lo: f64, hi: f64) -> arbitrary::Result<f64> {
    let span = hi - lo;
    Ok(match u.int_in_range(0..=5)? {
        0 | 1 => lo,
        2 | 3 => hi,
        4 => {
            if u.arbitrary()? {
                lo + span * 1e-9
            } else {
                hi - span * 1e-9
            }
        }
        _ => lo + span * f64::from(u.arbitrary::<u16>()?) / f64::from(u16::MAX),
    })
}

fn pair(x: f64, y: f64) -> toml::Value {
    toml::Value::Array(vec![toml::Value::Float(x), toml::Value::Float(y)])
}

/// A copy of a table, added after `n` others, with its id (if any) made
/// new.
fn renamed(mut item: toml::Value, n: usize) -> toml::Value {
    if let Some(toml::Value::String(id)) = item.get_mut("id") {
        id.push_str(&format!("-{n}"));
    }
    item
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::field::number_at;

    #[test]
    fn names_round_trip_and_refusals_are_errors() {
        for t in Target::ALL {
            assert_eq!(Target::from_name(t.name()), Some(t));
            assert!(
                t.run(&[0xff, 0xfe, 0x00]).is_err()
                    || [Target::Image, Target::SceneExtremes, Target::Regions].contains(&t),
                "{t:?}"
            );
            assert!(t.run(&vec![b' '; MAX_INPUT + 1]).is_err(), "{t:?}");
        }
        assert_eq!(Target::from_name("nothing"), None);
    }

    /// The kept `regions` case reads back as the path linesweeper 0.5.0
    /// panics on (docs/upstream/linesweeper-entry-at.md), and runs.
    #[test]
    fn the_regions_crasher_is_the_path_linesweeper_panics_on() {
        let bytes = std::fs::read(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("fuzz/crashers/regions/linesweeper-retraced-cubic.bin"),
        )
        .unwrap();
        let mut u = Unstructured::new(&bytes[2..]);
        let path = region_path(&mut u).unwrap();
        let expected =
            kurbo::BezPath::from_svg(crate::geom::region::tests::LINESWEEPER_PANICS).unwrap();
        assert_eq!(path, expected);
        assert!(u.is_empty());
        Target::Regions.run(&bytes).unwrap();
    }

    /// Bytes from a fixed xorshift stream, as a fuzzer's would be.
    fn choices(n: usize, state: &mut u64) -> Vec<u8> {
        (0..n)
            .map(|_| {
                *state ^= *state << 13;
                *state ^= *state >> 7;
                *state ^= *state << 17;
                (*state >> 24) as u8
            })
            .collect()
    }

    #[test]
    fn extreme_edits_keep_descriptions_valid_and_put_numbers_at_their_limits() {
        for name in EXTREMES_BASES {
            crate::templates::get(name).unwrap();
        }
        let mut state = 99;
        let (mut valid, mut at_limit) = (0, 0);
        for _ in 0..60 {
            let bytes = choices(48, &mut state);
            let text = extreme_description(&bytes).unwrap();
            assert_eq!(text, extreme_description(&bytes).unwrap());
            // Always a description in shape; mostly a valid one.
            let spec = match SceneSpec::parse(&text, Format::Toml) {
                Ok(spec) => spec,
                Err(Error::Invalid { .. }) => continue,
                Err(e) => panic!("{e}\n{text}"),
            };
            valid += 1;
            let base = EXTREMES_BASES
                .iter()
                .map(|n| crate::templates::get(n).unwrap().spec().unwrap())
                .find(|b| b.title == spec.title)
                .unwrap();
            at_limit += spec
                .ranges()
                .iter()
                .filter(|r| {
                    let v: toml::Value = toml::from_str(&text).unwrap();
                    let b: toml::Value = toml::from_str(&base.to_toml()).unwrap();
                    let now = number_at(&v, &r.field);
                    let was = number_at(&b, &r.field);
                    now != was && (now == Some(r.lo) || now == Some(r.hi))
                })
                .count();
        }
        assert!(valid >= 30, "{valid} of 60 valid");
        assert!(at_limit >= 20, "{at_limit} fields moved to a limit");
    }

    #[test]
    fn good_inputs_pass() {
        let toml = "version = 1\n[[layers]]\nname = \"a\"\n[[layers.trees]]\nrule = \"tree1\"\ncount = 1\ncentre = [[10, 100], [100, 100]]\n";
        Target::SceneToml.run(toml.as_bytes()).unwrap();
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="50mm" height="50mm" viewBox="0 0 50 50"><rect x="5" y="5" width="20" height="20" fill="red"/><path d="M0 0 L50 50" stroke="black"/></svg>"#;
        Target::Svg.run(svg.as_bytes()).unwrap();
        Target::LsystemRules.run(b"F\nF -> F[+F]F[-F]F").unwrap();
        Target::Obj
            .run(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n")
            .unwrap();
    }
}
