//! The friction law of the belt–pulley contact, chosen at run time: Kerkkänen's tri-linear
//! creep-rate law (Fig. 3.3) or the Coulomb–tanh law (Ribaric (6.2)).

use contact::{CoulombTanh, CreepRate, FrictionForce, FrictionLaw, NormalForce, NormalLaw};
use serde::{Deserialize, Serialize};

/// Friction law per unit belt length.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "law", rename_all = "snake_case", deny_unknown_fields)]
pub enum BeltFriction {
    /// `|f_t| = min(ν_s |v_t|, μ |f_n|)` (Kerkkänen (3.23) with Fig. 3.3).
    CreepRate {
        /// Friction coefficient `μ`.
        mu: f64,
        /// Creep-rate factor `ν_s` \[kg/(m·s)\].
        creep: f64,
    },
    /// `f_t = −μ tanh(κ v_t) |f_n|` (Ribaric (6.2)).
    Tanh {
        /// Friction coefficient `μ`.
        mu: f64,
        /// Slope parameter `κ` \[s/m\].
        kappa: f64,
    },
}

impl BeltFriction {
    /// Friction coefficient `μ`.
    pub fn mu(&self) -> f64 {
        match *self {
            BeltFriction::CreepRate { mu, .. } | BeltFriction::Tanh { mu, .. } => mu,
        }
    }

    /// Check the parameters; `Err` is `(field, reason)`.
    pub fn validate(&self) -> Result<(), (String, String)> {
        let (mu, other, name) = match *self {
            BeltFriction::CreepRate { mu, creep } => (mu, creep, "creep"),
            BeltFriction::Tanh { mu, kappa } => (mu, kappa, "kappa"),
        };
        if !(mu.is_finite() && mu >= 0.0) {
            return Err(("friction.mu".into(), format!("must be ≥ 0, got {mu}")));
        }
        if !(other.is_finite() && other > 0.0) {
            return Err((
                format!("friction.{name}"),
                format!("must be > 0, got {other}"),
            ));
        }
        Ok(())
    }
}

impl FrictionLaw for BeltFriction {
    #[inline]
    fn friction(&self, slip: f64, normal: f64) -> FrictionForce {
        match *self {
            BeltFriction::CreepRate { mu, creep } => CreepRate { mu, creep }.friction(slip, normal),
            BeltFriction::Tanh { mu, kappa } => CoulombTanh { mu, kappa }.friction(slip, normal),
        }
    }
}

/// Normal law per unit belt length: `f_n = k₂ d² + k_p d + c_p ḋ` — Kerkkänen's linear penalty
/// with damping (3.20) when `k₂ = 0`, Ribaric's polynomial penalty (6.1) (there per contact node,
/// here per unit length) when `k₂ > 0`. Not clipped (seed note §4.2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeltNormal {
    /// Linear coefficient `k_p` \[N/m²\].
    pub stiffness: f64,
    /// Quadratic coefficient `k₂` \[N/m³\].
    pub quadratic: f64,
    /// Damping `c_p` \[N·s/m²\].
    pub damping: f64,
}

impl NormalLaw for BeltNormal {
    #[inline]
    fn normal(&self, pen: f64, pen_rate: f64) -> NormalForce {
        NormalForce {
            force: (self.quadratic * pen + self.stiffness) * pen + self.damping * pen_rate,
            d_pen: 2.0 * self.quadratic * pen + self.stiffness,
            d_rate: self.damping,
        }
    }
}
