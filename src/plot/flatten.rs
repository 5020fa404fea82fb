//! Flattening a scene for plotting: one layer per pen, one flat group of
//! paths per layer, everything in page coordinates.
//!
//! The other plot stages ([`super::merge`], [`super::sort`],
//! [`super::simplify`], [`super::multipass`]) work on such a *flat scene*,
//! layer by layer, so they never mix pens and never have to think about
//! group transforms. [`by_pen`] makes one from any scene:
//!
//! - one [`Layer`] per pen number used by the scene, in ascending pen number,
//!   with id `pen-N.layer` (the SVG writer names the pen's Inkscape layer
//!   `pen-N`), the pen's name (empty when the pen is not in [`Scene::pens`])
//!   and depth 0;
//! - its content is one group `pen-N.paths` with the identity transform
//!   whose children are every path of that pen's layers, in paint order
//!   ([`Scene::layers_back_to_front`], then document order inside a layer);
//! - every group transform *and the margin translation* is applied to the
//!   path coordinates, so the coordinates are **page coordinates** (origin
//!   at the top-left corner of the sheet, mm, y down). To say so in the
//!   data, the flat scene has the same page size and **zero margins**: its
//!   drawable area is the whole sheet and [`Scene::page_transform`] is the
//!   identity. (To fit a drawing inside the original margins, run
//!   [`super::transform`] before flattening or give it the margin
//!   explicitly.)
//!
//! Paths keep their ids and styles; a path with several subpaths stays one
//! path here (stages that need single-subpath paths call
//! [`split_subpaths`]).
//!
//! The helpers [`take_paths`] and [`set_paths`] are how the stages read and
//! write a layer's paths. On a layer that is not flat they flatten it first
//! (applying its group transforms, in the layer's own coordinates), so the
//! stages also do something sensible on a scene that did not go through
//! [`by_pen`] — but distances are then measured in each layer's coordinates.
//!
//! # Layers that are not plotted
//!
//! A documentation layer (AxiDraw's `%` layers, [`Layer::is_plotted`]
//! false) is reference material, not drawing, and the plot stages leave it
//! as it is:
//!
//! - [`by_pen`] does not merge it into its pen's layer. It stays a layer of
//!   its own, with its id, name, pen, groups and paths unchanged; only the
//!   margin translation is composed into its content group's transform (the
//!   flat scene has zero margins), so it stays where it was on the sheet.
//!   These layers come first in the flat scene, back to front, before the
//!   pens' layers — the order of the SVG writer, which paints them behind
//!   the drawing.
//! - [`take_paths`] gives no paths for it and leaves its content in place,
//!   and [`set_paths`] with no paths leaves it alone, so the per-pen stages
//!   ([`super::merge`], [`super::simplify`], [`super::sort`],
//!   [`super::multipass`]) pass it through untouched.
//! - [`take_unplotted`] and [`restore_unplotted`] set such layers aside
//!   around stages that walk the layers themselves (hatching, hidden-line
//!   removal): set aside, they are neither hatched, nor hidden, nor hide.
//!
//! The G-code and HPGL writers and [`super::stats()`] skip or flag them.

use kurbo::{Affine, BezPath, PathEl, Point};

use crate::geom::subpath::subpaths;

use crate::scene::{Group, Layer, Node, Scene, StyledPath};
use crate::units::Margins;

