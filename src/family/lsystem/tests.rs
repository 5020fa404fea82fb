use kurbo::{Affine, BezPath, ParamCurve, ParamCurveArclen, PathEl, Point, Rect, Shape as _};

use crate::motif::test_scene;
use crate::scene::Scene;

fn scene(table: &str) -> Scene {
    test_scene::scene("lsystem", table)
}

fn error(table: &str) -> String {
    test_scene::error("lsystem", table)
}

/// Every path of the scene on the page.
fn paths(scene: &Scene) -> Vec<BezPath> {
    let mut out = Vec::new();
    scene.layers[0]
        .content
        .visit_paths(Affine::IDENTITY, &mut |p, t| out.push(t * p.path.clone()));
    out
}

fn length(paths: &[BezPath]) -> f64 {
    paths
        .iter()
        .flat_map(|p| p.segments())
        .map(|s| s.arclen(1e-6))
        .sum()
}

fn bounds(paths: &[BezPath]) -> Rect {
    paths
        .iter()
        .map(|p| p.bounding_box())
        .reduce(|a, b| a.union(b))
        .unwrap()
}

#[test]
fn a_placed_drawing_starts_at_its_root_heading_up_one_step_per_unit() {
    // F F + F: 20 mm up from (50, 150), then 10 mm to the upper left
    // (`+` turns left as seen on the page).
    let s = scene("axiom = \"FF+F\"\nangle = 90\nat = [[50, 150]]\nstep = 10\n");
    let p = paths(&s);
    assert_eq!(p.len(), 1);
    let pts: Vec<Point> = p[0]
        .elements()
        .iter()
        .filter_map(|e| match e {
            PathEl::MoveTo(p) | PathEl::LineTo(p) => Some(*p),
            _ => None,
        })
        .collect();
    let want = [(50.0, 150.0), (50.0, 140.0), (50.0, 130.0), (40.0, 130.0)];
    assert_eq!(pts.len(), want.len(), "{pts:?}");
    for (p, w) in pts.iter().zip(want) {
        assert!(p.distance(Point::from(w)) < 1e-9, "{pts:?}");
    }
    // Turned a quarter clockwise, it heads right.
    let s = scene("axiom = \"F\"\nat = [[50, 150]]\nstep = 10\nrotate = 90\n");
    let b = bounds(&paths(&s));
    assert!(
        (b.x1 - 60.0).abs() < 1e-9 && (b.y0 - 150.0).abs() < 1e-9,
        "{b:?}"
    );
}

#[test]
fn a_fitted_drawing_fills_the_page_inside_its_margins() {
    // A5 with 10 mm margins: 128 × 190 mm, scene coordinates starting at
    // the margins' corner. The Koch snowflake is wider than tall, so it
    // spans the width, centred.
    let s = scene("axiom = \"F--F--F\"\nrules = [\"F -> F+F--F+F\"]\niterations = 3\nangle = 60\n");
    let b = bounds(&paths(&s));
    assert!(b.x0.abs() < 1e-6 && (b.x1 - 128.0).abs() < 1e-6, "{b:?}");
    assert!(((b.y0 + b.y1) / 2.0 - 95.0).abs() < 1e-6, "{b:?}");
    assert!(b.height() < 190.0);
}

#[test]
fn the_koch_curve_grows_by_four_thirds_a_step_and_stays_exact() {
    // Placed (not fitted), each step makes the curve 4/3 as long.
    let len = |n: u32| {
        let s = scene(&format!(
            "axiom = \"F\"\nrules = [\"F -> F+F--F+F\"]\niterations = {n}\nangle = 60\nat = [[20, 150]]\nstep = {}\n",
            100.0 / 3f64.powi(n as i32)
        ));
        let p = paths(&s);
        // Exact lines: no curve in the output.
        assert!(p
            .iter()
            .flat_map(|p| p.elements())
            .all(|e| matches!(e, PathEl::MoveTo(_) | PathEl::LineTo(_))));
        length(&p)
    };
    for n in 0..4 {
        let ratio = len(n + 1) / len(n);
        assert!((ratio - 4.0 / 3.0).abs() < 1e-9, "step {n}: {ratio}");
    }
}

