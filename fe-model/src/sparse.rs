//! Small helpers on faer sparse matrices: triplet iteration, sub-matrices (DOF elimination),
//! dense ↔ sparse conversion and symmetry checks.

use crate::FeError;
use faer::sparse::{SparseColMat, SparseColMatRef, Triplet};
use faer::{Mat, MatRef};

/// Iterate the stored entries `(row, col, value)` of a CSC matrix, column by column.
pub fn triplets<'a>(
    a: SparseColMatRef<'a, usize, f64>,
) -> impl Iterator<Item = (usize, usize, f64)> + 'a {
    (0..a.ncols()).flat_map(move |j| {
        a.row_idx_of_col(j)
            .zip(a.val_of_col(j).iter())
            .map(move |(i, &v)| (i, j, v))
    })
}

/// Sparse copy of a dense matrix, keeping entries with `|a_ij| > drop_tol`.
pub fn from_dense(a: MatRef<'_, f64>, drop_tol: f64) -> Result<SparseColMat<usize, f64>, FeError> {
    let mut t = Vec::new();
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            let v = a[(i, j)];
            if v.abs() > drop_tol {
                t.push(Triplet::new(i, j, v));
            }
        }
    }
    SparseColMat::try_new_from_triplets(a.nrows(), a.ncols(), &t)
        .map_err(|e| FeError::Sparse(format!("from_dense: {e:?}")))
}

/// The sub-matrix `A[rows, cols]` (e.g. `K_ff` after eliminating fixed DOFs).
///
/// `rows` and `cols` are lists of distinct indices; their order defines the new numbering.
pub fn submatrix(
    a: SparseColMatRef<'_, usize, f64>,
    rows: &[usize],
    cols: &[usize],
) -> Result<SparseColMat<usize, f64>, FeError> {
    const NONE: usize = usize::MAX;
    let mut row_map = vec![NONE; a.nrows()];
    for (new, &r) in rows.iter().enumerate() {
        if r >= a.nrows() {
            return Err(FeError::Index {
                context: "submatrix rows".into(),
                index: r,
                size: a.nrows(),
            });
        }
        row_map[r] = new;
    }
    let mut t = Vec::new();
    for (new_c, &c) in cols.iter().enumerate() {
        if c >= a.ncols() {
            return Err(FeError::Index {
                context: "submatrix cols".into(),
                index: c,
                size: a.ncols(),
            });
        }
        for (i, &v) in a.row_idx_of_col(c).zip(a.val_of_col(c).iter()) {
            let nr = row_map[i];
            if nr != NONE {
                t.push(Triplet::new(nr, new_c, v));
            }
        }
    }
    SparseColMat::try_new_from_triplets(rows.len(), cols.len(), &t)
        .map_err(|e| FeError::Sparse(format!("submatrix: {e:?}")))
}

/// Dense sub-matrix `A[rows, cols]`.
pub fn dense_submatrix(a: MatRef<'_, f64>, rows: &[usize], cols: &[usize]) -> Mat<f64> {
    Mat::from_fn(rows.len(), cols.len(), |i, j| a[(rows[i], cols[j])])
}

/// Largest asymmetry `max |a_ij − a_ji|` relative to `max |a_ij|` (0 for a symmetric matrix).
pub fn relative_asymmetry(a: SparseColMatRef<'_, usize, f64>) -> f64 {
    let mut max_abs: f64 = 0.0;
    let mut entries = std::collections::HashMap::new();
    for (i, j, v) in triplets(a) {
        max_abs = max_abs.max(v.abs());
        *entries.entry((i, j)).or_insert(0.0) += v;
    }
    let mut asym: f64 = 0.0;
    for (&(i, j), &v) in &entries {
        let w = entries.get(&(j, i)).copied().unwrap_or(0.0);
        asym = asym.max((v - w).abs());
    }
    if max_abs > 0.0 { asym / max_abs } else { 0.0 }
}
