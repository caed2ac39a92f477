//! Certifying a straight-line motion that comes without a triangulation
//! (docs/design.md §13): triangulate where a piece starts, certify as far
//! as that triangulation holds; where it fails, look for a triangulation
//! that holds for the whole segment (`certified_triangulation`, exact),
//! else triangulate again just before the failure, and go on; a shape
//! that is not self-overlapping at an exact s ends the search with a
//! definite "invalid".
//!
//! Shapes inside a segment are rational (`p(s)` for a dyadic s), not
//! `f64`, so deciding self-overlap there needs the triangulation DP of
//! docs/design.md §3 on exact predicates of rational points
//! ([`triangulate_exact`]): the same recurrence and the same validity rule
//! as [`crate::immersion`], with each orientation decided by a
//! floating-point filter and, when it cannot, in big integers. New
//! triangulations are taken from the Delaunay-improved triangulation of
//! the shape rounded to `f64` when that is valid for the exact shape (it
//! lasts longer than the DP's thin witness), else from the exact DP.

use super::exact::Alg;
use super::filter::{self, Fe};
use super::{Failure, Player, Span, certify_span, valid_at_unchecked};
use crate::geom::Point;
use crate::immersion::check;
use crate::immersion::dp::from_apexes;
use crate::quality::{Quality, triangulate_with};

/// Most points of a shape whose self-overlap [`certify_motion`] decides
/// at a rational s (the exact DP's tables take O(n²) memory).
pub(crate) const MAX_EXACT_DP_POINTS: usize = 3000;

/// Limits of [`certify_motion`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MotionOptions {
    /// Most pieces (triangulations) per segment before the answer is
    /// "undecided".
    pub max_pieces: usize,
}

impl Default for MotionOptions {
    fn default() -> Self {
        MotionOptions { max_pieces: 24 }
    }
}

/// Where a piece's triangulation came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Source {
    /// The i-th triangulation given with the motion.
    Given(usize),
    /// Triangulated where the piece starts.
    Triangulated,
}

/// A certified piece `[from, to]` of a segment under one triangulation.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Piece {
    /// Where it starts.
    pub from: f64,
    /// Where it ends (1 for the last piece of a certified segment).
    pub to: f64,
    /// Its triangulation's origin.
    pub source: Source,
    /// Its triangulation.
    #[serde(skip)]
    pub triangles: Vec<[u32; 3]>,
}

/// The answer about one segment.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// Valid for every s in [0, 1], with a certificate: the pieces.
    Certified,
    /// Not self-overlapping at this exact s: invalid.
    Invalid {
        /// The parameter (a double, so exact).
        at: f64,
    },
    /// Neither certified nor shown invalid within the limits: certified
    /// for every s up to `reached` only.
    Undecided {
        /// Certified on [0, reached].
        reached: f64,
        /// Why the search stopped.
        reason: String,
    },
}

/// The report on one segment of [`certify_motion`].
#[derive(Clone, Debug, PartialEq)]
pub struct MotionReport {
    /// The answer.
    pub verdict: Verdict,
    /// The certified pieces, in order.
    pub pieces: Vec<Piece>,
    /// The first certificate failure met (why a piece ended), if any.
    pub first_failure: Option<Failure>,
    /// Triangulations computed.
    pub triangulations: usize,
}

