//! Multipass: draw every path several times, for darker lines or for a
//! cutter that needs several passes through thick material.
//!
//! Each subpath is repeated in place without lifting the pen: a closed
//! subpath ([`Subpath::is_closed`]) goes round its loop
//! [`MultipassOptions::passes`] times (with one close-path at the end if it
//! had one); an open one is drawn forwards, then backwards,
//! then forwards again, and so on, so every pass starts where the previous
//! one ended. Pen-down length is multiplied by the number of passes; paths,
//! ids and pen-up travel are unchanged. Works on any layer, in the
//! coordinates of the flat scene (see [`super::flatten`]).
//!
//! [`Subpath::is_closed`]: crate::geom::subpath::Subpath::is_closed

use kurbo::{BezPath, PathEl};
use serde::{Deserialize, Serialize};

use super::flatten::{el_end, reverse_open, set_paths, take_paths};
use crate::geom::subpath::subpaths;
use crate::scene::Scene;

/// Options of [`run`] and [`repeat_path`].
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MultipassOptions {
    /// How many times each path is drawn; 0 and 1 leave paths unchanged.
    pub passes: u32,
}

impl MultipassOptions {
    /// One pass: nothing changes. Ask for more with
    /// [`MultipassOptions::with_passes`].
    pub const DEFAULT: MultipassOptions = MultipassOptions { passes: 1 };

    /// These options with [`MultipassOptions::passes`] set.
    pub const fn with_passes(mut self, passes: u32) -> MultipassOptions {
        self.passes = passes;
        self
    }
}

impl Default for MultipassOptions {
    fn default() -> MultipassOptions {
        MultipassOptions::DEFAULT
    }
}

/// Repeats every path of every layer of `scene` (see the module
/// documentation).
pub fn run(scene: &mut Scene, options: &MultipassOptions) {
    if options.passes <= 1 {
        return;
    }
    for layer in &mut scene.layers {
        let mut paths = take_paths(layer);
        for p in &mut paths {
            p.path = repeat_path(&p.path, options);
        }
        set_paths(layer, paths);
    }
}

/// `path` with each subpath drawn `options.passes` times.
pub fn repeat_path(path: &BezPath, options: &MultipassOptions) -> BezPath {
    let passes = options.passes.max(1) as usize;
    if passes == 1 {
        return path.clone();
    }
    let mut out: Vec<PathEl> = Vec::with_capacity(path.elements().len() * passes);
    for sub in subpaths(path) {
        if sub.is_closed() {
            // Round the loop: the closing line made explicit for all passes
            // but the last, and a close-path at the end if it had one.
            let start = sub.start();
            let body = sub.drawn();
            let ends_at_start = !matches!(body.last(), Some(el) if el_end(*el) != start);
            out.push(PathEl::MoveTo(start));
            for pass in 0..passes {
                out.extend_from_slice(body);
                if pass + 1 < passes && !ends_at_start {
                    out.push(PathEl::LineTo(start));
                }
            }
            if sub.ends_with_close() {
                out.push(PathEl::ClosePath);
            }
        } else {
            let sub = sub.to_path();
            let back = reverse_open(&sub);
            out.extend_from_slice(sub.elements());
            for pass in 1..passes {
                let next = if pass % 2 == 1 { &back } else { &sub };
                out.extend_from_slice(&next.elements()[1..]);
            }
        }
    }
    BezPath::from_vec(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::path_length;
    use crate::plot::stats::pen_up_length;
    use kurbo::{Circle, Point, Shape};

    fn twice() -> MultipassOptions {
        MultipassOptions::DEFAULT.with_passes(2)
    }

    #[test]
    fn open_paths_go_back_and_forth() {
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.line_to((10.0, 0.0));
        p.curve_to((12.0, 2.0), (12.0, 4.0), (10.0, 6.0));
        let r = repeat_path(&p, &MultipassOptions::DEFAULT.with_passes(3));
        assert!((path_length(&r) - 3.0 * path_length(&p)).abs() < 1e-6);
        assert_eq!(r.elements().len(), 1 + 3 * 2);
        assert_eq!(subpaths(&r).next().unwrap().end(), Point::new(10.0, 6.0));
        assert_eq!(
            r.elements()[3],
            PathEl::CurveTo((12.0, 4.0).into(), (12.0, 2.0).into(), (10.0, 0.0).into())
        );
        assert_eq!(pen_up_length([&r]), pen_up_length([&p]));
    }

    #[test]
    fn closed_paths_loop_and_length_doubles() {
        let circle = Circle::new((50.0, 50.0), 10.0).to_path(1e-3);
        let r = repeat_path(&circle, &twice());
        assert!((path_length(&r) - 2.0 * path_length(&circle)).abs() < 1e-6);
        assert_eq!(subpaths(&r).count(), 1);
        let mut tri = BezPath::new();
        tri.move_to((0.0, 0.0));
        tri.line_to((3.0, 0.0));
        tri.line_to((3.0, 4.0));
        tri.close_path();
        let r = repeat_path(&tri, &twice());
        assert!((path_length(&r) - 24.0).abs() < 1e-12);
        // Back at its start without a close-path: round again, no
        // close-path added.
        let mut back = BezPath::new();
        back.move_to((0.0, 0.0));
        back.line_to((3.0, 0.0));
        back.line_to((3.0, 4.0));
        back.line_to((0.0, 0.0));
        let r = repeat_path(&back, &twice());
        assert_eq!(r.elements().len(), 7);
        assert_eq!(r.elements()[4], PathEl::LineTo((3.0, 0.0).into()));
        assert!((path_length(&r) - 24.0).abs() < 1e-12);
    }

    #[test]
    fn one_pass_and_zero_passes_change_nothing() {
        let circle = Circle::new((5.0, 5.0), 1.0).to_path(1e-3);
        assert_eq!(repeat_path(&circle, &MultipassOptions::DEFAULT), circle);
        assert_eq!(
            repeat_path(&circle, &MultipassOptions::DEFAULT.with_passes(0)),
            circle
        );
    }

    #[test]
    fn run_doubles_scene_length() {
        use crate::scene::{Group, Layer, Scene, Style};
        use crate::units::{Margins, Orientation, Page, PaperName};
        let mut g = Group::new("g");
        g.push_path(
            "c",
            Circle::new((5.0, 5.0), 1.0).to_path(1e-3),
            Style::default(),
        );
        let mut two = BezPath::new();
        two.move_to((0.0, 0.0));
        two.line_to((1.0, 0.0));
        two.move_to((5.0, 0.0));
        two.line_to((5.0, 1.0));
        g.push_path("two", two, Style::default());
        let mut scene = Scene {
            page: Page::named(PaperName::A5, Orientation::Portrait, Margins::default()),
            pens: vec![],
            layers: vec![Layer {
                id: "l".into(),
                name: "l".into(),
                pen: 1,
                depth: 0,
                content: g,
            }],
            description: None,
        };
        let before = scene.stats();
        run(&mut scene, &twice());
        let after = scene.stats();
        assert_eq!(after.paths, before.paths);
        assert!((after.pen_down_mm - 2.0 * before.pen_down_mm).abs() < 1e-6);
    }
}
