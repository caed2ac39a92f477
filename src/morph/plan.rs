//! Morphing two curves end to end: equal vertex counts, triangulation,
//! correspondence, then the morph (docs/design.md §5–7).

use crate::correspond::{insert_vertices, resample_arc_length, shift_triangles};
use crate::flip::sequence::crossings_per_shift;
use crate::geom::Point;
use crate::geom::polygon::min_triangle_angle as min_angle;
use crate::immersion::NotSelfOverlapping;
use crate::morph::Fallback;
use crate::morph::{MorphError, MorphOptions, Staged, ThirdVertexPath};
#[cfg(feature = "cli")]
use crate::propagate::paths::HIDE_EXPERIMENTAL;
use crate::quality::{Quality, triangulate_with};
use crate::staged::{Intermediate, Limit, Peak, SideInput};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// How the two curves are brought to the same vertex count. With the `cli`
/// feature it is the command line's `--counts` (each variant's first doc
/// paragraph is its help there).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Counts {
    /// Insert vertices on the longest edges; original vertices stay put.
    ///
    /// The edges of the curve with fewer vertices; its original vertices
    /// stay exactly where they are.
    #[default]
    Insert,
    /// Resample both curves evenly by arc length.
    ///
    /// To the larger count (original vertices move onto the resampled
    /// positions). Where that would make a curve not self-overlapping,
    /// vertices are inserted instead and the report's fallbacks say so.
    Resample,
}

/// Options of a curve morph ([`crate::morph::Tween::new`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct CurveMorphOptions {
    /// Triangulation quality of each curve. Default: [`Quality::Delaunay`].
    pub quality: Quality,
    /// Options of the morph itself. Default: [`MorphOptions::DEFAULT`].
    pub morph: MorphOptions,
    /// How vertex counts are equalised. Default: [`Counts::Insert`].
    pub counts: Counts,
    /// The intermediate of incompatible morphs. Default:
    /// [`Intermediate::Target`].
    pub intermediate: Intermediate,
    /// How vertices are matched. Default: [`Correspondence::Best`] (the
    /// outline and min-flips rules tried, the one whose vertices travel
    /// less kept; measured on `curves/motion-pairs.list`, see
    /// docs/motion.md).
    pub correspondence: Correspondence,
    /// How far the straight segment between two keyframes may stray from
    /// the planned path, as a fraction of the larger end's bounding-box
    /// diagonal (docs/design.md §12): finite, above 0 and at most
    /// 0.1. Default [`KEY_TOLERANCE`] (0.25 %).
    pub key_tolerance: f64,
}

/// The default [`CurveMorphOptions::key_tolerance`]: 0.25 % of the
/// diagonal.
pub const KEY_TOLERANCE: f64 = 0.0025;

/// The largest [`CurveMorphOptions::key_tolerance`] accepted: 10 % of the
/// diagonal.
pub(crate) const MAX_KEY_TOLERANCE: f64 = 0.1;

impl CurveMorphOptions {
    /// The defaults.
    pub const DEFAULT: CurveMorphOptions = CurveMorphOptions {
        quality: Quality::Delaunay,
        morph: MorphOptions::DEFAULT,
        counts: Counts::Insert,
        correspondence: Correspondence::Best,
        intermediate: Intermediate::Target,
        key_tolerance: KEY_TOLERANCE,
    };

    /// Checks the options that are numbers.
    ///
    /// # Errors
    ///
    /// [`CurveMorphError::KeyTolerance`] for a key tolerance that is not
    /// finite, not above 0 or above 0.1.
    pub fn validate(&self) -> Result<(), CurveMorphError> {
        let k = self.key_tolerance;
        if k.is_finite() && k > 0.0 && k <= MAX_KEY_TOLERANCE {
            Ok(())
        } else {
            Err(CurveMorphError::KeyTolerance(k))
        }
    }
}

crate::options::setters! {
    CurveMorphOptions: Default {
        /// Sets the key tolerance (a fraction of the diagonal; checked when the
        /// morph is planned).
        fn with_key_tolerance(key_tolerance: f64);
        /// Sets the triangulation quality.
        fn with_quality(quality: Quality);
        /// Sets the morph options.
        fn with_morph(morph: MorphOptions);
        /// Sets the intermediate of incompatible morphs.
        fn with_intermediate(intermediate: Intermediate);
        /// Sets the correspondence rule.
        fn with_correspondence(correspondence: Correspondence);
        /// Sets how vertex counts are equalised.
        fn with_counts(counts: Counts);
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
    /// Both curves are self-overlapping, but inserting vertices on their
    /// edges (to equalise the counts) made one of them not so: rounding put
    /// an inserted vertex on the wrong side of a part thinner than the
    /// coordinates can resolve. Not the user's fault; giving both curves
    /// the same count avoids it.
    #[error(
        "inserting vertices to equalise the counts made a curve not self-overlapping ({reason}): a part of it is thinner than its coordinates can resolve; give both curves the same number of points"
    )]
    Insertion {
        /// What the triangulation found.
        reason: NotSelfOverlapping,
    },
    /// A key tolerance that is not a fraction of the diagonal above 0 and
    /// at most 0.1.
    #[error(
        "key tolerance {0} is not a fraction of the diagonal above 0 and at most 0.1; give e.g. 0.0025 (0.25 %)"
    )]
    KeyTolerance(f64),
    /// The morph failed.
    #[error(transparent)]
    Morph(#[from] MorphError),
}

