//! `<text>` read from the raw XML and laid out in single strokes
//! ([`crate::text`]): usvg, built without fonts, drops text, so the scan
//! replaces each text element, in the source handed to usvg, by a group
//! with the text's own attributes (id, class, style, transform, paint,
//! visibility…) around a stand-in path. usvg then resolves the text's
//! paint, transforms, `use` and visibility as for any path, and the walk
//! draws the glyphs laid out here, in the text's user space, wherever a
//! stand-in lands. A stand-in is known by its geometry, which holds the
//! text's number ([`stand_in_index`]): usvg drops ids inside a `use`.
//!
//! What is read: the character data of `text`, `tspan` and `a`; `x`,
//! `y`, `dx` and `dy` (the first length of each list); `font-size`,
//! `text-anchor` and `xml:space`, as attributes or in `style`, inherited
//! from the ancestors; `font-family`, only to name it in the warning.
//! Each element with `x` or `y` starts a chunk, which its `text-anchor`
//! puts by its start, middle or end. The cap height is
//! [`CAP_PER_EM`] of the font size. Not read: styles from a stylesheet
//! (the paint comes through usvg, but a stylesheet's `font-size` or
//! `text-anchor` does not), a `tspan`'s own paint (the text's is used),
//! per-character positions after the first, `rotate`, `textLength`,
//! vertical writing, and text on a path (`textPath`, skipped with a
//! warning), as is Inkscape's flowed text (`flowRoot`).

use std::collections::{BTreeSet, HashMap, HashSet};
use std::ops::Range;
use std::str::FromStr;

use kurbo::{Affine, BezPath};
use resvg::usvg::roxmltree::{self, NodeId};
use resvg::usvg::tiny_skia_path;
use svgtypes::{Length, LengthListParser, LengthUnit};

use super::scan::{is_svg, SVG_NS};
use crate::text::{layout, quoted, Align, Font, TextStyle, MAX_CHARS};
use crate::units::MM_PER_INCH;

/// The cap height of imported text, in font sizes: what most fonts'
/// capitals measure (Arial's are 0.716 em, Times's 0.662).
pub(super) const CAP_PER_EM: f64 = 0.7;

/// CSS's `medium`, the font size of a document that names none (px).
const MEDIUM: f64 = 16.0;

const XML_NS: &str = "http://www.w3.org/XML/1998/namespace";

/// The attributes of a text element that only place its characters: the
/// group standing in for it does not take them.
const TEXT_ONLY: &[&str] = &["x", "y", "dx", "dy", "rotate", "textLength", "lengthAdjust"];

/// A text element laid out.
#[derive(Debug)]
pub(super) struct Lettered {
    /// The text element's id (empty when it had none).
    pub id: String,
    /// Its glyphs in its own user space (its `transform` not applied).
    pub path: BezPath,
}

/// A change to the source handed to usvg: the text element at `range`
/// replaced by `markup`, the stand-in of text number `index`.
#[derive(Debug)]
pub(super) struct Edit {
    pub range: Range<usize>,
    pub markup: String,
    pub index: usize,
}

/// What the scan made of the document's text.
#[derive(Debug, Default)]
pub(super) struct Texts {
    /// The laid-out texts, by number (`None` once found not to be in the
    /// source after all).
    pub laid: Vec<Option<Lettered>>,
    /// The replacements that put the stand-ins in the source.
    pub edits: Vec<Edit>,
    /// The font families the texts name, as written (at most
    /// [`MAX_FAMILIES`] of them).
    families: BTreeSet<String>,
    /// Characters without a glyph, each once, in order of appearance.
    missing: Vec<char>,
    /// Characters laid out so far.
    chars: usize,
    /// Text elements skipped: flowed text, text on a path, past the
    /// characters moyo draws, not found in the source.
    flowed: usize,
    on_paths: usize,
    past_limit: usize,
    pub unlocated: usize,
}

/// The most font families a warning names.
const MAX_FAMILIES: usize = 5;

/// What an element hands on to its children, as text layout reads it.
#[derive(Debug, Clone, Copy)]
struct Inherited {
    /// Font size in user units.
    size: f64,
    anchor: Align,
    /// `xml:space="preserve"`.
    preserve: bool,
}

