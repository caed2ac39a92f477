//! The interval DP that decides whether a polygon bounds an immersed disk
//! and returns a witness triangulation.
//!
//! Provenance: the classic O(n³) polygon-triangulation DP over sub-chains, used
//! for self-overlapping curves by Shor and Van Wyk (*Detecting and Decomposing
//! Self-Overlapping Curves*, ref. \[24\] of Mukherjee & Gopi); the bitset
//! formulation is docs/design.md §3.
//!
//! `Q[i][j]` (i < j) is true when the sub-polygon `i, i+1, …, j` closed by the
//! chord `j → i` has a triangulation by valid triangles whose diagonals all
//! pass [`may_be_diagonal`]: `Q[i][i+1]` is true and `Q[i][j] =
//! D(i, j) ∧ ∨_{i<k<j} Q[i][k] ∧ Q[k][j] ∧ valid(i, k, j)`. The filter `D` is
//! a necessary condition, from the half-plane masks alone, for a chord to be
//! a diagonal of *some* valid triangulation of the whole polygon, so
//! `Q[0][n−1]` is exactly the answer of the unfiltered DP (every sub-polygon
//! of a valid triangulation passes it), while most chords are refused in
//! O(1).
//!
//! The rows `Q[i][·]` and the columns `Q[·][j]` are bitsets, each with a
//! summary (one bit per nonzero word), so a cell visits only the words where
//! both its row and its column have bits; in them the corner tests are word
//! operations ([`HalfPlanes::corners`]) and the surviving apexes `k` get one
//! exact orientation each. A true cell stops at its first valid apex.
//!
//! Cells are filled by square tiles along anti-diagonals of tiles: every
//! operand of a tile lies in a tile of a smaller anti-diagonal or in the tile
//! itself (filled rows downwards, columns upwards), so the tiles of one
//! anti-diagonal run in parallel (rayon). The witness is read back from the
//! table by the same apex search.
//!
//! Complexity: O(n²) exact orientations for the masks (parallel), O(n³/64)
//! word operations in the worst case for the DP (far fewer in practice: the
//! filter and the summaries skip most of them), O(n) apex searches for the
//! witness. Memory: four n × n bit matrices (`Q` rows and columns, the
//! half-plane masks and their transpose) and the summaries, about n²/2 bytes
//! ([`super::dp_memory_bytes`]): 200 MB at n = 20,000.

use std::sync::atomic::{AtomicU64, Ordering::Relaxed};

use rayon::prelude::*;

use super::valid::{HalfPlanes, open_range_word};
use crate::geom::{Point, orient};

/// A matrix of bits that threads fill concurrently (each bit is only ever
/// set, never cleared). Rows are a whole number of `u64` words.
pub(crate) struct SharedBits {
    words: usize,
    data: Vec<AtomicU64>,
}

impl SharedBits {
    /// `rows` rows of `cols` zero bits.
    pub(crate) fn new(rows: usize, cols: usize) -> Self {
        let words = cols.div_ceil(64).max(1);
        Self {
            words,
            data: (0..words * rows).map(|_| AtomicU64::new(0)).collect(),
        }
    }

    /// Bytes of storage.
    pub(crate) fn bytes(&self) -> usize {
        self.data.len() * 8
    }

    #[inline]
    pub(crate) fn word(&self, r: usize, w: usize) -> u64 {
        self.data[r * self.words + w].load(Relaxed)
    }

    #[inline]
    pub(crate) fn get(&self, r: usize, c: usize) -> bool {
        self.word(r, c / 64) >> (c % 64) & 1 == 1
    }

    #[inline]
    pub(crate) fn set(&self, r: usize, c: usize) {
        self.data[r * self.words + c / 64].fetch_or(1 << (c % 64), Relaxed);
    }

    #[inline]
    pub(crate) fn row(&self, r: usize) -> &[AtomicU64] {
        &self.data[r * self.words..(r + 1) * self.words]
    }
}

