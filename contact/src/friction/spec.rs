//! Friction laws named in configuration files: a `law = "…"` table per law, each mapped to its
//! [`FrictionLaw`] by enum dispatch (no allocation, `Copy`).

use super::{
    Augmented, Coulomb, CoulombTanh, CreepRate, FrictionForce, FrictionLaw, Frictionless,
    SlipRegularized, Stribeck, TangentFriction,
};
use mbd_core::validate::{InvalidField, Validate};
use nalgebra::{Matrix2, Vector2};
use serde::{Deserialize, Serialize};

/// A friction law chosen in a configuration table, e.g. `{ law = "tanh", mu = 1.2, kappa = 40 }`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "law", rename_all = "snake_case", deny_unknown_fields)]
pub enum FrictionSpec {
    /// [`CreepRate`]: `|f_t| = min(ν_s |v_t|, μ |f_n|)` (Kerkkänen (3.23), Fig. 3.3).
    CreepRate {
        /// Friction coefficient `μ` \[-\].
        mu: f64,
        /// Creep-rate factor `ν_s` \[kg/(m·s)\].
        creep: f64,
    },
    /// [`CoulombTanh`]: `f_t = −μ tanh(κ v_t) |f_n|` (Ribaric (6.2)).
    Tanh {
        /// Friction coefficient `μ` \[-\].
        mu: f64,
        /// Slope parameter `κ` \[s/m\].
        kappa: f64,
    },
    /// [`CoulombTanh`] stated by its slip-velocity scale: `f_t = −μ tanh(v_t / v_s) |f_n|`
    /// (`κ = 1/v_s`; issue 34). The law's sharpness is a property of the contact, not of the
    /// drive's speed: the friction reaches 76 % of μ|f_n| at `v_t = v_s` on any drive, and
    /// the speed loss approaches its Coulomb limit as `v_s → 0` (BENCHMARKS.md, "friction
    /// regularisation").
    TanhSlip {
        /// Friction coefficient `μ` \[-\].
        mu: f64,
        /// Slip-velocity scale `v_s` \[m/s\] (default [`DEFAULT_SLIP_VELOCITY`]).
        #[serde(default = "default_slip_velocity")]
        slip_velocity: f64,
    },
    /// [`Coulomb`]: set-valued, with stick (Ribaric §7.3, §8.4.3).
    Coulomb {
        /// Friction coefficient `μ` \[-\].
        mu: f64,
    },
    /// [`SlipRegularized`]: `f_t = −μ|f_n| v_t/√(|v_t|²+ε²)` (Ribaric, seed note U20).
    Regularized {
        /// Friction coefficient `μ` \[-\].
        mu: f64,
        /// Regularisation `ε` \[m/s\].
        epsilon: f64,
    },
    /// [`Stribeck`]: `μ(v) = μ_k + (μ_s − μ_k) e^{−|v|/v_s}` with `tanh(κ v_t)`.
    Stribeck {
        /// Static coefficient `μ_s`.
        mu_static: f64,
        /// Kinetic coefficient `μ_k`.
        mu_kinetic: f64,
        /// Stribeck velocity `v_s` \[m/s\].
        stribeck_velocity: f64,
        /// Slope `κ` \[s/m\].
        kappa: f64,
    },
    /// [`Frictionless`].
    #[serde(deserialize_with = "mbd_core::validate::unit_variant")]
    Frictionless,
}

