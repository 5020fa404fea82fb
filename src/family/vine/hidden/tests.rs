//! Tests of hidden-line removal: cuts, loops, tubes and the tree.

use super::*;
use crate::rng::Seed;
use std::f64::consts::TAU;

const STEP: f64 = 0.05;
const TOLERANCE: f64 = 1e-6;
const EPS: f64 = 1e-6;

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// Looking from +z at the origin, +y up: picture (x, −y).
fn front() -> Camera {
    Camera::orthographic(v(0.0, 0.0, 100.0), DVec3::ZERO, DVec3::Y)
}

fn front_perspective() -> Camera {
    Camera::perspective(v(0.0, 0.0, 100.0), DVec3::ZERO, DVec3::Y, 30.0)
}

/// The rectangle [x0, x1] × [y0, y1] at height `z`, as two triangles
/// sharing the diagonal from (x0, y0) to (x1, y1).
fn rect(x0: f64, x1: f64, y0: f64, y1: f64, z: f64) -> Vec<[DVec3; 3]> {
    let (a, b, c, d) = (v(x0, y0, z), v(x1, y0, z), v(x1, y1, z), v(x0, y1, z));
    vec![[a, b, c], [a, c, d]]
}

/// A closed cylinder wall of `radius` round the y axis from y0 to y1, in
/// `n` facets (corners at angle 0 and π: its contour seen from the front
/// is exactly x = ±radius).
fn cylinder(radius: f64, y0: f64, y1: f64, n: usize) -> Vec<[DVec3; 3]> {
    let at = |k: usize, y: f64| {
        let a = TAU * k as f64 / n as f64;
        v(radius * a.cos(), y, radius * a.sin())
    };
    (0..n)
        .flat_map(|k| {
            let (p, q) = ((at(k, y0), at(k + 1, y0)), (at(k, y1), at(k + 1, y1)));
            [[p.0, p.1, q.1], [p.0, q.1, q.0]]
        })
        .collect()
}

fn circle(radius: f64, z: f64, n: usize) -> Vec<DVec3> {
    (0..n)
        .map(|k| {
            let a = TAU * k as f64 / n as f64;
            v(radius * a.cos(), radius * a.sin(), z)
        })
        .collect()
}

/// x of the ends of each run.
fn ends_x(runs: &[Vec<DVec3>]) -> Vec<(f64, f64)> {
    runs.iter().map(|r| (r[0].x, r[r.len() - 1].x)).collect()
}

fn assert_cuts(runs: &[Vec<DVec3>], want: &[(f64, f64)], within: f64) {
    let got = ends_x(runs);
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g.0 - w.0).abs() < within && (g.1 - w.1).abs() < within,
            "{got:?} vs {want:?}"
        );
    }
}

#[test]
fn a_square_in_front_hides_exactly_the_middle_of_a_segment() {
    let square = Occluders::new(rect(-1.0, 1.0, -1.0, 1.0, 1.0));
    assert_eq!(square.len(), 2);
    let segment = [v(-3.0, 0.0, 0.0), v(3.0, 0.0, 0.0)];
    let runs = square.visible_runs(&front(), &segment, STEP, TOLERANCE, EPS);
    assert_cuts(&runs, &[(-3.0, -1.0), (1.0, 3.0)], 1e-4);
    // The runs keep the segment's own ends, and the cuts lie on the
    // visible side, within the tolerance.
    assert_eq!(runs[0][0], segment[0]);
    assert_eq!(runs[1][1], segment[1]);
    assert_eq!(runs[0].len(), 2);
    assert!(runs[0][1].x <= -1.0 + 1e-9 && runs[0][1].x > -1.0 - 2.0 * TOLERANCE);
    assert!(runs[1][0].x >= 1.0 - 1e-9 && runs[1][0].x < 1.0 + 2.0 * TOLERANCE);
    // Along the diagonal the two triangles share: hidden all the way
    // across, nothing shows through the seam.
    let diagonal = [v(-3.0, -3.0, 0.0), v(3.0, 3.0, 0.0)];
    let runs = square.visible_runs(&front(), &diagonal, STEP, TOLERANCE, EPS);
    assert_cuts(&runs, &[(-3.0, -1.0), (1.0, 3.0)], 1e-4);
    // In perspective from z = 100, the square's shadow on z = 0 is wider:
    // x = ±100 / 99.
    let runs = square.visible_runs(&front_perspective(), &segment, 1e-3, TOLERANCE, EPS);
    let edge = 100.0 / 99.0;
    assert_cuts(&runs, &[(-3.0, -edge), (edge, 3.0)], 1e-4);
    // Behind the segment, the square hides nothing.
    let behind = Occluders::new(rect(-1.0, 1.0, -1.0, 1.0, -1.0));
    let runs = behind.visible_runs(&front(), &segment, STEP, TOLERANCE, EPS);
    assert_eq!(runs, vec![segment.to_vec()]);
}

