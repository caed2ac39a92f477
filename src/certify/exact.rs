//! Exact arithmetic of the certificate (docs/design.md §13): dyadic
//! inputs as big integers, quadratics in s with integer coefficients, and
//! numbers of the form (p + σ√d)/q, compared and signed without rounding.
//!
//! Every `f64` is a dyadic rational m·2^e. The coordinates (and margins)
//! that one triangle or one fan depends on are scaled by one common power
//! of two into integers ([`Scaled`]); a doubled signed area or a cross or
//! dot product of edge vectors is then a quadratic in s with integer
//! coefficients, in one common unit, so signs and comparisons are exact.
//! A root of such a quadratic is `(−c₁ ± √D)/(2c₂)` ([`Alg`]); the sign of
//! another quadratic there reduces to the sign of `X + Y√D` with integers
//! X, Y, D ([`sign_sqrt`]): the signs of X and Y when they agree, else the
//! comparison of X² with Y²D.

use num_bigint::{BigInt, Sign};
use std::cmp::Ordering;

/// −1, 0 or +1.
pub(crate) fn sgn(x: &BigInt) -> i32 {
    match x.sign() {
        Sign::Minus => -1,
        Sign::NoSign => 0,
        Sign::Plus => 1,
    }
}

/// `x = m · 2^e` exactly, with `m` odd (or zero).
pub(crate) fn split(x: f64) -> (i64, i64) {
    let bits = x.to_bits();
    let negative = bits >> 63 == 1;
    let exp = ((bits >> 52) & 0x7ff) as i64;
    let frac = bits & ((1u64 << 52) - 1);
    let (mut m, mut e) = if exp == 0 {
        (frac, -1074)
    } else {
        (frac | (1u64 << 52), exp - 1075)
    };
    if m == 0 {
        return (0, 0);
    }
    let tz = m.trailing_zeros();
    m >>= tz;
    e += i64::from(tz);
    let m = m as i64;
    (if negative { -m } else { m }, e)
}

/// Finite `f64` values (each times a power of two `2^shift`), all scaled
/// by one common power of two into integers.
pub(crate) struct Scaled {
    /// The common exponent: value = integer · 2^unit.
    unit: i64,
}

impl Scaled {
    /// The common unit of the values `x · 2^shift`: the smallest exponent
    /// among them, so every one is an integer multiple of it.
    pub(crate) fn new(values: impl IntoIterator<Item = (f64, i64)>) -> Self {
        let unit = values
            .into_iter()
            .filter(|&(x, _)| x != 0.0)
            .map(|(x, shift)| split(x).1 + shift)
            .min()
            .unwrap_or(0);
        Scaled { unit }
    }

    /// `x · 2^shift` in the common unit (an integer, exactly).
    pub(crate) fn int(&self, x: f64, shift: i64) -> BigInt {
        let (m, e) = split(x);
        if m == 0 {
            return BigInt::ZERO;
        }
        let by = e + shift - self.unit;
        debug_assert!(by >= 0, "a value below the common unit: a bug");
        BigInt::from(m) << (by.max(0) as usize)
    }
}

/// `c0 + c1 s + c2 s²` with integer coefficients.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Quad {
    pub(crate) c0: BigInt,
    pub(crate) c1: BigInt,
    pub(crate) c2: BigInt,
}

impl Quad {
    /// `−q`.
    pub(crate) fn neg(&self) -> Quad {
        Quad {
            c0: -&self.c0,
            c1: -&self.c1,
            c2: -&self.c2,
        }
    }

    /// `q + k` for a constant `k`.
    pub(crate) fn plus(&self, k: &BigInt) -> Quad {
        Quad {
            c0: &self.c0 + k,
            c1: self.c1.clone(),
            c2: self.c2.clone(),
        }
    }

    /// The discriminant `c1² − 4 c2 c0`.
    pub(crate) fn discriminant(&self) -> BigInt {
        &self.c1 * &self.c1 - ((&self.c2 * &self.c0) << 2)
    }

    /// The sign of `q(x)`, exactly.
    pub(crate) fn sign_at(&self, x: &Alg) -> i32 {
        // q² · q(x) with x = (p + σ√d)/q: X + Y√d below.
        let Alg { p, sigma, d, q } = x;
        let qq = q * q;
        let mut big_x = &self.c2 * (p * p) + &self.c1 * (q * p) + &self.c0 * &qq;
        if *sigma == 0 {
            return sgn(&big_x);
        }
        big_x += &self.c2 * d;
        let mut big_y: BigInt = ((&self.c2 * p) << 1u32) + &self.c1 * q;
        if *sigma < 0 {
            big_y = -big_y;
        }
        sign_sqrt(&big_x, &big_y, d)
    }

