//! Flip sequences between two triangulations of the abstract n-gon
//! (Mukherjee & Gopi §6.2; docs/design.md §7). Index-only: no coordinates.
//!
//! Two diagonals cross when their endpoints interleave around the polygon.
//! The target's diagonals are sorted by how many of the source's they
//! cross and inserted in that order; inserting (x, y) repeatedly flips the
//! diagonal of the triangle at x that (x, y) enters. Each flip removes
//! exactly one crossing with (x, y), so an insertion costs exactly its
//! number of crossings at that moment, and an inserted diagonal is never
//! flipped again (target diagonals do not cross each other).

pub(crate) use crate::flip::{Flip, FlipTriangulation, crosses};
use crate::flip::{canonical, key};
use crate::geom::Point;
use crate::geom::polygon::min_angle_sine;
use crate::immersion::is_valid_triangle;

/// Counts, for any chord, how many chords of a fixed set it crosses, in
/// O(log² m) per query (a merge-sort tree over the set's first endpoints).
#[derive(Clone, Debug)]
pub(crate) struct CrossingCounter {
    /// The chords `(c, d)`, `c < d`, sorted by `c`.
    firsts: Vec<u32>,
    /// Per tree level, the second endpoints of each block of 2^level
    /// chords (in `firsts` order), sorted within the block.
    levels: Vec<Vec<u32>>,
}

impl CrossingCounter {
    pub(crate) fn new(chords: &[(u32, u32)]) -> CrossingCounter {
        let mut sorted: Vec<(u32, u32)> = chords.iter().map(|&(a, b)| key(a, b)).collect();
        sorted.sort_unstable();
        let firsts: Vec<u32> = sorted.iter().map(|c| c.0).collect();
        let mut levels = vec![sorted.iter().map(|c| c.1).collect::<Vec<u32>>()];
        let mut width = 1usize;
        while width < sorted.len() {
            width *= 2;
            let mut next = levels.last().cloned().unwrap_or_default();
            for block in next.chunks_mut(width) {
                block.sort_unstable();
            }
            levels.push(next);
        }
        CrossingCounter { firsts, levels }
    }

    /// Chords with first endpoint in `[lo, hi)` (by index range in
    /// `firsts`) whose second endpoint satisfies `pred` (a range test).
    fn count_range(&self, from: usize, to: usize, lo2: u32, hi2: u32) -> usize {
        // Second endpoints in [lo2, hi2).
        let mut total = 0;
        let mut i = from;
        let top = self.levels.len() - 1;
        while i < to {
            // The largest aligned block starting at i that fits in [i, to):
            // 2^level divides i (level ≤ its trailing zeros) and is at most
            // to − i (level ≤ ⌊log₂(to − i)⌋).
            let aligned = i.trailing_zeros() as usize; // 64 where i = 0
            let fits = (to - i).ilog2() as usize;
            let level = aligned.min(fits).min(top);
            let w = 1usize << level;
            let block = &self.levels[level][i..i + w];
            total += block.partition_point(|&x| x < hi2) - block.partition_point(|&x| x < lo2);
            i += w;
        }
        total
    }

    /// How many of the chords the chord `(a, b)` crosses.
    pub(crate) fn count(&self, d: (u32, u32)) -> usize {
        let (a, b) = key(d.0, d.1);
        let idx = |v: u32| self.firsts.partition_point(|&x| x < v);
        // c in (a, b) and d > b, or c < a and d in (a, b).
        self.count_range(idx(a + 1), idx(b), b + 1, u32::MAX)
            + self.count_range(0, idx(a), a + 1, b)
    }
}

