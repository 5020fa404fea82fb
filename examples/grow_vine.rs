//! Grows a twining vine round a pole with the 3D simulation alone, and
//! reads what grew: how many times the first stem winds round the pole,
//! how high it climbs, its leaves. (A `[[layers.vine]]` table draws the
//! same plant through a camera, with its hidden lines removed.)
//!
//! Run with `cargo run --example grow_vine -- [SEED]` (default 7).

// `unused_crate_dependencies` (Cargo.toml) is for the library: an example uses the library, not each of its dependencies.
#![allow(unused_crate_dependencies)]

use glam::DVec3;
use moyo::vine::{grow, Shape, Supports, Twining, VineParams};
use moyo::Seed;

fn main() -> Result<(), moyo::Error> {
    let seed = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(7);
    // A pole 6 mm thick and 400 mm tall, 20 mm from where the seed lies
    // (millimetres, y up).
    let pole_at = DVec3::new(20.0, 0.0, 0.0);
    let pole = Supports::new(vec![Shape::Pole {
        base: pole_at,
        top: pole_at + DVec3::Y * 400.0,
        radius: 6.0,
    }]);
    let params = VineParams {
        twining: Twining::Right,
        internodes: 40,
        ..VineParams::default()
    };
    let plant = grow(&params, &pole, &mut Seed(seed).stream())?;

    let stem = &plant.stems[0];
    // The turns round the pole: the angle about its axis, unwrapped.
    let mut turns = 0.0;
    for pair in stem.points.windows(2) {
        let [a, b] = [pair[0] - pole_at, pair[1] - pole_at];
        let step = (-b.z).atan2(b.x) - (-a.z).atan2(a.x);
        turns +=
            (step + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
    }
    let top = stem.points.iter().map(|p| p.y).fold(0.0, f64::max);
    println!(
        "seed {seed}: {} stems, {} leaves after {} steps; the first stem reaches {top:.0} mm \
         (the pole stands 400) in {:.1} turns ({})",
        plant.stems.len(),
        plant.leaves.len(),
        plant.steps,
        turns.abs() / std::f64::consts::TAU,
        if turns > 0.0 {
            "counter-clockwise seen from above"
        } else {
            "clockwise seen from above"
        }
    );
    Ok(())
}
