//! Curves: reading, cleaning and orienting closed polygons.
//!
//! A [`Curve`] can only be built by parsing and cleaning, so later stages
//! take `&Curve` without re-checking it: it has at least three distinct
//! points, finite coordinates in the range where the exact predicates are
//! safe, no consecutive duplicates (the closing point is not repeated), and
//! not all points on one line. When its turning number is −1 it has been
//! reversed (see [`Curve::reversed`]) so that its turning number is +1.
//!
//! Formats (chosen by file extension):
//! - JSON: `{"name": "...", "points": [[x, y], ...]}` or a bare array of
//!   `[x, y]` pairs (y up);
//! - text (`.txt`, `.xy`, `.csv`): one `x y` per line, separated by
//!   whitespace or a comma, `#` starts a comment (y up);
//! - SVG: the one closed subpath of a `path`, `polygon`, `rect`, `circle`
//!   or `ellipse`, with transforms applied (a file of several is a
//!   [`crate::drawing::Drawing`], refused here naming its parts),
//!   Béziers flattened to 0.1 % of the shape's size,
//!   and y flipped (SVG is y down).

mod clean;
mod error;
mod json;
pub(crate) mod svg;
mod text;

pub use clean::{MAX_COORDINATE, MAX_POINTS, MIN_COORDINATE};
pub use error::CurveError;
pub(crate) use error::one_line as error_one_line;
pub use svg::{MAX_SVG_PATH_NUMBER, MAX_SVG_SHAPES, SvgShapes};

use crate::geom::Point;
use crate::geom::polygon::{self, Turning};
use immerse_base::input::ReadError;
use std::path::Path;

/// Largest curve file accepted, in bytes (64 MiB).
pub const MAX_FILE_BYTES: u64 = 64 << 20;

/// A cleaned, oriented closed polygon.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// The curve's name: the JSON `name` field, else the file stem.
    pub name: String,
    /// The vertices in oriented order (y up), without a repeated closing
    /// point or consecutive duplicates.
    pub points: Vec<Point>,
    /// True when the curve was given clockwise (turning number −1) and has
    /// been reversed; the first point stays first.
    pub reversed: bool,
    /// The turning number of the cleaned curve as given (before any
    /// reversal); [`Turning::Cusp`] when the curve doubles back on itself.
    pub turning_as_given: Turning,
    /// How many points cleaning dropped (a repeated closing point and
    /// consecutive duplicates).
    pub dropped: usize,
    /// For each point as read (counting from 0, before cleaning), the
    /// vertex of [`Curve::points`] it became: a dropped duplicate maps to
    /// the vertex it repeats, and the order follows any reversal.
    pub source_vertex: Vec<usize>,
}

impl Curve {
    /// Reads and cleans a curve file; the format follows the extension.
    ///
    /// # Errors
    ///
    /// Any [`CurveError`]: the file is missing or unreadable, too large,
    /// has an unknown extension or bad syntax, or the curve is degenerate.
    pub fn from_path(path: impl AsRef<Path>) -> Result<Curve, CurveError> {
        let file = InputFile::read(path.as_ref(), "curve")?;
        Curve::from_bytes(&file.bytes, file.format, &file.label, &file.stem)
    }

    /// Parses and cleans a curve from memory. `label` names the source in
    /// error messages; `default_name` is used when the data has no name.
    ///
    /// Data longer than [`MAX_FILE_BYTES`] is refused before parsing, as a
    /// file of that size would be.
    ///
    /// # Errors
    ///
    /// As [`Curve::from_path`], except the I/O errors.
    pub fn from_bytes(
        bytes: &[u8],
        format: Format,
        label: &str,
        default_name: &str,
    ) -> Result<Curve, CurveError> {
        let bytes = screen_bytes(bytes, label)?;
        let raw = match format {
            Format::Json => json::parse(bytes, label)?,
            Format::Text => text::parse(bytes, label)?,
            Format::Svg => svg::parse(bytes, label)?,
        };
        let name = raw.name.unwrap_or_else(|| default_name.to_string());
        clean::build(name, raw.points, raw.lines, label)
    }

