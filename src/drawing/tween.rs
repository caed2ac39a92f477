//! Morphing drawings: every matched pair of shapes morphs as a curve does
//! ([`Tween`], in parallel), unmatched shapes grow from or shrink to a
//! small similar copy at their centroid, and styles are interpolated
//! (docs/design.md §2b).

use super::matching::Matching;
use super::style::Style;
use super::{Drawing, Shape};
use crate::frames::Frame;
use crate::geom::Point;
use crate::geom::polygon::area_centroid;
use crate::immersion::{self, NotSelfOverlapping, check_triangles};
use crate::morph::{CurveMorphError, CurveMorphOptions, Keyframe, MorphError, Tween};
use rayon::prelude::*;

/// The scale of the copy an unmatched shape grows from or shrinks to: a
/// shape of size zero is not a disk, so the copy is small, not a point.
pub(crate) const GROWN_SCALE: f64 = 0.02;

/// What a shape of a drawing morph does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ShapeRole {
    /// Morphs from a source shape into its partner.
    Matched,
    /// A target shape without partner: grows from a small copy and fades
    /// in.
    Appearing,
    /// A source shape without partner: shrinks to a small copy and fades
    /// out.
    Vanishing,
}

/// One shape of a drawing frame.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FrameShape {
    /// The source shape's id, else the target's (empty when neither has
    /// one).
    pub id: String,
    /// What the shape does.
    pub role: ShapeRole,
    /// Its vertices (vertex `i` is vertex `i` in every frame).
    #[serde(serialize_with = "crate::frames::ser_points")]
    pub points: Vec<Point>,
    /// Its triangles, counter-clockwise: it is an immersed disk.
    pub triangles: Vec<[u32; 3]>,
    /// Its paint at this frame.
    #[serde(flatten)]
    pub style: Style,
}

/// A frame of a drawing morph: every shape, in painting order.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct DrawingFrame {
    /// The morph parameter, in [0, 1].
    pub t: f64,
    /// The shapes, bottom first.
    pub shapes: Vec<FrameShape>,
}

/// Why a drawing morph could not be planned or a frame made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DrawingTweenError {
    /// A matched pair could not be morphed.
    #[error("{from} → {to}: {source}")]
    Pair {
        /// The source shape.
        from: String,
        /// The target shape.
        to: String,
        /// Why.
        #[source]
        source: CurveMorphError,
    },
    /// An unmatched shape is not self-overlapping.
    #[error("{shape} is not self-overlapping: {reason}")]
    NotSelfOverlapping {
        /// The shape.
        shape: String,
        /// Why.
        reason: NotSelfOverlapping,
    },
    /// A frame of a shape failed.
    #[error("{shape}: {source}")]
    Frame {
        /// The shape.
        shape: String,
        /// Why.
        #[source]
        source: MorphError,
    },
    /// A scaled copy failed the exact immersion check: a bug in immerse.
    #[error(
        "{shape} scaled by {scale} is not an immersion ({defect}); this is a bug in immerse, please report it with the two drawings"
    )]
    Scaled {
        /// The shape.
        shape: String,
        /// The scale.
        scale: f64,
        /// What the checker found.
        defect: String,
    },
}

/// The certified keys of one shape of a drawing morph
/// ([`DrawingTween::shape_keys`]).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ShapeKeys {
    /// The shape's id (as [`FrameShape::id`]).
    pub id: String,
    /// What names it in messages (`shape K (…) → shape J (…)`).
    #[serde(skip)]
    pub label: String,
    /// What the shape does.
    pub role: ShapeRole,
    /// Its paint at t = 0.
    #[serde(skip)]
    pub from: Style,
    /// Its paint at t = 1.
    #[serde(skip)]
    pub to: Style,
    /// How many keys.
    pub key_count: usize,
    /// Its keys, `t` in [0, 1] on the morph's axis: linear interpolation
    /// between consecutive keys gives the shape's frames, and every
    /// segment between two keys is certified an immersed disk (a matched
    /// shape's [`Tween::keyframes`]; the two ends of a growing or
    /// shrinking shape, whose motion is a scaling).
    pub keyframes: Vec<Keyframe>,
}

impl ShapeKeys {
    /// The shape's paint at `t`: the two styles interpolated (colours in
    /// OKLab).
    pub fn style_at(&self, t: f64) -> Style {
        self.from.lerp(&self.to, t)
    }
}

/// How one shape of the morph moves.
#[derive(Clone, Debug)]
enum Motion {
    Tween(Box<Tween>),
    /// Scaled about `centre`, from `from` to `to`.
    Scale {
        points: Vec<Point>,
        triangles: Vec<[u32; 3]>,
        centre: Point,
        from: f64,
        to: f64,
    },
}

