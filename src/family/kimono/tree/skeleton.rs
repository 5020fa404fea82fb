//! The eight tree rules of the source (docs/SPEC.md §1.2, [000 §3.1]) as vertex
//! skeletons: polylines ("limbs") with their kind, side and parent.
//!
//! The rules are transcribed from the pseudo-code of the thesis:
//!
//! * `Rotate(v, a)` rotates `v` by `a` degrees with the screen convention of
//!   the source (y down, positive is clockwise on the page), so `-Ang2` puts
//!   a branch on the *left* of an upward-growing trunk.
//! * Branch tips in the pseudo-code are offsets; here they are absolute
//!   points (`Top + Rotate(…)`).
//! * Every vertex is tested against the region lines before it is used
//!   (`if (Top > 上領域線) return`): a vertex beyond stops growth there and
//!   is not drawn, so no vertex of a skeleton lies beyond the upper line.
//!   Branches that are computed before the test of the next trunk vertex
//!   keep that order, as in the source.
//!
//! Lengths get an optional random factor and angles an optional random bend
//! (`jitter_length`, `jitter_angle`) from the tree's own random stream.

use kurbo::{Point, Vec2};

use crate::error::Result;
use crate::geom::{PathWalker, Side, TOLERANCE};
use crate::rng::RandomStream;
use crate::scene::PathBudget;
use crate::spec::{ResolvedTreeParams, TreeRule};

/// What part of a tree a limb is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) enum LimbKind {
    /// A trunk (Tree7 has two; Tree8's stem along its base curve).
    Trunk,
    /// A Tree6 root branch.
    Root,
    /// A branch leaving a trunk (simple or complex).
    Branch,
    /// A twig leaving a complex branch.
    Twig,
    /// A side prong of a Tree4 three-way fork.
    Prong,
}

/// Where a limb leaves its parent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Attach {
    /// Index of the parent limb in [`Skeleton::limbs`].
    pub limb: usize,
    /// Index of the parent's vertex the limb starts at.
    pub vertex: usize,
}

/// One limb: a polyline from its base to its tip.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Limb {
    /// Vertices, base first; at least two.
    pub points: Vec<Point>,
    /// Trunk, branch, …
    pub kind: LimbKind,
    /// The side of its parent's growth direction it leaves towards; `None`
    /// for trunks.
    pub side: Option<Side>,
    /// The parent and the vertex it leaves from; `None` for trunks.
    pub parent: Option<Attach>,
}

/// All limbs of one tree; parents come before their children.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Skeleton {
    /// The limbs.
    pub limbs: Vec<Limb>,
}

impl Skeleton {
    /// Every vertex of every limb.
    pub(crate) fn vertices(&self) -> impl Iterator<Item = Point> + '_ {
        self.limbs.iter().flat_map(|l| l.points.iter().copied())
    }

    /// Number of limbs of a kind.
    #[cfg(test)]
    pub(crate) fn count(&self, kind: LimbKind) -> usize {
        self.limbs.iter().filter(|l| l.kind == kind).count()
    }
}

/// Where a tree grows and what stops it.
pub(crate) struct Growth<'a> {
    /// The root point.
    pub root: Point,
    /// Unit growth direction of the first trunk step.
    pub direction: Vec2,
    /// True for vertices where growth must stop (beyond a region line).
    pub blocked: &'a dyn Fn(Point) -> bool,
    /// Grow the mirror image: every turn the other way, so each branch
    /// leaves on the other side.
    pub mirror: bool,
}

/// Grows a tree of `rule`. Every limb is taken from `budget` before it is
/// made; `what` names the tree in a budget error.
pub(crate) fn grow(
    rule: TreeRule,
    params: &ResolvedTreeParams,
    growth: &Growth<'_>,
    rng: RandomStream,
    budget: &mut PathBudget,
    what: &str,
) -> Result<Skeleton> {
    let mut g = Grower {
        p: params,
        blocked: growth.blocked,
        mirror: growth.mirror,
        rng,
        budget,
        what,
        limbs: Vec::new(),
    };
    let root = growth.root;
    let top = root + growth.direction * params.trunk;
    let gens = params.generations;
    match rule {
        TreeRule::Tree1 => g.trunk(gens, root, top, Branching::Complex)?,
        TreeRule::Tree2 => g.trunk(gens, root, top, Branching::Simple)?,
        TreeRule::Tree3 => g.trunk(gens, root, top, Branching::ByMod3)?,
        TreeRule::Tree4 => g.trunk(gens, root, top, Branching::Fork)?,
        TreeRule::Tree5 => g.trunk(gens, root, top, Branching::LeftDeep)?,
        TreeRule::Tree6 => g.tree6(gens, root, top)?,
        TreeRule::Tree7 => g.tree7(gens, root, top)?,
        TreeRule::Tree8 => g.tree8(gens, root, growth.direction)?,
    }
    Ok(Skeleton { limbs: g.limbs })
}

