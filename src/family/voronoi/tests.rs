//! The Voronoi family through the seam: what each kind draws, shared
//! sites across layers, what relaxation does, determinism and errors.

use kurbo::{BezPath, Point, Shape};

use crate::error::Error;
use crate::geom::path_length;
use crate::geom::region::Region;
use crate::motif::test_scene;
use crate::project::build_scene;
use crate::scene::Scene;
use crate::spec::{Format, SceneSpec};

/// A5 with 10 mm margins: the drawable area is 128 × 190 mm.
const W: f64 = 128.0;
const H: f64 = 190.0;

fn text(table: &str) -> String {
    test_scene::text("voronoi", table)
}

fn scene(table: &str) -> Scene {
    test_scene::scene("voronoi", table)
}

fn error(table: &str) -> String {
    test_scene::error("voronoi", table)
}

/// The paths of one kind (`cells`, `inset`, …), in layer coordinates.
fn paths_of(scene: &Scene, kind: &str) -> Vec<BezPath> {
    let mut out = Vec::new();
    for layer in &scene.layers {
        layer
            .content
            .visit_paths(kurbo::Affine::IDENTITY, &mut |p, t| {
                if p.id.split('.').nth(2) == Some(kind) {
                    out.push(t * p.path.clone());
                }
            });
    }
    out
}

fn total_length(paths: &[BezPath]) -> f64 {
    paths.iter().map(path_length).sum()
}

/// Points of a path (move-tos and line-tos).
fn vertices(path: &BezPath) -> Vec<Point> {
    path.elements()
        .iter()
        .filter_map(|el| match *el {
            kurbo::PathEl::MoveTo(p) | kurbo::PathEl::LineTo(p) => Some(p),
            _ => None,
        })
        .collect()
}

#[test]
fn the_cell_network_draws_each_edge_once() {
    let s = scene("draw = [\"cells\", \"inset\"]\ninset = 0.01\nsites = { spacing = 15 }\n");
    let network = total_length(&paths_of(&s, "cells"));
    // Inset by 0.01 mm, the cells' outlines are their perimeters (less
    // 8 × 0.01 mm a corner at most). Interior edges belong to two cells,
    // the page's outline to one: the network is half of all perimeters
    // plus half the outline.
    let cells = paths_of(&s, "inset");
    let perimeters = total_length(&cells);
    let outline = 2.0 * (W + H);
    let expected = (perimeters + outline) / 2.0;
    assert!(
        (network - expected).abs() < 0.01 * expected,
        "network {network:.1} mm, expected {expected:.1} mm"
    );
    // And nothing outside the page.
    for p in paths_of(&s, "cells") {
        let b = p.bounding_box();
        assert!(b.x0 > -1e-6 && b.y0 > -1e-6 && b.x1 < W + 1e-6 && b.y1 < H + 1e-6);
    }
}

#[test]
fn holes_stay_empty_and_cells_stay_in_the_region() {
    let s = scene(
        "draw = [\"cells\", \"sites\"]\nsites = { spacing = 8 }\n\
         [layers.voronoi.region]\ncircle = { centre = [64, 95], radius = 60 }\n\
         holes = [{ polygon = [[50, 80], [80, 80], [80, 110], [50, 110]] }]\n",
    );
    let centre = Point::new(64.0, 95.0);
    let hole = Region::from_rect(kurbo::Rect::new(50.0, 80.0, 80.0, 110.0)).unwrap();
    let inner = Region::from_rect(kurbo::Rect::new(50.1, 80.1, 79.9, 109.9)).unwrap();
    for p in paths_of(&s, "cells") {
        for v in vertices(&p) {
            assert!(v.distance(centre) < 60.0 + 0.02, "{v:?} outside the circle");
            assert!(!inner.contains(v), "{v:?} inside the hole");
        }
    }
    let sites = paths_of(&s, "sites");
    assert!(sites.len() > 100);
    for dot in sites {
        let c = dot.bounding_box().center();
        assert!(!hole.contains(c) && c.distance(centre) < 60.0, "site {c:?}");
    }
}

#[test]
fn inset_cells_are_smaller_and_round_corners() {
    let sharp = paths_of(&scene("draw = [\"inset\"]\ninset = 1\n"), "inset");
    let round = paths_of(
        &scene("draw = [\"inset\"]\ninset = 1\nround = 2\n"),
        "inset",
    );
    // Opening by the corner radius also takes away cells narrower than
    // twice inset + round.
    assert!(round.len() <= sharp.len() && round.len() > sharp.len() * 9 / 10);
    let area = |ps: &[BezPath]| ps.iter().map(|p| p.area().abs()).sum::<f64>();
    // Rounding takes the corners off: less area, more vertices.
    assert!(area(&round) < area(&sharp));
    let count = |ps: &[BezPath]| ps.iter().map(|p| vertices(p).len()).sum::<usize>();
    assert!(count(&round) > 2 * count(&sharp));
    // Inset by 1 mm, the cells leave 2 mm between neighbours: together
    // they cover clearly less than the page.
    assert!(area(&sharp) < 0.9 * W * H);
}

