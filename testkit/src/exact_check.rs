//! The independent exact checker of a straight-line segment between two
//! shapes under one triangulation, for the certificate's tests and the
//! long measurement runs (`examples/independent_check.rs`).
//!
//! It shares no code or method with the certificate (`immerse::certify`).
//! It decides validity of the motion from the static definition of an
//! immersion triangulation (docs/design.md §3: each triangle
//! counter-clockwise, and at each corner v with (u, w) after it not "u
//! strictly right of the edge v → v+1 while w is not"; no corner on a
//! zero-length edge), required at every s in [0, 1]. Every predicate is a
//! polynomial in s of degree ≤ 2, interpolated exactly from its values at
//! s = 0, ½, 1 in rational arithmetic (`num-rational`); the set of s where
//! a triangle's condition fails is found by isolating the roots of its one
//! or two polynomials with Sturm sequences and bisection on rationals,
//! ordering them, and testing the condition at each root (signs at a root
//! by gcd and refinement) and at a rational point between consecutive
//! roots; a polynomial whose Bernstein coefficients on [0, 1] share one
//! sign keeps it there, and needs no roots. The fan angle is thus tracked through the fan-order predicates
//! of every triangle, not through the alignment of the fan's two edges
//! that the certificate uses.

use immerse_base::geom::Point;
use num_bigint::BigInt;
use num_rational::BigRational;

/// An exact rational number.
pub type Q = BigRational;

/// The rational value of a finite double.
///
/// # Panics
///
/// On a NaN or an infinity.
pub fn q(x: f64) -> Q {
    Q::from_float(x).expect("finite")
}

fn qi(n: i64) -> Q {
    Q::from_integer(BigInt::from(n))
}

fn sign(x: &Q) -> i32 {
    match x.numer().sign() {
        num_bigint::Sign::Minus => -1,
        num_bigint::Sign::NoSign => 0,
        num_bigint::Sign::Plus => 1,
    }
}

/// A polynomial, coefficients from degree 0 up, no trailing zeros.
#[derive(Clone, Debug, PartialEq)]
struct Poly(Vec<Q>);

impl Poly {
    fn new(mut c: Vec<Q>) -> Poly {
        while c.last().is_some_and(|x| sign(x) == 0) {
            c.pop();
        }
        Poly(c)
    }

    fn is_zero(&self) -> bool {
        self.0.is_empty()
    }

    fn degree(&self) -> usize {
        self.0.len().saturating_sub(1)
    }

    fn eval(&self, x: &Q) -> Q {
        self.0.iter().rev().fold(qi(0), |acc, c| acc * x + c)
    }

    fn derivative(&self) -> Poly {
        Poly::new(
            self.0
                .iter()
                .enumerate()
                .skip(1)
                .map(|(i, c)| c * qi(i as i64))
                .collect(),
        )
    }

    /// Remainder of the division by `d` (not zero).
    fn rem(&self, d: &Poly) -> Poly {
        let mut r = self.0.clone();
        let lead = d.0.last().expect("nonzero divisor").clone();
        while r.len() >= d.0.len() && !r.is_empty() {
            let k = r.len() - d.0.len();
            let f = r.last().expect("nonempty") / &lead;
            for (i, c) in d.0.iter().enumerate() {
                r[k + i] = &r[k + i] - &f * c;
            }
            r.pop();
            while r.last().is_some_and(|x| sign(x) == 0) {
                r.pop();
            }
        }
        Poly::new(r)
    }

    fn neg(&self) -> Poly {
        Poly(self.0.iter().map(|c| -c).collect())
    }

    /// Quotient of the division by `d` (not zero).
    fn div(&self, d: &Poly) -> Poly {
        let mut r = self.0.clone();
        let lead = d.0.last().expect("nonzero divisor").clone();
        let mut quot = vec![qi(0); (r.len() + 1).saturating_sub(d.0.len())];
        while r.len() >= d.0.len() && !r.is_empty() {
            let k = r.len() - d.0.len();
            let f = r.last().expect("nonempty") / &lead;
            for (i, c) in d.0.iter().enumerate() {
                r[k + i] = &r[k + i] - &f * c;
            }
            quot[k] = f;
            r.pop();
        }
        Poly::new(quot)
    }

