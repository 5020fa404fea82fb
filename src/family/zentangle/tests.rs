//! The zentangle family: the loop's invariants (strokes stay in their
//! region, the widest white circle never grows), what the description
//! allows, determinism and errors.

use kurbo::{BezPath, PathEl, Point, Rect};

use super::filling::{Filling, Settings};
use super::procedure::{seed_group, Allowed};
use super::Shape;
use crate::geom::offset::offset;
use crate::geom::region::Region;
use crate::motif::test_scene;
use crate::project::build_scene;
use crate::rng::Seed;
use crate::scene::Scene;
use crate::spec::{Format, SceneSpec};

/// A zentangle table running the paper's loop unless it names its look:
/// most of these tests check what the paper says.
fn paper(table: &str) -> String {
    if table.contains("look =") {
        table.to_owned()
    } else {
        format!("look = \"sampler\"\n{table}")
    }
}

fn text(table: &str) -> String {
    test_scene::text("zentangle", &paper(table))
}

fn scene(table: &str) -> Scene {
    test_scene::scene("zentangle", &paper(table))
}

fn error(table: &str) -> String {
    test_scene::error("zentangle", &paper(table))
}

/// The procedure each step group drew (`…step-K-pP`).
fn procedures(s: &Scene) -> Vec<u32> {
    let mut out = Vec::new();
    s.layers[0]
        .content
        .visit_paths(kurbo::Affine::IDENTITY, &mut |p, _| {
            let step = p.id.split('.').nth(2).unwrap_or("");
            if let Some(proc) = step.rsplit_once("-p").and_then(|(_, n)| n.parse().ok()) {
                if out.last() != Some(&proc) || !p.id.ends_with("-0") {
                    out.push(proc);
                }
            }
        });
    out
}

fn points(path: &BezPath) -> Vec<Point> {
    let mut out = Vec::new();
    kurbo::flatten(path.iter(), 0.05, |el| match el {
        PathEl::MoveTo(p) | PathEl::LineTo(p) => out.push(p),
        _ => {}
    });
    out
}

fn all() -> Allowed {
    Allowed {
        procedures: (0..20).collect(),
        elements: Shape::ALL.to_vec(),
    }
}

/// The loop's settings of the tests that run it directly (a 0.3 mm pen).
fn settings() -> Settings<'static> {
    Settings {
        scale: 0.35,
        smallest: 1.5,
        wobble: 0.6,
        hand: 0.4,
        retrace: 0.2,
        pen: 0.3,
        fragment: 1.2,
        hatch: Some(0.5),
        follow: 0.0,
        branching: 2,
        tone: None,
        choice: None,
        depth: u32::MAX,
    }
}

#[test]
fn every_stroke_stays_in_its_region_and_the_widest_circle_never_grows() {
    let page = Region::from_rect(Rect::new(0.0, 0.0, 150.0, 200.0)).unwrap();
    let pen = settings().pen;
    let hand = Seed(11).derive("hand").stream();
    let (mut filling, _) = Filling::new(&[page], Vec::new(), all(), settings(), hand).unwrap();
    let mut rng = Seed(11).derive("t").stream();
    let mut last = f64::INFINITY;
    for k in 0..60 {
        let Some((region, radius)) = filling.widest() else {
            break;
        };
        // Radii are found to within `precision`.
        let slack = super::filling::precision(&region, pen);
        assert!(radius <= last + slack, "step {k}: {radius} after {last}");
        last = radius;
        let step = filling.step(&mut rng).unwrap().unwrap();
        // Within the pen's half width (and the flattening) of the region.
        let reach = offset(&region, pen / 2.0 + 0.02, 0.01).unwrap();
        for stroke in &step.strokes {
            for p in points(stroke) {
                assert!(reach.contains(p), "step {k}: {p:?} outside its region");
            }
        }
        for b in &step.black {
            assert!(b.area() <= region.area() + 1e-6);
        }
    }
}

