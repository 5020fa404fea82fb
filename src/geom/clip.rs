//! Clipping open strokes by a region: the parts of a stroke inside and the
//! parts outside (SPEC §2.4 "draw only inside that region", and hidden
//! lines for occlusion).
//!
//! The stroke keeps its curves: each of its segments is cut exactly at the
//! parameters where it crosses the region's boundary, and each piece is
//! classified by the containment of its middle point. The boundary is the
//! region's outline flattened within `tolerance`, so cut points (and the
//! inside/outside decision near the boundary) are right to within
//! `tolerance`; the pieces themselves are exact sub-curves of the stroke,
//! so inside and outside together have exactly the stroke's length.
//! Strokes that run along the boundary go either way.

use kurbo::{BezPath, Line, ParamCurve, PathEl, PathSeg, Point, Rect};

use super::region::Region;
use super::TOLERANCE;

/// Cuts closer than this in a segment's parameter are merged, and pieces
/// shorter than this in parameter are not made (a stroke that touches the
/// boundary at a vertex of the flattened outline would otherwise be cut
/// twice at the same place).
const PARAM_EPS: f64 = 1e-9;

/// A stroke split by a region.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Clipped {
    /// The parts inside the region, in the order and direction of the
    /// stroke.
    pub inside: Vec<BezPath>,
    /// The parts outside the region, likewise.
    pub outside: Vec<BezPath>,
}

/// Splits `stroke` into its parts inside and outside `region`, with the
/// region's boundary flattened within `tolerance` (mm; non-finite or
/// non-positive means [`TOLERANCE`]).
///
/// Each subpath of the stroke is cut where it crosses the boundary; runs of
/// pieces on the same side are joined into one path. A closed subpath that
/// never crosses stays closed; one that does is split into open paths (the
/// run through its start point is joined across it).
///
/// To clip many strokes by one region, make a [`StrokeClipper`] once.
pub fn clip_stroke(stroke: &BezPath, region: &Region, tolerance: f64) -> Clipped {
    StrokeClipper::new(region, tolerance).clip(stroke)
}

/// A region prepared for clipping many strokes: its flattened outline in a
/// grid of horizontal bands, so that each query looks at the edges nearby.
#[derive(Debug, Clone)]
pub struct StrokeClipper {
    edges: Vec<Line>,
    bounds: Rect,
    y0: f64,
    band_height: f64,
    bands: Vec<Vec<u32>>,
}

impl StrokeClipper {
    /// Prepares `region` (boundary flattened within `tolerance` mm;
    /// non-finite or non-positive means [`TOLERANCE`]).
    pub fn new(region: &Region, tolerance: f64) -> StrokeClipper {
        let tolerance = if tolerance.is_finite() && tolerance > 0.0 {
            tolerance
        } else {
            TOLERANCE
        };
        let mut edges = Vec::new();
        for poly in region.polygons(tolerance) {
            for i in 0..poly.len() {
                edges.push(Line::new(poly[i], poly[(i + 1) % poly.len()]));
            }
        }
        let bounds = region.bounds();
        let n_bands = (edges.len() / 4).clamp(1, 4096);
        let band_height = (bounds.height() / n_bands as f64).max(f64::MIN_POSITIVE);
        let mut bands = vec![Vec::new(); n_bands];
        let mut clipper = StrokeClipper {
            edges: Vec::new(),
            bounds,
            y0: bounds.y0,
            band_height,
            bands: Vec::new(),
        };
        for (k, e) in edges.iter().enumerate() {
            let (lo, hi) = clipper.band_range(e.p0.y.min(e.p1.y), e.p0.y.max(e.p1.y), n_bands);
            for band in &mut bands[lo..=hi] {
                band.push(k as u32);
            }
        }
        clipper.edges = edges;
        clipper.bands = bands;
        clipper
    }

