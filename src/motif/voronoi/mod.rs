//! The `voronoi` family: Voronoi cells, Delaunay edges, inset cells,
//! stipple dots and a one-line tour, inside a region (see
//! [`VoronoiSpec`]).
//!
//! Sites are spread over the region ([`crate::geom::sample`]), relaxed
//! (Lloyd), and the diagram is clipped to the region exactly
//! ([`crate::geom::voronoi`]). Each kind listed in `draw` is a group
//! `<layer>.<pattern>.<kind>`:
//! - `cells`: the cell network, each edge between two cells drawn once
//!   (a plotter would draw shared edges twice if every cell were closed),
//!   the region's outline with it, as few strokes as the cells allow;
//! - `delaunay`: the constrained Delaunay triangulation of the sites and
//!   the region's outline, cut to the region, chained into strokes;
//! - `inset`: each cell shrunk (and rounded), one closed path a cell, ids
//!   `inset-<site>` so `[[adjust]]` can hide one;
//! - `sites`: a small circle at each site, ids `site-<i>`;
//! - `tour`: one pen-down line through every site.

mod network;
mod region;

use std::collections::BTreeMap;

use kurbo::{BezPath, Circle, Point, Shape};

use super::adjust::about;
use super::Context;
use crate::error::{Error, Result};
use crate::geom::density::Density;
use crate::geom::offset::offset;
use crate::geom::region::Region;
use crate::geom::voronoi::{
    constrained_delaunay, delaunay_edges, lloyd_step, weighted_lloyd_step, CellOptions, Diagram,
    Domain,
};
use crate::geom::{sample, tour, TOLERANCE};
use crate::rng::RandomStream;
use crate::scene::{Group, Style};
use crate::spec::{Distribution, Draw, VoronoiSpec, MAX_SITES};

/// Builds a Voronoi pattern into a group with id `group_id`.
///
/// # Errors
/// A region that encloses nothing; more sites than [`MAX_SITES`]; the path
/// budget; an SVG region file that was not loaded.
pub(super) fn build(spec: &VoronoiSpec, group_id: &str, cx: &mut Context<'_>) -> Result<Group> {
    let region = region::region(&spec.region, cx)?;
    let domain = Domain::new(&region, TOLERANCE)?;
    let options = CellOptions::DEFAULT.with_max_sites(MAX_SITES);
    // Sites come from the table's own id, not the layer's: tables with the
    // same id in two layers share their sites, so one window's lead and
    // glass can go to two pens.
    let table_id = group_id.rsplit('.').next().unwrap_or(group_id);
    let mut rng = cx.stream(&format!("voronoi/{table_id}"));
    let image = match &spec.sites.image {
        Some(name) => Some(cx.library().image(name)?),
        None => None,
    };
    let density = image.map(|img| Density::fitted(img, region.bounds()));
    let mut sites = sites(spec, &region, density.as_ref(), &mut rng, cx)?;
    for _ in 0..spec.relax {
        let step = match &density {
            Some(d) => weighted_lloyd_step(&sites, &domain, &options, &|p| d.at(p))?,
            None => lloyd_step(&sites, &domain, &options)?,
        };
        sites = step.sites;
        cx.advance(1);
    }
    let mut group = Group::new(group_id);
    let style = Style::default();
    let needs_diagram = spec
        .draw
        .iter()
        .any(|d| matches!(d, Draw::Cells | Draw::Inset));
    let diagram = if needs_diagram {
        Some(Diagram::new(&sites, &domain, &options)?)
    } else {
        None
    };
    let edges = if spec.draw.contains(&Draw::Tour) {
        delaunay_edges(&sites, &domain, &options)?
    } else {
        Vec::new()
    };
    for draw in &spec.draw {
        let id = format!("{group_id}.{}", name(*draw));
        let mut part = Group::new(&id);
        let paths: Vec<(String, BezPath)> = match draw {
            Draw::Cells => {
                let diagram = diagram.as_ref().expect("made for cells");
                numbered(&id, "stroke", network::cell_network(diagram))
            }
            Draw::Delaunay => numbered(&id, "stroke", triangulation(&sites, &region, &options)?),
            Draw::Inset => inset(spec, diagram.as_ref().expect("made for inset"), &id)?,
            Draw::Sites => sites
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    let dot = Circle::new(*p, spec.dot).to_path(TOLERANCE);
                    (format!("{id}.site-{i}"), dot)
                })
                .collect(),
            Draw::Tour => vec![(format!("{id}.line"), tour_path(&sites, &edges))],
        };
        cx.take_paths(paths.len(), || format!("voronoi {id}"))?;
        for (path_id, path) in paths {
            let adjusted = cx.adjust().take_without_motif(&path_id, "a Voronoi line")?;
            if adjusted.is_some_and(|a| a.hide) {
                continue;
            }
            let path = about(adjusted, path.bounding_box().center()) * path;
            part.push_path(path_id, path, style.clone());
        }
        group.push_group(part);
    }
    cx.advance(1);
    Ok(group)
}

