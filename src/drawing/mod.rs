//! Drawings: many styled closed shapes per file (docs/design.md §2a).
//!
//! A [`Drawing`] is an ordered list of [`Shape`]s, bottom first (the order
//! they are painted in). Each shape is a cleaned, oriented closed polygon
//! (as a [`Curve`] is) with its id, fill and stroke colours, stroke width,
//! opacity and fill rule.
//!
//! Formats (chosen by the file extension):
//! - SVG: every closed subpath of every visible `path`, `polygon`, `rect`,
//!   `circle` or `ellipse`, in groups with transforms, in document order;
//!   a filled subpath that is left open is closed as SVG fills it.
//!   Gradients and patterns are flattened to one colour with a notice;
//!   stroke-only open subpaths are left out with a notice. A subpath that
//!   is a hole of another (docs/design.md §2a) is refused.
//! - JSON: `{"shapes": [{"id", "points", "fill", "stroke", "stroke_width",
//!   "opacity", "fill_rule"}]}` (only `points` is required), or a single
//!   curve in any curve format, which is a drawing of one shape.
//!
//! [`Drawing::from_path`] also requires every shape to be
//! self-overlapping, naming the first that is not and why;
//! [`Drawing::read_path`] reads without that requirement (for `check`,
//! which answers per shape).

mod holes;
mod json;
mod matching;
mod style;
mod svg;
mod tween;

pub use matching::{MatchMode, Matching, match_shapes};
pub use style::{Color, FillRule, Style};
pub use tween::{DrawingFrame, DrawingTween, DrawingTweenError, FrameShape, ShapeKeys, ShapeRole};

use crate::curve::{Curve, CurveError, Format};
use crate::geom::Point;
use crate::immersion::{self, Immersion, NotSelfOverlapping};
use rayon::prelude::*;
use std::path::Path;

/// Most shapes one drawing may hold.
pub(crate) const MAX_SHAPES: usize = crate::curve::MAX_SVG_SHAPES;

/// One closed shape of a drawing with its style.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Shape {
    /// Its id: the SVG element's `id` (followed by `.K` for the K-th
    /// closed subpath of an element of several), the JSON `id`; empty when
    /// it has none.
    pub id: String,
    /// What names it in messages: `shape K` (counting from 1 in the
    /// drawing) and, for SVG, the element and subpath it came from.
    #[serde(skip)]
    pub label: String,
    /// The vertices, cleaned and oriented (y up) as [`Curve::points`].
    #[serde(serialize_with = "crate::frames::ser_points")]
    pub points: Vec<Point>,
    /// True when the shape was given clockwise and has been reversed.
    #[serde(skip)]
    pub reversed: bool,
    /// Its paint.
    #[serde(flatten)]
    pub style: Style,
}

impl Shape {
    /// The shape of a cleaned and oriented `curve`, with its id, label and
    /// paint.
    pub(crate) fn new(id: String, label: String, curve: Curve, style: Style) -> Shape {
        Shape {
            id,
            label,
            points: curve.points,
            reversed: curve.reversed,
            style,
        }
    }
}

/// An ordered list of shapes, bottom first.
#[derive(Clone, Debug, PartialEq)]
pub struct Drawing {
    /// The drawing's name (the file stem).
    pub name: String,
    /// The shapes, in painting order (bottom first).
    pub shapes: Vec<Shape>,
    /// What reading changed or left out (gradients flattened, open strokes
    /// left out), one line each, naming the element.
    pub notices: Vec<String>,
    /// True when the file held one plain curve (JSON points, text, or an
    /// SVG of one closed subpath): the drawing of one shape.
    pub single_curve: bool,
}

/// Why a drawing could not be read. All of these are bad input (the CLI
/// exits with code 2).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DrawingError {
    /// The file, or one shape of it, could not be read as a curve.
    #[error(transparent)]
    Curve(#[from] CurveError),
    /// A subpath cuts a hole into another (docs/design.md §2a).
    #[error(
        "{path}: {hole} is a hole in {outer} (under the {rule} fill rule it cuts a region out of it); holes are not supported yet: draw the parts as separate shapes"
    )]
    Hole {
        /// The file.
        path: String,
        /// The subpath that is a hole.
        hole: String,
        /// The subpath it cuts into.
        outer: String,
        /// The fill rule of their element.
        rule: FillRule,
    },
    /// A shape is not self-overlapping, so it cannot be morphed.
    #[error(
        "{path}: {shape} is not self-overlapping ({reason}); every shape of a drawing must bound an immersed disk"
    )]
    NotSelfOverlapping {
        /// The file.
        path: String,
        /// The shape (`shape K 'ID'`).
        shape: String,
        /// Why.
        reason: NotSelfOverlapping,
    },
    /// The drawing has no shape at all.
    #[error("{path}: no closed shape found ({why}); draw closed, filled paths")]
    Empty {
        /// The file.
        path: String,
        /// What was left out.
        why: String,
    },
    /// Two shapes of a JSON drawing share an id.
    #[error("{path}: shapes {first} and {second} share the id '{id}'; give every shape its own id")]
    DuplicateId {
        /// The file.
        path: String,
        /// The id.
        id: String,
        /// The first shape with it (counting from 1).
        first: usize,
        /// The second.
        second: usize,
    },
}

impl Drawing {
    /// Reads a drawing and requires every shape to be self-overlapping.
    ///
    /// # Errors
    ///
    /// As [`Drawing::read_path`], and [`DrawingError::NotSelfOverlapping`]
    /// naming the first shape that is not.
    pub fn from_path(path: impl AsRef<Path>) -> Result<Drawing, DrawingError> {
        let path = path.as_ref();
        let drawing = Drawing::read_path(path)?;
        drawing.require_self_overlapping(&path.display().to_string())?;
        Ok(drawing)
    }

