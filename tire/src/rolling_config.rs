//! Integration and contact settings of the rolling tire ([`RollingConfig`], the
//! `[rig.rolling]` table): the generalized-α scheme, the contact law, friction law and
//! tolerances, the spindle force evaluation and the use of mirror symmetry. Read by the time
//! step ([`crate::rolling`]) and by the contact step ([`crate::contact_step`]).

use crate::friction::TireFriction;
use contact::friction::spec::check_coefficient;
use mbd_core::Validate;
use mbd_core::integrators::{AlphaCoefficients, AlphaConfig, DriftTrigger, NewtonUpdate};
use mbd_core::validate::{InvalidField, check};
use serde::{Deserialize, Serialize};

/// Normal contact law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case", tag = "law", deny_unknown_fields)]
pub enum NormalContact {
    /// Rigid unilateral constraint with Lagrange multipliers (Ribaric §7.3).
    #[serde(deserialize_with = "mbd_core::validate::unit_variant")]
    Lagrange,
    /// Linear penalty `λ = k · penetration` \[N/m\].
    Penalty {
        /// Stiffness per contact node \[N/m\].
        stiffness: f64,
    },
}

/// How the spindle force (the force of the tire on the wheel) is evaluated.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum SpindleForceMethod {
    /// Newton's second law for the tire (default): the ground's force on the tire minus the
    /// rate of the tire's translational momentum and the mass-proportional damping force,
    /// `F = Σ fᶜ − eᵀM d̈ − α P ż` (module docs). The force-summation (mode-acceleration)
    /// form: it uses only `M` and the contact forces, so it keeps the exact force balance of
    /// the truncated model (steady rolling: `F = Σ fᶜ`, the load).
    #[default]
    Momentum,
    /// The rim forces of Ribaric (7.2), `F = −K_r (z + β ż) − β θ̇ K_r,θ z` (the
    /// mode-displacement form): equal to `Momentum` when nothing is truncated, but carrying
    /// the elastic residual of the truncated basis otherwise (e.g. the centrifugal load).
    Rim,
}

/// Integration and contact settings of the rolling tire.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct RollingConfig {
    /// Time step `h` \[s\].
    pub time_step: f64,
    /// Newmark β of the generalized-α update \[-\] (see [`RollingConfig::generalized_alpha`]).
    pub newmark_beta: f64,
    /// Newmark γ of the generalized-α update \[-\].
    pub newmark_gamma: f64,
    /// Generalized-α weight α_m of the pseudo-acceleration \[-\] (0 with `alpha_f = 0`: plain
    /// Newmark).
    pub alpha_m: f64,
    /// Generalized-α weight α_f of the true acceleration \[-\].
    pub alpha_f: f64,
    /// Coulomb friction coefficient μ \[-\] (Ribaric §8.4.3: 0.85 nominal, 0 pure slip).
    pub friction: f64,
    /// Friction law: `coulomb` (set-valued, with stick; default), `regularized`
    /// (Ribaric's slip-only `f = −μλ u/√(|u|²+ε²)`, seed note U20), or a law table
    /// (see [`TireFriction`]).
    pub friction_law: TireFriction,
    /// Slip-velocity regularisation ε of the `regularized` friction law \[m/s\] (unused by
    /// `coulomb`).
    pub slip_regularization: f64,
    /// Relative tolerance of the contact solve \[-\]: Alart–Curnier residual (complementarity and
    /// friction law, in force units) below this times the largest normal force.
    pub contact_tolerance: f64,
    /// Normal contact law.
    pub normal: NormalContact,
    /// Spin inertia of the wheel (without the rim nodes, which are added) \[kg·m²\].
    pub wheel_spin_inertia: f64,
    /// Relative drift of θ̇ \[-\] at which the spin-dependent force matrix `R` (gyroscopic,
    /// centrifugal and damping terms) is re-formed.
    pub spin_tolerance: f64,
    /// Relative drift of θ̇ \[-\] at which the iteration matrix `S` is inverted again; between
    /// inversions its gyroscopic part `2γh(θ̇_R − θ̇_S)G₁` is lagged by one step (see
    /// [`RollingTire::step`](crate::RollingTire::step)).
    pub matrix_tolerance: f64,
    /// Contact-node candidates: gap below this margin \[m\] (plus `h·v` for nodes facing the
    /// cleat, whose faces approach at up to the surface speed `v`).
    pub contact_margin: f64,
    /// Evaluation of the spindle force: `momentum` (default) or `rim` (Ribaric (7.2)).
    pub spindle_force: SpindleForceMethod,
    /// Threads of the step's two large matrix–vector products (the force matrix `[G₁ H]` and
    /// the explicit inverse `S⁻¹`): 1 = the calling thread alone; 2 or more = a worker thread
    /// computes half of the rows of each ([`mbd_core::parallel`]; bitwise the same results).
    /// Default 1: with the mirror half model (`symmetry`) the products fit a core's L2 cache
    /// and a second thread no longer pays: on an idle 2-core machine the cleat run at
    /// h = 0.05 ms takes 0.68–0.72 wall s per simulated s with 1 thread against 0.77–0.80 with
    /// 2 (whose worker spins between products, 1.6 CPU s/s, and slows the caller's contact
    /// work), the default run 0.33–0.40 against 0.27–0.36 (BENCHMARKS.md, tire section). The
    /// full model (`symmetry = "off"`) gains from 2 threads (its products stream 2.8 MB a
    /// step from L3). On a loaded machine the products fall back to the calling thread
    /// ([`mbd_core::parallel::SplitProduct::apply`]).
    pub threads: usize,
    /// Use of the tire's mirror symmetry about its mid-plane: `auto` (default) steps the half
    /// model of symmetric motion ([`super::mirror`]: the symmetric modal coordinates, one
    /// contact unknown per mirrored node pair; the same solution as the full model at about a
    /// quarter of the work per step) when the tire and the initial state are symmetric to
    /// [`super::mirror::MIRROR_TOLERANCE`], else the full model ([`RollingTire::symmetry`](crate::RollingTire::symmetry)
    /// says which and why); `off` always steps the full model.
    pub symmetry: Symmetry,
}

