//! Betweed: pods — round shapes with concentric lines inside and a black
//! heart — grow from the section's edges, then from the edges of the pods
//! before them, each new one filling the gap between its neighbours and
//! tucked behind the pod it grows from.

use std::f64::consts::TAU;

use kurbo::{Point, Vec2};

use super::super::element::{Mark, Paint};
use super::shapes::{along_outline, circle, mark};
use super::Section;
use crate::rng::RandomStream;

/// Most pods in one section.
const MAX_PODS: usize = 400;

/// Generations of pods grown from pods.
const GENERATIONS: usize = 6;

/// Places a new pod may grow from along each pod's edge.
const BUDS: usize = 24;

/// A pod: its centre, radius and the pod it grows from.
#[derive(Debug, Clone, Copy)]
pub(super) struct Pod {
    pub(super) centre: Point,
    pub(super) radius: f64,
    pub(super) parent: Option<usize>,
}

/// The marks: the pods from the last grown (the farthest back) to the
/// first, each a white disc, an inner line and a black heart.
pub(super) fn draw(s: &Section<'_>, rng: &mut RandomStream) -> Vec<Mark> {
    let pods = grow(s, rng);
    let mut out = Vec::with_capacity(3 * pods.len());
    for p in pods.iter().rev() {
        out.push(mark(circle(p.centre, p.radius), Paint::White));
        let inner = 0.64 * p.radius;
        let heart = 0.32 * p.radius;
        if inner - heart > 3.0 * s.pen {
            out.push(mark(circle(p.centre, inner), Paint::Line));
        }
        out.push(mark(circle(p.centre, heart), Paint::Black));
    }
    out
}

/// The pods in the order they grow: first along the section's outline,
/// centred on it, then generation by generation from the edges of the
/// last, each as large as the gap it grows into lets it be.
pub(super) fn grow(s: &Section<'_>, rng: &mut RandomStream) -> Vec<Pod> {
    let gap = 2.0 * s.pen;
    let smallest = (0.3 * s.unit).max(5.0 * s.pen);
    let largest = 1.5 * s.unit;
    let mut pods: Vec<Pod> = Vec::new();
    for (at, _) in along_outline(s.region, 0.9 * largest) {
        let radius = largest * rng.range(0.55, 1.0);
        if fits(&pods, at, radius, gap, None) {
            pods.push(Pod {
                centre: at,
                radius,
                parent: None,
            });
        }
    }
    let mut last = 0..pods.len();
    for _ in 0..GENERATIONS {
        let mut buds: Vec<Pod> = Vec::new();
        for k in last.clone() {
            let p = pods[k];
            let turn = rng.unit() * TAU;
            for b in 0..BUDS {
                let at = p.centre + Vec2::from_angle(turn + b as f64 * TAU / BUDS as f64) * p.radius;
                if !s.region.contains(at) {
                    continue;
                }
                let room = pods
                    .iter()
                    .enumerate()
                    .filter(|&(i, _)| i != k)
                    .map(|(_, o)| o.centre.distance(at) - o.radius - gap)
                    .fold(f64::INFINITY, f64::min);
                let radius = room.min(0.8 * p.radius);
                if radius >= smallest {
                    buds.push(Pod {
                        centre: at,
                        radius,
                        parent: Some(k),
                    });
                }
            }
        }
        buds.sort_by(|a, b| b.radius.total_cmp(&a.radius));
        let start = pods.len();
        for bud in buds {
            if pods.len() >= MAX_PODS {
                break;
            }
            if fits(&pods, bud.centre, bud.radius, gap, bud.parent) {
                pods.push(bud);
            }
        }
        if pods.len() == start {
            break;
        }
        last = start..pods.len();
    }
    pods
}

/// Whether a pod at `centre` of `radius` keeps `gap` from every pod but
/// its parent.
fn fits(pods: &[Pod], centre: Point, radius: f64, gap: f64, parent: Option<usize>) -> bool {
    pods.iter()
        .enumerate()
        .filter(|&(i, _)| Some(i) != parent)
        .all(|(_, o)| o.centre.distance(centre) >= o.radius + radius + gap)
}
