//! Tests of the vine simulation, on the 3D axis and leaves: the thesis'
//! documented effects of each parameter (ch. 4), the geometric promises
//! (no point inside a support, twined points touching a support or a
//! stem, stems beside each other and never through each other), leaves
//! facing the light, supports and their distance queries, OBJ reading,
//! and the tube mesh.

use std::collections::BTreeMap;
use std::f64::consts::{PI, TAU};

use glam::DVec3;

use super::*;
use crate::geom::mesh::ray_crosses;
use crate::geom::segment_distance_3d;
use crate::rng::Seed;

const R: f64 = 2.0;

/// The test pole of the brief: radius 6, 400 high, standing at x = `x`.
fn pole_at(x: f64) -> Supports {
    Supports::new(vec![Shape::Pole {
        base: DVec3::new(x, 0.0, 0.0),
        top: DVec3::new(x, 400.0, 0.0),
        radius: 6.0,
    }])
}

fn grown(params: &VineParams, supports: &Supports, seed: u64) -> Plant {
    grow(params, supports, &mut Seed(seed).stream()).unwrap_or_else(|e| panic!("{e}"))
}

fn with(f: impl FnOnce(&mut VineParams)) -> VineParams {
    let mut p = VineParams::default();
    f(&mut p);
    p
}

/// The closest any raw or shaped axis point of `plant` comes to a support.
fn clearance(plant: &Plant, supports: &Supports) -> f64 {
    plant
        .stems
        .iter()
        .flat_map(|s| s.raw.iter().chain(&s.points))
        .map(|&p| supports.distance(p))
        .fold(f64::INFINITY, f64::min)
}

/// Asserts the promise of the module: no axis point closer than r.
fn assert_clear(plant: &Plant, supports: &Supports, r: f64, what: &str) {
    let c = clearance(plant, supports);
    assert!(
        c >= r - 1e-6,
        "{what}: a point is {c} from a support (r = {r})"
    );
}

/// The longest run of consecutive twined points of the first stem.
fn longest_twined_run(stem: &Stem) -> &[DVec3] {
    let (mut best, mut start) = ((0, 0), None);
    for i in 0..=stem.raw.len() {
        match (stem.twined.get(i).copied().unwrap_or(false), start) {
            (true, None) => start = Some(i),
            (false, Some(s)) => {
                if i - s > best.1 - best.0 {
                    best = (s, i);
                }
                start = None;
            }
            _ => {}
        }
    }
    &stem.raw[best.0..best.1]
}

/// ψ = atan2(−z, x) round the vertical axis through `centre`, unwrapped
/// along `points`.
fn unwrapped_psi(points: &[DVec3], centre: DVec3) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::with_capacity(points.len());
    for p in points {
        let psi = (-(p.z - centre.z)).atan2(p.x - centre.x);
        let psi = match out.last() {
            Some(&last) => last + (psi - last + PI).rem_euclid(TAU) - PI,
            None => psi,
        };
        out.push(psi);
    }
    out
}

/// Height gained per full turn round the pole at x = 20 along the longest
/// twined run, and the turn it covers (radians).
fn pitch(plant: &Plant) -> (f64, f64) {
    let run = longest_twined_run(&plant.stems[0]);
    let psi = unwrapped_psi(run, DVec3::new(20.0, 0.0, 0.0));
    let turn = (psi[psi.len() - 1] - psi[0]).abs();
    let rise = run[run.len() - 1].y - run[0].y;
    (TAU * rise / turn, turn)
}

fn arc_length(points: &[DVec3]) -> f64 {
    points.windows(2).map(|w| w[0].distance(w[1])).sum()
}

#[test]
fn the_stem_winds_round_the_pole_in_the_twining_direction() {
    for (twining, sign) in [(Twining::Right, 1.0), (Twining::Left, -1.0)] {
        for seed in [7, 8, 9] {
            let plant = grown(&with(|p| p.twining = twining), &pole_at(20.0), seed);
            let run = longest_twined_run(&plant.stems[0]);
            assert!(
                run.len() > 24,
                "{twining:?} seed {seed}: only {} twined points",
                run.len()
            );
            let psi = unwrapped_psi(run, DVec3::new(20.0, 0.0, 0.0));
            // Every step climbs and turns the right way (right: ψ grows,
            // clockwise seen from below).
            for (w, q) in psi.windows(2).zip(run.windows(2)) {
                assert!(q[1].y > q[0].y, "{twining:?}: the twined stem goes down");
                assert!(
                    (w[1] - w[0]) * sign > 0.0,
                    "{twining:?}: ψ turns the wrong way"
                );
            }
            assert!(
                (psi[psi.len() - 1] - psi[0]) * sign > TAU,
                "{twining:?}: less than a turn"
            );
        }
    }
}

#[test]
fn twined_points_touch_the_pole_or_a_stem_and_nothing_enters_the_pole() {
    let pole = pole_at(20.0);
    for twining in [Twining::Left, Twining::Right] {
        let mut climbed = 0;
        for seed in [1, 2, 3, 4] {
            let params = with(|p| p.twining = twining);
            let plant = grown(&params, &pole, seed);
            let gaps = axis_gaps(&plant, &params);
            let mut on_pole = 0;
            for (a, stem) in plant.stems.iter().enumerate() {
                for (i, p) in stem.raw.iter().enumerate() {
                    if !stem.twined[i] {
                        continue;
                    }
                    // Touching: at r from the pole's surface, or at the
                    // clearance kept from a stem's axis (2r).
                    let gap = pole.distance(*p);
                    if (gap - R).abs() <= 0.5 {
                        on_pole += 1;
                    } else if !gaps[a][i].is_some_and(|(d, keep)| d - keep <= 0.5) {
                        panic!(
                            "twined point {i} of stem {a} is {gap} from the pole and \
                             {:?} from a stem",
                            gaps[a][i]
                        );
                    }
                }
            }
            // Apexes that stop above the pole hand over to buds below,
            // which twine round the pole or round the stems already there;
            // a first apex that misses the pole (it circles one turn while
            // its rod grows, module docs) may leave the plant without it.
            if on_pole > 24 {
                climbed += 1;
            }
            assert_clear(&plant, &pole, R, "pole");
        }
        assert!(climbed >= 3, "{twining:?}: {climbed} of 4 plants climbed the pole");
    }
}