#[derive(Clone, Debug)]
struct Part {
    id: String,
    label: String,
    role: ShapeRole,
    motion: Motion,
    from: Style,
    to: Style,
}

/// A planned morph from one drawing to another: a verified frame of every
/// shape at any t.
#[derive(Clone, Debug)]
pub struct DrawingTween {
    parts: Vec<Part>,
    matching: Matching,
}

impl DrawingTween {
    /// Plans the morph of drawing `a` into `b` with `matching` (from
    /// [`super::match_shapes`]): one [`Tween`] per pair, with `options`,
    /// planned in parallel.
    ///
    /// Stacking order follows the source: matched and vanishing shapes in
    /// `a`'s order, each appearing shape just above the shape that holds
    /// the nearest matched shape below it in `b` (at the bottom when there
    /// is none). When `b` stacks its matched shapes differently, `a`'s
    /// order is kept throughout.
    ///
    /// # Errors
    ///
    /// [`DrawingTweenError::Pair`] naming the pair whose tween failed,
    /// [`DrawingTweenError::NotSelfOverlapping`] for an unmatched shape.
    pub fn new(
        a: &Drawing,
        b: &Drawing,
        matching: &Matching,
        options: &CurveMorphOptions,
    ) -> Result<DrawingTween, DrawingTweenError> {
        enum Job<'a> {
            Pair(&'a Shape, &'a Shape),
            Vanish(&'a Shape),
            Appear(&'a Shape),
        }
        // The painting order: source order, appearing shapes slotted in.
        let mut order: Vec<Job<'_>> = Vec::new();
        let partner_of_target = |j: usize| matching.pairs.iter().find(|p| p.1 == j).map(|p| p.0);
        let mut placed_after: Vec<Vec<usize>> = vec![Vec::new(); a.len() + 1];
        for &j in &matching.appearing {
            let below = (0..j).rev().find_map(partner_of_target);
            placed_after[below.map_or(0, |i| i + 1)].push(j);
        }
        for &j in &placed_after[0] {
            order.push(Job::Appear(&b.shapes[j]));
        }
        for (i, shape) in a.shapes.iter().enumerate() {
            match matching.pairs.iter().find(|p| p.0 == i) {
                Some(&(_, j)) => order.push(Job::Pair(shape, &b.shapes[j])),
                None => order.push(Job::Vanish(shape)),
            }
            for &j in &placed_after[i + 1] {
                order.push(Job::Appear(&b.shapes[j]));
            }
        }
        let scaled = |s: &Shape, from: f64, to: f64| -> Result<Motion, DrawingTweenError> {
            let imm = immersion::triangulate(&s.points).map_err(|reason| {
                DrawingTweenError::NotSelfOverlapping {
                    shape: s.label.clone(),
                    reason,
                }
            })?;
            Ok(Motion::Scale {
                centre: area_centroid(&s.points),
                points: imm.points,
                triangles: imm.triangles,
                from,
                to,
            })
        };
        let faded = |s: &Style| Style { opacity: 0.0, ..*s };
        let id = |s: &Shape, t: &Shape| {
            if s.id.is_empty() {
                t.id.clone()
            } else {
                s.id.clone()
            }
        };
        let parts = order
            .par_iter()
            .map(|job| {
                Ok(match *job {
                    Job::Pair(s, t) => Part {
                        id: id(s, t),
                        label: format!("{} → {}", s.label, t.label),
                        role: ShapeRole::Matched,
                        motion: Motion::Tween(Box::new(
                            Tween::new(&s.points, &t.points, options).map_err(|source| {
                                DrawingTweenError::Pair {
                                    from: s.label.clone(),
                                    to: t.label.clone(),
                                    source,
                                }
                            })?,
                        )),
                        from: s.style,
                        to: t.style,
                    },
                    Job::Vanish(s) => Part {
                        id: s.id.clone(),
                        label: s.label.clone(),
                        role: ShapeRole::Vanishing,
                        motion: scaled(s, 1.0, GROWN_SCALE)?,
                        from: s.style,
                        to: faded(&s.style),
                    },
                    Job::Appear(t) => Part {
                        id: t.id.clone(),
                        label: t.label.clone(),
                        role: ShapeRole::Appearing,
                        motion: scaled(t, GROWN_SCALE, 1.0)?,
                        from: faded(&t.style),
                        to: t.style,
                    },
                })
            })
            .collect::<Result<Vec<Part>, DrawingTweenError>>()?;
        Ok(DrawingTween {
            parts,
            matching: matching.clone(),
        })
    }

    /// The matching the morph follows.
    pub fn matching(&self) -> &Matching {
        &self.matching
    }

    /// Number of shapes in every frame.
    pub fn shape_count(&self) -> usize {
        self.parts.len()
    }

    /// Every shape's certified keys, in painting order (as
    /// [`DrawingFrame::shapes`]).
    ///
    /// # Errors
    ///
    /// [`DrawingTweenError::Scaled`] when a growing or shrinking shape's
    /// segment is not certified (a bug).
    pub fn shape_keys(&self) -> Result<Vec<ShapeKeys>, DrawingTweenError> {
        self.parts
            .par_iter()
            .map(|part| {
                let keyframes = match &part.motion {
                    Motion::Tween(tween) => tween.keyframes(),
                    Motion::Scale { triangles, .. } => {
                        let ends = [part.frame(0.0)?, part.frame(1.0)?];
                        let n = ends[0].points.len();
                        let certified = crate::certify::segment_holds(
                            &ends[0].points,
                            &ends[1].points,
                            &crate::immersion::CheckedTriangles::new(n, triangles),
                            crate::certify::Player::Exact,
                        );
                        if !certified {
                            return Err(DrawingTweenError::Scaled {
                                shape: part.label.clone(),
                                scale: GROWN_SCALE,
                                defect: "the scaling between its two keys is not certified"
                                    .to_string(),
                            });
                        }
                        ends.into_iter()
                            .map(|f| Keyframe {
                                t: f.t,
                                points: f.points,
                                triangles: f.triangles,
                            })
                            .collect()
                    }
                };
                Ok(ShapeKeys {
                    id: part.id.clone(),
                    label: part.label.clone(),
                    role: part.role,
                    from: part.from,
                    to: part.to,
                    key_count: keyframes.len(),
                    keyframes,
                })
            })
            .collect()
    }

    /// True when every matched shape's tween is certified between its
    /// keys ([`Tween::is_certified`]); growing and shrinking shapes are
    /// certified by [`DrawingTween::shape_keys`].
    pub fn is_certified(&self) -> bool {
        self.parts.iter().all(|p| match &p.motion {
            Motion::Tween(t) => t.is_certified(),
            Motion::Scale { .. } => true,
        })
    }

    /// The pace of the morph: the largest of its shapes'
    /// ([`Tween::path_length`]; for a growing or shrinking shape, the
    /// farthest any vertex travels).
    pub fn path_length(&self) -> f64 {
        self.parts
            .iter()
            .map(|p| match &p.motion {
                Motion::Tween(t) => t.path_length(),
                Motion::Scale {
                    points,
                    centre,
                    from,
                    to,
                    ..
                } => {
                    let r = points
                        .iter()
                        .map(|&q| (q - *centre).length())
                        .fold(0.0, f64::max);
                    r * (to - from).abs()
                }
            })
            .fold(0.0, f64::max)
    }

    /// The frame at `t` in [0, 1]: every shape's frame at t (a tween's, or
    /// the scaled copy), each checked exactly to be an immersion, with its
    /// interpolated style.
    ///
    /// # Errors
    ///
    /// [`DrawingTweenError::Frame`] for a t outside [0, 1] or a tween's
    /// failed frame (a bug); [`DrawingTweenError::Scaled`] (a bug).
    pub fn frame(&self, t: f64) -> Result<DrawingFrame, DrawingTweenError> {
        let shapes = self
            .parts
            .par_iter()
            .map(|part| {
                let frame = part.frame(t)?;
                Ok(FrameShape {
                    id: part.id.clone(),
                    role: part.role,
                    points: frame.points,
                    triangles: frame.triangles,
                    style: part.from.lerp(&part.to, t),
                })
            })
            .collect::<Result<Vec<_>, DrawingTweenError>>()?;
        Ok(DrawingFrame { t, shapes })
    }
}

impl Part {
    fn frame(&self, t: f64) -> Result<Frame, DrawingTweenError> {
        match &self.motion {
            Motion::Tween(tween) => tween.frame(t).map_err(|source| DrawingTweenError::Frame {
                shape: self.label.clone(),
                source,
            }),
            Motion::Scale {
                points,
                triangles,
                centre,
                from,
                to,
            } => {
                if !(0.0..=1.0).contains(&t) {
                    return Err(DrawingTweenError::Frame {
                        shape: self.label.clone(),
                        source: MorphError::Fraction(t),
                    });
                }
                let scale = from + t * (to - from);
                let points: Vec<Point> = points
                    .iter()
                    .map(|&p| *centre + scale * (p - *centre))
                    .collect();
                check_triangles(&points, triangles).map_err(|defect| {
                    DrawingTweenError::Scaled {
                        shape: self.label.clone(),
                        scale,
                        defect: defect.to_string(),
                    }
                })?;
                Ok(Frame {
                    t,
                    points,
                    triangles: triangles.clone(),
                })
            }
        }
    }
}
