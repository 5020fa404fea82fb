use super::*;
use crate::rng::Seed;

#[test]
fn every_motif_fits_its_box() {
    for kind in MotifKind::ALL {
        let d = draw(kind, &MotifParams::DEFAULT, &mut Seed(1).stream());
        let b = d.outline.bounding_box();
        assert!(b.x0 >= -0.5 - 1e-6 && b.x1 <= 0.5 + 1e-6, "{kind:?} {b:?}");
        assert!(b.y0 >= -0.5 - 1e-6 && b.y1 <= 0.5 + 1e-6, "{kind:?} {b:?}");
    }
}

/// Pixels of `path` filled by the non-zero rule at `scale` px per motif
/// unit (no anti-aliasing), `side` px square, the motif's centre in the
/// middle: what a renderer paints for a motif drawn with a fill.
fn painted(path: &BezPath, scale: f64, side: u32) -> Vec<u8> {
    use resvg::tiny_skia::{FillRule, Paint, PathBuilder, Pixmap, Transform};
    let placed = Affine::translate((f64::from(side) / 2.0, f64::from(side) / 2.0))
        * Affine::scale(scale)
        * path.clone();
    let mut pb = PathBuilder::new();
    let f = |p: Point| (p.x as f32, p.y as f32);
    for el in placed.elements() {
        match *el {
            kurbo::PathEl::MoveTo(p) => pb.move_to(f(p).0, f(p).1),
            kurbo::PathEl::LineTo(p) => pb.line_to(f(p).0, f(p).1),
            kurbo::PathEl::QuadTo(a, p) => pb.quad_to(f(a).0, f(a).1, f(p).0, f(p).1),
            kurbo::PathEl::CurveTo(a, b, p) => {
                pb.cubic_to(f(a).0, f(a).1, f(b).0, f(b).1, f(p).0, f(p).1)
            }
            kurbo::PathEl::ClosePath => pb.close(),
        }
    }
    let mut pixmap = Pixmap::new(side, side).unwrap();
    let mut paint = Paint::default();
    paint.set_color_rgba8(0, 0, 0, 255);
    pixmap.fill_path(
        &pb.finish().unwrap(),
        &paint,
        FillRule::Winding,
        Transform::identity(),
        None,
    );
    pixmap.pixels().iter().map(|p| p.alpha()).collect()
}

/// A motif drawn with a fill is painted all over inside its outline and
/// nowhere outside it, at any size: its details (seigaiha's arcs, shippo's
/// lenses, veins, petal edges) never leave crescent or lens-shaped gaps.
/// Anti-aliased, as the preview renders it: a gap is a pixel the outline
/// alone paints fully and the whole motif less than half.
#[test]
fn a_filled_motif_has_no_gaps_inside_its_outline() {
    for kind in MotifKind::ALL {
        for petals in [None, Some(1), Some(3), Some(5), Some(8)] {
            for (jitter, seed) in [(0.0, 1), (0.6, 2), (1.0, 3)] {
                let params = MotifParams { petals, jitter };
                let d = draw(kind, &params, &mut Seed(seed).stream());
                for scale in [24.0, 90.0, 400.0] {
                    let side = scale as u32 + 8;
                    let outline = painted(&d.outline, scale, side);
                    let whole = painted(&d.to_path(Affine::IDENTITY), scale, side);
                    let what = format!("{kind:?} petals {petals:?} jitter {jitter} at {scale} px");
                    let gaps = outline
                        .iter()
                        .zip(&whole)
                        .filter(|(o, w)| **o == 255 && **w < 128);
                    assert_eq!(gaps.count(), 0, "{what}: gaps");
                    let spill = outline
                        .iter()
                        .zip(&whole)
                        .filter(|(o, w)| **o == 0 && **w >= 128);
                    assert_eq!(spill.count(), 0, "{what}: paint outside the outline");
                }
            }
        }
    }
}
