//! Hatching: fills become parallel pen lines (docs/SPEC.md §6 "fills become
//! hatching (angle, spacing, cross-hatch)").
//!
//! A filled region is cut by parallel scanlines on a grid aligned to the
//! page origin (so neighbouring regions hatched alike line up), clipped to
//! the region's flattened outline (within [`TOLERANCE`]) with the non-zero
//! rule, holes included. Consecutive lines are then joined back and forth
//! into runs, each join a short walk along the outline from the end of one
//! line to the start of the next — so a joined run never leaves the region,
//! and every join saves a pen lift. Ends on different contours, or farther
//! apart along the outline than a few spacings, start a new path.
//!
//! The outline of a hatched fill stays drawn, so the lines keep
//! [`OUTLINE_CLEARANCE`] pen widths inside it (beyond any `inset`): the
//! joins then walk beside the outline instead of drawing it a second time,
//! while the ink of the lines still meets the outline's.

use kurbo::{Affine, BezPath, Point, Vec2};

use crate::error::{Error, Result};
use crate::geom::offset::offset;
use crate::geom::region::{FillRule, Region};
use crate::geom::TOLERANCE;
use crate::scene::{Color, Group, Node, Scene, Style, StyledPath};

/// A region is hatched with at most this many lines per direction.
pub const MAX_LINES: usize = 1_000_000;

/// Consecutive lines are joined only where the walk along the outline
/// between their ends is at most this many spacings long: longer walks
/// follow an outline nearly parallel to the lines (closer than about 20°)
/// and would retrace too much of it.
const MAX_CONNECTOR_SPACINGS: f64 = 3.0;

/// Hatch lines of a fill whose outline is drawn keep this many widths of
/// the layer's pen inside the outline, on top of the options' `inset`.
/// The outline's ink reaches half a width inside and a line's ink half a
/// width beside it, so at 0.6 the two overlap by a tenth of a width (no
/// paper shows between them) while the joins along the outline run 0.6
/// widths beside it, not on it (drawn twice, a line needs to lie within a
/// quarter width: `plot::dedupe`). A band narrower than 1.2 widths gets no
/// lines: its outline alone inks all of it but a sliver of at most 0.2
/// widths.
pub const OUTLINE_CLEARANCE: f64 = 0.6;

/// Pieces of a scanline shorter than this (mm) are dropped: they are where
/// a line grazes a corner, and would be dots.
const MIN_PIECE: f64 = TOLERANCE;

/// How to hatch.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HatchOptions {
    /// Distance between neighbouring lines, mm (> 0).
    pub spacing: f64,
    /// Direction of the lines in degrees, anticlockwise on the page from
    /// the x axis (45 runs from lower left to upper right).
    pub angle_deg: f64,
    /// Also hatch at right angles to `angle_deg`.
    pub cross: bool,
    /// Keep the lines this far (mm, ≥ 0) inside the outline.
    pub inset: f64,
}

impl HatchOptions {
    /// 0.5 mm spacing at 45°, no cross-hatch, no inset.
    pub const DEFAULT: HatchOptions = HatchOptions {
        spacing: 0.5,
        angle_deg: 45.0,
        cross: false,
        inset: 0.0,
    };

    /// With this spacing (mm).
    pub fn with_spacing(mut self, spacing: f64) -> Self {
        self.spacing = spacing;
        self
    }

    /// With this angle (degrees).
    pub fn with_angle_deg(mut self, angle_deg: f64) -> Self {
        self.angle_deg = angle_deg;
        self
    }

    /// With or without cross-hatching.
    pub fn with_cross(mut self, cross: bool) -> Self {
        self.cross = cross;
        self
    }

    /// With this inset from the outline (mm).
    pub fn with_inset(mut self, inset: f64) -> Self {
        self.inset = inset;
        self
    }

    /// Checks the values.
    ///
    /// # Errors
    /// [`Error::Invalid`] naming the field (`hatch.spacing`, …) when the
    /// spacing is not a finite number > 0, the angle is not finite, or the
    /// inset is not a finite number ≥ 0.
    pub fn validate(&self) -> Result<()> {
        if !(self.spacing.is_finite() && self.spacing > 0.0) {
            return Err(Error::invalid(
                "hatch.spacing",
                format!("must be a finite number of mm > 0, got {}", self.spacing),
            ));
        }
        if !self.angle_deg.is_finite() {
            return Err(Error::invalid(
                "hatch.angle_deg",
                format!("must be a finite number of degrees, got {}", self.angle_deg),
            ));
        }
        if !(self.inset.is_finite() && self.inset >= 0.0) {
            return Err(Error::invalid(
                "hatch.inset",
                format!("must be a finite number of mm ≥ 0, got {}", self.inset),
            ));
        }
        Ok(())
    }
}

