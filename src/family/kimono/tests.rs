//! Placement along centre lines, overrides by id, and the flow's lines.

use kurbo::Point;

use super::*;
use crate::motif::flora::Library;
use crate::motif::Flow;
use crate::spec::{
    AdjustSpec, Format, Points, Rhythm, SceneSpec, TreeOverride, TreeParams, TreeRule, VarySpec,
};

/// Runs `f` on layer `l` (at `depth`, default limbs) of a scene with seed 9
/// whose adjustments are `adjust`; every adjustment must be used.
fn in_context<T>(
    lib: &Library,
    depth: i32,
    adjust: &[AdjustSpec],
    f: impl FnOnce(&mut Context<'_>) -> crate::error::Result<T>,
) -> crate::error::Result<T> {
    let spec = SceneSpec::parse(
        "version = 1\nseed = 9\n[[layers]]\nname = \"l\"\n",
        Format::Toml,
    )?
    .edit(|s| s.adjust = adjust.to_vec())?;
    let flow = Flow::new(&spec.lines);
    let mut report = |_| {};
    let mut cx = Context::new(&spec, lib, &flow, &mut report);
    cx.enter_layer((0, &spec.layers[0]), "l", depth);
    let out = f(&mut cx)?;
    cx.finish()?;
    Ok(out)
}

fn set(centre: Points, count: u32) -> TreeSetSpec {
    TreeSetSpec {
        id: None,
        rule: TreeRule::Tree2,
        count,
        centre,
        growth: Orientation::Perpendicular,
        rotate: 0.0,
        params: TreeParams {
            jitter_angle: Some(0.0),
            jitter_length: Some(0.0),
            ..TreeParams::default()
        },
        rhythm: Default::default(),
        reach: None,
        vary: None,
        overrides: Vec::new(),
        flowers: None,
        leaves: Default::default(),
    }
}

#[test]
fn trees_are_evenly_spaced_by_arc_length() {
    let s = set(vec![[0.0, 100.0], [100.0, 100.0]], 4);
    let roots: Vec<f64> = placements(&s).iter().map(|p| p.root.x).collect();
    for (r, want) in roots.iter().zip([12.5, 37.5, 62.5, 87.5]) {
        assert!((r - want).abs() < crate::geom::TOLERANCE, "{roots:?}");
    }
}

#[test]
fn perpendicular_grows_up_whichever_way_the_line_runs() {
    for centre in [
        vec![[0.0, 0.0], [100.0, 0.0]],
        vec![[100.0, 0.0], [0.0, 0.0]],
    ] {
        let p = placements(&set(centre, 1))[0];
        assert!((p.direction - Vec2::new(0.0, -1.0)).hypot() < 1e-9);
    }
    let mut s = set(vec![[0.0, 0.0], [100.0, 0.0]], 1);
    s.growth = Orientation::Parallel;
    assert!((placements(&s)[0].direction - Vec2::new(1.0, 0.0)).hypot() < 1e-9);
    s.rotate = 90.0;
    // Clockwise on the page (y down): +x turns to +y.
    assert!((placements(&s)[0].direction - Vec2::new(0.0, 1.0)).hypot() < 1e-9);
}

#[test]
fn overrides_change_exactly_the_addressed_tree() {
    let plain = set(vec![[0.0, 100.0], [120.0, 100.0]], 3);
    let mut adjusted = plain.clone();
    adjusted.overrides.push(TreeOverride {
        id: "tree-1".into(),
        root: Some([60.0, 50.0]),
        rotate: Some(20.0),
        scale: Some(1.5),
        params: TreeParams {
            generations: Some(2),
            ..TreeParams::default()
        },
    });
    let a = placements(&plain);
    let b = placements(&adjusted);
    assert_eq!(a[0], b[0]);
    assert_eq!(a[2], b[2]);
    assert_eq!(b[1].root, Point::new(60.0, 50.0));
    assert_eq!(b[1].scale, 1.5);

    let draw =
        |s: &TreeSetSpec| in_context(&Library::new(), 0, &[], |cx| tree_set(s, "l.t", cx)).unwrap();
    let (ga, gb) = (draw(&plain), draw(&adjusted));
    assert_eq!(ga.children[0], gb.children[0]);
    assert_eq!(ga.children[2], gb.children[2]);
    assert_ne!(ga.children[1], gb.children[1]);
    let crate::scene::Node::Group(tree1) = &gb.children[1] else {
        panic!("tree group")
    };
    // Tree2 with 2 generations: trunk + 2 branches.
    assert_eq!(tree1.children.len(), 3);
    assert_eq!(tree1.id, "l.t.tree-1");
}

#[test]
fn region_lines_block_above_upper_and_below_lower() {
    let spec = SceneSpec::parse(
        "version = 1\n[lines]\nupper = [[100, 20], [0, 20]]\nlower = [[0, 80], [100, 80]]\n",
        Format::Toml,
    )
    .unwrap();
    let flow = Flow::new(&spec.lines);
    // The upper line is drawn right to left; it still means "above".
    assert!(flow.blocks(Point::new(50.0, 10.0), false));
    assert!(!flow.blocks(Point::new(50.0, 30.0), false));
    // The lower line stops only downward growth.
    assert!(!flow.blocks(Point::new(50.0, 90.0), false));
    assert!(flow.blocks(Point::new(50.0, 90.0), true));
}

// ------------------------------------------------ flowers and leaves

/// A regular polygon with `n` corners filling the unit box, anchored at its
/// centre: user motifs told apart by their element count, whatever the
/// built-in drawings look like.
fn polygon(n: usize) -> crate::motif::flora::Drawing {
    let mut outline = kurbo::BezPath::new();
    for i in 0..n {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        let p = Point::new(0.5 * a.sin(), -0.5 * a.cos());
        if i == 0 {
            outline.move_to(p);
        } else {
            outline.line_to(p);
        }
    }
    outline.close_path();
    crate::motif::flora::Drawing {
        outline,
        details: kurbo::BezPath::new(),
        anchor: Point::ZERO,
        aspect: 1.0,
    }
}

/// Polygons with 3 to 7 corners, named `p3` … `p7`.
fn polygons() -> crate::motif::flora::Library {
    let mut lib = crate::motif::flora::Library::new();
    for n in 3..=7 {
        lib.add_user(format!("p{n}"), polygon(n));
    }
    lib
}

/// The corner count of a polygon motif placed as one path.
fn corners(path: &kurbo::BezPath) -> usize {
    path.elements()
        .iter()
        .filter(|e| !matches!(e, kurbo::PathEl::ClosePath))
        .count()
}

/// The first tree set of a one-layer description with the given set body.
fn flowering_set(body: &str) -> TreeSetSpec {
    let text = format!(
        "version = 1\n[[layers]]\nname = \"l\"\n[[layers.trees]]\nrule = \"tree2\"\n\
         centre = [[0, 100], [200, 100]]\n{body}"
    );
    SceneSpec::parse(&text, Format::Toml)
        .unwrap_or_else(|e| panic!("{e}\n{text}"))
        .into_inner()
        .layers
        .remove(0)
        .trees
        .remove(0)
}

/// The paths of a grown set, by id.
fn grown(
    set: &TreeSetSpec,
    lib: &crate::motif::flora::Library,
    depth: i32,
    adjust: &[crate::spec::AdjustSpec],
) -> crate::error::Result<std::collections::BTreeMap<String, kurbo::BezPath>> {
    let group = in_context(lib, depth, adjust, |cx| tree_set(set, "l.s", cx))?;
    let mut paths = std::collections::BTreeMap::new();
    group.visit_paths(kurbo::Affine::IDENTITY, &mut |p, t| {
        paths.insert(p.id.clone(), t * p.path.clone());
    });
    Ok(paths)
}

/// `n` in the `name-n` part of an id.
fn index(id: &str, name: &str) -> Option<usize> {
    id.split('.')
        .find_map(|s| s.strip_prefix(name)?.strip_prefix('-')?.parse().ok())
}

fn last_part(id: &str) -> &str {
    id.rsplit('.').next().unwrap()
}

const ASSIGN_BODY: &str = r#"count = 5
params = { generations = 3, trunk = 15, jitter_angle = 0, jitter_length = 0 }
[layers.trees.flowers]
motifs = [{ svg = "p3" }, { svg = "p4" }, { svg = "p5" }]
assign = "ASSIGN"
width = 6
[layers.trees.leaves.ring]
motifs = [{ svg = "p6" }, { svg = "p7" }]
count = 2
[layers.trees.leaves.joints]
motifs = [{ svg = "p7" }, { svg = "p3" }, { svg = "p4" }, { svg = "p5" }]
"#;

#[test]
fn type_1_cycles_flower_motifs_per_tree_and_uses_the_first_leaf_motif() {
    let set = flowering_set(&ASSIGN_BODY.replace("ASSIGN", "type1"));
    let paths = grown(&set, &polygons(), 0, &[]).unwrap();
    let mut flowers_of_tree = [0usize; 5];
    for (id, p) in &paths {
        let last = last_part(id);
        if last.starts_with("flower-") {
            let i = index(id, "flower").unwrap();
            assert_eq!(corners(p), 3 + i % 3, "{id}");
            flowers_of_tree[index(id, "tree").unwrap()] += 1;
        } else if last.starts_with("leaf-") {
            assert_eq!(corners(p), 6, "{id}");
        } else if last.starts_with("joint-") {
            assert_eq!(corners(p), 7, "{id}");
        }
    }
    // Enough flowers on every tree to see the motifs cycle.
    assert!(
        flowers_of_tree.iter().all(|n| *n > 3),
        "{flowers_of_tree:?}"
    );
}

#[test]
fn type_2_gives_every_flower_and_leaf_of_tree_k_motif_k_mod_n() {
    let set = flowering_set(&ASSIGN_BODY.replace("ASSIGN", "type2"));
    let paths = grown(&set, &polygons(), 0, &[]).unwrap();
    let mut seen = [[false; 3]; 5];
    for (id, p) in &paths {
        let k = index(id, "tree").unwrap();
        let last = last_part(id);
        let (want, slot) = if last.starts_with("flower-") {
            ([3, 4, 5][k % 3], 0)
        } else if last.starts_with("leaf-") {
            ([6, 7][k % 2], 1)
        } else if last.starts_with("joint-") {
            ([7, 3, 4, 5][k % 4], 2)
        } else {
            continue;
        };
        assert_eq!(corners(p), want, "{id}");
        seen[k][slot] = true;
    }
    assert_eq!(
        seen, [[true; 3]; 5],
        "every tree has flowers and both kinds of leaves"
    );
}

/// Widths of the flowers of tree 0, in flower order.
fn flower_widths(paths: &std::collections::BTreeMap<String, kurbo::BezPath>) -> Vec<f64> {
    let mut w: Vec<(usize, f64)> = paths
        .iter()
        .filter(|(id, _)| id.starts_with("l.s.tree-0.") && last_part(id).starts_with("flower-"))
        .map(|(id, p)| {
            (
                index(id, "flower").unwrap(),
                kurbo::Shape::bounding_box(p).width(),
            )
        })
        .collect();
    w.sort_by_key(|(i, _)| *i);
    w.into_iter().map(|(_, w)| w).collect()
}

#[test]
fn main_largest_order_shrinks_flowers_evenly_to_smallest() {
    // The diamond's width in motif units.
    let unit = kurbo::Shape::bounding_box(&polygon(4).outline).width();
    let set = flowering_set(
        r#"params = { generations = 4, trunk = 15 }
[layers.trees.flowers]
motifs = [{ svg = "p4" }]
width = 10
main_largest = "order"
smallest = 0.4
"#,
    );
    let w = flower_widths(&grown(&set, &polygons(), 0, &[]).unwrap());
    let n = w.len();
    assert!(n >= 4, "{w:?}");
    for (i, wi) in w.iter().enumerate() {
        let want = 10.0 * unit * (1.0 - 0.6 * i as f64 / (n - 1) as f64);
        assert!(
            (wi - want).abs() < 1e-9,
            "flower {i}: {wi} instead of {want}"
        );
    }

    let none = flowering_set(
        r#"params = { generations = 4, trunk = 15 }
[layers.trees.flowers]
motifs = [{ svg = "p4" }]
width = 10
"#,
    );
    for wi in flower_widths(&grown(&none, &polygons(), 2, &[]).unwrap()) {
        assert!((wi - 10.0 * unit).abs() < 1e-9, "{wi}");
    }
}

#[test]
fn main_largest_depth_shrinks_by_smallest_per_depth_step() {
    let unit = kurbo::Shape::bounding_box(&polygon(4).outline).width();
    let set = flowering_set(
        r#"params = { generations = 3, trunk = 15 }
[layers.trees.flowers]
motifs = [{ svg = "p4" }]
width = 10
main_largest = "depth"
smallest = 0.5
"#,
    );
    for (depth, factor) in [(0, 1.0), (1, 0.5), (2, 0.25)] {
        for wi in flower_widths(&grown(&set, &polygons(), depth, &[]).unwrap()) {
            assert!(
                (wi - 10.0 * unit * factor).abs() < 1e-9,
                "depth {depth}: {wi}"
            );
        }
    }
}

#[test]
fn flowers_and_leaves_scale_with_a_scaled_tree() {
    let body = r#"params = { generations = 3, trunk = 15 }
[layers.trees.flowers]
motifs = [{ svg = "p4" }]
width = 10
[layers.trees.leaves.ring]
motifs = [{ svg = "p5" }]
count = 1
width = 4
"#;
    let plain = flowering_set(body);
    let mut scaled = plain.clone();
    scaled.overrides.push(TreeOverride {
        id: "tree-0".into(),
        root: None,
        rotate: None,
        scale: Some(2.0),
        params: TreeParams::default(),
    });
    let (a, b) = (
        grown(&plain, &polygons(), 0, &[]).unwrap(),
        grown(&scaled, &polygons(), 0, &[]).unwrap(),
    );
    let width = |p: &kurbo::BezPath| kurbo::Shape::bounding_box(p).width();
    let mut n = 0;
    for (id, p) in a.iter().filter(|(id, _)| !id.contains(".limb-")) {
        assert!((width(&b[id]) - 2.0 * width(p)).abs() < 1e-9, "{id}");
        n += 1;
    }
    assert!(n >= 4, "{n}");
}

#[test]
fn a_hidden_flower_takes_its_ring_with_it_and_uses_up_their_adjustments() {
    let set = flowering_set(
        r#"params = { generations = 2, trunk = 15 }
[layers.trees.flowers]
motifs = [{ svg = "p4" }]
[layers.trees.leaves.ring]
motifs = [{ svg = "p5" }]
count = 3
"#,
    );
    let adjust = |id: &str, hide: bool| crate::spec::AdjustSpec {
        id: id.into(),
        offset: (!hide).then_some([1.0, 1.0]),
        rotate: None,
        scale: None,
        hide,
        motif: None,
    };
    let list = [
        adjust("l.s.tree-0.flower-1", true),
        // Addresses a leaf of the hidden flower: it exists, so it is no
        // error, and it brings nothing back.
        adjust("l.s.tree-0.flower-1.leaf-2", false),
    ];
    let before = grown(&set, &polygons(), 0, &[]).unwrap();
    let after = grown(&set, &polygons(), 0, &list).unwrap();
    let gone: Vec<&String> = before
        .keys()
        .filter(|id| !after.contains_key(*id))
        .collect();
    assert_eq!(
        gone,
        [
            "l.s.tree-0.flower-1",
            "l.s.tree-0.flower-1.leaf-0",
            "l.s.tree-0.flower-1.leaf-1",
            "l.s.tree-0.flower-1.leaf-2"
        ]
    );
    for (id, p) in &after {
        assert_eq!(p, &before[id], "{id} changed");
    }
}

#[test]
fn a_user_motif_that_was_not_loaded_is_an_error_naming_it() {
    let set = flowering_set(
        r#"params = { generations = 2, trunk = 15 }
[layers.trees.flowers]
motifs = [{ svg = "p4" }, { svg = "missing.svg" }]
"#,
    );
    let e = grown(&set, &polygons(), 0, &[]).unwrap_err().to_string();
    assert!(e.contains("missing.svg"), "{e}");
}

#[test]
fn a_rhythm_leads_with_a_large_tree_crowds_towards_a_quiet_tail_and_rests() {
    let mut s = set(vec![[0.0, 100.0], [100.0, 100.0]], 5);
    s.rhythm = Rhythm {
        lead: 1.5,
        tail: 0.6,
        spacing: 0.8,
        turn: 20.0,
        rests: vec![2],
    };
    let p = placements(&s);
    // Sizes fall in even ratios from the lead to the tail.
    let scales: Vec<f64> = p.iter().map(|p| p.scale).collect();
    assert!((scales[0] - 1.5).abs() < 1e-12 && (scales[4] - 0.6).abs() < 1e-12);
    for w in scales.windows(3) {
        assert!((w[1] / w[0] - w[2] / w[1]).abs() < 1e-12, "{scales:?}");
    }
    // Gaps shrink by 0.8 each, and the rest after tree 2 is one more gap.
    let x: Vec<f64> = p.iter().map(|p| p.root.x).collect();
    let gaps: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    // (Points on the line are found within the flattening tolerance.)
    let tol = 5.0 * crate::geom::TOLERANCE;
    assert!((gaps[1] - 0.8 * gaps[0]).abs() < tol, "{gaps:?}");
    assert!((gaps[2] - 2.0 * 0.8 * gaps[1]).abs() < tol, "{gaps:?}");
    assert!((gaps[3] - 0.8 * gaps[2] / 2.0).abs() < tol, "{gaps:?}");
    // Half a gap before the first tree and after the last.
    assert!((x[0] - 0.5 * gaps[0]).abs() < tol && (100.0 - x[4] - 0.5 * gaps[3]).abs() < tol);
    // The trees fan out by 20° from first to last, the middle one upright.
    let angle = |d: Vec2| d.y.atan2(d.x).to_degrees() + 90.0;
    assert!((angle(p[0].direction) + 10.0).abs() < 1e-9);
    assert!(angle(p[2].direction).abs() < 1e-9);
    assert!((angle(p[4].direction) - 10.0).abs() < 1e-9);
    // The default rhythm is the even one.
    s.rhythm = Rhythm::default();
    let even: Vec<f64> = placements(&s).iter().map(|p| p.root.x).collect();
    for (x, want) in even.iter().zip([10.0, 30.0, 50.0, 70.0, 90.0]) {
        assert!((x - want).abs() < tol, "{even:?}");
    }
}

#[test]
fn ten_thousand_trees_with_the_widest_gaps_stand_in_order_on_the_line() {
    // spacing^9998 is far beyond f64; the places must still be finite,
    // in order and on the line (and found in one pass: this was quadratic).
    for spacing in [10.0, 0.1] {
        let rhythm = Rhythm {
            spacing,
            rests: (0..9998).step_by(7).collect(),
            ..Rhythm::default()
        };
        let places = rhythm.places(10_000);
        assert_eq!(places.len(), 10_000);
        assert!(places
            .iter()
            .all(|p| p.0.is_finite() && (0.0..=1.0).contains(&p.0)));
        assert!(places.windows(2).all(|w| w[0].0 <= w[1].0), "{spacing}");
        // The widest gap is at the growing end.
        let (first, last) = (places[1].0 - places[0].0, places[9999].0 - places[9998].0);
        assert_eq!(spacing > 1.0, last > first, "{spacing}: {first} {last}");
    }
}

#[test]
fn a_rest_after_the_last_tree_is_refused() {
    let text = "version = 1\n[[layers]]\nname = \"l\"\n[[layers.trees]]\nrule = \"tree2\"\n\
                count = 3\ncentre = [[0, 100], [100, 100]]\nrhythm = { rests = [2] }\n";
    let e = SceneSpec::parse(text, Format::Toml)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("layers[0].trees[0].rhythm.rests[0]") && e.contains("0 … 1"),
        "{e}"
    );
}

