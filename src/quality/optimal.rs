//! The max–min-angle immersion triangulation, by the same interval DP.
//!
//! Provenance: docs/design.md §3 (the `maxmin` quality); the DP over sub-chains
//! is Shor and Van Wyk's (*Detecting and Decomposing Self-Overlapping Curves*,
//! ref. \[24\] of Mukherjee & Gopi), the objective is Klincsek-style optimal
//! polygon triangulation. Validity is decided exactly with the bitsets of
//! [`crate::immersion`]; only the objective is measured in floats.
//!
//! For each sub-polygon `(i, j)` the DP keeps the best value of the pair
//! (smallest minimum angle over its triangles, sum over its triangles of
//! sin² of the triangle's minimum angle), compared lexicographically: first
//! the minimum angle is maximised, then, among exact ties, the sum (which
//! favours many well-shaped triangles), then the smallest apex index `k`
//! wins. A triangle's minimum angle θ ≤ π/3 is compared through sin²θ =
//! (2·area)² / (product of the squared two longest sides), which is monotone
//! on (0, π/3] and needs no trigonometry.
//!
//! The decision table ([`crate::immersion::dp`]) is filled first; the values
//! are then computed only for the cells it marks feasible, over the apexes
//! it marks feasible, tile by tile in parallel as the decision is. Skipped
//! cells are exactly those no valid triangulation of the whole polygon
//! uses, so the optimum and its tie-breaks are those of the unrestricted DP.
//!
//! Complexity: O(n³) objective evaluations in the worst case (candidates
//! whose sub-polygon values already lose are skipped before the triangle is
//! tested or measured), plus the decision DP. The candidates are counted
//! from the decision table first ([`candidate_count`], O(n³/64) word
//! operations) and a curve with more than the caller's limit is refused
//! before the DP runs. Memory: four `n × n` `f64`
//! tables (row-major and transposed copies of the two objective values) and
//! one `n × n` `u32` table of apexes, 36n² bytes allocated, of which the DP
//! touches the half each table uses (cells i < j, or their transposes),
//! about 18n² bytes (18 MB at n = 1000, 288 MB at n = 4000), plus the
//! decision table.

use std::sync::atomic::{AtomicU32, AtomicU64, Ordering::Relaxed};

use rayon::prelude::*;

use crate::geom::Point;
use crate::immersion::NotSelfOverlapping;
use crate::immersion::dp::{Table, decide, fill_by_tiles, from_apexes, is_ccw};
use crate::immersion::valid::open_range_word;

use crate::geom::polygon::sin2_min_angle;

const NONE: u32 = u32::MAX;

/// Working memory of [`maxmin`] for `n` points, in bytes: the halves of
/// its tables it touches (module docs) and the decision table.
pub(crate) fn memory_bytes(n: usize) -> usize {
    18 * n * n + crate::immersion::dp_memory_bytes(n)
}

/// A table of `f64` that the parallel fill writes cell by cell.
struct Floats(Vec<AtomicU64>);

impl Floats {
    /// `len` cells of 0.0, in memory the allocator hands out zeroed: a
    /// page none of whose cells is set is never touched, so the half of a
    /// square table that the DP does not use costs no memory.
    fn zeroed(len: usize) -> Self {
        Self(bytemuck::zeroed_vec(len))
    }

    #[inline]
    fn get(&self, at: usize) -> f64 {
        f64::from_bits(self.0[at].load(Relaxed))
    }

    #[inline]
    fn set(&self, at: usize, x: f64) {
        self.0[at].store(x.to_bits(), Relaxed);
    }
}

/// The candidate triangles `(i, k, j)` of the max–min DP over the
/// feasible cells of `table`: apexes `k` with `Q[i][k]` and `Q[k][j]`
/// (before the corner tests, so an upper bound on the triangles the DP
/// visits), counted by popcounts of the row and column words: O(n³/64)
/// word operations at worst, a few percent of the DP it bounds.
pub(crate) fn candidate_count(table: &Table, n: usize) -> u64 {
    let total = AtomicU64::new(0);
    (0..n.saturating_sub(2)).into_par_iter().for_each(|i| {
        let row = table.rows.row(i);
        let mut here = 0u64;
        for j in i + 2..n {
            if !table.get(i, j) {
                continue;
            }
            let col = table.cols.row(j);
            let (first, last) = ((i + 1) / 64, (j - 1) / 64);
            for w in first..=last {
                let mut bits = row[w].load(Relaxed) & col[w].load(Relaxed);
                if w == first || w == last {
                    bits &= open_range_word(w, i, j);
                }
                here += u64::from(bits.count_ones());
            }
        }
        total.fetch_add(here, Relaxed);
    });
    total.into_inner()
}

/// Share of the progress bar given to the decision DP.
const DECIDE_SHARE: f64 = 0.2;

