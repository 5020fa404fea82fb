//! The scene-description examples in README.md parse, so the reference
//! cannot drift from the format.

use moyo::spec::{Format, SceneSpec};

#[test]
fn readme_toml_examples_parse() {
    let readme = include_str!("../README.md");
    let blocks: Vec<&str> = readme
        .split("```toml\n")
        .skip(1)
        .map(|rest| rest.split("```").next().unwrap())
        .collect();
    assert!(blocks.len() >= 2, "README has its TOML examples");
    for block in blocks {
        // Fragments (e.g. a lone [plot] table) are completed with the one
        // required key.
        let text = if block.contains("version =") {
            block.to_string()
        } else {
            format!("version = 1\n{block}")
        };
        let spec = SceneSpec::parse(&text, Format::Toml)
            .unwrap_or_else(|e| panic!("README example does not parse: {e}\n{text}"));
        moyo::project::render(&spec).unwrap_or_else(|e| panic!("{e}"));
    }
}
