//! The path budget: a hard cap on how many paths a scene may make.
//!
//! Generators take from the budget *before* they allocate, so a runaway
//! description (thousands of trees, deep recursion) stops with
//! [`Error::Budget`] instead of exhausting memory or time.

use crate::error::{Error, Result};

/// Counts paths against `limits.max_paths`.
#[derive(Debug, Clone)]
pub struct PathBudget {
    limit: usize,
    used: usize,
}

impl PathBudget {
    /// The default limit: generous for plotter art (an A3 sheet with
    /// 100,000 strokes takes many hours to plot), small enough to stay fast.
    pub const DEFAULT_LIMIT: usize = 200_000;

    /// A budget of `limit` paths.
    pub fn new(limit: usize) -> PathBudget {
        PathBudget { limit, used: 0 }
    }

    /// Takes `n` paths for `what`; fails when the limit would be passed.
    pub fn take(&mut self, n: usize, what: impl FnOnce() -> String) -> Result<()> {
        let next = self.used.saturating_add(n);
        if next > self.limit {
            return Err(Error::Budget {
                limit: self.limit,
                what: what(),
            });
        }
        self.used = next;
        Ok(())
    }

    /// Paths taken so far.
    pub fn used(&self) -> usize {
        self.used
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
}
