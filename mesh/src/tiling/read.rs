//! Reading tilings from Wavefront OBJ and JSON (docs/design.md §10).
//!
//! * JSON: `{"points": [[x,y],...], "faces": [[i,j,k,...], ...]}`, 0-based.
//! * OBJ: `v x y [z ...]` lines (z ignored) and `f a b c ...` lines with
//!   1-based (or negative, relative) indices in any of the forms `a`,
//!   `a/t`, `a/t/n`, `a//n`; other statements are ignored.
//!
//! Every reader validates the result ([`super::validate`]).

use super::{MAX_FILE_BYTES, MAX_VERTICES, Tiling, TilingError};
use immerse_base::geom::Point;
use immerse_base::input::{ReadError, read_capped};
use std::path::Path;

#[derive(serde::Deserialize)]
struct JsonTiling {
    points: Vec<[f64; 2]>,
    faces: Vec<Vec<u32>>,
}

impl Tiling {
    /// Reads a tiling from a file: `.obj` as OBJ, `.json` as JSON, otherwise
    /// JSON when the text starts with `{` and OBJ else.
    ///
    /// # Errors
    ///
    /// [`TilingError::Io`] when the file cannot be read or is a folder,
    /// [`TilingError::TooLarge`] past [`MAX_FILE_BYTES`] (read through
    /// that cap: devices, FIFOs and pipes included), otherwise
    /// [`TilingError::InFile`] wrapping the parse or validation problem.
    pub fn from_path(path: &Path) -> Result<Tiling, TilingError> {
        let io = |source| TilingError::Io {
            path: path.to_path_buf(),
            source,
        };
        let bytes = read_capped(path, MAX_FILE_BYTES).map_err(|e| match e {
            ReadError::TooLarge { .. } => TilingError::TooLarge {
                path: path.to_path_buf(),
                size: e.size_text().unwrap_or_default(),
                limit: MAX_FILE_BYTES,
            },
            ReadError::IsDirectory => io(std::io::Error::other(
                "it is a folder; name a .obj or .json file",
            )),
            ReadError::Io(source) => io(source),
        })?;
        let text = String::from_utf8(bytes).map_err(|_| {
            io(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                "stream did not contain valid UTF-8",
            ))
        })?;
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let is_json = match ext.as_deref() {
            Some("json") => true,
            Some("obj") => false,
            _ => text.trim_start().starts_with('{'),
        };
        let result = if is_json {
            Tiling::from_json_str(&text)
        } else {
            Tiling::from_obj_str(&text)
        };
        result.map_err(|e| TilingError::InFile {
            path: path.to_path_buf(),
            source: Box::new(e),
        })
    }

    /// Parses and validates a JSON tiling.
    ///
    /// # Errors
    ///
    /// [`TilingError::Json`] for malformed text, else a validation error.
    pub fn from_json_str(text: &str) -> Result<Tiling, TilingError> {
        let raw: JsonTiling = serde_json::from_str(text).map_err(|e| TilingError::Json {
            line: e.line(),
            column: e.column(),
            message: e.to_string(),
        })?;
        let points = raw.points.iter().map(|&[x, y]| Point::new(x, y)).collect();
        Tiling::new(points, raw.faces)
    }

    /// Parses and validates an OBJ tiling (z ignored, 1-based indices).
    ///
    /// # Errors
    ///
    /// [`TilingError::Obj`] for a malformed line, else a validation error.
    pub fn from_obj_str(text: &str) -> Result<Tiling, TilingError> {
        let mut points: Vec<Point> = Vec::new();
        let mut faces: Vec<Vec<u32>> = Vec::new();
        for (ln, line) in text.lines().enumerate() {
            let line_no = ln + 1;
            let bad = |message: String| TilingError::Obj {
                line: line_no,
                message,
            };
            let line = line.split('#').next().unwrap_or("");
            let mut tokens = line.split_whitespace();
            match tokens.next() {
                Some("v") => {
                    let mut coord = || -> Result<f64, TilingError> {
                        let tok = tokens
                            .next()
                            .ok_or_else(|| bad("a vertex needs x and y".into()))?;
                        tok.parse::<f64>()
                            .map_err(|_| bad(format!("{tok:?} is not a number")))
                    };
                    let x = coord()?;
                    let y = coord()?;
                    if points.len() >= MAX_VERTICES {
                        return Err(TilingError::TooManyVertices {
                            count: points.len() + 1,
                            max: MAX_VERTICES,
                        });
                    }
                    points.push(Point::new(x, y));
                }
                Some("f") => {
                    let mut face = Vec::new();
                    for tok in tokens {
                        let first = tok.split('/').next().unwrap_or("");
                        let idx: i64 = first
                            .parse()
                            .map_err(|_| bad(format!("{tok:?} is not a vertex index")))?;
                        let n = points.len() as i64;
                        let zero_based = if idx > 0 {
                            idx - 1
                        } else if idx < 0 {
                            n + idx
                        } else {
                            return Err(bad("vertex index 0 (obj indices start at 1)".into()));
                        };
                        if zero_based < 0 || zero_based >= n {
                            return Err(TilingError::IndexOutOfRange {
                                face: faces.len(),
                                index: zero_based,
                                vertices: points.len(),
                            });
                        }
                        face.push(zero_based as u32);
                    }
                    faces.push(face);
                }
                _ => {}
            }
        }
        Tiling::new(points, faces)
    }

    /// Writes the tiling as JSON `{"points": ..., "faces": ...}`.
    pub fn to_json_string(&self) -> String {
        let points: Vec<[f64; 2]> = self.points.iter().map(|p| [p.x, p.y]).collect();
        serde_json::json!({ "points": points, "faces": self.faces }).to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn obj_forms() {
        let t = Tiling::from_obj_str(
            "# square\nv 0 0 5\nv 1 0\nv 1 1\nv 0 1\nvt 0 0\nf 1/1 2/1/1 3//1\nf -4 -2 -1\n",
        )
        .unwrap();
        assert_eq!(t.faces, vec![vec![0, 1, 2], vec![0, 2, 3]]);
    }

    #[test]
    fn obj_errors() {
        assert!(matches!(
            Tiling::from_obj_str("v 0 0\nf 1 2 3\n"),
            Err(TilingError::IndexOutOfRange { face: 0, .. })
        ));
        assert!(Tiling::from_obj_str("v nan 0\n").is_err());
        assert!(Tiling::from_obj_str("").is_err());
        assert!(Tiling::from_json_str("{").is_err());
        assert!(Tiling::from_json_str(r#"{"points": [[0,0]], "faces": [[0,0,0]]}"#).is_err());
    }
}