    /// Reads every closed shape of an SVG drawing that `mode` picks, in
    /// document order, each cleaned and oriented as [`Curve::from_path`]
    /// does: the keyframes of a sequence drawn in one file. Each curve's
    /// name is the file stem and what names the shape in the drawing
    /// (`shape 2`, `group 'layer3'`); errors name the file and the shape.
    ///
    /// # Errors
    ///
    /// As [`Curve::from_path`]; [`CurveError::TooLarge`] for more than
    /// [`MAX_SVG_SHAPES`] shapes.
    pub fn all_from_svg_path(
        path: impl AsRef<Path>,
        mode: SvgShapes,
    ) -> Result<Vec<Curve>, CurveError> {
        let path = path.as_ref();
        let label = path.display().to_string();
        let bytes = read_file(path, &label)?;
        let stem = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("drawing")
            .to_string();
        Curve::all_from_svg_bytes(&bytes, &label, &stem, mode)
    }

    /// [`Curve::all_from_svg_path`] on data in memory; `label` names the
    /// source in errors and `stem` starts each curve's name.
    ///
    /// # Errors
    ///
    /// As [`Curve::all_from_svg_path`], except the I/O errors.
    pub fn all_from_svg_bytes(
        bytes: &[u8],
        label: &str,
        stem: &str,
        mode: SvgShapes,
    ) -> Result<Vec<Curve>, CurveError> {
        if bytes.len() as u64 > MAX_FILE_BYTES {
            return Err(CurveError::TooLarge {
                path: label.to_string(),
                what: format!("{} bytes", bytes.len()),
                limit: format!("{MAX_FILE_BYTES} bytes"),
            });
        }
        svg::parse_all(bytes, label, mode)?
            .into_iter()
            .map(|(what, raw)| {
                clean::build(
                    format!("{stem} {what}"),
                    raw.points,
                    raw.lines,
                    &format!("{label} ({what})"),
                )
            })
            .collect()
    }

    /// Parses a JSON curve from a string (see the module docs for the
    /// format).
    ///
    /// # Errors
    ///
    /// As [`Curve::from_bytes`].
    pub fn from_json_str(json: &str, label: &str) -> Result<Curve, CurveError> {
        Curve::from_bytes(json.as_bytes(), Format::Json, label, "curve")
    }

    /// Builds a curve from points already in memory (cleaning and orienting
    /// them as a file would be).
    ///
    /// # Errors
    ///
    /// The degenerate-curve variants of [`CurveError`].
    pub fn from_points(name: &str, points: Vec<Point>) -> Result<Curve, CurveError> {
        let raw = points
            .into_iter()
            .enumerate()
            .map(|(i, p)| (p, i + 1))
            .collect();
        clean::build(name.to_string(), raw, false, name)
    }

    /// Cleans and orients points as read (each with its 1-based place in
    /// the source), naming `label` in errors.
    pub(crate) fn from_raw(name: String, raw: RawCurve, label: &str) -> Result<Curve, CurveError> {
        clean::build(name, raw.points, raw.lines, label)
    }

    /// Number of vertices.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Always false: a curve has at least three points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The turning number of the oriented curve, or `None` at a cusp.
    pub fn turning_number(&self) -> Option<i64> {
        match polygon::turning_number(&self.points) {
            Turning::Number(k) => Some(k),
            Turning::Cusp(_) => None,
        }
    }

    /// The turning number as given (before reversal), or `None` at a cusp.
    pub fn turning_number_as_given(&self) -> Option<i64> {
        match self.turning_as_given {
            Turning::Number(k) => Some(k),
            Turning::Cusp(_) => None,
        }
    }

    /// True when no two edges of the curve touch except adjacent ones at
    /// their shared vertex (decided exactly).
    pub fn is_simple(&self) -> bool {
        polygon::is_simple(&self.points)
    }
}

