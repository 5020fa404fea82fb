//! Background layers (docs/SPEC.md §1.6, [000 §3.3, §4.9–4.10]): a mask grown from
//! hidden trees, and a pattern composited only inside it.
//!
//! **Mask.** `count` hidden trees stand along the background's centre line
//! and grow both ways from it, as in the source's figures: up (stopped by
//! the upper region line) and down (stopped by the lower one). A stamp —
//! a circle unless another motif is named — is put on every vertex; the
//! mask is the union of the stamps, one region, rounded into clouds by a
//! closing of radius `cloud` (beyond the source, whose union of circles
//! reads as a string of balloons: every notch between two stamps is a
//! sharp corner). The composite modes:
//!
//! 1. the trees grow freely between the region lines;
//! 2. as 1, and a vertex outside every given circle also stops growth (a
//!    root outside every circle gets no stamp either);
//! 3. a sparser tree (Tree4 by default: few long forked branches), as 1;
//! 4. as 3, and only vertices inside a circle get a stamp.
//!
//! **Pattern.** What fills the mask, clipped to it (tiles are cut exactly
//! at the mask's outline):
//!
//! 0. none (beyond the source): the mask's outline alone, with its
//!    `paint` if any — a region for a later layer to fill with tangles or
//!    cells (`region.layer`);
//! 1. solid: the mask itself, filled (preview) and hatched (pens) — when
//!    the description gives no paint, a grey fill hatched every 1 mm;
//! 2. the motifs tiled edge to edge on a grid, alternating like a
//!    chequerboard (one motif repeats) — a single seigaiha, kikkō or
//!    shippō tile is drawn as the seamless ground it is cut from
//!    (`motif::ground`): no frame around each tile, no seam, every line
//!    once and as long as it runs; alternating with other motifs, a
//!    seigaiha tile is drawn without the square its waves fill;
//! 3. as 2 with `spacing` between tiles, every other column mirrored left
//!    to right;
//! 4. motifs at random places, sizes (0.6–1.2×) and angles, about one per
//!    tile area (with spacing) of the mask;
//! 5. "special solid": the motif fitted to each stamp's box separately.
//!
//! The mask's outline is drawn unless `outline = false`; the base paint
//! (`paint`) fills it under patterns 2–5, and its `bokashi` shades it in
//! line (with the outline, in the mask's path). Ids: `<layer>.background.mask`,
//! `<layer>.background.tile-<n>` (`….ground` for a seamless ground, one
//! path of all its strokes). Later layers can fill the mask's islands
//! (`region.layer`).

use kurbo::{Affine, BezPath, Point, Rect, Shape, Vec2};

use super::placements;
use crate::error::Result;
use crate::family::kimono::tree::{self, Growth};
use crate::geom::clip::StrokeClipper;
use crate::geom::offset::closing;
use crate::geom::region::{FillRule, Region};
use crate::geom::PathWalker;
use crate::geom::voronoi::distinct;
use crate::geom::TOLERANCE;
use crate::motif::bokashi::shade;
use crate::motif::flora::Drawing;
use crate::motif::flow_line;
use crate::motif::Context;
use crate::rng::RandomStream;
use crate::scene::traditional::Palette;
use crate::scene::{Color, Group, Style};
use crate::motif::ground::{self, Ground, Laid};
use crate::spec::{
    BackgroundSpec, LeavesSpec, MistSpec, MotifKind, MotifRef, PaintSpec, TreeSetSpec,
};

/// Each step of a mist band stands this much of the band's height above
/// the one below it.
const STEP_LIFT: f64 = 0.4;

/// Grey of a solid pattern when the description gives no paint.
const SOLID_GREY: Color = Color::rgb(0xc8, 0xc8, 0xc8);

/// Hatch spacing (mm) of a solid pattern when the description gives none.
const SOLID_HATCH: f64 = 1.0;

/// At most this many tiles are tried for pattern 4 (a safety net: the
/// count follows the mask's area).
const MAX_RANDOM_TILES: usize = 100_000;