#[test]
fn whirls_stop_before_they_blot() {
    // Paradox whirls alone, 120 of them in ever smaller regions: each
    // turn is a line a little inside the last, so without the ink limit
    // their last turns converge to several times solid ink.
    let s = scene("steps = 120\nprocedures = [17]\n");
    let mut lines = Vec::new();
    s.visit_paths(|_, p, t| {
        if p.style.fill.is_none() {
            lines.push(t * p.path.clone());
        }
    });
    assert!(lines.len() > 500, "{} lines", lines.len());
    let densest = crate::plot::stats::densest(lines.iter(), s.pen_width(1));
    // The loop counts a little under what is drawn, and keeps a margin.
    assert!(densest <= 2.0, "{densest}× solid");
}

#[test]
fn the_loop_stops_when_no_region_can_take_a_step_and_its_work_is_bounded() {
    // Paradox whirls alone: each turn is a line a little inside the
    // last, so the small regions they leave soon hold no whirl under the
    // ink limit. Such a region used to go back as the widest and be
    // tried again at every step left: 2,000 tries here.
    let page = Region::from_rect(Rect::new(0.0, 0.0, 128.0, 190.0)).unwrap();
    let whirls = Allowed {
        procedures: vec![17],
        elements: Shape::ALL.to_vec(),
    };
    let hand = Seed(5).derive("hand").stream();
    let (mut filling, _) = Filling::new(&[page], Vec::new(), whirls, settings(), hand).unwrap();
    let mut rng = Seed(5).derive("t").stream();
    let asked = 2000;
    let mut steps = 0;
    while steps < asked && filling.step(&mut rng).unwrap().is_some() {
        steps += 1;
    }
    assert!(steps < asked / 4, "{steps} steps: the loop did not stop");
    assert_eq!(filling.open(), 0);
    // Some regions drew nothing (else this tests nothing) and were tried
    // at most `TRIES` times each.
    let failed = filling.attempts() - steps;
    assert!(failed > 0, "no step drew nothing");
    assert!(
        failed <= super::filling::TRIES as usize * filling.made(),
        "{failed} tries drew nothing in {} regions",
        filling.made()
    );
    // 711 here (192 steps).
    assert!(filling.attempts() < asked / 2, "{} tries for {steps} steps", filling.attempts());

    // The scene says where it stopped, and draws that many steps.
    let table = "steps = 2000\nprocedures = [17]\n";
    let s = scene(table);
    let notes = test_scene::notes("zentangle", &paper(table));
    let stopped = notes[0]
        .split_once("the loop stopped after step ")
        .and_then(|(_, rest)| rest.split_once(' '))
        .and_then(|(k, _)| k.parse::<usize>().ok())
        .unwrap_or_else(|| panic!("{notes:?}"));
    assert!(stopped < 500, "{notes:?}");
    assert!(notes[0].contains("of the 2000 steps asked for"), "{notes:?}");
    let mut last = 0;
    s.layers[0]
        .content
        .visit_paths(kurbo::Affine::IDENTITY, &mut |p, _| {
            let k = p.id.split('.').nth(2).and_then(|g| g.split('-').nth(1));
            if let Some(k) = k.and_then(|k| k.parse::<usize>().ok()) {
                last = last.max(k);
            }
        });
    assert_eq!(last, stopped, "{notes:?}");
}

#[test]
fn only_allowed_procedures_are_drawn_and_seeds_follow_their_groups() {
    // Triangles hold circles (G3), circles squares (G5), squares
    // triangles (G4): with only 0–2 allowed, every step is one of them.
    let s = scene("steps = 30\nprocedures = [0, 1, 2]\nwobble = 0\n");
    let drawn = procedures(&s);
    assert!(drawn.len() >= 10, "{drawn:?}");
    assert!(drawn.iter().all(|p| [0, 1, 2].contains(p)), "{drawn:?}");
    assert_eq!(seed_group(0), Some(&[2][..]));
    // Line-only procedures make no seeds.
    for p in [3, 11, 12, 14, 16, 17, 18] {
        assert_eq!(seed_group(p), None, "{p}");
    }
    // One procedure only: contour lines every time.
    let s = scene("steps = 8\nprocedures = [16]\n");
    assert!(procedures(&s).iter().all(|&p| p == 16));
}

