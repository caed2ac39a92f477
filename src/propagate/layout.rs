//! Laying out a triangulated n-gon from its triangle angles: the one
//! layout every angle-based path, the target intermediate and
//! [`crate::morph::lay_out`] use (docs/design.md §6).
//!
//! With no interior vertices the dual tree is a tree, so any angle vector
//! lays out: the root edge is placed, then every triangle puts its third
//! vertex on its (already placed) base. The shape is unique up to a
//! similarity.
//!
//! Two things keep the result an immersion in the arithmetic we run, not
//! only in real numbers:
//! - each triangle's third vertex is placed relative to its parent edge as
//!   *world* coordinates, after the similarity that places the whole shape
//!   has been chosen (a first pass in a unit frame measures the shape for
//!   that choice). Moving a finished layout by a similarity would round a
//!   tiny triangle far from the origin flat;
//! - every placed triangle is tested with the exact orientation predicate
//!   and, where rounding left it clockwise or flat, its third vertex is
//!   moved off the base edge by the smallest steps of the coordinate grid
//!   until the predicate says counter-clockwise. The count of such repairs
//!   is returned.
//!
//! The length ratio of the law of sines, sin(a_y) / sin(a_w), is evaluated
//! with sin(a_w) = sin(a_x + a_y) where a_w is obtuse, so that a triangle
//! whose third angle is close to π keeps its digits.

use crate::geom::{Point, orient};
use crate::tree::Rooted;

/// Base-frame factor of each triangle: the third vertex sits at
/// `x + c · (y − x)` (complex product) on its base `x → y`. `angles` are
/// given per triangle as (base start, base end, third).
pub(crate) fn factors(angles: &[[f64; 3]]) -> Vec<Point> {
    angles.iter().map(|&a| factor(a)).collect()
}

/// The base-frame factor of one triangle with angles (base start, base
/// end, third).
pub(crate) fn factor([ax, ay, aw]: [f64; 3]) -> Point {
    let s_w = if aw > std::f64::consts::FRAC_PI_2 {
        (ax + ay).sin()
    } else {
        aw.sin()
    };
    Point::from_angle(ax) * (ay.sin() / s_w)
}

/// A similarity z ↦ a·z + b of the plane (a as a complex number).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Similarity {
    pub(crate) a: Point,
    pub(crate) b: Point,
}

impl Similarity {
    pub(crate) fn apply(&self, p: Point) -> Point {
        self.a.rotate(p) + self.b
    }
}

/// Places the layout: the root's base at `x0`, `y0`, then every triangle
/// in breadth-first order; returns the positions and the number of exact
/// orientation repairs.
pub(crate) fn place(
    rooted: &Rooted,
    factors: &[Point],
    x0: Point,
    y0: Point,
) -> (Vec<Point>, usize) {
    let n = rooted.order.len() + 2;
    let mut pos = vec![Point::ZERO; n];
    let [rx, ry] = rooted.base[rooted.root].map(|v| v as usize);
    pos[rx] = x0;
    pos[ry] = y0;
    let mut repairs = 0;
    for &tri in &rooted.order {
        let [x, y] = rooted.base[tri].map(|v| v as usize);
        let w = rooted.third[tri] as usize;
        let (px, py) = (pos[x], pos[y]);
        let e = py - px;
        let mut q = px + factors[tri].rotate(e);
        if !orient(px, py, q).is_ccw() {
            q = repair(px, py, q);
            repairs += 1;
        }
        pos[w] = q;
    }
    (pos, repairs)
}

/// Moves `w` off the base `x → y` to its left by the smallest steps of the
/// coordinate grid until `(x, y, w)` is exactly counter-clockwise.
fn repair(x: Point, y: Point, w: Point) -> Point {
    let e = y - x;
    let len = e.length();
    if len.is_nan() || len <= 0.0 || !w.is_finite() {
        return w;
    }
    let normal = e.perp() / len;
    let grid = [x, y, w]
        .iter()
        .map(|p| p.x.abs().max(p.y.abs()))
        .fold(f64::MIN_POSITIVE, f64::max)
        * f64::EPSILON;
    let mut step = grid;
    for _ in 0..64 {
        let q = w + normal * step;
        if orient(x, y, q).is_ccw() {
            return q;
        }
        step *= 2.0;
    }
    w
}

/// Lays out `factors` twice: once with the root edge from (0, 0) to
/// (1, 0) to measure the shape, then in world coordinates under the
/// similarity `fit` chooses from that measurement. Returns the positions
/// and the number of orientation repairs of the second pass.
pub(crate) fn lay_out_fitted(
    rooted: &Rooted,
    factors: &[Point],
    fit: impl FnOnce(&[Point]) -> Similarity,
) -> (Vec<Point>, usize) {
    let (unit, _) = place(rooted, factors, Point::ZERO, Point::X);
    let s = fit(&unit);
    place(rooted, factors, s.b, s.a + s.b)
}

