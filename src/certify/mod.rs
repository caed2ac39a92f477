//! Certified keyframes: decide exactly whether the straight-line motion
//! between two shapes stays an immersed disk for every s in [0, 1].
//!
//! Players (Lottie, SVG SMIL, CSS, game engines) move every vertex on a
//! straight line between stored shapes, `p(s) = P + s(Q − P)`. With the
//! triangulation fixed (an n-gon triangulated by diagonals on its own
//! vertices, as [`crate::triangulate`] makes them), the motion is valid for
//! every s exactly when (docs/design.md §13):
//!
//! 1. the triangulation is valid at s = 0 ([`crate::immersion::check`]);
//! 2. **triangles:** each doubled signed area, a quadratic
//!    `A s² + B s + C` with exact rational coefficients, stays positive on
//!    [0, 1]: `C > 0`, `A + B + C > 0`, and where `A > 0` and the vertex
//!    `−B/2A` lies in (0, 1), `4AC − B² > 0`;
//! 3. **fans:** at each vertex v, with `a = p(v+1) − p(v)` and
//!    `b = p(v−1) − p(v)`, the fan angle (the sum of its triangles' angles,
//!    continuous while they stay counter-clockwise) reaches 2π only where
//!    a and b point the same way. So at every root r ∈ [0, 1] of the
//!    quadratic `cross(a, b)`, `dot(a, b) ≤ 0` must hold; where
//!    `cross ≡ 0` (neighbours collinear, as at a vertex inserted on an
//!    edge) `dot ≤ 0` must hold on all of [0, 1]. Roots are
//!    `(−c₁ ± √D)/(2c₂)`: the sign of `dot` there is that of `X + Y√D`
//!    with integers X, Y, D, decided without a square root.
//!
//! All three are necessary too: a triangle whose area reaches 0, or a fan
//! whose edges align (the angle is then a positive multiple of 2π), is an
//! invalid shape under this triangulation at that s.
//!
//! **Cost.** O(n) per segment. A floating-point filter with a proven error
//! bound (`filter`) decides nearly every triangle and fan; only what it
//! cannot decide is recomputed in big-integer arithmetic (`exact`): `f64`
//! coordinates are dyadic rationals, scaled by a common power of two into
//! integers. No epsilon decides anything.
//!
//! **Players' arithmetic** ([`Player`]). A player evaluates `p(s)` in
//! floating point, so it draws each vertex up to δ_v from the exact point
//! (per coordinate; `δ_v = 8 u m_v`, u the player's unit roundoff and m_v
//! the largest coordinate magnitude of v at either end; the derivation is
//! in docs/design.md §13). The certificate then holds with margins: each
//! doubled area stays above the most that moving its corners by δ can
//! change it, `M = (δ_a + δ_c)L₁ + (δ_a + δ_b)L₂ + 2(δ_a + δ_b)(δ_a + δ_c)`
//! (L the larger 1-norm of an edge at the two ends, which bounds it on the
//! whole segment since the norm is convex in s); and where
//! `|cross(a, b)| ≤ K` (the same bound for the fan's two edges),
//! `dot(a, b) + K ≤ 0`. Every shape the player can draw is then valid.
//! Where a triangle or fan fails only with the margin, the test is
//! repeated on pieces of the span with L taken at each piece's ends (an
//! edge that shrinks inside the segment has a far smaller norm there).
//!
//! **Failure report.** A failing segment names the triangle that turns
//! over or the fan that wraps, and where: an s given exactly when it is
//! rational and always as a bracket of two adjacent doubles (or, for a
//! margin failure of a fan, an interval holding the first failing s). The
//! motion is certified on `[0, lo)` of the earliest failure, so a caller
//! can split the segment there.
//!
//! # Examples
//!
//! ```
//! use immerse::certify::{certify_segment, Player};
//! use immerse::Point;
//! let square = [Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(1.0, 1.0), Point::new(0.0, 1.0)];
//! let moved: Vec<Point> = square.iter().map(|p| *p * 2.0 + Point::new(3.0, 0.0)).collect();
//! let tris = [[0, 1, 2], [0, 2, 3]];
//! assert!(certify_segment(&square, &moved, &tris, Player::Exact)?.is_certified());
//! // Turned by 180° in one straight segment: every vertex passes the centre.
//! let turned: Vec<Point> = square.iter().map(|p| Point::new(1.0, 1.0) - *p).collect();
//! let report = certify_segment(&square, &turned, &tris, Player::Exact)?;
//! let failure = report.failure.expect("not certified");
//! assert_eq!(failure.at.exact.as_deref(), Some("1/2"));
//! # Ok::<(), immerse::certify::CertifyError>(())
//! ```

