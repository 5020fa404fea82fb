//! `[[layers.vine]]`: a twining vine (docs/SPEC.md §5, source 004) grown in 3D
//! round its supports and drawn through a camera with hidden lines.
//!
//! The growth fields are the thesis' parameters (表3.1) with its base
//! values (表4.1); one thesis unit is one millimetre in the model (y up),
//! and the camera fits the drawing into `fit` on the page.

mod camera;

pub use camera::{CameraPreset, CameraSpec, Orbit};

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::family::vine::engine;
use crate::family::vine::engine::{Shape, TriMesh, Twining, VineParams};
use crate::family::Family;
use crate::spec::validate::range;
use crate::spec::{one_stroke, FlowLine, MotifKind, MotifRef, Points};

/// A twining vine on a layer. A field left out takes its value from
/// [`VineSpec::default`], whose growth fields are
/// [`VineParams::default`]'s: the simulation's defaults are the
/// description's, written once.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct VineSpec {
    /// Id of the vine, unique in its layer (default `vine-K`). The plant's
    /// randomness is keyed by it alone, so the same table in two layers
    /// (each with its own `draw`) grows the same plant: the stem with one
    /// pen, the leaves with another.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
    /// Internode length l, mm (1–1000, default 60): the gap between leaves.
    pub internode: f64,
    /// Stem radius r, mm (0.05–100, default 2).
    pub radius: f64,
    /// `"left"` (the default: counter-clockwise seen from below) or
    /// `"right"` (clockwise seen from below).
    pub twining: Twining,
    /// Growth interval t: time between two points of the stem (0.1–1000,
    /// default 10); smaller grows faster, so the tip reaches further before
    /// it meets a support.
    pub interval: f64,
    /// Circumnutation angle θp of the tip from the vertical, degrees
    /// (1–80, default 18); larger spreads wider and coils tighter.
    pub angle: f64,
    /// Nodes above the cotyledons that do not circumnutate, U (0–20,
    /// default 1): more gives a longer untwined stem at the base.
    pub untwined: u32,
    /// Points per internode d (2–64, default 12; made even).
    pub steps: u32,
    /// Time the tip takes to turn once (1–100000, default 240: one turn
    /// per two internodes at t = 10).
    pub period: f64,
    /// Internodes grown in all, every apex together (1–2000, default 24).
    pub internodes: u32,
    /// Leaves per node: 0 (none), 1 (alternate, the default) or 2
    /// (opposite).
    pub leaves: u32,
    /// Cotyledons: 0, 1 (the default) or 2 leaves at the first node.
    pub cotyledons: u32,
    /// Leaf size γ, mm (0–1000, default 12): half the blade's length
    /// (the diagonal of the thesis' square leaf).
    pub leaf_size: f64,
    /// The direction the light comes from, `[x, y, z]` (default `[0, 0.5,
    /// 1]`: from the front and above): every leaf blade turns its face
    /// towards it, then droops 30° and rolls a little at random.
    #[serde(skip_serializing_if = "is_default_light")]
    pub light: [f64; 3],
    /// Where the seeds sprout, `[x, y, z]` mm (y up; default one at the
    /// origin): one plant each, all alike but for chance, seen together
    /// (each hides the others' lines).
    #[serde(skip_serializing_if = "is_origin")]
    pub roots: Vec<[f64; 3]>,
    /// What the vines climb (default: one pole of radius 6, 400 tall, 20
    /// to the right of the first root); `supports = []` for none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub supports: Option<Vec<SupportSpec>>,
    /// Where the drawing is seen from (default `"front"`): a preset
    /// (`"front"`, `"three-quarter"`, `"below"`), an orbit round the middle
    /// of the plant and its supports (`{ turn = 30, tilt = 15 }`, degrees),
    /// or a camera placed by hand (`{ eye = [..], target = [..] }`); see
    /// [`CameraSpec`].
    #[serde(skip_serializing_if = "CameraSpec::is_front")]
    pub camera: CameraSpec,
    /// The box `[x0, y0, x1, y1]` (mm) the drawing is fitted into, aspect
    /// kept, centred (default: the page inside its margins).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fit: Option<[f64; 4]>,
    /// Draws the picture at this scale (page mm per model mm, 0.001–100)
    /// instead of as large as fits: centred across `fit` (or the page)
    /// and standing on its bottom edge. The panels of a parameter row
    /// given one scale compare, the ground on one line; an error names
    /// the scale that fits when the picture is too large for its box.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scale: Option<f64>,
    /// What this table draws (default all): `"stem"`, `"leaves"`,
    /// `"supports"`. Hidden lines are always removed against all of them.
    #[serde(skip_serializing_if = "is_all_parts")]
    pub draw: Vec<Part>,
    /// The leaf motif mapped onto each leaf blade (default `"leaf"`).
    #[serde(skip_serializing_if = "is_default_leaf")]
    pub leaf: MotifRef,
    /// Grown along a line on the page instead (a border): the vine winds
    /// over and under a rod laid along it, seen from the front, in page
    /// millimetres. Then `supports`, `roots`, `camera` and `fit` are not
    /// used.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub guide: Option<GuideSpec>,
}

