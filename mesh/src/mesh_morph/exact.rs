//! The exact linear-morph test of a star: Surazhsky & Gotsman *Controllable
//! Morphing* Appendix A.
//!
//! Appendix A checks that every sector angle `φ_i(t)` of a star stays in
//! (0, π) while its vertices move linearly, by finding the extrema of
//! `φ_i(t)` as the roots of a quadratic (its eq. 36). We decide the same
//! property directly: the signed area of the sector triangle
//! `q(t) = orient(c(t), a(t), b(t))`, with all three points moving linearly,
//! is a quadratic `c0 + c1 t + c2 t²`, and the sector stays valid on [0, 1]
//! iff `q(0) > 0`, `q(1) > 0` and, when the minimum lies inside (0, 1)
//! (`c2 > 0`, `−2c2 < c1 < 0`), the discriminant `c1² − 4 c0 c2` is negative.
//! `q(0)` and `q(1)` are [`orient`] of input points; the interior test is
//! decided with exact floating-point expansions (Shewchuk's two-sum,
//! two-product, grow- and scale-expansion), so no rounding enters any
//! decision. Exactness assumes no intermediate product underflows, which
//! holds unless coordinate differences are below about 1e-70.
//!
//! Deviation: we test the sign of the area instead of the extrema of the
//! angle; the two are equivalent because an angle of a continuously moving
//! valid sector leaves (0, π) exactly when the area changes sign.

use immerse_base::geom::{Orientation, Point, orient};

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bv = s - a;
    let av = s - bv;
    (s, (a - av) + (b - bv))
}

fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// Adds a double to a nonoverlapping expansion (increasing magnitude).
fn grow(e: &[f64], b: f64) -> Vec<f64> {
    let mut out = Vec::with_capacity(e.len() + 1);
    let mut q = b;
    for &x in e {
        let (s, h) = two_sum(q, x);
        if h != 0.0 {
            out.push(h);
        }
        q = s;
    }
    if q != 0.0 || out.is_empty() {
        out.push(q);
    }
    out
}

fn add(e: &[f64], f: &[f64]) -> Vec<f64> {
    let mut r = e.to_vec();
    for &x in f {
        r = grow(&r, x);
    }
    r
}

fn neg(e: &[f64]) -> Vec<f64> {
    e.iter().map(|x| -x).collect()
}

fn scale(e: &[f64], b: f64) -> Vec<f64> {
    let mut out = Vec::with_capacity(2 * e.len());
    let Some((&e0, rest)) = e.split_first() else {
        return vec![0.0];
    };
    let (mut q, h) = two_prod(e0, b);
    if h != 0.0 {
        out.push(h);
    }
    for &x in rest {
        let (t_hi, t_lo) = two_prod(x, b);
        let (s, h) = two_sum(q, t_lo);
        if h != 0.0 {
            out.push(h);
        }
        let (s2, h2) = two_sum(t_hi, s);
        if h2 != 0.0 {
            out.push(h2);
        }
        q = s2;
    }
    if q != 0.0 || out.is_empty() {
        out.push(q);
    }
    out
}

fn mul(e: &[f64], f: &[f64]) -> Vec<f64> {
    let mut r = vec![0.0];
    for &x in f {
        r = add(&r, &scale(e, x));
    }
    r
}

fn sign(e: &[f64]) -> i32 {
    match e.iter().rev().find(|&&x| x != 0.0) {
        Some(&x) if x > 0.0 => 1,
        Some(_) => -1,
        None => 0,
    }
}

fn estimate(e: &[f64]) -> f64 {
    e.iter().sum()
}

/// Exact `a − b` as an expansion.
fn diff(a: f64, b: f64) -> Vec<f64> {
    let (s, e) = two_sum(a, -b);
    if e == 0.0 { vec![s] } else { vec![e, s] }
}

fn cross(ux: &[f64], uy: &[f64], vx: &[f64], vy: &[f64]) -> Vec<f64> {
    add(&mul(ux, vy), &neg(&mul(uy, vx)))
}

/// The coefficients `(c0, c1, c2)` of `orient(c(t), a(t), b(t))` (twice the
/// signed area) as exact expansions, for points moving linearly from
/// `p0 = [c, a, b]` at t = 0 to `p1` at t = 1.
fn coefficients(p0: [Point; 3], p1: [Point; 3]) -> [Vec<f64>; 3] {
    let u0x = diff(p0[1].x, p0[0].x);
    let u0y = diff(p0[1].y, p0[0].y);
    let v0x = diff(p0[2].x, p0[0].x);
    let v0y = diff(p0[2].y, p0[0].y);
    let dux = add(&diff(p1[1].x, p1[0].x), &neg(&u0x));
    let duy = add(&diff(p1[1].y, p1[0].y), &neg(&u0y));
    let dvx = add(&diff(p1[2].x, p1[0].x), &neg(&v0x));
    let dvy = add(&diff(p1[2].y, p1[0].y), &neg(&v0y));
    let c0 = cross(&u0x, &u0y, &v0x, &v0y);
    let c1 = add(
        &cross(&u0x, &u0y, &dvx, &dvy),
        &cross(&dux, &duy, &v0x, &v0y),
    );
    let c2 = cross(&dux, &duy, &dvx, &dvy);
    [c0, c1, c2]
}

