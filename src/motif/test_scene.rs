//! Scenes for the families' tests: a one-layer A5 description (10 mm
//! margins, seed 5) around one table of a family, built or refused.

use crate::project::build_scene;
use crate::scene::Scene;
use crate::spec::{Format, SceneSpec};

/// The description of one `[[layers.<family>]]` table with `table`'s
/// lines in it.
pub(crate) fn text(family: &str, table: &str) -> String {
    format!(
        "version = 1\nseed = 5\npage = {{ size = \"A5\", margin = 10 }}\n\
         [[layers]]\nname = \"l\"\n[[layers.{family}]]\n{table}"
    )
}

/// The scene of that description; panics with the text when it fails.
pub(crate) fn scene(family: &str, table: &str) -> Scene {
    let text = text(family, table);
    let spec = SceneSpec::parse(&text, Format::Toml).unwrap_or_else(|e| panic!("{e}\n{text}"));
    build_scene(&spec).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The error that description gives; panics when it is accepted.
pub(crate) fn error(family: &str, table: &str) -> String {
    let text = text(family, table);
    match SceneSpec::parse(&text, Format::Toml).and_then(|s| build_scene(&s)) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// The notes a render of that description gives the user (their texts).
pub(crate) fn notes(family: &str, table: &str) -> Vec<String> {
    let spec = SceneSpec::parse(&text(family, table), Format::Toml).unwrap();
    crate::project::render(&spec)
        .unwrap()
        .notes
        .into_iter()
        .map(|n| n.text)
        .collect()
}

/// The scene of any description after its plot stages but the pen stage
/// (layers, groups and ids kept, see
/// [`crate::project::render_for_editing`]), with no user files.
pub(crate) fn editing(spec: &crate::spec::ValidSpec) -> Scene {
    let library = crate::motif::Library::new();
    let cancel = crate::project::Cancel::default();
    crate::project::render_for_editing(spec, &library, &mut |_| {}, &cancel)
        .unwrap_or_else(|e| panic!("{e}"))
        .scene
}