#[test]
fn relaxation_evens_out_the_cells() {
    // Cells of uniform random sites vary a lot in size; Lloyd's centroids
    // even them out (the coefficient of variation of the cell areas falls).
    let spread = |relax: u32| {
        let table = format!(
            "draw = [\"inset\"]\ninset = 0.01\nrelax = {relax}\n\
             sites = {{ distribution = \"uniform\", count = 150 }}\n"
        );
        let areas: Vec<f64> = paths_of(&scene(&table), "inset")
            .iter()
            .map(|p| p.area().abs())
            .collect();
        let mean = areas.iter().sum::<f64>() / areas.len() as f64;
        let var = areas.iter().map(|a| (a - mean).powi(2)).sum::<f64>() / areas.len() as f64;
        var.sqrt() / mean
    };
    let (raw, relaxed) = (spread(0), spread(10));
    assert!(relaxed < 0.5 * raw, "spread {raw:.2} → {relaxed:.2}");
}

#[test]
fn the_tour_is_one_line_through_every_site() {
    let s = scene("draw = [\"tour\", \"sites\"]\nsites = { spacing = 9 }\n");
    let tour = paths_of(&s, "tour");
    assert_eq!(tour.len(), 1);
    let visited = vertices(&tour[0]);
    let sites: Vec<Point> = paths_of(&s, "sites")
        .iter()
        .map(|d| d.bounding_box().center())
        .collect();
    assert_eq!(visited.len(), sites.len());
    for site in &sites {
        let hits = visited.iter().filter(|v| v.distance(*site) < 1e-6).count();
        assert_eq!(hits, 1, "site {site:?} visited {hits} times");
    }
    // A good tour steps about one spacing from site to site.
    let step = path_length(&tour[0]) / (visited.len() - 1) as f64;
    assert!(step < 12.0, "mean step {step:.1} mm");
}

#[test]
fn delaunay_edges_triangulate_the_region_without_crossing_its_outline() {
    let s = scene(
        "draw = [\"delaunay\", \"sites\"]\nsites = { spacing = 7 }\n\
         [layers.voronoi.region]\npolygon = [[5, 5], [120, 5], [120, 90], [60, 90], [60, 40], [5, 40]]\n",
    );
    let corners = [
        (5.0, 5.0),
        (120.0, 5.0),
        (120.0, 90.0),
        (60.0, 90.0),
        (60.0, 40.0),
        (5.0, 40.0),
    ]
    .map(Point::from);
    let l = Region::polygon(&corners).unwrap();
    // Grown by a hair: edges along the outline count as inside.
    let grown = crate::geom::offset::offset(&l, 1e-6, 1e-7).unwrap();
    let strokes = paths_of(&s, "delaunay");
    let mut edges = 0;
    let mut corner_hits = 0;
    for stroke in &strokes {
        let vs = vertices(stroke);
        // The mesh's outline lies a hair inside the region's.
        corner_hits += vs
            .iter()
            .filter(|v| corners.iter().any(|c| c.distance(**v) < 0.1))
            .count();
        for w in vs.windows(2) {
            edges += 1;
            // No edge crosses the bay of the L.
            assert!(grown.contains(w[0].midpoint(w[1])), "{:?}–{:?}", w[0], w[1]);
        }
    }
    // The outline's corners are triangle corners: the mesh reaches the
    // border.
    assert!(corner_hits >= corners.len(), "{corner_hits} corner visits");
    // The outline is drawn: the whole perimeter (430 mm) is in the mesh.
    let total: f64 = strokes.iter().map(path_length).sum();
    assert!(total > 430.0);
    // A triangulation of v points with h on its hull has 3v − 3 − h edges;
    // refinement adds points along the outline and where a triangle would
    // be a sliver, not many.
    let n = paths_of(&s, "sites").len();
    assert!(
        edges > 2 * n && edges < 4 * (n + 40),
        "{edges} edges for {n} sites"
    );
    // Chained: far fewer strokes than edges.
    assert!(strokes.len() * 3 < edges);
}

#[test]
fn tables_with_one_id_share_their_sites_across_layers() {
    let text = "version = 1\nseed = 9\npage = { size = \"A5\", margin = 10 }\n\
        [[layers]]\nname = \"a\"\n[[layers.voronoi]]\nid = \"w\"\ndraw = [\"sites\"]\n\
        [[layers]]\nname = \"b\"\n[[layers.voronoi]]\nid = \"w\"\ndraw = [\"sites\"]\n\
        [[layers]]\nname = \"c\"\n[[layers.voronoi]]\nid = \"v\"\ndraw = [\"sites\"]\n";
    let s = build_scene(&SceneSpec::parse(text, Format::Toml).unwrap()).unwrap();
    let dots = |layer: usize| {
        let mut out = Vec::new();
        s.layers[layer]
            .content
            .visit_paths(kurbo::Affine::IDENTITY, &mut |p, _| {
                out.push(p.path.clone())
            });
        out
    };
    assert_eq!(dots(0), dots(1));
    assert_ne!(dots(0), dots(2));
}

#[test]
fn the_seed_decides_everything() {
    let table = "draw = [\"cells\", \"tour\"]\nrelax = 2\n";
    assert_eq!(scene(table), scene(table));
    let other = text(table).replace("seed = 5", "seed = 6");
    let other = build_scene(&SceneSpec::parse(&other, Format::Toml).unwrap()).unwrap();
    assert_ne!(paths_of(&scene(table), "tour"), paths_of(&other, "tour"));
}

