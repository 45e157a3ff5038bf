//! Sparse (CSC) assembly with a pattern built once: every element's `ndof × ndof` block has a
//! precomputed scatter map into the value array, so refilling a tangent or mass matrix is an
//! allocation-free loop.

use faer::Mat;
use faer::prelude::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMat, SymbolicSparseColMat};

/// Sentinel for an element entry that is not assembled (a fixed/eliminated DOF).
const DROPPED: usize = usize::MAX;

/// Sparsity pattern of an `n × n` assembled matrix and per-element scatter maps.
#[derive(Debug, Clone)]
pub struct Pattern {
    n: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    scatter: Vec<Vec<usize>>,
    /// faer's structure of the pattern, checked once: [`Pattern::to_matrix`] clones it instead
    /// of checking the sorted row indices of every assembled matrix again.
    structure: SymbolicSparseColMat<usize>,
}

impl Pattern {
    /// Pattern of the matrix assembled from elements whose coordinates map to global rows
    /// `element_dofs[e][k]` (`None` = not assembled). Every diagonal entry is included.
    pub fn new(n: usize, element_dofs: &[Vec<Option<usize>>]) -> Self {
        let mut cols: Vec<Vec<usize>> = (0..n).map(|j| vec![j]).collect();
        for dofs in element_dofs {
            for &dj in dofs.iter().flatten() {
                for &di in dofs.iter().flatten() {
                    cols[dj].push(di);
                }
            }
        }
        let (col_ptr, row_idx) = mbd_core::linalg::csc_pattern(cols);
        let scatter = element_dofs
            .iter()
            .map(|dofs| {
                let m = dofs.len();
                let mut s = vec![DROPPED; m * m];
                for (b, dj) in dofs.iter().enumerate() {
                    for (a, di) in dofs.iter().enumerate() {
                        if let (Some(i), Some(j)) = (di, dj) {
                            // the entry exists by construction
                            s[a + b * m] =
                                mbd_core::linalg::csc_position(&col_ptr, &row_idx, *i, *j);
                        }
                    }
                }
                s
            })
            .collect();
        let structure =
            SymbolicSparseColMat::new_checked(n, n, col_ptr.clone(), None, row_idx.clone());
        Self {
            n,
            col_ptr,
            row_idx,
            scatter,
            structure,
        }
    }

    /// Matrix dimension.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// A zeroed value array.
    pub fn zeros(&self) -> Vec<f64> {
        vec![0.0; self.row_idx.len()]
    }

    /// `vals += scale · ke` for element `el` (`ke` column-major, as given to [`Pattern::new`]).
    #[inline]
    pub fn add_element(&self, vals: &mut [f64], el: usize, ke: &[f64], scale: f64) {
        for (&pos, &v) in self.scatter[el].iter().zip(ke) {
            if pos != DROPPED {
                vals[pos] += scale * v;
            }
        }
    }

    /// [`Pattern::add_element`] of the entries `(a, b)` of `ke` (`m × m`, `m` the element's
    /// coordinates) with `a` and `b` in `local` only (local coordinates of the element, in the
    /// order given), for an element matrix that is zero outside those rows and columns.
    ///
    /// The same bits as [`Pattern::add_element`] for such a `ke` when `vals` was accumulated
    /// from zeros (`+0.0`) by additions only: the entries left out would add `scale · (±0)`,
    /// and in round-to-nearest `x + (±0) = x` for every `x` but `−0`, which such a sum never
    /// holds (`+0 + y` is `y` or `+0`; a sum is `−0` only when both terms are).
    #[inline]
    pub fn add_element_on(
        &self, vals: &mut [f64], el: usize, ke: &[f64], scale: f64, local: &[usize],
    ) {
        let s = &self.scatter[el];
        let m = ke.len().isqrt();
        debug_assert_eq!(m * m, s.len());
        for &b in local {
            for &a in local {
                let pos = s[a + b * m];
                if pos != DROPPED {
                    vals[pos] += scale * ke[a + b * m];
                }
            }
        }
    }

    /// Position of the diagonal entry `(i, i)` in the value array.
    pub fn diagonal_position(&self, i: usize) -> usize {
        let col = &self.row_idx[self.col_ptr[i]..self.col_ptr[i + 1]];
        self.col_ptr[i] + col.binary_search(&i).unwrap_or(0)
    }

    /// Position of entry `(i, j)` in the value array, if stored.
    pub fn position(&self, i: usize, j: usize) -> Option<usize> {
        let col = &self.row_idx[self.col_ptr[j]..self.col_ptr[j + 1]];
        col.binary_search(&i).ok().map(|p| self.col_ptr[j] + p)
    }

