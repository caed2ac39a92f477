//! The only module that touches the sparse backend (faer's sparse LU).
//!
//! The mesh morphs solve `x_i − Σ_j λ_ij x_j = Σ_{j ∈ B} λ_ij x_j` for the
//! interior vertices `i` (seed 001 eq. 5.3), once per frame. The matrix is
//! not symmetric, its sparsity pattern is fixed by the connectivity, and its
//! values change every frame. So [`SparseSolver::new`] does the symbolic
//! analysis (fill-reducing column ordering and elimination structure) once,
//! and [`SparseSolver::solve`] redoes only the numeric factorisation and
//! the two triangular solves (x and y together) per frame. faer is built
//! without its `rayon` feature, so it runs on one thread.

use crate::geom::Point;
use faer::Mat;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};

/// A square sparse system with a fixed pattern, analysed once.
pub(crate) struct SparseSolver {
    n: usize,
    pattern: SymbolicSparseColMat<usize>,
    symbolic: SymbolicLu<usize>,
    /// For each entry in row order (as given to `new`), its CSC slot.
    slot: Vec<usize>,
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
        let pattern = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        let symbolic = SymbolicLu::try_new(pattern.as_ref()).map_err(|e| format!("{e:?}"))?;
        Ok(SparseSolver {
            n,
            pattern,
            symbolic,
            slot,
        })
    }

    /// Number of unknowns.
    pub(crate) fn len(&self) -> usize {
        self.n
    }

    /// Factors the matrix with `values` (in the row order given to `new`)
    /// and solves for both coordinates; `rhs` is overwritten by the solution.
    pub(crate) fn solve(&self, values: &[f64], rhs: &mut [Point]) -> Result<(), String> {
        debug_assert_eq!(values.len(), self.slot.len());
        debug_assert_eq!(rhs.len(), self.n);
        if self.n == 0 {
            return Ok(());
        }
        let mut csc = vec![0.0; values.len()];
        for (v, &s) in values.iter().zip(&self.slot) {
            csc[s] = *v;
        }
        let mat = SparseColMatRef::new(self.pattern.as_ref(), &csc);
        let lu =
            Lu::try_new_with_symbolic(self.symbolic.clone(), mat).map_err(|e| format!("{e:?}"))?;
        let mut b = Mat::<f64>::from_fn(self.n, 2, |i, j| if j == 0 { rhs[i].x } else { rhs[i].y });
        lu.solve_in_place(b.as_mut());
        for (i, r) in rhs.iter_mut().enumerate() {
            *r = Point::new(b[(i, 0)], b[(i, 1)]);
        }
        if rhs.iter().all(|p| p.is_finite()) {
            Ok(())
        } else {
            Err("the sparse solve produced a non-finite value".into())
        }
    }
}