/// Equalises vertex counts as `counts` says.
pub(crate) fn equal_counts(a: &[Point], b: &[Point], counts: Counts) -> (Vec<Point>, Vec<Point>) {
    let n = a.len().max(b.len());
    match counts {
        Counts::Resample => (resample_arc_length(a, n), resample_arc_length(b, n)),
        Counts::Insert => (
            insert_vertices(a, n - a.len()).0,
            insert_vertices(b, n - b.len()).0,
        ),
    }
}

/// How vertex `i` of the source is matched to a vertex of the target (after
/// equalising counts): a cyclic shift chosen by one of these rules. Every
/// rule is symmetric, so swapping the curves gives the opposite shift. With
/// the `cli` feature it is the command line's `--correspondence`, variants
/// in its order (each variant's first doc paragraph is its help there; the
/// experimental rules are hidden, and refused by
/// [`FromStr`](std::str::FromStr), unless built with the `experimental`
/// feature).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Correspondence {
    /// Match the outlines by arc length up to a rotation and scale; inserted
    /// vertices go where the other curve's are.
    ///
    /// The shift that maps one outline best onto the other (up to a
    /// rotation, scale and translation), with the inserted vertices placed
    /// where the other curve's vertices are (original vertices stay
    /// exact). What the user sees corresponds.
    #[cfg_attr(feature = "cli", value(hide = HIDE_EXPERIMENTAL))]
    Outline,
    /// As outline, with the curves' corners (turns of 60° or more, else rounded
    /// caps: 160° within 3% of the perimeter) matched in order and the arc
    /// between them piece by piece.
    ///
    /// As [`Correspondence::Outline`], piece by piece between corners (a
    /// strip's long and short edges correspond); where the sharp corners
    /// do not match up, the rounded caps (a stretch of at most 3% of the
    /// perimeter turning by 160° or more, else of at most 10%) are matched
    /// instead; the outline rule when neither matches.
    Corners,
    /// The cyclic shift with the fewest edge flips between the triangulations.
    ///
    /// The fewest crossings between the two triangulations; ties go to
    /// the shapes' best geometric match.
    MinFlips,
    /// Match the pivot vertices of the two triangulations (Mukherjee & Gopi
    /// §6.1).
    #[cfg_attr(feature = "cli", value(hide = HIDE_EXPERIMENTAL))]
    Pivot,
    /// The cyclic shift that best matches the shapes themselves.
    ///
    /// The least sum of squared distances between matched vertices after
    /// normalising position and size.
    #[cfg_attr(feature = "cli", value(hide = HIDE_EXPERIMENTAL))]
    Shape,
    /// Vertex 0 matches vertex 0.
    #[cfg_attr(feature = "cli", value(hide = HIDE_EXPERIMENTAL))]
    Identity,
    /// Plan with the outline, min-flips and (when the corners match up) corners
    /// rules; keep the one whose vertices travel less.
    ///
    /// A trial morph per rule (docs/design.md §7b: choose by what the user
    /// sees).
    #[default]
    Best,
}

impl Correspondence {
    /// All rules, in CLI order.
    pub const ALL: [Correspondence; 7] = [
        Correspondence::Outline,
        Correspondence::Corners,
        Correspondence::MinFlips,
        Correspondence::Pivot,
        Correspondence::Shape,
        Correspondence::Identity,
        Correspondence::Best,
    ];

    /// True for the rules offered only with the `experimental` cargo
    /// feature: `outline`, `pivot`, `shape` and `identity`. Each is
    /// dominated on the motion measures of docs/design.md §7c by `best`,
    /// `corners` or `min-flips` (docs/motion-by-option.md); `best` still
    /// plans with the outline rule inside.
    pub fn is_experimental(self) -> bool {
        matches!(
            self,
            Correspondence::Outline
                | Correspondence::Pivot
                | Correspondence::Shape
                | Correspondence::Identity
        )
    }

    /// The rules a user may ask for in this build: `best`, `corners` and
    /// `min-flips`, and the experimental ones with the `experimental`
    /// feature.
    pub fn offered() -> Vec<Correspondence> {
        crate::propagate::paths::offered(&Correspondence::ALL, Correspondence::is_experimental)
    }

    /// The CLI name.
    pub fn as_str(self) -> &'static str {
        match self {
            Correspondence::Identity => "identity",
            Correspondence::Pivot => "pivot",
            Correspondence::MinFlips => "min-flips",
            Correspondence::Shape => "shape",
            Correspondence::Outline => "outline",
            Correspondence::Corners => "corners",
            Correspondence::Best => "best",
        }
    }
}

impl std::str::FromStr for Correspondence {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        crate::propagate::paths::parse_offered(
            "correspondence",
            s,
            &Correspondence::ALL,
            Correspondence::as_str,
            Correspondence::is_experimental,
        )
    }
}

/// Normalised shape-matching cost of every cyclic shift k: Σ |â_i −
/// b̂_{i+k}|², with both curves centred at their vertex mean and scaled
/// to unit RMS radius. O(n²).
pub(crate) fn shape_cost_per_shift(a: &[Point], b: &[Point]) -> Vec<f64> {
    let norm = |p: &[Point]| -> Vec<Point> {
        let c = p.iter().copied().sum::<Point>() / p.len() as f64;
        let r = (p.iter().map(|q| (*q - c).length_squared()).sum::<f64>() / p.len() as f64)
            .sqrt()
            .max(f64::MIN_POSITIVE);
        p.iter().map(|q| (*q - c) / r).collect()
    };
    let (a, b) = (norm(a), norm(b));
    let n = a.len();
    (0..n)
        .map(|k| {
            (0..n)
                .map(|i| (a[i] - b[(i + k) % n]).length_squared())
                .sum()
        })
        .collect()
}