    /// The two roots, smaller first, when the discriminant is ≥ 0 and
    /// `c2 ≠ 0`; one root for `c2 = 0 ≠ c1`; none otherwise (constants,
    /// complex roots).
    pub(crate) fn roots(&self) -> Vec<Alg> {
        match (sgn(&self.c2), sgn(&self.c1)) {
            (0, 0) => Vec::new(),
            (0, _) => vec![Alg::rational(-&self.c0, self.c1.clone())],
            (s2, _) => {
                let d = self.discriminant();
                if sgn(&d) < 0 {
                    return Vec::new();
                }
                // (−c1 ± √d)/(2 c2), denominator made positive.
                let (p, q, lower) = if s2 > 0 {
                    (-&self.c1, &self.c2 << 1, -1)
                } else {
                    (self.c1.clone(), -(&self.c2 << 1u32), -1)
                };
                if sgn(&d) == 0 {
                    return vec![Alg::rational(p, q)];
                }
                vec![
                    Alg::new(p.clone(), lower, d.clone(), q.clone()),
                    Alg::new(p, -lower, d, q),
                ]
            }
        }
    }
}

/// The sign of `x + y√d` (d ≥ 0), exactly.
pub(crate) fn sign_sqrt(x: &BigInt, y: &BigInt, d: &BigInt) -> i32 {
    let (sx, sy) = (sgn(x), sgn(y));
    if sy == 0 || sgn(d) == 0 {
        return sx;
    }
    if sx == 0 || sx == sy {
        return sy;
    }
    match (x * x).cmp(&(y * y * d)) {
        Ordering::Greater => sx,
        Ordering::Less => sy,
        Ordering::Equal => 0,
    }
}

/// A real number `(p + σ√d)/q` with `q > 0`, `d ≥ 0`, `σ ∈ {−1, 0, 1}`: a
/// dyadic or rational parameter, or a root of a quadratic.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Alg {
    p: BigInt,
    sigma: i32,
    d: BigInt,
    q: BigInt,
}

impl Alg {
    fn new(p: BigInt, sigma: i32, d: BigInt, q: BigInt) -> Self {
        debug_assert!(sgn(&q) > 0 && sgn(&d) >= 0);
        // A perfect square under the root makes the number rational.
        if sigma != 0 && sgn(&d) > 0 {
            let r = d.sqrt();
            if &r * &r == d {
                let p = if sigma > 0 { p + r } else { p - r };
                return Alg::rational(p, q);
            }
        }
        Alg { p, sigma, d, q }
    }

    /// `p / q` (q ≠ 0).
    pub(crate) fn rational(p: BigInt, q: BigInt) -> Self {
        let (p, q) = if sgn(&q) < 0 { (-p, -q) } else { (p, q) };
        Alg {
            p,
            sigma: 0,
            d: BigInt::ZERO,
            q,
        }
    }

    /// The value of a finite `f64`.
    pub(crate) fn from_f64(x: f64) -> Self {
        let (m, e) = split(x);
        if e >= 0 {
            Alg::rational(BigInt::from(m) << (e as usize), BigInt::from(1))
        } else {
            Alg::rational(BigInt::from(m), BigInt::from(1) << ((-e) as usize))
        }
    }

    /// True when the number is rational.
    pub(crate) fn is_rational(&self) -> bool {
        self.sigma == 0 || sgn(&self.d) == 0
    }

    /// Exact comparison; `None` when both are irrational with different
    /// radicands (never asked by the certificate).
    pub(crate) fn cmp(&self, other: &Alg) -> Option<Ordering> {
        // self − other = (p1 q2 − p2 q1 + (σ1 q2 √d1 − σ2 q1 √d2)) / (q1 q2).
        let x = &self.p * &other.q - &other.p * &self.q;
        let (y, d) = match (self.is_rational(), other.is_rational()) {
            (true, true) => (BigInt::ZERO, BigInt::ZERO),
            (false, true) => (BigInt::from(self.sigma) * &other.q, self.d.clone()),
            (true, false) => (BigInt::from(-other.sigma) * &self.q, other.d.clone()),
            (false, false) if self.d == other.d => (
                BigInt::from(self.sigma) * &other.q - BigInt::from(other.sigma) * &self.q,
                self.d.clone(),
            ),
            (false, false) => return None,
        };
        Some(sign_sqrt(&x, &y, &d).cmp(&0))
    }

