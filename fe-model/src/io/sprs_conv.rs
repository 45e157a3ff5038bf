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

#[cfg(test)]
mod tests {
    use super::*;

    /// Round trip faer → sprs → faer reproduces the matrix (CSR input too).
    #[test]
    fn round_trip() {
        let mut tri = sprs::TriMat::new((3, 4));
        tri.add_triplet(0, 0, 1.5);
        tri.add_triplet(2, 3, -2.0);
        tri.add_triplet(1, 2, 4.0);
        tri.add_triplet(1, 2, 1.0); // duplicate: summed
        let csr: sprs::CsMat<f64> = tri.to_csr();
        let f = from_sprs(&csr).unwrap();
        let d = f.to_dense();
        assert_eq!(d[(1, 2)], 5.0);
        assert_eq!(d[(2, 3)], -2.0);
        let back = from_sprs(&to_sprs(f.as_ref())).unwrap().to_dense();
        assert_eq!(back, d);
    }
}