impl Default for HatchOptions {
    fn default() -> Self {
        HatchOptions::DEFAULT
    }
}

/// The hatch lines of `region`: polylines, one per back-and-forth run,
/// all inside the region (shrunk by the inset), within [`TOLERANCE`] of
/// its curved outline. Lines of the first direction come first, then (with
/// `cross`) those at right angles; within a direction, runs are in the
/// order their first lines appear across the region.
///
/// # Errors
/// When the options are invalid (see [`HatchOptions::validate`]) or the
/// region would need more than [`MAX_LINES`] lines in one direction.
pub fn hatch_region(region: &Region, o: &HatchOptions) -> Result<Vec<BezPath>> {
    o.validate()?;
    let shrunk;
    let region = if o.inset > 0.0 {
        shrunk = offset(region, -o.inset, TOLERANCE)?;
        &shrunk
    } else {
        region
    };
    if region.is_empty() {
        return Ok(Vec::new());
    }
    let polygons = region.polygons(TOLERANCE);
    let mut out = Vec::new();
    let mut angles = vec![o.angle_deg];
    if o.cross {
        angles.push(o.angle_deg + 90.0);
    }
    for angle in angles {
        out.extend(hatch_direction(&polygons, angle, o.spacing)?);
    }
    Ok(out)
}

/// An edge of the outline in scanline coordinates (`u` along the lines,
/// `v` across them): from vertex `index` of contour `contour` to the next.
#[derive(Debug, Clone, Copy)]
struct Edge {
    a: Point,
    b: Point,
    contour: usize,
    index: usize,
}

/// Where a piece of a scanline ends: on `edge`, at parameter `t` along it.
#[derive(Debug, Clone, Copy)]
struct End {
    u: f64,
    edge: usize,
    t: f64,
}

/// A piece of a scanline inside the region.
#[derive(Debug, Clone, Copy)]
struct Piece {
    start: End,
    end: End,
}

/// A back-and-forth run being built: its points in scanline coordinates,
/// the piece on the previous scanline, and whether that piece was drawn
/// towards +u (so the run now stands at its `end`).
struct Run {
    points: Vec<Point>,
    last: Piece,
    rightwards: bool,
}

/// The outline in scanline coordinates.
struct Outline {
    contours: Vec<Vec<Point>>,
    edges: Vec<Edge>,
}

impl Outline {
    /// The points of the outline strictly between `from` (on line `v0`) and
    /// `to` (on line `v1`), walking along their common contour the shorter
    /// way, when both lie on one contour and that way is at most `limit`
    /// long.
    fn walk(&self, from: End, v0: f64, to: End, v1: f64, limit: f64) -> Option<Vec<Point>> {
        let (ea, eb) = (self.edges[from.edge], self.edges[to.edge]);
        if ea.contour != eb.contour {
            return None;
        }
        let poly = &self.contours[ea.contour];
        let n = poly.len();
        let (p, q) = (Point::new(from.u, v0), Point::new(to.u, v1));
        let forward = || -> Option<(f64, Vec<Point>)> {
            if ea.index == eb.index && to.t >= from.t {
                return Some(((q - p).hypot(), Vec::new()));
            }
            let mut pts = Vec::new();
            let mut len = 0.0;
            let mut at = p;
            let mut i = ea.index;
            loop {
                let next = poly[(i + 1) % n];
                len += (next - at).hypot();
                if len > limit {
                    return None;
                }
                pts.push(next);
                at = next;
                i = (i + 1) % n;
                if i == eb.index {
                    return Some((len + (q - at).hypot(), pts));
                }
            }
        };
        let backward = || -> Option<(f64, Vec<Point>)> {
            if ea.index == eb.index && to.t <= from.t {
                return Some(((q - p).hypot(), Vec::new()));
            }
            let mut pts = Vec::new();
            let mut len = 0.0;
            let mut at = p;
            let mut i = ea.index;
            loop {
                let here = poly[i];
                len += (here - at).hypot();
                if len > limit {
                    return None;
                }
                pts.push(here);
                at = here;
                i = (i + n - 1) % n;
                if i == eb.index {
                    return Some((len + (q - at).hypot(), pts));
                }
            }
        };
        let best = match (forward(), backward()) {
            (Some(f), Some(b)) => Some(if f.0 <= b.0 { f } else { b }),
            (f, b) => f.or(b),
        };
        best.filter(|(len, _)| *len <= limit).map(|(_, pts)| pts)
    }
}

