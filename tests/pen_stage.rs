//! The pen stage on every built-in template: what a render writes is what
//! the design draws, with no line drawn twice, no debris and little
//! travel — and the same ink on the paper.
//!
//! Ink is measured as a pen lays it down: every path of a pen stroked at
//! that pen's width with round caps and joins, without anti-aliasing (a
//! pixel is ink or paper, so a line drawn twice covers what it covers
//! once), at [`PX_PER_MM`]; the ink of a plot is the sum over its pens.

use moyo::plot::{self, flatten, PlotOptions, Speeds};
use moyo::project;
use moyo::spec::{Format, SceneSpec, ValidSpec};
use moyo::{templates, Scene};
use resvg::tiny_skia::{
    FillRule, LineCap, LineJoin, Paint, PathBuilder, Pixmap, Stroke, Transform,
};

use crate::rendered;

/// Resolution of the ink pictures: a 0.25 mm pen is 3 pixels wide.
const PX_PER_MM: f64 = 12.0;

/// How much the ink may change, as a share of the ink before.
const MAX_INK_CHANGE: f64 = 0.005;

/// The most ink any square millimetre of a template may hold, in multiples
/// of what covers it solid for its pen.
const MAX_DENSEST: f64 = 2.0;

/// Pixels of ink each pen of `scene` puts down, summed over the pens.
fn ink(scene: &Scene) -> u64 {
    let flat = flatten::by_pen(scene);
    let w = (flat.page.width * PX_PER_MM).ceil() as u32;
    let h = (flat.page.height * PX_PER_MM).ceil() as u32;
    let mut total = 0;
    for layer in flat.layers.iter().filter(|l| l.is_plotted()) {
        let mut pixmap = Pixmap::new(w, h).expect("a page-sized picture");
        let mut paint = Paint::default();
        paint.set_color_rgba8(0, 0, 0, 255);
        paint.anti_alias = false;
        let stroke = Stroke {
            width: (flat.pen_width(layer.pen) * PX_PER_MM) as f32,
            line_cap: LineCap::Round,
            line_join: LineJoin::Round,
            ..Stroke::default()
        };
        let scale = Transform::from_scale(PX_PER_MM as f32, PX_PER_MM as f32);
        layer
            .content
            .visit_paths(kurbo::Affine::IDENTITY, &mut |p, t| {
                let mut b = PathBuilder::new();
                let mut dot = None;
                for el in (t * p.path.clone()).elements() {
                    match *el {
                        kurbo::PathEl::MoveTo(q) => {
                            b.move_to(q.x as f32, q.y as f32);
                            dot = Some(q);
                        }
                        kurbo::PathEl::LineTo(q) => b.line_to(q.x as f32, q.y as f32),
                        kurbo::PathEl::QuadTo(c, q) => {
                            b.quad_to(c.x as f32, c.y as f32, q.x as f32, q.y as f32)
                        }
                        kurbo::PathEl::CurveTo(c, d, q) => b.cubic_to(
                            c.x as f32, c.y as f32, d.x as f32, d.y as f32, q.x as f32, q.y as f32,
                        ),
                        kurbo::PathEl::ClosePath => b.close(),
                    }
                }
                match b.finish() {
                    Some(path) => pixmap.stroke_path(&path, &paint, &stroke, scale, None),
                    // A tap: the pen's round dot.
                    None => {
                        if let Some(q) = dot {
                            let r = stroke.width / 2.0;
                            let (x, y) = ((q.x * PX_PER_MM) as f32, (q.y * PX_PER_MM) as f32);
                            if let Some(circle) = PathBuilder::from_circle(x, y, r) {
                                pixmap.fill_path(
                                    &circle,
                                    &paint,
                                    FillRule::Winding,
                                    Transform::identity(),
                                    None,
                                );
                            }
                        }
                    }
                }
            });
        total += pixmap.pixels().iter().filter(|p| p.alpha() > 0).count() as u64;
    }
    total
}

fn spec(name: &str) -> ValidSpec {
    let t = templates::get(name).unwrap();
    SceneSpec::parse(t.text, Format::Toml).unwrap()
}

