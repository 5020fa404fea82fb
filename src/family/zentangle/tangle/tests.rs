//! The tangles' invariants: each stays inside its section and under the
//! ink limit, and each has the structure its step-out teaches.

use std::f64::consts::{PI, TAU};

use kurbo::{Circle, PathEl, Point, Rect, Shape as _};

use super::super::compose::{compose, Composed};
use super::super::element::tests::{distance_to, samples};
use super::super::element::{Mark, Paint};
use super::super::filling::MAX_INK;
use super::super::ink::{Cells, Ink};
use super::super::procedure::Target;
use super::*;
use crate::rng::Seed;

const PEN: f64 = 0.3;
const TOL: f64 = PEN / 8.0;

fn square() -> Region {
    Region::from_rect(Rect::new(10.0, 10.0, 56.0, 56.0)).unwrap()
}

fn disc() -> Region {
    Region::new(
        Circle::new((40.0, 40.0), 24.0).to_path(1e-4),
        FillRule::NonZero,
    )
    .unwrap()
}

/// An L, as a string cuts a tile.
fn ell() -> Region {
    Region::polygon(&[
        Point::new(0.0, 0.0),
        Point::new(50.0, 0.0),
        Point::new(50.0, 18.0),
        Point::new(20.0, 24.0),
        Point::new(18.0, 50.0),
        Point::new(0.0, 50.0),
    ])
    .unwrap()
}

/// What `tangle` draws into `region` (the loop's sizes for it) with seed
/// `seed`, and that composed.
fn drawn(tangle: Tangle, region: &Region, seed: u64) -> (Vec<Mark>, Composed) {
    let b = region.bounds();
    let t = Target {
        region,
        pole: b.center(),
        radius: b.width().min(b.height()) / 2.0,
        size: 0.35 * b.area().sqrt(),
        wobble: 0.0,
        pen: PEN,
        follow: 0.0,
        branching: 0,
        black: 1.0,
        tone: None,
    };
    let mut rng = Seed(seed).derive(tangle.name()).stream();
    let marks = draw(tangle, &t, &mut rng).unwrap();
    let composed = compose(region, &marks, PEN, TOL, 0.0).unwrap();
    (marks, composed)
}

#[test]
fn names_and_ids_match_the_description() {
    for (k, t) in Tangle::ALL.into_iter().enumerate() {
        assert_eq!(t.name(), TANGLES[k]);
        assert_eq!(Tangle::from_id(t.id()), Some(t));
    }
    assert_eq!(Tangle::from_id(PROCEDURES - 1), None);
    assert_eq!(Tangle::from_id(PROCEDURES + 12), None);
}

#[test]
fn every_tangle_stays_in_its_section_under_the_ink_limit() {
    for region in [square(), disc(), ell()] {
        for tangle in Tangle::ALL {
            let (marks, c) = drawn(tangle, &region, 7);
            let name = tangle.name();
            assert!(!c.strokes.is_empty(), "{name} draws nothing");
            for s in &c.strokes {
                for p in samples(s) {
                    let d = distance_to(region.path(), p);
                    assert!(region.contains(p) || d <= 2.0 * TOL, "{name}: {p:?} {d} outside");
                }
            }
            for black in &c.black {
                let outside = black.difference(&region).area();
                assert!(outside < 1e-6 * region.area(), "{name}: black {outside} mm² outside");
            }
            // Nothing reaches far past the section (the loop weighs marks
            // whole for the ink limit).
            let unit = (UNIT_OF_SIZE * 0.35 * region.bounds().area().sqrt()).max(10.0 * PEN);
            let reach = region.bounds().inflate(0.51 * unit, 0.51 * unit);
            assert!(marks.iter().all(|m| reach.contains_rect(m.path.bounding_box())), "{name}");
            // Under the limit the loop holds every square millimetre to.
            let mut cells = Cells::default();
            c.strokes.iter().for_each(|s| cells.line(s));
            c.black.iter().for_each(|b| cells.black(b.path()));
            let mut ink = Ink::new(PEN, MAX_INK, Some(0.5));
            ink.add(&cells);
            assert!(ink.fullest() <= 1.0, "{name}: {:.2} of the ink limit", ink.fullest());
            // The same seed draws the same.
            assert_eq!(drawn(tangle, &region, 7).0.len(), marks.len(), "{name}");
        }
    }
}

