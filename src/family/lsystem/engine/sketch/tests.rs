//! Tests of the Sketching L-System: the a-nodes against the stroke, the
//! recursion depth against the stroke's length, self-similarity on a
//! straight stroke, incremental growth, the handles, the rule text and
//! the budget.

use glam::{DVec2, DVec3};

use super::{Branch, Kind, Sketch, SketchRules, MIN_LIMB_PENS};
use crate::family::lsystem::engine::{Limb, Skeleton};

const FIELD: &str = "layers[0].lsystem[0].sketch";

fn rules(a: &str, c: &str, module: f64) -> SketchRules {
    let mut r = SketchRules::parse(a, c, FIELD).unwrap_or_else(|e| panic!("{a} / {c}: {e}"));
    r.module = module;
    r.width = 2.0;
    r
}

fn grown(rules: SketchRules, stroke: &[DVec2]) -> Sketch {
    let mut s = Sketch::new(rules, 1_000_000).unwrap();
    s.extend(stroke).unwrap();
    s
}

/// A stroke up the page from (50, 200), `length` mm long.
fn straight(length: f64) -> Vec<DVec2> {
    vec![DVec2::new(50.0, 200.0), DVec2::new(50.0, 200.0 - length)]
}

/// A wavy stroke with a sharp corner, densely sampled.
fn wavy() -> Vec<DVec2> {
    let mut points: Vec<DVec2> = (0..=300)
        .map(|i| {
            let t = f64::from(i) / 300.0;
            DVec2::new(40.0 + 30.0 * (t * 9.0).sin(), 190.0 - 120.0 * t)
        })
        .collect();
    points.push(DVec2::new(120.0, 60.0));
    points.push(DVec2::new(110.0, 20.0));
    points
}

/// Distance from `p` to the polyline.
fn distance_to(line: &[DVec2], p: DVec2) -> f64 {
    line.windows(2)
        .map(|w| {
            let d = w[1] - w[0];
            let t = ((p - w[0]).dot(d) / d.length_squared()).clamp(0.0, 1.0);
            p.distance(w[0] + d * t)
        })
        .fold(f64::INFINITY, f64::min)
}

/// The point `s` mm along the polyline, computed afresh.
fn at_length(line: &[DVec2], s: f64) -> DVec2 {
    let mut walked = 0.0;
    for w in line.windows(2) {
        let l = w[0].distance(w[1]);
        if walked + l >= s {
            return w[0].lerp(w[1], (s - walked) / l);
        }
        walked += l;
    }
    line[line.len() - 1]
}

fn length(line: &[DVec2]) -> f64 {
    line.windows(2).map(|w| w[0].distance(w[1])).sum()
}

fn flat(p: DVec3) -> DVec2 {
    p.truncate()
}

/// The limbs of the `c` branches `a`'s rule made, in step order: those
/// leaving the `a` chain whose width does not end at 0 (a `b` ends in a
/// point).
fn side_cs(sketch: &Sketch) -> Vec<usize> {
    let skeleton = sketch.skeleton();
    (0..skeleton.limbs.len())
        .filter(|&i| {
            sketch.parents()[i] == Some(0) && *skeleton.limbs[i].widths.last().unwrap() > 0.0
        })
        .collect()
}

/// The limbs of the subtree grown from limb `root`, in creation order.
fn subtree(sketch: &Sketch, root: usize) -> Vec<Limb> {
    let skeleton = sketch.skeleton();
    let mut inside = vec![false; skeleton.limbs.len()];
    inside[root] = true;
    for i in root + 1..skeleton.limbs.len() {
        // A limb comes after its parent.
        inside[i] = sketch.parents()[i].is_some_and(|p| inside[p]);
    }
    (0..skeleton.limbs.len())
        .filter(|&i| inside[i])
        .map(|i| skeleton.limbs[i].clone())
        .collect()
}

/// Whether `a` is `b` moved by `map` with widths times `scale`.
fn similar(a: &[Limb], b: &[Limb], map: impl Fn(DVec3) -> DVec3, scale: f64) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(a, b)| {
            a.order == b.order
                && a.tip == b.tip
                && a.points.len() == b.points.len()
                && a.points
                    .iter()
                    .zip(&b.points)
                    .all(|(p, q)| p.distance(map(*q)) < 1e-9)
                && a.widths
                    .iter()
                    .zip(&b.widths)
                    .all(|(v, w)| (v - w * scale).abs() < 1e-12)
        })
}