/// Use of the tire's mirror symmetry ([`RollingConfig::symmetry`]).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum Symmetry {
    /// The half model when the tire and the start are mirror-symmetric, else the full model.
    #[default]
    Auto,
    /// Always the full model.
    Off,
}

impl Default for RollingConfig {
    fn default() -> Self {
        Self {
            time_step: 2e-4,
            newmark_beta: GA_DEFAULT.2,
            newmark_gamma: GA_DEFAULT.3,
            alpha_m: GA_DEFAULT.0,
            alpha_f: GA_DEFAULT.1,
            friction: 0.85,
            friction_law: TireFriction::Coulomb,
            slip_regularization: 0.05,
            contact_tolerance: 1e-10,
            normal: NormalContact::Lagrange,
            wheel_spin_inertia: 2.0,
            spin_tolerance: 1e-2,
            matrix_tolerance: 0.1,
            contact_margin: 0.0005,
            spindle_force: SpindleForceMethod::Momentum,
            threads: 1,
            symmetry: Symmetry::Auto,
        }
    }
}

/// `(α_m, α_f, β, γ)` of the default generalized-α scheme, spectral radius ρ∞ = 0.5.
///
/// Why 0.5: with the index-3 contact of the cleat test the impact leaves the patch nodes
/// bouncing on the ground unless the highest (unresolved) frequencies are damped. On the
/// default cord-reinforced truck tire at 60 km/h on the drum the patch never settles again
/// after the cleat for ρ∞ ≥ 0.75 (0.85: 2171 impacts begun within a step, 15.5 instead of 21
/// contacts per step), settles at ρ∞ = 0.7 on the drum but not on the road at 70 and 100 km/h
/// (and with the rig's impact sub-steps not on the drum either: 746 late impacts), and settles
/// at every speed 20–100 km/h on both grounds at ρ∞ = 0.5 (BENCHMARKS.md, "tire").
/// The dissipation in the resolved band is negligible: at the 76 Hz vertical line and
/// h = 0.2 ms, Ω h ≈ 0.1, where the algorithmic damping ratio is O((Ω h)³).
const GA_DEFAULT: (f64, f64, f64, f64) = {
    // Chung–Hulbert (1993) with ρ∞ = 0.5: α_m = (2ρ∞ − 1)/(ρ∞ + 1) = 0, α_f = ρ∞/(ρ∞ + 1),
    // γ = 1/2 − α_m + α_f, β = (γ + 1/2)²/4 (written out: const fns cannot use powi)
    let (am, af) = (0.0 / 1.5, 0.5 / 1.5);
    let g = 0.5 - am + af;
    (am, af, 0.25 * (g + 0.5) * (g + 0.5), g)
};