#[test]
fn a_wider_angle_coils_tighter_and_spreads_wider() {
    let pole = pole_at(20.0);
    let (narrow, narrow_turn) = pitch(&grown(&VineParams::default(), &pole, 7));
    let (wide, wide_turn) = pitch(&grown(&with(|p| p.angle = 30.0), &pole, 7));
    assert!(narrow_turn > TAU && wide_turn > TAU);
    assert!(
        wide < narrow,
        "pitch at 30° {wide} is not below {narrow} at 18°"
    );
    // A helix at distance R + r from the pole's axis whose tangent stays
    // θp from the vertical rises 2π(R + r)/tan θp per turn.
    for (got, angle) in [(narrow, 18.0_f64), (wide, 30.0)] {
        let expected = TAU * 8.0 / angle.to_radians().tan();
        assert!(
            (got / expected - 1.0).abs() < 0.1,
            "pitch {got}, expected {expected}"
        );
    }
    // Before contact (here: with nothing to touch) the circumnutating tip
    // sweeps wider.
    let spread = |angle: f64| {
        let plant = grown(&with(|p| p.angle = angle), &Supports::new(Vec::new()), 7);
        plant.stems[0]
            .raw
            .iter()
            .map(|p| p.x.hypot(p.z))
            .fold(0.0, f64::max)
    };
    assert!(spread(30.0) > 1.3 * spread(18.0));
}

#[test]
fn the_growth_interval_sets_how_far_the_first_apex_circles_before_it_stops() {
    // The first apex turns t/period of a turn per point and stops two
    // internodes (2d points) after it began to turn unless it touches:
    // 2d·t/period of a turn in all, one turn at t = 10, half a turn at
    // t = 5, a tenth at t = 1. It catches the pole when its random first
    // yaw lies within that sweep, plus the pole's width seen from the
    // seed (asin(8/20) either side): the share of seeds the model
    // predicts, counting only the turning after the rod is long enough.
    let seeds = 0..40u64;
    let share = |interval: f64| {
        let caught = seeds
            .clone()
            .filter(|&seed| {
                let plant = grown(&with(|p| p.interval = interval), &pole_at(20.0), seed);
                plant.stems[0].twined.contains(&true)
            })
            .count();
        caught as f64 / seeds.clone().count() as f64
    };
    let window = 2.0 * (8.0_f64 / 20.0).asin();
    // The rod reaches the pole (12 mm from the seed's axis, less r and the
    // pole's radius: 20 − 6 − 2) once it is 12/sin θp long.
    let reach = 12.0 / 18.0_f64.to_radians().sin() / 5.0;
    for interval in [1.0, 5.0, 10.0, 40.0] {
        let sweep = (24.0 - reach) * TAU * interval / 240.0;
        let predicted = ((sweep + window) / TAU).min(1.0);
        let got = share(interval);
        assert!(
            (got - predicted).abs() <= 0.2,
            "t = {interval}: {got} of the first apexes caught the pole, {predicted} predicted"
        );
    }
    // So a faster growth reaches the pole higher up on average: the stem
    // grows twice as much per turn, and when the first apex misses, a bud
    // one internode higher catches it.
    let first_contact = |interval: f64| {
        let heights: Vec<f64> = seeds
            .clone()
            .filter_map(|seed| {
                let plant = grown(&with(|p| p.interval = interval), &pole_at(20.0), seed);
                plant
                    .stems
                    .iter()
                    .filter_map(|s| s.twined.iter().position(|&t| t).map(|i| s.raw[i].y))
                    .reduce(f64::min)
            })
            .collect();
        heights.iter().sum::<f64>() / heights.len() as f64
    };
    let (fast, base) = (first_contact(5.0), first_contact(10.0));
    assert!(fast > base, "first contact at {fast} (t = 5), {base} (t = 10)");
}

#[test]
fn more_untwined_nodes_make_a_longer_bare_base() {
    let first_twined_height = |untwined: u32| {
        let plant = grown(&with(|p| p.untwined = untwined), &pole_at(20.0), 7);
        let stem = &plant.stems[0];
        let i = stem
            .twined
            .iter()
            .position(|&t| t)
            .expect("the stem twines");
        // The untwined nodes grow straight up.
        let straight = untwined as usize * 12;
        assert!(stem.raw[..=straight]
            .iter()
            .all(|p| p.x == 0.0 && p.z == 0.0));
        stem.raw[i].y
    };
    let (one, two) = (first_twined_height(1), first_twined_height(2));
    assert!(
        two > one + 50.0,
        "U = 2 twines from {two}, U = 1 from {one}"
    );
}

#[test]
fn longer_internodes_space_the_leaves_further() {
    let mean_gap = |internode: f64| {
        let tall = Supports::new(vec![Shape::Pole {
            base: DVec3::new(20.0, 0.0, 0.0),
            top: DVec3::new(20.0, 1200.0, 0.0),
            radius: 6.0,
        }]);
        let plant = grown(&with(|p| p.internode = internode), &tall, 7);
        let stem = &plant.stems[0];
        let nodes: Vec<usize> = plant
            .leaves
            .iter()
            .filter(|l| l.stem == 0 && !l.cotyledon)
            .map(|l| l.node)
            .collect();
        assert!(nodes.len() >= 4);
        let gaps: Vec<f64> = nodes
            .windows(2)
            .map(|w| arc_length(&stem.points[w[0]..=w[1]]) / ((w[1] - w[0]) / 12) as f64)
            .collect();
        // Along the drawn axis a node follows the last about l further on.
        for g in &gaps {
            assert!(
                (g / internode - 1.0).abs() < 0.3,
                "l = {internode}: a gap of {g}"
            );
        }
        gaps.iter().sum::<f64>() / gaps.len() as f64
    };
    assert!(mean_gap(100.0) > 1.4 * mean_gap(60.0));
}

