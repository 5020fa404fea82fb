//! The subpaths of a path, and when a subpath is closed: the one reading
//! of kurbo's element lists that every part of moyo shares.
//!
//! **Splitting** follows SVG: a move-to starts a subpath, and a close-path
//! ends one and puts the pen back at that subpath's start, so a drawing
//! element after a close-path without a move-to of its own starts a new
//! subpath *at the closed one's start*. (kurbo insists that a path begin
//! with a move-to; should one not, it starts at the origin.) Elements that draw nothing are dropped: a
//! lone move-to (followed by another move-to or by the end) and a
//! close-path with no subpath to close (at the very beginning, or right
//! after another close-path). A subpath `M p Z` is kept: a pen draws it as
//! a dot.
//!
//! So every [`Subpath`] is one move-to (written or implied) followed by at
//! least one element, of which only the last may be a close-path, and
//! [`Subpath::to_path`] gives it as a path of its own. Concatenating the
//! subpaths of a path draws exactly the path's segments
//! ([`BezPath::segments`]); it gives back the very same elements when the
//! path is *normalised*: every subpath begins with its own move-to, and
//! nothing is dropped.
//!
//! **Closed** has one meaning ([`Subpath::is_closed`]): the subpath ends
//! with a close-path, or its last point lies within [`CLOSE_TOLERANCE`] of
//! its start. Such a subpath bounds an area: it hides what lies behind it,
//! it can serve as an outline, and a plotter may start drawing it at any of
//! its vertices. Whether a close-path is actually *written*
//! ([`Subpath::ends_with_close`]) is a different question, about the
//! elements rather than the shape; stages that edit elements (joining
//! paths end to end, cutting a stroke, repeating it) ask that one.

use kurbo::{BezPath, PathEl, PathSeg, Point};

/// A subpath whose last point lies this close to its start (in the path's
/// own units: mm on the page, motif units in a motif) is closed even
/// without a close-path. It is rounding noise, not a drawing tolerance: a
/// circle built from arcs ends within it of its start, a pen stroke that
/// ends 0.01 mm short of its start does not.
pub const CLOSE_TOLERANCE: f64 = 1e-9;

/// The subpaths of `path`, in order, borrowed from it (see the
/// [module docs](self) for the rules).
pub fn subpaths(path: &BezPath) -> Subpaths<'_> {
    Subpaths {
        rest: path.elements(),
        start: Point::ORIGIN,
    }
}

/// Iterator over the subpaths of a path; made by [`subpaths`].
#[derive(Debug, Clone)]
pub struct Subpaths<'a> {
    /// The elements not read yet.
    rest: &'a [PathEl],
    /// Where a subpath without a move-to of its own starts.
    start: Point,
}

impl<'a> Iterator for Subpaths<'a> {
    type Item = Subpath<'a>;

    fn next(&mut self) -> Option<Subpath<'a>> {
        loop {
            let (first, after) = self.rest.split_first()?;
            let body_from = match first {
                PathEl::MoveTo(p) => {
                    self.start = *p;
                    after
                }
                // Nothing to close: a close-path at the beginning, or a
                // repeated one.
                PathEl::ClosePath => {
                    self.rest = after;
                    continue;
                }
                // Drawing without a move-to: from the last subpath's start.
                _ => self.rest,
            };
            // The body runs to the next move-to, or through the first
            // close-path.
            let len = body_from
                .iter()
                .position(|el| matches!(el, PathEl::MoveTo(_) | PathEl::ClosePath))
                .map_or(body_from.len(), |k| match body_from[k] {
                    PathEl::ClosePath => k + 1,
                    _ => k,
                });
            let (body, rest) = body_from.split_at(len);
            self.rest = rest;
            if !body.is_empty() {
                return Some(Subpath {
                    start: self.start,
                    body,
                });
            }
        }
    }
}