/// Default slip-velocity scale `v_s` \[m/s\] of [`FrictionSpec::TanhSlip`], and with μ = 1.2
/// the belt drives' default friction (`belt::BeltContact::default`, the friction a layout gets
/// when it states none): `f_t = −μ tanh(v_t / v_s) |f_n|` (Ribaric (6.2) with `κ = 1/v_s`;
/// issue 34 item 3).
///
/// The regularised law lets the belt creep on the whole wrap at slip velocities of order
/// `v_s`, on top of the creep of its stretch (`u ≈ v ΔT / EA`); the speed loss reaches its
/// Coulomb limit (`v_s → 0`) when `v_s` is well below the wrap's creep scale
/// `μ θ T v / EA` (24 mm/s on Ribaric's Table 6-1 at 62.8 rad/s, 0.1 m/s on the
/// Pechstein–Gerstmayr drive). 0.3 mm/s (`κ` ≈ 3333 s/m) is the largest scale of the
/// convergence study (BENCHMARKS.md, "friction regularisation" and "0.3 mm/s as the default",
/// 2026-12-07) at which every model (flowing with its chord contact rates and damping, nodal,
/// ANCF) runs Table 6-1 at 10 and 30 N·m, the Pechstein–Gerstmayr drive and the default FEAD
/// drive at 800 rpm with its default settings (the ANCF belt with the FEAD study's settings for
/// a sharp law and its Newton velocity tolerance; the nodal belt's speed-loss means over whole
/// loop passages, `drives::speed_loss::averaging_steps`) and its speed loss lies within 1 % of
/// its Coulomb limit: the nodal belt's lightly loaded power-steering pulley of the FEAD drive,
/// the slowest to converge, +0.79 % from its Richardson limit (0.5 mm/s: +1.3 %); every other
/// point measured at 0.3 mm/s within 0.81 % of its Richardson limit or of its run at a smaller
/// scale (the farthest: the ANCF belt's tensioner idler on the FEAD drive against 0.125 mm/s,
/// −0.81 %; the nodal belt on the Pechstein–Gerstmayr drive −0.12 %; its flowing and ANCF
/// belts, run at 0.5 and 0.25 mm/s, within 0.4 % of the creep theory of their spans at both). Ribaric's
/// κ = 40 s/m (`v_s` = 25 mm/s) gives 2.3 times the limit on Table 6-1 at 10 N·m. The sharper
/// law costs Newton iterations: 1–9 times κ = 40's CPU on these drives (9 for the ANCF belt on
/// the FEAD drive), 32 times for the ANCF belt on a three-pulley drive at 1500 rpm. The
/// earlier 0.05 mm/s cost 5–9 times κ = 40's on the flowing and nodal belts and failed on the
/// ANCF belt (Table 6-1 at 0.1 ms steps, the Pechstein–Gerstmayr drive); 0.5 mm/s, the default
/// until this study, missed the 1 % on the power-steering pulley above.
pub const DEFAULT_SLIP_VELOCITY: f64 = 3.0e-4;

fn default_slip_velocity() -> f64 {
    DEFAULT_SLIP_VELOCITY
}

impl FrictionSpec {
    /// `μ tanh(v_t / v_s)` with the default scale [`DEFAULT_SLIP_VELOCITY`]
    /// ([`FrictionSpec::TanhSlip`]).
    pub fn tanh_slip(mu: f64) -> Self {
        FrictionSpec::TanhSlip {
            mu,
            slip_velocity: DEFAULT_SLIP_VELOCITY,
        }
    }
}

macro_rules! dispatch {
    ($s:expr, $l:ident => $e:expr) => {
        match *$s {
            FrictionSpec::CreepRate { mu, creep } => {
                let $l = CreepRate { mu, creep };
                $e
            }
            FrictionSpec::Tanh { mu, kappa } => {
                let $l = CoulombTanh { mu, kappa };
                $e
            }
            FrictionSpec::TanhSlip { mu, slip_velocity } => {
                let $l = CoulombTanh {
                    mu,
                    kappa: 1.0 / slip_velocity,
                };
                $e
            }
            FrictionSpec::Coulomb { mu } => {
                let $l = Coulomb { mu };
                $e
            }
            FrictionSpec::Regularized { mu, epsilon } => {
                let $l = SlipRegularized { mu, epsilon };
                $e
            }
            FrictionSpec::Stribeck {
                mu_static,
                mu_kinetic,
                stribeck_velocity,
                kappa,
            } => {
                let $l = Stribeck {
                    mu_static,
                    mu_kinetic,
                    stribeck_velocity,
                    kappa,
                };
                $e
            }
            FrictionSpec::Frictionless => {
                let $l = Frictionless;
                $e
            }
        }
    };
}

impl FrictionSpec {
    /// Whether this is Ribaric's law `μ tanh(κ v_t)` with its time constant κ (Ribaric (6.2),
    /// [`FrictionSpec::Tanh`]): the law the seed's figures were computed with, to which the
    /// belt models tie their seed formulations (flowing contact rates and damping, the ANCF
    /// belt's FEAD Newton settings).
    pub fn is_ribaric_tanh(&self) -> bool {
        matches!(self, FrictionSpec::Tanh { .. })
    }

    /// Friction coefficient `μ` \[-\] (the largest one of a Stribeck law).
    pub fn mu(&self) -> f64 {
        self.coefficient()
    }