/// The paths of the background layer of a one-layer scene (A4, the
/// default region lines) whose background tiles `motifs`.
fn background_paths(motifs: &str) -> Vec<(String, kurbo::BezPath)> {
    background_paths_with(&format!("pattern = 2\nmotifs = {motifs}\nwidth = 10\n"))
}

/// The paths of the background layer of a one-layer scene (A4, the
/// default region lines) whose background table ends in `pattern`.
fn background_paths_with(pattern: &str) -> Vec<(String, kurbo::BezPath)> {
    let table = format!(
        "composite = 1\ncount = 3\ncentre = [[20, 150], [190, 140]]\n\
         params = {{ generations = 3, trunk = 12 }}\nstamp_width = 14\n{pattern}"
    );
    let text = format!(
        "version = 1\nseed = 9\n[[layers]]\nname = \"back\"\n[layers.background]\n{table}"
    );
    let spec = SceneSpec::parse(&text, Format::Toml).unwrap();
    let scene = crate::project::build_scene(&spec).unwrap();
    let mut out = Vec::new();
    scene.layers[0]
        .content
        .visit_paths(kurbo::Affine::IDENTITY, &mut |p, t| {
            out.push((p.id.clone(), t * p.path.clone()))
        });
    out
}

#[test]
fn a_single_ground_tile_is_drawn_as_its_seamless_ground() {
    for motif in ["seigaiha", "kikko", "shippo"] {
        let paths = background_paths(&format!("[\"{motif}\"]"));
        let ids: Vec<&str> = paths.iter().map(|(id, _)| id.as_str()).collect();
        assert!(!ids.iter().any(|id| id.contains(".tile-")), "{motif}: {ids:?}");
        let (_, ground) = paths
            .iter()
            .find(|(id, _)| id.ends_with(".background.ground"))
            .unwrap_or_else(|| panic!("{motif}: no ground in {ids:?}"));
        // No tile frame or seam: nothing drawn twice. Runs of a
        // millimetre within 0.01 mm, as the wagara grounds are held to
        // (shippō's circles touch where four meet, for half a millimetre).
        let subpaths: Vec<kurbo::BezPath> = crate::geom::subpath::subpaths(ground)
            .map(|s| s.to_path())
            .collect();
        assert!(subpaths.len() > 50, "{motif}: {} strokes", subpaths.len());
        let doubled = crate::plot::dedupe::doubled_length(subpaths.iter(), 0.01, 1.0);
        assert!(doubled == 0.0, "{motif}: {doubled} mm drawn twice");
        // Seigaiha and shippō are arcs only: no straight frame.
        if motif != "kikko" {
            for seg in ground.segments() {
                if let kurbo::PathSeg::Line(l) = seg {
                    assert!(l.p0.distance(l.p1) < 0.05, "{motif}: a straight line {l:?}");
                }
            }
        }
    }
    // Two motifs alternate as tiles, as before.
    let paths = background_paths("[\"seigaiha\", \"kikko\"]");
    assert!(paths.iter().any(|(id, _)| id.contains(".tile-")));
    // Side by side, seigaiha tiles have no frame: beside shippō (arcs
    // only) nothing straight is drawn.
    let paths = background_paths("[\"seigaiha\", \"shippo\"]");
    let tiles: Vec<&kurbo::BezPath> = paths
        .iter()
        .filter(|(id, _)| id.contains(".tile-"))
        .map(|(_, p)| p)
        .collect();
    assert!(tiles.len() > 10, "{} tiles", tiles.len());
    for seg in tiles.iter().flat_map(|p| p.segments()) {
        if let kurbo::PathSeg::Line(l) = seg {
            assert!(l.p0.distance(l.p1) < 0.05, "a tile frame: {l:?}");
        }
    }
}