/// The filled DP table.
pub(crate) struct Table {
    /// `rows.get(i, j)` = Q[i][j].
    pub(crate) rows: SharedBits,
    /// `cols.get(j, i)` = Q[i][j].
    pub(crate) cols: SharedBits,
    /// `row_sum.get(i, w)`: word `w` of row `i` of `rows` is nonzero.
    row_sum: SharedBits,
    /// `col_sum.get(j, w)`: word `w` of row `j` of `cols` is nonzero.
    col_sum: SharedBits,
    /// Bounding box `[min x, min y, max x, max y]` of the points of each
    /// word (64 consecutive vertices).
    boxes: Vec<[f64; 4]>,
    pub(crate) planes: HalfPlanes,
    /// The half-plane masks of the other curves of a common decision
    /// ([`decide_common`]; empty for one curve).
    others: Vec<HalfPlanes>,
}

/// Where the points of one word lie relative to a directed line.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    /// All strictly right: every apex there is counter-clockwise.
    Right,
    /// None strictly right: no apex there is counter-clockwise.
    Left,
    /// Some of each, or unknown: test apex by apex.
    Mixed,
}

impl Table {
    fn new(points: &[Point]) -> Self {
        Self::with_planes(points, HalfPlanes::new(points))
    }

    /// [`Table::new`] with the half-plane masks of `points` given.
    fn with_planes(points: &[Point], planes: HalfPlanes) -> Self {
        let n = points.len();
        let words = n.div_ceil(64).max(1);
        Self {
            rows: SharedBits::new(n, n),
            cols: SharedBits::new(n, n),
            row_sum: SharedBits::new(n, words),
            col_sum: SharedBits::new(n, words),
            boxes: points
                .chunks(64)
                .map(|c| {
                    c.iter().fold(
                        [f64::INFINITY, f64::INFINITY, -f64::INFINITY, -f64::INFINITY],
                        |[a, b, c, d], p| [a.min(p.x), b.min(p.y), c.max(p.x), d.max(p.y)],
                    )
                })
                .collect(),
            planes,
            others: Vec::new(),
        }
    }

    /// Bytes of storage.
    pub(crate) fn bytes(&self) -> usize {
        self.rows.bytes()
            + self.cols.bytes()
            + self.row_sum.bytes()
            + self.col_sum.bytes()
            + self.boxes.len() * 32
            + self.planes.bytes()
            + self.others.iter().map(HalfPlanes::bytes).sum::<usize>()
    }

    /// Q[i][j].
    pub(crate) fn get(&self, i: usize, j: usize) -> bool {
        self.rows.get(i, j)
    }

    fn set(&self, i: usize, j: usize) {
        self.rows.set(i, j);
        self.cols.set(j, i);
        self.row_sum.set(i, j / 64);
        self.col_sum.set(j, i / 64);
    }

    /// Necessary for the chord `(i, j)`, `i + 2 ≤ j`, to be a diagonal of a
    /// valid triangulation of the whole polygon (module docs), from mask
    /// bits only. In such a triangulation the neighbours of `i`, in cyclic
    /// order after `i`, have increasing fan angles from `i + 1` (angle 0) to
    /// `i − 1`, so 0 < φ_i(j) < φ_i(i − 1), and likewise 0 < φ_j(i) <
    /// φ_j(j − 1). With `R_v` the points strictly right of the edge
    /// `v → v + 1`: when `i − 1` is not in `R_i` (a convex or straight
    /// corner), `j` must be strictly left of the edge `i → i + 1` and not
    /// right of the line `i − 1 → i`; when it is (a reflex corner), `j` must
    /// avoid one of the two right half-planes. The test is relaxed where a
    /// point lies on one of those lines, which only keeps more chords.
    #[inline]
    pub(crate) fn may_be_diagonal(&self, i: usize, j: usize) -> bool {
        may_be_diagonal(&self.planes, i, j) && self.others.iter().all(|p| may_be_diagonal(p, i, j))
    }

