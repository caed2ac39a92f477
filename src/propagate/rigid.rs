//! The as-rigid-as-possible guide (docs/design.md §6, the `rigid` path;
//! Alexa, Cohen-Or & Levin, *As-Rigid-As-Possible Shape Interpolation*).
//!
//! Each triangle's linear map from the source to the end, A = R(θ)S (polar
//! decomposition: a rotation and a symmetric positive stretch), is
//! interpolated as A(t) = R(tθ)S^t: the rotation and the stretch
//! separately, so a turning part turns instead of shrinking through its
//! centre. The stretch is interpolated geometrically (its eigenvalues
//! λᵗ), where Alexa et al. interpolate it linearly ((1 − t)I + tS): then a
//! triangle's area moves monotonically between its ends' instead of
//! swelling past both when it is stretched one way and squeezed the other. The positions at t are the least-squares fit of every
//! triangle's map to its A(t), weighted by source area (a sparse system
//! whose matrix does not depend on t).
//!
//! The rotations are unwound along the dual tree: each triangle's θ is
//! taken within half a turn of its parent's, not in (−π, π], so a strip
//! that winds several turns further at one end than at the other winds up
//! along its turns. The whole vector of rotations is then shifted by the
//! whole turns that put its area-weighted median in (−π, π].
//!
//! The system is solved in O(n) per frame: a triangulated polygon (no
//! interior vertex) always has an ear, a vertex in one triangle, whose two
//! neighbours are adjacent, so eliminating ears one by one creates no
//! fill-in. The matrix is factored once.
//!
//! Thin triangles far apart in size make the matrix so ill-conditioned
//! that one solve in double precision is accurate to a few digits only, and
//! its rounding changes from one t to the next: the guide, and every frame
//! laid out from it, would shake. Where the elimination cancels much of a
//! diagonal entry, the solve is refined with residuals taken per triangle
//! ([`RigidGuide::at_checked`]); a guide whose refinement cannot reach
//! 10⁻⁶ of its extent is not used (the straight guide stands in, and the
//! morph's report says so).

use crate::geom::Point;
use crate::tree::Rooted;
use std::f64::consts::{PI, TAU};

/// Per triangle: its corners, its area-weighted gradient operator and its
/// interpolated map's rotation and stretch.
#[derive(Clone, Debug)]
struct Element {
    corners: [usize; 3],
    /// w·K where K = D F⁻¹ (3 × 2): row k is the gradient of corner k's
    /// hat function on the source triangle, w its area.
    wk: [[f64; 2]; 3],
    /// The source area w.
    area: f64,
    /// The unwound rotation angle θ.
    theta: f64,
    /// The stretch S = Q diag(e^l₁, e^l₂) Qᵀ: with c, s the cosine and
    /// sine of the angle of Q's first column, (c², s², cs), and the
    /// logarithms of the eigenvalues.
    stretch: ([f64; 3], [f64; 2]),
}

/// One elimination step: vertex `v`, its pivot, and the multipliers of its
/// (at most two) remaining neighbours.
#[derive(Clone, Debug)]
struct Step {
    v: usize,
    pivot: f64,
    next: [(usize, f64); 2],
    count: usize,
}

/// The as-rigid-as-possible interpolation between two shapes sharing a
/// triangulation, factored once, evaluated at any t in O(n).
#[derive(Clone, Debug)]
pub(crate) struct RigidGuide {
    elements: Vec<Element>,
    steps: Vec<Step>,
    /// The vertex held at the origin while solving.
    pinned: usize,
    means: [Point; 2],
    n: usize,
    /// Whether [`RigidGuide::at`] refines its solve: the elimination
    /// cancelled more than [`REFINE_GROWTH`] of some diagonal entry.
    refined: bool,
}

/// The cancellation (assembled diagonal entry ÷ its pivot) beyond which
/// the solve is refined. The solve's relative error grows about as this
/// ratio times the f64 epsilon, and it varies from one t to the next, not
/// smoothly: thin triangles far apart in size (ratios of 10¹⁰ and more in
/// the stress generators) would make the guide, and every frame laid out
/// from it, shake.
const REFINE_GROWTH: f64 = 1e4;