fn hatch_direction(polygons: &[Vec<Point>], angle_deg: f64, spacing: f64) -> Result<Vec<BezPath>> {
    let theta = angle_deg.to_radians();
    // Along the lines (anticlockwise on a y-down page) and across them.
    let d = Vec2::new(theta.cos(), -theta.sin());
    let n = Vec2::new(theta.sin(), theta.cos());
    let to_uv = |p: Point| Point::new(p.to_vec2().dot(d), p.to_vec2().dot(n));
    let from_uv = |q: Point| (d * q.x + n * q.y).to_point();

    let contours: Vec<Vec<Point>> = polygons
        .iter()
        .map(|poly| poly.iter().map(|p| to_uv(*p)).collect())
        .collect();
    let mut edges = Vec::new();
    for (c, poly) in contours.iter().enumerate() {
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            if a.y != b.y {
                edges.push(Edge {
                    a,
                    b,
                    contour: c,
                    index: i,
                });
            }
        }
    }
    if edges.is_empty() {
        return Ok(Vec::new());
    }
    let lo = |e: &Edge| e.a.y.min(e.b.y);
    let hi = |e: &Edge| e.a.y.max(e.b.y);
    let v_min = edges.iter().map(lo).fold(f64::INFINITY, f64::min);
    let v_max = edges.iter().map(hi).fold(f64::NEG_INFINITY, f64::max);
    let k0 = (v_min / spacing).ceil();
    let k1 = (v_max / spacing).floor();
    if k1 < k0 {
        return Ok(Vec::new());
    }
    let count = k1 - k0 + 1.0;
    if count > MAX_LINES as f64 {
        return Err(Error::invalid(
            "hatch.spacing",
            format!(
                "{spacing} mm would need {count:.0} lines across this region \
                 (at most {MAX_LINES}); use a larger spacing"
            ),
        ));
    }
    let outline = Outline { contours, edges };

    // Edges sorted by their lowest v, swept with an active list.
    let mut order: Vec<usize> = (0..outline.edges.len()).collect();
    order.sort_by(|&i, &j| lo(&outline.edges[i]).total_cmp(&lo(&outline.edges[j])));
    let mut next = 0;
    let mut active: Vec<usize> = Vec::new();
    let mut crossings: Vec<(End, i32)> = Vec::new();

    let mut done: Vec<Vec<Point>> = Vec::new();
    let mut runs: Vec<Run> = Vec::new();
    let max_connector = MAX_CONNECTOR_SPACINGS * spacing;

    for k in 0..count as usize {
        let v = (k0 + k as f64) * spacing;
        while next < order.len() && lo(&outline.edges[order[next]]) <= v {
            active.push(order[next]);
            next += 1;
        }
        active.retain(|&i| hi(&outline.edges[i]) > v);
        crossings.clear();
        for &i in &active {
            let Edge { a, b, .. } = outline.edges[i];
            // Half-open in v, so a vertex on the line counts once.
            if (a.y <= v) != (b.y <= v) {
                let t = (v - a.y) / (b.y - a.y);
                let u = a.x + t * (b.x - a.x);
                crossings.push((End { u, edge: i, t }, if b.y > a.y { 1 } else { -1 }));
            }
        }
        crossings.sort_by(|x, y| x.0.u.total_cmp(&y.0.u));
        let mut pieces: Vec<Piece> = Vec::new();
        let mut w = 0;
        let mut start = None;
        for &(end, dw) in &crossings {
            let was_inside = w != 0;
            w += dw;
            match (was_inside, w != 0, start) {
                (false, true, _) => start = Some(end),
                (true, false, Some(s)) if end.u - s.u >= MIN_PIECE => {
                    pieces.push(Piece { start: s, end });
                }
                _ => {}
            }
        }

        // Continue runs from the previous line into overlapping pieces.
        let mut taken = vec![false; pieces.len()];
        let mut continued: Vec<Run> = Vec::new();
        for mut run in runs.drain(..) {
            let (r0, r1) = (run.last.start.u, run.last.end.u);
            let from = if run.rightwards {
                run.last.end
            } else {
                run.last.start
            };
            let mut choice = None;
            for (j, piece) in pieces.iter().enumerate() {
                if taken[j] || piece.end.u < r0 || piece.start.u > r1 {
                    continue;
                }
                let to = if run.rightwards {
                    piece.end
                } else {
                    piece.start
                };
                if let Some(between) = outline.walk(from, v - spacing, to, v, max_connector) {
                    choice = Some((j, between));
                    break;
                }
            }
            match choice {
                Some((j, between)) => {
                    taken[j] = true;
                    let piece = pieces[j];
                    let (first, second) = if run.rightwards {
                        (piece.end, piece.start)
                    } else {
                        (piece.start, piece.end)
                    };
                    run.points.extend(between);
                    run.points.push(Point::new(first.u, v));
                    run.points.push(Point::new(second.u, v));
                    run.rightwards = !run.rightwards;
                    run.last = piece;
                    continued.push(run);
                }
                None => done.push(run.points),
            }
        }
        for (j, piece) in pieces.iter().enumerate() {
            if !taken[j] {
                continued.push(Run {
                    points: vec![Point::new(piece.start.u, v), Point::new(piece.end.u, v)],
                    last: *piece,
                    rightwards: true,
                });
            }
        }
        // Keep runs in order along the line, so matching is stable.
        continued.sort_by(|x, y| x.last.start.u.total_cmp(&y.last.start.u));
        runs = continued;
    }
    done.extend(runs.into_iter().map(|r| r.points));

    Ok(done
        .into_iter()
        .map(|pts| {
            let mut path = BezPath::new();
            path.move_to(from_uv(pts[0]));
            for p in &pts[1..] {
                path.line_to(from_uv(*p));
            }
            path
        })
        .collect())
}

