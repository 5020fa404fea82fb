//! `[[layers.text]]`: a title, a caption or a signature in single-stroke
//! letters, its first baseline starting (or centred, or ending) at `at`,
//! turned by `rotate` degrees clockwise about that point.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::family::Family;
use crate::spec::validate::{point, range};
use crate::text::{TextStyle, MAX_CHARS};

pub use crate::text::{Align, Font};

/// A text on a layer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TextSpec {
    /// Id of the text, unique in its layer (default `text-K`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
    /// What it says (1–10,000 characters; `\n` starts a line).
    pub text: String,
    /// Where the first line's baseline is anchored, mm.
    pub at: [f64; 2],
    /// Cap height, mm (0.5–500, default 5).
    #[serde(default = "default_size")]
    pub size: f64,
    /// Which point of each line stands on `at` (default start).
    #[serde(default, skip_serializing_if = "is_default")]
    pub align: Align,
    /// Turn the text by this many degrees, clockwise about `at` (−360–360).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub rotate: f64,
    /// The typeface: `sans` (default) or `script`.
    #[serde(default, skip_serializing_if = "is_default")]
    pub font: Font,
    /// Added between characters, mm (−10–100, default 0).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub letter_spacing: f64,
    /// Baseline to baseline, in cap heights (0.5–10, default 1.6).
    #[serde(default = "default_line_height")]
    pub line_height: f64,
}

fn default_size() -> f64 {
    5.0
}

fn default_line_height() -> f64 {
    TextStyle::DEFAULT_LINE_HEIGHT
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

fn is_default<T: Default + PartialEq>(v: &T) -> bool {
    *v == T::default()
}

impl TextSpec {
    /// How the text is set.
    pub fn style(&self) -> TextStyle {
        TextStyle {
            font: self.font,
            size: self.size,
            align: self.align,
            letter_spacing: self.letter_spacing,
            line_height: self.line_height,
        }
    }
}

impl Family for TextSpec {
    fn check(&self, f: &str) -> Result<()> {
        let chars = self.text.chars().count();
        if self.text.trim().is_empty() {
            return Err(Error::invalid(
                format!("{f}.text"),
                "says nothing; give the words to draw",
            ));
        }
        if chars > MAX_CHARS {
            return Err(Error::invalid(
                format!("{f}.text"),
                format!("has {chars} characters; at most {MAX_CHARS}"),
            ));
        }
        point(&format!("{f}.at"), self.at)?;
        range(&format!("{f}.size"), self.size, 0.5, 500.0)?;
        range(&format!("{f}.rotate"), self.rotate, -360.0, 360.0)?;
        range(
            &format!("{f}.letter_spacing"),
            self.letter_spacing,
            -10.0,
            100.0,
        )?;
        range(&format!("{f}.line_height"), self.line_height, 0.5, 10.0)
    }
}