/// The background of a layer, as a group `group_id`.
pub(crate) fn background(
    bg: &BackgroundSpec,
    group_id: &str,
    cx: &mut Context<'_>,
) -> Result<Group> {
    let mut group = Group::new(group_id);
    let mut rng = cx.stream(&format!("{group_id}.stamp"));
    let stamp = cx.library().draw(&bg.stamp, &mut rng)?;
    let (regions, stamp_boxes) = match &bg.mist {
        Some(mist) => {
            let mut rng = cx.stream(&format!("{group_id}.mist"));
            let bands = mist_bands(bg, mist, &mut rng);
            // Pattern 5 fits its motif to each band's box.
            let boxes = bands
                .iter()
                .map(|r| {
                    let (b, s) = (r.bounds(), stamp.outline.bounding_box());
                    Affine::translate(b.center().to_vec2())
                        * Affine::scale_non_uniform(b.width() / s.width(), b.height() / s.height())
                        * Affine::translate(-s.center().to_vec2())
                })
                .collect();
            (bands, boxes)
        }
        None => {
            let stamps = stamp_sites(bg, group_id, cx)?;
            let boxes: Vec<Affine> = stamps
                .iter()
                .map(|p| {
                    Affine::translate(p.to_vec2())
                        * unit_to(&stamp, bg.stamp_width, bg.stamp_height)
                })
                .collect();
            let regions = boxes
                .iter()
                .filter_map(|m| Region::new(*m * stamp.outline.clone(), FillRule::NonZero).ok())
                .collect();
            (regions, boxes)
        }
    };
    // Rounded into clouds: the notches between stamps become arcs.
    let mask = closing(&Region::union_all(&regions), bg.cloud_radius(), TOLERANCE)?;
    if mask.is_empty() {
        return Ok(group);
    }
    if cx.regions_wanted() {
        // Each island of the mask is a region of its own to fill.
        cx.offer(mask.components());
    }

    let base = if bg.pattern == 1 {
        solid_style(&bg.paint, cx.palette())
    } else {
        paint_style(&bg.paint, cx.palette())
    };
    if bg.outline || base.fill.is_some() || bg.paint.bokashi.is_some() {
        cx.take_paths(1, || format!("background {group_id}"))?;
        // Without outline and fill, the shading is drawn alone.
        let mut path = if bg.outline || base.fill.is_some() {
            mask.path().clone()
        } else {
            BezPath::new()
        };
        if let Some(b) = &bg.paint.bokashi {
            path.extend(shade(mask.path(), b)?.elements().iter().copied());
        }
        group.push_path(format!("{group_id}.mask"), path, base);
    }

    if let Some(laid) = seamless(bg) {
        ground_in(laid, &mask, group_id, &mut group, cx)?;
        return Ok(group);
    }
    let clipper = StrokeClipper::new(&mask, TOLERANCE);
    let motifs: Vec<Drawing> = bg
        .motifs
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let mut rng = cx.stream(&format!("{group_id}.motif-{i}"));
            cx.library().draw(m, &mut rng)
        })
        .collect::<Result<_>>()?;
    let mut scatter = cx.stream(&format!("{group_id}.scatter"));
    let mut tiles = Tiles {
        group: &mut group,
        clipper: &clipper,
        cx,
        id: group_id,
        n: 0,
    };
    let bounds = mask.bounds();
    match bg.pattern {
        2 | 3 => {
            let mirror = bg.pattern == 3;
            let gap = if mirror { bg.spacing } else { 0.0 };
            let w = bg.width;
            let h = bg.height.unwrap_or(w * motifs[0].aspect);
            let (cols, rows) = grid(bounds, w + gap, h + gap);
            // Every cell is tried and clipped, drawn or not: the grid is
            // work the budget has to allow before it starts.
            tiles.cx.take_paths(cols.saturating_mul(rows), || {
                format!("background {group_id}: a grid of {cols} × {rows} tiles")
            })?;
            for row in 0..rows {
                for col in 0..cols {
                    let k = (row + col) % motifs.len();
                    let d = &motifs[k];
                    let centre = Point::new(
                        grid_start(bounds.x0, w + gap) + (col as f64 + 0.5) * (w + gap),
                        grid_start(bounds.y0, h + gap) + (row as f64 + 0.5) * (h + gap),
                    );
                    let flip = if mirror && col % 2 == 1 { -1.0 } else { 1.0 };
                    let m = Affine::translate(centre.to_vec2())
                        * Affine::scale_non_uniform(flip * w, h)
                        * Affine::translate(-d.outline.bounding_box().center().to_vec2());
                    tiles.push_in_grid(d, m, kind_of(&bg.motifs[k]))?;
                }
            }
        }
        4 => {
            let rng = &mut scatter;
            let w = bg.width;
            let cell = (w + bg.spacing).powi(2);
            let wanted = ((mask.area() / cell).ceil() as usize).min(MAX_RANDOM_TILES);
            tiles.cx.take_paths(wanted, || {
                format!("background {group_id}: {wanted} scattered tiles")
            })?;
            let mut placed = 0;
            for _ in 0..wanted * 20 {
                if placed == wanted {
                    break;
                }
                let p = Point::new(
                    rng.range(bounds.x0, bounds.x1),
                    rng.range(bounds.y0, bounds.y1),
                );
                if !mask.contains(p) {
                    continue;
                }
                let d = &motifs[placed % motifs.len()];
                let size = rng.range(0.6, 1.2);
                let angle = rng.range(0.0, std::f64::consts::TAU);
                let h = bg.height.unwrap_or(w * d.aspect);
                let m = Affine::translate(p.to_vec2())
                    * Affine::rotate(angle)
                    * Affine::scale_non_uniform(w * size, h * size)
                    * Affine::translate(-d.outline.bounding_box().center().to_vec2());
                tiles.push(d, m)?;
                placed += 1;
            }
        }
        5 => {
            tiles.cx.take_paths(stamp_boxes.len(), || {
                format!("background {group_id}: tiles")
            })?;
            for m in &stamp_boxes {
                let d = &motifs[0];
                let fit = *m
                    * Affine::translate(stamp.outline.bounding_box().center().to_vec2())
                    * Affine::translate(-d.outline.bounding_box().center().to_vec2());
                tiles.push(d, fit)?;
            }
        }
        _ => {}
    }
    Ok(group)
}

