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
//! `ab` is not locally Delaunay when `d` lies strictly inside the
//! circumcircle of the counter-clockwise triangle `(a, b, c)` (exact
//! [`in_circle`]; co-circular quads are left alone). Then the opposite
//! angles sum to more than π, the quad `a, d, b, c` is strictly convex, and
//! the flip leaves every vertex's fan sum and fan order unchanged, so both
//! new triangles are valid (docs/design.md §3): that is a debug assertion, not a
//! branch. Each flip raises the sorted angle vector lexicographically, so
//! the loop terminates; the result is locally Delaunay everywhere (for a
//! simple polygon: its constrained Delaunay triangulation).
//!
//! The combinatorics ([`crate::flip::FlipTriangulation`], shared with the
//! staged morph) work on indices only; coordinates enter
//! only through the in-circle test. Complexity: O(n) per pass over the
//! stack plus O(1) per flip; the number of flips is O(n²) in the worst case.

use crate::flip::{FlipTriangulation, key};
use crate::geom::Point;
use crate::geom::predicates::in_circle;
use crate::immersion::Immersion;

/// Flip an immersion triangulation to an immersed Delaunay one (Mukherjee & Gopi
/// Algorithm 1; module docs). The points are unchanged, only the triangles.
///
/// The input should be an immersion triangulation (e.g. from
/// [`crate::immersion::triangulate`]); input that fails
/// [`crate::immersion::check`] is returned unchanged.
///
/// # Examples
///
/// ```
/// use immerse::geom::Point;
/// use immerse::{improve, triangulate};
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
/// # Ok::<(), immerse::NotSelfOverlapping>(())
/// ```
pub fn improve(imm: Immersion) -> Immersion {
    let Immersion { points, triangles } = imm;
    // Termination and validity rest on the input being an immersion
    // triangulation; anything else is returned unchanged (O(n log n) check).
    if crate::immersion::check(&points, &triangles).is_err() {
        return Immersion { points, triangles };
    }
    let triangles = flip_while(points.len(), &triangles, |[a, b, c, d]| {
        if !is_flippable(&points, a, b, c, d) {
            return false;
        }
        debug_assert!(
            [[a, b, d], [b, c, d]].iter().all(|&t| valid_on(&points, t)),
            "a Delaunay flip produced an invalid triangle: a bug"
        );
        true
    });
    Immersion { points, triangles }
}

/// Improve a triangulation that is an immersion triangulation of every
/// curve in `curves` (a common triangulation, see
/// [`crate::immersion::common_triangulation`]) while it stays one: a
/// diagonal is flipped when both new triangles are valid on every curve
/// and the smallest angle of the quad, over all curves, grows. Each flip
/// raises the sorted vector of per-triangle smallest angles
/// lexicographically, so the loop terminates. Triangulations that are not
/// common to the curves come back unchanged.
pub(crate) fn improve_common(curves: &[&[Point]], triangles: Vec<[u32; 3]>) -> Vec<[u32; 3]> {
    let Some(n) = curves.first().map(|c| c.len()) else {
        return triangles;
    };
    if curves
        .iter()
        .any(|c| c.len() != n || crate::immersion::check(c, &triangles).is_err())
    {
        return triangles;
    }
    // A triangle's value is computed from one fixed rotation of its
    // corners, so that it is the same number whichever quad asks: with
    // values that depend on the order, rounding could make a flip and its
    // reverse both look better, and the loop would not end.
    let worst = |t: [u32; 3]| {
        let t = crate::flip::canonical(t);
        curves
            .iter()
            .map(|c| {
                let p = |v: u32| c[v as usize];
                crate::geom::polygon::sin2_min_angle(p(t[0]), p(t[1]), p(t[2]))
            })
            .fold(f64::INFINITY, f64::min)
    };
    flip_while(n, &triangles, |[a, b, c, d]| {
        let new = [[a, b, d], [b, c, d]];
        let old = worst([a, b, c]).min(worst([a, c, d]));
        worst(new[0]).min(worst(new[1])) > old
            && curves.iter().all(|c| new.iter().all(|&t| valid_on(c, t)))
    })
}

/// Is the triangle (corners in cyclic order) valid on `points`? Sorted, as
/// the validity predicate takes its corners (`d` may come before `a`: the
/// quad is `a, b, c, d` cyclically).
fn valid_on(points: &[Point], t: [u32; 3]) -> bool {
    let [x, y, z] = crate::flip::canonical(t);
    crate::immersion::is_valid_triangle(points, x as usize, y as usize, z as usize)
}

/// The flip loop shared by the improvements: keep a stack of diagonals, pop
/// one, and flip it when `should_flip` accepts its quad `[a, b, c, d]`
/// (cyclic order around diagonal `a–c`, `(a, b, c)` counter-clockwise, `d`
/// across `a–c`); then push the four edges of the quad that are diagonals
/// and not already queued. Returns the triangles sorted.
fn flip_while(
    n: usize,
    triangles: &[[u32; 3]],
    mut should_flip: impl FnMut([u32; 4]) -> bool,
) -> Vec<[u32; 3]> {
    let mut tri = FlipTriangulation::new(n, triangles);
    let mut stack: Vec<(u32, u32)> = tri.diagonals();
    let mut queued: rustc_hash::FxHashSet<(u32, u32)> = stack.iter().copied().collect();
    // Popped from the largest: deterministic.
    while let Some(e) = stack.pop() {
        queued.remove(&e);
        let Some((quad, _)) = tri.quad(e.0, e.1) else {
            continue;
        };
        if !should_flip(quad) {
            continue;
        }
        let [a, b, c, d] = quad;
        tri.flip(a, c);
        for q in [key(a, b), key(b, c), key(c, d), key(d, a)] {
            if q.1 - q.0 != 1 && q.1 - q.0 != n as u32 - 1 && queued.insert(q) {
                stack.push(q);
            }
        }
    }
    let mut triangles = tri.triangles().to_vec();
    triangles.sort_unstable();
    triangles
}

/// Diagonal `a–c` of the quad `a, b, c, d` (with `(a, b, c)`
/// counter-clockwise and `d` across `a–c`) is not locally Delaunay: `d`
/// strictly inside the circumcircle of `(a, b, c)`.
fn is_flippable(points: &[Point], a: u32, b: u32, c: u32, d: u32) -> bool {
    let p = |v: u32| points[v as usize];
    in_circle(p(a), p(b), p(c), p(d))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::immersion::triangulate;
    use crate::testing::points;

    #[test]
    fn square_with_bad_diagonal_flips() {
        // A kite where diagonal 0–2 is not Delaunay.
        let pts = points([(0.0, 0.0), (2.0, -0.5), (4.0, 0.0), (2.0, 0.5)]).to_vec();
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
        let pts = points([(0.0, 0.0), (2.0, 0.5), (4.0, 0.0), (2.0, -0.5)]).to_vec(); // clockwise
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
