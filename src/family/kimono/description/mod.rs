//! The kimono family's tables: tree sets (docs/SPEC.md §1.2–1.4: the rule, the
//! centre line the trees stand on, their parameters, per-tree overrides,
//! and the limb drawing of a layer) and backgrounds (docs/SPEC.md §1.6: a mask
//! from hidden trees or mist bands, and a pattern clipped to it).

mod params;

pub use params::{ResolvedTreeParams, TreeParams};

use std::collections::BTreeSet;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::family::Family;
use crate::spec::flora::size;
use crate::spec::validate::{point, points, range};
use crate::spec::{FlowerSpec, LeavesSpec, MotifKind, MotifRef, PaintSpec, Points};

/// How limbs become paths (docs/SPEC.md §1.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LimbStyle {
    /// A closed outline whose width tapers from `width` to `tip_width`.
    #[default]
    Outline,
    /// A single centre stroke, for one-pass plotting.
    Stroke,
}

/// Limb drawing settings of a layer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LimbSpec {
    /// `outline` or `stroke`.
    #[serde(default)]
    pub style: LimbStyle,
    /// Trunk width at the root in mm (0.05–50); branches start at the
    /// width of their parent where they leave it.
    #[serde(default = "default_limb_width")]
    pub width: f64,
    /// Width at every tip in mm (0–50).
    #[serde(default = "default_tip_width")]
    pub tip_width: f64,
    /// Sideways bow of two-point limbs as a fraction of their length
    /// (−1 – 1); positive bows towards the branch's own side.
    #[serde(default = "default_bow")]
    pub bow: f64,
    /// Fill colour for outlines, any colour or palette slot (default:
    /// none, outline only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fill: Option<String>,
}

impl Default for LimbSpec {
    fn default() -> Self {
        LimbSpec {
            style: LimbStyle::default(),
            width: default_limb_width(),
            tip_width: default_tip_width(),
            bow: default_bow(),
            fill: None,
        }
    }
}

fn default_limb_width() -> f64 {
    2.4
}

fn default_tip_width() -> f64 {
    0.3
}

fn default_bow() -> f64 {
    0.08
}

/// The eight tree rules of docs/SPEC.md §1.2.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TreeRule {
    /// Trunk with alternating complex branches (TreeSub depth 3).
    Tree1,
    /// Trunk with alternating simple branches.
    Tree2,
    /// Branches on both sides, pattern by generation mod 3.
    Tree3,
    /// Branches that fork in three at their end.
    Tree4,
    /// Branches on the left only, each as deep as the generations left.
    Tree5,
    /// Two root branches, then a Tree2 trunk.
    Tree6,
    /// Splits at the root into two Tree2 trunks.
    Tree7,
    /// Spray along a 4-point base curve (not recursive).
    Tree8,
}

impl TreeRule {
    /// All rules in order.
    pub const ALL: [TreeRule; 8] = [
        TreeRule::Tree1,
        TreeRule::Tree2,
        TreeRule::Tree3,
        TreeRule::Tree4,
        TreeRule::Tree5,
        TreeRule::Tree6,
        TreeRule::Tree7,
        TreeRule::Tree8,
    ];
}

/// How trees stand on their centre line (docs/SPEC.md §1.4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Growth {
    /// Perpendicular to the centre line, on its upper side.
    #[default]
    Perpendicular,
    /// Along the centre line, in its drawing direction.
    Parallel,
}

/// A set of trees of one rule along one centre line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TreeSetSpec {
    /// Id of the set, unique in its layer (default `trees-K`, K its index).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
    /// Which of Tree1–Tree8.
    pub rule: TreeRule,
    /// Number of trees (0–10,000), at even arc-length spacing unless
    /// `rhythm` says otherwise.
    #[serde(default = "default_count")]
    pub count: u32,
    /// The centre line (中心線) of this set: ≥ 2 control points in mm.
    pub centre: Points,
    /// Perpendicular to or along the centre line.
    #[serde(default)]
    pub growth: Growth,
    /// Extra rotation of every tree in degrees, clockwise (180 grows
    /// downward from a perpendicular line).
    #[serde(default)]
    pub rotate: f64,
    /// Rule parameters.
    #[serde(default)]
    pub params: TreeParams,
    /// How size, spacing and turn vary along the centre line (default:
    /// all alike, evenly spaced).
    #[serde(default, skip_serializing_if = "Rhythm::is_even")]
    pub rhythm: Rhythm,
    /// Growth toward the upper region line (the flow as the composition's
    /// rule, [000 §2.1]): every upward tree is sized so that its highest
    /// limb comes within this many mm of the line (0.5–200), a tree under
    /// a peak taller than one under a valley. Default: sized as written.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reach: Option<f64>,
    /// A main tree and companions that differ from it (default: trees
    /// alike but for their jitter).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vary: Option<VarySpec>,
    /// Per-tree adjustments by id (`tree-0`, `tree-1`, …).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub overrides: Vec<TreeOverride>,
    /// Flowers at the trees' vertices.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flowers: Option<FlowerSpec>,
    /// Leaves around the flowers and at the branch joints.
    #[serde(default, skip_serializing_if = "LeavesSpec::is_empty")]
    pub leaves: LeavesSpec,
}

