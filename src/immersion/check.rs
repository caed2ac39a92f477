//! An independent checker for immersion triangulations.
//!
//! Written directly from the definition (docs/design.md §3) and the exact
//! predicates, sharing no code with the DP: a list of triangles is an
//! immersion triangulation of the closed polygon `p_0 … p_{n−1}` when there
//! are exactly n − 2 triangles, each `[a, b, c]` with `a < b < c < n`, every
//! polygon edge lies in exactly one triangle, every other edge (a diagonal)
//! in exactly two, no two diagonals cross (interleaved endpoints), and every
//! triangle is valid ([`is_valid_triangle`]).
//!
//! Complexity: O(n) (edge counting by counting sorts, crossing test by a
//! stack over the diagonals as nested intervals), O(n) exact predicates.

use super::valid::is_valid_triangle;
use crate::geom::Point;

/// What is wrong with a would-be immersion triangulation (the first defect
/// found, in the order of the variants).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ImmersionDefect {
    /// The polygon has fewer than 3 points.
    #[error("a polygon needs at least 3 points, found {0}")]
    TooFewPoints(usize),
    /// There are not exactly n − 2 triangles.
    #[error("expected {expected} triangles, found {found}")]
    TriangleCount {
        /// n − 2.
        expected: usize,
        /// The number given.
        found: usize,
    },
    /// A corner index is not below n.
    #[error("triangle {triangle} has corner {index}, out of range")]
    IndexOutOfRange {
        /// Position of the triangle in the list.
        triangle: usize,
        /// The offending index.
        index: u32,
    },
    /// The corners are not strictly increasing.
    #[error("triangle {triangle} corners {corners:?} are not strictly increasing")]
    NotIncreasing {
        /// Position of the triangle in the list.
        triangle: usize,
        /// Its corners as given.
        corners: [u32; 3],
    },
    /// A polygon edge `(v, v + 1)` is not in exactly one triangle.
    #[error("polygon edge ({}, {}) lies in {count} triangles, not 1", edge.0, edge.1)]
    BoundaryEdge {
        /// The edge, smaller index first.
        edge: (u32, u32),
        /// In how many triangles it lies.
        count: usize,
    },
    /// A diagonal is not in exactly two triangles.
    #[error("diagonal ({}, {}) lies in {count} triangles, not 2", edge.0, edge.1)]
    Diagonal {
        /// The diagonal, smaller index first.
        edge: (u32, u32),
        /// In how many triangles it lies.
        count: usize,
    },
    /// Two diagonals have interleaved endpoints.
    #[error("diagonals ({}, {}) and ({}, {}) cross", first.0, first.1, second.0, second.1)]
    Crossing {
        /// One diagonal.
        first: (u32, u32),
        /// The other.
        second: (u32, u32),
    },
    /// A triangle is not counter-clockwise or makes a vertex fan wrap.
    #[error("triangle {triangle} {corners:?} is not valid (clockwise, degenerate or a fan wraps)")]
    InvalidTriangle {
        /// Position of the triangle in the list.
        triangle: usize,
        /// Its corners.
        corners: [u32; 3],
    },
}

/// Check that `triangles` is an immersion triangulation of the closed
/// polygon `points` (module docs); the first defect found is returned.
///
/// # Examples
///
/// ```
/// use immerse::geom::Point;
/// use immerse::check;
/// let square = [Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(1.0, 1.0), Point::new(0.0, 1.0)];
/// assert!(check(&square, &[[0, 1, 2], [0, 2, 3]]).is_ok());
/// assert!(check(&square, &[[0, 1, 2], [1, 2, 3]]).is_err());
/// ```
///
/// # Errors
///
/// The first [`ImmersionDefect`], in the order of the variants.
pub fn check(points: &[Point], triangles: &[[u32; 3]]) -> Result<(), ImmersionDefect> {
    check_structure(points.len(), triangles)?;
    check_triangles(points, triangles)
}

