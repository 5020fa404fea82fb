//! Limbs drawn for the pen, the same for every family that grows them
//! (tree sets, L-systems): a limb too thin for an outline is a centre
//! stroke, and strokes are painted before outlines.

use kurbo::BezPath;

/// A limb whose outline would be narrower than this many pen widths is
/// drawn as a centre stroke.
pub(crate) const THIN: f64 = 2.0;

/// Limbs (each with its number) with the centre strokes first: the
/// outlines painted after them — a tree's silhouette — hide what of a
/// twig lies inside its branch when hidden lines are removed.
pub(crate) fn strokes_first(
    limbs: impl IntoIterator<Item = (usize, BezPath)>,
) -> Vec<(usize, BezPath)> {
    let (mut strokes, outlines): (Vec<_>, Vec<_>) = limbs
        .into_iter()
        .partition(|(_, p)| !crate::geom::subpath::is_closed(p));
    strokes.extend(outlines);
    strokes
}