/// The refinement stops once its correction is at most this fraction of
/// the guide's extent, or once it stops halving (it has reached the
/// rounding of the residual), or after [`REFINE_STEPS`].
const REFINE_TOLERANCE: f64 = 1e-9;

/// The solve is accurate where the last correction was at most this
/// fraction of the guide's extent: the guide then moves by no more than
/// about this much between one t and the next beyond its own motion.
const REFINE_ACCEPT: f64 = 1e-6;

/// The most refinement steps of one solve.
const REFINE_STEPS: usize = 24;

impl RigidGuide {
    /// The interpolation from `src` to the end whose triangle `i` has edge
    /// vectors `ends[i]` (from its first corner to its second and third,
    /// corners as in `rooted`'s triangulation `triangles`), with the ends'
    /// vertex means `means`. Every triangle must be counter-clockwise on
    /// `src` and every end edge pair counter-clockwise; `None` where the
    /// system cannot be factored in floating point (a degenerate source).
    pub(crate) fn new(
        src: &[Point],
        triangles: &[[u32; 3]],
        ends: &[[Point; 2]],
        rooted: &Rooted,
        means: [Point; 2],
    ) -> Option<RigidGuide> {
        let n = src.len();
        let m = triangles.len();
        let mut raw = Vec::with_capacity(m);
        for (t, tri) in triangles.iter().enumerate() {
            let c = tri.map(|v| v as usize);
            let (f0, f1) = (src[c[1]] - src[c[0]], src[c[2]] - src[c[0]]);
            let det = f0.perp_dot(f1);
            if !(det > 0.0 && det.is_finite()) {
                return None;
            }
            // F⁻¹ with F = [f0 f1] (columns).
            let inv = [[f1.y / det, -f1.x / det], [-f0.y / det, f0.x / det]];
            // K = D F⁻¹, D = [[-1, -1], [1, 0], [0, 1]].
            let k1 = inv[0];
            let k2 = inv[1];
            let k0 = [-k1[0] - k2[0], -k1[1] - k2[1]];
            let w = 0.5 * det;
            let wk = [k0, k1, k2].map(|r| [w * r[0], w * r[1]]);
            // A = G F⁻¹, G = [g0 g1] (columns).
            let [g0, g1] = ends[t];
            let a = [
                [
                    g0.x * inv[0][0] + g1.x * inv[1][0],
                    g0.x * inv[0][1] + g1.x * inv[1][1],
                ],
                [
                    g0.y * inv[0][0] + g1.y * inv[1][0],
                    g0.y * inv[0][1] + g1.y * inv[1][1],
                ],
            ];
            // The polar rotation R(θ): (cos θ, sin θ) ∝ (a₀₀ + a₁₁, a₁₀ − a₀₁).
            let (rc, rs) = (a[0][0] + a[1][1], a[1][0] - a[0][1]);
            let theta = rs.atan2(rc);
            let h = rc.hypot(rs);
            let (co, si) = if h > 0.0 {
                (rc / h, rs / h)
            } else {
                (1.0, 0.0)
            };
            // S = R(−θ) A, symmetrised (it is symmetric up to rounding).
            let s11 = co * a[0][0] + si * a[1][0];
            let s12 = 0.5 * ((co * a[0][1] + si * a[1][1]) + (-si * a[0][0] + co * a[1][0]));
            let s22 = -si * a[0][1] + co * a[1][1];
            // Eigen-decomposition of the symmetric S: its eigenvalues are
            // positive where the end triangle is counter-clockwise.
            let mean = 0.5 * (s11 + s22);
            let radius = (0.5 * (s11 - s22)).hypot(s12);
            let (l1, l2) = (mean + radius, mean - radius);
            if !(l2 > 0.0 && l1.is_finite()) {
                return None;
            }
            // The first eigenvector at angle α, 2α = atan2(2 s₁₂, s₁₁ − s₂₂):
            // cos²α, sin²α and cos α sin α from the double angle.
            let (c2, s2) = if radius > 0.0 {
                (0.5 * (s11 - s22) / radius, s12 / radius)
            } else {
                (1.0, 0.0)
            };
            raw.push(Element {
                corners: c,
                wk,
                area: w,
                theta,
                stretch: (
                    [0.5 * (1.0 + c2), 0.5 * (1.0 - c2), 0.5 * s2],
                    [l1.ln(), l2.ln()],
                ),
            });
        }
        // Unwind the rotations along the dual tree, parents first.
        for &t in &rooted.order {
            if let Some(p) = rooted.parent[t] {
                let base = raw[p].theta;
                let d = (raw[t].theta - base + PI).rem_euclid(TAU) - PI;
                raw[t].theta = base + d;
            }
        }
        // Whole turns: the area-weighted median rotation into (−π, π].
        let mut weighted: Vec<(f64, f64)> = raw.iter().map(|e| (e.theta, e.area)).collect();
        weighted.sort_by(|x, y| x.0.total_cmp(&y.0));
        let half = weighted.iter().map(|x| x.1).sum::<f64>() / 2.0;
        let mut acc = 0.0;
        let mut median = 0.0;
        for &(theta, w) in &weighted {
            acc += w;
            if acc >= half {
                median = theta;
                break;
            }
        }
        let turns = ((median + PI) / TAU).floor();
        if turns != 0.0 {
            raw.iter_mut().for_each(|e| e.theta -= turns * TAU);
        }
        let (steps, pinned, growth) = factor(n, &raw, rooted)?;
        Some(RigidGuide {
            elements: raw,
            steps,
            pinned,
            means,
            n,
            refined: growth > REFINE_GROWTH,
        })
    }

