//! Single-stroke text: characters laid out as the lines a pen draws, in
//! the Hershey fonts built into moyo, for titles and signatures
//! (`[[layers.text]]`) and for the `<text>` of an imported SVG.
//!
//! [`layout`] turns a string into one path per drawn character, each
//! stroke of the glyph a subpath (a pen lift between strokes), in
//! millimetres — or in any unit: everything scales with
//! [`TextStyle::size`], the cap height. The first line's baseline starts
//! at the origin, y down as on the page; `\n` starts a line
//! [`TextStyle::line_height`] × size further down; [`Align`] puts each
//! line's start, middle or end on x = 0.
//!
//! The fonts (`src/text/fonts/`, whose README gives their source and
//! licence) are Hershey's, in James Hurt's format, as Debian packages
//! them (`hershey-fonts-data` 0.1-1.1, byte for byte): the simplex sans
//! serif `futural` ([`Font::Sans`]) and script `scripts` ([`Font::Script`])
//! for printable ASCII, and `japanese` for both: hiragana and katakana
//! (with the voiced forms, ゐ ゑ ヰ ヱ, and small kana drawn as their
//! full-size kana at 70 %), 。、ー and 24 kanji (日円年大国人東中本京出時上者
//! and 一二三四五六七十入九). The Japanese glyphs draw each brush stroke as a
//! pair of lines. Other kanji are not there yet: the licensed
//! stroke-order data that covers them, KanjiVG (some 6,700 characters),
//! is under CC BY-SA 3.0, whose share-alike terms would bind a font built
//! from it, so it is not embedded in a crate under MIT OR Apache-2.0.
//!
//! Full-width ASCII, typographer's quotes, dashes and spaces fall back on
//! their plain forms (an em dash has a line of its own). A character with
//! no glyph is drawn as a box the size of a capital, never dropped, and
//! listed in [`Lettering::missing`] for the caller to report.

mod font;

pub use font::Font;

use kurbo::{Affine, BezPath, Point, Rect, Shape as _};
use serde::{Deserialize, Serialize};

use font::{normalise, shape, Shape, BASELINE_UNITS, CAP_UNITS};

/// The most characters a text table or an imported SVG lays out: a
/// page of small print, and a bound on the work a description or a file
/// can ask for.
pub const MAX_CHARS: usize = 10_000;

/// Which point of each line stands on the anchor (x = 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Align {
    /// The line starts there.
    #[default]
    Start,
    /// The line is centred there (the middle of its advance).
    Middle,
    /// The line ends there.
    End,
}

/// How [`layout`] sets a text.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextStyle {
    /// The typeface.
    pub font: Font,
    /// The cap height (an `H` from baseline to top), in the unit of the
    /// output; finite and positive.
    pub size: f64,
    /// Which point of each line stands on x = 0.
    pub align: Align,
    /// Added between characters, in the unit of the output (negative
    /// draws them closer).
    pub letter_spacing: f64,
    /// Baseline to baseline, in multiples of `size`.
    pub line_height: f64,
}

impl TextStyle {
    /// The line height when none is given: the Hershey fonts' own (32
    /// units to a cap height of 21) with a little air.
    pub const DEFAULT_LINE_HEIGHT: f64 = 1.6;

    /// Sans serif at cap height `size`, starting at the anchor, no
    /// letter spacing, the default line height.
    pub fn new(size: f64) -> TextStyle {
        TextStyle {
            font: Font::Sans,
            size,
            align: Align::Start,
            letter_spacing: 0.0,
            line_height: TextStyle::DEFAULT_LINE_HEIGHT,
        }
    }
}

/// A laid-out text.
#[derive(Debug, Clone, PartialEq, Default)]
#[non_exhaustive]
pub struct Lettering {
    /// One path per drawn character in reading order (spaces draw
    /// nothing), one subpath per stroke.
    pub glyphs: Vec<BezPath>,
    /// The characters that had no glyph and were drawn as boxes, each
    /// once, in order of first appearance.
    pub missing: Vec<char>,
    /// The advance of the widest line.
    pub width: f64,
    /// How many lines (one more than the line breaks).
    pub lines: usize,
}

