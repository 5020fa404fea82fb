//! Colours of pens and fills, as `#rrggbb`, named, or a palette's slot.

use std::fmt;

use super::traditional::{traditional, Palette};

/// An sRGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Color {
    /// Red 0–255.
    pub r: u8,
    /// Green 0–255.
    pub g: u8,
    /// Blue 0–255.
    pub b: u8,
}

/// CSS names accepted besides hex notation.
const NAMED: [(&str, Color); 12] = [
    ("black", Color::rgb(0, 0, 0)),
    ("white", Color::rgb(255, 255, 255)),
    ("red", Color::rgb(255, 0, 0)),
    ("green", Color::rgb(0, 128, 0)),
    ("blue", Color::rgb(0, 0, 255)),
    ("navy", Color::rgb(0, 0, 128)),
    ("gray", Color::rgb(128, 128, 128)),
    ("grey", Color::rgb(128, 128, 128)),
    ("brown", Color::rgb(165, 42, 42)),
    ("gold", Color::rgb(255, 215, 0)),
    ("crimson", Color::rgb(220, 20, 60)),
    ("indigo", Color::rgb(75, 0, 130)),
];

impl Color {
    /// Black.
    pub const BLACK: Color = Color::rgb(0, 0, 0);

    /// A colour from its components.
    pub const fn rgb(r: u8, g: u8, b: u8) -> Color {
        Color { r, g, b }
    }

    /// Parses `#rgb`, `#rrggbb`, one of a few CSS names (black, white,
    /// red, green, blue, navy, gray/grey, brown, gold, crimson, indigo) or
    /// a traditional Japanese colour ([`super::traditional`]: `ai-iro`,
    /// `ai` or `藍色`). A palette slot (`@1`–`@5`) needs its palette:
    /// [`Color::parse_in`].
    pub fn parse(s: &str) -> Option<Color> {
        let s = s.trim();
        if let Some(hex) = s.strip_prefix('#') {
            let digit = |c: u8| (c as char).to_digit(16).map(|d| d as u8);
            let b = hex.as_bytes();
            return match b.len() {
                3 => Some(Color::rgb(
                    digit(b[0])? * 17,
                    digit(b[1])? * 17,
                    digit(b[2])? * 17,
                )),
                6 => Some(Color::rgb(
                    digit(b[0])? * 16 + digit(b[1])?,
                    digit(b[2])? * 16 + digit(b[3])?,
                    digit(b[4])? * 16 + digit(b[5])?,
                )),
                _ => None,
            };
        }
        NAMED
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(s))
            .map(|(_, c)| *c)
            .or_else(|| traditional(s).map(|t| t.color))
    }

    /// As [`Color::parse`], and `@1`–`@5` for the colours of `palette`.
    pub fn parse_in(s: &str, palette: &Palette) -> Option<Color> {
        match slot(s) {
            Some(n) => palette.slot(n),
            None => Color::parse(s),
        }
    }

    /// Whether `s` is a colour in some palette: what [`Color::parse`]
    /// reads, or a palette slot `@1`–`@5`.
    pub fn is_valid(s: &str) -> bool {
        Color::parse(s).is_some() || slot(s).is_some_and(|n| (1..=5).contains(&n))
    }

    /// Darker towards black for `brightness` < 1, lighter towards white
    /// above 1 (0 is black, 2 is white).
    pub fn shaded(self, brightness: f64) -> Color {
        let b = brightness.clamp(0.0, 2.0);
        let (target, t) = if b <= 1.0 {
            (0.0, 1.0 - b)
        } else {
            (255.0, b - 1.0)
        };
        self.map(|c| c + (target - c) * t)
    }

    /// The colour seen when painted with `opacity` (0–1) on white paper.
    pub fn over_white(self, opacity: f64) -> Color {
        let a = opacity.clamp(0.0, 1.0);
        self.map(|c| 255.0 + (c - 255.0) * a)
    }

    fn map(self, f: impl Fn(f64) -> f64) -> Color {
        let ch = |c: u8| f(f64::from(c)).round().clamp(0.0, 255.0) as u8;
        Color::rgb(ch(self.r), ch(self.g), ch(self.b))
    }
}

/// The palette slot `@n` names, if `s` is one.
fn slot(s: &str) -> Option<usize> {
    s.trim().strip_prefix('@')?.parse().ok()
}

impl fmt::Display for Color {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{:02x}{:02x}{:02x}", self.r, self.g, self.b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_hex_and_names() {
        assert_eq!(Color::parse("#fff"), Some(Color::rgb(255, 255, 255)));
        assert_eq!(Color::parse("#1a2B3c"), Some(Color::rgb(0x1a, 0x2b, 0x3c)));
        assert_eq!(Color::parse("Navy"), Some(Color::rgb(0, 0, 128)));
        assert_eq!(Color::parse("#12345"), None);
        assert_eq!(Color::parse("#gg0000"), None);
        assert_eq!(Color::parse("chartreuse-ish"), None);
        assert_eq!(Color::rgb(1, 2, 255).to_string(), "#0102ff");
        assert_eq!(Color::parse("ai-iro"), Color::parse("藍色"));
        assert!(Color::parse("Ai").is_some());
    }

    #[test]
    fn slots_take_their_palettes_colours() {
        use super::super::traditional::{palette, traditional};
        let kaga = palette("kaga-gosai").unwrap();
        let kyo = palette("kyo").unwrap();
        assert_eq!(
            Color::parse_in("@2", kaga),
            traditional("ai-iro").map(|t| t.color)
        );
        assert_eq!(
            Color::parse_in("@1", kyo),
            traditional("shu-iro").map(|t| t.color)
        );
        assert_eq!(Color::parse_in("#fff", kyo), Color::parse("#fff"));
        assert_eq!(Color::parse_in("@6", kyo), None);
        assert_eq!(Color::parse("@1"), None);
        assert!(Color::is_valid("@5") && Color::is_valid("moegi"));
        assert!(!Color::is_valid("@0") && !Color::is_valid("@6") && !Color::is_valid("@x"));
    }

    #[test]
    fn brightness_and_opacity_mix_towards_black_and_paper() {
        let c = Color::rgb(200, 100, 0);
        assert_eq!(c.shaded(1.0), c);
        assert_eq!(c.shaded(0.0), Color::BLACK);
        assert_eq!(c.shaded(2.0), Color::rgb(255, 255, 255));
        assert_eq!(c.shaded(0.5), Color::rgb(100, 50, 0));
        assert_eq!(c.over_white(1.0), c);
        assert_eq!(c.over_white(0.0), Color::rgb(255, 255, 255));
        assert_eq!(c.over_white(0.5), Color::rgb(228, 178, 128));
    }
}
