//! Kernels of the shift-invert operator `T = L⁻¹ (P M Pᵀ) L⁻ᵀ` on a block of vectors: the
//! symmetric mass product in the factor's (permuted) order, without forming `P M Pᵀ` by
//! sorting triplets, and the shifted matrix `K − σM` by merging the sorted columns of K and M.

use crate::FeError;
use faer::sparse::{SparseColMat, SparseColMatRef, SymbolicSparseColMat};
use faer::{MatMut, MatRef};
use rayon::prelude::*;

/// `K − σM` on the union pattern of K and M (CSC, rows sorted in each column), merged column by
/// column: every shift gives the same pattern, so one symbolic factorisation serves all shifts.
/// Equal (entry by entry, bit for bit) to summing the triplets of K and −σM, in O(nnz).
pub(crate) fn shifted_merge(
    k: SparseColMatRef<'_, usize, f64>, m: SparseColMatRef<'_, usize, f64>, sigma: f64,
) -> Result<SparseColMat<usize, f64>, FeError> {
    let n = k.ncols();
    if k.nrows() != m.nrows() || k.ncols() != m.ncols() || k.nrows() != n {
        return Err(FeError::Dimension {
            context: "K − σM: K and M must be square and of equal size".into(),
            expected: k.nrows(),
            got: m.nrows(),
        });
    }
    let (kc, kr, kv) = (k.symbolic().col_ptr(), k.symbolic().row_idx(), k.val());
    let (mc, mr, mv) = (m.symbolic().col_ptr(), m.symbolic().row_idx(), m.val());
    let kn = k.symbolic().col_nnz();
    let mn = m.symbolic().col_nnz();
    let mut col_ptr = Vec::with_capacity(n + 1);
    let mut rows = Vec::with_capacity(k.compute_nnz() + m.compute_nnz());
    let mut vals = Vec::with_capacity(rows.capacity());
    col_ptr.push(0usize);
    // sums the (possibly repeated) entries of one sorted-or-not column into (row, value) pairs
    let mut buf: Vec<(usize, f64)> = Vec::new();
    for c in 0..n {
        let (k0, k1) = (kc[c], kn.map_or(kc[c + 1], |l| kc[c] + l[c]));
        let (m0, m1) = (mc[c], mn.map_or(mc[c + 1], |l| mc[c] + l[c]));
        let sorted = kr[k0..k1].windows(2).all(|w| w[0] < w[1])
            && mr[m0..m1].windows(2).all(|w| w[0] < w[1]);
        if sorted {
            let (mut i, mut j) = (k0, m0);
            while i < k1 || j < m1 {
                let ri = if i < k1 { kr[i] } else { usize::MAX };
                let rj = if j < m1 { mr[j] } else { usize::MAX };
                if ri < rj {
                    rows.push(ri);
                    vals.push(kv[i]);
                    i += 1;
                } else if rj < ri {
                    rows.push(rj);
                    vals.push(-sigma * mv[j]);
                    j += 1;
                } else {
                    rows.push(ri);
                    vals.push(kv[i] + -sigma * mv[j]);
                    i += 1;
                    j += 1;
                }
            }
        } else {
            buf.clear();
            buf.extend((k0..k1).map(|p| (kr[p], kv[p])));
            buf.extend((m0..m1).map(|p| (mr[p], -sigma * mv[p])));
            buf.sort_by_key(|e| e.0);
            for &(r, v) in &buf {
                if rows.len() > col_ptr[c] && rows.last() == Some(&r) {
                    *vals.last_mut().expect("non-empty") += v;
                } else {
                    rows.push(r);
                    vals.push(v);
                }
            }
        }
        col_ptr.push(rows.len());
    }
    let sym = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, rows);
    Ok(SparseColMat::new(sym, vals))
}

/// The symmetric M (both triangles stored) in the factor's order, `P M Pᵀ`, as gather lists
/// without its stored zeros:
/// row `j` of `P M Pᵀ X` is `Σ_p val[p] · X[row[p], :]` over `p` in `ptr[j]..ptr[j+1]` (column
/// `fwd[j]` of M = its row, by symmetry, with rows renumbered by the inverse permutation).
#[derive(Debug, Clone)]
pub(crate) struct PermutedSymmetric {
    ptr: Vec<usize>,
    row: Vec<u32>,
    val: Vec<f64>,
}

