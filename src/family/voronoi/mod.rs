//! The `voronoi` family: Voronoi cells, Delaunay edges, inset cells,
//! stipple dots and a one-line tour, inside a region (see
//! [`VoronoiSpec`]).
//!
//! Sites are spread over the region ([`crate::geom::sample`]) or given by
//! hand (`sites.points`: those inside the region, each once), relaxed
//! (Lloyd), and the diagram is clipped to the region exactly
//! ([`crate::geom::voronoi`]) — one diagram for each connected part of a
//! region in pieces, so no cell reaches across a gap (a rose window's
//! tracery, the space between two shapes) to leave a sliver on the far
//! side. Only the spreading draws random numbers, so
//! the sites a distribution spread, given back as points
//! ([`crate::project::voronoi_sites`]), draw the same pattern. Each kind
//! listed in `draw` is a group
//! `<layer>.<pattern>.<kind>`:
//! - `cells`: the cell network, each edge between two cells drawn once
//!   (a plotter would draw shared edges twice if every cell were closed),
//!   the region's outline with it, as few strokes as the cells allow;
//! - `delaunay`: the constrained Delaunay triangulation of the sites and
//!   the region's outline, refined so that no triangle is a sliver, inside
//!   the region (see [`mesh`]), chained into strokes;
//! - `inset`: each cell shrunk (and rounded), one closed path a cell, ids
//!   `inset-<site>` so `[[adjust]]` can hide one;
//! - `sites`: a small circle at each site, ids `site-<i>`;
//! - `tour`: one pen-down line through every site;
//! - `cracks`: mud cracks (see [`cracks`]), the region split by curved
//!   cracks that end on older ones, drawn as the plates' outlines, ids
//!   `plate-<i>`.

pub(crate) mod cracks;
pub(crate) mod description;
mod features;
pub(crate) mod mesh;
mod rose;
#[cfg(feature = "studio")]
mod gesture;

use std::borrow::Cow;

use kurbo::{BezPath, Point, Rect, Shape};

use crate::error::{Error, Result};
use crate::geom::density::{Density, Formula, GreyImage};
use crate::geom::offset::offset;
use crate::geom::region::Region;
use crate::geom::subpath::subpaths;
use crate::geom::voronoi::{
    cell_network, delaunay_edges, distinct, relax, CellOptions,
    Diagram, Domain, Lbg, Relaxation, Relaxed,
};
use crate::geom::{sample, tour, TOLERANCE};
use crate::motif::adjust::about;
use crate::motif::region::region;
use crate::motif::dot::dot;
use crate::motif::Context;
use crate::rng::RandomStream;
use crate::scene::{Group, PathBudget, Style};
use crate::spec::{Distribution, Draw, RelaxationMethod, VoronoiSpec, MAX_SITES};

