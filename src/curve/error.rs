use thiserror::Error;

/// Why a curve could not be read. Every message names the file and says
/// what to do; all of these are bad input (the CLI exits with code 2).
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum CurveError {
    /// The file could not be opened or read. The operating system's reason
    /// is the error's source (the CLI prints it after a colon).
    #[error("cannot read {path} (check the path and permissions)")]
    Io {
        /// The file.
        path: String,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// The path names a folder.
    #[error("{path} is a folder, not a curve file; name a .json, .txt or .svg file")]
    IsDirectory {
        /// The folder.
        path: String,
    },
    /// The extension is not one of the known formats.
    #[error(
        "{path}: unknown curve format '{extension}'; use .json (points array), .txt (x y per line) or .svg"
    )]
    UnknownFormat {
        /// The file.
        path: String,
        /// Its extension (lower case, may be empty).
        extension: String,
    },
    /// The file or the curve is larger than immerse accepts.
    #[error("{path}: too large ({what}; the limit is {limit}); simplify the curve first")]
    TooLarge {
        /// The file.
        path: String,
        /// What was too large.
        what: String,
        /// The limit.
        limit: String,
    },
    /// Malformed JSON.
    #[error("{path}:{line}:{column}: {message}")]
    Json {
        /// The file.
        path: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What is wrong and the expected shape.
        message: String,
    },
    /// Well-formed JSON of the wrong shape.
    #[error("{path}: {message}")]
    JsonShape {
        /// The file.
        path: String,
        /// What is wrong and the expected shape.
        message: String,
    },
    /// A line of a text curve is not an `x y` pair.
    #[error("{path}:{line}: {message}")]
    Text {
        /// The file.
        path: String,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The SVG could not be parsed.
    #[error("{path}: not a readable SVG: {message}")]
    Svg {
        /// The file.
        path: String,
        /// The parser's message.
        message: String,
    },
    /// A number in an SVG's path data is so large that parsing the path
    /// could take unbounded memory (an elliptical arc of huge radius is
    /// split into ever more Bézier segments).
    #[error(
        "{path}:{line}: path data has a number of magnitude {value:e}, over the limit {limit:e} for SVG path data; rescale the drawing"
    )]
    SvgNumberTooLarge {
        /// The file.
        path: String,
        /// 1-based line of the element.
        line: u32,
        /// The offending value.
        value: f64,
        /// The limit ([`crate::curve::MAX_SVG_PATH_NUMBER`]).
        limit: f64,
    },
    /// The SVG has no closed subpath to use as the curve.
    #[error(
        "{path}: no closed shape found; draw a closed path (ending in Z), polygon, rect, circle or ellipse"
    )]
    NoClosedShape {
        /// The file.
        path: String,
    },
    /// The SVG has a closed shape, but its transforms put its coordinates
    /// beyond what the SVG parser represents (finite 32-bit floats), so
    /// the parser dropped it.
    #[error(
        "{path}: the shape's coordinates are not finite or too large after its transforms are applied; rescale the drawing"
    )]
    SvgOutOfRange {
        /// The file.
        path: String,
    },
    /// The file holds several closed shapes where one curve is expected:
    /// it is a drawing (`crate::drawing`), not one curve.
    #[error(
        "{path}: {count} closed shapes ({parts}), not one curve; read it as a drawing (`immerse check`, `immerse morph`) or keep one shape"
    )]
    SeveralParts {
        /// The file (and the group, for one key of a sequence).
        path: String,
        /// How many closed shapes it has.
        count: usize,
        /// Their names (`path 'ID'`, `path K subpath J`), the first few.
        parts: String,
    },
    /// A coordinate is NaN or infinite.
    #[error("{path}: point {index} ({place}) has a non-finite coordinate; give finite numbers")]
    NonFinite {
        /// The file.
        path: String,
        /// 0-based point index in the file.
        index: usize,
        /// Where in the file (line or point number).
        place: String,
    },
    /// A coordinate's magnitude is outside the range where the exact
    /// predicates cannot overflow or underflow.
    #[error(
        "{path}: point {index} ({place}) has a coordinate of magnitude {value:e}, outside [{min:e}, {max:e}]; rescale the curve"
    )]
    OutOfRange {
        /// The file.
        path: String,
        /// 0-based point index in the file.
        index: usize,
        /// Where in the file (line or point number).
        place: String,
        /// The offending value.
        value: f64,
        /// Smallest non-zero magnitude allowed.
        min: f64,
        /// Largest magnitude allowed.
        max: f64,
    },
    /// Fewer than three distinct points remain after cleaning.
    #[error(
        "{path}: only {distinct} distinct point(s) after dropping repeated points; a curve needs at least 3"
    )]
    TooFewPoints {
        /// The file.
        path: String,
        /// Distinct points left.
        distinct: usize,
    },
    /// All points lie on one line, so the curve encloses no area.
    #[error(
        "{path}: all {count} points lie on one line (zero area); a curve must enclose a region"
    )]
    ZeroArea {
        /// The file.
        path: String,
        /// Number of points.
        count: usize,
    },
}

/// `text` with every control character escaped (`\n`, `\r`, `\t`,
/// `\u{..}`), so that a message quoting the input stays on one line.
pub(crate) fn one_line(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}
