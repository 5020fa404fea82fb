//! The library's error type: what went wrong and where.
//!
//! Input errors carry enough context for a person to fix the input: the field
//! path inside the scene description (`layers[1].trees[0].ratio1`), the
//! allowed range, and — where the parser knows it — the line and column.
//! The CLI prefixes the file name.
//!
//! Every message is complete on its own line: an error that wraps another
//! (a file that could not be read, an SVG that did not parse) includes the
//! cause's text in its own, and keeps the cause as
//! [`source`](std::error::Error::source) so that a program can look at it
//! (an [`std::io::ErrorKind`], say). Failures of the geometry engines are
//! [`Error::Geometry`], never a complaint about the input.

use std::path::PathBuf;

/// A position inside a text file, both counted from 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LineCol {
    /// Line number, from 1.
    pub line: usize,
    /// Column (in characters), from 1.
    pub column: usize,
}

impl LineCol {
    /// The line and column of byte `offset` in `text`.
    pub fn of_offset(text: &str, offset: usize) -> LineCol {
        let offset = offset.min(text.len());
        let before = &text[..floor_char_boundary(text, offset)];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let column = before[line_start..].chars().count() + 1;
        LineCol { line, column }
    }
}

fn floor_char_boundary(text: &str, mut i: usize) -> usize {
    while !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

impl std::fmt::Display for LineCol {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}", self.line, self.column)
    }
}

/// Everything that can go wrong in moyo.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The scene description is not well-formed TOML/JSON, has an unknown
    /// key, or a value of the wrong type.
    #[error("{}{message}", at_prefix(*at, field))]
    Parse {
        /// Where the parser stopped, when it knows.
        at: Option<LineCol>,
        /// The field path, when known (e.g. `layers[0].pen`).
        field: Option<String>,
        /// The parser's message.
        message: String,
    },
    /// A value is well-formed but not allowed (out of range, not finite,
    /// refers to something that does not exist).
    #[error("{}{field}: {message}", at_prefix(*at, &None))]
    Invalid {
        /// Where the offending value stands, when known.
        at: Option<LineCol>,
        /// The field path (e.g. `layers[0].trees[1].ratio1`).
        field: String,
        /// What is wrong and what is allowed.
        message: String,
    },
    /// Generation would exceed the scene's path budget (`limits.max_paths`).
    #[error(
        "path budget exceeded: {what} would make more than {limit} paths \
         (raise limits.max_paths, or lower count/generations)"
    )]
    Budget {
        /// The configured limit.
        limit: usize,
        /// What was being generated when the budget ran out.
        what: String,
    },
    /// Generation would exceed the scene's segment budget
    /// (`limits.max_segments`): few paths, but very long ones.
    #[error(
        "segment budget exceeded: {what} would make more than {limit} path segments \
         (raise limits.max_segments, or lower iterations/count)"
    )]
    SegmentBudget {
        /// The configured limit.
        limit: usize,
        /// What was being generated when the budget ran out.
        what: String,
    },
    /// The work was called off before it finished (a newer edit in the
    /// studio made it stale); nothing is wrong with the input.
    #[error("cancelled: a newer request replaced this one")]
    Cancelled,
    /// The work was called off because the process held more memory than
    /// its budget (the studio's `--memory-mb`): the description asks for
    /// more than this machine was told to give a render.
    #[error(
        "memory budget exceeded: the render held {resident_mb} MB, past the budget of \
         {limit_mb} MB (lower the counts, iterations, steps or relax of the last edit)"
    )]
    MemoryBudget {
        /// The budget, in MiB.
        limit_mb: u64,
        /// The resident memory when it was found past the budget, in MiB.
        resident_mb: u64,
    },
    /// No built-in template has this name.
    #[error("unknown template '{name}' (available: {available})")]
    UnknownTemplate {
        /// The name asked for.
        name: String,
        /// Comma-separated list of the names that exist.
        available: String,
    },
    /// Reading or writing a file failed.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file involved.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// A file a description names (a motif, a paths table's or a
    /// sketch's SVG, an image, a mesh) could not be used.
    #[error("{kind} {name}: {message}")]
    Motif {
        /// What the file is to the description, as messages word it:
        /// [`UserFile`].
        kind: UserFile,
        /// The file as named in the description.
        name: String,
        /// What is wrong with it, including the cause's message.
        message: String,
        /// The underlying error (unreadable file, SVG that did not parse),
        /// when there is one.
        source: Option<Cause>,
    },
    /// The SVG could not be rasterised for the preview.
    #[error("preview: {message}")]
    Preview {
        /// What failed, including the cause's message.
        message: String,
        /// The underlying error (SVG parser, PNG encoder), when there is one.
        source: Option<Cause>,
    },
    /// A geometry engine failed on a computation it should be able to do:
    /// a defect of moyo or of a library it uses, not of the input.
    #[error(
        "geometry engine failure: {operation}; please report it with the \
         scene description and seed"
    )]
    Geometry {
        /// What was being computed.
        operation: String,
    },
    /// A file's content is wrong: `source` says what and where in it.
    #[error("{}: {source}", path.display())]
    File {
        /// The file.
        path: PathBuf,
        /// What is wrong inside it.
        source: Box<Error>,
    },
    /// A G-code program would move the machine outside its travel
    /// ([`GcodeOptions::area`](crate::output::gcode::GcodeOptions::area)).
    #[error(
        "gcode: {what} reaches ({x_mm:.3}, {y_mm:.3}) mm in machine coordinates, outside \
         the machine's travel X {}…{}, Y {}…{} mm (gcode.area); shrink or move the \
         drawing, or change the origin",
        area[0], area[2], area[1], area[3]
    )]
    MachineArea {
        /// The scene path the point belongs to, or the move (`park`,
        /// `refill`).
        what: String,
        /// The point in machine millimetres.
        x_mm: f64,
        /// See `x_mm`.
        y_mm: f64,
        /// The machine's travel, `[x_min, y_min, x_max, y_max]`.
        area: [f64; 4],
    },
    /// A point of a plotter program lies outside the coordinates the device
    /// accepts (HPGL: [`HpglOptions::device_range`](crate::output::hpgl::HpglOptions::device_range)).
    #[error(
        "hpgl: path {path} reaches ({x_mm:.3}, {y_mm:.3}) mm on the device, \
         ({x_units:.0}, {y_units:.0}) plotter units: outside the device range \
         {min_units}…{max_units} units ({min_mm:.3}…{max_mm:.3} mm); shrink or \
         move the drawing, or widen the range"
    )]
    DeviceRange {
        /// The id of the scene path the point belongs to.
        path: String,
        /// The point in device millimetres (after any mirroring, Y flip and
        /// knife offset).
        x_mm: f64,
        /// See `x_mm`.
        y_mm: f64,
        /// The point in plotter units, rounded.
        x_units: f64,
        /// See `x_units`.
        y_units: f64,
        /// The smallest coordinate the device accepts, in plotter units.
        min_units: i32,
        /// The largest coordinate the device accepts, in plotter units.
        max_units: i32,
        /// `min_units` in millimetres.
        min_mm: f64,
        /// `max_units` in millimetres.
        max_mm: f64,
    },
}