impl Inherited {
    /// The properties of `node`, which inherits `self`.
    fn of(self, node: roxmltree::Node<'_, '_>, px_per_inch: f64) -> Inherited {
        Inherited {
            size: property(node, "font-size")
                .and_then(|v| font_size(v, self.size, px_per_inch))
                .unwrap_or(self.size),
            anchor: match property(node, "text-anchor") {
                Some("start") => Align::Start,
                Some("middle") => Align::Middle,
                Some("end") => Align::End,
                _ => self.anchor,
            },
            preserve: match node.attribute((XML_NS, "space")) {
                Some("preserve") => true,
                Some("default") => false,
                _ => self.preserve,
            },
        }
    }
}

/// One step of a text's content, in document order.
#[derive(Debug)]
enum Piece {
    /// An element's positioning: absolute `x`/`y` start a chunk
    /// anchored by `anchor`; `dx`/`dy` shift the current point.
    Move {
        x: Option<f64>,
        y: Option<f64>,
        dx: f64,
        dy: f64,
        anchor: Align,
    },
    /// Characters at a font size (user units), white space handled.
    Chars { text: String, size: f64 },
}

impl Texts {
    /// Reads every text element of `doc` (parsed from `source`), laying
    /// out those that draw something.
    pub(super) fn read(source: &str, doc: &roxmltree::Document<'_>, px_per_inch: f64) -> Texts {
        let mut texts = Texts::default();
        let mut styles: HashMap<NodeId, Inherited> = HashMap::new();
        for node in doc.descendants() {
            if is_svg(node, "flowRoot") {
                texts.flowed += 1;
                continue;
            }
            // A text inside a text is part of the outer one's content.
            if !is_svg(node, "text") || node.ancestors().skip(1).any(|a| is_svg(a, "text")) {
                continue;
            }
            let style = inherited(node, px_per_inch, &mut styles);
            let pieces = texts.pieces(node, style, px_per_inch);
            let chars: usize = pieces
                .iter()
                .map(|p| match p {
                    Piece::Chars { text, .. } => text.chars().count(),
                    Piece::Move { .. } => 0,
                })
                .sum();
            if chars == 0 {
                continue;
            }
            if texts.chars + chars > MAX_CHARS {
                texts.past_limit += 1;
                continue;
            }
            let path = texts.lay_out(&pieces);
            if path.elements().is_empty() {
                continue;
            }
            texts.chars += chars;
            if texts.families.len() < MAX_FAMILIES {
                if let Some(family) = node
                    .ancestors()
                    .find_map(|a| property(a, "font-family"))
                    .map(|f| f.trim().to_string())
                    .filter(|f| !f.is_empty())
                {
                    texts.families.insert(family);
                }
            }
            let index = texts.laid.len();
            let Some((range, markup)) = stand_in(source, node, index) else {
                texts.unlocated += 1;
                continue;
            };
            texts.laid.push(Some(Lettered {
                id: node.attribute("id").unwrap_or_default().to_string(),
                path,
            }));
            texts.edits.push(Edit {
                range,
                markup,
                index,
            });
        }
        texts
    }