/// The combinatorial half of [`check`]: `triangles` is a triangulation of
/// the n-gon by diagonals (counts, index order, edge multiplicities, no
/// crossing diagonals), whatever the positions. O(n).
pub(crate) fn check_structure(n: usize, triangles: &[[u32; 3]]) -> Result<(), ImmersionDefect> {
    if n < 3 {
        return Err(ImmersionDefect::TooFewPoints(n));
    }
    if triangles.len() != n - 2 {
        return Err(ImmersionDefect::TriangleCount {
            expected: n - 2,
            found: triangles.len(),
        });
    }
    for (t, &tri) in triangles.iter().enumerate() {
        if let Some(&index) = tri.iter().find(|&&v| v as usize >= n) {
            return Err(ImmersionDefect::IndexOutOfRange { triangle: t, index });
        }
        if !(tri[0] < tri[1] && tri[1] < tri[2]) {
            return Err(ImmersionDefect::NotIncreasing {
                triangle: t,
                corners: tri,
            });
        }
    }
    // Edge multiplicities by sorting (two stable counting passes: O(n)).
    let edges: Vec<(u32, u32)> = triangles
        .iter()
        .flat_map(|&[a, b, c]| [(a, b), (b, c), (a, c)])
        .collect();
    let edges = counting_sort(&counting_sort(&edges, n, |e| e.1), n, |e| e.0);
    let is_boundary = |(a, b): (u32, u32)| b == a + 1 || (a == 0 && b as usize == n - 1);
    let mut counted: Vec<((u32, u32), usize)> = Vec::with_capacity(edges.len());
    for e in edges {
        match counted.last_mut() {
            Some((last, c)) if *last == e => *c += 1,
            _ => counted.push((e, 1)),
        }
    }
    // Every polygon edge exactly once (a missing one has count 0).
    let mut boundary_seen = 0;
    for &(e, count) in &counted {
        if is_boundary(e) {
            boundary_seen += 1;
            if count != 1 {
                return Err(ImmersionDefect::BoundaryEdge { edge: e, count });
            }
        }
    }
    if boundary_seen != n {
        let present: std::collections::HashSet<(u32, u32)> =
            counted.iter().map(|&(e, _)| e).collect();
        let missing = (0..n as u32)
            .map(|v| {
                let w = (v + 1) % n as u32;
                (v.min(w), v.max(w))
            })
            .find(|e| !present.contains(e))
            .unwrap_or((0, 1));
        return Err(ImmersionDefect::BoundaryEdge {
            edge: missing,
            count: 0,
        });
    }
    let mut diagonals = Vec::with_capacity(n - 3);
    for &(e, count) in &counted {
        if !is_boundary(e) {
            if count != 2 {
                return Err(ImmersionDefect::Diagonal { edge: e, count });
            }
            diagonals.push(e);
        }
    }
    // Crossing: (a, b) and (c, d) cross iff a < c < b < d. Sorted by a
    // ascending then b descending, the diagonals are a laminar family of
    // intervals iff each one nests inside the innermost open interval.
    let last = n as u32 - 1;
    let diagonals = counting_sort(&counting_sort(&diagonals, n, |d| last - d.1), n, |d| d.0);
    let mut open: Vec<(u32, u32)> = Vec::new();
    for &d in &diagonals {
        while open.last().is_some_and(|top| top.1 <= d.0) {
            open.pop();
        }
        if let Some(&top) = open.last() {
            if d.1 > top.1 {
                return Err(ImmersionDefect::Crossing {
                    first: top,
                    second: d,
                });
            }
        }
        open.push(d);
    }
    Ok(())
}

/// A list of triangles with the combinatorial half of [`check`]
/// ([`check_structure`]) done once, for the n-gon: made for a
/// triangulation that many shapes are checked or certified under (the
/// keys of a leg, the pieces of a bridge), so that each of them costs only
/// the geometric half.
#[derive(Clone, Debug)]
pub(crate) struct CheckedTriangles<'a> {
    n: usize,
    triangles: &'a [[u32; 3]],
    structure: Result<(), ImmersionDefect>,
}

impl<'a> CheckedTriangles<'a> {
    /// `triangles` as a would-be triangulation of the `n`-gon, its
    /// structure checked.
    pub(crate) fn new(n: usize, triangles: &'a [[u32; 3]]) -> Self {
        let structure = check_structure(n, triangles);
        Self {
            n,
            triangles,
            structure,
        }
    }

    /// The triangles.
    pub(crate) fn triangles(&self) -> &'a [[u32; 3]] {
        self.triangles
    }

    /// [`check`] of `points` under these triangles: the same answer, with
    /// the structure's half taken from [`CheckedTriangles::new`].
    pub(crate) fn check(&self, points: &[Point]) -> Result<(), ImmersionDefect> {
        if points.len() != self.n {
            return check(points, self.triangles);
        }
        self.structure.clone()?;
        check_triangles(points, self.triangles)
    }
}

