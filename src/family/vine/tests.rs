use std::collections::BTreeMap;

use glam::DVec3;
use kurbo::{Affine, BezPath, ParamCurveArclen, Rect, Shape as _};

use super::sight::{camera_for, Sight};
use crate::family::vine::camera::Camera;
use crate::family::vine::engine;
use crate::family::vine::engine::{Plant, Supports, TriMesh};
use crate::motif::{test_scene, Library};
use crate::rng::Seed;
use crate::scene::Scene;
use crate::spec::{CameraPreset, CameraSpec, Format, Orbit, Part, SceneSpec, VineSpec};

fn scene(table: &str) -> Scene {
    test_scene::scene("vine", table)
}

fn error(table: &str) -> String {
    test_scene::error("vine", table)
}

/// A vine table on its own, with what it grows.
fn grown(table: &str) -> (VineSpec, Plant, Supports) {
    let spec: VineSpec = toml::from_str(table).unwrap();
    let supports = Supports::new(spec.shapes("vine", &|_| unreachable!()).unwrap());
    let plant = engine::grow(
        &spec.params(spec.roots[0]),
        &supports,
        &mut Seed(5).stream(),
    )
    .unwrap();
    (spec, plant, supports)
}

fn sight(spec: &VineSpec, plant: &Plant, supports: &Supports) -> Sight {
    let library = Library::new();
    let mut rng = Seed(1).stream();
    let leaves: Vec<_> = plant
        .leaves
        .iter()
        .map(|_| library.draw(&spec.leaf, &mut rng).unwrap())
        .collect();
    let camera = camera_for(&spec.camera, plant, supports);
    Sight::new(camera, spec.radius, plant, supports.shapes(), None, &leaves)
}

fn length3(run: &[DVec3]) -> f64 {
    run.windows(2).map(|w| w[0].distance(w[1])).sum()
}

/// The paths a pen draws of the scene on the page, by id.
fn paths(scene: &Scene) -> Vec<(String, BezPath)> {
    let mut out = Vec::new();
    for layer in &scene.layers {
        layer.content.visit_paths(Affine::IDENTITY, &mut |p, t| {
            if p.style.is_drawn() {
                out.push((p.id.clone(), t * p.path.clone()));
            }
        });
    }
    out
}

fn pen_length(paths: &[(String, BezPath)]) -> f64 {
    paths
        .iter()
        .flat_map(|(_, p)| p.segments())
        .map(|s| s.arclen(1e-6))
        .sum()
}

#[test]
fn behind_its_pole_the_stem_is_hidden_and_in_front_it_hides_the_pole() {
    // The default pole: radius 6 at x = 20, z = 0, 400 tall, seen from the
    // front (orthographic along −z, one picture unit a millimetre).
    let (spec, plant, supports) = grown("leaves = 0\ncotyledons = 0\n");
    assert!(plant.stems[0].twined.iter().any(|t| *t), "the stem wraps");
    let sight = sight(&spec, &plant, &supports);
    let (mut seen, mut all, mut in_front) = (0.0, 0.0, 0);
    for line in sight.lines().iter().filter(|l| l.part == Part::Stem) {
        all += length3(&line.points);
        for run in sight.visible(line, 0.2, 1e-5) {
            seen += length3(&run);
            for p in run {
                let dx = p.x - 20.0;
                if dx.abs() < 6.0 - 0.05 && p.y > 0.05 && p.y < 400.0 - 0.05 {
                    // Seen over the pole: it must lie in front of it, up
                    // to the hiding cylinder's inset and facets (0.07 mm),
                    // where the stem touches the pole.
                    let front = (36.0 - dx * dx).sqrt();
                    assert!(p.z > front - 0.1, "{p} is behind the pole yet drawn");
                    in_front += 1;
                }
            }
        }
    }
    assert!(in_front > 0, "the stem passes in front of the pole");
    assert!(
        seen < 0.9 * all,
        "the stem is hidden behind the pole: {seen} of {all}"
    );
    // And where it passes in front, the pole's contours are cut.
    let (mut seen, mut all) = (0.0, 0.0);
    for line in sight
        .lines()
        .iter()
        .filter(|l| l.part == Part::Supports && !l.closed)
    {
        all += length3(&line.points);
        seen += sight
            .visible(line, 0.2, 1e-5)
            .iter()
            .map(|r| length3(r))
            .sum::<f64>();
    }
    assert!(
        seen < all - 10.0,
        "the stem hides the pole: {seen} of {all}"
    );
}