    /// The content of the text element `node` (with properties `style`)
    /// as pieces, white space handled as `xml:space` asks. Text on a path
    /// is left out and counted.
    fn pieces(
        &mut self,
        node: roxmltree::Node<'_, '_>,
        style: Inherited,
        px_per_inch: f64,
    ) -> Vec<Piece> {
        // The text element starts the first chunk, at (0, 0) unless it
        // says otherwise.
        let mut pieces = vec![match position(node, style, px_per_inch) {
            Piece::Move {
                x,
                y,
                dx,
                dy,
                anchor,
            } => Piece::Move {
                x: x.or(Some(0.0)),
                y: y.or(Some(0.0)),
                dx,
                dy,
                anchor,
            },
            chars => chars,
        }];
        // The properties of each element of the content, found before its
        // children (document order), so no recursion however deep.
        let mut styles: HashMap<NodeId, Inherited> = HashMap::from([(node.id(), style)]);
        let mut skipped: HashSet<NodeId> = HashSet::new();
        // Whether the last character kept is a space (leading spaces go).
        let mut after_space = true;
        for n in node.descendants().skip(1) {
            let Some(parent) = n.parent() else { continue };
            if skipped.contains(&parent.id()) {
                skipped.insert(n.id());
                continue;
            }
            let Some(&outer) = styles.get(&parent.id()) else {
                continue;
            };
            if n.is_text() {
                let text = white_space(n.text().unwrap_or_default(), outer, &mut after_space);
                // A font size of 0 draws nothing.
                if !text.is_empty() && outer.size > 0.0 {
                    pieces.push(Piece::Chars {
                        text,
                        size: outer.size,
                    });
                }
            } else if is_svg(n, "tspan") || is_svg(n, "a") {
                let own = outer.of(n, px_per_inch);
                styles.insert(n.id(), own);
                if is_svg(n, "tspan") {
                    pieces.push(position(n, own, px_per_inch));
                }
            } else if n.is_element() {
                if is_svg(n, "textPath") {
                    self.on_paths += 1;
                }
                // Titles, descriptions and the rest hold no characters
                // to draw.
                skipped.insert(n.id());
            }
        }
        // Trailing spaces go too, unless preserved.
        if !style.preserve {
            if let Some(Piece::Chars { text, .. }) = pieces
                .iter_mut()
                .rev()
                .find(|p| matches!(p, Piece::Chars { .. }))
            {
                let kept = text.trim_end_matches(' ').len();
                text.truncate(kept);
            }
        }
        pieces
    }

    /// The glyphs of `pieces` in the text's user space.
    fn lay_out(&mut self, pieces: &[Piece]) -> BezPath {
        let mut path = BezPath::new();
        // The current point, and the chunk being set: where it starts,
        // how it is anchored and its glyphs.
        let (mut x, mut y) = (0.0, 0.0);
        let mut start = 0.0;
        let mut anchor = Align::Start;
        let mut chunk: Vec<BezPath> = Vec::new();
        let mut end_chunk = |chunk: &mut Vec<BezPath>, x: &mut f64, start: f64, anchor| {
            let width: f64 = *x - start;
            let shift = match anchor {
                Align::Start => 0.0,
                Align::Middle => -width / 2.0,
                Align::End => -width,
            };
            *x += shift;
            for glyph in chunk.drain(..) {
                path.extend(
                    (Affine::translate((shift, 0.0)) * glyph)
                        .elements()
                        .iter()
                        .copied(),
                );
            }
        };
        for piece in pieces {
            match piece {
                Piece::Move {
                    x: to_x,
                    y: to_y,
                    dx,
                    dy,
                    anchor: own,
                } => {
                    if to_x.is_some() || to_y.is_some() {
                        end_chunk(&mut chunk, &mut x, start, anchor);
                        x = to_x.unwrap_or(x);
                        y = to_y.unwrap_or(y);
                        start = x;
                        anchor = *own;
                    }
                    x += dx;
                    y += dy;
                }
                Piece::Chars { text, size } => {
                    let lettering = layout(text, &TextStyle::new(size * CAP_PER_EM));
                    for c in &lettering.missing {
                        if !self.missing.contains(c) {
                            self.missing.push(*c);
                        }
                    }
                    let here = Affine::translate((x, y));
                    chunk.extend(lettering.glyphs.into_iter().map(|g| here * g));
                    x += lettering.width;
                }
            }
        }
        end_chunk(&mut chunk, &mut x, start, anchor);
        let finite = path.elements().iter().all(|e| {
            e.end_point()
                .is_none_or(|p| p.x.is_finite() && p.y.is_finite())
        });
        if finite {
            path
        } else {
            BezPath::new()
        }
    }

