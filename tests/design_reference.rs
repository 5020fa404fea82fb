//! The design reference, docs/SPEC.md, holds every section the source's
//! `docs/SPEC.md §x.y` comments point to.

use std::path::Path;

/// Every `.rs` file below `dir`.
fn sources(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn every_section_the_source_cites_is_in_the_design_reference() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let reference = std::fs::read_to_string(root.join("docs/SPEC.md")).unwrap();
    let headings: Vec<&str> = reference
        .lines()
        .filter(|l| l.starts_with("## ") || l.starts_with("### "))
        .map(|l| l.trim_start_matches('#').trim())
        .collect();
    let mut files = Vec::new();
    sources(&root.join("src"), &mut files);
    let mut cited = 0;
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        for (at, _) in text.match_indices("docs/SPEC.md §") {
            let number: String = text[at + "docs/SPEC.md §".len()..]
                .chars()
                .take_while(|c| c.is_ascii_digit() || *c == '.')
                .collect();
            let number = number.trim_end_matches('.');
            assert!(
                !number.is_empty(),
                "{}: a § without a number",
                file.display()
            );
            // `## 1. Kimono …` or `### 1.6 Background layer`.
            let found = headings.iter().any(|h| {
                h.strip_prefix(number)
                    .is_some_and(|rest| rest.starts_with(". ") || rest.starts_with(' '))
            });
            assert!(
                found,
                "{} cites §{number}, which docs/SPEC.md lacks",
                file.display()
            );
            cited += 1;
        }
    }
    assert!(cited > 40, "only {cited} citations found");
}