mod animation;
pub(crate) mod exact;
mod filter;
mod motion;
mod read;
mod repair;

use std::cmp::Ordering;
use std::fmt;

pub use animation::{
    AnimationReport, Answer, FailureReport, PathOutcome, SegmentOutcome, certify_animation,
};
pub use motion::{MotionOptions, MotionReport, Piece, Source, Verdict, certify_motion};
pub use read::{
    AnimatedPath, Animation, Format, MAX_ANIMATION_BYTES, Play, ReadError, ReadKey, read_animation,
};

use exact::{Alg, Quad, Scaled, fan_ok, first_nonpositive, positive_on};
use num_bigint::BigInt;
use rayon::prelude::*;
pub use repair::certified_triangulation;
pub(crate) use repair::flip_to_certify;

use crate::geom::Point;
use crate::immersion::{CheckedTriangles, ImmersionDefect, check, check_structure};

/// The arithmetic a player interpolates with; sets the certificate's margin
/// (module docs). With the `cli` feature it is the command line's
/// `--player` (each variant's first doc paragraph is its help there).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Player {
    /// The coordinates as written, interpolated exactly: no margin.
    Exact,
    /// Interpolation in double precision (browsers' SVG and CSS).
    ///
    /// `f64`: browsers' SMIL and CSS, most desktop players.
    F64,
    /// Interpolation in single precision (native Lottie players, GPUs).
    ///
    /// `f32`, also in game engines; coordinates are read into `f32` first.
    F32,
}

impl Player {
    /// Every player, weakest margin first.
    pub const ALL: [Player; 3] = [Player::Exact, Player::F64, Player::F32];

    /// The name used on the command line and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            Player::Exact => "exact",
            Player::F64 => "f64",
            Player::F32 => "f32",
        }
    }

    /// log₂ of 8u: δ_v = 2^shift · m_v exactly.
    fn shift(self) -> Option<i32> {
        match self {
            Player::Exact => None,
            Player::F64 => Some(-50),
            Player::F32 => Some(-21),
        }
    }

    /// The per-coordinate displacement bound δ = 8 u m of a vertex whose
    /// largest coordinate magnitude (at either end of the segment) is
    /// `magnitude` (docs/design.md §13).
    pub fn delta(self, magnitude: f64) -> f64 {
        self.shift().map_or(0.0, |k| magnitude.abs() * 2f64.powi(k))
    }
}

impl fmt::Display for Player {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A value of the segment parameter s, exactly or by a bracket.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SParam {
    /// A double at or below the value.
    pub lo: f64,
    /// A double at or above the value (equal to `lo` when the value is
    /// that double).
    pub hi: f64,
    /// The value as a fraction `p/q` in lowest terms, when it is rational
    /// and known exactly.
    pub exact: Option<String>,
}

impl SParam {
    fn point(x: f64) -> Self {
        SParam {
            lo: x,
            hi: x,
            exact: Some(exact::Alg::from_f64(x).as_fraction().unwrap_or_default()),
        }
    }
}

impl fmt::Display for SParam {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.exact {
            Some(_) if self.lo == self.hi => write!(f, "s = {}", self.lo),
            Some(x) => write!(f, "s = {x} ≈ {}", self.lo),
            None if exact::next_up(self.lo) >= self.hi => write!(f, "s ≈ {}", self.lo),
            None => write!(f, "s in [{}, {}]", self.lo, self.hi),
        }
    }
}

/// What fails in a segment.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Defect {
    /// The triangulation is not an immersion triangulation of the shape
    /// where the span starts.
    Start(ImmersionDefect),
    /// This triangle turns over: its signed area reaches zero.
    Triangle {
        /// Its position in the triangle list.
        index: usize,
        /// Its corners.
        corners: [u32; 3],
    },
    /// The fan at this vertex reaches a full turn: its first and last
    /// edges point the same way.
    Fan {
        /// The vertex.
        vertex: usize,
    },
}

