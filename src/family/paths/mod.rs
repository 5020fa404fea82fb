//! The `paths` family: the user's own paths placed on the page (see
//! [`PathsSpec`] for where copies stand and how they are sized and turned).
//!
//! Each copy is one path, id `<layer>.<set>.path-<i>`, so `[[adjust]]` can
//! move, turn, scale or hide it about its site. Closed paths take the
//! set's paint (fill colour for the preview, hatching for pens, bokashi
//! lines in the copy's own path) and hide what lies behind them like any
//! other shape.

pub(crate) mod description;

use kurbo::{Affine, BezPath, PathEl, Point, Shape};

use crate::error::{Error, Result};
use crate::geom::{natural_spline, PathWalker, TOLERANCE};
use crate::motif::adjust::about;
use crate::motif::bokashi::shade;
use crate::motif::{flow_line, Context};
use crate::scene::{Group, Style};
use crate::spec::{Anchor, Orient, PathsSpec, MAX_COPIES};
use crate::units::MAX_COORD;

/// Places the copies of a paths table into a group with id `group_id`.
///
/// # Errors
/// The path budget; an SVG file that was not loaded; an adjustment that
/// asks for a motif; copies that would reach beyond ±MAX_COORD or number
/// more than [`MAX_COPIES`].
pub(super) fn build(spec: &PathsSpec, group_id: &str, cx: &mut Context<'_>) -> Result<Group> {
    let mut group = Group::new(group_id);
    let source = source(spec, cx)?;
    let Some(anchor) = anchor(&source, spec.anchor) else {
        return Ok(group);
    };
    let bounds = source.bounding_box();
    let fit = match spec.width {
        Some(w) if bounds.width() > 0.0 => w / bounds.width(),
        _ => 1.0,
    };
    let sites = sites(spec, anchor, cx)?;
    cx.take_paths(sites.len(), || format!("paths {group_id}"))?;
    let style = Style {
        fill: spec.paint.color(cx.palette()),
        hatch: spec.paint.hatch,
        fill_only: false,
        edge_drawn: false,
        mask: false,
    };
    let shape = Affine::rotate(spec.rotate.to_radians())
        * Affine::scale(fit * spec.scale)
        * Affine::translate(-anchor.to_vec2());
    for (i, (site, angle)) in sites.into_iter().enumerate() {
        let id = format!("{group_id}.path-{i}");
        let adjusted = cx.adjust().take_without_motif(&id, "a placed path")?;
        if adjusted.is_some_and(|a| a.hide) {
            continue;
        }
        let placed = about(adjusted, site)
            * Affine::translate(site.to_vec2())
            * Affine::rotate(angle)
            * shape
            * source.clone();
        let b = placed.bounding_box();
        if ![b.x0, b.y0, b.x1, b.y1]
            .iter()
            .all(|v| v.is_finite() && v.abs() <= MAX_COORD)
        {
            return Err(Error::invalid(
                cx.field("scale"),
                format!("copy {id} would reach beyond ±{MAX_COORD} mm"),
            ));
        }
        let mut path = placed;
        if let Some(b) = &spec.paint.bokashi {
            let lines = shade(&path, b)?;
            path.extend(lines.elements().iter().copied());
        }
        group.push_path(id, path, style.clone());
    }
    Ok(group)
}

/// The source geometry in its own mm.
fn source(spec: &PathsSpec, cx: &Context<'_>) -> Result<BezPath> {
    if let Some(points) = &spec.points {
        let pts: Vec<Point> = points.iter().map(|[x, y]| Point::new(*x, *y)).collect();
        let mut line = if spec.smooth {
            let mut through = pts.clone();
            if spec.closed {
                through.push(pts[0]);
            }
            natural_spline(&through)
        } else {
            let mut line = BezPath::new();
            line.move_to(pts[0]);
            for p in &pts[1..] {
                line.line_to(*p);
            }
            line
        };
        if spec.closed {
            line.close_path();
        }
        return Ok(line);
    }
    if let Some(path) = spec.parsed_d(&cx.item_field())? {
        return Ok(path);
    }
    match &spec.svg {
        Some(name) => cx.library().paths(name).cloned(),
        None => Ok(BezPath::new()),
    }
}

/// The point of the source put on each site; `None` for an empty source.
fn anchor(source: &BezPath, anchor: Anchor) -> Option<Point> {
    let start = match source.elements().first()? {
        PathEl::MoveTo(p) => *p,
        _ => return None,
    };
    Some(match anchor {
        Anchor::Centre => source.bounding_box().center(),
        Anchor::Origin => Point::ZERO,
        Anchor::Start => start,
    })
}

/// Where the copies stand and how far each is turned (radians, clockwise
/// on the page).
fn sites(spec: &PathsSpec, anchor: Point, cx: &Context<'_>) -> Result<Vec<(Point, f64)>> {
    let Some(line) = &spec.along else {
        let at = spec.at.map_or(anchor, |[x, y]| Point::new(x, y));
        return Ok(vec![(at, 0.0)]);
    };
    let walker = PathWalker::new(&flow_line(line), TOLERANCE);
    let length = walker.length();
    let spots: Vec<f64> = match spec.spacing {
        Some(step) => {
            let n = (length / step).floor() + 1.0;
            if n > MAX_COPIES as f64 {
                return Err(Error::invalid(
                    cx.field("spacing"),
                    format!(
                        "{step} mm along a {length:.0} mm line makes {n:.0} copies; at most {MAX_COPIES}"
                    ),
                ));
            }
            (0..n as usize).map(|k| k as f64 * step).collect()
        }
        None => {
            let n = spec.count.unwrap_or(1) as usize;
            (0..n)
                .map(|i| length * (i as f64 + 0.5) / n as f64)
                .collect()
        }
    };
    Ok(spots
        .into_iter()
        .map(|s| {
            let turn = match spec.orient {
                Orient::Line => {
                    let t = walker.tangent_at(s);
                    t.y.atan2(t.x)
                }
                Orient::Page => 0.0,
            };
            (walker.point_at(s), turn)
        })
        .collect())
}

#[cfg(test)]
mod tests;