/// Certify the straight-line motion from `start` to `end` for every s in
/// [0, 1], finding triangulations as needed (module docs). The `given`
/// triangulations are tried first wherever they are valid (a key's own,
/// the next key's).
///
/// Expects finite points of equal count (≥ 3); otherwise the answer is
/// undecided with the reason.
pub fn certify_motion(
    start: &[Point],
    end: &[Point],
    given: &[&[[u32; 3]]],
    player: Player,
    options: MotionOptions,
) -> MotionReport {
    let mut report = MotionReport {
        verdict: Verdict::Certified,
        pieces: Vec::new(),
        first_failure: None,
        triangulations: 0,
    };
    if super::check_input(start, end, 0.0, 1.0).is_err() {
        report.verdict = Verdict::Undecided {
            reached: 0.0,
            reason: "the two shapes are not a motion (counts differ, too few or non-finite points)"
                .into(),
        };
        return report;
    }
    let mut s = 0.0f64;
    // The triangulation found just after the last failure: it may hold
    // from before the failure on, through the moment where the last one
    // degenerated.
    let mut beyond: Option<Vec<[u32; 3]>> = None;
    loop {
        if report.pieces.len() >= options.max_pieces.max(1) {
            report.verdict = Verdict::Undecided {
                reached: s,
                reason: format!(
                    "{} triangulations did not reach the end of the segment",
                    report.pieces.len()
                ),
            };
            return report;
        }
        // Triangulations valid at the exact shape p(s): the given ones
        // first; a new one when none is valid, after the first piece, or
        // when the given ones fail.
        let mut candidates: Vec<(Vec<[u32; 3]>, Source)> = given
            .iter()
            .enumerate()
            .filter(|(_, t)| valid_at_unchecked(start, end, t, s).is_ok())
            .map(|(i, t)| (t.to_vec(), Source::Given(i)))
            .collect();
        let mut triangulate_now = candidates.is_empty() || !report.pieces.is_empty();
        if let Some(t) = beyond.take()
            && valid_at_unchecked(start, end, &t, s).is_ok()
        {
            candidates.push((t, Source::Triangulated));
        }
        let mut best: Option<(Vec<[u32; 3]>, Source, Option<Failure>)> = None;
        loop {
            if triangulate_now {
                report.triangulations += 1;
                match triangulate_at(start, end, s) {
                    Ok(t) => candidates.push((t, Source::Triangulated)),
                    Err(Some(())) if best.is_none() => {
                        report.verdict = Verdict::Invalid { at: s };
                        return report;
                    }
                    Err(None) if best.is_none() => {
                        report.verdict = Verdict::Undecided {
                            reached: s,
                            reason: format!(
                                "{} points is more than the {MAX_EXACT_DP_POINTS} whose self-overlap is decided at a rational s",
                                start.len()
                            ),
                        };
                        return report;
                    }
                    Err(_) => {}
                }
            }
            // The candidate that lasts longest.
            for (t, source) in candidates.drain(..) {
                let Ok(r) = certify_span(start, end, &t, s, 1.0, player) else {
                    continue;
                };
                let reach = |f: &Option<Failure>| f.as_ref().map_or(f64::INFINITY, |f| f.at.lo);
                if best
                    .as_ref()
                    .is_none_or(|b| reach(&r.failure) > reach(&b.2))
                {
                    best = Some((t, source, r.failure));
                }
            }
            let failed = best.as_ref().is_none_or(|b| b.2.is_some());
            if triangulate_now || !failed {
                break;
            }
            triangulate_now = true;
        }
        // Where no triangulation tried so far holds for the whole
        // segment, one that does is looked for among all of them (exactly:
        // `certified_triangulation`) before the segment is cut into
        // pieces.
        if s == 0.0
            && best.as_ref().is_some_and(|b| b.2.is_some())
            && let Some(t) = super::certified_triangulation(start, end, player)
        {
            report.triangulations += 1;
            best = Some((t, Source::Triangulated, None));
        }
        let Some((triangles, source, failure)) = best else {
            report.verdict = Verdict::Undecided {
                reached: s,
                reason: "no triangulation could be certified".into(),
            };
            return report;
        };
        let Some(failure) = failure else {
            report.pieces.push(Piece {
                from: s,
                to: 1.0,
                source,
                triangles,
            });
            return report;
        };
        if report.first_failure.is_none() {
            report.first_failure = Some(failure.clone());
        }
        // Invalid just after the failure? With a margin, the exact motion
        // under the same triangulation fails later (or not at all): look
        // just after that.
        let after = if player == Player::Exact {
            Some(failure.at.hi)
        } else {
            certify_span(start, end, &triangles, s, 1.0, Player::Exact)
                .ok()
                .and_then(|r| r.failure)
                .map(|f| f.at.hi)
        };
        if let Some(after) = after
            && failure.at.lo > s
        {
            report.triangulations += 1;
            match triangulate_at(start, end, after) {
                Err(Some(())) => {
                    report.pieces.push(Piece {
                        from: s,
                        to: failure.at.lo,
                        source,
                        triangles,
                    });
                    report.verdict = Verdict::Invalid { at: after };
                    return report;
                }
                Ok(t) => beyond = Some(t),
                Err(None) => {}
            }
        }
        // Triangulate again a little before the failure.
        let next = s + (failure.at.lo - s) * (15.0 / 16.0);
        if next <= s || next.is_nan() {
            report.verdict = Verdict::Undecided {
                reached: s,
                reason: format!("the certificate fails at once: {failure}"),
            };
            return report;
        }
        report.pieces.push(Piece {
            from: s,
            to: next,
            source,
            triangles,
        });
        s = next;
    }
}