#[test]
fn vertices_inside_visible_runs_are_kept() {
    let square = Occluders::new(rect(-1.0, 1.0, -1.0, 1.0, 1.0));
    // A zigzag with vertices on both sides of the square and inside it.
    let zigzag = [
        v(-4.0, 0.0, 0.0),
        v(-3.0, 0.5, 0.0),
        v(-2.0, -0.5, 0.0),
        v(0.0, 0.5, 0.0),
        v(2.0, -0.5, 0.0),
        v(3.0, 0.5, 0.0),
    ];
    let runs = square.visible_runs(&front(), &zigzag, STEP, TOLERANCE, EPS);
    assert_eq!(runs.len(), 2);
    assert_eq!(&runs[0][..3], &zigzag[..3]);
    assert_eq!(runs[0].len(), 4);
    assert_eq!(runs[1].len(), 3);
    assert_eq!(&runs[1][1..], &zigzag[4..]);
    assert!((runs[0][3].x + 1.0).abs() < 1e-4 && (runs[1][0].x - 1.0).abs() < 1e-4);
}

#[test]
fn a_point_on_a_triangle_is_not_hidden_by_it() {
    let triangle = [v(0.0, 0.0, 0.0), v(4.0, 0.0, 1.0), v(0.0, 4.0, 2.0)];
    let occluders = Occluders::new(vec![triangle]);
    let on = (triangle[0] + triangle[1] + triangle[2]) / 3.0;
    for camera in [front(), front_perspective()] {
        assert!(!occluders.hides(&camera, on, EPS));
        // Just behind it: hidden; just in front: not.
        assert!(occluders.hides(&camera, on - v(0.0, 0.0, 0.01), EPS));
        assert!(!occluders.hides(&camera, on + v(0.0, 0.0, 0.01), EPS));
        // Without eps, its own surface may hide it or not: no promise;
        // with an eps larger than the gap, the point behind shows.
        assert!(!occluders.hides(&camera, on - v(0.0, 0.0, 0.01), 0.1));
    }
    // An orthographic view sees along whole lines: a triangle behind its
    // eye still hides.
    let eye_side = Occluders::new(rect(-1.0, 1.0, -1.0, 1.0, 200.0));
    assert!(eye_side.hides(&front(), DVec3::ZERO, EPS));
    assert!(!eye_side.hides(&front_perspective(), DVec3::ZERO, EPS));
}

