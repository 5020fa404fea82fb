//! The embedded Hershey fonts (`fonts/`, whose README gives their source
//! and licence): James Hurt's format read into glyphs, and which glyph
//! draws which character.
//!
//! A glyph's coordinates are Hershey's units, y down: capitals stand from
//! y = −12 to the baseline at y = 9 (a cap height of 21 units), and the
//! Japanese glyphs share that frame, so the fonts mix on one line at one
//! size. The files are parsed once, on first use.

use std::collections::BTreeMap;
use std::sync::OnceLock;

use serde::{Deserialize, Serialize};

/// The cap height, in font units.
pub(super) const CAP_UNITS: f64 = 21.0;
/// Where the baseline lies, in font units (y down).
pub(super) const BASELINE_UNITS: f64 = 9.0;

/// A single-stroke typeface of the embedded Hershey fonts. Both have the
/// printable ASCII characters (32–126) of their own and share the
/// Japanese glyphs (kana, 。、ー and 24 kanji).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Font {
    /// Hershey's simplex sans serif (`futural`), one line per stroke.
    #[default]
    Sans,
    /// Hershey's simplex script (`scripts`): joined, slanted letters for a
    /// signature (its digits are drawn with doubled lines).
    Script,
}

impl Font {
    /// What warnings and documents call it.
    pub fn name(self) -> &'static str {
        match self {
            Font::Sans => "Hershey Sans",
            Font::Script => "Hershey Script",
        }
    }
}

/// One glyph: its left and right edges (the advance is the distance
/// between them) and its strokes, each a polyline drawn pen down.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Glyph {
    pub left: i8,
    pub right: i8,
    pub strokes: Vec<Vec<(i8, i8)>>,
}

const FUTURAL: &str = include_str!("fonts/futural.jhf");
const SCRIPTS: &str = include_str!("fonts/scripts.jhf");
const JAPANESE: &str = include_str!("fonts/japanese.jhf");

/// The characters of `japanese.jhf`'s 193 glyphs in file order, read off
/// the glyphs (the file names none). `_` marks a glyph left unmapped: the
/// dots that fill unused places, and the repeats that complete the old
/// fifty-sound table (い, え and う in the や and わ rows, and an old form
/// of え).
const JAPANESE_CHARS: &str = concat!(
    "。、ー日円年大国人東中本京出時上者十一二三四五六七入九______",
    "あいうえおかきくけこさしすせそたちつてとなにぬねのはひふへほまみむめも",
    "や_ゆ_よらりるれろわゐ_ゑをん____",
    "がぎぐげござじずぜぞだぢづでどばびぶべぼぱぴぷぺぽ",
    "アイウエオカキクケコサシスセソタチツテトナニヌネノハヒフヘホマミムメモ",
    "ヤ_ユ_ヨラリルレロワヰ_ヱヲン____",
    "ガギグゲゴザジズゼゾダヂヅデドバビブベボパピプペポ",
);

/// Small kana, drawn as their full-size kana scaled by [`SMALL_KANA`]
/// about the bottom centre of the glyph's cell.
const SMALL: &[(char, char)] = &[
    ('ぁ', 'あ'),
    ('ぃ', 'い'),
    ('ぅ', 'う'),
    ('ぇ', 'え'),
    ('ぉ', 'お'),
    ('っ', 'つ'),
    ('ゃ', 'や'),
    ('ゅ', 'ゆ'),
    ('ょ', 'よ'),
    ('ゎ', 'わ'),
    ('ァ', 'ア'),
    ('ィ', 'イ'),
    ('ゥ', 'ウ'),
    ('ェ', 'エ'),
    ('ォ', 'オ'),
    ('ッ', 'ツ'),
    ('ャ', 'ヤ'),
    ('ュ', 'ユ'),
    ('ョ', 'ヨ'),
    ('ヮ', 'ワ'),
    ('ヵ', 'カ'),
    ('ヶ', 'ケ'),
];

/// How much smaller a small kana is than its full-size kana.
pub(super) const SMALL_KANA: f64 = 0.7;

/// The glyph a character is drawn with, and the scale it is drawn at
/// about the bottom centre of its cell (1 but for small kana).
#[derive(Debug, Clone, Copy)]
pub(super) struct Shape<'a> {
    pub glyph: &'a Glyph,
    pub scale: f64,
}

/// Every glyph, parsed.
struct Fonts {
    sans: Vec<Glyph>,
    script: Vec<Glyph>,
    /// The Japanese glyphs and those moyo draws itself (an em dash, the
    /// ideographic space), by character.
    shared: BTreeMap<char, Glyph>,
}

fn fonts() -> &'static Fonts {
    static FONTS: OnceLock<Fonts> = OnceLock::new();
    FONTS.get_or_init(|| {
        let mut shared: BTreeMap<char, Glyph> = JAPANESE_CHARS
            .chars()
            .zip(parse(JAPANESE))
            .filter(|(c, _)| *c != '_')
            .collect();
        // An em dash a little longer than the hyphen's 18 units, and a
        // space as wide as a kana.
        shared.insert(
            '—',
            Glyph {
                left: -16,
                right: 16,
                strokes: vec![vec![(-14, 0), (14, 0)]],
            },
        );
        shared.insert(
            '\u{3000}',
            Glyph {
                left: -14,
                right: 13,
                strokes: Vec::new(),
            },
        );
        Fonts {
            sans: parse(FUTURAL),
            script: parse(SCRIPTS),
            shared,
        }
    })
}