/// A triangulation valid at the exact shape `p(s)`: `Err(Some(()))` when
/// there is none (not self-overlapping, decided exactly), `Err(None)` when
/// the shape has too many points to decide.
fn triangulate_at(start: &[Point], end: &[Point], s: f64) -> Result<Vec<[u32; 3]>, Option<()>> {
    let exact_shape = if s == 0.0 {
        Some(start)
    } else if s == 1.0 {
        Some(end)
    } else {
        None
    };
    if let Some(points) = exact_shape {
        return match triangulate_with(points, Quality::Delaunay) {
            Ok(imm) => Ok(imm.triangles),
            Err(e) if e.is_answer() => Err(Some(())),
            Err(_) => Err(None),
        };
    }
    // The rounded shape's Delaunay-improved triangulation, when it is
    // valid for the exact shape.
    let rounded: Vec<Point> = start
        .iter()
        .zip(end)
        .map(|(a, b)| *a + (*b - *a) * s)
        .collect();
    if let Ok(imm) = triangulate_with(&rounded, Quality::Delaunay)
        && check(&rounded, &imm.triangles).is_ok()
        && valid_at_unchecked(start, end, &imm.triangles, s).is_ok()
    {
        return Ok(imm.triangles);
    }
    if start.len() > MAX_EXACT_DP_POINTS {
        return Err(None);
    }
    triangulate_exact(start, end, s).ok_or(Some(()))
}

/// The exact shape `p(s)` as an orientation oracle.
struct Oracle<'a> {
    span: Span<'a>,
    at: Alg,
    approx: Vec<[Fe; 2]>,
}

impl Oracle<'_> {
    fn orient(&self, a: usize, b: usize, c: usize) -> i32 {
        filter::orient_sign(self.approx[a], self.approx[b], self.approx[c])
            .unwrap_or_else(|| self.span.orient_at([a, b, c], &self.at))
    }

    fn same(&self, a: usize, b: usize) -> bool {
        if filter::surely_apart(self.approx[a], self.approx[b]) {
            return false;
        }
        let ints = self.span.ints(&[a, b], None);
        (0..2).all(|k| {
            let diff = super::exact::Quad {
                c0: &ints.p[1][k] - &ints.p[0][k],
                c1: &ints.d[1][k] - &ints.d[0][k],
                c2: num_bigint::BigInt::ZERO,
            };
            diff.sign_at(&self.at) == 0
        })
    }
}