/// Builds a Voronoi pattern into a group with id `group_id`.
///
/// # Errors
/// A region that encloses nothing; more sites than [`MAX_SITES`]; given
/// points none of which lies inside the region; the path budget; an SVG
/// region file that was not loaded.
pub(super) fn build(spec: &VoronoiSpec, group_id: &str, cx: &mut Context<'_>) -> Result<Group> {
    let region = window(spec, cx)?;
    let domain = Domain::new(&region, TOLERANCE)?;
    let options = CellOptions::DEFAULT.with_max_sites(MAX_SITES);
    let formula = formula(spec, cx)?;
    let image = image(spec, cx)?;
    let density = density(spec, &region, formula.as_ref(), image.as_deref(), cx)?;
    let sites = sites(spec, group_id, &region, density.as_ref(), cx)?;
    let sites = relaxed(
        spec,
        sites,
        &domain,
        &options,
        density.as_ref(),
        group_id,
        cx,
    )?;
    let mut group = Group::new(group_id);
    let style = Style::default();
    let needs_diagram = spec
        .draw
        .iter()
        .any(|d| matches!(d, Draw::Cells | Draw::Inset));
    let parts = if needs_diagram {
        cells_by_part(&sites, &region, &domain, &options)?
    } else {
        Vec::new()
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
                let strokes = parts
                    .iter()
                    .flat_map(|p| cell_network(&p.diagram, &p.domain, spec.outline))
                    .collect();
                numbered(&id, "stroke", strokes)
            }
            Draw::Delaunay => {
                // The mesh's own outline lies a hair inside the region (see
                // `mesh`); the outline a pen draws is the region's, exact.
                let mut strokes = mesh::triangulate(&sites, &region)?.strokes();
                if spec.outline {
                    strokes.extend(subpaths(region.path()).map(|s| s.to_path()));
                }
                numbered(&id, "stroke", strokes)
            }
            Draw::Inset => {
                let mut insets = Vec::new();
                for p in &parts {
                    insets.extend(inset(spec, p, &id)?);
                }
                insets
            }
            Draw::Sites => {
                let width = cx.pen_width();
                let radius = |p: Point| match (spec.dot_range, &density) {
                    (Some([light, dark]), Some(d)) => {
                        light + (dark - light) * d.at(p).clamp(0.0, 1.0)
                    }
                    _ => spec.dot,
                };
                sites
                    .iter()
                    .enumerate()
                    .map(|(i, p)| (format!("{id}.site-{i}"), dot(*p, radius(*p), width)))
                    .collect()
            }
            Draw::Tour => vec![(format!("{id}.line"), tours(&sites, &edges, &region))],
            Draw::Cracks => numbered(&id, "plate", plates(spec, group_id, &region, cx)?),
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
    if cx.regions_wanted() {
        let offered = offered(spec, &parts, &sites, &domain, &region, &options)?;
        cx.offer(offered);
    }
    cx.advance(1);
    Ok(group)
}

/// The sites the pattern with group id `group_id` starts from, before
/// relaxation: the ones [`build`] spreads or is given (see
/// [`crate::project::voronoi_sites`]).
///
/// # Errors
/// As [`build`], up to the sites.
pub(super) fn starting_sites(
    spec: &VoronoiSpec,
    group_id: &str,
    cx: &Context<'_>,
) -> Result<Vec<Point>> {
    let region = window(spec, cx)?;
    let formula = formula(spec, cx)?;
    let image = image(spec, cx)?;
    let density = density(spec, &region, formula.as_ref(), image.as_deref(), cx)?;
    sites(spec, group_id, &region, density.as_ref(), cx)
}

/// The region the pattern fills: the description's, less a rose's
/// tracery rings (see [`rose`]).
fn window(spec: &VoronoiSpec, cx: &Context<'_>) -> Result<Region> {
    let region = region(&spec.region, cx)?;
    match spec.sites.tracery {
        Some(width) if width > 0.0 => rose_plan(spec, &region).cut(&region, width),
        _ => Ok(region),
    }
}

/// The rose window the sites spread over `region` (its bounds) make.
fn rose_plan(spec: &VoronoiSpec, region: &Region) -> rose::Rose {
    rose::plan(region.bounds(), spec.sites.petals(), spec.sites.spacing())
}

/// The density formula of the sites, parsed.
fn formula(spec: &VoronoiSpec, cx: &Context<'_>) -> Result<Option<Formula>> {
    spec.sites
        .density
        .as_deref()
        .map(|text| Formula::parse(text).map_err(|e| site_error(e, spec, 0.0, cx)))
        .transpose()
}

/// The image that weighs the sites, as `sites.image` and `sites.edges`
/// say (see [`features`]).
fn image<'a>(spec: &VoronoiSpec, cx: &Context<'a>) -> Result<Option<Cow<'a, GreyImage>>> {
    let Some(name) = &spec.sites.image else {
        return Ok(None);
    };
    let image = cx.library().image(name)?;
    features::weighed(image, spec.sites.edges.unwrap_or(0.0)).map(Some)
}

/// What weighs the sites, when `image` or `density` is given: the image
/// times the formula over the region's bounds, checked to be above 0
/// somewhere.
fn density<'d>(
    spec: &VoronoiSpec,
    region: &Region,
    formula: Option<&'d Formula>,
    image: Option<&'d GreyImage>,
    cx: &Context<'_>,
) -> Result<Option<Density<'d>>> {
    if !spec.sites.is_weighted() {
        return Ok(None);
    }
    let mut density = Density::new(region.bounds());
    if let Some(image) = image {
        density = density.with_image(image);
    }
    if let Some(f) = formula {
        density = density.with_formula(f);
    }
    check_density(spec, &density, region, cx)?;
    Ok(Some(density))
}