#[test]
fn every_a_node_lies_on_the_stroke_a_module_apart() {
    let stroke = wavy();
    let module = 3.7;
    let sketch = grown(rules("a -> b c a", "c -> b c", module), &stroke);
    let nodes = sketch.a_nodes();
    assert_eq!(sketch.steps(), (length(&stroke) / module).floor() as usize);
    assert_eq!(nodes.len(), sketch.steps() + 1);
    for (k, &node) in nodes.iter().enumerate() {
        assert_eq!(node.z, 0.0);
        assert!(distance_to(&stroke, flat(node)) < 1e-6, "node {k}");
        let expected = at_length(&stroke, k as f64 * module);
        assert!(flat(node).distance(expected) < 1e-6, "node {k}: {node}");
        if k > 0 {
            assert!(node.distance(nodes[k - 1]) <= module + 1e-9);
        }
    }
    // The a chain is the polyline through the nodes.
    assert_eq!(sketch.skeleton().limbs[0].points, nodes);
    // Around the corner the chord is shorter than the module.
    assert!(nodes.windows(2).any(|w| w[0].distance(w[1]) < module - 0.1));
}

#[test]
fn longer_strokes_give_more_modules_and_deeper_side_branches() {
    let mut last = (0, 0);
    for length in [25.0, 55.0, 95.0, 160.0] {
        let sketch = grown(SketchRules::paper(), &straight(length));
        let n = sketch.steps();
        let skeleton = sketch.skeleton();
        let cs = side_cs(&sketch);
        assert_eq!(cs.len(), n);
        // The c of step k has been rewritten n − k times: its limb (the
        // lineage continued by c's `c`) has n − k + 1 segments.
        let depths: Vec<usize> = cs
            .iter()
            .map(|&i| skeleton.limbs[i].points.len() - 2)
            .collect();
        let expected: Vec<usize> = (1..=n).map(|k| n - k).collect();
        assert_eq!(depths, expected);
        let deepest = depths[0];
        assert_eq!(deepest, n - 1);
        assert!(n > last.0 && deepest > last.1, "{length} mm: {n} steps");
        last = (n, deepest);
    }
}

#[test]
fn a_straight_stroke_gives_a_self_similar_structure() {
    let rules = SketchRules::paper();
    let module = rules.module;
    let up = DVec3::new(0.0, -module, 0.0);
    let a_ratio = rules.a[3].handle.width;
    let sketch = |steps: usize| grown(rules.clone(), &straight(steps as f64 * module + 1.0));
    let (ten, six, five) = (sketch(10), sketch(6), sketch(5));
    assert_eq!((ten.steps(), six.steps(), five.steps()), (10, 6, 5));
    // The c of step 7 after step 10 is the c of step 3 after step 6,
    // moved 4 modules up the stroke, its widths times a's width ratio
    // once per step between them: both are 3 levels deep.
    let late = subtree(&ten, side_cs(&ten)[6]);
    let early = subtree(&six, side_cs(&six)[2]);
    assert_eq!(
        late.len(),
        1 + 3 * 2,
        "the lineage and two leaflets per level"
    );
    let shifted = |steps: i32| move |p: DVec3| p + up * f64::from(steps);
    assert!(similar(&late, &early, shifted(4), a_ratio.powi(4)));
    // The c of step 2 after step 5, also 3 levels deep, leaves on the
    // other side: mirrored across the stroke (x = 50).
    let other_side = subtree(&five, side_cs(&five)[1]);
    let mirrored = |p: DVec3| shifted(5)(DVec3::new(100.0 - p.x, p.y, p.z));
    assert!(similar(&late, &other_side, mirrored, a_ratio.powi(5)));
    // Cut to 3 levels, an older c is the same too: the first points of
    // the lineage of the c of step 3 after step 10 are those of step 7's.
    let old_lineage = &ten.skeleton().limbs[side_cs(&ten)[2]];
    assert_eq!(old_lineage.points.len(), 9);
    assert!(late[0]
        .points
        .iter()
        .zip(&old_lineage.points)
        .all(|(p, q)| p.distance(shifted(4)(*q)) < 1e-9));
    // Without alternation every side branch leaves on the same side.
    let mut one_sided = SketchRules::paper();
    one_sided.a[3].handle.roll = 0.0;
    let sketch = grown(one_sided, &straight(80.5));
    let skeleton = sketch.skeleton();
    assert!(side_cs(&sketch)
        .iter()
        .all(|&i| skeleton.limbs[i].points[1].x < 50.0));
}

