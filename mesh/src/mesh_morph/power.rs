//! Neighbourhood matrices raised to a power (Surazhsky & Gotsman *Controllable
//! Morphing* §3.3, eq. 14).
//!
//! `M = [[A, B], [0, I]]` is the row-stochastic matrix whose interior rows
//! hold the barycentric weights and whose boundary rows are the identity,
//! so a tiling is a fixed point `x = M x`, and so of `M^m`. The morph solves
//! `x = M(t) x` with `M(t) = (1 − d)·[(1 − t) M₀^m + t M₁^m] +
//! d·[(1 − t) M₀^{m+1} + t M₁^{m+1}]`. Powers are computed as sparse
//! products (binary exponentiation); their fill grows with `m` (the m-ring
//! of each vertex), so this method suits small and medium tilings, and
//! products beyond [`MAX_POWER_ENTRIES`] entries end the search.

use super::{MeshFrame, MeshMorphError, MeshMorphOptions, Problem};
use crate::solve::SparseSolver;
use crate::tiling::Tiling;
use immerse_base::geom::Point;

/// Largest number of stored entries of a matrix power before the power
/// search stops (bounds memory: 16 bytes per entry).
pub const MAX_POWER_ENTRIES: usize = 20_000_000;

/// Largest power the search tries, whatever [`MeshMorphOptions::max_power`]
/// says.
pub const MAX_POWER: u32 = 1 << 16;

/// Largest number of validity samples used, whatever
/// [`MeshMorphOptions::validity_samples`] says.
pub const MAX_SAMPLES: usize = 4096;

/// The power chosen by the `power` method.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct PowerChoice {
    /// Integer power `m ≥ 1`.
    pub m: u32,
    /// Fractional refinement `d ∈ [0, 1)`: blend towards power `m + 1`.
    pub d: f64,
}

/// Row-compressed sparse matrix.
#[derive(Clone, Debug)]
struct Csr {
    ptr: Vec<usize>,
    col: Vec<u32>,
    val: Vec<f64>,
}

impl Csr {
    fn row(&self, r: usize) -> (&[u32], &[f64]) {
        let (s, e) = (self.ptr[r], self.ptr[r + 1]);
        (&self.col[s..e], &self.val[s..e])
    }

    fn identity(n: usize) -> Csr {
        Csr {
            ptr: (0..=n).collect(),
            col: (0..n as u32).collect(),
            val: vec![1.0; n],
        }
    }

    /// `self · other`, or `None` when the result is too large.
    fn mul(&self, other: &Csr) -> Option<Csr> {
        let n = self.ptr.len() - 1;
        let mut acc = vec![0.0; n];
        let mut mark = vec![usize::MAX; n];
        let mut out = Csr {
            ptr: vec![0],
            col: Vec::new(),
            val: Vec::new(),
        };
        let mut cols: Vec<u32> = Vec::new();
        for r in 0..n {
            cols.clear();
            let (c1, v1) = self.row(r);
            for (&k, &a) in c1.iter().zip(v1) {
                let (c2, v2) = other.row(k as usize);
                for (&j, &b) in c2.iter().zip(v2) {
                    if mark[j as usize] != r {
                        mark[j as usize] = r;
                        acc[j as usize] = 0.0;
                        cols.push(j);
                    }
                    acc[j as usize] += a * b;
                }
            }
            cols.sort_unstable();
            for &j in &cols {
                out.col.push(j);
                out.val.push(acc[j as usize]);
            }
            if out.col.len() > MAX_POWER_ENTRIES {
                return None;
            }
            out.ptr.push(out.col.len());
        }
        Some(out)
    }

    fn pow(&self, mut m: u32) -> Option<Csr> {
        let mut result: Option<Csr> = None;
        let mut base = self.clone();
        loop {
            if m & 1 == 1 {
                result = Some(match result {
                    None => base.clone(),
                    Some(r) => r.mul(&base)?,
                });
            }
            m >>= 1;
            if m == 0 {
                break;
            }
            base = base.mul(&base)?;
        }
        Some(result.unwrap_or_else(|| Csr::identity(self.ptr.len() - 1)))
    }
}