/// The regions the pattern offers later layers to fill: the closed shapes
/// it draws — inset cells, else cells, else Delaunay triangles (when those
/// are all it draws) — or its cells when it draws none of them.
fn offered(
    spec: &VoronoiSpec,
    parts: &[Part],
    sites: &[Point],
    domain: &Domain,
    region: &Region,
    options: &CellOptions,
) -> Result<Vec<Region>> {
    let cells = |parts: &[Part]| -> Vec<Region> {
        parts
            .iter()
            .flat_map(|p| p.diagram.cells())
            .filter(|c| !c.is_empty())
            .map(|c| c.to_region())
            .collect()
    };
    if spec.draw.contains(&Draw::Delaunay) && parts.is_empty() {
        let mesh = mesh::triangulate(sites, region)?;
        return Ok(mesh
            .triangles
            .iter()
            .filter_map(|&t| Region::polygon(&mesh.corners(t)).ok())
            .collect());
    }
    if parts.is_empty() {
        return Ok(cells(&cells_by_part(sites, region, domain, options)?));
    }
    if spec.draw.contains(&Draw::Inset) {
        let mut insets = Vec::new();
        for p in parts {
            insets.extend(
                inset(spec, p, "")?
                    .into_iter()
                    .map(|(_, path)| Region::from_normalised(path)),
            );
        }
        return Ok(insets);
    }
    Ok(cells(parts))
}

/// The sites relaxed as the description says, with a note on how far
/// they settled; one unit of progress a step (the steps convergence saved
/// are counted as done).
fn relaxed(
    spec: &VoronoiSpec,
    sites: Vec<Point>,
    domain: &Domain,
    options: &CellOptions,
    density: Option<&Density<'_>>,
    group_id: &str,
    cx: &mut Context<'_>,
) -> Result<Vec<Point>> {
    if spec.relax == 0 {
        return Ok(sites);
    }
    // Its cost, before any is spent: every step run on these sites (LBG's
    // count changes, so `relax` also stops before a step past the budget).
    let left = cx.budget().site_steps_left();
    let estimate = sites.len().saturating_mul(spec.relax as usize);
    if estimate > left {
        return Err(relax_budget(spec, sites.len(), estimate, left, cx));
    }
    let how = match spec.relaxation {
        RelaxationMethod::Lloyd => Relaxation::lloyd(spec.relax),
        RelaxationMethod::Lbg => Relaxation::lbg(
            spec.relax,
            Lbg::new(Lbg::mass_for_spacing(spec.sites.spacing())),
        ),
    }
    .with_settled(spec.converge.unwrap_or(0.0))
    .with_max_site_steps(left);
    // Cells weigh what they hold to the scale the density changes on:
    // an image's pixel, and at most half the spacing of the sites — that
    // of `count` (or the given) sites spread evenly when none is given.
    let s = &spec.sites;
    let spacing = match (s.spacing, &s.points, s.distribution(), s.count) {
        (None, Some(_), _, _) => (domain.area() / sites.len() as f64).sqrt(),
        (None, None, Distribution::Uniform, Some(n)) => (domain.area() / n as f64).sqrt(),
        _ => s.spacing(),
    };
    let detail = density
        .and_then(Density::pixel)
        .map_or(spacing / 2.0, |px| px.min(spacing / 2.0));
    let options = options.with_density_detail(detail);
    let start = cx.done();
    let rho = density.map(|d| move |p: Point| d.at(p));
    let rho = rho.as_ref().map(|f| f as &dyn Fn(Point) -> f64);
    let first = sites.len();
    let relaxed = relax(sites, domain, &options, rho, &how, &mut |_| cx.advance(1))
        .map_err(|e| site_error(e, spec, domain.area(), cx))?;
    // The sites each step ran on: the first count, then each step's result.
    let spent = std::iter::once(first)
        .chain(relaxed.steps.iter().map(|r| r.sites))
        .take(relaxed.steps.len())
        .sum();
    let taken = cx.budget().take_site_steps(spent);
    debug_assert!(taken, "relax runs no step past the site-steps left");
    cx.advance_to(start + spec.relax as usize);
    cx.note(group_id, convergence(spec, first, &relaxed));
    Ok(relaxed.sites)
}

