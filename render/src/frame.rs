//! [`Frame`]: the plain geometry of one picture.

use crate::RenderError;

/// The plain geometry of one frame, in world coordinates with y pointing up.
///
/// Every list other than `points` may be empty. Indices are `u32` positions
/// in `points` (or, for [`spine`](Frame::spine), in `triangles`).
///
/// Primitives that touch a non-finite coordinate (NaN or ±∞) are skipped when
/// drawing; an index that is out of range is an error
/// ([`RenderError::BadIndex`]).
///
/// # Examples
///
/// ```
/// use immerse_render::Frame;
///
/// let frame = Frame::from_triangles(
///     vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
///     vec![[0, 1, 2]],
/// );
/// assert_eq!(frame.outline, vec![0, 1, 2]);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frame {
    /// Vertex positions, y up.
    pub points: Vec<[f64; 2]>,
    /// Triangles as counter-clockwise index triples. They may overlap each
    /// other (an immersed disk); a spot covered by k triangles is drawn
    /// k layers deep.
    pub triangles: Vec<[u32; 3]>,
    /// The closed boundary loop, as indices into `points`; drawn as a closed
    /// stroke. May be empty.
    pub outline: Vec<u32>,
    /// Polygon faces (for tilings), as index loops; each face counts as one
    /// layer, exactly like a triangle.
    pub faces: Vec<Vec<u32>>,
    /// A path of *triangle* indices (into `triangles`), such as the spine of
    /// the dual tree; drawn as a polyline through the triangles' centroids
    /// when [`Style::spine`](crate::Style::spine) is on.
    pub spine: Vec<u32>,
    /// Marker positions in world coordinates (e.g. the pivot vertex), drawn
    /// as dots when [`Style::markers`](crate::Style::markers) is on.
    pub markers: Vec<[f64; 2]>,
    /// The shapes of a drawing, bottom first, each painted with its own
    /// style over the frame's own fill (which a drawing leaves empty).
    pub layers: Vec<Layer>,
}

/// One styled shape of a drawing frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    /// The shape's closed boundary, as indices into the frame's `points`.
    pub outline: Vec<u32>,
    /// Fill colour (its alpha is multiplied by `opacity`); `None`: not
    /// filled.
    pub fill: Option<crate::Rgba>,
    /// Stroke colour; `None`: not stroked.
    pub stroke: Option<crate::Rgba>,
    /// Stroke width in world units (scaled with the view).
    pub stroke_width: f64,
    /// Opacity in [0, 1] of the whole shape.
    pub opacity: f64,
    /// True for the even-odd fill rule, false for nonzero.
    pub evenodd: bool,
}

impl Frame {
    /// A frame of `points` and `triangles` whose outline is the points in
    /// order (the usual case for a triangulated polygon).
    pub fn from_triangles(points: Vec<[f64; 2]>, triangles: Vec<[u32; 3]>) -> Frame {
        let n = u32::try_from(points.len()).unwrap_or(u32::MAX);
        Frame {
            outline: (0..n).collect(),
            points,
            triangles,
            ..Frame::default()
        }
    }

    /// Checks that every index is in range.
    ///
    /// # Errors
    ///
    /// [`RenderError::BadIndex`] naming the first bad index.
    pub fn check_indices(&self) -> Result<(), RenderError> {
        let n = self.points.len();
        let check = |what: &'static str, index: u32, len: usize| {
            if (index as usize) < len {
                Ok(())
            } else {
                Err(RenderError::BadIndex { what, index, len })
            }
        };
        for t in &self.triangles {
            for &i in t {
                check("triangle", i, n)?;
            }
        }
        for layer in &self.layers {
            for &i in &layer.outline {
                check("layer outline", i, n)?;
            }
        }
        for &i in &self.outline {
            check("outline", i, n)?;
        }
        for f in &self.faces {
            for &i in f {
                check("face", i, n)?;
            }
        }
        for &i in &self.spine {
            check("spine", i, self.triangles.len())?;
        }
        Ok(())
    }

    /// The finite points and markers, for bounds.
    pub(crate) fn finite_positions(&self) -> impl Iterator<Item = [f64; 2]> + '_ {
        self.points
            .iter()
            .chain(&self.markers)
            .copied()
            .filter(|p| p[0].is_finite() && p[1].is_finite())
    }

    /// The centroid of triangle `t` (indices already checked).
    pub(crate) fn centroid(&self, t: u32) -> [f64; 2] {
        let [a, b, c] = self.triangles[t as usize].map(|i| self.points[i as usize]);
        [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_indices_are_reported() {
        let mut f = Frame::from_triangles(vec![[0.0, 0.0]; 3], vec![[0, 1, 3]]);
        assert!(matches!(
            f.check_indices(),
            Err(RenderError::BadIndex {
                what: "triangle",
                index: 3,
                len: 3
            })
        ));
        f.triangles = vec![[0, 1, 2]];
        f.spine = vec![1];
        assert!(f.check_indices().is_err());
        f.spine = vec![0];
        assert!(f.check_indices().is_ok());
    }
}
