//! Paths to pens, and the scene: one bucket of paths per top-level layer
//! (with the layer label's pen number), per colour or cluster of colours
//! (k-means in OKLab, at most a given number of pens), or one for
//! everything, documentation layers kept apart and numbered after the
//! plotted pens, no pen past 999; then one scene layer per bucket, pens
//! with their most common colour and width, and ids unique in the scene.

use std::collections::{BTreeMap, HashMap, HashSet};

use super::scan::LayerSource;
use super::walk::{Drawn, Walked};
use crate::error::{Error, Result};
use crate::output::grouped;
#[cfg(doc)]
use crate::scene::LayerCodes;
use crate::scene::{Color, Group, Layer, Pen, Scene, Style, UniqueIds};
use crate::units::Page;

/// Width of a pen none of whose paths is stroked (a fine liner).
const DEFAULT_PEN_WIDTH: f64 = 0.3;

/// Pen numbers a layer label may carry (as in the scene description).
const PEN_NUMBERS: std::ops::RangeInclusive<u32> = 1..=999;

/// One future scene layer: a pen number, names and its paths (indices
/// into the drawn list, in paint order).
#[derive(Debug)]
pub(super) struct Bucket {
    pen: u32,
    pen_name: String,
    layer_name: String,
    members: Vec<usize>,
    /// False for a documentation layer (its `layer_name` starts with `%`).
    plotted: bool,
}

impl Bucket {
    /// A bucket for a documentation layer labelled `label`; its pen is
    /// numbered later, after every plotted pen ([`number_unplotted`]).
    fn unplotted(label: &str) -> Bucket {
        let name = label.trim().to_string();
        Bucket {
            pen: 0,
            pen_name: name.clone(),
            layer_name: name,
            members: Vec::new(),
            plotted: false,
        }
    }
}

/// Gives each documentation layer's bucket a pen of its own: the smallest
/// numbers no other bucket uses, in document order. They come after all the
/// plotted pens are numbered, so a `%` layer never changes the numbering of
/// the layers that are plotted.
fn number_unplotted(buckets: &mut [Bucket]) {
    let mut taken: HashSet<u32> = buckets
        .iter()
        .filter(|b| b.plotted)
        .map(|b| b.pen)
        .collect();
    for bucket in buckets.iter_mut().filter(|b| !b.plotted) {
        let n = (1..)
            .find(|n| !taken.contains(n))
            .expect("some number is free");
        taken.insert(n);
        bucket.pen = n;
    }
}

/// One bucket per found top-level layer (in document order), plus one for
/// paths outside every layer.
pub(super) fn by_layer(
    layers: &[LayerSource],
    walked: &Walked,
    warnings: &mut Vec<String>,
) -> Vec<Bucket> {
    // Documentation layers claim no pen number: "% 2 notes" is not pen 2.
    let labels: Vec<(Option<u32>, String)> = layers
        .iter()
        .map(|l| {
            if l.plotted {
                split_label(&l.label)
            } else {
                (None, String::new())
            }
        })
        .collect();
    let mut taken: HashSet<u32> = labels.iter().filter_map(|(n, _)| *n).collect();
    let mut next_free = || {
        let n = (1..)
            .find(|n| !taken.contains(n))
            .expect("some number is free");
        taken.insert(n);
        n
    };
    let mut buckets = Vec::new();
    let mut index_of = vec![None; layers.len()];
    for (i, (layer, (number, name))) in layers.iter().zip(labels).enumerate() {
        if !walked.found[i] {
            let why = if layer.hidden {
                "it is hidden"
            } else {
                "it is hidden or has nothing usvg could draw"
            };
            warnings.push(format!("skipped layer '{}': {why}", layer.label));
            continue;
        }
        index_of[i] = Some(buckets.len());
        if !layer.plotted {
            buckets.push(Bucket::unplotted(&layer.label));
            continue;
        }
        let pen = number.unwrap_or_else(&mut next_free);
        // The layer keeps the whole label when the rest alone would be no
        // name, or would read as a documentation layer ("3 %odd" is
        // plotted, with pen 3).
        let layer_name = if name.is_empty() || !Layer::name_is_plotted(&name) {
            layer.label.clone()
        } else {
            name.clone()
        };
        buckets.push(Bucket {
            pen,
            pen_name: name,
            layer_name,
            members: Vec::new(),
            plotted: true,
        });
    }
    let mut outside = Vec::new();
    for (k, d) in walked.drawn.iter().enumerate() {
        match d.layer.and_then(|i| index_of[i]) {
            Some(b) => buckets[b].members.push(k),
            None => outside.push(k),
        }
    }
    if !outside.is_empty() {
        let pen = next_free();
        let n = outside.len();
        let paths = if n == 1 { "path" } else { "paths" };
        warnings.push(format!(
            "{n} {paths} outside every layer went to an extra layer 'unlayered' (pen {pen})"
        ));
        buckets.push(Bucket {
            pen,
            pen_name: "unlayered".into(),
            layer_name: "unlayered".into(),
            members: outside,
            plotted: true,
        });
    }
    number_unplotted(&mut buckets);
    buckets
}