impl fmt::Display for Defect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Defect::Start(d) => write!(
                f,
                "the triangulation is not valid where the segment starts ({d})"
            ),
            Defect::Triangle {
                corners: [a, b, c], ..
            } => {
                write!(f, "triangle ({a}, {b}, {c}) turns over")
            }
            Defect::Fan { vertex } => write!(f, "the fan at vertex {vertex} wraps (a full turn)"),
        }
    }
}

/// Where and why a segment is not certified.
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    /// What fails.
    pub defect: Defect,
    /// Where: the first s at which it fails. The motion is certified for
    /// every s below `at.lo`.
    pub at: SParam,
    /// True when the exact motion keeps this triangle or fan valid and
    /// only the player's margin fails: the player's rounding could turn it
    /// over (or wrap it), the exact motion does not.
    pub within_margin: bool,
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (&self.defect, self.within_margin) {
            (
                Defect::Triangle {
                    corners: [a, b, c], ..
                },
                true,
            ) => write!(
                f,
                "triangle ({a}, {b}, {c}) comes within the player's rounding of turning over at {}",
                self.at
            ),
            (Defect::Fan { vertex }, true) => write!(
                f,
                "the fan at vertex {vertex} comes within the player's rounding of a full turn at {}",
                self.at
            ),
            (d, _) => write!(f, "{d} at {}", self.at),
        }
    }
}

/// The certificate of one segment (or span of one).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct SegmentReport {
    /// The earliest failure; `None` when the segment is certified.
    pub failure: Option<Failure>,
    /// Triangles that fail somewhere in the span.
    pub failing_triangles: usize,
    /// Fans that fail somewhere in the span.
    pub failing_fans: usize,
    /// Triangles the floating-point filter left to exact arithmetic.
    pub exact_triangles: usize,
    /// Fans the floating-point filter left to exact arithmetic.
    pub exact_fans: usize,
}

impl SegmentReport {
    /// True when every s of the span is certified.
    pub fn is_certified(&self) -> bool {
        self.failure.is_none()
    }
}

/// Input that cannot be certified at all (not a negative answer).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CertifyError {
    /// The two ends have different numbers of points.
    #[error(
        "the two shapes have {start} and {end} points; a straight-line motion needs the same number"
    )]
    CountMismatch {
        /// Points at the start.
        start: usize,
        /// Points at the end.
        end: usize,
    },
    /// Fewer than 3 points.
    #[error("a shape needs at least 3 points, found {0}")]
    TooFewPoints(usize),
    /// A coordinate is NaN or infinite.
    #[error("point {point} {} has a coordinate that is not a finite number", if *at_end { "at the end" } else { "at the start" })]
    NotFinite {
        /// The point.
        point: usize,
        /// True for the end shape.
        at_end: bool,
    },
    /// The span is not `0 ≤ s0 ≤ s1 ≤ 1`.
    #[error("the span [{s0}, {s1}] is not inside [0, 1] in increasing order")]
    BadSpan {
        /// Its start.
        s0: f64,
        /// Its end.
        s1: f64,
    },
    /// Key times are not finite and strictly increasing.
    #[error("key {key} has time {t}, not finite and after the key before it")]
    KeyTime {
        /// The key.
        key: usize,
        /// Its time.
        t: f64,
    },
    /// No keys.
    #[error("no keys to certify")]
    NoKeys,
    /// A key's points or triangles cannot be certified.
    #[error("key {key}: {source}")]
    InKey {
        /// The key.
        key: usize,
        /// Why.
        source: Box<CertifyError>,
    },
}

/// Checks the two ends and the span.
fn check_input(start: &[Point], end: &[Point], s0: f64, s1: f64) -> Result<(), CertifyError> {
    if start.len() != end.len() {
        return Err(CertifyError::CountMismatch {
            start: start.len(),
            end: end.len(),
        });
    }
    if start.len() < 3 {
        return Err(CertifyError::TooFewPoints(start.len()));
    }
    for (at_end, pts) in [(false, start), (true, end)] {
        if let Some(point) = pts.iter().position(|p| !p.is_finite()) {
            return Err(CertifyError::NotFinite { point, at_end });
        }
    }
    if !(0.0 <= s0 && s0 <= s1 && s1 <= 1.0) {
        return Err(CertifyError::BadSpan { s0, s1 });
    }
    Ok(())
}