#[test]
fn bad_tables_are_refused_with_their_field() {
    let cases = [
        (
            "sites = { distribution = \"uniform\" }\n",
            "layers[0].voronoi[0].sites.count: the uniform distribution needs a count",
        ),
        (
            "sites = { distribution = \"poisson\", count = 5 }\n",
            "layers[0].voronoi[0].sites.count: does not apply to the poisson distribution",
        ),
        ("draw = []\n", "layers[0].voronoi[0].draw: draws nothing"),
        (
            "draw = [\"cells\", \"cells\"]\n",
            "layers[0].voronoi[0].draw[1]: is listed twice",
        ),
        ("relax = 5000\n", "layers[0].voronoi[0].relax: must be between 0 and 1000"),
        (
            "relaxation = \"lbg\"\n",
            "layers[0].voronoi[0].relax: lbg relaxation needs steps",
        ),
        (
            "converge = 0.01\n",
            "layers[0].voronoi[0].converge: does nothing without relax steps",
        ),
        (
            "relax = 5\nconverge = -1\n",
            "layers[0].voronoi[0].converge: must be between",
        ),
        (
            "sites = { spacing = 5, density = \"1 - \" }\n",
            "layers[0].voronoi[0].sites.density: is not a formula of x, y, u, v",
        ),
        (
            "sites = { spacing = 5, density = \"1 - w\" }\n",
            "layers[0].voronoi[0].sites.density: uses the unknown name `w`",
        ),
        (
            "sites = { distribution = \"uniform\", count = 5, spacing = 2 }\n",
            "layers[0].voronoi[0].sites.spacing: does not apply to the uniform distribution \
             with lloyd relaxation",
        ),
        (
            "[layers.voronoi.region]\npolygon = [[0, 0], [10, 0], [20, 0]]\n",
            "layers[0].voronoi[0].region.polygon",
        ),
        (
            "[layers.voronoi.region]\ncircle = { centre = [50, 50], radius = 10 }\n\
             holes = [{ circle = { centre = [50, 50], radius = 20 } }]\n",
            "layers[0].voronoi[0].region.holes: leave nothing of the region",
        ),
        (
            "[layers.voronoi.region]\ncircle = { centre = [50, 50], radius = 10 }\npolygon = [[0, 0], [1, 0], [0, 1]]\n",
            "layers[0].voronoi[0].region: give at most one of circle, polygon, svg",
        ),
        (
            "[layers.voronoi.region]\ncircle = { centre = [nan, 50], radius = 10 }\n",
            "layers[0].voronoi[0].region.circle.centre",
        ),
    ];
    for (table, expected) in cases {
        let e = error(table);
        assert!(e.contains(expected), "{table}\n→ {e}\nwanted {expected}");
    }
}

#[test]
fn too_many_sites_fail_fast_on_the_budget() {
    // 0.1 mm spacing over 128 × 190 mm would be millions of sites.
    let e = error("sites = { spacing = 0.1 }\n");
    assert!(
        e.contains("layers[0].voronoi[0].sites.spacing: would place more than 1000000 sites"),
        "{e}"
    );
    // And the path budget counts every drawn path.
    let text = text("draw = [\"sites\"]\n")
        .replace("[[layers]]", "limits = { max_paths = 50 }\n[[layers]]");
    let spec = SceneSpec::parse(&text, Format::Toml).unwrap();
    assert!(matches!(build_scene(&spec), Err(Error::Budget { .. })));
}

#[test]
fn an_svg_outline_is_a_region_with_its_inner_shapes_as_holes() {
    use crate::motif::Library;
    use crate::project::build_scene_with_progress;
    // A frame: a 100 mm square with a 40 mm square inside (even-odd: a hole).
    let mut frame = BezPath::new();
    for (x0, x1) in [(10.0, 110.0), (40.0, 80.0)] {
        frame.move_to((x0, x0));
        frame.line_to((x1, x0));
        frame.line_to((x1, x1));
        frame.line_to((x0, x1));
        frame.close_path();
    }
    let mut library = Library::new();
    library.add_paths("frame.svg", frame);
    let text =
        text("draw = [\"sites\"]\nsites = { spacing = 5 }\nregion = { svg = \"frame.svg\" }\n");
    let spec = SceneSpec::parse(&text, Format::Toml).unwrap();
    let s = build_scene_with_progress(&spec, &library, &mut |_| {}).unwrap();
    let sites: Vec<Point> = paths_of(&s, "sites")
        .iter()
        .map(|d| d.bounding_box().center())
        .collect();
    // About 0.63 sites per spacing² over 100² − 40² mm²: 212.
    assert!(
        sites.len() > 180 && sites.len() < 260,
        "{} sites",
        sites.len()
    );
    for p in sites {
        let inside = |lo: f64, hi: f64| p.x > lo && p.x < hi && p.y > lo && p.y < hi;
        assert!(inside(10.0, 110.0) && !inside(40.0, 80.0), "{p:?}");
    }
}

/// The scene of `table` with a library holding `image` as `ramp.png`.
fn scene_with_image(table: &str, image: crate::geom::density::GreyImage) -> Result<Scene, Error> {
    use crate::motif::Library;
    use crate::project::build_scene_with_progress;
    let mut library = Library::new();
    library.add_image("ramp.png", image);
    let spec = SceneSpec::parse(&text(table), Format::Toml)?;
    build_scene_with_progress(&spec, &library, &mut |_| {})
}

