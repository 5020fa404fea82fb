//! Refills and resuming: how a plot is cut into runs of limited pen-down
//! length, and where it starts again after a failure.
//!
//! Both work on the strokes the G-code and HPGL writers draw, in the order
//! they draw them ([`super::strokes`]), and measure pen-down length along
//! the flattened polylines, exactly what the machine draws.
//!
//! - **Resume** ([`RunOptions::from_distance_mm`] `D`): the strokes are
//!   walked in order, adding up their lengths; everything drawn before the
//!   running total reaches `D` is left out, and the stroke in which it
//!   reaches `D` starts at that point. A pen with nothing left is not
//!   chosen at all. What is left out and what is written are exactly the
//!   whole plot, nothing lost or drawn twice.
//! - **Refill** ([`RunOptions::refill_mm`] `R`): each pen's strokes are cut
//!   into runs of at most `R` mm of pen-down, and the first stroke of every
//!   run after the first is marked [`Stroke::refill_before`]; the writer
//!   then moves to [`RunOptions::refill_at`] to dip the pen there (or
//!   pauses, without a place). A run ends *between* strokes: a stroke that
//!   would overflow the run starts the next one, so short strokes (a dot, a
//!   hatch line) are never cut. Only a stroke longer than `R` itself is cut,
//!   into pieces of exactly `R` (the last one shorter), each after a
//!   refill. A new pen starts full. Runs are counted from where a resumed
//!   plot starts. A run may be [`SLACK`] longer than asked (a hundredth of
//!   a millimetre), so that coordinate noise never leaves a crumb.

use kurbo::Point;
use serde::{Deserialize, Serialize};

use super::strokes::{PenBlock, Stroke};
use crate::error::{Error, Result};

/// Where a plot starts and when its pen is refilled (see the module
/// documentation). The default does neither.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RunOptions {
    /// Refill the pen after at most this many millimetres of pen-down;
    /// `None` never refills. Default `None`.
    pub refill_mm: Option<f64>,
    /// Where the pen is refilled, in machine millimetres: the writer
    /// travels there, lowers the pen into the well, lifts it and goes on.
    /// `None` pauses for the operator instead. Default `None`.
    pub refill_at: Option<[f64; 2]>,
    /// Leave out the first this many millimetres of pen-down (to resume a
    /// plot that failed there). Default 0.
    pub from_distance_mm: f64,
}

impl Default for RunOptions {
    fn default() -> RunOptions {
        RunOptions::NONE
    }
}

impl RunOptions {
    /// No refills, from the start.
    pub const NONE: RunOptions = RunOptions {
        refill_mm: None,
        refill_at: None,
        from_distance_mm: 0.0,
    };

    /// These options refilling every `mm` of pen-down (`None`: never).
    pub fn with_refill_mm(mut self, mm: Option<f64>) -> RunOptions {
        self.refill_mm = mm;
        self
    }

    /// These options refilling at machine `(x, y)` (`None`: pause).
    pub fn with_refill_at(mut self, at: Option<[f64; 2]>) -> RunOptions {
        self.refill_at = at;
        self
    }

    /// These options resuming after `mm` of pen-down.
    pub fn with_from_distance_mm(mut self, mm: f64) -> RunOptions {
        self.from_distance_mm = mm;
        self
    }

    /// Checks the options; `prefix` names the table (`gcode`, `hpgl`).
    pub fn validate(&self, prefix: &str) -> Result<()> {
        if let Some(r) = self.refill_mm {
            // A run shorter than a tenth of a millimetre would cut every
            // stroke into thousands of pieces.
            if !(r.is_finite() && r >= 0.1) {
                return Err(Error::invalid(
                    format!("{prefix}.runs.refill_mm"),
                    format!("must be at least 0.1 mm, got {r}"),
                ));
            }
        }
        if let Some([x, y]) = self.refill_at {
            if !(x.is_finite() && y.is_finite()) {
                return Err(Error::invalid(
                    format!("{prefix}.runs.refill_at"),
                    "must be finite",
                ));
            }
            if self.refill_mm.is_none() {
                return Err(Error::invalid(
                    format!("{prefix}.runs.refill_at"),
                    "needs refill_mm: how much the pen draws between refills",
                ));
            }
        }
        let d = self.from_distance_mm;
        if !(d.is_finite() && d >= 0.0) {
            return Err(Error::invalid(
                format!("{prefix}.runs.from_distance_mm"),
                format!("must be 0 or more mm, got {d}"),
            ));
        }
        Ok(())
    }
}

/// Applies `runs` to the writer's strokes: resume, then refill marks.
pub(super) fn apply(blocks: &mut Vec<PenBlock<'_>>, runs: &RunOptions) {
    if runs.from_distance_mm > 0.0 {
        resume(blocks, runs.from_distance_mm);
    }
    if let Some(r) = runs.refill_mm.filter(|r| r.is_finite() && *r > 0.0) {
        for block in blocks.iter_mut() {
            refill(block, r);
        }
    }
}