#[test]
fn a_leaf_hides_what_lies_behind_it() {
    // A big leaf on a short vine: somewhere a stem or pole line runs
    // behind a blade, so hiding only by the stem and pole shows more.
    let table = "leaf_size = 30\ninternodes = 4\n";
    let (spec, plant, supports) = grown(table);
    let bare = VineSpec {
        leaves: 0,
        cotyledons: 0,
        ..spec.clone()
    };
    let with = sight(&spec, &plant, &supports);
    let mut plant_bare = plant.clone();
    plant_bare.leaves.clear();
    let without = sight(&bare, &plant_bare, &supports);
    let seen = |s: &Sight| -> f64 {
        s.lines()
            .iter()
            .filter(|l| l.part != Part::Leaves)
            .flat_map(|l| s.visible(l, 0.2, 1e-5))
            .map(|r| length3(&r))
            .sum()
    };
    assert!(seen(&with) < seen(&without) - 1.0);
}

#[test]
fn the_same_vine_in_two_layers_lines_up() {
    let whole = scene("id = \"ivy\"\n");
    let text = "version = 1\nseed = 5\npage = { size = \"A5\", margin = 10 }\n\
        [[layers]]\nname = \"l\"\n[[layers.vine]]\nid = \"ivy\"\ndraw = [\"stem\"]\n\
        [[layers]]\nname = \"m\"\n[[layers.vine]]\nid = \"ivy\"\ndraw = [\"leaves\", \"supports\"]\n";
    let split =
        crate::project::build_scene(&SceneSpec::parse(text, Format::Toml).unwrap()).unwrap();
    let stems = |s: &Scene| -> Vec<BezPath> {
        paths(s)
            .into_iter()
            .filter(|(id, _)| id.contains(".stem-"))
            .map(|(_, p)| p)
            .collect()
    };
    assert!(!stems(&whole).is_empty());
    assert_eq!(stems(&whole), stems(&split));
    let whole_len = pen_length(&paths(&whole));
    let split_len = pen_length(&paths(&split));
    assert!((whole_len - split_len).abs() < 1e-6 * whole_len);
}

#[test]
fn a_vine_hides_what_lies_behind_it_in_a_composition() {
    // Horizontal lines every 2 mm across the page, on a layer behind a
    // vine drawn whole (which gives its mask) and behind one drawing its
    // stem alone (which gives none).
    let text = |draw: &str| {
        let lines: Vec<String> = (0..95)
            .map(|k| format!("M 0 {y} L 128 {y}", y = 2 * k + 1))
            .collect();
        format!(
            "version = 1\nseed = 5\npage = {{ size = \"A5\", margin = 10 }}\n\
             [plot.occlude]\n\
             [[layers]]\nname = \"vine\"\n[[layers.vine]]\nid = \"ivy\"\n{draw}\
             [[layers]]\nname = \"back\"\n[[layers.paths]]\nd = \"{}\"\n",
            lines.join(" ")
        )
    };
    // What the pens draw of the lines behind, and the area of the mask.
    let drawn = |draw: &str| -> (f64, f64) {
        let spec = SceneSpec::parse(&text(draw), Format::Toml).unwrap();
        // Without the pen stage, which joins strokes of one pen whatever
        // table drew them.
        let scene = crate::motif::test_scene::editing(&spec);
        let behind: Vec<(String, BezPath)> = paths(&scene)
            .into_iter()
            .filter(|(id, _)| id.starts_with("back"))
            .collect();
        // The mask as the vine gives it, before hidden-line removal.
        let scene = crate::project::build_scene(&spec).unwrap();
        let mut area = 0.0;
        for layer in &scene.layers {
            layer.content.visit_paths(Affine::IDENTITY, &mut |p, t| {
                if p.id.ends_with(".mask") {
                    area += (t * p.path.clone()).area().abs();
                }
            });
        }
        (pen_length(&behind), area)
    };
    let full = 95.0 * 128.0;
    let (whole, area) = drawn("");
    // Lines 2 mm apart lose about half the mask's area in length (less
    // where a thin leaf slips between two lines).
    assert!(area > 300.0, "{area}");
    let hidden = full - whole;
    assert!(
        (hidden - area / 2.0).abs() < 0.2 * area / 2.0,
        "{hidden} mm hidden, mask {area} mm²"
    );
    let (stem_only, none) = drawn("draw = [\"stem\"]\n");
    assert_eq!(none, 0.0);
    assert!(
        (stem_only - full).abs() < 1e-6 * full,
        "{stem_only} of {full}"
    );
}