/// Darkness rising from 0 on the left to 1 on the right, 64 × 95 px (the
/// drawable area's aspect, so it fills the page region).
fn ramp() -> crate::geom::density::GreyImage {
    let (w, h) = (64, 95);
    let d = (0..h)
        .flat_map(|_| (0..w).map(move |x| (x as f32 + 0.5) / w as f32))
        .collect();
    crate::geom::density::GreyImage::new(w, h, d).unwrap()
}

/// Sites per vertical band of the page, left to right.
fn bands(s: &Scene, n: usize) -> Vec<usize> {
    let mut counts = vec![0; n];
    for dot in paths_of(s, "sites") {
        let x = dot.bounding_box().center().x;
        counts[((x / W * n as f64) as usize).min(n - 1)] += 1;
    }
    counts
}

/// Pearson correlation of two series.
fn correlation(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let cov: f64 = a.iter().zip(b).map(|(x, y)| (x - ma) * (y - mb)).sum();
    let va: f64 = a.iter().map(|x| (x - ma).powi(2)).sum();
    let vb: f64 = b.iter().map(|y| (y - mb).powi(2)).sum();
    cov / (va * vb).sqrt()
}

#[test]
fn stipples_follow_the_image_darkness() {
    // Weighted Voronoi stippling: sites placed by darkness, then Lloyd
    // steps weighted by it. The count per band follows the darkness.
    let table = "draw = [\"sites\"]\nrelax = 8\n\
                 sites = { distribution = \"uniform\", count = 1500, image = \"ramp.png\" }\n";
    let s = scene_with_image(table, ramp()).unwrap();
    let counts = bands(&s, 8);
    assert_eq!(counts.iter().sum::<usize>(), 1500);
    let darkness: Vec<f64> = (0..8).map(|i| (i as f64 + 0.5) / 8.0).collect();
    let counts_f: Vec<f64> = counts.iter().map(|&c| c as f64).collect();
    let r = correlation(&darkness, &counts_f);
    assert!(r > 0.95, "correlation {r:.3}, counts {counts:?}");
    // The darkest band holds several times the lightest.
    assert!(counts[7] > 4 * counts[0].max(1), "{counts:?}");
    // Poisson-disk sites too: spacing grows where the image is light.
    let s = scene_with_image(
        "draw = [\"sites\"]\nsites = { spacing = 3, image = \"ramp.png\" }\n",
        ramp(),
    )
    .unwrap();
    let counts = bands(&s, 4);
    assert!(counts[3] > 2 * counts[0], "{counts:?}");
}

#[test]
fn a_white_image_cannot_hold_sites() {
    let table = "sites = { distribution = \"uniform\", count = 10, image = \"ramp.png\" }\n";
    let white = crate::geom::density::GreyImage::new(4, 4, vec![0.0; 16]).unwrap();
    let e = scene_with_image(table, white).unwrap_err().to_string();
    assert!(
        e.contains("layers[0].voronoi[0].sites.image: gives no density anywhere"),
        "{e}"
    );
    let mut faint = vec![0.0; 16];
    faint[0] = 1e-4;
    let faint = crate::geom::density::GreyImage::new(4, 4, faint).unwrap();
    let e = scene_with_image(table, faint).unwrap_err().to_string();
    assert!(
        e.contains("layers[0].voronoi[0].sites.image: is too light"),
        "{e}"
    );
    // A formula that is 0 everywhere is refused the same way.
    let e = error("sites = { spacing = 5, density = \"x - 1000\" }\n");
    assert!(
        e.contains("layers[0].voronoi[0].sites.density: gives no density anywhere"),
        "{e}"
    );
}

#[test]
fn images_are_read_by_the_caller_from_png_or_jpeg() {
    // The description names the file; load_motifs reads it relative to the
    // description's folder.
    let fixtures = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures");
    let table = "draw = [\"sites\"]\nsites = { distribution = \"uniform\", count = 50, image = \"ramp.jpg\" }\n";
    let spec = SceneSpec::parse(&text(table), Format::Toml).unwrap();
    let library = crate::project::load_motifs(&spec, &fixtures).unwrap();
    assert_eq!(library.image("ramp.jpg").unwrap().width(), 16);
    // A file that is not an image names itself and keeps the cause.
    let table =
        "sites = { distribution = \"uniform\", count = 5, image = \"motifs/broken.svg\" }\n";
    let spec = SceneSpec::parse(&text(table), Format::Toml).unwrap();
    let e = crate::project::load_motifs(&spec, &fixtures).unwrap_err();
    // Worded as what it is to the table: an image, not a motif.
    assert!(
        e.to_string().starts_with("image motifs/broken.svg: ")
            && e.to_string().contains("not a PNG or JPEG"),
        "{e}"
    );
    assert!(std::error::Error::source(&e).is_some());
}

#[test]
fn a_density_formula_places_sites_as_an_image_does() {
    let s = scene(
        "draw = [\"sites\"]\nsites = { distribution = \"uniform\", count = 600, density = \"u\" }\n",
    );
    let counts = bands(&s, 4);
    // ∫u over the four bands: 1/16, 3/16, 5/16, 7/16 of the sites.
    assert!(counts.windows(2).all(|w| w[1] > w[0]), "{counts:?}");
    assert!(counts[3] > 4 * counts[0], "{counts:?}");
}

