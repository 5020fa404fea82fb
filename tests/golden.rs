//! What the built-in templates look like: each template's PNG preview,
//! rendered at [`DPI`], is compared with a reference picture,
//! `tests/golden/{template}.png`, with a tolerance that ignores
//! anti-aliasing noise but fails on a change a person would see.
//!
//! **References** keep 6 levels per colour channel (0, 51, …, 255: 216
//! colours, an indexed PNG of 10–50 KB per template).
//!
//! **The measure** ([`compare`]): a pixel of the new picture, at full
//! precision, is off by how far each channel lies *outside* the
//! reference's level (more than half a step, 25.5, from it); these
//! excesses are averaged over 3 × 3 pixels, and a pixel has changed when
//! one channel's average exceeds [`MAX_EXCESS`]. Noise of up to
//! [`MAX_EXCESS`] on every pixel can never fail the test, whichever side of
//! a level boundary the reference fell on. A picture has changed when more
//! than [`MAX_CHANGED_PIXELS`] pixels have (that constant says how the
//! numbers were chosen).
//!
//! On a failure the new picture and a picture of the difference are
//! written to `target/tmp/golden/` and the message says where. With
//! `MOYO_BLESS=1` every reference that is missing or differs is rewritten
//! (references that still match are left alone, so invisible changes do
//! not churn the files) and references of templates that are gone are
//! deleted. See tests/README.md.

use std::path::{Path, PathBuf};

use resvg::tiny_skia::{Pixmap, PremultipliedColorU8};

use moyo::project;
use moyo::spec::{Format, SceneSpec, ValidSpec};
use moyo::templates;

use crate::rendered;

/// Resolution of the compared pictures: an A3 template is 468 × 661
/// pixels, and a millimetre 1.6 pixels.
const DPI: f64 = 40.0;

/// Steps between the levels a reference keeps of each colour channel.
const LEVEL_STEP: u8 = 51;

/// A pixel has changed when, averaged over its 3 × 3 neighbourhood, one
/// channel lies further than this (out of 255) outside the reference's
/// level.
const MAX_EXCESS: i32 = 4;

/// A picture has changed when more pixels than this have.
///
/// Measured on the templates at 40 dpi (`a_visible_change_fails`,
/// `noise_and_rounding_pass` keep the decisive cases): rounding the SVG to
/// 0.01 mm instead of 0.001 mm changes at most 1 pixel of any template,
/// moving the whole drawing by 0.02 mm at most 4, noise of ±4 on every
/// channel of every pixel none (±8: 27, on kimono-3). Moving one flower of
/// kimono-1 by 1 mm changes 43 pixels or more (the least visible: a small
/// pale flower in the back row; 300 for a front one), turning one tree by
/// 0.5° 468 or more. At 30 dpi the weakest flower would change only 14.
const MAX_CHANGED_PIXELS: usize = 10;

/// Where the references live.
fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

/// Where new pictures and differences of a failed comparison go.
fn failure_dir() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join("golden")
}

/// An opaque picture, one `[r, g, b]` per pixel, row by row.
#[derive(Clone)]
struct Picture {
    width: usize,
    height: usize,
    pixels: Vec<[u8; 3]>,
}

impl Picture {
    /// Decodes a PNG (any colour type tiny-skia reads), on white.
    fn decode(png: &[u8]) -> Picture {
        let pixmap = Pixmap::decode_png(png).expect("a PNG");
        let pixels = pixmap
            .pixels()
            .iter()
            .map(|p| {
                // Premultiplied: white shows through what alpha leaves.
                let white = 255 - p.alpha();
                [p.red() + white, p.green() + white, p.blue() + white]
            })
            .collect();
        Picture {
            width: pixmap.width() as usize,
            height: pixmap.height() as usize,
            pixels,
        }
    }

