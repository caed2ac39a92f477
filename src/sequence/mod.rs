//! Keyframe sequences K1 → K2 → K3 … (docs/design.md §12).
//!
//! A [`Sequence`] is planned once from its keys (oriented point lists),
//! the shape hints that pin points of consecutive keys together, and the
//! morph options:
//!
//! 1. every hinted point is made a vertex of its key (a point between
//!    vertices is inserted on its edge);
//! 2. vertex counts are equalised once across all keys by inserting
//!    vertices on edges, so every original vertex of every key stays
//!    exactly where it is. Where consecutive keys share hints, the
//!    vertices are distributed arc by arc between the hints so that each
//!    hinted point has the same vertex number in both keys;
//! 3. one [`Tween`] per segment: hinted segments use exactly the hinted
//!    correspondence, the others choose their cyclic shift by the options'
//!    rule; vertex numbers are then carried along the chain (vertex `i` of
//!    key `j + 1` is the one that vertex `i` of key `j` moves to), so a
//!    vertex keeps its identity through the whole sequence.
//!
//! [`Sequence::schedule`] places the frames (module `timing`): by vertex
//! travel across the whole sequence, so the speed is continuous at a key
//! unless the key holds, a segment's easing stops there, or a time or
//! duration fixes it; [`Sequence::frames`] makes them, each checked
//! exactly; [`key_speeds`] measures the speed on both sides of each key.

mod align;
mod timing;

pub use timing::{
    Ease, KeySpeed, KeyTiming, Sample, Schedule, Timing, key_speeds, schedule_lengths,
};

use crate::correspond::shift_triangles;
use crate::frames::{Fallback, Frame, Morph};
use crate::geom::Point;
use crate::immersion::NotSelfOverlapping;
use crate::morph::{
    Correspondence, Counts, CurveMorphError, CurveMorphOptions, Keyframe, MorphError, Side,
    ThirdVertexPath, Tween,
};
use rayon::prelude::*;

/// One key: a closed curve, oriented (turning number +1, as
/// [`crate::Curve`] gives it), and the name errors call it by.
#[derive(Clone, Debug, PartialEq)]
pub struct Key {
    /// What errors call the key (a file name, say).
    pub name: String,
    /// The vertices, counter-clockwise (turning number +1).
    pub points: Vec<Point>,
}

impl Key {
    /// A key from its name and points.
    pub fn new(name: impl Into<String>, points: Vec<Point>) -> Key {
        Key {
            name: name.into(),
            points,
        }
    }
}

/// Where a hint sits on its key.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HintAt {
    /// A vertex of the key, by its index in [`Key::points`].
    Vertex(usize),
    /// The point of the curve nearest to this one (it must lie within
    /// [`SequenceOptions::hint_tolerance`] of the curve); the vertex there
    /// or within 10⁻³ of the key's size, else a vertex inserted
    /// on its edge.
    Point(Point),
    /// The point at this fraction of the arc length from vertex 0, along
    /// the key's (counter-clockwise) order; in [0, 1]. Snapped to a vertex
    /// as [`HintAt::Point`] is.
    Fraction(f64),
}

impl std::fmt::Display for HintAt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            HintAt::Vertex(i) => write!(f, "vertex {i}"),
            HintAt::Point(p) => write!(f, "[{}, {}]", p.x, p.y),
            HintAt::Fraction(x) => write!(f, "fraction {x}"),
        }
    }
}

/// A shape hint: a point of key `segment` and a point of key
/// `segment + 1` that must correspond (Adobe Animate's shape hints). The
/// hinted point of the first key lands exactly on its partner.
#[derive(Clone, Debug, PartialEq)]
pub struct Hint {
    /// The hint's name, for errors.
    pub name: String,
    /// The segment: the hint joins key `segment` and key `segment + 1`
    /// (counting from 0).
    pub segment: usize,
    /// The point on key `segment`.
    pub from: HintAt,
    /// The point on key `segment + 1`.
    pub to: HintAt,
}