/// Replaces fills by hatching, throughout the scene.
///
/// Every path with a fill loses it and keeps its outline; unless the fill
/// is white (paper: nothing to draw), hatch lines for the area it enclosed
/// (non-zero rule, like an SVG fill), [`OUTLINE_CLEARANCE`] widths of the
/// layer's pen inside the outline, are added right after it in the same
/// group, with ids `<id>.hatch-<k>`, drawn by the same pen. A
/// [fill-only](Style::fill_only) path (paint whose outline no pen draws)
/// is hatched to its edge — or as clear of it as of an outline when other
/// line work draws it ([`Style::edge_drawn`]) — and becomes a
/// [mask](Style::mask): it still
/// hides what lies behind it, and is drawn no more than before. A path whose
/// [`Style::hatch`] gives its own spacing is hatched at that spacing (the
/// other options as given). Spacing, inset and angle are measured on the
/// page, whatever the group transforms. Paths that enclose no area only
/// lose their fill.
///
/// # Errors
/// When the options are invalid or a region needs too many lines (see
/// [`hatch_region`]).
pub fn run(scene: &mut Scene, o: &HatchOptions) -> Result<()> {
    run_with(scene, Some(o))
}

/// Hatches only the filled paths that carry their own spacing
/// ([`Style::hatch`]), with [`HatchOptions::DEFAULT`] otherwise; other
/// fills stay fills. This is what a scene gets whose motifs ask for
/// hatching when its plot options do not.
///
/// # Errors
/// As [`run`].
pub fn run_own(scene: &mut Scene) -> Result<()> {
    run_with(scene, None)
}

/// True when some path carries its own hatch spacing.
pub fn has_own_hatch(scene: &Scene) -> bool {
    let mut found = false;
    scene.visit_paths(|_, p, _| found |= p.style.hatch.is_some() && p.style.fill.is_some());
    found
}

fn run_with(scene: &mut Scene, o: Option<&HatchOptions>) -> Result<()> {
    if let Some(o) = o {
        o.validate()?;
    }
    let page = scene.page_transform();
    let clearances: Vec<f64> = scene
        .layers
        .iter()
        .map(|l| OUTLINE_CLEARANCE * scene.pen_width(l.pen))
        .collect();
    for (layer, clearance) in scene.layers.iter_mut().zip(clearances) {
        hatch_group(&mut layer.content, page, o, clearance)?;
    }
    Ok(())
}

const WHITE: Color = Color::rgb(255, 255, 255);

/// Hatches the fills in `group`, their lines `clearance` mm (beyond the
/// options' inset) inside the outline.
fn hatch_group(
    group: &mut Group,
    outer: Affine,
    o: Option<&HatchOptions>,
    clearance: f64,
) -> Result<()> {
    let here = outer * group.transform;
    let children = std::mem::take(&mut group.children);
    let mut out = Vec::with_capacity(children.len());
    for child in children {
        match child {
            Node::Group(mut g) => {
                hatch_group(&mut g, here, o, clearance)?;
                out.push(Node::Group(g));
            }
            Node::Path(mut p) => {
                let options = match (p.style.hatch, o) {
                    (Some(spacing), o) => {
                        let o = o.copied().unwrap_or(HatchOptions::DEFAULT);
                        let o = o.with_spacing(spacing);
                        o.validate()?;
                        o
                    }
                    (None, Some(o)) => *o,
                    (None, None) => {
                        out.push(Node::Path(p));
                        continue;
                    }
                };
                let Some(fill) = p.style.fill.take() else {
                    out.push(Node::Path(p));
                    continue;
                };
                p.style.hatch = None;
                // Paint that no pen outlines (an imported shape with an
                // invisible stroke) has no outline to keep clear of,
                // unless other line work draws its edge; its colour
                // becomes the lines, and what is left of it only hides
                // what lies behind it, as the paint did.
                let clearance = if p.style.fill_only {
                    p.style.fill_only = false;
                    p.style.mask = true;
                    if p.style.edge_drawn {
                        clearance
                    } else {
                        0.0
                    }
                } else {
                    clearance
                };
                let options = options.with_inset(options.inset + clearance);
                let lines = if fill == WHITE {
                    Vec::new()
                } else {
                    hatch_path(&p.path, here, &options)?
                };
                let id = p.id.clone();
                out.push(Node::Path(p));
                for (k, path) in lines.into_iter().enumerate() {
                    out.push(Node::Path(StyledPath {
                        id: format!("{id}.hatch-{k}"),
                        path,
                        style: Style::default(),
                    }));
                }
            }
        }
    }
    group.children = out;
    Ok(())
}

