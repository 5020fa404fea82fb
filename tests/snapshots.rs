//! Snapshot tests of the geometry, through the library and the path dump
//! (`Rendered::dump`): one per tree rule, one outline-style tree and one
//! of every built-in motif as per-path dumps, and one readable summary per
//! built-in template (its pictures are compared in `golden.rs`). Snapshots
//! live in `tests/snapshots/`; tests/README.md says how to read them and
//! how to review a change.

use kurbo::{PathEl, Rect, Shape};
use moyo::project::{self, Rendered};
use moyo::spec::{Format, SceneSpec};
use moyo::{Layer, Scene};

use crate::rendered;

/// Decimals of the per-path snapshots: 0.01 mm, enough to see any real
/// change, coarse enough that float noise (last-bit differences between
/// machines) almost never moves a number across a rounding boundary.
const PRECISION: u8 = 2;

/// Decimals of the template summaries' dump hashes: 0.1 mm, as coarse as
/// their other figures.
const SUMMARY_PRECISION: u8 = 1;

/// Longest line allowed in a snapshot file, so that a diff stays readable.
const MAX_LINE: usize = 2000;

/// Path commands per line of a wrapped dump (see [`wrap`]).
const COMMANDS_PER_LINE: usize = 6;

/// One tree of `rule`, upright in the middle of an A4 page: no jitter, no
/// region lines, every parameter given so that changed defaults do not
/// change these snapshots.
fn one_tree_scene(rule: &str, style: &str) -> String {
    // Tree8 bends by Ang1 between base-curve samples: a larger angle shows
    // its sprays the way the source uses it.
    let ang1 = if rule == "tree8" { 40 } else { 8 };
    format!(
        r#"version = 1
seed = 1

[page]
size = "A4"
margin = 10

# A fine pen: every outlined limb (0.3 mm at its thinnest) is wider than
# two of it, so the outline dump shows outlines only.
[[pens]]
number = 1
width = 0.1

[output]
precision = {PRECISION}

[[layers]]
name = "rule"

[layers.limbs]
style = "{style}"
width = 2
tip_width = 0.3
bow = 0.08

[[layers.trees]]
id = "{rule}"
rule = "{rule}"
count = 1
centre = [[40, 220], [150, 220]]

[layers.trees.params]
generations = 6
trunk = 20
ang1 = {ang1}
ang2 = 55
ang3 = 35
ratio1 = 0.85
ratio2 = 0.6
ratio3 = 0.6
sub_generations = 3
jitter_angle = 0
jitter_length = 0
"#
    )
}

/// The drawing of a small scene as its generators made it, without the
/// pen stage: these dumps are about the geometry of motifs.
fn render(text: &str) -> Rendered {
    let spec = SceneSpec::parse(text, Format::Toml).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let library = moyo::motif::Library::new();
    project::render_for_editing(&spec, &library, &mut |_| {}, &Default::default())
        .unwrap_or_else(|e| panic!("{e}"))
}

/// Structural checks that hold whatever the exact numbers: every line is
/// `layer<TAB>id<TAB>data`, every path starts with a move, stroke paths
/// are open and outline paths closed.
fn check_dump(dump: &str, style: &str) {
    assert!(!dump.is_empty());
    for line in dump.lines() {
        let fields: Vec<&str> = line.split('\t').collect();
        assert_eq!(fields.len(), 3, "{line}");
        let data = fields[2];
        assert!(data.starts_with("M "), "{line}");
        assert_eq!(data.matches('M').count(), 1, "one subpath per limb: {line}");
        match style {
            "stroke" => assert!(!data.contains('Z'), "stroke limb is closed: {line}"),
            "outline" => assert!(data.ends_with(" Z"), "outline limb is open: {line}"),
            _ => unreachable!(),
        }
    }
}

/// A path dump laid out for review: the path's first line is the dump's
/// `layer<TAB>id<TAB>` and its first commands; a new line starts at every
/// further subpath (`M`) and after every [`COMMANDS_PER_LINE`] commands,
/// beginning with two tabs, so it lines up under the path data. Breaking
/// after a fixed number of commands rather than at a width keeps a changed
/// number from reflowing the lines after it. Joining each path's lines
/// with single spaces (dropping the two tabs) gives the dump back.
fn wrap(dump: &str) -> String {
    let mut out = String::new();
    for line in dump.lines() {
        let (head, data) = line.rsplit_once('\t').expect("three fields");
        out.push_str(head);
        out.push('\t');
        // Commands start with a letter; numbers never do.
        let mut in_line = 0;
        for (i, token) in data.split(' ').enumerate() {
            let command = token.starts_with(|c: char| c.is_ascii_alphabetic());
            if command && i > 0 && (token == "M" || in_line == COMMANDS_PER_LINE) {
                out.push_str("\n\t\t");
                in_line = 0;
            } else if i > 0 {
                out.push(' ');
            }
            out.push_str(token);
            in_line += usize::from(command);
        }
        out.push('\n');
    }
    let longest = out.lines().map(str::len).max().unwrap_or(0);
    assert!(
        longest <= MAX_LINE,
        "a snapshot line of {longest} characters"
    );
    out
}