#[test]
fn every_stamp_carries_its_own_tile_once() {
    // The hidden trees grow up and down from one root: before the stamps
    // were made distinct, the root's blossom was drawn twice, exactly on
    // itself (kimono-3's band was a fifth drawn twice before the pen stage).
    use kurbo::Shape;
    let paths = background_paths_with("pattern = 5\nmotifs = [\"ume\"]\n");
    let tiles: Vec<&kurbo::BezPath> = paths
        .iter()
        .filter(|(id, _)| id.contains(".tile-"))
        .map(|(_, p)| p)
        .collect();
    assert!(tiles.len() > 5, "{} tiles", tiles.len());
    for (i, a) in tiles.iter().enumerate() {
        let centre = a.bounding_box().center();
        for b in &tiles[..i] {
            assert!(
                b.bounding_box().center().distance(centre) > 1e-3,
                "two blossoms at {centre:?}"
            );
        }
    }
}

// ------------------------------------------- the flow and the main tree

/// Draws set `s` as layer `l` of a scene with seed 9 under the region
/// lines `lines` (a TOML `[lines]` table, or nothing).
fn draw_under(lines: &str, s: &TreeSetSpec) -> Group {
    let spec = SceneSpec::parse(
        &format!("version = 1\nseed = 9\n{lines}[[layers]]\nname = \"l\"\n"),
        Format::Toml,
    )
    .unwrap();
    let lib = Library::new();
    let flow = Flow::new(&spec.lines);
    let mut report = |_| {};
    let mut cx = Context::new(&spec, &lib, &flow, &mut report);
    cx.enter_layer((0, &spec.layers[0]), "l", 0);
    let group = tree_set(s, "l.t", &mut cx).unwrap();
    cx.finish().unwrap();
    group
}