#[test]
fn an_apex_that_finds_nothing_stops_and_the_next_node_takes_over() {
    let plant = grown(&VineParams::default(), &pole_at(300.0), 7);
    let stems = &plant.stems;
    assert!(stems.len() >= 3);
    let first = &stems[0];
    assert!(first.stopped && first.twined.iter().all(|&t| !t));
    // Straight for U = 1 internode, then the rod grows for two internodes
    // touching nothing and the apex stops (the thesis' rule): 12 + 24.
    assert_eq!(first.raw.len() - 1, 36);
    assert_eq!(stems[1].parent, Some((0, 24)));
    // The first stem's last node is its tip: the next bud is on the next
    // stem.
    assert_eq!(stems[2].parent, Some((1, 12)));
    // The branches find the first stem and twine round it, but not for
    // ever: each one stops, except the one growing when the growth ends.
    let grown_points: usize = stems.iter().map(|s| s.raw.len() - 1).sum();
    for (i, stem) in stems.iter().enumerate().skip(1) {
        let (ps, n) = stem.parent.unwrap();
        assert_eq!(stem.raw[0], stems[ps].raw[n]);
        assert_eq!(stem.points[0], stems[ps].points[n]);
        assert!(stem.stopped || (i == stems.len() - 1 && grown_points == 24 * 12));
    }
    let has_leaf = |stem, node| {
        plant
            .leaves
            .iter()
            .any(|l| l.stem == stem && l.node == node)
    };
    assert!(has_leaf(0, 0) && has_leaf(0, 12));
    assert!(!has_leaf(0, 24), "node 24 branched but keeps its leaf");
    assert!(!has_leaf(1, 0) && !has_leaf(1, 12));
}

#[test]
fn no_stem_stands_more_than_two_internodes_above_its_last_contact() {
    // The cases of issue 30: long internodes on a 560 pole, 24 internodes
    // on a 300 pole, and a tee whose bar stops the climb.
    let pole = |height: f64| {
        Supports::new(vec![Shape::Pole {
            base: DVec3::new(20.0, 0.0, 0.0),
            top: DVec3::new(20.0, height, 0.0),
            radius: 6.0,
        }])
    };
    let cases = [
        ("internode 100", with(|p| (p.internode, p.internodes) = (100.0, 10)), pole(560.0)),
        ("short pole", VineParams::default(), pole(300.0)),
        (
            "tee",
            with(|p| p.internodes = 30),
            Supports::new(tee(DVec3::new(15.0, 0.0, 0.0), 250.0, 120.0, 4.0)),
        ),
    ];
    for (name, params, supports) in cases {
        for seed in [1, 2, 3] {
            let plant = grown(&params, &supports, seed);
            let l = params.internode;
            let (mut drooped, mut stopped) = (0, 0);
            for (a, stem) in plant.stems.iter().enumerate() {
                // The last contact before each point: the last twined point,
                // or where the stem began (a bud, or the top of the first
                // stem's untwined base).
                let start = if a == 0 { params.untwined as usize * 12 } else { 0 };
                let mut last = stem.points[start.min(stem.points.len() - 1)].y;
                for (i, p) in stem.points.iter().enumerate() {
                    if stem.twined[i] {
                        last = p.y;
                    }
                    let down = match (stem.points.get(i + 1), i.checked_sub(1)) {
                        (Some(q), _) => q.y - p.y,
                        (None, Some(h)) => p.y - stem.points[h].y,
                        (None, None) => 0.0,
                    };
                    assert!(
                        p.y - last <= 2.0 * l + 1e-6 || down < 0.0,
                        "{name} seed {seed}: point {i} of stem {a} stands {} above its last contact",
                        p.y - last
                    );
                }
                // A stopped apex's free tip arches over and hangs.
                let free = stem.twined.iter().rposition(|&t| t).unwrap_or(start);
                if stem.stopped && stem.points.len() - 1 - free >= 12 {
                    let n = stem.points.len();
                    stopped += 1;
                    if stem.points[n - 1].y < stem.points[n - 2].y {
                        drooped += 1;
                    }
                }
            }
            // Most do: a tip bent into a support is put back where it grew.
            assert!(
                drooped > 0 && 2 * drooped >= stopped,
                "{name} seed {seed}: {drooped} of {stopped} stopped tips hang"
            );
        }
    }
}

#[test]
fn an_apex_stops_above_the_top_of_a_short_pole() {
    let short = Supports::new(vec![Shape::Pole {
        base: DVec3::new(20.0, 0.0, 0.0),
        top: DVec3::new(20.0, 150.0, 0.0),
        radius: 6.0,
    }]);
    let plant = grown(&VineParams::default(), &short, 7);
    let first = &plant.stems[0];
    assert!(first.twined.iter().any(|&t| t));
    assert!(first.stopped);
    assert!(first.raw.last().unwrap().y > 150.0);
    assert!(plant.stems.len() > 1);
    assert_clear(&plant, &short, R, "short pole");
}

#[test]
fn leaves_per_node_follow_the_parameters() {
    let pole = pole_at(20.0);
    let count = |plant: &Plant| {
        let mut at: BTreeMap<(usize, usize), usize> = BTreeMap::new();
        for l in &plant.leaves {
            *at.entry((l.stem, l.node)).or_default() += 1;
        }
        at
    };
    for (leaves, cotyledons) in [(1, 1), (2, 1), (1, 2), (2, 2), (0, 1), (1, 0)] {
        let params = with(|p| {
            p.leaves = leaves;
            p.cotyledons = cotyledons;
        });
        let plant = grown(&params, &pole, 7);
        let at = count(&plant);
        for (si, stem) in plant.stems.iter().enumerate() {
            for node in stem.nodes() {
                let branched = plant.stems.iter().any(|s| s.parent == Some((si, node)));
                let expected = match (si, node) {
                    (0, 0) => cotyledons as usize,
                    (_, 0) => 0,
                    _ => leaves as usize - usize::from(branched && leaves > 0),
                };
                let got = at.get(&(si, node)).copied().unwrap_or(0);
                assert_eq!(
                    got, expected,
                    "leaves {leaves}/{cotyledons}, stem {si} node {node}"
                );
            }
        }
        for l in &plant.leaves {
            assert_eq!(l.cotyledon, l.stem == 0 && l.node == 0);
        }
    }
    let woody = grown(&with(|p| (p.leaves, p.cotyledons) = (0, 0)), &pole, 7);
    assert!(woody.leaves.is_empty());
}