#[test]
fn growing_point_by_point_is_growing_all_at_once() {
    let stroke = wavy();
    let once = grown(SketchRules::paper(), &stroke);
    assert!(once.steps() > 20);
    let mut by_point = Sketch::new(SketchRules::paper(), 1_000_000).unwrap();
    let mut steps = 0;
    for p in &stroke {
        steps += by_point.extend(std::slice::from_ref(p)).unwrap();
    }
    assert_eq!(steps, once.steps());
    assert_eq!(by_point.skeleton(), once.skeleton());
    assert_eq!(by_point.a_nodes(), once.a_nodes());
    assert_eq!(by_point.parents(), once.parents());
    // In uneven pieces, with repeated points and an empty extension.
    let mut pieces = Sketch::new(SketchRules::paper(), 1_000_000).unwrap();
    for chunk in stroke.chunks(7) {
        pieces.extend(chunk).unwrap();
        pieces.extend(&chunk[chunk.len() - 1..]).unwrap();
        pieces.extend(&[]).unwrap();
    }
    assert_eq!(pieces.skeleton(), once.skeleton());
    // Deterministic.
    assert_eq!(
        grown(SketchRules::paper(), &stroke).skeleton(),
        once.skeleton()
    );
}

#[test]
fn every_step_grows_the_structure_on_what_exists() {
    let stroke = wavy();
    let mut sketch = Sketch::new(SketchRules::paper(), 1_000_000).unwrap();
    let mut before = Skeleton::default();
    for p in &stroke {
        if sketch.extend(std::slice::from_ref(p)).unwrap() == 0 {
            continue;
        }
        let after = sketch.skeleton();
        assert!(after.limbs.len() > before.limbs.len());
        // What was drawn stays: every limb keeps its points and grows
        // only at its end, or is cut back where the trunk came near.
        for (old, new) in before.limbs.iter().zip(&after.limbs) {
            let n = old.points.len().min(new.points.len());
            assert_eq!(new.points[..n], old.points[..n]);
            assert_eq!(new.widths[..n], old.widths[..n]);
            assert_eq!(new.order, old.order);
        }
        before = after;
    }
}

#[test]
fn handles_do_what_they_say() {
    let module = 10.0;
    let stroke = straight(10.5);
    let node = DVec3::new(50.0, 190.0, 0.0);
    let limb = |a: &str, c: &str, i: usize| {
        grown(rules(a, c, module), &stroke).skeleton().limbs[i].clone()
    };

    // Angle 0 goes straight on from the parent's tip.
    let b = limb("a -> b(0, 0, 1, 0.5) a", "c ->", 1);
    assert_eq!(b.points, vec![node, node + DVec3::new(0.0, -5.0, 0.0)]);
    // Roll 0 leaves on the left (−x for a stroke going up the page), in
    // the page; 180 on the right; 90 towards the viewer.
    let left = limb("a -> b(30, 0) a", "c ->", 1);
    assert!(left.points[1].x < 50.0 && left.points[1].z == 0.0);
    let right = limb("a -> b(30, 180) a", "c ->", 1);
    assert!(right.points[1].x > 50.0 && right.points[1].z == 0.0);
    assert!((right.points[1].x - 50.0 - (50.0 - left.points[1].x)).abs() < 1e-12);
    let lifted = limb("a -> b(30, 90) a", "c ->", 1);
    assert!(lifted.points[1].z > 0.0);
    assert!((lifted.points[1].z - 5.0 * 0.5).abs() < 1e-12);
    assert!((lifted.points[1].x - 50.0).abs() < 1e-12);
    let negative = limb("a -> b(-30, 0) a", "c ->", 1);
    assert!(negative.points[1].distance(right.points[1]) < 1e-12);
    // `at` 0.5 leaves from the middle of the parent.
    let middle = limb("a -> b(30, 0, 0.5, 0.5, 0.5) a", "c ->", 1);
    assert_eq!(middle.points[0], DVec3::new(50.0, 195.0, 0.0));

    // Width and length ratios multiply down a lineage: a b of the a,
    // a c of the a, its continuation, and the a chain itself.
    let sketch = grown(
        rules(
            "a -> b(40, 0, 0.6, 0.5) c(30, 0, 0.7, 0.8) a(0, 0, 0.9)",
            "c -> c(10, 0, 0.5, 0.25)",
            module,
        ),
        &straight(30.5),
    );
    let skeleton = sketch.skeleton();
    let b = &skeleton.limbs[1];
    assert_eq!(b.widths, vec![2.0 * 0.6, 0.0]);
    assert!((b.points[0].distance(b.points[1]) - 10.0 * 0.5).abs() < 1e-12);
    let c = &skeleton.limbs[2];
    assert_eq!(c.points.len(), 4, "the first c, rewritten twice");
    let lengths: Vec<f64> = c.points.windows(2).map(|w| w[0].distance(w[1])).collect();
    for (l, expected) in lengths.iter().zip([8.0, 2.0, 0.5]) {
        assert!((l - expected).abs() < 1e-12, "{lengths:?}");
    }
    let w = 2.0 * 0.7;
    assert_eq!(
        c.widths,
        vec![w, w * 0.5, w * 0.5 * 0.5, w * 0.5 * 0.5 * 0.5]
    );
    assert_eq!(
        skeleton.limbs[0].widths,
        vec![2.0, 2.0 * 0.9, 2.0 * 0.9 * 0.9, 2.0 * 0.9 * 0.9 * 0.9]
    );
    // The c's lineage turns by 10° per step, in the page.
    let turn = (c.points[2] - c.points[1])
        .normalize()
        .angle_between((c.points[1] - c.points[0]).normalize());
    assert!((turn.to_degrees() - 10.0).abs() < 1e-9);
}

