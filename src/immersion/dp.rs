//! The interval DP that decides whether a polygon bounds an immersed disk
//! and returns a witness triangulation.
//!
//! Provenance: the classic O(n³) polygon-triangulation DP over sub-chains, used
//! for self-overlapping curves by Shor and Van Wyk (*Detecting and Decomposing
//! Self-Overlapping Curves*, ref. \[24\] of Mukherjee & Gopi); the bitset
//! formulation is docs/design.md §3.
//!
//! `Q[i][j]` (i < j) is true when the sub-polygon `i, i+1, …, j` closed by the
//! chord `j → i` has a triangulation by valid triangles: `Q[i][i+1]` is true
//! and `Q[i][j] = ∨_{i<k<j} Q[i][k] ∧ Q[k][j] ∧ valid(i, k, j)`. The rows
//! `Q[i][·]` and the columns `Q[·][j]` are kept as bitsets, and for fixed
//! `(i, j)` the valid apexes `k` are a bitset too (the counter-clockwise set
//! from [`CcwRows`], the corner masks from [`HalfPlanes`]), so each cell costs
//! O((j − i)/64) word operations. Rows are filled from `i = n − 1` down to 0
//! and, inside a row, `j` upwards, so every operand is ready when read and
//! the counter-clockwise sets are only ever needed for one row at a time.
//!
//! Complexity: O(n² log n) exact orientations for the angular sorts and the
//! half-plane masks, O(n³/64) word operations for the DP, O(n²) exact tests
//! for the witness. Memory: five `n × n` bit matrices (`Q` rows, `Q`
//! columns, the half-plane masks and their transpose, the counter-clockwise
//! sets of the current row), i.e. 5n²/8 bytes: 0.6 MB at n = 1000, 2.5 MB at
//! n = 2000.

use super::valid::{BitMatrix, CcwRows, HalfPlanes, open_range_word};
use crate::geom::Point;

/// The filled DP tables.
pub(crate) struct Table {
    /// `rows.get(i, j)` = Q[i][j].
    pub(crate) rows: BitMatrix,
    /// `cols.get(j, i)` = Q[i][j].
    pub(crate) cols: BitMatrix,
    /// The half-plane masks of each curve the table was filled for.
    pub(crate) planes: Vec<HalfPlanes>,
}

/// Visit the apexes `k ∈ (i, j)` with `(i, k, j)` valid and bits set in
/// both `row` and `col` (`Q[i][k]` and `Q[k][j]`), word by word: `f(w, bits)`
/// gets the word index and the mask. Stops when `f` returns true; returns
/// whether it did.
#[inline]
pub(crate) fn for_valid_words(
    planes: &HalfPlanes,
    ccw: &BitMatrix,
    (row, col): (&[u64], &[u64]),
    i: usize,
    j: usize,
    mut f: impl FnMut(usize, u64) -> bool,
) -> bool {
    if planes.bad_flags[i] || planes.bad_flags[j] {
        return false;
    }
    let c = planes.corners(i, j);
    let (first, last) = ((i + 1) / 64, (j - 1) / 64);
    let r = first..last + 1;
    // Equal-length slices over the word range: no bounds checks inside.
    let ccw = &ccw.row(j)[r.clone()];
    let len = ccw.len();
    let (row, col) = (&row[r.clone()][..len], &col[r.clone()][..len]);
    let (ri, rj) = (&c.ri[r.clone()][..len], &c.rj[r.clone()][..len]);
    let (ti, tj) = (&c.ti[r.clone()][..len], &c.tj[r.clone()][..len]);
    let bad = &c.bad[r][..len];
    for t in 0..len {
        let at_i = !ri[t] | c.keep_i;
        let at_j = rj[t] | c.keep_j;
        // Corner k (u = j, w = i): fails iff j ∈ R_k and i ∉ R_k.
        let at_k = !(tj[t] & !ti[t]);
        let mut bits = row[t] & col[t] & ccw[t] & at_i & at_j & at_k & !bad[t];
        if bits != 0 {
            if t == 0 || t == len - 1 {
                bits &= open_range_word(first + t, i, j);
            }
            if bits != 0 && f(first + t, bits) {
                return true;
            }
        }
    }
    false
}

/// Fill the decision table. `progress` receives the fraction of work done.
pub(crate) fn decide(points: &[Point], progress: &mut dyn FnMut(f64)) -> Table {
    decide_common(&[points], progress)
}