/// One subpath: a move-to to [`Subpath::start`] (written in the path or
/// implied) and the elements that follow it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Subpath<'a> {
    start: Point,
    /// At least one element; only the last may be a close-path; no
    /// move-to.
    body: &'a [PathEl],
}

impl<'a> Subpath<'a> {
    /// Where the subpath starts.
    pub fn start(&self) -> Point {
        self.start
    }

    /// Where the pen is after drawing it: its start when it ends with a
    /// close-path, else the end of its last element.
    pub fn end(&self) -> Point {
        match self.body.last() {
            Some(el) => el.end_point().unwrap_or(self.start),
            None => self.start,
        }
    }

    /// The elements after the move-to: at least one, only the last of
    /// them may be a close-path.
    pub fn body(&self) -> &'a [PathEl] {
        self.body
    }

    /// The body without its close-path: the elements that draw a curve
    /// each (none for a dot `M p Z`).
    pub fn drawn(&self) -> &'a [PathEl] {
        &self.body[..self.body.len() - usize::from(self.ends_with_close())]
    }

    /// The move-to and the body.
    pub fn elements(&self) -> impl Iterator<Item = PathEl> + Clone + 'a {
        std::iter::once(PathEl::MoveTo(self.start)).chain(self.body.iter().copied())
    }

    /// The segments it draws, the line a close-path adds included (none
    /// for a dot `M p Z`).
    pub fn segments(&self) -> impl Iterator<Item = PathSeg> + Clone + 'a {
        kurbo::segments(self.elements())
    }

    /// The subpath as a path of its own.
    pub fn to_path(&self) -> BezPath {
        BezPath::from_vec(self.elements().collect())
    }

    /// Whether its last element is a close-path (a question about the
    /// elements; see [`Subpath::is_closed`] for the shape).
    pub fn ends_with_close(&self) -> bool {
        matches!(self.body.last(), Some(PathEl::ClosePath))
    }

    /// Whether it is closed: it ends with a close-path, or its last point
    /// lies within [`CLOSE_TOLERANCE`] of its start.
    pub fn is_closed(&self) -> bool {
        self.ends_with_close() || self.end().distance(self.start) <= CLOSE_TOLERANCE
    }
}