/// Chooses the cyclic shift k (target vertex `i + k` matches source
/// vertex `i`) by `rule` ([`Correspondence::Best`] needs trial morphs,
/// which [`crate::morph::Tween::new`] runs; here it means `MinFlips`).
pub(crate) fn choose_shift(
    a: &[Point],
    b: &[Point],
    ta: &[[u32; 3]],
    tb: &[[u32; 3]],
    rule: Correspondence,
) -> usize {
    let n = a.len();
    match rule {
        Correspondence::Identity => 0,
        Correspondence::Pivot => {
            let spine = |p: &[Point], t: &[[u32; 3]]| {
                crate::tree::DualTree::new(p.len(), t)
                    .map(|tree| tree.spine(p).pivot_vertex as usize)
                    .unwrap_or(0)
            };
            (spine(b, tb) + n - spine(a, ta)) % n
        }
        Correspondence::Outline => crate::correspond::align(a, b).2,
        Correspondence::Corners => crate::correspond::align_corners(a, b)
            .map_or_else(|| crate::correspond::align(a, b).2, |(_, _, k)| k),
        Correspondence::Shape => {
            let geo = shape_cost_per_shift(a, b);
            (0..n)
                .min_by(|&i, &j| {
                    geo[i]
                        .total_cmp(&geo[j])
                        .then(i.min(n - i).cmp(&j.min(n - j)))
                })
                .unwrap_or(0)
        }
        // Without a trial morph, `best` starts from the fewest flips.
        Correspondence::MinFlips | Correspondence::Best => {
            let geo = shape_cost_per_shift(a, b);
            let cross = crossings_per_shift(n, ta, tb);
            (0..n)
                .min_by(|&i, &j| {
                    cross[i]
                        .cmp(&cross[j])
                        .then(geo[i].total_cmp(&geo[j]))
                        .then(i.min(n - i).cmp(&j.min(n - j)))
                })
                .unwrap_or(0)
        }
    }
}

/// What [`crate::morph::Tween::new`] did.
#[derive(Clone, Debug, PartialEq)]
pub struct MorphReport {
    /// Vertices of each curve after equalising counts.
    pub n: usize,
    /// The cyclic shift of the correspondence (target vertex `i + shift`
    /// matches source vertex `i`).
    pub shift: usize,
    /// Flips on the side used.
    pub flips: usize,
    /// Where the source's side reached the target's triangulation: on the
    /// disk route the fraction of the way to the disk (0 when no flip was
    /// needed); on the target route the number of legs toward a target.
    /// NaN when that side was not finished: it failed, or (target route)
    /// it was given up because its vertices travelled farther than the
    /// other side's.
    pub u_star: f64,
    /// The same from the target's side.
    pub v_star: f64,
    /// The side whose path was used.
    pub used: Side,
    /// Local unblocks on the side used (target route).
    pub unblocks: usize,
    /// True when the side used needed the disk (always for the disk
    /// route; a fallback for the target route).
    pub used_disk: bool,
    /// The third-vertex paths of the side used, in order of first use.
    pub paths: Vec<ThirdVertexPath>,
    /// What was done instead of what was asked, and why, in order.
    pub fallbacks: Vec<Fallback>,
    /// Triangles whose third vertex the layout moved by the exact
    /// orientation test (rounding repairs), over every checked sample.
    pub repairs: usize,
}

/// One side of a plan: its staged path, or `None` when it was given up
/// because its vertices travelled farther than a plan already made.
pub(crate) type SideResult = Result<Option<Staged>, MorphError>;

/// Both sides of the morph for one shift, and which one to use.
pub(crate) struct Sides {
    pub(crate) k: usize,
    pub(crate) a: SideResult,
    pub(crate) b: SideResult,
    pub(crate) use_a: bool,
}

impl Sides {
    /// The side to use, when it was finished.
    pub(crate) fn chosen(&self) -> Option<&Staged> {
        let s = if self.use_a { &self.a } else { &self.b };
        s.as_ref().ok().and_then(Option::as_ref)
    }
}

/// The curves after equalising counts and triangulating, with what that
/// took.
pub(crate) struct Prepared {
    pub(crate) a: Vec<Point>,
    pub(crate) b: Vec<Point>,
    pub(crate) ta: Vec<[u32; 3]>,
    pub(crate) tb: Vec<[u32; 3]>,
    /// The shift, when preparing the curves chose it (outline rule).
    pub(crate) shift: Option<usize>,
    pub(crate) fallbacks: Vec<Fallback>,
}

/// The triangulations of the two input curves, computed once and shared by
/// every plan that uses a curve unchanged (the trials of
/// [`Correspondence::Best`] run side by side).
pub(crate) struct Triangulations<'a> {
    a: &'a [Point],
    b: &'a [Point],
    quality: Quality,
    ta: std::sync::OnceLock<Result<Vec<[u32; 3]>, NotSelfOverlapping>>,
    tb: std::sync::OnceLock<Result<Vec<[u32; 3]>, NotSelfOverlapping>>,
}

impl<'a> Triangulations<'a> {
    pub(crate) fn new(a: &'a [Point], b: &'a [Point], quality: Quality) -> Self {
        Triangulations {
            a,
            b,
            quality,
            ta: std::sync::OnceLock::new(),
            tb: std::sync::OnceLock::new(),
        }
    }

