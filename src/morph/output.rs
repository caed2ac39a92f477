//! What a morph gives: its frames, the paths that made them and the
//! recoveries on the way (docs/design.md §8). A morph's JSON, with the
//! motion measures of its frames, is written in [`crate::frames`].

use crate::geom::Point;
use crate::morph::ThirdVertexPath;
use crate::staged::Fallback;

/// One in-between: vertex positions and the triangulation they carry.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Frame {
    /// The morph parameter of this frame, in [0, 1].
    pub t: f64,
    /// Vertex positions (y up), in the curve's cyclic order.
    #[serde(serialize_with = "ser_points")]
    pub points: Vec<Point>,
    /// Triangles, counter-clockwise, corners in cyclic order.
    pub triangles: Vec<[u32; 3]>,
}

pub(crate) fn ser_points<S: serde::Serializer>(points: &[Point], s: S) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeSeq;
    let mut seq = s.serialize_seq(Some(points.len()))?;
    for p in points {
        seq.serialize_element(&[p.x, p.y])?;
    }
    seq.end()
}

impl Frame {
    /// Checks with exact predicates that the frame is an immersion: every
    /// triangle counter-clockwise and no vertex fan wraps.
    ///
    /// # Errors
    ///
    /// The defect found by the immersion checker.
    pub fn check(&self) -> Result<(), crate::immersion::ImmersionDefect> {
        crate::immersion::check(&self.points, &self.triangles)
    }

    /// True when [`Frame::check`] passes.
    pub fn is_immersion(&self) -> bool {
        self.check().is_ok()
    }

    /// The smallest triangle angle of the frame, in radians.
    pub(crate) fn min_angle(&self) -> f64 {
        crate::geom::polygon::min_triangle_angle(&self.points, &self.triangles)
    }

    /// Total area of the triangles (overlaps counted with multiplicity).
    pub fn total_area(&self) -> f64 {
        crate::morph::area_and_centroid(&self.points, &self.triangles).0
    }
}

/// A morph: its frames, the paths that produced them and everything that
/// did not go as asked.
///
/// In JSON: `{"path": ..., "fallback": ..., "fallbacks": [...], "motion":
/// {"detour": ..., "unwind": ...}, "frames": [...]}`, where `motion` holds
/// the [`detour`](crate::frames::detour) and [`unwind`](crate::frames::unwind) of the frames (`null` where they are not
/// defined, e.g. when the vertex count changes between frames). They are
/// computed from the frames the first time the morph is written and kept,
/// so writing it again does not search again; change `frames` only
/// before writing it.
#[derive(Clone, Debug, PartialEq)]
pub struct Morph {
    /// The third-vertex paths the frames were made with, in order of first
    /// use (in JSON: `path`, one name or names joined by `+`).
    pub paths: Vec<ThirdVertexPath>,
    /// True when anything other than what was asked was used (another
    /// path, the disk, another triangulation, other counts); `fallbacks`
    /// says what and why.
    pub fallback: bool,
    /// What was tried instead of what was asked, and why, in order.
    pub fallbacks: Vec<Fallback>,
    /// The frames, in order of t.
    pub frames: Vec<Frame>,
    /// The motion measures of `frames`, once they are first written.
    pub(crate) motion: MotionOnce,
}

/// A morph's motion measures in JSON: each `None` (`null`) where it is not
/// defined.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub(crate) struct Motion {
    pub(crate) detour: Option<f64>,
    pub(crate) unwind: Option<f64>,
}

/// The [`Motion`] of a morph's frames, computed at most once. It is a
/// cache of what the frames determine, so two morphs are equal by their
/// other fields whether or not either has filled it.
#[derive(Clone, Debug, Default)]
pub(crate) struct MotionOnce(std::sync::OnceLock<Motion>);

impl MotionOnce {
    /// The measures, computed by `compute` the first time only.
    pub(crate) fn get_or_init(&self, compute: impl FnOnce() -> Motion) -> Motion {
        *self.0.get_or_init(compute)
    }
}

impl PartialEq for MotionOnce {
    fn eq(&self, _: &MotionOnce) -> bool {
        true
    }
}

impl Morph {
    /// A morph of `frames`, made with `paths` (in order of first use),
    /// with the recoveries `fallbacks` (`fallback` is set when there are
    /// any).
    pub fn new(paths: Vec<ThirdVertexPath>, fallbacks: Vec<Fallback>, frames: Vec<Frame>) -> Morph {
        Morph {
            paths,
            fallback: !fallbacks.is_empty(),
            fallbacks,
            frames,
            motion: MotionOnce::default(),
        }
    }

    /// The paths used, as in the JSON: one name, or names joined by `+`.
    pub fn path_name(&self) -> String {
        path_names(&self.paths)
    }
}

/// Path names joined by `+`.
pub(crate) fn path_names(paths: &[ThirdVertexPath]) -> String {
    paths
        .iter()
        .map(|p| p.as_str())
        .collect::<Vec<_>>()
        .join("+")
}