    /// Which side of the directed line `a → b` the points of word `w`
    /// lie on, from two exact orientations of corners of their box: the
    /// corner furthest right decides "none strictly right", the one
    /// furthest left "all strictly right". (`orient(p_i, p_k, p_j)` is
    /// counter-clockwise exactly when `p_k` is strictly right of
    /// `p_i → p_j`.)
    #[inline]
    fn side(&self, w: usize, a: Point, b: Point) -> Side {
        let [x0, y0, x1, y1] = self.boxes[w];
        // The signs of the differences are exact, so the corners are too.
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        // Right normal (dy, −dx): its largest projection.
        let far = Point::new(
            if dy >= 0.0 { x1 } else { x0 },
            if dx <= 0.0 { y1 } else { y0 },
        );
        if !orient(a, b, far).is_cw() {
            return Side::Left;
        }
        let near = Point::new(
            if dy >= 0.0 { x0 } else { x1 },
            if dx <= 0.0 { y0 } else { y1 },
        );
        if orient(a, b, near).is_cw() {
            Side::Right
        } else {
            Side::Mixed
        }
    }

    /// Visit the candidate apexes `k ∈ (i, j)`: those with `Q[i][k]`,
    /// `Q[k][j]` and the corner tests passed, in increasing order, until
    /// `f` returns true; returns whether it did. `f(k, ccw)` gets
    /// `ccw = true` when `(i, k, j)` is known to be counter-clockwise, hence
    /// valid; otherwise the caller must test [`is_ccw`] itself before using
    /// `k` (it may first rule `k` out more cheaply).
    #[inline]
    pub(crate) fn for_candidates(
        &self,
        points: &[Point],
        i: usize,
        j: usize,
        mut f: impl FnMut(usize, bool) -> bool,
    ) -> bool {
        let planes = &self.planes;
        if planes.bad_flags[i] || planes.bad_flags[j] {
            return false;
        }
        let c = planes.corners(i, j);
        let (first, last) = ((i + 1) / 64, (j - 1) / 64);
        let (row, col) = (self.rows.row(i), self.cols.row(j));
        let (rs, cs) = (self.row_sum.row(i), self.col_sum.row(j));
        let (pi, pj) = (points[i], points[j]);
        for s in first / 64..=last / 64 {
            let mut m = rs[s].load(Relaxed) & cs[s].load(Relaxed);
            while m != 0 {
                let w = s * 64 + m.trailing_zeros() as usize;
                m &= m - 1;
                if w < first || w > last {
                    continue;
                }
                let at_i = !c.ri[w] | c.keep_i;
                let at_j = c.rj[w] | c.keep_j;
                // Corner k (u = j, w = i): fails iff j ∈ R_k and i ∉ R_k.
                let at_k = !(c.tj[w] & !c.ti[w]);
                let mut bits =
                    row[w].load(Relaxed) & col[w].load(Relaxed) & at_i & at_j & at_k & !c.bad[w];
                if w == first || w == last {
                    bits &= open_range_word(w, i, j);
                }
                if bits == 0 {
                    continue;
                }
                let side = self.side(w, pi, pj);
                if side == Side::Left {
                    continue;
                }
                while bits != 0 {
                    let k = w * 64 + bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    if f(k, side == Side::Right) {
                        return true;
                    }
                }
            }
        }
        false
    }

    /// The smallest valid apex of a true cell (the witness's choice):
    /// valid on `curves[0]` (the table's curve) and on each other curve
    /// of a common decision, and passing `keep`.
    fn apex(
        &self,
        curves: &[&[Point]],
        keep: &(dyn Fn(usize, usize, usize) -> bool + Sync),
        i: usize,
        j: usize,
    ) -> Option<usize> {
        let points = curves[0];
        let mut found = None;
        self.for_candidates(points, i, j, |k, ccw| {
            if (ccw || is_ccw(points, i, k, j))
                && curves[1..]
                    .iter()
                    .zip(&self.others)
                    .all(|(c, planes)| planes.is_valid(c, i, k, j))
                && keep(i, k, j)
            {
                found = Some(k);
            }
            found.is_some()
        });
        found
    }
}