/// The limb paths of each tree of a drawn set, by tree id, in paint order.
fn trees_of(group: &Group) -> Vec<(String, Vec<kurbo::BezPath>)> {
    group
        .children
        .iter()
        .filter_map(|n| match n {
            crate::scene::Node::Group(g) if g.id.contains(".tree-") => Some(g),
            _ => None,
        })
        .map(|g| {
            let paths = g
                .children
                .iter()
                .filter_map(|n| match n {
                    crate::scene::Node::Path(p) => Some(p.path.clone()),
                    crate::scene::Node::Group(_) => None,
                })
                .collect();
            (g.id.clone(), paths)
        })
        .collect()
}

/// A tree's drawing moved so that its root is at the origin, rounded to
/// 0.01 mm: two trees that are the same drawing give the same list.
fn drawing(paths: &[kurbo::BezPath]) -> Vec<(i64, i64)> {
    let root = paths
        .first()
        .and_then(|p| p.elements().first().and_then(|e| e.end_point()))
        .unwrap_or(Point::ZERO);
    paths
        .iter()
        .flat_map(|p| p.elements().iter().filter_map(|e| e.end_point()).collect::<Vec<_>>())
        .map(|q| (((q.x - root.x) * 100.0).round() as i64, ((q.y - root.y) * 100.0).round() as i64))
        .collect()
}