/// Certify the straight-line motion from `start` to `end` under the fixed
/// `triangles`, for every s in [0, 1], against `player`'s arithmetic.
///
/// The answer is exact (module docs). A triangulation that is not an
/// immersion triangulation of `start` is a failure at s = 0
/// ([`Defect::Start`]).
///
/// # Errors
///
/// [`CertifyError`] when the input cannot be a motion: different point
/// counts, fewer than 3 points, a coordinate that is not finite.
pub fn certify_segment(
    start: &[Point],
    end: &[Point],
    triangles: &[[u32; 3]],
    player: Player,
) -> Result<SegmentReport, CertifyError> {
    certify_span(start, end, triangles, 0.0, 1.0, player)
}

/// Whether [`certify_segment`] certifies the motion: the same answer,
/// reached sooner where it is no. Every triangle and fan is first taken
/// without the pieces that a margin failure calls for, so a triangle that
/// the exact motion turns over answers at once; the pieces are tried
/// last, on those that fail only with the player's margin. False also
/// for input [`certify_segment`] refuses. The triangulation's structure
/// is checked once, by the caller ([`CheckedTriangles`]), however many
/// segments are certified under it.
pub(crate) fn segment_holds(
    start: &[Point],
    end: &[Point],
    triangles: &CheckedTriangles<'_>,
    player: Player,
) -> bool {
    if check_input(start, end, 0.0, 1.0).is_err() || triangles.check(start).is_err() {
        return false;
    }
    let span = Span::new(start, end, 0.0, 1.0, player);
    let mut later_triangles = Vec::new();
    for &[a, b, c] in triangles.triangles() {
        let corners = [a as usize, b as usize, c as usize];
        match span.triangle_whole(corners) {
            Holds::Filtered | Holds::Exactly => {}
            Holds::No(_, true) => later_triangles.push(corners),
            Holds::No(_, false) => return false,
        }
    }
    let mut later_fans = Vec::new();
    for v in 0..start.len() {
        match span.fan_whole(v, &mut 0) {
            None => {}
            Some((_, true)) => later_fans.push(v),
            Some((_, false)) => return false,
        }
    }
    later_triangles
        .into_iter()
        .all(|c| span.triangle_in_pieces(c))
        && later_fans.into_iter().all(|v| span.fan_in_pieces(v))
}

/// [`certify_segment`] for the part `s0 ≤ s ≤ s1` of the motion only: the
/// triangulation must be valid at the exact shape `p(s0)` (a rational
/// shape, decided exactly) and stay valid up to `p(s1)`.
///
/// # Errors
///
/// As [`certify_segment`], and [`CertifyError::BadSpan`] unless
/// `0 ≤ s0 ≤ s1 ≤ 1`.
pub fn certify_span(
    start: &[Point],
    end: &[Point],
    triangles: &[[u32; 3]],
    s0: f64,
    s1: f64,
    player: Player,
) -> Result<SegmentReport, CertifyError> {
    check_input(start, end, s0, s1)?;
    let n = start.len();
    let at_start = if s0 == 0.0 {
        check(start, triangles)
    } else {
        valid_at_unchecked(start, end, triangles, s0)
    };
    if let Err(defect) = at_start {
        return Ok(SegmentReport {
            failure: Some(Failure {
                defect: Defect::Start(defect),
                at: SParam::point(s0),
                within_margin: false,
            }),
            ..SegmentReport::default()
        });
    }
    let span = Span::new(start, end, s0, s1, player);
    let mut report = SegmentReport::default();
    let mut found = Vec::new();
    for (index, &[a, b, c]) in triangles.iter().enumerate() {
        match span.triangle_holds([a as usize, b as usize, c as usize]) {
            Holds::Filtered => {}
            Holds::Exactly => report.exact_triangles += 1,
            Holds::No(bad, within_margin) => {
                report.exact_triangles += 1;
                report.failing_triangles += 1;
                found.push(Found {
                    defect: Defect::Triangle {
                        index,
                        corners: [a, b, c],
                    },
                    lo: bad.clone(),
                    hi: bad,
                    within_margin,
                });
            }
        }
    }
    for v in 0..n {
        if let Some((bad, within_margin)) = span.fan_fails(v, &mut report.exact_fans) {
            report.failing_fans += 1;
            found.push(Found {
                defect: Defect::Fan { vertex: v },
                lo: bad.lo,
                hi: bad.hi,
                within_margin,
            });
        }
    }
    report.failure = earliest(found, s0, s1);
    Ok(report)
}

