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

impl Layer {
    /// The layer's paint (everything but its outline and fill rule).
    pub fn paint(&self) -> Paint {
        Paint {
            fill: self.fill,
            stroke: self.stroke,
            stroke_width: self.stroke_width,
            opacity: self.opacity,
        }
    }
}

/// The paint of one shape of a drawing at one moment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Paint {
    /// Fill colour; `None`: not filled.
    pub fill: Option<crate::Rgba>,
    /// Stroke colour; `None`: not stroked.
    pub stroke: Option<crate::Rgba>,
    /// Stroke width in world units (scaled with the view).
    pub stroke_width: f64,
    /// Opacity in [0, 1] of the whole shape.
    pub opacity: f64,
}

/// One shape of a keyed drawing ([`DrawingKeys`]): its outline at its key
/// times, played linearly in between, and its paint at its paint times.
#[derive(Clone, Copy, Debug)]
pub struct Track<'a> {
    /// The key shapes; each one's `outline` is the shape.
    pub shapes: &'a [Frame],
    /// Their frame positions: finite, strictly increasing, the first 0
    /// and the last the animation's last frame.
    pub times: &'a [f64],
    /// The paint at each of `paint_times`.
    pub paints: &'a [Paint],
    /// Frame positions of the paints, as `times` are.
    pub paint_times: &'a [f64],
    /// True for the even-odd fill rule, false for nonzero.
    pub evenodd: bool,
}

/// A stretch of a keyed drawing: the shapes shown from frame position
/// `start` until the next scene's start (the last scene until the end).
#[derive(Clone, Copy, Debug)]
pub struct Scene<'a> {
    /// Where it starts showing: 0 for the first scene, strictly
    /// increasing.
    pub start: f64,
    /// Its shapes, bottom first (painting order).
    pub tracks: &'a [Track<'a>],
}

/// A drawing written as keyframes by [`crate::lottie_drawing`] and
/// [`crate::animated_svg_drawing`]: scenes of shapes, each keyed on its own
/// times, in an animation of `frames` frames (0 to `frames − 1`).
#[derive(Clone, Copy, Debug)]
pub struct DrawingKeys<'a> {
    /// The scenes, in time order.
    pub scenes: &'a [Scene<'a>],
    /// Frames of the whole animation.
    pub frames: usize,
    /// World to pixels.
    pub view: crate::View,
    /// Decimals of every written coordinate; `None` for full `f64`
    /// precision.
    pub digits: Option<u32>,
}

impl DrawingKeys<'_> {
    /// Checks the scenes, their tracks' shapes and times.
    pub(crate) fn check(&self) -> Result<(), RenderError> {
        if self.scenes.is_empty() || self.frames == 0 {
            return Err(RenderError::NoFrames);
        }
        let last = self.frames - 1;
        let bad = |key: usize, time: f64| RenderError::KeyTime { key, time, last };
        for (i, s) in self.scenes.iter().enumerate() {
            let after = if i == 0 {
                s.start == 0.0
            } else {
                s.start > self.scenes[i - 1].start
            };
            if !(after && s.start <= last as f64) {
                return Err(bad(i, s.start));
            }
            for t in s.tracks {
                self.keys(t).check()?;
                let spans = |times: &[f64]| {
                    times.first() == Some(&0.0) && times.last() == Some(&(last as f64))
                };
                if !spans(t.times) {
                    return Err(bad(0, t.times.first().copied().unwrap_or(f64::NAN)));
                }
                if t.paints.len() != t.paint_times.len() || !spans(t.paint_times) {
                    return Err(bad(0, t.paint_times.first().copied().unwrap_or(f64::NAN)));
                }
                for (k, w) in t.paint_times.windows(2).enumerate() {
                    if w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater) {
                        return Err(bad(k + 1, w[1]));
                    }
                }
            }
        }
        Ok(())
    }

    /// The keys of one track, as the one-shape writers take them.
    pub(crate) fn keys<'t>(&self, t: &Track<'t>) -> crate::Keys<'t> {
        crate::Keys {
            shapes: t.shapes,
            times: t.times,
            frames: self.frames,
            view: self.view,
            digits: self.digits,
        }
    }
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