    fn band_range(&self, y_lo: f64, y_hi: f64, n: usize) -> (usize, usize) {
        let idx = |y: f64| {
            let k = ((y - self.y0) / self.band_height).floor();
            if k.is_nan() || k < 0.0 {
                0
            } else {
                (k as usize).min(n - 1)
            }
        };
        (idx(y_lo), idx(y_hi))
    }

    /// Whether `p` is inside the flattened region (non-zero winding; points
    /// on the outline may go either way).
    pub fn contains(&self, p: Point) -> bool {
        if self.bands.is_empty() || !self.bounds.contains(p) {
            return false;
        }
        let (k, _) = self.band_range(p.y, p.y, self.bands.len());
        let mut winding = 0;
        for &e in &self.bands[k] {
            let Line { p0: a, p1: b } = self.edges[e as usize];
            if (a.y <= p.y) != (b.y <= p.y) {
                let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if x > p.x {
                    winding += if b.y > a.y { 1 } else { -1 };
                }
            }
        }
        winding != 0
    }

    /// The edges whose bounding boxes meet `r`, each once, in index order.
    fn edges_near(&self, r: Rect) -> Vec<usize> {
        if self.bands.is_empty() || r.y1 < self.bounds.y0 || r.y0 > self.bounds.y1 {
            return Vec::new();
        }
        let (lo, hi) = self.band_range(r.y0, r.y1, self.bands.len());
        let mut found: Vec<usize> = Vec::new();
        for band in &self.bands[lo..=hi] {
            for &e in band {
                let l = self.edges[e as usize];
                let eb = Rect::from_points(l.p0, l.p1);
                if eb.x0 <= r.x1 && r.x0 <= eb.x1 && eb.y0 <= r.y1 && r.y0 <= eb.y1 {
                    found.push(e as usize);
                }
            }
        }
        found.sort_unstable();
        found.dedup();
        found
    }

    /// Splits `stroke` into its parts inside and outside (see
    /// [`clip_stroke`]).
    pub fn clip(&self, stroke: &BezPath) -> Clipped {
        let mut out = Clipped::default();
        for sub in subpaths(stroke) {
            self.clip_subpath(&sub, &mut out);
        }
        out
    }

    fn clip_subpath(&self, sub: &Subpath, out: &mut Clipped) {
        // Pieces in order: (segment piece, inside?).
        let mut pieces: Vec<(PathSeg, bool)> = Vec::new();
        for seg in &sub.segments {
            let cuts = self.cuts(seg);
            for w in cuts.windows(2) {
                let (t0, t1) = (w[0], w[1]);
                let inside = self.contains(seg.eval(0.5 * (t0 + t1)));
                pieces.push((seg.subsegment(t0..t1), inside));
            }
        }
        if pieces.is_empty() {
            return;
        }
        // Runs of pieces on one side.
        let mut runs: Vec<(Vec<PathSeg>, bool)> = Vec::new();
        for (p, side) in pieces {
            match runs.last_mut() {
                Some((run, s)) if *s == side => run.push(p),
                _ => runs.push((vec![p], side)),
            }
        }
        let whole = runs.len() == 1;
        if sub.closed && !whole && runs[0].1 == runs[runs.len() - 1].1 {
            // The last run goes on through the start point into the first.
            let (first, _) = runs.remove(0);
            if let Some((last, _)) = runs.last_mut() {
                last.extend(first);
            }
        }
        for (run, inside) in runs {
            let mut path = BezPath::new();
            path.move_to(run[0].start());
            for seg in &run {
                match *seg {
                    PathSeg::Line(l) => path.line_to(l.p1),
                    PathSeg::Quad(q) => path.quad_to(q.p1, q.p2),
                    PathSeg::Cubic(c) => path.curve_to(c.p1, c.p2, c.p3),
                }
            }
            if whole && sub.closed {
                path.close_path();
            }
            if inside {
                out.inside.push(path);
            } else {
                out.outside.push(path);
            }
        }
    }