/// [`Table::may_be_diagonal`] for one curve's masks.
#[inline]
fn may_be_diagonal(planes: &HalfPlanes, i: usize, j: usize) -> bool {
    let r = &planes.right;
    let n = planes.bad_flags.len();
    if i == 0 && j == n - 1 {
        return true;
    }
    let corner = |v: usize, prev: usize, x: usize| {
        let (a, b) = (r.get(v, x), r.get(prev, x));
        if r.get(v, prev) { !(a && b) } else { !(a || b) }
    };
    let prev_i = if i == 0 { n - 1 } else { i - 1 };
    corner(i, prev_i, j) && corner(j, j - 1, i)
}

/// Exact: is the triangle `(i, k, j)` counter-clockwise?
#[inline]
pub(crate) fn is_ccw(points: &[Point], i: usize, k: usize, j: usize) -> bool {
    orient(points[i], points[k], points[j]).is_ccw()
}

/// Side of the square tiles of the parallel fill for `n` points: a
/// multiple of 64, so tiles never share a word of the bit matrices, at
/// most 256 (tiles stay in cache), and small enough that there are a dozen
/// or more tiles a side for the threads to share.
fn tile_side(n: usize) -> usize {
    (n / 12 / 64 * 64).clamp(64, 256)
}

/// Fill the cells `(i, j)`, `i + 2 ≤ j < n`, by calling `cell(i, j)`, tile
/// by tile along anti-diagonals of tiles (module docs): when `cell(i, j)`
/// runs, every `(i, k)` and `(k, j)` with `i < k < j` has been filled and
/// its writes are visible. Tiles of one anti-diagonal run in parallel.
/// `progress` receives the fraction done after each anti-diagonal.
pub(crate) fn fill_by_tiles(
    n: usize,
    progress: &mut dyn FnMut(f64),
    cell: impl Fn(usize, usize) + Sync,
) {
    let tile = tile_side(n);
    let nb = n.div_ceil(tile);
    // Work of a tile grows with its span: weigh anti-diagonal d by its
    // tiles times (d + 1).
    let weight = |d: usize| ((nb - d) * (d + 1)) as f64;
    let total: f64 = (0..nb).map(weight).sum::<f64>().max(1.0);
    let mut done = 0.0;
    for d in 0..nb {
        (0..nb - d).into_par_iter().for_each(|bi| {
            let bj = bi + d;
            let (i0, i1) = (bi * tile, ((bi + 1) * tile).min(n));
            let (j0, j1) = (bj * tile, ((bj + 1) * tile).min(n));
            for i in (i0..i1).rev() {
                for j in j0.max(i + 2)..j1 {
                    cell(i, j);
                }
            }
        });
        done += weight(d);
        progress((done / total).min(1.0));
    }
}

/// Fill the decision table. `progress` receives the fraction of work done.
pub(crate) fn decide(points: &[Point], progress: &mut dyn FnMut(f64)) -> Table {
    decide_common(&[points], progress)
}

/// Fill the decision table for triangulations valid on every curve of
/// `curves` at once (same length; vertex `v` of each corresponds): a
/// chord passes the diagonal filter of each curve and an apex counts when
/// its triangle is valid on each, so `Q[0][n−1]` says whether the curves
/// have a common (compatible) immersion triangulation. With one curve this
/// is the decision DP of the module docs.
pub(crate) fn decide_common(curves: &[&[Point]], progress: &mut dyn FnMut(f64)) -> Table {
    let planes = curves.iter().map(|c| HalfPlanes::new(c)).collect();
    decide_common_with(curves, planes, &ANY, progress)
}

/// A triangle test that keeps every triangle: the plain decision.
pub(crate) const ANY: fn(usize, usize, usize) -> bool = |_, _, _| true;