/// One layer per pen, with every path in page coordinates (see the module
/// documentation), preceded by the layers that are not plotted, kept as
/// they are. The result has the page size of `scene`, zero margins, the
/// same pens and description.
pub fn by_pen(scene: &Scene) -> Scene {
    let page_transform = scene.page_transform();
    let back_to_front = scene.layers_back_to_front();
    let mut layers: Vec<Layer> = back_to_front
        .iter()
        .filter(|l| !l.is_plotted())
        .map(|&l| {
            let mut layer = l.clone();
            layer.depth = 0;
            layer.content.transform = page_transform * layer.content.transform;
            layer
        })
        .collect();
    let plotted = back_to_front.iter().copied().filter(|l| l.is_plotted());
    layers.extend(
        Scene::layers_by_pen(plotted)
            .into_iter()
            .map(|(number, of_pen)| {
                let mut content = Group::new(format!("pen-{number}.paths"));
                for layer in of_pen {
                    layer.content.visit_paths(page_transform, &mut |p, t| {
                        // A fill without a stroke is preview colour, a mask only
                        // hides: nothing to plot.
                        if !p.style.is_drawn() {
                            return;
                        }
                        content.children.push(Node::Path(StyledPath {
                            id: p.id.clone(),
                            path: transformed(&p.path, t),
                            style: p.style.clone(),
                        }));
                    });
                }
                Layer {
                    id: format!("pen-{number}.layer"),
                    name: plotted_layer_name(number, scene.pen(number).map_or("", |p| &p.name)),
                    pen: number,
                    depth: 0,
                    content,
                }
            }),
    );
    let mut page = scene.page;
    page.margins = Margins::default();
    Scene {
        page,
        pens: scene.pens.clone(),
        layers,
        description: scene.description.clone(),
    }
}

/// The name of pen `number`'s flat layer: the pen's name, unless that name
/// would read as a layer that is not plotted (`%…`); then the pen number
/// comes first, as in the SVG layer label (`"2 %red"`).
fn plotted_layer_name(number: u32, pen_name: &str) -> String {
    if Layer::name_is_plotted(pen_name) {
        pen_name.to_string()
    } else {
        format!("{number} {pen_name}")
    }
}

/// Takes the layers that are not plotted ([`Layer::is_plotted`] false) out
/// of `scene`, with their positions in [`Scene::layers`], so that a stage
/// that walks every layer (hatching, hidden-line removal) neither changes
/// them nor lets them change the rest. Give them back with
/// [`restore_unplotted`].
pub fn take_unplotted(scene: &mut Scene) -> Vec<(usize, Layer)> {
    let mut taken = Vec::new();
    let mut kept = Vec::with_capacity(scene.layers.len());
    for (i, layer) in std::mem::take(&mut scene.layers).into_iter().enumerate() {
        if layer.is_plotted() {
            kept.push(layer);
        } else {
            taken.push((i, layer));
        }
    }
    scene.layers = kept;
    taken
}

/// Puts back the layers taken by [`take_unplotted`] at their old positions
/// (or at the end, when the scene has fewer layers than it had).
pub fn restore_unplotted(scene: &mut Scene, mut taken: Vec<(usize, Layer)>) {
    // In ascending positions, each insertion finds the ones before it in
    // place.
    taken.sort_by_key(|(i, _)| *i);
    for (i, layer) in taken {
        let at = i.min(scene.layers.len());
        scene.layers.insert(at, layer);
    }
}

/// Whether `layer` is flat: its content has the identity transform and only
/// paths as children.
pub fn is_flat(layer: &Layer) -> bool {
    layer.content.transform == Affine::IDENTITY
        && layer
            .content
            .children
            .iter()
            .all(|n| matches!(n, Node::Path(_)))
}

/// Takes the paths out of `layer`, leaving its content empty. A flat layer
/// gives its paths as they are; any other layer is flattened first (group
/// transforms applied, coordinates in the layer's own frame). A layer that
/// is not plotted ([`Layer::is_plotted`] false) gives no paths and keeps
/// its content, so that a stage passes it through unchanged.
pub fn take_paths(layer: &mut Layer) -> Vec<StyledPath> {
    if !layer.is_plotted() {
        return Vec::new();
    }
    if is_flat(layer) {
        return std::mem::take(&mut layer.content.children)
            .into_iter()
            .filter_map(|n| match n {
                Node::Path(p) => Some(p),
                Node::Group(_) => None,
            })
            .collect();
    }
    let mut out = Vec::new();
    layer.content.visit_paths(Affine::IDENTITY, &mut |p, t| {
        out.push(StyledPath {
            id: p.id.clone(),
            path: transformed(&p.path, t),
            style: p.style.clone(),
        });
    });
    layer.content.children.clear();
    out
}

/// Makes `paths` the content of `layer`: a flat group (the content keeps
/// its id; its transform becomes the identity). On a layer that is not
/// plotted, no paths leave the content as it is (the other half of
/// [`take_paths`]' pass-through); paths replace it as on any layer.
pub fn set_paths(layer: &mut Layer, paths: Vec<StyledPath>) {
    if paths.is_empty() && !layer.is_plotted() {
        return;
    }
    layer.content.transform = Affine::IDENTITY;
    layer.content.children = paths.into_iter().map(Node::Path).collect();
}