    /// The triangulation of `p` (one of the inputs: from the cache).
    fn of(&self, p: &[Point]) -> Result<Vec<[u32; 3]>, NotSelfOverlapping> {
        let compute = |q: &[Point]| triangulate_with(q, self.quality).map(|i| i.triangles);
        if p == self.a {
            self.ta.get_or_init(|| compute(self.a)).clone()
        } else if p == self.b {
            self.tb.get_or_init(|| compute(self.b)).clone()
        } else {
            compute(p)
        }
    }

    /// The input `side` triangulated, naming it in the error.
    fn side(&self, side: Side) -> Result<Vec<[u32; 3]>, CurveMorphError> {
        let p = if side == Side::Source { self.a } else { self.b };
        self.of(p)
            .map_err(|reason| CurveMorphError::NotSelfOverlapping { side, reason })
    }
}

/// Equalises counts (falling back from resampling to insertion when
/// resampling would make a curve not self-overlapping) and triangulates
/// (the two curves side by side).
pub(crate) fn prepare(
    tri: &Triangulations<'_>,
    counts: Counts,
    correspondence: Correspondence,
) -> Result<Prepared, CurveMorphError> {
    let (a, b) = (tri.a, tri.b);
    let mut fallbacks = Vec::new();
    let by_outline = matches!(
        correspondence,
        Correspondence::Outline | Correspondence::Corners
    );
    if counts == Counts::Insert && by_outline {
        let by_corners = (correspondence == Correspondence::Corners)
            .then(|| crate::correspond::align_corners(a, b))
            .flatten();
        if correspondence == Correspondence::Corners && by_corners.is_none() {
            fallbacks.push(Fallback::new(
                "matched the vertices by the outline rule",
                "the two curves' corners do not match up (not the same number of corners turning the same ways, between 2 and 16)",
            ));
        }
        let (pa, pb, k) = by_corners.unwrap_or_else(|| {
            // With equal counts nothing is inserted and the curves
            // themselves are triangulated: that starts beside the
            // alignment.
            let (aligned, ()) = rayon::join(
                || crate::correspond::align(a, b),
                || {
                    if a.len() == b.len() {
                        rayon::join(|| tri.of(a).ok(), || tri.of(b).ok());
                    }
                },
            );
            aligned
        });
        match rayon::join(|| tri.of(&pa), || tri.of(&pb)) {
            (Ok(ta), Ok(tb)) => {
                return Ok(Prepared {
                    a: pa,
                    b: pb,
                    ta,
                    tb,
                    shift: Some(k),
                    fallbacks,
                });
            }
            (Err(reason), _) | (_, Err(reason)) => {
                // Rounding put an inserted vertex on the wrong side of a
                // thin part: split the longest edges instead (below), and
                // say so; the user's curves are only blamed if they are
                // not self-overlapping themselves.
                tri.side(Side::Source)?;
                tri.side(Side::Target)?;
                fallbacks.push(Fallback::new(
                    "split the longest edges instead of inserting vertices where the other curve's are",
                    &format!("the aligned insertion made a curve not self-overlapping ({reason})"),
                ));
            }
        }
    }
    if counts == Counts::Resample {
        let (ra, rb) = equal_counts(a, b, Counts::Resample);
        let (ta, tb) = rayon::join(|| tri.of(&ra), || tri.of(&rb));
        let tried = [
            ta.map_err(|reason| (Side::Source, reason)),
            tb.map_err(|reason| (Side::Target, reason)),
        ];
        match tried {
            [Ok(ta), Ok(tb)] => {
                return Ok(Prepared {
                    a: ra,
                    b: rb,
                    ta,
                    tb,
                    shift: None,
                    fallbacks,
                });
            }
            [Err((side, reason)), _] | [_, Err((side, reason))] => {
                // Is the user's curve itself self-overlapping? Then the
                // resampling did it: insert vertices instead, and say so.
                tri.side(side)?;
                fallbacks.push(Fallback::new(
                    "inserted vertices instead of resampling",
                    &format!(
                        "resampling the {side} curve by arc length made it not self-overlapping ({reason})"
                    ),
                ));
            }
        }
    }
    let (ia, ib) = equal_counts(a, b, Counts::Insert);
    let (ta, tb) = match rayon::join(|| tri.of(&ia), || tri.of(&ib)) {
        (Ok(ta), Ok(tb)) => (ta, tb),
        (Err(reason), _) | (_, Err(reason)) => {
            // Is it the user's curve, or the insertion?
            tri.side(Side::Source)?;
            tri.side(Side::Target)?;
            return Err(CurveMorphError::Insertion { reason });
        }
    };
    let (a, b) = (ia, ib);
    Ok(Prepared {
        a,
        b,
        ta,
        tb,
        shift: None,
        fallbacks,
    })
}

/// Checked samples of the path per bounding-box diagonal of vertex travel
/// at least: a leg's samples are refined until no vertex moves more than
/// 1/32 of the larger input's diagonal between two of them (output
/// frames are checked again at their own parameter).
const SAMPLES_PER_DIAGONAL: f64 = 32.0;

/// Builds both sides for the shift `k` and picks the one to use. On the
/// target route a side is given up once its vertices travel farther than
/// `give_up_past` (a plan already made travels less), and the side that
/// follows in the race once they travel farther than the leading side's
/// finished travel (what is kept does not depend on which finishes
/// first).
pub(crate) fn sides(
    p: &Prepared,
    k: usize,
    options: &CurveMorphOptions,
    give_up_past: f64,
) -> Sides {
    sides_beside(p, k, options, give_up_past, || ()).0
}