#[test]
fn a_polyline_wholly_visible_comes_back_unchanged() {
    let mut stream = Seed(5).stream();
    let polyline: Vec<DVec3> = (0..40)
        .map(|_| {
            v(
                stream.symmetric(10.0),
                stream.symmetric(10.0),
                stream.symmetric(1.0),
            )
        })
        .collect();
    // Behind the polyline, and nothing at all.
    let behind = Occluders::new(rect(-20.0, 20.0, -20.0, 20.0, -5.0));
    for occluders in [behind, Occluders::new(Vec::new())] {
        for camera in [front(), front_perspective()] {
            let runs = occluders.visible_runs(&camera, &polyline, STEP, TOLERANCE, EPS);
            assert_eq!(runs, vec![polyline.clone()]);
        }
    }
    assert!(Occluders::new(Vec::new()).is_empty());
    // Fewer than two points: nothing to draw.
    let none = Occluders::default();
    assert!(none
        .visible_runs(&front(), &polyline[..1], STEP, TOLERANCE, EPS)
        .is_empty());
    assert!(none
        .visible_runs(&front(), &[], STEP, TOLERANCE, EPS)
        .is_empty());
    assert!(none
        .visible_loop_runs(&front(), &[], STEP, TOLERANCE, EPS)
        .is_empty());
}

#[test]
fn a_cylinder_hides_a_line_behind_it_and_not_one_in_front() {
    let pole = Occluders::new(cylinder(1.0, -5.0, 5.0, 64));
    let behind = [v(-4.0, 0.0, -3.0), v(4.0, 0.0, -3.0)];
    let runs = pole.visible_runs(&front(), &behind, STEP, TOLERANCE, EPS);
    assert_cuts(&runs, &[(-4.0, -1.0), (1.0, 4.0)], 1e-4);
    let in_front = [v(-4.0, 0.0, 3.0), v(4.0, 0.0, 3.0)];
    let runs = pole.visible_runs(&front(), &in_front, STEP, TOLERANCE, EPS);
    assert_eq!(runs, vec![in_front.to_vec()]);
    // A line through the pole, across its middle: the front half of the
    // wall hides it from where it enters the wall to where it leaves.
    let through = [v(-4.0, 0.5, 0.0), v(4.0, 0.5, 0.0)];
    let runs = pole.visible_runs(&front(), &through, STEP, TOLERANCE, EPS);
    assert_cuts(&runs, &[(-4.0, -1.0), (1.0, 4.0)], 1e-4);
}

#[test]
fn the_silhouette_of_a_straight_tube_seen_from_the_front() {
    let axis: Vec<DVec3> = (0..=10).map(|k| v(0.0, k as f64 - 5.0, 0.0)).collect();
    let (left, right) = tube_silhouette(&front(), &axis, 1.0);
    assert_eq!((left.len(), right.len()), (axis.len(), axis.len()));
    for ((l, r), a) in left.iter().zip(&right).zip(&axis) {
        // Up the page, left is towards smaller x.
        assert!((*l - (*a - DVec3::X)).length() < 1e-12, "{l:?}");
        assert!((*r - (*a + DVec3::X)).length() < 1e-12, "{r:?}");
    }
    // Its contour lines lie on its own wall and are not hidden by it.
    let pole = Occluders::new(cylinder(1.0, -5.0, 5.0, 64));
    for line in [&left, &right] {
        let runs = pole.visible_runs(&front(), line, STEP, TOLERANCE, EPS);
        assert_eq!(runs, vec![line.clone()]);
    }
    // In perspective the contour lies on the near side, still at ±1 in x
    // from the axis (to first order) and seen.
    let camera = front_perspective();
    let (left, right) = tube_silhouette(&camera, &axis, 1.0);
    for (l, r) in left.iter().zip(&right) {
        assert!(l.x < -0.99 && r.x > 0.99);
        assert!(l.is_finite() && r.is_finite());
    }
}

