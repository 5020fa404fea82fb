use kurbo::{Affine, ParamCurve, PathEl, Point, Rect, Shape};

use super::*;
use crate::input::{import_svg, ImportOptions};
use crate::output::path_dump;
use crate::scene::Style;

/// A frame — a square from 10 to 90 mm with a square hole from 35 to 65
/// mm, two separate shapes — and one open line right across it.
const FRAME: &str = r##"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100">
    <rect id="outer" x="10" y="10" width="80" height="80" stroke="#000" fill="none"/>
    <rect id="hole" x="35" y="35" width="30" height="30" stroke="#000" fill="none"/>
    <path id="line" d="M 0 50 L 100 50" stroke="#000" fill="none"/>
</svg>"##;

fn frame() -> Scene {
    import_svg(FRAME, &ImportOptions::DEFAULT).unwrap().scene
}

/// The points a layer draws, its curves flattened to 0.01 mm.
fn points(layer: &Layer) -> Vec<Point> {
    let mut out = Vec::new();
    layer.content.visit_paths(Affine::IDENTITY, &mut |p, t| {
        kurbo::flatten(t * p.path.clone(), 0.01, |el| match el {
            PathEl::MoveTo(q) | PathEl::LineTo(q) => out.push(q),
            _ => {}
        });
    });
    out
}

/// The points of every segment `step` mm apart along the layer's lines
/// (their ends included).
fn along(layer: &Layer, step: f64) -> Vec<Point> {
    let mut out = Vec::new();
    let mut at: Option<Point> = None;
    layer.content.visit_paths(Affine::IDENTITY, &mut |p, t| {
        kurbo::flatten(t * p.path.clone(), 0.01, |el| match el {
            PathEl::MoveTo(q) => {
                out.push(q);
                at = Some(q);
            }
            PathEl::LineTo(q) => {
                let from = at.unwrap_or(q);
                let n = (from.distance(q) / step).ceil().max(1.0) as usize;
                out.extend((1..=n).map(|k| from.lerp(q, k as f64 / n as f64)));
                at = Some(q);
            }
            _ => {}
        });
    });
    out
}

fn fill_layer(filled: &Filled) -> &Layer {
    let layer = filled.scene.layers.last().unwrap();
    assert_eq!(layer.id, filled.layer);
    layer
}

#[test]
fn every_pattern_fills_the_frame_and_leaves_its_hole_empty() {
    let drawing = frame();
    assert_eq!(drawing.pens.len(), 1);
    for pattern in FillPattern::ALL {
        let job = match pattern {
            FillPattern::Zentangle => FillJob::new(pattern).with_steps(10),
            _ => FillJob::new(pattern).with_spacing(4.0),
        };
        let filled = fill_scene(drawing.clone(), &job).unwrap();
        let layer = fill_layer(&filled);
        assert_eq!(layer.pen, 2, "{pattern:?}");
        assert_eq!((filled.pen, filled.new_pen), (2, true));
        let pen = filled.scene.pen(2).unwrap();
        assert_ne!(pen.color, drawing.pens[0].color);
        assert_eq!(filled.scene.pens.len(), 2);
        assert_eq!(filled.fill.paths, {
            let mut n = 0;
            layer
                .content
                .visit_paths(Affine::IDENTITY, &mut |_, _| n += 1);
            n
        });
        // The tour's straight steps between sites may cross the hole;
        // every other pattern keeps its lines out of it. Dots reach out
        // of their site by their radius. (The import computes in f32:
        // the outline is known to a few µm.)
        let (pts, slack) = match pattern {
            FillPattern::Tour => (points(layer), 1e-4),
            FillPattern::Stipple => (along(layer, 0.2), 0.3 + 1e-4),
            _ => (along(layer, 0.2), 1e-4),
        };
        assert!(pts.len() > 200, "{pattern:?}: {} points", pts.len());
        let outer = Rect::new(10.0, 10.0, 90.0, 90.0).inflate(slack, slack);
        let hole = Rect::new(35.0, 35.0, 65.0, 65.0).inflate(-slack, -slack);
        for p in &pts {
            assert!(outer.contains(*p), "{pattern:?}: {p:?} outside the frame");
            let in_hole = p.x > hole.x0 && p.x < hole.x1 && p.y > hole.y0 && p.y < hole.y1;
            assert!(!in_hole, "{pattern:?}: {p:?} inside the hole");
        }
        // All four sides of the frame are filled (the open line across it
        // cuts nothing off).
        for side in [
            Rect::new(10.0, 10.0, 35.0, 90.0),
            Rect::new(65.0, 10.0, 90.0, 90.0),
            Rect::new(10.0, 10.0, 90.0, 35.0),
            Rect::new(10.0, 65.0, 90.0, 90.0),
        ] {
            let n = pts.iter().filter(|p| side.contains(**p)).count();
            assert!(n > 20, "{pattern:?}: {n} points in {side:?}");
        }
    }
}