    /// The polynomial with the same roots, each simple.
    fn squarefree(&self) -> Poly {
        let g = self.gcd(&self.derivative());
        if g.degree() == 0 {
            self.clone()
        } else {
            self.div(&g)
        }
    }

    fn gcd(&self, other: &Poly) -> Poly {
        let (mut a, mut b) = (self.clone(), other.clone());
        while !b.is_zero() {
            let r = a.rem(&b);
            a = b;
            b = r;
        }
        a
    }

    /// Sturm sequence.
    fn sturm(&self) -> Vec<Poly> {
        let mut seq = vec![self.clone(), self.derivative()];
        while !seq[seq.len() - 1].is_zero() {
            let n = seq.len();
            let r = seq[n - 2].rem(&seq[n - 1]).neg();
            seq.push(r);
        }
        seq.pop();
        seq
    }

    /// Distinct roots in (a, b].
    fn count(&self, a: &Q, b: &Q) -> usize {
        if self.is_zero() || self.degree() == 0 {
            return 0;
        }
        let seq = self.sturm();
        let var = |x: &Q| {
            let signs: Vec<i32> = seq
                .iter()
                .map(|p| sign(&p.eval(x)))
                .filter(|&s| s != 0)
                .collect();
            signs.windows(2).filter(|w| w[0] != w[1]).count()
        };
        var(a) - var(b)
    }
}

/// The sign `p` keeps on all of [0, 1], where its Bernstein coefficients
/// there all have it (they bound it: `p` is their weighted mean with
/// non-negative weights), or 0 for the zero polynomial; `None` otherwise.
fn constant_sign(p: &Poly) -> Option<i32> {
    let c = &p.0;
    let bernstein: Vec<Q> = match c.len() {
        0 => return Some(0),
        1 => vec![c[0].clone()],
        2 => vec![c[0].clone(), &c[0] + &c[1]],
        _ => {
            debug_assert_eq!(c.len(), 3, "degree at most 2");
            let half = &c[1] / qi(2);
            vec![c[0].clone(), &c[0] + half, &c[0] + &c[1] + &c[2]]
        }
    };
    let first = sign(&bernstein[0]);
    (first != 0 && bernstein.iter().all(|b| sign(b) == first)).then_some(first)
}

/// A root of a polynomial in [0, 1]: exact, or alone in the open interval
/// (lo, hi) with p(lo), p(hi) ≠ 0.
#[derive(Clone, Debug)]
struct Root {
    p: Poly,
    lo: Q,
    hi: Q,
    exact: Option<Q>,
}

impl Root {
    fn refine(&mut self) {
        if self.exact.is_some() {
            return;
        }
        let mid = (&self.lo + &self.hi) / qi(2);
        if sign(&self.p.eval(&mid)) == 0 {
            self.exact = Some(mid.clone());
            self.lo = mid.clone();
            self.hi = mid;
        } else if self.p.count(&self.lo, &mid) == 1 {
            self.hi = mid;
        } else {
            self.lo = mid;
        }
    }

    fn low(&self) -> &Q {
        self.exact.as_ref().unwrap_or(&self.lo)
    }

    fn high(&self) -> &Q {
        self.exact.as_ref().unwrap_or(&self.hi)
    }

    /// The sign of `h` at the root.
    fn sign_of(&mut self, h: &Poly) -> i32 {
        if let Some(x) = &self.exact {
            return sign(&h.eval(x));
        }
        if h.is_zero() {
            return 0;
        }
        let g = self.p.gcd(h);
        if g.degree() > 0 && g.count(&self.lo, &self.hi) > 0 {
            return 0;
        }
        while h.count(&self.lo, &self.hi) > 0 || sign(&h.eval(&self.hi)) == 0 {
            self.refine();
            if let Some(x) = &self.exact {
                return sign(&h.eval(x));
            }
        }
        sign(&h.eval(&self.hi))
    }

