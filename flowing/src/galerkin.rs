//! The analytical moving string by Galerkin's method (Ribaric (4.23)–(4.30)).

use crate::error::{FlowError, invalid};
use crate::gyroscopic::GyroscopicSystem;
use crate::params::StringConfig;
use faer::Mat;
use std::f64::consts::PI;

/// `ä + A ȧ + B a = 0` (Ribaric (4.27)) for the first `n_terms` sine modes
/// `φ_n = sin(nπx/L)` (4.24) of a string travelling at constant speed `v` between fixed ends.
#[derive(Debug, Clone)]
pub struct GalerkinString {
    /// String parameters.
    pub params: StringConfig,
    /// Axial speed `v` \[m/s\].
    pub speed: f64,
    /// Gyroscopic matrix `A` (4.28), skew-symmetric \[1/s\].
    pub a: Mat<f64>,
    /// Stiffness `B` (4.28), diagonal `(c² − v²)(nπ/L)²` \[1/s²\].
    pub b: Mat<f64>,
}

impl GalerkinString {
    /// Builds (4.28):
    /// `A_mn = (2vn/L)[(1 − cos((m+n)π))/(m+n) + (1 − cos((m−n)π))/(m−n)]` (m ≠ n), `A_mm = 0`;
    /// `B_mm = (c² − v²)(πm/L)²`.
    pub fn new(params: StringConfig, speed: f64, n_terms: usize) -> Result<Self, FlowError> {
        params.validate()?;
        if n_terms == 0 {
            return Err(invalid(
                "Galerkin string: terms",
                "at least one term is needed",
            ));
        }
        if !speed.is_finite() {
            return Err(invalid(
                "Galerkin string: speed",
                format!("{speed} is not finite"),
            ));
        }
        let l = params.length;
        let c2 = params.tension / params.mu();
        let a = Mat::from_fn(n_terms, n_terms, |i, j| {
            let (m, n) = ((i + 1) as f64, (j + 1) as f64);
            if i == j {
                0.0
            } else {
                2.0 * speed * n / l
                    * ((1.0 - ((m + n) * PI).cos()) / (m + n)
                        + (1.0 - ((m - n) * PI).cos()) / (m - n))
            }
        });
        let b = Mat::from_fn(n_terms, n_terms, |i, j| {
            if i == j {
                (c2 - speed * speed) * (PI * (i + 1) as f64 / l).powi(2)
            } else {
                0.0
            }
        });
        Ok(Self {
            params,
            speed,
            a,
            b,
        })
    }

    /// The system as a gyroscopic system with identity mass (state matrix (4.29)).
    pub fn system(&self) -> GyroscopicSystem {
        let n = self.a.nrows();
        GyroscopicSystem {
            mass: Mat::identity(n, n),
            gyro: self.a.clone(),
            stiffness: self.b.clone(),
        }
    }

    /// Deflection `u(x) = Σ a_n sin(nπx/L)` (4.24) \[m\] for modal amplitudes `amp`.
    pub fn deflection(&self, amp: &[f64], x: f64) -> f64 {
        amp.iter()
            .enumerate()
            .map(|(i, a)| a * ((i + 1) as f64 * PI * x / self.params.length).sin())
            .sum()
    }
}
