//! The scene graph: page → layers → groups → paths.
//!
//! Generators build [`Group`]s of [`StyledPath`]s (each a `kurbo::BezPath`);
//! the plot pipeline and the writers only read them. A [`Layer`] carries both
//! meanings of "layer" in docs/SPEC.md §0: its `depth` (what is in front of what) and
//! its `pen` (which physical pen draws it). Ids are stable: they are made from
//! names and indices in the scene description, never from memory addresses or
//! hash order, so they are the same on every run.

mod budget;
mod codes;
mod color;
pub(crate) mod embed;
mod model;
pub mod traditional;
mod unique;

pub use budget::PathBudget;
pub use codes::LayerCodes;
pub use color::Color;
pub use embed::embedded_description;
pub use model::{Model, ModelPart};
pub(crate) use unique::UniqueIds;

use kurbo::{Affine, BezPath, PathEl, Point, Rect, Shape};

use crate::units::Page;

/// A physical pen (or cutter tool): one SVG layer per pen.
#[derive(Debug, Clone, PartialEq)]
pub struct Pen {
    /// The pen number, also the leading number of the SVG layer label.
    pub number: u32,
    /// A short name, e.g. `black`.
    pub name: String,
    /// Preview colour.
    pub color: Color,
    /// Line width in mm (for the preview and as the SVG stroke width).
    pub width: f64,
}

impl Pen {
    /// Width of a pen a scene uses but does not list, mm: its paths are
    /// still written (dropping drawing silently would be worse), in black
    /// at a common fineliner width.
    pub const FALLBACK_WIDTH: f64 = 0.3;
}

/// How a path is painted.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Style {
    /// Fill colour; `None` draws the outline only (the plotter default).
    pub fill: Option<Color>,
    /// Hatch spacing (mm) of this path's fill, overriding the hatch
    /// stage's; a path with it is hatched even when the scene's plot
    /// options ask for no hatching ([`crate::plot::hatch`]).
    pub hatch: Option<f64>,
    /// Only the fill is painted, no stroke: the preview colour of what
    /// stays visible of a filled shape that hidden-line removal cut
    /// ([`crate::plot::occlude`]), or an imported shape whose stroke the
    /// SVG makes invisible ([`crate::input::import_svg`]). A pen has
    /// nothing to draw here, so the plot outputs (per-pen stages, G-code,
    /// HPGL, stats) leave it out; the area still hides what lies behind
    /// it in hidden-line removal.
    pub fill_only: bool,
    /// The edge of this [fill-only](Style::fill_only) paint is drawn by
    /// other line work of the same pen (a zentangle's black part, whose
    /// every edge is the line of a mark): hatching keeps as clear of the
    /// edge as it keeps of a drawn outline ([`crate::plot::hatch`]), where
    /// paint with no line at its edge is hatched right up to it.
    pub edge_drawn: bool,
    /// Never drawn, by a pen or in the preview: the area the path encloses
    /// (non-zero) only hides what lies behind it in hidden-line removal
    /// ([`crate::plot::occlude`]), for a solid shape that its generator
    /// drew as open pieces (a vine seen through a camera, its own hidden
    /// lines already removed). The plot stages drop it once it has done
    /// that.
    pub mask: bool,
}

impl Style {
    /// Whether a pen draws the path: neither preview colour
    /// ([`Style::fill_only`]) nor a [`Style::mask`].
    pub fn is_drawn(&self) -> bool {
        !self.fill_only && !self.mask
    }
}

/// A path with its style and stable id.
#[derive(Debug, Clone, PartialEq)]
pub struct StyledPath {
    /// Stable id, unique within the scene.
    pub id: String,
    /// The geometry, in the coordinates of the enclosing group.
    pub path: BezPath,
    /// Paint.
    pub style: Style,
}

/// A node of a group: another group or a path.
#[derive(Debug, Clone, PartialEq)]
pub enum Node {
    /// A nested group.
    Group(Group),
    /// A leaf path.
    Path(StyledPath),
}

