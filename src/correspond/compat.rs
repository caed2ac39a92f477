//! Compatibility of two triangulations of n-gons by cyclic degree
//! sequences.
//!
//! A triangulated polygon is determined by its sequence of per-vertex
//! triangle counts: a vertex in exactly one triangle is an ear, and
//! removing it lowers its two neighbours' counts by one
//! ([`from_degree_sequence`]). So two triangulations are the same up to a
//! cyclic relabelling iff their degree sequences agree up to a cyclic
//! shift. Mukherjee & Gopi compare all shifts in O(n²); here the shift is
//! found in O(n) by Knuth–Morris–Pratt matching of one sequence in the
//! other, doubled.

/// Number of triangles at each vertex of a triangulated `n`-gon.
pub fn degree_sequence(n: usize, triangles: &[[u32; 3]]) -> Vec<u32> {
    let mut d = vec![0u32; n];
    for t in triangles {
        for &v in t {
            if let Some(x) = d.get_mut(v as usize) {
                *x += 1;
            }
        }
    }
    d
}

/// The smallest shift `k` with `a[i] == b[(i + k) % n]` for all `i`, found
/// in O(n) (KMP of `a` in `b` doubled); `None` when there is none or the
/// lengths differ.
///
/// With triangulations T1 of curve A and T2 of curve B, vertex `i` of A
/// then corresponds to vertex `i + k` of B.
///
/// # Examples
///
/// ```
/// use immerse::correspond::compatible_shift;
/// assert_eq!(compatible_shift(&[1, 2, 3, 1, 3], &[3, 1, 3, 1, 2]), Some(3));
/// assert_eq!(compatible_shift(&[1, 2, 2], &[1, 1, 3]), None);
/// ```
pub fn compatible_shift(a: &[u32], b: &[u32]) -> Option<usize> {
    let n = a.len();
    if n != b.len() || n == 0 {
        return None;
    }
    // Failure function of the pattern a.
    let mut fail = vec![0usize; n];
    let mut k = 0;
    for i in 1..n {
        while k > 0 && a[i] != a[k] {
            k = fail[k - 1];
        }
        if a[i] == a[k] {
            k += 1;
        }
        fail[i] = k;
    }
    // Scan b doubled (minus its last element).
    let mut k = 0;
    for j in 0..(2 * n - 1) {
        let c = b[j % n];
        while k > 0 && c != a[k] {
            k = fail[k - 1];
        }
        if c == a[k] {
            k += 1;
        }
        if k == n {
            return Some(j + 1 - n);
        }
    }
    None
}

/// Relabels a triangulation of B by the shift `k` of [`compatible_shift`]:
/// B's vertex `i + k` becomes vertex `i`. Each triangle's corners stay in
/// cyclic order, smallest first.
pub fn shift_triangles(n: usize, triangles: &[[u32; 3]], k: usize) -> Vec<[u32; 3]> {
    let n32 = n as u32;
    let k32 = (k % n) as u32;
    triangles
        .iter()
        .map(|t| {
            let mut s = t.map(|v| (v + n32 - k32) % n32);
            // Rotate so the smallest comes first; rotation keeps the cyclic
            // order.
            while s[0] > s[1] || s[0] > s[2] {
                s = [s[1], s[2], s[0]];
            }
            s
        })
        .collect()
}

/// Rebuilds the triangulation of an n-gon from its degree sequence by ear
/// removal, or `None` when the sequence belongs to no triangulation.
/// Triangles come out with corners in cyclic order, smallest first, sorted.
pub fn from_degree_sequence(degrees: &[u32]) -> Option<Vec<[u32; 3]>> {
    let n = degrees.len();
    if n < 3 || degrees.contains(&0) {
        return None;
    }
    let mut deg = degrees.to_vec();
    let mut next: Vec<usize> = (0..n).map(|i| (i + 1) % n).collect();
    let mut prev: Vec<usize> = (0..n).map(|i| (i + n - 1) % n).collect();
    let mut removed = vec![false; n];
    let mut stack: Vec<usize> = (0..n).filter(|&i| deg[i] == 1).collect();
    let mut out = Vec::with_capacity(n - 2);
    let mut left = n;
    while left > 3 {
        let v = stack.pop()?;
        if removed[v] || deg[v] != 1 {
            continue;
        }
        let (p, q) = (prev[v], next[v]);
        out.push(sorted_cyclic([p as u32, v as u32, q as u32]));
        removed[v] = true;
        left -= 1;
        next[p] = q;
        prev[q] = p;
        for w in [p, q] {
            deg[w] = deg[w].checked_sub(1)?;
            if deg[w] == 0 {
                return None;
            }
            if deg[w] == 1 {
                stack.push(w);
            }
        }
    }
    let v = (0..n).find(|&i| !removed[i])?;
    let tri = [v, next[v], next[next[v]]];
    if tri.iter().any(|&w| deg[w] != 1) {
        return None;
    }
    out.push(sorted_cyclic(tri.map(|w| w as u32)));
    out.sort_unstable();
    Some(out)
}

fn sorted_cyclic(mut t: [u32; 3]) -> [u32; 3] {
    // Corners of a polygon triangle in cyclic order: rotate smallest first,
    // then they are increasing.
    while t[0] > t[1] || t[0] > t[2] {
        t = [t[1], t[2], t[0]];
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A random triangulation of an n-gon by recursive splitting.
    fn random_triangulation(n: u32, seed: &mut u64) -> Vec<[u32; 3]> {
        fn split(i: u32, j: u32, seed: &mut u64, out: &mut Vec<[u32; 3]>) {
            if j - i < 2 {
                return;
            }
            *seed ^= *seed << 13;
            *seed ^= *seed >> 7;
            *seed ^= *seed << 17;
            let k = i + 1 + (*seed % u64::from(j - i - 1)) as u32;
            out.push([i, k, j]);
            split(i, k, seed, out);
            split(k, j, seed, out);
        }
        let mut out = Vec::new();
        split(0, n - 1, seed, &mut out);
        out.sort_unstable();
        out
    }

    #[test]
    fn degree_sequence_rebuilds_the_triangulation() {
        let mut seed = 0x2545F4914F6CDD1D;
        for n in 3..40 {
            for _ in 0..20 {
                let t = random_triangulation(n, &mut seed);
                let d = degree_sequence(n as usize, &t);
                assert_eq!(d.iter().sum::<u32>(), 3 * (n - 2));
                assert_eq!(from_degree_sequence(&d), Some(t.clone()), "n={n}");
            }
        }
    }

    #[test]
    fn invalid_degree_sequences_are_rejected() {
        assert_eq!(from_degree_sequence(&[1, 1, 1, 1]), None);
        assert_eq!(from_degree_sequence(&[2, 2, 2, 2, 2]), None);
        assert_eq!(from_degree_sequence(&[0, 1, 1]), None);
    }

    #[test]
    fn shift_is_found_and_relabels_compatibly() {
        let mut seed = 0x9E3779B97F4A7C15;
        for n in 4..30u32 {
            let t = random_triangulation(n, &mut seed);
            let n_us = n as usize;
            for k in 0..n_us {
                // B is A relabelled: vertex i of A is vertex i + k of B.
                let b: Vec<[u32; 3]> = shift_triangles(n_us, &t, n_us - k);
                let (da, db) = (degree_sequence(n_us, &t), degree_sequence(n_us, &b));
                let found = compatible_shift(&da, &db).expect("a shift exists");
                let mut back = shift_triangles(n_us, &b, found);
                back.sort_unstable();
                assert_eq!(back, t, "n={n} k={k} found={found}");
            }
        }
    }
}