/// Splits `"3 blue"` into pen 3 and `blue`; a label without a leading pen
/// number (1–999) is all name. Whitespace before the number and
/// separators after it (whitespace, `-`, `_`, `:`) are dropped, so
/// `"3-blue"`, `"3_blue"`, `"3: blue"` and `" 3 blue"` are all pen 3 named
/// `blue`.
///
/// AxiDraw's forced pause, a `!` before the number, stays with the name
/// (`"!2 pause"` is pen 2 named `!pause`), and so do the codes after the
/// number (`"3+S40 fine"` is pen 3 named `+S40 fine`): the writers act on
/// them ([`LayerCodes`]).
fn split_label(label: &str) -> (Option<u32>, String) {
    let label = label.trim();
    let (pause, numbered) = match label.strip_prefix('!') {
        Some(rest) => ("!", rest),
        None => ("", label),
    };
    let digits = numbered.len()
        - numbered
            .trim_start_matches(|c: char| c.is_ascii_digit())
            .len();
    match numbered[..digits].parse::<u32>() {
        Ok(n) if PEN_NUMBERS.contains(&n) => {
            let rest = numbered[digits..]
                .trim_start_matches(|c: char| c.is_whitespace() || "-_:".contains(c));
            (Some(n), format!("{pause}{}", rest.trim_end()))
        }
        _ => (None, label.to_string()),
    }
}

/// How [`by_color`] turns colours into pens.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum ColorPens {
    /// One pen per colour, the colours clustered into at most this many
    /// pens when there are more; 0: no clustering.
    AtMost(u32),
    /// Every plotted path on pen 1.
    Single,
}

/// One bucket per colour (stroke, else fill), or per cluster of colours
/// ([`ColorPens`]), pens numbered in order of first appearance; the paths
/// of each documentation layer (`%` label) stay apart, in a bucket of
/// their own after the colours. Paint that no pen draws
/// ([`Drawn::paint_only`]) takes no pen of its own: it goes, in paint
/// order, with the first pen, whose layer the writer puts behind the other
/// pens' (the white page behind a graphviz graph is no pen to load, and
/// must not cover the graph in the preview).
///
/// # Errors
///
/// [`Error::Invalid`] when one pen per colour (`AtMost(0)`) would number
/// pens past 999.
pub(super) fn by_color(
    drawn: &[Drawn],
    layers: &[LayerSource],
    policy: ColorPens,
    warnings: &mut Vec<String>,
) -> Result<Vec<Bucket>> {
    let plotted = |d: &Drawn| d.layer.is_none_or(|i| layers[i].plotted);
    let color_of = |d: &Drawn| d.stroke.map(|(c, _)| c).or(d.fill);
    let first_pen = drawn
        .iter()
        .filter(|d| !d.paint_only && plotted(d))
        .find_map(color_of);
    // The distinct colours in order of first appearance, with their use
    // (paths), and each plotted path's colour (index into `colors`).
    let mut colors: Vec<(Color, usize)> = Vec::new();
    let mut index: HashMap<u32, usize> = HashMap::new();
    let mut plotted_paths: Vec<(usize, usize)> = Vec::new();
    // Documentation layer (index into `layers`) → its paths.
    let mut unplotted: BTreeMap<usize, Vec<usize>> = Default::default();
    for (k, d) in drawn.iter().enumerate() {
        let Some(own) = color_of(d) else {
            continue;
        };
        if let Some(i) = d.layer.filter(|&i| !layers[i].plotted) {
            unplotted.entry(i).or_default().push(k);
            continue;
        }
        let color = match first_pen {
            Some(first) if d.paint_only => first,
            _ => own,
        };
        let c = *index.entry(color_key(color)).or_insert_with(|| {
            colors.push((color, 0));
            colors.len() - 1
        });
        colors[c].1 += 1;
        plotted_paths.push((k, c));
    }
    let group_of: Vec<usize> = match policy {
        ColorPens::Single => vec![0; colors.len()],
        ColorPens::AtMost(n) if n > 0 && colors.len() > n as usize => {
            let groups = cluster(&colors, n as usize);
            let pens = groups.iter().max().map_or(0, |g| g + 1);
            warnings.push(format!(
                "{} colours merged into {} by nearest colour (OKLab); --pens N to \
                 choose, --pens 0 for one pen per colour up to {}",
                grouped(colors.len()),
                if pens == 1 {
                    "1 pen".to_string()
                } else {
                    format!("{pens} pens")
                },
                PEN_NUMBERS.end()
            ));
            groups
        }
        ColorPens::AtMost(_) => {
            if colors.len() > *PEN_NUMBERS.end() as usize {
                return Err(Error::invalid(
                    "pens",
                    format!(
                        "one pen per colour would make {} pens, more than the {} a plot \
                         allows; merge them into fewer (--pens N, N at most {})",
                        grouped(colors.len()),
                        PEN_NUMBERS.end(),
                        PEN_NUMBERS.end()
                    ),
                ));
            }
            (0..colors.len()).collect()
        }
    };
    // Group → bucket, in order of first appearance (the colours are).
    let mut bucket_of: HashMap<usize, usize> = HashMap::new();
    let mut buckets: Vec<Bucket> = Vec::new();
    for (c, &group) in group_of.iter().enumerate() {
        bucket_of.entry(group).or_insert_with(|| {
            // A pen's name is its most used colour, ties to the first seen.
            let name = group_of
                .iter()
                .zip(&colors)
                .filter(|(&g, _)| g == group)
                .map(|(_, &(color, uses))| (color, uses))
                .fold(colors[c], |best, x| if x.1 > best.1 { x } else { best })
                .0
                .to_string();
            buckets.push(Bucket {
                pen: buckets.len() as u32 + 1,
                pen_name: name.clone(),
                layer_name: name,
                members: Vec::new(),
                plotted: true,
            });
            buckets.len() - 1
        });
    }
    for (k, c) in plotted_paths {
        buckets[bucket_of[&group_of[c]]].members.push(k);
    }
    for (i, members) in unplotted {
        let mut bucket = Bucket::unplotted(&layers[i].label);
        bucket.members = members;
        buckets.push(bucket);
    }
    number_unplotted(&mut buckets);
    Ok(buckets)
}