/// The flips that turn `from` into `to` (both triangulations of the
/// n-gon), by the insertion order of Mukherjee & Gopi §6.2: `to`'s diagonals by
/// increasing number of crossings with `from`'s.
pub(crate) fn flip_sequence(n: usize, from: &[[u32; 3]], to: &[[u32; 3]]) -> Vec<Flip> {
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
/// `v − k`). O(n²) in all, with no sorting: for each first endpoint c the
/// number f(d) of `t1`'s diagonals that the chord (c, d) crosses follows
/// from f(d − 1) by looking only at the diagonals at d − 1 and d (a chord
/// crosses (c, d) when one endpoint is strictly inside (c, d) and the
/// other outside [c, d]):
/// f(d + 1) = f(d) + #{(d, w): w < c or w > d + 1} − #{(v, d + 1): c < v < d},
/// and each diagonal of `t2`, under each shift, is one chord (c, d). The
/// first endpoints are shared out between the cores.
pub(crate) fn crossings_per_shift(n: usize, t1: &[[u32; 3]], t2: &[[u32; 3]]) -> Vec<usize> {
    use rayon::prelude::*;
    let d1 = FlipTriangulation::new(n, t1).diagonals();
    let d2 = FlipTriangulation::new(n, t2).diagonals();
    let mut at: Vec<Vec<usize>> = vec![Vec::new(); n];
    for &(a, b) in &d1 {
        at[a as usize].push(b as usize);
        at[b as usize].push(a as usize);
    }
    (0..n)
        .into_par_iter()
        .fold(
            || (vec![0usize; n], vec![0i64; n]),
            |(mut per_shift, mut f), c| {
                if c + 2 >= n {
                    return (per_shift, f);
                }
                f[c + 1] = 0;
                for d in c + 1..n - 1 {
                    let gained = at[d].iter().filter(|&&w| w < c || w > d + 1).count();
                    let lost = at[d + 1].iter().filter(|&&v| c < v && v < d).count();
                    f[d + 1] = f[d] + gained as i64 - lost as i64;
                }
                for &(a, b) in &d2 {
                    for (e, o) in [(a as usize, b as usize), (b as usize, a as usize)] {
                        // The shift that takes e to c, and where it takes o.
                        let k = (e + n - c) % n;
                        let d = (o + n - k) % n;
                        if d > c {
                            per_shift[k] += f[d] as usize;
                        }
                    }
                }
                (per_shift, f)
            },
        )
        .map(|(per_shift, _)| per_shift)
        .reduce(
            || vec![0usize; n],
            |mut a, b| {
                for (x, y) in a.iter_mut().zip(b) {
                    *x += y;
                }
                a
            },
        )
}

/// The flip gate of docs/design.md §7: the flip of the quad `[a, b, c, d]`
/// (diagonal a–c to b–d) may be applied in shape `p` when both new
/// triangles are valid and their minimum angle is at least min(the old
/// pair's, `floor`); returns the sine of that minimum angle (it orders
/// flips as the angle does). With `floor` = 0 only validity is required.
pub(crate) fn gate(p: &[Point], quad: [u32; 4], floor: f64) -> Option<f64> {
    let [a, b, c, d] = quad;
    let q = |v: u32| p[v as usize];
    // Cheap exact rejection first: the quad must be strictly convex at
    // b and d for both new triangles to be counter-clockwise.
    if !(crate::geom::orient(q(a), q(b), q(d)).is_ccw()
        && crate::geom::orient(q(b), q(c), q(d)).is_ccw())
    {
        return None;
    }
    let new = [canonical([a, b, d]), canonical([b, c, d])];
    if !new
        .iter()
        .all(|t| is_valid_triangle(p, t[0] as usize, t[1] as usize, t[2] as usize))
    {
        return None;
    }
    let sine = |t: [u32; 3]| min_angle_sine(q(t[0]), q(t[1]), q(t[2]));
    let m = sine([a, b, d]).min(sine([b, c, d]));
    let old = sine([a, b, c]).min(sine([c, d, a]));
    (m >= old.min(floor.min(std::f64::consts::FRAC_PI_2).sin())).then_some(m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::propagate::compatible::tests::{Rng, random_polygon, random_triangulation};

    /// The number of crossings between the diagonals of two
    /// triangulations, pair by pair: the oracle of the fast counts.
    fn crossing_count(d1: &[(u32, u32)], d2: &[(u32, u32)]) -> usize {
        d1.iter()
            .map(|&a| d2.iter().filter(|&&b| crosses(a, b)).count())
            .sum()
    }

    /// Two random triangulations of one [`random_polygon`].
    fn two_triangulations(
        rng: &mut Rng,
        min: usize,
        span: f64,
    ) -> (usize, Vec<[u32; 3]>, Vec<[u32; 3]>) {
        let (n, t1) = random_polygon(rng, min, span);
        let t2 = random_triangulation(n as u32, rng);
        (n, t1, t2)
    }

    #[test]
    fn flip_sequence_reaches_the_target_at_the_counted_cost() {
        let mut rng = Rng(0x5eed);
        for _ in 0..300 {
            let (n, t1, t2) = two_triangulations(&mut rng, 4, 40.0);
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
    fn the_crossing_counter_matches_the_pairwise_count() {
        let mut rng = Rng(0xc0ffee);
        for _ in 0..100 {
            let (n, tris) = random_polygon(&mut rng, 4, 60.0);
            let goal = FlipTriangulation::new(n, &tris).diagonals();
            let counter = CrossingCounter::new(&goal);
            for a in 0..n as u32 {
                for b in a + 2..n as u32 {
                    let want = goal.iter().filter(|&&g| crosses(g, (a, b))).count();
                    assert_eq!(counter.count((a, b)), want, "n={n} ({a}, {b})");
                    assert_eq!(counter.count((b, a)), want);
                }
            }
        }
    }

    #[test]
    fn fast_crossing_count_matches_the_pairwise_count() {
        let mut rng = Rng(77);
        for _ in 0..100 {
            let (n, t1, t2) = two_triangulations(&mut rng, 4, 30.0);
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
