//! The ready scene descriptions in `templates/`, built into the binary,
//! with the files they read (images under `templates/images/`), so a
//! template renders anywhere, not only beside the repository's files.

use crate::error::{Error, Result};
use crate::motif::Library;
use crate::project::{load_motifs_with, render_with_progress, Rendered};
use crate::spec::{Format, SceneSpec, ValidSpec};

/// A built-in scene description.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Template {
    /// Name, as given to `moyo new NAME`.
    pub name: &'static str,
    /// The TOML text.
    pub text: &'static str,
}

/// The template `moyo render` and `moyo studio` use when no scene is
/// given: the same design from either door.
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
    "stipple-portrait",
    "stipple-lbg",
    "zentangle-1",
    "zentangle-2",
    "zentangle-10",
    "zentangle-50",
    "zentangle-200",
    "zentangle-string",
    "zentangle-ring",
    "zentangle-geometric",
    "zentangle-voronoi",
    "wagara",
    "text-titled",
    "kimono-tangles",
    "zentangle-tangles",
    "delaunay-lowpoly",
    "lsystem-plant-a",
    "lsystem-plant-d",
    "lsystem-plant-f",
    "lsystem-koch",
    "lsystem-hilbert",
    "lsystem-dragon",
    "lsystem-bush",
    "lsystem-tree",
    "lsystem-ternary",
    "lsystem-sketch-straight",
    "lsystem-sketch-s",
    "lsystem-sketch-spiral",
    "kimono-lsystem",
    "vine-basic",
    "vine-internode-100",
    "vine-radius-4",
    "vine-right",
    "vine-interval-5",
    "vine-angle-30",
    "vine-untwined-2",
    "vine-woody",
    "vine-cotyledons-2",
    "vine-opposite",
    "vine-leaf-25",
    "vine-growth",
    "vine-leaves",
    "vine-cross",
    "vine-fence",
    "vine-orbit",
    "vine-border",
    "kimono-vine",
    "kimono-egasumi",
    "kimono-bokashi",
    "katagami",
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

/// The files templates read, by the name they use (relative to
/// `templates/`), compiled in.
pub const FILES: &[(&str, &[u8])] = &[(
    "images/portrait.jpg",
    include_bytes!("../templates/images/portrait.jpg"),
)];

/// A built-in file by the name a template uses for it.
pub fn file(name: &str) -> Option<&'static [u8]> {
    FILES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, bytes)| *bytes)
}

impl Template {
    /// The user files the template names, read from the built-in
    /// [`FILES`].
    ///
    /// # Errors
    /// [`Error::Motif`] for a file that is not built in or cannot be used.
    pub fn library(&self) -> Result<Library> {
        load_motifs_with(&self.spec()?, &|name| {
            let bytes = file(name).map(<[u8]>::to_vec).ok_or_else(|| {
                std::io::Error::new(std::io::ErrorKind::NotFound, "not among the built-in files")
            });
            (format!("built-in {name}"), bytes)
        })
    }

    /// The template rendered with its built-in files.
    ///
    /// # Errors
    /// As [`crate::render`].
    pub fn render(&self) -> Result<Rendered> {
        render_with_progress(&self.spec()?, &self.library()?, &mut |_| {})
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