/// What both sides of one plan are built from: the curves in each
/// side's labels, the paths and the bounds on angles and steps.
struct SidePair<'p> {
    p: &'p Prepared,
    b_in_a: Vec<Point>,
    tb_in_a: Vec<[u32; 3]>,
    a_in_b: Vec<Point>,
    ta_in_b: Vec<[u32; 3]>,
    options: &'p CurveMorphOptions,
    leg_path: ThirdVertexPath,
    floor: f64,
    max_step: f64,
}

impl<'p> SidePair<'p> {
    /// The sides of `p` at the shift `k` (`b[(i + k) % n]` corresponds to
    /// `a[i]`).
    fn new(p: &'p Prepared, k: usize, options: &'p CurveMorphOptions) -> SidePair<'p> {
        let (a, b, ta, tb) = (&p.a, &p.b, &p.ta, &p.tb);
        let n = a.len();
        let m = &options.morph;
        let diag = crate::geom::polygon::bbox_diagonal;
        SidePair {
            p,
            b_in_a: (0..n).map(|i| b[(i + k) % n]).collect(),
            tb_in_a: shift_triangles(n, tb, k),
            a_in_b: (0..n).map(|j| a[(j + n - k) % n]).collect(),
            ta_in_b: shift_triangles(n, ta, (n - k) % n),
            options,
            leg_path: if m.path.is_guaranteed() {
                m.path
            } else {
                ThirdVertexPath::Hybrid
            },
            floor: 0.25 * min_angle(a, ta).min(min_angle(b, tb)),
            max_step: diag(a).max(diag(b)) / SAMPLES_PER_DIAGONAL,
        }
    }

    /// Whether the side from `a` leads the race: its curve is first by
    /// coordinates.
    fn a_leads(&self) -> bool {
        let lex = crate::geom::polygon::lex_key;
        lex(&self.p.a) <= lex(&self.p.b)
    }

    /// The side from `a` (else from `b`) built under `limit`.
    fn build(&self, from_a: bool, limit: Limit<'_>) -> (SideResult, Peak) {
        let p = self.p;
        let (s, t, o, to) = if from_a {
            (&p.a[..], &p.ta[..], &self.b_in_a[..], &self.tb_in_a[..])
        } else {
            (&p.b[..], &p.tb[..], &self.a_in_b[..], &self.ta_in_b[..])
        };
        let m = &self.options.morph;
        Staged::build(&SideInput {
            s,
            t_start: t,
            other: o,
            t_other: to,
            leg_path: self.leg_path,
            final_path: m.path,
            rivals: m.rivals,
            root: m.root,
            margin: m.fan_margin,
            intermediate: self.options.intermediate,
            floor: self.floor,
            max_step: self.max_step,
            limit,
        })
    }
}

/// What a finished side gives the other side's limit: its travel (the
/// lead's, for the follower), or its reach (the follower's, for the lead):
/// the largest travel at which it went on, at least its travel.
fn finished_at(built: &(SideResult, Peak), reach: bool) -> Option<f64> {
    let (Ok(Some(st)), peak) = built else {
        return None;
    };
    Some(if reach {
        st.mean_travel()
            .max(peak.went_on_walking)
            .max(peak.went_on_last)
    } else {
        st.mean_travel()
    })
}

/// [`sides`], with `beside` run next to them: the leading side and
/// `beside` one after the other on one core and the following side on the
/// other, so that whichever core finishes first takes `beside` over if the
/// other has not started it.
fn sides_beside<R: Send>(
    p: &Prepared,
    k: usize,
    options: &CurveMorphOptions,
    give_up_past: f64,
    beside: impl FnOnce() -> R + Send,
) -> (Sides, R) {
    let pair = SidePair::new(p, k, options);
    // On the target route the sides race, in an order fixed by the
    // curves, so that what is kept never depends on timing (nor on which
    // curve is the source): what is kept is what building the side of the
    // curve first by coordinates (the lead) given up only past
    // `give_up_past`, then the other side (the follower) also given up
    // once it travels farther than the lead's finished travel, would keep.
    // Both are built at once: the follower is given up past the lead's
    // travel once the lead has finished, and the lead once the travel it
    // must at least end with passes the follower's reach, once the
    // follower has finished ([`Limit::reach`]). The disk route picks a side by
    // where it reaches the other triangulation, not by travel: nothing is
    // given up there.
    let racing = options.intermediate == Intermediate::Target;
    let fixed = if racing { give_up_past } else { f64::INFINITY };
    let a_leads = pair.a_leads();
    let lead_done = AtomicU64::new(f64::INFINITY.to_bits());
    let follow_done = AtomicU64::new(f64::INFINITY.to_bits());
    // A side built under `limit`; when it finishes, `done` gets its travel,
    // or with `reach` its reach ([`finished_at`]).
    let side = |from_a: bool, limit: Limit<'_>, done: Option<(&AtomicU64, bool)>| {
        let built = pair.build(from_a, limit);
        if let Some((done, reach)) = done
            && let Some(v) = finished_at(&built, reach)
        {
            done.store(v.to_bits(), Ordering::Relaxed);
        }
        built
    };
    let travel = |s: &SideResult| match s {
        Ok(Some(s)) => s.mean_travel(),
        Ok(None) | Err(_) => f64::INFINITY,
    };
    // The lead first, then the follower, which on one core starts with
    // the lead's travel as its limit; `beside` is taken first by an idle
    // core (on two cores it runs beside the lead, and the follower after
    // whichever ends first).
    let (((lead, lead_peak), (follow, follow_peak)), r) = rayon::join(
        || {
            rayon::join(
                || {
                    let limit = Limit {
                        fixed,
                        rival: None,
                        reach: racing.then_some(&follow_done),
                    };
                    side(a_leads, limit, Some((&lead_done, false)))
                },
                || {
                    let limit = Limit {
                        fixed,
                        rival: racing.then_some(&lead_done),
                        reach: None,
                    };
                    side(!a_leads, limit, Some((&follow_done, true)))
                },
            )
        },
        beside,
    );
    // A side whose travel (or, if it failed, whose travel when it last
    // consulted its limit) passes `limit` is given up.
    let settle = |s: SideResult, peak: Peak, limit: f64| -> SideResult {
        match s {
            Ok(Some(st)) if racing && st.mean_travel() > limit => Ok(None),
            Err(_) if racing && peak.consulted > limit => Ok(None),
            s => s,
        }
    };
    let limit = fixed.min(travel(&lead));
    // The follower decided everything as it would have under `limit` from
    // the start unless it went on past `limit` before the lead finished.
    // Where it first did so on a leg toward an intermediate, it would have
    // been given up there; where on its last leg, that leg's choice could
    // differ, and it is built again under `limit` (rare: only where the
    // follower outran the lead's finish).
    let follow = if !racing {
        follow
    } else if follow_peak.went_on_walking > limit {
        Ok(None)
    } else if follow_peak.went_on_last > limit {
        let (again, peak) = side(!a_leads, Limit::fixed(limit), None);
        settle(again, peak, limit)
    } else {
        settle(follow, follow_peak, limit)
    };
    let lead = settle(lead, lead_peak, fixed.min(travel(&follow)));
    let (side_a, side_b) = if a_leads {
        (lead, follow)
    } else {
        (follow, lead)
    };
    // The disk route compares where each side reaches the other
    // triangulation (Mukherjee & Gopi); the target route compares how far
    // the vertices travel (the detour of docs/design.md §7b). A side that
    // failed or was given up loses.
    let key = |s: &SideResult| match s {
        Ok(Some(s)) => match options.intermediate {
            Intermediate::Disk => s.u_star,
            Intermediate::Target => s.mean_travel(),
        },
        Ok(None) | Err(_) => f64::INFINITY,
    };
    let use_a = match key(&side_a).total_cmp(&key(&side_b)) {
        std::cmp::Ordering::Less => true,
        std::cmp::Ordering::Greater => false,
        std::cmp::Ordering::Equal => a_leads,
    };
    let sides = Sides {
        k,
        a: side_a,
        b: side_b,
        use_a,
    };
    (sides, r)
}

