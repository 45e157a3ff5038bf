//! Conversion from `sprs` sparse matrices (feature `sprs`), for users whose FE data come from
//! the sprs ecosystem. faer stays the computational type.

use crate::FeError;
use faer::sparse::{SparseColMat, Triplet};

/// Convert a `sprs` matrix (CSR or CSC, any index type) into a faer CSC matrix. Duplicate
/// entries are summed; non-finite values are rejected with their position.
pub fn from_sprs<I, Iptr>(
    a: &sprs::CsMatI<f64, I, Iptr>,
) -> Result<SparseColMat<usize, f64>, FeError>
where
    I: sprs::SpIndex,
    Iptr: sprs::SpIndex,
{
    let (m, n) = (a.rows(), a.cols());
    let mut t = Vec::with_capacity(a.nnz());
    for (&v, (r, c)) in a.iter() {
        let (r, c) = (r.index(), c.index());
        if !v.is_finite() {
            return Err(FeError::Eigen(format!(
                "sprs matrix entry ({r},{c}) = {v} is not finite"
            )));
        }
        t.push(Triplet::new(r, c, v));
    }
    SparseColMat::try_new_from_triplets(m, n, &t)
        .map_err(|e| FeError::Sparse(format!("from_sprs: {e:?}")))
}

/// Convert a faer CSC matrix into a `sprs` CSC matrix.
pub fn to_sprs(a: faer::sparse::SparseColMatRef<'_, usize, f64>) -> sprs::CsMat<f64> {
    let mut tri = sprs::TriMat::new((a.nrows(), a.ncols()));
    for (r, c, v) in crate::sparse::triplets(a) {
        tri.add_triplet(r, c, v);
    }
    tri.to_csc()
}
