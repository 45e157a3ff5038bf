//! Generalized symmetric eigenproblems `K φ = λ M φ` (M symmetric positive definite).
//!
//! All solvers return [`Modes`]: eigenvalues ascending, vectors M-normalised
//! (`φᵀ M φ = 1`), each vector signed so that its largest-magnitude component is positive
//! (the first such component on ties), which makes results reproducible across solvers.

use faer::{Mat, MatMut};
use serde::Serialize;

mod block_lanczos;
pub mod dense;
pub mod factor;
mod operator;
pub mod sparse;
pub mod sturm;

pub use dense::{DenseEigenReport, dense_modes, dense_modes_report, dense_modes_shifted};
pub use sparse::{SparseEigenOptions, SparseEigenReport, sparse_modes};
pub use sturm::sturm_count;

/// Eigen solution of `K φ = λ M φ`.
#[derive(Debug, Clone)]
pub struct Modes {
    /// Eigenvalues λ = ω² \[rad²/s²\], ascending.
    pub values: Vec<f64>,
    /// Natural frequencies \[Hz\]: `sign(λ) √|λ| / 2π` (a slightly negative λ of a rigid mode
    /// shows as a tiny negative frequency rather than being hidden).
    pub frequencies_hz: Vec<f64>,
    /// Mode shapes, one M-normalised column per eigenvalue (`n × count`).
    pub vectors: Mat<f64>,
}

/// Summary of a mode set for JSON output.
#[derive(Debug, Clone, Serialize)]
pub struct ModesSummary {
    /// Number of DOFs.
    pub dof: usize,
    /// Frequencies \[Hz\], ascending.
    pub frequencies_hz: Vec<f64>,
}

impl Modes {
    /// Build from eigenvalues and vectors (already M-normalised), sorting ascending and
    /// applying the sign convention.
    pub fn from_parts(values: Vec<f64>, vectors: Mat<f64>) -> Self {
        let mut order: Vec<usize> = (0..values.len()).collect();
        order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
        let n = vectors.nrows();
        let mut v = Mat::from_fn(n, order.len(), |i, j| vectors[(i, order[j])]);
        normalize_signs(v.as_mut());
        let values: Vec<f64> = order.iter().map(|&i| values[i]).collect();
        let frequencies_hz = values.iter().map(|&l| frequency_hz(l)).collect();
        Self {
            values,
            frequencies_hz,
            vectors: v,
        }
    }

    /// Number of modes.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Whether there are no modes.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// Circular frequencies ω = sign(λ)√|λ| \[rad/s\].
    pub fn omegas(&self) -> Vec<f64> {
        self.values
            .iter()
            .map(|&l| l.signum() * l.abs().sqrt())
            .collect()
    }

    /// JSON-friendly summary.
    pub fn summary(&self) -> ModesSummary {
        ModesSummary {
            dof: self.vectors.nrows(),
            frequencies_hz: self.frequencies_hz.clone(),
        }
    }
}

/// `sign(λ) √|λ| / 2π` \[Hz\] for an eigenvalue λ \[rad²/s²\].
pub fn frequency_hz(lambda: f64) -> f64 {
    lambda.signum() * lambda.abs().sqrt() / (2.0 * std::f64::consts::PI)
}

/// Sign convention: flip each column so that its largest-magnitude entry is positive (the
/// first one within a relative 1e-8 of the maximum, so near-ties resolve deterministically).
pub fn normalize_signs(mut v: MatMut<'_, f64>) {
    for j in 0..v.ncols() {
        let mut max = 0.0f64;
        for i in 0..v.nrows() {
            max = max.max(v[(i, j)].abs());
        }
        let mut s = 1.0;
        for i in 0..v.nrows() {
            if v[(i, j)].abs() >= max * (1.0 - 1e-8) {
                s = v[(i, j)].signum();
                break;
            }
        }
        if s < 0.0 {
            for i in 0..v.nrows() {
                v[(i, j)] = -v[(i, j)];
            }
        }
    }
}