#[test]
fn a_vine_along_a_guide_winds_over_and_under_its_rod_and_ends_with_it() {
    // A straight guide across the page at y = 100, from x = 10 to 118.
    let s = scene(
        "internode = 14\nradius = 0.6\nleaf_size = 4\nangle = 30\ninternodes = 30\n\
         guide = { points = [[10, 100], [118, 100]], smooth = false, radius = 1 }\n",
    );
    let all = paths(&s);
    let of = |part: &str| -> Vec<&BezPath> {
        all.iter()
            .filter(|(id, _)| id.contains(part))
            .map(|(_, p)| p)
            .collect()
    };
    let points = |paths: &[&BezPath]| -> Vec<kurbo::Point> {
        paths
            .iter()
            .flat_map(|p| p.elements().iter().filter_map(|e| e.end_point()))
            .collect()
    };
    let runs = |paths: &[&BezPath]| -> usize {
        paths
            .iter()
            .flat_map(|p| p.elements())
            .filter(|e| matches!(e, kurbo::PathEl::MoveTo(_)))
            .count()
    };
    let (stems, rod) = (of(".stem-"), of(".support-"));
    assert!(!stems.is_empty() && rod.len() == 1);
    // The rod lies on the guide, as long as it.
    for p in points(&rod) {
        assert!(
            (p.y - 100.0).abs() < 1.0 + 1e-6 && (10.0 - 1e-6..=118.0 + 1e-6).contains(&p.x),
            "{p:?}"
        );
    }
    // The stem hugs it, sprouting at its start and cut at its end (the
    // rounded tip is r long); the free base may wander a little.
    for p in points(&stems) {
        assert!((p.y - 100.0).abs() < 10.0, "{p:?}");
        assert!((5.0..=118.0 + 0.6 + 1e-6).contains(&p.x), "{p:?}");
    }
    let on_rod = points(&stems)
        .iter()
        .filter(|p| (p.y - 100.0).abs() < 1.0 + 2.0 * 0.6 + 0.01)
        .count();
    assert!(on_rod * 2 > points(&stems).len(), "{on_rod}");
    // Over and under: the stem hides the rod where it passes in front, the
    // rod hides the stem where it passes behind, many times along it.
    assert!(runs(&rod) > 2 * 5, "rod in {} pieces", runs(&rod));
    assert!(runs(&stems) > 2 * 5, "stems in {} pieces", runs(&stems));
}

#[test]
fn a_vine_is_the_same_for_the_same_seed() {
    let a = scene("");
    assert_eq!(paths(&a), paths(&scene("")));
    let text = test_scene::text("vine", "");
    let other = text.replace("seed = 5", "seed = 6");
    let b = crate::project::build_scene(&SceneSpec::parse(&other, Format::Toml).unwrap()).unwrap();
    assert_ne!(paths(&a), paths(&b));
}

#[test]
fn the_drawing_fits_its_box() {
    let s = scene("fit = [10, 20, 90, 120]\n");
    let b = paths(&s)
        .iter()
        .map(|(_, p)| p.bounding_box())
        .reduce(|a, b| a.union(b))
        .unwrap();
    assert!(b.x0 >= 10.0 - 1e-6 && b.x1 <= 90.0 + 1e-6, "{b:?}");
    assert!(b.y0 >= 20.0 - 1e-6 && b.y1 <= 120.0 + 1e-6, "{b:?}");
    assert!(b.height() > 99.0, "tall drawings fill the height: {b:?}");
}

