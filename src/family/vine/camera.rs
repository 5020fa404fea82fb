//! A camera for 3D line drawings: where a point of the model lands in the
//! picture, how far away it is, and the ray that sees it.
//!
//! **What it owns.** A [`Camera`] is an eye, a viewing direction and the
//! picture's axes (x right, y *down*, as on the page), orthographic or
//! perspective. Its picture is not fitted to anything: an orthographic
//! picture is in model units, a perspective one has the edge of the field
//! of view at ±1 vertically; the caller scales and translates the picture
//! onto the page. [`super::hidden`] asks it for the rays that decide what
//! hides what.
//!
//! **Cost.** Every query is a few dot products; nothing is allocated.

use glam::DVec3;
use kurbo::Point;

/// How close to the eye (along the viewing direction, model units) a point
/// of a perspective view may be and still be seen: nearer, its picture
/// would be arbitrarily large.
pub(super) const NEAR: f64 = 1e-6;

/// The narrowest and widest perspective fields of view, in degrees: 0° and
/// 180° have no picture.
const FOV_RANGE: (f64, f64) = (1e-3, 179.0);

/// An eye looking at a 3D model (see the [module docs](self)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Camera {
    eye: DVec3,
    /// Unit viewing direction.
    forward: DVec3,
    /// Unit picture x, perpendicular to `forward`.
    right: DVec3,
    /// Unit picture up (picture y is down, along −`up`).
    up: DVec3,
    /// For a perspective view, the picture distance of a point one unit
    /// off the axis at depth one: 1 / tan(fov / 2). None: orthographic.
    focal: Option<f64>,
}

impl Camera {
    /// Looking from `eye` at `target`, `up` up the picture. Orthographic:
    /// parallel rays along `target − eye`; the picture is in model units.
    ///
    /// Degenerate input does not panic nor give NaN: when `eye == target`
    /// the view is along −z (as from the front, +z towards the viewer);
    /// when `up` is zero or parallel to the view, up is +y, or, for a view
    /// along the y axis, the one of ±z that keeps +x to the right.
    pub(crate) fn orthographic(eye: DVec3, target: DVec3, up: DVec3) -> Camera {
        Camera::frame(eye, target, up, None)
    }

    /// Perspective from `eye` towards `target`, `up` up the picture, with a
    /// vertical field of view of `fov` degrees: the picture's edges at
    /// y = ±1 are `fov / 2` off the viewing direction (the scale of the
    /// picture does not matter: the caller fits it to the page). `fov` is
    /// clamped to [0.001°, 179°]; degenerate `eye`, `target` and `up` are
    /// handled as by [`Camera::orthographic`].
    pub(crate) fn perspective(eye: DVec3, target: DVec3, up: DVec3, fov: f64) -> Camera {
        // `clamp` keeps NaN: a NaN field of view falls back to 60°.
        let fov = if fov.is_nan() { 60.0 } else { fov };
        let half = fov.clamp(FOV_RANGE.0, FOV_RANGE.1).to_radians() / 2.0;
        Camera::frame(eye, target, up, Some(1.0 / half.tan()))
    }

    fn frame(eye: DVec3, target: DVec3, up: DVec3, focal: Option<f64>) -> Camera {
        let forward = (target - eye).try_normalize().unwrap_or(DVec3::NEG_Z);
        let across = forward.cross(up);
        let right = if across.length() > 1e-9 * up.length() {
            across.normalize()
        } else {
            // Looking down (−y), the far side (−z) is up the picture;
            // looking up, +z: either way +x stays to the right.
            let fallback = if forward.y.abs() > 0.9 {
                DVec3::new(0.0, 0.0, forward.y.signum())
            } else {
                DVec3::Y
            };
            forward.cross(fallback).normalize()
        };
        Camera {
            eye,
            forward,
            right,
            up: right.cross(forward),
            focal,
        }
    }