/// Every template: the pen stage keeps the ink within half a percent,
/// leaves at most half a percent of the line drawn twice and of the
/// strokes debris, no square millimetre past twice solid ink, and travels
/// no more than 5 % more than `moyo plot --merge --sort` would leave of
/// what it writes.
#[test]
fn the_pen_stage_keeps_the_ink_and_takes_out_what_a_pen_should_not_draw() {
    let mut failures = Vec::new();
    for (t, editing) in rendered::for_editing() {
        let spec = spec(t.name);
        let plotted = editing.pen_ready(&spec).unwrap();
        let (before, after) = (ink(&editing.scene), ink(&plotted.scene));
        let change = (after as f64 - before as f64) / before.max(1) as f64;
        if change.abs() > MAX_INK_CHANGE {
            failures.push(format!(
                "{}: ink {before} → {after} px ({:+.2} %)",
                t.name,
                100.0 * change
            ));
        }
        let figures = plot::stats(&plotted.scene, &Speeds::DEFAULT);
        if figures.doubled_mm > 0.005 * figures.pen_down_mm {
            failures.push(format!(
                "{}: {:.1} of {:.1} mm drawn twice",
                t.name, figures.doubled_mm, figures.pen_down_mm
            ));
        }
        if figures.densest > MAX_DENSEST {
            failures.push(format!(
                "{}: a square millimetre holds {:.3}× solid ink",
                t.name, figures.densest
            ));
        }
        if figures.debris as f64 > 0.005 * figures.pen_lifts as f64 {
            failures.push(format!(
                "{}: {} debris of {} strokes",
                t.name, figures.debris, figures.pen_lifts
            ));
        }
        let sorted = plot::run(
            plotted.scene.clone(),
            &PlotOptions {
                merge: Some(plot::MergeOptions::DEFAULT),
                sort: Some(plot::SortOptions::DEFAULT),
                ..PlotOptions::default()
            },
        )
        .unwrap();
        let reference = plot::stats(&sorted, &Speeds::DEFAULT).pen_up_mm;
        if figures.pen_up_mm > 1.05 * reference + 1.0 {
            failures.push(format!(
                "{}: {:.0} mm pen-up, {:.0} sorted again",
                t.name, figures.pen_up_mm, reference
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A render is the editing render with the pen stage run on it, byte for
/// byte: what the studio saves is what `moyo render` writes.
#[test]
fn a_render_is_the_editing_render_made_pen_ready() {
    let spec = spec("kimono-2");
    let library = templates::get("kimono-2").unwrap().library().unwrap();
    let cancel = &project::Cancel::default();
    let editing = project::render_for_editing(&spec, &library, &mut |_| {}, cancel).unwrap();
    let rendered = project::render_cancellable(&spec, &library, &mut |_| {}, cancel).unwrap();
    assert_eq!(editing.pen_ready(&spec).unwrap().svg, rendered.svg);
    // The editing render keeps the description's layers and the tables'
    // groups; the plot has one layer per pen.
    assert!(editing.svg.contains("id=\"front.motifs\""), "groups kept");
    assert!(!rendered.svg.contains("id=\"front.motifs\""));
}

/// A description can turn the pen stage's steps off one by one.
#[test]
fn the_pen_stage_can_be_turned_off() {
    let text = templates::get("lsystem-plant-f").unwrap().text;
    let off =
        format!("{text}\n[plot]\ndedupe = false\nmerge = false\ndebris = false\nsort = false\n");
    let on = project::render(&SceneSpec::parse(text, Format::Toml).unwrap()).unwrap();
    let off = project::render(&SceneSpec::parse(&off, Format::Toml).unwrap()).unwrap();
    let length = |r: &project::Rendered| plot::stats(&r.scene, &Speeds::DEFAULT);
    let (on, off) = (length(&on), length(&off));
    // lsystem-plant-f starts a branch on top of its stem: a third of its
    // line is drawn twice unless the pen stage takes it out.
    assert!(off.doubled_mm > 0.3 * off.pen_down_mm, "{off:?}");
    assert!(on.doubled_mm < 0.005 * on.pen_down_mm, "{on:?}");
    assert!(on.pen_down_mm < 0.7 * off.pen_down_mm);
}

/// No template draws past its page's margins — what `moyo render` warns
/// of, since plotters clip or crash at the page edge (`kimono-vine` once
/// overran its own margin): a newcomer's first renders print no warning.
#[test]
fn no_template_draws_past_its_margins() {
    let slack = 0.01;
    let past: Vec<String> = rendered::plotted()
        .iter()
        .filter_map(|(t, r)| {
            let b = r.scene.bounds()?;
            let area = r.scene.page.drawable();
            let inside = b.x0 >= area.x0 - slack
                && b.y0 >= area.y0 - slack
                && b.x1 <= area.x1 + slack
                && b.y1 <= area.y1 + slack;
            (!inside).then(|| format!("{}: drawing {b:?}, margins {area:?}", t.name))
        })
        .collect();
    assert!(past.is_empty(), "{}", past.join("\n"));
}