    /// The guide's positions at `t` ∈ [0, 1]: the least-squares positions
    /// moved so that their vertex mean is the ends' means interpolated
    /// linearly.
    pub(crate) fn at(&self, t: f64) -> Vec<Point> {
        self.at_checked(t).0
    }

    /// Whether the solve is refined ([`RigidGuide::at_checked`]); where it
    /// is not, every solve is accurate.
    pub(crate) fn refines(&self) -> bool {
        self.refined
    }

    /// [`RigidGuide::at`], and whether its solve is accurate to
    /// [`REFINE_ACCEPT`] of the guide's extent. Where the elimination
    /// cancels much ([`REFINE_GROWTH`]), the solve is refined (as in
    /// Björck's corrected semi-normal equations): the residual is taken
    /// per triangle, as the difference between its map A(t) and the map of
    /// the positions found, so that it does not carry the rounding of the
    /// assembled matrix, and the correction it asks for is solved with
    /// the same factors, until the correction is below
    /// [`REFINE_TOLERANCE`] or stops halving.
    pub(crate) fn at_checked(&self, t: f64) -> (Vec<Point>, bool) {
        let mut b = vec![Point::ZERO; self.n];
        let mut maps = Vec::with_capacity(if self.refined { self.elements.len() } else { 0 });
        for e in &self.elements {
            // A(t) = R(tθ) S^t: the stretch interpolated geometrically, so
            // each triangle's area and its principal stretches move
            // monotonically between the ends' (never ballooning past both).
            let ([cc, ss, cs], [l1, l2]) = e.stretch;
            // (At t = 0, as at the start of every leg, exp and sin_cos give
            // exactly 1 and (0, 1): skipped.)
            let (e1, e2) = if t == 0.0 {
                (1.0, 1.0)
            } else {
                ((t * l1).exp(), (t * l2).exp())
            };
            let m = [
                [e1 * cc + e2 * ss, (e1 - e2) * cs],
                [(e1 - e2) * cs, e1 * ss + e2 * cc],
            ];
            let (si, co) = if t == 0.0 {
                (0.0, 1.0)
            } else {
                (t * e.theta).sin_cos()
            };
            let a = [
                [co * m[0][0] - si * m[1][0], co * m[0][1] - si * m[1][1]],
                [si * m[0][0] + co * m[1][0], si * m[0][1] + co * m[1][1]],
            ];
            add_rows(&mut b, e, a);
            if self.refined {
                maps.push(a);
            }
        }
        let mut x = solve(&self.steps, self.pinned, b);
        let mut converged = true;
        if self.refined {
            let extent = crate::geom::polygon::bbox_diagonal(&x);
            let mut last = f64::INFINITY;
            for _ in 0..REFINE_STEPS {
                let mut r = vec![Point::ZERO; self.n];
                for (e, a) in self.elements.iter().zip(&maps) {
                    add_rows(&mut r, e, misfit(e, a, &x));
                }
                let dx = solve(&self.steps, self.pinned, r);
                let step = dx.iter().map(|d| d.length()).fold(0.0, f64::max);
                x.iter_mut().zip(&dx).for_each(|(p, d)| *p += *d);
                // A correction that does not halve the one before has
                // reached the rounding of the residual itself.
                let stalled = step > 0.5 * last;
                last = step;
                if step <= REFINE_TOLERANCE * extent || stalled {
                    break;
                }
            }
            converged = last <= REFINE_ACCEPT * extent;
        }
        let n = self.n as f64;
        let mean = x.iter().copied().sum::<Point>() / n;
        let goal = self.means[0].lerp(self.means[1], t);
        x.iter_mut().for_each(|p| *p += goal - mean);
        (x, converged)
    }
}