/// A group of nodes sharing an affine transform.
#[derive(Debug, Clone, PartialEq)]
pub struct Group {
    /// Stable id, unique within the scene.
    pub id: String,
    /// Maps the group's coordinates to its parent's.
    pub transform: Affine,
    /// Children in paint order (first is painted first, i.e. behind).
    pub children: Vec<Node>,
    /// The group's closed paths are parts of one solid shape (the limbs of
    /// a tree): hidden-line removal with silhouettes merges them into one
    /// outline ([`crate::plot::occlude`]). Motifs and imported groups are
    /// not solid.
    pub solid: bool,
}

impl Group {
    /// An empty group with the identity transform.
    pub fn new(id: impl Into<String>) -> Group {
        Group {
            id: id.into(),
            transform: Affine::IDENTITY,
            children: Vec::new(),
            solid: false,
        }
    }

    /// An empty solid group (see [`Group::solid`]).
    pub fn solid(id: impl Into<String>) -> Group {
        Group {
            solid: true,
            ..Group::new(id)
        }
    }

    /// Appends a path.
    pub fn push_path(&mut self, id: impl Into<String>, path: BezPath, style: Style) {
        self.children.push(Node::Path(StyledPath {
            id: id.into(),
            path,
            style,
        }));
    }

    /// Appends a child group.
    pub fn push_group(&mut self, group: Group) {
        self.children.push(Node::Group(group));
    }

    /// Number of segments (lines and curves) in all paths below this group.
    pub fn segment_count(&self) -> usize {
        let mut n = 0;
        self.visit_paths(Affine::IDENTITY, &mut |p, _| {
            n += p
                .path
                .elements()
                .iter()
                .filter(|e| !matches!(e, kurbo::PathEl::MoveTo(_)))
                .count();
        });
        n
    }

    /// Calls `f` for every path below this group with its transform to the
    /// coordinates of `outer` (the transform of everything above the group).
    pub fn visit_paths<'a>(&'a self, outer: Affine, f: &mut impl FnMut(&'a StyledPath, Affine)) {
        let here = outer * self.transform;
        for child in &self.children {
            match child {
                Node::Group(g) => g.visit_paths(here, f),
                Node::Path(p) => f(p, here),
            }
        }
    }
}

/// One depth layer of the scene, drawn with one pen.
#[derive(Debug, Clone, PartialEq)]
pub struct Layer {
    /// Stable id.
    pub id: String,
    /// Human name.
    pub name: String,
    /// Pen number (see [`Scene::pens`]).
    pub pen: u32,
    /// 0 is the frontmost; larger is further back.
    pub depth: i32,
    /// The content, in page coordinates of the drawable area.
    pub content: Group,
}

impl Layer {
    /// The first character of the name of a layer that is not plotted:
    /// AxiDraw's *documentation layer* (`%guides`, `% sketch`).
    pub const NOT_PLOTTED_PREFIX: char = '%';

    /// Whether the plotter draws this layer: false for a documentation
    /// layer, one whose name starts with [`Layer::NOT_PLOTTED_PREFIX`]
    /// after any leading whitespace (see [`Layer::name_is_plotted`]).
    ///
    /// Such a layer is reference material kept in the drawing (guides, a
    /// sketch, notes): the SVG writer keeps it as an Inkscape layer with
    /// its name as the label (AxiDraw skips it), the PNG preview shows it,
    /// G-code and HPGL leave it out, the plot stages pass it through
    /// unchanged, and plot statistics list it without counting it.
    pub fn is_plotted(&self) -> bool {
        Layer::name_is_plotted(&self.name)
    }

    /// Whether a layer named `name` is plotted: false when its first
    /// non-whitespace character is [`Layer::NOT_PLOTTED_PREFIX`], as in
    /// AxiDraw's layer control (`"%guides"`, `"  % 2 notes"`); true
    /// otherwise (`"1 black"`, `"guides %"`, `""`).
    pub fn name_is_plotted(name: &str) -> bool {
        !name.trim_start().starts_with(Layer::NOT_PLOTTED_PREFIX)
    }
}

