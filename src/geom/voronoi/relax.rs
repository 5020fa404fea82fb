//! Relaxation: moving sites towards the centroids of their cells until
//! they settle — plain Lloyd (even cells), density-weighted Lloyd (Secord
//! 2002, weighted Voronoi stippling) and weighted Linde-Buzo-Gray (Deussen
//! et al. 2017), which also splits and removes sites until each cell holds
//! one site's worth of density, so the count follows the density.
//!
//! [`lloyd_step`] and [`weighted_lloyd_step`] are one step; [`relax`] runs
//! a [`Relaxation`] — a method, a most number of steps and a movement
//! under which the sites count as settled — and reports every step
//! ([`StepReport`]) and whether it converged.

use kurbo::{Point, Vec2};

use super::density_grid::DensityGrid;
use super::{shoelace, Cell, CellOptions, Diagram, Domain};
use crate::error::{Error, Result};
use crate::geom::polylabel::pole_of_inaccessibility;

/// The outcome of one Lloyd step.
#[derive(Debug, Clone, PartialEq)]
pub struct LloydStep {
    /// The moved sites, in input order.
    pub sites: Vec<Point>,
    /// The centroidal energy of the *input* sites, `Σᵢ ∫_{cellᵢ} ρ(x)·|x −
    /// siteᵢ|² dx` (mm⁴ times density; ρ = 1 for [`lloyd_step`]). It never
    /// increases from one step to the next, and falls as the sites
    /// converge: the figure to report.
    pub energy: f64,
    /// Mean distance (mm) the sites moved, over all input sites.
    pub mean_movement: f64,
    /// Largest distance (mm) a site moved.
    pub max_movement: f64,
}

/// One step of Lloyd relaxation: each site moves to the area centroid of
/// its cell clipped to the region (for a cell of several pieces, the
/// area-weighted centroid of all of them).
///
/// Where that centroid falls outside the region (a cell cut by a bay or a
/// hole), the site goes to whichever of the largest piece's centroid, that
/// piece's pole of inaccessibility and the site's old place lies inside and
/// nearest to the centroid, which keeps the energy from rising. Sites with
/// an empty cell (merged, dropped, or outside sites whose cell misses the
/// region) stay where they are.
///
/// # Errors
/// As [`Diagram::new`].
pub fn lloyd_step(sites: &[Point], domain: &Domain, options: &CellOptions) -> Result<LloydStep> {
    lloyd(sites, domain, options, None)
}

/// One step of density-weighted Lloyd relaxation (weighted Voronoi
/// stippling, Secord 2002): each site moves to the centroid of its cell
/// weighted by `density`, `∫ρx / ∫ρ`.
///
/// The integrals are taken over a fan of triangles per contour, each cut
/// into `n²` triangles (`n` = [`CellOptions::density_subdivisions`]) with
/// `density` sampled at three interior points of each (a rule exact for
/// quadratic functions): linear in the number of cells. Negative or
/// non-finite density values count as 0. A site whose cell has no mass
/// stays where it is: nothing pulls it anywhere, and moving it to its
/// cell's area centroid would walk it out into the blank parts (a white
/// margin of an image) step by step. A centroid outside the region is
/// handled as in [`lloyd_step`].
///
/// # Errors
/// As [`Diagram::new`].
pub fn weighted_lloyd_step(
    sites: &[Point],
    domain: &Domain,
    options: &CellOptions,
    density: &dyn Fn(Point) -> f64,
) -> Result<LloydStep> {
    lloyd(sites, domain, options, Some(density))
}

/// How cells are weighed.
enum Weights<'a> {
    /// By area.
    Even,
    /// By a density sampled at points of each cell.
    Sampled(&'a dyn Fn(Point) -> f64, u32),
    /// By a density on a grid, integrated exactly.
    Grid(DensityGrid),
}

