//! Validation of a parsed description: ranges, finiteness, references.
//!
//! Returns the first problem found, as [`Error::Invalid`] with the field
//! path; [`super::SceneSpec::parse`] adds the line and column.

use std::cell::RefCell;
use std::collections::BTreeSet;
use std::fmt::Display;

use super::{LayerSpec, MarginSpec, PaperSize, SceneSpec};
use super::{MAX_PATHS, MAX_SEGMENTS};
use crate::error::{Error, Result};
use crate::scene::traditional;
use crate::scene::Color;
use crate::units::MAX_COORD;

/// A numeric field and the range validation allows it, as recorded by
/// [`super::ValidSpec::ranges`].
#[derive(Debug, Clone, PartialEq)]
pub struct FieldRange {
    /// The field's path, as errors name it (`layers[0].trees[1].count`).
    pub field: String,
    /// The least value allowed (beyond 2⁵³, the nearest float inside
    /// the range).
    pub lo: f64,
    /// The greatest value allowed (likewise).
    pub hi: f64,
    /// Whether the field holds whole numbers.
    pub integer: bool,
    /// For whole numbers, the bounds exactly (a seed's 2⁶³−1 has no
    /// float).
    pub exact: Option<[i128; 2]>,
}

/// A number validation checks against a range.
pub(crate) trait Bound: PartialOrd + Display + Copy {
    /// Whether the type holds whole numbers.
    const INTEGER: bool;
    /// The value as a float, for [`FieldRange`] (exact up to 2⁵³).
    fn to_f64(self) -> f64;
    /// The value exactly, for a whole number.
    fn exact(self) -> Option<i128>;
}

macro_rules! bound {
    ($($t:ty),*) => {$(
        impl Bound for $t {
            const INTEGER: bool = true;
            #[allow(clippy::cast_precision_loss, clippy::cast_lossless)]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[allow(clippy::cast_lossless)]
            fn exact(self) -> Option<i128> {
                Some(self as i128)
            }
        }
    )*};
}
bound!(u8, u16, u32, u64, usize, i32, i64);

impl Bound for f64 {
    const INTEGER: bool = false;
    fn to_f64(self) -> f64 {
        self
    }
    fn exact(self) -> Option<i128> {
        None
    }
}

/// The greatest float not above `x` (past 2⁵³ whole numbers have no
/// float of their own: a range's float bound must not lie outside it).
#[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation)]
fn float_at_most(x: i128) -> f64 {
    let f = x as f64;
    if f as i128 > x {
        f.next_down()
    } else {
        f
    }
}

/// The least float not below `x`.
#[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation)]
fn float_at_least(x: i128) -> f64 {
    let f = x as f64;
    if (f as i128) < x {
        f.next_up()
    } else {
        f
    }
}

thread_local! {
    /// The ranges checked while [`recording`] runs, in the order checked.
    static RECORDED: RefCell<Option<Vec<FieldRange>>> = const { RefCell::new(None) };
}

/// Runs `validate` and gives the range of every field it checked on the
/// way (one source of truth for the ranges: the checks themselves).
pub(crate) fn recording(validate: impl FnOnce() -> Result<()>) -> (Result<()>, Vec<FieldRange>) {
    let outer = RECORDED.with(|r| r.borrow_mut().replace(Vec::new()));
    let result = validate();
    let ranges = RECORDED.with(|r| std::mem::replace(&mut *r.borrow_mut(), outer));
    (result, ranges.unwrap_or_default())
}

/// `lo <= v <= hi`; NaN fails with the same message.
pub(crate) fn range<T: Bound>(field: &str, v: T, lo: T, hi: T) -> Result<()> {
    RECORDED.with(|r| {
        if let Some(ranges) = r.borrow_mut().as_mut() {
            let exact = lo.exact().zip(hi.exact()).map(|(l, h)| [l, h]);
            let (lo, hi) = match exact {
                Some([l, h]) => (float_at_least(l), float_at_most(h)),
                None => (lo.to_f64(), hi.to_f64()),
            };
            ranges.push(FieldRange {
                field: field.to_string(),
                lo,
                hi,
                integer: T::INTEGER,
                exact,
            });
        }
    });
    if lo <= v && v <= hi {
        Ok(())
    } else {
        Err(Error::invalid(
            field,
            format!("must be between {lo} and {hi}, got {v}"),
        ))
    }
}

pub(crate) fn point(field: &str, p: [f64; 2]) -> Result<()> {
    for (axis, v) in ["x", "y"].iter().zip(p) {
        if !(v.is_finite() && v.abs() <= MAX_COORD) {
            return Err(Error::invalid(
                field,
                format!("{axis} must be a finite number within ±{MAX_COORD} mm, got {v}"),
            ));
        }
    }
    Ok(())
}