#[test]
fn manual_steps_come_first_and_name_their_region() {
    let s = scene("steps = 0\nmanual = [{ at = [60, 90], procedure = 18 }, { at = [5, 5], procedure = 16 }]\n");
    let drawn = procedures(&s);
    assert_eq!(drawn.first(), Some(&18), "{drawn:?}");
    let e = error("steps = 0\nmanual = [{ at = [60, 90], procedure = 1 }, { at = [500, 500], procedure = 16 }]\n");
    assert!(
        e.contains("layers[0].zentangle[0].manual[1].at: (500, 500) lies in no white region"),
        "{e}"
    );
}

#[test]
fn manual_steps_after_the_loop_touch_up_what_it_left_white() {
    let loop_only = scene("steps = 6\n");
    let dump = |s: &Scene| crate::output::path_dump(s, 3);
    // The first place on a 6 mm grid that the loop left white.
    let touched = (1..22)
        .flat_map(|i| (1..32).map(move |j| (f64::from(i) * 6.0, f64::from(j) * 6.0)))
        .find_map(|(x, y)| {
            let table = format!(
                "steps = 6\nmanual = [{{ at = [{x}, {y}], procedure = 18, after = true }}]\n"
            );
            let text = text(&table);
            let spec = SceneSpec::parse(&text, Format::Toml).unwrap();
            build_scene(&spec).ok()
        })
        .expect("the loop leaves a white region somewhere");
    // What the loop drew is as it was; one more step follows it.
    let (before, after) = (dump(&loop_only), dump(&touched));
    assert!(
        after.starts_with(before.trim_end()),
        "the loop's steps changed"
    );
    let steps = |s: &Scene| {
        let mut ids = std::collections::BTreeSet::new();
        s.layers[0]
            .content
            .visit_paths(kurbo::Affine::IDENTITY, &mut |p, _| {
                ids.insert(p.id.split('.').nth(2).unwrap_or("").to_string());
            });
        ids
    };
    let new: Vec<String> = steps(&touched)
        .difference(&steps(&loop_only))
        .cloned()
        .collect();
    assert_eq!(new.len(), 1, "{new:?}");
    assert!(new[0].ends_with("-p18"), "{new:?}");
    // A touch-up where no white region is is named by its field.
    let e = error("steps = 6\nmanual = [{ at = [500, 5], procedure = 2, after = true }]\n");
    assert!(
        e.contains("manual[0].at: (500, 5) lies in no white region"),
        "{e}"
    );
}

#[test]
fn user_lines_split_the_page_first() {
    let s = scene("steps = 0\nlines = [[[0, 95], [128, 95]]]\n");
    let mut ids = Vec::new();
    s.layers[0]
        .content
        .visit_paths(kurbo::Affine::IDENTITY, &mut |p, _| ids.push(p.id.clone()));
    assert_eq!(ids, ["l.zentangle-0.step-0-lines.line-0"]);
}

#[test]
fn the_seed_decides_everything() {
    let table = "steps = 25\n";
    let a = crate::output::path_dump(&scene(table), 4);
    assert_eq!(a, crate::output::path_dump(&scene(table), 4));
    let other = text(table).replace("seed = 5", "seed = 6");
    let b = build_scene(&SceneSpec::parse(&other, Format::Toml).unwrap()).unwrap();
    assert_ne!(a, crate::output::path_dump(&b, 4));
}