#[test]
fn the_model_holds_stems_leaves_and_closed_supports() {
    let text = test_scene::text("vine", "");
    let spec = SceneSpec::parse(&text, Format::Toml).unwrap();
    let rendered = crate::project::render(&spec).unwrap();
    assert_eq!(rendered.models.len(), 1);
    let model = &rendered.models[0];
    let (_, plant, _) = grown("");
    let named = |prefix: &str| {
        model
            .parts
            .iter()
            .filter(|p| p.name.starts_with(prefix))
            .count()
    };
    // The scene's own stream grows its plant: as many parts as it has.
    assert!(named("stem-") >= plant.stems.len().min(1));
    assert!(named("leaf-") > 0);
    assert_eq!(named("support-"), 1);
    let stem = &model.parts[0];
    assert_eq!(stem.lines.len(), 1, "the axis as a polyline");
    let support = model.parts.iter().find(|p| p.name == "support-0").unwrap();
    let mesh = TriMesh {
        vertices: support
            .vertices
            .iter()
            .map(|v| DVec3::from_array(*v))
            .collect(),
        triangles: support.faces.iter().map(|f| [f[0], f[1], f[2]]).collect(),
    };
    mesh.check_closed("support").unwrap();
    // Leaves are the thesis' quads: a square of half-diagonal γ = 12.
    let leaf = model.parts.iter().find(|p| p.name == "leaf-0").unwrap();
    let v: Vec<DVec3> = leaf
        .vertices
        .iter()
        .map(|v| DVec3::from_array(*v))
        .collect();
    assert!((v[0].distance(v[2]) - 24.0).abs() < 1e-9);
    assert!((v[1].distance(v[3]) - 24.0).abs() < 1e-9);
    // Only the parts a table draws are exported.
    let text = test_scene::text("vine", "draw = [\"supports\"]\n");
    let spec = SceneSpec::parse(&text, Format::Toml).unwrap();
    let rendered = crate::project::render(&spec).unwrap();
    assert_eq!(rendered.models[0].parts.len(), 1);
}

#[test]
fn bad_tables_are_refused_with_the_field() {
    for (table, field) in [
        ("internode = 0\n", "vine[0].internode"),
        ("angle = 90\n", "vine[0].angle"),
        ("leaves = 3\n", "vine[0].leaves"),
        ("draw = []\n", "vine[0].draw"),
        (
            "supports = [{ kind = \"pole\", from = [0, 0, 0], to = [0, 0, 0], radius = 5 }]\n",
            "vine[0].supports[0].to",
        ),
        (
            "supports = [{ kind = \"pole\", from = [0, 0, 0], to = [0, 9, 0], radius = 0 }]\n",
            "vine[0].supports[0].radius",
        ),
        (
            "supports = [{ kind = \"box\", min = [0, 0, 0], max = [5, 0, 5] }]\n",
            "vine[0].supports[0].max",
        ),
        (
            "camera = { eye = [0, 100, 0], target = [0, 0, 0] }\n",
            "vine[0].camera.up",
        ),
        (
            "camera = { eye = [0, 0, 100], target = [0, 0, 0], perspective = 180 }\n",
            "vine[0].camera.perspective",
        ),
        ("camera = { turn = 30, tilt = 95 }\n", "vine[0].camera.tilt"),
        ("camera = { turn = -361 }\n", "vine[0].camera.turn"),
        (
            "camera = { turn = 30, perspective = 0.5 }\n",
            "vine[0].camera.perspective",
        ),
        ("fit = [10, 10, 5, 50]\n", "vine[0].fit"),
        ("roots = []\n", "vine[0].roots"),
        // A seed inside the default pole.
        ("roots = [[0, 0, 0], [20, 0, 0]]\n", "vine[0].roots[1]"),
    ] {
        let e = error(table);
        assert!(e.contains(field), "{table}: {e}");
    }
}

/// The SVG a vine table draws, without the description it embeds (which
/// names the camera).
fn drawn_svg(table: &str) -> String {
    let spec = SceneSpec::parse(&test_scene::text("vine", table), Format::Toml).unwrap();
    let mut scene = crate::project::render(&spec).unwrap().scene;
    scene.description = None;
    crate::output::to_svg(&scene, &crate::project::svg_options(&spec))
}

/// Vines whose drawings a change of the view in the last bit leaves in
/// place: no pole, whose rims (rings of points seen as ellipses, symmetric
/// about the view) leave the simplification a near tie between two points
/// that such a change may break the other way, moving a kept point by a
/// tenth of a millimetre along the rim.
const STEADY: [&str; 3] = [
    "supports = []\n",
    "supports = [{ kind = \"box\", min = [-60, -40, -30], max = [80, -3, 40] }]\n",
    "supports = [{ kind = \"box\", min = [60, 0, -30], max = [160, 20, 30] }]\n",
];