/// The most points a line of points may have.
pub(crate) const MAX_POINTS: usize = 10_000;

pub(crate) fn points(field: &str, pts: &[[f64; 2]], min: usize) -> Result<()> {
    if pts.len() < min {
        return Err(Error::invalid(
            field,
            format!("needs at least {min} points [x, y], got {}", pts.len()),
        ));
    }
    if pts.len() > MAX_POINTS {
        return Err(Error::invalid(
            field,
            format!("at most {MAX_POINTS} points"),
        ));
    }
    for (i, p) in pts.iter().enumerate() {
        point(&format!("{field}[{i}]"), *p)?;
    }
    let first = pts[0];
    if pts.iter().all(|p| *p == first) {
        return Err(Error::invalid(
            field,
            "all points are the same; a line needs length",
        ));
    }
    Ok(())
}

/// Tree8's base curve: four finite points in trunk units, not all equal.
pub(crate) fn base_curve(field: &str, pts: &[[f64; 2]; 4]) -> Result<()> {
    for (i, p) in pts.iter().enumerate() {
        for v in p {
            if !(v.is_finite() && v.abs() <= 1000.0) {
                return Err(Error::invalid(
                    format!("{field}[{i}]"),
                    format!("must be finite and within ±1000 trunk lengths, got {v}"),
                ));
            }
        }
    }
    if pts.iter().all(|p| *p == pts[0]) {
        return Err(Error::invalid(
            field,
            "all points are the same; the base curve needs length",
        ));
    }
    Ok(())
}

/// An id usable in SVG and in override references.
fn id(field: &str, s: &str) -> Result<()> {
    let ok = !s.is_empty()
        && s.len() <= 64
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
    if ok {
        Ok(())
    } else {
        Err(Error::invalid(
            field,
            format!("'{s}' is not a valid id: use 1–64 letters, digits, '-' or '_'"),
        ))
    }
}

pub(crate) fn scene(s: &SceneSpec) -> Result<()> {
    if s.version != super::FORMAT_VERSION {
        return Err(Error::invalid(
            "version",
            format!(
                "unsupported format version {}; this moyo reads version {}",
                s.version,
                super::FORMAT_VERSION
            ),
        ));
    }
    range("seed", s.seed, 0, super::seed::MAX_SEED)?;
    page(s)?;
    range("output.precision", s.output.precision, 0, 8)?;
    range("limits.max_paths", s.limits.max_paths, 1, MAX_PATHS)?;
    range(
        "limits.max_segments",
        s.limits.max_segments,
        1,
        MAX_SEGMENTS,
    )?;

    if let Some(name) = &s.palette {
        if traditional::palette(name).is_none() {
            let names: Vec<&str> = traditional::PALETTES.iter().map(|p| p.name).collect();
            return Err(Error::invalid(
                "palette",
                format!(
                    "unknown palette '{name}'; the palettes are {}",
                    names.join(", ")
                ),
            ));
        }
    }
    if s.pens.is_empty() {
        return Err(Error::invalid("pens", "at least one pen is needed"));
    }
    let mut numbers = BTreeSet::new();
    for (i, pen) in s.pens.iter().enumerate() {
        let f = format!("pens[{i}]");
        range(&format!("{f}.number"), pen.number, 1, 999)?;
        if !numbers.insert(pen.number) {
            return Err(Error::invalid(
                format!("{f}.number"),
                format!("pen {} is defined twice", pen.number),
            ));
        }
        if pen.name.trim().is_empty() || pen.name.len() > 64 {
            return Err(Error::invalid(
                format!("{f}.name"),
                "must be 1–64 characters",
            ));
        }
        if !Color::is_valid(&pen.color) {
            return Err(bad_color(&format!("{f}.color"), &pen.color));
        }
        range(&format!("{f}.width"), pen.width, 0.01, 20.0)?;
    }

    if let Some(upper) = &s.lines.upper {
        points("lines.upper", upper, 2)?;
    }
    if let Some(lower) = &s.lines.lower {
        points("lines.lower", lower, 2)?;
    }

    s.plot.validate("plot")?;
    if let Some(device) = &s.device {
        device.resolve()?;
    }

    // Not a `range`: the ranges recorded are the numbers a fuzzer edits.
    if s.layers.len() > super::MAX_LAYERS {
        return Err(Error::invalid(
            "layers",
            format!(
                "has {} layers; a description may have at most {}",
                s.layers.len(),
                super::MAX_LAYERS
            ),
        ));
    }
    let mut names = BTreeSet::new();
    for (i, layer) in s.layers.iter().enumerate() {
        let f = format!("layers[{i}]");
        if !names.insert(layer.name.as_str()) {
            return Err(Error::invalid(
                format!("{f}.name"),
                format!("layer name '{}' is used twice", layer.name),
            ));
        }
        self::layer(&f, layer, &numbers)?;
        for item in layer.items() {
            for (field, name) in item.table.family().layers_read() {
                read_layer(&format!("{f}.{}.{field}", item.field), name, &s.layers[..i])?;
            }
        }
    }
    let mut adjusted = BTreeSet::new();
    for (i, a) in s.adjust.iter().enumerate() {
        let f = format!("adjust[{i}]");
        a.check(&f)?;
        if !adjusted.insert(a.id.as_str()) {
            return Err(Error::invalid(
                format!("{f}.id"),
                format!("'{}' is adjusted twice", a.id),
            ));
        }
    }
    Ok(())
}