/// The notes a render of `table` makes.
fn notes(table: &str) -> Vec<String> {
    let spec = SceneSpec::parse(&text(table), Format::Toml).unwrap();
    crate::project::render(&spec)
        .unwrap()
        .notes
        .into_iter()
        .map(|n| format!("{}: {}", n.motif, n.text))
        .collect()
}

#[test]
fn relaxation_reports_how_it_converged() {
    let n = notes("relax = 500\nconverge = 0.05\nsites = { spacing = 8 }\n");
    assert_eq!(n.len(), 1, "{n:?}");
    assert!(
        n[0].starts_with("l.voronoi-0: Lloyd relaxation: converged in "),
        "{n:?}"
    );
    assert!(n[0].contains("energy −"), "{n:?}");
    let n = notes("relax = 3\nsites = { spacing = 8 }\n");
    assert!(n[0].contains(": 3 steps;"), "{n:?}");
    // No relaxation, no note.
    assert!(notes("sites = { spacing = 8 }\n").is_empty());
}

#[test]
fn lbg_sets_the_count_from_the_density_and_the_spacing() {
    // Density u over 128 × 190 mm: half of 24,320 mm², one site per
    // (√3/2)·8² = 55.4 mm²: about 219 sites, whatever the start.
    let table = |start: &str| {
        format!(
            "relaxation = \"lbg\"\nrelax = 200\ndraw = [\"sites\"]\n\
             sites = {{ {start}, spacing = 8, density = \"u\" }}\n"
        )
    };
    for start in [
        "distribution = \"uniform\", count = 5",
        "distribution = \"uniform\", count = 2000",
        "distribution = \"poisson\"",
    ] {
        let s = scene(&table(start));
        let n = paths_of(&s, "sites").len() as f64;
        assert!(n > 219.0 / 1.5 && n < 219.0 / 0.6, "{start}: {n} sites");
        let counts = bands(&s, 4);
        assert!(counts[3] > 3 * counts[0], "{start}: {counts:?}");
        let note = &notes(&table(start))[0];
        assert!(note.contains("LBG relaxation: settled in"), "{note}");
    }
}

/// The centres of the site dots, in the order drawn.
fn dots(s: &Scene) -> Vec<Point> {
    paths_of(s, "sites")
        .iter()
        .map(|d| d.bounding_box().center())
        .collect()
}

/// A table with the lines `rest` whose sites are `points`, in TOML; more
/// keys of the sites may follow.
fn given(points: &[(f64, f64)], rest: &str) -> String {
    let list: Vec<String> = points.iter().map(|(x, y)| format!("[{x}, {y}]")).collect();
    format!(
        "{rest}[layers.voronoi.sites]\npoints = [{}]\n",
        list.join(", ")
    )
}

#[test]
fn given_points_are_the_sites_one_cell_each() {
    // Inside the page (128 × 190 mm), two outside it, one repeated, one
    // a hair from another: seven sites.
    let inside = [
        (10.0, 10.0),
        (100.0, 20.0),
        (64.0, 95.0),
        (20.0, 170.0),
        (110.0, 180.0),
        (40.0, 60.0),
        (90.0, 120.0),
    ];
    let mut points = inside.to_vec();
    points.insert(2, (-5.0, 50.0));
    points.insert(5, (64.0, 95.0));
    points.push((140.0, 10.0));
    points.push((40.0, 60.0 + 1e-9));
    let s = scene(&given(
        &points,
        "draw = [\"inset\", \"sites\"]\ninset = 0.01\n",
    ));
    // The sites are the points inside, each once, in their order.
    let expected: Vec<Point> = inside.iter().map(|&p| Point::from(p)).collect();
    let sites = dots(&s);
    assert_eq!(sites.len(), expected.len(), "{sites:?}");
    for (a, b) in sites.iter().zip(&expected) {
        assert!(a.distance(*b) < 1e-9, "{a:?} ≠ {b:?}");
    }
    // One cell a site, and each cell holds exactly one given point.
    let cells = paths_of(&s, "inset");
    assert_eq!(cells.len(), expected.len());
    for cell in &cells {
        let held = expected.iter().filter(|p| cell.contains(**p)).count();
        assert_eq!(held, 1, "a cell holds {held} sites");
    }
    // The cells tile the page (less 0.01 mm along every edge).
    let area: f64 = cells.iter().map(|c| c.area().abs()).sum();
    assert!((area - W * H).abs() < 0.01 * W * H, "{area:.0} mm²");
}

#[test]
fn given_points_outside_the_region_are_left_out() {
    // A circle of radius 30 about (64, 95), less a hole in its middle.
    let region = "[layers.voronoi.region]\ncircle = { centre = [64, 95], radius = 30 }\n\
                  holes = [{ circle = { centre = [64, 95], radius = 5 } }]\n";
    let points = [
        (64.0, 70.0),
        (64.0, 95.0), // in the hole
        (64.0, 120.0),
        (10.0, 10.0), // outside the circle
        (40.0, 95.0),
        (93.9, 95.0), // just inside the outline
        (94.1, 95.0), // just outside
    ];
    let s = scene(&given(
        &points,
        &format!("draw = [\"sites\", \"cells\"]\n{region}"),
    ));
    let kept: Vec<Point> = [(64.0, 70.0), (64.0, 120.0), (40.0, 95.0), (93.9, 95.0)]
        .map(Point::from)
        .to_vec();
    let sites = dots(&s);
    assert_eq!(sites.len(), kept.len(), "{sites:?}");
    assert!(
        sites.iter().zip(&kept).all(|(a, b)| a.distance(*b) < 1e-9),
        "{sites:?}"
    );
    // None inside at all: refused, naming the points.
    let e = error(&given(&[(64.0, 95.0), (0.0, 0.0)], region));
    assert!(
        e.contains(
            "layers[0].voronoi[0].sites.points: none of the 2 points lies inside the region"
        ),
        "{e}"
    );
}