    fn same_as(&self, other: &Root) -> bool {
        match (&self.exact, &other.exact) {
            (Some(a), Some(b)) => a == b,
            (Some(a), None) => sign(&other.p.eval(a)) == 0 && other.lo < *a && *a < other.hi,
            (None, Some(b)) => sign(&self.p.eval(b)) == 0 && self.lo < *b && *b < self.hi,
            (None, None) => {
                let lo = std::cmp::max(&self.lo, &other.lo).clone();
                let hi = std::cmp::min(&self.hi, &other.hi).clone();
                let g = self.p.gcd(&other.p);
                lo < hi && g.degree() > 0 && g.count(&lo, &hi) > 0
            }
        }
    }
}

/// The roots of `p` in [0, 1].
fn roots(p: &Poly) -> Vec<Root> {
    if p.is_zero() || p.degree() == 0 {
        return Vec::new();
    }
    let p = &p.squarefree();
    let (zero, one) = (qi(0), qi(1));
    let exact = |x: Q| Root {
        p: p.clone(),
        lo: x.clone(),
        hi: x.clone(),
        exact: Some(x),
    };
    let mut out = Vec::new();
    if sign(&p.eval(&zero)) == 0 {
        out.push(exact(zero.clone()));
    }
    let mut stack = vec![(zero, one.clone())];
    while let Some((a, b)) = stack.pop() {
        // Roots in (a, b), b excluded unless b = 1.
        let mut c = p.count(&a, &b);
        if sign(&p.eval(&b)) == 0 {
            if b == one {
                out.push(exact(b.clone()));
            }
            c -= 1;
        }
        if c == 0 {
            continue;
        }
        if c == 1 && sign(&p.eval(&b)) != 0 {
            out.push(Root {
                p: p.clone(),
                lo: a,
                hi: b,
                exact: None,
            });
            continue;
        }
        let mid = (&a + &b) / qi(2);
        if sign(&p.eval(&mid)) == 0 {
            out.push(exact(mid.clone()));
        }
        stack.push((a, mid.clone()));
        stack.push((mid, b));
    }
    out
}