#[test]
fn wrapping_keeps_the_dump() {
    let dump = "l\ta\tM 0 0 L 1 1 L 2 2 L 3 3 L 4 4 L 5 5 L 6 6 L 7 7 Z M 9 9 L 8 8\nl\tb\t\n";
    let wrapped = wrap(dump);
    assert_eq!(
        wrapped,
        "l\ta\tM 0 0 L 1 1 L 2 2 L 3 3 L 4 4 L 5 5\n\
         \t\tL 6 6 L 7 7 Z\n\
         \t\tM 9 9 L 8 8\n\
         l\tb\t\n"
    );
    let unwrapped = wrapped.replace("\n\t\t", " ");
    assert_eq!(unwrapped, dump);
}

#[test]
fn every_tree_rule() {
    for n in 1..=8 {
        let rule = format!("tree{n}");
        let rendered = render(&one_tree_scene(&rule, "stroke"));
        let dump = rendered.dump(PRECISION);
        check_dump(&dump, "stroke");
        assert!(
            dump.lines()
                .all(|l| l.starts_with(&format!("rule\trule.{rule}.tree-0.limb-"))),
            "{dump}"
        );
        // A trunk and at least one branch.
        assert!(dump.lines().count() >= 2, "{rule}: {dump}");
        insta::assert_snapshot!(format!("tree{n}"), wrap(&dump));
    }
}

#[test]
fn tree1_outline() {
    let rendered = render(&one_tree_scene("tree1", "outline"));
    let dump = rendered.dump(PRECISION);
    check_dump(&dump, "outline");
    // Same skeleton, other drawing: as many limbs as the stroke version.
    let strokes = render(&one_tree_scene("tree1", "stroke")).dump(PRECISION);
    assert_eq!(dump.lines().count(), strokes.lines().count());
    insta::assert_snapshot!("tree1-outline", wrap(&dump));
}

/// Every built-in motif at its defaults, 20 mm wide, one path each.
#[test]
fn every_motif() {
    use kurbo::Affine;
    use moyo::motif::{draw, MotifParams};
    use moyo::spec::MotifKind;
    use moyo::{Group, Margins, Page, PaperName, Seed, Style};

    let mut group = Group::new("motifs");
    for (i, kind) in MotifKind::ALL.into_iter().enumerate() {
        let d = draw(kind, &MotifParams::DEFAULT, &mut Seed(1).stream());
        let at = Affine::translate((25.0 + 25.0 * (i % 7) as f64, 25.0 + 40.0 * (i / 7) as f64));
        let path = d.to_path(at * Affine::scale_non_uniform(20.0, 20.0 * d.aspect));
        group.push_path(format!("{kind:?}").to_lowercase(), path, Style::default());
    }
    let scene = Scene {
        page: Page::named(
            PaperName::A4,
            moyo::Orientation::Landscape,
            Margins::uniform(10.0),
        ),
        pens: Vec::new(),
        layers: vec![Layer {
            id: "motifs".into(),
            name: "motifs".into(),
            pen: 1,
            depth: 0,
            content: group,
        }],
        description: None,
    };
    let dump = moyo::output::path_dump(&scene, PRECISION);
    assert_eq!(dump.lines().count(), MotifKind::ALL.len());
    insta::assert_snapshot!("motifs", wrap(&dump));
}

/// Every built-in template as a summary a person can read (see
/// [`summary`]); what it looks like is checked by `golden.rs`.
#[test]
fn every_template() {
    for (t, r) in rendered::plotted() {
        assert!(r.scene.path_count() > 0, "{} draws nothing", t.name);
        insta::assert_snapshot!(format!("template-{}", t.name), summary(&r.scene));
    }
}