/// Adds triangle `e`'s rows of the right-hand side for the map `a`:
/// w K Aᵣᵀ for each coordinate row r.
fn add_rows(b: &mut [Point], e: &Element, a: [[f64; 2]; 2]) {
    for (k, &v) in e.corners.iter().enumerate() {
        let g = e.wk[k];
        b[v].x += g[0] * a[0][0] + g[1] * a[0][1];
        b[v].y += g[0] * a[1][0] + g[1] * a[1][1];
    }
}

/// The map `a` less the map J of triangle `e` on the positions `x`,
/// J = Σₖ xₖ Kₖᵀ taken from the edge vectors out of its first corner (the
/// rows of K sum to zero), so that it does not carry the positions'
/// magnitude.
fn misfit(e: &Element, a: &[[f64; 2]; 2], x: &[Point]) -> [[f64; 2]; 2] {
    let [c0, c1, c2] = e.corners;
    let (d1, d2) = (x[c1] - x[c0], x[c2] - x[c0]);
    let (k1, k2) = (e.wk[1], e.wk[2]);
    let j = |d1: f64, d2: f64, col: usize| (d1 * k1[col] + d2 * k2[col]) / e.area;
    [
        [a[0][0] - j(d1.x, d2.x, 0), a[0][1] - j(d1.x, d2.x, 1)],
        [a[1][0] - j(d1.y, d2.y, 0), a[1][1] - j(d1.y, d2.y, 1)],
    ]
}

/// The three corner pairs of a triangle, in the order of its edge slots.
const PAIRS: [[usize; 2]; 3] = [[0, 1], [1, 2], [2, 0]];

/// The slot (0–2) of the edge between corners holding `a` and `b` in
/// `corners`.
fn slot(corners: &[usize; 3], a: usize, b: usize) -> usize {
    PAIRS
        .iter()
        .position(|&[i, j]| {
            (corners[i] == a && corners[j] == b) || (corners[i] == b && corners[j] == a)
        })
        .expect("the two vertices are corners of the triangle")
}

