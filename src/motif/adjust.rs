//! Final adjustment (docs/SPEC.md §1, design step 4): the description's `[[adjust]]`
//! entries, looked up by the id a motif of any family has in the SVG (a
//! tree, a flower, a leaf, a placed path …).
//!
//! Every entry must address something: after the scene is built,
//! [`Adjustments::finish`] reports the first id that matched nothing, so a
//! typo is an error instead of a silent no-op.

use std::collections::BTreeMap;

use kurbo::{Affine, Point, Rect, Shape, Vec2};

use crate::error::{Error, Result};
use crate::scene::{Group, Layer, Node};
use crate::spec::AdjustSpec;

/// The adjustments of a scene, by id, with a record of which were used.
#[derive(Debug)]
pub(crate) struct Adjustments<'a> {
    by_id: BTreeMap<&'a str, usize>,
    list: &'a [AdjustSpec],
    used: Vec<bool>,
}

impl<'a> Adjustments<'a> {
    /// Indexes a description's adjustments (ids are unique after
    /// validation).
    pub(crate) fn new(list: &'a [AdjustSpec]) -> Adjustments<'a> {
        Adjustments {
            by_id: list
                .iter()
                .enumerate()
                .map(|(i, a)| (a.id.as_str(), i))
                .collect(),
            list,
            used: vec![false; list.len()],
        }
    }

    /// The adjustment of `id`, if any; marks it used.
    pub(crate) fn take(&mut self, id: &str) -> Option<&'a AdjustSpec> {
        let i = *self.by_id.get(id)?;
        self.used[i] = true;
        Some(&self.list[i])
    }

    /// Like [`Adjustments::take`] for something that has no motif to swap
    /// (a tree, a placed path), called `what` in the error.
    ///
    /// # Errors
    /// When the adjustment asks for a motif.
    pub(crate) fn take_without_motif(
        &mut self,
        id: &str,
        what: &str,
    ) -> Result<Option<&'a AdjustSpec>> {
        let Some(i) = self.by_id.get(id).copied() else {
            return Ok(None);
        };
        if self.list[i].motif.is_some() {
            return Err(Error::invalid(
                format!("adjust[{i}].motif"),
                format!("'{id}' is {what}; only flowers and leaves have a motif to swap"),
            ));
        }
        Ok(self.take(id))
    }

    /// Like [`Adjustments::take_without_motif`], but only an adjustment that
    /// nothing has taken yet (a tree's group was adjusted as the tree).
    ///
    /// # Errors
    /// When the adjustment asks for a motif.
    fn take_unused(&mut self, id: &str, what: &str) -> Result<Option<&'a AdjustSpec>> {
        match self.by_id.get(id) {
            Some(&i) if !self.used[i] => self.take_without_motif(id, what),
            _ => Ok(None),
        }
    }

    /// Applies the adjustments that name a group of `layers` rather than
    /// one motif — a layer (`front`), a tree set (`front.plum`), a
    /// background, any family's table — and that nothing took while the
    /// scene was built: the whole group moves, turns and scales as one,
    /// about the centre of what it holds, or is left out (`hide`).
    /// Several sets adjusted as one are the sets of one layer.
    ///
    /// # Errors
    /// An adjustment of a group that asks for a motif.
    pub(crate) fn apply_to_groups(&mut self, layers: &mut [Layer]) -> Result<()> {
        for layer in layers {
            let id = layer.id.clone();
            self.group(&mut layer.content, Some(&id), Affine::IDENTITY)?;
        }
        Ok(())
    }

    /// Adjusts `group` (also known as `alias`, a layer's id) if it is
    /// named, and the groups below it; `outer` maps its parent to the
    /// scene's coordinates.
    fn group(&mut self, group: &mut Group, alias: Option<&str>, outer: Affine) -> Result<()> {
        let named = match alias {
            Some(alias) => self.take_unused(alias, "a layer")?,
            None => None,
        };
        let named = match named {
            Some(a) => Some(a),
            None => self.take_unused(&group.id, "a group")?,
        };
        if let Some(a) = named {
            if a.hide {
                self.take_parts_of(&group.id);
                group.children.clear();
                return Ok(());
            }
            let mut bounds: Option<Rect> = None;
            group.visit_paths(outer, &mut |p, t| {
                let b = (t * p.path.clone()).bounding_box();
                bounds = Some(bounds.map_or(b, |r| r.union(b)));
            });
            if let Some(b) = bounds {
                // About its centre in the scene, applied in its parent's
                // coordinates.
                group.transform =
                    outer.inverse() * about(Some(a), b.center()) * outer * group.transform;
            }
        }
        let here = outer * group.transform;
        for child in &mut group.children {
            if let Node::Group(g) = child {
                self.group(g, None, here)?;
            }
        }
        Ok(())
    }

    /// Marks every adjustment of the parts of `id` (ids starting with
    /// `id.`) used: they address something real that is hidden with it.
    pub(crate) fn take_parts_of(&mut self, id: &str) {
        let prefix = format!("{id}.");
        for (k, i) in self.by_id.range(prefix.as_str()..) {
            if !k.starts_with(&prefix) {
                break;
            }
            self.used[*i] = true;
        }
    }

    /// Fails on the first adjustment whose id matched nothing.
    ///
    /// # Errors
    /// [`Error::Invalid`] naming `adjust[i].id`.
    pub(crate) fn finish(self) -> Result<()> {
        match self.used.iter().position(|u| !u) {
            None => Ok(()),
            Some(i) => Err(Error::invalid(
                format!("adjust[{i}].id"),
                format!(
                    "'{}' matches nothing drawn (ids are as in the SVG, e.g. \
                     front.trees-0.tree-1.flower-2)",
                    self.list[i].id
                ),
            )),
        }
    }
}