    /// A floating-point approximation (for choosing where to look; every
    /// decision compares exactly).
    pub(crate) fn approx(&self) -> f64 {
        let f = |x: &BigInt| -> f64 { big_to_f64(x) };
        let root = if self.is_rational() {
            0.0
        } else {
            f64::from(self.sigma) * sqrt_big(&self.d)
        };
        let v = (f(&self.p) + root) / f(&self.q);
        if v.is_finite() {
            return v;
        }
        // Very large integers: scale both down first.
        let shift = self.q.bits().max(self.p.bits()).saturating_sub(900) as usize;
        let p = f(&(&self.p >> shift));
        let q = f(&(&self.q >> shift));
        let r = if self.is_rational() {
            0.0
        } else {
            f64::from(self.sigma) * sqrt_big(&(&self.d >> (2 * shift)))
        };
        (p + r) / q
    }

    /// The exact value as `p/q` in lowest terms, when rational.
    pub(crate) fn as_fraction(&self) -> Option<String> {
        if !self.is_rational() {
            return None;
        }
        let g = gcd(self.p.clone(), self.q.clone());
        let (p, q) = if sgn(&g) == 0 {
            (self.p.clone(), self.q.clone())
        } else {
            (&self.p / &g, &self.q / &g)
        };
        Some(if q == BigInt::from(1) {
            p.to_string()
        } else {
            format!("{p}/{q}")
        })
    }

    /// Doubles `lo ≤ self ≤ hi` inside `[floor, ceil]` (which must hold the
    /// number): adjacent doubles (or `lo = hi` when the number is a double)
    /// when `tight`, else within about 2⁻³⁰ of it.
    pub(crate) fn bracket(&self, floor: f64, ceil: f64, tight: bool) -> (f64, f64) {
        let le = |x: f64| self.cmp(&Alg::from_f64(x)) != Some(Ordering::Greater);
        let ge = |x: f64| self.cmp(&Alg::from_f64(x)) != Some(Ordering::Less);
        let (mut lo, mut hi) = (floor, ceil);
        let guess = self.approx();
        if guess.is_finite() && guess >= floor && guess <= ceil {
            if self.cmp(&Alg::from_f64(guess)) == Some(Ordering::Equal) {
                return (guess, guess);
            }
            // A narrow window around the guess, widened until it holds.
            let mut w = (guess.abs() * f64::EPSILON * 64.0).max(f64::MIN_POSITIVE);
            for _ in 0..40 {
                let (a, b) = ((guess - w).max(floor), (guess + w).min(ceil));
                if ge(a) && le(b) {
                    lo = a;
                    hi = b;
                    break;
                }
                w *= 1024.0;
            }
        }
        let width = |lo: f64, hi: f64| {
            if tight {
                next_up(lo) >= hi
            } else {
                hi - lo <= (lo.abs().max(hi.abs()) * 2f64.powi(-30)).max(f64::MIN_POSITIVE)
            }
        };
        for _ in 0..2200 {
            if width(lo, hi) {
                break;
            }
            let mid = lo + (hi - lo) / 2.0;
            if mid <= lo || mid >= hi {
                break;
            }
            match self.cmp(&Alg::from_f64(mid)) {
                Some(Ordering::Equal) => return (mid, mid),
                Some(Ordering::Less) => hi = mid,
                _ => lo = mid,
            }
        }
        (lo, hi)
    }
}

/// The next double above `x` (`f64::next_up`, for the toolchain this
/// crate supports).
pub(crate) fn next_up(x: f64) -> f64 {
    if x.is_nan() || x == f64::INFINITY {
        return x;
    }
    if x == 0.0 {
        return f64::from_bits(1);
    }
    let bits = x.to_bits();
    f64::from_bits(if x > 0.0 { bits + 1 } else { bits - 1 })
}

/// The next double below `x` (`f64::next_down`, for the toolchain this
/// crate supports).
pub(crate) fn next_down(x: f64) -> f64 {
    -next_up(-x)
}

