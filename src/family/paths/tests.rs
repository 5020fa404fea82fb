//! Placing user paths: sources, anchors, copies along a line, sizes,
//! adjustment by id, and the errors found while placing.

use std::collections::BTreeMap;

use kurbo::{Affine, BezPath, ParamCurve, Point, Shape};

use crate::project::build_scene;
use crate::spec::{Format, SceneSpec};

/// The paths of a one-layer scene whose layer body is `body`, by id.
fn placed(body: &str) -> crate::error::Result<BTreeMap<String, BezPath>> {
    let text = format!("version = 1\nseed = 2\n[[layers]]\nname = \"l\"\n{body}");
    let spec = SceneSpec::parse(&text, Format::Toml)?;
    let scene = build_scene(&spec)?;
    let mut out = BTreeMap::new();
    for layer in &scene.layers {
        layer.content.visit_paths(Affine::IDENTITY, &mut |p, t| {
            out.insert(p.id.clone(), t * p.path.clone());
        });
    }
    Ok(out)
}

fn near(a: Point, b: Point) -> bool {
    a.distance(b) < 1e-9
}

/// Within the arc-length walker's tolerance.
fn close(a: Point, b: Point) -> bool {
    a.distance(b) <= crate::geom::TOLERANCE
}

#[test]
fn a_point_list_is_drawn_where_it_lies() {
    let paths = placed("[[layers.paths]]\npoints = [[10, 10], [30, 10], [30, 40]]\n").unwrap();
    assert_eq!(paths.len(), 1);
    let p = &paths["l.paths-0.path-0"];
    let b = p.bounding_box();
    assert!(
        near(Point::new(b.x0, b.y0), Point::new(10.0, 10.0)),
        "{b:?}"
    );
    assert!(
        near(Point::new(b.x1, b.y1), Point::new(30.0, 40.0)),
        "{b:?}"
    );
    // Straight lines, open.
    assert!((p.perimeter(1e-9) - 50.0).abs() < 1e-9);
    assert!(!p
        .elements()
        .iter()
        .any(|e| matches!(e, kurbo::PathEl::ClosePath)));
}

#[test]
fn a_smooth_list_passes_through_its_points_and_a_closed_one_ends_at_its_start() {
    let pts = [[0.0, 0.0], [20.0, 10.0], [40.0, 0.0], [20.0, 30.0]];
    let body = "[[layers.paths]]\npoints = [[0, 0], [20, 10], [40, 0], [20, 30]]\nsmooth = true\nclosed = true\n";
    let p = &placed(body).unwrap()["l.paths-0.path-0"];
    let ends: Vec<Point> = p.segments().map(|s| s.eval(1.0)).collect();
    for [x, y] in pts {
        assert!(
            ends.iter().any(|e| near(*e, Point::new(x, y))),
            "{x},{y} not on {ends:?}"
        );
    }
    assert!(matches!(
        p.elements().last(),
        Some(kurbo::PathEl::ClosePath)
    ));
    assert!(p.area().abs() > 100.0);
}

#[test]
fn copies_along_a_line_sit_at_even_arc_length_and_turn_with_it() {
    // A 10 mm bar centred on each site; the line runs straight down.
    let body = "[[layers.paths]]\nd = \"M 0 0 L 10 0\"\nalong = [[50, 0], [50, 100]]\ncount = 4\n";
    let paths = placed(body).unwrap();
    assert_eq!(paths.len(), 4);
    for i in 0..4 {
        let p = &paths[&format!("l.paths-0.path-{i}")];
        let b = p.bounding_box();
        let y = 100.0 * (i as f64 + 0.5) / 4.0;
        // Turned to follow the line: the bar is now vertical.
        assert!(
            (b.width()).abs() < 1e-9 && (b.height() - 10.0).abs() < 1e-9,
            "{b:?}"
        );
        assert!(close(b.center(), Point::new(50.0, y)), "{b:?} vs {y}");
    }
    // Upright copies keep the bar horizontal.
    let upright = placed(&format!("{body}orient = \"page\"\n")).unwrap();
    let b = upright["l.paths-0.path-0"].bounding_box();
    assert!(
        (b.width() - 10.0).abs() < 1e-9 && b.height().abs() < 1e-9,
        "{b:?}"
    );
}