#[test]
fn leaves_are_shaped_and_stay_out_of_the_supports() {
    // (Seed 3 grows little here: its first branch leans on the first stem
    // up into the underside of the arm, and both stop there.)
    let supports = Supports::new(cross(DVec3::new(20.0, 0.0, 0.0), 400.0, 200.0, 160.0, 5.0));
    let plant = grown(&with(|p| p.leaves = 2), &supports, 1);
    assert!(plant.leaves.len() > 20);
    for l in &plant.leaves {
        let axis = plant.stems[l.stem].points[l.node];
        assert!((l.stalk[0].distance(axis) - R).abs() < 1e-9);
        assert!((l.stalk[1].distance(l.stalk[0]) - 0.4 * 12.0).abs() < 1e-9);
        assert!((l.midrib.length() - 1.0).abs() < 1e-9);
        assert!((l.across.length() - 1.0).abs() < 1e-9);
        assert!(l.midrib.dot(l.across).abs() < 1e-9);
        assert_eq!(l.length, 24.0);
        assert_eq!(l.quad[0], l.stalk[1]);
        assert!((l.quad[2] - (l.quad[0] + l.midrib * 24.0)).length() < 1e-9);
        for q in l.quad {
            assert!(
                supports.distance(q) > 0.0,
                "a leaf corner is inside a support"
            );
        }
    }
    // On a node twined round the pole (and no stem against it) the
    // leaves face away from the pole: the level part of the midrib (the
    // blade droops, so the midrib itself points well down).
    let pole = pole_at(20.0);
    let params = with(|p| p.internodes = 60);
    let plant = grown(&params, &pole, 7);
    let gaps = axis_gaps(&plant, &params);
    let mut facing = 0;
    for l in &plant.leaves {
        let at = plant.stems[l.stem].points[l.node];
        if !plant.stems[l.stem].twined[l.node] || pole.distance(at) > R + 0.5 {
            continue;
        }
        // A node that also has a stem against it (a branch twining beside
        // its parent) puts its leaves between the two: away from the pole
        // still, but less.
        let against_stem = gaps[l.stem][l.node].is_some_and(|(d, keep)| d - keep < 0.5);
        let least = if against_stem { 0.0 } else { 0.5 };
        let out = pole.outward(at).unwrap();
        let level = (l.midrib - DVec3::Y * l.midrib.y).normalize();
        assert!(
            level.dot(out) > least,
            "a leaf on a twined node faces the pole: {}",
            level.dot(out)
        );
        facing += 1;
    }
    assert!(facing > 3, "{facing} leaves on the pole alone");
}

#[test]
fn the_same_seed_grows_the_same_plant() {
    let pole = pole_at(20.0);
    let params = VineParams::default();
    let (mut a, mut b) = (Seed(7).stream(), Seed(7).stream());
    let first = grow(&params, &pole, &mut a).unwrap();
    assert_eq!(first, grow(&params, &pole, &mut b).unwrap());
    let other = grown(&params, &pole, 8);
    assert_ne!(first, other);
    // The base's bend moves P_d by a random offset.
    let bend = |p: &Plant| p.stems[0].points[12] - p.stems[0].raw[12];
    assert!(bend(&first).distance(bend(&other)) > 1e-3);
    assert!(bend(&first).length() > 1e-3);
}

#[test]
fn bad_input_is_named() {
    let error = |params: VineParams| {
        grow(&params, &pole_at(20.0), &mut Seed(1).stream())
            .unwrap_err()
            .to_string()
    };
    assert_eq!(
        error(with(|p| p.internode = 0.0)),
        "internode: must be between 1 and 1000, got 0"
    );
    assert!(error(with(|p| p.angle = f64::NAN)).starts_with("angle: must be between 1 and 80"));
    assert!(error(with(|p| p.leaves = 3)).starts_with("leaves: must be between 0 and 2"));
    assert!(error(with(|p| p.base = DVec3::new(19.0, 0.0, 0.0))).starts_with("base: "));
    for light in [DVec3::ZERO, DVec3::new(f64::NAN, 1.0, 0.0)] {
        assert!(error(with(|p| p.light = light))
            .starts_with("light: must be a finite, non-zero direction, got "));
    }
    let big = with(|p| (p.internodes, p.steps) = (2000, 64));
    assert!(error(big).starts_with("internodes: 2000 internodes of 64 points"));
    let e = with(|p| p.radius = 0.0)
        .check("layers[0].vine[1]")
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "layers[0].vine[1].radius: must be between 0.05 and 100, got 0"
    );
    // An odd d is lowered by one.
    let plant = grown(&with(|p| p.steps = 13), &pole_at(20.0), 1);
    assert_eq!(plant.steps, 12);
    assert_eq!(
        plant.stems[0].nodes().take(3).collect::<Vec<_>>(),
        [0, 12, 24]
    );

    let mut open = TriMesh::parse_obj(CUBE_OBJ, "cube").unwrap();
    assert!(open.check_closed("cube").is_ok());
    open.triangles.pop();
    let message = open
        .check_closed("supports[0].mesh")
        .unwrap_err()
        .to_string();
    assert!(
        message.starts_with("supports[0].mesh: is not a closed mesh: edge ")
            && message.contains("has 1 face (and 2 more edges like it")
            && message.ends_with("a support must be a solid"),
        "{message}"
    );
    let obj_error = |text: &str| TriMesh::parse_obj(text, "m").unwrap_err().to_string();
    assert_eq!(
        obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
        "m: line 4: face index 9 but only 3 vertices"
    );
    assert_eq!(
        obj_error("# a comment\nv 1 x 2\n"),
        "m: line 2: vertex coordinate 'x' is not a finite number"
    );
    assert!(obj_error("v 1 2 1e999\n").starts_with("m: line 1: vertex coordinate '1e999'"));
    assert!(obj_error("v 0 0 0\nv 1 0 0\nf 1 2\n").starts_with("m: line 3: a face needs"));
    assert!(obj_error("v 0 0 0\n").contains("has no faces"));
    assert!(obj_error("v 0 0 0\nf 1 -3 1\n").starts_with("m: line 2: face index -3"));
}

