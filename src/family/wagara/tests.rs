//! The grounds: inside their region, every line once, no seam (the repeat
//! laid over a shifted window is the same repeat shifted), and each
//! parameter doing what its doc says.

use kurbo::{
    Affine, BezPath, ParamCurve, ParamCurveArclen, ParamCurveNearest, PathSeg, Point, Rect, Shape,
    Vec2,
};

use crate::motif::ground::{draw, estimate};
use crate::motif::test_scene;
use crate::plot::dedupe::doubled_length;
use crate::spec::Ground;

/// The page paths of a wagara table (A5, 10 mm margins).
fn drawn(table: &str) -> Vec<BezPath> {
    let scene = test_scene::scene("wagara", table);
    let mut paths = Vec::new();
    scene.layers[0]
        .content
        .visit_paths(Affine::IDENTITY, &mut |p, t| paths.push(t * p.path.clone()));
    paths
}

/// Everything `ground` draws over `window` (strokes and dark shapes), in
/// the repeat's frame, for a 0.3 mm pen.
fn strokes(ground: Ground, scale: f64, lines: u32, window: Rect) -> Vec<BezPath> {
    let drawn = draw(ground, scale, lines, 0.3, window);
    drawn.strokes.into_iter().chain(drawn.dark).collect()
}

/// Points along `paths`, about every 0.2 mm.
fn samples(paths: &[BezPath]) -> Vec<Point> {
    paths
        .iter()
        .flat_map(|p| p.segments().collect::<Vec<_>>())
        .flat_map(|seg| {
            let n = (seg.arclen(1e-3) / 0.2).ceil().max(1.0) as usize;
            (0..=n).map(move |k| seg.eval(k as f64 / n as f64))
        })
        .collect()
}

fn distance_to(paths: &[BezPath], p: Point) -> f64 {
    paths
        .iter()
        .flat_map(|path| path.segments().collect::<Vec<_>>())
        .map(|seg| seg.nearest(p, 1e-6).distance_sq.sqrt())
        .fold(f64::INFINITY, f64::min)
}

/// The repeat's periods: shifting the plane by one maps the ground onto
/// itself.
fn period(ground: Ground, s: f64) -> Vec2 {
    match ground {
        Ground::Kagome => Vec2::new(2.0 * s / 3f64.sqrt(), 0.0),
        Ground::Asanoha => Vec2::new(0.5 * s, s * 3f64.sqrt() / 2.0),
        Ground::Kikko => Vec2::new(s * 3f64.sqrt() / 2.0, 1.5 * s),
        Ground::Shippo => Vec2::new(s * 2f64.sqrt(), 0.0),
        Ground::Seigaiha | Ground::SameKomon => Vec2::new(s, 0.5 * s),
        Ground::Uroko => Vec2::new(0.5 * s, s * 3f64.sqrt() / 2.0),
        Ground::Yagasuri => Vec2::new(s, 0.75 * s),
        Ground::Tatewaku => Vec2::new(2.0 * s, 0.0),
    }
}

fn table(ground: Ground, extra: &str) -> String {
    format!("pattern = \"{}\"\nscale = 8\n{extra}", ground.name())
}

#[test]
fn every_ground_stays_inside_its_region() {
    for ground in Ground::ALL {
        let paths = drawn(&table(
            ground,
            "region = { circle = { centre = [60, 80], radius = 40 } }",
        ));
        // Tatewaku's waves run the whole height: a dozen fill the circle.
        assert!(paths.len() > 8, "{ground:?}: {} strokes", paths.len());
        for p in samples(&paths) {
            let r = p.distance(Point::new(60.0, 80.0));
            assert!(r <= 40.0 + 0.02, "{ground:?}: {p:?} at {r} from the centre");
        }
        // And it fills the circle: a point near the rim and the centre
        // each have a line within a repeat.
        for p in [Point::new(60.0, 80.0), Point::new(97.0, 80.0)] {
            assert!(distance_to(&paths, p) < 8.0, "{ground:?} near {p:?}");
        }
    }
}