/// How a trunk branches at each of its vertices.
#[derive(Clone, Copy)]
enum Branching {
    /// Tree1: alternating complex branches (TreeSub of depth `sub_generations`).
    Complex,
    /// Tree2/6/7: alternating single-segment branches.
    Simple,
    /// Tree3: by generation mod 3 — complex left + simple right, simple
    /// left + complex right, simple both.
    ByMod3,
    /// Tree4: alternating branches that fork in three.
    Fork,
    /// Tree5: left only, each branch TreeSub(generation − 1).
    LeftDeep,
}

/// Twig placement along a complex branch.
#[derive(Clone, Copy)]
enum Twigs {
    /// Left on even remaining generations, right on odd.
    Alternate,
    /// Left only (Tree5).
    LeftOnly,
}

/// The side a parity-alternating rule puts a branch on: the source's
/// `if (世代 == 偶数) 左 else 右`.
fn side_by_parity(generation: u32) -> Side {
    if generation.is_multiple_of(2) {
        Side::Left
    } else {
        Side::Right
    }
}

/// The rotation sign of a side: left is `-Ang`, right is `+Ang`.
fn sign(side: Side) -> f64 {
    match side {
        Side::Left => -1.0,
        Side::Right => 1.0,
    }
}

struct Grower<'a> {
    p: &'a ResolvedTreeParams,
    blocked: &'a dyn Fn(Point) -> bool,
    mirror: bool,
    rng: RandomStream,
    budget: &'a mut PathBudget,
    what: &'a str,
    limbs: Vec<Limb>,
}