#[test]
fn children_inherit_their_parents_roll() {
    // A c lifted towards the viewer (roll 90): its own roll-0 children
    // turn within its plane, the plane through the stroke and the page
    // normal, never sideways in the page.
    let sketch = grown(
        rules(
            "a -> c(30, 90, 0.7, 0.8) a",
            "c -> b(40) b(-40) c(20)",
            10.0,
        ),
        &straight(60.5),
    );
    let skeleton = sketch.skeleton();
    assert!(skeleton.limbs.len() > 20);
    let points = skeleton.limbs[1..].iter().flat_map(|l| &l.points);
    assert!(points.clone().all(|p| (p.x - 50.0).abs() < 1e-9));
    assert!(points.clone().any(|p| p.z > 1.0));
    // Roll 90 on the c's own children takes them out of that plane.
    let sketch = grown(
        rules("a -> c(30, 90, 0.7, 0.8) a", "c -> b(40, 90) c(20)", 10.0),
        &straight(60.5),
    );
    assert!(sketch.skeleton().limbs[1..]
        .iter()
        .flat_map(|l| &l.points)
        .any(|p| (p.x - 50.0).abs() > 1.0));
}

#[test]
fn limbs_have_their_orders_and_tips() {
    let sketch = grown(SketchRules::paper(), &straight(40.5));
    let skeleton = sketch.skeleton();
    let chain = &skeleton.limbs[0];
    assert_eq!((chain.order, chain.tip), (0, false));
    for (limb, parent) in skeleton.limbs.iter().zip(sketch.parents()).skip(1) {
        let parent = &skeleton.limbs[parent.unwrap()];
        assert_eq!(limb.order, parent.order + 1);
        // Leaflets end in a point and nothing grows on them; growing
        // shoots end where they will go on.
        assert!(limb.tip);
        assert!(limb.widths.iter().all(|w| *w >= 0.0));
    }
    assert_eq!(skeleton.limbs.iter().map(|l| l.order).max(), Some(2));
    // A c whose rule has no continuation ends where its branches leave.
    let sketch = grown(rules("a -> c a", "c -> b b", 10.0), &straight(30.5));
    let skeleton = sketch.skeleton();
    let c = &skeleton.limbs[1];
    assert!(!c.tip && c.widths[1] == 0.0 && c.points.len() == 2);
}

