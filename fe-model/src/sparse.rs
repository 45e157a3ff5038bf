//! Small helpers on faer sparse matrices: triplet iteration, sub-matrices (DOF elimination),
//! dense ↔ sparse conversion and symmetry checks.

use crate::FeError;
use faer::sparse::{SparseColMat, SparseColMatRef, Triplet};
use faer::{Mat, MatMut, MatRef};
use rayon::prelude::*;

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
    a: SparseColMatRef<'_, usize, f64>, rows: &[usize], cols: &[usize],
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

/// Row-major scratch of [`csc_times_block`].
#[derive(Debug, Default)]
pub struct BlockProductWork {
    xt: Vec<f64>,
    ot: Vec<f64>,
}

/// `out = A X` for a sparse `A` (CSC) and a dense block `X` (`n × b`), streaming A once: the
/// block is transposed into row-major scratch so that every stored entry `a_rc` updates the
/// `b` contiguous values of row r (faer's `sparse_dense_matmul` streams A once per column of
/// X, which made the mass product the costliest part of the block operator).
pub fn csc_times_block(
    a: SparseColMatRef<'_, usize, f64>, x: MatRef<'_, f64>, mut out: MatMut<'_, f64>,
    work: &mut BlockProductWork,
) {
    let (n, b) = (x.nrows(), x.ncols());
    work.xt.clear();
    work.xt.resize(n * b, 0.0);
    work.ot.clear();
    work.ot.resize(a.nrows() * b, 0.0);
    for k in 0..b {
        for r in 0..n {
            work.xt[r * b + k] = x[(r, k)];
        }
    }
    let (cp, ri, vals) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
    for c in 0..a.ncols() {
        let xc = &work.xt[c * b..(c + 1) * b];
        for p in cp[c]..cp[c + 1] {
            let (r, v) = (ri[p], vals[p]);
            let oc = &mut work.ot[r * b..(r + 1) * b];
            for (o, &xv) in oc.iter_mut().zip(xc) {
                *o += v * xv;
            }
        }
    }
    for k in 0..b {
        for r in 0..a.nrows() {
            out[(r, k)] = work.ot[r * b + k];
        }
    }
}

/// `A X` for a sparse `A` (CSC) and a dense `X`, in blocks of up to [`PRODUCT_BLOCK`] columns
/// of `X` handled in parallel (rayon), each by one pass over `A` ([`csc_times_block`]): a few
/// passes over `A` instead of faer's one per column of `X` (`sparse_dense_matmul`), which made
/// the products `K T` of the reduced tire (60 480 × 335) memory-bound. Each entry of the result
/// is summed over the columns of `A` in ascending order, as in faer's product.
///
/// # Panics
/// If `x.nrows() != a.ncols()` (a programming error, as for faer's products).
pub fn sparse_times_dense(a: SparseColMatRef<'_, usize, f64>, x: MatRef<'_, f64>) -> Mat<f64> {
    assert_eq!(a.ncols(), x.nrows(), "sparse_times_dense: inner dimensions");
    let b = x.ncols();
    let mut out = Mat::<f64>::zeros(a.nrows(), b);
    // blocks: at least one per thread, at most PRODUCT_BLOCK columns each
    let threads = rayon::current_num_threads().max(1);
    let width = b.div_ceil(threads).clamp(1, PRODUCT_BLOCK);
    let mut blocks = Vec::new();
    let mut rest = out.as_mut();
    let mut start = 0;
    while start < b {
        let w = width.min(b - start);
        let (head, tail) = rest.split_at_col_mut(w);
        blocks.push((start, head));
        rest = tail;
        start += w;
    }
    blocks
        .into_par_iter()
        .for_each(|(j0, o): (usize, MatMut<'_, f64>)| {
            let w = o.ncols();
            csc_times_block(a, x.subcols(j0, w), o, &mut BlockProductWork::default());
        });
    out
}

/// Largest block of columns of [`sparse_times_dense`] (its row-major scratch of a 60 000-row
/// block is 2 × 31 MB).
pub const PRODUCT_BLOCK: usize = 64;