/// The infimum of the s in [0, 1] where `cond(signs of polys at s)` holds,
/// as a rational interval (a point when exact), or `None`.
fn first_where(polys: &[Poly], cond: impl Fn(&[i32]) -> bool) -> Option<(Q, Q)> {
    // Where every polynomial keeps one sign on [0, 1], so does the
    // condition: decided at once, without isolating roots.
    let signs: Option<Vec<i32>> = polys.iter().map(constant_sign).collect();
    if let Some(signs) = signs {
        return cond(&signs).then(|| (qi(0), qi(0)));
    }
    let mut all: Vec<Root> = Vec::new();
    for p in polys {
        for r in roots(p) {
            if !all.iter().any(|x| x.same_as(&r)) {
                all.push(r);
            }
        }
    }
    // Separate distinct roots, then order them.
    loop {
        let mut overlapping = false;
        for i in 0..all.len() {
            for j in i + 1..all.len() {
                let (a, b) = (&all[i], &all[j]);
                if a.low() <= b.high() && b.low() <= a.high() {
                    overlapping = true;
                    all[i].refine();
                    all[j].refine();
                }
            }
        }
        if !overlapping {
            break;
        }
    }
    all.sort_by(|a, b| a.low().cmp(b.low()));
    let signs_at = |x: &Q| polys.iter().map(|p| sign(&p.eval(x))).collect::<Vec<_>>();
    // The infimum is a root: narrow it for the caller.
    let at_root = |mut r: Root| {
        let eps = Q::new(BigInt::from(1), BigInt::from(1) << 64);
        while r.exact.is_none() && &r.hi - &r.lo > eps {
            r.refine();
        }
        Some((r.low().clone(), r.high().clone()))
    };
    let (zero, one) = (qi(0), qi(1));
    let is_root = |x: &Q, all: &[Root]| all.iter().any(|r| r.exact.as_ref() == Some(x));
    if !is_root(&zero, &all) && cond(&signs_at(&zero)) {
        return Some((zero.clone(), zero));
    }
    let mut prev: Option<Root> = None;
    for mut r in all {
        // The open interval before this root.
        let from = prev.as_ref().map_or(zero.clone(), |p| p.high().clone());
        if *r.low() > from && cond(&signs_at(&((&from + r.low()) / qi(2)))) {
            return match prev {
                Some(p) => at_root(p),
                None => Some((zero.clone(), zero)),
            };
        }
        let signs: Vec<i32> = polys.iter().map(|p| r.sign_of(p)).collect();
        if cond(&signs) {
            return at_root(r);
        }
        prev = Some(r);
    }
    let from = prev.as_ref().map_or(zero.clone(), |p| p.high().clone());
    if from < one && cond(&signs_at(&((&from + &one) / qi(2)))) {
        return match prev {
            Some(p) => at_root(p),
            None => Some((zero.clone(), zero)),
        };
    }
    if prev.as_ref().is_none_or(|p| p.exact.as_ref() != Some(&one)) && cond(&signs_at(&one)) {
        return Some((one.clone(), one));
    }
    None
}

/// The first s in [0, 1] where `tris` is not an immersion triangulation
/// of the straight-line motion from `p` to `qp` at s, as a bracket (low,
/// high; equal where exact), or `None` where it is one for every s.
pub fn first_invalid(p: &[Point], qp: &[Point], tris: &[[u32; 3]]) -> Option<(Q, Q)> {
    let n = p.len();
    // Each vertex at s = 0, ½ and 1 as integers: every coordinate is an
    // integer multiple of the smallest power of two among them, and the
    // values at s = 0 and 1 are doubled so that the midpoint's sum needs
    // no halving. Every predicate is then a positive multiple of the
    // true one (the same signs and roots).
    let split = |x: f64| -> (i64, i32) {
        assert!(x.is_finite(), "a finite coordinate");
        let bits = x.to_bits();
        let exp = ((bits >> 52) & 0x7ff) as i32;
        let frac = (bits & ((1u64 << 52) - 1)) as i64;
        let (m, e) = if exp == 0 {
            (frac, -1074)
        } else {
            (frac | (1 << 52), exp - 1075)
        };
        (if bits >> 63 == 1 { -m } else { m }, e)
    };
    let coords = || p.iter().chain(qp).flat_map(|v| [v.x, v.y]);
    let least = coords()
        .filter(|&x| x != 0.0)
        .map(|x| split(x).1)
        .min()
        .unwrap_or(0);
    let int = |x: f64| -> BigInt {
        match split(x) {
            (0, _) => BigInt::ZERO,
            (m, e) => BigInt::from(m) << ((e - least) as usize),
        }
    };
    let at: Vec<[(BigInt, BigInt); 3]> = (0..n)
        .map(|v| {
            let (x0, y0, x1, y1) = (int(p[v].x), int(p[v].y), int(qp[v].x), int(qp[v].y));
            let mid = (&x0 + &x1, &y0 + &y1);
            [(x0 * 2, y0 * 2), mid, (x1 * 2, y1 * 2)]
        })
        .collect();
    let orient = |a: usize, b: usize, c: usize| -> IntPoly {
        let val = |i: usize| {
            let (pa, pb, pc) = (&at[a][i], &at[b][i], &at[c][i]);
            (&pb.0 - &pa.0) * (&pc.1 - &pa.1) - (&pb.1 - &pa.1) * (&pc.0 - &pa.0)
        };
        IntPoly::interpolate(val(0), val(1), val(2))
    };
    let coord = |v: usize, axis: usize| -> IntPoly {
        let val = |i: usize| {
            let (pw, pv) = (&at[(v + 1) % n][i], &at[v][i]);
            if axis == 0 {
                &pw.0 - &pv.0
            } else {
                &pw.1 - &pv.1
            }
        };
        IntPoly::interpolate(val(0), val(1), val(2))
    };
    let mut first: Option<(Q, Q)> = None;
    let mut note = |x: Option<(Q, Q)>| {
        if let Some(x) = x {
            if first.as_ref().is_none_or(|f| x.0 < f.0) {
                first = Some(x);
            }
        }
    };
    for &[a, b, c] in tris {
        let (a, b, c) = (a as usize, b as usize, c as usize);
        note(decide(&[orient(a, b, c)], |s| s[0] <= 0));
        for (v, u, w) in [(a, b, c), (b, c, a), (c, a, b)] {
            let next = (v + 1) % n;
            note(decide(&[orient(v, next, u), orient(v, next, w)], |s| {
                s[0] < 0 && s[1] >= 0
            }));
            note(decide(&[coord(v, 0), coord(v, 1)], |s| {
                s[0] == 0 && s[1] == 0
            }));
        }
    }
    first
}