    /// All stored entries as `(row, col, position)`.
    pub fn entries(&self) -> impl Iterator<Item = (usize, usize, usize)> + '_ {
        (0..self.n).flat_map(move |j| {
            (self.col_ptr[j]..self.col_ptr[j + 1]).map(move |p| (self.row_idx[p], j, p))
        })
    }

    /// faer CSC matrix with this pattern and the given values.
    pub fn to_matrix(&self, vals: Vec<f64>) -> SparseColMat<usize, f64> {
        SparseColMat::new(self.structure.clone(), vals)
    }

    /// Symbolic structure (for symbolic factorizations that are reused).
    pub fn symbolic(&self) -> SymbolicSparseColMat<usize> {
        self.structure.clone()
    }

    /// Newton correction `dx = −A⁻¹ r` on the first `n` rows (the rest of `dx` zeroed) for the
    /// values `vals` in this pattern, by sparse LU with the reused symbolic factorisation
    /// `symbolic` (of [`Pattern::symbolic`]); the error carries faer's message.
    pub fn lu_correction(
        &self, symbolic: &SymbolicLu<usize>, vals: &[f64], r: &[f64], dx: &mut [f64],
    ) -> Result<(), String> {
        let n = self.n;
        let rhs = Mat::<f64>::from_fn(n, 1, |i, _| -r[i]);
        let kmat = self.to_matrix(vals.to_vec());
        let lu = Lu::try_new_with_symbolic(symbolic.clone(), kmat.as_ref())
            .map_err(|e| format!("{e:?}"))?;
        let d = lu.solve(&rhs);
        dx.fill(0.0);
        for i in 0..n {
            dx[i] = d[(i, 0)];
        }
        Ok(())
    }

    /// `y = A x` for values `vals` in this pattern (overwrites `y`).
    pub fn mul_vec(&self, vals: &[f64], x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for j in 0..self.n {
            let xj = x[j];
            for p in self.col_ptr[j]..self.col_ptr[j + 1] {
                y[self.row_idx[p]] += vals[p] * xj;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`Pattern::add_element_on`] gives the bits of [`Pattern::add_element`] (reference: the
    /// full add) for element matrices that are zero (`+0` and `−0`) outside the given rows and
    /// columns, on values accumulated from zeros by earlier adds (some of them cancelling to
    /// zero exactly), with a dropped coordinate and repeated adds to shared entries.
    #[test]
    fn add_on_the_local_rows_is_the_full_add_bit_for_bit() {
        let dofs = vec![
            vec![Some(0), Some(1), Some(2), None, Some(5)],
            vec![Some(2), Some(3), Some(4), Some(1), Some(5)],
            vec![Some(4), Some(5), Some(0), Some(3), Some(2)],
        ];
        let pat = Pattern::new(6, &dofs);
        let m = 5;
        let locals: [&[usize]; 3] = [&[0, 1, 2], &[1, 3, 4], &[4, 0]];
        let (mut full, mut on) = (pat.zeros(), pat.zeros());
        for round in 0..4 {
            for (el, local) in locals.iter().enumerate() {
                let ke: Vec<f64> = (0..m * m)
                    .map(|i| {
                        let (a, b) = (i % m, i / m);
                        if local.contains(&a) && local.contains(&b) {
                            // cancels the previous round's add exactly in round 2
                            let r = if round == 2 { 1 } else { round };
                            let sign = if round == 2 { -1.0 } else { 1.0 };
                            sign * ((i * 7 + el + r) as f64 * 0.41).sin()
                        } else if i % 2 == 0 {
                            -0.0
                        } else {
                            0.0
                        }
                    })
                    .collect();
                pat.add_element(&mut full, el, &ke, 1.0);
                pat.add_element_on(&mut on, el, &ke, 1.0, local);
            }
        }
        assert!(full.contains(&0.0) && full.iter().any(|&v| v != 0.0));
        for (a, b) in full.iter().zip(&on) {
            assert_eq!(a.to_bits(), b.to_bits());
        }
    }

    /// The matrix of [`Pattern::to_matrix`], built on the structure checked once, is the one
    /// checked anew from the pattern's own arrays as before (reference: faer's checked
    /// constructor on `col_ptr` and `row_idx`): the same dimensions, column pointers, row
    /// indices and values, on a two-element chain with a dropped coordinate.
    #[test]
    fn matrix_on_the_stored_structure_is_the_checked_one() {
        let dofs = vec![
            vec![Some(0), Some(1), Some(2), None],
            vec![Some(2), Some(3), Some(4), Some(1)],
        ];
        let pat = Pattern::new(5, &dofs);
        let vals: Vec<f64> = (0..pat.nnz()).map(|k| (k as f64 * 0.3).sin()).collect();
        let got = pat.to_matrix(vals.clone());
        let reference = SparseColMat::new(
            SymbolicSparseColMat::new_checked(5, 5, pat.col_ptr.clone(), None, pat.row_idx.clone()),
            vals,
        );
        assert_eq!(got.nrows(), reference.nrows());
        assert_eq!(got.ncols(), reference.ncols());
        assert_eq!(got.symbolic().col_ptr(), reference.symbolic().col_ptr());
        assert_eq!(got.symbolic().row_idx(), reference.symbolic().row_idx());
        assert!(got.symbolic().col_nnz().is_none());
        assert_eq!(got.val(), reference.val());
        assert_eq!(pat.symbolic().row_idx(), reference.symbolic().row_idx());
    }
}