/// Refuses buckets whose pens are numbered past 999: more layers, or
/// documentation layers, than a plot has pen numbers for.
pub(super) fn check_pen_numbers(buckets: &[Bucket]) -> Result<()> {
    let most = *PEN_NUMBERS.end();
    match buckets.iter().map(|b| b.pen).max() {
        Some(top) if top > most => Err(Error::invalid(
            "svg",
            format!(
                "the document's layers need pen numbers up to {}, past the {most} a plot \
                 allows; merge layers, or read it by colour",
                grouped(top as usize)
            ),
        )),
        _ => Ok(()),
    }
}

/// Lloyd iterations at most; they stop as soon as no colour changes cluster.
const CLUSTER_ROUNDS: usize = 32;

/// Colour-to-centre distances the Lloyd iterations may compute in all:
/// 100,000 colours into 999 pens would otherwise take seconds a round.
/// Fewer rounds leave the clusters a little less even, never wrong: every
/// colour is still on the pen of its nearest centre.
const CLUSTER_BUDGET: usize = 200_000_000;

/// Clusters `colors` (each with its use) into at most `n` groups by
/// nearest colour in OKLab, deterministically: the first centre is the
/// most used colour (ties to the first seen), each next one the colour
/// farthest from every centre so far (maximin; ties to the more used, then
/// the first seen); then weighted k-means (Lloyd) steps move each centre
/// to the use-weighted mean of its colours. Returns each colour's group,
/// groups numbered in order of first appearance, with no gaps.
fn cluster(colors: &[(Color, usize)], n: usize) -> Vec<usize> {
    let labs: Vec<[f64; 3]> = colors.iter().map(|&(c, _)| oklab(c)).collect();
    let better = |a: (f64, usize, usize), b: (f64, usize, usize)| {
        // (distance, use, position): larger distance, larger use, earlier.
        a.0 > b.0 || (a.0 == b.0 && (a.1 > b.1 || (a.1 == b.1 && a.2 < b.2)))
    };
    let mut centres: Vec<[f64; 3]> = Vec::new();
    let mut nearest = vec![f64::INFINITY; colors.len()];
    while centres.len() < n {
        let mut pick: Option<(f64, usize, usize)> = None;
        for (i, &(_, uses)) in colors.iter().enumerate() {
            let candidate = (nearest[i], uses, i);
            if pick.is_none_or(|p| better(candidate, p)) {
                pick = Some(candidate);
            }
        }
        match pick {
            Some((d, _, i)) if d > 0.0 => {
                centres.push(labs[i]);
                for (near, lab) in nearest.iter_mut().zip(&labs) {
                    *near = near.min(distance2(lab, &labs[i]));
                }
            }
            // Every colour is a centre already.
            _ => break,
        }
    }
    let assign = |centres: &[[f64; 3]]| -> Vec<usize> {
        labs.iter()
            .map(|lab| {
                (0..centres.len())
                    .min_by(|&a, &b| {
                        distance2(lab, &centres[a]).total_cmp(&distance2(lab, &centres[b]))
                    })
                    .unwrap_or(0)
            })
            .collect()
    };
    let mut groups = assign(&centres);
    let rounds = (CLUSTER_BUDGET / (colors.len() * centres.len()).max(1)).min(CLUSTER_ROUNDS);
    for _ in 0..rounds {
        let mut sums = vec![([0.0; 3], 0.0); centres.len()];
        for ((lab, &g), &(_, uses)) in labs.iter().zip(&groups).zip(colors) {
            let w = uses as f64;
            for (s, v) in sums[g].0.iter_mut().zip(lab) {
                *s += v * w;
            }
            sums[g].1 += w;
        }
        for (centre, (sum, weight)) in centres.iter_mut().zip(sums) {
            // A centre left without colours stays where it is.
            if weight > 0.0 {
                *centre = sum.map(|s| s / weight);
            }
        }
        let next = assign(&centres);
        if next == groups {
            break;
        }
        groups = next;
    }
    // Renumber by first appearance.
    let mut renumbered: HashMap<usize, usize> = HashMap::new();
    groups
        .into_iter()
        .map(|g| {
            let k = renumbered.len();
            *renumbered.entry(g).or_insert(k)
        })
        .collect()
}

