//! `camera = …` of a `[[layers.vine]]`: where the vine is seen from — a
//! preset, an orbit round the plant given as two angles, or a camera
//! placed by hand — how each is read (with errors that name the field in
//! the table) and checked, and the orbit any of them amounts to, for the
//! studio to start turning from.
//!
//! An orbit is two plain numbers so that turning the camera round a vine
//! by dragging is a change of `turn` and `tilt`, with ranges a form can
//! show. The presets `"front"` and `"three-quarter"` are orbits
//! ([`Orbit::FRONT`], [`Orbit::THREE_QUARTER`]): `{ turn = 0, tilt = 0 }`
//! draws the same bytes as `"front"`, the three-quarter angles the
//! preset's drawing to the last bit of its direction.

use std::fmt;

use glam::DVec3;
use serde::de::value::{MapAccessDeserializer, StrDeserializer};
use serde::de::{self, Deserializer, MapAccess, Visitor};
use serde::{Deserialize, Serialize};

use super::vec3;
use crate::error::{Error, Result};
use crate::spec::validate::range;

/// Where a vine is seen from: a preset or an orbit, aimed at the middle of
/// the plant and its supports, or a camera placed by hand.
///
/// Written `"front"`, `{ turn = 30, tilt = 15 }` or `{ eye = [..], target
/// = [..] }`: a table with `turn` or `tilt` is an orbit (the other is 0
/// when left out), one with `eye` and `target` a placed camera, and a
/// table mixing the two is refused.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
pub enum CameraSpec {
    /// `"front"` (the default), `"three-quarter"` or `"below"`.
    Preset(CameraPreset),
    /// Round the middle of the plant and its supports, at two angles.
    Orbit(Orbit),
    /// A camera placed by hand.
    Placed {
        /// Where the eye is, `[x, y, z]` mm.
        eye: [f64; 3],
        /// The point looked at.
        target: [f64; 3],
        /// Which way is up in the picture (default `[0, 1, 0]`).
        up: [f64; 3],
        /// Vertical field of view in degrees (1–170) for a perspective
        /// camera; without it the camera is orthographic.
        #[serde(skip_serializing_if = "Option::is_none")]
        perspective: Option<f64>,
    },
}

/// The camera presets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CameraPreset {
    /// Orthographic, from +z: x right, y up ([`Orbit::FRONT`]).
    Front,
    /// Orthographic, from the front right and a little above: from the
    /// direction (0.8, 0.45, 1) ([`Orbit::THREE_QUARTER`]).
    ThreeQuarter,
    /// Perspective, from near the ground in front, looking up the vine.
    Below,
}

/// A camera circling the middle of a vine (the middle of the box holding
/// the plant and its supports), `camera = { turn = 30, tilt = 15 }`.
///
/// It looks from the front direction (+z) turned about the vertical (+y)
/// by `turn`, then raised above the horizontal by `tilt`; up in the picture
/// is up in the world. Orthographic, it stands 2 × the size of the box (its
/// diagonal) from the middle, as the presets do. In perspective it stands
/// where the sphere round the box (diameter: the size) just fits the
/// vertical field of view: ½ size / sin(½ fov); a wide field of view brings
/// the eye close and makes the near parts large.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Orbit {
    /// Degrees about the vertical from the front, positive towards +x
    /// (the three-quarter view is a positive turn), −360–360: a whole
    /// turn either way, so that a drag passes ±180° without a jump
    /// (default 0).
    pub turn: f64,
    /// Degrees above the horizontal, positive from above, −89–89: never
    /// straight down or up, where up in the picture would be undefined
    /// (default 0).
    pub tilt: f64,
    /// Vertical field of view in degrees (1–170) for a perspective
    /// camera; without it the camera is orthographic.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub perspective: Option<f64>,
}

/// The greatest `tilt`, degrees either way.
const MAX_TILT: f64 = 89.0;

/// The greatest `turn`, degrees either way.
const MAX_TURN: f64 = 360.0;

/// How far (as a unit vector) a placed camera's picture x may lie from the
/// orbit's for [`CameraSpec::orbit`] to call them the same view.
const SAME_VIEW: f64 = 1e-9;