/// The triangulation DP of docs/design.md §3 on the exact shape
/// `p(s) = start + s(end − start)`: `Q[i][j]` holds when the sub-polygon
/// `i..=j` has a triangulation by valid triangles; `None` when the whole
/// polygon has none (it is not self-overlapping at s). Validity is the
/// rule of [`crate::immersion::is_valid_triangle`] (counter-clockwise; at
/// each corner v with (u, w) after it, not "u strictly right of the edge
/// v → v+1 while w is not"; no corner on a zero-length edge), and chords
/// are filtered by the same necessary cone test as the decision DP.
/// O(n²) exact orientations for the masks, O(n³/64) word operations.
pub(crate) fn triangulate_exact(start: &[Point], end: &[Point], s: f64) -> Option<Vec<[u32; 3]>> {
    let n = start.len();
    if n < 3 {
        return None;
    }
    let oracle = Oracle {
        span: Span::at(start, end, s),
        at: Alg::from_f64(s),
        approx: start
            .iter()
            .zip(end)
            .map(|(a, b)| filter::point_at(*a, *b, s))
            .collect(),
    };
    let words = n.div_ceil(64);
    let bit = |m: &[u64], r: usize, c: usize| m[r * words + c / 64] >> (c % 64) & 1 == 1;
    let set = |m: &mut [u64], r: usize, c: usize| m[r * words + c / 64] |= 1 << (c % 64);
    let bad: Vec<bool> = (0..n).map(|v| oracle.same(v, (v + 1) % n)).collect();
    let mut bad_bits = vec![0u64; words];
    for v in (0..n).filter(|&v| bad[v]) {
        bad_bits[v / 64] |= 1 << (v % 64);
    }
    // right[v] = { x : p_x strictly right of v → v+1 }, and its transpose.
    let rows: Vec<Vec<u64>> = {
        use rayon::prelude::*;
        (0..n)
            .into_par_iter()
            .map(|v| {
                let mut row = vec![0u64; words];
                if !bad[v] {
                    for x in 0..n {
                        if oracle.orient(v, (v + 1) % n, x) < 0 {
                            row[x / 64] |= 1 << (x % 64);
                        }
                    }
                }
                row
            })
            .collect()
    };
    let right: Vec<u64> = rows.concat();
    let mut right_t = vec![0u64; n * words];
    for v in 0..n {
        for x in 0..n {
            if bit(&right, v, x) {
                set(&mut right_t, x, v);
            }
        }
    }
    let may_be_diagonal = |i: usize, j: usize| {
        if i == 0 && j == n - 1 {
            return true;
        }
        let corner = |v: usize, prev: usize, x: usize| {
            let (a, b) = (bit(&right, v, x), bit(&right, prev, x));
            if bit(&right, v, prev) {
                !(a && b)
            } else {
                !(a || b)
            }
        };
        let prev_i = if i == 0 { n - 1 } else { i - 1 };
        corner(i, prev_i, j) && corner(j, j - 1, i)
    };
    let mut q_rows = vec![0u64; n * words];
    let mut q_cols = vec![0u64; n * words];
    let mut apex = vec![u32::MAX; n * n];
    for i in (0..n - 1).rev() {
        set(&mut q_rows, i, i + 1);
        set(&mut q_cols, i + 1, i);
        for j in i + 2..n {
            if bad[i] || bad[j] || !may_be_diagonal(i, j) {
                continue;
            }
            let keep_i = if bit(&right, i, j) { u64::MAX } else { 0 };
            let keep_j = if bit(&right, j, i) { 0 } else { u64::MAX };
            let mut found = None;
            'words: for w in (i + 1) / 64..=(j - 1) / 64 {
                let at_i = !right[i * words + w] | keep_i;
                let at_j = right[j * words + w] | keep_j;
                let at_k = !(right_t[j * words + w] & !right_t[i * words + w]);
                let mut bits = q_rows[i * words + w]
                    & q_cols[j * words + w]
                    & at_i
                    & at_j
                    & at_k
                    & !bad_bits[w];
                bits &= crate::immersion::valid::open_range_word(w, i, j);
                while bits != 0 {
                    let k = w * 64 + bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    if oracle.orient(i, k, j) > 0 {
                        found = Some(k);
                        break 'words;
                    }
                }
            }
            if let Some(k) = found {
                set(&mut q_rows, i, j);
                set(&mut q_cols, j, i);
                apex[i * n + j] = k as u32;
            }
        }
    }
    if !bit(&q_rows, 0, n - 1) {
        return None;
    }
    let mut out = from_apexes(n, |i, j| Some(apex[i * n + j] as usize))?;
    out.sort_unstable();
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::immersion::triangulate;
    use crate::testing::{grid_rounds, unit_square};

    #[test]
    fn the_exact_dp_decides_as_the_immersion_dp() {
        // At s = 0 the exact DP sees the f64 shape itself: its answer must
        // be the decision DP's, on shapes with many degeneracies.
        let (yes, no) = grid_rounds(5, 3000, (3, 9.0), (2, 4.0), |n, point| {
            let pts: Vec<Point> = (0..n).map(|_| point()).collect();
            let want = triangulate(&pts).is_ok();
            let got = triangulate_exact(&pts, &pts, 0.0);
            assert_eq!(got.is_some(), want, "{pts:?}");
            let Some(t) = got else {
                return Some(false);
            };
            assert_eq!(check(&pts, &t), Ok(()), "{pts:?}");
            Some(true)
        });
        assert!(yes > 200 && no > 200, "{yes} {no}");
    }

    #[test]
    fn the_exact_dp_decides_midway_shapes_as_the_immersion_dp() {
        // On a grid, p(½) = (P + Q)/2 is a double: the exact DP at s = ½
        // (orientations of the moving points, filtered then in big
        // integers) must answer as the decision DP on that shape.
        let (yes, no) = grid_rounds(17, 3000, (3, 9.0), (2, 4.0), |n, point| {
            let (p, q): (Vec<Point>, Vec<Point>) = (0..n).map(|_| (point(), point())).unzip();
            let mid: Vec<Point> = p.iter().zip(&q).map(|(a, b)| (*a + *b) * 0.5).collect();
            let want = triangulate(&mid).is_ok();
            let got = triangulate_exact(&p, &q, 0.5);
            assert_eq!(got.is_some(), want, "{p:?} {q:?}");
            let Some(t) = got else {
                return Some(false);
            };
            assert_eq!(check(&mid, &t), Ok(()));
            assert_eq!(valid_at_unchecked(&p, &q, &t, 0.5), Ok(()));
            Some(true)
        });
        assert!(yes > 100 && no > 200, "{yes} {no}");
    }

    #[test]
    fn a_half_turned_square_is_invalid_at_one_half() {
        let p = unit_square();
        let q: Vec<Point> = p.iter().map(|a| Point::new(1.0, 1.0) - *a).collect();
        let r = certify_motion(&p, &q, &[], Player::Exact, MotionOptions::default());
        assert_eq!(r.verdict, Verdict::Invalid { at: 0.5 }, "{r:?}");
        // A quarter turn is certified with the start's own triangulation.
        let q: Vec<Point> = p.iter().map(|a| Point::new(1.0 - a.y, a.x)).collect();
        let r = certify_motion(&p, &q, &[], Player::F32, MotionOptions::default());
        assert_eq!(r.verdict, Verdict::Certified);
        assert_eq!(r.pieces.len(), 1);
    }
}
