//! The friction law of the belt–pulley contact, chosen at run time: Kerkkänen's tri-linear
//! creep-rate law (Fig. 3.3) or the Coulomb–tanh law (Ribaric (6.2)).

use contact::{CoulombTanh, CreepRate, FrictionForce, FrictionLaw};
use serde::{Deserialize, Serialize};

/// Friction law per unit belt length.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "law", rename_all = "snake_case", deny_unknown_fields)]
pub enum BeltFriction {
    /// `|f_t| = min(ν_s |v_t|, μ |f_n|)` (Kerkkänen (3.23) with Fig. 3.3).
    CreepRate {
        /// Friction coefficient `μ`.
        mu: f64,
        /// Creep-rate factor `ν_s` [kg/(m·s)].
        creep: f64,
    },
    /// `f_t = −μ tanh(κ v_t) |f_n|` (Ribaric (6.2)).
    Tanh {
        /// Friction coefficient `μ`.
        mu: f64,
        /// Slope parameter `κ` [s/m].
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
