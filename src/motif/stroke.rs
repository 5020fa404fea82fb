//! A line on the page given one of three ways — points (a natural spline
//! or straight lines), the first path of an SVG file, or a region line of
//! the scene's flow — as a dense polyline: what a sketch grows along and
//! what a vine winds round.

use glam::DVec2;
use kurbo::BezPath;

use super::{flow_line, Context};
use crate::error::{Error, Result};
use crate::geom::TOLERANCE;
use crate::spec::{FlowLine, Points};

/// Where a stroke comes from (the spec has checked that one is given).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Stroke<'a> {
    /// Points, mm.
    pub(crate) points: Option<&'a Points>,
    /// With `points`: a natural spline through them, not straight lines.
    pub(crate) smooth: bool,
    /// Or the name of an SVG file the library holds.
    pub(crate) svg: Option<&'a str>,
    /// Or a region line of the scene's flow.
    pub(crate) line: Option<FlowLine>,
}

/// The stroke as a dense polyline (page mm); errors name `field`.
///
/// # Errors
/// [`Error::Invalid`] when the flow has no such region line or the stroke
/// is empty; [`Error::Motif`] for an SVG file not loaded.
pub(crate) fn stroke_points(
    stroke: &Stroke<'_>,
    field: &str,
    cx: &Context<'_>,
) -> Result<Vec<DVec2>> {
    let path = match (stroke.points, stroke.svg) {
        (Some(points), _) if stroke.smooth => flow_line(points),
        (Some(points), _) => {
            let mut line = BezPath::new();
            for (i, &[x, y]) in points.iter().enumerate() {
                if i == 0 {
                    line.move_to((x, y));
                } else {
                    line.line_to((x, y));
                }
            }
            line
        }
        (None, Some(name)) => first_subpath(cx.library().paths(name)?),
        (None, None) => match stroke.line {
            Some(which) => {
                let upper = which == FlowLine::Upper;
                cx.flow().line(upper).cloned().ok_or_else(|| {
                    Error::invalid(
                        format!("{field}.line"),
                        format!(
                            "the scene has no {} region line: give [lines] {0} = [[x, y], …]",
                            if upper { "upper" } else { "lower" }
                        ),
                    )
                })?
            }
            None => BezPath::new(),
        },
    };
    let mut out: Vec<DVec2> = Vec::new();
    kurbo::flatten(&path, TOLERANCE, |el| {
        if let kurbo::PathEl::MoveTo(p) | kurbo::PathEl::LineTo(p) = el {
            out.push(DVec2::new(p.x, p.y));
        }
    });
    if out.len() < 2 {
        return Err(Error::invalid(
            field,
            "its stroke is empty: give a line with length",
        ));
    }
    Ok(out)
}

/// The first subpath of `path`.
fn first_subpath(path: &BezPath) -> BezPath {
    let mut out = BezPath::new();
    for el in path.elements() {
        if matches!(el, kurbo::PathEl::MoveTo(_)) && !out.elements().is_empty() {
            break;
        }
        out.push(*el);
    }
    out
}