/// The polygon of a mark (flattened), for containment tests.
fn area_of(m: &Mark) -> Region {
    Region::new(m.path.clone(), FillRule::NonZero).unwrap()
}

#[test]
fn hollibaugh_bands_pass_behind_the_ones_drawn_before() {
    let region = square();
    let (marks, c) = drawn(Tangle::Hollibaugh, &region, 3);
    assert_eq!(marks[0].paint, Paint::Black, "the black ground first");
    // Painter's order: the last band is the first drawn, in front.
    let bands: Vec<Region> = marks[1..].iter().map(area_of).collect();
    assert!(bands.len() >= 6, "{} bands", bands.len());
    let mut hidden = 0.0;
    for s in &c.strokes {
        for p in samples(s) {
            // The bands whose edge the point lies on …
            let owners: Vec<usize> = (0..bands.len())
                .filter(|&i| distance_to(bands[i].path(), p) < 2.0 * TOL)
                .collect();
            assert!(!owners.is_empty(), "{p:?} lies on no band's edge");
            // … and none in front of the frontmost of them covers it.
            let o = *owners.iter().max().unwrap();
            for (f, front) in bands.iter().enumerate().skip(o + 1) {
                assert!(
                    !front.contains(p) || distance_to(front.path(), p) < 2.0 * TOL,
                    "{p:?}: band {o}'s line crosses band {f} in front of it"
                );
            }
        }
    }
    // And bands do pass behind others: less line shows than they have.
    for b in &bands {
        hidden += b.intersection(&region).perimeter(0.01);
    }
    let shown: f64 = c.strokes.iter().map(|s| s.perimeter(0.01)).sum();
    assert!(shown < 0.8 * hidden, "{shown:.0} mm shown of {hidden:.0}");
}

#[test]
fn knightsbridge_is_a_checkerboard() {
    let region = square();
    let (marks, c) = drawn(Tangle::Knightsbridge, &region, 5);
    let black = |p: Point| c.black.iter().any(|b| b.contains(p));
    let inner = region.bounds().inset(-6.0);
    let mut checked = 0;
    for m in marks.iter().filter(|m| m.paint == Paint::Black) {
        // Squares cut by the section's edge are not whole: only those
        // inside count.
        if !inner.contains(m.path.bounding_box().center()) {
            continue;
        }
        let corners = corners(&m.path);
        assert_eq!(corners.len(), 4);
        let centre = corners[0].midpoint(corners[2]);
        checked += 1;
        assert!(black(centre));
        for k in 0..4 {
            // Across each side: white; across each corner: black.
            let side = corners[k].midpoint(corners[(k + 1) % 4]);
            assert!(!black(centre + 2.0 * (side - centre)), "a black square beside {centre:?}");
            assert!(black(centre + 2.0 * (corners[k] - centre)), "no black square diagonally");
        }
    }
    assert!(checked >= 10, "{checked}");
}

/// The points a polyline mark moves and draws to, in order.
fn corners(path: &kurbo::BezPath) -> Vec<Point> {
    path.elements()
        .iter()
        .filter_map(|e| match e {
            PathEl::MoveTo(p) | PathEl::LineTo(p) => Some(*p),
            _ => None,
        })
        .collect()
}

/// Centre and radius of a circle mark.
fn circle_of(m: &Mark) -> (Point, f64) {
    let b = m.path.bounding_box();
    (b.center(), b.width() / 2.0)
}

#[test]
fn tipple_circles_do_not_touch_and_vary_in_size() {
    let (marks, _) = drawn(Tangle::Tipple, &square(), 11);
    let circles: Vec<(Point, f64)> = marks.iter().map(circle_of).collect();
    assert!(circles.len() >= 60, "{}", circles.len());
    for (i, a) in circles.iter().enumerate() {
        for b in &circles[i + 1..] {
            assert!(a.0.distance(b.0) > a.1 + b.1 + PEN, "{a:?} and {b:?} touch");
        }
    }
    let (small, big) = circles
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(s, b), c| (s.min(c.1), b.max(c.1)));
    assert!(big > 2.5 * small, "radii {small}–{big}");
}

