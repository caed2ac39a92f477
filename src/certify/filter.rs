//! The floating-point filter of the certificate: decides most triangles
//! and fans in `f64` with a proven error bound, and says "undecided"
//! (never "no") otherwise, leaving those to [`super::exact`].
//!
//! The quadratics are taken in the Bernstein basis of [0, 1]:
//! `q(s) = b₀(1 − s)² + 2b₁ s(1 − s) + b₂ s²`, where for a cross (or dot)
//! product of edge vectors moving linearly, `b₀` is the product at s = 0,
//! `b₂` at s = 1 and `b₁` the mean of the two mixed products. `q > 0` on
//! [0, 1] iff `b₀ > 0`, `b₂ > 0` and (`b₁ ≥ 0` or `b₁² < b₀b₂`): with
//! x = s/(1 − s) ∈ [0, ∞), `q/(1 − s)² = b₀ + 2b₁x + b₂x²`.
//!
//! **Error bound.** Every value carries a bound on its distance from the
//! exact value of the same expression ([`Fe`]): a difference or product of
//! `f64` values rounds by at most u = 2⁻⁵³ of its magnitude, plus 2⁻¹⁰⁷⁵
//! where a product underflows; the bounds add the propagated errors
//! (|a|·e_b + |b|·e_a + e_a·e_b for a product) and the rounding of the
//! result, are themselves computed in floating point and so are enlarged
//! by the factor 1 + 2⁻⁴⁰ (far more than the few roundings of the bound's
//! own arithmetic) plus 2⁻¹⁰⁰⁰ (every underflow of the bound's
//! arithmetic). A value is *surely positive* when `v > e`, a comparison of
//! two doubles, which then holds for the exact value. An overflow gives
//! ∞ or NaN, which is never surely anything: undecided.

use crate::geom::Point;

/// Unit roundoff of `f64`.
const U: f64 = f64::EPSILON / 2.0;
/// Enlargement of every computed bound.
const GROW: f64 = 1.0 + 1.0 / (1u64 << 40) as f64;
/// Absolute slack of every computed bound (underflow).
const ETA: f64 = 9.332_636_185_032_189e-302; // 2^-1000

/// A computed value and a bound on its error.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fe {
    v: f64,
    e: f64,
}

impl Fe {
    /// An exact value.
    pub(crate) fn exact(v: f64) -> Fe {
        Fe { v, e: 0.0 }
    }

    /// An upper bound `v ≥ x` of a nonnegative quantity x, as a value whose
    /// error bound covers the whole of `[0, v]` from `v`'s side: used for
    /// margins, where only an upper bound matters.
    fn upper(v: f64) -> Fe {
        Fe { v, e: 0.0 }
    }

    fn add(self, o: Fe) -> Fe {
        let v = self.v + o.v;
        Fe {
            v,
            e: (self.e + o.e + U * v.abs()) * GROW + ETA,
        }
    }

    fn sub(self, o: Fe) -> Fe {
        let v = self.v - o.v;
        Fe {
            v,
            e: (self.e + o.e + U * v.abs()) * GROW + ETA,
        }
    }

    fn mul(self, o: Fe) -> Fe {
        let v = self.v * o.v;
        Fe {
            v,
            e: (self.v.abs() * o.e + o.v.abs() * self.e + self.e * o.e + U * v.abs()) * GROW + ETA,
        }
    }

    fn half(self) -> Fe {
        Fe {
            v: self.v * 0.5,
            e: self.e * 0.5 + ETA,
        }
    }

    fn neg(self) -> Fe {
        Fe {
            v: -self.v,
            e: self.e,
        }
    }

    /// The exact value is > 0.
    fn pos(self) -> bool {
        self.v > self.e
    }

    /// The exact value is ≥ 0.
    fn nonneg(self) -> bool {
        self.v >= self.e && self.e.is_finite()
    }
}

/// A Bernstein quadratic on [0, 1] with error bounds.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bern([Fe; 3]);

impl Bern {
    fn minus(self, m: Fe) -> Bern {
        Bern(self.0.map(|b| b.sub(m)))
    }

    fn neg(self) -> Bern {
        Bern(self.0.map(Fe::neg))
    }

    /// Surely positive on [0, 1] (false: undecided).
    fn positive(self) -> bool {
        let [b0, b1, b2] = self.0;
        b0.pos() && b2.pos() && (b1.nonneg() || b0.mul(b2).sub(b1.mul(b1)).pos())
    }
}

/// An edge vector `to − from` at both ends of the segment, with its
/// rounding bounds.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Edge {
    x0: Fe,
    y0: Fe,
    x1: Fe,
    y1: Fe,
}

impl Edge {
    /// The edge from vertex `a` to vertex `b`.
    pub(crate) fn new(p: &[Point], q: &[Point], a: usize, b: usize) -> Edge {
        let d = |u: f64, v: f64| Fe::exact(u).sub(Fe::exact(v));
        Edge {
            x0: d(p[b].x, p[a].x),
            y0: d(p[b].y, p[a].y),
            x1: d(q[b].x, q[a].x),
            y1: d(q[b].y, q[a].y),
        }
    }