    /// Reads a drawing without deciding whether its shapes are
    /// self-overlapping (holes are still refused).
    ///
    /// # Errors
    ///
    /// [`DrawingError::Curve`] for a file or a shape that cannot be read
    /// (naming the shape), [`DrawingError::Hole`], [`DrawingError::Empty`].
    pub fn read_path(path: impl AsRef<Path>) -> Result<Drawing, DrawingError> {
        let file = crate::curve::InputFile::read(path.as_ref(), "drawing")?;
        Drawing::from_bytes(&file.bytes, file.format, &file.label, &file.stem)
    }

    /// [`Drawing::read_path`] on data in memory; `label` names the source
    /// in errors and `name` is the drawing's name.
    ///
    /// # Errors
    ///
    /// As [`Drawing::read_path`], except the I/O errors.
    pub fn from_bytes(
        bytes: &[u8],
        format: Format,
        label: &str,
        name: &str,
    ) -> Result<Drawing, DrawingError> {
        let bytes = crate::curve::screen_bytes(bytes, label)?;
        let drawing = match format {
            Format::Svg => svg::read(bytes, label, name)?,
            Format::Json if json::is_drawing(bytes) => json::read(bytes, label, name)?,
            _ => {
                let curve = Curve::from_bytes(bytes, format, label, name)?;
                Drawing::of_curve(curve, Style::default())
            }
        };
        if drawing.shapes.len() > MAX_SHAPES {
            return Err(CurveError::TooLarge {
                path: label.to_string(),
                what: format!("{} shapes", drawing.shapes.len()),
                limit: format!("{MAX_SHAPES} shapes"),
            }
            .into());
        }
        Ok(drawing)
    }

    /// Every top-level group of an SVG file as a drawing (a sequence of
    /// drawings in one file: each group, or Inkscape layer, one key),
    /// each named as its group (`group 'ID'`, `group K`). Every closed
    /// subpath of a group is a shape of its drawing, as
    /// [`Drawing::read_path`] reads a whole file; holes are refused.
    ///
    /// # Errors
    ///
    /// As [`Drawing::read_path`], naming the group.
    pub fn groups_from_path(path: impl AsRef<Path>) -> Result<Vec<Drawing>, DrawingError> {
        let path = path.as_ref();
        let label = path.display().to_string();
        let bytes = crate::curve::read_file(path, &label)?;
        let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(&bytes);
        let drawings = svg::read_groups(bytes, &label)?;
        for d in &drawings {
            if d.shapes.len() > MAX_SHAPES {
                return Err(CurveError::TooLarge {
                    path: format!("{label} ({})", d.name),
                    what: format!("{} shapes", d.shapes.len()),
                    limit: format!("{MAX_SHAPES} shapes"),
                }
                .into());
            }
        }
        Ok(drawings)
    }

    /// The drawing of one curve, painted with `style`.
    pub(crate) fn of_curve(mut curve: Curve, style: Style) -> Drawing {
        Drawing {
            name: std::mem::take(&mut curve.name),
            shapes: vec![Shape::new(
                String::new(),
                "shape 1".to_string(),
                curve,
                style,
            )],
            notices: Vec::new(),
            single_curve: true,
        }
    }

    /// Number of shapes.
    pub fn len(&self) -> usize {
        self.shapes.len()
    }

    /// True when the drawing has no shape (never, once read).
    pub fn is_empty(&self) -> bool {
        self.shapes.is_empty()
    }

    /// Triangulates every shape (in parallel): its immersion, or why it is
    /// not self-overlapping.
    pub fn triangulate(&self) -> Vec<Result<Immersion, NotSelfOverlapping>> {
        self.shapes
            .par_iter()
            .map(|s| immersion::triangulate(&s.points))
            .collect()
    }

    /// Every shape's triangulation; the first shape that is not
    /// self-overlapping is an error naming it (`path` names the file).
    ///
    /// # Errors
    ///
    /// [`DrawingError::NotSelfOverlapping`].
    pub fn require_self_overlapping(&self, path: &str) -> Result<Vec<Immersion>, DrawingError> {
        self.triangulate()
            .into_iter()
            .zip(&self.shapes)
            .map(|(r, s)| {
                r.map_err(|reason| DrawingError::NotSelfOverlapping {
                    path: path.to_string(),
                    shape: s.label.clone(),
                    reason,
                })
            })
            .collect()
    }
}

/// Exact winding number of the closed polygon `poly` around `p`, or `None`
/// when `p` lies on one of its edges. Crossings of the horizontal ray to
/// the right of `p` are counted with the half-open rule on y, and the side
/// of each crossing edge is an exact orientation.
pub fn winding_number(poly: &[Point], p: Point) -> Option<i64> {
    use crate::geom::predicates::{Orientation, orient};
    let mut w = 0_i64;
    for i in 0..poly.len() {
        let a = poly[i];
        let b = poly[(i + 1) % poly.len()];
        let side = orient(a, b, p);
        if side == Orientation::Collinear
            && p.x >= a.x.min(b.x)
            && p.x <= a.x.max(b.x)
            && p.y >= a.y.min(b.y)
            && p.y <= a.y.max(b.y)
        {
            return None;
        }
        if a.y <= p.y {
            if b.y > p.y && side.is_ccw() {
                w += 1;
            }
        } else if b.y <= p.y && side.is_cw() {
            w -= 1;
        }
    }
    Some(w)
}