/// The word a kind of line goes by in ids.
fn name(draw: Draw) -> &'static str {
    match draw {
        Draw::Cells => "cells",
        Draw::Delaunay => "delaunay",
        Draw::Inset => "inset",
        Draw::Sites => "sites",
        Draw::Tour => "tour",
    }
}

fn numbered(id: &str, what: &str, paths: Vec<BezPath>) -> Vec<(String, BezPath)> {
    paths
        .into_iter()
        .enumerate()
        .map(|(i, p)| (format!("{id}.{what}-{i}"), p))
        .collect()
}

/// The sites of the pattern, spread as the description says, denser where
/// `density` is dark.
fn sites(
    spec: &VoronoiSpec,
    region: &Region,
    density: Option<&Density<'_>>,
    rng: &mut RandomStream,
    cx: &Context<'_>,
) -> Result<Vec<Point>> {
    let s = &spec.sites;
    // The samplers name their own arguments; the description's fields are
    // these.
    let renamed = |e| match e {
        Error::Invalid { field, message, .. } => {
            let name = if field == "radius" {
                "spacing"
            } else {
                field.as_str()
            };
            Error::invalid(cx.field(&format!("sites.{name}")), message)
        }
        // The sampler's cap is this family's limit on sites, not the
        // scene's path budget.
        Error::Budget { .. } => {
            let name = if s.distribution == Distribution::Uniform {
                "count"
            } else {
                "spacing"
            };
            Error::invalid(
                cx.field(&format!("sites.{name}")),
                format!(
                    "would place more than {MAX_SITES} sites in a region of {:.0} mm²; \
                     widen the spacing",
                    region.area()
                ),
            )
        }
        other => other,
    };
    match (s.distribution, density) {
        (Distribution::Uniform, None) => {
            sample::uniform(region, s.count.unwrap_or(1) as usize, rng).map_err(renamed)
        }
        (Distribution::Uniform, Some(d)) => {
            darkness_sampled(region, s.count.unwrap_or(1) as usize, d, rng, cx)
        }
        (Distribution::Grid, _) => {
            let mut grid =
                sample::jittered_grid(region, s.spacing(), s.jitter(), rng).map_err(renamed)?;
            if let Some(d) = density {
                grid.retain(|p| rng.unit() < d.at(*p));
            }
            Ok(grid)
        }
        (Distribution::Poisson, None) => {
            let r = s.spacing();
            sample::poisson_disk(region, &|_| r, r..=r, rng, MAX_SITES).map_err(renamed)
        }
        (Distribution::Poisson, Some(d)) => {
            // Area per site in proportion to lightness: the radius grows
            // as 1/√darkness, up to ten times the spacing on white.
            let r = s.spacing();
            let radius = |p: Point| r / d.at(p).max(0.01).sqrt();
            sample::poisson_disk(region, &radius, r..=10.0 * r, rng, MAX_SITES).map_err(renamed)
        }
    }
}

/// Most tries per site wanted when placing sites by darkness: an image
/// that is almost white over the region cannot hold them.
const TRIES_PER_SITE: usize = 1000;

