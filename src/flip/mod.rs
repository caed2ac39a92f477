//! A triangulation of the abstract n-gon that can be flipped: the one
//! edge-to-triangle adjacency that the Delaunay improvement
//! ([`crate::quality`]) and the staged morph ([`crate::morph`]) share.
//! Index-only: no coordinates.
//!
//! Vertices are `0..n` in cyclic order; every triangle lists its corners
//! in cyclic order with the smallest first (so sorted). Two diagonals
//! cross when their endpoints interleave around the polygon.

pub(crate) mod delaunay;
pub(crate) mod sequence;

use rustc_hash::FxHashMap;

/// One flip: the diagonal `from` is replaced by `to` in the quad they
/// share.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct Flip {
    /// The diagonal removed, `(min, max)`.
    pub from: (u32, u32),
    /// The diagonal added, `(min, max)`.
    pub to: (u32, u32),
}

const NONE: u32 = u32::MAX;

/// The undirected edge `{a, b}` as `(min, max)`.
pub(crate) fn key(a: u32, b: u32) -> (u32, u32) {
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
pub(crate) fn crosses(d1: (u32, u32), d2: (u32, u32)) -> bool {
    let (a, b) = key(d1.0, d1.1);
    let (c, d) = key(d2.0, d2.1);
    (a < c && c < b && b < d) || (c < a && a < d && d < b)
}

/// A triangulation of the abstract n-gon that can be flipped.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct FlipTriangulation {
    n: u32,
    triangles: Vec<[u32; 3]>,
    /// For each edge (min, max), the one or two triangles containing it.
    edges: FxHashMap<(u32, u32), [u32; 2]>,
}

impl FlipTriangulation {
    /// Wraps a triangulation of the n-gon (corners in cyclic order).
    pub(crate) fn new(n: usize, triangles: &[[u32; 3]]) -> FlipTriangulation {
        let mut t = FlipTriangulation {
            n: n as u32,
            triangles: triangles.iter().map(|&t| canonical(t)).collect(),
            edges: FxHashMap::with_capacity_and_hasher(3 * n, Default::default()),
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

    /// The number of polygon vertices.
    pub(crate) fn vertex_count(&self) -> usize {
        self.n as usize
    }

    /// The triangles, corners in cyclic order, smallest first.
    pub(crate) fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// True when `(a, b)` is an edge (side or diagonal).
    pub(crate) fn has_edge(&self, a: u32, b: u32) -> bool {
        self.edges.contains_key(&key(a, b))
    }

    /// The diagonals, each `(min, max)`, sorted.
    pub(crate) fn diagonals(&self) -> Vec<(u32, u32)> {
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
    /// (`a` the smaller end) with the two triangles `(a, b, c)` and
    /// `(c, d, a)`, and their indices; `None` for a side or a missing edge.
    pub(crate) fn quad(&self, a: u32, c: u32) -> Option<([u32; 4], [usize; 2])> {
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
    /// side or not an edge. The two triangles keep their indices: `(a, b,
    /// c)` becomes `(a, b, d)` and `(c, d, a)` becomes `(b, c, d)`.
    pub(crate) fn flip(&mut self, a: u32, c: u32) -> Option<Flip> {
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
    /// enters, or `None` when `(x, y)` is already an edge. Walks the fan of
    /// `x` from the side `(x, x + 1)`: O(degree of x).
    pub(crate) fn entered(&self, x: u32, y: u32) -> Option<(u32, u32)> {
        if self.has_edge(x, y) || x == y {
            return None;
        }
        let n = self.n;
        // Cyclic position after x.
        let pos = |v: u32| (v + n - x) % n;
        let py = pos(y);
        let mut a = (x + 1) % n;
        let mut came_from = NONE;
        // Each step moves to the next triangle of the fan: at most n − 2.
        for _ in 0..n {
            let slot = self.edges.get(&key(x, a))?;
            let t = if slot[0] != came_from {
                slot[0]
            } else {
                slot[1]
            };
            if t == NONE {
                return None;
            }
            let b = self.triangles[t as usize]
                .into_iter()
                .find(|&v| v != x && v != a)?;
            if pos(b) > py {
                return Some(key(a, b));
            }
            came_from = t;
            a = b;
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fan from vertex 0.
    fn fan(n: u32) -> Vec<[u32; 3]> {
        (1..n - 1).map(|i| [0, i, i + 1]).collect()
    }

    #[test]
    fn the_entered_diagonal_is_found_by_walking_the_fan() {
        let t = FlipTriangulation::new(8, &fan(8));
        // From vertex 3 toward 5: the fan of 3 is (0, 2, 3), (0, 3, 4);
        // the segment 3-5 enters triangle (0, 3, 4) through diagonal 0-4.
        assert_eq!(t.entered(3, 5), Some((0, 4)));
        assert_eq!(t.entered(3, 0), None);
        assert_eq!(t.entered(3, 4), None);
        assert_eq!(t.entered(1, 6), Some((0, 2)));
    }

    #[test]
    fn flips_keep_the_adjacency() {
        let mut t = FlipTriangulation::new(6, &fan(6));
        let f = t.flip(0, 3).unwrap();
        assert_eq!(f.to, (2, 4));
        assert!(t.has_edge(2, 4) && !t.has_edge(0, 3));
        assert_eq!(t.diagonals(), vec![(0, 2), (0, 4), (2, 4)]);
        assert_eq!(t.quad(0, 4).map(|q| q.0), Some([0, 2, 4, 5]));
        assert!(t.flip(0, 1).is_none());
    }
}