/// The seamless ground a tiled pattern draws (with its scale, lines and
/// turn, matching the tile's size), or `None`: patterns 2 and 3 of one
/// built-in seigaiha, kikkō or shippō tile at its own proportions (3
/// without spacing, its mirrored columns being the same) draw the ground
/// the tiles are cut from, not a grid of framed tiles.
///
/// * seigaiha: two fans across a tile, `petals` rings each;
/// * kikkō: the tile's hexagon (points left and right, the tile's width
///   across them) in a honeycomb, `petals` + 1 outlines each;
/// * shippō: circles as wide as a tile, at every tile's centre and corner.
fn seamless(bg: &BackgroundSpec) -> Option<(Ground, f64, u32, f64)> {
    if !matches!(bg.pattern, 2 | 3) || bg.height.is_some() || bg.pattern == 3 && bg.spacing != 0.0 {
        return None;
    }
    let [motif] = bg.motifs.as_slice() else {
        return None;
    };
    let kind = kind_of(motif)?;
    let petals = match motif {
        MotifRef::Built(b) => b.petals,
        _ => None,
    };
    let w = bg.width;
    match kind {
        MotifKind::Seigaiha => Some((Ground::Seigaiha, w / 4.0, petals.unwrap_or(4).clamp(1, 5), 0.0)),
        MotifKind::Kikko => Some((Ground::Kikko, w / 2.0, petals.unwrap_or(1).clamp(1, 2) + 1, 30.0)),
        MotifKind::Shippo => Some((Ground::Shippo, w / 2.0, 1, 45.0)),
        _ => None,
    }
}

/// The built-in motif `motif` names, or `None` for one read from a file.
fn kind_of(motif: &MotifRef) -> Option<MotifKind> {
    match motif {
        MotifRef::Name(kind) => Some(*kind),
        MotifRef::Built(b) => Some(b.kind),
        MotifRef::File(_) => None,
    }
}

/// A ground `(ground, scale, lines, angle)` over all of `mask`, appended
/// to `group` as one path: no frame, no seam, every line once. The frame's
/// origin is the page's, so neighbouring backgrounds of one ground line
/// up. One path, as a tile is: its closed strokes (shippō's circles,
/// kikkō's hexagons) are lines of one pattern, not shapes hiding one
/// another when hidden lines are removed.
fn ground_in(
    (ground, scale, lines, angle): (Ground, f64, u32, f64),
    mask: &Region,
    group_id: &str,
    group: &mut Group,
    cx: &mut Context<'_>,
) -> Result<()> {
    let laid = Laid::new(mask.bounds(), scale, Point::ZERO, angle);
    let estimate = ground::estimate(ground, scale, lines, laid.window());
    let what = || format!("background {group_id}: {} at {scale} mm", ground.name());
    // A ground too fine for its mask fails here, before the work.
    cx.budget()
        .clone()
        .take(estimate.min(usize::MAX as f64) as usize, what)?;
    let drawn = laid.draw(mask, ground, scale, lines, cx.pen_width())?;
    if drawn.strokes.is_empty() {
        return Ok(());
    }
    // Each stroke is a pen's stroke, as a tile was a path.
    cx.take_paths(drawn.strokes.len(), what)?;
    let mut path = BezPath::new();
    for stroke in drawn.strokes {
        path.extend(stroke.elements().iter().copied());
    }
    group.push_path(format!("{group_id}.ground"), path, Style::default());
    Ok(())
}

