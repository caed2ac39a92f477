//! Morphing two curves end to end: equal vertex counts, triangulation,
//! correspondence, then the morph (DESIGN.md §5–7).

use super::{MorphError, MorphOptions, morph_with};
use crate::correspond::{
    compatible_shift, degree_sequence, insert_vertices, resample_arc_length, shift_triangles,
};
use crate::frames::Morph;
use crate::geom::Point;
use crate::immersion::{Immersion, NotSelfOverlapping, check};
use crate::quality::{Quality, triangulate_with};

/// How the two curves are brought to the same vertex count.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Counts {
    /// Insert vertices on the longest edges of the curve with fewer
    /// vertices; original vertices stay exactly where they are.
    #[default]
    Insert,
    /// Resample both curves evenly by arc length to the larger count
    /// (original vertices move onto the resampled positions).
    Resample,
}

/// Options of [`morph_curves`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct CurveMorphOptions {
    /// Triangulation quality of each curve. Default: [`Quality::Delaunay`].
    pub quality: Quality,
    /// Options of the morph itself. Default: [`MorphOptions::DEFAULT`].
    pub morph: MorphOptions,
    /// How vertex counts are equalised. Default: [`Counts::Insert`].
    pub counts: Counts,
}

impl CurveMorphOptions {
    /// The defaults.
    pub const DEFAULT: CurveMorphOptions = CurveMorphOptions {
        quality: Quality::Delaunay,
        morph: MorphOptions::DEFAULT,
        counts: Counts::Insert,
    };

    /// Sets the triangulation quality.
    pub fn with_quality(mut self, quality: Quality) -> Self {
        self.quality = quality;
        self
    }

    /// Sets the morph options.
    pub fn with_morph(mut self, morph: MorphOptions) -> Self {
        self.morph = morph;
        self
    }

    /// Sets how vertex counts are equalised.
    pub fn with_counts(mut self, counts: Counts) -> Self {
        self.counts = counts;
        self
    }
}

impl Default for CurveMorphOptions {
    fn default() -> Self {
        CurveMorphOptions::DEFAULT
    }
}

/// Which input a message is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// The source curve (the first).
    Source,
    /// The target curve (the second).
    Target,
}

impl std::fmt::Display for Side {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Side::Source => "source",
            Side::Target => "target",
        })
    }
}

/// Why two curves could not be morphed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CurveMorphError {
    /// One curve does not bound an immersed disk (a negative answer).
    #[error("the {side} curve is not self-overlapping: {reason}")]
    NotSelfOverlapping {
        /// Which curve.
        side: Side,
        /// Why.
        reason: NotSelfOverlapping,
    },
    /// No common triangulation was found (a negative answer).
    #[error(
        "the triangulations of the two curves are incompatible (no cyclic shift matches their degree sequences, and neither triangulation is valid on the other curve)"
    )]
    Incompatible,
    /// The morph failed.
    #[error(transparent)]
    Morph(#[from] MorphError),
}

/// Two curves with equal vertex counts, a correspondence and a common
/// triangulation.
#[derive(Clone, Debug, PartialEq)]
pub struct Prepared {
    /// The source polygon (with any inserted vertices).
    pub source: Vec<Point>,
    /// The target polygon, cyclically shifted so that vertex `i`
    /// corresponds to source vertex `i`.
    pub target: Vec<Point>,
    /// The shift: target vertex `i` is the target curve's vertex
    /// `(i + shift) % n` after equalising counts.
    pub shift: usize,
    /// The triangulation valid on both.
    pub triangles: Vec<[u32; 3]>,
}

/// Equalises vertex counts as `counts` says.
pub fn equal_counts(a: &[Point], b: &[Point], counts: Counts) -> (Vec<Point>, Vec<Point>) {
    let n = a.len().max(b.len());
    match counts {
        Counts::Resample => (resample_arc_length(a, n), resample_arc_length(b, n)),
        Counts::Insert => (
            insert_vertices(a, n - a.len()).0,
            insert_vertices(b, n - b.len()).0,
        ),
    }
}

/// Triangulates one curve, naming it in the error.
///
/// # Errors
///
/// [`CurveMorphError::NotSelfOverlapping`].
pub fn triangulate_side(
    points: &[Point],
    quality: Quality,
    side: Side,
) -> Result<Immersion, CurveMorphError> {
    triangulate_with(points, quality)
        .map_err(|reason| CurveMorphError::NotSelfOverlapping { side, reason })
}

/// Finds a common triangulation of two curves with equal vertex counts:
/// first a cyclic shift under which the two triangulations' degree
/// sequences agree (then they are the same triangulation), else either
/// triangulation if it is valid on the other curve as it stands.
///
/// # Errors
///
/// [`CurveMorphError::NotSelfOverlapping`] or
/// [`CurveMorphError::Incompatible`].
pub fn prepare_compatible(
    a: &[Point],
    b: &[Point],
    quality: Quality,
) -> Result<Prepared, CurveMorphError> {
    let ia = triangulate_side(a, quality, Side::Source)?;
    let ib = triangulate_side(b, quality, Side::Target)?;
    let n = a.len();
    let (da, db) = (
        degree_sequence(n, &ia.triangles),
        degree_sequence(n, &ib.triangles),
    );
    let shifted = |k: usize| -> Vec<Point> { (0..n).map(|i| b[(i + k) % n]).collect() };
    if let Some(k) = compatible_shift(&da, &db) {
        let target = shifted(k);
        let mut t2 = shift_triangles(n, &ib.triangles, k);
        t2.sort_unstable();
        let mut t1 = ia.triangles.clone();
        t1.sort_unstable();
        if t1 == t2 && check(&target, &t1).is_ok() {
            return Ok(Prepared {
                source: a.to_vec(),
                target,
                shift: k,
                triangles: ia.triangles,
            });
        }
    }
    for tris in [&ia.triangles, &ib.triangles] {
        if check(a, tris).is_ok() && check(b, tris).is_ok() {
            return Ok(Prepared {
                source: a.to_vec(),
                target: b.to_vec(),
                shift: 0,
                triangles: tris.clone(),
            });
        }
    }
    Err(CurveMorphError::Incompatible)
}

/// Morphs curve `a` into curve `b` (both oriented, turning number +1),
/// one frame per value of `times`; every frame passes the exact immersion
/// check.
///
/// # Errors
///
/// [`CurveMorphError`]: a curve is not self-overlapping, no common
/// triangulation was found, or the morph failed.
pub fn morph_curves(
    a: &[Point],
    b: &[Point],
    times: &[f64],
    options: &CurveMorphOptions,
) -> Result<(Prepared, Morph), CurveMorphError> {
    let (a, b) = equal_counts(a, b, options.counts);
    let prepared = prepare_compatible(&a, &b, options.quality)?;
    let plan = super::Compatible::new(
        &prepared.source,
        &prepared.target,
        &prepared.triangles,
        options.morph.root,
        options.morph.fan_margin,
    )
    .map_err(MorphError::from)?;
    let morph = morph_with(&plan, times, options.morph.path)?;
    Ok((prepared, morph))
}
