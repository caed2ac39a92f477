//! The only module that touches the sparse backend (faer's sparse LU).
//!
//! The mesh morphs solve `x_i − Σ_j λ_ij x_j = Σ_{j ∈ B} λ_ij x_j` for the
//! interior vertices `i` (seed 001 eq. 5.3), once per frame. The matrix is
//! not symmetric, its sparsity pattern is fixed by the connectivity, and its
//! values change every frame. So:
//!
//! * [`SparseSolver::new`] does the symbolic analysis (COLAMD column
//!   ordering, elimination structure) once per connectivity;
//! * the first [`SparseSolver::solve`] factors numerically (LU with partial
//!   pivoting) and solves directly;
//! * later solves run BiCGSTAB on both coordinates at once, preconditioned
//!   by the last numeric factorisation and warm-started from the previous
//!   solution; the weights change smoothly with t, so a factorisation of a
//!   nearby frame is an excellent preconditioner. When BiCGSTAB does not
//!   reach [`RELATIVE_RESIDUAL`] within [`MAX_ITERATIONS`], or breaks down,
//!   the matrix is refactored (reusing the symbolic analysis) and solved
//!   directly, and that factorisation becomes the new preconditioner.
//!
//! faer is built without its `rayon` feature, so it runs on one thread.

use crate::geom::Point;
use faer::Mat;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};

/// Residual norm, relative to the right-hand side's, at which BiCGSTAB
/// stops.
pub(crate) const RELATIVE_RESIDUAL: f64 = 1e-13;

/// BiCGSTAB iterations before falling back to a fresh factorisation.
pub(crate) const MAX_ITERATIONS: usize = 5;

/// A square sparse system with a fixed pattern, analysed once.
pub(crate) struct SparseSolver {
    n: usize,
    pattern: SymbolicSparseColMat<usize>,
    /// `None` when there are no unknowns.
    symbolic: Option<SymbolicLu<usize>>,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// For each entry in row order (as given to `new`), its CSC slot.
    slot: Vec<usize>,
    /// The last numeric factorisation: the preconditioner.
    lu: Option<Lu<usize, f64>>,
    /// The previous solution: the warm start.
    last: Option<Mat<f64>>,
    /// Numeric factorisations so far.
    pub(crate) factorisations: usize,
    /// BiCGSTAB iterations so far.
    pub(crate) iterations: std::cell::Cell<usize>,
}

impl std::fmt::Debug for SparseSolver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SparseSolver").field("n", &self.n).finish()
    }
}