/// A unit cube from (0,0,0) to (1,1,1) as quads, with the corner syntaxes
/// OBJ allows (`a/t/n`, `a//n`, negative indices).
const CUBE_OBJ: &str = "\
o cube
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
vn 0 0 1
f 1 4 3 2
f 5 6 7 8
f 1/1/1 2/2/1 6/3/1 5/4/1
f 4//1 8//1 7//1 3//1
f -7 -6 -2 -3
f 1 5 8 4
";

#[test]
fn obj_faces_are_fanned_into_triangles() {
    let cube = TriMesh::parse_obj(CUBE_OBJ, "cube").unwrap();
    assert_eq!(cube.vertices.len(), 8);
    assert_eq!(cube.triangles.len(), 12);
    // `f -7 -6 -2 -3` after eight vertices is `f 2 3 7 6`.
    assert_eq!(cube.triangles[8], [1, 2, 6]);
    assert_eq!(cube.triangles[9], [1, 6, 5]);
    let moved = cube.transformed(10.0, DVec3::new(0.0, 5.0, 0.0));
    assert_eq!(moved.vertices[6], DVec3::new(10.0, 15.0, 10.0));
}

#[test]
fn distances_to_poles_blocks_and_meshes() {
    let pole = pole_at(20.0);
    let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
    assert!(close(pole.distance(DVec3::new(30.0, 50.0, 0.0)), 4.0));
    assert!(close(pole.distance(DVec3::new(20.0, 50.0, 0.0)), -6.0));
    assert!(close(pole.distance(DVec3::new(21.0, 2.0, 0.0)), -2.0));
    assert!(close(pole.distance(DVec3::new(20.0, 410.0, 3.0)), 10.0));
    assert!(close(pole.distance(DVec3::new(29.0, 404.0, 0.0)), 5.0));
    assert_eq!(pole.outward(DVec3::new(20.0, 50.0, 9.0)), Some(DVec3::Z));
    assert_eq!(pole.outward(DVec3::new(20.0, 50.0, 1.0)), Some(DVec3::Z));
    // A pole along x.
    let bar = Supports::new(vec![Shape::Pole {
        base: DVec3::new(-10.0, 5.0, 0.0),
        top: DVec3::new(10.0, 5.0, 0.0),
        radius: 1.0,
    }]);
    assert!(close(bar.distance(DVec3::new(3.0, 5.0, 4.0)), 3.0));
    assert!(close(bar.distance(DVec3::new(-13.0, 5.0, 0.0)), 3.0));

    let block = Supports::new(vec![Shape::Block {
        min: DVec3::splat(10.0),
        max: DVec3::ZERO,
    }]);
    let mesh = Supports::new(vec![Shape::Mesh(
        TriMesh::parse_obj(CUBE_OBJ, "cube")
            .unwrap()
            .transformed(10.0, DVec3::ZERO),
    )]);
    for (p, d) in [
        (DVec3::new(15.0, 5.0, 5.0), 5.0),
        (DVec3::new(5.0, 5.0, 5.0), -5.0),
        (DVec3::new(5.0, 2.0, 5.0), -2.0),
        (DVec3::new(13.0, 14.0, 5.0), 5.0),
        (DVec3::new(-1.0, -2.0, -2.0), 3.0),
        // On the extension of an edge and of a face: the ray of the inside
        // test runs along faces and through edges.
        (DVec3::new(5.0, 10.0, 10.0), 0.0),
        (DVec3::new(5.0, 5.0, 10.0), 0.0),
        (DVec3::new(-3.0, 10.0, 5.0), 3.0),
        (DVec3::new(2.0, 10.0 - 1e-12, 5.0), -1e-12),
    ] {
        assert!(
            close(block.distance(p), d),
            "block at {p}: {}",
            block.distance(p)
        );
        assert!(
            close(mesh.distance(p), d),
            "mesh at {p}: {}",
            mesh.distance(p)
        );
    }
    assert_eq!(mesh.outward(DVec3::new(5.0, 12.0, 5.0)), Some(DVec3::Y));
    assert_eq!(mesh.outward(DVec3::new(5.0, 9.0, 5.0)), Some(DVec3::Y));
    let none = Supports::new(Vec::new());
    assert_eq!(none.distance(DVec3::ZERO), f64::INFINITY);
    assert_eq!(none.outward(DVec3::ZERO), None);
    // Overlapping solids: inside one is inside.
    let two = Supports::new(tee(DVec3::ZERO, 100.0, 80.0, 3.0));
    assert!(two.distance(DVec3::new(0.0, 101.0, 0.0)) < 0.0);
    assert!(two.distance(DVec3::new(30.0, 100.0, 0.0)) < 0.0);
    assert!(close(two.distance(DVec3::new(30.0, 100.0, 5.0)), 2.0));
}

/// A sphere of `radius` round `centre` from an icosahedron split `levels`
/// times (20·4^levels triangles), outward-facing.
fn icosphere(centre: DVec3, radius: f64, levels: u32) -> TriMesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut vertices: Vec<DVec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| DVec3::new(x, y, z).normalize())
    .collect();
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut middle: BTreeMap<(u32, u32), u32> = BTreeMap::new();
        let mut split = |a: u32, b: u32, vertices: &mut Vec<DVec3>| {
            *middle.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let m = (vertices[a as usize] + vertices[b as usize]).normalize();
                vertices.push(m);
                vertices.len() as u32 - 1
            })
        };
        let mut next = Vec::with_capacity(triangles.len() * 4);
        for [a, b, c] in triangles {
            let (ab, bc, ca) = (
                split(a, b, &mut vertices),
                split(b, c, &mut vertices),
                split(c, a, &mut vertices),
            );
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        triangles = next;
    }
    TriMesh {
        vertices,
        triangles,
    }
    .transformed(radius, centre)
}

