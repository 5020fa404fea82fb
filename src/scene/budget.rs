//! The path budget: a hard cap on how many paths a scene may make, and on
//! how many segments (lines and curves) they may hold in all.
//!
//! Generators take paths from the budget *before* they allocate, so a
//! runaway description (thousands of trees, deep recursion) stops with
//! [`Error::Budget`] instead of exhausting memory or time. Segments are
//! counted per table once it is built, and a family whose one path can
//! grow without bound (an L-system's turtle) stops at what is left
//! ([`PathBudget::segments_left`]), with [`Error::SegmentBudget`].
//! Relaxation (Voronoi sites moved step by step) is counted in
//! site-steps, before each table relaxes
//! ([`PathBudget::take_site_steps`]): its time grows with sites × steps
//! while it makes no path at all.

use crate::error::{Error, Result};

/// Counts paths against `limits.max_paths` and segments against
/// `limits.max_segments`.
#[derive(Debug, Clone)]
pub struct PathBudget {
    paths: Count,
    segments: Count,
    site_steps: Count,
}

/// One count against its limit.
#[derive(Debug, Clone, Copy)]
struct Count {
    limit: usize,
    used: usize,
}

impl Count {
    fn new(limit: usize) -> Count {
        Count { limit, used: 0 }
    }

    /// Takes `n`, or leaves the count as it is and says no when that
    /// would pass the limit.
    fn take(&mut self, n: usize) -> bool {
        let next = self.used.saturating_add(n);
        let fits = next <= self.limit;
        if fits {
            self.used = next;
        }
        fits
    }
}

impl PathBudget {
    /// The default limit: generous for plotter art (an A3 sheet with
    /// 100,000 strokes takes many hours to plot), small enough to stay fast.
    pub const DEFAULT_LIMIT: usize = 200_000;

    /// The default segment limit, also the most a description may ask
    /// for: five million segments make an SVG of about 75 MB, far past
    /// what a plotter draws in a day, and a render of them stays under
    /// about 2 GB.
    pub const DEFAULT_SEGMENT_LIMIT: usize = 5_000_000;

    /// The most site-steps of relaxation in a scene (each step's sites,
    /// summed over the steps and tables): a step costs 3–6 µs a site in
    /// release on two cores, so the whole budget about 3–6 s. The
    /// templates use at most 385,000 (`stipple-lbg`).
    pub const SITE_STEP_LIMIT: usize = 1_000_000;

    /// A budget of `limit` paths and the default number of segments.
    pub fn new(limit: usize) -> PathBudget {
        PathBudget {
            paths: Count::new(limit),
            segments: Count::new(PathBudget::DEFAULT_SEGMENT_LIMIT),
            site_steps: Count::new(PathBudget::SITE_STEP_LIMIT),
        }
    }

    /// The same budget with `limit` segments.
    #[must_use]
    pub fn with_segments(self, limit: usize) -> PathBudget {
        PathBudget {
            segments: Count::new(limit),
            ..self
        }
    }

    /// Takes `n` paths for `what`; fails when the limit would be passed.
    pub fn take(&mut self, n: usize, what: impl FnOnce() -> String) -> Result<()> {
        if self.paths.take(n) {
            Ok(())
        } else {
            Err(Error::Budget {
                limit: self.paths.limit,
                what: what(),
            })
        }
    }

    /// Paths taken so far.
    pub fn used(&self) -> usize {
        self.paths.used
    }

    /// Paths that may still be made.
    pub fn paths_left(&self) -> usize {
        self.paths.limit - self.paths.used
    }

    /// Takes `n` segments for `what`; fails when the limit would be passed.
    pub fn take_segments(&mut self, n: usize, what: impl FnOnce() -> String) -> Result<()> {
        if self.segments.take(n) {
            Ok(())
        } else {
            Err(Error::SegmentBudget {
                limit: self.segments.limit,
                what: what(),
            })
        }
    }

    /// Segments that may still be made.
    pub fn segments_left(&self) -> usize {
        self.segments.limit - self.segments.used
    }

    /// Takes `n` site-steps of relaxation; says no, taking nothing, when
    /// that would pass [`PathBudget::SITE_STEP_LIMIT`].
    pub fn take_site_steps(&mut self, n: usize) -> bool {
        self.site_steps.take(n)
    }

    /// Site-steps of relaxation that may still be run.
    pub fn site_steps_left(&self) -> usize {
        self.site_steps.limit - self.site_steps.used
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stops_exactly_at_the_limit() {
        let mut b = PathBudget::new(10);
        b.take(10, || "x".into()).unwrap();
        let e = b.take(1, || "tree 3".into()).unwrap_err();
        assert!(e.to_string().contains("more than 10 paths"), "{e}");
        assert!(e.to_string().contains("tree 3"));
        assert_eq!(b.used(), 10);
    }

    #[test]
    fn segments_stop_exactly_at_their_limit() {
        let mut b = PathBudget::new(10).with_segments(100);
        b.take_segments(60, || "x".into()).unwrap();
        assert_eq!(b.segments_left(), 40);
        let e = b.take_segments(41, || "koch".into()).unwrap_err();
        assert!(e.to_string().contains("more than 100 path segments"), "{e}");
        assert!(e.to_string().contains("koch"));
        b.take_segments(40, || "x".into()).unwrap();
        assert_eq!(b.segments_left(), 0);
    }

    #[test]
    fn site_steps_are_counted_over_the_scene() {
        let mut b = PathBudget::new(10);
        assert!(b.take_site_steps(PathBudget::SITE_STEP_LIMIT - 5));
        assert!(!b.take_site_steps(6));
        assert_eq!(b.site_steps_left(), 5);
        assert!(b.take_site_steps(5));
        assert_eq!(b.site_steps_left(), 0);
    }
}
