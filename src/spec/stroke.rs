//! A stroke on the page that a family follows (a sketch's, a vine's
//! guide): given as points, as an SVG file's first path, or as a region
//! line of the scene's flow. The tables that take one share these checks.

use serde::{Deserialize, Serialize};

use super::validate::points;
use super::Points;
use crate::error::{Error, Result};

/// Checks that exactly one of a stroke's three sources is given, and
/// given well.
pub(crate) fn one_stroke(
    f: &str,
    given_points: Option<&Points>,
    svg: Option<&str>,
    line: Option<FlowLine>,
) -> Result<()> {
    let given = [given_points.is_some(), svg.is_some(), line.is_some()];
    match given.iter().filter(|g| **g).count() {
        0 => {
            return Err(Error::invalid(
                f,
                "needs a stroke: `points = [[x, y], …]`, `svg = \"stroke.svg\"` or `line = \"upper\"`",
            ));
        }
        1 => {}
        _ => {
            return Err(Error::invalid(
                f,
                "has more than one of `points`, `svg` and `line`: give one stroke",
            ));
        }
    }
    if let Some(p) = given_points {
        points(&format!("{f}.points"), p, 2)?;
    }
    if svg.is_some_and(|n| n.trim().is_empty()) {
        return Err(Error::invalid(format!("{f}.svg"), "needs a file name"));
    }
    Ok(())
}

/// A region line of the scene's flow.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FlowLine {
    /// `[lines] upper`.
    Upper,
    /// `[lines] lower`.
    Lower,
}