impl SparseSolver {
    /// Analyses the pattern given row by row: `rows[r]` lists the columns of
    /// the entries of row `r` (distinct, any order, each `< rows.len()`).
    pub(crate) fn new(rows: &[Vec<u32>]) -> Result<SparseSolver, String> {
        let n = rows.len();
        let mut per_col: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
        let mut k = 0usize;
        for (r, cols) in rows.iter().enumerate() {
            for &c in cols {
                per_col[c as usize].push((r, k));
                k += 1;
            }
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::with_capacity(k);
        let mut slot = vec![0usize; k];
        col_ptr.push(0usize);
        for col in &mut per_col {
            col.sort_unstable();
            for &(r, entry) in col.iter() {
                slot[entry] = row_idx.len();
                row_idx.push(r);
            }
            col_ptr.push(row_idx.len());
        }
        let pattern =
            SymbolicSparseColMat::new_checked(n, n, col_ptr.clone(), None, row_idx.clone());
        let symbolic = if n == 0 {
            None
        } else {
            Some(SymbolicLu::try_new(pattern.as_ref()).map_err(|e| format!("{e:?}"))?)
        };
        Ok(SparseSolver {
            n,
            pattern,
            symbolic,
            col_ptr,
            row_idx,
            slot,
            lu: None,
            last: None,
            factorisations: 0,
            iterations: std::cell::Cell::new(0),
        })
    }

    /// Number of unknowns.
    pub(crate) fn len(&self) -> usize {
        self.n
    }

    /// `y = A x` for both columns, with `A` given by its CSC values.
    fn apply(&self, csc: &[f64], x: &Mat<f64>, y: &mut Mat<f64>) {
        y.fill(0.0);
        for j in 0..self.n {
            let (x0, x1) = (x[(j, 0)], x[(j, 1)]);
            let range = self.col_ptr[j]..self.col_ptr[j + 1];
            for (&r, &a) in self.row_idx[range.clone()].iter().zip(&csc[range]) {
                y[(r, 0)] += a * x0;
                y[(r, 1)] += a * x1;
            }
        }
    }

    /// Refactors with `csc` and solves `b` directly.
    fn direct(&mut self, csc: &[f64], b: &Mat<f64>) -> Result<Mat<f64>, String> {
        let mat = SparseColMatRef::new(self.pattern.as_ref(), csc);
        let lu = Lu::try_new_with_symbolic(self.symbolic.clone().ok_or("no unknowns")?, mat)
            .map_err(|e| format!("{e:?}"))?;
        self.factorisations += 1;
        let mut x = b.clone();
        lu.solve_in_place(x.as_mut());
        self.lu = Some(lu);
        Ok(x)
    }

    /// Right-preconditioned BiCGSTAB on both columns at once; `None` when it
    /// breaks down or does not converge.
    fn bicgstab(&self, csc: &[f64], b: &Mat<f64>, x0: &Mat<f64>) -> Option<Mat<f64>> {
        let lu = self.lu.as_ref()?;
        let n = self.n;
        let dot = |a: &Mat<f64>, b: &Mat<f64>, c: usize| -> f64 {
            (0..n).map(|i| a[(i, c)] * b[(i, c)]).sum()
        };
        let mut x = x0.clone();
        let mut r = Mat::<f64>::zeros(n, 2);
        self.apply(csc, &x, &mut r);
        for c in 0..2 {
            for i in 0..n {
                r[(i, c)] = b[(i, c)] - r[(i, c)];
            }
        }
        let bnorm = [dot(b, b, 0).sqrt(), dot(b, b, 1).sqrt()];
        let tol = [
            RELATIVE_RESIDUAL * bnorm[0].max(f64::MIN_POSITIVE),
            RELATIVE_RESIDUAL * bnorm[1].max(f64::MIN_POSITIVE),
        ];
        let mut done = [
            dot(&r, &r, 0).sqrt() <= tol[0],
            dot(&r, &r, 1).sqrt() <= tol[1],
        ];
        let rhat = r.clone();
        let (mut rho, mut alpha, mut omega) = ([1.0; 2], [1.0; 2], [1.0; 2]);
        let mut v = Mat::<f64>::zeros(n, 2);
        let mut p = Mat::<f64>::zeros(n, 2);
        let mut t = Mat::<f64>::zeros(n, 2);
        for _ in 0..MAX_ITERATIONS {
            if done[0] && done[1] {
                return Some(x);
            }
            self.iterations.set(self.iterations.get() + 1);
            for c in 0..2 {
                if done[c] {
                    continue;
                }
                let rho_new = dot(&rhat, &r, c);
                if rho_new == 0.0 || !rho_new.is_finite() {
                    return None;
                }
                let beta = (rho_new / rho[c]) * (alpha[c] / omega[c]);
                rho[c] = rho_new;
                for i in 0..n {
                    p[(i, c)] = r[(i, c)] + beta * (p[(i, c)] - omega[c] * v[(i, c)]);
                }
            }
            let mut phat = p.clone();
            lu.solve_in_place(phat.as_mut());
            self.apply(csc, &phat, &mut v);
            let mut s = r.clone();
            for c in 0..2 {
                if done[c] {
                    continue;
                }
                let d = dot(&rhat, &v, c);
                if d == 0.0 || !d.is_finite() {
                    return None;
                }
                alpha[c] = rho[c] / d;
                for i in 0..n {
                    s[(i, c)] = r[(i, c)] - alpha[c] * v[(i, c)];
                }
            }
            let mut shat = s.clone();
            lu.solve_in_place(shat.as_mut());
            self.apply(csc, &shat, &mut t);
            for c in 0..2 {
                if done[c] {
                    continue;
                }
                let tt = dot(&t, &t, c);
                omega[c] = if tt > 0.0 { dot(&t, &s, c) / tt } else { 0.0 };
                for i in 0..n {
                    x[(i, c)] += alpha[c] * phat[(i, c)] + omega[c] * shat[(i, c)];
                    r[(i, c)] = s[(i, c)] - omega[c] * t[(i, c)];
                }
                let rn = dot(&r, &r, c).sqrt();
                if !rn.is_finite() {
                    return None;
                }
                done[c] = rn <= tol[c];
                if !done[c] && omega[c] == 0.0 {
                    return None;
                }
            }
        }
        (done[0] && done[1]).then_some(x)
    }

    /// Solves with the matrix `values` (in the row order given to `new`);
    /// `rhs` is overwritten by the solution. See the module docs for when
    /// this refactors.
    pub(crate) fn solve(&mut self, values: &[f64], rhs: &mut [Point]) -> Result<(), String> {
        debug_assert_eq!(values.len(), self.slot.len());
        debug_assert_eq!(rhs.len(), self.n);
        if self.n == 0 {
            return Ok(());
        }
        let mut csc = vec![0.0; values.len()];
        for (v, &s) in values.iter().zip(&self.slot) {
            csc[s] = *v;
        }
        let b = Mat::<f64>::from_fn(self.n, 2, |i, j| if j == 0 { rhs[i].x } else { rhs[i].y });
        let iterative = match self.last.take() {
            Some(x0) if self.lu.is_some() => self.bicgstab(&csc, &b, &x0),
            _ => None,
        };
        let x = match iterative {
            Some(x) => x,
            None => self.direct(&csc, &b)?,
        };
        for (i, r) in rhs.iter_mut().enumerate() {
            *r = Point::new(x[(i, 0)], x[(i, 1)]);
        }
        self.last = Some(x);
        if rhs.iter().all(|p| p.is_finite()) {
            Ok(())
        } else {
            Err("the sparse solve produced a non-finite value".into())
        }
    }
}
