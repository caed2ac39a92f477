//! Immersed Delaunay edge flips (Mukherjee & Gopi §4, Algorithm 1).
//!
//! Start from any immersion triangulation, keep a stack of diagonals, pop
//! one, and flip it when it is not locally Delaunay; then push the four
//! edges of its quadrilateral that are diagonals and not already queued.
//!
//! ```text
//!        c                    c
//!       / \                  /|\
//!      /   \                / | \
//!     a-----b     ==>      a  |  b
//!      \   /                \ | /
//!       \ /                  \|/
//!        d                    d
//!  (a,b,c), (b,a,d)     (a,d,c), (d,b,c)
//! ```
//!
//! `ab` is not locally Delaunay when `d` lies strictly inside the circumcircle
//! of the counter-clockwise triangle `(a, b, c)` (exact [`in_circle`];
//! co-circular quads are left alone). Then the opposite angles sum to more than
//! π, the quad `a, d, b, c` is strictly convex, and the flip leaves every
//! vertex's fan sum and fan order unchanged, so both new triangles are valid
//! (docs/design.md §3): that is a debug assertion, not a branch. Each flip
//! raises the sorted angle vector lexicographically, so the loop terminates;
//! the result is locally Delaunay everywhere (for a simple polygon: its
//! constrained Delaunay triangulation).
//!
//! The combinatorics ([`Adjacency`]) work on indices only; coordinates enter
//! only through the in-circle test. Complexity: O(n) per pass over the
//! stack plus O(1) per flip; the number of flips is O(n²) in the worst case.

use std::collections::HashMap;

use crate::geom::Point;
use crate::geom::predicates::in_circle;
use crate::immersion::Immersion;

const NONE: u32 = u32::MAX;

/// An undirected edge, smaller index first.
type Edge = (u32, u32);

fn edge(a: u32, b: u32) -> Edge {
    (a.min(b), a.max(b))
}

/// The corner of `t` that is not on edge `e`.
fn third(t: [u32; 3], e: Edge) -> u32 {
    t.into_iter()
        .find(|&v| v != e.0 && v != e.1)
        .unwrap_or(NONE)
}

/// Rotate the counter-clockwise triangle `t` (corners increasing) so that
/// `apex` comes last: returns `(a, b)` with `(a, b, apex)` counter-clockwise.
fn ccw_base(t: [u32; 3], apex: u32) -> (u32, u32) {
    match t.iter().position(|&v| v == apex) {
        Some(0) => (t[1], t[2]),
        Some(1) => (t[2], t[0]),
        _ => (t[0], t[1]),
    }
}

fn sorted(mut t: [u32; 3]) -> [u32; 3] {
    t.sort_unstable();
    t
}

/// Edge → incident triangles of a triangulated polygon (index-only).
#[derive(Debug, Default)]
pub(crate) struct Adjacency {
    /// For each edge: the (one or two) triangles on it and whether it is
    /// currently on the stack.
    edges: HashMap<Edge, ([u32; 2], bool)>,
}

impl Adjacency {
    pub(crate) fn new(triangles: &[[u32; 3]]) -> Self {
        let mut edges: HashMap<Edge, ([u32; 2], bool)> =
            HashMap::with_capacity(triangles.len() * 2);
        for (t, &[a, b, c]) in triangles.iter().enumerate() {
            for e in [edge(a, b), edge(b, c), edge(a, c)] {
                let entry = edges.entry(e).or_insert(([NONE, NONE], false));
                if entry.0[0] == NONE {
                    entry.0[0] = t as u32;
                } else {
                    entry.0[1] = t as u32;
                }
            }
        }
        Self { edges }
    }

    /// The two triangles of a diagonal, or `None` for a polygon edge.
    pub(crate) fn pair(&self, e: Edge) -> Option<[u32; 2]> {
        self.edges
            .get(&e)
            .and_then(|&(t, _)| (t[1] != NONE).then_some(t))
    }

    /// Mark `e` queued; returns whether it was a diagonal not yet queued.
    fn enqueue(&mut self, e: Edge) -> bool {
        match self.edges.get_mut(&e) {
            Some((t, queued)) if t[1] != NONE && !*queued => {
                *queued = true;
                true
            }
            _ => false,
        }
    }

    fn dequeue(&mut self, e: Edge) {
        if let Some((_, queued)) = self.edges.get_mut(&e) {
            *queued = false;
        }
    }

    /// Replace triangle `from` by `to` on edge `e`.
    fn retarget(&mut self, e: Edge, from: u32, to: u32) {
        if let Some((t, _)) = self.edges.get_mut(&e) {
            for x in t.iter_mut() {
                if *x == from {
                    *x = to;
                }
            }
        }
    }

    /// Flip the diagonal `ab` of the triangles `t0 = (a, b, c)` and
    /// `t1 = (b, a, d)` (both counter-clockwise) to `cd`, updating
    /// `triangles` and the adjacency.
    fn flip(&mut self, triangles: &mut [[u32; 3]], [t0, t1]: [u32; 2], [a, b, c, d]: [u32; 4]) {
        triangles[t0 as usize] = sorted([a, d, c]);
        triangles[t1 as usize] = sorted([d, b, c]);
        self.edges.remove(&edge(a, b));
        self.edges.insert(edge(c, d), ([t0, t1], false));
        self.retarget(edge(a, d), t1, t0);
        self.retarget(edge(b, c), t0, t1);
    }
}