/// A hint as planned: the vertex number it became.
#[derive(Clone, Debug, PartialEq)]
pub struct HintVertex {
    /// The hint's name.
    pub name: String,
    /// Its segment (key `segment` to key `segment + 1`).
    pub segment: usize,
    /// The vertex (in the sequence's numbering) at the hinted point in
    /// both keys.
    pub vertex: usize,
    /// The hinted point on key `segment`.
    pub from: Point,
    /// Its partner on key `segment + 1`.
    pub to: Point,
}

/// Options of a [`Sequence`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct SequenceOptions {
    /// The options of each segment's morph. Counts are always equalised
    /// by insertion (original vertices stay exact); hinted segments use
    /// the hints instead of the correspondence rule.
    pub morph: CurveMorphOptions,
    /// How far from its curve a [`HintAt::Point`] may lie, as a fraction
    /// of the diagonal of the key's bounding box. Default 0.02.
    pub hint_tolerance: f64,
}

impl SequenceOptions {
    /// The defaults.
    pub const DEFAULT: SequenceOptions = SequenceOptions {
        morph: CurveMorphOptions::DEFAULT,
        hint_tolerance: 0.02,
    };
}

crate::options::setters! {
    SequenceOptions: Default {
        /// Sets the morph options.
        fn with_morph(morph: CurveMorphOptions);
        /// Sets the hint tolerance.
        fn with_hint_tolerance(hint_tolerance: f64);
    }
}

/// Why a sequence could not be planned or timed. Keys are numbered from 1
/// (K1, K2, …) in messages.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SequenceError {
    /// Fewer than two keys.
    #[error("{count} key given; a sequence needs at least 2 keys")]
    TooFewKeys {
        /// How many.
        count: usize,
    },
    /// A hint that cannot be honoured.
    #[error("key {key} ({name}): hint '{hint}': {reason}")]
    Hint {
        /// The key, counting from 1.
        key: usize,
        /// The key's name.
        name: String,
        /// The hint's name.
        hint: String,
        /// What is wrong and what to do.
        reason: String,
    },
    /// A key does not bound an immersed disk.
    #[error("key {key} ({name}) is not self-overlapping: {reason}")]
    NotSelfOverlapping {
        /// The key, counting from 1.
        key: usize,
        /// The key's name.
        name: String,
        /// Why.
        reason: NotSelfOverlapping,
    },
    /// Timing that cannot be met (a message naming the key or setting).
    #[error("{0}")]
    Timing(String),
    /// A segment's morph failed (a bug).
    #[error("segment from key {key} to key {}: {source}", key + 1)]
    Morph {
        /// The segment's first key, counting from 1.
        key: usize,
        /// What failed.
        source: MorphError,
    },
}