/// The refusal of a relaxation of `sites` whose `estimate` (site-steps)
/// passes the `left` of the scene's budget.
fn relax_budget(
    spec: &VoronoiSpec,
    sites: usize,
    estimate: usize,
    left: usize,
    cx: &Context<'_>,
) -> Error {
    let limit = PathBudget::SITE_STEP_LIMIT;
    let earlier = if left < limit {
        format!(" ({} taken by earlier tables)", limit - left)
    } else {
        String::new()
    };
    Error::invalid(
        cx.field("relax"),
        format!(
            "{} steps × {sites} sites is {estimate} site-steps of relaxation, more than the \
             {left} left of a scene's {limit}{earlier}: lower relax, or widen the sites' spacing",
            spec.relax
        ),
    )
}

/// One line on how a relaxation went: steps, sites, the last step's mean
/// movement and how far the energy fell.
fn convergence(spec: &VoronoiSpec, first: usize, relaxed: &Relaxed) -> String {
    let method = match spec.relaxation {
        RelaxationMethod::Lloyd => "Lloyd",
        RelaxationMethod::Lbg => "LBG",
    };
    let (Some(head), Some(last)) = (relaxed.steps.first(), relaxed.steps.last()) else {
        return format!("{method}: no steps");
    };
    let n = relaxed.steps.len();
    let outcome = match (relaxed.converged, spec.converge) {
        (true, Some(c)) => format!("converged in {n} steps (mean movement under {c} mm)"),
        (true, None) => format!("settled in {n} steps"),
        (false, Some(c)) => format!(
            "did not converge in {n} steps (mean movement {:.3} mm, asked under {c} mm)",
            last.mean_movement
        ),
        (false, None) => format!("{n} steps"),
    };
    let count = if relaxed.sites.len() == first {
        format!("{first} sites")
    } else {
        format!("{first} → {} sites", relaxed.sites.len())
    };
    let energy = if head.energy > 0.0 {
        format!(
            ", energy −{:.1}%",
            100.0 * (1.0 - last.energy / head.energy)
        )
    } else {
        String::new()
    };
    format!(
        "{method} relaxation: {outcome}; {count}; last step moved sites {:.4} mm on average{energy}",
        last.mean_movement
    )
}

/// A density that is 0 (or not a number) over the whole region would
/// leave every site where it fell, or no site at all: say so.
fn check_density(
    spec: &VoronoiSpec,
    density: &Density<'_>,
    region: &Region,
    cx: &Context<'_>,
) -> Result<()> {
    let b = region.bounds();
    const N: usize = 32;
    let any = (0..N * N).any(|k| {
        let (i, j) = (k % N, k / N);
        let p = Point::new(
            b.x0 + (i as f64 + 0.5) / N as f64 * b.width(),
            b.y0 + (j as f64 + 0.5) / N as f64 * b.height(),
        );
        density.at(p) > 0.0
    });
    if any {
        return Ok(());
    }
    let field = if spec.sites.density.is_some() {
        "sites.density"
    } else {
        "sites.image"
    };
    Err(Error::invalid(
        cx.field(field),
        "gives no density anywhere over the region (0, or not a number): nothing would \
         draw sites to any place",
    ))
}

/// The word a kind of line goes by in ids.
fn name(draw: Draw) -> &'static str {
    match draw {
        Draw::Cells => "cells",
        Draw::Delaunay => "delaunay",
        Draw::Inset => "inset",
        Draw::Sites => "sites",
        Draw::Tour => "tour",
        Draw::Cracks => "cracks",
    }
}

/// The plates of mud the region cracks into, from the table's own stream
/// (see [`sites`]), after the sites' own.
fn plates(
    spec: &VoronoiSpec,
    group_id: &str,
    region: &Region,
    cx: &mut Context<'_>,
) -> Result<Vec<BezPath>> {
    let table_id = group_id.rsplit('.').next().unwrap_or(group_id);
    let mut rng = cx.stream(&format!("voronoi/{table_id}/cracks"));
    let cracked = cracks::crack(region, spec.sites.spacing(), spec.crack, &mut rng)
        .map_err(|e| site_error(e, spec, region.area(), cx))?;
    cx.note(
        group_id,
        format!(
            "{} cracks, {} plates",
            cracked.cracks.len(),
            cracked.plates.len()
        ),
    );
    Ok(cracked.plates)
}