#[test]
fn views_see_the_3d_drawing_from_their_side() {
    // Up, then pitched down a quarter (`&`: towards the viewer's −z? the
    // turtle's up is +z, so `&` turns the heading towards −U): the second
    // step goes along z, which the front does not see and the side does.
    let table = "axiom = \"F&(90)F\"\nat = [[50, 150]]\nstep = 10\n";
    let front = bounds(&paths(&scene(table)));
    assert!(
        front.width() < 1e-9 && (front.height() - 10.0).abs() < 1e-9,
        "{front:?}"
    );
    let side = bounds(&paths(&scene(&format!("{table}view = \"side\"\n"))));
    assert!(
        (side.width() - 10.0).abs() < 1e-9 && (side.height() - 10.0).abs() < 1e-9,
        "{side:?}"
    );
    let top = bounds(&paths(&scene(&format!("{table}view = \"top\"\n"))));
    assert!(
        top.width() < 1e-9 && (top.height() - 10.0).abs() < 1e-9,
        "{top:?}"
    );
}

#[test]
fn outlines_are_closed_and_as_wide_as_the_turtle() {
    let s = scene("axiom = \"F\"\nat = [[50, 150]]\nstep = 10\nstyle = \"outline\"\nwidth = 0.4\n");
    let p = paths(&s);
    assert_eq!(p.len(), 1);
    assert!(matches!(p[0].elements().last(), Some(PathEl::ClosePath)));
    let b = p[0].bounding_box();
    // 4 mm wide (0.4 units of 10 mm), a round cap on top.
    assert!((b.width() - 4.0).abs() < 1e-6, "{b:?}");
    assert!(
        (b.y1 - 150.0).abs() < 1e-6 && (b.y0 - 138.0).abs() < 1e-6,
        "{b:?}"
    );
}

#[test]
fn smooth_limbs_pass_through_the_turtle_points() {
    let table = "axiom = \"F+F+F\"\nangle = 30\nat = [[50, 150]]\nstep = 10\n";
    let sharp = paths(&scene(table));
    let smooth = paths(&scene(&format!("{table}smooth = true\n")));
    assert!(smooth[0]
        .elements()
        .iter()
        .any(|e| matches!(e, PathEl::CurveTo(..))));
    // The same ends.
    let end = |p: &BezPath| p.segments().last().unwrap().end();
    assert!(end(&sharp[0]).distance(end(&smooth[0])) < 1e-9);
}

#[test]
fn a_sketch_lies_on_its_stroke_and_grows_with_its_steps() {
    let table = "style = \"outline\"\n[layers.lsystem.sketch]\npoints = [[64, 185], [64, 20]]\nmodule = 10\n";
    let whole = scene(table);
    let b = bounds(&paths(&whole));
    // Along the stroke, branching to both sides of it.
    assert!(b.y1 <= 191.0 && b.y0 >= 19.0 - 60.0, "{b:?}");
    assert!(b.x0 < 60.0 && b.x1 > 68.0, "{b:?}");
    let count = |k: u32| paths(&scene(&format!("{table}steps = {k}\n"))).len();
    let (three, six) = (count(3), count(6));
    assert!(0 < three && three < six && six < paths(&whole).len());
}

#[test]
fn a_sketch_stays_on_the_page_and_says_where_its_stroke_leaves_it() {
    // A5 with 10 mm margins: 128 × 190 mm to draw in. The stroke runs
    // off the right edge, as a gesture past the paper's edge does.
    let table = "style = \"outline\"\n[layers.lsystem.sketch]\n\
                 points = [[20, 180], [110, 100], [180, 30]]\nmodule = 8\nwidth = 2\n";
    let drawn = paths(&scene(table));
    let b = bounds(&drawn);
    assert!(drawn.len() > 20);
    assert!(
        b.x0 >= 0.0 && b.y0 >= 0.0 && b.x1 <= 128.0 && b.y1 <= 190.0,
        "{b:?} leaves the page"
    );
    let notes = test_scene::notes("lsystem", table);
    assert_eq!(notes.len(), 1, "{notes:?}");
    assert!(
        notes[0].starts_with("the stroke leaves the page (inside its margins) after"),
        "{notes:?}"
    );
    // On the page, no warning.
    let inside = "[layers.lsystem.sketch]\npoints = [[64, 180], [64, 60]]\n";
    assert!(test_scene::notes("lsystem", inside).is_empty());
}