impl Lettering {
    /// Every glyph in one path.
    pub fn path(&self) -> BezPath {
        let mut path = BezPath::new();
        for glyph in &self.glyphs {
            path.extend(glyph.elements().iter().copied());
        }
        path
    }

    /// The missing characters quoted for a message: `'秋', '庭'`, the
    /// first ten of them and how many more.
    pub fn missing_list(&self) -> String {
        quoted(&self.missing)
    }
}

/// `chars` quoted for a message, the first ten and how many more.
pub(crate) fn quoted(chars: &[char]) -> String {
    const SHOWN: usize = 10;
    let mut list: Vec<String> = chars
        .iter()
        .take(SHOWN)
        .map(|c| format!("'{}'", c.escape_debug()))
        .collect();
    if chars.len() > SHOWN {
        list.push(format!("and {} more", chars.len() - SHOWN));
    }
    list.join(", ")
}

/// Lays `text` out in single strokes (see the module documentation).
///
/// ```
/// use moyo::text::{layout, Align, TextStyle};
///
/// let style = TextStyle { align: Align::Middle, ..TextStyle::new(5.0) };
/// let title = layout("Hello\nmoyo", &style);
/// assert_eq!(title.lines, 2);
/// assert_eq!(title.glyphs.len(), 9); // nine letters, no spaces
/// assert!(title.missing.is_empty());
/// // The capital stands on the baseline, 5 mm tall.
/// let h = kurbo::Shape::bounding_box(&title.glyphs[0]);
/// assert!((h.y1 - 0.0).abs() < 1e-9 && (h.y0 + 5.0).abs() < 1e-9);
/// ```
pub fn layout(text: &str, style: &TextStyle) -> Lettering {
    let unit = style.size / CAP_UNITS;
    let mut out = Lettering::default();
    for (i, line) in text.split('\n').enumerate() {
        let baseline = i as f64 * style.line_height * style.size;
        let first = out.glyphs.len();
        let mut pen = 0.0;
        let mut started = false;
        for c in line.chars().filter(|c| *c != '\r').map(normalise) {
            if started {
                pen += style.letter_spacing;
            }
            started = true;
            pen += match shape(style.font, c) {
                Some(shape) => {
                    out.glyphs.extend(draw(shape, pen, baseline, unit));
                    f64::from(i16::from(shape.glyph.right) - i16::from(shape.glyph.left)) * unit
                }
                None => {
                    if !out.missing.contains(&c) {
                        out.missing.push(c);
                    }
                    let s = style.size;
                    let rect = Rect::new(pen + 0.1 * s, baseline - s, pen + 0.7 * s, baseline);
                    out.glyphs.push(rect.to_path(0.0));
                    0.8 * s
                }
            };
        }
        let shift = match style.align {
            Align::Start => 0.0,
            Align::Middle => -pen / 2.0,
            Align::End => -pen,
        };
        if shift != 0.0 {
            for glyph in &mut out.glyphs[first..] {
                glyph.apply_affine(Affine::translate((shift, 0.0)));
            }
        }
        out.width = out.width.max(pen);
        out.lines += 1;
    }
    out
}

/// The strokes of a glyph whose cell starts at `pen` on the baseline at
/// `baseline`, `unit` output units to the font unit; `None` when it has
/// none (a space).
fn draw(shape: Shape<'_>, pen: f64, baseline: f64, unit: f64) -> Option<BezPath> {
    let glyph = shape.glyph;
    let left = f64::from(glyph.left);
    // Scaled (small kana) about the bottom centre of the cell.
    let centre = (left + f64::from(glyph.right)) / 2.0;
    let k = shape.scale;
    let place = |(x, y): (i8, i8)| {
        let u = centre + k * (f64::from(x) - centre);
        let v = BASELINE_UNITS + k * (f64::from(y) - BASELINE_UNITS);
        Point::new(
            pen + (u - left) * unit,
            baseline + (v - BASELINE_UNITS) * unit,
        )
    };
    let mut path = BezPath::new();
    for stroke in glyph.strokes.iter().filter(|s| s.len() >= 2) {
        path.move_to(place(stroke[0]));
        for p in &stroke[1..] {
            path.line_to(place(*p));
        }
    }
    (!path.elements().is_empty()).then_some(path)
}

#[cfg(test)]
mod tests;