#[test]
fn spacing_puts_a_copy_every_step_from_the_start() {
    let body = "[[layers.paths]]\nd = \"M 0 0 L 2 0 L 2 2 Z\"\nalong = [[0, 50], [100, 50]]\nspacing = 25\nanchor = \"start\"\n";
    let paths = placed(body).unwrap();
    assert_eq!(paths.len(), 5);
    for p in paths.values() {
        let start = p.segments().next().unwrap().eval(0.0);
        assert!(
            (0..5).any(|k| close(start, Point::new(25.0 * k as f64, 50.0))),
            "{start:?}"
        );
    }
}

#[test]
fn width_and_scale_size_each_copy_about_its_anchor() {
    let body =
        "[[layers.paths]]\nd = \"M 0 0 L 4 0 L 4 2 Z\"\nat = [100, 100]\nwidth = 20\nscale = 1.5\n";
    let b = placed(body).unwrap()["l.paths-0.path-0"].bounding_box();
    assert!((b.width() - 30.0).abs() < 1e-9, "{b:?}");
    assert!((b.height() - 15.0).abs() < 1e-9, "{b:?}");
    assert!(near(b.center(), Point::new(100.0, 100.0)), "{b:?}");
    // The origin anchor puts the source's (0, 0) on the site.
    let origin =
        placed(&body.replace("width = 20\nscale = 1.5\n", "anchor = \"origin\"\n")).unwrap();
    let b = origin["l.paths-0.path-0"].bounding_box();
    assert!(
        near(Point::new(b.x0, b.y0), Point::new(100.0, 100.0)),
        "{b:?}"
    );
}

#[test]
fn adjust_moves_and_hides_copies_by_id() {
    let body = "[[layers.paths]]\nid = \"row\"\nd = \"M 0 0 L 2 0\"\nalong = [[0, 0], [90, 0]]\ncount = 3\n\
                [[adjust]]\nid = \"l.row.path-1\"\nmove = [0, 5]\n\
                [[adjust]]\nid = \"l.row.path-2\"\nhide = true\n";
    let paths = placed(body).unwrap();
    assert_eq!(paths.len(), 2);
    let b = paths["l.row.path-1"].bounding_box();
    assert!(close(b.center(), Point::new(45.0, 5.0)), "{b:?}");
}

#[test]
fn errors_name_the_field() {
    let cases = [
        ("[[layers.paths]]\n", "layers[0].paths[0]: give exactly one source"),
        (
            "[[layers.paths]]\npoints = [[0, 0], [1, 1]]\nd = \"M 0 0 L 1 1\"\n",
            "give exactly one source",
        ),
        ("[[layers.paths]]\nd = \"M 0 0 Q\"\n", "layers[0].paths[0].d: is not SVG path data"),
        ("[[layers.paths]]\nd = \"M 0 0 L 1e9 0\"\n", "layers[0].paths[0].d: point (1000000000, 0)"),
        (
            "[[layers.paths]]\nd = \"M 0 0 L 1 0\"\ncount = 3\n",
            "layers[0].paths[0].count: applies to copies along a line",
        ),
        (
            "[[layers.paths]]\nd = \"M 0 0 L 1 0\"\nalong = [[0, 0], [1, 0]]\ncount = 3\nspacing = 1\n",
            "layers[0].paths[0].spacing: give either count or spacing",
        ),
        (
            "[[layers.paths]]\nd = \"M 0 0 L 1 0\"\nscale = 0\n",
            "layers[0].paths[0].scale: must be between 0.001 and 1000",
        ),
        (
            "[[layers.paths]]\nd = \"M 0 0 L 1 0\"\nalong = [[0, 0], [9000, 0]]\nspacing = 0.5\n",
            "layers[0].paths[0].spacing: 0.5 mm along a 9000 mm line makes 18001 copies",
        ),
        (
            "[[layers.paths]]\nd = \"M 0 0 L 100 0\"\nat = [0, 0]\nwidth = 10000\nscale = 1000\n",
            "layers[0].paths[0].scale: copy l.paths-0.path-0 would reach beyond",
        ),
        (
            "[[layers.paths]]\nd = \"M 0 0 L 1 0\"\n[[layers.paths]]\nid = \"paths-0\"\nd = \"M 0 0 L 1 0\"\n",
            "layers[0].paths[1].id: id 'paths-0' is used twice in this layer",
        ),
        (
            "[[layers.paths]]\nsvg = \"nowhere.svg\"\n",
            "paths file nowhere.svg: cannot read",
        ),
    ];
    for (body, wanted) in cases {
        let e = placed(body).unwrap_err().to_string();
        assert!(e.contains(wanted), "{body}\n→ {e}\nwanted {wanted}");
    }
}