    /// The same law with its friction coefficient scaled by `factor` \[-\]: `μ → factor·μ`
    /// (both `μ_s` and `μ_k` of a Stribeck law), every other parameter (`κ`, `v_s`, `ε`, `ν_s`,
    /// the Stribeck velocity) unchanged; [`FrictionSpec::Frictionless`] stays frictionless.
    ///
    /// This is the friction of a wedge: a V- or V-ribbed belt of included angle `β` in a
    /// groove carries the flank normal force `N/sin(β/2)` for the radial force `N`, so each
    /// flank's law, stated per unit flank normal force, acts on the radial force with
    /// `μ/sin(β/2)` (Johnson, *Contact Mechanics* §8.6; `factor = 1/sin(β/2)`,
    /// `belt::Section::friction_factor`). The regularisation parameters are slip-velocity
    /// scales of the flank contact and so stay as they are; the creep-rate law's sliding
    /// branch `μ|f_n|` scales, its creep branch `ν_s |v_t|` does not. The result is not
    /// re-validated: a factor above 1 may take `μ` past [`MAX_FRICTION_COEFFICIENT`], which
    /// bounds what a user writes, not an effective coefficient.
    pub fn scaled(&self, factor: f64) -> Self {
        let f = factor;
        match *self {
            FrictionSpec::CreepRate { mu, creep } => FrictionSpec::CreepRate { mu: f * mu, creep },
            FrictionSpec::Tanh { mu, kappa } => FrictionSpec::Tanh { mu: f * mu, kappa },
            FrictionSpec::TanhSlip { mu, slip_velocity } => FrictionSpec::TanhSlip {
                mu: f * mu,
                slip_velocity,
            },
            FrictionSpec::Coulomb { mu } => FrictionSpec::Coulomb { mu: f * mu },
            FrictionSpec::Regularized { mu, epsilon } => FrictionSpec::Regularized {
                mu: f * mu,
                epsilon,
            },
            FrictionSpec::Stribeck {
                mu_static,
                mu_kinetic,
                stribeck_velocity,
                kappa,
            } => FrictionSpec::Stribeck {
                mu_static: f * mu_static,
                mu_kinetic: f * mu_kinetic,
                stribeck_velocity,
                kappa,
            },
            FrictionSpec::Frictionless => FrictionSpec::Frictionless,
        }
    }
}

/// Largest friction coefficient a configuration may give. Dry friction of engineering
/// materials stays below μ ≈ 2 (rubber on dry asphalt about 1, racing slicks up to 1.8,
/// Kerkkänen's belt 1.2); a larger number is an input error (e.g. `friction = 1e300`, issue 20),
/// not a contact law.
pub const MAX_FRICTION_COEFFICIENT: f64 = 5.0;

/// Checks a friction coefficient `μ`: finite, in \[0, [`MAX_FRICTION_COEFFICIENT`]\].
pub fn check_coefficient(field: &str, mu: f64) -> Result<(), InvalidField> {
    mbd_core::validate::check::within(field, mu, 0.0, MAX_FRICTION_COEFFICIENT, "")
}

impl Validate for FrictionSpec {
    /// Check the parameters: coefficients in \[0, [`MAX_FRICTION_COEFFICIENT`]\], rates and
    /// velocities finite and `> 0` (field paths relative to the friction table, e.g. `mu`).
    fn validate(&self) -> Result<(), InvalidField> {
        use mbd_core::validate::check::positive as pos;
        let mu = check_coefficient;
        match *self {
            FrictionSpec::CreepRate { mu: m, creep } => {
                mu("mu", m).and(pos("creep", creep, "kg/(m·s)"))
            }
            FrictionSpec::Tanh { mu: m, kappa } => mu("mu", m).and(pos("kappa", kappa, "s/m")),
            FrictionSpec::TanhSlip {
                mu: m,
                slip_velocity,
            } => mu("mu", m).and(mbd_core::validate::check::within(
                "slip_velocity",
                slip_velocity,
                1e-7,
                10.0,
                "m/s",
            )),
            FrictionSpec::Coulomb { mu: m } => mu("mu", m),
            FrictionSpec::Regularized { mu: m, epsilon } => {
                mu("mu", m).and(pos("epsilon", epsilon, "m/s"))
            }
            FrictionSpec::Stribeck {
                mu_static,
                mu_kinetic,
                stribeck_velocity,
                kappa,
            } => mu("mu_static", mu_static)
                .and(mu("mu_kinetic", mu_kinetic))
                .and(pos("stribeck_velocity", stribeck_velocity, "m/s"))
                .and(pos("kappa", kappa, "s/m")),
            FrictionSpec::Frictionless => Ok(()),
        }
    }
}