impl Grower<'_> {
    /// `Rotate(v · ratio, angle)` with jitter.
    fn step(&mut self, v: Vec2, ratio: f64, angle_deg: f64) -> Vec2 {
        let len = ratio * (1.0 + self.rng.symmetric(self.p.jitter_length));
        let angle_deg = if self.mirror { -angle_deg } else { angle_deg };
        let a = (angle_deg + self.rng.symmetric(self.p.jitter_angle)).to_radians();
        let (s, c) = a.sin_cos();
        let v = v * len;
        Vec2::new(v.x * c - v.y * s, v.x * s + v.y * c)
    }

    fn is_blocked(&self, p: Point) -> bool {
        // Far outside any page: stop, whatever the lines say, so lengths
        // growing with Ratio1 > 1 cannot run away.
        let limit = crate::units::MAX_COORD;
        !(p.x.abs() <= limit && p.y.abs() <= limit) || (self.blocked)(p)
    }

    /// Adds a limb; a mirrored tree's limbs are labelled with the side
    /// they really leave towards.
    fn push(&mut self, mut limb: Limb) -> Result<usize> {
        let what = self.what;
        self.budget.take(1, || what.to_string())?;
        if self.mirror {
            limb.side = limb.side.map(Side::opposite);
        }
        self.limbs.push(limb);
        Ok(self.limbs.len() - 1)
    }

    /// A single-segment limb from `base` to `tip`, unless `tip` is blocked
    /// or the segment has no length.
    fn simple(
        &mut self,
        base: Point,
        tip: Point,
        kind: LimbKind,
        side: Side,
        at: Attach,
    ) -> Result<()> {
        if self.is_blocked(tip) || (tip - base).hypot() < TOLERANCE {
            return Ok(());
        }
        self.push(Limb {
            points: vec![base, tip],
            kind,
            side: Some(side),
            parent: Some(at),
        })?;
        Ok(())
    }

    /// TreeMain of Tree1–Tree6: a trunk of `gens` steps from `root`→`top`,
    /// branching at each new vertex. Returns nothing when `top` is blocked.
    fn trunk(&mut self, gens: u32, root: Point, top: Point, branching: Branching) -> Result<()> {
        self.trunk_limb(gens, root, top, None, branching)
    }

    fn trunk_limb(
        &mut self,
        gens: u32,
        root: Point,
        top: Point,
        side: Option<Side>,
        branching: Branching,
    ) -> Result<()> {
        if self.is_blocked(top) {
            return Ok(());
        }
        let trunk = self.push(Limb {
            points: vec![root, top],
            kind: LimbKind::Trunk,
            side,
            parent: None,
        })?;
        let (mut a, mut b) = (root, top);
        for generation in (1..=gens).rev() {
            let c = b + self.step(b - a, self.p.ratio1, self.p.ang1);
            let at = Attach {
                limb: trunk,
                vertex: self.limbs[trunk].points.len() - 1,
            };
            self.branch(branching, generation, b, c - b, at)?;
            if self.is_blocked(c) {
                break;
            }
            self.limbs[trunk].points.push(c);
            a = b;
            b = c;
        }
        Ok(())
    }

    /// The branches a trunk grows at vertex `b` in generation `generation`;
    /// `r` is the next trunk step (`NewTop1 - Top`).
    fn branch(
        &mut self,
        branching: Branching,
        generation: u32,
        b: Point,
        r: Vec2,
        at: Attach,
    ) -> Result<()> {
        let (ang2, ratio2) = (self.p.ang2, self.p.ratio2);
        match branching {
            Branching::Simple => {
                let side = side_by_parity(generation);
                let tip = b + self.step(r, ratio2, sign(side) * ang2);
                self.simple(b, tip, LimbKind::Branch, side, at)
            }
            Branching::Complex => {
                let side = side_by_parity(generation);
                let tip = b + self.step(r, ratio2, sign(side) * ang2);
                self.sub(self.p.sub_generations, b, tip, side, Twigs::Alternate, at)
            }
            Branching::ByMod3 => {
                let left = b + self.step(r, ratio2, -ang2);
                let right = b + self.step(r, ratio2, ang2);
                let depth = self.p.sub_generations;
                match generation % 3 {
                    0 => {
                        self.sub(depth, b, left, Side::Left, Twigs::Alternate, at)?;
                        self.simple(b, right, LimbKind::Branch, Side::Right, at)
                    }
                    1 => {
                        self.simple(b, left, LimbKind::Branch, Side::Left, at)?;
                        self.sub(depth, b, right, Side::Right, Twigs::Alternate, at)
                    }
                    _ => {
                        self.simple(b, left, LimbKind::Branch, Side::Left, at)?;
                        self.simple(b, right, LimbKind::Branch, Side::Right, at)
                    }
                }
            }
            Branching::Fork => {
                let side = side_by_parity(generation);
                let tip = b + self.step(r, ratio2, sign(side) * ang2);
                self.fork(b, tip, side, at)
            }
            Branching::LeftDeep => {
                let tip = b + self.step(r, ratio2, -ang2);
                self.sub(generation - 1, b, tip, Side::Left, Twigs::LeftOnly, at)
            }
        }
    }

    /// TreeSub(n, a, b): a complex branch from `a` through `b`, continuing
    /// `n` steps with Ratio1/Ang1 and a twig (Ratio2/Ang2) at each vertex.
    fn sub(
        &mut self,
        n: u32,
        a: Point,
        b: Point,
        side: Side,
        twigs: Twigs,
        at: Attach,
    ) -> Result<()> {
        if self.is_blocked(b) || (b - a).hypot() < TOLERANCE {
            return Ok(());
        }
        let limb = self.push(Limb {
            points: vec![a, b],
            kind: LimbKind::Branch,
            side: Some(side),
            parent: Some(at),
        })?;
        let (mut a, mut b) = (a, b);
        for remaining in (1..=n).rev() {
            let c = b + self.step(b - a, self.p.ratio1, self.p.ang1);
            let twig_side = match twigs {
                Twigs::Alternate => side_by_parity(remaining),
                Twigs::LeftOnly => Side::Left,
            };
            let tip = b + self.step(c - b, self.p.ratio2, sign(twig_side) * self.p.ang2);
            let twig_at = Attach {
                limb,
                vertex: self.limbs[limb].points.len() - 1,
            };
            self.simple(b, tip, LimbKind::Twig, twig_side, twig_at)?;
            if self.is_blocked(c) {
                break;
            }
            self.limbs[limb].points.push(c);
            a = b;
            b = c;
        }
        Ok(())
    }

    /// Tree4's TreeSub(1): a branch to `tip` that continues one step and
    /// forks there into left (−Ang3), middle and right (+Ang3) prongs.
    fn fork(&mut self, base: Point, tip: Point, side: Side, at: Attach) -> Result<()> {
        if self.is_blocked(tip) || (tip - base).hypot() < TOLERANCE {
            return Ok(());
        }
        let middle = tip + self.step(tip - base, self.p.ratio1, self.p.ang1);
        let mut points = vec![base, tip];
        if !self.is_blocked(middle) {
            points.push(middle);
        }
        let limb = self.push(Limb {
            points,
            kind: LimbKind::Branch,
            side: Some(side),
            parent: Some(at),
        })?;
        let fork_at = Attach { limb, vertex: 1 };
        let reference = middle - tip;
        let left = tip + self.step(reference, self.p.ratio2, -self.p.ang3);
        let right = tip + self.step(reference, self.p.ratio2, self.p.ang3);
        self.simple(tip, left, LimbKind::Prong, Side::Left, fork_at)?;
        self.simple(tip, right, LimbKind::Prong, Side::Right, fork_at)
    }

    /// Tree6: two root branches (Ratio3, ∓Ang3) and a Tree2 trunk.
    fn tree6(&mut self, gens: u32, root: Point, top: Point) -> Result<()> {
        if self.is_blocked(top) {
            return Ok(());
        }
        self.trunk(gens, root, top, Branching::Simple)?;
        // The source grows root branches inside `if (世代 > 0)`.
        if gens == 0 {
            return Ok(());
        }
        let at = Attach { limb: 0, vertex: 0 };
        for side in [Side::Left, Side::Right] {
            let tip = root + self.step(top - root, self.p.ratio3, sign(side) * self.p.ang3);
            self.simple(root, tip, LimbKind::Root, side, at)?;
        }
        Ok(())
    }

    /// Tree7: the first step only gives a direction; two trunks leave the
    /// root at ±Ang1 (Ratio1) and grow as Tree2 trunks of `gens − 1` steps.
    fn tree7(&mut self, gens: u32, root: Point, top: Point) -> Result<()> {
        if gens == 0 || self.is_blocked(top) {
            return Ok(());
        }
        for side in [Side::Right, Side::Left] {
            let start = root + self.step(top - root, self.p.ratio1, sign(side) * self.p.ang1);
            self.trunk_limb(gens - 1, root, start, Some(side), Branching::Simple)?;
        }
        Ok(())
    }

    /// Tree8: a stem along a base curve through 4 control points, sampled
    /// at `gens` points; from each sample after the first a branch
    /// `Rotate((S[i+1] − S[i]) · Ratio2, ∓Ang1)`, left for even `i`.
    fn tree8(&mut self, gens: u32, root: Point, direction: Vec2) -> Result<()> {
        if gens < 2 {
            return Ok(());
        }
        let right = Side::Right.normal(direction);
        let unit = self.p.trunk;
        let control: Vec<Point> = self
            .p
            .base
            .iter()
            .map(|[x, y]| {
                let x = if self.mirror { -*x } else { *x };
                root + (right * x + direction * *y) * unit
            })
            .collect();
        let base = crate::geom::natural_spline(&control);
        let samples = PathWalker::new(&base, TOLERANCE).sample_even(gens as usize);
        if samples.len() < 2 || self.is_blocked(samples[1]) {
            return Ok(());
        }
        let stem = self.push(Limb {
            points: vec![samples[0], samples[1]],
            kind: LimbKind::Trunk,
            side: None,
            parent: None,
        })?;
        for i in 0..samples.len() - 1 {
            let (a, b) = (samples[i], samples[i + 1]);
            if self.is_blocked(b) {
                break;
            }
            if i > 0 {
                self.limbs[stem].points.push(b);
            }
            let side = if i % 2 == 0 { Side::Left } else { Side::Right };
            let tip = b + self.step(b - a, self.p.ratio2, sign(side) * self.p.ang1);
            let at = Attach {
                limb: stem,
                vertex: i + 1,
            };
            self.simple(b, tip, LimbKind::Branch, side, at)?;
        }
        Ok(())
    }
}