#[test]
fn bad_tables_are_refused_with_their_field() {
    for (table, expected) in [
        (
            "procedures = [32]\n",
            "layers[0].zentangle[0].procedures[0]: must be between 0 and 31",
        ),
        ("procedures = [\"zendala\"]\n", "unknown tangle `zendala`"),
        ("procedures = []\n", "layers[0].zentangle[0].procedures: allows nothing"),
        (
            "elements = [\"xx\"]\n",
            "layers[0].zentangle[0].elements[0]: unknown element `xx`",
        ),
        ("steps = 9000\n", "layers[0].zentangle[0].steps: must be between 0 and 5000"),
        // The loop's work: 19 steps at the smallest scale are past it.
        (
            "steps = 19\nscale = 0.05\n",
            "layers[0].zentangle[0].steps: 19 steps at scale 0.05 are about 152000 units",
        ),
        (
            "smallest = 50\n[layers.zentangle.region]\ncircle = { centre = [50, 50], radius = 20 }\n",
            "layers[0].zentangle[0].region: is too small to draw in",
        ),
        (
            "lines = [[[0, 0]]]\n",
            "layers[0].zentangle[0].lines[0]",
        ),
        ("wobble = nan\n", "layers[0].zentangle[0].wobble"),
        ("follow = 1.5\n", "layers[0].zentangle[0].follow: must be between 0 and 1"),
        ("branching = 4\n", "layers[0].zentangle[0].branching: must be between 0 and 3"),
        (
            "tone = { contrast = 0.5 }\n",
            "layers[0].zentangle[0].tone: needs an `image`, a `formula` or both",
        ),
        (
            "tone = { formula = \"u +\" }\n",
            "layers[0].zentangle[0].tone.formula",
        ),
        (
            "tone = { formula = \"w\" }\n",
            "layers[0].zentangle[0].tone.formula",
        ),
        (
            "tone = { formula = \"u\", contrast = 2 }\n",
            "layers[0].zentangle[0].tone.contrast: must be between 0 and 1",
        ),
        (
            "tone = { image = \"missing.png\" }\n",
            "missing.png",
        ),
    ] {
        let e = error(table);
        assert!(e.contains(expected), "{table}\n→ {e}\nwanted {expected}");
    }
}

#[test]
fn the_light_parts_of_an_image_are_the_regions() {
    use crate::geom::density::GreyImage;
    use crate::motif::Library;
    use crate::project::build_scene_with_progress;
    // A light disc on dark, 64 × 95 px over the 128 × 190 mm drawable
    // area (2 mm a pixel): the disc has radius 50 mm about (64, 95).
    let (w, h) = (64usize, 95usize);
    let d = (0..h)
        .flat_map(|j| (0..w).map(move |i| (i, j)))
        .map(|(i, j)| {
            let (x, y) = (i as f64 * 2.0 + 1.0, j as f64 * 2.0 + 1.0);
            if (x - 64.0).hypot(y - 95.0) < 50.0 {
                0.0
            } else {
                1.0
            }
        })
        .collect();
    let mut library = Library::new();
    library.add_image("stencil.png", GreyImage::new(w, h, d).unwrap());
    let text = text("steps = 20\n[layers.zentangle.region]\nimage = \"stencil.png\"\n");
    let spec = SceneSpec::parse(&text, Format::Toml).unwrap();
    let s = build_scene_with_progress(&spec, &library, &mut |_| {}).unwrap();
    let mut n = 0;
    s.layers[0]
        .content
        .visit_paths(kurbo::Affine::IDENTITY, &mut |p, t| {
            n += 1;
            for q in points(&(t * p.path.clone())) {
                assert!(
                    q.distance(Point::new(64.0, 95.0)) < 51.5,
                    "{} at {q:?}",
                    p.id
                );
            }
        });
    assert!(n > 20, "{n} paths");
    // An image dark all over has nothing to fill.
    let mut library = Library::new();
    library.add_image("stencil.png", GreyImage::new(2, 2, vec![1.0; 4]).unwrap());
    let e = build_scene_with_progress(&spec, &library, &mut |_| {}).unwrap_err();
    assert!(
        e.to_string()
            .contains("layers[0].zentangle[0].region.image: stencil.png: has no light part"),
        "{e}"
    );
}