#[test]
fn a_stroke_that_doubles_back_still_grows() {
    let stroke = [
        DVec2::new(0.0, 0.0),
        DVec2::new(5.0, 0.0),
        DVec2::new(0.0, 0.0),
        DVec2::new(0.0, 10.0),
    ];
    let sketch = grown(rules("a -> b c a", "c -> b c", 10.0), &stroke);
    assert_eq!(sketch.steps(), 2);
    assert_eq!(sketch.a_nodes()[1], DVec3::ZERO);
    let skeleton = sketch.skeleton();
    assert!(skeleton
        .limbs
        .iter()
        .flat_map(|l| &l.points)
        .all(|p| p.is_finite()));
}

#[test]
fn the_rules_read_their_text() {
    // The paper's rule text as printed reads back to the paper's rules.
    let paper = SketchRules::paper();
    let read = SketchRules::parse(&paper.a_text(), &paper.c_text(), "sketch").unwrap();
    assert_eq!(read, paper);
    assert_eq!(
        paper.a_text(),
        "a -> b(40, 0, 0.25, 0.45) b(-40, 0, 0.25, 0.45) c(55, 0, 0.7, 0.7) a(0, 180, 0.97, 1)"
    );
    // Defaults: the bare paper rule spreads its b's (and c's) both ways.
    let bare = SketchRules::parse("a -> b, b, c, a", "c→b b c c", FIELD).unwrap();
    let angles = |r: &[Branch]| r.iter().map(|b| b.handle.angle).collect::<Vec<_>>();
    assert_eq!(angles(&bare.a), [45.0, -45.0, 30.0, 0.0]);
    assert_eq!(angles(&bare.c), [45.0, -45.0, 30.0, -30.0]);
    assert_eq!(bare.a[0], Branch::new(Kind::B, 45.0, 0.0, 0.5, 0.5));
    assert_eq!(bare.a[2], Branch::new(Kind::C, 30.0, 0.0, 0.7, 0.7));
    assert_eq!(bare.a[3], Branch::new(Kind::A, 0.0, 0.0, 1.0, 1.0));
    // By position and by name, `at` last.
    let r = SketchRules::parse(
        " a->b( -20 ,90 ) c(10, length = 0.9, at=0.25) a(roll=137.5, width=0.9)",
        "c ->",
        FIELD,
    )
    .unwrap();
    assert_eq!(r.a[0], Branch::new(Kind::B, -20.0, 90.0, 0.5, 0.5));
    assert_eq!(r.a[1].handle.length, 0.9);
    assert_eq!(r.a[1].handle.at, 0.25);
    assert_eq!(r.a[2], Branch::new(Kind::A, 0.0, 137.5, 0.9, 1.0));
    assert!(r.c.is_empty());
    assert_eq!(r.field, FIELD);
    assert_eq!(
        r.a_text(),
        "a -> b(-20, 90, 0.5, 0.5) c(10, 0, 0.7, 0.9, 0.25) a(0, 137.5, 0.9, 1)"
    );
}