    /// The part of the edge's motion on `[l, r]` of the segment, as an
    /// edge moving linearly from its vector at `l` to its vector at `r`
    /// (bounds included).
    fn on(&self, l: f64, r: f64) -> Edge {
        let at = |a: Fe, b: Fe, s: f64| a.add(Fe::exact(s).mul(b.sub(a)));
        Edge {
            x0: at(self.x0, self.x1, l),
            y0: at(self.y0, self.y1, l),
            x1: at(self.x0, self.x1, r),
            y1: at(self.y0, self.y1, r),
        }
    }

    /// An upper bound of the larger 1-norm at the two ends.
    fn norm1(&self) -> f64 {
        let n0 = (self.x0.v.abs() + self.x0.e) + (self.y0.v.abs() + self.y0.e);
        let n1 = (self.x1.v.abs() + self.x1.e) + (self.y1.v.abs() + self.y1.e);
        n0.max(n1) * GROW + ETA
    }
}

fn cross(ax: Fe, ay: Fe, bx: Fe, by: Fe) -> Fe {
    ax.mul(by).sub(ay.mul(bx))
}

fn dot(ax: Fe, ay: Fe, bx: Fe, by: Fe) -> Fe {
    ax.mul(bx).add(ay.mul(by))
}

/// `form(u(s), w(s))` in the Bernstein basis, for a bilinear `form`
/// ([`cross`] or [`dot`]) of two edges moving linearly in s.
fn bern(u: &Edge, w: &Edge, form: fn(Fe, Fe, Fe, Fe) -> Fe) -> Bern {
    Bern([
        form(u.x0, u.y0, w.x0, w.y0),
        form(u.x0, u.y0, w.x1, w.y1)
            .add(form(u.x1, u.y1, w.x0, w.y0))
            .half(),
        form(u.x1, u.y1, w.x1, w.y1),
    ])
}

/// `cross(u(s), w(s))` in the Bernstein basis.
fn cross_bern(u: &Edge, w: &Edge) -> Bern {
    bern(u, w, cross)
}

/// `dot(u(s), w(s))` in the Bernstein basis.
fn dot_bern(u: &Edge, w: &Edge) -> Bern {
    bern(u, w, dot)
}

/// Upper bound of the margin `L_u δ_w + L_w δ_u + 2 δ_u δ_w` (module docs
/// of `certify`), from the edges and upper bounds of their displacement
/// bounds `du`, `dw`.
fn margin(u: &Edge, w: &Edge, du: f64, dw: f64) -> Fe {
    if du == 0.0 && dw == 0.0 {
        return Fe::exact(0.0);
    }
    let m = u.norm1() * dw + w.norm1() * du + 2.0 * du * dw;
    Fe::upper(m * GROW + ETA)
}

/// Surely: the triangle `(a, b, c)` keeps `2·area > M` on [0, 1], where M
/// is the margin of the vertex displacement bounds `delta` (upper bounds,
/// zero for an exact player). False: undecided.
pub(crate) fn triangle(p: &[Point], q: &[Point], corners: [usize; 3], delta: &[f64]) -> bool {
    let (e1, e2, d1, d2) = triangle_edges(p, q, corners, delta);
    triangle_on(&e1, &e2, d1, d2)
}

/// The edges of triangle `(a, b, c)` out of its first corner, with their
/// displacement bounds.
fn triangle_edges(
    p: &[Point],
    q: &[Point],
    [a, b, c]: [usize; 3],
    delta: &[f64],
) -> (Edge, Edge, f64, f64) {
    (
        Edge::new(p, q, a, b),
        Edge::new(p, q, a, c),
        delta[a] + delta[b],
        delta[a] + delta[c],
    )
}

/// The triangle test on the edges `e1`, `e2` out of its first corner,
/// with their displacement bounds.
fn triangle_on(e1: &Edge, e2: &Edge, d1: f64, d2: f64) -> bool {
    cross_bern(e1, e2).minus(margin(e1, e2, d1, d2)).positive()
}

/// Surely: the fan at `v` never comes near a full turn on [0, 1] (its
/// first and last edges stay out of the cone that the margin allows).
/// False: undecided.
pub(crate) fn fan(p: &[Point], q: &[Point], v: usize, delta: &[f64]) -> bool {
    let (a, b, da, db) = fan_edges(p, q, v, delta);
    fan_on(&a, &b, da, db)
}

/// The first and last edges of the fan at `v` (to its next and previous
/// vertex), with their displacement bounds.
fn fan_edges(p: &[Point], q: &[Point], v: usize, delta: &[f64]) -> (Edge, Edge, f64, f64) {
    let n = p.len();
    let (next, prev) = ((v + 1) % n, (v + n - 1) % n);
    (
        Edge::new(p, q, v, next),
        Edge::new(p, q, v, prev),
        delta[v] + delta[next],
        delta[v] + delta[prev],
    )
}

