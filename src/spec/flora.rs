//! The ornament parts of a description that several families share:
//! motifs by name or file, flowers and leaves on limbs (docs/SPEC.md §1.5), paint
//! and shading, and the final adjustment of single trees, flowers and
//! leaves by id (docs/SPEC.md §1, design step 4).
//!
//! Decisions where the source is silent:
//!
//! * Flowers and leaves belong to a **tree set**, not to a layer: a set is
//!   what the source calls a layer (one centre line, one tree kind), and a
//!   moyo layer may hold several sets.
//! * Brightness and opacity make the **preview fill colour**: the motif's
//!   `fill` is darkened or lightened by `brightness` and mixed with the
//!   white paper by `opacity` (what lies behind a motif is hidden by the
//!   plot stage, so mixing with the paper is what a viewer sees). For pens,
//!   `hatch` gives the motif its own hatch spacing.

use serde::{Deserialize, Serialize};

use super::validate::{point, range};
use crate::error::{Error, Result};
use crate::scene::traditional::Palette;
use crate::scene::Color;

/// A built-in vector motif (docs/SPEC.md §1.5): flowers, leaves, and shapes for
/// background stamps and tiles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MotifKind {
    /// 梅 plum blossom: five round petals, stamens.
    Ume,
    /// 桜 cherry blossom: five notched petals.
    Sakura,
    /// 菊 chrysanthemum: many narrow rayed petals.
    Kiku,
    /// 椿 camellia: five broad overlapping petals around a stamen cup.
    Tsubaki,
    /// 桔梗 bellflower: five pointed petals, star-shaped.
    Kikyo,
    /// 牡丹 peony: layered ruffled petals.
    Botan,
    /// 紅葉 maple leaf: seven pointed lobes.
    Momiji,
    /// 松 pine: a fan of needles.
    Matsu,
    /// 竹 bamboo leaves: a spray of long narrow leaves.
    Take,
    /// A generic pointed leaf with a midrib.
    Leaf,
    /// A plain circle (the default background stamp).
    Circle,
    /// 青海波 waves: concentric arcs (a background tile).
    Seigaiha,
    /// 亀甲 tortoise shell: a hexagon (a background tile).
    Kikko,
    /// 七宝 interlocking circles (a background tile).
    Shippo,
}

impl MotifKind {
    /// The flowers among the motifs.
    pub const FLOWERS: [MotifKind; 6] = [
        MotifKind::Ume,
        MotifKind::Sakura,
        MotifKind::Kiku,
        MotifKind::Tsubaki,
        MotifKind::Kikyo,
        MotifKind::Botan,
    ];

    /// Every built-in motif.
    pub const ALL: [MotifKind; 14] = [
        MotifKind::Ume,
        MotifKind::Sakura,
        MotifKind::Kiku,
        MotifKind::Tsubaki,
        MotifKind::Kikyo,
        MotifKind::Botan,
        MotifKind::Momiji,
        MotifKind::Matsu,
        MotifKind::Take,
        MotifKind::Leaf,
        MotifKind::Circle,
        MotifKind::Seigaiha,
        MotifKind::Kikko,
        MotifKind::Shippo,
    ];
}

/// A motif named in a description: `"ume"`, `{ kind = "kiku", petals = 24,
/// jitter = 0.2 }`, or a user motif `{ svg = "fan.svg" }` (a path relative
/// to the description file).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(
    untagged,
    expecting = "a motif: a name (ume, sakura, kiku, tsubaki, kikyo, botan, momiji, matsu, take, leaf, circle, seigaiha, kikko, shippo), { kind = \"…\", petals = N, jitter = J } or { svg = \"file.svg\" }"
)]
pub enum MotifRef {
    /// A built-in motif with its defaults.
    Name(MotifKind),
    /// A built-in motif with settings.
    Built(BuiltMotif),
    /// A motif drawn by the user.
    File(FileMotif),
}

/// A built-in motif with settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BuiltMotif {
    /// Which motif.
    pub kind: MotifKind,
    /// Petal, lobe, needle or leaf count (1–64); default: the motif's own.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub petals: Option<u32>,
    /// Random variation of each instance, 0–1.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub jitter: f64,
}

/// A user motif loaded from an SVG file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FileMotif {
    /// Path of the SVG file, relative to the description file.
    pub svg: String,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

impl MotifRef {
    /// The built-in kind, `None` for a user motif.
    pub fn kind(&self) -> Option<MotifKind> {
        match self {
            MotifRef::Name(k) => Some(*k),
            MotifRef::Built(b) => Some(b.kind),
            MotifRef::File(_) => None,
        }
    }