/// A whole drawing.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Paper, margins.
    pub page: Page,
    /// Pens, in ascending pen number.
    pub pens: Vec<Pen>,
    /// Layers in the order of the scene description.
    pub layers: Vec<Layer>,
    /// The scene description that produced this scene, embedded in the SVG
    /// so that the drawing can be reopened.
    pub description: Option<String>,
}

/// Size figures of a scene or layer.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Stats {
    /// Number of paths a pen draws (fill-only paths are not counted).
    pub paths: usize,
    /// Total length drawn with the pen down, in mm.
    pub pen_down_mm: f64,
}

impl Scene {
    /// One layer (id and name `l`) drawn by one black 0.3 mm pen on
    /// `page`: what most unit tests start from.
    #[cfg(test)]
    pub(crate) fn one_pen(page: crate::units::Page, content: Group) -> Scene {
        Scene {
            page,
            pens: vec![Pen {
                number: 1,
                name: "black".into(),
                color: Color::BLACK,
                width: 0.3,
            }],
            layers: vec![Layer {
                id: "l".into(),
                name: "l".into(),
                pen: 1,
                depth: 0,
                content,
            }],
            description: None,
        }
    }

    /// The transform from drawable-area coordinates to page coordinates.
    pub fn page_transform(&self) -> Affine {
        Affine::translate((self.page.margins.left, self.page.margins.top))
    }

    /// Layers in paint order: back (largest depth) first. Layers of equal
    /// depth keep their order in the description.
    pub fn layers_back_to_front(&self) -> Vec<&Layer> {
        let mut v: Vec<&Layer> = self.layers.iter().collect();
        v.sort_by_key(|l| std::cmp::Reverse(l.depth));
        v
    }

    /// The pen with this number.
    pub fn pen(&self, number: u32) -> Option<&Pen> {
        // Pens are kept in ascending number, so a lookup is a binary search
        // (every plot stage asks once per layer: 100,000 pens must not
        // cost 10¹⁰ comparisons); a list someone left unsorted is still
        // searched whole.
        match self.pens.binary_search_by_key(&number, |p| p.number) {
            Ok(i) => Some(&self.pens[i]),
            Err(_) => self.pens.iter().find(|p| p.number == number),
        }
    }

