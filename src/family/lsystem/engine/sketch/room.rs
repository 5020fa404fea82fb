//! The room a sketch's branches may grow into: clear of the trunk (the `a`
//! chain along the stroke) and inside the page. This module owns the
//! segments drawn so far, filed in a grid so that a new segment is tested
//! against its neighbours only, and the tests: whether a branch segment
//! keeps clear of the trunk, which branch segments a new trunk segment
//! comes too near, whether a point stands on the page.
//!
//! "Too near" is measured in 3D between the segments' centre lines: closer
//! than their half widths and a gap (the pen's width), so that outlines
//! neither cross nor touch. A segment that leaves the trunk at a node is
//! not tested against the two trunk segments meeting there, which it
//! touches by birth.

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use crate::geom::segment_distance_3d;

/// A grid cell's key: its column and row.
type Cell = (i64, i64);

/// A segment filed in the grid: its ends, how far its outline reaches
/// from its centre line, and what it is (a trunk node, or a branch's
/// place in [`Room::branches`]).
#[derive(Debug, Clone, Copy)]
struct Filed {
    from: DVec3,
    to: DVec3,
    reach: f64,
    id: usize,
}

/// A branch segment: the limb it belongs to, the index of its last point
/// in that limb, and the trunk node it leaves from, if it does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(super) struct BranchSegment {
    pub(super) limb: usize,
    pub(super) end: usize,
    pub(super) root: Option<usize>,
}

/// Segments filed by the cells their outlines reach.
#[derive(Debug, Clone, Default)]
struct Grid {
    cells: HashMap<Cell, Vec<Filed>>,
    /// Segments too long to file cell by cell: tested against everything.
    wide: Vec<Filed>,
}

/// The most cells one segment is filed in; a longer one goes to
/// [`Grid::wide`].
const MAX_CELLS: i64 = 4096;

impl Grid {
    fn cells_of(from: DVec3, to: DVec3, reach: f64, size: f64) -> Option<(Cell, Cell)> {
        let lo = from.truncate().min(to.truncate()) - DVec2::splat(reach);
        let hi = from.truncate().max(to.truncate()) + DVec2::splat(reach);
        let key = |v: f64| (v / size).floor() as i64;
        let (c0, c1) = ((key(lo.x), key(lo.y)), (key(hi.x), key(hi.y)));
        let count = (c1.0 - c0.0 + 1).saturating_mul(c1.1 - c0.1 + 1);
        (count <= MAX_CELLS).then_some((c0, c1))
    }

    fn file(&mut self, filed: Filed, size: f64) {
        match Grid::cells_of(filed.from, filed.to, filed.reach, size) {
            Some((c0, c1)) => {
                for x in c0.0..=c1.0 {
                    for y in c0.1..=c1.1 {
                        self.cells.entry((x, y)).or_default().push(filed);
                    }
                }
            }
            None => self.wide.push(filed),
        }
    }

    /// The ids of the segments that come nearer to `from`–`to` than their
    /// reach plus `reach`, in increasing order.
    fn near(&self, from: DVec3, to: DVec3, reach: f64, size: f64) -> Vec<usize> {
        let mut candidates: Vec<&Filed> = self.wide.iter().collect();
        match Grid::cells_of(from, to, reach, size) {
            Some((c0, c1)) => {
                for x in c0.0..=c1.0 {
                    for y in c0.1..=c1.1 {
                        candidates.extend(self.cells.get(&(x, y)).into_iter().flatten());
                    }
                }
            }
            None => candidates.extend(self.cells.values().flatten()),
        }
        let mut ids: Vec<usize> = candidates
            .into_iter()
            .filter(|f| segment_distance_3d(from, to, f.from, f.to) < reach + f.reach)
            .map(|f| f.id)
            .collect();
        ids.sort_unstable();
        ids.dedup();
        ids
    }
}

/// See the module docs.
#[derive(Debug, Clone)]
pub(super) struct Room {
    /// The grid's cell size, mm (the module).
    size: f64,
    /// Space kept between outlines, mm.
    gap: f64,
    /// The page's corners: where the outlines must stay (none: anywhere).
    page: Option<(DVec2, DVec2)>,
    /// Trunk segments, by the index of their last node.
    trunk: Grid,
    branch_grid: Grid,
    branches: Vec<BranchSegment>,
}

impl Room {
    /// Room with segments filed in cells of `size` mm.
    pub(super) fn new(size: f64) -> Room {
        Room {
            size,
            gap: 0.0,
            page: None,
            trunk: Grid::default(),
            branch_grid: Grid::default(),
            branches: Vec::new(),
        }
    }