pub(crate) fn bad_color(field: &str, value: &str) -> Error {
    Error::invalid(
        field,
        format!(
            "'{value}' is not a colour: use #rrggbb, #rgb, a CSS name such as black, \
             a traditional colour such as ai-iro, or a palette slot @1–@5"
        ),
    )
}

fn page(s: &SceneSpec) -> Result<()> {
    if let PaperSize::Custom([w, h]) = s.page.size {
        range("page.size[0]", w, 10.0, 10_000.0)?;
        range("page.size[1]", h, 10.0, 10_000.0)?;
    }
    let sides = match s.page.margin {
        MarginSpec::Uniform(m) => [m; 4],
        MarginSpec::Sides(m) => m,
    };
    for v in sides {
        range("page.margin", v, 0.0, 1_000.0)?;
    }
    let p = s.page();
    if sides[1] + sides[3] >= p.width || sides[0] + sides[2] >= p.height {
        return Err(Error::invalid(
            "page.margin",
            format!(
                "the margins leave no drawable area on a {} × {} mm page",
                p.width, p.height
            ),
        ));
    }
    Ok(())
}

fn layer(f: &str, layer: &LayerSpec, pens: &BTreeSet<u32>) -> Result<()> {
    if layer.name.trim().is_empty() || layer.name.len() > 64 {
        return Err(Error::invalid(
            format!("{f}.name"),
            "must be 1–64 characters",
        ));
    }
    if !pens.contains(&layer.pen) {
        return Err(Error::invalid(
            format!("{f}.pen"),
            format!(
                "no pen {} is defined (defined: {})",
                layer.pen,
                pens.iter()
                    .map(u32::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ));
    }
    if let Some(d) = layer.depth {
        range(&format!("{f}.depth"), d, -1000, 1000)?;
    }
    let l = &layer.limbs;
    range(&format!("{f}.limbs.width"), l.width, 0.05, 50.0)?;
    range(&format!("{f}.limbs.tip_width"), l.tip_width, 0.0, 50.0)?;
    range(&format!("{f}.limbs.bow"), l.bow, -1.0, 1.0)?;
    if let Some(fill) = &l.fill {
        if !Color::is_valid(fill) {
            return Err(bad_color(&format!("{f}.limbs.fill"), fill));
        }
    }
    let mut ids = BTreeSet::new();
    for item in layer.items() {
        let field = format!("{f}.{}", item.field);
        id(&format!("{field}.id"), &item.id)?;
        if !ids.insert(item.id.clone()) {
            return Err(Error::invalid(
                format!("{field}.id"),
                format!("id '{}' is used twice in this layer", item.id),
            ));
        }
        item.table.family().check(&field)?;
    }
    Ok(())
}

/// Checks that the layer `name`, whose regions a table fills, comes
/// before it and draws regions.
fn read_layer(f: &str, name: &str, earlier: &[LayerSpec]) -> Result<()> {
    let Some(layer) = earlier.iter().find(|l| l.name == name) else {
        let names: Vec<&str> = earlier.iter().map(|l| l.name.as_str()).collect();
        let known = if names.is_empty() {
            "none: this is the first layer".to_string()
        } else {
            names.join(", ")
        };
        return Err(Error::invalid(
            f,
            format!(
                "no layer named '{name}' comes before this one (layers are built in order, \
                 so a table fills the regions of an earlier one; earlier layers: {known})"
            ),
        ));
    };
    if !layer
        .items()
        .iter()
        .any(|it| it.table.family().offers_regions())
    {
        return Err(Error::invalid(
            f,
            format!(
                "layer '{name}' draws no regions to fill (voronoi tables offer their cells, \
                 a background its mask)"
            ),
        ));
    }
    Ok(())
}