#[test]
fn a_hand_bends_each_stroke_a_little_and_differently() {
    use super::element::{Mark, Paint};
    let mut line = BezPath::new();
    line.move_to((0.0, 0.0));
    line.line_to((100.0, 0.0));
    let mark = Mark {
        path: line,
        paint: Paint::Line,
    };
    let mut rng = Seed(3).derive("hand").stream();
    let a = super::filling::by_hand(&mark, 0.5, &mut rng).unwrap();
    let b = super::filling::by_hand(&mark, 0.5, &mut rng).unwrap();
    let (pa, pb) = (points(&a.path), points(&b.path));
    // Every point within the amount of the line (the lattice's weights
    // sum to one), the two copies different, and the line really bent.
    let off = |ps: &[Point]| ps.iter().map(|p| p.y.abs()).fold(0.0, f64::max);
    assert!(off(&pa) <= 0.5 + 1e-9 && off(&pb) <= 0.5 + 1e-9);
    assert!(off(&pa) > 0.05);
    assert_ne!(pa, pb);
    // Off by default; on, the same tangle is drawn (the same steps and
    // procedures), its lines bent.
    let plain = scene("steps = 6\n");
    let by_hand = scene("steps = 6\nhand = 0.4\n");
    let steps = |s: &Scene| {
        let mut ids: Vec<String> = Vec::new();
        s.layers[0]
            .content
            .visit_paths(kurbo::Affine::IDENTITY, &mut |p, _| {
                let step = p.id.split('.').nth(2).unwrap_or("").to_string();
                if ids.last() != Some(&step) {
                    ids.push(step);
                }
            });
        ids
    };
    assert_eq!(steps(&plain), steps(&by_hand));
    assert_ne!(
        crate::output::path_dump(&plain, 3),
        crate::output::path_dump(&by_hand, 3)
    );
}

#[test]
fn retracing_draws_each_line_twice_near_itself() {
    let once = scene("steps = 4\nwobble = 0\n");
    let twice = scene("steps = 4\nwobble = 0\nretrace = 0.3\n");
    let length = |s: &Scene| s.stats().pen_down_mm;
    // The same steps, about twice the ink (a little less where a copy
    // falls outside its region or under a later fill).
    let ratio = length(&twice) / length(&once);
    assert!(ratio > 1.6 && ratio < 2.2, "{ratio}");
    assert!(error("retrace = 2\n").contains("layers[0].zentangle[0].retrace"));
}

/// A bordered 89 mm tile with a string, as `zentangle-string` draws it.
const TILE: &str = "steps = 60\nhand = 0.3\nlook = \"tangles\"\n\
    [layers.zentangle.border]\ncorner = 5\n\
    [layers.zentangle.string]\nlines = [[[0, 30], [40, 45], [60, 89]], [[40, 45], [89, 20]]]\n\
    [layers.zentangle.region]\npolygon = [[0, 0], [89, 0], [89, 89], [0, 89]]\n";

/// The paths of the first layer whose id has `part`, on the page.
fn paths_with(s: &Scene, part: &str) -> Vec<BezPath> {
    let mut out = Vec::new();
    s.layers[0].content.visit_paths(kurbo::Affine::IDENTITY, &mut |p, t| {
        if p.id.contains(part) {
            out.push(t * p.path.clone());
        }
    });
    out
}