    pub(super) fn set_gap(&mut self, gap: f64) {
        self.gap = gap;
    }

    pub(super) fn set_page(&mut self, min: DVec2, max: DVec2) {
        self.page = Some((min, max));
    }

    /// Whether a disc `width` wide at `p` lies on the page (in the page's
    /// plane: a sketch is seen from the front).
    pub(super) fn on_page(&self, p: DVec3, width: f64) -> bool {
        self.page.is_none_or(|(min, max)| {
            let r = width / 2.0;
            let p = p.truncate();
            p.x - r >= min.x && p.y - r >= min.y && p.x + r <= max.x && p.y + r <= max.y
        })
    }

    /// Files the trunk segment `from`–`to` ending at node `node`, `width`
    /// wide, and returns the branch segments it comes too near, but those
    /// leaving from its own nodes, in increasing order.
    pub(super) fn add_trunk(
        &mut self,
        from: DVec3,
        to: DVec3,
        width: f64,
        node: usize,
    ) -> Vec<BranchSegment> {
        let reach = width / 2.0 + self.gap;
        let near = self
            .branch_grid
            .near(from, to, reach, self.size)
            .into_iter()
            .map(|id| self.branches[id])
            .filter(|b| b.root.is_none_or(|r| r + 1 != node && r != node))
            .collect();
        self.trunk.file(
            Filed {
                from,
                to,
                reach: width / 2.0,
                id: node,
            },
            self.size,
        );
        near
    }

    /// Whether the branch segment `from`–`to`, `width` wide, leaving from
    /// trunk node `root` if any, keeps clear of the trunk.
    pub(super) fn clear_of_trunk(
        &self,
        from: DVec3,
        to: DVec3,
        width: f64,
        root: Option<usize>,
    ) -> bool {
        let reach = width / 2.0 + self.gap;
        self.trunk
            .near(from, to, reach, self.size)
            .into_iter()
            .all(|node| root.is_some_and(|r| node == r || node == r + 1))
    }

    /// Files a drawn branch segment.
    pub(super) fn add_branch(&mut self, from: DVec3, to: DVec3, width: f64, is: BranchSegment) {
        self.branch_grid.file(
            Filed {
                from,
                to,
                reach: width / 2.0,
                id: self.branches.len(),
            },
            self.size,
        );
        self.branches.push(is);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_trunk_segment_finds_the_branches_it_comes_near_but_its_own() {
        let mut room = Room::new(5.0);
        room.set_gap(0.5);
        let at = |x: f64, y: f64| DVec3::new(x, y, 0.0);
        // A trunk node 1 at (0, 10); a branch from it, one far away, one
        // across where the next trunk segment goes.
        assert!(room.add_trunk(at(0., 0.), at(0., 10.), 1.0, 1).is_empty());
        let own = BranchSegment { limb: 1, end: 1, root: Some(1) };
        let far = BranchSegment { limb: 2, end: 1, root: None };
        let across = BranchSegment { limb: 3, end: 1, root: None };
        room.add_branch(at(0., 10.), at(6., 14.), 0.5, own);
        room.add_branch(at(40., 0.), at(50., 0.), 0.5, far);
        room.add_branch(at(-5., 15.), at(5., 15.), 0.5, across);
        assert_eq!(room.add_trunk(at(0., 10.), at(0., 20.), 1.0, 2), vec![across]);
        // A branch running beside the trunk closer than the half widths
        // and the gap is not clear; one further off is.
        assert!(!room.clear_of_trunk(at(0.9, 2.), at(0.9, 8.), 0.2, None));
        assert!(room.clear_of_trunk(at(1.2, 2.), at(1.2, 8.), 0.2, None));
        // Leaving from node 1, a branch may touch the trunk there.
        assert!(room.clear_of_trunk(at(0., 10.), at(5., 10.), 0.5, Some(1)));
        assert!(!room.clear_of_trunk(at(0., 10.), at(5., 10.), 0.5, None));
    }

    #[test]
    fn the_page_holds_whole_outlines() {
        let mut room = Room::new(5.0);
        assert!(room.on_page(DVec3::new(-1e6, 0.0, 0.0), 1.0));
        room.set_page(DVec2::ZERO, DVec2::new(100.0, 50.0));
        assert!(room.on_page(DVec3::new(1.0, 1.0, 9.0), 2.0));
        assert!(!room.on_page(DVec3::new(0.9, 1.0, 0.0), 2.0));
        assert!(!room.on_page(DVec3::new(50.0, 49.5, 0.0), 2.0));
    }
}