/// `camera = { turn, tilt }` with `orbit`'s angles, exactly (Rust prints
/// the shortest text that reads back as the same float).
fn orbit_table(orbit: Orbit) -> String {
    format!(
        "camera = {{ turn = {}, tilt = {} }}\n",
        orbit.turn, orbit.tilt
    )
}

/// Asserts that two scenes draw the same paths, point for point, within
/// `tolerance` mm.
fn assert_same_paths(a: &Scene, b: &Scene, tolerance: f64) {
    let (a, b) = (paths(a), paths(b));
    assert_eq!(a.len(), b.len());
    for ((id, p), (other, q)) in a.iter().zip(&b) {
        assert_eq!(id, other);
        let (p, q) = (p.elements(), q.elements());
        assert_eq!(p.len(), q.len(), "{id}");
        for (e, f) in p.iter().zip(q) {
            let (e, f) = (e.end_point(), f.end_point());
            assert_eq!(e.is_some(), f.is_some(), "{id}");
            if let (Some(e), Some(f)) = (e, f) {
                assert!(e.distance(f) < tolerance, "{id}: {e:?} against {f:?}");
            }
        }
    }
}

/// The box round the pictures of `points`.
fn picture_box(camera: &Camera, points: impl IntoIterator<Item = DVec3>) -> kurbo::Rect {
    let mut pictures = points.into_iter().map(|p| camera.project(p).unwrap().0);
    let first = pictures.next().unwrap();
    pictures.fold(kurbo::Rect::from_points(first, first), |r, q| r.union_pt(q))
}

#[test]
fn an_orbit_at_no_angle_draws_the_front_view_to_the_byte() {
    let front = drawn_svg("camera = \"front\"\n");
    assert!(front.contains("<path"));
    assert_eq!(drawn_svg("camera = { turn = 0, tilt = 0 }\n"), front);
    assert_eq!(drawn_svg(&orbit_table(Orbit::FRONT)), front);
    // Not so for any angle.
    assert_ne!(drawn_svg("camera = { turn = 0.5 }\n"), front);
    assert_ne!(drawn_svg("camera = { tilt = 0.5 }\n"), front);
}

#[test]
fn the_three_quarter_angles_draw_the_three_quarter_view() {
    let from = Orbit::THREE_QUARTER.direction();
    let preset = DVec3::new(0.8, 0.45, 1.0).normalize();
    assert!(from.distance(preset) < 1e-15, "{from} against {preset}");
    let towards = Orbit::towards(DVec3::new(0.8, 0.45, 1.0)).unwrap();
    assert!((towards.turn - Orbit::THREE_QUARTER.turn).abs() < 1e-12);
    assert!((towards.tilt - Orbit::THREE_QUARTER.tilt).abs() < 1e-12);
    assert_eq!(
        CameraSpec::Preset(CameraPreset::ThreeQuarter).orbit(),
        Some(Orbit::THREE_QUARTER)
    );
    for table in STEADY {
        assert_same_paths(
            &scene(&format!("{table}camera = \"three-quarter\"\n")),
            &scene(&format!("{table}{}", orbit_table(Orbit::THREE_QUARTER))),
            1e-6,
        );
    }
}

#[test]
fn a_turn_swings_the_eye_towards_plus_x() {
    // The default pole stands at x = 20, off the middle of the plant.
    let (spec, plant, supports) = grown("camera = { turn = 90, tilt = 0 }\n");
    let camera = camera_for(&spec.camera, &plant, &supports);
    let depth = |p: DVec3| camera.project(p).unwrap().1;
    let across = |p: DVec3| camera.project(p).unwrap().0.x;
    // A quarter turn looks from +x along −x: +x comes nearer, the front
    // (+z) is on the left.
    assert!(depth(DVec3::X * 10.0) < depth(DVec3::ZERO) - 9.0);
    assert!(across(DVec3::Z * 10.0) < across(DVec3::ZERO) - 9.0);
    // So the picture is as wide as the lines reach in z, not in x.
    let sight = sight(&spec, &plant, &supports);
    let reach = |axis: fn(&DVec3) -> f64| {
        let values = sight.lines().iter().flat_map(|l| l.points.iter().map(axis));
        let (lo, hi) = values.fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
        hi - lo
    };
    let (x, z) = (reach(|p| p.x), reach(|p| p.z));
    assert!(
        (x - z).abs() > 1.0,
        "x {x}, z {z}: the test needs them apart"
    );
    let width = sight.bounds().width();
    assert!((width - z).abs() < 1e-9, "{width} against z {z}");
}

