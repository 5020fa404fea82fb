//! How a scene's description rides inside an SVG: one
//! `<moyo:scene format="toml">` element of CDATA sections. The SVG writer
//! puts it there ([`write_element`]) and both the SVG import and
//! `moyo render --from-svg` read it back ([`embedded_description`]), so the
//! format lives here, between them, rather than in either.

/// Opening of the embedded scene description, up to the first CDATA section.
const SCENE_OPEN: &str = "<moyo:scene xmlns:moyo=\"https://moyo.invalid/scene\" format=\"toml\">";
const SCENE_CLOSE: &str = "</moyo:scene>";
const CDATA_OPEN: &str = "<![CDATA[";
const CDATA_CLOSE: &str = "]]>";

/// Appends the `<moyo:scene>` element carrying `description`.
pub(crate) fn write_element(out: &mut String, description: &str) {
    out.push_str(SCENE_OPEN);
    write_cdata(out, description);
    out.push_str(SCENE_CLOSE);
}

/// Appends `text` as CDATA. A CDATA section ends at the first "]]>", so that
/// sequence is split across two sections ("]]" ends one, ">" starts the
/// next); an XML reader joins them back into the original text.
fn write_cdata(out: &mut String, text: &str) {
    out.push_str(CDATA_OPEN);
    out.push_str(&text.replace(CDATA_CLOSE, "]]]]><![CDATA[>"));
    out.push_str(CDATA_CLOSE);
}

/// The scene description embedded by [`to_svg`](crate::output::to_svg),
/// exactly as it was given, or `None` when `svg` carries none (or was not
/// written by moyo).
pub fn embedded_description(svg: &str) -> Option<String> {
    let start = svg.find(SCENE_OPEN)? + SCENE_OPEN.len();
    let mut rest = &svg[start..];
    let mut text = String::new();
    // The text may be split over several CDATA sections (see
    // `write_cdata`); since none of them contains "]]>", the first one
    // found closes the current section.
    while let Some(after_open) = rest.strip_prefix(CDATA_OPEN) {
        let end = after_open.find(CDATA_CLOSE)?;
        text.push_str(&after_open[..end]);
        rest = &after_open[end + CDATA_CLOSE.len()..];
    }
    rest.starts_with(SCENE_CLOSE).then_some(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_text_comes_back_exactly() {
        for text in [
            "",
            "seed = 1\n",
            "a = \"]]>\"\nb = ']]]]>' # ]]\n]]>",
            "</moyo:scene> <![CDATA[ & < > \r\n 模様",
        ] {
            let mut svg = String::from("<svg><metadata>");
            write_element(&mut svg, text);
            svg.push_str("</metadata></svg>");
            assert_eq!(embedded_description(&svg).as_deref(), Some(text));
        }
        assert_eq!(embedded_description("<svg/>"), None);
        // A cut-off element is no description.
        let mut svg = String::new();
        write_element(&mut svg, "seed = 1");
        assert_eq!(embedded_description(&svg[..svg.len() - 3]), None);
    }
}