/// The least-squares similarity (rotation, uniform scale, translation)
/// that maps `p` onto `q`.
pub(crate) fn fit_similarity(p: &[Point], q: &[Point]) -> Similarity {
    let n = p.len() as f64;
    let (cp, cq) = (
        p.iter().copied().sum::<Point>() / n,
        q.iter().copied().sum::<Point>() / n,
    );
    // As complex numbers: a = Σ conj(p̃) q̃ / Σ |p̃|².
    let (mut re, mut im, mut den) = (0.0, 0.0, 0.0);
    for (x, y) in p.iter().zip(q) {
        let (x, y) = (*x - cp, *y - cq);
        re += x.dot(y);
        im += x.perp_dot(y);
        den += x.length_squared();
    }
    if den.is_nan() || den <= 0.0 {
        return Similarity {
            a: Point::X,
            b: cq - cp,
        };
    }
    let a = Point::new(re / den, im / den);
    Similarity {
        a,
        b: cq - a.rotate(cp),
    }
}

/// Vertex fan sums of an angle vector given per triangle in the order of
/// `corners`.
pub(crate) fn fan_sums(n: usize, corners: &[[usize; 3]], angles: &[[f64; 3]]) -> Vec<f64> {
    let mut s = vec![0.0; n];
    for (c, a) in corners.iter().zip(angles) {
        for k in 0..3 {
            s[c[k]] += a[k];
        }
    }
    s
}

/// The closed-form blend of docs/design.md §6 and §7a: the smallest λ ∈ [0, 1]
/// such that every vertex fan of (1 − λ)·a + λ·b is at most `cap(v)`,
/// given the fan sums `sa` of `a` and `sb` of `b` (with `sb[v] < cap(v)`).
/// Fan sums are linear in λ, so λ is a maximum over vertices.
pub(crate) fn fan_blend(sa: &[f64], sb: &[f64], cap: impl Fn(usize) -> f64) -> f64 {
    let mut lambda: f64 = 0.0;
    for v in 0..sa.len() {
        let c = cap(v);
        if sa[v] > c && sa[v] > sb[v] {
            lambda = lambda.max((sa[v] - c) / (sa[v] - sb[v]));
        }
    }
    lambda.clamp(0.0, 1.0)
}

/// Linear interpolation of two angle triples.
pub(crate) fn lerp3(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::points;
    use crate::tree::DualTree;

    #[test]
    fn similarity_fit_recovers_a_similarity() {
        let p = points([(0.0, 0.0), (2.0, 0.0), (1.0, 3.0)]);
        let a = Point::new(0.6, -1.7);
        let q: Vec<Point> = p
            .iter()
            .map(|&x| a.rotate(x) + Point::new(5.0, -2.0))
            .collect();
        let f = fit_similarity(&p, &q);
        for (x, y) in p.iter().zip(&q) {
            assert!((f.apply(*x) - *y).length() < 1e-12);
        }
    }

    /// A fan of `n − 2` thin triangles from vertex 0 whose angles at the
    /// fan apex are ~1e-16: the law of sines in f64 rounds such triangles
    /// flat; the repaired layout keeps every one counter-clockwise.
    #[test]
    fn needle_triangles_stay_counter_clockwise() {
        let n = 40usize;
        let tris: Vec<[u32; 3]> = (1..n as u32 - 1).map(|i| [0, i, i + 1]).collect();
        let tree = DualTree::new(n, &tris).unwrap();
        let rooted = tree.rooted(tree.centre());
        // Corners in (base start, base end, third) order: 1.4e-16 at the
        // fan apex, the rest shared by the other two.
        let rest = std::f64::consts::PI - 1.4e-16;
        let angles: Vec<[f64; 3]> = (0..tris.len())
            .map(|t| {
                let [x, y] = rooted.base[t];
                [x, y, rooted.third[t]].map(|v| if v == 0 { 1.4e-16 } else { rest / 2.0 })
            })
            .collect();
        let f = factors(&angles);
        let (pos, repairs) = lay_out_fitted(&rooted, &f, |_| Similarity {
            a: Point::new(3.0, 1.0),
            b: Point::new(1e6, -2e5),
        });
        for t in &tris {
            let [a, b, c] = t.map(|v| pos[v as usize]);
            assert!(orient(a, b, c).is_ccw(), "{t:?}");
        }
        assert!(repairs > 0);
    }
}