impl<'a> Weights<'a> {
    /// The weights `density` gives (see [`CellOptions::density_detail`]).
    fn new(
        density: Option<&'a dyn Fn(Point) -> f64>,
        domain: &Domain,
        options: &CellOptions,
    ) -> Weights<'a> {
        match density {
            None => Weights::Even,
            Some(rho) if options.density_detail > 0.0 => Weights::Grid(DensityGrid::new(
                domain.bounds(),
                options.density_detail,
                rho,
            )),
            Some(rho) => Weights::Sampled(rho, options.density_subdivisions),
        }
    }

    fn moments(&self, contours: &[Vec<Point>], origin: Vec2) -> Moments {
        match self {
            Weights::Even => Moments::of(contours, origin),
            Weights::Sampled(rho, n) => Moments::weighted(contours, origin, *rho, *n),
            Weights::Grid(grid) => grid.moments(contours, origin),
        }
    }
}

/// One Lloyd step, plain (`density` = `None`) or weighted.
fn lloyd(
    sites: &[Point],
    domain: &Domain,
    options: &CellOptions,
    density: Option<&dyn Fn(Point) -> f64>,
) -> Result<LloydStep> {
    lloyd_weighed(
        sites,
        domain,
        options,
        &Weights::new(density, domain, options),
    )
}

fn lloyd_weighed(
    sites: &[Point],
    domain: &Domain,
    options: &CellOptions,
    weights: &Weights<'_>,
) -> Result<LloydStep> {
    let diagram = Diagram::new(sites, domain, options)?;
    let mut moved = sites.to_vec();
    let (mut energy, mut total, mut max) = (0.0, 0.0, 0.0f64);
    for (i, cell) in diagram.cells.iter().enumerate() {
        // A cell's density integral samples the density (a formula) many
        // times; a step on 50,000 cells is too long to wait out.
        crate::cancel::checkpoint()?;
        if cell.is_empty() {
            continue;
        }
        let site = sites[i];
        let origin = site.to_vec2();
        let moments = weights.moments(&cell.contours, origin);
        energy += moments.second();
        let Some(c) = moments.centroid(origin) else {
            continue;
        };
        let next = settle(c, site, cell, domain);
        let d = next.distance(site);
        moved[i] = next;
        total += d;
        max = max.max(d);
    }
    Ok(LloydStep {
        sites: moved,
        energy,
        mean_movement: total / sites.len() as f64,
        max_movement: max,
    })
}

// ---------------------------------------------------------------------------
// Relaxing to convergence.

/// How sites relax.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Lloyd: every site moves to its cell's centroid (weighted by the
    /// density when there is one); the count stays.
    Lloyd,
    /// Weighted Linde-Buzo-Gray (Deussen et al. 2017): as Lloyd, but a
    /// site whose cell holds too little density is removed and one whose
    /// cell holds too much is split in two, so the count comes from the
    /// density and [`Lbg::mass`], not from the start.
    Lbg(Lbg),
}

/// The settings of weighted Linde-Buzo-Gray relaxation.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Lbg {
    /// The density one site stands for, `∫ρ` over its cell (mm² at ρ = 1).
    pub mass: f64,
    /// The band around `mass` a cell may hold and keep its site as it is,
    /// as a fraction of `mass`: below `(1 − h/2)·mass` the site goes,
    /// above `(1 + h/2)·mass` it splits (the paper's hysteresis, 0.6).
    pub hysteresis: f64,
    /// How much the band widens each step, so splitting and removing die
    /// out (the paper's 0.01).
    pub hysteresis_step: f64,
}

impl Lbg {
    /// One site per `mass` of density, with the paper's hysteresis (0.6,
    /// widening by 0.01 a step).
    pub const fn new(mass: f64) -> Lbg {
        Lbg {
            mass,
            hysteresis: 0.6,
            hysteresis_step: 0.01,
        }
    }

    /// The density a site holds when sites `spacing` apart pack in
    /// hexagons where the density is 1: `(√3/2)·spacing²`.
    pub fn mass_for_spacing(spacing: f64) -> f64 {
        3f64.sqrt() / 2.0 * spacing * spacing
    }
}

/// What relaxation to run and when to stop.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Relaxation {
    /// The method.
    pub method: Method,
    /// The most steps.
    pub steps: u32,
    /// Sites count as settled once a step moves them less than this on
    /// average (mm); 0: run every step (Lloyd) or until no site splits or
    /// goes (LBG).
    pub settled: f64,
    /// The most work: the sites of each step summed over the steps run
    /// (a step's cost grows with its sites). A step that would pass it is
    /// not run.
    pub max_site_steps: usize,
}