/// The map of an adjustment about `anchor` (page mm): scale, then turn
/// clockwise, about the anchor, then move.
pub(crate) fn about(adjust: Option<&AdjustSpec>, anchor: Point) -> Affine {
    let Some(a) = adjust else {
        return Affine::IDENTITY;
    };
    let [dx, dy] = a.offset.unwrap_or([0.0, 0.0]);
    Affine::translate(anchor.to_vec2() + Vec2::new(dx, dy))
        * Affine::rotate(a.rotate.unwrap_or(0.0).to_radians())
        * Affine::scale(a.scale.unwrap_or(1.0))
        * Affine::translate(-anchor.to_vec2())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn adjust(id: &str) -> AdjustSpec {
        AdjustSpec {
            id: id.into(),
            offset: None,
            rotate: None,
            scale: None,
            hide: false,
            motif: None,
        }
    }

    #[test]
    fn unused_ids_are_errors_naming_the_entry() {
        let list = [adjust("a.tree-0"), adjust("a.tree-9")];
        let mut adj = Adjustments::new(&list);
        assert!(adj.take("a.tree-0").is_some());
        assert!(adj.take("a.tree-1").is_none());
        let e = adj.finish().unwrap_err().to_string();
        assert!(e.starts_with("adjust[1].id: 'a.tree-9' matches no"), "{e}");
    }

    #[test]
    fn parts_of_a_hidden_item_count_as_used() {
        let list = [
            adjust("a.tree-1"),
            adjust("a.tree-1.flower-0"),
            adjust("a.tree-10.flower-0"),
        ];
        let mut adj = Adjustments::new(&list);
        adj.take("a.tree-1");
        adj.take_parts_of("a.tree-1");
        let e = adj.finish().unwrap_err().to_string();
        assert!(e.starts_with("adjust[2].id"), "{e}");
    }

    #[test]
    fn map_turns_and_scales_about_the_anchor_then_moves() {
        let mut a = adjust("x");
        a.offset = Some([1.0, 2.0]);
        a.rotate = Some(90.0);
        a.scale = Some(2.0);
        let anchor = Point::new(10.0, 10.0);
        let m = about(Some(&a), anchor);
        assert!((m * anchor - Point::new(11.0, 12.0)).hypot() < 1e-12);
        // One mm to the right of the anchor: doubled, turned clockwise on
        // the page (y down) to point down, then moved.
        let p = m * Point::new(11.0, 10.0);
        assert!((p - Point::new(11.0, 14.0)).hypot() < 1e-12, "{p:?}");
        assert_eq!(about(None, anchor), Affine::IDENTITY);
    }
}