/// `x` rounded to a double (saturating to ±∞ past the range).
pub(crate) fn big_to_f64(x: &BigInt) -> f64 {
    let bits = x.bits();
    if bits <= 63 {
        let v: i64 = x.try_into().unwrap_or(0);
        return v as f64;
    }
    let shift = bits - 63;
    let top: i64 = (x >> shift as usize).try_into().unwrap_or(0);
    (top as f64) * 2f64.powi(shift.min(2000) as i32)
}

fn sqrt_big(d: &BigInt) -> f64 {
    let v = big_to_f64(d);
    if v.is_finite() {
        v.sqrt()
    } else {
        let shift = (d.bits() - 100) & !1;
        big_to_f64(&(d >> shift as usize)).sqrt() * 2f64.powi((shift / 2) as i32)
    }
}

fn gcd(mut a: BigInt, mut b: BigInt) -> BigInt {
    if sgn(&a) < 0 {
        a = -a;
    }
    if sgn(&b) < 0 {
        b = -b;
    }
    while sgn(&b) != 0 {
        let r = &a % &b;
        a = b;
        b = r;
    }
    a
}

/// Whether `q > 0` on the closed interval `[l, r]` (l ≤ r): at both ends,
/// and at the vertex when it is a minimum inside.
pub(crate) fn positive_on(q: &Quad, l: &Alg, r: &Alg) -> bool {
    if q.sign_at(l) <= 0 || q.sign_at(r) <= 0 {
        return false;
    }
    if sgn(&q.c2) <= 0 {
        return true;
    }
    let v = Alg::rational(-&q.c1, &q.c2 << 1);
    let inside = l.cmp(&v) == Some(Ordering::Less) && v.cmp(r) == Some(Ordering::Less);
    // Minimum value c0 − c1²/(4 c2) > 0 ⇔ 4 c2 c0 − c1² > 0.
    !inside || sgn(&q.discriminant()) < 0
}

/// Whether `g ≤ 0` on the closed interval `[l, r]` (l ≤ r).
pub(crate) fn nonpositive_on(g: &Quad, l: &Alg, r: &Alg) -> bool {
    if g.sign_at(l) > 0 || g.sign_at(r) > 0 {
        return false;
    }
    if sgn(&g.c2) >= 0 {
        return true;
    }
    let v = Alg::rational(-&g.c1, &g.c2 << 1);
    let inside = l.cmp(&v) == Some(Ordering::Less) && v.cmp(r) == Some(Ordering::Less);
    // Maximum value g0 − g1²/(4 g2) ≤ 0 ⇔ (g2 < 0) g1² − 4 g2 g0 ≤ 0.
    !inside || sgn(&g.discriminant()) <= 0
}

/// The first s in `[l, r]` with `q(s) ≤ 0`, given that there is one.
pub(crate) fn first_nonpositive(q: &Quad, l: &Alg, r: &Alg) -> Alg {
    if q.sign_at(l) <= 0 {
        return l.clone();
    }
    // q(l) > 0: the first zero after l is the smallest root above l.
    q.roots()
        .into_iter()
        .find(|x| l.cmp(x) == Some(Ordering::Less) && x.cmp(r) != Some(Ordering::Greater))
        .unwrap_or_else(|| r.clone())
}

/// Where a fan may reach a full turn: the first point, or an interval
/// holding the first point, of `[l, r]` where the fan test fails.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Bad {
    /// The first failing point, or the start of an interval holding it.
    pub(crate) lo: Alg,
    /// The same point, or the end of the interval.
    pub(crate) hi: Alg,
}

/// The fan test on `[l, r]` (module docs of `certify`): with `cross` and
/// `dot` the cross and dot products of the fan's first and last edge
/// vectors, and `k ≥ 0` the margin, fails where `|cross| ≤ k` and
/// `dot + k > 0`. With `k = 0`: a root of `cross` where `dot > 0`, or
/// `cross ≡ 0` and `dot > 0` somewhere.
pub(crate) fn fan_ok(
    cross: &Quad,
    dot: &Quad,
    k: &BigInt,
    l: &Alg,
    r: &Alg,
) -> Result<(), Box<Bad>> {
    let g = dot.plus(k);
    for (a, b) in near_set(cross, k, l, r) {
        if !nonpositive_on(&g, &a, &b) {
            return Err(Box::new(first_bad(&g, a, b)));
        }
    }
    Ok(())
}

