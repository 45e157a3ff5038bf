//! DOF partitions: split the DOFs of a model into two ordered sets (fixed/free,
//! boundary/interior, contact/free) and extract the blocks of M and K (Lin (6.1):
//! `[K_bb K_bi; K_ib K_ii]`; Ribaric (4.2)–(4.3): `f`/`c` sets).

use crate::FeError;
use crate::sparse::{dense_submatrix, submatrix};
use faer::sparse::{SparseColMat, SparseColMatRef};
use faer::{Mat, MatRef};

/// An ordered split of `0..n` into a *selected* set `a` and its complement `b`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DofSplit {
    n: usize,
    a: Vec<usize>,
    b: Vec<usize>,
    /// For each DOF: its position in `a` (Ok) or in `b` (Err).
    slot: Vec<Result<usize, usize>>,
}

impl DofSplit {
    /// Partition with set `a` = `selected` (sorted, de-duplicated) and `b` = the rest
    /// (ascending). Errors if a DOF is ≥ n.
    pub fn new(n: usize, selected: &[usize]) -> Result<Self, FeError> {
        let mut mark = vec![false; n];
        for &d in selected {
            if d >= n {
                return Err(FeError::Index {
                    context: "DOF partition".into(),
                    index: d,
                    size: n,
                });
            }
            mark[d] = true;
        }
        let mut a = Vec::new();
        let mut b = Vec::new();
        let mut slot = Vec::with_capacity(n);
        for (d, &m) in mark.iter().enumerate() {
            if m {
                slot.push(Ok(a.len()));
                a.push(d);
            } else {
                slot.push(Err(b.len()));
                b.push(d);
            }
        }
        Ok(Self { n, a, b, slot })
    }

    /// Fixed/free partition: `a` = fixed DOFs, `b` = free DOFs.
    pub fn fixed(n: usize, fixed: &[usize]) -> Result<Self, FeError> {
        Self::new(n, fixed)
    }

    /// Total DOFs.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Selected set (boundary / fixed / contact), ascending.
    pub fn selected(&self) -> &[usize] {
        &self.a
    }

    /// Complement (interior / free), ascending.
    pub fn rest(&self) -> &[usize] {
        &self.b
    }

    /// Position of a global DOF: `Ok(i)` in the selected set or `Err(i)` in the rest.
    pub fn slot(&self, dof: usize) -> Option<Result<usize, usize>> {
        self.slot.get(dof).copied()
    }

    /// Sparse block `A[rows, cols]` where each set is chosen by `true` = selected, `false` = rest.
    pub fn block(
        &self, a: SparseColMatRef<'_, usize, f64>, rows_selected: bool, cols_selected: bool,
    ) -> Result<SparseColMat<usize, f64>, FeError> {
        self.check(a.nrows(), a.ncols())?;
        submatrix(a, self.set(rows_selected), self.set(cols_selected))
    }

    /// Dense block `A[rows, cols]`.
    pub fn dense_block(
        &self, a: MatRef<'_, f64>, rows_selected: bool, cols_selected: bool,
    ) -> Result<Mat<f64>, FeError> {
        self.check(a.nrows(), a.ncols())?;
        Ok(dense_submatrix(
            a,
            self.set(rows_selected),
            self.set(cols_selected),
        ))
    }

    /// Expand a vector on the rest set to full length, with `fill` on the selected DOFs
    /// (e.g. mode shapes of a fixed model back to all DOFs with zeros at the supports).
    pub fn expand_rest(&self, x: MatRef<'_, f64>, fill: f64) -> Mat<f64> {
        let mut out = Mat::from_fn(self.n, x.ncols(), |_, _| fill);
        for (i, &d) in self.b.iter().enumerate() {
            for j in 0..x.ncols() {
                out[(d, j)] = x[(i, j)];
            }
        }
        out
    }

    /// Keep the selected (fixed) DOFs in a full-size matrix instead of eliminating them: their
    /// rows and columns are zeroed and `diag` is put on their diagonal (e.g. 1 in K and 0 in a
    /// static solve's load, so that `u_fixed = 0`). The matrix keeps its size and numbering.
    pub fn keep_fixed(
        &self, a: SparseColMatRef<'_, usize, f64>, diag: f64,
    ) -> Result<SparseColMat<usize, f64>, FeError> {
        self.check(a.nrows(), a.ncols())?;
        let mut t = Vec::with_capacity(a.compute_nnz());
        for (r, c, v) in crate::sparse::triplets(a) {
            let fr = self.slot[r].is_ok();
            let fc = self.slot[c].is_ok();
            if !fr && !fc {
                t.push(faer::sparse::Triplet::new(r, c, v));
            }
        }
        for &d in &self.a {
            t.push(faer::sparse::Triplet::new(d, d, diag));
        }
        SparseColMat::try_new_from_triplets(self.n, self.n, &t)
            .map_err(|e| FeError::Sparse(format!("keep_fixed: {e:?}")))
    }

    fn set(&self, selected: bool) -> &[usize] {
        if selected { &self.a } else { &self.b }
    }

    fn check(&self, r: usize, c: usize) -> Result<(), FeError> {
        if r != self.n || c != self.n {
            return Err(FeError::Dimension {
                context: "DofSplit block (matrix size)".into(),
                expected: self.n,
                got: if r != self.n { r } else { c },
            });
        }
        Ok(())
    }
}
