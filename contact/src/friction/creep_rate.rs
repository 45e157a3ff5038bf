//! Kerkkänen's tri-linear creep-rate friction law (Fig. 3.3, (3.23); ch. 4.5 for the plate belt).

use super::{FrictionForce, FrictionLaw};
use serde::{Deserialize, Serialize};

/// Kerkkänen's tri-linear creep-rate friction law (Fig. 3.3, seed note §4.3):
/// `|f_t| = min(ν_s |v_t|, μ |f_n|)`, `f_t = −sign(v_t) |f_t|` — a line of slope `ν_s`
/// \[kg/(m·s) per unit length\] through the origin saturated at the Coulomb bound.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct CreepRate {
    /// Friction coefficient `μ` \[-\].
    pub mu: f64,
    /// Creep-rate factor `ν_s` \[N·s/m per unit length\].
    pub creep: f64,
}

impl FrictionLaw for CreepRate {
    fn friction(&self, slip: f64, normal: f64) -> FrictionForce {
        let lin = self.creep * slip;
        let cap = self.mu * normal.abs();
        if lin.abs() <= cap {
            FrictionForce {
                force: -lin,
                d_slip: -self.creep,
                d_normal: 0.0,
            }
        } else {
            FrictionForce {
                force: -slip.signum() * cap,
                d_slip: 0.0,
                d_normal: -slip.signum() * self.mu * normal.signum(),
            }
        }
    }
    fn coefficient(&self) -> f64 {
        self.mu
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: the tri-linear law's three branches (Kerkkänen Fig. 3.3).
    #[test]
    fn creep_rate_branches() {
        let law = CreepRate {
            mu: 1.2,
            creep: 1e4,
        };
        assert_eq!(law.friction(1e-3, 100.0).force, -10.0);
        assert_eq!(law.friction(1.0, 100.0).force, -120.0);
        assert_eq!(law.friction(-1.0, 100.0).force, 120.0);
    }
}
