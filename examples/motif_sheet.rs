//! Draws every built-in motif (flowers, leaves, tiles) on one A4 sheet with
//! the library API, plainly and with jitter, and writes the SVG and a PNG
//! preview: `cargo run --example motif_sheet -- OUT.svg OUT.png`
//! (default `motifs.svg` and `motifs.png`).

// `unused_crate_dependencies` (Cargo.toml) is for the library: an example uses the library, not each of its dependencies.
#![allow(unused_crate_dependencies)]

use kurbo::Affine;
use moyo::motif::{draw, MotifParams};
use moyo::output::{render_png, to_svg, write_atomic, SvgOptions};
use moyo::spec::MotifKind;
use moyo::{Color, Group, Layer, Margins, Orientation, Page, PaperName, Pen, Scene, Seed, Style};

fn main() -> Result<(), moyo::Error> {
    let mut args = std::env::args().skip(1);
    let svg_path = args.next().unwrap_or_else(|| "motifs.svg".into());
    let png_path = args.next().unwrap_or_else(|| "motifs.png".into());

    let fill = Style {
        fill: Some(Color::rgb(0xf3, 0xd6, 0xdc)),
        ..Style::default()
    };
    let mut sheet = Group::new("sheet");
    // Row 1: every motif at its defaults; row 2: the same with jitter 0.4,
    // each from its own stream.
    for (row, jitter) in [0.0, 0.4].into_iter().enumerate() {
        for (i, kind) in MotifKind::ALL.into_iter().enumerate() {
            let mut rng = Seed(7).derive(&format!("{kind:?}/{row}")).stream();
            let params = MotifParams {
                petals: None,
                jitter,
            };
            let d = draw(kind, &params, &mut rng);
            let (col, line) = (i % 7, i / 7 + 2 * row);
            let width = 24.0 / d.aspect.max(1.0);
            let at = Affine::translate((20.0 + 38.0 * col as f64, 22.0 + 44.0 * line as f64))
                * Affine::scale_non_uniform(width, width * d.aspect);
            sheet.push_path(
                format!("{kind:?}-{row}").to_lowercase(),
                d.to_path(at),
                fill.clone(),
            );
        }
    }
    let scene = Scene {
        page: Page::named(
            PaperName::A4,
            Orientation::Landscape,
            Margins::uniform(10.0),
        ),
        pens: vec![Pen {
            number: 1,
            name: "sumi".into(),
            color: Color::rgb(0x1d, 0x1d, 0x1f),
            width: 0.25,
        }],
        layers: vec![Layer {
            id: "motifs".into(),
            name: "motifs".into(),
            pen: 1,
            depth: 0,
            content: sheet,
        }],
        description: None,
    };
    let svg = to_svg(&scene, &SvgOptions::DEFAULT);
    let png = render_png(&svg, 100.0)?;
    write_atomic(svg_path.as_ref(), svg.as_bytes())?;
    write_atomic(png_path.as_ref(), &png)?;
    eprintln!("wrote {svg_path} and {png_path}");
    Ok(())
}