/// A curve or drawing file as read: its bytes, the format its extension
/// names, the label naming it in errors, and its file stem.
pub(crate) struct InputFile {
    pub(crate) bytes: Vec<u8>,
    pub(crate) format: Format,
    pub(crate) label: String,
    pub(crate) stem: String,
}

impl InputFile {
    /// Reads `path` (at most [`MAX_FILE_BYTES`]); an unknown extension is
    /// refused before the file is read. `unnamed` is the stem of a path
    /// without one.
    pub(crate) fn read(path: &Path, unnamed: &str) -> Result<InputFile, CurveError> {
        let label = path.display().to_string();
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .unwrap_or_default();
        let format = Format::from_extension(&ext).ok_or_else(|| CurveError::UnknownFormat {
            path: label.clone(),
            extension: ext.clone(),
        })?;
        let bytes = read_file(path, &label)?;
        let stem = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or(unnamed)
            .to_string();
        Ok(InputFile {
            bytes,
            format,
            label,
            stem,
        })
    }
}

/// Data given in memory, screened as a file would be: longer than
/// [`MAX_FILE_BYTES`] is refused before parsing, and a UTF-8 byte order
/// mark (as some editors save) is not data.
pub(crate) fn screen_bytes<'a>(bytes: &'a [u8], label: &str) -> Result<&'a [u8], CurveError> {
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(CurveError::TooLarge {
            path: label.to_string(),
            what: format!("{} bytes", bytes.len()),
            limit: format!("{MAX_FILE_BYTES} bytes"),
        });
    }
    Ok(bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes))
}

/// Reads a curve file through the [`MAX_FILE_BYTES`] cap
/// ([`immerse_base::input::read_capped`]: devices, FIFOs and pipes included).
pub(crate) fn read_file(path: &Path, label: &str) -> Result<Vec<u8>, CurveError> {
    immerse_base::input::read_capped(path, MAX_FILE_BYTES).map_err(|e| match e {
        ReadError::IsDirectory => CurveError::IsDirectory {
            path: label.to_string(),
        },
        ReadError::TooLarge { .. } => CurveError::TooLarge {
            path: label.to_string(),
            what: e.size_text().unwrap_or_default(),
            limit: format!("{MAX_FILE_BYTES} bytes"),
        },
        ReadError::Io(source) => CurveError::Io {
            path: label.to_string(),
            source,
        },
    })
}

/// A curve file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// JSON object with `points`, or a bare array of pairs.
    Json,
    /// One `x y` pair per line.
    Text,
    /// An SVG drawing.
    Svg,
}

impl Format {
    /// The format for a lower-case file extension, if known.
    pub fn from_extension(ext: &str) -> Option<Format> {
        match ext {
            "json" => Some(Format::Json),
            "txt" | "xy" | "csv" => Some(Format::Text),
            "svg" => Some(Format::Svg),
            _ => None,
        }
    }
}

/// Points as read, each with its 1-based position in the source (point
/// number or line) for error messages, before cleaning.
#[derive(Debug)]
pub(crate) struct RawCurve {
    pub(crate) name: Option<String>,
    pub(crate) points: Vec<(Point, usize)>,
    /// True when the positions are line numbers (text files); otherwise
    /// errors count points from 0.
    pub(crate) lines: bool,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_bytes_refuses_data_over_the_file_limit() {
        // Valid text up front, so only the size bound can reject it.
        let mut data = b"0 0\n1 0\n0 1\n".to_vec();
        data.resize(MAX_FILE_BYTES as usize + 1, b' ');
        let e = Curve::from_bytes(&data, Format::Text, "big.txt", "big").unwrap_err();
        assert!(matches!(e, CurveError::TooLarge { .. }), "{e}");
        assert_eq!(
            e.to_string(),
            format!(
                "big.txt: too large ({} bytes; the limit is {MAX_FILE_BYTES} bytes); simplify the curve first",
                MAX_FILE_BYTES + 1
            )
        );
        data.truncate(MAX_FILE_BYTES as usize);
        let c = Curve::from_bytes(&data, Format::Text, "big.txt", "big").unwrap();
        assert_eq!(c.len(), 3);
    }
}