#[test]
fn a_large_mesh_answers_through_the_index_as_by_brute_force() {
    let centre = DVec3::new(0.0, 100.0, 0.0);
    let sphere = icosphere(centre, 50.0, 4);
    assert_eq!(sphere.triangles.len(), 5120);
    sphere.check_closed("sphere").unwrap();
    let supports = Supports::new(vec![Shape::Mesh(sphere.clone())]);
    let corners = |t: &[u32; 3]| t.map(|v| sphere.vertices[v as usize]);
    let mut rng = Seed(11).stream();
    for _ in 0..300 {
        let p = centre
            + DVec3::new(
                rng.symmetric(80.0),
                rng.symmetric(80.0),
                rng.symmetric(80.0),
            );
        let unsigned = sphere
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = corners(t);
                p.distance(crate::geom::mesh::nearest_on_triangle(p, a, b, c))
            })
            .fold(f64::INFINITY, f64::min);
        let crossings = sphere
            .triangles
            .iter()
            .filter(|t| {
                let [a, b, c] = corners(t);
                ray_crosses(p, a, b, c)
            })
            .count();
        let brute = if crossings % 2 == 1 {
            -unsigned
        } else {
            unsigned
        };
        let got = supports.distance(p);
        assert!(
            (got - brute).abs() < 1e-9,
            "at {p}: {got}, brute force {brute}"
        );
        // And the polyhedron is close to the sphere it approximates.
        let r = p.distance(centre);
        assert!(
            (got - (r - 50.0)).abs() < 0.5,
            "at {p}: {got} for a radius of {r}"
        );
    }
}

#[test]
fn a_vine_twines_round_many_supports() {
    let cases: Vec<(&str, Vec<Shape>)> = vec![
        (
            "tilted pole",
            vec![Shape::Pole {
                base: DVec3::new(20.0, 0.0, 0.0),
                top: DVec3::new(35.0, 400.0, 8.0),
                radius: 5.0,
            }],
        ),
        (
            "cross",
            cross(DVec3::new(15.0, 0.0, 0.0), 400.0, 200.0, 160.0, 4.0),
        ),
        ("tee", tee(DVec3::new(0.0, 0.0, 15.0), 250.0, 120.0, 3.0)),
        (
            "fence",
            fence(DVec3::new(-100.0, 0.0, 10.0), 200.0, 300.0, 5, 3, 3.0),
        ),
        (
            "block",
            vec![Shape::Block {
                min: DVec3::new(8.0, 0.0, -6.0),
                max: DVec3::new(20.0, 300.0, 6.0),
            }],
        ),
        (
            "mesh",
            vec![Shape::Mesh(
                stretched(TriMesh::parse_obj(CUBE_OBJ, "cube").unwrap(), 40.0)
                    .transformed(8.0, DVec3::new(12.0, 0.0, -4.0)),
            )],
        ),
    ];
    for (name, shapes) in cases {
        let supports = Supports::new(shapes);
        for twining in [Twining::Left, Twining::Right] {
            let plant = grown(
                &with(|p| (p.twining, p.internodes) = (twining, 40)),
                &supports,
                5,
            );
            let twined: usize = plant
                .stems
                .iter()
                .map(|s| s.twined.iter().filter(|&&t| t).count())
                .sum();
            assert!(twined >= 12, "{name} {twining:?}: {twined} twined points");
            assert_clear(&plant, &supports, R, name);
        }
    }
}

/// `mesh` stretched along y.
fn stretched(mut mesh: TriMesh, factor: f64) -> TriMesh {
    for v in &mut mesh.vertices {
        v.y *= factor;
    }
    mesh
}

#[test]
fn no_input_makes_the_growth_hang_or_enter_a_support() {
    // Random parameters round random clutter near the seed.
    let mut rng = Seed(99).stream();
    for case in 0..40 {
        let params = VineParams {
            internode: rng.range(5.0, 150.0),
            radius: rng.range(0.05, 6.0),
            twining: if rng.unit() < 0.5 {
                Twining::Left
            } else {
                Twining::Right
            },
            interval: rng.range(0.1, 200.0),
            angle: rng.range(1.0, 80.0),
            untwined: rng.below(4) as u32,
            steps: 2 + rng.below(20) as u32,
            period: rng.range(1.0, 2000.0),
            internodes: 1 + rng.below(12) as u32,
            leaves: rng.below(3) as u32,
            cotyledons: rng.below(3) as u32,
            leaf_size: rng.range(0.0, 30.0),
            base: DVec3::ZERO,
            droop: case % 2 == 0,
            light: DVec3::new(rng.symmetric(1.0), rng.symmetric(1.0), rng.symmetric(1.0)),
        };
        let mut shapes = Vec::new();
        for _ in 0..rng.below(6) {
            let at = DVec3::new(
                rng.symmetric(60.0),
                rng.range(-10.0, 200.0),
                rng.symmetric(60.0),
            );
            if rng.unit() < 0.5 {
                shapes.push(Shape::Pole {
                    base: at,
                    top: at
                        + DVec3::new(
                            rng.symmetric(100.0),
                            rng.symmetric(200.0),
                            rng.symmetric(100.0),
                        ),
                    radius: rng.range(0.1, 15.0),
                });
            } else {
                let size = DVec3::new(
                    rng.range(0.1, 40.0),
                    rng.range(0.1, 100.0),
                    rng.range(0.1, 40.0),
                );
                shapes.push(Shape::Block {
                    min: at,
                    max: at + size,
                });
            }
        }
        let supports = Supports::new(shapes);
        match grow(&params, &supports, &mut Seed(case).stream()) {
            Ok(plant) => {
                assert_clear(&plant, &supports, params.radius, &format!("case {case}"));
                let d = plant.steps as usize;
                let grown: usize = plant.stems.iter().map(|s| s.raw.len() - 1).sum();
                assert!(grown <= params.internodes as usize * d);
                for stem in &plant.stems {
                    assert_eq!(stem.points.len(), stem.raw.len());
                    assert_eq!(stem.twined.len(), stem.raw.len());
                    assert!(stem.points.iter().all(|p| p.is_finite()));
                }
            }
            Err(e) => assert!(e.to_string().starts_with("base: "), "case {case}: {e}"),
        }
    }
}