#[test]
fn tube_silhouettes_stay_continuous_where_the_axis_turns_along_the_view() {
    // Straight at the viewer, then a helix round the view axis, then a
    // hairpin back along itself: nothing NaN, no jump from side to side.
    let mut axis = vec![v(0.0, 0.0, -3.0), v(0.0, 0.0, -2.0), v(0.0, 0.0, -1.0)];
    axis.extend((0..=40).map(|k| {
        let a = k as f64 * 0.3;
        v(a.cos() - 1.0, a.sin(), a * 0.2)
    }));
    let last = *axis.last().unwrap();
    axis.push(last + v(1.0, 0.0, 0.0));
    axis.push(last);
    for camera in [front(), front_perspective()] {
        let (left, _) = tube_silhouette(&camera, &axis, 0.5);
        let s: Vec<DVec3> = left
            .iter()
            .zip(&axis)
            .map(|(l, a)| (*l - *a) / 0.5)
            .collect();
        for pair in s.windows(2) {
            assert!(pair[1].is_finite() && (pair[1].length() - 1.0).abs() < 1e-9);
            assert!(pair[0].dot(pair[1]) >= 0.0, "{pair:?}");
        }
        // The first points, seen end on, borrow the first proper side.
        assert!((s[0] - s[2]).length() < 1e-12);
    }
    // An axis seen wholly end on, or a single point: picture x.
    let end_on = [v(0.0, 0.0, 0.0), v(0.0, 0.0, -1.0)];
    let (left, right) = tube_silhouette(&front(), &end_on, 2.0);
    assert_eq!(left, vec![v(2.0, 0.0, 0.0), v(2.0, 0.0, -1.0)]);
    assert_eq!(right[0], v(-2.0, 0.0, 0.0));
    let (left, _) = tube_silhouette(&front(), &end_on[..1], 2.0);
    assert_eq!(left, vec![v(2.0, 0.0, 0.0)]);
    assert_eq!(tube_silhouette(&front(), &[], 1.0), (vec![], vec![]));
}

#[test]
fn loops_partly_hidden_do_not_break_at_their_start() {
    let ring = circle(2.0, 0.0, 90);
    let left_square = rect(-3.0, -1.5, -3.0, 3.0, 1.0);
    let right_square = rect(1.5, 3.0, -3.0, 3.0, 1.0);
    let camera = front();
    // Wholly visible: one run, closed, the ring as it is.
    let runs = Occluders::default().visible_loop_runs(&camera, &ring, STEP, TOLERANCE, EPS);
    assert_eq!(runs.len(), 1);
    assert_eq!(&runs[0][..90], &ring[..]);
    assert_eq!(runs[0][90], ring[0]);
    // A ring given closed is not closed again.
    let mut closed = ring.clone();
    closed.push(ring[0]);
    let again = Occluders::default().visible_loop_runs(&camera, &closed, STEP, TOLERANCE, EPS);
    assert_eq!(again, runs);

    // Hidden on the left: one run through the start (2, 0), from the cut
    // below to the cut above (the ring turns anticlockwise in the model).
    let left = Occluders::new(left_square.clone());
    let runs = left.visible_loop_runs(&camera, &ring, STEP, TOLERANCE, EPS);
    assert_eq!(runs.len(), 1, "{:?}", ends_x(&runs));
    let run = &runs[0];
    let (first, last) = (run[0], run[run.len() - 1]);
    assert!((first.x + 1.5).abs() < 1e-4 && first.y < 0.0, "{first:?}");
    assert!((last.x + 1.5).abs() < 1e-4 && last.y > 0.0, "{last:?}");
    assert_eq!(run.iter().filter(|&&p| p == ring[0]).count(), 1);
    assert!(run.iter().all(|p| p.x > -1.5 - 1e-4));

    // Hidden at the start: one run from cut to cut, the ring's order.
    let right = Occluders::new(right_square.clone());
    let runs = right.visible_loop_runs(&camera, &ring, STEP, TOLERANCE, EPS);
    assert_eq!(runs.len(), 1);
    let run = &runs[0];
    assert!((run[0].x - 1.5).abs() < 1e-4 && run[0].y > 0.0);
    assert!((run[run.len() - 1].x - 1.5).abs() < 1e-4 && run[run.len() - 1].y < 0.0);

    // Both: two runs, the lower one (through angle 3π/2) after the upper.
    let both = Occluders::new([left_square, right_square].concat());
    let runs = both.visible_loop_runs(&camera, &ring, STEP, TOLERANCE, EPS);
    assert_cuts(&runs, &[(1.5, -1.5), (-1.5, 1.5)], 1e-4);
    assert!(runs[0][1].y > 0.0 && runs[1][1].y < 0.0);
}

