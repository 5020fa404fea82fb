//! Finds where a field path (`layers[0].trees[1].params.ratio1`) stands in
//! TOML text, so validation errors can point at a line and column.

use toml::de::DeTable;

use crate::error::LineCol;

/// The line and column of the value at `path`, or of the deepest part of
/// the path that exists.
pub(crate) fn toml_field(text: &str, path: &str) -> Option<LineCol> {
    let root = DeTable::parse(text).ok()?;
    let mut segs = segments(path).into_iter();
    let Some(Segment::Key(first)) = segs.next() else {
        return None;
    };
    let mut node = root.get_ref().get(first)?;
    for seg in segs {
        let next = match seg {
            Segment::Key(k) => node.get_ref().get(k),
            Segment::Index(i) => node.get_ref().get(i),
        };
        match next {
            Some(n) => node = n,
            None => break,
        }
    }
    Some(LineCol::of_offset(text, node.span().start))
}

enum Segment<'a> {
    Key(&'a str),
    Index(usize),
}

fn segments(path: &str) -> Vec<Segment<'_>> {
    let mut out = Vec::new();
    for part in path.split('.') {
        let (key, rest) = match part.find('[') {
            Some(i) => (&part[..i], &part[i..]),
            None => (part, ""),
        };
        if !key.is_empty() {
            out.push(Segment::Key(key));
        }
        for idx in rest.split('[').filter(|s| !s.is_empty()) {
            if let Ok(i) = idx.trim_end_matches(']').parse() {
                out.push(Segment::Index(i));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_nested_array_of_tables() {
        let text = "version = 1\n[[layers]]\nname = \"a\"\n[[layers]]\nname = \"b\"\n\
                    [[layers.trees]]\nrule = \"tree1\"\n[layers.trees.params]\nratio1 = 9.0\n";
        let at = toml_field(text, "layers[1].trees[0].params.ratio1").unwrap();
        assert_eq!((at.line, at.column), (9, 10));
        let at = toml_field(text, "version").unwrap();
        assert_eq!((at.line, at.column), (1, 11));
        assert!(toml_field(text, "nothing").is_none());
    }
}
