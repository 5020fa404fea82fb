//! Placement along centre lines, overrides by id, and the flow's lines.

use kurbo::Point;

use super::*;
use crate::spec::{Format, SceneSpec, TreeOverride, TreeParams, TreeRule};

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

    let flow = Flow::new(&RegionLinesSpec::default());
    let limbs = LimbSpec::default();
    let draw = |s: &TreeSetSpec| {
        tree_set(
            s,
            "l.t",
            &limbs,
            &flow,
            Seed(3),
            &mut PathBudget::new(10_000),
            &mut || {},
        )
        .unwrap()
    };
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
