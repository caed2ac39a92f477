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
//! Complexity: O(n³) objective evaluations in the worst case (candidates
//! whose sub-polygon values already lose are skipped before the triangle is
//! measured), plus the O(n² log n) exact predicates of the decision DP.
//! Memory: four `n × n` `f64` tables (row-major and transposed copies of the
//! two objective values) and one `n × n` `u32` table of apexes, 36n² bytes:
//! 36 MB at n = 1000, 144 MB at n = 2000.

use crate::geom::Point;
use crate::immersion::dp::for_valid_words;
use crate::immersion::valid::{BitMatrix, CcwRows, HalfPlanes};

const NONE: u32 = u32::MAX;

/// sin² of the smallest angle of the triangle `a, b, c` (a measurement).
#[inline]
pub(crate) fn sin2_min_angle(a: Point, b: Point, c: Point) -> f64 {
    let (ab, bc, ca) = (b - a, c - b, a - c);
    let (x, y, z) = (
        ab.length_squared(),
        bc.length_squared(),
        ca.length_squared(),
    );
    let cross = ab.perp_dot(c - a);
    let big = x.max(y).max(z);
    let mid = if big == x {
        y.max(z)
    } else if big == y {
        x.max(z)
    } else {
        x.max(y)
    };
    let denom = big * mid;
    if denom > 0.0 {
        (cross * cross / denom).min(1.0)
    } else {
        0.0
    }
}

/// Working memory of [`maxmin`] for `n` points, in bytes.
pub(crate) fn memory_bytes(n: usize) -> usize {
    36 * n * n + crate::immersion::dp_memory_bytes(n)
}

/// The max–min-angle triangulation by valid triangles (module docs), or
/// `None` when none exists. `n ≥ 3` is assumed.
pub(crate) fn maxmin(points: &[Point], progress: &mut dyn FnMut(f64)) -> Option<Vec<[u32; 3]>> {
    let n = points.len();
    if n < 3 {
        return None;
    }
    let planes = HalfPlanes::new(points);
    let mut ccw = CcwRows::new(n);
    let mut rows = BitMatrix::new(n);
    let mut cols = BitMatrix::new(n);
    let mut val = vec![f64::NEG_INFINITY; n * n]; // val[i n + j]
    let mut val_t = vec![f64::NEG_INFINITY; n * n]; // val_t[j n + i]
    let mut sum = vec![0.0f64; n * n];
    let mut sum_t = vec![0.0f64; n * n];
    let mut arg = vec![NONE; n * n];
    let total = (n as f64).powi(3) / 6.0 + 1.0;
    let mut done = 0.0;
    for i in (0..n - 1).rev() {
        rows.set(i, i + 1);
        cols.set(i + 1, i);
        val[i * n + i + 1] = f64::INFINITY;
        val_t[(i + 1) * n + i] = f64::INFINITY;
        ccw.compute(points, i);
        for j in i + 2..n {
            let (mut best_v, mut best_s, mut best_k) = (f64::NEG_INFINITY, f64::NEG_INFINITY, NONE);
            {
                let (row_i, col_j) = (rows.row(i), cols.row(j));
                let (vi, vj) = (&val[i * n..(i + 1) * n], &val_t[j * n..(j + 1) * n]);
                let (si, sj) = (&sum[i * n..(i + 1) * n], &sum_t[j * n..(j + 1) * n]);
                for_valid_words(&planes, &ccw.ccw, (row_i, col_j), i, j, |w, bits| {
                    let mut m = bits;
                    while m != 0 {
                        let k = w * 64 + m.trailing_zeros() as usize;
                        m &= m - 1;
                        let lo = vi[k].min(vj[k]);
                        if lo < best_v {
                            continue;
                        }
                        let q = sin2_min_angle(points[i], points[k], points[j]);
                        let v = lo.min(q);
                        let s = si[k] + sj[k] + q;
                        if v > best_v || (v == best_v && s > best_s) {
                            (best_v, best_s, best_k) = (v, s, k as u32);
                        }
                    }
                    false
                });
            }
            if best_k != NONE {
                rows.set(i, j);
                cols.set(j, i);
                val[i * n + j] = best_v;
                val_t[j * n + i] = best_v;
                sum[i * n + j] = best_s;
                sum_t[j * n + i] = best_s;
                arg[i * n + j] = best_k;
            }
        }
        let len = (n - i) as f64;
        done += len * len / 2.0;
        progress((done / total).min(1.0));
    }
    if arg[n - 1] == NONE {
        return None;
    }
    let mut out = Vec::with_capacity(n - 2);
    let mut stack = vec![(0usize, n - 1)];
    while let Some((i, j)) = stack.pop() {
        if j < i + 2 {
            continue;
        }
        let k = arg[i * n + j];
        if k == NONE {
            debug_assert!(false, "max-min DP backtrack hit an empty cell: a bug");
            return None;
        }
        let k = k as usize;
        out.push([i as u32, k as u32, j as u32]);
        stack.push((i, k));
        stack.push((k, j));
    }
    out.sort_unstable();
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::polygon::triangle_angles;

    #[test]
    fn sin2_matches_angles() {
        let (a, b, c) = (
            Point::new(0.0, 0.0),
            Point::new(3.0, 0.2),
            Point::new(1.0, 2.0),
        );
        let m = triangle_angles(a, b, c)
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        assert!((sin2_min_angle(a, b, c) - m.sin().powi(2)).abs() < 1e-12);
    }

    #[test]
    fn regular_polygon_is_triangulated() {
        let pts: Vec<Point> = (0..9)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / 9.0;
                Point::new(a.cos(), a.sin())
            })
            .collect();
        let t = maxmin(&pts, &mut |_| {}).expect("convex");
        assert_eq!(crate::immersion::check(&pts, &t), Ok(()));
    }
}