impl FrictionLaw for FrictionSpec {
    #[inline]
    fn friction(&self, slip: f64, normal: f64) -> FrictionForce {
        dispatch!(self, l => l.friction(slip, normal))
    }
    fn coefficient(&self) -> f64 {
        dispatch!(self, l => l.coefficient())
    }
    fn transition_width(&self) -> Option<f64> {
        dispatch!(self, l => l.transition_width())
    }
    fn friction_tangent(&self, slip: Vector2<f64>, normal: f64) -> TangentFriction {
        dispatch!(self, l => l.friction_tangent(slip, normal))
    }
    #[inline]
    fn friction_tangent_force(&self, slip: Vector2<f64>, normal: f64) -> Vector2<f64> {
        dispatch!(self, l => l.friction_tangent_force(slip, normal))
    }
    /// The law chosen once for the whole batch (its own batch loop).
    #[inline(always)]
    fn friction_tangent_forces(&self, slip: [&[f64]; 2], normal: &[f64], out: [&mut [f64]; 2]) {
        dispatch!(self, l => l.friction_tangent_forces(slip, normal, out))
    }
    fn is_set_valued(&self) -> bool {
        dispatch!(self, l => l.is_set_valued())
    }
    fn augmented(
        &self, force: Vector2<f64>, slip: Vector2<f64>, normal: f64, r_t: f64, jacobian: bool,
    ) -> Augmented {
        dispatch!(self, l => l.augmented(force, slip, normal, r_t, jacobian))
    }
    fn local_force(&self, b: Matrix2<f64>, r: Vector2<f64>, normal: f64) -> Vector2<f64> {
        dispatch!(self, l => l.local_force(b, r, normal))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: the table form of each law parses and dispatches to the law itself.
    #[test]
    fn tables_map_to_laws() {
        let s: FrictionSpec =
            serde_json::from_str(r#"{"law":"tanh","mu":1.2,"kappa":40.0}"#).unwrap();
        let t = CoulombTanh {
            mu: 1.2,
            kappa: 40.0,
        };
        assert_eq!(s.friction(0.01, 50.0), t.friction(0.01, 50.0));
        // the same law by its slip-velocity scale v_s = 1/κ = 25 mm/s
        let s: FrictionSpec =
            serde_json::from_str(r#"{"law":"tanh_slip","mu":1.2,"slip_velocity":0.025}"#).unwrap();
        let (a, b) = (s.friction(0.01, 50.0), t.friction(0.01, 50.0));
        assert!(
            (a.force - b.force).abs() < 1e-12 * b.force.abs(),
            "{a:?} {b:?}"
        );
        // without `slip_velocity` the default scale (by hand: the constant)
        let s: FrictionSpec = serde_json::from_str(r#"{"law":"tanh_slip","mu":1.2}"#).unwrap();
        assert_eq!(
            s,
            FrictionSpec::TanhSlip {
                mu: 1.2,
                slip_velocity: DEFAULT_SLIP_VELOCITY
            }
        );
        let bad = FrictionSpec::Stribeck {
            mu_static: 0.5,
            mu_kinetic: 0.4,
            stribeck_velocity: 0.0,
            kappa: 40.0,
        };
        assert_eq!(bad.validate().unwrap_err().field, "stribeck_velocity");
    }

    // Reference: the wedge (Johnson §8.6) scales the force of every law by the factor on its
    // sliding branch, f'(v, N) = factor · f(v, N), at the law's own slip scale; the creep-rate
    // law's creep branch ν_s|v| (below μN) does not scale; factor 1 is the law itself.
    #[test]
    fn scaled_laws_scale_the_sliding_force() {
        let k = 1.0 / 20f64.to_radians().sin();
        let n = 50.0;
        let laws = [
            FrictionSpec::Tanh {
                mu: 1.2,
                kappa: 40.0,
            },
            FrictionSpec::TanhSlip {
                mu: 0.5,
                slip_velocity: 0.025,
            },
            FrictionSpec::Coulomb { mu: 0.4 },
            FrictionSpec::Regularized {
                mu: 0.6,
                epsilon: 0.01,
            },
            FrictionSpec::Stribeck {
                mu_static: 0.6,
                mu_kinetic: 0.4,
                stribeck_velocity: 0.1,
                kappa: 40.0,
            },
            FrictionSpec::CreepRate {
                mu: 1.2,
                creep: 1.0e5,
            },
            FrictionSpec::Frictionless,
        ];
        for law in laws {
            let s = law.scaled(k);
            assert_eq!(law.scaled(1.0), law);
            assert!(
                (s.coefficient() - k * law.coefficient()).abs() < 1e-12,
                "{law:?}"
            );
            // sliding at 0.05 and 0.5 m/s (creep-rate: past μN/ν_s = 0.6 mm/s and k times it)
            for v in [0.05, 0.5] {
                let (a, b) = (s.friction(v, n).force, law.friction(v, n).force);
                assert!(
                    (a - k * b).abs() < 1e-9 * b.abs().max(1.0),
                    "{law:?} at {v}"
                );
            }
        }
        // the creep branch of the creep-rate law (ν_s |v| below μN) is the flank's, unscaled
        let c = FrictionSpec::CreepRate {
            mu: 1.2,
            creep: 1.0e5,
        };
        let v = 1e-4;
        assert_eq!(c.scaled(k).friction(v, n).force, c.friction(v, n).force);
        if let FrictionSpec::Stribeck {
            mu_static,
            mu_kinetic,
            ..
        } = laws[4].scaled(k)
        {
            assert!((mu_static - 0.6 * k).abs() < 1e-12 && (mu_kinetic - 0.4 * k).abs() < 1e-12);
        } else {
            panic!("Stribeck stays Stribeck");
        }
    }
}