    /// Picture coordinates of `p`: x right, **y down** (the page's
    /// convention, so the caller only scales and translates), and its depth:
    /// its distance from the eye along the viewing direction, larger is
    /// further. None if a perspective view cannot see `p`: its depth is at
    /// most a tiny near distance (1e-6). An orthographic view sees
    /// everything; depths behind the eye are negative.
    pub(crate) fn project(&self, p: DVec3) -> Option<(Point, f64)> {
        let d = p - self.eye;
        let depth = self.depth(p);
        let (x, y) = (d.dot(self.right), -d.dot(self.up));
        match self.focal {
            None => Some((Point::new(x, y), depth)),
            Some(_) if depth <= NEAR => None,
            Some(f) => Some((Point::new(f * x / depth, f * y / depth), depth)),
        }
    }

    /// The ray that sees `p`: its origin, unit direction, and the parameter
    /// `t` at which it reaches `p` (`origin + t · direction == p`).
    ///
    /// Perspective: the origin is the eye and `t` the distance to `p` (a
    /// point at the eye gets the viewing direction and `t = 0`).
    /// Orthographic: the ray is a whole line, from `t = −∞`; its origin is
    /// `p` moved onto the plane through the eye across the view, so `t` is
    /// `p`'s depth, and anything on the line at a smaller `t` lies in front
    /// of `p`, even behind the eye.
    pub(crate) fn ray_to(&self, p: DVec3) -> (DVec3, DVec3, f64) {
        let d = p - self.eye;
        match self.focal {
            None => {
                let t = d.dot(self.forward);
                (p - t * self.forward, self.forward, t)
            }
            Some(_) => {
                let t = d.length();
                let direction = if t > 0.0 { d / t } else { self.forward };
                (self.eye, direction, t)
            }
        }
    }

    /// The unit direction from the eye towards `p`: the viewing direction
    /// for an orthographic view (and for `p` at the eye).
    pub(crate) fn looking_at(&self, p: DVec3) -> DVec3 {
        match self.focal {
            None => self.forward,
            Some(_) => (p - self.eye).try_normalize().unwrap_or(self.forward),
        }
    }

    /// The eye.
    #[cfg(test)]
    pub(crate) fn eye(&self) -> DVec3 {
        self.eye
    }

    /// Whether this is a perspective view.
    pub(crate) fn is_perspective(&self) -> bool {
        self.focal.is_some()
    }

    /// The distance of `p` from the eye along the viewing direction
    /// (negative behind the eye).
    pub(super) fn depth(&self, p: DVec3) -> f64 {
        (p - self.eye).dot(self.forward)
    }