    pub(crate) fn check(&self, f: &str) -> Result<()> {
        match self {
            MotifRef::Name(_) => Ok(()),
            MotifRef::Built(b) => {
                if let Some(n) = b.petals {
                    range(&format!("{f}.petals"), n, 1, 64)?;
                }
                range(&format!("{f}.jitter"), b.jitter, 0.0, 1.0)
            }
            MotifRef::File(file) => {
                if file.svg.trim().is_empty() {
                    Err(Error::invalid(format!("{f}.svg"), "needs a file name"))
                } else {
                    Ok(())
                }
            }
        }
    }
}

/// How motifs are handed out to the trees of a set ([000 §4.6.1]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Assign {
    /// Type 1: on every tree the i-th flower gets motif `(i mod n) + 1`;
    /// leaves all use the first leaf motif.
    #[default]
    Type1,
    /// Type 2: every flower (and leaf) of tree k gets motif `(k mod n) + 1`.
    Type2,
}

/// Which flowers are drawn largest (docs/SPEC.md §1 "the main flower is the
/// largest").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MainLargest {
    /// All the same size.
    #[default]
    None,
    /// The first flower of each tree (at the trunk's top) is the largest;
    /// later ones shrink evenly to `smallest` × the size.
    Order,
    /// Flowers shrink with the layer's depth: × `smallest` per depth step
    /// behind the front.
    Depth,
}

/// Preview colour and pen treatment of motifs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PaintSpec {
    /// Fill colour of the preview, any colour or palette slot (default:
    /// none, outline only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fill: Option<String>,
    /// 0 (black) – 1 (as given) – 2 (white).
    #[serde(default = "one")]
    pub brightness: f64,
    /// 0 (paper white) – 1 (as given).
    #[serde(default = "one")]
    pub opacity: f64,
    /// Hatch the fill with lines this far apart (mm, 0.1–20) when
    /// plotting.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hatch: Option<f64>,
    /// Shade each shape in line, dense at one side and thinning away from
    /// it (default: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bokashi: Option<BokashiSpec>,
}

impl Default for PaintSpec {
    fn default() -> Self {
        PaintSpec {
            fill: None,
            brightness: 1.0,
            opacity: 1.0,
            hatch: None,
            bokashi: None,
        }
    }
}

/// Bokashi (暈し), the dyer's shading, drawn with one pen: lines inside a
/// shape, close together at the side the shading comes `from` and further
/// apart away from it, so the shape darkens towards that side.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BokashiSpec {
    /// Where the shading is densest.
    #[serde(default)]
    pub from: ShadeFrom,
    /// The gap between the dense side and the first line, mm (0.1–20).
    #[serde(default = "default_shade_spacing")]
    pub spacing: f64,
    /// Each gap is this many times the one before it (1–4; 1 is even
    /// hatching).
    #[serde(default = "default_shade_growth")]
    pub growth: f64,
    /// How far across the shape the shading reaches, as a fraction of the
    /// way from the dense side to the far side (0.05–1).
    #[serde(default = "default_shade_reach")]
    pub reach: f64,
}

impl Default for BokashiSpec {
    fn default() -> Self {
        BokashiSpec {
            from: ShadeFrom::default(),
            spacing: default_shade_spacing(),
            growth: default_shade_growth(),
            reach: default_shade_reach(),
        }
    }
}

impl BokashiSpec {
    fn check(&self, f: &str) -> Result<()> {
        range(&format!("{f}.spacing"), self.spacing, 0.1, 20.0)?;
        range(&format!("{f}.growth"), self.growth, 1.0, 4.0)?;
        range(&format!("{f}.reach"), self.reach, 0.05, 1.0)
    }
}

fn default_shade_spacing() -> f64 {
    0.4
}

fn default_shade_growth() -> f64 {
    1.4
}

fn default_shade_reach() -> f64 {
    0.6
}

/// The side of a shape a [`BokashiSpec`] shades from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ShadeFrom {
    /// The outline: lines follow it inwards (the shape's contours), as
    /// dye gathers at a petal's rim.
    #[default]
    Edge,
    /// The shape's deepest point: contours around it, dense at the middle.
    #[serde(alias = "center")]
    Centre,
    /// The top of the page: straight lines across, dense at the top.
    Top,
    /// The bottom of the page.
    Bottom,
    /// The left of the page: upright lines.
    Left,
    /// The right of the page.
    Right,
}

impl PaintSpec {
    /// True when every field has its default.
    pub fn is_default(&self) -> bool {
        *self == PaintSpec::default()
    }

    /// The preview fill colour after brightness and opacity, `@n` taken
    /// from `palette`.
    pub fn color(&self, palette: &Palette) -> Option<Color> {
        let c = Color::parse_in(self.fill.as_deref()?, palette)?;
        Some(c.shaded(self.brightness).over_white(self.opacity))
    }