#[test]
fn a_sketch_drawn_point_by_point_is_the_one_the_render_grows() {
    use super::GrowingSketch;
    use crate::spec::{Format, SceneSpec};
    use glam::DVec2;
    // A wavy stroke of many short pieces, as a pen gives it.
    let stroke: Vec<DVec2> = (0..=240)
        .map(|i| {
            let t = f64::from(i) / 240.0;
            DVec2::new(60.0 + 18.0 * (t * 7.0).sin(), 185.0 - 165.0 * t)
        })
        .collect();
    let points: Vec<String> = stroke
        .iter()
        .map(|p| format!("[{}, {}]", p.x, p.y))
        .collect();
    for steps in ["", "steps = 7\n"] {
        let table = format!(
            "style = \"outline\"\n[layers.lsystem.sketch]\npoints = [{}]\nsmooth = false\nmodule = 9\n{steps}",
            points.join(", ")
        );
        let whole = scene(&table);
        let rendered = paths(&whole);
        let text = test_scene::text("lsystem", &table);
        let spec = SceneSpec::parse(&text, Format::Toml).unwrap();
        let table = &spec.layers[0].lsystem[0];
        // The layer's pen: the default 0.3 mm; the page inside its margins.
        let mut growing = GrowingSketch::new(table, "layers[0].lsystem[0]", usize::MAX)
            .unwrap()
            .with_pen_width(0.3)
            .within(whole.page.drawable().size());
        let mut grown = Vec::new();
        for p in &stroke {
            growing.extend(std::slice::from_ref(p)).unwrap();
            grown.push(growing.steps());
        }
        // It grew while the stroke was drawn, a step at a time.
        assert!(grown.windows(2).all(|w| w[1] <= w[0] + 1), "{grown:?}");
        let (last, half) = (growing.steps(), grown[grown.len() / 2]);
        if steps.is_empty() {
            assert!(half > 0 && half < last, "{half} of {last}");
        } else {
            // Full grown at seven steps, long before the stroke ends.
            assert_eq!((half, last), (7, 7));
        }
        let live = growing.paths();
        assert_eq!(live.len(), rendered.len(), "{steps}");
        let same = live
            .iter()
            .zip(&rendered)
            .all(|(a, b)| a.to_svg() == b.to_svg());
        assert!(same, "the live drawing differs from the render ({steps})");
    }
    let no_sketch = SceneSpec::parse(
        &test_scene::text("lsystem", "axiom = \"F\"\n"),
        Format::Toml,
    )
    .unwrap();
    let e = GrowingSketch::new(&no_sketch.layers[0].lsystem[0], "layers[0].lsystem[0]", 10)
        .unwrap_err();
    assert!(
        e.to_string()
            .starts_with("layers[0].lsystem[0]: has no [sketch]"),
        "{e}"
    );
}

#[test]
fn the_seed_draws_stochastic_rules() {
    let table = "axiom = \"F\"\nrules = [\"F ->(1) F[+F]F\", \"F ->(1) F[-F]F\"]\niterations = 4\n";
    let a = crate::output::path_dump(&scene(table), 3);
    assert_eq!(a, crate::output::path_dump(&scene(table), 3));
    let other = test_scene::text("lsystem", table).replace("seed = 5", "seed = 6");
    let spec = crate::spec::SceneSpec::parse(&other, crate::spec::Format::Toml).unwrap();
    let b = crate::output::path_dump(&crate::project::build_scene(&spec).unwrap(), 3);
    assert_ne!(a, b);
}