#[test]
fn no_line_is_drawn_twice() {
    for ground in Ground::ALL {
        let paths = drawn(&table(ground, ""));
        // Runs of a millimetre within 0.01 mm: shippō's diagonal circles
        // touch where four meet (a point of the pattern, the arcs within
        // 0.01 mm of each other for half a millimetre), a line drawn
        // twice runs on.
        let doubled = doubled_length(&paths, 0.01, 1.0);
        assert!(doubled < 1e-6, "{ground:?}: {doubled} mm drawn twice");
    }
}

#[test]
fn the_repeat_laid_over_a_shifted_window_is_the_same_repeat_shifted() {
    // Seamless: what a window of the ground holds does not depend on
    // where the window is, so a ground has no tile edge to show.
    for ground in Ground::ALL {
        let s = 6.0;
        let shift = period(ground, s) * 3.0;
        let window = Rect::new(-20.0, -15.0, 25.0, 30.0);
        let here = strokes(ground, s, 3.min(ground.lines().map_or(1, |l| l.1)), window);
        let there = strokes(
            ground,
            s,
            3.min(ground.lines().map_or(1, |l| l.1)),
            window + shift,
        );
        let inner = (window + shift).inset(-2.0 * s);
        let moved: Vec<BezPath> = here
            .iter()
            .map(|p| Affine::translate(shift) * p.clone())
            .collect();
        let mut checked = 0;
        for p in samples(&moved).into_iter().filter(|p| inner.contains(*p)) {
            let d = distance_to(&there, p);
            assert!(d < 1e-6, "{ground:?}: {p:?} is {d} mm off the shifted repeat");
            checked += 1;
        }
        assert!(checked > 500, "{ground:?}: {checked} points checked");
        // A shift that is not a period moves it off itself.
        let off = Affine::translate(period(ground, s) * 0.37);
        let wrong = samples(&[off * here[here.len() / 2].clone()]);
        assert!(
            wrong
                .iter()
                .filter(|p| inner.contains(**p))
                .any(|p| distance_to(&there, *p) > 0.1)
                || wrong.iter().all(|p| !inner.contains(*p)),
            "{ground:?}: a third of a period is a period too?"
        );
    }
}

#[test]
fn curved_grounds_have_no_straight_line_and_straight_ones_no_long_seam() {
    for ground in [Ground::Seigaiha, Ground::Shippo, Ground::Tatewaku] {
        let paths = drawn(&table(ground, ""));
        let lines = paths
            .iter()
            .flat_map(|p| p.segments().collect::<Vec<_>>())
            .filter(|s| matches!(s, PathSeg::Line(_)))
            .count();
        assert_eq!(lines, 0, "{ground:?} has straight lines");
    }
    // Kikkō's lines are the hexagons' sides: none longer than a side.
    let longest = drawn(&table(Ground::Kikko, ""))
        .iter()
        .flat_map(|p| p.segments().collect::<Vec<_>>())
        .map(|s| s.arclen(1e-6))
        .fold(0.0, f64::max);
    assert!(longest <= 8.0 + 1e-6, "a kikko line of {longest} mm");
}