/// Row-major scratch of [`PermutedSymmetric::apply`].
#[derive(Debug, Default)]
pub(crate) struct ProductWork {
    xt: Vec<f64>,
    ot: Vec<f64>,
}

impl PermutedSymmetric {
    /// Gather lists of `P M Pᵀ` for the permutation `fwd` (pivot j is DOF `fwd[j]`) with
    /// inverse `inv`.
    pub(crate) fn new(
        m: SparseColMatRef<'_, usize, f64>, fwd: &[usize], inv: &[usize],
    ) -> Result<Self, FeError> {
        let n = m.ncols();
        if n > u32::MAX as usize {
            return Err(FeError::Sparse("P M Pᵀ: more than 2³² DOFs".into()));
        }
        let mut ptr = Vec::with_capacity(n + 1);
        let mut row = Vec::with_capacity(m.compute_nnz());
        let mut val = Vec::with_capacity(m.compute_nnz());
        ptr.push(0);
        for &c in fwd {
            for (r, v) in m.row_idx_of_col(c).zip(m.val_of_col(c)) {
                // stored zeros (two thirds of an isotropic consistent mass assembled on the
                // pattern of K) add exact zeros: dropping them leaves the product unchanged
                if *v != 0.0 {
                    row.push(inv[r] as u32);
                    val.push(*v);
                }
            }
            ptr.push(row.len());
        }
        Ok(Self { ptr, row, val })
    }

    /// `out = P M Pᵀ x` for a block `x` (`n × b`), rows split over rayon's current pool when
    /// `threaded`.
    pub(crate) fn apply(
        &self, x: MatRef<'_, f64>, mut out: MatMut<'_, f64>, w: &mut ProductWork, threaded: bool,
    ) {
        let (n, b) = (x.nrows(), x.ncols());
        w.xt.resize(n * b, 0.0);
        w.ot.resize(n * b, 0.0);
        for k in 0..b {
            let col = x.col(k);
            for r in 0..n {
                w.xt[r * b + k] = col[r];
            }
        }
        let threads = if threaded {
            rayon::current_num_threads()
        } else {
            1
        };
        let xt = &w.xt;
        if threads <= 1 || b == 0 {
            gather_rows(&self.ptr, &self.row, &self.val, xt, &mut w.ot, 0, b);
        } else {
            let chunk = n.div_ceil(4 * threads).max(1);
            w.ot.par_chunks_mut(chunk * b)
                .enumerate()
                .for_each(|(i, o)| {
                    gather_rows(&self.ptr, &self.row, &self.val, xt, o, i * chunk, b)
                });
        }
        for k in 0..b {
            let mut col = out.as_mut().col_mut(k);
            for r in 0..n {
                col[r] = w.ot[r * b + k];
            }
        }
    }
}

/// Rows `r0..r0 + out.len()/b` of the gather product into `out` (row-major, `b` wide).
fn gather_rows(
    ptr: &[usize], row: &[u32], val: &[f64], xt: &[f64], out: &mut [f64], r0: usize, b: usize,
) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
            // SAFETY: the CPU supports the features the function is compiled for
            unsafe { gather_rows_avx2(ptr, row, val, xt, out, r0, b) };
            return;
        }
    }
    gather_rows_generic(ptr, row, val, xt, out, r0, b);
}

#[inline(always)]
fn gather_rows_generic(
    ptr: &[usize], row: &[u32], val: &[f64], xt: &[f64], out: &mut [f64], r0: usize, b: usize,
) {
    for (i, o) in out.chunks_exact_mut(b).enumerate() {
        o.fill(0.0);
        let j = r0 + i;
        for p in ptr[j]..ptr[j + 1] {
            let (r, v) = (row[p] as usize, val[p]);
            let xr = &xt[r * b..r * b + b];
            for (oo, &xv) in o.iter_mut().zip(xr) {
                *oo += v * xv;
            }
        }
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn gather_rows_avx2(
    ptr: &[usize], row: &[u32], val: &[f64], xt: &[f64], out: &mut [f64], r0: usize, b: usize,
) {
    gather_rows_generic(ptr, row, val, xt, out, r0, b)
}
