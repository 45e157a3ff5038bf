//! Mass-normalised modal bases and small helpers on [`SysMatrix`].

use crate::error::{FlowError, invalid};
use faer::sparse::linalg::matmul::sparse_dense_matmul;
use faer::{Accum, Mat, MatRef, Par};
use mbd_core::SysMatrix;

/// Mass-normalised mode shapes `Ψ` (`n_dof × k`) and eigenvalues `Λ = diag(ω²)` \[rad²/s²\], with
/// `ΨᵀMΨ = I`, `ΨᵀKΨ = Λ` (Ribaric (4.7)).
#[derive(Debug, Clone)]
pub struct ModalBasis {
    /// Mode shapes (columns).
    pub psi: Mat<f64>,
    /// Eigenvalues `ω²` \[rad²/s²\], ascending.
    pub lambda: Vec<f64>,
}

impl ModalBasis {
    /// Checks shapes.
    pub fn new(psi: Mat<f64>, lambda: Vec<f64>) -> Result<Self, FlowError> {
        if psi.ncols() != lambda.len() {
            return Err(invalid(
                "modal basis",
                format!(
                    "{} mode shapes but {} eigenvalues",
                    psi.ncols(),
                    lambda.len()
                ),
            ));
        }
        if psi.ncols() == 0 {
            return Err(invalid("modal basis", "no modes"));
        }
        Ok(Self { psi, lambda })
    }

    /// The first `k` modes (modal truncation, Ribaric (4.7)/(4.20): drop columns of Ψ).
    pub fn truncated(&self, k: usize) -> Result<Self, FlowError> {
        if k == 0 || k > self.lambda.len() {
            return Err(invalid(
                "modal truncation",
                format!("cannot keep {k} of {} modes", self.lambda.len()),
            ));
        }
        Ok(Self {
            psi: self.psi.subcols(0, k).to_owned(),
            lambda: self.lambda[..k].to_vec(),
        })
    }

    /// Number of modes.
    pub fn len(&self) -> usize {
        self.lambda.len()
    }

    /// Whether there are no modes (never true once built).
    pub fn is_empty(&self) -> bool {
        self.lambda.is_empty()
    }
}

/// `A · X` for a dense or sparse system matrix.
pub fn sys_mul(a: &SysMatrix, x: MatRef<'_, f64>) -> Mat<f64> {
    match a {
        SysMatrix::Dense(m) => m * x,
        SysMatrix::Sparse(s) => {
            let mut out = Mat::zeros(s.nrows(), x.ncols());
            sparse_dense_matmul(out.as_mut(), Accum::Replace, s.as_ref(), x, 1.0, Par::Seq);
            out
        }
    }
}