/// Fill the decision table for triangulations valid on every curve of
/// `curves` at once (same length, vertex `v` of each corresponds): a
/// triangle is allowed when it is valid on each curve, so `Q[0][n−1]` says
/// whether the curves have a common (compatible) immersion
/// triangulation. With one curve this is the decision DP above; with more,
/// the apex set of each chord is narrowed curve by curve.
pub(crate) fn decide_common(curves: &[&[Point]], progress: &mut dyn FnMut(f64)) -> Table {
    let points = curves[0];
    let n = points.len();
    debug_assert!(curves.iter().all(|c| c.len() == n));
    let planes: Vec<HalfPlanes> = curves.iter().map(|c| HalfPlanes::new(c)).collect();
    let mut rows = BitMatrix::new(n);
    let mut cols = BitMatrix::new(n);
    let mut ccw: Vec<CcwRows> = curves.iter().map(|_| CcwRows::new(n)).collect();
    debug_assert!(
        curves.len() > 1
            || rows.bytes() + cols.bytes() + planes[0].bytes() + ccw[0].bytes()
                == super::dp_memory_bytes(n)
    );
    // The apexes that passed the curves so far (only with several curves).
    let mut narrowed = vec![0u64; if curves.len() > 1 { rows.words() } else { 0 }];
    let mut spare = narrowed.clone();
    let total = (n as f64).powi(3) / 6.0 + 1.0;
    let mut done = 0.0;
    for i in (0..n.saturating_sub(1)).rev() {
        rows.set(i, i + 1);
        cols.set(i + 1, i);
        for (c, rows_c) in curves.iter().zip(ccw.iter_mut()) {
            rows_c.compute(c, i);
        }
        for j in i + 2..n {
            let rc = (rows.row(i), cols.row(j));
            let found = if curves.len() == 1 {
                for_valid_words(&planes[0], &ccw[0].ccw, rc, i, j, |_, _| true)
            } else {
                narrowed.fill(0);
                let mut any = false;
                for_valid_words(&planes[0], &ccw[0].ccw, rc, i, j, |w, bits| {
                    narrowed[w] = bits;
                    any = true;
                    false
                });
                let last = curves.len() - 1;
                let mut found = any;
                for c in (1..curves.len()).take_while(|_| any) {
                    spare.fill(0);
                    let (prev, next) = (&narrowed, &mut spare);
                    // The last curve stops at the first apex left.
                    found = false;
                    for_valid_words(&planes[c], &ccw[c].ccw, (prev, rc.1), i, j, |w, bits| {
                        next[w] = bits;
                        found = true;
                        c == last
                    });
                    std::mem::swap(&mut narrowed, &mut spare);
                    if !found {
                        break;
                    }
                }
                found
            };
            if found {
                rows.set(i, j);
                cols.set(j, i);
            }
        }
        let len = (n - i) as f64;
        done += len * len / 2.0;
        progress((done / total).min(1.0));
    }
    Table { rows, cols, planes }
}

/// A triangulation of the whole polygon from a filled table, or `None` when
/// `Q[0][n−1]` is false. Triangles come out as `[i, k, j]`, `i < k < j`.
pub(crate) fn witness(points: &[Point], table: &Table) -> Option<Vec<[u32; 3]>> {
    witness_common(&[points], table)
}

/// [`witness`] for a table of [`decide_common`]: every triangle is valid on
/// every curve.
pub(crate) fn witness_common(curves: &[&[Point]], table: &Table) -> Option<Vec<[u32; 3]>> {
    let n = curves[0].len();
    if n < 3 || !table.rows.get(0, n - 1) {
        return None;
    }
    let mut out = Vec::with_capacity(n - 2);
    let mut stack = vec![(0usize, n - 1)];
    while let Some((i, j)) = stack.pop() {
        if j < i + 2 {
            continue;
        }
        let k = (i + 1..j).find(|&k| {
            table.rows.get(i, k)
                && table.cols.get(j, k)
                && curves
                    .iter()
                    .zip(&table.planes)
                    .all(|(c, planes)| planes.is_valid(c, i, k, j))
        })?;
        out.push([i as u32, k as u32, j as u32]);
        stack.push((i, k));
        stack.push((k, j));
    }
    Some(out)
}