#[test]
fn relaxation_moves_given_points() {
    // Nine sites bunched in a corner: Lloyd steps spread them over the
    // page, one cell each all the way.
    let points: Vec<(f64, f64)> = (0..9)
        .map(|i| (5.0 + 3.0 * (i % 3) as f64, 5.0 + 3.0 * (i / 3) as f64))
        .collect();
    let table = |relax: u32| {
        given(
            &points,
            &format!("draw = [\"sites\", \"inset\"]\ninset = 0.01\nrelax = {relax}\n"),
        )
    };
    let still = dots(&scene(&table(0)));
    let moved = scene(&table(20));
    let sites = dots(&moved);
    assert_eq!(sites.len(), 9);
    assert_eq!(paths_of(&moved, "inset").len(), 9);
    let far = |ps: &[Point]| ps.iter().map(|p| p.x + p.y).sum::<f64>() / ps.len() as f64;
    assert!(far(&still) < 20.0 && far(&sites) > 120.0, "{sites:?}");
    // Weighted by a density, they settle where it is dense.
    let dense = given(&points, "draw = [\"sites\"]\nrelax = 30\n") + "density = \"u^4\"\n";
    let dense = scene(&dense);
    let mean_x = dots(&dense).iter().map(|p| p.x).sum::<f64>() / 9.0;
    assert!(mean_x > 0.6 * W, "mean x {mean_x:.1}");
}

#[test]
fn given_points_refuse_the_keys_that_spread_sites() {
    let points = "points = [[10, 10], [50, 50]]";
    let cases = [
        (
            format!("sites = {{ {points}, distribution = \"poisson\" }}\n"),
            "layers[0].voronoi[0].sites.distribution: does not apply to given points",
        ),
        (
            format!("sites = {{ {points}, count = 5 }}\n"),
            "layers[0].voronoi[0].sites.count: does not apply to given points",
        ),
        (
            format!("sites = {{ {points}, jitter = 0.2 }}\n"),
            "layers[0].voronoi[0].sites.jitter: does not apply to given points",
        ),
        (
            format!("sites = {{ {points}, spacing = 4 }}\n"),
            "layers[0].voronoi[0].sites.spacing: does nothing to given points without relax steps",
        ),
        (
            format!("relax = 3\nsites = {{ {points}, spacing = 4 }}\n"),
            "layers[0].voronoi[0].sites.spacing: does not apply to given points relaxed by \
             unweighted lloyd steps",
        ),
        (
            format!("sites = {{ {points}, density = \"u\" }}\n"),
            "layers[0].voronoi[0].sites.density: does nothing to given points without relax",
        ),
        (
            "sites = { points = [] }\n".to_string(),
            "layers[0].voronoi[0].sites.points: needs at least one point [x, y]",
        ),
        (
            "sites = { points = [[10, 10], [20, nan]] }\n".to_string(),
            "layers[0].voronoi[0].sites.points[1]: y must be a finite number",
        ),
        (
            "sites = { points = [[1e9, 10]] }\n".to_string(),
            "layers[0].voronoi[0].sites.points[0]: x must be a finite number within",
        ),
    ];
    for (table, expected) in cases {
        let e = error(&table);
        assert!(e.contains(expected), "{table}\n→ {e}\nwanted {expected}");
    }
    // With relaxation that reads it, the spacing is taken; the ranges of
    // the fields checked are recorded, none for the points.
    let table = format!("relax = 3\nrelaxation = \"lbg\"\nsites = {{ {points}, spacing = 4 }}\n");
    let spec = SceneSpec::parse(&text(&table), Format::Toml).unwrap();
    let ranges = spec.ranges();
    assert!(ranges
        .iter()
        .any(|r| r.field == "layers[0].voronoi[0].sites.spacing"));
    assert!(!ranges.iter().any(|r| r.field.contains("points")));
    for table in [
        format!("relax = 3\nsites = {{ {points}, spacing = 4, density = \"u\" }}\n"),
        format!("relax = 3\nsites = {{ {points}, density = \"u\" }}\n"),
    ] {
        scene(&table);
    }
}

/// The SVG without the description it embeds.
fn drawing(svg: &str) -> String {
    let (head, rest) = svg
        .split_once("<metadata>")
        .expect("an embedded description");
    let (_, tail) = rest.split_once("</metadata>").expect("its end");
    format!("{head}{tail}")
}