/// The neighbourhood matrix of `tiling` (Surazhsky & Gotsman *Controllable
/// Morphing* §3).
fn neighbourhood(p: &Problem<'_>, tiling: &Tiling, opts: &MeshMorphOptions) -> Csr {
    let n = tiling.points.len();
    let weights = p.weights_of(tiling, opts.weights);
    let mut m = Csr {
        ptr: vec![0],
        col: Vec::new(),
        val: Vec::new(),
    };
    for v in 0..n {
        let k = p.index[v];
        if k == u32::MAX {
            m.col.push(v as u32);
            m.val.push(1.0);
        } else {
            let mut row: Vec<(u32, f64)> = p.topo.fan[v]
                .iter()
                .copied()
                .zip(weights[k as usize].iter().copied())
                .collect();
            row.sort_unstable_by_key(|e| e.0);
            for (c, w) in row {
                m.col.push(c);
                m.val.push(w);
            }
        }
        m.ptr.push(m.col.len());
    }
    m
}

/// One matrix term of the interior system: interior entries (flat value
/// slot, value) and boundary entries (row, vertex, value).
type Term = (Vec<(usize, f64)>, Vec<(u32, u32, f64)>);

/// The interior system of `x = M(t) x` for a fixed set of matrix terms.
struct PowerSystem {
    solver: SparseSolver,
    nvals: usize,
    diag: Vec<usize>,
    terms: Vec<Term>,
}

impl PowerSystem {
    fn new(p: &Problem<'_>, mats: &[&Csr]) -> Result<PowerSystem, MeshMorphError> {
        let ni = p.interior.len();
        let mut rows: Vec<Vec<u32>> = Vec::with_capacity(ni);
        for (k, &v) in p.interior.iter().enumerate() {
            let mut r = vec![k as u32];
            for m in mats {
                r.extend(
                    m.row(v as usize)
                        .0
                        .iter()
                        .map(|&c| p.index[c as usize])
                        .filter(|&i| i != u32::MAX),
                );
            }
            r.sort_unstable();
            r.dedup();
            rows.push(r);
        }
        let mut start = vec![0usize; ni + 1];
        for k in 0..ni {
            start[k + 1] = start[k] + rows[k].len();
        }
        let slot =
            |k: usize, col: u32| -> usize { start[k] + rows[k].binary_search(&col).unwrap_or(0) };
        let diag = (0..ni).map(|k| slot(k, k as u32)).collect();
        let terms = mats
            .iter()
            .map(|m| {
                let mut inner = Vec::new();
                let mut bound = Vec::new();
                for (k, &v) in p.interior.iter().enumerate() {
                    let (cols, vals) = m.row(v as usize);
                    for (&c, &x) in cols.iter().zip(vals) {
                        let i = p.index[c as usize];
                        if i == u32::MAX {
                            bound.push((k as u32, c, x));
                        } else {
                            inner.push((slot(k, i), x));
                        }
                    }
                }
                (inner, bound)
            })
            .collect();
        let solver = SparseSolver::new(&rows).map_err(MeshMorphError::Solver)?;
        Ok(PowerSystem {
            solver,
            nvals: start[ni],
            diag,
            terms,
        })
    }

    fn solve(
        &mut self,
        p: &Problem<'_>,
        coefs: &[f64],
        points: &mut [Point],
    ) -> Result<(), MeshMorphError> {
        let mut values = vec![0.0; self.nvals];
        for &d in &self.diag {
            values[d] += 1.0;
        }
        let mut rhs = vec![Point::ZERO; p.interior.len()];
        for ((inner, bound), &c) in self.terms.iter().zip(coefs) {
            for &(s, x) in inner {
                values[s] -= c * x;
            }
            for &(k, w, x) in bound {
                rhs[k as usize] += (c * x) * points[w as usize];
            }
        }
        self.solver
            .solve(&values, &mut rhs)
            .map_err(MeshMorphError::Solver)?;
        for (k, &v) in p.interior.iter().enumerate() {
            points[v as usize] = rhs[k];
        }
        Ok(())
    }
}