/// The line a 2D vine follows, given one of three ways, and the rod laid
/// along it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GuideSpec {
    /// The line as points (mm, ≥ 2), from where the vine sprouts.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub points: Option<Points>,
    /// With `points`: a natural spline through them (default true), not
    /// straight lines.
    #[serde(default = "yes", skip_serializing_if = "Clone::clone")]
    pub smooth: bool,
    /// Or the first path of an SVG file (relative to the description), in
    /// its own millimetres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub svg: Option<String>,
    /// Or a region line of the scene's `[lines]` (the kimono flow).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub line: Option<FlowLine>,
    /// Radius of the rod along the line, mm (0.05–50, default 1).
    #[serde(default = "default_rod")]
    pub radius: f64,
}

fn yes() -> bool {
    true
}

fn default_rod() -> f64 {
    1.0
}

/// A part of the drawing of a vine.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Part {
    /// The stems: the outlines of their tubes.
    Stem,
    /// The leaves and their stalks.
    Leaves,
    /// The supports' outlines.
    Supports,
}

/// One support, `{ kind = "pole", … }`. Points are `[x, y, z]` mm, y up.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum SupportSpec {
    /// A capped cylinder from `from` to `to`.
    Pole {
        /// One end (the foot).
        from: [f64; 3],
        /// The other end.
        to: [f64; 3],
        /// Radius, mm (0.1–1000).
        radius: f64,
    },
    /// A vertical pole with a horizontal arm (along x) across it.
    Cross {
        /// The foot of the pole.
        at: [f64; 3],
        /// Height of the pole, mm.
        height: f64,
        /// Height of the arm above the foot (default 0.7 × height).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        arm: Option<f64>,
        /// Length of the arm, mm.
        span: f64,
        /// Radius of both, mm.
        radius: f64,
    },
    /// A vertical pole with a bar (along x) across its top.
    Tee {
        /// The foot of the pole.
        at: [f64; 3],
        /// Height of the pole, mm.
        height: f64,
        /// Length of the bar, mm.
        span: f64,
        /// Radius of both, mm.
        radius: f64,
    },
    /// A lattice fence in the x–y plane: `posts` upright, `rails` across.
    Fence {
        /// Its lower left corner.
        at: [f64; 3],
        /// Width along x, mm.
        width: f64,
        /// Height, mm.
        height: f64,
        /// Upright posts (2–100).
        posts: u32,
        /// Horizontal rails (1–100).
        rails: u32,
        /// Radius of posts and rails, mm.
        radius: f64,
    },
    /// An axis-aligned box.
    Box {
        /// The corner with the smallest coordinates.
        min: [f64; 3],
        /// The opposite corner.
        max: [f64; 3],
    },
    /// A closed triangle mesh from a Wavefront OBJ file (relative to the
    /// description), y up: the stem winds round its surface, along its
    /// edges (a sculpture, a trellis modelled elsewhere).
    Mesh {
        /// The OBJ file.
        obj: String,
        /// Millimetres per unit of the file (0.001–1000, default 1).
        #[serde(default = "unit_scale")]
        scale: f64,
        /// Moved by this after scaling, `[x, y, z]` mm.
        #[serde(default)]
        offset: [f64; 3],
    },
}

fn unit_scale() -> f64 {
    1.0
}

fn is_origin(p: &Vec<[f64; 3]>) -> bool {
    *p == [VineParams::default().base.to_array()]
}
fn all_parts() -> Vec<Part> {
    vec![Part::Stem, Part::Leaves, Part::Supports]
}
fn is_all_parts(p: &Vec<Part>) -> bool {
    *p == all_parts()
}
fn default_leaf() -> MotifRef {
    MotifRef::Name(MotifKind::Leaf)
}
fn is_default_light(l: &[f64; 3]) -> bool {
    *l == VineParams::default().light.to_array()
}
fn is_default_leaf(m: &MotifRef) -> bool {
    *m == default_leaf()
}