/// Whether a triangle stays counter-clockwise (with the player's margin)
/// on a span, and how that was decided.
enum Holds {
    /// By the floating-point filter.
    Filtered,
    /// In exact arithmetic.
    Exactly,
    /// Not: the first s where it fails, and whether only the player's
    /// margin fails there.
    No(Alg, bool),
}

/// One failing triangle or fan, located exactly.
struct Found {
    defect: Defect,
    lo: Alg,
    hi: Alg,
    within_margin: bool,
}

/// The earliest of the failures, with a tight bracket: coarse brackets
/// for all, tight ones for those that may come first.
fn earliest(found: Vec<Found>, s0: f64, s1: f64) -> Option<Failure> {
    if found.is_empty() {
        return None;
    }
    let coarse: Vec<(f64, f64)> = found
        .iter()
        .map(|f| (f.lo.bracket(s0, s1, false).0, f.hi.bracket(s0, s1, false).1))
        .collect();
    let first_hi = coarse.iter().map(|c| c.1).fold(f64::INFINITY, f64::min);
    let mut best: Option<(Failure, f64)> = None;
    for (f, c) in found.into_iter().zip(coarse) {
        if c.0 > first_hi {
            continue;
        }
        let (lo, _) = f.lo.bracket(s0, s1, true);
        let (_, hi) = f.hi.bracket(s0, s1, true);
        let exact = if f.lo == f.hi {
            f.lo.as_fraction()
        } else {
            None
        };
        if best.as_ref().is_none_or(|(_, b)| lo < *b) {
            best = Some((
                Failure {
                    defect: f.defect,
                    at: SParam { lo, hi, exact },
                    within_margin: f.within_margin,
                },
                lo,
            ));
        }
    }
    best.map(|b| b.0)
}

/// The motion `p(s) = p + s(q − p)` on `[l, r]` (`s0` and `s1` as
/// doubles), for exact tests.
struct Span<'a> {
    p: &'a [Point],
    q: &'a [Point],
    l: Alg,
    r: Alg,
    s: [f64; 2],
    shift: Option<i32>,
    deltas: Vec<f64>,
}

/// The exact data of some vertices: positions at both ends and the
/// displacement bounds, as integers in one unit.
struct Ints {
    p: Vec<[BigInt; 2]>,
    d: Vec<[BigInt; 2]>,
    delta: Vec<BigInt>,
}