#[test]
fn a_half_turn_mirrors_the_front_view() {
    // A picture that is not symmetric: the pole is off the middle, but
    // when stems or leaf tips bound it on both sides it is symmetric.
    let (spec, plant, supports, front) = [
        "",
        "leaves = 0\ncotyledons = 0\n",
        // Out of the vine's reach the pole alone bounds the picture on
        // its side, the stem's outline on the other.
        "leaves = 0\ncotyledons = 0\n\
         supports = [{ kind = \"pole\", from = [200, 0, 0], to = [200, 400, 0], radius = 6 }]\n",
    ]
        .into_iter()
        .map(|table| {
            let (spec, plant, supports) = grown(table);
            let front = sight(&spec, &plant, &supports).bounds();
            (spec, plant, supports, front)
        })
        .find(|(.., front)| (front.x0 + front.x1).abs() > 1.0)
        .expect("an asymmetric picture");
    let turned = |turn: f64| {
        let spec = VineSpec {
            camera: CameraSpec::Orbit(Orbit {
                turn,
                ..Orbit::FRONT
            }),
            ..spec.clone()
        };
        sight(&spec, &plant, &supports).bounds()
    };
    for turn in [180.0, -180.0] {
        let back = turned(turn);
        for (a, b) in [
            (back.x0, -front.x1),
            (back.x1, -front.x0),
            (back.y0, front.y0),
            (back.y1, front.y1),
        ] {
            assert!((a - b).abs() < 1e-9, "{turn}: {back:?} against {front:?}");
        }
    }
    // A whole turn either way is the front view again.
    for turn in [360.0, -360.0] {
        let again = turned(turn);
        assert!((again.x0 - front.x0).abs() + (again.y1 - front.y1).abs() < 1e-9);
    }
}

#[test]
fn a_tilt_from_above_shows_the_top_of_a_box() {
    // A slab 100 wide, 20 tall and 60 deep, beside the vine: raised by φ,
    // the camera sees its top face, and the picture is 20 cos φ + 60 sin φ
    // tall; from below (φ < 0) it sees the bottom face instead.
    let slab = "leaves = 0\ncotyledons = 0\ninternodes = 2\n\
        supports = [{ kind = \"box\", min = [60, 0, -30], max = [160, 20, 30] }]\n";
    let mut heights = Vec::new();
    for tilt in [-40.0, 0.0, 20.0, 45.0, 89.0] {
        let table = format!("{slab}camera = {{ turn = 0, tilt = {tilt} }}\n");
        let (spec, plant, supports) = grown(&table);
        let camera = camera_for(&spec.camera, &plant, &supports);
        let sight = sight(&spec, &plant, &supports);
        let edges: Vec<_> = sight
            .lines()
            .iter()
            .filter(|l| l.part == Part::Supports)
            .collect();
        assert_eq!(edges.len(), 12);
        let b = picture_box(&camera, edges.iter().flat_map(|l| l.points.clone()));
        let phi = f64::to_radians(tilt);
        let height = 20.0 * phi.cos() + 60.0 * phi.sin().abs();
        assert!((b.height() - height).abs() < 1e-9, "{tilt}: {b:?}");
        heights.push(b.height());
        // The top face's far edge: drawn from above, hidden from below.
        let far_top = edges
            .iter()
            .find(|l| l.points.iter().all(|p| p.y == 20.0 && p.z == -30.0))
            .unwrap();
        let seen: f64 = sight
            .visible(far_top, 0.2, 1e-5)
            .iter()
            .map(|r| length3(r))
            .sum();
        match tilt {
            t if t > 0.0 => assert!(seen > 99.0, "{tilt}: {seen}"),
            t if t < 0.0 => assert!(seen < 1.0, "{tilt}: {seen}"),
            _ => {}
        }
    }
    assert!(heights[1..].windows(2).all(|w| w[0] < w[1]), "{heights:?}");
}