impl Relaxation {
    /// Up to `steps` Lloyd steps.
    pub const fn lloyd(steps: u32) -> Relaxation {
        Relaxation {
            method: Method::Lloyd,
            steps,
            settled: 0.0,
            max_site_steps: usize::MAX,
        }
    }

    /// Up to `steps` weighted Linde-Buzo-Gray steps.
    pub const fn lbg(steps: u32, lbg: Lbg) -> Relaxation {
        Relaxation {
            method: Method::Lbg(lbg),
            steps,
            settled: 0.0,
            max_site_steps: usize::MAX,
        }
    }

    /// This relaxation, stopping once the mean movement of a step is below
    /// `mm`.
    pub const fn with_settled(mut self, mm: f64) -> Relaxation {
        self.settled = mm;
        self
    }

    /// This relaxation, running no step that would bring the sites summed
    /// over the steps past `n` (see [`Relaxation::max_site_steps`]).
    pub const fn with_max_site_steps(mut self, n: usize) -> Relaxation {
        self.max_site_steps = n;
        self
    }
}

/// What one step of [`relax`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct StepReport {
    /// Sites after the step.
    pub sites: usize,
    /// The centroidal energy of the sites before the step (see
    /// [`LloydStep::energy`]).
    pub energy: f64,
    /// Mean distance the kept sites moved (mm); a split site counts the
    /// middle of its two.
    pub mean_movement: f64,
    /// Largest distance a site moved (mm).
    pub max_movement: f64,
    /// Sites split in two (LBG).
    pub split: usize,
    /// Sites removed (LBG).
    pub removed: usize,
}

/// The outcome of [`relax`].
#[derive(Debug, Clone, PartialEq)]
pub struct Relaxed {
    /// The sites.
    pub sites: Vec<Point>,
    /// One report per step run.
    pub steps: Vec<StepReport>,
    /// Whether the sites settled (see [`Relaxation::settled`]) within the
    /// steps allowed.
    pub converged: bool,
}

/// Relaxes `sites` as `how` says, weighting cells by `density` (`None`:
/// 1 everywhere), calling `on_step` after each step.
///
/// # Errors
/// As [`Diagram::new`] (for LBG, [`Error::Budget`] when splitting passes
/// [`CellOptions::max_sites`]); with LBG, [`Error::Invalid`] (field
/// `mass`) when every site was removed: the region holds less than one
/// site's worth of density; [`Error::Invalid`] (field `relax`) before a
/// step that would pass [`Relaxation::max_site_steps`] (LBG's sites grow
/// as they split).
pub fn relax(
    sites: Vec<Point>,
    domain: &Domain,
    options: &CellOptions,
    density: Option<&dyn Fn(Point) -> f64>,
    how: &Relaxation,
    on_step: &mut dyn FnMut(&StepReport),
) -> Result<Relaxed> {
    let one = |_: Point| 1.0;
    let weights = match how.method {
        // LBG weighs by density even without one: 1 everywhere.
        Method::Lbg(_) => Weights::new(Some(density.unwrap_or(&one)), domain, options),
        Method::Lloyd => Weights::new(density, domain, options),
    };
    let mut sites = sites;
    let mut steps = Vec::new();
    let mut converged = false;
    let mut work = 0usize;
    for k in 0..how.steps {
        crate::cancel::checkpoint()?;
        work = work.saturating_add(sites.len());
        if work > how.max_site_steps {
            return Err(Error::invalid(
                "relax",
                format!(
                    "step {} of {} sites would bring the relaxation to {work} site-steps \
                     (sites × steps), more than the {} allowed",
                    k + 1,
                    sites.len(),
                    how.max_site_steps
                ),
            ));
        }
        let report = match how.method {
            Method::Lloyd => {
                let step = lloyd_weighed(&sites, domain, options, &weights)?;
                let report = StepReport {
                    sites: sites.len(),
                    energy: step.energy,
                    mean_movement: step.mean_movement,
                    max_movement: step.max_movement,
                    split: 0,
                    removed: 0,
                };
                sites = step.sites;
                report
            }
            Method::Lbg(lbg) => {
                let h = lbg.hysteresis + lbg.hysteresis_step * k as f64;
                let (next, report) = lbg_step(&sites, domain, options, &weights, lbg.mass, h)?;
                if next.is_empty() {
                    return Err(Error::invalid(
                        "mass",
                        format!(
                            "removed every site: the region holds less than one \
                             site's worth of density ({} mm² at density 1)",
                            lbg.mass
                        ),
                    ));
                }
                if next.len() > options.max_sites {
                    return Err(Error::Budget {
                        what: "sites".into(),
                        limit: options.max_sites,
                    });
                }
                sites = next;
                report
            }
        };
        on_step(&report);
        steps.push(report);
        // LBG has settled once no site splits or goes (and, if asked, the
        // sites hardly move); Lloyd once they hardly move.
        let still = report.split == 0 && report.removed == 0;
        let slow = report.mean_movement < how.settled
            || report.mean_movement == 0.0
            || (how.settled == 0.0 && matches!(how.method, Method::Lbg(_)));
        if still && slow {
            converged = true;
            break;
        }
    }
    Ok(Relaxed {
        sites,
        steps,
        converged,
    })
}