    /// The parameters where `seg` crosses the outline, with 0 and 1, sorted
    /// and without near-duplicates.
    fn cuts(&self, seg: &PathSeg) -> Vec<f64> {
        let mut ts = vec![0.0];
        let bb = kurbo::ParamCurveExtrema::bounding_box(seg);
        for e in self.edges_near(bb.inflate(1e-9, 1e-9)) {
            for hit in seg.intersect_line(self.edges[e]) {
                let t = hit.segment_t;
                if t > PARAM_EPS && t < 1.0 - PARAM_EPS {
                    ts.push(t);
                }
            }
        }
        ts.push(1.0);
        ts.sort_by(f64::total_cmp);
        ts.dedup_by(|b, a| *b - *a < PARAM_EPS);
        if let Some(last) = ts.last_mut() {
            // `dedup` may have merged 1 into a cut just before it.
            *last = 1.0;
        }
        ts
    }
}

/// One subpath: its segments (a closing line included) and whether it was
/// closed.
struct Subpath {
    segments: Vec<PathSeg>,
    closed: bool,
}

fn subpaths(path: &BezPath) -> Vec<Subpath> {
    let mut out = Vec::new();
    let mut segments = Vec::new();
    let mut start = Point::ORIGIN;
    let mut current = Point::ORIGIN;
    let flush = |segments: &mut Vec<PathSeg>, closed: bool, out: &mut Vec<Subpath>| {
        if !segments.is_empty() {
            out.push(Subpath {
                segments: std::mem::take(segments),
                closed,
            });
        }
    };
    for el in path.elements() {
        match *el {
            PathEl::MoveTo(p) => {
                flush(&mut segments, false, &mut out);
                start = p;
                current = p;
            }
            PathEl::LineTo(p) => {
                segments.push(PathSeg::Line(Line::new(current, p)));
                current = p;
            }
            PathEl::QuadTo(a, p) => {
                segments.push(PathSeg::Quad(kurbo::QuadBez::new(current, a, p)));
                current = p;
            }
            PathEl::CurveTo(a, b, p) => {
                segments.push(PathSeg::Cubic(kurbo::CubicBez::new(current, a, b, p)));
                current = p;
            }
            PathEl::ClosePath => {
                if current != start {
                    segments.push(PathSeg::Line(Line::new(current, start)));
                }
                flush(&mut segments, true, &mut out);
                current = start;
            }
        }
    }
    flush(&mut segments, false, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::region::tests::{arb_region, circle, rect};
    use crate::scene::path_length;
    use kurbo::{CubicBez, Shape};
    use proptest::prelude::*;

    fn total(paths: &[BezPath]) -> f64 {
        paths.iter().map(path_length).sum()
    }

    #[test]
    fn line_through_a_square() {
        let sq = rect(0.0, 0.0, 10.0, 10.0);
        let mut l = BezPath::new();
        l.move_to((-5.0, 5.0));
        l.line_to((15.0, 5.0));
        let c = clip_stroke(&l, &sq, 0.01);
        assert_eq!(c.inside.len(), 1);
        assert_eq!(c.outside.len(), 2);
        assert!((total(&c.inside) - 10.0).abs() < 1e-9);
        assert!((total(&c.outside) - 10.0).abs() < 1e-9);
        // Direction of the stroke is kept.
        assert_eq!(
            c.outside[0].elements()[0],
            PathEl::MoveTo(Point::new(-5.0, 5.0))
        );
    }

    #[test]
    fn curves_stay_curves_and_cut_at_the_circle() {
        let disc = circle(0.0, 0.0, 5.0);
        let mut s = BezPath::new();
        s.move_to((-10.0, 0.0));
        s.curve_to((-3.0, 8.0), (3.0, -8.0), (10.0, 0.0));
        let c = clip_stroke(&s, &disc, 1e-4);
        assert_eq!(c.inside.len(), 1);
        let inner = &c.inside[0];
        assert!(matches!(inner.elements()[1], PathEl::CurveTo(..)));
        for p in [
            inner.segments().next().unwrap().start(),
            inner.segments().last().unwrap().end(),
        ] {
            assert!((p.to_vec2().hypot() - 5.0).abs() < 1e-3, "{p:?}");
        }
        let len = path_length(&s);
        assert!((total(&c.inside) + total(&c.outside) - len).abs() < 1e-6);
    }

    #[test]
    fn holes_cut_strokes_too() {
        let ring = circle(0.0, 0.0, 10.0).difference(&circle(0.0, 0.0, 4.0));
        let mut l = BezPath::new();
        l.move_to((-20.0, 0.0));
        l.line_to((20.0, 0.0));
        let c = clip_stroke(&l, &ring, 1e-4);
        assert_eq!(c.inside.len(), 2);
        assert_eq!(c.outside.len(), 3);
        assert!((total(&c.inside) - 12.0).abs() < 1e-3);
    }

    #[test]
    fn closed_strokes() {
        let sq = rect(0.0, 0.0, 10.0, 10.0);
        // Wholly inside: stays one closed path.
        let inner = Rect::new(2.0, 2.0, 4.0, 4.0).to_path(0.0);
        let c = clip_stroke(&inner, &sq, 0.01);
        assert_eq!(c.inside.len(), 1);
        assert!(c.outside.is_empty());
        assert_eq!(c.inside[0].elements().last(), Some(&PathEl::ClosePath));
        // Crossing: the run through the start point is one path.
        let across = Rect::new(5.0, 2.0, 15.0, 4.0).to_path(0.0);
        let c = clip_stroke(&across, &sq, 0.01);
        assert_eq!((c.inside.len(), c.outside.len()), (1, 1));
        assert!((total(&c.inside) - 12.0).abs() < 1e-9);
        assert!((total(&c.outside) - 12.0).abs() < 1e-9);
    }

    #[test]
    fn empty_inputs() {
        let sq = rect(0.0, 0.0, 1.0, 1.0);
        assert_eq!(clip_stroke(&BezPath::new(), &sq, 0.01), Clipped::default());
        let mut l = BezPath::new();
        l.move_to((0.5, 0.5));
        l.line_to((2.0, 0.5));
        let c = clip_stroke(&l, &Region::empty(), 0.01);
        assert!(c.inside.is_empty());
        assert_eq!(c.outside.len(), 1);
    }

    fn arb_stroke() -> impl Strategy<Value = BezPath> {
        prop::collection::vec((-10.0..100.0f64, -10.0..100.0f64), 4..13).prop_map(|pts| {
            let mut p = BezPath::new();
            p.move_to(pts[0]);
            let mut i = 1;
            while i + 2 < pts.len() {
                let c = CubicBez::new(pts[i - 1], pts[i], pts[i + 1], pts[i + 2]);
                p.curve_to(c.p1, c.p2, c.p3);
                i += 3;
            }
            while i < pts.len() {
                p.line_to(pts[i]);
                i += 1;
            }
            p
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn inside_plus_outside_is_the_whole_length(r in arb_region(), s in arb_stroke()) {
            let c = clip_stroke(&s, &r, TOLERANCE);
            let len = path_length(&s);
            let sum = total(&c.inside) + total(&c.outside);
            let segments = s.segments().count() as f64;
            prop_assert!((sum - len).abs() <= TOLERANCE * segments, "{sum} vs {len}");
        }

        #[test]
        fn parts_are_on_their_side(r in arb_region(), s in arb_stroke()) {
            let c = clip_stroke(&s, &r, 1e-4);
            let clipper = StrokeClipper::new(&r, 1e-4);
            for p in &c.inside {
                for seg in p.segments() {
                    prop_assert!(clipper.contains(seg.eval(0.5)));
                }
            }
            for p in &c.outside {
                for seg in p.segments() {
                    prop_assert!(!clipper.contains(seg.eval(0.5)));
                }
            }
        }
    }
}