/// Leaves out the first `distance` mm of pen-down.
fn resume(blocks: &mut Vec<PenBlock<'_>>, distance: f64) {
    let mut left = distance;
    for block in blocks.iter_mut() {
        for path in &mut block.paths {
            let mut kept = Vec::with_capacity(path.strokes.len());
            for stroke in std::mem::take(&mut path.strokes) {
                if left <= 0.0 {
                    kept.push(stroke);
                    continue;
                }
                let length = length_of(&stroke.points);
                if length <= left {
                    left -= length;
                    continue;
                }
                let (_, after) = split_at(&stroke.points, left);
                left = 0.0;
                kept.push(Stroke {
                    points: after,
                    closed: false,
                    refill_before: false,
                });
            }
            path.strokes = kept;
        }
        block.paths.retain(|p| !p.strokes.is_empty());
    }
    blocks.retain(|b| !b.paths.is_empty());
}

/// Lengths within this of a run's end fit the run (mm), far below what a
/// pen can show: the few micrometres of noise in imported coordinates must
/// not leave a crumb of a stroke after it is cut into whole runs.
pub(super) const SLACK: f64 = 0.01;

/// Marks (and where needed cuts) one pen's strokes into runs of at most
/// `run` mm.
fn refill(block: &mut PenBlock<'_>, run: f64) {
    let mut used = 0.0;
    for path in &mut block.paths {
        let mut out = Vec::with_capacity(path.strokes.len());
        for mut stroke in std::mem::take(&mut path.strokes) {
            let length = length_of(&stroke.points);
            if used > 0.0 && used + length > run + SLACK {
                stroke.refill_before = true;
                used = 0.0;
            }
            if length <= run + SLACK {
                used += length;
                out.push(stroke);
                continue;
            }
            // Longer than a whole run: pieces of exactly `run`.
            let mut rest = stroke.points;
            let mut refill_before = stroke.refill_before;
            loop {
                let left = length_of(&rest);
                if left <= run + SLACK {
                    used = left;
                    out.push(Stroke {
                        points: rest,
                        closed: false,
                        refill_before,
                    });
                    break;
                }
                let (piece, after) = split_at(&rest, run);
                out.push(Stroke {
                    points: piece,
                    closed: false,
                    refill_before,
                });
                rest = after;
                refill_before = true;
            }
        }
        path.strokes = out;
    }
}

/// The length of a polyline.
pub(super) fn length_of(points: &[Point]) -> f64 {
    points.windows(2).map(|w| w[0].distance(w[1])).sum()
}

/// The polyline cut `at` mm from its start: the part before (ending at the
/// cut) and the part after (starting there). `at` is within the length.
fn split_at(points: &[Point], at: f64) -> (Vec<Point>, Vec<Point>) {
    let mut walked = 0.0;
    for (i, w) in points.windows(2).enumerate() {
        let segment = w[0].distance(w[1]);
        if walked + segment >= at && segment > 0.0 {
            let t = ((at - walked) / segment).clamp(0.0, 1.0);
            let cut = w[0].lerp(w[1], t);
            let mut before = points[..=i].to_vec();
            before.push(cut);
            let mut after = vec![cut];
            after.extend_from_slice(&points[i + 1..]);
            return (before, after);
        }
        walked += segment;
    }
    (points.to_vec(), vec![points[points.len() - 1]])
}

#[cfg(test)]
mod tests {
    use super::super::strokes::PathStrokes;
    use super::*;
    use crate::scene::LayerCodes;
    use proptest::prelude::*;

    fn stroke(points: &[(f64, f64)]) -> Stroke {
        Stroke {
            points: points.iter().map(|&p| p.into()).collect(),
            closed: false,
            refill_before: false,
        }
    }