#[test]
fn an_adjustment_cannot_swap_a_placed_path_for_a_motif() {
    let body = "[[layers.paths]]\nd = \"M 0 0 L 1 0\"\n\n[[adjust]]\nid = \"l.paths-0.path-0\"\nmotif = \"ume\"\n";
    let e = placed(body).unwrap_err().to_string();
    assert!(
        e.contains("adjust[0].motif: 'l.paths-0.path-0' is a placed path"),
        "{e}"
    );
    // TOML descriptions point at the line of the offending field.
    assert!(e.starts_with("10:9: "), "{e}");
}

/// A closed copy's paint bokashi shades it in its own path: level lines
/// from its top, inside it, further apart further down; an open copy
/// encloses nothing to shade.
#[test]
fn bokashi_shades_closed_copies_in_their_own_path() {
    let square = "[[layers.paths]]\npoints = [[0, 0], [40, 0], [40, 40], [0, 40]]\nclosed = true\n";
    let bare = &placed(square).unwrap()["l.paths-0.path-0"];
    let shaded = format!(
        "{square}paint = {{ bokashi = {{ from = \"top\", spacing = 1, growth = 2, reach = 1 }} }}\n"
    );
    let p = &placed(&shaded).unwrap()["l.paths-0.path-0"];
    let n = bare.elements().len();
    assert_eq!(&p.elements()[..n], bare.elements());
    let ys: Vec<f64> = p.elements()[n..]
        .iter()
        .filter_map(|e| match e {
            kurbo::PathEl::MoveTo(q) => Some(q.y),
            _ => None,
        })
        .collect();
    assert_eq!(ys, vec![1.0, 3.0, 7.0, 15.0, 31.0]);
    let open = "[[layers.paths]]\npoints = [[0, 0], [40, 0], [40, 40]]\npaint = { bokashi = {} }\n";
    assert_eq!(
        placed(open).unwrap()["l.paths-0.path-0"].elements().len(),
        3
    );
}

/// `@n` takes the palette's colour, for pens and fills alike; another
/// palette recolours the same description.
#[test]
fn palette_slots_colour_pens_and_fills() {
    use crate::scene::traditional::traditional;
    let text = |palette: &str| {
        format!(
            "version = 1\npalette = \"{palette}\"\n[[pens]]\nnumber = 1\ncolor = \"@2\"\n\
             [[layers]]\nname = \"l\"\n[[layers.paths]]\n\
             points = [[0, 0], [40, 0], [40, 40]]\nclosed = true\npaint = {{ fill = \"@3\" }}\n"
        )
    };
    let colours = |palette: &str| {
        let spec = SceneSpec::parse(&text(palette), Format::Toml).unwrap();
        let scene = build_scene(&spec).unwrap();
        let mut fill = None;
        scene.layers[0]
            .content
            .visit_paths(Affine::IDENTITY, &mut |p, _| fill = p.style.fill);
        (scene.pens[0].color, fill.unwrap())
    };
    let colour = |name: &str| traditional(name).unwrap().color;
    assert_eq!(
        colours("kaga-gosai"),
        (colour("ai-iro"), colour("matsuba-iro"))
    );
    assert_eq!(colours("kyo"), (colour("asagi-iro"), colour("moegi")));
}