/// `pairs` stably sorted by `key`, whose values are below `n`: a counting
/// sort, O(len + n).
fn counting_sort(
    pairs: &[(u32, u32)],
    n: usize,
    key: impl Fn((u32, u32)) -> u32,
) -> Vec<(u32, u32)> {
    let mut start = vec![0usize; n + 1];
    for &p in pairs {
        start[key(p) as usize + 1] += 1;
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut out = vec![(0, 0); pairs.len()];
    for &p in pairs {
        let at = &mut start[key(p) as usize];
        out[*at] = p;
        *at += 1;
    }
    out
}

/// The geometric half of [`check`]: every triangle is valid (counter-
/// clockwise, no fan wraps), for a list already known to be a
/// triangulation of the n-gon (for example every frame of a morph under a
/// fixed triangulation). O(n) exact predicates.
///
/// # Errors
///
/// [`ImmersionDefect::InvalidTriangle`] for the first invalid triangle.
pub(crate) fn check_triangles(
    points: &[Point],
    triangles: &[[u32; 3]],
) -> Result<(), ImmersionDefect> {
    for (t, &[a, b, c]) in triangles.iter().enumerate() {
        if !is_valid_triangle(points, a as usize, b as usize, c as usize) {
            return Err(ImmersionDefect::InvalidTriangle {
                triangle: t,
                corners: [a, b, c],
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{regular_polygon, unit_square};

    #[test]
    fn defects_are_named() {
        let sq = unit_square();
        assert_eq!(
            check(&sq, &[[0, 1, 2]]),
            Err(ImmersionDefect::TriangleCount {
                expected: 2,
                found: 1
            })
        );
        assert!(matches!(
            check(&sq, &[[0, 1, 2], [0, 2, 9]]),
            Err(ImmersionDefect::IndexOutOfRange { index: 9, .. })
        ));
        assert!(matches!(
            check(&sq, &[[0, 2, 1], [0, 2, 3]]),
            Err(ImmersionDefect::NotIncreasing { .. })
        ));
        assert!(matches!(
            check(&sq, &[[0, 1, 2], [0, 1, 3]]),
            Err(ImmersionDefect::BoundaryEdge { .. })
        ));
        assert!(check(&sq, &[[0, 1, 2], [0, 2, 3]]).is_ok());
        assert!(check(&sq, &[[0, 1, 3], [1, 2, 3]]).is_ok());
        // Clockwise square: combinatorially fine, geometrically invalid.
        let mut cw = sq;
        cw.reverse();
        assert!(matches!(
            check(&cw, &[[0, 1, 2], [0, 2, 3]]),
            Err(ImmersionDefect::InvalidTriangle { .. })
        ));
    }

    #[test]
    fn crossing_diagonals_are_found() {
        // Hexagon: (0,2,4) center with (0,3) crossing is combinatorially
        // caught by counts or crossing; build a list with crossing diagonals
        // but correct counts is impossible for a true triangulation, so test
        // the stack directly through a bad list.
        let hex = regular_polygon(6);
        assert!(check(&hex, &[[0, 1, 2], [2, 3, 4], [4, 5, 0], [0, 2, 4]]).is_err()); // [4,5,0] unordered
        assert!(check(&hex, &[[0, 1, 2], [2, 3, 4], [0, 4, 5], [0, 2, 4]]).is_ok());
        let r = check(&hex, &[[0, 1, 3], [1, 2, 4], [0, 3, 5], [3, 4, 5]]);
        assert!(r.is_err(), "{r:?}");
    }

    /// A triangulation checked once answers [`check`] of every shape as
    /// `check` does, defect for defect: a valid structure under valid and
    /// invalid shapes, every kind of broken structure, and a shape with
    /// another point count than the triangulation was made for.
    #[test]
    fn triangles_checked_once_answer_as_check_does() {
        let hex = regular_polygon(6);
        let mut cw = hex.clone();
        cw.reverse();
        let mut pinched = hex.clone();
        pinched[1] = Point::new(0.0, 0.0);
        let shapes = [
            hex.clone(),
            cw,
            pinched,
            hex[..5].to_vec(),
            unit_square().to_vec(),
        ];
        let lists: [&[[u32; 3]]; 6] = [
            &[[0, 1, 2], [2, 3, 4], [0, 4, 5], [0, 2, 4]],
            &[[0, 1, 2], [2, 3, 4], [4, 5, 0], [0, 2, 4]],
            &[[0, 1, 3], [1, 2, 4], [0, 3, 5], [3, 4, 5]],
            &[[0, 1, 2], [2, 3, 4], [0, 4, 5]],
            &[[0, 1, 2], [2, 3, 4], [0, 4, 9], [0, 2, 4]],
            &[[0, 1, 2], [0, 2, 3]],
        ];
        let mut answers = std::collections::HashSet::new();
        for tris in lists {
            let checked = CheckedTriangles::new(6, tris);
            assert_eq!(checked.triangles(), tris);
            for p in &shapes {
                let want = check(p, tris);
                assert_eq!(checked.check(p), want, "{tris:?} on {p:?}");
                answers.insert(want.as_ref().err().map(std::mem::discriminant));
            }
        }
        // Valid shapes, invalid triangles and broken structures of several
        // kinds all came up.
        assert!(answers.len() >= 5, "{}", answers.len());
    }
}