/// [`decide_common`] with the half-plane masks of every curve given (in
/// the order of `curves`): a search over relabellings of one curve
/// computes them once and rotates them ([`HalfPlanes::rotated`]). A
/// triangle `(i, k, j)`, `i < k < j`, counts only where it is valid on
/// every curve and `keep(i, k, j)` holds too (a further test of the
/// caller's: [`ANY`] for none); the witness must be taken with the same
/// `keep`.
pub(crate) fn decide_common_with(
    curves: &[&[Point]],
    mut planes: Vec<HalfPlanes>,
    keep: &(dyn Fn(usize, usize, usize) -> bool + Sync),
    progress: &mut dyn FnMut(f64),
) -> Table {
    let points = curves[0];
    let n = points.len();
    debug_assert!(curves.iter().all(|c| c.len() == n));
    debug_assert_eq!(planes.len(), curves.len());
    let others = planes.split_off(1);
    let Some(first) = planes.pop() else {
        return Table::new(points);
    };
    let mut table = Table::with_planes(points, first);
    debug_assert_eq!(table.bytes(), super::dp_memory_bytes(n));
    table.others = others;
    for i in 0..n.saturating_sub(1) {
        table.set(i, i + 1);
    }
    fill_by_tiles(n, progress, |i, j| {
        if table.may_be_diagonal(i, j) && table.apex(curves, keep, i, j).is_some() {
            table.set(i, j);
        }
    });
    table
}

/// A triangulation of the whole polygon from a filled table, or `None` when
/// `Q[0][n−1]` is false. Triangles come out as `[i, k, j]`, `i < k < j`.
pub(crate) fn witness(points: &[Point], table: &Table) -> Option<Vec<[u32; 3]>> {
    witness_common(&[points], table, &ANY)
}

/// [`witness`] for a table of [`decide_common_with`]: every triangle is
/// valid on every curve and passes `keep` (the test the table was filled
/// with).
pub(crate) fn witness_common(
    curves: &[&[Point]],
    table: &Table,
    keep: &(dyn Fn(usize, usize, usize) -> bool + Sync),
) -> Option<Vec<[u32; 3]>> {
    let n = curves[0].len();
    if n < 3 || !table.get(0, n - 1) {
        return None;
    }
    from_apexes(n, |i, j| {
        debug_assert!(table.get(i, j), "the witness reached a false cell: a bug");
        table.apex(curves, keep, i, j)
    })
}

/// The triangulation of the n-gon that an interval DP chose: from the
/// chord (0, n − 1) down, the triangle `[i, k, j]` on each chord (i, j)
/// with `k = apex(i, j)`, then the chords (i, k) and (k, j). `None` when
/// `apex` has none for a chord it reaches.
pub(crate) fn from_apexes(
    n: usize,
    mut apex: impl FnMut(usize, usize) -> Option<usize>,
) -> Option<Vec<[u32; 3]>> {
    let mut out = Vec::with_capacity(n.saturating_sub(2));
    let mut stack = vec![(0usize, n - 1)];
    while let Some((i, j)) = stack.pop() {
        if j < i + 2 {
            continue;
        }
        let k = apex(i, j)?;
        out.push([i as u32, k as u32, j as u32]);
        stack.push((i, k));
        stack.push((k, j));
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::predicates::is_fan_order_less;

    /// The exact cone condition that [`Table::may_be_diagonal`] relaxes:
    /// 0 < φ_v(x) < φ_v(v − 1) at both ends of the chord.
    fn in_cone(points: &[Point], v: usize, x: usize) -> bool {
        let n = points.len();
        let (next, prev) = (points[(v + 1) % n], points[(v + n - 1) % n]);
        is_fan_order_less(points[v], next, next, points[x])
            && is_fan_order_less(points[v], next, points[x], prev)
    }

    #[test]
    fn the_diagonal_filter_keeps_every_chord_in_both_cones() {
        let mut s = 17u64;
        let mut r = move || testkit::rng::xorshift64(&mut s);
        let mut kept = 0;
        for round in 0..500 {
            let n = 4 + (r() % 70) as usize;
            let g = if round % 2 == 0 { 5 } else { 1000 };
            let pts: Vec<Point> = (0..n)
                .map(|_| Point::new((r() % g) as f64, (r() % g) as f64))
                .collect();
            let table = Table::new(&pts);
            for i in 0..n {
                for j in i + 2..n {
                    if in_cone(&pts, i, j) && in_cone(&pts, j, i) {
                        assert!(table.may_be_diagonal(i, j), "{pts:?} {i} {j}");
                        kept += 1;
                    }
                }
            }
        }
        assert!(kept > 1000, "{kept}");
    }
}
