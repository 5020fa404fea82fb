//! Flowers, leaves and background tiles as vector motifs (docs/SPEC.md §1.5, §1.6).
//!
//! The source pasted bitmap images; moyo draws every motif as Bézier paths
//! so a plotter can draw it and a cutter can cut it. A motif is drawn once
//! in *motif units* and then placed with an affine map:
//!
//! * the drawing fills the box `[-0.5, 0.5] × [-0.5, 0.5]` (width and height
//!   1), so a placement scales it straight to its width and height in mm;
//! * it is **upright**: its top is towards −y (up the page, y points down);
//! * its [`Drawing::anchor`] is the point that sits on the tree: the centre
//!   of a flower, the stem end of a leaf (bottom centre, `(0, 0.5)`).
//!
//! A drawing has a closed **outline** — the shape that hides what lies
//! behind it and the line a cutter cuts — and **details**: inner lines
//! (petal edges, veins, stamens) drawn on top. [`Drawing::to_path`] joins
//! them into one path, outline first, with every subpath wound like the
//! outline (an open one as a fill closes it), so the non-zero area of the
//! whole path is exactly the area of the outline: details never punch
//! holes into the motif's fill or into what it hides.
//!
//! Randomness (`jitter`) comes from the caller's stream, so each placed
//! motif varies a little and the same seed gives the same drawing.

mod flowers;
mod leaves;
mod tiles;

use std::collections::BTreeMap;
use std::sync::{Arc, RwLock};

use kurbo::{Affine, BezPath, ParamCurveArea, Point, Shape};

use crate::error::{Error, Result, UserFile};
use crate::geom::clip::clip_stroke;
use crate::geom::density::GreyImage;
use crate::geom::mesh::TriMesh;
use crate::geom::offset::offset;
use crate::geom::region::{FillRule, Region};
use crate::geom::subpath::subpaths;
use crate::rng::RandomStream;
use crate::spec::{MotifKind, MotifRef};

/// A motif drawn in motif units (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Drawing {
    /// Closed subpaths bounding the motif.
    pub outline: BezPath,
    /// Inner lines, open or closed, inside the outline.
    pub details: BezPath,
    /// The point placed on the tree (flower centre, leaf stem end).
    pub anchor: Point,
    /// The motif's natural height divided by its width: a placement given
    /// only a width gets height `width × aspect`.
    pub aspect: f64,
}

/// How one motif instance is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotifParams {
    /// Petal (or lobe, needle, leaf) count; `None` is the kind's default.
    pub petals: Option<u32>,
    /// Random variation, 0 (none) – 1 (strong): petal lengths, angles.
    pub jitter: f64,
}

impl MotifParams {
    /// The kind's default count, no jitter.
    pub const DEFAULT: MotifParams = MotifParams {
        petals: None,
        jitter: 0.0,
    };
}

impl Default for MotifParams {
    fn default() -> Self {
        MotifParams::DEFAULT
    }
}

/// Draws a built-in motif. Draws numbers from `rng` only when
/// `params.jitter > 0`.
pub fn draw(kind: MotifKind, params: &MotifParams, rng: &mut RandomStream) -> Drawing {
    let d = match kind {
        MotifKind::Ume => flowers::ume(params, rng),
        MotifKind::Sakura => flowers::sakura(params, rng),
        MotifKind::Kiku => flowers::kiku(params, rng),
        MotifKind::Tsubaki => flowers::tsubaki(params, rng),
        MotifKind::Kikyo => flowers::kikyo(params, rng),
        MotifKind::Botan => flowers::botan(params, rng),
        MotifKind::Momiji => leaves::momiji(params, rng),
        MotifKind::Matsu => leaves::matsu(params, rng),
        MotifKind::Take => leaves::take(params, rng),
        MotifKind::Leaf => leaves::leaf(params, rng),
        MotifKind::Circle => tiles::circle(),
        MotifKind::Seigaiha => tiles::seigaiha(params),
        MotifKind::Kikko => tiles::kikko(params),
        MotifKind::Shippo => tiles::shippo(params),
    };
    d.normalised()
}