    /// Two pens: pen 1 draws strokes of the given lengths along y = 0,
    /// pen 2 one stroke of 10 mm.
    fn blocks(lengths: &[f64]) -> Vec<PenBlock<'static>> {
        let mut x = 0.0;
        let strokes = lengths
            .iter()
            .map(|&l| {
                let s = stroke(&[(x, 0.0), (x + l / 2.0, 0.0), (x + l, 0.0)]);
                x += l + 1.0;
                s
            })
            .collect();
        let block = |number, strokes| PenBlock {
            number,
            name: "",
            codes: LayerCodes::default(),
            paths: vec![PathStrokes { id: "p", strokes }],
        };
        vec![
            block(1, strokes),
            block(2, vec![stroke(&[(0.0, 5.0), (10.0, 5.0)])]),
        ]
    }

    fn strokes<'a>(blocks: &'a [PenBlock<'_>]) -> impl Iterator<Item = &'a Stroke> + 'a {
        blocks
            .iter()
            .flat_map(|b| b.paths.iter().flat_map(|p| &p.strokes))
    }

    /// Every run's pen-down length, per pen, in order.
    fn runs(blocks: &[PenBlock<'_>]) -> Vec<f64> {
        let mut out = Vec::new();
        for b in blocks {
            out.push(0.0);
            for s in b.paths.iter().flat_map(|p| &p.strokes) {
                if s.refill_before {
                    out.push(0.0);
                }
                *out.last_mut().unwrap() += length_of(&s.points);
            }
        }
        out
    }

    #[test]
    fn refills_come_between_strokes() {
        let mut b = blocks(&[4.0, 4.0, 4.0, 4.0]);
        apply(&mut b, &RunOptions::default().with_refill_mm(Some(10.0)));
        let marks: Vec<bool> = strokes(&b).map(|s| s.refill_before).collect();
        // 4 + 4 | 4 + 4 | pen 2 starts full.
        assert_eq!(marks, [false, false, true, false, false]);
        assert_eq!(strokes(&b).count(), 5, "no stroke was cut");
    }

    #[test]
    fn a_stroke_longer_than_a_run_is_cut_into_whole_runs() {
        let mut b = blocks(&[3.0, 25.0]);
        apply(&mut b, &RunOptions::default().with_refill_mm(Some(10.0)));
        let r = runs(&b);
        assert_eq!(r.len(), 5, "{r:?}");
        for (got, want) in r.iter().zip([3.0, 10.0, 10.0, 5.0, 10.0]) {
            assert!((got - want).abs() < 1e-9, "{r:?}");
        }
    }

    #[test]
    fn a_stroke_of_whole_runs_leaves_no_crumb() {
        // A 240 mm stroke a few micrometres long, as an imported square is.
        let mut b = blocks(&[240.000_006_7]);
        apply(&mut b, &RunOptions::default().with_refill_mm(Some(60.0)));
        let pieces: Vec<f64> = b[0].paths[0]
            .strokes
            .iter()
            .map(|s| length_of(&s.points))
            .collect();
        assert_eq!(pieces.len(), 4, "{pieces:?}");
    }

    #[test]
    fn resume_leaves_out_exactly_the_distance() {
        let mut b = blocks(&[4.0, 6.0, 4.0]);
        apply(&mut b, &RunOptions::default().with_from_distance_mm(7.0));
        let left: Vec<f64> = strokes(&b).map(|s| length_of(&s.points)).collect();
        for (got, want) in left.iter().zip([3.0, 4.0, 10.0]) {
            assert!((got - want).abs() < 1e-9, "{left:?}");
        }
        assert!((strokes(&b).next().unwrap().points[0].x - 8.0).abs() < 1e-9);

        // Past pen 1: it is not chosen at all.
        let mut b = blocks(&[4.0]);
        apply(&mut b, &RunOptions::default().with_from_distance_mm(6.0));
        assert_eq!(b.iter().map(|b| b.number).collect::<Vec<_>>(), [2]);
        // Past everything: nothing.
        let mut b = blocks(&[4.0]);
        apply(&mut b, &RunOptions::default().with_from_distance_mm(100.0));
        assert!(b.is_empty());
    }

    #[test]
    fn validate_names_the_field() {
        for (runs, field) in [
            (
                RunOptions::default().with_refill_mm(Some(0.0)),
                "gcode.runs.refill_mm",
            ),
            (
                RunOptions::default().with_refill_at(Some([0.0, 0.0])),
                "gcode.runs.refill_at",
            ),
            (
                RunOptions::default().with_from_distance_mm(-1.0),
                "gcode.runs.from_distance_mm",
            ),
        ] {
            let e = runs.validate("gcode").unwrap_err().to_string();
            assert!(e.starts_with(field), "{e}");
        }
        RunOptions::default()
            .with_refill_mm(Some(50.0))
            .with_refill_at(Some([-10.0, 0.0]))
            .validate("hpgl")
            .unwrap();
    }

    proptest! {
        /// Runs never exceed their length, and refills and resume neither
        /// lose nor repeat line: the skipped part and the rest, end to
        /// end, are the whole plot.
        #[test]
        fn runs_and_resume_keep_every_millimetre(
            lengths in prop::collection::vec(0.0f64..30.0, 1..20),
            run in 0.5f64..40.0,
            from in 0.0f64..200.0,
        ) {
            let whole = blocks(&lengths);
            let total: f64 = strokes(&whole).map(|s| length_of(&s.points)).sum();

            let mut refilled = blocks(&lengths);
            apply(&mut refilled, &RunOptions::default().with_refill_mm(Some(run)));
            for r in runs(&refilled) {
                prop_assert!(r <= run + SLACK + 1e-9, "run of {r} > {run}");
            }
            let after: f64 = strokes(&refilled).map(|s| length_of(&s.points)).sum();
            prop_assert!((after - total).abs() < 1e-6);

            let mut resumed = blocks(&lengths);
            apply(&mut resumed, &RunOptions::default().with_from_distance_mm(from));
            let left: f64 = strokes(&resumed).map(|s| length_of(&s.points)).sum();
            prop_assert!((left - (total - from).max(0.0)).abs() < 1e-6, "{left} {total} {from}");
            // What is left is the tail of the plot: the points of the
            // remaining strokes are points of the whole, or the cut.
            let all: Vec<Point> = strokes(&whole).flat_map(|s| s.points.clone()).collect();
            for (k, s) in strokes(&resumed).enumerate() {
                for (i, p) in s.points.iter().enumerate() {
                    if k == 0 && i == 0 {
                        continue;
                    }
                    prop_assert!(all.contains(p));
                }
            }
        }
    }
}