/// Flip an immersion triangulation to an immersed Delaunay one
/// (Mukherjee & Gopi Algorithm 1; module docs). The points are unchanged, only
/// the triangles.
///
/// The input should be an immersion triangulation (e.g. from
/// [`crate::immersion::triangulate`]); input that fails
/// [`crate::immersion::check`] is returned unchanged.
///
/// # Examples
///
/// ```
/// use immerse::geom::Point;
/// use immerse::{immersion::triangulate, quality::improve};
/// let pts: Vec<Point> = (0..12)
///     .map(|i| {
///         let a = i as f64 * std::f64::consts::TAU / 12.0;
///         let r = if i % 2 == 0 { 1.0 } else { 0.6 };
///         Point::new(r * a.cos(), r * a.sin())
///     })
///     .collect();
/// let any = triangulate(&pts)?;
/// let del = improve(any.clone());
/// assert!(del.is_immersion());
/// assert!(del.min_angle() >= any.min_angle());
/// # Ok::<(), immerse::immersion::NotSelfOverlapping>(())
/// ```
pub fn improve(imm: Immersion) -> Immersion {
    let Immersion {
        points,
        mut triangles,
    } = imm;
    // Termination and validity rest on the input being an immersion
    // triangulation; anything else is returned unchanged (O(n log n) check).
    if crate::immersion::check(&points, &triangles).is_err() {
        return Immersion { points, triangles };
    }
    let mut adj = Adjacency::new(&triangles);
    let mut stack: Vec<Edge> = adj.edges.keys().copied().collect();
    stack.sort_unstable(); // deterministic order
    stack.retain(|&e| adj.enqueue(e));
    while let Some(e) = stack.pop() {
        adj.dequeue(e);
        let Some([t0, t1]) = adj.pair(e) else {
            continue;
        };
        let c = third(triangles[t0 as usize], e);
        let d = third(triangles[t1 as usize], e);
        if c == NONE || d == NONE {
            continue;
        }
        let (a, b) = ccw_base(triangles[t0 as usize], c);
        if !is_flippable(&points, a, b, c, d) {
            continue;
        }
        adj.flip(&mut triangles, [t0, t1], [a, b, c, d]);
        debug_assert!(
            [triangles[t0 as usize], triangles[t1 as usize]]
                .iter()
                .all(|&[x, y, z]| {
                    crate::immersion::is_valid_triangle(&points, x as usize, y as usize, z as usize)
                }),
            "a Delaunay flip produced an invalid triangle: a bug"
        );
        for q in [edge(a, c), edge(c, b), edge(b, d), edge(d, a)] {
            if adj.enqueue(q) {
                stack.push(q);
            }
        }
    }
    triangles.sort_unstable();
    Immersion { points, triangles }
}

/// `ab` (with `(a, b, c)` counter-clockwise and `d` across `ab`) is not
/// locally Delaunay: `d` strictly inside the circumcircle of `(a, b, c)`.
fn is_flippable(points: &[Point], a: u32, b: u32, c: u32, d: u32) -> bool {
    let p = |v: u32| points[v as usize];
    in_circle(p(a), p(b), p(c), p(d))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::immersion::triangulate;

    #[test]
    fn square_with_bad_diagonal_flips() {
        // A kite where diagonal 0–2 is not Delaunay.
        let pts = vec![
            Point::new(0.0, 0.0),
            Point::new(2.0, -0.5),
            Point::new(4.0, 0.0),
            Point::new(2.0, 0.5),
        ];
        let imm = Immersion {
            points: pts,
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        };
        let out = improve(imm);
        assert_eq!(out.triangles, vec![[0, 1, 3], [1, 2, 3]]);
        assert!(out.is_immersion());
    }

    #[test]
    fn non_immersions_come_back_unchanged() {
        let pts = vec![
            Point::new(0.0, 0.0),
            Point::new(2.0, 0.5),
            Point::new(4.0, 0.0),
            Point::new(2.0, -0.5),
        ]; // clockwise
        let bad = Immersion {
            points: pts,
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        };
        assert_eq!(improve(bad.clone()), bad);
        let garbage = Immersion {
            points: bad.points.clone(),
            triangles: vec![[0, 7, 2], [3, 3, 3], [1, 0, 2]],
        };
        assert_eq!(improve(garbage.clone()), garbage);
    }

    #[test]
    fn flips_keep_an_immersion_on_spirals() {
        // A spiral strip that overlaps itself.
        let n = 40;
        let mut pts = Vec::new();
        for i in 0..n {
            let a = i as f64 / (n - 1) as f64 * 3.0 * std::f64::consts::PI;
            pts.push(Point::new(
                (2.0 + 0.2 * a) * a.cos(),
                (2.0 + 0.2 * a) * a.sin(),
            ));
        }
        for i in (0..n).rev() {
            let a = i as f64 / (n - 1) as f64 * 3.0 * std::f64::consts::PI;
            pts.push(Point::new(
                (1.0 + 0.2 * a) * a.cos(),
                (1.0 + 0.2 * a) * a.sin(),
            ));
        }
        let imm = triangulate(&pts).expect("spiral strip is self-overlapping");
        let before = imm.min_angle();
        let out = improve(imm);
        assert_eq!(crate::immersion::check(&out.points, &out.triangles), Ok(()));
        assert!(out.min_angle() >= before);
    }
}