    pub(crate) fn check(&self, f: &str) -> Result<()> {
        if let Some(fill) = &self.fill {
            if !Color::is_valid(fill) {
                return Err(super::validate::bad_color(&format!("{f}.fill"), fill));
            }
        }
        range(&format!("{f}.brightness"), self.brightness, 0.0, 2.0)?;
        range(&format!("{f}.opacity"), self.opacity, 0.0, 1.0)?;
        if let Some(h) = self.hatch {
            range(&format!("{f}.hatch"), h, 0.1, 20.0)?;
        }
        if let Some(b) = &self.bokashi {
            b.check(&format!("{f}.bokashi"))?;
        }
        Ok(())
    }
}

fn one() -> f64 {
    1.0
}

/// Where flowers grow on a tree.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FlowerSites {
    /// At the tip of every limb (trunk tip first).
    #[default]
    Tips,
    /// At every vertex except the root.
    Vertices,
}

/// Flowers of a tree set (docs/SPEC.md §1.5).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlowerSpec {
    /// One to five motifs.
    pub motifs: Vec<MotifRef>,
    /// Type 1 or type 2 assignment (also used by the set's leaves).
    #[serde(default)]
    pub assign: Assign,
    /// Where flowers sit.
    #[serde(default)]
    pub at: FlowerSites,
    /// Width in mm (0.5–500).
    #[serde(default = "default_flower_size")]
    pub width: f64,
    /// Height in mm (0.5–500); default: the width × the motif's own
    /// height-to-width ratio.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
    /// Random turn of each flower, degrees (0–180); flowers stay upright
    /// when 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub turn: f64,
    /// Which flowers are largest.
    #[serde(default)]
    pub main_largest: MainLargest,
    /// The smallest size relative to the main flower (0.05–1).
    #[serde(default = "default_smallest")]
    pub smallest: f64,
    /// Preview colour and hatching.
    #[serde(default, skip_serializing_if = "PaintSpec::is_default")]
    pub paint: PaintSpec,
}

fn default_flower_size() -> f64 {
    12.0
}

fn default_smallest() -> f64 {
    0.6
}

/// Leaf 1: a ring of leaves around every flower.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LeafRingSpec {
    /// One to five motifs (type 1 uses the first only).
    pub motifs: Vec<MotifRef>,
    /// Leaves per flower (0–8), evenly around it, the first pointing up.
    #[serde(default = "default_ring_count")]
    pub count: u32,
    /// Distance from the flower's centre to each leaf's stem end, mm
    /// (0–500).
    #[serde(default = "default_spacing")]
    pub spacing: f64,
    /// Width in mm (0.5–500).
    #[serde(default = "default_leaf_width")]
    pub width: f64,
    /// Height in mm; default: from the motif's own proportions.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
    /// Preview colour and hatching.
    #[serde(default, skip_serializing_if = "PaintSpec::is_default")]
    pub paint: PaintSpec,
}

fn default_ring_count() -> u32 {
    3
}

fn default_spacing() -> f64 {
    4.0
}

fn default_leaf_width() -> f64 {
    5.0
}

/// Leaf 2: a leaf at every branch joint.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointLeafSpec {
    /// One to five motifs (type 1 uses the first only).
    pub motifs: Vec<MotifRef>,
    /// Width in mm (0.5–500).
    #[serde(default = "default_leaf_width")]
    pub width: f64,
    /// Height in mm; default: from the motif's own proportions.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
    /// Angle between the leaf and its branch, degrees (−180–180); the
    /// leaf leans away from the parent limb.
    #[serde(default = "default_joint_angle")]
    pub angle: f64,
    /// Preview colour and hatching.
    #[serde(default, skip_serializing_if = "PaintSpec::is_default")]
    pub paint: PaintSpec,
}

fn default_joint_angle() -> f64 {
    35.0
}

/// Leaves of a tree set.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LeavesSpec {
    /// Leaf 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ring: Option<LeafRingSpec>,
    /// Leaf 2.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub joints: Option<JointLeafSpec>,
}

/// Motifs on an L-system (flowers or leaves): at the tip of every limb,
/// or wherever the turtle met `symbol`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OrnamentSpec {
    /// One to five motifs: the i-th ornament gets motif i mod n.
    pub motifs: Vec<MotifRef>,
    /// One character: an ornament wherever the turtle meets it (e.g. `L`
    /// in `F[+FL]F`); default: at the tip of every limb.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub symbol: Option<String>,
    /// Width in mm (0.5–500, default 6).
    #[serde(default = "default_ornament_size")]
    pub width: f64,
    /// Height in mm (0.5–500); default: the width × the motif's own
    /// height-to-width ratio.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
    /// Random turn of each, degrees (0–180).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub turn: f64,
    /// Preview colour and hatching.
    #[serde(default, skip_serializing_if = "PaintSpec::is_default")]
    pub paint: PaintSpec,
}

fn default_ornament_size() -> f64 {
    6.0
}