/// What a Linde-Buzo-Gray step does with one site.
#[derive(Debug, Clone, Copy)]
enum Fate {
    Stay(Point),
    Split(Point, Point),
    Go,
}

/// One weighted Linde-Buzo-Gray step with band `h`: each cell's density
/// mass decides whether its site goes (too little), splits along the
/// cell's main axis (too much) or moves to the weighted centroid.
///
/// Of two neighbouring sites (Delaunay) whose cells are both too light
/// only one goes in a step: otherwise a start much denser than the
/// density asks for would lose every site at once (the paper starts from
/// one site and never meets this). Cells with no density at all go
/// regardless.
fn lbg_step(
    sites: &[Point],
    domain: &Domain,
    options: &CellOptions,
    weights: &Weights<'_>,
    mass: f64,
    h: f64,
) -> Result<(Vec<Point>, StepReport)> {
    let diagram = Diagram::new(sites, domain, options)?;
    let (low, high) = ((1.0 - h / 2.0) * mass, (1.0 + h / 2.0) * mass);
    let mut report = StepReport {
        sites: 0,
        energy: 0.0,
        mean_movement: 0.0,
        max_movement: 0.0,
        split: 0,
        removed: 0,
    };
    let mut fates = Vec::with_capacity(sites.len());
    // Light cells that still hold some density, with where their site
    // would move if it stayed.
    let mut light = Vec::new();
    for (i, cell) in diagram.cells.iter().enumerate() {
        crate::cancel::checkpoint()?;
        let site = sites[i];
        let origin = site.to_vec2();
        let m = if cell.is_empty() {
            Moments::default()
        } else {
            weights.moments(&cell.contours, origin)
        };
        report.energy += m.second();
        let Some(c) = m.centroid(origin) else {
            fates.push(Fate::Go);
            continue;
        };
        let fate = if m.mass < low {
            light.push((i, settle(c, site, cell, domain)));
            Fate::Go
        } else if m.mass > high {
            // The new sites go to the weighted centroids of the cell's two
            // halves across its main axis: where the density of each half
            // lies. (A fixed offset along the axis can land in a blank
            // part of a cell that reaches out over white, and that site is
            // removed again next step.)
            let (axis, _) = m.main_axis();
            let [a, b] = [1.0, -1.0].map(|side| {
                let part = half(&cell.contours, c, axis * side);
                weights.moments(&part, origin).centroid(origin).unwrap_or(c)
            });
            Fate::Split(settle(a, site, cell, domain), settle(b, site, cell, domain))
        } else {
            Fate::Stay(settle(c, site, cell, domain))
        };
        fates.push(fate);
    }
    if light.len() > 1 {
        let mut neighbours = vec![Vec::new(); sites.len()];
        for [i, j] in super::delaunay_edges(sites, domain, options)? {
            neighbours[i].push(j);
            neighbours[j].push(i);
        }
        let mut gone = vec![false; sites.len()];
        for (i, stay) in light {
            if neighbours[i].iter().any(|&j| gone[j]) {
                fates[i] = Fate::Stay(stay);
            } else {
                gone[i] = true;
            }
        }
    }
    let mut next = Vec::with_capacity(sites.len());
    let mut total = 0.0;
    for (i, fate) in fates.into_iter().enumerate() {
        let moved = match fate {
            Fate::Go => {
                report.removed += 1;
                continue;
            }
            Fate::Stay(p) => {
                next.push(p);
                p.distance(sites[i])
            }
            Fate::Split(a, b) => {
                next.extend([a, b]);
                report.split += 1;
                a.midpoint(b).distance(sites[i])
            }
        };
        total += moved;
        report.max_movement = report.max_movement.max(moved);
    }
    let kept = sites.len() - report.removed;
    report.mean_movement = if kept > 0 { total / kept as f64 } else { 0.0 };
    report.sites = next.len();
    Ok((next, report))
}

