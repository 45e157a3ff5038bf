//! Friction laws: tangential force as a function of the slip velocity `v_t` (body relative to
//! the obstacle surface) and the normal force, with derivatives for implicit integration.
//! The returned force opposes the slip: `f_t·v_t ≤ 0`.

use serde::{Deserialize, Serialize};

/// Tangential force and its partial derivatives.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FrictionForce {
    /// Signed force along the tangent `t` \[N or N/m\].
    pub force: f64,
    /// `∂force/∂v_t`.
    pub d_slip: f64,
    /// `∂force/∂f_n`.
    pub d_normal: f64,
}

/// A friction law `f_t(v_t, f_n)`.
pub trait FrictionLaw {
    /// Force along `t` for slip velocity `v_t` \[m/s\] and normal force `f_n` (the magnitude
    /// `|f_n|` bounds the force, Kerkkänen (3.23)).
    fn friction(&self, slip: f64, normal: f64) -> FrictionForce;
}

/// Coulomb friction regularised by `tanh`, Ribaric (6.2): `F_T = −μ tanh(κ v_t) |F_N|`
/// (Ribaric: `μ = 1.2`, `κ = 40 s/m`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CoulombTanh {
    /// Friction coefficient `μ`.
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
}

/// Kerkkänen's tri-linear creep-rate friction law (Fig. 3.3, seed note §4.3):
/// `|f_t| = min(ν_s |v_t|, μ |f_n|)`, `f_t = −sign(v_t) |f_t|` — a line of slope `ν_s`
/// \[kg/(m·s) per unit length\] through the origin saturated at the Coulomb bound.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CreepRate {
    /// Friction coefficient `μ`.
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
}

/// Pure Coulomb slip friction per contact node without stick, Ribaric §8.4.3:
/// `F_T = −μ |F_N| sign(v_t)` with `sign(0) = 0`; `∂F_T/∂v_t = 0` (set-valued at 0).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CoulombSlip {
    /// Friction coefficient `μ` (Ribaric: 0.85 nominal, 0 for pure slip).
    pub mu: f64,
}

impl FrictionLaw for CoulombSlip {
    fn friction(&self, slip: f64, normal: f64) -> FrictionForce {
        let s = if slip > 0.0 {
            1.0
        } else if slip < 0.0 {
            -1.0
        } else {
            0.0
        };
        FrictionForce {
            force: -self.mu * normal.abs() * s,
            d_slip: 0.0,
            d_normal: -self.mu * s * normal.signum(),
        }
    }
}

/// No friction.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Frictionless;

impl FrictionLaw for Frictionless {
    fn friction(&self, _slip: f64, _normal: f64) -> FrictionForce {
        FrictionForce::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fd(law: &dyn FrictionLaw, v: f64, n: f64) {
        let h = 1e-7;
        let f = law.friction(v, n);
        let dv = (law.friction(v + h, n).force - law.friction(v - h, n).force) / (2.0 * h);
        let dn = (law.friction(v, n + h).force - law.friction(v, n - h).force) / (2.0 * h);
        assert!(
            (dv - f.d_slip).abs() < 1e-5 * (1.0 + dv.abs()),
            "d/dv {dv} vs {}",
            f.d_slip
        );
        assert!(
            (dn - f.d_normal).abs() < 1e-6,
            "d/dfn {dn} vs {}",
            f.d_normal
        );
    }

    // Reference: finite differences away from the kinks; dissipativity f_t v_t ≤ 0.
    #[test]
    fn derivatives_and_dissipation() {
        let laws: [&dyn FrictionLaw; 3] = [
            &CoulombTanh {
                mu: 1.2,
                kappa: 40.0,
            },
            &CreepRate {
                mu: 1.2,
                creep: 1e5,
            },
            &CoulombSlip { mu: 0.85 },
        ];
        for law in laws {
            for (v, n) in [
                (0.003, 100.0),
                (-0.01, 50.0),
                (0.5, 20.0),
                (-2.0, 80.0),
                (1e-6, 300.0),
            ] {
                fd(law, v, n);
                assert!(law.friction(v, n).force * v <= 0.0);
            }
        }
    }

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
