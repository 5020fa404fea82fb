//! Growth as one animated SVG: the frames (SVG documents moyo wrote, all on
//! one page) shown one after another in a loop, each for its turn, the
//! last held longer so the finished drawing can be seen. SMIL animation:
//! browsers play it; plot software sees every frame at once, so this file
//! is for looking at, not for plotting.

use crate::error::{Error, Result};

/// How long each frame shows, seconds.
pub const FRAME_SECONDS: f64 = 0.5;

/// How many frames' time the last one is held.
const HOLD_LAST: f64 = 4.0;

/// One SVG playing `frames` in a loop. Each frame must be a whole SVG
/// document as [`crate::to_svg`] writes it; the first one's root element
/// (page size and view box) is the animation's. Ids are prefixed with
/// `f<k>-` so that they stay unique.
///
/// # Errors
/// [`Error::Invalid`] (field `frames`) when there are no frames or one is
/// not an SVG document moyo wrote.
pub fn animated_svg(frames: &[&str]) -> Result<String> {
    let bad = |k: usize| Error::invalid("frames", format!("frame {k} is not an SVG moyo wrote"));
    let first = frames
        .first()
        .ok_or_else(|| Error::invalid("frames", "there are no frames to animate"))?;
    let root_end = first
        .find("<svg")
        .and_then(|at| first[at..].find('>').map(|end| at + end + 1))
        .ok_or_else(|| bad(0))?;
    let n = frames.len();
    // Frame k shows from starts[k] to starts[k + 1], in seconds.
    let starts: Vec<f64> = (0..=n)
        .map(|k| {
            FRAME_SECONDS * k as f64
                + if k == n {
                    (HOLD_LAST - 1.0) * FRAME_SECONDS
                } else {
                    0.0
                }
        })
        .collect();
    let total = starts[n];
    let mut out = String::from(&first[..root_end]);
    out.push('\n');
    for (k, frame) in frames.iter().enumerate() {
        // The drawing: after the embedded description, before the root's
        // end.
        let body_start = frame
            .find("</metadata>")
            .map(|at| at + "</metadata>".len())
            .or_else(|| {
                frame
                    .find("<svg")
                    .and_then(|at| frame[at..].find('>').map(|e| at + e + 1))
            })
            .ok_or_else(|| bad(k))?;
        let body_end = frame.rfind("</svg>").ok_or_else(|| bad(k))?;
        if body_end < body_start {
            return Err(bad(k));
        }
        let body = frame[body_start..body_end].replace(" id=\"", &format!(" id=\"f{k}-"));
        let (on, off) = (starts[k] / total, starts[k + 1] / total);
        let (values, times) = if n == 1 {
            ("visible".to_string(), "0".to_string())
        } else if k == 0 {
            ("visible;hidden".to_string(), format!("0;{off:.6}"))
        } else if k == n - 1 {
            ("hidden;visible".to_string(), format!("0;{on:.6}"))
        } else {
            (
                "hidden;visible;hidden".to_string(),
                format!("0;{on:.6};{off:.6}"),
            )
        };
        out.push_str(&format!(
            " <g id=\"frame-{k}\" visibility=\"{}\">\n  <animate attributeName=\"visibility\" \
             values=\"{values}\" keyTimes=\"{times}\" dur=\"{total:.3}s\" calcMode=\"discrete\" \
             repeatCount=\"indefinite\"/>{body}</g>\n",
            if k == 0 { "visible" } else { "hidden" },
        ));
    }
    out.push_str("</svg>\n");
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use resvg::usvg;

    fn frame(d: &str) -> String {
        format!(
            "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" \
             height=\"50mm\" viewBox=\"0 0 100 50\">\n <metadata>described</metadata>\n \
             <g id=\"pen-1\" style=\"fill:none;stroke:#000\"><path id=\"p\" d=\"{d}\"/></g>\n</svg>\n"
        )
    }

    #[test]
    fn frames_take_turns_in_one_loop_on_the_first_page() {
        let frames = [
            frame("M 0 0 L 10 0"),
            frame("M 0 0 L 20 0"),
            frame("M 0 0 L 30 0"),
        ];
        let refs: Vec<&str> = frames.iter().map(String::as_str).collect();
        let svg = animated_svg(&refs).unwrap();
        // The page of the first, each frame once, ids unique, no
        // description.
        assert!(svg.starts_with("<?xml") && svg.contains("width=\"100mm\""));
        assert_eq!(svg.matches("<animate ").count(), 3);
        for k in 0..3 {
            assert!(svg.contains(&format!("id=\"f{k}-pen-1\"")), "{svg}");
            assert!(svg.contains(&format!("L {} 0", 10 * (k + 1))));
        }
        assert!(!svg.contains("described"));
        // 0.5 s each, the last held four times as long (2 s): 3 s in all;
        // the second frame shows from 1/6 to 1/3 of it.
        assert!(svg.contains("dur=\"3.000s\""), "{svg}");
        assert!(svg.contains("keyTimes=\"0;0.166667;0.333333\""), "{svg}");
        // Well-formed: usvg reads it (and, not animating, sees the first).
        usvg::Tree::from_str(&svg, &usvg::Options::default()).unwrap();
    }

    #[test]
    fn what_is_not_a_frame_is_refused() {
        assert!(animated_svg(&[]).is_err());
        assert!(animated_svg(&["not svg"]).is_err());
        let one = frame("M 0 0 L 1 1");
        assert!(animated_svg(&[&one])
            .unwrap()
            .contains("values=\"visible\""));
    }
}