fn at_prefix(at: Option<LineCol>, field: &Option<String>) -> String {
    let mut s = String::new();
    if let Some(at) = at {
        s.push_str(&format!("{at}: "));
    }
    if let Some(field) = field {
        if !field.is_empty() && field != "." {
            s.push_str(&format!("{field}: "));
        }
    }
    s
}

impl Error {
    /// Shorthand for an [`Error::Invalid`] without a location.
    pub fn invalid(field: impl Into<String>, message: impl Into<String>) -> Error {
        Error::Invalid {
            at: None,
            field: field.into(),
            message: message.into(),
        }
    }

    /// An [`Error::Preview`]: `message`, then the cause's own, which is
    /// kept as the source.
    pub fn preview(message: &str, cause: impl Into<Cause>) -> Error {
        let cause = cause.into();
        Error::Preview {
            message: format!("{message}: {cause}"),
            source: Some(cause),
        }
    }

    /// Attaches an I/O error to the path it concerns.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Error {
        Error::Io {
            path: path.into(),
            source,
        }
    }
}

/// The cause kept inside an [`Error`] that wraps another library's error.
pub type Cause = Box<dyn std::error::Error + Send + Sync + 'static>;

/// `Result` with moyo's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What a file a description names is to it: the word an
/// [`Error::Motif`] starts with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UserFile {
    /// A user motif (`[[…motifs]] svg = …`): `motif`.
    Motif,
    /// An SVG whose paths a table follows (a paths table's `svg`, a
    /// sketch's stroke): `paths file`.
    Paths,
    /// A density image (PNG or JPEG): `image`.
    Image,
    /// A triangle mesh (OBJ): `mesh`.
    Mesh,
}

impl std::fmt::Display for UserFile {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            UserFile::Motif => "motif",
            UserFile::Paths => "paths file",
            UserFile::Image => "image",
            UserFile::Mesh => "mesh",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_col_counts_from_one_and_in_chars() {
        let text = "ab\ncdé\nx";
        assert_eq!(LineCol::of_offset(text, 0), LineCol { line: 1, column: 1 });
        assert_eq!(LineCol::of_offset(text, 3), LineCol { line: 2, column: 1 });
        // 'x' is after "cdé\n": é is two bytes.
        let x = text.find('x').unwrap();
        assert_eq!(LineCol::of_offset(text, x), LineCol { line: 3, column: 1 });
        assert_eq!(LineCol::of_offset(text, 6), LineCol { line: 2, column: 3 });
    }

    #[test]
    fn invalid_message_names_field_and_place() {
        let e = Error::Invalid {
            at: Some(LineCol { line: 4, column: 9 }),
            field: "layers[0].trees[0].ratio1".into(),
            message: "must be between 0.05 and 1.5, got 7".into(),
        };
        assert_eq!(
            e.to_string(),
            "4:9: layers[0].trees[0].ratio1: must be between 0.05 and 1.5, got 7"
        );
    }
}
