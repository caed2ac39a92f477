//! Validity of one triangle of an immersed disk, exactly, and its bitset form.
//!
//! Provenance: docs/design.md §3, after Shor and Van Wyk (*Detecting and
//! Decomposing Self-Overlapping Curves*, ref. \[24\] of Mukherjee & Gopi). A
//! triangle `(a, b, c)` with `a < b < c` (its corners in cyclic polygon order)
//! is *valid* when
//!
//! 1. `orient(p_a, p_b, p_c)` is strictly counter-clockwise, and
//! 2. no vertex fan wraps: at each corner `v`, with the other two corners
//!    `u`, `w` taken in cyclic order after `v`, φ_v(u) < φ_v(w), where φ_v(x)
//!    is the counter-clockwise angle in [0, 2π) from `p_{v+1} − p_v` to
//!    `p_x − p_v`.
//!
//! The definition reads with [`is_fan_order_less`] (the tests evaluate it
//! literally). [`is_valid_triangle`] and the DP use an equivalent form, the
//! DP with per-vertex half-plane masks: for a counter-clockwise triangle the
//! test at
//! `v` fails exactly when `u` lies strictly right of the directed edge
//! `(v, v + 1)` while `w` does not (the angle from `u` to `w` is below π, so
//! it wraps past 2π only when it starts in the open right half-plane).
//!
//! A polygon with a zero-length edge `p_{v+1} = p_v` has no reference
//! direction at `v`; every triangle with a corner at such a `v` is defined to
//! be invalid (cleaned curves have no such edges).

use rayon::prelude::*;

use crate::geom::Point;
#[cfg(doc)]
use crate::geom::predicates::is_fan_order_less;
use crate::geom::predicates::orient;

/// A dense square matrix of bits, row-major, each row a whole number of
/// `u64` words. Index-only; knows nothing about coordinates.
#[derive(Clone, Debug)]
pub(crate) struct BitMatrix {
    words: usize,
    data: Vec<u64>,
}

impl BitMatrix {
    /// An `n × n` matrix of zeros.
    pub(crate) fn new(n: usize) -> Self {
        let words = n.div_ceil(64).max(1);
        Self {
            words,
            data: vec![0; words * n],
        }
    }

    /// Bytes of storage.
    pub(crate) fn bytes(&self) -> usize {
        self.data.len() * 8
    }

    pub(crate) fn row(&self, r: usize) -> &[u64] {
        &self.data[r * self.words..(r + 1) * self.words]
    }

    pub(crate) fn get(&self, r: usize, c: usize) -> bool {
        self.data[r * self.words + c / 64] >> (c % 64) & 1 == 1
    }

    /// The matrix of the same relation after relabelling `v` as
    /// `(v + n − shift) % n`: entry `(r, c)` is entry
    /// `((r + shift) % n, (c + shift) % n)` of this one.
    fn rotated(&self, shift: usize) -> BitMatrix {
        let words = self.words;
        let n = self.data.len() / words;
        let mut out = BitMatrix::new(n);
        if n == 0 {
            return out;
        }
        let shift = shift % n;
        for (r, dst) in out.data.chunks_mut(words).enumerate() {
            let src = self.row((r + shift) % n);
            for (w, d) in dst.iter_mut().enumerate() {
                let len = (n - 64 * w).min(64);
                let start = (64 * w + shift) % n;
                *d = if start + len <= n {
                    read_bits(src, start, len)
                } else {
                    let first = n - start;
                    read_bits(src, start, first) | read_bits(src, 0, len - first) << first
                };
            }
        }
        out
    }