impl Default for VineSpec {
    /// The thesis' base vine ([`VineParams::default`]) from the origin,
    /// round the default pole, seen from the front, every part drawn.
    fn default() -> Self {
        let p = VineParams::default();
        VineSpec {
            id: None,
            internode: p.internode,
            radius: p.radius,
            twining: p.twining,
            interval: p.interval,
            angle: p.angle,
            untwined: p.untwined,
            steps: p.steps,
            period: p.period,
            internodes: p.internodes,
            leaves: p.leaves,
            cotyledons: p.cotyledons,
            leaf_size: p.leaf_size,
            light: p.light.to_array(),
            roots: vec![p.base.to_array()],
            supports: None,
            camera: CameraSpec::default(),
            fit: None,
            scale: None,
            draw: all_parts(),
            leaf: default_leaf(),
            guide: None,
        }
    }
}

/// Coordinates of the model stay within this many mm of the origin.
const MAX_MODEL: f64 = 1e5;

pub(super) fn vec3(field: &str, p: [f64; 3]) -> Result<DVec3> {
    for v in p {
        if !(v.is_finite() && v.abs() <= MAX_MODEL) {
            return Err(Error::invalid(
                field,
                format!("must be [x, y, z] within ±{MAX_MODEL} mm, got {v}"),
            ));
        }
    }
    Ok(DVec3::from_array(p))
}

fn length(field: &str, v: f64) -> Result<f64> {
    range(field, v, 0.1, MAX_MODEL).map(|()| v)
}

impl VineSpec {
    /// The simulation's parameters for the plant from `root`.
    pub fn params(&self, root: [f64; 3]) -> VineParams {
        VineParams {
            internode: self.internode,
            radius: self.radius,
            twining: self.twining,
            interval: self.interval,
            angle: self.angle,
            untwined: self.untwined,
            steps: self.steps,
            period: self.period,
            internodes: self.internodes,
            leaves: self.leaves,
            cotyledons: self.cotyledons,
            leaf_size: self.leaf_size,
            base: DVec3::from_array(root),
            droop: true,
            light: DVec3::from_array(self.light),
        }
    }

    /// The supports as shapes, with errors at `f.supports[i].…`; `mesh`
    /// gives the mesh of an OBJ file by name (generators never read files).
    ///
    /// # Errors
    /// [`Error::Invalid`] for a size out of range or a degenerate shape;
    /// what `mesh` gives for a file.
    pub fn shapes(&self, f: &str, mesh: &dyn Fn(&str) -> Result<TriMesh>) -> Result<Vec<Shape>> {
        let Some(supports) = &self.supports else {
            let root = self.roots.first().copied().unwrap_or_default();
            let foot = DVec3::from_array(root) + DVec3::new(20.0, 0.0, 0.0);
            return Ok(vec![Shape::Pole {
                base: foot,
                top: foot + DVec3::new(0.0, 400.0, 0.0),
                radius: 6.0,
            }]);
        };
        if supports.len() > 1000 {
            return Err(Error::invalid(
                format!("{f}.supports"),
                "at most 1000 supports",
            ));
        }
        let mut shapes = Vec::new();
        for (i, s) in supports.iter().enumerate() {
            let g = format!("{f}.supports[{i}]");
            let field = |name: &str| format!("{g}.{name}");
            match s {
                SupportSpec::Pole { from, to, radius } => {
                    let base = vec3(&field("from"), *from)?;
                    let top = vec3(&field("to"), *to)?;
                    if base.distance(top) < 0.1 {
                        return Err(Error::invalid(
                            field("to"),
                            "is where `from` is: a pole needs a length",
                        ));
                    }
                    let radius = length(&field("radius"), *radius)?;
                    shapes.push(Shape::Pole { base, top, radius });
                }
                SupportSpec::Cross {
                    at,
                    height,
                    arm,
                    span,
                    radius,
                } => {
                    let height = length(&field("height"), *height)?;
                    let arm = match arm {
                        Some(a) => range(&field("arm"), *a, 0.0, height).map(|()| *a)?,
                        None => 0.7 * height,
                    };
                    shapes.extend(engine::cross(
                        vec3(&field("at"), *at)?,
                        height,
                        arm,
                        length(&field("span"), *span)?,
                        length(&field("radius"), *radius)?,
                    ));
                }
                SupportSpec::Tee {
                    at,
                    height,
                    span,
                    radius,
                } => shapes.extend(engine::tee(
                    vec3(&field("at"), *at)?,
                    length(&field("height"), *height)?,
                    length(&field("span"), *span)?,
                    length(&field("radius"), *radius)?,
                )),
                SupportSpec::Fence {
                    at,
                    width,
                    height,
                    posts,
                    rails,
                    radius,
                } => {
                    range(&field("posts"), *posts, 2, 100)?;
                    range(&field("rails"), *rails, 1, 100)?;
                    shapes.extend(engine::fence(
                        vec3(&field("at"), *at)?,
                        length(&field("width"), *width)?,
                        length(&field("height"), *height)?,
                        *posts,
                        *rails,
                        length(&field("radius"), *radius)?,
                    ));
                }
                SupportSpec::Box { min, max } => {
                    let min = vec3(&field("min"), *min)?;
                    let max = vec3(&field("max"), *max)?;
                    if (max - min).min_element() < 0.1 {
                        return Err(Error::invalid(
                            field("max"),
                            "must be above `min` in x, y and z (by 0.1 mm at least)",
                        ));
                    }
                    shapes.push(Shape::Block { min, max });
                }
                SupportSpec::Mesh { obj, scale, offset } => {
                    if obj.trim().is_empty() {
                        return Err(Error::invalid(field("obj"), "needs a file name"));
                    }
                    range(&field("scale"), *scale, 0.001, 1000.0)?;
                    let offset = vec3(&field("offset"), *offset)?;
                    shapes.push(Shape::Mesh(mesh(obj)?.transformed(*scale, offset)));
                }
            }
        }
        Ok(shapes)
    }
}