/// The part of `contours` on the side of the line through `c` that
/// `towards` points to (Sutherland-Hodgman on each contour: a concave
/// contour may come out with zero-width bridges, which add nothing to its
/// moments).
fn half(contours: &[Vec<Point>], c: Point, towards: Vec2) -> Vec<Vec<Point>> {
    let side = |p: Point| (p - c).dot(towards);
    contours
        .iter()
        .filter_map(|contour| {
            let mut out = Vec::with_capacity(contour.len() + 2);
            for (k, &p) in contour.iter().enumerate() {
                let q = contour[(k + 1) % contour.len()];
                let (sp, sq) = (side(p), side(q));
                if sp >= 0.0 {
                    out.push(p);
                }
                if (sp >= 0.0) != (sq >= 0.0) {
                    out.push(p.lerp(q, sp / (sp - sq)));
                }
            }
            (out.len() >= 3).then_some(out)
        })
        .collect()
}

/// Where a site whose cell has centroid `c` goes: `c` if inside the region,
/// else the candidate inside nearest to `c`. For a fixed cell the energy of
/// a site at `p` is the energy at the centroid plus mass × |p − c|², so the
/// nearest candidate is the best, and the old site is always a candidate.
fn settle(c: Point, site: Point, cell: &Cell, domain: &Domain) -> Point {
    if domain.contains(c) {
        return c;
    }
    let mut candidates = vec![site];
    if let Some(largest) = cell.pieces().max_by(|a, b| {
        let area = |p: &[Vec<Point>]| p.iter().map(|c| shoelace(c)).sum::<f64>();
        area(a).total_cmp(&area(b))
    }) {
        let origin = largest[0][0].to_vec2();
        if let Some(pc) = Moments::of(largest, origin).centroid(origin) {
            candidates.push(pc);
        }
        let piece = Cell {
            contours: largest.to_vec(),
        };
        if let Some((pole, _)) = pole_of_inaccessibility(&piece.to_region(), domain.tolerance) {
            candidates.push(pole);
        }
    }
    candidates
        .into_iter()
        .filter(|&p| domain.contains(p))
        .min_by(|a, b| a.distance_squared(c).total_cmp(&b.distance_squared(c)))
        .unwrap_or(site)
}

/// Mass, first and second moments of a set of contours about `origin`.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Moments {
    /// ∫ρ
    pub(super) mass: f64,
    /// ∫ρ(x − origin)
    pub(super) first: Vec2,
    /// ∫ρ·dx², ∫ρ·dx·dy, ∫ρ·dy² with d = x − origin.
    pub(super) xx: f64,
    pub(super) xy: f64,
    pub(super) yy: f64,
}

impl Moments {
    /// Exact moments of the polygons (ρ = 1), by Green's theorem.
    pub(super) fn of(contours: &[Vec<Point>], origin: Vec2) -> Moments {
        let mut m = Moments::default();
        for c in contours {
            for (k, p) in c.iter().enumerate() {
                let a = p.to_vec2() - origin;
                let b = c[(k + 1) % c.len()].to_vec2() - origin;
                let w = a.cross(b);
                m.mass += w / 2.0;
                m.first += (a + b) * (w / 6.0);
                m.xx += w * (a.x * a.x + a.x * b.x + b.x * b.x) / 12.0;
                m.yy += w * (a.y * a.y + a.y * b.y + b.y * b.y) / 12.0;
                m.xy += w * (2.0 * a.x * a.y + a.x * b.y + b.x * a.y + 2.0 * b.x * b.y) / 24.0;
            }
        }
        m
    }

