//! The README and the guide (`docs/guide/`) say what works: every scene
//! description they show parses and renders, every `moyo` command of the
//! README's tour and of the guide's shell blocks runs as written, and every
//! file and chapter they name exists.

use std::fs;
use std::path::{Path, PathBuf};

use moyo::spec::{Format, SceneSpec};

use crate::cli::{moyo, tempdir};

/// The repository's top folder.
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// README.md and every chapter of the guide, with their paths.
fn documents() -> Vec<(PathBuf, String)> {
    let mut paths = vec![root().join("README.md")];
    let mut chapters: Vec<PathBuf> = fs::read_dir(root().join("docs/guide"))
        .expect("docs/guide exists")
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "md"))
        .collect();
    chapters.sort();
    paths.extend(chapters);
    paths
        .into_iter()
        .map(|path| {
            let text = fs::read_to_string(&path).unwrap();
            (path, text)
        })
        .collect()
}

/// The bodies of the fenced blocks of `text` opened with `fence`.
fn blocks<'a>(text: &'a str, fence: &str) -> Vec<&'a str> {
    text.split(fence)
        .skip(1)
        .map(|rest| rest.split("```").next().unwrap())
        .collect()
}

#[test]
fn every_scene_description_shown_parses_and_renders() {
    let mut seen = 0;
    for (path, text) in documents() {
        for block in blocks(&text, "```toml\n") {
            // Fragments (e.g. a lone [plot] table) are completed with the
            // one required key.
            let text = if block.contains("version =") {
                block.to_string()
            } else {
                format!("version = 1\n{block}")
            };
            let spec = SceneSpec::parse(&text, Format::Toml).unwrap_or_else(|e| {
                panic!("{}: example does not parse: {e}\n{text}", path.display())
            });
            moyo::project::render(&spec)
                .unwrap_or_else(|e| panic!("{}: {e}\n{text}", path.display()));
            seen += 1;
        }
    }
    assert!(
        seen >= 12,
        "the guide shows its descriptions ({seen} found)"
    );
}

/// The README's five-minute tour runs as written: each `moyo` line of its
/// shell blocks, in order, in a fresh folder that sees the repository's
/// `examples/` (the files the tour names), succeeds and writes the files
/// it names.
#[test]
fn the_readme_tour_runs_as_written() {
    let readme = fs::read_to_string(root().join("README.md")).unwrap();
    let dir = tempdir();
    std::os::unix::fs::symlink(root().join("examples"), dir.path().join("examples")).unwrap();
    let mut ran = 0;
    for block in blocks(&readme, "```sh\n") {
        for line in block.lines() {
            let command = line.split(" #").next().unwrap().trim();
            let Some(args) = command.strip_prefix("moyo ") else {
                continue;
            };
            assert!(
                !args.contains(['"', '\'', '$', '|']),
                "the tour's commands are plain words: {command}"
            );
            let args: Vec<&str> = args.split_whitespace().collect();
            moyo(&dir).args(&args).assert().success();
            for (flag, file) in args.iter().zip(args.iter().skip(1)) {
                if ["-o", "--png"].contains(flag) {
                    let written = dir.path().join(file);
                    assert!(
                        fs::metadata(&written).is_ok_and(|m| m.len() > 0),
                        "`{command}` wrote {file}"
                    );
                }
            }
            ran += 1;
        }
    }
    assert!(ran >= 10, "the tour has its commands ({ran} ran)");
}

/// The words of a shell command line: split at blanks, except inside
/// single or double quotes (which are taken off).
fn shell_words(line: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word: Option<String> = None;
    let mut quote: Option<char> = None;
    for c in line.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => word.get_or_insert_with(String::new).push(c),
            (None, '\'' | '"') => {
                quote = Some(c);
                word.get_or_insert_with(String::new);
            }
            (None, c) if c.is_whitespace() => words.extend(word.take()),
            (None, c) => word.get_or_insert_with(String::new).push(c),
        }
    }
    assert!(quote.is_none(), "an unclosed quote: {line}");
    words.extend(word);
    words
}

/// Every example of the guide runs as written: each `moyo` line of a
/// chapter's shell blocks (```` ```sh ````; a plain block is a synopsis,
/// with placeholders), in order, in a fresh folder per chapter that sees
/// the repository's `examples/`, succeeds and writes the files it names.
#[test]
fn every_example_of_the_guide_runs_as_written() {
    let mut ran = 0;
    for (path, text) in documents().into_iter().skip(1) {
        let dir = tempdir();
        std::os::unix::fs::symlink(root().join("examples"), dir.path().join("examples")).unwrap();
        for block in blocks(&text, "```sh\n") {
            for line in block.lines() {
                let command = line.split(" # ").next().unwrap().trim();
                let Some(args) = command.strip_prefix("moyo ") else {
                    continue;
                };
                let args = shell_words(args);
                let out = moyo(&dir).args(&args).assert();
                let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
                assert!(
                    out.get_output().status.success(),
                    "{}: `{command}` failed:\n{stderr}",
                    path.display()
                );
                for (flag, file) in args.iter().zip(args.iter().skip(1)) {
                    if ["-o", "--png", "--obj", "--frames"].contains(&flag.as_str()) {
                        assert!(
                            dir.path().join(file).exists(),
                            "{}: `{command}` wrote no {file}",
                            path.display()
                        );
                    }
                }
                ran += 1;
            }
        }
    }
    assert!(ran >= 12, "the guide shows its examples ({ran} ran)");
}

/// Links to files in the README and the guide point at files that exist,
/// and the inputs the tour names are in the repository.
#[test]
fn every_file_linked_exists() {
    for (path, text) in documents() {
        let folder = path.parent().unwrap();
        for link in text.split("](").skip(1) {
            let target = link.split(')').next().unwrap();
            let target = target.split('#').next().unwrap();
            if target.is_empty() || target.contains("://") {
                continue;
            }
            assert!(
                folder.join(target).exists(),
                "{} links to {target}, which does not exist",
                path.display()
            );
        }
    }
    for input in ["outline.svg", "cameo.svg", "stroke.svg", "photo.jpg"] {
        assert!(root().join("examples/inputs").join(input).is_file());
    }
}