    /// The transpose, by 64 × 64 blocks (rows of blocks in parallel).
    fn transpose(&self) -> BitMatrix {
        let n = self.data.len() / self.words;
        let mut out = BitMatrix::new(n);
        let words = self.words;
        out.data
            .par_chunks_mut(64 * words)
            .enumerate()
            .for_each(|(bx, dst)| {
                // dst holds rows 64 bx .. 64 bx + 64 of the transpose.
                for bv in 0..words {
                    let mut block = [0u64; 64];
                    for (t, b) in block.iter_mut().enumerate() {
                        let v = 64 * bv + t;
                        if v < n {
                            *b = self.data[v * words + bx];
                        }
                    }
                    transpose64(&mut block);
                    for (t, &b) in block.iter().enumerate() {
                        if let Some(d) = dst.get_mut(t * words + bv) {
                            *d = b;
                        }
                    }
                }
            });
        out
    }
}

/// Bits `start .. start + len` (`len` ≤ 64) of a bit row, as the low bits
/// of a word.
fn read_bits(row: &[u64], start: usize, len: usize) -> u64 {
    if len == 0 {
        return 0;
    }
    let (w, o) = (start / 64, start % 64);
    let mut bits = row[w] >> o;
    if o > 0 && w + 1 < row.len() {
        bits |= row[w + 1] << (64 - o);
    }
    if len == 64 {
        bits
    } else {
        bits & ((1u64 << len) - 1)
    }
}

/// Transpose a 64 × 64 bit block in place (bit `c` of word `r` is entry
/// `(r, c)`), by swapping ever smaller sub-blocks.
fn transpose64(a: &mut [u64; 64]) {
    let mut j = 32;
    let mut m: u64 = 0x0000_0000_FFFF_FFFF;
    while j != 0 {
        for k in 0..64 {
            if k & j == 0 {
                let t = ((a[k] >> j) ^ a[k + j]) & m;
                a[k + j] ^= t;
                a[k] ^= t << j;
            }
        }
        j >>= 1;
        m ^= m << j;
    }
}

/// Mask of the bits of word `w` that lie strictly between `lo` and `hi`.
#[inline]
pub(crate) fn open_range_word(w: usize, lo: usize, hi: usize) -> u64 {
    let base = w * 64;
    let start = (lo + 1).saturating_sub(base).min(64);
    let end = hi.saturating_sub(base).min(64);
    if end <= start {
        return 0;
    }
    let upper = if end == 64 {
        u64::MAX
    } else {
        (1u64 << end) - 1
    };
    upper & !((1u64 << start) - 1)
}

/// Per-vertex half-plane masks of a polygon, from O(n²) exact orientations.
///
/// `right.row(v)` = { x : p_x strictly right of the directed edge v → v+1 };
/// `right_t.row(x)` = { v : x ∈ right.row(v) } (the transpose);
/// `bad` = { v : p_{v+1} = p_v } (no reference direction at v).
#[derive(Clone, Debug)]
pub(crate) struct HalfPlanes {
    pub(crate) right: BitMatrix,
    pub(crate) right_t: BitMatrix,
    pub(crate) bad: Vec<u64>,
    pub(crate) bad_flags: Vec<bool>,
}

impl HalfPlanes {
    /// The masks, from n² exact orientations (rows in parallel).
    pub(crate) fn new(points: &[Point]) -> Self {
        let n = points.len();
        let mut right = BitMatrix::new(n);
        let words = right.words;
        let bad_flags: Vec<bool> = (0..n).map(|v| points[v] == points[(v + 1) % n]).collect();
        let mut bad = vec![0u64; words];
        for v in (0..n).filter(|&v| bad_flags[v]) {
            bad[v / 64] |= 1 << (v % 64);
        }
        right
            .data
            .par_chunks_mut(words)
            .enumerate()
            .for_each(|(v, row)| {
                if bad_flags[v] {
                    return;
                }
                let (pv, pn) = (points[v], points[(v + 1) % n]);
                for (w, word) in row.iter_mut().enumerate() {
                    let mut bits = 0u64;
                    for (b, &px) in points.iter().skip(64 * w).take(64).enumerate() {
                        bits |= u64::from(orient(pv, pn, px).is_cw()) << b;
                    }
                    *word = bits;
                }
            });
        let right_t = right.transpose();
        Self {
            right,
            right_t,
            bad,
            bad_flags,
        }
    }