/// The first point of `[a, b]` where `g > 0` (or where `g` reaches 0 on
/// its way up), exactly when `a` is rational; else `[a, b]` itself.
fn first_bad(g: &Quad, a: Alg, b: Alg) -> Bad {
    if g.sign_at(&a) > 0 {
        return Bad {
            lo: a.clone(),
            hi: a,
        };
    }
    if a.is_rational() {
        // g ≤ 0 at a and > 0 somewhere in [a, b]: the first root where it
        // turns up.
        for x in g.roots() {
            if a.cmp(&x) == Some(Ordering::Greater) || x.cmp(&b) == Some(Ordering::Greater) {
                continue;
            }
            if crosses_up(g, &x, &b) {
                return Bad {
                    lo: x.clone(),
                    hi: x,
                };
            }
        }
    }
    Bad { lo: a, hi: b }
}

/// Whether `g` is positive just after its root `x` (and `x < b`).
fn crosses_up(g: &Quad, x: &Alg, b: &Alg) -> bool {
    if x.cmp(b) != Some(Ordering::Less) {
        return false;
    }
    // Derivative 2 g2 x + g1 > 0, or = 0 with g2 > 0 (a double root of a
    // convex g touches 0 from above: g > 0 on both sides).
    let slope = Quad {
        c0: g.c1.clone(),
        c1: &g.c2 << 1,
        c2: BigInt::ZERO,
    };
    match slope.sign_at(x) {
        1 => true,
        0 => sgn(&g.c2) > 0,
        _ => false,
    }
}

/// The closed intervals of `[l, r]` (l ≤ r) where `|cross| ≤ k`, in order.
fn near_set(cross: &Quad, k: &BigInt, l: &Alg, r: &Alg) -> Vec<(Alg, Alg)> {
    let clip = |a: Alg, b: Alg| -> Option<(Alg, Alg)> {
        // [a, b] ∩ [l, r], when not empty (a ≤ b is known).
        if a.cmp(r) == Some(Ordering::Greater) || b.cmp(l) == Some(Ordering::Less) {
            return None;
        }
        let lo = if a.cmp(l) == Some(Ordering::Greater) {
            a
        } else {
            l.clone()
        };
        let hi = if b.cmp(r) == Some(Ordering::Less) {
            b
        } else {
            r.clone()
        };
        Some((lo, hi))
    };
    let (c2, c1) = (sgn(&cross.c2), sgn(&cross.c1));
    if c2 == 0 && c1 == 0 {
        // A constant.
        let c = &cross.c0;
        return if c <= k && -c <= *k {
            vec![(l.clone(), r.clone())]
        } else {
            Vec::new()
        };
    }
    if c2 == 0 {
        // Linear: −k ≤ c1 s + c0 ≤ k.
        let at = |v: &BigInt| Alg::rational(v - &cross.c0, cross.c1.clone());
        let (a, b) = (at(&-k), at(k));
        let (a, b) = if c1 > 0 { (a, b) } else { (b, a) };
        return clip(a, b).into_iter().collect();
    }
    let c = if c2 > 0 { cross.clone() } else { cross.neg() };
    // c ≤ k on [u − w₊, u + w₊]; c ≥ −k off (u − w₋, u + w₋).
    let upper = c.plus(&-k).roots();
    let Some((lo_plus, hi_plus)) = ends(&upper) else {
        return Vec::new();
    };
    let lower = c.plus(k);
    if sgn(&lower.discriminant()) <= 0 {
        return clip(lo_plus, hi_plus).into_iter().collect();
    }
    let inner = lower.roots();
    let Some((lo_minus, hi_minus)) = ends(&inner) else {
        return clip(lo_plus, hi_plus).into_iter().collect();
    };
    if sgn(k) == 0 {
        // Two points (or one double root, already merged by `roots`).
        return [lo_minus, hi_minus]
            .into_iter()
            .filter_map(|x| clip(x.clone(), x))
            .collect();
    }
    [clip(lo_plus, lo_minus), clip(hi_minus, hi_plus)]
        .into_iter()
        .flatten()
        .collect()
}