/// A polynomial in s of degree at most 2 with integer coefficients, from
/// degree 0 up, no trailing zeros.
struct IntPoly(Vec<BigInt>);

impl IntPoly {
    /// The quadratic through (0, `v0`), (½, `vh`), (1, `v1`): v(s) =
    /// v0 (2s − 1)(s − 1) − 4 vh s(s − 1) + v1 s(2s − 1), whose
    /// coefficients v0, −3v0 + 4vh − v1 and 2v0 − 4vh + 2v1 are integers.
    fn interpolate(v0: BigInt, vh: BigInt, v1: BigInt) -> IntPoly {
        let c1 = -3 * &v0 + 4 * &vh - &v1;
        let c2 = 2 * &v0 - 4 * &vh + 2 * &v1;
        let mut c = vec![v0, c1, c2];
        while c
            .last()
            .is_some_and(|x| x.sign() == num_bigint::Sign::NoSign)
        {
            c.pop();
        }
        IntPoly(c)
    }

    /// As [`constant_sign`], on integers: the Bernstein coefficients on
    /// [0, 1] (times 2, which keeps their signs).
    fn constant_sign(&self) -> Option<i32> {
        let c = &self.0;
        let bernstein: Vec<BigInt> = match c.len() {
            0 => return Some(0),
            1 => vec![c[0].clone()],
            2 => vec![c[0].clone(), &c[0] + &c[1]],
            _ => vec![c[0].clone(), 2 * &c[0] + &c[1], &c[0] + &c[1] + &c[2]],
        };
        let sign = |x: &BigInt| match x.sign() {
            num_bigint::Sign::Minus => -1,
            num_bigint::Sign::NoSign => 0,
            num_bigint::Sign::Plus => 1,
        };
        let first = sign(&bernstein[0]);
        (first != 0 && bernstein.iter().all(|b| sign(b) == first)).then_some(first)
    }

    fn rational(&self) -> Poly {
        Poly::new(self.0.iter().cloned().map(Q::from_integer).collect())
    }
}

/// [`first_where`] for integer polynomials: decided at once where each
/// keeps one sign on [0, 1], else by isolating their roots.
fn decide(polys: &[IntPoly], cond: impl Fn(&[i32]) -> bool) -> Option<(Q, Q)> {
    let signs: Option<Vec<i32>> = polys.iter().map(IntPoly::constant_sign).collect();
    match signs {
        Some(signs) => cond(&signs).then(|| (qi(0), qi(0))),
        None => {
            let rational: Vec<Poly> = polys.iter().map(IntPoly::rational).collect();
            first_where(&rational, cond)
        }
    }
}
