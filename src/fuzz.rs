//! Entry points for fuzzing: each reads arbitrary bytes the way one of
//! moyo's commands reads a file, then runs what that command runs after
//! it, within a small path budget. None may panic, hang or run out of
//! memory; an input it cannot use is an `Err`, which is a fine answer.
//!
//! The coverage-guided targets in `fuzz/` (cargo-afl, see
//! `fuzz/README.md`) call [`Target::run`], and so does the regression test
//! `tests/fuzz_regressions.rs`, on every input a fuzzer ever found that
//! panicked or hung (`fuzz/crashers/<target>/`), so a fixed finding stays
//! fixed in plain `cargo test`.

use std::collections::BTreeMap;

use crate::error::{Error, Result};
use crate::input::{decode_image, import_svg, ImportOptions};
use crate::lsystem::LSystem;
use crate::output::to_obj;
use crate::plot::{HatchOptions, MergeOptions, OccludeOptions, PlotOptions, SortOptions};
use crate::project::{self, plot_scene, PlotFormat, PlotJob};
use crate::rng::Seed;
use crate::scene::embedded_description;
use crate::spec::{Format, SceneSpec};
use crate::vine::TriMesh;

/// The path budget of a fuzzed description: its own `limits.max_paths`,
/// but at most this many, so one case cannot take long.
pub const MAX_PATHS: usize = 20_000;

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
}

impl Target {
    /// Every target.
    pub const ALL: [Target; 7] = [
        Target::SceneToml,
        Target::SceneJson,
        Target::Svg,
        Target::RenderFrom,
        Target::Obj,
        Target::Image,
        Target::LsystemRules,
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
        }
    }
}

fn text(bytes: &[u8]) -> Result<&str> {
    std::str::from_utf8(bytes).map_err(|e| Error::invalid("input", format!("not UTF-8: {e}")))
}

/// Validates a description and renders it, with every plot output, its
/// path budget capped at [`MAX_PATHS`]. The files it names are not there.
fn scene(text: &str, format: Format) -> Result<()> {
    let mut spec = SceneSpec::parse(text, format)?.into_inner();
    spec.limits.max_paths = spec.limits.max_paths.min(MAX_PATHS);
    let spec = spec.validate()?;
    let library = project::load_motifs_with(&spec, &|name: &str| {
        let missing = std::io::Error::new(std::io::ErrorKind::NotFound, "not in a fuzz case");
        (name.to_string(), Err(missing))
    })?;
    let rendered = project::render_with_progress(&spec, &library, &mut |_| {})?;
    to_obj(&rendered.models, spec.output.precision);
    outputs(rendered.scene)
}

/// Imports an SVG and runs every plot stage and output on it.
fn svg(text: &str) -> Result<()> {
    let imported = import_svg(text, &ImportOptions::DEFAULT)?;
    let stages = PlotOptions {
        occlude: Some(OccludeOptions::default()),
        hatch: Some(HatchOptions::default()),
        merge: Some(MergeOptions::default()),
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_refusals_are_errors() {
        for t in Target::ALL {
            assert_eq!(Target::from_name(t.name()), Some(t));
            assert!(
                t.run(&[0xff, 0xfe, 0x00]).is_err() || t == Target::Image,
                "{t:?}"
            );
            assert!(t.run(&vec![b' '; MAX_INPUT + 1]).is_err(), "{t:?}");
        }
        assert_eq!(Target::from_name("nothing"), None);
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