/// The fan test on its first and last edges `a`, `b`, with their
/// displacement bounds.
fn fan_on(a: &Edge, b: &Edge, da: f64, db: f64) -> bool {
    let k = margin(a, b, da, db);
    let c = cross_bern(a, b);
    // |cross| > k throughout, or dot < −k throughout.
    c.minus(k).positive() || c.neg().minus(k).positive() || dot_bern(a, b).neg().minus(k).positive()
}

/// Most pieces [`triangle_in_pieces`] and [`fan_in_pieces`] try.
const PIECES: usize = 256;

/// [`triangle`] on `[s0, s1]` cut in pieces, each with the margin of its
/// own ends (at most [`PIECES`], halving where a piece is undecided).
/// The margin of a whole segment takes each edge's larger norm at its
/// ends, which overstates it where an edge shrinks in the middle; on a
/// piece the norms at its own ends bound the edge there. True: every
/// piece surely keeps `2·area > M`, so the span does.
pub(crate) fn triangle_in_pieces(
    p: &[Point],
    q: &[Point],
    corners: [usize; 3],
    delta: &[f64],
    [s0, s1]: [f64; 2],
) -> bool {
    let (e1, e2, d1, d2) = triangle_edges(p, q, corners, delta);
    in_pieces(s0, s1, |l, r| {
        triangle_on(&e1.on(l, r), &e2.on(l, r), d1, d2)
    })
}

/// [`fan`] on `[s0, s1]` cut in pieces, as [`triangle_in_pieces`].
pub(crate) fn fan_in_pieces(
    p: &[Point],
    q: &[Point],
    v: usize,
    delta: &[f64],
    [s0, s1]: [f64; 2],
) -> bool {
    let (a, b, da, db) = fan_edges(p, q, v, delta);
    in_pieces(s0, s1, |l, r| fan_on(&a.on(l, r), &b.on(l, r), da, db))
}

/// Whether `test` holds on every piece of `[s0, s1]`, halving undecided
/// pieces, with at most [`PIECES`] tested.
fn in_pieces(s0: f64, s1: f64, test: impl Fn(f64, f64) -> bool) -> bool {
    let mut todo = vec![(s0, s1)];
    let mut tested = 0;
    while let Some((l, r)) = todo.pop() {
        if tested == PIECES {
            return false;
        }
        tested += 1;
        if test(l, r) {
            continue;
        }
        let m = 0.5 * (l + r);
        if !(l < m && m < r) {
            return false;
        }
        todo.push((m, r));
        todo.push((l, m));
    }
    true
}

/// Upper bounds of the vertex displacement bounds δ_v = 2^shift · m_v
/// (m_v the largest coordinate magnitude of v at either end).
pub(crate) fn deltas(p: &[Point], q: &[Point], shift: Option<i32>) -> Vec<f64> {
    let Some(shift) = shift else {
        return vec![0.0; p.len()];
    };
    let f = 2f64.powi(shift);
    p.iter()
        .zip(q)
        .map(|(a, b)| {
            let m = a.x.abs().max(a.y.abs()).max(b.x.abs()).max(b.y.abs());
            m * f * GROW + ETA
        })
        .collect()
}

/// The point `p + s(q − p)` with error bounds per coordinate.
pub(crate) fn point_at(p: Point, q: Point, s: f64) -> [Fe; 2] {
    let f = |a: f64, b: f64| {
        let (a, b) = (Fe::exact(a), Fe::exact(b));
        a.add(Fe::exact(s).mul(b.sub(a)))
    };
    [f(p.x, q.x), f(p.y, q.y)]
}

/// The sign of `orient(a, b, c)` when the bounds decide it.
pub(crate) fn orient_sign(a: [Fe; 2], b: [Fe; 2], c: [Fe; 2]) -> Option<i32> {
    let det = cross(
        b[0].sub(a[0]),
        b[1].sub(a[1]),
        c[0].sub(a[0]),
        c[1].sub(a[1]),
    );
    if det.pos() {
        Some(1)
    } else if det.neg().pos() {
        Some(-1)
    } else {
        None
    }
}

/// True when the two points surely differ.
pub(crate) fn surely_apart(a: [Fe; 2], b: [Fe; 2]) -> bool {
    (0..2).any(|k| {
        let d = a[k].sub(b[k]);
        d.pos() || d.neg().pos()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bernstein_positivity() {
        let b = |x: [f64; 3]| Bern(x.map(Fe::exact));
        assert!(b([1.0, -0.9, 1.0]).positive());
        assert!(!b([1.0, -1.0, 1.0]).positive());
        assert!(!b([1.0, -1.1, 1.0]).positive());
        assert!(b([1.0, 5.0, 1e-300]).positive());
        assert!(!b([0.0, 1.0, 1.0]).positive());
        // An overflow is never surely positive.
        let big = Fe::exact(1e300).mul(Fe::exact(1e300));
        assert!(!big.pos() && !big.nonneg());
        assert!(!Bern([big, Fe::exact(1.0), Fe::exact(1.0)]).positive());
        assert!(!b([1.0, f64::NAN, 1.0]).positive());
    }
}