    /// The unit direction of picture x in the model.
    pub(super) fn right(&self) -> DVec3 {
        self.right
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn front() -> Camera {
        Camera::orthographic(DVec3::new(0.0, 0.0, 100.0), DVec3::ZERO, DVec3::Y)
    }

    fn close(a: Point, b: Point) -> bool {
        a.distance(b) < 1e-12
    }

    #[test]
    fn orthographic_front_view_has_y_down() {
        let (at, depth) = front().project(DVec3::new(1.0, 2.0, 0.0)).unwrap();
        assert!(close(at, Point::new(1.0, -2.0)), "{at:?}");
        assert!((depth - 100.0).abs() < 1e-12);
        // Behind the eye is still seen, at a negative depth.
        let (_, behind) = front().project(DVec3::new(0.0, 0.0, 150.0)).unwrap();
        assert!((behind + 50.0).abs() < 1e-12);
        assert!(!front().is_perspective());
        assert_eq!(front().looking_at(DVec3::new(5.0, 5.0, 5.0)), DVec3::NEG_Z);
    }

    #[test]
    fn perspective_shrinks_with_distance() {
        let camera = Camera::perspective(DVec3::new(0.0, 0.0, 10.0), DVec3::ZERO, DVec3::Y, 90.0);
        assert!(camera.is_perspective());
        let (near, d1) = camera.project(DVec3::new(1.0, 1.0, 0.0)).unwrap();
        let (far, d2) = camera.project(DVec3::new(2.0, 2.0, -10.0)).unwrap();
        assert!((d1 - 10.0).abs() < 1e-12 && (d2 - 20.0).abs() < 1e-12);
        // Twice the offset twice as far: the same place; the same offset
        // twice as far: half as far from the centre.
        assert!(close(near, far), "{near:?} {far:?}");
        let (half, _) = camera.project(DVec3::new(1.0, 1.0, -10.0)).unwrap();
        assert!(close(half, Point::new(near.x / 2.0, near.y / 2.0)));
        assert!(near.x > 0.0 && near.y < 0.0);
        // With a 90° field of view, 45° off the axis is the picture's edge.
        let (edge, _) = camera.project(DVec3::new(0.0, 10.0, 0.0)).unwrap();
        assert!(close(edge, Point::new(0.0, -1.0)), "{edge:?}");
        // Not in front of the eye: no picture.
        assert!(camera.project(DVec3::new(0.0, 0.0, 10.0)).is_none());
        assert!(camera.project(DVec3::new(1.0, 0.0, 20.0)).is_none());
    }

    #[test]
    fn rays_reach_their_points() {
        let target = DVec3::new(1.0, -2.0, 0.5);
        let up = DVec3::new(0.3, 1.0, 0.1);
        let eye = DVec3::new(30.0, 40.0, 50.0);
        let cameras = [
            Camera::orthographic(eye, target, up),
            Camera::perspective(eye, target, up, 40.0),
        ];
        for camera in cameras {
            for p in [
                DVec3::new(3.0, -1.0, 2.0),
                target,
                DVec3::new(-7.0, 9.0, 1.0),
            ] {
                let (origin, direction, t) = camera.ray_to(p);
                assert!((origin + t * direction - p).length() < 1e-12);
                assert!((direction.length() - 1.0).abs() < 1e-12);
                assert!((direction - camera.looking_at(p)).length() < 1e-12);
                // t is the distance along the ray, as far as the eye is
                // concerned: the depth (orthographic) or the distance.
                let (_, depth) = camera.project(p).unwrap();
                let want = if camera.is_perspective() {
                    (p - eye).length()
                } else {
                    depth
                };
                assert!((t - want).abs() < 1e-12);
            }
            assert_eq!(camera.eye(), eye);
        }
    }

    #[test]
    fn degenerate_input_gives_finite_cameras() {
        let finite = |c: &Camera| {
            [c.forward, c.right, c.up].iter().all(|v| v.is_finite())
                && (c.right.length() - 1.0).abs() < 1e-12
                && (c.up.length() - 1.0).abs() < 1e-12
                && c.forward.dot(c.right).abs() < 1e-12
        };
        let p = DVec3::new(1.0, 2.0, 3.0);
        let o = DVec3::ZERO;
        let cameras = [
            // eye == target: looking along −z with +y up, as from the front.
            Camera::orthographic(o, o, DVec3::Y),
            Camera::perspective(p, p, DVec3::Y, 50.0),
            // up along the view, or zero.
            Camera::orthographic(DVec3::new(0.0, 0.0, 5.0), o, DVec3::Z),
            Camera::orthographic(DVec3::new(0.0, 0.0, 5.0), o, DVec3::ZERO),
            // looking down and up the y axis with +y up.
            Camera::orthographic(DVec3::new(0.0, 5.0, 0.0), o, DVec3::Y),
            Camera::perspective(DVec3::new(0.0, -5.0, 0.0), o, DVec3::Y, 0.0),
            Camera::perspective(p, o, p, f64::NAN),
            Camera::perspective(p, o, DVec3::Y, 400.0),
        ];
        for camera in &cameras {
            assert!(finite(camera), "{camera:?}");
            let (at, depth) = camera.project(DVec3::new(-0.5, 0.25, -1.0)).unwrap();
            assert!(at.is_finite() && depth.is_finite(), "{camera:?}");
            let (origin, direction, t) = camera.ray_to(camera.eye());
            assert!(origin.is_finite() && direction.is_finite() && t.is_finite());
        }
        // The fallbacks keep +x to the right.
        assert_eq!(
            cameras[0].project(DVec3::X).unwrap().0,
            Point::new(1.0, 0.0)
        );
        for camera in &cameras[2..6] {
            assert!(camera.right.dot(DVec3::X) > 0.99, "{camera:?}");
        }
    }
}