impl<'a> Span<'a> {
    /// The motion from `p` to `q` on `[s0, s1]`, against `player`.
    fn new(p: &'a [Point], q: &'a [Point], s0: f64, s1: f64, player: Player) -> Span<'a> {
        Span {
            p,
            q,
            l: Alg::from_f64(s0),
            r: Alg::from_f64(s1),
            s: [s0, s1],
            shift: player.shift(),
            deltas: filter::deltas(p, q, player.shift()),
        }
    }

    /// The exact shape at the one time `s` (no player margin).
    fn at(p: &'a [Point], q: &'a [Point], s: f64) -> Span<'a> {
        Span {
            p,
            q,
            l: Alg::from_f64(s),
            r: Alg::from_f64(s),
            s: [s, s],
            shift: None,
            deltas: Vec::new(),
        }
    }

    fn whole(&self) -> bool {
        self.s == [0.0, 1.0]
    }

    /// Whether the triangle with these corners stays counter-clockwise on
    /// the span, with the player's margin: the filter first (on the whole
    /// segment), then exact arithmetic; where only the margin fails, the
    /// margin is taken piece by piece (it overstates the margin where an
    /// edge shrinks inside the span).
    fn triangle_holds(&self, corners: [usize; 3]) -> Holds {
        match self.triangle_whole(corners) {
            Holds::No(_, true) if self.triangle_in_pieces(corners) => Holds::Exactly,
            holds => holds,
        }
    }

    /// [`Span::triangle_holds`] without the pieces.
    fn triangle_whole(&self, corners: [usize; 3]) -> Holds {
        if self.whole() && filter::triangle(self.p, self.q, corners, &self.deltas) {
            return Holds::Filtered;
        }
        let Err(bad) = self.triangle(corners, self.shift) else {
            return Holds::Exactly;
        };
        let within_margin = self.shift.is_some() && self.triangle(corners, None).is_ok();
        Holds::No(bad, within_margin)
    }

    /// The pieces of [`Span::triangle_holds`]: every piece keeps the
    /// triangle above the margin of its own ends.
    fn triangle_in_pieces(&self, corners: [usize; 3]) -> bool {
        filter::triangle_in_pieces(self.p, self.q, corners, &self.deltas, self.s)
    }

    /// Where the fan at `v` reaches a full turn on the span (with the
    /// player's margin), and whether only the margin fails there; `None`
    /// when it does not. Counts in `exact` a fan the filter left to exact
    /// arithmetic. The fan's edges are the curve's own, so the answer
    /// does not depend on the triangulation (while its triangles stay
    /// counter-clockwise).
    fn fan_fails(&self, v: usize, exact: &mut usize) -> Option<(exact::Bad, bool)> {
        match self.fan_whole(v, exact)? {
            (_, true) if self.fan_in_pieces(v) => None,
            failure => Some(failure),
        }
    }

    /// [`Span::fan_fails`] without the pieces.
    fn fan_whole(&self, v: usize, exact: &mut usize) -> Option<(exact::Bad, bool)> {
        if self.whole() && filter::fan(self.p, self.q, v, &self.deltas) {
            return None;
        }
        *exact += 1;
        let bad = self.fan(v, self.shift).err()?;
        let within_margin = self.shift.is_some() && self.fan(v, None).is_ok();
        Some((*bad, within_margin))
    }

    /// The pieces of [`Span::fan_fails`].
    fn fan_in_pieces(&self, v: usize) -> bool {
        filter::fan_in_pieces(self.p, self.q, v, &self.deltas, self.s)
    }

    /// Integers for the vertices `vs` (with δ_v when `shift` is given).
    fn ints(&self, vs: &[usize], shift: Option<i32>) -> Ints {
        let mag = |v: usize| {
            let (a, b) = (self.p[v], self.q[v]);
            a.x.abs().max(a.y.abs()).max(b.x.abs()).max(b.y.abs())
        };
        let coords = vs.iter().flat_map(|&v| {
            let (a, b) = (self.p[v], self.q[v]);
            [(a.x, 0), (a.y, 0), (b.x, 0), (b.y, 0)]
        });
        let deltas = shift
            .into_iter()
            .flat_map(|k| vs.iter().map(move |&v| (mag(v), i64::from(k))));
        let scale = Scaled::new(coords.chain(deltas));
        let mut out = Ints {
            p: Vec::with_capacity(vs.len()),
            d: Vec::with_capacity(vs.len()),
            delta: Vec::with_capacity(vs.len()),
        };
        for &v in vs {
            let (a, b) = (self.p[v], self.q[v]);
            let (px, py) = (scale.int(a.x, 0), scale.int(a.y, 0));
            let (qx, qy) = (scale.int(b.x, 0), scale.int(b.y, 0));
            out.d.push([&qx - &px, &qy - &py]);
            out.p.push([px, py]);
            out.delta
                .push(shift.map_or(BigInt::ZERO, |k| scale.int(mag(v), i64::from(k))));
        }
        out
    }

    /// `cross` or `dot` of the edges `i → j` and `i → k` of `ints`, as
    /// quadratics in s, and the margin for them.
    fn pair(ints: &Ints, i: usize, j: usize, k: usize) -> (Quad, Quad, BigInt) {
        let e = |a: usize| {
            let p = [&ints.p[a][0] - &ints.p[i][0], &ints.p[a][1] - &ints.p[i][1]];
            let d = [&ints.d[a][0] - &ints.d[i][0], &ints.d[a][1] - &ints.d[i][1]];
            (p, d)
        };
        let ((u0, du), (w0, dw)) = (e(j), e(k));
        let cross = |a: &[BigInt; 2], b: &[BigInt; 2]| &a[0] * &b[1] - &a[1] * &b[0];
        let dot = |a: &[BigInt; 2], b: &[BigInt; 2]| &a[0] * &b[0] + &a[1] * &b[1];
        let c = Quad {
            c0: cross(&u0, &w0),
            c1: cross(&u0, &dw) + cross(&du, &w0),
            c2: cross(&du, &dw),
        };
        let g = Quad {
            c0: dot(&u0, &w0),
            c1: dot(&u0, &dw) + dot(&du, &w0),
            c2: dot(&du, &dw),
        };
        // Margin L_u δ_w + L_w δ_u + 2 δ_u δ_w, L the larger 1-norm of the
        // edge at s = 0 and s = 1.
        let norm1 = |e0: &[BigInt; 2], de: &[BigInt; 2]| {
            let e1 = [&e0[0] + &de[0], &e0[1] + &de[1]];
            let n = |v: &[BigInt; 2]| v[0].magnitude() + v[1].magnitude();
            BigInt::from(n(e0).max(n(&e1)))
        };
        let du_b = &ints.delta[i] + &ints.delta[j];
        let dw_b = &ints.delta[i] + &ints.delta[k];
        let m = if exact::sgn(&du_b) == 0 && exact::sgn(&dw_b) == 0 {
            BigInt::ZERO
        } else {
            norm1(&u0, &du) * &dw_b + norm1(&w0, &dw) * &du_b + ((&du_b * &dw_b) << 1)
        };
        (c, g, m)
    }

    /// The exact triangle test on the span: `Err` with the first s where
    /// `2·area ≤ M`.
    fn triangle(&self, [a, b, c]: [usize; 3], shift: Option<i32>) -> Result<(), Alg> {
        let ints = self.ints(&[a, b, c], shift);
        let (area, _, m) = Self::pair(&ints, 0, 1, 2);
        let q = area.plus(&-m);
        if positive_on(&q, &self.l, &self.r) {
            Ok(())
        } else {
            Err(first_nonpositive(&q, &self.l, &self.r))
        }
    }

    /// The exact fan test at `v` on the span.
    fn fan(&self, v: usize, shift: Option<i32>) -> Result<(), Box<exact::Bad>> {
        let n = self.p.len();
        let ints = self.ints(&[v, (v + 1) % n, (v + n - 1) % n], shift);
        let (cross, dot, k) = Self::pair(&ints, 0, 1, 2);
        fan_ok(&cross, &dot, &k, &self.l, &self.r)
    }

    /// The exact sign of `orient(p_a, p_b, p_c)` at the parameter `s`.
    fn orient_at(&self, [a, b, c]: [usize; 3], s: &Alg) -> i32 {
        let ints = self.ints(&[a, b, c], None);
        let (area, _, _) = Self::pair(&ints, 0, 1, 2);
        area.sign_at(s)
    }
}

