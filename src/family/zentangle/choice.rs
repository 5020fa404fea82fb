//! A tangler's choices: which tangle fills each section of the tile.
//!
//! A tangler fills a section with one tangle, not a sampler of them, and
//! picks it against its neighbours: dark beside light, organic beside
//! geometric, never the same tangle twice side by side. Each procedure
//! has a [`Character`] for that; [`choose`] gives every section one
//! procedure by weight, largest section first, among those that contrast
//! best with the neighbours already chosen — and with a tone map, those
//! whose darkness class matches the target at the section's widest
//! point.

use kurbo::Point;

use super::procedure::Allowed;
use crate::geom::offset::offset;
use crate::geom::region::Region;
use crate::rng::RandomStream;

/// How a tangle reads from a step back.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Character {
    /// Mostly black or densely lined (rather than open, mostly white).
    pub(super) dark: bool,
    /// Free, grown or flowing (rather than ruled, on a lattice).
    pub(super) organic: bool,
}

/// The character of procedure `id`. A procedure not listed reads as light
/// and geometric.
pub(super) fn character(id: u32) -> Character {
    let (dark, organic) = match id {
        // Scattered elements on a ground painted black a third of the time.
        4 => (true, true),
        // Stretched squares on a black ground; elements turned in rows;
        // fine triangle cells; small tiles; whirls; bands of black.
        8 | 10 | 14 | 15 | 17 | 19 => (true, false),
        // Plants, scattered curves, contour lines, cells.
        7 | 12 | 16 | 18 => (false, true),
        _ => (false, false),
    };
    Character { dark, organic }
}

/// The procedures that fill a section on their own: patterns over the
/// whole region, not a single element at its widest point (those, 0–3
/// and 11, are what tangles nest), nor a few curves strewn about (12).
pub(super) const SECTION_TANGLES: &[u32] = &[4, 5, 6, 7, 8, 9, 10, 13, 14, 15, 16, 17, 18, 19];

/// How sections are given their tangles.
#[derive(Clone, Copy)]
pub(super) struct Choice<'a> {
    /// The weight of procedure `id` (≥ 0; 0: never).
    pub(super) weight: &'a dyn Fn(u32) -> f64,
    /// Neighbouring sections contrast: differ in tangle, in darkness and
    /// in kind where the allowed tangles let them.
    pub(super) contrast: bool,
}

/// One procedure for each of `sections` (in their order): by weight among
/// the allowed section tangles (any allowed procedure if none is), largest
/// section first; with `choice.contrast`, among those that differ most
/// from the neighbours (sections less than two pen widths apart, along
/// more than a few pen widths) chosen before; with `tone` (darkness at a
/// point), weighted towards the darkness class the target asks for at
/// each section's `poles`; a tangle already used elsewhere is less likely
/// again.
pub(super) fn choose(
    sections: &[Region],
    poles: &[Point],
    allowed: &Allowed,
    choice: &Choice<'_>,
    tone: Option<&dyn Fn(Point) -> f64>,
    pen: f64,
    rng: &mut RandomStream,
) -> Vec<u32> {
    let pool: Vec<u32> = {
        let own: Vec<u32> = allowed
            .procedures
            .iter()
            .copied()
            .filter(|p| SECTION_TANGLES.contains(p) && (choice.weight)(*p) > 0.0)
            .collect();
        if own.is_empty() {
            allowed.procedures.clone()
        } else {
            own
        }
    };
    let near = if choice.contrast {
        neighbours(sections, pen)
    } else {
        vec![Vec::new(); sections.len()]
    };
    let mut order: Vec<usize> = (0..sections.len()).collect();
    order.sort_by(|&a, &b| sections[b].area().total_cmp(&sections[a].area()));
    let mut chosen: Vec<Option<u32>> = vec![None; sections.len()];
    for s in order {
        let around: Vec<u32> = near[s].iter().filter_map(|&n| chosen[n]).collect();
        let differs = |p: u32, strict: usize| {
            let c = character(p);
            around.iter().all(|&q| {
                let d = character(q);
                q != p && (strict < 2 || d.dark != c.dark) && (strict < 3 || d.organic != c.organic)
            })
        };
        // The strictest contrast some allowed tangle meets.
        let candidates: Vec<u32> = (0..=3)
            .rev()
            .map(|strict| {
                pool.iter()
                    .copied()
                    .filter(|&p| strict == 0 || differs(p, strict))
                    .collect::<Vec<u32>>()
            })
            .find(|c| !c.is_empty())
            .unwrap_or_else(|| pool.clone());
        let dark = tone.map(|t| t(poles[s]).clamp(0.0, 1.0));
        let weights: Vec<f64> = candidates
            .iter()
            .map(|&p| {
                let mut w = (choice.weight)(p).max(0.0);
                if chosen.contains(&Some(p)) {
                    w *= REUSED;
                }
                if let Some(d) = dark {
                    let wants = if character(p).dark { d } else { 1.0 - d };
                    w *= 0.05 + wants;
                }
                w
            })
            .collect();
        chosen[s] = Some(weighted(&candidates, &weights, rng));
    }
    chosen.into_iter().map(|c| c.unwrap_or(pool[0])).collect()
}