/// A triangle list.
type Triangles = Vec<[u32; 3]>;

/// How many shifts on each side of the chosen one a common triangulation
/// is looked for, by vertex count: each try is a decision DP over both
/// curves (O(n³/64) word operations), so the reach shrinks as n grows, and
/// past the last bound none is tried (the plan keeps the curves' own
/// triangulations).
const COMMON_REACH: [(usize, usize); 1] = [(1500, 1)];

/// A triangulation valid on both curves at once, at the shift `k` or one
/// within the [`COMMON_REACH`] of it (nearest first; `b[(v + shift) % n]`
/// corresponds to `a[v]`): `(shift, triangles of a, triangles of b)`. The
/// curves then morph without a single edge flip (often along a straighter
/// and always along a cheaper way than a flip route). Improved by max–min
/// flips that keep it common unless `quality` is [`Quality::Any`]. Shifts
/// in `tried` (searched already on the same curves) are skipped; the ones
/// searched here are added to it. With `all_at_once` every shift is
/// searched side by side (when the cores have nothing else to do).
fn common_near(
    a: &[Point],
    b: &[Point],
    k: usize,
    quality: Quality,
    tried: &mut Vec<usize>,
    all_at_once: bool,
) -> Option<(usize, Triangles, Triangles)> {
    let n = a.len();
    let (_, reach) = COMMON_REACH.iter().find(|&&(most, _)| n <= most)?;
    let reach = (*reach).min(n / 2);
    // Searched from one curve chosen by coordinates, so that swapping the
    // curves finds the same triangulation at the same pairing.
    let swap = crate::geom::polygon::lex_key(b) < crate::geom::polygon::lex_key(a);
    let (base, other, k) = if swap { (b, a, (n - k) % n) } else { (a, b, k) };
    // A shift from `base` to `other` as one from `a` to `b` (an involution).
    let a_to_b = |s: usize| if swap { (n - s) % n } else { s };
    let shifts: Vec<usize> = std::iter::once(k)
        .chain((1..=reach).flat_map(|d| [(k + d) % n, (k + n - d) % n]))
        .filter(|&s| !tried.contains(&a_to_b(s)))
        .collect();
    if shifts.is_empty() {
        return None;
    }
    // Masks computed once: each shift relabels the other curve's.
    let (base_masks, other_masks) = rayon::join(
        || crate::immersion::CurveMasks::new(base),
        || crate::immersion::CurveMasks::new(other),
    );
    // A common triangulation at `shift` (base's labels), if any.
    let at = |shift: usize| -> Option<Triangles> {
        // other[(v + shift) % n] corresponds to base[v].
        let other_in_base: Vec<Point> = (0..n).map(|i| other[(i + shift) % n]).collect();
        let curves = [base, &other_in_base[..]];
        let masks = vec![base_masks.clone(), other_masks.rotated(shift)];
        crate::immersion::common_triangulation_with(&curves, masks)
    };
    // Nearest first; all at once (side by side) when asked, else one by
    // one until one is found.
    let found = if all_at_once {
        tried.extend(shifts.iter().map(|&s| a_to_b(s)));
        let each: Vec<Option<Triangles>> = shifts.par_iter().map(|&s| at(s)).collect();
        shifts.iter().zip(each).find_map(|(&s, t)| Some((s, t?)))
    } else {
        shifts.iter().find_map(|&s| {
            tried.push(a_to_b(s));
            Some((s, at(s)?))
        })
    };
    let (shift, t) = found?;
    // Improved only at the shift kept.
    let t = match quality {
        Quality::Any => t,
        _ => {
            let other_in_base: Vec<Point> = (0..n).map(|i| other[(i + shift) % n]).collect();
            crate::quality::improve_common(&[base, &other_in_base[..]], t)
        }
    };
    let t_other = shift_triangles(n, &t, (n - shift) % n);
    Some(if swap {
        ((n - shift) % n, t_other, t)
    } else {
        (shift, t, t_other)
    })
}

