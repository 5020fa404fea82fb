//! The tile before any tangle, as the Zentangle method begins it: the
//! border inked once round the region (corners rounded if asked, bent by
//! the hand like every other line) and the string that splits what the
//! border encloses into sections. The loop starts from the sections; the
//! border's line is drawn whole, never clipped, and nothing is drawn
//! outside it.

use kurbo::{BezPath, Point};

use super::compose::uninked;
use super::element::{Mark, Paint};
use super::filling::by_hand;
use crate::error::{Error, Result};
use crate::geom::natural_spline;
use crate::geom::offset::offset;
use crate::geom::region::{FillRule, Region};
use crate::rng::RandomStream;
use crate::spec::{BorderSpec, StringSpec};

/// What the tile starts from.
#[derive(Debug, Default)]
pub(super) struct Tile {
    /// The blank sections: inside the border, less the border's ink and
    /// the ink of a string that is left out.
    pub(super) sections: Vec<Region>,
    /// The border's lines, one closed path per contour of each region.
    pub(super) border: Vec<BezPath>,
    /// The string's curves to ink: they split the sections as the
    /// description's `lines` do (empty when the string is left out).
    pub(super) string: Vec<BezPath>,
}

/// The tile of `regions`, each bordered if `border` asks, split by
/// `string`; `hand` mm of bending (0: none) drawn from `rng`, a pen
/// `pen` mm wide.
///
/// # Errors
/// [`Error::Invalid`] (field `border.corner`) when rounding the corners
/// leaves nothing of a region; the region machinery on degenerate
/// geometry.
pub(super) fn tile(
    regions: &[Region],
    border: Option<&BorderSpec>,
    string: Option<&StringSpec>,
    hand: f64,
    pen: f64,
    rng: &mut RandomStream,
) -> Result<Tile> {
    let tolerance = pen / 8.0;
    let mut tile = Tile::default();
    for region in regions {
        let Some(border) = border else {
            tile.sections.push(region.clone());
            continue;
        };
        let rounded = rounded(region, border.corner, tolerance)?;
        let line = bent(rounded.path().clone(), hand, rng)?;
        // The bent line's inside is the tile: nothing is drawn beyond it.
        let inside = Region::new(line.clone(), FillRule::NonZero)?;
        tile.sections
            .extend(uninked(&inside, std::slice::from_ref(&line), pen, tolerance));
        tile.border.push(line);
    }
    let Some(string) = string else {
        return Ok(tile);
    };
    let mut curves = Vec::with_capacity(string.lines.len());
    for points in &string.lines {
        let points: Vec<Point> = points.iter().map(|&[x, y]| Point::new(x, y)).collect();
        let curve = if string.smooth {
            natural_spline(&points)
        } else {
            polyline(&points)
        };
        curves.push(bent(curve, hand, rng)?);
    }
    if string.ink {
        tile.string = curves;
    } else {
        tile.sections = tile
            .sections
            .iter()
            .flat_map(|s| uninked(s, &curves, pen, tolerance))
            .collect();
    }
    Ok(tile)
}

/// `region` with its convex corners rounded to `radius` mm (an opening:
/// shrunk by the radius and grown back).
fn rounded(region: &Region, radius: f64, tolerance: f64) -> Result<Region> {
    if radius <= 0.0 {
        return Ok(region.clone());
    }
    let out = offset(&offset(region, -radius, tolerance)?, radius, tolerance)?;
    if out.is_empty() {
        return Err(Error::invalid(
            "border.corner",
            format!("{radius} mm rounds the region away: it is narrower than twice that"),
        ));
    }
    Ok(out)
}

/// `path` bent by the hand (`amount` mm; 0 leaves it as it is).
fn bent(path: BezPath, amount: f64, rng: &mut RandomStream) -> Result<BezPath> {
    if amount <= 0.0 {
        return Ok(path);
    }
    let mark = Mark {
        path,
        paint: Paint::Line,
    };
    Ok(by_hand(&mark, amount, rng)?.path)
}

/// A polyline through `points`.
pub(super) fn polyline(points: &[Point]) -> BezPath {
    let mut path = BezPath::new();
    for (i, &p) in points.iter().enumerate() {
        if i == 0 {
            path.move_to(p);
        } else {
            path.line_to(p);
        }
    }
    path
}