/// Whether `path` has subpaths and every one of them is closed.
pub fn is_closed(path: &BezPath) -> bool {
    let mut subs = subpaths(path).peekable();
    subs.peek().is_some() && subs.all(|s| s.is_closed())
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn pt(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    fn paths(path: &BezPath) -> Vec<BezPath> {
        subpaths(path).map(|s| s.to_path()).collect()
    }

    fn concat(path: &BezPath) -> BezPath {
        let mut out = BezPath::new();
        for s in subpaths(path) {
            out.extend(s.elements());
        }
        out
    }

    #[test]
    fn after_a_close_path_the_pen_is_at_the_start() {
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.line_to((1.0, 0.0));
        p.line_to((1.0, 1.0));
        p.close_path();
        p.close_path(); // draws nothing
        p.line_to((5.0, 5.0)); // a new subpath from (0, 0)
        p.move_to((9.0, 9.0)); // a lone move-to
        p.move_to((7.0, 7.0));
        p.close_path(); // a dot
        let subs: Vec<Subpath> = subpaths(&p).collect();
        assert_eq!(subs.len(), 3);
        assert_eq!(subs[0].body().len(), 3);
        assert!(subs[0].ends_with_close() && subs[0].is_closed());
        assert_eq!(subs[0].end(), pt(0.0, 0.0));
        assert_eq!(
            subs[1].to_path().elements(),
            [PathEl::MoveTo(pt(0.0, 0.0)), PathEl::LineTo(pt(5.0, 5.0))]
        );
        assert!(!subs[1].is_closed());
        assert_eq!(subs[1].end(), pt(5.0, 5.0));
        assert_eq!(
            subs[2].to_path().elements(),
            [PathEl::MoveTo(pt(7.0, 7.0)), PathEl::ClosePath]
        );
        assert!(subs[2].is_closed());
        assert_eq!(subs[2].segments().count(), 0);
    }

    #[test]
    fn drawing_before_any_move_to_starts_at_the_origin() {
        // kurbo's builders insist on a first move-to; the elements can
        // still be changed afterwards.
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.close_path();
        p.close_path();
        p.line_to((3.0, 4.0));
        p.elements_mut()[0] = PathEl::ClosePath;
        let subs = paths(&p);
        assert_eq!(subs.len(), 1);
        assert_eq!(
            subs[0].elements(),
            [PathEl::MoveTo(Point::ORIGIN), PathEl::LineTo(pt(3.0, 4.0))]
        );
    }

    fn first(p: &BezPath) -> Subpath<'_> {
        subpaths(p).next().unwrap()
    }

    #[test]
    fn closed_means_a_close_path_or_back_at_the_start() {
        let mut open = BezPath::new();
        open.move_to((0.0, 0.0));
        open.line_to((1.0, 0.0));
        open.line_to((0.0, 1.0));
        let mut back = open.clone();
        back.line_to((0.5 * CLOSE_TOLERANCE, 0.0));
        let mut short = open.clone();
        short.line_to((2.0 * CLOSE_TOLERANCE, 0.0));
        let mut written = open.clone();
        written.close_path();
        assert!(!first(&open).is_closed());
        assert!(first(&back).is_closed() && !first(&back).ends_with_close());
        assert!(!first(&short).is_closed());
        assert!(first(&written).is_closed() && first(&written).ends_with_close());
        // A whole path is closed when all its subpaths are.
        let mut two = written.clone();
        two.extend(back.iter());
        assert!(is_closed(&two));
        two.extend(open.iter());
        assert!(!is_closed(&two));
        assert!(!is_closed(&BezPath::new()));
    }

    #[test]
    fn segments_include_the_closing_line() {
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.line_to((2.0, 0.0));
        p.line_to((2.0, 2.0));
        p.close_path();
        let s = subpaths(&p).next().unwrap();
        assert_eq!(s.segments().count(), 3);
        assert!(s.segments().eq(p.segments()));
    }

    /// Any list of elements that starts with a move-to.
    fn any_path() -> impl Strategy<Value = BezPath> {
        let p = || (0i32..8, 0i32..8).prop_map(|(x, y)| pt(f64::from(x), f64::from(y)));
        let el = prop_oneof![
            p().prop_map(PathEl::MoveTo),
            p().prop_map(PathEl::LineTo),
            (p(), p()).prop_map(|(a, b)| PathEl::QuadTo(a, b)),
            (p(), p(), p()).prop_map(|(a, b, c)| PathEl::CurveTo(a, b, c)),
            Just(PathEl::ClosePath),
        ];
        (p(), prop::collection::vec(el, 0..16)).prop_map(|(first, rest)| {
            let mut els = vec![PathEl::MoveTo(first)];
            els.extend(rest);
            BezPath::from_vec(els)
        })
    }

    proptest! {
        #[test]
        fn every_subpath_is_one_move_to_and_a_body(path in any_path()) {
            for s in subpaths(&path) {
                let p = s.to_path();
                let els = p.elements();
                prop_assert!(matches!(els[0], PathEl::MoveTo(q) if q == s.start()));
                prop_assert!(els.len() >= 2);
                prop_assert!(els[1..].iter().all(|e| !matches!(e, PathEl::MoveTo(_))));
                prop_assert!(els[1..els.len() - 1].iter().all(|e| *e != PathEl::ClosePath));
                prop_assert_eq!(s.is_closed(), s.ends_with_close() || s.end() == s.start());
            }
        }

        #[test]
        fn concatenated_subpaths_draw_the_path(path in any_path()) {
            let joined = concat(&path);
            prop_assert!(joined.segments().eq(path.segments()));
            // A normalised path comes back element for element.
            prop_assert_eq!(concat(&joined), joined);
        }
    }
}
