//! Unique ids by numbering: the id wanted, else the first of `-2`, `-3`, …
//! appended that is free — the rule of the layer ids of a render and of
//! every id an SVG import gives.
//!
//! Both the ids taken (a set) and, for each id wanted, the last number
//! tried are kept, so a thousand layers or paths that all want one id cost
//! a thousand steps, not half a million (a list searched from `-2` up each
//! time made 4,000 such layer names take 77 s).

use std::collections::{HashMap, HashSet};

/// The ids handed out so far (see the module documentation).
#[derive(Debug, Default)]
pub(crate) struct UniqueIds {
    taken: HashSet<String>,
    /// For an id wanted more than once: the next number to try.
    next: HashMap<String, usize>,
}

impl UniqueIds {
    /// Hands out ids none of which is one of `reserved`.
    pub(crate) fn reserving(reserved: impl IntoIterator<Item = String>) -> UniqueIds {
        UniqueIds {
            taken: reserved.into_iter().collect(),
            next: HashMap::new(),
        }
    }

    /// `wanted` when it is free, else `wanted-N` with the smallest free
    /// N ≥ 2; either way taken from now on.
    pub(crate) fn unique(&mut self, wanted: &str) -> String {
        let mut id = wanted.to_string();
        if self.taken.contains(&id) {
            // Numbers below `next` are taken already: ids are only added.
            let n = self.next.entry(wanted.to_string()).or_insert(2);
            loop {
                id = format!("{wanted}-{n}");
                *n += 1;
                if !self.taken.contains(&id) {
                    break;
                }
            }
        }
        self.taken.insert(id.clone());
        id
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_free_number_is_taken() {
        let mut ids = UniqueIds::reserving(["pen-1".to_string()]);
        let got: Vec<String> = ["a", "a", "a-2", "a", "pen-1", "a-2"]
            .iter()
            .map(|w| ids.unique(w))
            .collect();
        assert_eq!(got, ["a", "a-2", "a-2-2", "a-3", "pen-1-2", "a-2-3"]);
    }

    /// 100,000 paths that all want one id (an SVG whose paths repeat one):
    /// linear, so this ends at once.
    #[test]
    fn many_wanting_one_id_stay_linear() {
        let mut ids = UniqueIds::default();
        let last = (0..100_000).map(|_| ids.unique("p")).last().unwrap();
        assert_eq!(last, "p-100000");
    }
}