/// How much less likely a tangle is in a section once another section has
/// it: a tile shows several tangles, but may repeat one.
const REUSED: f64 = 0.1;

/// One of `items` with chances in proportion to `weights` (the first when
/// they are all 0).
fn weighted(items: &[u32], weights: &[f64], rng: &mut RandomStream) -> u32 {
    let total: f64 = weights.iter().sum();
    if total <= 0.0 {
        return items[0];
    }
    let mut left = rng.unit() * total;
    for (&item, &w) in items.iter().zip(weights) {
        if left < w {
            return item;
        }
        left -= w;
    }
    items[items.len() - 1]
}

/// For each section, the sections beside it: closer than two pen widths
/// (a line between them) along more than a few pen widths.
pub(super) fn neighbours(sections: &[Region], pen: f64) -> Vec<Vec<usize>> {
    let grown: Vec<Option<Region>> = sections
        .iter()
        .map(|s| offset(s, 2.0 * pen, pen / 4.0).ok())
        .collect();
    let mut out = vec![Vec::new(); sections.len()];
    for a in 0..sections.len() {
        for b in a + 1..sections.len() {
            let Some(g) = &grown[a] else { continue };
            if !g.bounds().overlaps(sections[b].bounds()) {
                continue;
            }
            // A shared edge `l` long overlaps by about `l` × pen; a corner
            // touch by about pen².
            if g.intersection(&sections[b]).area() > SHARED_EDGE_PENS * pen * pen {
                out[a].push(b);
                out[b].push(a);
            }
        }
    }
    out
}

/// Sections count as neighbours along an edge longer than this many pen
/// widths.
const SHARED_EDGE_PENS: f64 = 10.0;

#[cfg(test)]
mod tests {
    use kurbo::Rect;

    use super::*;
    use crate::family::zentangle::element::Shape;
    use crate::rng::Seed;

    const PEN: f64 = 0.3;

    /// A 3 × 3 grid of 20 mm squares a pen's width apart, as a string of
    /// two lines each way leaves them.
    fn grid() -> Vec<Region> {
        (0..9)
            .map(|k| {
                let (x, y) = (f64::from(k % 3) * 20.3, f64::from(k / 3) * 20.3);
                Region::from_rect(Rect::new(x, y, x + 20.0, y + 20.0)).unwrap()
            })
            .collect()
    }

    fn all() -> Allowed {
        Allowed {
            procedures: (0..20).collect(),
            elements: Shape::ALL.to_vec(),
        }
    }

    fn chosen(contrast: bool, seed: u64) -> Vec<u32> {
        let sections = grid();
        let poles: Vec<Point> = sections.iter().map(|s| s.bounds().center()).collect();
        let choice = Choice {
            weight: &|_| 1.0,
            contrast,
        };
        let mut rng = Seed(seed).derive("choice").stream();
        choose(&sections, &poles, &all(), &choice, None, PEN, &mut rng)
    }

    #[test]
    fn squares_beside_each_other_are_neighbours_and_corners_are_not() {
        let near = neighbours(&grid(), PEN);
        assert_eq!(near[4], [1, 3, 5, 7]);
        assert_eq!(near[0], [1, 3]);
    }

    #[test]
    fn neighbours_differ_in_tangle_darkness_and_kind_when_asked() {
        let near = neighbours(&grid(), PEN);
        let clashes = |tangles: &[u32]| {
            let mut n = 0;
            for (a, around) in near.iter().enumerate() {
                for &b in around {
                    let (ca, cb) = (character(tangles[a]), character(tangles[b]));
                    n += usize::from(tangles[a] == tangles[b] || ca.dark == cb.dark);
                }
            }
            n
        };
        let mut loose = 0;
        for seed in 0..8 {
            let tangles = chosen(true, seed);
            assert!(tangles.iter().all(|p| SECTION_TANGLES.contains(p)));
            // A grid is two-coloured: dark and light alternate everywhere.
            assert_eq!(clashes(&tangles), 0, "seed {seed}: {tangles:?}");
            loose += clashes(&chosen(false, seed));
        }
        // Without contrast, neighbours often match.
        assert!(loose > 8, "{loose}");
    }

    #[test]
    fn weights_decide_which_tangles_are_chosen() {
        let sections = grid();
        let poles: Vec<Point> = sections.iter().map(|s| s.bounds().center()).collect();
        let only = |p: u32| if p == 16 || p == 17 { 1.0 } else { 0.0 };
        let choice = Choice {
            weight: &only,
            contrast: true,
        };
        let mut rng = Seed(1).stream();
        let tangles = choose(&sections, &poles, &all(), &choice, None, PEN, &mut rng);
        assert!(tangles.iter().all(|&p| p == 16 || p == 17), "{tangles:?}");
        // 16 is light, 17 dark: a chequerboard.
        assert_eq!(tangles[0] == 16, tangles[4] == 16);
        assert_ne!(tangles[0], tangles[1]);
    }
}