impl Orbit {
    /// The `"front"` preset: straight from +z.
    pub const FRONT: Orbit = Orbit {
        turn: 0.0,
        tilt: 0.0,
        perspective: None,
    };

    /// The `"three-quarter"` preset: from the direction (0.8, 0.45, 1),
    /// turned atan(0.8) ≈ 38.66° and tilted atan(0.45 / √1.64) ≈ 19.36°.
    /// These angles give that direction to the last bit only, so their
    /// drawing matches the preset's up to where that bit changes which of
    /// two nearly equal points the simplification keeps (on a pole's
    /// rim: a tenth of a millimetre along it); the preset keeps its own
    /// direction, so drawings made with it do not change.
    pub const THREE_QUARTER: Orbit = Orbit {
        turn: 38.659_808_254_090_095,
        tilt: 19.361_014_406_459_47,
        perspective: None,
    };

    /// The unit vector from the middle of the vine towards the eye.
    pub fn direction(&self) -> DVec3 {
        let (turn, tilt) = (self.turn.to_radians(), self.tilt.to_radians());
        DVec3::new(tilt.cos() * turn.sin(), tilt.sin(), tilt.cos() * turn.cos())
    }

    /// The orthographic orbit seeing the vine from `direction` (from the
    /// middle towards the eye), with `turn` in −180–180; None when it is
    /// zero, not finite, or steeper than ±89°.
    pub fn towards(direction: DVec3) -> Option<Orbit> {
        let level = direction.x.hypot(direction.z);
        let orbit = Orbit {
            turn: direction.x.atan2(direction.z).to_degrees(),
            tilt: direction.y.atan2(level).to_degrees(),
            perspective: None,
        };
        (level > 0.0 && orbit.turn.is_finite() && orbit.tilt.abs() <= MAX_TILT).then_some(orbit)
    }
}

impl Default for CameraSpec {
    fn default() -> Self {
        CameraSpec::Preset(CameraPreset::Front)
    }
}

impl CameraPreset {
    /// The orbit this preset is; None for `"below"`, which looks from a
    /// point near the ground rather than round the middle.
    pub fn orbit(self) -> Option<Orbit> {
        match self {
            CameraPreset::Front => Some(Orbit::FRONT),
            CameraPreset::ThreeQuarter => Some(Orbit::THREE_QUARTER),
            CameraPreset::Below => None,
        }
    }
}

impl CameraSpec {
    pub(super) fn is_front(&self) -> bool {
        *self == CameraSpec::default()
    }

    /// The orbit that draws what this camera draws, to start turning it
    /// from: an orbit itself; `"front"` (exactly) and `"three-quarter"`
    /// (to the last bit: see [`Orbit::THREE_QUARTER`]); and a placed
    /// orthographic camera whose picture is upright (its `up` leans
    /// towards +y across the line of sight) and which looks no steeper
    /// than ±89° — the same picture up to rounding, since an orthographic
    /// picture fitted to the page depends only on the direction of sight
    /// and up, not on where the eye stands. None for `"below"`, a placed
    /// perspective camera, and any other placed camera.
    ///
    /// ```
    /// use moyo::spec::{CameraPreset, CameraSpec, Orbit};
    /// let front = CameraSpec::Preset(CameraPreset::Front).orbit();
    /// assert_eq!(front, Some(Orbit::FRONT));
    /// let side = CameraSpec::Placed {
    ///     eye: [500.0, 0.0, 0.0],
    ///     target: [0.0; 3],
    ///     up: [0.0, 1.0, 0.0],
    ///     perspective: None,
    /// };
    /// assert_eq!(side.orbit().map(|o| (o.turn, o.tilt)), Some((90.0, 0.0)));
    /// ```
    pub fn orbit(&self) -> Option<Orbit> {
        match *self {
            CameraSpec::Preset(preset) => preset.orbit(),
            CameraSpec::Orbit(orbit) => Some(orbit),
            CameraSpec::Placed {
                eye,
                target,
                up,
                perspective: None,
            } => {
                let back = DVec3::from_array(eye) - DVec3::from_array(target);
                let orbit = Orbit::towards(back)?;
                // Picture x as the camera makes it, for this `up` and for
                // the orbit's +y.
                let across = |up: DVec3| back.cross(up).normalize_or_zero();
                let turned = across(DVec3::from_array(up)) - across(DVec3::Y);
                (turned.length() < SAME_VIEW).then_some(orbit)
            }
            CameraSpec::Placed { .. } => None,
        }
    }

