//! The ready scene descriptions in `templates/`, built into the binary.

use crate::error::{Error, Result};
use crate::spec::{Format, SceneSpec, ValidSpec};

/// A built-in scene description.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Template {
    /// Name, as given to `moyo new NAME`.
    pub name: &'static str,
    /// The TOML text.
    pub text: &'static str,
}

/// The template `moyo render` uses when no scene is given.
pub const DEFAULT: &str = "kimono-1";

/// `Template`s for files `templates/<name>.toml`.
macro_rules! templates {
    ($($name:literal),* $(,)?) => {
        &[$(Template {
            name: $name,
            text: include_str!(concat!("../templates/", $name, ".toml")),
        }),*]
    };
}

/// Every template, in listing order.
pub const ALL: &[Template] = templates![
    "kimono-1",
    "kimono-2",
    "kimono-3",
    "kimono-4",
    "kimono-5",
    "kimono-6",
    "kimono-7",
    "kimono-8",
    "tomesode-hem",
    "tree-rules",
    "voronoi-stained-glass",
    "cracked-earth",
];

impl Template {
    /// The template's parsed description.
    pub fn spec(&self) -> Result<ValidSpec> {
        SceneSpec::parse(self.text, Format::Toml)
    }

    /// Its one-line description (the `description` field).
    pub fn summary(&self) -> String {
        self.spec()
            .ok()
            .and_then(|s| s.into_inner().description)
            .unwrap_or_default()
    }
}

/// The template called `name`.
pub fn get(name: &str) -> Result<&'static Template> {
    ALL.iter()
        .find(|t| t.name == name)
        .ok_or_else(|| Error::UnknownTemplate {
            name: name.to_string(),
            available: ALL.iter().map(|t| t.name).collect::<Vec<_>>().join(", "),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_template_parses_and_has_a_summary() {
        for t in ALL {
            let spec = t.spec().unwrap_or_else(|e| panic!("{}: {e}", t.name));
            assert!(spec.description.is_some(), "{} has no description", t.name);
        }
        assert!(get(DEFAULT).is_ok());
        assert!(get("nope")
            .unwrap_err()
            .to_string()
            .contains("tomesode-hem"));
    }
}