    /// The reference of this picture: an indexed PNG of each channel at
    /// the nearest level, palette entry `36·r + 6·g + b` of the levels.
    fn encode_reference(&self) -> Vec<u8> {
        let levels = 255 / LEVEL_STEP + 1;
        let level =
            |v: u8| ((u16::from(v) + u16::from(LEVEL_STEP / 2)) / u16::from(LEVEL_STEP)) as u8;
        let palette: Vec<u8> = (0..levels * levels * levels)
            .flat_map(|i| {
                [i / (levels * levels), i / levels % levels, i % levels].map(|l| l * LEVEL_STEP)
            })
            .collect();
        let index: Vec<u8> = self
            .pixels
            .iter()
            .map(|p| {
                let [r, g, b] = p.map(level);
                (r * levels + g) * levels + b
            })
            .collect();
        let mut out = Vec::new();
        let mut encoder = png::Encoder::new(&mut out, self.width as u32, self.height as u32);
        encoder.set_color(png::ColorType::Indexed);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_palette(palette);
        encoder.set_compression(png::Compression::High);
        let mut writer = encoder.write_header().expect("PNG header");
        writer.write_image_data(&index).expect("PNG data");
        writer.finish().expect("PNG end");
        out
    }
}

/// Which pixels of a new picture differ from the reference.
struct Difference {
    /// Per pixel, whether it has changed (see the module documentation).
    changed: Vec<bool>,
    /// How many have.
    count: usize,
}

/// Compares a new picture, at full precision, with a reference of the
/// same size (see the module documentation for the measure).
fn compare(reference: &Picture, new: &Picture) -> Difference {
    assert_eq!((reference.width, reference.height), (new.width, new.height));
    // Twice the excess, signed, so that half a step is a whole number.
    let excess: Vec<[i32; 3]> = reference
        .pixels
        .iter()
        .zip(&new.pixels)
        .map(|(r, n)| {
            [0, 1, 2].map(|c| {
                let d = 2 * (i32::from(n[c]) - i32::from(r[c]));
                d.signum() * (d.abs() - i32::from(LEVEL_STEP)).max(0)
            })
        })
        .collect();
    let (w, h) = (reference.width as isize, reference.height as isize);
    let mut changed = vec![false; excess.len()];
    for y in 0..h {
        for x in 0..w {
            let mut sum = [0; 3];
            for (dx, dy) in (-1..=1).flat_map(|dy| (-1..=1).map(move |dx| (dx, dy))) {
                // The border repeats beyond the edges.
                let (sx, sy) = ((x + dx).clamp(0, w - 1), (y + dy).clamp(0, h - 1));
                let e = excess[(sy * w + sx) as usize];
                for c in 0..3 {
                    sum[c] += e[c];
                }
            }
            changed[(y * w + x) as usize] = sum.iter().any(|s| s.abs() > 2 * 9 * MAX_EXCESS);
        }
    }
    let count = changed.iter().filter(|&&c| c).count();
    Difference { changed, count }
}

/// The reference faded, changed pixels in red.
fn difference_png(reference: &Picture, difference: &Difference) -> Vec<u8> {
    let mut pixmap = Pixmap::new(reference.width as u32, reference.height as u32).unwrap();
    for ((out, p), &changed) in pixmap
        .pixels_mut()
        .iter_mut()
        .zip(&reference.pixels)
        .zip(&difference.changed)
    {
        let [r, g, b] = if changed {
            [255, 0, 0]
        } else {
            p.map(|v| 255 - (255 - v) / 4)
        };
        *out = PremultipliedColorU8::from_rgba(r, g, b, 255).unwrap();
    }
    pixmap.encode_png().unwrap()
}

/// Whether `MOYO_BLESS` asks for references to be rewritten.
fn blessing() -> bool {
    std::env::var_os("MOYO_BLESS").is_some_and(|v| !v.is_empty() && v != "0")
}

/// Compares the picture `png` of `name` with its reference: `Err` with a
/// message when it differs (or the reference is missing), after writing
/// the new picture (and the difference, if any) to [`failure_dir`]; when
/// blessing, writes the reference instead.
fn check(name: &str, png: &[u8]) -> Result<(), String> {
    let new = Picture::decode(png);
    let path = golden_dir().join(format!("{name}.png"));
    let Some(message) = difference(name, &path, &new) else {
        return Ok(());
    };
    if blessing() {
        std::fs::write(&path, new.encode_reference()).unwrap();
        eprintln!("blessed {}", path.display());
        return Ok(());
    }
    let new_path = failure_dir().join(format!("{name}.png"));
    std::fs::write(&new_path, png).unwrap();
    Err(format!(
        "{message}; the new picture is {}",
        new_path.display()
    ))
}