/// Splits every path with several subpaths into one path per subpath, in
/// order, each *normalised*: its own move-to, then the elements that draw
/// (see [`crate::geom::subpath`] for the exact rules). The first subpath
/// keeps the id; the k-th further one gets `{id}.{k}` (k from 1). Styles
/// are copied. Subpaths that draw nothing (a lone move-to) are dropped,
/// and so are paths left empty.
pub fn split_subpaths(paths: Vec<StyledPath>) -> Vec<StyledPath> {
    let mut out = Vec::with_capacity(paths.len());
    for p in paths {
        if is_single_subpath(&p.path) {
            out.push(p);
            continue;
        }
        for (k, sub) in subpaths(&p.path).enumerate() {
            out.push(StyledPath {
                id: if k == 0 {
                    p.id.clone()
                } else {
                    format!("{}.{k}", p.id)
                },
                path: sub.to_path(),
                style: p.style.clone(),
            });
        }
    }
    out
}

/// An open normalised subpath (see [`split_subpaths`]) drawn the other way
/// round. Exact: the same
/// points in reverse order, so every segment is the same curve.
pub(crate) fn reverse_open(path: &BezPath) -> BezPath {
    let mut out = path.clone();
    reverse_open_in_place(&mut out);
    out
}

/// [`reverse_open`] without allocating.
pub(crate) fn reverse_open_in_place(path: &mut BezPath) {
    debug_assert!(subpaths(path).all(|s| !s.ends_with_close()));
    let end = path.elements().last().map_or(Point::ZERO, |el| el_end(*el));
    let els = path.elements_mut();
    // Element i (from the end of element i - 1 to its own end) becomes the
    // way back: its control points swapped, ending where it started.
    for i in (1..els.len()).rev() {
        let prev = el_end(els[i - 1]);
        els[i] = match els[i] {
            PathEl::QuadTo(c, _) => PathEl::QuadTo(c, prev),
            PathEl::CurveTo(c1, c2, _) => PathEl::CurveTo(c2, c1, prev),
            _ => PathEl::LineTo(prev),
        };
    }
    if let Some(first) = els.first_mut() {
        *first = PathEl::MoveTo(end);
    }
    if els.len() > 1 {
        els[1..].reverse();
    }
}

/// The on-curve end point of an element (the origin for a close-path,
/// which callers never ask about).
pub(crate) fn el_end(el: PathEl) -> Point {
    match el {
        PathEl::MoveTo(p) | PathEl::LineTo(p) | PathEl::QuadTo(_, p) | PathEl::CurveTo(_, _, p) => {
            p
        }
        PathEl::ClosePath => Point::ZERO,
    }
}

/// Whether `path` is already one normalised subpath (the common case, so
/// that splitting does not copy it).
fn is_single_subpath(path: &BezPath) -> bool {
    let els = path.elements();
    matches!(els.first(), Some(PathEl::MoveTo(_)))
        && subpaths(path)
            .next()
            .is_some_and(|s| s.body().len() + 1 == els.len())
}