/// Decides exactly whether the triangle `p(t) = (1 − t) p0 + t p1` stays
/// strictly counter-clockwise for all t in [0, 1]. On failure returns an
/// approximate interval `[t_from, t_to]` ⊂ [0, 1] where it is not.
pub(crate) fn triangle_stays_ccw(p0: [Point; 3], p1: [Point; 3]) -> Result<(), (f64, f64)> {
    let ok0 = orient(p0[0], p0[1], p0[2]) == Orientation::CounterClockwise;
    let ok1 = orient(p1[0], p1[1], p1[2]) == Orientation::CounterClockwise;
    let [c0, c1, c2] = coefficients(p0, p1);
    let bad_inside = ok0 && ok1 && {
        // Minimum inside (0, 1): c2 > 0, c1 < 0, c1 + 2 c2 > 0; and it is
        // not positive: c1² − 4 c0 c2 ≥ 0.
        sign(&c2) > 0
            && sign(&c1) < 0
            && sign(&add(&c1, &scale(&c2, 2.0))) > 0
            && sign(&add(&mul(&c1, &c1), &neg(&scale(&mul(&c0, &c2), 4.0)))) >= 0
    };
    if ok0 && ok1 && !bad_inside {
        return Ok(());
    }
    Err(bad_interval(
        estimate(&c0),
        estimate(&c1),
        estimate(&c2),
        ok0,
        ok1,
    ))
}

/// The first sub-interval of [0, 1] where `c0 + c1 t + c2 t² ≤ 0`, in floats
/// (a measurement for the report; the decision was exact).
fn bad_interval(c0: f64, c1: f64, c2: f64, ok0: bool, ok1: bool) -> (f64, f64) {
    let q = |t: f64| c0 + t * (c1 + t * c2);
    let mut roots: Vec<f64> = Vec::new();
    if c2 != 0.0 {
        let disc = c1 * c1 - 4.0 * c0 * c2;
        if disc >= 0.0 {
            let s = disc.sqrt();
            let qq = -0.5 * (c1 + c1.signum() * s);
            if qq != 0.0 {
                roots.push(c0 / qq);
                roots.push(qq / c2);
            } else {
                roots.push(0.0);
            }
        } else {
            roots.push((-c1 / (2.0 * c2)).clamp(0.0, 1.0));
        }
    } else if c1 != 0.0 {
        roots.push(-c0 / c1);
    }
    let mut cuts: Vec<f64> = roots
        .into_iter()
        .filter(|r| r.is_finite() && (0.0..=1.0).contains(r))
        .collect();
    cuts.push(0.0);
    cuts.push(1.0);
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    if !ok0 {
        let end = cuts
            .iter()
            .copied()
            .find(|&r| r > 0.0 && q((r + 1e-9).min(1.0)) > 0.0);
        return (0.0, end.unwrap_or(1.0).min(1.0));
    }
    for w in cuts.windows(2) {
        let mid = 0.5 * (w[0] + w[1]);
        if q(mid) <= 0.0 {
            return (w[0], w[1]);
        }
    }
    if !ok1 {
        let start = cuts.iter().copied().rev().find(|&r| r < 1.0).unwrap_or(1.0);
        return (start, 1.0);
    }
    // A tangency too tight to see in floats.
    let t = if c2 != 0.0 {
        (-c1 / (2.0 * c2)).clamp(0.0, 1.0)
    } else {
        0.5
    };
    (t, t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    #[test]
    fn expansion_sign() {
        let e = add(&[1e-30], &[1.0]);
        assert_eq!(sign(&add(&e, &[-1.0])), 1);
        assert_eq!(sign(&mul(&diff(0.1, 0.3), &[3.0])), -1);
    }

    #[test]
    fn static_triangle_is_valid() {
        let t = [p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0)];
        assert!(triangle_stays_ccw(t, t).is_ok());
    }

    #[test]
    fn half_turn_fails_only_inside() {
        let o = p(0.0, 0.0);
        let t0 = [o, p(1.0, 0.0), p(0.0, 1.0)];
        // cross = (1 − 2t)² − 0.1 t²: negative around t = 1/2.
        let bad = [o, p(-1.0, 0.1), p(1.0, -1.0)];
        let (a, b) = triangle_stays_ccw(t0, bad).unwrap_err();
        assert!(a < 0.5 && 0.5 < b, "{a} {b}");
        // cross = (1 − 2t)² + 0.1 t² > 0 throughout.
        let good = [o, p(-1.0, 0.1), p(-1.0, -1.0)];
        assert!(triangle_stays_ccw(t0, good).is_ok());
        // cross = (1 − 2t)²: touches zero at 1/2.
        let touch = [o, p(-1.0, 0.0), p(0.0, -1.0)];
        assert!(triangle_stays_ccw(t0, touch).is_err());
    }
}
