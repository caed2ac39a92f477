//! Flip sequences between two triangulations of the abstract n-gon
//! (seed 004 §6.2; DESIGN.md §7). Index-only: no coordinates.
//!
//! Two diagonals cross when their endpoints interleave around the polygon.
//! The target's diagonals are sorted by how many of the source's they
//! cross and inserted in that order; inserting (x, y) repeatedly flips the
//! diagonal of the triangle at x that (x, y) enters. Each flip removes
//! exactly one crossing with (x, y), so an insertion costs exactly its
//! number of crossings at that moment, and an inserted diagonal is never
//! flipped again (target diagonals do not cross each other).

use std::collections::HashMap;

/// A triangulation of the abstract n-gon that can be flipped.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FlipTriangulation {
    n: u32,
    triangles: Vec<[u32; 3]>,
    /// For each edge (min, max), the triangles containing it.
    edges: HashMap<(u32, u32), [u32; 2]>,
}

/// One flip: the diagonal `from` is replaced by `to` in the quad they
/// share.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Flip {
    /// The diagonal removed, `(min, max)`.
    pub from: (u32, u32),
    /// The diagonal added, `(min, max)`.
    pub to: (u32, u32),
}

const NONE: u32 = u32::MAX;

fn key(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

/// Rotates a triangle so its smallest corner is first (keeps cyclic order).
pub(crate) fn canonical(mut t: [u32; 3]) -> [u32; 3] {
    while t[0] > t[1] || t[0] > t[2] {
        t = [t[1], t[2], t[0]];
    }
    t
}

/// Do the diagonals `(a, b)` and `(c, d)` of a convex polygon cross
/// (strictly interleaved endpoints)?
pub fn crosses(d1: (u32, u32), d2: (u32, u32)) -> bool {
    let (a, b) = key(d1.0, d1.1);
    let (c, d) = key(d2.0, d2.1);
    (a < c && c < b && b < d) || (c < a && a < d && d < b)
}

impl FlipTriangulation {
    /// Wraps a triangulation of the n-gon (corners in cyclic order).
    pub fn new(n: usize, triangles: &[[u32; 3]]) -> FlipTriangulation {
        let mut t = FlipTriangulation {
            n: n as u32,
            triangles: triangles.iter().map(|&t| canonical(t)).collect(),
            edges: HashMap::with_capacity(3 * n),
        };
        for i in 0..t.triangles.len() {
            t.index(i);
        }
        t
    }

    fn index(&mut self, i: usize) {
        let tri = self.triangles[i];
        for k in 0..3 {
            let e = key(tri[k], tri[(k + 1) % 3]);
            let slot = self.edges.entry(e).or_insert([NONE, NONE]);
            if slot[0] == NONE {
                slot[0] = i as u32;
            } else {
                slot[1] = i as u32;
            }
        }
    }

    fn unindex(&mut self, i: usize) {
        let tri = self.triangles[i];
        for k in 0..3 {
            let e = key(tri[k], tri[(k + 1) % 3]);
            if let Some(slot) = self.edges.get_mut(&e) {
                if slot[0] == i as u32 {
                    slot[0] = slot[1];
                }
                slot[1] = NONE;
                if slot[0] == NONE {
                    self.edges.remove(&e);
                }
            }
        }
    }

    /// The triangles, corners in cyclic order, smallest first.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// True when `(a, b)` is an edge (side or diagonal).
    pub fn has_edge(&self, a: u32, b: u32) -> bool {
        self.edges.contains_key(&key(a, b))
    }

    /// The diagonals, each `(min, max)`, sorted.
    pub fn diagonals(&self) -> Vec<(u32, u32)> {
        let n = self.n;
        let mut d: Vec<(u32, u32)> = self
            .edges
            .keys()
            .copied()
            .filter(|&(a, b)| b - a != 1 && b - a != n - 1)
            .collect();
        d.sort_unstable();
        d
    }

    /// The quad around diagonal `(a, c)`: `[a, b, c, d]` in cyclic order
    /// with the two triangles `(a, b, c)` and `(c, d, a)`, and their
    /// indices; `None` for a side or a missing edge.
    pub fn quad(&self, a: u32, c: u32) -> Option<([u32; 4], [usize; 2])> {
        let slot = self.edges.get(&key(a, c))?;
        if slot[1] == NONE {
            return None;
        }
        let (t0, t1) = (slot[0] as usize, slot[1] as usize);
        let apex = |t: usize| {
            self.triangles[t]
                .into_iter()
                .find(|&v| v != a && v != c)
                .unwrap_or(NONE)
        };
        let (p, q) = (apex(t0), apex(t1));
        let (lo, hi) = key(a, c);
        // The apex strictly between lo and hi (going up) is b.
        let between = |v: u32| lo < v && v < hi;
        let (b, d, tb, td) = if between(p) {
            (p, q, t0, t1)
        } else {
            (q, p, t1, t0)
        };
        Some(([lo, b, hi, d], [tb, td]))
    }

    /// Flips diagonal `(a, c)` and returns the flip, or `None` when it is a
    /// side or not an edge.
    pub fn flip(&mut self, a: u32, c: u32) -> Option<Flip> {
        let ([a, b, c, d], [t0, t1]) = self.quad(a, c)?;
        self.unindex(t0);
        self.unindex(t1);
        self.triangles[t0] = canonical([a, b, d]);
        self.triangles[t1] = canonical([b, c, d]);
        self.index(t0);
        self.index(t1);
        Some(Flip {
            from: key(a, c),
            to: key(b, d),
        })
    }

    /// The diagonal of the triangle at `x` that the segment `(x, y)`
    /// enters, or `None` when `(x, y)` is already an edge.
    fn entered(&self, x: u32, y: u32) -> Option<(u32, u32)> {
        if self.has_edge(x, y) {
            return None;
        }
        let n = self.n;
        // Cyclic position after x.
        let pos = |v: u32| (v + n - x) % n;
        let py = pos(y);
        for tri in &self.triangles {
            if !tri.contains(&x) {
                continue;
            }
            let others: Vec<u32> = tri.iter().copied().filter(|&v| v != x).collect();
            let (p, q) = (others[0], others[1]);
            let (lo, hi) = if pos(p) < pos(q) { (p, q) } else { (q, p) };
            if pos(lo) < py && py < pos(hi) {
                return Some(key(lo, hi));
            }
        }
        None
    }
}

/// The number of crossings between the diagonals of two triangulations.
pub fn crossing_count(d1: &[(u32, u32)], d2: &[(u32, u32)]) -> usize {
    d1.iter()
        .map(|&a| d2.iter().filter(|&&b| crosses(a, b)).count())
        .sum()
}

/// The flips that turn `from` into `to` (both triangulations of the
/// n-gon), by the insertion order of seed 004 §6.2: `to`'s diagonals by
/// increasing number of crossings with `from`'s.
pub fn flip_sequence(n: usize, from: &[[u32; 3]], to: &[[u32; 3]]) -> Vec<Flip> {
    let mut cur = FlipTriangulation::new(n, from);
    let target = FlipTriangulation::new(n, to).diagonals();
    let source = cur.diagonals();
    let mut order: Vec<((u32, u32), usize)> = target
        .iter()
        .map(|&t| (t, source.iter().filter(|&&s| crosses(s, t)).count()))
        .collect();
    order.sort_by_key(|&(d, c)| (c, d));
    let mut flips = Vec::new();
    for ((x, y), _) in order {
        // Each flip removes one crossing with (x, y); bound the loop by n²
        // in case of a malformed input rather than spinning.
        let mut guard = n * n;
        while let Some((p, q)) = cur.entered(x, y) {
            match cur.flip(p, q) {
                Some(f) => flips.push(f),
                None => break,
            }
            guard -= 1;
            if guard == 0 {
                break;
            }
        }
    }
    flips
}

/// For every cyclic shift k, the number of crossings between `t1`'s
/// diagonals and `t2`'s relabelled by k (vertex `v` of t2 becomes
/// `v − k`). O(n² log n) in all, with a Fenwick tree per shift.
pub fn crossings_per_shift(n: usize, t1: &[[u32; 3]], t2: &[[u32; 3]]) -> Vec<usize> {
    let d1 = FlipTriangulation::new(n, t1).diagonals();
    let d2 = FlipTriangulation::new(n, t2).diagonals();
    (0..n)
        .map(|k| {
            let shifted: Vec<(u32, u32)> = d2
                .iter()
                .map(|&(a, b)| {
                    let m = n as u32;
                    let k = k as u32;
                    key((a + m - k) % m, (b + m - k) % m)
                })
                .collect();
            count_crossings_fast(n, &d1, &shifted)
        })
        .collect()
}

/// Crossings between two sets of chords of an n-gon in O((|a| + |b|) log n):
/// pairs with a.0 < b.0 < a.1 < b.1 plus pairs with b.0 < a.0 < b.1 < a.1.
fn count_crossings_fast(n: usize, a: &[(u32, u32)], b: &[(u32, u32)]) -> usize {
    one_way(n, a, b) + one_way(n, b, a)
}

/// Pairs (p in `a`, q in `b`) with p.0 < q.0 < p.1 < q.1.
fn one_way(n: usize, a: &[(u32, u32)], b: &[(u32, u32)]) -> usize {
    let mut a_sorted: Vec<(u32, u32)> = a.to_vec();
    a_sorted.sort_unstable();
    let mut b_sorted: Vec<(u32, u32)> = b.to_vec();
    b_sorted.sort_unstable();
    let mut fen = vec![0usize; n + 1];
    let add = |fen: &mut Vec<usize>, i: usize| {
        let mut i = i + 1;
        while i <= n {
            fen[i] += 1;
            i += i & i.wrapping_neg();
        }
    };
    let prefix = |fen: &Vec<usize>, i: usize| {
        // Count of inserted keys < i.
        let mut s = 0;
        let mut i = i;
        while i > 0 {
            s += fen[i];
            i -= i & i.wrapping_neg();
        }
        s
    };
    let mut total = 0;
    let mut ia = 0;
    for &(c, d) in &b_sorted {
        while ia < a_sorted.len() && a_sorted[ia].0 < c {
            add(&mut fen, a_sorted[ia].1 as usize);
            ia += 1;
        }
        // a.1 strictly between c and d.
        total += prefix(&fen, d as usize) - prefix(&fen, c as usize + 1);
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::morph::compatible::tests::{Rng, random_triangulation};

    #[test]
    fn flip_sequence_reaches_the_target_at_the_counted_cost() {
        let mut rng = Rng(0x5eed);
        for _ in 0..300 {
            let n = 4 + (rng.next() * 40.0) as usize;
            let t1 = random_triangulation(n as u32, &mut rng);
            let t2 = random_triangulation(n as u32, &mut rng);
            let mut cur = FlipTriangulation::new(n, &t1);
            let target = FlipTriangulation::new(n, &t2);
            let target_diagonals = target.diagonals();
            let mut order: Vec<((u32, u32), usize)> = target_diagonals
                .iter()
                .map(|&t| {
                    (
                        t,
                        cur.diagonals().iter().filter(|&&s| crosses(s, t)).count(),
                    )
                })
                .collect();
            order.sort_by_key(|&(d, c)| (c, d));
            let mut total = 0;
            for ((x, y), _) in order {
                // Crossings with (x, y) just before inserting it.
                let before = cur
                    .diagonals()
                    .iter()
                    .filter(|&&s| crosses(s, (x, y)))
                    .count();
                let mut cost = 0;
                while let Some((p, q)) = cur.entered(x, y) {
                    cur.flip(p, q).unwrap();
                    cost += 1;
                }
                assert_eq!(
                    cost, before,
                    "insertion of {x}-{y} cost {cost}, crossings {before}"
                );
                total += cost;
            }
            assert_eq!(cur.diagonals(), target_diagonals);
            let flips = flip_sequence(n, &t1, &t2);
            assert_eq!(flips.len(), total);
            // Replaying the flips reaches the target.
            let mut replay = FlipTriangulation::new(n, &t1);
            for f in &flips {
                assert_eq!(replay.flip(f.from.0, f.from.1), Some(*f));
            }
            assert_eq!(replay.diagonals(), target_diagonals);
            assert!(
                flips.len()
                    <= crossing_count(
                        &FlipTriangulation::new(n, &t1).diagonals(),
                        &target_diagonals
                    )
            );
        }
    }

    #[test]
    fn fast_crossing_count_matches_the_pairwise_count() {
        let mut rng = Rng(77);
        for _ in 0..100 {
            let n = 4 + (rng.next() * 30.0) as usize;
            let t1 = random_triangulation(n as u32, &mut rng);
            let t2 = random_triangulation(n as u32, &mut rng);
            let per_shift = crossings_per_shift(n, &t1, &t2);
            let d1 = FlipTriangulation::new(n, &t1).diagonals();
            for (k, &c) in per_shift.iter().enumerate() {
                let shifted = crate::correspond::shift_triangles(n, &t2, k);
                let d2 = FlipTriangulation::new(n, &shifted).diagonals();
                assert_eq!(c, crossing_count(&d1, &d2), "n={n} k={k}");
            }
        }
    }
}