#[test]
fn tubes_are_closed_round_the_axis() {
    // A helix that also turns back on itself at the end.
    let mut axis: Vec<DVec3> = (0..40)
        .map(|i| {
            let a = i as f64 * 0.3;
            DVec3::new(10.0 * a.cos(), 3.0 * i as f64, -10.0 * a.sin())
        })
        .collect();
    let last = *axis.last().unwrap();
    axis.extend((1..6).map(|i| last - DVec3::Y * (2.0 * i as f64) + DVec3::X * 0.1));
    let (sides, radius) = (8, 1.5);
    let (vertices, triangles) = tube(&axis, radius, sides);
    let n = axis.len();
    assert_eq!(vertices.len(), n * 8 + 2);
    assert_eq!(triangles.len(), 2 * 8 * (n - 1) + 2 * 8);
    for (i, &p) in axis.iter().enumerate() {
        let t = (axis[(i + 1).min(n - 1)] - axis[i.saturating_sub(1)]).normalize();
        for v in &vertices[i * 8..(i + 1) * 8] {
            assert!((v.distance(p) - radius).abs() < 1e-9);
            assert!((*v - p).dot(t).abs() < 1e-9);
        }
        if i > 0 {
            // Parallel transport: consecutive rings do not twist.
            let (a, b) = (vertices[i * 8] - p, vertices[(i - 1) * 8] - axis[i - 1]);
            assert!(a.normalize().dot(b.normalize()) > 0.5, "ring {i} twisted");
        }
    }
    let mesh = TriMesh {
        vertices: vertices.clone(),
        triangles: triangles.clone(),
    };
    mesh.check_closed("tube").unwrap();
    // Outward-facing: the signed volume is positive, about πr² × length.
    let volume: f64 = triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| vertices[i as usize]);
            a.dot(b.cross(c)) / 6.0
        })
        .sum();
    let straight = PI * radius * radius * arc_length(&axis);
    assert!(
        volume > 0.8 * straight && volume < 1.1 * straight,
        "{volume} vs {straight}"
    );
    assert_eq!(tube(&axis[..1], 1.0, 8), (Vec::new(), Vec::new()));
    assert_eq!(tube(&axis[..2], 1.0, 1).1.len(), 2 * 3 + 2 * 3);
}

/// The clearance the simulation keeps between point `i` of stem `a` and
/// the axis of stem `b`: 2r, except that a branch grows out of its
/// parent's axis, its clearance from it growing from 0 over its first
/// [`axes::Axes::emergence`] of stem.
fn keep(plant: &Plant, params: &VineParams, (a, i): (usize, usize), b: usize) -> f64 {
    let emergence = super::axes::Axes::emergence(params);
    let step = params.internode / plant.steps as f64;
    let grown = (i as f64 * step / emergence).min(1.0);
    let grown = match plant.stems[a].parent {
        Some((parent, _)) if parent == b => grown,
        Some(_) => grown.max(0.5),
        None => 1.0,
    };
    2.0 * params.radius * grown
}

/// Whether segment `j` (points j, j + 1) of a stem is an obstacle to its
/// own point `i`: further than [`axes::Axes::near`] points down the stem.
fn own_obstacle(params: &VineParams, i: usize, j: usize) -> bool {
    j < i && i - j > super::axes::Axes::near(params)
}

/// By brute force, for each simulated axis point of each stem, the
/// nearest axis it grew beside (every earlier stem, and its own stem
/// further down than [`axes::Axes::near`] points) as (distance,
/// clearance kept there, see [`keep`]), the one with the least margin;
/// `None` when there is none.
fn axis_gaps(plant: &Plant, params: &VineParams) -> Vec<Vec<Option<(f64, f64)>>> {
    let mut out = Vec::new();
    for (a, stem) in plant.stems.iter().enumerate() {
        let mut gaps = Vec::new();
        for (i, &p) in stem.raw.iter().enumerate() {
            let mut best: Option<(f64, f64)> = None;
            for (b, other) in plant.stems.iter().enumerate().take(a + 1) {
                for (j, w) in other.raw.windows(2).enumerate() {
                    if a == b && !own_obstacle(params, i, j) {
                        continue;
                    }
                    let d = segment_distance_3d(p, p, w[0], w[1]);
                    let k = keep(plant, params, (a, i), b);
                    if best.is_none_or(|(bd, bk)| d - k < bd - bk) {
                        best = Some((d, k));
                    }
                }
            }
            gaps.push(best);
        }
        out.push(gaps);
    }
    out
}

