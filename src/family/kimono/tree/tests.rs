//! Topology of each rule on an unconstrained tree, the region-line
//! invariant, and the path budget.

use kurbo::{Point, Vec2};
use proptest::prelude::*;

use super::draw::*;
use super::skeleton::*;
use crate::error::Error;
use crate::geom::{natural_spline, Side, SideTest};
use crate::rng::Seed;
use crate::scene::PathBudget;
use crate::spec::{ResolvedTreeParams, TreeParams, TreeRule};

fn exact(generations: u32) -> ResolvedTreeParams {
    let mut p = TreeParams {
        generations: Some(generations),
        jitter_angle: Some(0.0),
        jitter_length: Some(0.0),
        ..TreeParams::default()
    }
    .resolve();
    p.trunk = 20.0;
    p
}

fn grow_free(rule: TreeRule, p: &ResolvedTreeParams) -> Skeleton {
    let free = |_: Point| false;
    grow(
        rule,
        p,
        &Growth {
            root: Point::new(0.0, 0.0),
            direction: Vec2::new(0.0, -1.0),
            blocked: &free,
            mirror: false,
        },
        Seed(1).stream(),
        &mut PathBudget::new(1_000_000),
        "test tree",
    )
    .unwrap()
}

/// The side a limb actually leaves its parent towards, from geometry.
fn geometric_side(s: &Skeleton, limb: &Limb) -> Side {
    let at = limb.parent.expect("child limb");
    let parent = &s.limbs[at.limb].points;
    let k = at.vertex;
    // The parent's local direction: the step arriving at the vertex, or
    // leaving it at the root.
    let d = if k > 0 {
        parent[k] - parent[k - 1]
    } else {
        parent[1] - parent[0]
    };
    let b = limb.points[1] - limb.points[0];
    if b.dot(Side::Left.normal(d)) > 0.0 {
        Side::Left
    } else {
        Side::Right
    }
}

fn sides(s: &Skeleton, kind: LimbKind) -> Vec<Side> {
    s.limbs
        .iter()
        .filter(|l| l.kind == kind)
        .map(|l| {
            let side = l.side.expect("branches have a side");
            assert_eq!(side, geometric_side(s, l), "declared side matches geometry");
            side
        })
        .collect()
}

/// Sides of trunk branches in generation order G, G−1, …, 1: left on even.
fn alternating(generations: u32) -> Vec<Side> {
    (1..=generations)
        .rev()
        .map(|g| if g % 2 == 0 { Side::Left } else { Side::Right })
        .collect()
}

#[test]
fn tree1_alternates_complex_branches() {
    let g = 5;
    let s = grow_free(TreeRule::Tree1, &exact(g));
    assert_eq!(s.count(LimbKind::Trunk), 1);
    assert_eq!(s.limbs[0].points.len(), g as usize + 2);
    assert_eq!(sides(&s, LimbKind::Branch), alternating(g));
    // TreeSub(3): each branch has 3 further steps and 3 twigs.
    for b in s.limbs.iter().filter(|l| l.kind == LimbKind::Branch) {
        assert_eq!(b.points.len(), 5);
    }
    assert_eq!(s.count(LimbKind::Twig), 3 * g as usize);
    sides(&s, LimbKind::Twig);
}

#[test]
fn tree2_has_simple_alternating_branches() {
    let g = 7;
    let s = grow_free(TreeRule::Tree2, &exact(g));
    assert_eq!(s.limbs.len(), 1 + g as usize);
    assert_eq!(sides(&s, LimbKind::Branch), alternating(g));
    assert!(s.limbs[1..].iter().all(|l| l.points.len() == 2));
}

#[test]
fn tree3_follows_generation_mod_3() {
    let g = 6;
    let s = grow_free(TreeRule::Tree3, &exact(g));
    // Per generation, in order: which side carries the complex branch.
    let mut expected = Vec::new();
    for gen in (1..=g).rev() {
        expected.push(match gen % 3 {
            0 => (Side::Left, Some(Side::Left)),
            1 => (Side::Left, Some(Side::Right)),
            _ => (Side::Left, None),
        });
    }
    let branches: Vec<&Limb> = s
        .limbs
        .iter()
        .filter(|l| l.kind == LimbKind::Branch)
        .collect();
    assert_eq!(
        branches.len(),
        2 * g as usize,
        "two branches per generation"
    );
    for (pair, (first, complex)) in branches.chunks(2).zip(expected) {
        assert_eq!(pair[0].side, Some(first));
        assert_eq!(pair[1].side, Some(first.opposite()));
        for b in pair {
            let is_complex = b.points.len() > 2;
            assert_eq!(is_complex, complex == b.side, "generation pattern");
        }
    }
    assert_eq!(
        s.count(LimbKind::Twig),
        4 * 3,
        "generations 6, 4, 3, 1 are complex"
    );
}