/// The curves prepared and both sides planned as the options ask: one
/// rule's shift, or for [`Correspondence::Best`] the trial morphs of the
/// outline and min-flips rules. Each rule is planned with the curves'
/// own triangulations and, where the curves have one near the rule's
/// shift, with a common triangulation (no flips); of all these the plan
/// whose vertices travel less is kept (the detour of docs/design.md §7b,
/// whose denominator they share).
///
/// The first rule's plan on the curves' own triangulations is made in
/// full; the others are made side by side after it, each side given up
/// as soon as its vertices travel farther than that plan's (it could not
/// be kept), which saves most of the work of a losing plan.
pub(crate) fn plan(
    a: &[Point],
    b: &[Point],
    options: &CurveMorphOptions,
) -> Result<(Prepared, Sides), CurveMorphError> {
    let tri = Triangulations::new(a, b, options.quality);
    type Planned = (Prepared, Sides);
    let rules: &[Correspondence] = if options.correspondence == Correspondence::Best {
        // The corners rule only where it differs from the outline rule.
        if crate::correspond::align_corners(a, b).is_some() {
            // Corners first: where the corners match, its plan usually
            // travels least (the order only decides how early the other
            // plans are given up, and exact ties).
            &[
                Correspondence::Corners,
                Correspondence::Outline,
                Correspondence::MinFlips,
            ]
        } else {
            &[Correspondence::Outline, Correspondence::MinFlips]
        }
    } else {
        std::slice::from_ref(&options.correspondence)
    };
    // A rule's curves and shift.
    let prepared = |rule: Correspondence| -> Result<(Prepared, usize), CurveMorphError> {
        let p = prepare(&tri, options.counts, rule)?;
        let k = match p.shift {
            Some(k) => k,
            None => choose_shift(&p.a, &p.b, &p.ta, &p.tb, rule),
        };
        Ok((p, k))
    };
    // The same curves with a common triangulation near the shift `k`
    // (skipping the shifts `tried` on them).
    let common = |p: &Prepared,
                  k: usize,
                  tried: &mut Vec<usize>,
                  all_at_once: bool|
     -> Option<(Prepared, usize)> {
        let (shift, ta, tb) = common_near(&p.a, &p.b, k, options.quality, tried, all_at_once)?;
        let q = Prepared {
            a: p.a.clone(),
            b: p.b.clone(),
            ta,
            tb,
            shift: Some(shift),
            fallbacks: p.fallbacks.clone(),
        };
        Some((q, shift))
    };
    let (p0, k0) = prepared(rules[0])?;
    let mut tried = Vec::new();
    // A common triangulation near the first rule's shift, when there is
    // one, leads: it needs no flip, so its plan is cheap and usually
    // travels least, and the plans after it are then given up early.
    let (lead, lead_k, own0) = match common(&p0, k0, &mut tried, true) {
        Some((q, shift)) => (q, shift, Some((p0, k0))),
        None => (p0, k0, None),
    };
    let (a0, b0) = (&lead.a, &lead.b);
    // The lead plan in full; beside it, the other candidates are set up
    // (shifts, common triangulations), in a fixed order.
    let (first, others) = sides_beside(
        &lead,
        lead_k,
        options,
        f64::INFINITY,
        move || -> Result<Vec<(Prepared, usize)>, CurveMorphError> {
            let mut v: Vec<(Prepared, usize)> = own0.into_iter().collect();
            for &rule in &rules[1..] {
                let (p, k) = prepared(rule)?;
                if (&p.a, &p.b) != (a0, b0) {
                    tried.clear();
                }
                let c = common(&p, k, &mut tried, false);
                v.push((p, k));
                v.extend(c);
            }
            Ok(v)
        },
    );
    let travel = |s: &Sides| s.chosen().map_or(f64::INFINITY, Staged::mean_travel);
    let bound = travel(&first);
    let others: Vec<Planned> = others?
        .into_par_iter()
        .map(|(p, k)| {
            let s = sides(&p, k, options, bound);
            (p, s)
        })
        .collect();
    // The first plan that travels least.
    let best = others
        .into_iter()
        .fold((bound, (lead, first)), |best, candidate| {
            let t = travel(&candidate.1);
            if t < best.0 { (t, candidate) } else { best }
        });
    Ok(best.1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::propagate::compatible::same_bits;

    /// The benchmark's spiral ↔ blob pair: a spiral strip of `n` vertices
    /// wound `turns` times (it overlaps itself) and a star-shaped blob.
    fn spiral_blob(n: usize, turns: f64) -> (Vec<Point>, Vec<Point>) {
        let spiral = testkit::shapes::spiral_strip(n / 2, turns, 0.3).0;
        (spiral, testkit::shapes::star_blob(n))
    }

    /// Calls `f` with a label and the two sides of each rule's plan of
    /// the spiral ↔ blob pair at each (vertices, turns) of `sizes`.
    fn for_each_side_pair(sizes: &[(usize, f64)], mut f: impl FnMut(&str, &SidePair<'_>)) {
        let options = CurveMorphOptions::DEFAULT;
        for &(n, turns) in sizes {
            let (a, b) = spiral_blob(n, turns);
            let tri = Triangulations::new(&a, &b, options.quality);
            for rule in [Correspondence::Outline, Correspondence::MinFlips] {
                let p = prepare(&tri, options.counts, rule).expect("the pair prepares");
                let k = p
                    .shift
                    .unwrap_or_else(|| choose_shift(&p.a, &p.b, &p.ta, &p.tb, rule));
                f(
                    &format!("n = {n}, {rule:?}, shift {k}"),
                    &SidePair::new(&p, k, &options),
                );
            }
        }
    }

    /// Asserts that two built sides are the same plan bit for bit: travel,
    /// legs, paths and keys.
    fn assert_same_plan(x: &Staged, y: &Staged, label: &str) {
        assert_eq!(
            x.mean_travel().to_bits(),
            y.mean_travel().to_bits(),
            "{label}"
        );
        assert_eq!(x.legs.len(), y.legs.len(), "{label}");
        for (l, m) in x.legs.iter().zip(&y.legs) {
            assert_eq!(l.path, m.path, "{label}");
            assert_eq!(l.keys.len(), m.keys.len(), "{label}");
            for (p, q) in l.keys.iter().zip(&m.keys) {
                assert!(same_bits(p, q), "{label}: a key differs");
            }
        }
    }

    /// The follower as it is built beside a lead not yet done.
    fn follower_beside_a_running_lead(pair: &SidePair<'_>, from_a: bool) -> (SideResult, Peak) {
        let lead_not_done = AtomicU64::new(f64::INFINITY.to_bits());
        pair.build(
            from_a,
            Limit {
                fixed: f64::INFINITY,
                rival: Some(&lead_not_done),
                reach: None,
            },
        )
    }

    /// The lead is given up by the follower's reach R only where building
    /// it alone keeps the same (docs/design.md §7, the race of a plan's
    /// two sides): alone it then travels farther than R, or is given up
    /// or fails; where R does not give it up, it is built bit for bit as
    /// alone. Each rule's plan of each pair is checked with R the reach
    /// of the follower built first, as when it finishes before the lead.
    #[test]
    fn the_lead_is_given_up_by_the_followers_reach_only_where_it_would_lose() {
        let (mut given_up, mut kept) = (0, 0);
        for_each_side_pair(&[(160, 1.5), (240, 2.0), (320, 2.0)], |label, pair| {
            let a_leads = pair.a_leads();
            let follower = follower_beside_a_running_lead(pair, !a_leads);
            let Some(reach) = finished_at(&follower, true) else {
                return;
            };
            let alone = pair.build(a_leads, Limit::fixed(f64::INFINITY)).0;
            let follow_reach = AtomicU64::new(reach.to_bits());
            let raced = pair
                .build(
                    a_leads,
                    Limit {
                        fixed: f64::INFINITY,
                        rival: None,
                        reach: Some(&follow_reach),
                    },
                )
                .0;
            match (&raced, &alone) {
                (Ok(None), Ok(Some(st))) => {
                    given_up += 1;
                    assert!(
                        st.mean_travel() > reach,
                        "{label}: given up past reach {reach}, but alone it travels {}",
                        st.mean_travel()
                    );
                }
                (Ok(None), _) => given_up += 1,
                (Ok(Some(r)), Ok(Some(st))) => {
                    kept += 1;
                    assert_same_plan(r, st, label);
                }
                _ => panic!(
                    "{label}: raced {:?}, alone {:?}",
                    raced.is_ok(),
                    alone.is_ok()
                ),
            }
        });
        // Both outcomes are exercised.
        assert!(given_up > 0 && kept > 0, "given up {given_up}, kept {kept}");
    }

    /// The follower's reach is a limit under which it is built the same
    /// (docs/design.md §7, the race of a plan's two sides): built under
    /// any limit from its reach up, it keeps the same plan bit for bit as
    /// it did beside a lead not yet done. Limits between the reach and the
    /// largest travel at which it consulted its limit are tried, so that
    /// what its peak leaves out of the reach (the first path of a last leg
    /// that the second beat, `staged::Excuse`) is put to the test.
    #[test]
    fn the_follower_is_built_the_same_under_any_limit_from_its_reach() {
        let (mut checked, mut above) = (0, 0);
        let sizes = [(160, 1.5), (240, 2.0), (320, 2.0), (400, 2.0)];
        for_each_side_pair(&sizes, |label, pair| {
            for from_a in [true, false] {
                let follower = follower_beside_a_running_lead(pair, from_a);
                let Some(reach) = finished_at(&follower, true) else {
                    continue;
                };
                let (Ok(Some(kept)), peak) = &follower else {
                    unreachable!("a side with a reach finished");
                };
                let mut limits = vec![reach];
                if peak.consulted > reach {
                    above += 1;
                    limits.push(0.5 * (reach + peak.consulted));
                }
                for limit in limits {
                    let label = format!("{label}, from a: {from_a}, limit {limit}");
                    let (Ok(Some(again)), _) = pair.build(from_a, Limit::fixed(limit)) else {
                        panic!("{label}: not kept under its reach {reach}");
                    };
                    checked += 1;
                    assert_same_plan(&again, kept, &label);
                }
            }
        });
        // Some followers consulted their limit above their reach.
        assert!(checked > 0 && above > 0, "checked {checked}, above {above}");
    }
}