impl OrnamentSpec {
    pub(crate) fn check(&self, f: &str) -> Result<()> {
        motifs(&format!("{f}.motifs"), &self.motifs, 1)?;
        if let Some(symbol) = &self.symbol {
            if symbol.chars().count() != 1 || symbol.trim().is_empty() {
                return Err(Error::invalid(
                    format!("{f}.symbol"),
                    format!("`{symbol}` is not one character (a module of the rules, e.g. \"L\")"),
                ));
            }
        }
        size(&format!("{f}.width"), self.width)?;
        if let Some(h) = self.height {
            size(&format!("{f}.height"), h)?;
        }
        range(&format!("{f}.turn"), self.turn, 0.0, 180.0)?;
        self.paint.check(&format!("{f}.paint"))
    }

    /// The character of `symbol`.
    pub fn symbol_char(&self) -> Option<char> {
        self.symbol.as_deref().and_then(|s| s.chars().next())
    }
}

impl LeavesSpec {
    /// True when no leaves are asked for.
    pub fn is_empty(&self) -> bool {
        self.ring.is_none() && self.joints.is_none()
    }
}

/// Final adjustment of one tree, flower or leaf, by its id in the SVG.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AdjustSpec {
    /// The id as written in the SVG, e.g. `front.plum.tree-0.flower-3`.
    pub id: String,
    /// Move by `[dx, dy]` mm.
    #[serde(default, rename = "move", skip_serializing_if = "Option::is_none")]
    pub offset: Option<[f64; 2]>,
    /// Turn by this many degrees, clockwise, about its anchor (a tree's
    /// root, a flower's centre, a leaf's stem end, the centre of a group:
    /// a layer, a set, any family's table).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotate: Option<f64>,
    /// Scale about its anchor (0.01–100).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<f64>,
    /// Leave it out (a tree takes its flowers and leaves with it).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub hide: bool,
    /// Draw another motif here (flowers and leaves only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motif: Option<MotifRef>,
}

pub(crate) fn size(f: &str, v: f64) -> Result<()> {
    range(f, v, 0.5, 500.0)
}

fn motifs(f: &str, list: &[MotifRef], min: usize) -> Result<()> {
    if list.len() < min || list.len() > 5 {
        return Err(Error::invalid(
            f,
            format!("needs {min} to 5 motifs, got {}", list.len()),
        ));
    }
    for (i, m) in list.iter().enumerate() {
        m.check(&format!("{f}[{i}]"))?;
    }
    Ok(())
}

impl FlowerSpec {
    pub(crate) fn check(&self, f: &str) -> Result<()> {
        motifs(&format!("{f}.motifs"), &self.motifs, 1)?;
        size(&format!("{f}.width"), self.width)?;
        if let Some(h) = self.height {
            size(&format!("{f}.height"), h)?;
        }
        range(&format!("{f}.turn"), self.turn, 0.0, 180.0)?;
        range(&format!("{f}.smallest"), self.smallest, 0.05, 1.0)?;
        self.paint.check(&format!("{f}.paint"))
    }
}

impl LeavesSpec {
    pub(crate) fn check(&self, f: &str) -> Result<()> {
        if let Some(r) = &self.ring {
            let f = format!("{f}.ring");
            motifs(&format!("{f}.motifs"), &r.motifs, 1)?;
            range(&format!("{f}.count"), r.count, 0, 8)?;
            range(&format!("{f}.spacing"), r.spacing, 0.0, 500.0)?;
            size(&format!("{f}.width"), r.width)?;
            if let Some(h) = r.height {
                size(&format!("{f}.height"), h)?;
            }
            r.paint.check(&format!("{f}.paint"))?;
        }
        if let Some(j) = &self.joints {
            let f = format!("{f}.joints");
            motifs(&format!("{f}.motifs"), &j.motifs, 1)?;
            size(&format!("{f}.width"), j.width)?;
            if let Some(h) = j.height {
                size(&format!("{f}.height"), h)?;
            }
            range(&format!("{f}.angle"), j.angle, -180.0, 180.0)?;
            j.paint.check(&format!("{f}.paint"))?;
        }
        Ok(())
    }
}

impl AdjustSpec {
    pub(crate) fn check(&self, f: &str) -> Result<()> {
        if self.id.trim().is_empty() {
            return Err(Error::invalid(format!("{f}.id"), "needs an id"));
        }
        if let Some(m) = self.offset {
            point(&format!("{f}.move"), m)?;
        }
        if let Some(r) = self.rotate {
            range(&format!("{f}.rotate"), r, -360.0, 360.0)?;
        }
        if let Some(s) = self.scale {
            range(&format!("{f}.scale"), s, 0.01, 100.0)?;
        }
        if let Some(m) = &self.motif {
            m.check(&format!("{f}.motif"))?;
        }
        Ok(())
    }
}