#[test]
fn the_border_is_one_closed_line_and_nothing_lies_outside_it() {
    let s = scene(TILE);
    let border = paths_with(&s, ".border.");
    assert_eq!(border.len(), 1);
    let line = &border[0];
    let moves = line.elements().iter().filter(|e| matches!(e, PathEl::MoveTo(_))).count();
    assert_eq!(moves, 1);
    assert!(matches!(line.elements().last(), Some(PathEl::ClosePath)));
    // Rounded corners: the corner of the square is well outside it, and
    // the hand bent it (no side is straight).
    let inside = Region::new(line.clone(), crate::geom::region::FillRule::NonZero).unwrap();
    let b = inside.bounds();
    assert!(!inside.contains(Point::new(b.x0 + 0.8, b.y0 + 0.8)));
    let straight = Region::from_rect(Rect::new(0.0, 0.0, 89.0, 89.0)).unwrap();
    assert!(inside.xor(&straight).area() > 20.0, "{}", inside.xor(&straight).area());
    // Every other line lies inside it, short of its ink.
    let tangles = paths_with(&s, ".step-");
    assert!(tangles.len() > 50, "{}", tangles.len());
    let within = offset(&inside, -0.1, 0.01).unwrap();
    for t in &tangles {
        for p in points(t) {
            assert!(within.contains(p), "{p:?} outside the border");
        }
    }
    // Without `border` the edge is not drawn.
    let plain = scene(&TILE.replace("[layers.zentangle.border]\ncorner = 5\n", ""));
    assert!(paths_with(&plain, ".border.").is_empty());
}

#[test]
fn a_string_left_out_still_splits_the_sections() {
    let inked = scene(TILE);
    let hidden = scene(&TILE.replace("[layers.zentangle.string]\n", "[layers.zentangle.string]\nink = false\n"));
    assert!(paths_with(&inked, ".step-0-lines.").len() >= 2);
    assert!(paths_with(&hidden, ".step-0-lines.").is_empty());
    // No tangle line crosses the string's ink: every point of every step
    // stays a pen's half width away from the string's curves.
    let string: Vec<BezPath> = paths_with(&inked, ".step-0-lines.");
    for t in paths_with(&hidden, ".step-") {
        for p in points(&t) {
            let d = string
                .iter()
                .map(|c| super::element::tests::distance_to(c, p))
                .fold(f64::INFINITY, f64::min);
            assert!(d > 0.12, "{p:?} is {d} mm from the string");
        }
    }
}

#[test]
fn one_tangle_a_section_or_a_sampler() {
    // Sections: one depth-0 step each, then only nested ones.
    let count = |s: &Scene| {
        let mut set = std::collections::BTreeSet::new();
        for p in procedures(s) {
            set.insert(p);
        }
        set.len()
    };
    let tangles = scene(&format!("depth = 0\n{TILE}"));
    // Three sections, each one tangle and nothing nested.
    assert!(count(&tangles) <= 3, "{:?}", procedures(&tangles));
    let sampler = scene(&TILE.replace("look = \"tangles\"", "look = \"sampler\""));
    assert!(count(&sampler) > 6, "{:?}", procedures(&sampler));
    // A table that names no look fills a section with one tangle.
    let unnamed = test_scene::scene("zentangle", &format!("depth = 0\n{}", TILE.replace("look = \"tangles\"\n", "")));
    assert_eq!(
        crate::output::path_dump(&unnamed, 3),
        crate::output::path_dump(&tangles, 3)
    );
    assert!(error("look = \"quilt\"\n").contains("look"));
    assert!(error("weights = { \"20\" = 1 }\n").contains("layers[0].zentangle[0].weights.20: names no procedure"));
    assert!(error("depth = 30\n").contains("layers[0].zentangle[0].depth: must be between 0 and 20"));
    assert!(error(&TILE.replace("corner = 5", "corner = 45")).contains("layers[0].zentangle[0].border.corner"));
}

