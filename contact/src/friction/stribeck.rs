//! Stribeck friction: a static-to-kinetic exponential decay of the friction coefficient,
//! regularised with `tanh` — the worked example of adding a law (one file, one `impl`).

use super::{FrictionForce, FrictionLaw};
use serde::{Deserialize, Serialize};

/// Stribeck friction with exponential decay, regularised like Ribaric (6.2):
///
/// `μ(v) = μ_k + (μ_s − μ_k) e^{−|v|/v_s}`,  `F_T = −μ(v_t) tanh(κ v_t) |F_N|`.
///
/// With `μ_s = μ_k` it is [`CoulombTanh`](super::CoulombTanh) to the last bit. Dissipative for
/// `μ_s, μ_k ≥ 0` (`F_T v_t ≤ 0`); spatially the isotropic extension of the trait's default.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Stribeck {
    /// Static friction coefficient `μ_s`.
    pub mu_static: f64,
    /// Kinetic friction coefficient `μ_k`.
    pub mu_kinetic: f64,
    /// Stribeck velocity `v_s` \[m/s\].
    pub stribeck_velocity: f64,
    /// Regularisation slope `κ` \[s/m\].
    pub kappa: f64,
}

impl FrictionLaw for Stribeck {
    fn friction(&self, slip: f64, normal: f64) -> FrictionForce {
        let th = (self.kappa * slip).tanh();
        let a = normal.abs();
        let decay = (-slip.abs() / self.stribeck_velocity).exp();
        let dm = self.mu_static - self.mu_kinetic;
        let mu = self.mu_kinetic + dm * decay;
        // dμ/dv = −(μ_s − μ_k)/v_s e^{−|v|/v_s} sign(v)
        let dmu = -dm / self.stribeck_velocity * decay * slip.signum();
        FrictionForce {
            force: -mu * th * a,
            d_slip: -mu * self.kappa * (1.0 - th * th) * a - dmu * th * a,
            d_normal: -mu * th * normal.signum(),
        }
    }
    fn coefficient(&self) -> f64 {
        self.mu_static.max(self.mu_kinetic)
    }
    /// `1/κ` \[m/s\] of the `tanh` factor.
    fn transition_width(&self) -> Option<f64> {
        Some(1.0 / self.kappa)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::friction::CoulombTanh;

    // Reference: with μ_s = μ_k the law is Ribaric (6.2) (second formulation, bit for bit);
    // with μ_s > μ_k it exceeds it at small slip and tends to it at large slip.
    #[test]
    fn reduces_to_coulomb_tanh() {
        let tanh = CoulombTanh {
            mu: 1.2,
            kappa: 40.0,
        };
        let same = Stribeck {
            mu_static: 1.2,
            mu_kinetic: 1.2,
            stribeck_velocity: 0.01,
            kappa: 40.0,
        };
        let peak = Stribeck {
            mu_static: 1.5,
            ..same
        };
        for v in [-0.3, -1e-3, 0.0, 2e-4, 0.05, 4.0] {
            assert_eq!(same.friction(v, 80.0), tanh.friction(v, 80.0));
            let (p, t) = (peak.friction(v, 80.0).force, tanh.friction(v, 80.0).force);
            assert!(p.abs() >= t.abs());
        }
        let far = peak.friction(4.0, 80.0).force;
        assert!((far - tanh.friction(4.0, 80.0).force).abs() < 1e-9 * far.abs());
    }
}