#[test]
fn tree4_branches_fork_in_three() {
    let g = 5;
    let s = grow_free(TreeRule::Tree4, &exact(g));
    assert_eq!(sides(&s, LimbKind::Branch), alternating(g));
    assert_eq!(s.count(LimbKind::Prong), 2 * g as usize);
    for (i, b) in s
        .limbs
        .iter()
        .enumerate()
        .filter(|(_, l)| l.kind == LimbKind::Branch)
    {
        assert_eq!(b.points.len(), 3, "branch, then the middle prong");
        let prongs: Vec<&Limb> = s
            .limbs
            .iter()
            .filter(|l| l.kind == LimbKind::Prong && l.parent.unwrap().limb == i)
            .collect();
        assert_eq!(prongs.len(), 2);
        assert_eq!(prongs[0].side, Some(Side::Left));
        assert_eq!(prongs[1].side, Some(Side::Right));
        // The fork is at the branch's second vertex.
        assert!(prongs.iter().all(|p| p.points[0] == b.points[1]));
    }
    sides(&s, LimbKind::Prong);
}

#[test]
fn tree5_branches_left_only_with_depth_g_minus_1() {
    let g = 6;
    let s = grow_free(TreeRule::Tree5, &exact(g));
    assert!(sides(&s, LimbKind::Branch).iter().all(|s| *s == Side::Left));
    assert!(sides(&s, LimbKind::Twig).iter().all(|s| *s == Side::Left));
    let depths: Vec<usize> = s
        .limbs
        .iter()
        .filter(|l| l.kind == LimbKind::Branch)
        .map(|l| l.points.len() - 2)
        .collect();
    assert_eq!(depths, [5, 4, 3, 2, 1, 0]);
    assert_eq!(s.count(LimbKind::Twig), 15);
}

#[test]
fn tree6_has_two_root_branches_then_a_tree2_trunk() {
    let g = 4;
    let p = exact(g);
    let s = grow_free(TreeRule::Tree6, &p);
    assert_eq!(sides(&s, LimbKind::Root), [Side::Left, Side::Right]);
    for r in s.limbs.iter().filter(|l| l.kind == LimbKind::Root) {
        assert_eq!(r.points[0], Point::ZERO);
        let len = (r.points[1] - r.points[0]).hypot();
        assert!((len - p.trunk * p.ratio3).abs() < 1e-9);
    }
    assert_eq!(sides(&s, LimbKind::Branch), alternating(g));
}

#[test]
fn tree7_splits_into_two_tree2_trunks() {
    let g = 5;
    let p = exact(g);
    let s = grow_free(TreeRule::Tree7, &p);
    let trunks: Vec<&Limb> = s
        .limbs
        .iter()
        .filter(|l| l.kind == LimbKind::Trunk)
        .collect();
    assert_eq!(trunks.len(), 2);
    assert_eq!(trunks[0].side, Some(Side::Right));
    assert_eq!(trunks[1].side, Some(Side::Left));
    for t in &trunks {
        assert_eq!(t.points[0], Point::ZERO);
        assert_eq!(t.points.len(), g as usize + 1);
        let first = t.points[1] - t.points[0];
        assert!((first.hypot() - p.trunk * p.ratio1).abs() < 1e-9);
    }
    // Right trunk leans right of up (x > 0), left trunk left.
    assert!(trunks[0].points[1].x > 0.0 && trunks[1].points[1].x < 0.0);
    assert_eq!(s.count(LimbKind::Branch), 2 * (g as usize - 1));
}

#[test]
fn tree8_follows_its_base_curve() {
    let g = 7;
    let p = exact(g);
    let s = grow_free(TreeRule::Tree8, &p);
    assert_eq!(s.count(LimbKind::Trunk), 1);
    assert_eq!(s.limbs[0].points.len(), g as usize);
    let branch_sides = sides(&s, LimbKind::Branch);
    let expected: Vec<Side> = (0..g - 1)
        .map(|i| if i % 2 == 0 { Side::Left } else { Side::Right })
        .collect();
    assert_eq!(branch_sides, expected);
    // Stem samples lie on the base curve, whose last control point is
    // 3.9 trunk lengths up.
    let end = *s.limbs[0].points.last().unwrap();
    let [bx, by] = p.base[3];
    assert!((end - Point::new(bx * p.trunk, -by * p.trunk)).hypot() < 1e-6);
}

#[test]
fn zero_generations_is_just_the_first_step() {
    for rule in TreeRule::ALL {
        let s = grow_free(rule, &exact(0));
        assert!(s.limbs.len() <= 1, "{rule:?}");
    }
}