    /// Moments weighted by `rho`: a fan of signed triangles per contour
    /// (right for any simple contour and for holes: the signed parts cancel
    /// where they overlap), each cut into n² triangles sampled at three
    /// points.
    pub(super) fn weighted(
        contours: &[Vec<Point>],
        origin: Vec2,
        rho: &dyn Fn(Point) -> f64,
        n: u32,
    ) -> Moments {
        let mut m = Moments::default();
        let n = n.max(1);
        let step = 1.0 / n as f64;
        for c in contours {
            let apex = c[0].to_vec2() - origin;
            for k in 1..c.len().saturating_sub(1) {
                let (u, v) = (c[k] - c[0], c[k + 1] - c[0]);
                let area = u.cross(v) / 2.0 * step * step;
                // The barycentric grid in steps of 1/n: "up" triangles with
                // corners (i, j), (i+1, j), (i, j+1), and "down" ones with
                // (i+1, j), (i+1, j+1), (i, j+1).
                let at = |i: u32, j: u32| apex + u * (i as f64 * step) + v * (j as f64 * step);
                for i in 0..n {
                    for j in 0..n - i {
                        let up = [at(i, j), at(i + 1, j), at(i, j + 1)];
                        m.add_triangle(up, area, origin, rho);
                        if i + j + 1 < n {
                            let down = [at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                            m.add_triangle(down, area, origin, rho);
                        }
                    }
                }
            }
        }
        m
    }

    /// Adds the triangle `t` (about `origin`, signed `area`), `rho`
    /// sampled at three points.
    fn add_triangle(&mut self, t: [Vec2; 3], area: f64, origin: Vec2, rho: &dyn Fn(Point) -> f64) {
        for d in quadrature_points(t) {
            let r = rho((origin + d).to_point());
            let r = if r.is_finite() && r > 0.0 { r } else { 0.0 };
            let w = r * area / 3.0;
            self.mass += w;
            self.first += d * w;
            self.xx += w * d.x * d.x;
            self.xy += w * d.x * d.y;
            self.yy += w * d.y * d.y;
        }
    }

    /// ∫ρ|x − origin|²: the energy of a site at `origin`.
    fn second(&self) -> f64 {
        self.xx + self.yy
    }

    /// The direction in which the mass spreads most (a unit vector) and
    /// its standard deviation that way (mm), about the centroid.
    pub(super) fn main_axis(&self) -> (Vec2, f64) {
        let f = self.first / self.mass;
        let (cxx, cxy, cyy) = (
            self.xx / self.mass - f.x * f.x,
            self.xy / self.mass - f.x * f.y,
            self.yy / self.mass - f.y * f.y,
        );
        let largest = (cxx + cyy) / 2.0 + ((cxx - cyy) / 2.0).hypot(cxy);
        let axis = if cxy.abs() > 1e-12 * (cxx + cyy).abs() {
            Vec2::new(largest - cyy, cxy).normalize()
        } else if cxx >= cyy {
            Vec2::new(1.0, 0.0)
        } else {
            Vec2::new(0.0, 1.0)
        };
        (axis, largest.max(0.0).sqrt())
    }

    pub(super) fn centroid(&self, origin: Vec2) -> Option<Point> {
        let c = origin + self.first / self.mass;
        (self.mass > 0.0 && c.is_finite()).then_some(c.to_point())
    }
}

/// The three points of the degree-2 rule on a triangle (barycentric
/// (2/3, 1/6, 1/6) and its permutations, equal weights).
fn quadrature_points([a, b, c]: [Vec2; 3]) -> [Vec2; 3] {
    let p = |x: Vec2, y: Vec2, z: Vec2| x * (2.0 / 3.0) + (y + z) * (1.0 / 6.0);
    [p(a, b, c), p(b, c, a), p(c, a, b)]
}