#[test]
fn a_hatched_black_part_is_outlined_once_by_lines_not_by_itself() {
    // Procedure 13's black squares and bands, reaching the tile's edge
    // where no border is drawn.
    let s = scene("steps = 4\nprocedures = [13]\nwobble = 0\nelements = [\"msq2\"]\n");
    let pen = s.pen_width(1);
    let (mut black, mut lines, mut edges) = (Vec::new(), Vec::new(), Vec::new());
    s.visit_paths(|_, p, t| {
        let path = t * p.path.clone();
        if p.style.fill.is_some() {
            // Paint whose hatch keeps clear of an edge the lines draw.
            assert!(p.style.fill_only && p.style.edge_drawn, "{}", p.id);
            black.push(path);
        } else if p.id.ends_with(".edge") {
            edges.push(path);
        } else {
            lines.push(path);
        }
    });
    assert!(black.len() >= 5 && !edges.is_empty(), "{} black parts", black.len());
    // Every stretch of every black part's edge lies on a line, of a mark
    // or of the part's own bare edge.
    let drawn: Vec<BezPath> = lines.iter().chain(&edges).cloned().collect();
    let near = Near::new(&drawn);
    let samples: Vec<Point> = black.iter().flat_map(|b| along(b, 0.1)).collect();
    let bare = samples.iter().filter(|&&p| near.distance(p) > pen / 4.0).count();
    assert!(
        bare * 1000 <= samples.len(),
        "{bare} of {} points of black edges lie on no line",
        samples.len()
    );
    // Without the parts' own edges, the tile's edge is bare where black
    // meets it: the edges are needed.
    let marks_only = Near::new(&lines);
    let bare = samples.iter().filter(|&&p| marks_only.distance(p) > pen / 4.0).count();
    assert!(bare * 50 >= samples.len(), "{bare} of {}", samples.len());
    // And no stretch of an edge runs along a mark's line: the edges add
    // no line drawn twice.
    let doubled = |paths: &[BezPath]| {
        crate::plot::dedupe::doubled_length(paths, pen / 4.0, 2.0 * pen)
    };
    let (with, without) = (doubled(&drawn), doubled(&lines));
    let edge_length: f64 = edges.iter().map(|e| kurbo::Shape::perimeter(e, 0.01)).sum();
    assert!(
        with - without <= 0.02 * edge_length,
        "{with} mm doubled with the {edge_length} mm of edges, {without} without"
    );
}

/// Points along `path` at most `step` mm apart.
fn along(path: &BezPath, step: f64) -> Vec<Point> {
    let mut out = Vec::new();
    let (mut start, mut last) = (Point::ZERO, Point::ZERO);
    kurbo::flatten(path.iter(), 0.01, |el| {
        let to = match el {
            PathEl::MoveTo(p) => {
                out.push(p);
                (start, last) = (p, p);
                return;
            }
            PathEl::LineTo(p) => p,
            PathEl::ClosePath => start,
            _ => return,
        };
        let n = (last.distance(to) / step).ceil().max(1.0) as usize;
        out.extend((1..=n).map(|k| last.lerp(to, k as f64 / n as f64)));
        last = to;
    });
    out
}

/// The distance to a set of paths' flattened segments, through a grid of
/// 1 mm cells.
struct Near {
    cells: std::collections::HashMap<(i64, i64), Vec<(Point, Point)>>,
}

impl Near {
    fn new(paths: &[BezPath]) -> Near {
        let mut cells: std::collections::HashMap<_, Vec<_>> = Default::default();
        for path in paths {
            let pts = along(path, 0.5);
            for w in pts.windows(2) {
                let mid = w[0].midpoint(w[1]);
                let key = (mid.x.floor() as i64, mid.y.floor() as i64);
                cells.entry(key).or_default().push((w[0], w[1]));
            }
        }
        Near { cells }
    }

    fn distance(&self, p: Point) -> f64 {
        let (cx, cy) = (p.x.floor() as i64, p.y.floor() as i64);
        let mut best = f64::INFINITY;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for &(a, b) in self.cells.get(&(cx + dx, cy + dy)).into_iter().flatten() {
                    use kurbo::ParamCurveNearest;
                    best = best.min(kurbo::Line::new(a, b).nearest(p, 1e-9).distance_sq.sqrt());
                }
            }
        }
        best
    }
}