impl RollingConfig {
    /// Set the time integration to the generalized-α method of Chung and Hulbert (1993) in the
    /// form of Arnold and Brüls (2007) with spectral radius `rho_inf` ∈ \[0, 1\] at infinite
    /// frequency: `α_m = (2ρ∞ − 1)/(ρ∞ + 1)`, `α_f = ρ∞/(ρ∞ + 1)`, `γ = ½ − α_m + α_f`,
    /// `β = (γ + ½)²/4`. Second-order accurate; ρ∞ = 1 is the trapezoidal rule (Newmark
    /// β = ¼, γ = ½, no numerical damping); ρ∞ < 1 damps the highest frequencies, e.g. the
    /// period-two chatter of index-3 contact at the patch edges. The default is ρ∞ = 0.5
    /// (see `GA_DEFAULT` in the source for why).
    pub fn generalized_alpha(mut self, rho_inf: f64) -> Self {
        let am = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
        let af = rho_inf / (rho_inf + 1.0);
        let g = 0.5 - am + af;
        self.alpha_m = am;
        self.alpha_f = af;
        self.newmark_gamma = g;
        self.newmark_beta = 0.25 * (g + 0.5).powi(2);
        self
    }

    /// The coefficients `(β', γ')` of the end-of-step accelerations `z̈ₙ₊₁` in `zₙ₊₁` (times
    /// h²) and `żₙ₊₁` (times h): `β (1 − α_f)/(1 − α_m)`, `γ (1 − α_f)/(1 − α_m)`.
    pub fn implicit_coefficients(&self) -> (f64, f64) {
        let r = (1.0 - self.alpha_f) / (1.0 - self.alpha_m);
        (self.newmark_beta * r, self.newmark_gamma * r)
    }

    /// The settings of mbd-core's generalized-α stepper for the rolling tire (module
    /// documentation): these coefficients, the time step, a linearly implicit step with the
    /// frozen iteration matrix as its explicit inverse, re-factored when θ̇ drifts by more than
    /// `matrix_tolerance`.
    pub fn alpha_config(&self) -> AlphaConfig {
        AlphaConfig {
            h: self.time_step,
            coefficients: Some(AlphaCoefficients {
                alpha_m: self.alpha_m,
                alpha_f: self.alpha_f,
                beta: self.newmark_beta,
                gamma: self.newmark_gamma,
            }),
            update: NewtonUpdate::Frozen,
            linearly_implicit: true,
            zero_predictor: true,
            explicit_inverse: true,
            refactor_drift: Some(DriftTrigger {
                dof: 0,
                tolerance: self.matrix_tolerance,
            }),
            max_halvings: 0,
            ..AlphaConfig::default()
        }
    }
}

impl Validate for RollingConfig {
    /// Every field, named relative to the rolling settings (`time_step`, `normal.stiffness`):
    /// positive step, tolerances and inertia; the generalized-α coefficients within the ranges
    /// of [`AlphaCoefficients`]'s check (β ∈ (0, 1], γ ∈ \[½, 3/2\], |α| < 1); the friction
    /// coefficient within \[0, [`contact::friction::spec::MAX_FRICTION_COEFFICIENT`]\]; the
    /// friction law and the penalty stiffness.
    fn validate(&self) -> Result<(), InvalidField> {
        check::positive("time_step", self.time_step, "s")?;
        AlphaCoefficients {
            alpha_m: self.alpha_m,
            alpha_f: self.alpha_f,
            beta: self.newmark_beta,
            gamma: self.newmark_gamma,
        }
        .validate()
        .map_err(|e| {
            let field = match e.field.as_str() {
                "beta" => "newmark_beta",
                "gamma" => "newmark_gamma",
                other => other,
            };
            InvalidField::new(field, e.reason)
        })?;
        check::positive("slip_regularization", self.slip_regularization, "m/s")?;
        check::positive("contact_tolerance", self.contact_tolerance, "")?;
        check::positive("wheel_spin_inertia", self.wheel_spin_inertia, "kg·m²")?;
        check::positive("spin_tolerance", self.spin_tolerance, "")?;
        check::positive("matrix_tolerance", self.matrix_tolerance, "")?;
        check::positive("contact_margin", self.contact_margin, "m")?;
        check::count("threads", self.threads, 1, 1024)?;
        check_coefficient("friction", self.friction)?;
        if let NormalContact::Penalty { stiffness } = self.normal {
            check::positive("normal.stiffness", stiffness, "N/m")?;
        }
        if let TireFriction::Law(spec) = self.friction_law {
            spec.validate_within("friction_law")?;
        }
        Ok(())
    }
}