/// The glyph that draws `c` in `font` (after [`normalise`]), if any.
pub(super) fn shape(font: Font, c: char) -> Option<Shape<'static>> {
    let fonts = fonts();
    let ascii = match font {
        Font::Sans => &fonts.sans,
        Font::Script => &fonts.script,
    };
    let full = |glyph| Shape { glyph, scale: 1.0 };
    if (' '..='~').contains(&c) {
        return ascii.get(c as usize - ' ' as usize).map(full);
    }
    if let Some(glyph) = fonts.shared.get(&c) {
        return Some(full(glyph));
    }
    let (_, big) = SMALL.iter().find(|(small, _)| *small == c)?;
    fonts.shared.get(big).map(|glyph| Shape {
        glyph,
        scale: SMALL_KANA,
    })
}

/// The character whose glyph draws `c`: full-width ASCII as ASCII, the
/// typographer's quotes, dashes and spaces as their plain forms, a tab as
/// a space; anything else as it is.
pub(super) fn normalise(c: char) -> char {
    match c {
        '\u{FF01}'..='\u{FF5E}' => char::from_u32(c as u32 - 0xFEE0).unwrap_or(c),
        '\t' | '\u{A0}' | '\u{2002}'..='\u{200A}' | '\u{202F}' | '\u{205F}' => ' ',
        '‘' | '’' | '‚' | '′' => '\'',
        '“' | '”' | '„' | '″' => '"',
        '‐' | '‑' | '‒' | '–' | '−' => '-',
        '―' => '—',
        _ => c,
    }
}

/// The glyphs of a file in James Hurt's format, in file order. Line
/// breaks are not part of a record (some copies of these files wrap long
/// records), so they are dropped first; a record that does not parse ends
/// the list.
fn parse(data: &str) -> Vec<Glyph> {
    let bytes: Vec<u8> = data
        .bytes()
        .filter(|b| !matches!(b, b'\n' | b'\r'))
        .collect();
    let mut glyphs = Vec::new();
    let mut at = 0;
    while at + 8 <= bytes.len() {
        let count = std::str::from_utf8(&bytes[at + 5..at + 8])
            .ok()
            .and_then(|n| n.trim().parse::<usize>().ok());
        let Some(count) = count.filter(|n| *n >= 1) else {
            break;
        };
        let end = at + 8 + 2 * count;
        let Some(pairs) = bytes.get(at + 8..end) else {
            break;
        };
        let coord = |b: u8| (i16::from(b) - i16::from(b'R')) as i8;
        let mut strokes: Vec<Vec<(i8, i8)>> = vec![Vec::new()];
        for pair in pairs[2..].chunks_exact(2) {
            if pair == b" R" {
                strokes.push(Vec::new());
            } else if let Some(stroke) = strokes.last_mut() {
                stroke.push((coord(pair[0]), coord(pair[1])));
            }
        }
        strokes.retain(|s| !s.is_empty());
        glyphs.push(Glyph {
            left: coord(pairs[0]),
            right: coord(pairs[1]),
            strokes,
        });
        at = end;
    }
    glyphs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_record_of_every_file_is_read() {
        assert_eq!(parse(FUTURAL).len(), 96);
        assert_eq!(parse(SCRIPTS).len(), 96);
        assert_eq!(parse(JAPANESE).len(), 193);
        assert_eq!(JAPANESE_CHARS.chars().count(), 193);
    }

    #[test]
    fn each_japanese_character_is_mapped_once() {
        let mapped: Vec<char> = JAPANESE_CHARS.chars().filter(|c| *c != '_').collect();
        let distinct: std::collections::BTreeSet<char> = mapped.iter().copied().collect();
        assert_eq!(mapped.len(), distinct.len());
        // 73 hiragana (the 46 of today, ゐ and ゑ, 25 voiced), as many
        // katakana, 。、ー and 24 kanji.
        assert_eq!(mapped.len(), 2 * 73 + 3 + 24);
    }

    #[test]
    fn capitals_stand_on_the_baseline_at_cap_height() {
        for font in [Font::Sans, Font::Script] {
            let h = shape(font, 'H').unwrap().glyph;
            let ys: Vec<i8> = h.strokes.iter().flatten().map(|p| p.1).collect();
            let (top, bottom) = (*ys.iter().min().unwrap(), *ys.iter().max().unwrap());
            assert_eq!(f64::from(bottom), BASELINE_UNITS, "{font:?}");
            assert!(
                (f64::from(bottom - top) - CAP_UNITS).abs() <= 1.0,
                "{font:?}"
            );
        }
    }

    #[test]
    fn records_split_over_lines_read_as_one_and_a_broken_one_ends_the_list() {
        let whole = "12345  6JZRFR[ RKFYF\n12345  3NVRFR[\n";
        let split = "12345  6JZRFR[\n RKFYF\n12345  3NVRF\nR[\n";
        assert_eq!(parse(whole), parse(split));
        assert_eq!(parse(whole).len(), 2);
        assert_eq!(
            parse(whole)[0].strokes,
            vec![vec![(0, -12), (0, 9)], vec![(-7, -12), (7, -12)]]
        );
        assert_eq!(parse("12345  6JZRF").len(), 0);
        assert_eq!(parse("12345  xJZRF").len(), 0);
    }

    #[test]
    fn typographic_forms_fall_back_on_plain_ones() {
        assert_eq!(normalise('Ａ'), 'A');
        assert_eq!(normalise('２'), '2');
        assert_eq!(normalise('’'), '\'');
        assert_eq!(normalise('–'), '-');
        assert_eq!(normalise('\u{A0}'), ' ');
        assert_eq!(normalise('秋'), '秋');
        assert!(shape(Font::Sans, '—').is_some());
        assert!(shape(Font::Sans, 'ー').is_some());
        assert!(shape(Font::Script, 'ッ').is_some_and(|s| s.scale < 1.0));
        assert!(shape(Font::Sans, '秋').is_none());
    }
}