/// The max–min-angle triangulation by valid triangles (module docs).
/// `n ≥ 3` is assumed.
///
/// # Errors
///
/// [`NotSelfOverlapping::NoValidTriangulation`] when none exists;
/// [`NotSelfOverlapping::TooManyCandidates`], before the max–min DP
/// starts, when it would visit more than `limit` candidate triangles
/// ([`candidate_count`]).
pub(crate) fn maxmin(
    points: &[Point],
    limit: u64,
    progress: &mut dyn FnMut(f64),
) -> Result<Vec<[u32; 3]>, NotSelfOverlapping> {
    let n = points.len();
    if n < 3 {
        return Err(NotSelfOverlapping::Degenerate);
    }
    let table = decide(points, &mut |f| progress(DECIDE_SHARE * f));
    if !table.get(0, n - 1) {
        progress(1.0);
        return Err(NotSelfOverlapping::NoValidTriangulation);
    }
    let candidates = candidate_count(&table, n);
    if candidates > limit {
        progress(1.0);
        return Err(NotSelfOverlapping::TooManyCandidates { candidates, limit });
    }
    // Row-major (value, sum) pairs at 2 (i n + j) for i < j, and the
    // transposed copy at 2 (j n + i), so both operands of a cell are read
    // in order. The DP reads and writes only these halves (an apex k of
    // the chord (i, j) has i < k < j): their values start at −∞, and the
    // other halves are never touched.
    let (rows, cols) = (Floats::zeroed(2 * n * n), Floats::zeroed(2 * n * n));
    (0..n).into_par_iter().for_each(|r| {
        // Row r: its cells after the diagonal in `rows`, before it in `cols`.
        for c in r + 1..n {
            rows.set(2 * (r * n + c), f64::NEG_INFINITY);
        }
        for c in 0..r {
            cols.set(2 * (r * n + c), f64::NEG_INFINITY);
        }
    });
    // The apex of (i, j) plus one at i n + j; 0 where there is none.
    let arg: Vec<AtomicU32> = bytemuck::zeroed_vec(n * n);
    for i in 0..n - 1 {
        rows.set(2 * (i * n + i + 1), f64::INFINITY);
        cols.set(2 * ((i + 1) * n + i), f64::INFINITY);
    }
    let share = |f: f64| DECIDE_SHARE + (1.0 - DECIDE_SHARE) * f;
    fill_by_tiles(n, &mut |f| progress(share(f)), |i, j| {
        if !table.get(i, j) {
            return;
        }
        let (mut best_v, mut best_s, mut best_k) = (f64::NEG_INFINITY, f64::NEG_INFINITY, NONE);
        let (pi, pj) = (points[i], points[j]);
        let (ri, cj) = (2 * i * n, 2 * j * n);
        table.for_candidates(points, i, j, |k, ccw| {
            let lo = rows.get(ri + 2 * k).min(cols.get(cj + 2 * k));
            if lo < best_v {
                return false;
            }
            let base = rows.get(ri + 2 * k + 1) + cols.get(cj + 2 * k + 1);
            // A tie on the minimum at best wins on the sum, and q ≤ 1.
            if lo == best_v && base + 1.0 <= best_s {
                return false;
            }
            let q = sin2_min_angle(pi, points[k], pj);
            let v = lo.min(q);
            let s = base + q;
            if (v > best_v || (v == best_v && s > best_s)) && (ccw || is_ccw(points, i, k, j)) {
                (best_v, best_s, best_k) = (v, s, k as u32);
            }
            false
        });
        debug_assert_ne!(best_k, NONE, "a feasible cell without an apex: a bug");
        rows.set(ri + 2 * j, best_v);
        rows.set(ri + 2 * j + 1, best_s);
        cols.set(cj + 2 * i, best_v);
        cols.set(cj + 2 * i + 1, best_s);
        arg[i * n + j].store(if best_k == NONE { 0 } else { best_k + 1 }, Relaxed);
    });
    let mut out = from_apexes(n, |i, j| {
        let k = arg[i * n + j].load(Relaxed);
        debug_assert_ne!(k, 0, "max-min DP backtrack hit an empty cell: a bug");
        (k != 0).then(|| k as usize - 1)
    })
    .ok_or(NotSelfOverlapping::NoValidTriangulation)?;
    out.sort_unstable();
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::polygon::triangle_angles;
    use crate::testing::{points, regular_polygon};

    #[test]
    fn sin2_matches_angles() {
        let [a, b, c] = points([(0.0, 0.0), (3.0, 0.2), (1.0, 2.0)]);
        let m = triangle_angles(a, b, c)
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        assert!((sin2_min_angle(a, b, c) - m.sin().powi(2)).abs() < 1e-12);
    }

    #[test]
    fn regular_polygon_is_triangulated() {
        let pts = regular_polygon(9);
        let t = maxmin(&pts, u64::MAX, &mut |_| {}).expect("convex");
        assert_eq!(crate::immersion::check(&pts, &t), Ok(()));
    }

    #[test]
    fn the_candidate_count_bounds_the_work() {
        // A convex n-gon: every chord is feasible and every apex a
        // candidate, C(n, 3) triangles in all.
        let n = 40;
        let pts = regular_polygon(n);
        let table = decide(&pts, &mut |_| {});
        let all = (n * (n - 1) * (n - 2) / 6) as u64;
        assert_eq!(candidate_count(&table, n), all);
        assert_eq!(
            maxmin(&pts, all - 1, &mut |_| {}),
            Err(NotSelfOverlapping::TooManyCandidates {
                candidates: all,
                limit: all - 1
            })
        );
        assert!(maxmin(&pts, all, &mut |_| {}).is_ok());
    }
}