/// The smaller and larger root (equal for a double root).
fn ends(roots: &[Alg]) -> Option<(Alg, Alg)> {
    match roots {
        [x] => Some((x.clone(), x.clone())),
        [x, y] => Some((x.clone(), y.clone())),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(c0: i64, c1: i64, c2: i64) -> Quad {
        Quad {
            c0: c0.into(),
            c1: c1.into(),
            c2: c2.into(),
        }
    }

    fn r(p: i64, d: i64) -> Alg {
        Alg::rational(p.into(), d.into())
    }

    #[test]
    fn split_is_exact() {
        for x in [1.0, -0.1, 3.5e-300, 5e-324, 1.7e308, 0.0, 12345.678] {
            let (m, e) = split(x);
            // 2^e in two halves: 2^e alone can be below the normal range
            // (and powi then rounds it to zero), each half cannot.
            let (h, rest) = (e / 2, e - e / 2);
            let back = m as f64 * 2f64.powi(h as i32) * 2f64.powi(rest as i32);
            assert_eq!(back, x, "{x}");
        }
    }

    #[test]
    fn sign_of_x_plus_y_root_d() {
        let b = |x: i64| BigInt::from(x);
        assert_eq!(sign_sqrt(&b(3), &b(-1), &b(9)), 0);
        assert_eq!(sign_sqrt(&b(3), &b(-1), &b(8)), 1);
        assert_eq!(sign_sqrt(&b(3), &b(-1), &b(10)), -1);
        assert_eq!(sign_sqrt(&b(-3), &b(1), &b(10)), 1);
        assert_eq!(sign_sqrt(&b(0), &b(-1), &b(2)), -1);
        assert_eq!(sign_sqrt(&b(-2), &b(5), &b(0)), -1);
    }

    #[test]
    fn positivity_on_intervals() {
        let (zero, one) = (r(0, 1), r(1, 1));
        // (s − 1/2)² + 1/100 > 0; (s − 1/2)² ≥ 0 touches 0.
        assert!(positive_on(&q(26, -100, 100), &zero, &one));
        assert!(!positive_on(&q(25, -100, 100), &zero, &one));
        // Root at s = 1 exactly: not positive on [0, 1], positive on [0, 1/2].
        assert!(!positive_on(&q(1, -1, 0), &zero, &one));
        assert!(positive_on(&q(1, -1, 0), &zero, &r(1, 2)));
        let bad = first_nonpositive(&q(25, -100, 100), &zero, &one);
        assert_eq!(bad.cmp(&r(1, 2)), Some(Ordering::Equal));
        let bad = first_nonpositive(&q(1, 0, -2), &r(1, 4), &one);
        assert_eq!(bad.approx(), 0.5f64.sqrt());
        let (lo, hi) = bad.bracket(0.25, 1.0, true);
        assert!(
            lo < 0.5f64.sqrt() + 1e-16 && lo.next_up() == hi,
            "{lo} {hi}"
        );
    }

    #[test]
    fn fans_decide_roots_exactly() {
        let (zero, one) = (r(0, 1), r(1, 1));
        let k = BigInt::ZERO;
        // cross = s − 1/2 (root at 1/2), dot = 1 − 4s: dot(1/2) = −1 < 0: fine.
        assert!(fan_ok(&q(-1, 2, 0), &q(1, -4, 0), &k, &zero, &one).is_ok());
        // dot = 4s − 1: dot(1/2) = 1 > 0: wraps at exactly 1/2.
        let bad = fan_ok(&q(-1, 2, 0), &q(-1, 4, 0), &k, &zero, &one).unwrap_err();
        assert_eq!(bad.lo.cmp(&r(1, 2)), Some(Ordering::Equal));
        // cross ≡ 0, dot < 0 throughout: fine; dot crossing 0 at 3/4: wraps there.
        assert!(fan_ok(&q(0, 0, 0), &q(-1, 0, -1), &k, &zero, &one).is_ok());
        let bad = fan_ok(&q(0, 0, 0), &q(-3, 4, 0), &k, &zero, &one).unwrap_err();
        assert_eq!(bad.lo.cmp(&r(3, 4)), Some(Ordering::Equal));
        // cross = s² − 2 s + 1/2 → root 1 − √½ ≈ 0.29; dot = s − 0.2 > 0 there.
        let bad = fan_ok(&q(1, -4, 2), &q(-1, 5, 0), &k, &zero, &one).unwrap_err();
        assert!((bad.lo.approx() - (1.0 - 0.5f64.sqrt())).abs() < 1e-15);
        // dot = s − 0.3 < 0 at the root 0.2929: fine.
        assert!(fan_ok(&q(1, -4, 2), &q(-3, 10, 0), &k, &zero, &one).is_ok());
    }
}