/// Renders `text` and again with the sites of each voronoi table pinned
/// (given as the points they were spread as), written to TOML and read
/// back: the same SVG, byte for byte, but for the embedded description.
fn pinning_draws_the_same(text: &str) {
    use crate::motif::Library;
    use crate::project::{render_with_progress, voronoi_sites};
    let spec = SceneSpec::parse(text, Format::Toml).unwrap();
    let library = Library::new();
    let mut pinned = spec.clone();
    for (l, layer) in spec.layers.iter().enumerate() {
        for t in 0..layer.voronoi.len() {
            let sites = voronoi_sites(&spec, &library, l, t).unwrap();
            assert!(sites.len() > 3, "{} sites", sites.len());
            pinned = pinned
                .edit(|s| s.layers[l].voronoi[t] = s.layers[l].voronoi[t].pinned(sites))
                .unwrap();
            assert!(pinned.layers[l].voronoi[t].sites.points.is_some());
        }
    }
    let pinned = SceneSpec::parse(&pinned.to_toml(), Format::Toml).unwrap();
    let render =
        |s: &crate::spec::ValidSpec| render_with_progress(s, &library, &mut |_| {}).unwrap();
    let (before, after) = (render(&spec), render(&pinned));
    assert_ne!(before.svg, after.svg, "the descriptions differ");
    assert!(
        drawing(&before.svg) == drawing(&after.svg),
        "pinned sites draw otherwise:\n{text}\n{}",
        pinned.to_toml()
    );
    assert_eq!(before.notes, after.notes);
}

#[test]
fn pinned_sites_draw_the_same_svg() {
    let every = "draw = [\"cells\", \"delaunay\", \"inset\", \"sites\", \"tour\"]\n";
    for table in [
        format!("{every}sites = {{ spacing = 9 }}\n"),
        format!("{every}relax = 3\nsites = {{ distribution = \"grid\", spacing = 11, jitter = 1 }}\n"),
        format!("{every}relax = 2\nsites = {{ distribution = \"uniform\", count = 90 }}\n"),
        // Weighted: the spacing relaxation reads (the default, 10) is
        // written out; uniform sites' even spacing comes from their number.
        format!("{every}relax = 4\nsites = {{ density = \"u\" }}\n"),
        format!("{every}relax = 4\nsites = {{ distribution = \"uniform\", count = 80, density = \"v\" }}\n"),
        // No steps: the density placed the sites and is dropped.
        format!("{every}sites = {{ spacing = 6, density = \"1 - u\" }}\n"),
        // LBG splits and removes sites at the spacing it aims at.
        format!("{every}relaxation = \"lbg\"\nrelax = 15\nsites = {{ distribution = \"uniform\", count = 30, spacing = 12, density = \"u\" }}\n"),
        format!("{every}relaxation = \"lbg\"\nrelax = 15\nconverge = 0.1\nsites = {{ density = \"v\" }}\n"),
        // A rose window with its tracery: the rings stay with the points.
        format!("{every}sites = {{ distribution = \"rose\", petals = 8, spacing = 8, tracery = 1.2 }}\n"),
        // A region with a hole.
        format!(
            "{every}relax = 1\nsites = {{ spacing = 7 }}\n[layers.voronoi.region]\n\
             circle = {{ centre = [64, 95], radius = 50 }}\n\
             holes = [{{ polygon = [[50, 80], [80, 80], [80, 110], [50, 110]] }}]\n"
        ),
    ] {
        pinning_draws_the_same(&text(&table));
    }
}

#[test]
fn pinned_sites_draw_the_same_across_layers() {
    // Two tables with one id share their sites; a third fills the cells of
    // the first layer, so finding its sites builds that layer first.
    pinning_draws_the_same(
        "version = 1\nseed = 11\npage = { size = \"A5\", margin = 10 }\n\
         [[layers]]\nname = \"a\"\n[[layers.voronoi]]\nid = \"w\"\nrelax = 2\n\
         sites = { distribution = \"uniform\", count = 6 }\n\
         [[layers]]\nname = \"b\"\n[[layers.voronoi]]\nid = \"w\"\nrelax = 2\ndraw = [\"inset\"]\n\
         sites = { distribution = \"uniform\", count = 6 }\n\
         [[layers]]\nname = \"c\"\n[[layers.voronoi]]\nid = \"x\"\ndraw = [\"sites\", \"cells\"]\n\
         sites = { spacing = 5 }\nregion = { layer = \"a\" }\n",
    );
}

#[test]
fn sites_of_a_missing_table_are_refused_with_its_place() {
    use crate::motif::Library;
    use crate::project::voronoi_sites;
    let spec = SceneSpec::parse(&text("draw = [\"cells\"]\n"), Format::Toml).unwrap();
    let library = Library::new();
    assert!(voronoi_sites(&spec, &library, 0, 0).is_ok());
    for (layer, table) in [(0, 1), (1, 0)] {
        let e = voronoi_sites(&spec, &library, layer, table)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(&format!(
                "layers[{layer}].voronoi[{table}]: the description has no such voronoi table"
            )),
            "{e}"
        );
    }
}

#[test]
fn dots_follow_the_density_when_given_a_range() {
    // Density u: 0 at the left edge, 1 at the right; radii 0.2 to 0.8 mm.
    let s = scene(
        "draw = [\"sites\"]\ndot_range = [0.2, 0.8]\n\
         sites = { distribution = \"uniform\", count = 300, density = \"u\" }\n",
    );
    let dots = paths_of(&s, "sites");
    let width = 0.3;
    // The ink's radius: half the stroke's extent plus half the pen (a
    // tap is no wider than the pen).
    let radius = |d: &BezPath| (d.bounding_box().width() + width) / 2.0;
    let (left, right): (Vec<&BezPath>, Vec<&BezPath>) = dots
        .iter()
        .partition(|d| d.bounding_box().center().x < 64.0);
    let mean = |v: &[&BezPath]| v.iter().map(|d| radius(d)).sum::<f64>() / v.len() as f64;
    assert!(
        mean(&right) > mean(&left) + 0.2,
        "{} {}",
        mean(&left),
        mean(&right)
    );
    assert!(dots
        .iter()
        .all(|d| radius(d) <= 0.8 + 1e-9 && radius(d) >= 0.15));
    for (table, expected) in [
        (
            "dot_range = [0.5, 0.2]\n",
            "runs from the lightest dot to the darkest",
        ),
        (
            "dot_range = [0.2, 0.5]\n",
            "follows the density of the sites",
        ),
        ("dot_range = [0.01, 0.5]\n", "dot_range[0]"),
    ] {
        let e = error(&format!("draw = [\"sites\"]\n{table}"));
        assert!(e.contains(expected), "{table}: {e}");
    }
}

