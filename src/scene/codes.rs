//! AxiDraw's layer codes: what a layer or pen name asks of the plotter
//! beyond its number (AxiDraw Layer Control,
//! <https://wiki.evilmadscientist.com/AxiDraw_Layer_Control>).
//!
//! A name may start (after whitespace) with `!`, a forced pause before the
//! layer is plotted, then the layer number, then any of these codes, each a
//! `+`, a letter (either case) and an integer, written one after the other
//! without spaces:
//!
//! | code | meaning | accepted |
//! |---|---|---|
//! | `+S` | pen-down speed, percent of the machine's maximum | 1–110 |
//! | `+H` | pen-down height, percent of the pen's travel (0 lowest) | 0–100 |
//! | `+D` | delay before the layer, milliseconds | 1 and more |
//!
//! What follows the codes is the human name. As in AxiDraw, a value outside
//! its range is ignored (the code is still read), and when a code appears
//! twice the last one counts: `"!3+s40+d500 fine liner"` pauses, waits half
//! a second, then draws at 40 % speed. moyo reads the codes in a pen's name
//! (an imported SVG's Inkscape layer label after the pen number, or
//! `[[pens]] name` in a scene description) and the G-code and HPGL writers
//! act on them; the SVG writer puts them back into the Inkscape layer label
//! where AxiDraw reads them ([`LayerCodes::label`]).

/// The codes of a layer or pen name (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LayerCodes {
    /// `!`: stop before this layer until the operator resumes.
    pub pause: bool,
    /// `+D`: wait this many milliseconds before the layer.
    pub delay_ms: Option<u32>,
    /// `+H`: pen-down height, 0–100 percent of the pen's travel.
    pub height: Option<u8>,
    /// `+S`: pen-down speed, 1–110 percent of the machine's maximum.
    pub speed: Option<u8>,
}

impl LayerCodes {
    /// The codes of `name` and the text after them (see the module
    /// documentation); the layer number, when there is one, is skipped.
    pub fn parse(name: &str) -> (LayerCodes, &str) {
        let mut codes = LayerCodes::default();
        let mut rest = name.trim_start();
        if let Some(after) = rest.strip_prefix('!') {
            codes.pause = true;
            rest = after;
        }
        rest = rest.trim_start_matches(|c: char| c.is_ascii_digit());
        loop {
            let bytes = rest.as_bytes();
            if bytes.len() < 3 || bytes[0] != b'+' {
                break;
            }
            let key = bytes[1].to_ascii_lowercase();
            if !matches!(key, b'd' | b'h' | b's') {
                break;
            }
            let digits = rest[2..].len()
                - rest[2..]
                    .trim_start_matches(|c: char| c.is_ascii_digit())
                    .len();
            if digits == 0 {
                break;
            }
            // Digits beyond u32 are out of every range: read but ignored.
            let value = rest[2..2 + digits].parse::<u32>().ok();
            rest = &rest[2 + digits..];
            match (key, value) {
                (b'd', Some(v)) if v > 0 => codes.delay_ms = Some(v),
                (b'h', Some(v)) if v <= 100 => codes.height = Some(v as u8),
                (b's', Some(v)) if (1..=110).contains(&v) => codes.speed = Some(v as u8),
                _ => {}
            }
        }
        (codes, rest)
    }

    /// The codes of `name` (see [`LayerCodes::parse`]).
    pub fn of(name: &str) -> LayerCodes {
        LayerCodes::parse(name).0
    }

    /// Whether the name asks for anything.
    pub fn is_empty(&self) -> bool {
        *self == LayerCodes::default()
    }

    /// The Inkscape layer label of pen `number` named `name`, as AxiDraw
    /// reads it: `!` first when the name pauses, then the number, the codes
    /// right after it, and the rest of the name after a space
    /// (`"!3+D500+S40 fine"`). A name without codes gives `"3 fine"`.
    pub fn label(number: u32, name: &str) -> String {
        let (codes, text) = LayerCodes::parse(name);
        let mut out = String::new();
        if codes.pause {
            out.push('!');
        }
        out.push_str(&number.to_string());
        if let Some(d) = codes.delay_ms {
            out.push_str(&format!("+D{d}"));
        }
        if let Some(h) = codes.height {
            out.push_str(&format!("+H{h}"));
        }
        if let Some(s) = codes.speed {
            out.push_str(&format!("+S{s}"));
        }
        let text = if codes.is_empty() {
            name
        } else {
            text.trim_start()
        };
        if !text.is_empty() {
            out.push(' ');
            out.push_str(text);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_follow_axidraw() {
        let cases = [
            ("black", LayerCodes::default(), "black"),
            (
                "+S40 fine",
                LayerCodes {
                    speed: Some(40),
                    ..Default::default()
                },
                " fine",
            ),
            (
                "!3+d500+H20+s40 fine",
                LayerCodes {
                    pause: true,
                    delay_ms: Some(500),
                    height: Some(20),
                    speed: Some(40),
                },
                " fine",
            ),
            (
                "  !pause",
                LayerCodes {
                    pause: true,
                    ..Default::default()
                },
                "pause",
            ),
            // Out of range: read and ignored; the last of a kind counts.
            ("+S0+H101+D0 x", LayerCodes::default(), " x"),
            (
                "+S20+S30",
                LayerCodes {
                    speed: Some(30),
                    ..Default::default()
                },
                "",
            ),
            // Not a code: the text starts there.
            ("+X5 y", LayerCodes::default(), "+X5 y"),
            ("+S y", LayerCodes::default(), "+S y"),
            ("+S99999999999", LayerCodes::default(), ""),
            ("2 +S40", LayerCodes::default(), " +S40"),
        ];
        for (name, codes, rest) in cases {
            assert_eq!(LayerCodes::parse(name), (codes, rest), "{name}");
        }
    }

    #[test]
    fn labels_round_trip() {
        assert_eq!(LayerCodes::label(3, "black"), "3 black");
        assert_eq!(LayerCodes::label(3, ""), "3");
        assert_eq!(LayerCodes::label(2, "!pause"), "!2 pause");
        assert_eq!(LayerCodes::label(4, "+s40+d9 fine"), "4+D9+S40 fine");
        for name in ["!+H20 a", "+S5", "plain"] {
            let label = LayerCodes::label(7, name);
            assert_eq!(LayerCodes::of(&label), LayerCodes::of(name), "{label}");
        }
    }
}