#[test]
fn rule_errors_give_the_column() {
    for (a, c, expected) in [
        (
            "b -> a",
            "c ->",
            "sketch.a: column 1: expected the rule's head `a`",
        ),
        (
            "a => a",
            "c ->",
            "sketch.a: column 3: expected `->`, found `=`",
        ),
        (
            "a -> x",
            "c ->",
            "sketch.a: column 6: expected a branch (`a`, `b` or `c`), found `x`",
        ),
        (
            "a -> bc a",
            "c ->",
            "sketch.a: column 7: expected `(`, `,` or a space, found `c`",
        ),
        (
            "a -> b(40, 0, 0.6 0.5) a",
            "c ->",
            "sketch.a: column 19: expected `,` or `)`, found `0`",
        ),
        (
            "a -> b(40",
            "c ->",
            "sketch.a: column 10: expected `,` or `)`, found the end of the rule",
        ),
        (
            "a -> b(,) a",
            "c ->",
            "sketch.a: column 8: expected a number, found `,`",
        ),
        (
            "a -> b(4-0) a",
            "c ->",
            "sketch.a: column 8: `4-0` is not a number",
        ),
        (
            "a -> b(1, 2, 0.5, 0.5, 1, 6) a",
            "c ->",
            "sketch.a: column 27: a branch has at most 5 numbers",
        ),
        (
            "a -> b(bend=1) a",
            "c ->",
            "sketch.a: column 8: unknown handle `bend`",
        ),
        (
            "a -> b(roll=1, 2) a",
            "c ->",
            "sketch.a: column 16: expected a handle's name",
        ),
        (
            "a -> b(roll=1, roll=2) a",
            "c ->",
            "sketch.a: column 16: `roll` is given twice",
        ),
        (
            "a -> b c",
            "c ->",
            "sketch.a: column 9: `a`'s rule needs exactly one `a`",
        ),
        (
            "a -> a b a",
            "c ->",
            "sketch.a: column 10: `a`'s rule needs exactly one `a`",
        ),
        (
            "a -> a",
            "c -> b a",
            "sketch.c: column 8: `c`'s rule may not contain `a`",
        ),
        (
            "a -> a",
            "a -> b",
            "sketch.c: column 1: expected the rule's head `c`",
        ),
        // Ranges, at the offending number (or the branch, for a default).
        (
            "a -> b(400) a",
            "c ->",
            "sketch.a: column 8: angle must be between -360 and 360 degrees, got 400",
        ),
        (
            "a -> b(0, -361) a",
            "c ->",
            "sketch.a: column 11: roll must be between -360 and 360",
        ),
        (
            "a → b(width=0) a",
            "c ->",
            "sketch.a: column 13: width ratio must be more than 0 and at most 1.5, got 0",
        ),
        (
            "a -> a",
            "c -> c(length=1.6)",
            "sketch.c: column 15: length ratio must be more than 0 and at most 1.5",
        ),
        (
            "a -> a",
            "c -> c(1e999)",
            "sketch.c: column 8: angle must be between -360 and 360 degrees, got inf",
        ),
        (
            "a -> b(at=1.5) a",
            "c ->",
            "sketch.a: column 11: at (where along the parent",
        ),
        (
            "a -> a(30)",
            "c ->",
            "sketch.a: column 8: `a` follows the stroke, so its angle must be 0",
        ),
        (
            "a -> a(0, 0, 1, 0.5)",
            "c ->",
            "sketch.a: column 17: `a` is one module long",
        ),
        (
            "a -> a(at=0.5)",
            "c ->",
            "sketch.a: column 11: `a` continues from the tip",
        ),
    ] {
        let e = SketchRules::parse(a, c, FIELD).unwrap_err().to_string();
        assert_eq!(
            e.strip_prefix("layers[0].lsystem[0].")
                .map(|e| e.starts_with(expected)),
            Some(true),
            "{a} / {c}: {e}"
        );
    }
}

#[test]
fn rules_set_in_code_are_checked() {
    let check = |edit: &dyn Fn(&mut SketchRules)| {
        let mut r = SketchRules::paper();
        edit(&mut r);
        Sketch::new(r, 100).unwrap_err().to_string()
    };
    assert!(check(&|r| r.module = 0.0).starts_with("sketch.module: must be more than 0 mm"));
    assert!(check(&|r| r.width = f64::NAN).starts_with("sketch.width: must be 0 mm or more"));
    assert!(check(&|r| r.a.push(r.a[3])).starts_with("sketch.a: `a`'s rule needs exactly one"));
    assert!(check(&|r| r.c[0].kind = Kind::A).starts_with("sketch.c: `c`'s rule may not"));
    assert_eq!(
        check(&|r| r.c[2].handle.width = 2.0),
        "sketch.c: branch 3 (`c`): width ratio must be more than 0 and at most 1.5, got 2"
    );
}

#[test]
fn a_point_that_is_not_finite_is_refused() {
    let mut sketch = Sketch::new(SketchRules::paper(), 1000).unwrap();
    let e = sketch
        .extend(&[DVec2::ZERO, DVec2::new(f64::NAN, 1.0)])
        .unwrap_err();
    assert!(e
        .to_string()
        .starts_with("sketch: a point of the stroke is not finite"));
    assert_eq!(sketch.a_nodes(), [DVec3::ZERO]);
}