/// `path` mapped by `t`, without copying when `t` is the identity.
fn transformed(path: &BezPath, t: Affine) -> BezPath {
    if t == Affine::IDENTITY {
        path.clone()
    } else {
        t * path.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Color, Pen, Style};
    use crate::units::{Orientation, Page, PaperName};
    use kurbo::{Line, Shape};

    fn line(a: (f64, f64), b: (f64, f64)) -> BezPath {
        Line::new(a, b).into_path(0.1)
    }

    fn pen(number: u32, name: &str) -> Pen {
        Pen {
            number,
            name: name.into(),
            color: Color::BLACK,
            width: 0.3,
        }
    }

    fn layer(id: &str, pen: u32, depth: i32, content: Group) -> Layer {
        Layer {
            id: id.into(),
            name: id.into(),
            pen,
            depth,
            content,
        }
    }

    fn ids(layer: &Layer) -> Vec<&str> {
        layer
            .content
            .children
            .iter()
            .map(|n| match n {
                Node::Path(p) => p.id.as_str(),
                Node::Group(g) => g.id.as_str(),
            })
            .collect()
    }

    fn path_of<'a>(layer: &'a Layer, id: &str) -> &'a BezPath {
        layer
            .content
            .children
            .iter()
            .find_map(|n| match n {
                Node::Path(p) if p.id == id => Some(&p.path),
                _ => None,
            })
            .unwrap()
    }

    fn test_scene() -> Scene {
        // Pen 2, front: a line inside a scaled group inside a translated one.
        let mut front = Group::new("front");
        let mut outer = Group::new("outer");
        outer.transform = Affine::translate((100.0, 50.0));
        let mut inner = Group::new("inner");
        inner.transform = Affine::scale(2.0);
        inner.push_path("f1", line((1.0, 1.0), (11.0, 1.0)), Style::default());
        outer.push_group(inner);
        front.push_group(outer);
        front.push_path("f2", line((0.0, 0.0), (5.0, 0.0)), Style::default());

        // Pen 1, back and middle layers.
        let mut back = Group::new("back");
        back.push_path("b1", line((0.0, 0.0), (1.0, 0.0)), Style::default());
        let mut middle = Group::new("middle");
        middle.transform = Affine::translate((0.0, 3.0));
        middle.push_path("m1", line((0.0, 0.0), (1.0, 0.0)), Style::default());

        Scene {
            page: Page::named(PaperName::A4, Orientation::Portrait, Margins::uniform(10.0)),
            pens: vec![pen(1, "black"), pen(2, "red")],
            layers: vec![
                layer("front", 2, 0, front),
                layer("middle", 1, 1, middle),
                layer("back", 1, 5, back),
            ],
            description: Some("x".into()),
        }
    }

    #[test]
    fn by_pen_groups_by_pen_in_paint_order() {
        let flat = by_pen(&test_scene());
        let layer_ids: Vec<&str> = flat.layers.iter().map(|l| l.id.as_str()).collect();
        assert_eq!(layer_ids, ["pen-1.layer", "pen-2.layer"]);
        assert_eq!(flat.layers[0].name, "black");
        assert_eq!(flat.layers[1].name, "red");
        assert_eq!(flat.layers[0].content.id, "pen-1.paths");
        // Back (depth 5) before middle (depth 1).
        assert_eq!(ids(&flat.layers[0]), ["b1", "m1"]);
        assert_eq!(ids(&flat.layers[1]), ["f1", "f2"]);
        assert!(flat.layers.iter().all(is_flat));
        assert_eq!(flat.page.margins, Margins::default());
        assert_eq!(flat.page_transform(), Affine::IDENTITY);
        assert_eq!(flat.description.as_deref(), Some("x"));
    }

    #[test]
    fn by_pen_applies_nested_transforms_and_margins() {
        let scene = test_scene();
        let flat = by_pen(&scene);
        // (1,1) scaled by 2 → (2,2), translated → (102,52), margin → (112,62).
        let f1 = path_of(&flat.layers[1], "f1");
        assert_eq!(f1.elements()[0], PathEl::MoveTo(Point::new(112.0, 62.0)));
        assert_eq!(f1.elements()[1], PathEl::LineTo(Point::new(132.0, 62.0)));
        let m1 = path_of(&flat.layers[0], "m1");
        assert_eq!(m1.elements()[0], PathEl::MoveTo(Point::new(10.0, 13.0)));
        // Same ink and same page-coordinate bounds as before.
        assert_eq!(flat.bounds(), scene.bounds());
        assert!((flat.stats().pen_down_mm - scene.stats().pen_down_mm).abs() < 1e-9);
    }

    #[test]
    fn layer_of_unknown_pen_gets_empty_name() {
        let mut scene = test_scene();
        scene.pens.clear();
        let flat = by_pen(&scene);
        assert_eq!(flat.layers[0].name, "");
    }

    #[test]
    fn take_paths_flattens_a_nested_layer() {
        let mut scene = test_scene();
        let mut l = scene.layers.remove(0);
        let paths = take_paths(&mut l);
        let got: Vec<&str> = paths.iter().map(|p| p.id.as_str()).collect();
        assert_eq!(got, ["f1", "f2"]);
        assert_eq!(
            paths[0].path.elements()[0],
            PathEl::MoveTo(Point::new(102.0, 52.0))
        );
        set_paths(&mut l, paths);
        assert!(is_flat(&l));
        assert_eq!(l.content.id, "front");
    }

    #[test]
    fn split_keeps_ids_and_single_paths() {
        let mut two = line((0.0, 0.0), (1.0, 0.0));
        two.move_to((5.0, 5.0));
        two.line_to((6.0, 5.0));
        let paths = vec![
            StyledPath {
                id: "a".into(),
                path: two,
                style: Style::default(),
            },
            StyledPath {
                id: "b".into(),
                path: line((0.0, 0.0), (2.0, 0.0)),
                style: Style::default(),
            },
            StyledPath {
                id: "empty".into(),
                path: BezPath::new(),
                style: Style::default(),
            },
        ];
        let split = split_subpaths(paths);
        let got: Vec<&str> = split.iter().map(|p| p.id.as_str()).collect();
        assert_eq!(got, ["a", "a.1", "b"]);
    }

    /// The test scene with two layers that are not plotted: `%guides` (pen
    /// 1, nested, at the back) and `% notes` (pen 3, which nothing else
    /// uses), between the others in the list.
    fn scene_with_unplotted() -> Scene {
        let mut s = test_scene();
        let mut guides = Group::new("guides");
        let mut frame = Group::new("frame");
        frame.transform = Affine::scale(2.0);
        frame.push_path(
            "g1",
            kurbo::Rect::new(0.0, 0.0, 50.0, 50.0).into_path(0.1),
            Style {
                fill: Some(Color::rgb(200, 200, 200)),
                ..Style::default()
            },
        );
        guides.push_group(frame);
        guides.push_path("g2", line((0.0, 0.0), (1.0, 0.0)), Style::default());
        guides.push_path("g3", line((1.0, 0.0), (2.0, 0.0)), Style::default());
        let mut notes = Group::new("notes");
        notes.push_path("n1", line((5.0, 5.0), (6.0, 6.0)), Style::default());
        let mut g = layer("guides", 1, 9, guides);
        g.name = "%guides".into();
        let mut n = layer("notes", 3, 0, notes);
        n.name = "  % notes".into();
        s.layers.insert(1, g);
        s.layers.push(n);
        s.pens.push(pen(3, "grey"));
        s
    }

    #[test]
    fn unplotted_names_follow_axidraw() {
        for (name, plotted) in [
            ("%guides", false),
            ("  % 2 notes", false),
            ("%", false),
            ("1 black", true),
            ("guides %", true),
            ("", true),
            ("!%pause", true),
        ] {
            assert_eq!(Layer::name_is_plotted(name), plotted, "{name:?}");
        }
        let s = scene_with_unplotted();
        let plotted: Vec<bool> = s.layers.iter().map(Layer::is_plotted).collect();
        assert_eq!(plotted, [true, false, true, true, false]);
    }

    #[test]
    fn by_pen_keeps_unplotted_layers_apart_and_as_they_are() {
        let scene = scene_with_unplotted();
        let flat = by_pen(&scene);
        let layer_ids: Vec<&str> = flat.layers.iter().map(|l| l.id.as_str()).collect();
        // Unplotted first, back to front (guides at depth 9, notes at 0);
        // pen 3 draws nothing plotted, so it gets no flat layer.
        assert_eq!(layer_ids, ["guides", "notes", "pen-1.layer", "pen-2.layer"]);
        assert_eq!(ids(&flat.layers[2]), ["b1", "m1"], "no guide paths");
        let guides = &flat.layers[0];
        let original = &scene.layers[1];
        assert_eq!(
            (guides.name.as_str(), guides.pen, guides.depth),
            ("%guides", 1, 0)
        );
        // Groups, ids, styles and path data are those of the original; only
        // the margin moved into the content's transform.
        let mut content = original.content.clone();
        content.transform = scene.page_transform() * content.transform;
        assert_eq!(guides.content, content);
        let mut before = Vec::new();
        scene.layers[1]
            .content
            .visit_paths(scene.page_transform(), &mut |p, t| {
                before.push(t * p.path.clone())
            });
        let mut after = Vec::new();
        guides
            .content
            .visit_paths(flat.page_transform(), &mut |p, t| {
                after.push(t * p.path.clone())
            });
        assert_eq!(before, after, "same place on the sheet");
        // A second flattening changes nothing more.
        assert_eq!(by_pen(&flat).layers[0], flat.layers[0]);
    }

    #[test]
    fn plot_stages_pass_unplotted_layers_through() {
        use crate::plot::{merge, multipass, simplify, sort};
        let flat = by_pen(&scene_with_unplotted());
        let mut staged = flat.clone();
        merge::run(&mut staged, &merge::MergeOptions::DEFAULT);
        simplify::run(&mut staged, &simplify::SimplifyOptions::DEFAULT);
        sort::run(&mut staged, &sort::SortOptions::DEFAULT);
        let mut passes = multipass::MultipassOptions::DEFAULT;
        passes.passes = 3;
        multipass::run(&mut staged, &passes);
        assert_eq!(staged.layers[..2], flat.layers[..2]);
        // …while the plotted layers did change (g2 and g3 would have
        // merged, had the guides been plotted).
        assert_ne!(staged.layers[2], flat.layers[2]);

        let mut guides = flat.layers[0].clone();
        assert!(take_paths(&mut guides).is_empty());
        set_paths(&mut guides, Vec::new());
        assert_eq!(guides, flat.layers[0]);
    }

    #[test]
    fn unplotted_layers_are_set_aside_and_restored_in_place() {
        let scene = scene_with_unplotted();
        let mut s = scene.clone();
        let taken = take_unplotted(&mut s);
        let positions: Vec<usize> = taken.iter().map(|(i, _)| *i).collect();
        assert_eq!(positions, [1, 4]);
        assert!(s.layers.iter().all(Layer::is_plotted));
        assert_eq!(s.layers.len(), 3);
        restore_unplotted(&mut s, taken.into_iter().rev().collect());
        assert_eq!(s, scene);
    }

    #[test]
    fn set_aside_layers_are_neither_hatched_nor_hidden_nor_hide() {
        use crate::plot::{hatch, occlude};
        // A filled `%` frame in front of everything, over pen 1's lines.
        let mut scene = scene_with_unplotted();
        scene.layers[1].depth = -1;
        let run = |s: &mut Scene| {
            hatch::run(s, &hatch::HatchOptions::DEFAULT.with_spacing(2.0)).unwrap();
            occlude::run(s, &occlude::OccludeOptions::DEFAULT).unwrap();
        };
        let mut set_aside = scene.clone();
        let taken = take_unplotted(&mut set_aside);
        run(&mut set_aside);
        restore_unplotted(&mut set_aside, taken);
        assert_eq!(set_aside.layers[1], scene.layers[1], "not hatched");
        assert_eq!(set_aside.layers[4], scene.layers[4]);
        assert_eq!(set_aside.layers[2], scene.layers[2], "nothing hidden");
        assert_eq!(set_aside, scene);
        // Without setting them aside, the frame is hatched and hides the
        // lines behind it.
        let mut all = scene.clone();
        run(&mut all);
        assert_ne!(all.layers[1], scene.layers[1]);
        assert_ne!(all.layers[2], scene.layers[2]);
    }

    #[test]
    fn pen_named_like_an_unplotted_layer_is_still_plotted() {
        let mut scene = test_scene();
        scene.pens[1].name = "%red".into();
        let flat = by_pen(&scene);
        assert_eq!(flat.layers[1].name, "2 %red");
        assert!(flat.layers.iter().all(Layer::is_plotted));
    }

    #[test]
    fn reverse_open_is_exact() {
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.line_to((1.0, 0.0));
        p.quad_to((2.0, 1.0), (3.0, 0.0));
        p.curve_to((4.0, 1.0), (5.0, 2.0), (6.0, 0.0));
        let r = reverse_open(&p);
        let sub = subpaths(&r).next().unwrap();
        assert_eq!(sub.start(), Point::new(6.0, 0.0));
        assert_eq!(sub.end(), Point::new(0.0, 0.0));
        assert_eq!(reverse_open(&r), p);
    }
}
