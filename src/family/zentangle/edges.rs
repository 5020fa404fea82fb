//! The edges of hatched black parts, drawn once. A black part is paint
//! whose hatch keeps clear of its edge ([`Style::edge_drawn`]): where the
//! edge is the line of a mark (the one that painted it black, or a later
//! one over it) or of the border or string, that line draws it; where no
//! line runs — a section's edge that nothing inks, a tile without a
//! border — the part draws that stretch of its edge itself, as a line
//! right after it.

use kurbo::BezPath;

use crate::plot::dedupe::{beside, PEN_SHARE};
use crate::scene::{Group, Node, Style, StyledPath};

/// Adds to `group` (a zentangle, every transform the identity) the
/// stretches of its black parts' edges that none of its lines draws, for
/// a pen `pen` mm wide; the number of paths added.
pub(super) fn draw_bare_edges(group: &mut Group, pen: f64) -> usize {
    let mut lines = Vec::new();
    let mut edges = Vec::new();
    collect(group, &mut lines, &mut edges);
    if edges.is_empty() {
        return 0;
    }
    let bare = beside(&lines, edges, PEN_SHARE * pen, pen);
    let added = bare.iter().flatten().count();
    insert(group, &mut bare.into_iter());
    added
}

/// The drawn lines of `group` and the outlines of its black parts, in
/// paint order.
fn collect(group: &Group, lines: &mut Vec<BezPath>, edges: &mut Vec<BezPath>) {
    for node in &group.children {
        match node {
            Node::Group(g) => collect(g, lines, edges),
            Node::Path(p) if is_black(&p.style) => edges.push(p.path.clone()),
            Node::Path(p) if p.style.is_drawn() && p.style.fill.is_none() => {
                lines.push(p.path.clone());
            }
            Node::Path(_) => {}
        }
    }
}

/// Puts the next of `bare` after each black part of `group`, in the
/// order [`collect`] found them.
fn insert(group: &mut Group, bare: &mut impl Iterator<Item = Option<BezPath>>) {
    let children = std::mem::take(&mut group.children);
    for node in children {
        match node {
            Node::Group(mut g) => {
                insert(&mut g, bare);
                group.children.push(Node::Group(g));
            }
            Node::Path(p) if is_black(&p.style) => {
                let edge = bare.next().flatten().map(|path| StyledPath {
                    id: format!("{}.edge", p.id),
                    path,
                    style: Style::default(),
                });
                group.children.push(Node::Path(p));
                if let Some(edge) = edge {
                    group.children.push(Node::Path(edge));
                }
            }
            node => group.children.push(node),
        }
    }
}

/// A black part whose edge other lines draw.
fn is_black(style: &Style) -> bool {
    style.fill_only && style.edge_drawn
}
