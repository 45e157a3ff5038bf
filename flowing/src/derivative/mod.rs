//! Mode-shape derivative operators along a flow coordinate (Ribaric App. A).
//!
//! A [`DerivativeMethod`] turns a [`FlowGrid`] into a [`LineOperator`] acting on nodal values
//! sampled at the grid's flow coordinates (one scalar field, `n × m` for `m` mode shapes).
//! [`FlowLine`] and [`mode_shape_derivatives`] apply it per component to mode shapes of models
//! with several DOFs per node (belt: x, y, θ along s; tire: x, y, z along θ on every ring,
//! Ribaric A.5).

pub mod consistent;
pub mod finite_difference;
pub mod lines;
pub mod polynomial;
pub mod spectral;
pub mod stencil;

pub use consistent::{MassKind, consistent_matrices, line_fe_matrices};
pub use finite_difference::{FdScheme, FirstDifference, SecondDifference, fd_matrices};
pub use lines::{FlowLine, ModeDerivatives, mode_shape_derivatives};
pub use polynomial::polynomial_matrices;
pub use spectral::SpectralOperator;

use crate::error::FlowError;
use crate::grid::FlowGrid;
use faer::sparse::SparseColMat;
use faer::sparse::linalg::matmul::sparse_dense_matmul;
use faer::{Accum, Mat, MatRef, Par};

/// How mode-shape derivatives are computed.
#[derive(
    Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields)]
pub enum DerivativeMethod {
    /// Finite differences on non-uniform grids (Ribaric (A.1)–(A.4)).
    FiniteDifference(FdScheme),
    /// Galerkin operators of linear elements, `M₁⁻¹G₁` and `−M₁⁻¹K₁` (FE-consistent; see
    /// [`consistent`]).
    Consistent(MassKind),
    /// Polynomial least squares of the given degree (Ribaric (A.5)–(A.11)); open grids only.
    Polynomial {
        /// Polynomial degree `m` of (A.5).
        degree: usize,
    },
    /// Corrected FFT derivative (Ribaric (A.12)–(A.15), erratum E22); uniform grids only.
    Spectral,
}

impl Default for DerivativeMethod {
    /// FE-consistent operators with lumped mass (for the string of Ribaric (4.1) these are (A.1)
    /// and the 3-point second difference).
    fn default() -> Self {
        DerivativeMethod::Consistent(MassKind::Lumped)
    }
}

/// A derivative operator on one grid: maps nodal values to first and second derivatives.
#[derive(Debug, Clone)]
pub enum LineOperator {
    /// Sparse matrices `(D₁, D₂)`.
    Sparse(SparseColMat<usize, f64>, SparseColMat<usize, f64>),
    /// Dense matrices `(D₁, D₂)`.
    Dense(Mat<f64>, Mat<f64>),
    /// FFT-based.
    Spectral(SpectralOperator),
}

impl LineOperator {
    /// Builds the operator of `method` on `grid`.
    pub fn new(grid: &FlowGrid, method: DerivativeMethod) -> Result<Self, FlowError> {
        Ok(match method {
            DerivativeMethod::FiniteDifference(s) => {
                let (a, b) = fd_matrices(grid, s)?;
                LineOperator::Sparse(a, b)
            }
            DerivativeMethod::Consistent(m) => {
                let (a, b) = consistent_matrices(grid, m)?;
                LineOperator::Dense(a, b)
            }
            DerivativeMethod::Polynomial { degree } => {
                let (a, b) = polynomial_matrices(grid, degree)?;
                LineOperator::Dense(a, b)
            }
            DerivativeMethod::Spectral => LineOperator::Spectral(SpectralOperator::new(grid)?),
        })
    }

    /// Number of nodes the operator acts on.
    pub fn len(&self) -> usize {
        match self {
            LineOperator::Sparse(a, _) => a.nrows(),
            LineOperator::Dense(a, _) => a.nrows(),
            LineOperator::Spectral(s) => s.len(),
        }
    }

    /// Whether the operator acts on zero nodes (never true for a constructed operator).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// First and second derivatives `(Ψ_,s, Ψ_,ss)` of the columns of `values` (`n × m`).
    pub fn apply(&self, values: MatRef<'_, f64>) -> (Mat<f64>, Mat<f64>) {
        match self {
            LineOperator::Sparse(a, b) => {
                let mut d1 = Mat::zeros(values.nrows(), values.ncols());
                let mut d2 = Mat::zeros(values.nrows(), values.ncols());
                sparse_dense_matmul(
                    d1.as_mut(),
                    Accum::Replace,
                    a.as_ref(),
                    values,
                    1.0,
                    Par::Seq,
                );
                sparse_dense_matmul(
                    d2.as_mut(),
                    Accum::Replace,
                    b.as_ref(),
                    values,
                    1.0,
                    Par::Seq,
                );
                (d1, d2)
            }
            LineOperator::Dense(a, b) => (a * values, b * values),
            LineOperator::Spectral(s) => s.apply(values),
        }
    }

    /// The operator as dense matrices `(D₁, D₂)` (`n × n`).
    pub fn to_dense(&self) -> (Mat<f64>, Mat<f64>) {
        match self {
            LineOperator::Sparse(a, b) => (a.to_dense(), b.to_dense()),
            LineOperator::Dense(a, b) => (a.clone(), b.clone()),
            LineOperator::Spectral(s) => s.apply(Mat::<f64>::identity(s.len(), s.len()).as_ref()),
        }
    }
}