    /// One sentence per kind of news: the font substitution (for the `n`
    /// texts drawn), missing characters, and the text left out.
    pub(super) fn warnings(&self, n: usize) -> Vec<String> {
        let mut out = Vec::new();
        if n > 0 {
            let elements = if n == 1 { "element" } else { "elements" };
            let fonts = if self.families.is_empty() {
                "the document's font".to_string()
            } else {
                let names: Vec<&str> = self.families.iter().map(String::as_str).collect();
                names.join("; ")
            };
            out.push(format!(
                "{n} text {elements} drawn in moyo's single-stroke {} in place of {fonts}",
                Font::Sans.name()
            ));
        }
        if !self.missing.is_empty() {
            out.push(format!(
                "no single-stroke glyph for {}: drawn as boxes",
                quoted(&self.missing)
            ));
        }
        let mut skipped = |n: usize, one: &str, many: &str, why: &str| {
            if n > 0 {
                let what = if n == 1 { one } else { many };
                out.push(format!("skipped {n} {what}: {why}"));
            }
        };
        skipped(
            self.flowed,
            "flowed text element",
            "flowed text elements",
            "flowed text (flowRoot) is not imported (convert it to text, \
             Inkscape's Text > Convert to Text, or to paths)",
        );
        skipped(
            self.on_paths,
            "text path",
            "text paths",
            "text along a path (textPath) is not imported (convert it to paths first)",
        );
        skipped(
            self.past_limit,
            "text element",
            "text elements",
            &format!(
                "past the first {} characters of text, the most moyo draws from one file",
                crate::output::grouped(MAX_CHARS)
            ),
        );
        skipped(
            self.unlocated,
            "text element",
            "text elements",
            "it could not be located in the source (it comes from an entity?)",
        );
        out
    }
}

/// The properties `node` (an element) inherits from its ancestors,
/// remembered in `styles` for the next text that shares them.
fn inherited(
    node: roxmltree::Node<'_, '_>,
    px_per_inch: f64,
    styles: &mut HashMap<NodeId, Inherited>,
) -> Inherited {
    let mut chain = Vec::new();
    let mut style = Inherited {
        size: MEDIUM,
        anchor: Align::Start,
        preserve: false,
    };
    for a in node.ancestors().filter(|a| a.is_element()) {
        if let Some(&known) = styles.get(&a.id()) {
            style = known;
            break;
        }
        chain.push(a);
    }
    for a in chain.into_iter().rev() {
        style = style.of(a, px_per_inch);
        styles.insert(a.id(), style);
    }
    style
}

/// The positioning attributes of `node`: the first length of `x`, `y`,
/// `dx` and `dy` in user units (none that is not a finite length).
fn position(node: roxmltree::Node<'_, '_>, style: Inherited, px_per_inch: f64) -> Piece {
    let first = |name| {
        let value = node.attribute(name)?;
        let length = LengthListParser::from(value).next()?.ok()?;
        user_units(length, style.size, px_per_inch)
    };
    Piece::Move {
        x: first("x"),
        y: first("y"),
        dx: first("dx").unwrap_or(0.0),
        dy: first("dy").unwrap_or(0.0),
        anchor: style.anchor,
    }
}

/// A length in user units (px), ems of `font_size`; `None` for a
/// percentage (of a viewport moyo does not track for text) or a number
/// that is not finite.
fn user_units(length: Length, font_size: f64, px_per_inch: f64) -> Option<f64> {
    let n = length.number;
    let v = match length.unit {
        LengthUnit::None | LengthUnit::Px => n,
        LengthUnit::Em => n * font_size,
        LengthUnit::Ex => n * font_size / 2.0,
        LengthUnit::Mm => n * px_per_inch / MM_PER_INCH,
        LengthUnit::Cm => n * px_per_inch / MM_PER_INCH * 10.0,
        LengthUnit::In => n * px_per_inch,
        LengthUnit::Pt => n * px_per_inch / 72.0,
        LengthUnit::Pc => n * px_per_inch / 6.0,
        LengthUnit::Percent => return None,
    };
    v.is_finite().then_some(v)
}

/// A `font-size` value in user units, given the parent's; `None` when it
/// is not one (the parent's then holds).
fn font_size(value: &str, parent: f64, px_per_inch: f64) -> Option<f64> {
    let keyword = match value {
        "xx-small" => Some(9.0),
        "x-small" => Some(10.0),
        "small" => Some(13.0),
        "medium" => Some(MEDIUM),
        "large" => Some(18.0),
        "x-large" => Some(24.0),
        "xx-large" => Some(32.0),
        "larger" => Some(parent * 1.2),
        "smaller" => Some(parent / 1.2),
        _ => None,
    };
    let size = match keyword {
        Some(size) => size,
        None => {
            let length = Length::from_str(value).ok()?;
            match length.unit {
                LengthUnit::Percent => length.number / 100.0 * parent,
                _ => user_units(length, parent, px_per_inch)?,
            }
        }
    };
    (size.is_finite() && size >= 0.0).then_some(size)
}

