//! Ribaric's slip-only regularisation of Coulomb friction (seed note U20).

use super::{FrictionForce, FrictionLaw, TangentFriction};
use nalgebra::{Matrix2, Vector2};
use serde::{Deserialize, Serialize};

/// Ribaric's slip-only regularised sign (seed note U20): `f_t = −μ |f_n| v_t/√(|v_t|² + ε²)`,
/// with `ε` \[m/s\] the slip-velocity regularisation (Ribaric: 0.05 m/s).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct SlipRegularized {
    /// Friction coefficient `μ` \[-\].
    pub mu: f64,
    /// Regularisation `ε` \[m/s\].
    pub epsilon: f64,
}

impl FrictionLaw for SlipRegularized {
    fn friction(&self, slip: f64, normal: f64) -> FrictionForce {
        let r = (slip * slip + self.epsilon * self.epsilon).sqrt();
        let a = normal.abs();
        FrictionForce {
            force: -self.mu * a * slip / r,
            d_slip: -self.mu * a * self.epsilon * self.epsilon / (r * r * r),
            d_normal: -self.mu * normal.signum() * slip / r,
        }
    }
    fn coefficient(&self) -> f64 {
        self.mu
    }
    /// `ε` \[m/s\]: the law reaches 71 % of the sliding force there.
    fn transition_width(&self) -> Option<f64> {
        Some(self.epsilon)
    }
    fn friction_tangent_force(&self, u: Vector2<f64>, normal: f64) -> Vector2<f64> {
        self.friction_tangent(u, normal).force
    }
    /// `f_t = −μ|f_n| u/ρ`, `ρ = √(|u|²+ε²)`; `∂f_t/∂u = −μ|f_n| (I − s sᵀ)/ρ`, `s = u/ρ`.
    fn friction_tangent(&self, u: Vector2<f64>, normal: f64) -> TangentFriction {
        let r = (u[0] * u[0] + u[1] * u[1] + self.epsilon * self.epsilon).sqrt();
        let a = normal.abs();
        let sv = u / r;
        let js = (Matrix2::identity() - sv * sv.transpose()) / r;
        TangentFriction {
            force: Vector2::new(-self.mu * a * u[0] / r, -self.mu * a * u[1] / r),
            d_slip: js * (-self.mu * a),
            d_normal: sv * (-self.mu * normal.signum()),
        }
    }
}