/// An upper line with one peak at (100, 10), over a root at (100, 190).
const PEAK: &str = "[lines]\nupper = [[0, 60], [100, 10], [200, 60]]\n";

#[test]
fn a_set_with_reach_grows_each_tree_to_within_that_distance_of_the_upper_line() {
    let flow_spec = SceneSpec::parse(&format!("version = 1\n{PEAK}"), Format::Toml).unwrap();
    let flow = Flow::new(&flow_spec.lines);
    let highest = |g: &Group| {
        trees_of(g)
            .iter()
            .flat_map(|(_, paths)| paths.iter().flat_map(|p| p.elements().to_vec()))
            .filter_map(|e| e.end_point())
            .filter_map(|q| flow.headroom(q))
            .fold(f64::INFINITY, f64::min)
    };
    let mut s = set(vec![[50.0, 190.0], [150.0, 190.0]], 1);
    let plain = highest(&draw_under(PEAK, &s));
    assert!(plain > 40.0, "as written the tree stays low: {plain:.1} mm");
    for reach in [2.0, 6.0, 15.0] {
        s.reach = Some(reach);
        let h = highest(&draw_under(PEAK, &s));
        // Outline points stand half a tip width beside the last vertex.
        assert!(
            (-0.5..=reach + 0.5).contains(&h),
            "reach {reach}: the highest limb is {h:.2} mm below the line"
        );
    }
}