#[test]
fn the_budget_refuses_before_it_is_exceeded() {
    // c -> c c c triples the shoots at every step: lifted off the page,
    // with no width, so that none comes near the trunk and is left out.
    let explosive = || {
        let mut r = rules("a -> c(90, 90) a", "c -> c(30) c(0) c(-30)", 1.0);
        r.width = 0.0;
        r
    };
    let mut free = Sketch::new(explosive(), usize::MAX).unwrap();
    free.extend(&straight(8.5)).unwrap();
    let needed = free.segments();
    assert_eq!(free.steps(), 8);

    // Exactly enough for 8 steps: all 8 are taken, the 9th is refused.
    let mut sketch = Sketch::new(explosive(), needed).unwrap();
    assert_eq!(sketch.extend(&straight(8.5)).unwrap(), 8);
    assert_eq!(sketch.skeleton(), free.skeleton());
    let before = sketch.skeleton();
    let e = sketch
        .extend(&[DVec2::new(50.0, 180.0)])
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        format!(
            "{FIELD}: the sketch would have more than {needed} segments (the limit) after 8 \
             steps: use a shorter stroke, a longer module, or rules that branch less"
        )
    );
    assert_eq!(sketch.segments(), needed);
    assert_eq!(sketch.steps(), 8);
    assert_eq!(sketch.skeleton(), before);
    // It stays refused.
    assert!(sketch.extend(&[DVec2::new(50.0, 170.0)]).is_err());
    assert_eq!(sketch.skeleton(), before);

    // A long stroke stops at the budget, never past it.
    let mut sketch = Sketch::new(explosive(), 10_000).unwrap();
    assert!(sketch.extend(&straight(100.0)).is_err());
    assert!(sketch.segments() <= 10_000);
}

/// A stroke drawn by the pen of a plotter: 0.3 mm.
const PEN: f64 = 0.3;

fn drawn(rules: SketchRules, stroke: &[DVec2]) -> Sketch {
    let mut s = Sketch::new(rules, 1_000_000).unwrap().with_pen(PEN);
    s.extend(stroke).unwrap();
    s
}

/// An S, up the page, densely sampled.
fn s_curve() -> Vec<DVec2> {
    (0..=400)
        .map(|i| {
            let t = f64::from(i) / 400.0;
            DVec2::new(60.0 + 32.0 * (t * std::f64::consts::TAU).sin(), 185.0 - 160.0 * t)
        })
        .collect()
}

/// A spiral from the outside in, two and a half turns.
fn spiral() -> Vec<DVec2> {
    (0..=600)
        .map(|i| {
            let t = f64::from(i) / 600.0;
            let angle = t * 5.0 * std::f64::consts::PI;
            let r = 50.0 * (1.0 - 0.85 * t);
            DVec2::new(60.0 + r * angle.cos(), 100.0 + r * angle.sin())
        })
        .collect()
}

/// The documented alternative (docs/SPEC.md §4): a tree whose side
/// branches branch and grow in turn.
fn tree() -> SketchRules {
    let mut r = rules(
        "a -> b(40, 0, 0.25, 0.45) c(50, 0, 0.7, 0.7) a(0, 180, 0.97, 1)",
        "c -> c(-4, 0, 0.85, 0.85) c(40, 0, 0.6, 0.55) b(-45, 0, 0.4, 0.5)",
        8.0,
    );
    r.width = 1.5;
    r
}

/// The limb's length along its points.
fn limb_length(limb: &Limb) -> f64 {
    limb.points.windows(2).map(|w| w[0].distance(w[1])).sum()
}

