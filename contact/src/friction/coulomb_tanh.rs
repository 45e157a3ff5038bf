//! Coulomb friction regularised by `tanh`, Ribaric (6.2).

use super::{FrictionForce, FrictionLaw};
use serde::{Deserialize, Serialize};

/// Coulomb friction regularised by `tanh`, Ribaric (6.2): `F_T = −μ tanh(κ v_t) |F_N|`
/// (Ribaric: `μ = 1.2`, `κ = 40 s/m`). Spatially the isotropic extension
/// `f_t = −μ tanh(κ|v_t|) |F_N| v_t/|v_t|`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct CoulombTanh {
    /// Friction coefficient `μ` \[-\].
    pub mu: f64,
    /// Slope parameter `κ` \[s/m\].
    pub kappa: f64,
}

impl FrictionLaw for CoulombTanh {
    fn friction(&self, slip: f64, normal: f64) -> FrictionForce {
        let th = (self.kappa * slip).tanh();
        let a = normal.abs();
        FrictionForce {
            force: -self.mu * th * a,
            d_slip: -self.mu * self.kappa * (1.0 - th * th) * a,
            d_normal: -self.mu * th * normal.signum(),
        }
    }
    fn coefficient(&self) -> f64 {
        self.mu
    }
    /// `1/κ` \[m/s\]: `tanh` reaches 76 % of the sliding force there.
    fn transition_width(&self) -> Option<f64> {
        Some(1.0 / self.kappa)
    }
}