#[test]
fn lower_line_stops_downward_growth_only() {
    let line = natural_spline(&[Point::new(-100.0, 50.0), Point::new(100.0, 50.0)]);
    let below = SideTest::new(&line, Side::Right);
    let blocked = |p: Point| below.is_beyond(p);
    let p = exact(6);
    let down = grow(
        TreeRule::Tree2,
        &p,
        &Growth {
            root: Point::ZERO,
            direction: Vec2::new(0.0, 1.0),
            blocked: &blocked,
        mirror: false,
    },
        Seed(1).stream(),
        &mut PathBudget::new(1000),
        "t",
    )
    .unwrap();
    assert!(down.vertices().all(|v| v.y <= 50.0));
    assert!(down.limbs[0].points.len() < 8, "the trunk was cut");
}

#[test]
fn budget_stops_runaway_growth_with_a_clear_error() {
    let free = |_: Point| false;
    let mut budget = PathBudget::new(100);
    let err = grow(
        TreeRule::Tree5,
        &exact(20),
        &Growth {
            root: Point::ZERO,
            direction: Vec2::new(0.0, -1.0),
            blocked: &free,
            mirror: false,
        },
        Seed(1).stream(),
        &mut budget,
        "tree front.trees-0.tree-0",
    )
    .unwrap_err();
    assert!(matches!(err, Error::Budget { limit: 100, .. }));
    assert!(err.to_string().contains("front.trees-0.tree-0"));
}

#[test]
fn limb_paths_match_limbs() {
    let s = grow_free(TreeRule::Tree1, &exact(4));
    let look = LimbLook {
        pen_width: 0.0,
        style: crate::spec::LimbStyle::Outline,
        width: 3.0,
        tip_width: 0.3,
        bow: 0.08,
    };
    let paths = limb_paths(&s, &look);
    assert_eq!(paths.len(), s.limbs.len());
    for p in &paths {
        assert!(matches!(
            p.elements().last(),
            Some(kurbo::PathEl::ClosePath)
        ));
    }
}

#[test]
fn limbs_thinner_than_two_pen_widths_are_centre_strokes_drawn_first() {
    let s = grow_free(TreeRule::Tree1, &exact(4));
    let look = |pen_width| LimbLook {
        pen_width,
        style: crate::spec::LimbStyle::Outline,
        width: 3.0,
        tip_width: 0.3,
        bow: 0.08,
    };
    let closed = |p: &kurbo::BezPath| crate::geom::subpath::is_closed(p);
    // A fine pen draws every limb as an outline; a 0.5 mm pen the limbs
    // under 1 mm as strokes: the trunk (3 mm) stays an outline.
    assert!(limb_paths(&s, &look(0.05)).iter().all(closed));
    let paths = limb_paths(&s, &look(0.5));
    assert!(closed(&paths[0]));
    let strokes = paths.iter().filter(|p| !closed(p)).count();
    assert!(
        strokes > 0 && strokes < paths.len(),
        "{strokes} of {}",
        paths.len()
    );
    // In paint order the strokes come first, so that the outlines (the
    // tree's silhouette) painted after them hide what of a twig lies
    // inside its branch.
    let ordered = crate::motif::limb::strokes_first(paths.into_iter().enumerate());
    let first_outline = ordered.iter().position(|(_, p)| closed(p)).unwrap();
    assert!(ordered[first_outline..].iter().all(|(_, p)| closed(p)));
    assert_eq!(first_outline, strokes);
}

fn rule_strategy() -> impl Strategy<Value = TreeRule> {
    (0usize..8).prop_map(|i| TreeRule::ALL[i])
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// docs/SPEC.md §1.2: no vertex of any tree lies beyond the upper region line,
    /// whatever the rule and parameters.
    #[test]
    fn no_vertex_beyond_the_upper_line(
        rule in rule_strategy(),
        generations in 0u32..12,
        ang1 in -40.0f64..40.0,
        ang2 in 10.0f64..120.0,
        ratio1 in 0.5f64..1.3,
        ratio2 in 0.2f64..1.5,
        bumps in proptest::collection::vec(-40.0f64..40.0, 4),
        seed in 0u64..1000,
    ) {
        let upper: Vec<Point> = bumps
            .iter()
            .enumerate()
            .map(|(i, dy)| Point::new(-150.0 + 100.0 * i as f64, -60.0 + dy))
            .collect();
        let test = SideTest::new(&natural_spline(&upper), Side::Left);
        let blocked = |p: Point| test.is_beyond(p);
        let mut p = exact(generations);
        p.ang1 = ang1;
        p.ang2 = ang2;
        p.ratio1 = ratio1;
        p.ratio2 = ratio2;
        p.jitter_angle = 5.0;
        p.jitter_length = 0.1;
        let s = grow(
            rule,
            &p,
            &Growth { root: Point::new(0.0, 30.0), direction: Vec2::new(0.0, -1.0), blocked: &blocked, mirror: false },
            Seed(seed).stream(),
            &mut PathBudget::new(1_000_000),
            "t",
        ).unwrap();
        for v in s.vertices() {
            prop_assert!(!test.is_beyond(v), "{v:?} is beyond the upper line");
        }
    }
}