#[test]
fn a_perspective_orbit_fits_the_vine_in_its_field_of_view() {
    for fov in [5.0, 60.0, 170.0] {
        let table = format!("camera = {{ turn = 30, tilt = 20, perspective = {fov} }}\n");
        let (spec, plant, supports) = grown(&table);
        let camera = camera_for(&spec.camera, &plant, &supports);
        assert!(camera.is_perspective());
        // The stems' points and the leaves' corners lie in the box the
        // camera circles, so inside the sphere round it, so in view.
        let reach = plant
            .stems
            .iter()
            .flat_map(|s| s.points.iter())
            .chain(plant.leaves.iter().flat_map(|l| l.quad.iter()))
            .map(|p| camera.project(*p).unwrap().0.to_vec2().hypot())
            .fold(0.0, f64::max);
        assert!(reach <= 1.0 + 1e-9, "{fov}: {reach}");
        // A point of the sphere straight across the view from its middle
        // is seen at cos(½ fov); the vine reaches about that far.
        let across = (0.5 * f64::to_radians(fov)).cos();
        assert!(
            reach > 0.5 * across,
            "{fov}: {reach}: the eye stands too far"
        );
    }
}

#[test]
fn a_placed_camera_as_an_orbit_draws_the_same() {
    let placed = "camera = { eye = [300, 250, 400], target = [20, 100, 0] }\n";
    let spec: VineSpec = toml::from_str(placed).unwrap();
    let orbit = spec.camera.orbit().unwrap();
    assert!((orbit.turn - 280f64.atan2(400.0).to_degrees()).abs() < 1e-12);
    let level = 280f64.hypot(400.0);
    assert!((orbit.tilt - 150f64.atan2(level).to_degrees()).abs() < 1e-12);
    for table in STEADY {
        assert_same_paths(
            &scene(&format!("{table}{placed}")),
            &scene(&format!("{table}{}", orbit_table(orbit))),
            1e-6,
        );
    }
    // No orbit draws these.
    for camera in [
        "camera = \"below\"\n",
        "camera = { eye = [300, 250, 400], target = [20, 100, 0], perspective = 40 }\n",
        // Up leans to the side: the picture is turned.
        "camera = { eye = [0, 0, 400], target = [0, 0, 0], up = [1, 1, 0] }\n",
        // Steeper than 89°.
        "camera = { eye = [0, 400, 1], target = [0, 0, 0], up = [0, 0, -1] }\n",
    ] {
        let spec: VineSpec = toml::from_str(camera).unwrap();
        assert_eq!(spec.camera.orbit(), None, "{camera}");
    }
    // An upright placed camera whose `up` also leans along the view is.
    let leaning = "camera = { eye = [0, 0, 400], target = [0, 0, 0], up = [0, 1, 5] }\n";
    let spec: VineSpec = toml::from_str(leaning).unwrap();
    assert_eq!(spec.camera.orbit(), Some(Orbit::FRONT));
}

#[test]
fn a_parameter_row_is_drawn_at_one_scale_on_one_ground() {
    let rendered = crate::templates::get("vine-growth")
        .unwrap()
        .render()
        .unwrap();
    // Every panel's pole (560 tall) stands on the bottom edge of its box
    // (198 mm down the page) and reaches 560 mm × the row's scale up,
    // wherever its top is not hidden behind the vine.
    let mut panels: BTreeMap<String, Rect> = BTreeMap::new();
    for (id, path) in paths(&rendered.scene) {
        if let Some((panel, _)) = id.split_once(".support-") {
            let b = path.bounding_box();
            panels
                .entry(panel.to_string())
                .and_modify(|r| *r = r.union(b))
                .or_insert(b);
        }
    }
    assert_eq!(panels.len(), 7, "one pole a panel");
    let top = 198.0 - 560.0 * 0.29;
    for (panel, pole) in &panels {
        assert!((pole.y1 - 198.0).abs() < 1e-6, "{panel}: {pole:?}");
        assert!(pole.y0 > top - 1e-6, "{panel}: {pole:?}");
        assert!(pole.width() < 12.0 * 0.29 + 1e-6, "{panel}: {pole:?}");
    }
    let topped = panels.values().filter(|p| (p.y0 - top).abs() < 1e-6);
    assert!(topped.count() >= 5, "{panels:?}");
    // Too large a scale is named, with the one that fits.
    let e = error("scale = 50\n");
    assert!(e.contains("scale") && e.contains("at most"), "{e}");
}