/// Motif units → mm: `width × height` (height from the motif's aspect when
/// not given), anchor at the origin.
fn unit_to(d: &Drawing, width: f64, height: Option<f64>) -> Affine {
    let h = height.unwrap_or(width * d.aspect);
    Affine::scale_non_uniform(width, h) * Affine::translate(-d.anchor.to_vec2())
}

/// Grid lines are aligned to multiples of the cell from the page origin,
/// so neighbouring backgrounds with the same tiles line up.
fn grid_start(lo: f64, cell: f64) -> f64 {
    (lo / cell).floor() * cell
}

/// Columns and rows of cells covering `bounds`.
fn grid(bounds: Rect, cw: f64, ch: f64) -> (usize, usize) {
    let cols = ((bounds.x1 - grid_start(bounds.x0, cw)) / cw)
        .ceil()
        .max(0.0) as usize;
    let rows = ((bounds.y1 - grid_start(bounds.y0, ch)) / ch)
        .ceil()
        .max(0.0) as usize;
    (cols, rows)
}

/// Tiles clipped to the mask, appended to the group. The pattern takes
/// its tiles from the budget before it places them.
struct Tiles<'a, 'b, 'c> {
    group: &'a mut Group,
    clipper: &'a StrokeClipper,
    cx: &'a mut Context<'c>,
    id: &'b str,
    n: usize,
}

impl Tiles<'_, '_, '_> {
    /// Tile `d` placed by `m`, outline and details.
    fn push(&mut self, d: &Drawing, m: Affine) -> Result<()> {
        self.push_path(&d.to_path(m))
    }

    /// Tile `d` placed by `m` in a grid, without its outline when that is
    /// only the square its pattern fills (seigaiha): side by side the
    /// waves run on across the tiles' edges, and a frame would be a seam
    /// drawn between them.
    fn push_in_grid(&mut self, d: &Drawing, m: Affine, kind: Option<MotifKind>) -> Result<()> {
        match kind {
            Some(MotifKind::Seigaiha) => self.push_path(&(m * d.details.clone())),
            _ => self.push(d, m),
        }
    }

    fn push_path(&mut self, path: &BezPath) -> Result<()> {
        let inside = self.clipper.clip(path).inside;
        if inside.is_empty() {
            return Ok(());
        }
        let mut joined = BezPath::new();
        for piece in inside {
            joined.extend(piece.elements().iter().copied());
        }
        let id = format!("{}.tile-{}", self.id, self.n);
        self.n += 1;
        self.group.push_path(id, joined, Style::default());
        Ok(())
    }
}

fn paint_style(paint: &PaintSpec, palette: &Palette) -> Style {
    Style {
        fill: paint.color(palette),
        hatch: paint.hatch,
        fill_only: false,
        edge_drawn: false,
        mask: false,
    }
}

/// Pattern 1's paint: the description's, or grey hatched every 1 mm.
fn solid_style(paint: &PaintSpec, palette: &Palette) -> Style {
    let style = paint_style(paint, palette);
    Style {
        fill: style.fill.or(Some(SOLID_GREY)),
        hatch: style.hatch.or(Some(SOLID_HATCH)),
        fill_only: false,
        edge_drawn: false,
        mask: false,
    }
}