#[test]
fn more_lines_draw_more_rings_and_inner_outlines() {
    let length = |extra: &str, ground| -> f64 {
        drawn(&table(ground, extra))
            .iter()
            .map(|p| p.perimeter(1e-3))
            .sum()
    };
    for ground in [Ground::Seigaiha, Ground::Kikko] {
        let one = length("lines = 1", ground);
        let three = length("lines = 3", ground);
        assert!(three > 1.5 * one, "{ground:?}: {one} mm, then {three} mm");
    }
    // Same-komon's rings split the fan into finer bands of finer dots.
    let dots = |extra: &str| drawn(&table(Ground::SameKomon, extra)).len();
    let (one, three) = (dots("lines = 1"), dots("lines = 3"));
    assert!(three > 4 * one, "{one} dots, then {three}");
    // Seigaiha's rings split the fan's radius evenly: with two at scale
    // 10, every arc lies on a circle of radius 10 or 5.
    let arcs = strokes(Ground::Seigaiha, 10.0, 2, Rect::new(0.0, 0.0, 40.0, 40.0));
    let radii: std::collections::BTreeSet<i64> = arcs
        .iter()
        .filter(|arc| arc.perimeter(1e-3) > 1.0)
        .map(|arc| {
            let segs: Vec<PathSeg> = arc.segments().collect();
            let (a, b, c) = (
                segs[0].start(),
                segs[segs.len() / 2].eval(0.5),
                segs[segs.len() - 1].end(),
            );
            // The radius of the circle through three of its points.
            let area2 = (b - a).cross(c - a).abs();
            let r = (b - a).hypot() * (c - b).hypot() * (a - c).hypot() / (2.0 * area2);
            (r * 10.0).round() as i64
        })
        .collect();
    assert_eq!(radii, [50, 100].into());
}

#[test]
fn a_smaller_scale_draws_a_finer_ground() {
    for ground in Ground::ALL {
        let coarse = drawn(&table(ground, "")).len() as f64;
        let fine = drawn(&format!("pattern = \"{}\"\nscale = 4", ground.name())).len() as f64;
        assert!(fine > 1.8 * coarse, "{ground:?}: {coarse} then {fine} strokes");
    }
}

#[test]
fn the_angle_turns_the_repeat() {
    // Kagome's lines run at 0°, 60° and 120°; turned by 15°, at 15°, 75°
    // and 135° (clockwise on the page, y down).
    let directions = |extra: &str| -> std::collections::BTreeSet<i64> {
        drawn(&table(Ground::Kagome, extra))
            .iter()
            .flat_map(|p| p.segments().collect::<Vec<_>>())
            .filter(|s| s.arclen(1e-6) > 5.0)
            .map(|s| {
                let d = s.end() - s.start();
                (d.y.atan2(d.x).to_degrees().rem_euclid(180.0).round() as i64) % 180
            })
            .collect()
    };
    assert_eq!(directions(""), [0, 60, 120].into());
    assert_eq!(directions("angle = 15"), [15, 75, 135].into());
}

#[test]
fn the_offset_shifts_the_repeat() {
    let at = |extra: &str| drawn(&table(Ground::Shippo, extra));
    let plain = at("");
    let shifted = at("offset = [3, 0]");
    assert_ne!(plain, shifted);
    // Shifted by a whole period it is the same ground again.
    let period = 8.0 * 2f64.sqrt();
    let whole = at(&format!("offset = [{period}, 0]"));
    let inner = Rect::new(30.0, 30.0, 100.0, 160.0);
    for p in samples(&whole).into_iter().filter(|p| inner.contains(*p)) {
        assert!(distance_to(&plain, p) < 1e-6, "{p:?}");
    }
}

#[test]
fn bad_tables_name_their_field() {
    let e = test_scene::error("wagara", "pattern = \"kagome\"\nlines = 2");
    assert!(e.contains("layers[0].wagara[0].lines") && e.contains("kagome takes no"), "{e}");
    let e = test_scene::error("wagara", "pattern = \"seigaiha\"\nlines = 9");
    assert!(e.contains("layers[0].wagara[0].lines"), "{e}");
    let e = test_scene::error("wagara", "pattern = \"kikko\"\nscale = 0.5");
    assert!(e.contains("layers[0].wagara[0].scale"), "{e}");
    let e = test_scene::error("wagara", "pattern = \"kagome\"\nhatch = 1");
    assert!(e.contains("layers[0].wagara[0].hatch") && e.contains("kagome takes no"), "{e}");
    let e = test_scene::error("wagara", "pattern = \"uroko\"\nhatch = 0");
    assert!(e.contains("layers[0].wagara[0].hatch"), "{e}");
    let e = test_scene::error("wagara", "pattern = \"ichimatsu\"");
    assert!(e.contains("pattern"), "{e}");
}