/// The motifs and paths a scene can draw: the built-in motifs, and the
/// user motifs and path files its caller loaded (generators never read
/// files).
///
/// A motif without jitter is the same drawing every time, so it is drawn
/// once and reused (drawing a many-petalled flower takes a union of its
/// petals: far more work than placing it). The cache sits behind a lock,
/// so one library serves generators on several threads.
#[derive(Debug, Default)]
pub struct Library {
    user: BTreeMap<String, Drawing>,
    paths: BTreeMap<String, BezPath>,
    images: BTreeMap<String, GreyImage>,
    meshes: BTreeMap<String, TriMesh>,
    plain: RwLock<Plain>,
}

/// Drawings without jitter, by kind and petal count.
type Plain = BTreeMap<(MotifKind, Option<u32>), Arc<Drawing>>;

impl Clone for Library {
    fn clone(&self) -> Library {
        Library {
            user: self.user.clone(),
            paths: self.paths.clone(),
            images: self.images.clone(),
            meshes: self.meshes.clone(),
            plain: RwLock::new(self.cached().clone()),
        }
    }
}

impl Library {
    /// Only the built-in motifs.
    pub fn new() -> Library {
        Library::default()
    }

    /// Adds a user motif under the name the description uses for it (the
    /// `svg` of a [`MotifRef::File`]).
    pub fn add_user(&mut self, name: impl Into<String>, drawing: Drawing) {
        self.user.insert(name.into(), drawing);
    }

    /// Adds the paths of a file under the name the description uses for
    /// it (the `svg` of a `[[layers.paths]]` table), in the file's mm.
    pub fn add_paths(&mut self, name: impl Into<String>, paths: BezPath) {
        self.paths.insert(name.into(), paths);
    }

    /// Adds a density image under the name the description uses for it
    /// (the `image` of a `[[layers.voronoi]]` table's sites).
    pub fn add_image(&mut self, name: impl Into<String>, image: GreyImage) {
        self.images.insert(name.into(), image);
    }

    /// Adds a closed triangle mesh under the name the description uses
    /// for it (the `obj` of a vine's mesh support), in the file's units.
    pub fn add_mesh(&mut self, name: impl Into<String>, mesh: TriMesh) {
        self.meshes.insert(name.into(), mesh);
    }

    /// The mesh loaded under `name`.
    ///
    /// # Errors
    /// [`Error::Motif`] when no mesh of that name was loaded.
    pub fn mesh(&self, name: &str) -> Result<&TriMesh> {
        self.meshes.get(name).ok_or_else(|| Error::Motif {
            kind: UserFile::Mesh,
            name: name.to_string(),
            message: "was not loaded (meshes are read by the caller of the generator)".into(),
            source: None,
        })
    }

    /// The image loaded under `name`.
    ///
    /// # Errors
    /// [`Error::Motif`] when no image of that name was loaded.
    pub fn image(&self, name: &str) -> Result<&GreyImage> {
        self.images.get(name).ok_or_else(|| Error::Motif {
            kind: UserFile::Image,
            name: name.to_string(),
            message: "was not loaded (images are read by the caller of the generator)".into(),
            source: None,
        })
    }

    /// The paths loaded under `name`.
    ///
    /// # Errors
    /// [`Error::Motif`] when no file of that name was loaded.
    pub fn paths(&self, name: &str) -> Result<&BezPath> {
        self.paths.get(name).ok_or_else(|| Error::Motif {
            kind: UserFile::Paths,
            name: name.to_string(),
            message: "was not loaded (path files are read by the caller of the generator)".into(),
            source: None,
        })
    }

    /// Draws the motif a description names. `rng` is used for jitter only.
    ///
    /// # Errors
    /// [`Error::Motif`] for a user motif that was not loaded.
    pub fn draw(&self, motif: &MotifRef, rng: &mut RandomStream) -> Result<Drawing> {
        let (kind, params) = match motif {
            MotifRef::Name(kind) => (*kind, MotifParams::DEFAULT),
            MotifRef::Built(b) => (
                b.kind,
                MotifParams {
                    petals: b.petals,
                    jitter: b.jitter,
                },
            ),
            MotifRef::File(f) => {
                return self.user.get(&f.svg).cloned().ok_or_else(|| Error::Motif {
                    kind: UserFile::Motif,
                    name: f.svg.clone(),
                    message: "was not loaded (user motifs are read by the caller of the generator)"
                        .into(),
                    source: None,
                })
            }
        };
        if params.jitter > 0.0 {
            return Ok(draw(kind, &params, rng));
        }
        let key = (kind, params.petals);
        if let Some(d) = self.cached().get(&key) {
            return Ok(Drawing::clone(d));
        }
        // Two threads may both draw a missing motif; they draw the same
        // thing, so whichever is stored last is as good as the first.
        let d = Arc::new(draw(kind, &params, rng));
        self.plain
            .write()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .insert(key, Arc::clone(&d));
        Ok(Drawing::clone(&d))
    }