#[test]
fn printemps_is_spirals_in_their_circles() {
    let (marks, c) = drawn(Tangle::Printemps, &square(), 2);
    assert!(!c.black.is_empty(), "a black ground");
    let mut spirals = 0;
    for pair in marks[1..].chunks(2) {
        let [circle, spiral] = pair else { continue };
        if circle.paint != Paint::White || spiral.paint != Paint::Line {
            continue;
        }
        let (centre, r) = circle_of(circle);
        let points = corners(&spiral.path);
        // From the centre outwards, turning all the way, ending on the
        // circle.
        if points[0].distance(centre) > 1e-6 {
            continue;
        }
        spirals += 1;
        let mut turned = 0.0;
        for w in points[1..].windows(2) {
            assert!(w[1].distance(centre) > w[0].distance(centre));
            let step = (w[1] - centre).atan2() - (w[0] - centre).atan2();
            turned += (step + PI).rem_euclid(TAU) - PI;
        }
        assert!(turned.abs() >= 2.0 * TAU, "{:.1} turns", turned / TAU);
        let last = points[points.len() - 1];
        assert!((last.distance(centre) - r).abs() < 0.01 * r);
    }
    assert!(spirals >= 10, "{spirals}");
}

#[test]
fn crescent_moons_sit_on_the_border_and_auras_ring_them() {
    let region = square();
    let (marks, c) = drawn(Tangle::CrescentMoon, &region, 1);
    let b = region.bounds();
    let moons: Vec<(Point, f64)> = marks
        .iter()
        .filter(|m| m.paint == Paint::Black)
        .map(circle_of)
        .collect();
    assert!(moons.len() >= 12, "{}", moons.len());
    for (centre, _) in &moons {
        let off = [centre.x - b.x0, b.x1 - centre.x, centre.y - b.y0, b.y1 - centre.y]
            .into_iter()
            .fold(f64::INFINITY, |m, d| m.min(d.abs()));
        assert!(off < 0.05, "a moon {off} mm off the border");
    }
    // Half of each shows, black (those clear of the corners).
    let (_, r) = moons[0];
    let halves = c
        .black
        .iter()
        .filter(|p| (p.area() - PI * r * r / 2.0).abs() < 0.15 * r * r)
        .count();
    assert!(halves >= moons.len() - 8, "{halves} half-moons of {}", moons.len());
    let auras = marks.iter().filter(|m| m.paint == Paint::Line).count();
    assert!(auras >= 4, "{auras} auras");
}

#[test]
fn betweed_pods_grow_from_the_edge_and_from_each_other() {
    let region = square();
    let b = region.bounds();
    let s = Section {
        region: &region,
        unit: UNIT_OF_SIZE * 0.35 * b.area().sqrt(),
        pen: PEN,
    };
    let pods = betweed::grow(&s, &mut Seed(4).stream());
    assert!(pods.len() >= 15, "{}", pods.len());
    let mut grown = 0;
    for (i, p) in pods.iter().enumerate() {
        match p.parent {
            None => assert!(distance_to(region.path(), p.centre) < 0.01),
            Some(k) => {
                grown += 1;
                assert!(k < i);
                let q = pods[k];
                assert!((q.centre.distance(p.centre) - q.radius).abs() < 1e-6);
            }
        }
        for (j, o) in pods.iter().enumerate().skip(i + 1) {
            if o.parent != Some(i) {
                assert!(o.centre.distance(p.centre) >= o.radius + p.radius, "{i} and {j}");
            }
        }
    }
    assert!(grown >= 5, "{grown} grown from pods");
}

#[test]
fn a_description_names_tangles_and_their_steps_say_which() {
    let table = "steps = 3\nprocedures = [\"tipple\", \"florz\"]\n\
                 lines = [[[0, 100], [128, 100]]]\n\
                 manual = [{ at = [60, 50], procedure = \"crescent-moon\" }]\n";
    let dump = crate::output::path_dump(&crate::motif::test_scene::scene("zentangle", table), 4);
    assert!(dump.contains("step-1-crescent-moon"), "{dump}");
    // The section a tangle filled is finished: the loop draws an
    // allowed tangle in the other half, and nothing more.
    assert!(dump.contains("step-2-tipple") || dump.contains("step-2-florz"));
    assert!(!dump.contains("step-3"));
    assert!(!dump.contains("-p"), "only the allowed tangles");
}