/// Mist bands along the background's centre line: `bands` stacked across
/// it (the middle one on the line), each running along a random stretch of
/// 40–75 % of the line with rounded ends, and `steps` shorter bands on its
/// upper side, each [`STEP_LIFT`] of a height higher and cut shorter at a
/// random mix of its two ends, so the band's upper edge climbs in steps.
fn mist_bands(bg: &BackgroundSpec, mist: &MistSpec, rng: &mut RandomStream) -> Vec<Region> {
    let walker = PathWalker::new(&flow_line(&bg.centre), TOLERANCE);
    let total = walker.length();
    let h = mist.height;
    // A band with its steps is this thick; bands are `gap` apart.
    let lift = STEP_LIFT * h;
    let pitch = h + lift * f64::from(mist.steps) + mist.gap.unwrap_or(0.5 * h);
    let mut out = Vec::new();
    for band in 0..mist.bands {
        let across = (f64::from(band) - 0.5 * f64::from(mist.bands - 1)) * pitch;
        let length = total * rng.range(0.4, 0.75);
        let start = rng.range(0.0, total - length);
        for step in 0..=mist.steps {
            // Each step is shorter than the one below by a fifth of the
            // band, taken from its two ends in a random proportion.
            let cut = 0.2 * length * f64::from(step);
            let left = cut * rng.range(0.2, 0.8);
            let (a, b) = (start + left, start + length - (cut - left));
            if b - a < h {
                break;
            }
            let up = across + lift * f64::from(step);
            if let Some(r) = band_region(&walker, a, b, up, h) {
                out.push(r);
            }
        }
    }
    out
}

/// The band of thickness `h` with round ends along the stretch `a`–`b` of
/// the line, moved `lift` mm to its upper side (negative: the lower).
fn band_region(walker: &PathWalker, a: f64, b: f64, lift: f64, h: f64) -> Option<Region> {
    let n = ((b - a) / 0.5).ceil().max(1.0) as usize;
    let mut line = BezPath::new();
    for k in 0..=n {
        let s = a + (b - a) * k as f64 / n as f64;
        let t = walker.tangent_at(s);
        // Up the page from the line: its normal with y < 0.
        let normal = Vec2::new(t.y, -t.x);
        let up = if normal.y > 0.0 { -normal } else { normal };
        let p = walker.point_at(s) + up * lift;
        if k == 0 {
            line.move_to(p);
        } else {
            line.line_to(p);
        }
    }
    let style = kurbo::Stroke::new(h).with_caps(kurbo::Cap::Round);
    let outline = kurbo::stroke(line, &style, &kurbo::StrokeOpts::default(), TOLERANCE);
    Region::new(outline, FillRule::NonZero).ok()
}

/// The vertices that get a stamp, from the hidden mask trees.
fn stamp_sites(bg: &BackgroundSpec, group_id: &str, cx: &mut Context<'_>) -> Result<Vec<Point>> {
    let circles: Vec<(Point, f64)> = bg
        .circles
        .iter()
        .map(|[x, y, r]| (Point::new(*x, *y), *r))
        .collect();
    let in_circles = |p: Point| circles.iter().any(|(c, r)| c.distance(p) <= *r);
    let set = TreeSetSpec {
        id: None,
        rule: bg.mask_rule(),
        count: bg.count,
        centre: bg.centre.clone(),
        growth: bg.growth,
        rotate: 0.0,
        params: bg.params.clone(),
        rhythm: Default::default(),
        reach: None,
        vary: None,
        overrides: Vec::new(),
        flowers: None,
        leaves: LeavesSpec::default(),
    };
    let params = set.params.resolve();
    // The hidden trees' limbs are never drawn, but they cost like paths,
    // so they count against the budget.
    let mut sites = Vec::new();
    for (i, place) in placements(&set).into_iter().enumerate() {
        for (way, direction) in [("up", place.direction), ("down", -place.direction)] {
            let downward = direction.y > 0.0;
            let flow = cx.flow();
            let blocked =
                |q: Point| flow.blocks(q, downward) || (bg.composite == 2 && !in_circles(q));
            let id = format!("{group_id}.mask-{i}.{way}");
            let stream = cx.stream(&id);
            let skeleton = tree::grow(
                set.rule,
                &params,
                &Growth {
                    root: place.root,
                    direction,
                    blocked: &blocked,
                mirror: false,
            },
                stream,
                cx.budget(),
                &format!("background tree {id}"),
            )?;
            sites.extend(
                skeleton
                    .vertices()
                    .filter(|p| !matches!(bg.composite, 2 | 4) || in_circles(*p)),
            );
        }
        cx.advance(1);
    }
    // Trees grown up and down from one root share it, and limbs of equal
    // length can meet again: one stamp a place, or its tile is drawn twice.
    Ok(distinct(&sites))
}