/// An index for every edge of the triangulation, per triangle and slot:
/// a triangle's base (the edge it shares with its parent in `rooted`)
/// takes its parent's index, every other edge a new one.
fn edge_ids(elements: &[Element], rooted: &Rooted) -> (Vec<[usize; 3]>, usize) {
    let mut ids = vec![[usize::MAX; 3]; elements.len()];
    let mut next = 0;
    for &t in &rooted.order {
        let c = &elements[t].corners;
        let shared = rooted.parent[t].map(|p| {
            let [x, y] = rooted.base[t].map(|v| v as usize);
            (slot(c, x, y), ids[p][slot(&elements[p].corners, x, y)])
        });
        for (k, id) in ids[t].iter_mut().enumerate() {
            *id = match shared {
                Some((s, parent_id)) if s == k => parent_id,
                _ => {
                    next += 1;
                    next - 1
                }
            };
        }
    }
    (ids, next)
}

/// Assembles the matrix Σ w K Kᵀ and factors it by eliminating ears in
/// turn (no fill-in: every entry an elimination reads or writes lies on
/// an edge of the ear's triangle), holding one vertex of the last
/// triangle at zero. Returns the steps and the held vertex; `None` when a
/// pivot is not positive in floating point.
fn factor(n: usize, elements: &[Element], rooted: &Rooted) -> Option<(Vec<Step>, usize, f64)> {
    let mut diag = vec![0.0; n];
    let (ids, edges) = edge_ids(elements, rooted);
    let mut off = vec![0.0; edges];
    // Triangles of each vertex (flat lists), to find ears.
    let mut count = vec![0usize; n];
    for e in elements {
        for &v in &e.corners {
            count[v] += 1;
        }
    }
    let mut start = vec![0usize; n + 1];
    for v in 0..n {
        start[v + 1] = start[v] + count[v];
    }
    let mut fill = start.clone();
    let mut of_vertex = vec![0usize; start[n]];
    for (t, e) in elements.iter().enumerate() {
        for i in 0..3 {
            let vi = e.corners[i];
            of_vertex[fill[vi]] = t;
            fill[vi] += 1;
            // (w K Kᵀ)_ii = (wK)_i · (wK)_i / w; w = area.
            let gi = e.wk[i];
            diag[vi] += (gi[0] * gi[0] + gi[1] * gi[1]) / e.area;
        }
        for (k, &[i, j]) in PAIRS.iter().enumerate() {
            let (gi, gj) = (e.wk[i], e.wk[j]);
            off[ids[t][k]] += (gi[0] * gj[0] + gi[1] * gj[1]) / e.area;
        }
    }
    // The vertex held at zero: a corner of some triangle; it is never
    // eliminated.
    let pinned = elements.first().map_or(0, |e| e.corners[0]);
    // Each diagonal entry as assembled, to measure how much of it the
    // elimination cancels ([`Factored::growth`]).
    let assembled = diag.clone();
    let mut growth: f64 = 1.0;
    let mut alive = vec![true; elements.len()];
    let mut ears: Vec<usize> = (0..n).filter(|&v| count[v] == 1 && v != pinned).collect();
    let mut eliminated = vec![false; n];
    let mut steps = Vec::with_capacity(n);
    while let Some(v) = ears.pop() {
        if eliminated[v] || count[v] != 1 {
            continue;
        }
        let Some(&t) = of_vertex[start[v]..start[v + 1]]
            .iter()
            .find(|&&t| alive[t])
        else {
            continue;
        };
        alive[t] = false;
        eliminated[v] = true;
        let corners = &elements[t].corners;
        let edge = |a: usize, b: usize| ids[t][slot(corners, a, b)];
        // The ear's two other corners, in corner order (v is one of its
        // three).
        let others = match corners.iter().position(|&u| u == v) {
            Some(0) => [corners[1], corners[2]],
            Some(1) => [corners[0], corners[2]],
            _ => [corners[0], corners[1]],
        };
        let pivot = diag[v];
        if !(pivot > 0.0 && pivot.is_finite()) {
            return None;
        }
        growth = growth.max(assembled[v] / pivot);
        let mut next = [(0usize, 0.0f64); 2];
        let mut k = 0;
        for &u in &others {
            count[u] -= 1;
            if u == pinned {
                continue;
            }
            let l = off[edge(u, v)];
            next[k] = (u, l / pivot);
            k += 1;
            diag[u] -= l * l / pivot;
        }
        if k == 2 {
            let (u, mu) = next[0];
            let (w, _) = next[1];
            let lw = off[edge(w, v)];
            off[edge(u, w)] -= mu * lw;
        }
        steps.push(Step {
            v,
            pivot,
            next,
            count: k,
        });
        for &u in &others {
            if u != pinned && !eliminated[u] && count[u] == 1 {
                ears.push(u);
            }
        }
    }
    // Vertices left (the last triangle's, other than the pinned one) are
    // eliminated with no neighbour left.
    for v in 0..n {
        if v == pinned || eliminated[v] {
            continue;
        }
        let pivot = diag[v];
        if !(pivot > 0.0 && pivot.is_finite()) {
            return None;
        }
        growth = growth.max(assembled[v] / pivot);
        eliminated[v] = true;
        steps.push(Step {
            v,
            pivot,
            next: [(0, 0.0); 2],
            count: 0,
        });
    }
    Some((steps, pinned, growth))
}