/// A planned keyframe sequence: equal vertex counts across all keys,
/// hints honoured, one verified [`Tween`] per segment, vertex identity
/// kept through the chain.
///
/// # Examples
///
/// ```
/// use immerse::Curve;
/// use immerse::sequence::{Key, Sequence, SequenceOptions, Timing};
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let keys: Vec<Key> = [
///     "curves/spiral-strip-400deg-n30.json",
///     "curves/curl-strip-n10.json",
///     "curves/annulus-sector-300deg-n40.json",
/// ]
/// .iter()
/// .map(|f| Ok(Key::new(*f, Curve::from_path(f)?.points)))
/// .collect::<Result<_, immerse::curve::CurveError>>()?;
/// let seq = Sequence::new(&keys, &[], &SequenceOptions::DEFAULT)?;
/// let schedule = seq.schedule(&Timing::new(3).with_frames(Some(41)))?;
/// let frames = seq.frames(&schedule)?;
/// assert_eq!(frames.frames.len(), 41);
/// assert!(frames.frames.iter().all(|f| f.is_immersion()));
/// # Ok(())
/// # }
/// ```
#[derive(Clone, Debug)]
pub struct Sequence {
    n: usize,
    names: Vec<String>,
    /// Each key with n vertices in the sequence's numbering.
    keys: Vec<Vec<Point>>,
    /// For each key and vertex, the index of the input vertex it is.
    originals: Vec<Vec<Option<usize>>>,
    tweens: Vec<Tween>,
    /// Vertex `v` of the sequence is vertex `v + offsets[s]` of tween `s`.
    offsets: Vec<usize>,
    hints: Vec<HintVertex>,
}

impl Sequence {
    /// Plans the sequence.
    ///
    /// # Errors
    ///
    /// [`SequenceError::TooFewKeys`]; [`SequenceError::Hint`] for a hint on
    /// a missing segment, off its curve, out of range, sharing a point
    /// with another hint, or out of cyclic order;
    /// [`SequenceError::NotSelfOverlapping`]; [`SequenceError::Morph`] (a
    /// bug).
    pub fn new(
        keys: &[Key],
        hints: &[Hint],
        options: &SequenceOptions,
    ) -> Result<Sequence, SequenceError> {
        if keys.len() < 2 {
            return Err(SequenceError::TooFewKeys { count: keys.len() });
        }
        let aligned = align::align(keys, hints, options.hint_tolerance)?;
        let n = aligned.n;
        let segments = keys.len() - 1;
        let hinted: Vec<bool> = (0..segments)
            .map(|s| aligned.hints.iter().any(|h| h.segment == s))
            .collect();
        let base = options.morph.with_counts(Counts::Insert);
        let tweens: Vec<Tween> = (0..segments)
            .into_par_iter()
            .map(|s| {
                let opts = if hinted[s] {
                    base.with_correspondence(Correspondence::Identity)
                } else {
                    base
                };
                Tween::new(&aligned.keys[s], &aligned.keys[s + 1], &opts).map_err(|e| match e {
                    CurveMorphError::NotSelfOverlapping { side, reason } => {
                        let k = if side == Side::Source { s } else { s + 1 };
                        SequenceError::NotSelfOverlapping {
                            key: k + 1,
                            name: keys[k].name.clone(),
                            reason,
                        }
                    }
                    CurveMorphError::Morph(source) => SequenceError::Morph { key: s + 1, source },
                    // Planning asks for no fractions; nothing else is left.
                    other => SequenceError::Timing(format!(
                        "segment from key {} to key {}: {other}",
                        s + 1,
                        s + 2
                    )),
                })
            })
            .collect::<Result<_, _>>()?;
        // Carry vertex numbers along the chain: the sequence's vertex v is
        // vertex v + o_s of key s as aligned; tween s moves it to vertex
        // v + o_s + shift_s of key s + 1.
        let mut offsets = Vec::with_capacity(segments);
        let mut o = 0usize;
        for t in &tweens {
            offsets.push(o);
            debug_assert!(
                !hinted[offsets.len() - 1] || t.report().shift == 0,
                "hinted segments use the identity"
            );
            o = (o + t.report().shift) % n;
        }
        let rotate =
            |v: &[Point], o: usize| -> Vec<Point> { (0..n).map(|i| v[(i + o) % n]).collect() };
        let mut key_points = Vec::with_capacity(keys.len());
        let mut originals = Vec::with_capacity(keys.len());
        for (j, (pts, orig)) in aligned.keys.iter().zip(&aligned.originals).enumerate() {
            let o = if j < segments {
                offsets[j]
            } else {
                o // after the last segment
            };
            key_points.push(rotate(pts, o));
            originals.push((0..n).map(|i| orig[(i + o) % n]).collect());
        }
        let hints = aligned
            .hints
            .into_iter()
            .map(|h| HintVertex {
                vertex: (h.vertex + n - offsets[h.segment]) % n,
                ..h
            })
            .collect();
        Ok(Sequence {
            n,
            names: keys.iter().map(|k| k.name.clone()).collect(),
            keys: key_points,
            originals,
            tweens,
            offsets,
            hints,
        })
    }

    /// Vertices of every frame and key.
    pub fn vertex_count(&self) -> usize {
        self.n
    }

    /// Number of keys.
    pub fn key_count(&self) -> usize {
        self.keys.len()
    }

    /// The keys' names.
    pub fn key_names(&self) -> &[String] {
        &self.names
    }

    /// Key `j` (from 0) with the sequence's vertex numbering: its original
    /// vertices exactly, and the inserted ones on its edges.
    pub fn key_points(&self, j: usize) -> &[Point] {
        &self.keys[j]
    }

    /// For each vertex of key `j`, the index in the key's input points of
    /// the original vertex it is (`None` for an inserted vertex).
    pub fn original_vertices(&self, j: usize) -> &[Option<usize>] {
        &self.originals[j]
    }

    /// The hints as planned.
    pub fn hints(&self) -> &[HintVertex] {
        &self.hints
    }

    /// The tween of segment `s` (key `s` to key `s + 1`), in its own
    /// vertex numbering (see [`Sequence::frame`] for the sequence's).
    pub fn tween(&self, s: usize) -> &Tween {
        &self.tweens[s]
    }

    /// The pace of each segment ([`Tween::path_length`]).
    pub fn path_lengths(&self) -> Vec<f64> {
        self.tweens.iter().map(Tween::path_length).collect()
    }

    /// The segments' paces laid end to end: where a fraction of a segment
    /// falls on the axis of the whole sequence.
    fn pace(&self) -> Pace {
        let lengths = self.path_lengths();
        let mut starts = Vec::with_capacity(lengths.len());
        let mut total = 0.0;
        for l in &lengths {
            starts.push(total);
            total += l;
        }
        Pace {
            lengths,
            starts,
            total,
        }
    }

    /// The keys of the whole sequence (every segment's
    /// [`Tween::keyframes`], in the sequence's vertex numbering), with `t`
    /// the fraction of the whole sequence's pace, as [`Sequence::frames`]
    /// gives frames' `t`. A key of the sequence is written once, with the
    /// triangulation of the segment that follows it. Times strictly
    /// increase; a segment that does not move adds no key.
    pub fn keyframes(&self) -> Vec<Keyframe> {
        let pace = self.pace();
        let segments = self.tweens.len();
        let mut out: Vec<Keyframe> = Vec::new();
        for (s, tween) in self.tweens.iter().enumerate() {
            let (n, o) = (self.n, self.offsets[s]);
            for (k, key) in tween.keyframes().into_iter().enumerate() {
                let t = pace
                    .time(s, key.t)
                    .unwrap_or((s as f64 + key.t) / segments as f64);
                let key = Keyframe {
                    t,
                    points: (0..n).map(|i| key.points[(i + o) % n]).collect(),
                    triangles: shift_triangles(n, &key.triangles, o),
                };
                match out.last_mut() {
                    // The key between two segments: once, with the
                    // triangulation of the segment after it.
                    Some(last) if k == 0 => {
                        last.triangles = key.triangles;
                    }
                    Some(last) if key.t <= last.t && key.points == last.points => {
                        // A segment that does not move: keep the later
                        // key's triangulation.
                        *last = Keyframe { t: last.t, ..key };
                    }
                    _ => out.push(key),
                }
            }
        }
        if let Some(last) = out.last_mut() {
            last.t = 1.0;
        }
        // Keys that move less than the resolution of t apart.
        crate::morph::strictly_increasing(&mut out);
        out
    }

    /// The time of every frame of `schedule` on the axis of
    /// [`Sequence::keyframes`] (the fraction of the whole pace).
    pub fn frame_times(&self, schedule: &Schedule) -> Vec<f64> {
        let pace = self.pace();
        let segments = pace.lengths.len().max(1);
        schedule
            .samples
            .iter()
            .map(|sample| {
                let s = sample.segment;
                pace.time(s, sample.t)
                    .unwrap_or((s as f64 + sample.t) / segments as f64)
            })
            .collect()
    }

    /// The frame at fraction `t` of segment `s`'s travel, checked exactly,
    /// in the sequence's vertex numbering (`t` = 0 is key `s`, 1 is key
    /// `s + 1`, exactly).
    ///
    /// # Errors
    ///
    /// As [`Tween::frame`].
    pub fn frame(&self, s: usize, t: f64) -> Result<Frame, MorphError> {
        let f = self.tweens[s].frame(t)?;
        Ok(self.relabel(s, f))
    }

    fn relabel(&self, s: usize, f: Frame) -> Frame {
        let (n, o) = (self.n, self.offsets[s]);
        if o == 0 {
            return f;
        }
        Frame {
            t: f.t,
            points: (0..n).map(|i| f.points[(i + o) % n]).collect(),
            triangles: shift_triangles(n, &f.triangles, o),
        }
    }

    /// Places the frames of the whole sequence (module docs).
    ///
    /// # Errors
    ///
    /// [`SequenceError::Timing`] naming the key or setting that cannot be
    /// met.
    pub fn schedule(&self, timing: &Timing) -> Result<Schedule, SequenceError> {
        // The speed at a key is matched on the frames' own steps: the
        // rates over a first guess of the step, then over the steps
        // found, twice.
        let lengths = self.path_lengths();
        let rates = |h: &(dyn Fn(usize) -> f64 + Sync)| -> Vec<(f64, f64)> {
            self.tweens
                .par_iter()
                .enumerate()
                .map(|(j, t)| t.end_rates(h(j)))
                .collect()
        };
        let mut schedule = timing::schedule(
            &lengths,
            &rates(&|_| timing::RATE_WINDOW),
            timing,
            &self.names,
        )?;
        for _ in 0..2 {
            let steps = schedule.steps.clone();
            schedule = timing::schedule(
                &lengths,
                &rates(&|j| 1.0 / steps[j].max(1) as f64),
                timing,
                &self.names,
            )?;
        }
        Ok(schedule)
    }

    /// Every frame of `schedule`, each checked exactly, in parallel. A
    /// frame's `t` is its fraction of the whole sequence's travel.
    ///
    /// # Errors
    ///
    /// As [`Tween::frame`] (a bug), naming the segment.
    pub fn frames(&self, schedule: &Schedule) -> Result<Morph, SequenceError> {
        let pace = self.pace();
        let last = schedule.samples.len().saturating_sub(1).max(1);
        let made: Vec<(Frame, Option<Fallback>)> = schedule
            .samples
            .par_iter()
            .enumerate()
            .map(|(i, sample)| {
                let s = sample.segment;
                let (f, fb) = self.tweens[s]
                    .frame_with_fallback(sample.t)
                    .map_err(|source| SequenceError::Morph { key: s + 1, source })?;
                let mut f = self.relabel(s, f);
                f.t = pace.time(s, sample.t).unwrap_or(i as f64 / last as f64);
                Ok((f, fb))
            })
            .collect::<Result<_, SequenceError>>()?;
        let mut paths: Vec<ThirdVertexPath> = Vec::new();
        let mut fallbacks: Vec<Fallback> = Vec::new();
        for (s, t) in self.tweens.iter().enumerate() {
            for p in &t.report().paths {
                if !paths.contains(p) {
                    paths.push(*p);
                }
            }
            for fb in &t.report().fallbacks {
                fallbacks.push(Fallback::new(
                    &format!("segment {} → {}: {}", s + 1, s + 2, fb.what),
                    &fb.why,
                ));
            }
        }
        let mut frames = Vec::with_capacity(made.len());
        for (f, fb) in made {
            if let Some(fb) = fb {
                if let Some(p) = ThirdVertexPath::ALL
                    .into_iter()
                    .find(|p| fb.what.contains(p.as_str()))
                    && !paths.contains(&p)
                {
                    paths.push(p);
                }
                fallbacks.push(fb);
            }
            frames.push(f);
        }
        Ok(Morph::new(paths, fallbacks, frames))
    }
}

/// The segments of a sequence laid end to end by their paces
/// ([`Sequence::path_lengths`]).
struct Pace {
    /// Each segment's pace.
    lengths: Vec<f64>,
    /// Where each segment starts: the sum of the paces before it.
    starts: Vec<f64>,
    /// The sum of all paces.
    total: f64,
}

impl Pace {
    /// Fraction `t` of segment `s` as a fraction of the whole; `None` when
    /// nothing moves (each caller spreads the times its own way).
    fn time(&self, s: usize, t: f64) -> Option<f64> {
        (self.total > 0.0)
            .then(|| ((self.starts[s] + t * self.lengths[s]) / self.total).clamp(0.0, 1.0))
    }
}