/// Hatch lines for a path in group coordinates, hatched on the page.
fn hatch_path(path: &BezPath, to_page: Affine, o: &HatchOptions) -> Result<Vec<BezPath>> {
    let det = to_page.determinant();
    if !(det.is_finite() && det != 0.0) {
        return Ok(Vec::new());
    }
    let Ok(region) = Region::new(to_page * path.clone(), FillRule::NonZero) else {
        return Ok(Vec::new());
    };
    let back = to_page.inverse();
    Ok(hatch_region(&region, o)?
        .into_iter()
        .map(|l| back * l)
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::path_length;
    use crate::geom::region::tests::{arb_region, circle, rect};
    use crate::scene::Layer;
    use crate::units::{Margins, Orientation, Page, PaperName};
    use kurbo::{ParamCurve, ParamCurveNearest, PathEl, Rect, Shape};
    use proptest::prelude::*;

    fn boundary_distance(region: &Region, p: Point) -> f64 {
        region
            .path()
            .segments()
            .map(|s| s.nearest(p, 1e-9).distance_sq)
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    }

    /// Every point of every line is inside, or within `slack` of the
    /// outline.
    fn all_inside(
        region: &Region,
        lines: &[BezPath],
        slack: f64,
    ) -> std::result::Result<(), String> {
        for l in lines {
            for seg in l.segments() {
                for k in 0..=10 {
                    let p = seg.eval(k as f64 / 10.0);
                    if !region.contains(p) && boundary_distance(region, p) > slack {
                        return Err(format!("{p:?} is outside"));
                    }
                }
            }
        }
        Ok(())
    }

    fn horizontal_total(lines: &[BezPath]) -> f64 {
        // Length of the parts along the hatch direction (0°): horizontal.
        lines
            .iter()
            .flat_map(|l| l.segments())
            .filter(|s| (s.start().y - s.end().y).abs() < 1e-9)
            .map(|s| (s.end().x - s.start().x).abs())
            .sum()
    }

    #[test]
    fn square_at_zero_degrees_is_one_zigzag() {
        let sq = rect(0.0, 0.0, 10.0, 10.0);
        let o = HatchOptions::DEFAULT.with_angle_deg(0.0).with_spacing(1.0);
        let lines = hatch_region(&sq, &o).unwrap();
        // Lines at y = 1..9 (0 and 10 are on the outline: the half-open
        // rule keeps y = 0, whose piece is then the top edge itself).
        assert_eq!(lines.len(), 1, "{lines:?}");
        let pts: Vec<Point> = lines[0]
            .elements()
            .iter()
            .filter_map(|e| match e {
                PathEl::MoveTo(p) | PathEl::LineTo(p) => Some(*p),
                _ => None,
            })
            .collect();
        assert_eq!(pts.len() % 2, 0);
        assert!(pts.len() >= 18);
        assert!((horizontal_total(&lines) - 10.0 * (pts.len() / 2) as f64).abs() < 1e-9);
        all_inside(&sq, &lines, 1e-9).unwrap();
    }

    #[test]
    fn angle_convention_45_runs_up_to_the_right() {
        let sq = rect(0.0, 0.0, 10.0, 10.0);
        let o = HatchOptions::DEFAULT.with_spacing(2.0);
        let lines = hatch_region(&sq, &o).unwrap();
        let seg = lines[0].segments().next().unwrap();
        let dir = seg.end() - seg.start();
        // Along ±(1, −1): up the page to the right (y down).
        assert!((dir.x + dir.y).abs() < 1e-9, "{dir:?}");
    }

    #[test]
    fn ring_lines_avoid_the_hole() {
        let ring = circle(0.0, 0.0, 10.0).difference(&circle(0.0, 0.0, 5.0));
        let o = HatchOptions::DEFAULT.with_angle_deg(0.0).with_spacing(0.5);
        let lines = hatch_region(&ring, &o).unwrap();
        all_inside(&ring, &lines, 2.0 * TOLERANCE).unwrap();
        // The hatched length approximates area / spacing.
        let want = ring.area() / 0.5;
        let got = horizontal_total(&lines);
        assert!((got - want).abs() < 0.02 * want, "{got} vs {want}");
        // Joining saved most pen lifts: far fewer paths than lines.
        assert!(lines.len() < 12, "{}", lines.len());
    }

    #[test]
    fn cross_hatching_doubles_and_inset_keeps_away() {
        let sq = rect(0.0, 0.0, 20.0, 20.0);
        let one = hatch_region(&sq, &HatchOptions::DEFAULT.with_spacing(1.0)).unwrap();
        let two = hatch_region(
            &sq,
            &HatchOptions::DEFAULT.with_spacing(1.0).with_cross(true),
        )
        .unwrap();
        let len = |v: &[BezPath]| v.iter().map(path_length).sum::<f64>();
        assert!(len(&two) > 1.9 * len(&one));
        let inset = hatch_region(
            &sq,
            &HatchOptions::DEFAULT.with_spacing(1.0).with_inset(2.0),
        )
        .unwrap();
        for l in &inset {
            let b = l.bounding_box();
            assert!(
                b.x0 >= 2.0 - 1e-6
                    && b.y0 >= 2.0 - 1e-6
                    && b.x1 <= 18.0 + 1e-6
                    && b.y1 <= 18.0 + 1e-6
            );
        }
        // An inset larger than the region leaves nothing.
        let none = hatch_region(&sq, &HatchOptions::DEFAULT.with_inset(11.0)).unwrap();
        assert!(none.is_empty());
    }

    #[test]
    fn concave_bays_are_not_bridged() {
        // A U shape: lines across both arms must not be joined across the gap.
        let u = rect(0.0, 0.0, 30.0, 30.0).difference(&rect(10.0, 0.0, 20.0, 20.0));
        let o = HatchOptions::DEFAULT.with_angle_deg(0.0).with_spacing(1.0);
        let lines = hatch_region(&u, &o).unwrap();
        all_inside(&u, &lines, 1e-6).unwrap();
    }

    #[test]
    fn bad_options_are_errors() {
        let sq = rect(0.0, 0.0, 1.0, 1.0);
        let bad = [
            HatchOptions::DEFAULT.with_spacing(0.0),
            HatchOptions::DEFAULT.with_spacing(-1.0),
            HatchOptions::DEFAULT.with_spacing(f64::NAN),
            HatchOptions::DEFAULT.with_angle_deg(f64::INFINITY),
            HatchOptions::DEFAULT.with_inset(-0.1),
            HatchOptions::DEFAULT.with_inset(f64::NAN),
        ];
        for o in bad {
            let e = hatch_region(&sq, &o).unwrap_err().to_string();
            assert!(e.starts_with("hatch."), "{e}");
        }
        let huge = rect(0.0, 0.0, 1000.0, 1000.0);
        let e = hatch_region(&huge, &HatchOptions::DEFAULT.with_spacing(1e-6)).unwrap_err();
        assert!(e.to_string().contains("lines"), "{e}");
        assert!(hatch_region(&Region::empty(), &HatchOptions::DEFAULT)
            .unwrap()
            .is_empty());
    }

    #[test]
    fn options_serde_round_trip_and_defaults() {
        let o: HatchOptions = serde_json::from_str(r#"{"spacing": 0.8, "cross": true}"#).unwrap();
        assert_eq!(o, HatchOptions::DEFAULT.with_spacing(0.8).with_cross(true));
        let back: HatchOptions = serde_json::from_str(&serde_json::to_string(&o).unwrap()).unwrap();
        assert_eq!(back, o);
        assert!(serde_json::from_str::<HatchOptions>(r#"{"spacin": 1}"#).is_err());
    }

    #[test]
    fn run_replaces_fills_in_page_units() {
        let mut g = Group::new("g");
        // Scaled by 2: a 5×5 square in group units is 10×10 mm on the page.
        g.transform = Affine::scale(2.0);
        g.push_path(
            "black",
            Rect::new(0.0, 0.0, 5.0, 5.0).to_path(0.0),
            Style {
                fill: Some(Color::BLACK),
                ..Style::default()
            },
        );
        g.push_path(
            "white",
            Rect::new(10.0, 0.0, 15.0, 5.0).to_path(0.0),
            Style {
                fill: Some(WHITE),
                ..Style::default()
            },
        );
        g.push_path(
            "plain",
            Rect::new(0.0, 10.0, 5.0, 15.0).to_path(0.0),
            Style::default(),
        );
        let mut scene = Scene::one_pen(
            Page::named(PaperName::A5, Orientation::Portrait, Margins::uniform(10.0)),
            g,
        );
        let o = HatchOptions::DEFAULT.with_angle_deg(0.0).with_spacing(1.0);
        run(&mut scene, &o).unwrap();
        let scene_pen = scene.pen_width(1);
        let mut ids = Vec::new();
        let mut fills = 0;
        scene.visit_paths(|_, p, t| {
            ids.push(p.id.clone());
            fills += usize::from(p.style.fill.is_some());
            if p.id.contains(".hatch-") {
                // Horizontal pieces on the page are 10 mm long but for
                // the outline's clearance at each end.
                let page = t * p.path.clone();
                let s = page.segments().next().unwrap();
                let clear = OUTLINE_CLEARANCE * scene_pen;
                let length = (s.end() - s.start()).hypot();
                assert!((length - (10.0 - 2.0 * clear)).abs() < 1e-6, "{length}");
            }
        });
        assert_eq!(fills, 0);
        assert_eq!(&ids[..2], ["black", "black.hatch-0"]);
        assert!(ids.contains(&"white".to_string()) && ids.contains(&"plain".to_string()));
        assert!(!ids.iter().any(|i| i.starts_with("white.hatch")));
        assert!(run(&mut scene, &HatchOptions::DEFAULT.with_spacing(0.0)).is_err());
    }

    #[test]
    fn paint_no_pen_outlines_is_hatched_to_its_edge_and_still_hides() {
        // Paint whose edge no line draws is hatched up to the inset; paint
        // whose edge other line work draws keeps clear of it as of an
        // outline.
        for edge_drawn in [false, true] {
            let mut g = Group::new("g");
            g.push_path(
                "paint",
                Rect::new(0.0, 0.0, 10.0, 10.0).to_path(0.0),
                Style {
                    fill: Some(Color::BLACK),
                    fill_only: true,
                    edge_drawn,
                    ..Style::default()
                },
            );
            let mut scene = Scene::one_pen(
                Page::named(PaperName::A5, Orientation::Portrait, Margins::uniform(10.0)),
                g,
            );
            let clear = if edge_drawn {
                OUTLINE_CLEARANCE * scene.pen_width(1)
            } else {
                0.0
            };
            let o = HatchOptions::DEFAULT
                .with_angle_deg(0.0)
                .with_spacing(1.0)
                .with_inset(0.5);
            run(&mut scene, &o).unwrap();
            let mut found = Vec::new();
            scene.visit_paths(|_, p, t| {
                let page = t * p.path.clone();
                let s = page.segments().next().unwrap();
                found.push((p.id.clone(), p.style.clone(), (s.end() - s.start()).hypot()));
            });
            // The lines stop at the inset (and the clearance), 9 mm long
            // less the clearance at each end.
            assert!(found.len() >= 2, "{found:?}");
            for (id, style, length) in &found[1..] {
                assert!(id.starts_with("paint.hatch-") && style.is_drawn(), "{id}");
                let want = 9.0 - 2.0 * clear;
                assert!((length - want).abs() < 1e-6, "{id}: {length}, not {want}");
            }
            // The paint is now a mask: nothing to draw, an area that hides.
            let (id, style, _) = &found[0];
            assert_eq!(id, "paint");
            assert_eq!(
                *style,
                Style {
                    mask: true,
                    edge_drawn,
                    ..Style::default()
                }
            );
        }
    }

    #[test]
    fn lines_and_joins_run_beside_the_drawn_outline_not_on_it() {
        // A 10 mm square hatched at 45°: every vertex of the hatch (line
        // ends and the corners its joins turn) lies OUTLINE_CLEARANCE pen
        // widths inside the outline, and no closer — so a join never
        // draws the outline again, and the lines' ink still meets the
        // outline's.
        let mut g = Group::new("g");
        g.push_path(
            "black",
            Rect::new(0.0, 0.0, 10.0, 10.0).to_path(0.0),
            Style {
                fill: Some(Color::BLACK),
                ..Style::default()
            },
        );
        let mut scene = Scene::one_pen(
            Page::named(PaperName::A5, Orientation::Portrait, Margins::uniform(10.0)),
            g,
        );
        run(&mut scene, &HatchOptions::DEFAULT).unwrap();
        let clear = OUTLINE_CLEARANCE * scene.pen_width(1);
        assert!(clear > 0.5 * scene.pen_width(1), "the inks overlap");
        let mut vertices = 0;
        scene.visit_paths(|_, p, _| {
            if !p.id.contains(".hatch-") {
                return;
            }
            // In the square's own units (the group is not transformed).
            for el in p.path.elements() {
                if let PathEl::MoveTo(q) | PathEl::LineTo(q) = el {
                    let d = q.x.min(q.y).min(10.0 - q.x).min(10.0 - q.y);
                    assert!((d - clear).abs() < TOLERANCE, "{q:?} lies {d} mm inside");
                    vertices += 1;
                }
            }
        });
        assert!(vertices > 40, "{vertices}");
    }

    #[test]
    fn a_path_with_its_own_spacing_is_hatched_even_without_options() {
        let mut g = Group::new("l.g");
        let own = Style {
            fill: Some(Color::BLACK),
            hatch: Some(2.5),
            ..Style::default()
        };
        g.push_path("own", Rect::new(0.0, 0.0, 20.0, 20.0).to_path(0.0), own);
        g.push_path(
            "fill",
            Rect::new(30.0, 0.0, 40.0, 10.0).to_path(0.0),
            Style {
                fill: Some(Color::BLACK),
                ..Style::default()
            },
        );
        let mut scene = Scene {
            page: Page::named(PaperName::A5, Orientation::Portrait, Margins::uniform(10.0)),
            pens: Vec::new(),
            layers: vec![Layer {
                id: "l".into(),
                name: "l".into(),
                pen: 1,
                depth: 0,
                content: g,
            }],
            description: None,
        };
        assert!(has_own_hatch(&scene));
        let before = scene.clone();
        run_own(&mut scene).unwrap();
        let mut hatch_len = 0.0;
        let mut kept_fill = Vec::new();
        scene.visit_paths(|_, p, _| {
            if p.id.starts_with("own.hatch-") {
                hatch_len += path_length(&p.path);
            }
            if p.style.fill.is_some() {
                kept_fill.push(p.id.clone());
            }
        });
        // 400 mm² at 2.5 mm spacing: about 160 mm of lines (plus joins).
        assert!((150.0..200.0).contains(&hatch_len), "{hatch_len}");
        assert_eq!(kept_fill, ["fill"], "a fill without its own spacing stays");
        assert!(!has_own_hatch(&scene));
        // With options, the path's own spacing still wins over theirs.
        let mut with = before;
        run(&mut with, &HatchOptions::DEFAULT.with_spacing(0.5)).unwrap();
        let mut own_len = 0.0;
        with.visit_paths(|_, p, _| {
            if p.id.starts_with("own.hatch-") {
                own_len += path_length(&p.path);
            }
        });
        assert!(
            (own_len - hatch_len).abs() < 1e-6,
            "{own_len} vs {hatch_len}"
        );
    }

    /// Performance sanity, not asserted: `cargo test --release --lib
    /// hatch_a_page_of_blobs -- --ignored --nocapture`.
    #[test]
    #[ignore]
    #[allow(clippy::print_stderr)]
    fn hatch_a_page_of_blobs() {
        let blobs: Vec<Region> = (0..300)
            .map(|i| {
                let (x, y) = ((i % 15) as f64 * 13.0, (i / 15) as f64 * 14.0);
                circle(x + (i % 4) as f64, y, 5.0 + (i % 6) as f64)
            })
            .collect();
        let field = Region::union_all(&blobs);
        let o = HatchOptions::DEFAULT.with_spacing(0.5).with_cross(true);
        let t = std::time::Instant::now();
        let lines = hatch_region(&field, &o).unwrap();
        let segments: usize = lines.iter().map(|l| l.segments().count()).sum();
        eprintln!(
            "hatched {:.0} mm² (bounds {:?}) in {:?}: {} paths, {} segments, {:.0} mm of ink",
            field.area(),
            field.bounds(),
            t.elapsed(),
            lines.len(),
            segments,
            lines.iter().map(path_length).sum::<f64>()
        );
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        #[test]
        fn every_hatch_line_lies_inside(r in arb_region(), angle in 0.0..180.0f64,
                                        spacing in 0.3..3.0f64, cross in any::<bool>()) {
            let o = HatchOptions::DEFAULT
                .with_angle_deg(angle)
                .with_spacing(spacing)
                .with_cross(cross);
            let lines = hatch_region(&r, &o).unwrap();
            // The lines keep one grid over the page, so neighbouring regions
            // line up; a region narrower than the spacing may fall between
            // two of them. One at least as wide as the spacing cannot.
            let across = |deg: f64| {
                let t = f64::to_radians(deg);
                let n = Vec2::new(t.sin(), t.cos());
                let v: Vec<f64> = r.polygons(TOLERANCE).iter().flatten()
                    .map(|p| p.to_vec2().dot(n)).collect();
                v.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                    - v.iter().copied().fold(f64::INFINITY, f64::min)
            };
            let widest = if cross { across(angle).max(across(angle + 90.0)) } else { across(angle) };
            if widest >= spacing {
                prop_assert!(!lines.is_empty(), "{} wide, spacing {}", widest, spacing);
            }
            if let Err(e) = all_inside(&r, &lines, 2.0 * TOLERANCE) {
                return Err(TestCaseError::fail(e));
            }
        }
    }
}