#[test]
fn the_tree_agrees_with_testing_every_triangle() {
    let mut stream = Seed(3).stream();
    let mut point = |spread: f64| {
        v(
            stream.symmetric(spread),
            stream.symmetric(spread),
            stream.symmetric(spread),
        )
    };
    let triangles: Vec<[DVec3; 3]> = (0..500)
        .map(|_| {
            let c = point(10.0);
            [c + point(1.5), c + point(1.5), c + point(1.5)]
        })
        .collect();
    let occluders = Occluders::new(triangles);
    let cameras = [
        Camera::orthographic(v(20.0, 30.0, 40.0), DVec3::ZERO, DVec3::Y),
        Camera::perspective(v(-25.0, 10.0, 30.0), v(1.0, 0.0, 0.0), DVec3::Y, 50.0),
        // Axis-aligned rays, parallel to the boxes' faces.
        front(),
    ];
    let (mut hidden, mut seen) = (0, 0);
    for camera in &cameras {
        for _ in 0..3000 {
            let p = point(12.0);
            let (origin, direction, t) = camera.ray_to(p);
            let from = if camera.is_perspective() {
                0.0
            } else {
                f64::NEG_INFINITY
            };
            let want = occluders.bvh.brute_force(origin, direction, from, t - EPS);
            let got = occluders.hides(camera, p, EPS);
            assert_eq!(got, want, "{p:?} {camera:?}");
            if got {
                hidden += 1;
            } else {
                seen += 1;
            }
        }
    }
    // The scene is dense enough for both answers to be common.
    assert!(hidden > 1000 && seen > 1000, "{hidden} {seen}");
}

#[test]
fn the_tree_is_balanced() {
    // Median splits: depth log2(n / 4) rounded up whatever the geometry,
    // here every triangle on one line (the worst case for a split at the
    // middle of the box).
    let n = 10_000;
    let triangles: Vec<[DVec3; 3]> = (0..n)
        .map(|k| {
            let x = (k as f64).powi(3);
            [v(x, 0.0, 0.0), v(x + 1.0, 0.0, 0.0), v(x, 1.0, 0.0)]
        })
        .collect();
    let bvh = Bvh::new(triangles);
    assert_eq!(bvh.len(), n);
    assert_eq!(bvh.depth(), (n as f64 / 4.0).log2().ceil() as usize);
    // Non-finite triangles are left out.
    let nan = v(f64::NAN, 0.0, 0.0);
    let occluders = Occluders::new(vec![
        [nan, DVec3::X, DVec3::Y],
        [DVec3::ZERO, DVec3::X, DVec3::Y],
    ]);
    assert_eq!(occluders.len(), 1);
}

#[test]
fn a_segment_reaching_behind_a_perspective_eye_is_seen_up_to_the_eye() {
    let camera = front_perspective();
    let segment = [v(0.5, 0.0, 0.0), v(0.5, 0.0, 120.0)];
    let runs = Occluders::default().visible_runs(&camera, &segment, 1e-3, TOLERANCE, EPS);
    assert_eq!(runs.len(), 1);
    assert_eq!(runs[0][0], segment[0]);
    let end = runs[0][runs[0].len() - 1];
    assert!(end.z < 100.0 && end.z > 99.999, "{end:?}");
    // Wholly behind: nothing.
    let behind = [v(0.5, 0.0, 110.0), v(0.5, 3.0, 120.0)];
    let runs = Occluders::default().visible_runs(&camera, &behind, 1e-3, TOLERANCE, EPS);
    assert!(runs.is_empty());
}