    /// Checks the numbers of a camera at `field`.
    pub(super) fn check(&self, field: &str) -> Result<()> {
        let perspective = |fov: Option<f64>| match fov {
            Some(fov) => range(&format!("{field}.perspective"), fov, 1.0, 170.0),
            None => Ok(()),
        };
        match *self {
            CameraSpec::Preset(_) => Ok(()),
            CameraSpec::Orbit(Orbit {
                turn,
                tilt,
                perspective: fov,
            }) => {
                range(&format!("{field}.turn"), turn, -MAX_TURN, MAX_TURN)?;
                range(&format!("{field}.tilt"), tilt, -MAX_TILT, MAX_TILT)?;
                perspective(fov)
            }
            CameraSpec::Placed {
                eye,
                target,
                up,
                perspective: fov,
            } => {
                let eye = vec3(&format!("{field}.eye"), eye)?;
                let target = vec3(&format!("{field}.target"), target)?;
                let up = vec3(&format!("{field}.up"), up)?;
                if eye.distance(target) < 1e-6 {
                    return Err(Error::invalid(
                        format!("{field}.target"),
                        "is where the eye is: look at another point",
                    ));
                }
                if up.cross(target - eye).length() < 1e-9 * up.length() * eye.distance(target) {
                    return Err(Error::invalid(
                        format!("{field}.up"),
                        "must not lie along the line of sight (nor be zero)",
                    ));
                }
                perspective(fov)
            }
        }
    }
}

/// Every key of a camera table, read before deciding which camera it is,
/// so that a wrong value is reported at its own key (an untagged enum
/// could only say that nothing matched).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraTable {
    eye: Option<[f64; 3]>,
    target: Option<[f64; 3]>,
    up: Option<[f64; 3]>,
    perspective: Option<f64>,
    turn: Option<f64>,
    tilt: Option<f64>,
}

impl CameraTable {
    fn camera<E: de::Error>(self) -> Result<CameraSpec, E> {
        let CameraTable {
            eye,
            target,
            up,
            perspective,
            turn,
            tilt,
        } = self;
        let orbit = turn.is_some() || tilt.is_some();
        let placed = eye.is_some() || target.is_some() || up.is_some();
        match (orbit, placed) {
            (true, true) => Err(E::custom(
                "mixes an orbit (`turn`, `tilt`) with a placed camera (`eye`, `target`, `up`): \
                 give one or the other",
            )),
            (true, false) => Ok(CameraSpec::Orbit(Orbit {
                turn: turn.unwrap_or(0.0),
                tilt: tilt.unwrap_or(0.0),
                perspective,
            })),
            (false, true) => Ok(CameraSpec::Placed {
                eye: eye.ok_or_else(|| E::missing_field("eye"))?,
                target: target.ok_or_else(|| E::missing_field("target"))?,
                up: up.unwrap_or([0.0, 1.0, 0.0]),
                perspective,
            }),
            (false, false) => Err(E::custom(
                "needs `turn` and `tilt` (an orbit round the vine) or `eye` and `target` \
                 (a placed camera)",
            )),
        }
    }
}

impl<'de> Deserialize<'de> for CameraSpec {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct CameraVisitor;

        impl<'de> Visitor<'de> for CameraVisitor {
            type Value = CameraSpec;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(
                    "a camera: \"front\", \"three-quarter\", \"below\", \
                     { turn = …, tilt = … } or { eye = [x, y, z], target = [x, y, z] }",
                )
            }

            fn visit_str<E: de::Error>(self, name: &str) -> Result<CameraSpec, E> {
                CameraPreset::deserialize(StrDeserializer::<E>::new(name)).map(CameraSpec::Preset)
            }

            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<CameraSpec, A::Error> {
                CameraTable::deserialize(MapAccessDeserializer::new(map))?.camera()
            }
        }

        deserializer.deserialize_any(CameraVisitor)
    }
}