    /// The cache of plain drawings. A panic elsewhere while the lock was
    /// held cannot leave a half-written drawing (entries are inserted
    /// whole), so a poisoned lock is still read.
    fn cached(&self) -> std::sync::RwLockReadGuard<'_, Plain> {
        self.plain
            .read()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }
}

/// Turns the paths of a user's drawing (page coordinates of any size) into
/// a motif: stretched into the unit box, anchored at its centre, with its
/// natural aspect. The outline is the union of the areas its closed
/// subpaths enclose; the details are the parts of all its lines strictly
/// inside that outline (1% of the motif's size in), so lines that trace
/// the outline are not drawn twice.
///
/// # Errors
/// A message when the drawing is empty or encloses no area.
pub(crate) fn user_drawing(paths: &[BezPath]) -> std::result::Result<Drawing, String> {
    let bounds = paths
        .iter()
        .filter(|p| !p.elements().is_empty())
        .map(Shape::bounding_box)
        .reduce(|a, b| a.union(b))
        .ok_or("the SVG has no paths")?;
    if !(bounds.width() > 0.0 && bounds.height() > 0.0) {
        return Err("the drawing has no width or no height".into());
    }
    let to_unit = Affine::scale_non_uniform(1.0 / bounds.width(), 1.0 / bounds.height())
        * Affine::translate(-bounds.center().to_vec2());
    let mut closed = BezPath::new();
    for p in paths {
        for sub in subpaths(p).filter(|s| s.is_closed()) {
            closed.extend((to_unit * sub.to_path()).elements().iter().copied());
        }
    }
    if closed.elements().is_empty() {
        return Err("it has no closed shape to use as its outline".into());
    }
    let outline = Region::new(closed, FillRule::NonZero)
        .map_err(|e| format!("its closed shapes are unusable: {e}"))?;
    if outline.is_empty() {
        return Err("it has no closed shape to use as its outline".into());
    }
    let inner = offset(&outline, -0.01, 1e-4).unwrap_or_else(|_| Region::empty());
    let mut details = BezPath::new();
    for p in paths {
        for part in clip_stroke(&(to_unit * p.clone()), &inner, 1e-4).inside {
            details.extend(part.elements().iter().copied());
        }
    }
    Ok(Drawing {
        outline: outline.into_path(),
        details,
        anchor: Point::ZERO,
        aspect: bounds.height() / bounds.width(),
    }
    .normalised())
}

impl Drawing {
    /// The motif as one path mapped by `placement`: the outline's
    /// subpaths, then the details (see the module docs for the winding).
    pub fn to_path(&self, placement: Affine) -> BezPath {
        let mut out = placement * self.outline.clone();
        for el in (placement * self.details.clone()).elements() {
            out.push(*el);
        }
        out
    }

    /// Winds every subpath like the first outline subpath (see the
    /// module docs).
    fn normalised(self) -> Drawing {
        let sign = subpaths(&self.outline)
            .next()
            .map_or(1.0, |s| s.to_path().area().signum());
        Drawing {
            outline: wound(&self.outline, sign),
            details: wound(&self.details, sign),
            anchor: self.anchor,
            aspect: self.aspect,
        }
    }
}

/// `path` with every subpath whose area has the other sign than `sign`
/// reversed. An open subpath's area is taken as a fill closes it, with a
/// straight chord back to its start.
fn wound(path: &BezPath, sign: f64) -> BezPath {
    let mut out = BezPath::new();
    for sub in subpaths(path) {
        let chord = if sub.is_closed() {
            0.0
        } else {
            kurbo::Line::new(sub.end(), sub.start()).signed_area()
        };
        let sub = sub.to_path();
        let sub = if (sub.area() + chord) * sign < 0.0 {
            sub.reverse_subpaths()
        } else {
            sub
        };
        out.extend(sub.elements().iter().copied());
    }
    out
}

#[cfg(test)]
mod tests;