#[test]
fn bad_tables_are_refused_with_their_field() {
    for (table, expected) in [
        ("axiom = \"\"\n", "layers[0].lsystem[0].axiom: is empty"),
        (
            "axiom = \"F\"\nrules = [\"F -> F[+F\"]\n",
            "layers[0].lsystem[0].rules[0]",
        ),
        (
            "axiom = \"F\"\nrules = [\"F(x -> F\"]\n",
            "layers[0].lsystem[0].rules[0]: column",
        ),
        (
            "axiom = \"F\"\niterations = 101\n",
            "layers[0].lsystem[0].iterations: must be between 0 and 100",
        ),
        ("axiom = \"F\"\nangle = 400\n", "layers[0].lsystem[0].angle"),
        (
            "axiom = \"F\"\nview = { direction = [0, 1, 0], up = [0, 2, 0] }\n",
            "layers[0].lsystem[0].view: `up` must not lie along `direction`",
        ),
        (
            "axiom = \"F\"\nfit = [10, 10, 5, 50]\n",
            "layers[0].lsystem[0].fit",
        ),
        (
            "axiom = \"F\"\n[layers.lsystem.sketch]\npoints = [[0, 0], [0, 50]]\n",
            "layers[0].lsystem[0].axiom: is not used by a sketch",
        ),
        (
            "[layers.lsystem.sketch]\nmodule = 5\n",
            "layers[0].lsystem[0].sketch: needs a stroke",
        ),
        (
            "[layers.lsystem.sketch]\npoints = [[0, 0], [0, 50]]\nmodule = 0\n",
            "layers[0].lsystem[0].sketch.module",
        ),
        (
            "[layers.lsystem.sketch]\npoints = [[0, 0], [0, 50]]\na = \"a -> b(\"\n",
            "layers[0].lsystem[0].sketch",
        ),
        // Runaway growth stops with a message, before memory runs out.
        (
            "axiom = \"F\"\nrules = [\"F -> FFFFFFFFFF\"]\niterations = 12\n",
            "layers[0].lsystem[0]",
        ),
    ] {
        let e = error(table);
        assert!(e.contains(expected), "{table}\n→ {e}\nwanted {expected}");
    }
}

#[test]
fn flowers_sit_on_the_tips_and_leaves_where_the_turtle_met_their_symbol() {
    // Two branches and a stem: three tips; an L on each branch, half-way.
    let table = "axiom = \"F[+FLF][-FLF]F\"\nangle = 90\nat = [[60, 150]]\nstep = 10\n\
                 flowers = { motifs = [\"sakura\"], width = 4 }\n\
                 leaves = { motifs = [\"leaf\"], symbol = \"L\", width = 3 }\n";
    let s = scene(table);
    let mut ids = Vec::new();
    let mut boxes = std::collections::BTreeMap::new();
    s.layers[0]
        .content
        .visit_paths(Affine::IDENTITY, &mut |p, t| {
            ids.push(p.id.clone());
            boxes.insert(p.id.clone(), (t * p.path.clone()).bounding_box());
        });
    let flowers: Vec<&String> = ids.iter().filter(|i| i.contains(".flower-")).collect();
    let leaves: Vec<&String> = ids.iter().filter(|i| i.contains(".leaf-")).collect();
    assert_eq!(flowers.len(), 3, "{ids:?}");
    assert_eq!(leaves.len(), 2, "{ids:?}");
    // The tips: 20 mm left and right of (60, 140), and (60, 130).
    for tip in [(40.0, 140.0), (80.0, 140.0), (60.0, 130.0)] {
        let tip = Point::from(tip);
        assert!(
            flowers
                .iter()
                .any(|f| boxes[*f].center().distance(tip) < 3.0),
            "no flower at {tip:?}: {boxes:?}"
        );
    }
    // Leaves start where the L was (10 mm out along each branch) and
    // point along it: sideways, not up.
    for leaf in &leaves {
        let b = boxes[*leaf];
        assert!(b.width() > b.height(), "{leaf}: {b:?}");
        assert!((b.center().y - 140.0).abs() < 2.0, "{leaf}: {b:?}");
    }
    assert!(
        error("axiom = \"F\"\nleaves = { motifs = [\"leaf\"], symbol = \"LL\" }\n")
            .contains("layers[0].lsystem[0].leaves.symbol")
    );
}

#[test]
fn drawings_along_a_line_stand_on_its_upper_side() {
    // Three upright strokes on a level line; on a line going up to the
    // right at 45°, leaning to the upper left, perpendicular to it.
    let level = scene("axiom = \"F\"\nalong = [[10, 150], [110, 150]]\ncount = 3\nstep = 10\n");
    let p = paths(&level);
    assert_eq!(p.len(), 3);
    for (path, x) in p
        .iter()
        .zip([100.0 / 6.0 + 10.0, 60.0, 110.0 - 100.0 / 6.0])
    {
        let b = path.bounding_box();
        // Arc length along the line is measured flattened: within 0.01 mm.
        assert!((b.x0 - x).abs() < 0.01 && b.width() < 1e-6, "{b:?} at {x}");
        assert!(
            (b.y1 - 150.0).abs() < 1e-6 && (b.y0 - 140.0).abs() < 1e-6,
            "{b:?}"
        );
    }
    let slope = scene("axiom = \"F\"\nalong = [[10, 150], [110, 50]]\nstep = 10\n");
    let seg = paths(&slope)[0].segments().next().unwrap();
    let (a, b) = (seg.start(), seg.end());
    assert!(a.distance(Point::new(60.0, 100.0)) < 0.01, "{a:?}");
    let d = (b - a) / 10.0;
    let r = std::f64::consts::FRAC_1_SQRT_2;
    assert!((d.x + r).abs() < 1e-6 && (d.y + r).abs() < 1e-6, "{d:?}");
}

