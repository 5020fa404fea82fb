//! Other tools read moyo's SVG as a plot: every path in it is a line to
//! draw. So the SVG of every template holds exactly what pens draw — no
//! preview fill, no `%` layer — and vpype sees one layer per pen, with the
//! pen's name, colour and width, every path, and the same ink as moyo's
//! own statistics. The colour preview is a separate document.
//!
//! The vpype test runs when `MOYO_VPYPE` names a vpype executable
//! (`tools/test-env.sh` installs one in a virtual environment; see
//! `readers.rs` for what happens without it).

use std::process::Command;

use moyo::plot::stats::{stats, Speeds};
use moyo::project::Rendered;

use crate::rendered;

/// Paths a pen draws: in plotted layers, not fill-only.
fn drawn_paths(scene: &moyo::Scene) -> usize {
    let mut n = 0;
    scene.visit_paths(|layer, p, _| {
        n += usize::from(layer.is_plotted() && !p.style.fill_only);
    });
    n
}

#[test]
fn the_svg_holds_only_what_pens_draw_and_the_preview_the_rest() {
    for (t, r) in rendered::plotted() {
        let name = t.name;
        let svg = &r.svg;
        // Fill-only paths are written `style="fill:…;stroke:none"`, `%`
        // layers with their name as the label.
        assert!(!svg.contains("stroke:none"), "{name}: a fill-only path");
        assert!(!svg.contains("inkscape:label=\"%"), "{name}: a % layer");
        assert_eq!(
            svg.matches("<path ").count(),
            drawn_paths(&r.scene),
            "{name}"
        );
        // The preview has every path of the scene, and the plot's pen
        // layers exactly as they are.
        let preview = r.preview_svg();
        assert_eq!(
            preview.matches("<path ").count(),
            r.scene.path_count(),
            "{name}"
        );
        let pens = |s: &str| s[s.find("<g id=\"pen-").unwrap()..].to_string();
        assert!(pens(svg) == pens(&preview), "{name}: the pen layers differ");
    }
    let (_, kimono_1) = rendered::plotted()
        .iter()
        .find(|(t, _)| t.name == "kimono-1")
        .unwrap();
    let preview = kimono_1.preview_svg();
    assert!(preview.contains("inkscape:label=\"%preview fills\""));
    assert!(preview.matches(FILL_ONLY).count() > 20);
}

/// How a fill-only path's style starts, once its colour is written.
const FILL_ONLY: &str = ";stroke:none";

#[test]
fn vpype_reads_exactly_the_plotted_pens_with_their_ink() {
    let Some(vpype) = crate::readers::reader("MOYO_VPYPE") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    for (t, r) in rendered::plotted() {
        let name = t.name;
        let svg = dir.path().join(format!("{name}.svg"));
        std::fs::write(&svg, &r.svg).unwrap();
        let out = Command::new(&vpype)
            .arg("read")
            .args(["--quantization", QUANTIZATION])
            .arg(&svg)
            .arg("stat")
            .output()
            .expect("vpype runs");
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let stat = String::from_utf8_lossy(&out.stdout);
        check_layers(name, r, &stat);
    }
}

/// vpype's `stat` output for a template against moyo's figures.
fn check_layers(name: &str, rendered: &Rendered, stat: &str) {
    let figures = stats(&rendered.scene, &Speeds::DEFAULT);
    let pens: Vec<_> = figures.layers.iter().filter(|l| l.plotted).collect();
    // Exactly the plotted pens, no other layer.
    let layers = stat.matches("\nLayer ").count() + usize::from(stat.starts_with("Layer "));
    assert_eq!(layers, pens.len(), "{name}: vpype's layers\n{stat}");
    for layer in pens {
        let pen = rendered.scene.pen(layer.pen).expect("a pen of the scene");
        let section = stat
            .split(&format!("Layer {}\n", pen.number))
            .nth(1)
            .unwrap_or_else(|| panic!("{name}: vpype shows no layer {}:\n{stat}", pen.number));
        let section = section.split("\nLayer ").next().unwrap();
        let section = section.split("\nTotals").next().unwrap();
        assert!(
            section.contains(&format!("vp_name: '{} {}'", pen.number, pen.name)),
            "{name}: {section}"
        );
        assert!(
            section.contains(&format!("svg_stroke: '{}'", pen.color)),
            "{name}: {section}"
        );
        let field = |key: &str| -> f64 {
            section
                .lines()
                .find_map(|l| l.trim().strip_prefix(key))
                .unwrap_or_else(|| panic!("{name}: no {key} in {section}"))
                .parse()
                .unwrap()
        };
        // vpype counts every subpath as a path of its own.
        assert_eq!(
            field("Path count: ") as usize,
            layer.pen_lifts,
            "{name}, pen {}",
            pen.number
        );
        // vpype's lengths and widths are in CSS px (96 per inch); it draws
        // curves as polylines, a little shorter than the curves.
        let px = 25.4 / 96.0;
        let ink = field("Length: ") * px;
        eprintln!(
            "INK {name} {} {:.5}",
            pen.number,
            (ink - layer.pen_down_mm) / layer.pen_down_mm
        );
        assert!(
            (ink - layer.pen_down_mm).abs() <= INK_TOLERANCE * layer.pen_down_mm,
            "{name}, pen {}: vpype {ink:.1} mm, moyo {:.1} mm",
            pen.number,
            layer.pen_down_mm
        );
        let width = field("vp_pen_width: ") * px;
        assert!((width - pen.width).abs() < 1e-6, "{name}: {width}");
    }
}

/// Longest segment vpype draws a curve with (its default is 0.1 mm, which
/// shortens the small curls of the flowers by up to 0.7 %).
const QUANTIZATION: &str = "0.02mm";

/// Relative difference allowed between vpype's pen-down length and moyo's:
/// the chords vpype draws a curve with are a little shorter than the
/// curve. Measured on the templates at [`QUANTIZATION`]: at most 0.023 %
/// (kimono-3, pen 1). Outlines drawn twice, as preview fills read as lines
/// once made vpype do, cost 5–39 % more.
const INK_TOLERANCE: f64 = 0.001;