#[test]
fn stems_lie_beside_each_other_never_through_each_other() {
    let cases: Vec<(&str, Vec<Shape>, u64)> = vec![
        ("pole", pole_at(20.0).shapes().to_vec(), 3),
        (
            "thin pole",
            vec![Shape::Pole {
                base: DVec3::new(12.0, 0.0, 0.0),
                top: DVec3::new(12.0, 400.0, 0.0),
                radius: 1.5,
            }],
            1,
        ),
        ("tee", tee(DVec3::new(0.0, 0.0, 15.0), 250.0, 120.0, 3.0), 1),
        (
            "cross",
            cross(DVec3::new(20.0, 0.0, 0.0), 400.0, 200.0, 160.0, 5.0),
            2,
        ),
    ];
    for (name, shapes, seed) in cases {
        let supports = Supports::new(shapes);
        let params = with(|p| (p.internodes, p.twining) = (100, Twining::Right));
        let plant = grown(&params, &supports, seed);
        assert!(
            plant.stems.len() >= 5,
            "{name}: {} stems",
            plant.stems.len()
        );
        let twr = 2.0 * params.radius;
        // Each simulated point keeps its clearance from the axes it grew
        // beside (its parent's node, a branch's point 0, excepted).
        let gaps = axis_gaps(&plant, &params);
        let mut beside = 0;
        for (a, stem) in plant.stems.iter().enumerate() {
            for (i, gap) in gaps[a].iter().enumerate() {
                let Some((d, keep)) = *gap else { continue };
                if i == 0 && stem.parent.is_some() {
                    continue;
                }
                assert!(
                    d >= keep - 1e-6,
                    "{name}: point {i} of stem {a} is {d} from a stem's axis (keep {keep})"
                );
                beside += usize::from(a > 0 && keep == twr && d < twr + 0.5);
            }
        }
        assert!(beside > 10, "{name}: only {beside} points against a stem");
        // And no two pieces of axis cross closer than that, a little less
        // between the spheres: 10% less where 2r is kept, and 40% less at a
        // branch's start, where another stem lies against its node.
        for (a, stem) in plant.stems.iter().enumerate() {
            for (b, other) in plant.stems.iter().enumerate().take(a + 1) {
                for (i, sa) in stem.raw.windows(2).enumerate() {
                    for (j, sb) in other.raw.windows(2).enumerate() {
                        if a == b && !own_obstacle(&params, i, j + 1) {
                            continue;
                        }
                        let keep = keep(&plant, &params, (a, i), b);
                        let d = segment_distance_3d(sa[0], sa[1], sb[0], sb[1]);
                        let least = if keep < twr { 0.6 * keep } else { 0.9 * keep };
                        assert!(
                            d >= least,
                            "{name}: segment {i} of stem {a} is {d} from segment {j} of \
                             stem {b} (keep {keep})"
                        );
                    }
                }
            }
        }
    }
}

/// A leaf's unit normal: the side of the blade that faces the light.
fn normal(l: &Leaf) -> DVec3 {
    l.midrib.cross(l.across)
}

#[test]
fn leaves_turn_their_faces_to_the_light() {
    let pole = pole_at(20.0);
    let grown_lit =
        |light: DVec3| grown(&with(|p| (p.internodes, p.light) = (60, light)), &pole, 7);
    let facing = |plant: &Plant, light: DVec3| {
        let light = light.normalize();
        let sum: f64 = plant
            .leaves
            .iter()
            .map(|l| normal(l).dot(light).abs())
            .sum();
        sum / plant.leaves.len() as f64
    };
    let (front, side) = (DVec3::new(0.0, 0.5, 1.0), DVec3::new(-1.0, 0.3, 0.2));
    let lit = grown_lit(front);
    assert!(lit.leaves.len() > 20);
    assert_eq!(
        lit,
        grown(&with(|p| p.internodes = 60), &pole, 7),
        "the default"
    );
    assert_eq!(lit, grown_lit(front * 40.0), "only the direction matters");
    let other = grown_lit(side);
    assert!(facing(&lit, front) > 0.7, "{}", facing(&lit, front));
    // A lower light loses more to the droop.
    assert!(facing(&other, side) > 0.6, "{}", facing(&other, side));
    assert!(facing(&lit, front) > facing(&other, front) + 0.2);
    assert!(facing(&other, side) > facing(&lit, side) + 0.2);
    // The face, not the back: the normal and the light on the same side
    // for most leaves (a steep droop can tip a few over).
    let towards = lit
        .leaves
        .iter()
        .filter(|l| normal(l).dot(front) > 0.0)
        .count();
    assert!(towards * 10 >= lit.leaves.len() * 9);
}

#[test]
fn leaves_roll_a_little_out_of_the_lights_plane() {
    // With the light from straight above the droop keeps the blade's
    // across axis level (it turns about that axis), so across leaves the
    // level only by the roll.
    let plant = grown(
        &with(|p| (p.internodes, p.light) = (60, DVec3::Y)),
        &pole_at(20.0),
        7,
    );
    let rolls: Vec<f64> = plant
        .leaves
        .iter()
        .map(|l| l.across.dot(DVec3::Y).asin().to_degrees())
        .collect();
    assert!(rolls.iter().all(|r| r.abs() <= 15.0 + 1e-6), "{rolls:?}");
    // Random, both ways, and not all tiny.
    assert!(rolls.iter().any(|&r| r > 5.0) && rolls.iter().any(|&r| r < -5.0));
    // The same stream, the same rolls.
    assert_eq!(
        plant,
        grown(
            &with(|p| (p.internodes, p.light) = (60, DVec3::Y)),
            &pole_at(20.0),
            7
        )
    );
}

#[test]
fn leaf_blades_droop() {
    let plant = grown(&with(|p| p.internodes = 60), &pole_at(20.0), 7);
    let mut tilts = Vec::new();
    for l in &plant.leaves {
        let stem = &plant.stems[l.stem];
        let (p, n) = (stem.points[l.node], stem.points.len());
        let t = (stem.points[(l.node + 1).min(n - 1)] - stem.points[l.node.saturating_sub(1)])
            .normalize();
        // The blade's direction before the droop: 20° below the
        // direction the petiole leaves the stem in (eq. 3.6–3.8).
        let o = (l.stalk[0] - p).normalize();
        let (a, b) = (20f64.to_radians().cos(), 20f64.to_radians().sin());
        let level = o * a - t * b;
        let tilt = level.y.clamp(-1.0, 1.0).asin() - l.midrib.y.clamp(-1.0, 1.0).asin();
        assert!(tilt >= -1e-9, "a blade tilts up by {}°", -tilt.to_degrees());
        tilts.push(tilt.to_degrees());
    }
    let mean = tilts.iter().sum::<f64>() / tilts.len() as f64;
    assert!((20.0..=30.0 + 1e-6).contains(&mean), "mean droop {mean}°");
    assert!(tilts.iter().filter(|&&t| (t - 30.0).abs() < 0.5).count() * 2 > tilts.len());
}