/// Points along the paths, about `step` mm apart.
fn samples(paths: &[BezPath], step: f64) -> Vec<Point> {
    let mut out = Vec::new();
    let mut start = Point::ZERO;
    for path in paths {
        let line = |out: &mut Vec<Point>, p: Point| {
            let from = *out.last().expect("a move first");
            let n = (from.distance(p) / step).ceil().max(1.0) as usize;
            out.extend((1..=n).map(|k| from.lerp(p, k as f64 / n as f64)));
        };
        kurbo::flatten(path.iter(), 0.01, |el| match el {
            kurbo::PathEl::MoveTo(p) => {
                start = p;
                out.push(p);
            }
            kurbo::PathEl::LineTo(p) => line(&mut out, p),
            // A closed path's last side is drawn too.
            kurbo::PathEl::ClosePath => line(&mut out, start),
            _ => {}
        });
    }
    out
}

#[test]
fn a_rose_window_turns_into_itself_by_one_petal() {
    let window = "[layers.voronoi.region]\ncircle = { centre = [64, 95], radius = 60 }\n\
                  holes = [{ circle = { centre = [64, 95], radius = 10 } }]\n";
    let rose = |petals: u32| {
        let s = scene(&format!(
            "draw = [\"cells\"]\nsites = {{ distribution = \"rose\", petals = {petals}, \
             spacing = 7, tracery = 1.5 }}\n{window}"
        ));
        samples(&paths_of(&s, "cells"), 0.4)
    };
    let centre = Point::new(64.0, 95.0);
    // The largest distance from a turned point of the lead to the lead.
    let asymmetry = |lead: &[Point], degrees: f64| {
        let turn = kurbo::Affine::rotate_about(degrees.to_radians(), centre);
        lead.iter()
            .map(|&p| {
                let q = turn * p;
                lead.iter().map(|r| r.distance(q)).fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    };
    let nine = rose(9);
    assert!(asymmetry(&nine, 40.0) < 0.3, "{}", asymmetry(&nine, 40.0));
    // Not a disc of anything: a turn by other than a petal moves the lead.
    assert!(asymmetry(&nine, 20.0) > 1.0);
    // Tracery: circles of lead where the count of cells doubles, both
    // sides of a 1.5 mm ring of stone.
    let radii: Vec<f64> = nine.iter().map(|p| p.distance(centre)).collect();
    let on_circle = |r: f64| radii.iter().filter(|x| (*x - r).abs() < 0.06).count();
    let rings: Vec<f64> = (100..600)
        .map(|k| k as f64 / 10.0)
        .filter(|&r| on_circle(r) > 150 && on_circle(r + 1.5) > 150)
        .collect();
    assert!(!rings.is_empty(), "no tracery ring");
}

#[test]
fn cracks_draw_plates_inside_the_region() {
    let s = scene("draw = [\"cracks\"]\ncrack = [1.5, 0.6]\nsites = { spacing = 12 }\n");
    let plates = paths_of(&s, "cracks");
    let area: f64 = plates.iter().map(|p| p.area().abs()).sum();
    let n = plates.len() as f64;
    // About one plate per spacing squared, and the cracks take a share.
    assert!(n > 0.5 * W * H / 144.0 && n < 2.0 * W * H / 144.0, "{n} plates");
    assert!(area < 0.98 * W * H && area > 0.8 * W * H, "{area}");
    for p in &plates {
        let b = p.bounding_box();
        assert!(b.x0 >= -1e-6 && b.y0 >= -1e-6 && b.x1 <= W + 1e-6 && b.y1 <= H + 1e-6);
    }
    // Wider cracks leave less mud.
    let wide = scene("draw = [\"cracks\"]\ncrack = [4, 2]\nsites = { spacing = 12 }\n");
    let wide_area: f64 = paths_of(&wide, "cracks").iter().map(|p| p.area().abs()).sum();
    assert!(wide_area < area - 0.03 * W * H, "{wide_area} vs {area}");
    for (table, field) in [
        ("draw = [\"cracks\"]\ncrack = [0.5, 1]\n", "crack"),
        ("draw = [\"cracks\"]\ncrack = [30, 1]\n", "crack[0]"),
        ("draw = [\"cracks\"]\nsites = { spacing = 0.5 }\n", "sites.spacing"),
        ("sites = { petals = 5 }\n", "sites.petals"),
        ("sites = { distribution = \"rose\", petals = 2 }\n", "sites.petals"),
        ("sites = { edges = 0.5 }\n", "sites.edges"),
    ] {
        let e = error(table);
        assert!(e.contains(field), "{table}: {e}");
    }
}