/// What is wrong with `new` against the reference at `path`, `None` when
/// they match within the tolerance. Writes the picture of a difference.
fn difference(name: &str, path: &Path, new: &Picture) -> Option<String> {
    std::fs::create_dir_all(failure_dir()).unwrap();
    let reference = match std::fs::read(path) {
        Ok(bytes) => Picture::decode(&bytes),
        Err(e) => return Some(format!("{name}: no reference {}: {e}", path.display())),
    };
    if (reference.width, reference.height) != (new.width, new.height) {
        return Some(format!(
            "{name}: the picture is {}×{} pixels, its reference {}×{}",
            new.width, new.height, reference.width, reference.height
        ));
    }
    let difference = compare(&reference, new);
    if difference.count <= MAX_CHANGED_PIXELS {
        return None;
    }
    let diff = failure_dir().join(format!("{name}.diff.png"));
    std::fs::write(&diff, difference_png(&reference, &difference)).unwrap();
    Some(format!(
        "{name}: {} pixels changed (more than {MAX_CHANGED_PIXELS}), red in {}",
        difference.count,
        diff.display()
    ))
}

/// The PNG preview of a description at [`DPI`].
fn picture(spec: &ValidSpec) -> Vec<u8> {
    let rendered = project::render(spec).unwrap_or_else(|e| panic!("{e}"));
    rendered.png(DPI).unwrap()
}

#[test]
fn every_template_looks_as_before() {
    let mut failures = Vec::new();
    for (t, r) in rendered::plotted() {
        if let Err(message) = check(t.name, &r.png(DPI).unwrap()) {
            failures.push(message);
        }
    }
    // References of templates that are gone.
    for entry in std::fs::read_dir(golden_dir()).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        if templates::ALL.iter().all(|t| t.name != name) {
            if blessing() {
                std::fs::remove_file(&path).unwrap();
            } else {
                failures.push(format!("{}: no template of that name", path.display()));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{}\n(if the change is intended, rerun with MOYO_BLESS=1; see tests/README.md)",
        failures.join("\n")
    );
}

/// kimono-1 with `extra` appended to its description.
fn kimono_1_with(extra: &str) -> ValidSpec {
    let text = format!("{}\n{extra}", templates::get("kimono-1").unwrap().text);
    SceneSpec::parse(&text, Format::Toml).unwrap_or_else(|e| panic!("{e}\n{extra}"))
}

/// kimono-1 as it is, its picture and the reference made of it.
fn kimono_1() -> (ValidSpec, Picture, Picture) {
    let spec = kimono_1_with("");
    let new = Picture::decode(&picture(&spec));
    let reference = Picture::decode(&new.encode_reference());
    (spec, new, reference)
}

/// The least visible changes found among all flowers and trees of
/// kimono-1 (see [`MAX_CHANGED_PIXELS`]) must fail.
#[test]
fn a_visible_change_fails() {
    let (_, _, reference) = kimono_1();
    for adjust in [
        // A small pale flower in the back row, moved by 1 mm.
        "id = \"back.far.tree-3.flower-6\"\nmove = [1, 0]",
        // A tree turned by half a degree.
        "id = \"back.far.tree-3\"\nrotate = 0.5",
    ] {
        let new = Picture::decode(&picture(&kimono_1_with(&format!("[[adjust]]\n{adjust}\n"))));
        let changed = compare(&reference, &new).count;
        assert!(changed > MAX_CHANGED_PIXELS, "{adjust}: {changed} pixels");
    }
}

/// Noise and rounding nobody can see must pass.
#[test]
fn noise_and_rounding_pass() {
    let (spec, new, reference) = kimono_1();
    // Coordinates rounded to 0.01 mm instead of 0.001 mm.
    let spec = spec.edit(|s| s.output.precision = 2).unwrap();
    let rounded = Picture::decode(&picture(&spec));
    let changed = compare(&reference, &rounded).count;
    assert!(changed <= MAX_CHANGED_PIXELS, "rounding: {changed} pixels");
    // Every channel of every pixel off by up to the tolerance: never a
    // changed pixel, wherever the reference's levels fell.
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut noisy = new.clone();
    for v in noisy.pixels.iter_mut().flatten() {
        // xorshift64: fixed, so the test is the same on every run.
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let n = (state % (2 * MAX_EXCESS as u64 + 1)) as i32 - MAX_EXCESS;
        *v = (i32::from(*v) + n).clamp(0, 255) as u8;
    }
    assert_eq!(compare(&reference, &noisy).count, 0);
}