#[test]
fn a_sketch_grows_along_a_region_line_of_the_flow() {
    let text = "version = 1\nseed = 5\npage = { size = \"A5\", margin = 10 }\n\
                [lines]\nupper = [[120, 40], [60, 60], [5, 40]]\n\
                [[layers]]\nname = \"l\"\n[[layers.lsystem]]\n\
                [layers.lsystem.sketch]\nline = \"upper\"\nmodule = 10\n";
    let spec = crate::spec::SceneSpec::parse(text, crate::spec::Format::Toml).unwrap();
    let s = crate::project::build_scene(&spec).unwrap();
    let b = bounds(&paths(&s));
    // Along the line, left to right: about 130 mm of it.
    assert!(b.x0 < 10.0 && b.x1 > 110.0, "{b:?}");
    let no_line = text.replace("[lines]\nupper = [[120, 40], [60, 60], [5, 40]]\n", "");
    let spec = crate::spec::SceneSpec::parse(&no_line, crate::spec::Format::Toml).unwrap();
    let e = crate::project::build_scene(&spec).unwrap_err().to_string();
    assert!(
        e.contains("layers[0].lsystem[0].sketch.line: the scene has no upper region line"),
        "{e}"
    );
}

#[test]
fn placements_that_contradict_each_other_are_refused() {
    for (table, expected) in [
        (
            "axiom = \"F\"\nat = [[0, 0]]\nalong = [[0, 0], [50, 0]]\n",
            "layers[0].lsystem[0].along: and `at` both place the drawing",
        ),
        (
            "axiom = \"F\"\ncount = 3\n",
            "layers[0].lsystem[0].count: spreads drawings along a line",
        ),
        (
            "axiom = \"F\"\nalong = [[0, 0], [50, 0]]\ncount = 0\n",
            "layers[0].lsystem[0].count: must be between 1 and 1000",
        ),
        (
            "axiom = \"F\"\nalong = [[0, 0], [50, 0]]\nfit = [0, 0, 10, 10]\n",
            "layers[0].lsystem[0].fit",
        ),
        (
            "[layers.lsystem.sketch]\npoints = [[0, 0], [0, 50]]\nline = \"lower\"\n",
            "layers[0].lsystem[0].sketch: has more than one of",
        ),
    ] {
        let e = error(table);
        assert!(e.contains(expected), "{table}\n→ {e}\nwanted {expected}");
    }
}

#[test]
fn a_plant_in_front_hides_what_lies_behind_it() {
    // A level line behind a trunk 10 mm wide (width 0.2 at 50 mm a unit):
    // with hidden lines removed, 10 mm of it are gone.
    let text = "version = 1\nseed = 5\npage = { size = \"A5\", margin = 10 }\n\
                [plot.occlude]\n\
                [[layers]]\nname = \"front\"\n[[layers.lsystem]]\naxiom = \"F\"\n\
                at = [[60, 150]]\nstep = 50\nstyle = \"outline\"\nwidth = 0.2\n\
                [[layers]]\nname = \"back\"\n[[layers.paths]]\npoints = [[0, 120], [120, 120]]\n";
    let spec = crate::spec::SceneSpec::parse(text, crate::spec::Format::Toml).unwrap();
    // The description's layers kept, to find the back one.
    let scene = crate::motif::test_scene::editing(&spec);
    let mut behind = Vec::new();
    let back = scene
        .layers
        .iter()
        .find(|l| l.name == "back")
        .expect("the back layer");
    back.content.visit_paths(Affine::IDENTITY, &mut |p, t| {
        behind.push(t * p.path.clone())
    });
    let seen = length(&behind);
    assert!((seen - 110.0).abs() < 0.01, "{seen} mm of the line seen");
    // Without the plant, all 120 mm.
    let alone = text.replace("axiom = \"F\"", "axiom = \"f\"");
    let spec = crate::spec::SceneSpec::parse(&alone, crate::spec::Format::Toml).unwrap();
    let rendered = crate::project::render(&spec).unwrap();
    assert!((rendered.scene.stats().pen_down_mm - 120.0).abs() < 0.01);
}