#[test]
fn companions_differ_from_their_main_tree_and_from_each_other() {
    let mut s = set(vec![[0.0, 190.0], [300.0, 190.0]], 5);
    let drawings = |s: &TreeSetSpec| -> Vec<Vec<(i64, i64)>> {
        trees_of(&draw_under("", s))
            .iter()
            .map(|(_, paths)| drawing(paths))
            .collect()
    };
    s.vary = Some(VarySpec {
        main: 2,
        main_scale: 1.3,
        size: 0.15,
        turn: 8.0,
        generations: 1,
        mirror: true,
    });
    let varied = drawings(&s);
    assert_eq!(varied.len(), 5);
    for i in 0..5 {
        for j in 0..i {
            assert_ne!(varied[i], varied[j], "trees {i} and {j} are one drawing");
        }
    }
    // The main tree is painted last, in front, and is the largest.
    let trees = trees_of(&draw_under("", &s));
    assert_eq!(trees.last().unwrap().0, "l.t.tree-2");
    let height = |paths: &[kurbo::BezPath]| {
        paths
            .iter()
            .map(kurbo::Shape::bounding_box)
            .reduce(|a, b| a.union(b))
            .map_or(0.0, |b| b.height())
    };
    let main = height(&trees.last().unwrap().1);
    for (id, paths) in &trees[..4] {
        assert!(height(paths) < main, "{id} is taller than the main tree");
    }
}