impl Family for VineSpec {
    #[cfg(feature = "studio")]
    fn gestures(&self) -> Option<&dyn crate::family::gesture::Gestures> {
        Some(self)
    }

    fn check(&self, f: &str) -> Result<()> {
        self.params([0.0; 3]).check(f)?;
        if let Some(g) = &self.guide {
            let field = format!("{f}.guide");
            one_stroke(&field, g.points.as_ref(), g.svg.as_deref(), g.line)?;
            range(&format!("{field}.radius"), g.radius, 0.05, 50.0)?;
            for (name, given) in [
                ("supports", self.supports.is_some()),
                ("roots", !is_origin(&self.roots)),
                ("camera", !self.camera.is_front()),
                ("fit", self.fit.is_some()),
                ("scale", self.scale.is_some()),
            ] {
                if given {
                    return Err(Error::invalid(
                        format!("{f}.{name}"),
                        "is not used by a vine along a guide, which winds round the guide on the page: leave it out",
                    ));
                }
            }
        }
        range(&format!("{f}.roots"), self.roots.len(), 1, 100)?;
        for (i, root) in self.roots.iter().enumerate() {
            vec3(&format!("{f}.roots[{i}]"), *root)?;
        }
        // Meshes are read later, by the caller; here only their numbers
        // are checked.
        self.shapes(f, &|_| Ok(TriMesh::default()))?;
        self.camera.check(&format!("{f}.camera"))?;
        if let Some([x0, y0, x1, y1]) = self.fit {
            let field = format!("{f}.fit");
            for v in [x0, y0, x1, y1] {
                range(&field, v, -1e6, 1e6)?;
            }
            if x1 <= x0 || y1 <= y0 {
                return Err(Error::invalid(
                    field,
                    "must be [x0, y0, x1, y1] with x1 > x0 and y1 > y0",
                ));
            }
        }
        if let Some(scale) = self.scale {
            range(&format!("{f}.scale"), scale, 0.001, 100.0)?;
        }
        if self.draw.is_empty() {
            return Err(Error::invalid(
                format!("{f}.draw"),
                "draws nothing: give one or more of \"stem\", \"leaves\", \"supports\"",
            ));
        }
        self.leaf.check(&format!("{f}.leaf"))
    }

    fn work(&self) -> usize {
        self.internodes as usize * self.roots.len()
    }

    fn motifs(&self) -> Vec<&MotifRef> {
        vec![&self.leaf]
    }

    fn path_files(&self) -> Vec<&str> {
        self.guide
            .as_ref()
            .and_then(|g| g.svg.as_deref())
            .into_iter()
            .collect()
    }

    fn mesh_files(&self) -> Vec<&str> {
        self.supports
            .iter()
            .flatten()
            .filter_map(|s| match s {
                SupportSpec::Mesh { obj, .. } => Some(obj.as_str()),
                _ => None,
            })
            .collect()
    }
}