fn numbered(id: &str, what: &str, paths: Vec<BezPath>) -> Vec<(String, BezPath)> {
    paths
        .into_iter()
        .enumerate()
        .map(|(i, p)| (format!("{id}.{what}-{i}"), p))
        .collect()
}

/// The sites of the pattern, given or spread as the description says,
/// denser where `density` is dark.
fn sites(
    spec: &VoronoiSpec,
    group_id: &str,
    region: &Region,
    density: Option<&Density<'_>>,
    cx: &Context<'_>,
) -> Result<Vec<Point>> {
    let s = &spec.sites;
    if let Some(points) = &s.points {
        return given(points, region, cx);
    }
    // Sites come from the table's own id, not the layer's: tables with the
    // same id in two layers share their sites, so one window's lead and
    // glass can go to two pens. Nothing after the sites draws from this
    // stream: the sites it spread, given as points, draw the same pattern.
    let table_id = group_id.rsplit('.').next().unwrap_or(group_id);
    let mut rng = cx.stream(&format!("voronoi/{table_id}"));
    // The samplers name their own arguments; the description's fields are
    // these.
    let renamed = |e| site_error(e, spec, region.area(), cx);
    match (s.distribution(), density) {
        (Distribution::Uniform, None) => {
            sample::uniform(region, s.count.unwrap_or(1) as usize, &mut rng).map_err(renamed)
        }
        (Distribution::Uniform, Some(d)) => {
            darkness_sampled(region, s.count.unwrap_or(1) as usize, d, &mut rng, cx)
        }
        (Distribution::Grid, _) => {
            let mut grid = sample::jittered_grid(region, s.spacing(), s.jitter(), &mut rng)
                .map_err(renamed)?;
            if let Some(d) = density {
                grid.retain(|p| rng.unit() < d.at(*p));
            }
            Ok(grid)
        }
        (Distribution::Rose, _) => {
            // The window's bounds are the description's region's, not
            // those of what the tracery leaves (the same here: the rings
            // lie inside).
            let plan = rose_plan(spec, region);
            Ok(sample::inside(region, &plan.sites))
        }
        (Distribution::Poisson, None) => {
            let r = s.spacing();
            sample::poisson_disk(region, &|_| r, r..=r, &mut rng, MAX_SITES).map_err(renamed)
        }
        (Distribution::Poisson, Some(d)) => {
            // Area per site in proportion to lightness: the radius grows
            // as 1/√darkness, up to ten times the spacing on white.
            let r = s.spacing();
            let radius = |p: Point| r / d.at(p).max(0.01).sqrt();
            sample::poisson_disk(region, &radius, r..=10.0 * r, &mut rng, MAX_SITES)
                .map_err(renamed)
        }
    }
}

/// The sites given by hand: those inside the region (a dragged site may
/// land outside), each once (a repeated point would be a second site with
/// an empty cell, a dot drawn twice, a tour's step of length 0).
fn given(points: &[[f64; 2]], region: &Region, cx: &Context<'_>) -> Result<Vec<Point>> {
    let points: Vec<Point> = points.iter().map(|&[x, y]| Point::new(x, y)).collect();
    let sites = distinct(&sample::inside(region, &points));
    if sites.is_empty() {
        return Err(Error::invalid(
            cx.field("sites.points"),
            format!(
                "none of the {} points lies inside the region: there is no site to draw",
                points.len()
            ),
        ));
    }
    Ok(sites)
}

