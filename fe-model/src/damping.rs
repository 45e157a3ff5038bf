//! Rayleigh (proportional) damping `C = α M + β K`.
//!
//! The modal damping ratio of mode `ω` is `ζ(ω) = α/(2ω) + βω/2` (Ribaric (6.x) belt example,
//! Chopra *Dynamics of Structures* (11.4.9)). Given two target ratios `ζ1, ζ2` at `ω1 ≠ ω2`,
//! solving the 2×2 system gives
//! `α = 2 ω1 ω2 (ζ1 ω2 − ζ2 ω1)/(ω2² − ω1²)`, `β = 2 (ζ2 ω2 − ζ1 ω1)/(ω2² − ω1²)`.

use crate::FeError;
use faer::sparse::SparseColMat;
use serde::{Deserialize, Serialize};

/// Rayleigh coefficients.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Rayleigh {
    /// Mass-proportional coefficient α \[1/s\].
    pub alpha: f64,
    /// Stiffness-proportional coefficient β \[s\].
    pub beta: f64,
}

impl Rayleigh {
    /// Coefficients giving damping ratios `zeta1` at `omega1` and `zeta2` at `omega2`
    /// (circular frequencies in rad/s).
    pub fn from_modal_ratios(
        omega1: f64, zeta1: f64, omega2: f64, zeta2: f64,
    ) -> Result<Self, FeError> {
        FeError::check_positive("omega1", omega1)?;
        FeError::check_positive("omega2", omega2)?;
        FeError::check_non_negative("zeta1", zeta1)?;
        FeError::check_non_negative("zeta2", zeta2)?;
        let den = omega2 * omega2 - omega1 * omega1;
        if den.abs() <= 1e-12 * omega2 * omega2 {
            return Err(FeError::param(
                "omega2",
                omega2,
                "must differ from omega1 to determine alpha and beta",
            ));
        }
        Ok(Self {
            alpha: 2.0 * omega1 * omega2 * (zeta1 * omega2 - zeta2 * omega1) / den,
            beta: 2.0 * (zeta2 * omega2 - zeta1 * omega1) / den,
        })
    }

    /// Modal damping ratio `ζ(ω) = α/(2ω) + βω/2` at circular frequency `omega` \[rad/s\].
    pub fn ratio(&self, omega: f64) -> f64 {
        self.alpha / (2.0 * omega) + self.beta * omega / 2.0
    }

    /// Sparse damping matrix `C = α M + β K` (M and K must have the same shape).
    pub fn matrix(
        &self, m: &SparseColMat<usize, f64>, k: &SparseColMat<usize, f64>,
    ) -> Result<SparseColMat<usize, f64>, FeError> {
        if m.nrows() != k.nrows() || m.ncols() != k.ncols() {
            return Err(FeError::Dimension {
                context: "Rayleigh::matrix (M and K sizes)".into(),
                expected: m.nrows(),
                got: k.nrows(),
            });
        }
        let mut trip = Vec::with_capacity(m.compute_nnz() + k.compute_nnz());
        for (mat, s) in [(m, self.alpha), (k, self.beta)] {
            for (r, c, v) in crate::sparse::triplets(mat.as_ref()) {
                trip.push(faer::sparse::Triplet::new(r, c, s * v));
            }
        }
        SparseColMat::try_new_from_triplets(m.nrows(), m.ncols(), &trip)
            .map_err(|e| FeError::Sparse(format!("Rayleigh C: {e:?}")))
    }

    /// Dense damping matrix `C = α M + β K`.
    pub fn dense(
        &self, m: faer::MatRef<'_, f64>, k: faer::MatRef<'_, f64>,
    ) -> Result<faer::Mat<f64>, FeError> {
        if m.nrows() != k.nrows() || m.ncols() != k.ncols() {
            return Err(FeError::Dimension {
                context: "Rayleigh::dense (M and K sizes)".into(),
                expected: m.nrows(),
                got: k.nrows(),
            });
        }
        Ok(faer::Mat::from_fn(m.nrows(), m.ncols(), |i, j| {
            self.alpha * m[(i, j)] + self.beta * k[(i, j)]
        }))
    }
}