#[test]
fn a_mirrored_companion_grows_its_branches_on_the_other_side() {
    let mut s = set(vec![[0.0, 190.0], [200.0, 190.0]], 2);
    s.vary = Some(VarySpec {
        main: 0,
        main_scale: 1.0,
        size: 0.0,
        turn: 0.0,
        generations: 0,
        mirror: true,
    });
    let trees = trees_of(&draw_under("", &s));
    // tree-1 is painted first, tree-0 (the main tree) last.
    assert_eq!(trees[0].0, "l.t.tree-1");
    // Every end point relative to its tree's root (x 50 and 150), sorted,
    // in 0.01 mm.
    let points = |paths: &[kurbo::BezPath], root_x: f64, flip: f64| {
        let mut v: Vec<(i64, i64)> = paths
            .iter()
            .flat_map(|p| p.elements().to_vec())
            .filter_map(|e| e.end_point())
            .map(|q| {
                (
                    (flip * (q.x - root_x) * 100.0).round() as i64,
                    ((q.y - 190.0) * 100.0).round() as i64,
                )
            })
            .collect();
        v.sort_unstable();
        v
    };
    let main = points(&trees[1].1, 50.0, 1.0);
    assert_ne!(main, points(&trees[0].1, 150.0, 1.0));
    let flipped = points(&trees[0].1, 150.0, -1.0);
    assert_eq!(main.len(), flipped.len());
    assert!(
        main.iter()
            .zip(&flipped)
            .all(|(p, q)| (p.0 - q.0).abs() <= 1 && (p.1 - q.1).abs() <= 1),
        "the companion is the main tree mirrored"
    );
}