#[test]
fn the_drawing_comes_back_unchanged() {
    let drawing = frame();
    let mut job = FillJob::new(FillPattern::Voronoi).with_spacing(6.0);
    // As built: the pen stage would join and reorder the drawing's lines.
    job.pen_stage = false;
    let filled = fill_scene(drawing.clone(), &job).unwrap();
    let n = drawing.layers.len();
    assert_eq!(filled.scene.layers.len(), n + 1);
    assert_eq!(filled.scene.layers[..n], drawing.layers[..]);
    assert_eq!(filled.scene.pens[..1], drawing.pens[..]);
    assert_eq!(filled.scene.page, drawing.page);
    assert_eq!(filled.scene.description, drawing.description);
    // Byte for byte: the drawing's lines in the path dump, and its pen's
    // Inkscape layer in the SVG.
    let before = path_dump(&drawing, 3);
    let after = path_dump(&filled.scene, 3);
    assert!(after.starts_with(&before), "{before}\n----\n{after}");
    assert!(after.len() > before.len());
    let svg = to_svg(&drawing, &SvgOptions::DEFAULT);
    let pen_1 = &svg[svg.find("<g id=\"pen-1\"").unwrap()..svg.rfind("</svg>").unwrap()];
    let out = filled.svg(SvgOptions::DEFAULT.precision);
    assert!(out.contains(pen_1), "{out}");
    assert!(out.contains(r#"<g id="pen-2" inkscape:groupmode="layer" inkscape:label="2 fill""#));
    // Behind the drawing, in depth.
    assert!(fill_layer(&filled).depth > drawing.layers[0].depth);
}

#[test]
fn the_seed_decides_the_sites() {
    let job = FillJob::new(FillPattern::Stipple).with_spacing(5.0);
    let dump = |job: &FillJob| path_dump(&fill_scene(frame(), job).unwrap().scene, 3);
    assert_eq!(dump(&job), dump(&job));
    assert_eq!(job.seed, 1);
    assert_ne!(dump(&job), dump(&job.clone().with_seed(2)));
    // Every pattern draws from the same sites for one seed: the
    // stipple's dots sit where the tour turns.
    let stipple = fill_scene(frame(), &job).unwrap();
    let tour = fill_scene(frame(), &FillJob::new(FillPattern::Tour).with_spacing(5.0)).unwrap();
    let mut turns = points(fill_layer(&tour));
    let dots = fill_layer(&stipple);
    let mut centres = Vec::new();
    dots.content.visit_paths(Affine::IDENTITY, &mut |p, t| {
        centres.push((t * p.path.clone()).bounding_box().center());
    });
    let key = |p: &Point| ((p.x * 1e3).round() as i64, (p.y * 1e3).round() as i64);
    turns.sort_by_key(key);
    centres.sort_by_key(key);
    assert_eq!(turns.len(), centres.len());
    for (a, b) in turns.iter().zip(&centres) {
        assert!(a.distance(*b) < 1e-3, "{a:?} {b:?}");
    }
}

#[test]
fn points_are_sites_spread_uniformly() {
    let job = FillJob::new(FillPattern::Stipple)
        .with_points(150)
        .with_relax(0)
        .with_dot(0.5);
    let filled = fill_scene(frame(), &job).unwrap();
    assert_eq!(filled.fill.paths, 150);
    let dot = fill_layer(&filled).content.clone();
    // The ink reaches the dot's radius: the stroke's centre line lies half
    // the fill pen's width (0.3 mm) inside it.
    let mut radii = Vec::new();
    dot.visit_paths(Affine::IDENTITY, &mut |p, _| {
        radii.push(p.path.bounding_box().width() / 2.0 + 0.15)
    });
    assert!(radii.iter().all(|r| (r - 0.5).abs() < 1e-3), "{radii:?}");
}

fn invalid(drawing: Scene, job: FillJob) -> (String, String) {
    match fill_scene(drawing, &job) {
        Err(Error::Invalid { field, message, .. }) => (field, message),
        other => panic!("{job:?}: {other:?}"),
    }
}

#[test]
fn bad_options_are_named_as_options() {
    let job = FillJob::DEFAULT;
    let (field, message) = invalid(frame(), job.clone().with_spacing(4.0).with_points(100));
    assert_eq!(field, "points");
    assert!(message.contains("not both"), "{message}");
    let (field, message) = invalid(frame(), job.clone().with_dot(1.0));
    assert_eq!(field, "dot");
    assert!(message.contains("voronoi"), "{message}");
    for (job, option) in [
        (job.clone().with_spacing(0.0), "spacing"),
        (job.clone().with_spacing(f64::NAN), "spacing"),
        (job.clone().with_points(0), "points"),
        (job.clone().with_relax(5000), "relax"),
        (job.clone().with_relax(5).with_converge(-1.0), "converge"),
        (job.clone().with_pen(0), "pen"),
        (job.clone().with_pen(1000), "pen"),
        (job.clone().with_seed(u64::MAX), "seed"),
        (FillJob::new(FillPattern::Stipple).with_dot(0.0), "dot"),
    ] {
        let (field, message) = invalid(frame(), job.clone());
        assert_eq!(field, option, "{job:?}: {message}");
        assert!(message.starts_with("must be between"), "{message}");
    }
    let (field, message) = invalid(frame(), job.clone().with_density("1 +"));
    assert_eq!(field, "density");
    assert!(message.starts_with("is not a formula"), "{message}");
    // Too many sites for the family: on the spacing, with the numbers.
    let big = r##"<svg xmlns="http://www.w3.org/2000/svg" width="1000mm" height="1000mm" viewBox="0 0 1000 1000">
        <rect width="1000" height="1000" stroke="#000" fill="none"/>
    </svg>"##;
    let big = import_svg(big, &ImportOptions::DEFAULT).unwrap().scene;
    let (field, message) = invalid(big, job.clone().with_spacing(0.1));
    assert_eq!(field, "spacing");
    assert!(message.contains("1000000 sites"), "{message}");
}

#[test]
fn a_drawing_without_closed_shapes_has_nothing_to_fill() {
    let open = r##"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100">
        <path d="M 10 10 L 90 10 L 90 90 L 10 90" stroke="#000" fill="none"/>
        <g inkscape:groupmode="layer" inkscape:label="%guides" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape">
          <rect x="10" y="10" width="80" height="80" stroke="#00f" fill="none"/>
        </g>
    </svg>"##;
    let drawing = import_svg(open, &ImportOptions::DEFAULT).unwrap().scene;
    // The only closed shape is on a layer that is not plotted.
    assert!(drawing.layers.iter().any(|l| !l.is_plotted()));
    let (field, message) = invalid(drawing, FillJob::DEFAULT);
    assert_eq!(field, "input");
    assert!(
        message.starts_with("has no closed shape to fill"),
        "{message}"
    );

    // Closed shapes that enclose nothing: a dot and a retraced line.
    let mut content = Group::new("g");
    let mut flat = BezPath::new();
    flat.move_to((5.0, 5.0));
    flat.close_path();
    flat.move_to((10.0, 10.0));
    flat.line_to((50.0, 10.0));
    flat.close_path();
    content.push_path("flat", flat, Style::default());
    let page = crate::units::Page::sized(
        100.0,
        100.0,
        crate::units::Orientation::Portrait,
        crate::units::Margins::uniform(0.0),
    );
    let (field, message) = invalid(Scene::one_pen(page, content), FillJob::DEFAULT);
    assert_eq!(field, "input");
    assert!(
        message.starts_with("its closed shapes enclose no area"),
        "{message}"
    );
}

#[test]
fn transforms_margins_and_taken_ids_and_pens() {
    // A square drawn at the origin and moved by its group, on a page with
    // margins: the fill lies where the square is drawn.
    let mut square = Group::new("fill");
    square.transform = Affine::translate((40.0, 20.0));
    square.push_path(
        "fill.square",
        Rect::new(0.0, 0.0, 30.0, 30.0).to_path(0.1),
        Style::default(),
    );
    let mut content = Group::new("l.content");
    content.push_group(square);
    let page = crate::units::Page::sized(
        120.0,
        80.0,
        crate::units::Orientation::Landscape,
        crate::units::Margins::uniform(7.0),
    );
    let mut drawing = Scene::one_pen(page, content);
    drawing.pens.push(Pen {
        number: 3,
        name: "red".into(),
        color: Color::rgb(200, 0, 0),
        width: 0.5,
    });
    let filled = fill_scene(drawing.clone(), &FillJob::new(FillPattern::Glass)).unwrap();
    // Pen 2 is free; the ids `fill` and `fill.…` are taken.
    assert_eq!((filled.pen, filled.new_pen), (2, true));
    let numbers: Vec<u32> = filled.scene.pens.iter().map(|p| p.number).collect();
    assert_eq!(numbers, [1, 2, 3]);
    assert_eq!(filled.layer, "fill-2");
    let pts = points(fill_layer(&filled));
    assert!(!pts.is_empty());
    let square = Rect::new(40.0, 20.0, 70.0, 50.0);
    assert!(pts.iter().all(|p| square.contains(*p)), "{pts:?}");
    let mut ids = Vec::new();
    fill_layer(&filled)
        .content
        .visit_paths(Affine::IDENTITY, &mut |p, _| ids.push(p.id.clone()));
    assert!(ids.iter().all(|id| id.starts_with("fill-2.")), "{ids:?}");

    // A pen the drawing has: it keeps its name, colour and width.
    let filled = fill_scene(drawing.clone(), &FillJob::DEFAULT.with_pen(3)).unwrap();
    assert_eq!((filled.pen, filled.new_pen), (3, false));
    assert_eq!(filled.scene.pens, drawing.pens);
    assert_eq!(fill_layer(&filled).pen, 3);
}

#[test]
fn the_preview_is_a_png() {
    let filled = fill_scene(frame(), &FillJob::new(FillPattern::Delaunay)).unwrap();
    assert!(filled.png(20.0).unwrap().starts_with(b"\x89PNG"));
    assert!(filled.preview_svg(2).contains("2 fill"));
}

#[test]
fn an_image_makes_its_dark_side_denser() {
    // Dark on the right, white on the left; fitted to the frame's 80 mm
    // square (the shapes' bounding box).
    let (w, h) = (40, 40);
    let darkness = (0..h)
        .flat_map(|_| (0..w).map(move |x| if x >= w / 2 { 0.9 } else { 0.1 }))
        .collect();
    let image = GreyImage::new(w, h, darkness).unwrap();
    let job = FillJob::new(FillPattern::Stipple)
        .with_points(400)
        .with_relax(5)
        .with_image(image);
    let filled = fill_scene(frame(), &job).unwrap();
    let mut centres = Vec::new();
    fill_layer(&filled)
        .content
        .visit_paths(Affine::IDENTITY, &mut |p, t| {
            centres.push((t * p.path.clone()).bounding_box().center());
        });
    assert_eq!(centres.len(), 400);
    let right = centres.iter().filter(|p| p.x > 50.0).count();
    assert!(right > 3 * (400 - right), "{right} of 400 on the dark side");
    // And none in the hole.
    assert!(!centres
        .iter()
        .any(|p| p.x > 35.1 && p.x < 64.9 && p.y > 35.1 && p.y < 64.9));
}

#[test]
fn lbg_stippling_follows_a_density_formula() {
    // Density u over the frame: the count comes from the spacing, and
    // the right half holds most of the dots.
    let job = FillJob::new(FillPattern::Stipple)
        .with_spacing(4.0)
        .with_lbg()
        .with_relax(100)
        .with_density("u");
    let filled = fill_scene(frame(), &job).unwrap();
    let n = filled.fill.paths as f64;
    // (80² − 30²)/2 mm² at one dot per (√3/2)·4² mm²: about 198.
    assert!(n > 198.0 / 1.5 && n < 198.0 / 0.6, "{n} dots");
}

#[test]
fn a_zentangle_fills_the_frame_and_refuses_the_sites_options() {
    let job = FillJob::new(FillPattern::Zentangle).with_steps(15);
    let filled = fill_scene(frame(), &job).unwrap();
    assert!(filled.fill.paths > 15, "{} paths", filled.fill.paths);
    assert_eq!(filled.notes.len(), 1);
    assert!(
        filled.notes[0].text.starts_with("15 steps"),
        "{:?}",
        filled.notes
    );
    // Nothing is drawn in the frame's hole (30 × 30 mm at 35, 35).
    filled.scene.layers.last().unwrap().content.visit_paths(
        kurbo::Affine::IDENTITY,
        &mut |p, t| {
            let b = (t * p.path.clone()).bounding_box();
            let inside = b.x0 > 35.5 && b.x1 < 64.5 && b.y0 > 35.5 && b.y1 < 64.5;
            assert!(!inside, "{} lies in the hole", p.id);
        },
    );
    let (field, message) = invalid(frame(), job.clone().with_spacing(4.0));
    assert_eq!(field, "spacing");
    assert!(message.contains("zentangle pattern has none"), "{message}");
    let (field, _) = invalid(frame(), FillJob::new(FillPattern::Voronoi).with_steps(4));
    assert_eq!(field, "steps");
    let (field, _) = invalid(frame(), job.with_steps(9000));
    assert_eq!(field, "steps");
}

#[test]
fn the_fill_leaves_the_outline_to_the_drawing_unless_asked() {
    // Length of the fill's strokes that run along the frame's outlines
    // (the squares 10–90 and 35–65): both ends and the middle on them.
    let along_outline = |filled: &Filled| {
        let on = |p: Point| {
            [(10.0, 90.0), (35.0, 65.0)].iter().any(|&(lo, hi)| {
                // Clipped cells meet the outline within a micrometre.
                let inside = |v: f64| (lo - 1e-3..=hi + 1e-3).contains(&v);
                let at = |v: f64| (v - lo).abs() < 1e-3 || (v - hi).abs() < 1e-3;
                (at(p.x) && inside(p.y)) || (at(p.y) && inside(p.x))
            })
        };
        let mut length = 0.0;
        fill_layer(filled)
            .content
            .visit_paths(Affine::IDENTITY, &mut |p, t| {
                for seg in (t * p.path.clone()).segments() {
                    let (a, b) = (seg.start(), seg.end());
                    if on(a) && on(b) && on(a.midpoint(b)) {
                        length += a.distance(b);
                    }
                }
            });
        length
    };
    for pattern in [FillPattern::Voronoi, FillPattern::Delaunay] {
        let mut job = FillJob::new(pattern).with_spacing(6.0);
        let alone = along_outline(&fill_scene(frame(), &job).unwrap());
        assert!(alone < 1e-3, "{pattern:?}: {alone} mm along the outline");
        job.outline = true;
        // Both squares, all round.
        let with = along_outline(&fill_scene(frame(), &job).unwrap());
        assert!((with - 440.0).abs() < 1.0, "{pattern:?}: {with} mm");
    }
}

/// A dark square with a white square painted over its middle, and a
/// ring (a filled shape with a hole) with a disc painted in its hole.
const PAINTED: &str = r##"<svg xmlns="http://www.w3.org/2000/svg" width="200mm" height="100mm" viewBox="0 0 200 100">
    <rect x="10" y="10" width="80" height="80" fill="#234"/>
    <rect x="35" y="35" width="30" height="30" fill="#fff" stroke="#000"/>
    <path d="M 110 10 H 190 V 90 H 110 Z M 135 35 V 65 H 165 V 35 Z" fill="#234" fill-rule="evenodd"/>
    <circle cx="150" cy="50" r="8" fill="#c33"/>
</svg>"##;

/// How many of the fill's points lie inside `rect`.
fn points_in(filled: &Filled, rect: Rect) -> usize {
    along(fill_layer(filled), 0.2)
        .iter()
        .filter(|p| rect.contains(**p))
        .count()
}

#[test]
fn the_fill_follows_what_is_painted_unless_asked_for_even_odd() {
    let drawing = import_svg(PAINTED, &ImportOptions::DEFAULT).unwrap().scene;
    let job = FillJob::new(FillPattern::Voronoi).with_spacing(3.0);
    let middle = Rect::new(37.0, 37.0, 63.0, 63.0);
    let ring_hole = Rect::new(137.0, 37.0, 163.0, 63.0);
    let disc = Rect::new(146.0, 46.0, 154.0, 54.0);

    // As painted: the white square covers the dark one, it does not cut a
    // hole; the ring's hole is empty but where the disc is painted.
    let painted = fill_scene(drawing.clone(), &job).unwrap();
    assert!(points_in(&painted, middle) > 100);
    assert!(points_in(&painted, disc) > 10);
    let hole_not_disc = along(fill_layer(&painted), 0.2)
        .iter()
        .filter(|p| ring_hole.contains(**p) && p.distance((150.0, 50.0).into()) > 8.1)
        .count();
    assert_eq!(
        hole_not_disc, 0,
        "the ring's hole stays empty around the disc"
    );

    // Even-odd of the outlines: the stacked square is a hole, and the
    // disc inside the ring's hole is filled as an island.
    let even_odd = fill_scene(drawing, &job.with_region(FillRegion::EvenOdd)).unwrap();
    assert_eq!(points_in(&even_odd, middle), 0);
    assert!(points_in(&even_odd, disc) > 10);
}

#[test]
fn a_pattern_that_draws_nothing_is_an_error() {
    let tiny = r##"<svg xmlns="http://www.w3.org/2000/svg" width="20mm" height="20mm" viewBox="0 0 20 20">
        <rect x="5" y="5" width="0.6" height="0.6" stroke="#000" fill="none"/>
    </svg>"##;
    let drawing = import_svg(tiny, &ImportOptions::DEFAULT).unwrap().scene;
    let (field, message) = invalid(drawing, FillJob::new(FillPattern::Glass));
    assert_eq!(field, "pattern");
    assert!(message.contains("drew nothing"), "{message}");
}

#[test]
fn a_tour_lifts_the_pen_between_separate_shapes() {
    let two = r##"<svg xmlns="http://www.w3.org/2000/svg" width="200mm" height="100mm" viewBox="0 0 200 100">
        <rect x="10" y="10" width="60" height="80" stroke="#000" fill="none"/>
        <circle cx="140" cy="50" r="40" stroke="#000" fill="none"/>
    </svg>"##;
    let drawing = import_svg(two, &ImportOptions::DEFAULT).unwrap().scene;
    let filled = fill_scene(drawing, &FillJob::new(FillPattern::Tour).with_spacing(4.0)).unwrap();
    let (mut lines, mut across, mut starts) = (0, 0, 0);
    fill_layer(&filled)
        .content
        .visit_paths(Affine::IDENTITY, &mut |p, t| {
            for el in (t * p.path.clone()).elements() {
                if let PathEl::MoveTo(_) = el {
                    starts += 1;
                }
            }
            for seg in (t * p.path.clone()).segments() {
                let (a, b) = (seg.start(), seg.end());
                lines += 1;
                if (a.x < 75.0) != (b.x < 75.0) {
                    across += 1;
                }
            }
        });
    assert!(lines > 200, "{lines} steps");
    assert_eq!(
        across, 0,
        "a step runs across the blank paper between the shapes"
    );
    assert_eq!(starts, 2, "one tour a shape");
}