fn distance2(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// An sRGB colour in OKLab (L, a, b), after Björn Ottosson, "A perceptual
/// color space for image processing" (2020,
/// <https://bottosson.github.io/posts/oklab/>): the sRGB transfer curve
/// undone, linear RGB to LMS cone responses by his matrix `M1`, a cube
/// root, then `M2` to L, a, b. Euclidean distance there is close to a
/// perceived colour difference, far better than in RGB.
fn oklab(c: Color) -> [f64; 3] {
    let linear = |v: u8| {
        let v = f64::from(v) / 255.0;
        if v <= 0.04045 {
            v / 12.92
        } else {
            ((v + 0.055) / 1.055).powf(2.4)
        }
    };
    let (r, g, b) = (linear(c.r), linear(c.g), linear(c.b));
    let l = (0.412_221_470_8 * r + 0.536_332_536_3 * g + 0.051_445_992_9 * b).cbrt();
    let m = (0.211_903_498_2 * r + 0.680_699_545_1 * g + 0.107_396_956_6 * b).cbrt();
    let s = (0.088_302_461_9 * r + 0.281_718_837_6 * g + 0.629_978_700_5 * b).cbrt();
    [
        0.210_454_255_3 * l + 0.793_617_785_0 * m - 0.004_072_046_8 * s,
        1.977_998_495_1 * l - 2.428_592_205_0 * m + 0.450_593_709_9 * s,
        0.025_904_037_1 * l + 0.782_771_766_2 * m - 0.808_675_766_0 * s,
    ]
}

fn color_key(c: Color) -> u32 {
    u32::from_be_bytes([0, c.r, c.g, c.b])
}

/// The most frequent value by `key`, ties going to the one seen first.
fn most_common<T: Copy, K: std::hash::Hash + Eq>(
    values: impl IntoIterator<Item = T>,
    key: impl Fn(T) -> K,
) -> Option<T> {
    // key → (count, first position, value)
    let mut counts: HashMap<K, (usize, usize, T)> = HashMap::new();
    for (i, v) in values.into_iter().enumerate() {
        counts.entry(key(v)).or_insert((0, i, v)).0 += 1;
    }
    counts
        .into_values()
        .max_by_key(|&(n, first, _)| (n, std::cmp::Reverse(first)))
        .map(|(_, _, v)| v)
}

/// Builds the scene. `stacked`: the buckets are in paint order (layers),
/// so the first is the furthest back; colour buckets all get depth 0.
pub(super) fn assemble(
    page: Page,
    buckets: Vec<Bucket>,
    stacked: bool,
    drawn: Vec<Drawn>,
    description: Option<String>,
    warnings: &mut Vec<String>,
) -> Scene {
    // Pen number → its buckets, in ascending pen order.
    let mut of_pen: BTreeMap<u32, Vec<&Bucket>> = Default::default();
    for bucket in &buckets {
        of_pen.entry(bucket.pen).or_default().push(bucket);
    }
    let numbers: Vec<u32> = of_pen.keys().copied().collect();

    let mut pens = Vec::new();
    for (&number, pen_buckets) in &of_pen {
        let members = || {
            pen_buckets
                .iter()
                .flat_map(|b| b.members.iter().map(|&k| &drawn[k]))
        };
        let strokes = || members().filter_map(|d| d.stroke);
        // Paint no pen draws says nothing of the pen's colour, unless the
        // pen has nothing else.
        let fills = |paint: bool| members().filter(move |d| paint || !d.paint_only);
        let color = most_common(strokes().map(|(c, _)| c), color_key)
            .or_else(|| most_common(fills(false).filter_map(|d| d.fill), color_key))
            .or_else(|| most_common(fills(true).filter_map(|d| d.fill), color_key))
            .unwrap_or(Color::BLACK);
        let width =
            most_common(strokes().map(|(_, w)| w), f64::to_bits).unwrap_or(DEFAULT_PEN_WIDTH);
        let colors: HashSet<u32> = strokes().map(|(c, _)| color_key(c)).collect();
        // Pens from colours say once, on import, how colours were merged.
        if stacked && colors.len() > 1 {
            warnings.push(format!(
                "pen {number} draws {} stroke colours; it takes the most common one, {color}",
                colors.len()
            ));
        }
        pens.push(Pen {
            number,
            name: pen_buckets[0].pen_name.clone(),
            color,
            width,
        });
    }

    // The writer names its pen layers `pen-N`; keep those free.
    let mut ids = UniqueIds::reserving(numbers.iter().map(|n| format!("pen-{n}")));
    let layer_ids: Vec<(String, String)> = (1..=buckets.len())
        .map(|k| {
            let id = ids.unique(&format!("layer-{k}"));
            let group = ids.unique(&format!("{id}-paths"));
            (id, group)
        })
        .collect();
    let mut drawn: Vec<Option<Drawn>> = drawn.into_iter().map(Some).collect();
    let count = buckets.len();
    let layers = buckets
        .into_iter()
        .zip(layer_ids)
        .enumerate()
        .map(|(i, (bucket, (id, group_id)))| {
            let mut content = Group::new(group_id);
            for (n, k) in bucket.members.into_iter().enumerate() {
                let d = drawn[k].take().expect("each path is in one bucket");
                let wanted = if d.id.is_empty() {
                    format!("{id}-path-{}", n + 1)
                } else {
                    d.id
                };
                content.push_path(
                    ids.unique(&wanted),
                    d.path,
                    Style {
                        // Glyphs are lines: their fill chose the pen.
                        fill: d.fill.filter(|_| !d.glyphs),
                        fill_only: d.paint_only,
                        ..Style::default()
                    },
                );
            }
            Layer {
                id,
                name: bucket.layer_name,
                pen: bucket.pen,
                depth: if stacked { (count - 1 - i) as i32 } else { 0 },
                content,
            }
        })
        .collect();
    Scene {
        page,
        pens,
        layers,
        description,
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{assert_rect_near, doc, import, paths};
    use super::super::{import_svg, ImportOptions, PenGrouping};
    use crate::geom::path_length;
    use crate::scene::Color;
    use kurbo::{Rect, Shape};

    #[test]
    fn inkscape_layers_become_numbered_pens() {
        let imported = import(&doc(
            r##"<g id="L"><path d="M0 90 L10 90" stroke="#008000" fill="none"/></g>
            <g inkscape:groupmode="layer" id="layer1" inkscape:label="3 blue"
               style="stroke:#0000ff;stroke-width:0.5;fill:none">
              <path d="M0 0 L10 0"/>
              <g transform="translate(0 5)"><path id="second" d="M0 0 L10 0"/></g>
              <g inkscape:groupmode="layer" inkscape:label="sub-layer"><path d="M0 9 L10 9"/></g>
            </g>
            <g inkscape:groupmode="layer" inkscape:label="Outline" stroke="#ff0000"
               stroke-width="0.25" fill="none">
              <rect x="1" y="1" width="5" height="5"/>
            </g>
            <g inkscape:groupmode="layer" id="layer3" inkscape:label="1 black" stroke="black"
               fill="none" stroke-width="2" transform="scale(0.5)">
              <circle cx="10" cy="10" r="4"/>
            </g>
            <g inkscape:groupmode="layer" id="hid" inkscape:label="4 hidden"
               style="display: none" stroke="black">
              <path d="M0 0 L1 1"/>
            </g>
            <g inkscape:groupmode="layer" id="L" inkscape:label="2 - green" stroke="#008000">
              <path d="M0 50 L10 50" fill="none"/>
            </g>"##,
        ));
        let scene = &imported.scene;
        let pens: Vec<(u32, &str, String, f64)> = scene
            .pens
            .iter()
            .map(|p| (p.number, p.name.as_str(), p.color.to_string(), p.width))
            .collect();
        // "Outline" takes the smallest free number (5); the unlayered path
        // comes after it (6); the hidden layer's pen 4 is unused. Without a
        // stroke-width, SVG's default of one user unit (here 1 mm) holds.
        assert_eq!(
            pens,
            [
                (1, "black", "#000000".to_string(), 1.0),
                (2, "green", "#008000".to_string(), 1.0),
                (3, "blue", "#0000ff".to_string(), 0.5),
                (5, "Outline", "#ff0000".to_string(), 0.25),
                (6, "unlayered", "#008000".to_string(), 1.0),
            ]
        );
        let layers: Vec<(&str, u32, i32, usize)> = scene
            .layers
            .iter()
            .map(|l| (l.name.as_str(), l.pen, l.depth, l.content.children.len()))
            .collect();
        assert_eq!(
            layers,
            [
                ("blue", 3, 4, 3),
                ("Outline", 5, 3, 1),
                ("black", 1, 2, 1),
                ("green", 2, 1, 1),
                ("unlayered", 6, 0, 1),
            ]
        );
        // The layer's transform is baked in: circle at (5, 5), radius 2.
        let circle = &paths(scene)[4].1;
        assert_rect_near(circle.bounding_box(), Rect::new(3.0, 3.0, 7.0, 7.0), 1e-4);
        // Element ids survive; the rest are made from the layer's.
        let ids: Vec<String> = scene.layers[0]
            .content
            .children
            .iter()
            .map(|n| match n {
                crate::scene::Node::Path(p) => p.id.clone(),
                crate::scene::Node::Group(g) => panic!("flat layers, got {}", g.id),
            })
            .collect();
        assert_eq!(ids, ["layer-1-path-1", "second", "layer-1-path-3"]);
        assert_eq!(
            imported.warnings,
            [
                "skipped layer '4 hidden': it is hidden",
                "1 path outside every layer went to an extra layer 'unlayered' (pen 6)",
            ]
        );
    }

    #[test]
    fn without_layers_pens_follow_stroke_colours() {
        let imported = import(&doc(r##"<path d="M0 0 L10 0" stroke="red"/>
               <path d="M0 1 L10 1" stroke="#00f" stroke-width="0.7" fill="none"/>
               <path d="M0 2 L10 2" stroke="rgb(255,0,0)" fill="none"/>
               <rect x="0" y="5" width="5" height="5" fill="green"/>
               <path d="M0 3 L10 3" fill="none"/>
               <path d="M0 4 L10 4" fill="none" stroke="none"/>
               <path d="M0 4 L10 4" stroke="red" fill="none" visibility="hidden"/>"##));
        let scene = &imported.scene;
        let pens: Vec<(u32, String, String, f64)> = scene
            .pens
            .iter()
            .map(|p| (p.number, p.name.clone(), p.color.to_string(), p.width))
            .collect();
        assert_eq!(
            pens,
            [
                (1, "#ff0000".into(), "#ff0000".into(), 1.0),
                (2, "#0000ff".into(), "#0000ff".into(), 0.7),
                (3, "#008000".into(), "#008000".into(), 0.3),
            ]
        );
        assert_eq!(scene.pen_stats(1).paths, 2);
        assert_eq!(scene.pen_stats(2).paths, 1);
        assert_eq!(scene.pen_stats(3).paths, 1);
        assert!(scene.layers.iter().all(|l| l.depth == 0));
        // The fill-only rect is a region; SVG's default black fill stays on
        // the first line, as the renderer would paint it.
        let all = paths(scene);
        assert_eq!(all[3].2.fill, Some(Color::rgb(0, 128, 0)));
        assert_eq!(all[0].2.fill, Some(Color::BLACK));
        assert_eq!(all[1].2.fill, None);
        assert_eq!(
            imported.warnings,
            [
                "skipped 2 paths: no fill and no stroke",
                "skipped 1 path: hidden by `visibility`",
            ]
        );
    }

    #[test]
    fn inkscape_file_with_sublayer_hidden_layer_and_text() {
        let imported = import(include_str!(
            "../../../tests/fixtures/import/inkscape_layers.svg"
        ));
        let scene = &imported.scene;
        assert_eq!((scene.page.width, scene.page.height), (210.0, 297.0));
        let pens: Vec<(u32, &str, String, f64)> = scene
            .pens
            .iter()
            .map(|p| (p.number, p.name.as_str(), p.color.to_string(), p.width))
            .collect();
        assert_eq!(
            pens,
            [
                (1, "black outline", "#000000".to_string(), 0.5),
                (2, "red", "#ff0000".to_string(), 0.3),
            ]
        );
        // The sub-layer's wave belongs to pen 1.
        assert_eq!(scene.pen_stats(1).paths, 3);
        // The circle and the title.
        assert_eq!(scene.pen_stats(2).paths, 2);
        let all = paths(scene);
        assert_eq!(all[1].2.fill, Some(Color::rgb(0xd4, 0xaa, 0x00)));
        // The layer's translate(10,-5) is baked in.
        assert_rect_near(
            all[3].1.bounding_box(),
            Rect::new(135.0, 30.0, 185.0, 80.0),
            1e-3,
        );
        assert_eq!(
            imported.warnings,
            [
                "1 text element drawn in moyo's single-stroke Hershey Sans in place of \
                 sans-serif",
                "skipped layer '3 guides': it is hidden",
            ]
        );
    }

    #[test]
    fn axidraw_documentation_layers_are_imported_but_not_plotted() {
        let imported = import(include_str!(
            "../../../tests/fixtures/import/axidraw_layers.svg"
        ));
        assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
        let scene = &imported.scene;
        let pens: Vec<(u32, &str, String, f64)> = scene
            .pens
            .iter()
            .map(|p| (p.number, p.name.as_str(), p.color.to_string(), p.width))
            .collect();
        // The documentation layers' pens come after the plotted ones.
        assert_eq!(
            pens,
            [
                (1, "black", "#000000".to_string(), 0.3),
                (2, "red", "#ff0000".to_string(), 0.5),
                (3, "%guides", "#00aaff".to_string(), 0.2),
                (4, "% 2 notes", "#888888".to_string(), 0.1),
            ]
        );
        let layers: Vec<(&str, u32, i32, bool, usize)> = scene
            .layers
            .iter()
            .map(|l| {
                let n = l.content.children.len();
                (l.name.as_str(), l.pen, l.depth, l.is_plotted(), n)
            })
            .collect();
        assert_eq!(
            layers,
            [
                ("%guides", 3, 3, false, 2),
                ("black", 1, 2, true, 3),
                ("red", 2, 1, true, 1),
                ("% 2 notes", 4, 0, false, 1),
            ]
        );
        // The "%" sub-layer's path belongs to pen 1 and is plotted; the
        // frame keeps its fill.
        assert_eq!(scene.pen_stats(1).paths, 3);
        let all = paths(scene);
        assert_eq!(all[0].2.fill, Some(Color::rgb(0xe8, 0xf4, 0xff)));
        assert!((path_length(&all[0].1) - 560.0).abs() < 1e-3);
    }

    #[test]
    fn layer_labels_follow_axidraw() {
        let layer = |label: &str, y: f64| {
            format!(
                r#"<g inkscape:groupmode="layer" inkscape:label="{label}" stroke="black">
                   <path d="M0 {y} L10 {y}"/></g>"#
            )
        };
        let labels = [
            "%notes",
            "3 red",
            "% 2 guides",
            "7-green",
            "Outline",
            "5 %odd",
            "  %  spaced",
            "0 zero",
            "!2 pause",
            "9",
        ];
        let body: String = labels
            .iter()
            .enumerate()
            .map(|(i, l)| layer(l, i as f64))
            .collect();
        let imported = import(&doc(&body));
        assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
        let got: Vec<(&str, u32, &str, bool)> = imported
            .scene
            .layers
            .iter()
            .map(|l| {
                let pen = imported.scene.pen(l.pen).unwrap();
                (l.name.as_str(), l.pen, pen.name.as_str(), l.is_plotted())
            })
            .collect();
        // Numbered: 3, 7, 5, 2, 9. Free numbers in document order: plotted
        // layers first (1, 4), then the documentation layers (6, 8, 10).
        assert_eq!(
            got,
            [
                ("%notes", 6, "%notes", false),
                ("red", 3, "red", true),
                ("% 2 guides", 8, "% 2 guides", false),
                ("green", 7, "green", true),
                ("Outline", 1, "Outline", true),
                ("5 %odd", 5, "%odd", true),
                ("%  spaced", 10, "%  spaced", false),
                ("0 zero", 4, "0 zero", true),
                ("!pause", 2, "!pause", true),
                ("9", 9, "", true),
            ]
        );

        // Grouping by colour still keeps each documentation layer apart.
        let by_color = import_svg(
            &doc(&body),
            &ImportOptions::DEFAULT.with_pens(PenGrouping::StrokeColor),
        )
        .unwrap();
        let got: Vec<(&str, u32, bool, usize)> = by_color
            .scene
            .layers
            .iter()
            .map(|l| {
                let n = l.content.children.len();
                (l.name.as_str(), l.pen, l.is_plotted(), n)
            })
            .collect();
        assert_eq!(
            got,
            [
                ("#000000", 1, true, 7),
                ("%notes", 2, false, 1),
                ("% 2 guides", 3, false, 1),
                ("%  spaced", 4, false, 1),
            ]
        );
    }

    /// A stroked line per colour, `#rrggbb` each, in paint order.
    fn lines(colors: &[String]) -> String {
        colors
            .iter()
            .enumerate()
            .map(|(i, c)| format!(r#"<path d="M0 {i} L10 {i}" stroke="{c}" fill="none"/>"#))
            .collect()
    }

    fn pens_of(imported: &super::super::Imported) -> Vec<(u32, String, usize)> {
        let scene = &imported.scene;
        scene
            .pens
            .iter()
            .map(|p| {
                (
                    p.number,
                    p.color.to_string(),
                    scene.pen_stats(p.number).paths,
                )
            })
            .collect()
    }

    #[test]
    fn colours_beyond_the_cap_merge_into_the_nearest() {
        // Ten shades of red, then ten of blue; the most used red is drawn
        // twice.
        let mut colors: Vec<String> = (0..10)
            .map(|i| format!("#{:02x}{:02x}00", 200 + 5 * i, 3 * i))
            .chain((0..10).map(|i| format!("#00{:02x}{:02x}", 4 * i, 200 + 5 * i)))
            .collect();
        colors.insert(5, "#e61200".to_string());
        let text = doc(&lines(&colors));
        let two = ImportOptions::DEFAULT.with_max_pens(2);
        let imported = import_svg(&text, &two).unwrap();
        assert_eq!(
            pens_of(&imported),
            [(1, "#e61200".into(), 11), (2, "#0000c8".into(), 10)]
        );
        assert_eq!(
            imported.warnings,
            [
                "20 colours merged into 2 pens by nearest colour (OKLab); --pens N to choose, \
              --pens 0 for one pen per colour up to 999"
            ]
        );
        // The same every time.
        assert_eq!(import_svg(&text, &two).unwrap(), imported);

        // The two nearest colours share a pen; a third stays apart.
        let imported = import_svg(
            &doc(&lines(&[
                "#0000ff".into(),
                "#ff0000".into(),
                "#f00000".into(),
            ])),
            &two,
        )
        .unwrap();
        assert_eq!(
            pens_of(&imported),
            [(1, "#0000ff".into(), 1), (2, "#ff0000".into(), 2)]
        );

        // The default cap: 8 pens; 0 keeps one pen per colour.
        let imported = import(&text);
        assert_eq!(imported.scene.pens.len(), 8);
        assert!(imported.warnings[0].starts_with("20 colours merged into 8 pens"));
        let imported = import_svg(&text, &ImportOptions::DEFAULT.with_max_pens(0)).unwrap();
        assert_eq!(imported.scene.pens.len(), 20);
        assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
        // No more colours than the cap: nothing merged, nothing said.
        let imported = import_svg(&text, &ImportOptions::DEFAULT.with_max_pens(20)).unwrap();
        assert_eq!(imported.scene.pens.len(), 20);
        assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
    }

    #[test]
    fn pens_never_pass_999() {
        let colors: Vec<String> = (0..1200)
            .map(|i| format!("#{:02x}{:02x}{:02x}", i % 256, i / 256, 128))
            .collect();
        let text = doc(&lines(&colors));
        let e = import_svg(&text, &ImportOptions::DEFAULT.with_max_pens(0)).unwrap_err();
        assert_eq!(
            e.to_string(),
            "pens: one pen per colour would make 1,200 pens, more than the 999 a plot \
             allows; merge them into fewer (--pens N, N at most 999)"
        );
        let imported = import(&text);
        assert_eq!(imported.scene.pens.len(), 8);
        assert!(imported.warnings[0].starts_with("1,200 colours merged into 8 pens"));
        let e = import_svg(&text, &ImportOptions::DEFAULT.with_max_pens(1000)).unwrap_err();
        assert_eq!(e.to_string(), "max_pens: must be 0 to 999, got 1000");

        // Layers are not merged; past 999 they are refused.
        let layers: String = (0..1000)
            .map(|i| {
                format!(
                    r#"<g inkscape:groupmode="layer" inkscape:label="L{i}">
                       <path d="M0 0 L1 1" stroke="black"/></g>"#
                )
            })
            .collect();
        let e = import_svg(&doc(&layers), &ImportOptions::DEFAULT).unwrap_err();
        assert!(
            e.to_string()
                .contains("pen numbers up to 1,000, past the 999"),
            "{e}"
        );
    }

    #[test]
    fn layers_are_pens_whatever_the_cap() {
        let layers: String = (0..10)
            .map(|i| {
                format!(
                    r##"<g inkscape:groupmode="layer" inkscape:label="{} ink">
                       <path d="M0 {i} L1 {i}" stroke="#{:02x}0000"/></g>"##,
                    i + 1,
                    20 * i
                )
            })
            .collect();
        let imported = import_svg(&doc(&layers), &ImportOptions::DEFAULT.with_max_pens(2)).unwrap();
        assert_eq!(imported.scene.pens.len(), 10);
        assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
    }

    #[test]
    fn single_layer_puts_every_plotted_path_on_pen_1() {
        let body = r##"<g inkscape:groupmode="layer" inkscape:label="3 red">
                 <path d="M0 0 L1 0" stroke="red"/><path d="M0 1 L1 1" stroke="red"/></g>
               <g inkscape:groupmode="layer" inkscape:label="%notes">
                 <path d="M0 3 L1 3" stroke="gray"/></g>
               <path d="M0 2 L1 2" stroke="blue"/>"##;
        let imported = import_svg(
            &doc(body),
            &ImportOptions::DEFAULT.with_pens(PenGrouping::Single),
        )
        .unwrap();
        assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
        let layers: Vec<(&str, u32, bool, usize)> = imported
            .scene
            .layers
            .iter()
            .map(|l| {
                let n = l.content.children.len();
                (l.name.as_str(), l.pen, l.is_plotted(), n)
            })
            .collect();
        assert_eq!(layers, [("#ff0000", 1, true, 3), ("%notes", 2, false, 1)]);
        assert_eq!(imported.scene.pens[0].color, Color::rgb(255, 0, 0));
    }

    #[test]
    fn oklab_matches_ottosson() {
        // His reference values: white is L 1, a and b 0; sRGB red is
        // (0.628, 0.225, 0.126).
        let white = super::oklab(Color::rgb(255, 255, 255));
        assert!((white[0] - 1.0).abs() < 1e-6 && white[1].abs() < 1e-6 && white[2].abs() < 1e-6);
        let red = super::oklab(Color::rgb(255, 0, 0));
        for (got, want) in red.iter().zip([0.627_955, 0.224_863, 0.125_846]) {
            assert!((got - want).abs() < 1e-5, "{red:?}");
        }
    }
}