/// Whether `triangles` is an immersion triangulation of the exact shape
/// `p(s) = start + s(end − start)` (a rational shape for 0 < s < 1), with
/// the rules of [`crate::immersion::check`], decided exactly.
///
/// # Errors
///
/// The first [`ImmersionDefect`]; [`ImmersionDefect::TooFewPoints`] also
/// when the two ends differ in length, are not finite, or `s` is not in
/// [0, 1].
pub fn valid_at(
    start: &[Point],
    end: &[Point],
    triangles: &[[u32; 3]],
    s: f64,
) -> Result<(), ImmersionDefect> {
    if check_input(start, end, s, s).is_err() {
        return Err(ImmersionDefect::TooFewPoints(start.len().min(end.len())));
    }
    valid_at_unchecked(start, end, triangles, s)
}

fn valid_at_unchecked(
    start: &[Point],
    end: &[Point],
    triangles: &[[u32; 3]],
    s: f64,
) -> Result<(), ImmersionDefect> {
    if s == 0.0 {
        return check(start, triangles);
    }
    if s == 1.0 {
        return check(end, triangles);
    }
    let n = start.len();
    check_structure(n, triangles)?;
    let span = Span::at(start, end, s);
    let at = Alg::from_f64(s);
    // The rules of `immersion::valid`: counter-clockwise, and at each
    // corner v with (u, w) after it, not (u strictly right of v → v+1 and
    // w not).
    let right = |v: usize, x: usize| span.orient_at([v, (v + 1) % n, x], &at) < 0;
    let coincident = |v: usize| {
        let ints = span.ints(&[v, (v + 1) % n], None);
        (0..2).all(|axis| {
            let diff = Quad {
                c0: &ints.p[1][axis] - &ints.p[0][axis],
                c1: &ints.d[1][axis] - &ints.d[0][axis],
                c2: BigInt::ZERO,
            };
            diff.sign_at(&at) == 0
        })
    };
    let invalid = triangles.par_iter().position_first(|&[a, b, c]| {
        let (a, b, c) = (a as usize, b as usize, c as usize);
        if [a, b, c].iter().any(|&v| coincident(v)) {
            return true;
        }
        if span.orient_at([a, b, c], &at) <= 0 {
            return true;
        }
        let fails = |v: usize, u: usize, w: usize| right(v, u) && !right(v, w);
        fails(a, b, c) || fails(b, c, a) || fails(c, a, b)
    });
    match invalid {
        None => Ok(()),
        Some(t) => Err(ImmersionDefect::InvalidTriangle {
            triangle: t,
            corners: triangles[t],
        }),
    }
}