/// Frames of the morph with power `m` and fraction `d`; `None` when the
/// powers are too large to store.
fn frames(
    p: &Problem<'_>,
    m0: &Csr,
    m1: &Csr,
    choice: PowerChoice,
    times: &[f64],
    stop_at_invalid: bool,
) -> Result<Option<Vec<MeshFrame>>, MeshMorphError> {
    let (Some(a), Some(b)) = (m0.pow(choice.m), m1.pow(choice.m)) else {
        return Ok(None);
    };
    let next = if choice.d > 0.0 {
        match (m0.pow(choice.m + 1), m1.pow(choice.m + 1)) {
            (Some(a1), Some(b1)) => Some((a1, b1)),
            _ => return Ok(None),
        }
    } else {
        None
    };
    let mut mats = vec![&a, &b];
    if let Some((a1, b1)) = &next {
        mats.push(a1);
        mats.push(b1);
    }
    let mut system = PowerSystem::new(p, &mats)?;
    let mut out = Vec::with_capacity(times.len());
    for &t in times {
        let d = choice.d;
        let coefs = [(1.0 - d) * (1.0 - t), (1.0 - d) * t, d * (1.0 - t), d * t];
        let mut pts = p.boundary_at(t);
        system.solve(p, &coefs[..mats.len()], &mut pts)?;
        let f = p.frame(t, pts);
        if stop_at_invalid && !f.valid {
            out.push(f);
            return Ok(Some(out));
        }
        out.push(f);
    }
    Ok(Some(out))
}

fn check_times(times: &[f64], samples: usize) -> Vec<f64> {
    let mut ts: Vec<f64> = times.to_vec();
    ts.extend((1..=samples).map(|k| k as f64 / (samples + 1) as f64));
    ts.sort_by(f64::total_cmp);
    ts.dedup();
    ts
}

fn choose(
    p: &Problem<'_>,
    m0: &Csr,
    m1: &Csr,
    times: &[f64],
    opts: &MeshMorphOptions,
) -> Result<PowerChoice, MeshMorphError> {
    if let Some(m) = opts.power {
        if m == 0 || !(0.0..1.0).contains(&opts.power_fraction) {
            return Err(MeshMorphError::BadOption(format!(
                "power {m} with fraction {} (need m ≥ 1 and 0 ≤ d < 1)",
                opts.power_fraction
            )));
        }
        return Ok(PowerChoice {
            m,
            d: opts.power_fraction,
        });
    }
    let max = opts.max_power.clamp(1, MAX_POWER);
    let ts = check_times(times, opts.validity_samples.min(MAX_SAMPLES));
    let valid = |m: u32, d: f64| -> Result<bool, MeshMorphError> {
        Ok(frames(p, m0, m1, PowerChoice { m, d }, &ts, true)?
            .is_some_and(|f| f.iter().all(|f| f.valid)))
    };
    // Doubling (the last step clipped to `max`), then bisection.
    let (mut lo, mut hi) = (1u32, None);
    let mut m = 2u32.min(max);
    while m > lo {
        if valid(m, 0.0)? {
            lo = m;
            m = m.saturating_mul(2).min(max);
        } else {
            hi = Some(m);
            break;
        }
    }
    let Some(mut hi) = hi else {
        return Ok(PowerChoice { m: lo, d: 0.0 });
    };
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if valid(mid, 0.0)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (mut dlo, mut dhi) = (0.0f64, 1.0f64);
    for _ in 0..opts.fraction_steps.min(52) {
        let mid = 0.5 * (dlo + dhi);
        if valid(lo, mid)? {
            dlo = mid;
        } else {
            dhi = mid;
        }
    }
    Ok(PowerChoice { m: lo, d: dlo })
}

/// The power (and fraction) the `power` method would use for these inputs: the
/// largest `m ≤ max_power` whose morph is valid at `times` and the validity
/// samples, found by doubling then bisection, refined by a fraction `d`
/// (Surazhsky & Gotsman *Controllable Morphing* §3.3), or the fixed
/// [`MeshMorphOptions::power`].
///
/// # Errors
///
/// As [`super::mesh_morph`].
pub fn power_choice(
    a: &Tiling,
    b: &Tiling,
    times: &[f64],
    opts: &MeshMorphOptions,
) -> Result<PowerChoice, MeshMorphError> {
    let p = Problem::new(a, b, true)?;
    let m0 = neighbourhood(&p, a, opts);
    let m1 = neighbourhood(&p, b, opts);
    choose(&p, &m0, &m1, times, opts)
}

pub(crate) fn morph(
    p: &Problem<'_>,
    times: &[f64],
    opts: &MeshMorphOptions,
) -> Result<Vec<MeshFrame>, MeshMorphError> {
    let m0 = neighbourhood(p, p.a, opts);
    let m1 = neighbourhood(p, p.b, opts);
    let choice = choose(p, &m0, &m1, times, opts)?;
    match frames(p, &m0, &m1, choice, times, false)? {
        Some(f) => Ok(f),
        None => Err(MeshMorphError::BadOption(format!(
            "power {} needs more than {MAX_POWER_ENTRIES} matrix entries",
            choice.m
        ))),
    }
}