/// `count` sites placed at random with a probability in proportion to the
/// darkness under them (rejection sampling).
fn darkness_sampled(
    region: &Region,
    count: usize,
    density: &Density<'_>,
    rng: &mut RandomStream,
    cx: &Context<'_>,
) -> Result<Vec<Point>> {
    let mut sites = Vec::with_capacity(count);
    let mut tries = 0;
    while sites.len() < count {
        let batch = (count - sites.len()).max(64);
        tries += batch;
        if tries > TRIES_PER_SITE * count {
            return Err(Error::invalid(
                cx.field("sites.image"),
                format!(
                    "is too light over the region to place {count} sites \
                     ({} placed in {tries} tries); use a darker image or fewer sites",
                    sites.len()
                ),
            ));
        }
        for p in sample::uniform(region, batch, rng)? {
            if sites.len() < count && rng.unit() < density.at(p) {
                sites.push(p);
            }
        }
    }
    Ok(sites)
}

/// Each cell shrunk by `inset` and, with `round`, its corners rounded: the
/// cell eroded by `inset + round` and grown back by `round` (an opening),
/// which rounds convex corners to that radius.
fn inset(spec: &VoronoiSpec, diagram: &Diagram, id: &str) -> Result<Vec<(String, BezPath)>> {
    let mut out = Vec::new();
    for (i, cell) in diagram.cells().iter().enumerate() {
        if cell.is_empty() {
            continue;
        }
        let mut shape = offset(&cell.to_region(), -(spec.inset + spec.round), TOLERANCE)?;
        if spec.round > 0.0 && !shape.is_empty() {
            shape = offset(&shape, spec.round, TOLERANCE)?;
        }
        if !shape.is_empty() {
            out.push((format!("{id}.inset-{i}"), shape.into_path()));
        }
    }
    Ok(out)
}

/// How closely the triangulation's outline follows a curved region (mm):
/// its vertices are triangle corners, so a fine flattening would fan
/// slivers along every curve; half a millimetre keeps triangles whole and
/// the outline within a pen's width of the curve.
const TRIANGULATION_OUTLINE: f64 = 0.5;

/// The constrained Delaunay triangulation of the sites and the region's
/// outline (flattened within [`TRIANGULATION_OUTLINE`]), cut to the
/// region: every edge once, chained into strokes. Inside a bay or around a
/// hole no edge crosses out of the region, and the outline closes the
/// triangles at the edge (a low-poly look to the very border).
fn triangulation(sites: &[Point], region: &Region, options: &CellOptions) -> Result<Vec<BezPath>> {
    let coarse = Domain::new(region, TRIANGULATION_OUTLINE)?;
    let cdt = constrained_delaunay(sites, &coarse, options)?;
    // Outline vertices join the sites as points; lines name them by
    // their exact coordinates, which the triangulation gives back as put in.
    let key = |p: Point| (p.x.to_bits(), p.y.to_bits());
    let mut points = sites.to_vec();
    let mut index: BTreeMap<(u64, u64), usize> = BTreeMap::new();
    for (i, p) in sites.iter().enumerate() {
        index.entry(key(*p)).or_insert(i);
    }
    let mut edges = cdt.between_sites.clone();
    for line in cdt.to_outline.iter().chain(&cdt.outline) {
        let [a, b] = [line.p0, line.p1].map(|p| {
            *index.entry(key(p)).or_insert_with(|| {
                points.push(p);
                points.len() - 1
            })
        });
        edges.push([a.min(b), a.max(b)]);
    }
    Ok(network::chains(&points, &edges))
}

/// One line through every site, 2-opt tried among Delaunay neighbours.
fn tour_path(sites: &[Point], edges: &[[usize; 2]]) -> BezPath {
    let mut neighbours = vec![Vec::new(); sites.len()];
    for &[i, j] in edges {
        neighbours[i].push(j as u32);
        neighbours[j].push(i as u32);
    }
    let order = tour(sites, &neighbours);
    let mut path = BezPath::new();
    for (k, &i) in order.iter().enumerate() {
        if k == 0 {
            path.move_to(sites[i]);
        } else {
            path.line_to(sites[i]);
        }
    }
    path
}

#[cfg(test)]
mod tests;