/// ABOP fig. 1.24a at `n` fitted on A4 inside 10 mm margins (190 ×
/// 277 mm), seen from the front as a render sees it: the limbs a render
/// draws (each as its points, on the page), the turtle's work, the
/// word's length and the limbs the skeleton holds, with or without
/// `prune`.
fn fitted_124a(n: usize, prune: bool) -> (Vec<Vec<Point>>, super::engine::Work, usize, usize) {
    use super::draw::{flat, Projection};
    use super::engine::{LSystem, Prune, PruneScale, Turtle, TurtleOptions};
    use crate::family::lsystem::description::View;

    let system = LSystem::parse(
        "F",
        &["F -> F[+F]F[-F]F"],
        &std::collections::BTreeMap::new(),
        "",
        "t",
    )
    .unwrap();
    let word = system
        .derive(n, &mut crate::rng::Seed(1).stream(), super::MAX_MODULES)
        .unwrap();
    let view = Projection::of(View::default().axes());
    let (right, up) = view.axes();
    let frame = Rect::new(0.0, 0.0, 190.0, 277.0);
    let mut options = TurtleOptions::DEFAULT.with_max_segments(super::MAX_SEGMENTS);
    if prune {
        options = options.with_prune(Prune {
            right,
            up,
            min_length: super::MIN_LIMB,
            scale: PruneScale::Fit(frame.width(), frame.height()),
        });
    }
    let (skeleton, work) = Turtle::new(options).interpret_counted(&word).unwrap();
    let flat = flat(&skeleton, &view);
    let place = crate::motif::fitted(flat.bounds(false), frame);
    let scale = place.determinant().abs().sqrt();
    let drawn = flat
        .limbs
        .iter()
        .filter(|l| l.length() * scale >= super::MIN_LIMB)
        .map(|l| l.points.iter().map(|&p| place * p).collect())
        .collect();
    (drawn, work, word.len(), skeleton.limbs.len())
}

#[test]
fn branches_no_pen_can_draw_are_left_out_as_the_turtle_meets_them() {
    // Fitted on A4, a step of 1.24a is 277 mm / 3ⁿ: 0.13 mm at n = 7,
    // so every limb is drawn; at n = 8, 0.042 mm, so the one-step
    // limbs (under `MIN_LIMB`, 0.05 mm) are not.
    let (all, unpruned, _, _) = fitted_124a(8, false);
    let (drawn, pruned, _, _) = fitted_124a(8, true);
    // The same limbs on the page (a pruned branch can lie outside what is
    // drawn by less than `MIN_LIMB`, so the fit may move them by a hair).
    assert_eq!(drawn.len(), all.len());
    for (a, b) in drawn.iter().zip(&all) {
        assert_eq!(a.len(), b.len());
        assert!(a.iter().zip(b).all(|(p, q)| p.distance(*q) < 0.05));
    }
    // Only the one-step branches `[+F]` and `[-F]` are that small at
    // n = 8: 819,202 modules interpreted against 976,561.
    assert!(
        pruned.interpreted + 100_000 < unpruned.interpreted,
        "{pruned:?} against {unpruned:?}"
    );

    // n = 10 draws what n = 7 does (the limbs of 27 steps and more; a
    // limb of 3 is 0.014 mm), and holds hardly more: the turtle skips the
    // branches no pen draws, reading each once (and the word once more
    // for the main axis, which sets the scale it prunes by), and
    // interprets what it draws — 27 steps where n = 7 has one, 4.4
    // million of the 24.4 million modules.
    let (seven, at_seven, _, held_seven) = fitted_124a(7, true);
    let (ten, at_ten, modules, held_ten) = fitted_124a(10, true);
    assert_eq!(ten.len(), seven.len());
    assert!(held_ten <= 2 * held_seven, "{held_ten} limbs held, {held_seven} at n = 7");
    assert!(
        at_ten.interpreted < modules / 5,
        "{at_ten:?} in {modules} modules (n = 7: {at_seven:?})"
    );
    assert!(at_ten.read_ahead < 2 * modules + modules / 10, "{at_ten:?} in {modules} modules");
}