    /// The masks of the same points relabelled, `points[(v + shift) % n]`
    /// becoming vertex `v`, without a single orientation: equal to
    /// `HalfPlanes::new` of the relabelled points.
    pub(crate) fn rotated(&self, shift: usize) -> Self {
        let n = self.bad_flags.len();
        let bad_flags: Vec<bool> = (0..n).map(|v| self.bad_flags[(v + shift) % n]).collect();
        let mut bad = vec![0u64; self.bad.len()];
        for v in (0..n).filter(|&v| bad_flags[v]) {
            bad[v / 64] |= 1 << (v % 64);
        }
        Self {
            right: self.right.rotated(shift),
            right_t: self.right_t.rotated(shift),
            bad,
            bad_flags,
        }
    }

    /// Bytes of storage.
    pub(crate) fn bytes(&self) -> usize {
        self.right.bytes() + self.right_t.bytes() + self.bad.len() * 8
    }

    /// Validity of `(i, k, j)`, `i < k < j`, from the masks and one exact
    /// orientation. Same predicate as [`is_valid_triangle`] (the tests hold
    /// the masks to it); the common decision tests the other curves' apexes
    /// with it.
    pub(crate) fn is_valid(&self, points: &[Point], i: usize, k: usize, j: usize) -> bool {
        if self.bad_flags[i] || self.bad_flags[k] || self.bad_flags[j] {
            return false;
        }
        if !orient(points[i], points[k], points[j]).is_ccw() {
            return false;
        }
        let r = &self.right;
        // Corner v with (u, w) fails iff u ∈ R_v and w ∉ R_v.
        let fails = |v: usize, u: usize, w: usize| r.get(v, u) && !r.get(v, w);
        !(fails(i, k, j) || fails(k, j, i) || fails(j, i, k))
    }

    /// The masks of apexes `k` for which `(i, k, j)` passes the three
    /// corner tests and has no bad corner, given that it is
    /// counter-clockwise (the caller ANDs the counter-clockwise set).
    #[inline]
    pub(crate) fn corners(&self, i: usize, j: usize) -> Corners<'_> {
        Corners {
            ri: self.right.row(i),
            rj: self.right.row(j),
            ti: self.right_t.row(i),
            tj: self.right_t.row(j),
            bad: &self.bad,
            // Corner i (u = k, w = j): fails iff k ∈ R_i and j ∉ R_i.
            keep_i: if self.right.get(i, j) { u64::MAX } else { 0 },
            // Corner j (u = i, w = k): fails iff i ∈ R_j and k ∉ R_j.
            keep_j: if self.right.get(j, i) { 0 } else { u64::MAX },
        }
    }
}

/// Corner-test masks for one chord `(i, j)`; see [`HalfPlanes::corners`].
pub(crate) struct Corners<'a> {
    pub(crate) ri: &'a [u64],
    pub(crate) rj: &'a [u64],
    pub(crate) ti: &'a [u64],
    pub(crate) tj: &'a [u64],
    pub(crate) bad: &'a [u64],
    pub(crate) keep_i: u64,
    pub(crate) keep_j: u64,
}

#[cfg(test)]
impl Corners<'_> {
    /// Word `w` of the mask (the DP inlines the same expression).
    #[inline]
    pub(crate) fn word(&self, w: usize) -> u64 {
        let at_i = !self.ri[w] | self.keep_i;
        let at_j = self.rj[w] | self.keep_j;
        // Corner k (u = j, w = i): fails iff j ∈ R_k and i ∉ R_k.
        let at_k = !(self.tj[w] & !self.ti[w]);
        at_i & at_j & at_k & !self.bad[w]
    }
}