/// Whether the segments `p`–`q` and `r`–`s` cross, each passing strictly
/// through the other (touching at an end is not crossing).
fn cross(p: DVec2, q: DVec2, r: DVec2, s: DVec2) -> bool {
    let side = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    let (d1, d2) = (side(r, s, p), side(r, s, q));
    let (d3, d4) = (side(p, q, r), side(p, q, s));
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

#[test]
fn side_branches_grow_with_the_stroke_still_to_come() {
    // The lowest side branch of a stroke twice as long is longer, not
    // only the stroke more branched.
    let lowest = |modules: f64| {
        let sketch = drawn(SketchRules::paper(), &straight(modules * 8.0 + 1.0));
        limb_length(&sketch.skeleton().limbs[side_cs(&sketch)[0]])
    };
    let (short, long) = (lowest(5.0), lowest(10.0));
    assert!(long > 1.4 * short, "{short} mm, then {long} mm");
    // Along one stroke, the branches shorten towards its end.
    let sketch = drawn(SketchRules::paper(), &straight(12.0 * 8.0 + 1.0));
    let skeleton = sketch.skeleton();
    let lengths: Vec<f64> = side_cs(&sketch)
        .iter()
        .map(|&i| limb_length(&skeleton.limbs[i]))
        .collect();
    assert!(lengths.windows(2).all(|w| w[0] > w[1]), "{lengths:?}");
    // Still shorter than the stroke above them: a plant, not a broom.
    assert!(lengths[0] < 0.6 * 12.0 * 8.0, "{lengths:?}");
}

#[test]
fn no_limb_is_shorter_than_the_pen_allows() {
    let min = MIN_LIMB_PENS * PEN;
    let strokes = [straight(200.0), wavy(), spiral()];
    for (rules, stroke) in [SketchRules::paper(), tree()]
        .iter()
        .flat_map(|r| strokes.iter().map(move |s| (r, s)))
    {
        let sketch = drawn(rules.clone(), stroke);
        assert_eq!(sketch.min_limb(), min);
        for limb in &sketch.skeleton().limbs[1..] {
            for w in limb.points.windows(2) {
                assert!(w[0].distance(w[1]) >= min - 1e-9, "{limb:?}");
            }
        }
    }
    // Without a pen the rules grow segments finer than any pen can draw.
    let free = grown(SketchRules::paper(), &straight(200.0));
    assert!(free.skeleton().limbs[1..]
        .iter()
        .flat_map(|l| l.points.windows(2))
        .any(|w| w[0].distance(w[1]) < min));
}

#[test]
fn no_branch_crosses_the_trunk_however_the_stroke_curves() {
    let strokes = [("S", s_curve()), ("spiral", spiral()), ("wavy", wavy())];
    for (rules, (name, stroke)) in [SketchRules::paper(), tree()]
        .iter()
        .flat_map(|r| strokes.iter().map(move |s| (r, s)))
    {
        let sketch = drawn(rules.clone(), stroke);
        let skeleton = sketch.skeleton();
        let trunk: Vec<DVec2> = skeleton.limbs[0].points.iter().map(|&p| flat(p)).collect();
        let mut branch_segments = 0;
        for limb in &skeleton.limbs[1..] {
            for w in limb.points.windows(2) {
                branch_segments += 1;
                let (p, q) = (flat(w[0]), flat(w[1]));
                assert!(
                    !trunk.windows(2).any(|t| cross(p, q, t[0], t[1])),
                    "{name}: {p}–{q} crosses the trunk"
                );
            }
        }
        assert!(branch_segments > 5 * sketch.steps(), "{name}");
    }
    // The test sees a crossing, not a touch.
    let at = DVec2::new;
    assert!(cross(at(0., 0.), at(2., 2.), at(0., 2.), at(2., 0.)));
    assert!(!cross(at(0., 0.), at(2., 2.), at(2., 2.), at(4., 0.)));
}

#[test]
fn the_sketch_stays_on_its_page() {
    let (min, max) = (DVec2::new(0.0, 0.0), DVec2::new(100.0, 150.0));
    // A stroke that runs off the right edge, branches reaching out of
    // the page on both sides.
    let stroke = [DVec2::new(20.0, 140.0), DVec2::new(130.0, 20.0)];
    let mut sketch = Sketch::new(SketchRules::paper(), 1_000_000)
        .unwrap()
        .with_pen(PEN)
        .within(min, max);
    sketch.extend(&stroke).unwrap();
    assert!(sketch.off_page());
    assert!(sketch.steps() > 5);
    let skeleton = sketch.skeleton();
    for limb in &skeleton.limbs {
        for (p, w) in limb.points.iter().zip(&limb.widths) {
            let r = w / 2.0;
            assert!(
                p.x - r >= min.x && p.y - r >= min.y && p.x + r <= max.x && p.y + r <= max.y,
                "{p} ({w} wide) off the page"
            );
        }
    }
    // Stopped at the edge: a later point on the page does not restart it.
    let steps = sketch.steps();
    assert_eq!(sketch.extend(&[DVec2::new(50.0, 50.0)]).unwrap(), 0);
    assert_eq!(sketch.steps(), steps);
    // The same stroke on a page big enough grows on.
    let mut big = Sketch::new(SketchRules::paper(), 1_000_000)
        .unwrap()
        .with_pen(PEN)
        .within(DVec2::splat(-100.0), DVec2::splat(300.0));
    big.extend(&stroke).unwrap();
    assert!(!big.off_page() && big.steps() > steps);
}
