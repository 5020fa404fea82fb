//! Other tools read moyo's SVG: vpype must see one layer per pen, with the
//! pen's name, colour and width, and every path.
//!
//! Runs when `MOYO_VPYPE` names a vpype executable (`.ci/run` installs one
//! in a virtual environment). Without it the test says so and passes,
//! unless `CI` is set, where a missing vpype is a failure.

use std::process::Command;

#[test]
fn vpype_reads_one_layer_per_pen_with_every_path() {
    let Some(vpype) = std::env::var_os("MOYO_VPYPE") else {
        assert!(
            std::env::var_os("CI").is_none(),
            "MOYO_VPYPE is not set in CI; .ci/run installs vpype"
        );
        eprintln!("skipped: set MOYO_VPYPE to a vpype executable to run this test");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("hem.svg");
    // vpype does not know AxiDraw's `%` layers: it would read the preview
    // fills into layer 1. Plotting through vpype means turning them off.
    let spec = moyo::templates::get(moyo::templates::DEFAULT)
        .unwrap()
        .spec()
        .unwrap()
        .edit(|s| {
            if let Some(o) = s.plot.occlude.as_mut() {
                o.preview_fills = false;
            }
        })
        .unwrap();
    let rendered = moyo::project::render(&spec).unwrap();
    std::fs::write(&svg, &rendered.svg).unwrap();

    let out = Command::new(vpype)
        .arg("read")
        .arg(&svg)
        .arg("stat")
        .output()
        .expect("vpype runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stat = String::from_utf8_lossy(&out.stdout);

    let mut total = 0;
    for pen in &rendered.scene.pens {
        let section = stat
            .split(&format!("Layer {}\n", pen.number))
            .nth(1)
            .unwrap_or_else(|| panic!("vpype shows no layer {}:\n{stat}", pen.number));
        let section = section.split("\nLayer ").next().unwrap();
        assert!(
            section.contains(&format!("vp_name: '{} {}'", pen.number, pen.name)),
            "{section}"
        );
        assert!(
            section.contains(&format!("svg_stroke: '{}'", pen.color)),
            "{section}"
        );
        let count: usize = section
            .lines()
            .find_map(|l| l.trim().strip_prefix("Path count: "))
            .expect("path count")
            .parse()
            .unwrap();
        // vpype counts every subpath as a path of its own.
        assert_eq!(count, subpaths(&rendered.scene, Some(pen.number)));
        total += count;
        // vpype's pen width is in CSS px (96 per inch).
        let width: f64 = section
            .lines()
            .find_map(|l| l.trim().strip_prefix("vp_pen_width: "))
            .expect("pen width")
            .parse()
            .unwrap();
        assert!((width * 25.4 / 96.0 - pen.width).abs() < 1e-6, "{width}");
    }
    assert_eq!(total, subpaths(&rendered.scene, None));
}

/// Subpaths drawn with `pen` (all pens for `None`); `%` layers (the
/// preview fills) are not plotted, and vpype leaves them out too.
fn subpaths(scene: &moyo::Scene, pen: Option<u32>) -> usize {
    let mut n = 0;
    scene.visit_paths(|layer, p, _| {
        if layer.is_plotted() && pen.is_none_or(|pen| layer.pen == pen) {
            n += p
                .path
                .elements()
                .iter()
                .filter(|e| matches!(e, kurbo::PathEl::MoveTo(_)))
                .count();
        }
    });
    n
}