fn default_count() -> u32 {
    1
}

/// The main tree of a set and its companions ([000 §2.2]: a main tree,
/// larger and in front, and the others around it, each a drawing of its
/// own). Each companion draws its differences from its own random stream.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VarySpec {
    /// The main tree's number (default 0): painted last, so it stands in
    /// front of its companions.
    #[serde(default)]
    pub main: u32,
    /// Size of the main tree against its companions (0.1–10, default
    /// 1.25); with `reach`, the companions shrink and the main tree
    /// reaches the line.
    #[serde(default = "default_main_scale")]
    pub main_scale: f64,
    /// Companions' sizes differ by up to ± this fraction (0–0.9,
    /// default 0.15).
    #[serde(default = "default_size_spread")]
    pub size: f64,
    /// Companions' turns differ by up to ± this many degrees (0–90,
    /// default 8).
    #[serde(default = "default_turn_spread")]
    pub turn: f64,
    /// Companions have up to this many generations fewer than the set
    /// (0–16, default 1).
    #[serde(default = "default_generation_spread")]
    pub generations: u32,
    /// Every other companion grows mirrored, its branches on the other
    /// sides (default true).
    #[serde(default = "yes")]
    pub mirror: bool,
}

fn default_main_scale() -> f64 {
    1.25
}

fn default_size_spread() -> f64 {
    0.15
}

fn default_turn_spread() -> f64 {
    8.0
}

fn default_generation_spread() -> u32 {
    1
}

impl VarySpec {
    fn check(&self, f: &str, count: u32) -> Result<()> {
        if self.main >= count.max(1) {
            return Err(Error::invalid(
                format!("{f}.main"),
                format!(
                    "the main tree is one of the set's trees: 0 … {}, got {}",
                    count.saturating_sub(1),
                    self.main
                ),
            ));
        }
        range(&format!("{f}.main_scale"), self.main_scale, 0.1, 10.0)?;
        range(&format!("{f}.size"), self.size, 0.0, 0.9)?;
        range(&format!("{f}.turn"), self.turn, 0.0, 90.0)?;
        range(&format!("{f}.generations"), self.generations, 0, 16)
    }
}

/// The rhythm of a tree set along its centre line (beyond the source,
/// whose trees stand evenly in one size; its §7.2.2 asks for composition
/// without placing every tree by hand): a leading tree, a quieter tail,
/// gaps that shrink or grow, trees that fan out, and rests.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rhythm {
    /// Scale of the first tree, the lead (0.05–20, default 1).
    #[serde(default = "unit")]
    pub lead: f64,
    /// Scale of the last tree (0.05–20, default 1); the trees between
    /// change in even steps of ratio from `lead` to it.
    #[serde(default = "unit")]
    pub tail: f64,
    /// Each gap between neighbours is this times the one before (0.1–10,
    /// default 1: even); below 1 the trees crowd towards the tail.
    #[serde(default = "unit")]
    pub spacing: f64,
    /// Degrees (−90–90, default 0) by which the last tree is turned
    /// further than the first, clockwise; the trees between fan out
    /// evenly, the middle one keeping the set's `rotate`.
    #[serde(default)]
    pub turn: f64,
    /// Rests: after these trees (by number, from 0) the gap is twice as
    /// wide, the place of one more tree left empty.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rests: Vec<u32>,
}

fn unit() -> f64 {
    1.0
}

impl Default for Rhythm {
    fn default() -> Self {
        Rhythm {
            lead: 1.0,
            tail: 1.0,
            spacing: 1.0,
            turn: 0.0,
            rests: Vec::new(),
        }
    }
}

impl Rhythm {
    /// All trees alike and evenly spaced.
    pub fn is_even(&self) -> bool {
        *self == Rhythm::default()
    }