/// An error of the samplers or of relaxation in the description's terms:
/// they name their own arguments (`radius`, `mass`, `density`), and their
/// cap on sites is this family's limit, not the scene's path budget.
fn site_error(e: Error, spec: &VoronoiSpec, area: f64, cx: &Context<'_>) -> Error {
    let s = &spec.sites;
    match e {
        // The relaxation's own budget, found as LBG's sites grew.
        Error::Invalid { field, message, .. } if field == "relax" => {
            Error::invalid(cx.field("relax"), message)
        }
        Error::Invalid { field, message, .. } => {
            let name = match field.as_str() {
                "radius" | "mass" => "spacing",
                other => other,
            };
            Error::invalid(cx.field(&format!("sites.{name}")), message)
        }
        Error::Budget { .. } => {
            let name = if s.distribution == Some(Distribution::Uniform) && s.spacing.is_none() {
                "count"
            } else {
                // Given points are at most MAX_SITES: only LBG, which
                // splits sites by the spacing, can place more.
                "spacing"
            };
            Error::invalid(
                cx.field(&format!("sites.{name}")),
                format!(
                    "would place more than {MAX_SITES} sites in a region of {area:.0} mm²; \
                     widen the spacing"
                ),
            )
        }
        other => other,
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
fn inset(spec: &VoronoiSpec, part: &Part, id: &str) -> Result<Vec<(String, BezPath)>> {
    let mut out = Vec::new();
    for (&i, cell) in part.members.iter().zip(part.diagram.cells()) {
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

/// The index of the part of `parts` each site lies in. A site on no
/// part's inside (a hair outside, by rounding) goes with the first part
/// whose bounds hold it.
fn part_of(sites: &[Point], parts: &[Region]) -> Vec<usize> {
    let bounds: Vec<Rect> = parts.iter().map(Region::bounds).collect();
    sites
        .iter()
        .map(|&p| {
            let holding: Vec<usize> = (0..parts.len()).filter(|&k| bounds[k].contains(p)).collect();
            holding
                .iter()
                .copied()
                .find(|&k| parts[k].contains(p))
                .or(holding.first().copied())
                .unwrap_or(0)
        })
        .collect()
}

/// The Voronoi cells of one connected part of the region: the diagram of
/// the sites inside it, clipped to it alone.
struct Part {
    diagram: Diagram,
    domain: Domain,
    /// Each cell's site, as an index into all the sites.
    members: Vec<usize>,
}

/// The cells of `sites` in `region`, part by part: a cell ends where its
/// part of the region ends, and never reaches across a gap into another
/// part (across a rose window's ring of tracery, or between two shapes
/// of a fill, it would leave a sliver on the far side). A region in one
/// piece is one diagram over `domain`.
///
/// # Errors
/// As [`Diagram::new`].
fn cells_by_part(
    sites: &[Point],
    region: &Region,
    domain: &Domain,
    options: &CellOptions,
) -> Result<Vec<Part>> {
    let parts = region.components();
    if parts.len() <= 1 {
        return Ok(vec![Part {
            diagram: Diagram::new(sites, domain, options)?,
            domain: domain.clone(),
            members: (0..sites.len()).collect(),
        }]);
    }
    let part_of = part_of(sites, &parts);
    let mut out = Vec::new();
    for (k, part) in parts.iter().enumerate() {
        let members: Vec<usize> = (0..sites.len()).filter(|&i| part_of[i] == k).collect();
        if members.is_empty() {
            continue;
        }
        let points: Vec<Point> = members.iter().map(|&i| sites[i]).collect();
        let domain = Domain::new(part, TOLERANCE)?;
        out.push(Part {
            diagram: Diagram::new(&points, &domain, options)?,
            domain,
            members,
        });
    }
    Ok(out)
}

/// One pen-down line through the sites of each connected part of `region`,
/// the pen lifted between parts: a line across blank paper from one shape
/// to another is no part of the pattern.
fn tours(sites: &[Point], edges: &[[usize; 2]], region: &Region) -> BezPath {
    let parts = region.components();
    if parts.len() <= 1 {
        return tour_path(sites, edges);
    }
    let part_of = part_of(sites, &parts);
    let mut path = BezPath::new();
    for part in 0..parts.len() {
        let members: Vec<usize> = (0..sites.len()).filter(|&i| part_of[i] == part).collect();
        let mut local = vec![usize::MAX; sites.len()];
        for (k, &i) in members.iter().enumerate() {
            local[i] = k;
        }
        let points: Vec<Point> = members.iter().map(|&i| sites[i]).collect();
        let inner: Vec<[usize; 2]> = edges
            .iter()
            .filter(|[i, j]| part_of[*i] == part && part_of[*j] == part)
            .map(|&[i, j]| [local[i], local[j]])
            .collect();
        path.extend(tour_path(&points, &inner).elements().iter().copied());
    }
    path
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