/// True when the triangle `(a, b, c)`, `a < b < c < points.len()`, is a valid
/// triangle of an immersed disk bounded by the closed polygon `points`:
/// strictly counter-clockwise and no vertex fan wraps (module docs).
///
/// Exact. Returns false for indices out of order or out of range, and for a
/// corner `v` with `p_{v+1} = p_v`.
///
/// # Examples
///
/// ```
/// use immerse::geom::Point;
/// use immerse::is_valid_triangle;
/// let square = [Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(1.0, 1.0), Point::new(0.0, 1.0)];
/// assert!(is_valid_triangle(&square, 0, 1, 2));
/// assert!(!is_valid_triangle(&square, 2, 1, 0));
/// ```
pub fn is_valid_triangle(points: &[Point], a: usize, b: usize, c: usize) -> bool {
    let n = points.len();
    if !(a < b && b < c && c < n) {
        return false;
    }
    // Each corner and the vertex after it (index arithmetic without a
    // division: this runs for every triangle of every checked sample).
    let next = |v: usize| points[if v + 1 == n { 0 } else { v + 1 }];
    let (pa, pb, pc) = (points[a], points[b], points[c]);
    let (qa, qb, qc) = (next(a), next(b), next(c));
    if pa == qa || pb == qb || pc == qc {
        return false;
    }
    if !orient(pa, pb, pc).is_ccw() {
        return false;
    }
    // With the triangle counter-clockwise, the fan order φ_v(u) < φ_v(w)
    // at corner v fails exactly when u is strictly right of the edge
    // v → v+1 and w is not (the masks of the decision DP use the same
    // rule; the tests hold both to the fan-order definition): two exact
    // orientations per corner.
    let right = |v: Point, after: Point, x: Point| orient(v, after, x).is_cw();
    let fails =
        |v: Point, after: Point, u: Point, w: Point| right(v, after, u) && !right(v, after, w);
    !(fails(pa, qa, pb, pc) || fails(pb, qb, pc, pa) || fails(pc, qc, pa, pb))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::predicates::is_fan_order_less;

    /// The test kit's xorshift64 stream from `seed`.
    fn rng(seed: u64) -> impl FnMut() -> u64 {
        let mut s = seed | 1;
        move || testkit::rng::xorshift64(&mut s)
    }

    #[test]
    fn open_range_word_masks() {
        assert_eq!(open_range_word(0, 0, 3), 0b110);
        assert_eq!(open_range_word(0, 5, 6), 0);
        assert_eq!(open_range_word(1, 0, 200), u64::MAX);
        assert_eq!(open_range_word(1, 63, 65), 1);
        assert_eq!(open_range_word(2, 0, 100), 0);
    }

    /// The definition: counter-clockwise and the fan order holds at each
    /// corner (module docs).
    fn by_fan_order(points: &[Point], a: usize, b: usize, c: usize) -> bool {
        let n = points.len();
        let p = |v: usize| points[v];
        let next = |v: usize| points[(v + 1) % n];
        if [a, b, c].iter().any(|&v| p(v) == next(v)) {
            return false;
        }
        orient(p(a), p(b), p(c)).is_ccw()
            && is_fan_order_less(p(a), next(a), p(b), p(c))
            && is_fan_order_less(p(b), next(b), p(c), p(a))
            && is_fan_order_less(p(c), next(c), p(a), p(b))
    }

    /// Asserts that [`is_valid_triangle`] and the corner masks of `hp`
    /// (k's bit in the corners of i and j, neither end without a
    /// reference direction) answer for the triangle (i, k, j) as
    /// [`by_fan_order`]; returns that answer.
    fn agrees_with_the_definition(
        pts: &[Point],
        hp: &HalfPlanes,
        i: usize,
        k: usize,
        j: usize,
    ) -> bool {
        let exact = by_fan_order(pts, i, k, j);
        assert_eq!(is_valid_triangle(pts, i, k, j), exact, "i={i} j={j} k={k}");
        let bit = orient(pts[i], pts[k], pts[j]).is_ccw()
            && !hp.bad_flags[i]
            && !hp.bad_flags[j]
            && hp.corners(i, j).word(k / 64) >> (k % 64) & 1 == 1;
        assert_eq!(bit, exact, "i={i} j={j} k={k}");
        exact
    }

    #[test]
    fn masks_agree_with_the_definition() {
        // Small integer grids: many collinear and coincident points.
        let mut r = rng(7);
        for round in 0..400 {
            let n = 3 + (r() % 12) as usize;
            let g = if round % 2 == 0 { 4 } else { 1000 };
            let pts: Vec<Point> = (0..n)
                .map(|_| {
                    let (x, y) = ((r() % g) as f64, (r() % g) as f64);
                    match round % 4 {
                        // Nearly collinear: a line nudged by a few ulps.
                        1 => {
                            let y = 0.1 * x + 0.3;
                            Point::new(x, f64::from_bits(y.to_bits() + r() % 3) - 1e-17)
                        }
                        // Large magnitudes, still safe for the predicates.
                        3 => Point::new(x * 1e150, -y * 1e150),
                        _ => Point::new(x, y),
                    }
                })
                .collect();
            let hp = HalfPlanes::new(&pts);
            for i in 0..n {
                for j in i + 1..n {
                    for k in i + 1..j {
                        let exact = agrees_with_the_definition(&pts, &hp, i, k, j);
                        assert_eq!(hp.is_valid(&pts, i, k, j), exact, "{pts:?} {i} {k} {j}");
                    }
                }
            }
        }
    }

    #[test]
    fn multi_word_masks_and_transpose_agree_with_the_definition() {
        let mut r = rng(99);
        for n in [150, 200] {
            let pts: Vec<Point> = (0..n)
                .map(|_| Point::new((r() % 50) as f64, (r() % 50) as f64))
                .collect();
            let hp = HalfPlanes::new(&pts);
            for v in 0..n {
                for x in 0..n {
                    let pn = pts[(v + 1) % n];
                    let right = pts[v] != pn && orient(pts[v], pn, pts[x]).is_cw();
                    assert_eq!(hp.right.get(v, x), right, "v={v} x={x}");
                    assert_eq!(hp.right_t.get(x, v), right, "v={v} x={x}");
                }
            }
            for i in [0, 1, 62, 63, 64, 65, 100, 127, 128, 140] {
                for j in i + 2..n {
                    for k in i + 1..j {
                        agrees_with_the_definition(&pts, &hp, i, k, j);
                    }
                }
            }
        }
    }

    #[test]
    fn rotated_masks_are_the_masks_of_the_rotated_points() {
        let mut r = rng(11);
        for n in [1usize, 3, 5, 63, 64, 65, 130, 200] {
            // Coarse grid: collinear points and repeated neighbours.
            let pts: Vec<Point> = (0..n)
                .map(|_| Point::new((r() % 6) as f64, (r() % 6) as f64))
                .collect();
            let hp = HalfPlanes::new(&pts);
            for shift in [0, 1, n / 2, n.saturating_sub(1), 64 % n.max(1), 3 * n + 7] {
                let rot: Vec<Point> = (0..n).map(|v| pts[(v + shift) % n]).collect();
                let want = HalfPlanes::new(&rot);
                let got = hp.rotated(shift);
                assert_eq!(got.right.data, want.right.data, "n={n} shift={shift}");
                assert_eq!(got.right_t.data, want.right_t.data, "n={n} shift={shift}");
                assert_eq!(got.bad, want.bad, "n={n} shift={shift}");
                assert_eq!(got.bad_flags, want.bad_flags, "n={n} shift={shift}");
            }
        }
    }

    #[test]
    fn block_transpose() {
        let mut r = rng(3);
        let mut a = [0u64; 64];
        for w in &mut a {
            *w = r();
        }
        let mut t = a;
        transpose64(&mut t);
        for (x, &row) in t.iter().enumerate() {
            for (y, &orig) in a.iter().enumerate() {
                assert_eq!(row >> y & 1, orig >> x & 1);
            }
        }
    }
}