/// A template's figures, one table row per layer and per set (a group
/// directly in a layer: a tree set, a background), rounded to 0.1 mm so
/// that float noise does not change them:
///
/// - `paths`, `subpaths` (pen lifts), `length mm` (outline length of every
///   path, fill-only ones included);
/// - `bounds mm`: left, top, right, bottom on the page;
/// - `hash`: FNV-1a 64 of the part's path dump at 0.1 mm. It changes with
///   any change of geometry or ids that shows at that precision; whether
///   the change is visible is the PNG comparison's call.
///
/// The first line gives the totals of the plotted layers (the paths a pen
/// draws and their pen-down length) and the hash of the whole dump.
fn summary(scene: &Scene) -> String {
    let dump = moyo::output::path_dump(scene, SUMMARY_PRECISION);
    let mut lines = dump.lines();
    let page = scene.page_transform();
    let mut rows: Vec<(String, Part)> = Vec::new();
    let mut all = Part::default();
    let mut drawn = Part::default();
    for layer in &scene.layers {
        let mut whole = Part::default();
        // A set is a table's drawing: the first two parts of a path's id
        // (`front.camellia`), wherever the plot stages put the path.
        let mut sets: std::collections::BTreeMap<String, Part> = Default::default();
        layer.content.visit_paths(page, &mut |p, t| {
            let line = lines.next().expect("one dump line per path");
            let path = t * p.path.clone();
            let set = p.id.split('.').take(2).collect::<Vec<_>>().join(".");
            let set = sets.entry(set).or_default();
            for part in [&mut whole, &mut all, set] {
                part.add(&path, line);
            }
            if layer.is_plotted() && !p.style.fill_only {
                drawn.add(&path, line);
            }
        });
        let plotted = if layer.is_plotted() {
            ""
        } else {
            " (not plotted)"
        };
        rows.push((format!("{} pen {}{plotted}", layer.id, layer.pen), whole));
        rows.extend(sets.into_iter().map(|(id, part)| (format!("  {id}"), part)));
    }
    let figures = moyo::plot::stats(scene, &moyo::plot::Speeds::DEFAULT);
    let mut out = format!(
        "{} plotted paths, {} mm pen-down; every path within {} mm; dump hash {:016x}\n\
         pen: {} mm pen-up, {} mm doubled, {} debris, {} pen lifts, densest mm² {:.1}× solid\n\n",
        drawn.paths,
        mm(drawn.length),
        all.bounds_text(),
        all.hash,
        mm(figures.pen_up_mm),
        mm(figures.doubled_mm),
        figures.debris,
        figures.pen_lifts,
        figures.densest,
    );
    let width = rows
        .iter()
        .map(|(n, _)| n.chars().count())
        .max()
        .unwrap_or(0);
    out.push_str(&format!(
        "{:width$}  {:>6}  {:>8}  {:>10}  {:>27}  hash\n",
        "layer / set", "paths", "subpaths", "length mm", "bounds mm"
    ));
    for (name, part) in rows {
        out.push_str(&format!(
            "{name:width$}  {:>6}  {:>8}  {:>10}  {:>27}  {:016x}\n",
            part.paths,
            part.subpaths,
            mm(part.length),
            part.bounds_text(),
            part.hash
        ));
    }
    out
}

/// Running figures of a part of a scene (see [`summary`]).
struct Part {
    paths: usize,
    subpaths: usize,
    length: f64,
    bounds: Option<Rect>,
    hash: u64,
}

impl Default for Part {
    fn default() -> Part {
        Part {
            paths: 0,
            subpaths: 0,
            length: 0.0,
            bounds: None,
            hash: FNV_OFFSET,
        }
    }
}

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

impl Part {
    /// Adds a path (in page coordinates) and its dump line.
    fn add(&mut self, path: &kurbo::BezPath, line: &str) {
        self.paths += 1;
        self.subpaths += path
            .elements()
            .iter()
            .filter(|e| matches!(e, PathEl::MoveTo(_)))
            .count();
        self.length += moyo::geom::path_length(path);
        if !path.elements().is_empty() {
            let b = path.bounding_box();
            self.bounds = Some(self.bounds.map_or(b, |a| a.union(b)));
        }
        for byte in line.bytes().chain([b'\n']) {
            self.hash = (self.hash ^ u64::from(byte)).wrapping_mul(FNV_PRIME);
        }
    }

    fn bounds_text(&self) -> String {
        self.bounds.map_or_else(
            || "none".into(),
            |b| format!("{} {} {} {}", mm(b.x0), mm(b.y0), mm(b.x1), mm(b.y1)),
        )
    }
}

/// A length at 0.1 mm, never `-0.0`.
fn mm(v: f64) -> String {
    format!("{:.1}", (v * 10.0).round() / 10.0 + 0.0)
}