/// A presentation property of `node`: the last declaration of it in its
/// `style` attribute, else its attribute of that name.
pub(super) fn property<'a>(node: roxmltree::Node<'a, '_>, name: &str) -> Option<&'a str> {
    let declared = node.attribute("style").and_then(|style| {
        style
            .rsplit(';')
            .filter_map(|decl| decl.split_once(':'))
            .find(|(key, _)| key.trim() == name)
            .map(|(_, value)| value.trim().trim_end_matches("!important").trim())
    });
    declared.or_else(|| node.attribute(name).map(str::trim))
}

/// `raw` character data with white space handled as SVG's `xml:space`
/// says: newlines dropped (spaces when preserved), tabs as spaces, and,
/// unless preserved, runs of spaces as one and none at the start
/// (`after_space` carries that across pieces).
fn white_space(raw: &str, style: Inherited, after_space: &mut bool) -> String {
    let mut out = String::new();
    for c in raw.chars() {
        let c = match c {
            '\n' | '\r' if !style.preserve => continue,
            '\n' | '\r' | '\t' => ' ',
            c => c,
        };
        if c == ' ' && *after_space && !style.preserve {
            continue;
        }
        *after_space = c == ' ';
        out.push(c);
    }
    out
}

/// The replacement of the text element `node` in `source`: a group with
/// the element's attributes but those that place characters, around the
/// stand-in path of text number `index` (with no markers). `None` when
/// the element is not where its range says (it comes from an entity).
fn stand_in(
    source: &str,
    node: roxmltree::Node<'_, '_>,
    index: usize,
) -> Option<(Range<usize>, String)> {
    let range = node.range();
    let element = source.get(range.clone())?;
    let tag = element.strip_prefix('<')?;
    let qname = &tag[..tag.find(|c: char| c.is_whitespace() || c == '/' || c == '>')?];
    if !element.ends_with('>') || qname.rsplit(':').next() != Some("text") {
        return None;
    }
    // In SVG's namespace whatever prefix, if any, the text had there.
    let mut markup = format!("<g xmlns=\"{SVG_NS}\"");
    for attr in node.attributes() {
        if attr.namespace().is_some() || TEXT_ONLY.contains(&attr.name()) {
            continue;
        }
        markup.push_str(&format!(" {}=\"{}\"", attr.name(), escape(attr.value())));
    }
    markup.push_str(&format!(
        "><path d=\"{}\" marker-start=\"none\" marker-mid=\"none\" marker-end=\"none\"/></g>",
        stand_in_data(index)
    ));
    Some((range, markup))
}

/// Texts a stand-in can number: one per character at the most.
const STAND_INS: usize = 1 << 15;
const _: () = assert!(MAX_CHARS < STAND_INS);

/// The stand-in of text number `index` (below [`STAND_INS`]): a unit
/// square, which any paint fills, then a line from (0, ½) to (½ +
/// index/2¹⁵, ½), a number `f32` holds exactly, as usvg keeps it.
fn stand_in_data(index: usize) -> String {
    format!("M0 0H1V1H0ZM0 0.5H{}", stand_in_end(index))
}

fn stand_in_end(index: usize) -> f32 {
    0.5 + index as f32 / STAND_INS as f32
}

/// The number of the text whose stand-in `data` is, if it is one.
pub(super) fn stand_in_index(data: &tiny_skia_path::Path) -> Option<usize> {
    use tiny_skia_path::PathVerb::{Close, Line, Move};
    if data.verbs() != [Move, Line, Line, Line, Close, Move, Line] {
        return None;
    }
    let points: Vec<(f32, f32)> = data.points().iter().map(|p| (p.x, p.y)).collect();
    let [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.0, 0.5), (end, 0.5)] = points[..]
    else {
        return None;
    };
    let index = ((end - 0.5) * STAND_INS as f32).round();
    if !(0.0..STAND_INS as f32).contains(&index) {
        return None;
    }
    let index = index as usize;
    (stand_in_end(index) == end).then_some(index)
}

/// `value` as the content of a double-quoted attribute.
fn escape(value: &str) -> String {
    let mut out = String::with_capacity(value.len());
    for c in value.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '"' => out.push_str("&quot;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests;
