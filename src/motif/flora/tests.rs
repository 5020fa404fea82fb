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