#[test]
fn a_ground_too_fine_for_the_budget_fails_before_the_work() {
    let text = "version = 1\npage = { size = [1000, 1000] }\nlimits = { max_paths = 1000 }\n\
                [[layers]]\nname = \"l\"\n[[layers.wagara]]\npattern = \"seigaiha\"\nscale = 1";
    let spec = crate::spec::SceneSpec::parse(text, crate::spec::Format::Toml).unwrap();
    let e = crate::project::build_scene(&spec).unwrap_err().to_string();
    assert!(e.contains("wagara") && e.contains("1000"), "{e}");
    // The estimate is never below what is drawn.
    for ground in Ground::ALL {
        let window = Rect::new(-33.0, -21.0, 47.0, 64.0);
        let lines = ground.lines().map_or(1, |l| l.2);
        let made = strokes(ground, 5.0, lines, window).len() as f64;
        let guessed = estimate(ground, 5.0, lines, window);
        assert!(guessed >= made, "{ground:?}: {guessed} < {made}");
        assert!(guessed < 4.0 * made + 100.0, "{ground:?}: {guessed} for {made}");
    }
}

#[test]
fn uroko_is_dark_triangles_hatched_as_finely_as_asked() {
    // Before the plot stages: closed triangles filled black, nothing else.
    let scene = test_scene::scene("wagara", &table(Ground::Uroko, ""));
    let mut styles = Vec::new();
    scene.layers[0]
        .content
        .visit_paths(Affine::IDENTITY, &mut |p, _| styles.push(p.style.clone()));
    assert!(styles.len() > 50);
    assert!(styles.iter().all(|s| s.fill.is_some() && s.hatch == Some(0.5)));
    // Through the hatch stage: half the spacing, about twice the hatch.
    let ink = |hatch: &str| -> f64 {
        let text = test_scene::text("wagara", &table(Ground::Uroko, hatch));
        let spec = crate::spec::SceneSpec::parse(&text, crate::spec::Format::Toml).unwrap();
        let mut length = 0.0;
        test_scene::editing(&spec).layers[0]
            .content
            .visit_paths(Affine::IDENTITY, &mut |p, t| {
                length += (t * p.path.clone()).perimeter(1e-3);
            });
        length
    };
    let (fine, coarse) = (ink("hatch = 0.5"), ink("hatch = 1"));
    assert!(fine > 1.3 * coarse, "{fine} mm at 0.5, {coarse} mm at 1");
}

#[test]
fn same_komon_draws_dots_not_rings() {
    // Every stroke is a dot: a tap or a filled spiral no wider than the
    // band between rings.
    let paths = drawn(&table(Ground::SameKomon, "lines = 4"));
    assert!(paths.len() > 500, "{} dots", paths.len());
    for p in &paths {
        let b = p.bounding_box();
        assert!(b.width() <= 8.0 / 4.0 && b.height() <= 8.0 / 4.0, "{b:?}");
    }
}

#[test]
fn tatewaku_swells_and_narrows_between_mirrored_waves() {
    // Two neighbouring waves: a quarter of the spacing to either side, so
    // the paper between them runs from half the spacing to one and a half.
    let waves = strokes(Ground::Tatewaku, 10.0, 1, Rect::new(0.0, 0.0, 20.0, 40.0));
    let x_at = |k: usize, y: f64| -> f64 {
        samples(&waves[k..=k])
            .into_iter()
            .min_by(|a, b| (a.y - y).abs().total_cmp(&(b.y - y).abs()))
            .unwrap()
            .x
    };
    let (mut narrow, mut wide) = (f64::INFINITY, 0.0f64);
    for y in (0..40).map(f64::from) {
        let gap = x_at(2, y) - x_at(1, y);
        narrow = narrow.min(gap);
        wide = wide.max(gap);
    }
    assert!((narrow - 5.0).abs() < 0.1 && (wide - 15.0).abs() < 0.1, "{narrow} to {wide}");
}