    fn check(&self, f: &str, count: u32) -> Result<()> {
        range(&format!("{f}.lead"), self.lead, 0.05, 20.0)?;
        range(&format!("{f}.tail"), self.tail, 0.05, 20.0)?;
        range(&format!("{f}.spacing"), self.spacing, 0.1, 10.0)?;
        range(&format!("{f}.turn"), self.turn, -90.0, 90.0)?;
        for (i, r) in self.rests.iter().enumerate() {
            if *r + 1 >= count.max(1) {
                return Err(Error::invalid(
                    format!("{f}.rests[{i}]"),
                    format!(
                        "a rest comes after a tree that has one after it: 0 … {}, got {r}",
                        count.saturating_sub(2)
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Where each of `n` trees stands, as a fraction of the centre line,
    /// its scale and its extra turn in degrees; in one pass, as a set may
    /// hold ten thousand trees.
    pub fn places(&self, n: usize) -> Vec<(f64, f64, f64)> {
        // A half gap before the first tree and after the last; gap j (after
        // tree j) is `spacing^j`, twice that where a rest follows tree j.
        // Only their ratios matter: growing gaps are counted down from the
        // last, which is 1, as 10^10000 would be infinite.
        let last = n.saturating_sub(2) as f64;
        let gap = |j: usize| {
            if self.spacing > 1.0 {
                self.spacing.powf(j as f64 - last)
            } else {
                self.spacing.powf(j as f64)
            }
        };
        let rests: BTreeSet<usize> = self.rests.iter().map(|&r| r as usize).collect();
        let mut s = 0.5 * gap(0);
        let mut at = Vec::with_capacity(n);
        at.push(s);
        for j in 0..n.saturating_sub(1) {
            let rest = rests.contains(&j);
            s += if rest { 2.0 * gap(j) } else { gap(j) };
            at.push(s);
        }
        let total = s + 0.5 * gap(n.saturating_sub(2));
        at.into_iter()
            .take(n)
            .enumerate()
            .map(|(i, a)| {
                let t = if n > 1 {
                    i as f64 / (n - 1) as f64
                } else {
                    0.0
                };
                let scale = self.lead * (self.tail / self.lead).powf(t);
                (a / total, scale, self.turn * (t - 0.5))
            })
            .collect()
    }
}

/// Final adjustment of one tree (docs/SPEC.md §1.4).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TreeOverride {
    /// The tree's id within its set: `tree-N`.
    pub id: String,
    /// Move the root here (mm).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub root: Option<[f64; 2]>,
    /// Rotate the growth direction by this many degrees, clockwise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotate: Option<f64>,
    /// Scale lengths and widths (0.01–100).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<f64>,
    /// Parameters that replace the set's for this tree.
    #[serde(default, skip_serializing_if = "TreeParams::is_empty")]
    pub params: TreeParams,
}

impl Family for TreeSetSpec {
    fn check(&self, f: &str) -> Result<()> {
        range(&format!("{f}.count"), self.count, 0, 10_000)?;
        points(&format!("{f}.centre"), &self.centre, 2)?;
        range(&format!("{f}.rotate"), self.rotate, -360.0, 360.0)?;
        self.params.check(&format!("{f}.params"))?;
        self.rhythm.check(&format!("{f}.rhythm"), self.count)?;
        if let Some(r) = self.reach {
            range(&format!("{f}.reach"), r, 0.5, 200.0)?;
        }
        if let Some(v) = &self.vary {
            v.check(&format!("{f}.vary"), self.count)?;
        }
        let mut seen = BTreeSet::new();
        for (j, o) in self.overrides.iter().enumerate() {
            let of = format!("{f}.overrides[{j}]");
            if self.tree_of(o).is_none() {
                let hint = match self.count {
                    0 => "this set has no trees".to_string(),
                    1 => "the only tree is tree-0".to_string(),
                    n => format!("trees are tree-0 … tree-{}", n - 1),
                };
                return Err(Error::invalid(
                    format!("{of}.id"),
                    format!("'{}' matches no tree ({hint})", o.id),
                ));
            }
            if !seen.insert(o.id.as_str()) {
                return Err(Error::invalid(
                    format!("{of}.id"),
                    format!("'{}' is overridden twice", o.id),
                ));
            }
            if let Some(p) = o.root {
                point(&format!("{of}.root"), p)?;
            }
            if let Some(r) = o.rotate {
                range(&format!("{of}.rotate"), r, -360.0, 360.0)?;
            }
            if let Some(s) = o.scale {
                range(&format!("{of}.scale"), s, 0.01, 100.0)?;
            }
            o.params.check(&format!("{of}.params"))?;
        }
        if let Some(fl) = &self.flowers {
            fl.check(&format!("{f}.flowers"))?;
        }
        self.leaves.check(&format!("{f}.leaves"))
    }

    fn work(&self) -> usize {
        self.count as usize
    }

    fn motifs(&self) -> Vec<&MotifRef> {
        let mut refs: Vec<&MotifRef> = Vec::new();
        if let Some(f) = &self.flowers {
            refs.extend(&f.motifs);
        }
        if let Some(r) = &self.leaves.ring {
            refs.extend(&r.motifs);
        }
        if let Some(j) = &self.leaves.joints {
            refs.extend(&j.motifs);
        }
        refs
    }
}

impl TreeSetSpec {
    /// The number of the tree an override addresses (`tree-N`, `N <
    /// count`, written without leading zeros), if any.
    pub fn tree_of(&self, o: &TreeOverride) -> Option<usize> {
        o.id.strip_prefix("tree-")
            .and_then(|n| n.parse::<u32>().ok())
            .filter(|n| *n < self.count && o.id == format!("tree-{n}"))
            .map(|n| n as usize)
    }
}

/// A background layer (docs/SPEC.md §1.6): a mask grown from hidden trees and a
/// pattern clipped to it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BackgroundSpec {
    /// Mask generation mode, 1–4 (see docs/SPEC.md §1.6; default 1).
    #[serde(default = "default_composite")]
    pub composite: u8,
    /// Mist bands (egasumi) instead of stamps on hidden trees: the mask is
    /// made of long bands with rounded ends and stepped edges along the
    /// centre line.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mist: Option<MistSpec>,
    /// Tree rule of the hidden mask trees; default tree2 for composites
    /// 1 and 2, tree4 (sparser) for 3 and 4.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rule: Option<TreeRule>,
    /// Number of mask trees (0–1000) along the centre line.
    #[serde(default = "default_mask_count")]
    pub count: u32,
    /// Centre line of the mask trees (≥ 2 points, mm).
    pub centre: Points,
    /// Growth direction of the mask trees; they grow both ways from the
    /// centre line (up, limited by the upper line; down, by the lower).
    #[serde(default)]
    pub growth: Growth,
    /// Parameters of the mask trees.
    #[serde(default)]
    pub params: TreeParams,
    /// Circles `[x, y, radius]` (mm): composite 2 grows only inside them,
    /// composite 4 stamps only inside them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub circles: Vec<[f64; 3]>,
    /// The shape stamped at every mask vertex (default circle).
    #[serde(default = "default_stamp")]
    pub stamp: MotifRef,
    /// Stamp width in mm (0.5–500).
    #[serde(default = "default_stamp_size")]
    pub stamp_width: f64,
    /// Stamp height in mm; default: from the stamp's proportions.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stamp_height: Option<f64>,
    /// Rounds the union of stamps into clouds (kumo), mm (0–500; default
    /// a quarter of the stamp width): the mask is grown by this much, then shrunk
    /// by as much (a closing), which fills the notches between stamps with
    /// arcs of this radius and joins stamps closer than twice it. `0`
    /// keeps the source's union of stamps, a string of balloons.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cloud: Option<f64>,
    /// Pattern 1–5 composited into the mask (docs/SPEC.md §1.6), or 0: none, the
    /// mask's outline alone (for a later layer to fill).
    pub pattern: u8,
    /// The pattern's motifs: none for 0 and 1; one for 5; one or two for
    /// 2–4.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub motifs: Vec<MotifRef>,
    /// Tile width in mm (0.5–500).
    #[serde(default = "default_tile_size")]
    pub width: f64,
    /// Tile height in mm; default: from the motif's proportions.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
    /// Gap between tiles in mm (0–500), patterns 3 and 4.
    #[serde(default)]
    pub spacing: f64,
    /// Draw the mask's outline.
    #[serde(default = "yes")]
    pub outline: bool,
    /// The base: fill/hatch of the whole mask (pattern 1, and under the
    /// tiles of 2–4).
    #[serde(default, skip_serializing_if = "PaintSpec::is_default")]
    pub paint: PaintSpec,
}

fn default_mask_count() -> u32 {
    6
}

fn default_composite() -> u8 {
    1
}

/// Mist bands, 霞 egasumi (suyari-gasumi, the long trailing kind of
/// yūzen): the background's mask as bands that run along its centre line,
/// stacked across it, each with rounded ends and a stepped upper edge.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MistSpec {
    /// Bands stacked across the centre line (1–50, default 3).
    #[serde(default = "default_bands")]
    pub bands: u32,
    /// Thickness of a band, mm (0.5–500, default 12).
    #[serde(default = "default_band_height")]
    pub height: f64,
    /// Space between two bands (each with its steps), mm (0–500; default
    /// half the height).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gap: Option<f64>,
    /// Steps on a band's upper edge (0–5, default 2): shorter bands
    /// stacked on it, each 0.4 of a height higher.
    #[serde(default = "default_steps")]
    pub steps: u32,
}

fn default_bands() -> u32 {
    3
}

fn default_band_height() -> f64 {
    12.0
}

fn default_steps() -> u32 {
    2
}

impl MistSpec {
    fn check(&self, f: &str) -> Result<()> {
        range(&format!("{f}.bands"), self.bands, 1, 50)?;
        size(&format!("{f}.height"), self.height)?;
        if let Some(g) = self.gap {
            range(&format!("{f}.gap"), g, 0.0, 500.0)?;
        }
        range(&format!("{f}.steps"), self.steps, 0, 5)
    }
}

fn default_stamp() -> MotifRef {
    MotifRef::Name(MotifKind::Circle)
}

fn default_stamp_size() -> f64 {
    14.0
}

fn default_tile_size() -> f64 {
    10.0
}

fn yes() -> bool {
    true
}

impl BackgroundSpec {
    /// The radius (mm) of the closing that rounds the mask into clouds.
    pub fn cloud_radius(&self) -> f64 {
        self.cloud.unwrap_or(0.25 * self.stamp_width)
    }

    /// The rule of the mask trees.
    pub fn mask_rule(&self) -> TreeRule {
        self.rule.unwrap_or(if self.composite <= 2 {
            TreeRule::Tree2
        } else {
            TreeRule::Tree4
        })
    }
}

impl Family for BackgroundSpec {
    fn offers_regions(&self) -> bool {
        true
    }

    fn check(&self, f: &str) -> Result<()> {
        range(&format!("{f}.composite"), self.composite, 1, 4)?;
        if let Some(m) = &self.mist {
            m.check(&format!("{f}.mist"))?;
        }
        range(&format!("{f}.count"), self.count, 0, 1000)?;
        points(&format!("{f}.centre"), &self.centre, 2)?;
        self.params.check(&format!("{f}.params"))?;
        if matches!(self.composite, 2 | 4) && self.circles.is_empty() {
            return Err(Error::invalid(
                format!("{f}.circles"),
                format!(
                    "composite {} needs at least one circle [x, y, radius]",
                    self.composite
                ),
            ));
        }
        for (i, c) in self.circles.iter().enumerate() {
            point(&format!("{f}.circles[{i}]"), [c[0], c[1]])?;
            range(&format!("{f}.circles[{i}][2]"), c[2], 0.1, 10_000.0)?;
        }
        self.stamp.check(&format!("{f}.stamp"))?;
        size(&format!("{f}.stamp_width"), self.stamp_width)?;
        if let Some(h) = self.stamp_height {
            size(&format!("{f}.stamp_height"), h)?;
        }
        if let Some(c) = self.cloud {
            range(&format!("{f}.cloud"), c, 0.0, 500.0)?;
        }
        range(&format!("{f}.pattern"), self.pattern, 0, 5)?;
        let (min, max) = match self.pattern {
            0 | 1 => (0, 0),
            5 => (1, 1),
            _ => (1, 2),
        };
        let mf = format!("{f}.motifs");
        if self.motifs.len() < min || self.motifs.len() > max {
            let takes = match (min, max) {
                (0, 0) => "no motifs".to_string(),
                (1, 1) => "exactly one motif".to_string(),
                _ => format!("{min} or {max} motifs"),
            };
            return Err(Error::invalid(
                mf,
                format!(
                    "pattern {} takes {takes}, got {}",
                    self.pattern,
                    self.motifs.len()
                ),
            ));
        }
        for (i, m) in self.motifs.iter().enumerate() {
            m.check(&format!("{mf}[{i}]"))?;
        }
        size(&format!("{f}.width"), self.width)?;
        if let Some(h) = self.height {
            size(&format!("{f}.height"), h)?;
        }
        range(&format!("{f}.spacing"), self.spacing, 0.0, 500.0)?;
        self.paint.check(&format!("{f}.paint"))
    }

    /// One unit per hidden mask tree.
    fn work(&self) -> usize {
        self.count as usize
    }

    fn motifs(&self) -> Vec<&MotifRef> {
        std::iter::once(&self.stamp).chain(&self.motifs).collect()
    }
}