    /// `layers` grouped by pen: pens in ascending number, each with its
    /// layers in the order given. One pass, whatever the number of pens.
    pub(crate) fn layers_by_pen<'a>(
        layers: impl IntoIterator<Item = &'a Layer>,
    ) -> std::collections::BTreeMap<u32, Vec<&'a Layer>> {
        let mut by_pen = std::collections::BTreeMap::<u32, Vec<&'a Layer>>::new();
        for layer in layers {
            by_pen.entry(layer.pen).or_default().push(layer);
        }
        by_pen
    }

    /// Width of the pen with this number, mm; [`Pen::FALLBACK_WIDTH`] when
    /// the scene does not list it.
    pub fn pen_width(&self, number: u32) -> f64 {
        self.pen(number).map_or(Pen::FALLBACK_WIDTH, |p| p.width)
    }

    /// Calls `f` for every path with its transform to page coordinates.
    pub fn visit_paths<'a>(&'a self, mut f: impl FnMut(&'a Layer, &'a StyledPath, Affine)) {
        let page = self.page_transform();
        for layer in &self.layers {
            layer.content.visit_paths(page, &mut |p, t| f(layer, p, t));
        }
    }

    /// Bounding box of all paths in page coordinates, `None` for an empty
    /// scene.
    pub fn bounds(&self) -> Option<Rect> {
        let mut acc: Option<Rect> = None;
        self.visit_paths(|_, p, t| {
            if p.path.elements().is_empty() {
                return;
            }
            let b = (t * p.path.clone()).bounding_box();
            acc = Some(acc.map_or(b, |a| a.union(b)));
        });
        acc
    }

    /// Number of paths.
    pub fn path_count(&self) -> usize {
        let mut n = 0;
        self.visit_paths(|_, _, _| n += 1);
        n
    }

    /// Path count and pen-down length of the whole scene.
    pub fn stats(&self) -> Stats {
        self.stats_where(|_| true)
    }

    /// Path count and pen-down length of the layers drawn with one pen.
    pub fn pen_stats(&self, pen: u32) -> Stats {
        self.stats_where(|l| l.pen == pen)
    }

    /// [`Scene::stats`] of the scene as an SVG with `precision` decimals
    /// holds it: each path's coordinates rounded where they are written,
    /// in its group (the groups' transforms are written exactly).
    pub fn stats_at_precision(&self, precision: u8) -> Stats {
        let scale = 10f64.powi(i32::from(precision));
        let round =
            |p: Point| Point::new((p.x * scale).round() / scale, (p.y * scale).round() / scale);
        let mut s = Stats::default();
        self.visit_paths(|layer, p, t| {
            if layer.is_plotted() && p.style.is_drawn() {
                let mut path = p.path.clone();
                for el in path.elements_mut() {
                    *el = match *el {
                        PathEl::MoveTo(a) => PathEl::MoveTo(round(a)),
                        PathEl::LineTo(a) => PathEl::LineTo(round(a)),
                        PathEl::QuadTo(a, b) => PathEl::QuadTo(round(a), round(b)),
                        PathEl::CurveTo(a, b, c) => PathEl::CurveTo(round(a), round(b), round(c)),
                        PathEl::ClosePath => PathEl::ClosePath,
                    };
                }
                s.paths += 1;
                s.pen_down_mm += crate::geom::path_length(&(t * path));
            }
        });
        s
    }

    fn stats_where(&self, keep: impl Fn(&Layer) -> bool) -> Stats {
        let mut s = Stats::default();
        self.visit_paths(|layer, p, t| {
            // Fill-only paths are preview colour and masks hide only; no
            // pen draws them.
            if keep(layer) && p.style.is_drawn() {
                s.paths += 1;
                s.pen_down_mm += crate::geom::path_length(&(t * p.path.clone()));
            }
        });
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::{Margins, Orientation, PaperName};
    use kurbo::Line;

    fn scene_with_two_lines() -> Scene {
        let mut g = Group::new("g");
        g.push_path(
            "a",
            Line::new((0.0, 0.0), (30.0, 40.0)).into_path(0.1),
            Style::default(),
        );
        let mut inner = Group::new("inner");
        inner.transform = Affine::translate((100.0, 0.0)) * Affine::scale(2.0);
        inner.push_path(
            "b",
            Line::new((0.0, 0.0), (10.0, 0.0)).into_path(0.1),
            Style::default(),
        );
        g.push_group(inner);
        Scene::one_pen(
            Page::named(PaperName::A4, Orientation::Portrait, Margins::uniform(10.0)),
            g,
        )
    }

    #[test]
    fn queries_apply_nested_transforms_and_margins() {
        let s = scene_with_two_lines();
        assert_eq!(s.path_count(), 2);
        let st = s.stats();
        assert!((st.pen_down_mm - (50.0 + 20.0)).abs() < 1e-6);
        let b = s.bounds().unwrap();
        assert_eq!(b, Rect::new(10.0, 10.0, 130.0, 50.0));
    }

    #[test]
    fn back_to_front_sorts_by_depth_stably() {
        let mut s = scene_with_two_lines();
        let mut l2 = s.layers[0].clone();
        l2.id = "back".into();
        l2.depth = 3;
        let mut l3 = s.layers[0].clone();
        l3.id = "front2".into();
        s.layers.push(l2);
        s.layers.push(l3);
        let order: Vec<&str> = s
            .layers_back_to_front()
            .iter()
            .map(|l| l.id.as_str())
            .collect();
        assert_eq!(order, ["back", "l", "front2"]);
    }
}