/// Solves the factored system for the right-hand side `b` (both
/// coordinates at once), with the pinned vertex at zero.
fn solve(steps: &[Step], pinned: usize, mut b: Vec<Point>) -> Vec<Point> {
    for s in steps {
        let bv = b[s.v];
        for &(u, mu) in &s.next[..s.count] {
            b[u] -= bv * mu;
        }
    }
    let mut x = vec![Point::ZERO; b.len()];
    for s in steps.iter().rev() {
        let mut value = b[s.v] / s.pivot;
        for &(u, mu) in &s.next[..s.count] {
            value -= x[u] * mu;
        }
        x[s.v] = value;
    }
    x[pinned] = Point::ZERO;
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::propagate::compatible::tests::{Rng, random_pair};
    use crate::tree::DualTree;

    fn edges(p: &[Point], tris: &[[u32; 3]]) -> Vec<[Point; 2]> {
        tris.iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| p[v as usize]);
                [b - a, c - a]
            })
            .collect()
    }

    fn mean(p: &[Point]) -> Point {
        p.iter().copied().sum::<Point>() / p.len() as f64
    }

    /// At t = 0 the guide is the source and at t = 1 the end, on random
    /// immersed disks; a turned and scaled copy is turned and scaled
    /// rigidly at every t.
    #[test]
    fn ends_are_reproduced_and_similarities_interpolate_rigidly() {
        let mut rng = Rng(0x5eed_41a9);
        for case in 0..40 {
            let (n, tris, a, b) = random_pair(&mut rng, 4, 60.0);
            let tree = DualTree::new(n, &tris).unwrap();
            let rooted = tree.rooted(0);
            let g = RigidGuide::new(&a, &tris, &edges(&b, &tris), &rooted, [mean(&a), mean(&b)])
                .unwrap();
            let scale = a.iter().chain(&b).map(|p| p.length()).fold(0.0, f64::max);
            for (t, want) in [(0.0, &a), (1.0, &b)] {
                let got = g.at(t);
                for (p, q) in got.iter().zip(want) {
                    assert!((*p - *q).length() <= 1e-9 * scale, "case {case} t {t}");
                }
            }
            // A similarity: every frame is the source turned by tθ and
            // scaled by kᵗ.
            let turn = 2.5;
            let k = 1.7;
            let rot = Point::from_angle(turn) * k;
            let c: Vec<Point> = a.iter().map(|p| rot.rotate(*p)).collect();
            let g = RigidGuide::new(&a, &tris, &edges(&c, &tris), &rooted, [mean(&a), mean(&c)])
                .unwrap();
            let t = 0.3;
            let got = g.at(t);
            let s = Point::from_angle(t * turn) * k.powf(t);
            let ma = mean(&a);
            let goal = ma.lerp(mean(&c), t);
            for (p, q) in got.iter().zip(&a) {
                let want = goal + s.rotate(*q - ma);
                assert!((*p - want).length() <= 1e-9 * scale, "case {case}");
            }
        }
    }

    /// A strip wound one more turn at its far end: the far triangles turn
    /// by more than half a turn, and the guide winds them (their rotation
    /// is unwound along the tree, not taken in (−π, π]).
    #[test]
    fn rotations_are_unwound_along_the_tree() {
        use crate::propagate::compatible::tests::spiral_strip;
        let (a, tris) = spiral_strip(40, 0.25, 0.3);
        let (b, tris_b) = spiral_strip(40, 1.25, 0.3);
        assert_eq!(tris, tris_b);
        let n = a.len();
        let tree = DualTree::new(n, &tris).unwrap();
        let rooted = tree.rooted(0);
        let g =
            RigidGuide::new(&a, &tris, &edges(&b, &tris), &rooted, [mean(&a), mean(&b)]).unwrap();
        let spread = g
            .elements
            .iter()
            .map(|e| e.theta)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            });
        assert!(spread.1 - spread.0 > 1.5 * PI, "{spread:?}");
    }

    /// A strip whose width falls from 0.1 to 10⁻⁹ along its length, curled
    /// a quarter turn, to a strip of width 0.1 curled one and a quarter
    /// turns: its elimination cancels all but a tiny fraction of some
    /// diagonal entries. Solved once, the guide's rounding changes from
    /// one t to the next (its positions at t and t + 10⁻¹² differ by more
    /// than 10⁻⁴ of its extent, where the motion in between is about
    /// 10⁻¹²); refined, by less than 10⁻⁶.
    #[test]
    fn the_refined_solve_moves_smoothly_where_the_elimination_cancels() {
        const FALL: f64 = 1e-8;
        let strip = |turns: f64, fall: f64| {
            let m = 40;
            let station = |i: usize| {
                let th = turns * TAU * i as f64 / (m - 1) as f64;
                let width = 0.1 * fall.powf(i as f64 / (m - 1) as f64);
                (Point::from_angle(th), 1.0 + 0.12 * th / TAU, width)
            };
            let mut pts: Vec<Point> = (0..m)
                .map(|i| {
                    let (u, r, w) = station(i);
                    u * (r + w / 2.0)
                })
                .collect();
            pts.extend((0..m).rev().map(|i| {
                let (u, r, w) = station(i);
                u * (r - w / 2.0)
            }));
            let n = 2 * m as u32;
            let tris: Vec<[u32; 3]> = (0..(m as u32 - 1))
                .flat_map(|i| [[i, i + 1, n - 1 - i], [i + 1, n - 2 - i, n - 1 - i]])
                .collect();
            (pts, tris)
        };
        let (a, tris) = strip(0.25, FALL);
        let (b, _) = strip(1.25, 1.0);
        let tree = DualTree::new(a.len(), &tris).unwrap();
        let rooted = tree.rooted(0);
        let refined =
            RigidGuide::new(&a, &tris, &edges(&b, &tris), &rooted, [mean(&a), mean(&b)]).unwrap();
        assert!(refined.refined);
        let once = RigidGuide {
            refined: false,
            ..refined.clone()
        };
        // The largest move between t and t + 10⁻¹² over a few t, as a
        // fraction of the guide's extent.
        let shake = |g: &RigidGuide| {
            let mut worst: f64 = 0.0;
            for k in 1..20 {
                let t = k as f64 / 20.0;
                let (p, converged) = g.at_checked(t);
                assert!(converged, "t {t}");
                let q = g.at(t + 1e-12);
                let d = p
                    .iter()
                    .zip(&q)
                    .map(|(x, y)| x.distance(*y))
                    .fold(0.0, f64::max);
                worst = worst.max(d / crate::geom::polygon::bbox_diagonal(&p));
            }
            worst
        };
        let (smooth, rough) = (shake(&refined), shake(&once));
        assert!(smooth < 1e-6, "refined: {smooth:e}");
        assert!(rough > 1e-4, "solved once: {rough:e}");
    }
}