/// One key of an animation: a time, the shape, and the triangulation of
/// the segment that starts at this key (docs/design.md §13: a flip key is
/// one key whose triangles are those after the flip; the segment before
/// it ends at this shape under the old triangulation, so both are valid
/// there).
#[derive(Clone, Copy, Debug)]
pub struct Key<'a> {
    /// The time (any unit, strictly increasing along the keys).
    pub t: f64,
    /// The shape.
    pub points: &'a [Point],
    /// Triangles of the segment from this key to the next (for the last
    /// key: a triangulation valid at it).
    pub triangles: &'a [[u32; 3]],
}

/// The certificate of a key list.
#[derive(Clone, Debug, PartialEq)]
pub struct KeysReport {
    /// One report per segment, key i to key i + 1.
    pub segments: Vec<SegmentReport>,
    /// Why the last key's triangulation is not valid at it, if it is not.
    pub last: Option<ImmersionDefect>,
}

impl KeysReport {
    /// True when every segment is certified and the last key is valid.
    pub fn is_certified(&self) -> bool {
        self.last.is_none() && self.segments.iter().all(SegmentReport::is_certified)
    }

    /// The first segment that is not certified, with its failure.
    pub fn first_failure(&self) -> Option<(usize, &Failure)> {
        self.segments
            .iter()
            .enumerate()
            .find_map(|(i, s)| s.failure.as_ref().map(|f| (i, f)))
    }
}

/// Certify a whole key list: every segment between consecutive keys under
/// the triangulation of its first key, and the last key's triangulation at
/// the last key. Segments are certified in parallel.
///
/// # Errors
///
/// [`CertifyError::NoKeys`], [`CertifyError::KeyTime`] for times that are
/// not finite and strictly increasing, and [`CertifyError::InKey`] for a
/// key whose points differ in count from the first key's or are not
/// finite.
pub fn certify_keys(keys: &[Key<'_>], player: Player) -> Result<KeysReport, CertifyError> {
    let Some(first) = keys.first() else {
        return Err(CertifyError::NoKeys);
    };
    for (i, k) in keys.iter().enumerate() {
        if !k.t.is_finite() || (i > 0 && k.t.partial_cmp(&keys[i - 1].t) != Some(Ordering::Greater))
        {
            return Err(CertifyError::KeyTime { key: i, t: k.t });
        }
        check_input(first.points, k.points, 0.0, 0.0).map_err(|e| CertifyError::InKey {
            key: i,
            source: Box::new(e),
        })?;
    }
    let segments = keys
        .par_windows(2)
        .map(|w| certify_segment(w[0].points, w[1].points, w[0].triangles, player))
        .collect::<Result<Vec<_>, _>>()?;
    let last = keys.last().and_then(|k| check(k.points, k.triangles).err());
    Ok(KeysReport { segments, last })
}
