//! Time integration of a belt drive with mbd-core's integrators: implicit generalized-α with
//! the analytic Jacobian (the production path) or explicit RK4 at a fixed step (the reference
//! for the cost comparison of the benchmark).

use super::model::BeltDrive;
use crate::error::{AncfError, invalid};
use mbd_core::integrators::{AlphaParams, GeneralizedAlpha, JacobianMode, NewtonUpdate, Rk4};
use mbd_core::integrators::{Solution, State};
use serde::{Deserialize, Serialize};

/// Which integrator runs the drive.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum IntegratorKind {
    /// Implicit generalized-α (Chung–Hulbert) with the analytic tangent.
    GeneralizedAlpha,
    /// Explicit fixed-step RK4 (needs a step below the stability limit, ~1e-6 s for Table 3.1).
    Rk4,
}

/// Integration options.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SimulationOptions {
    /// Integrator.
    pub integrator: IntegratorKind,
    /// Step size [s].
    pub h: f64,
    /// Generalized-α spectral radius at infinite frequency ρ∞.
    pub rho_inf: f64,
    /// Newton tolerance on the position correction [m] (default 1e-7 m: far below the
    /// ~10⁻⁵ m contact penetrations, and loose enough that Newton does not cycle between the
    /// branches of the piecewise-linear friction law).
    pub newton_atol: f64,
    /// Maximum Newton iterations per step.
    pub max_newton_iterations: usize,
    /// Re-factor the Newton matrix every iteration (`false`: once per step, modified Newton).
    pub full_newton: bool,
}

impl Default for SimulationOptions {
    fn default() -> Self {
        Self {
            integrator: IntegratorKind::GeneralizedAlpha,
            h: 1e-4,
            rho_inf: 0.6,
            newton_atol: 1e-7,
            max_newton_iterations: 25,
            full_newton: true,
        }
    }
}

impl SimulationOptions {
    /// Check the parameters; the error names the field.
    pub fn validate(&self) -> Result<(), AncfError> {
        if !(self.h.is_finite() && self.h > 0.0) {
            return Err(invalid(
                "integrator.h",
                format!("must be > 0 s, got {}", self.h),
            ));
        }
        if !(0.0..=1.0).contains(&self.rho_inf) {
            return Err(invalid(
                "integrator.rho_inf",
                format!("must lie in [0, 1], got {}", self.rho_inf),
            ));
        }
        if !(self.newton_atol.is_finite() && self.newton_atol > 0.0) {
            return Err(invalid(
                "integrator.newton_atol",
                format!("must be > 0, got {}", self.newton_atol),
            ));
        }
        if self.max_newton_iterations == 0 {
            return Err(invalid("integrator.max_newton_iterations", "must be ≥ 1"));
        }
        Ok(())
    }

    /// The generalized-α parameters.
    pub fn alpha_params(&self) -> AlphaParams {
        AlphaParams {
            rho_inf: self.rho_inf,
            h: self.h,
            newton_atol: self.newton_atol,
            newton_rtol: 1e-8,
            max_newton_iterations: self.max_newton_iterations,
            jacobian: JacobianMode::Analytic,
            update: if self.full_newton {
                NewtonUpdate::EveryIteration
            } else {
                NewtonUpdate::EveryStep
            },
            max_halvings: 10,
            project_velocities: false,
        }
    }
}

/// Integrate `drive` from rest at `q0` (t = 0) to `t_end` [s]; `observer` sees every accepted
/// step.
pub fn simulate(
    drive: &BeltDrive,
    q0: &[f64],
    t_end: f64,
    opts: &SimulationOptions,
    observer: impl FnMut(&State),
) -> Result<Solution, AncfError> {
    opts.validate()?;
    if !(t_end.is_finite() && t_end >= 0.0) {
        return Err(invalid("t_end", format!("must be ≥ 0 s, got {t_end}")));
    }
    let state = State::new(0.0, q0.to_vec(), vec![0.0; q0.len()]);
    let sol = match opts.integrator {
        IntegratorKind::GeneralizedAlpha => {
            GeneralizedAlpha::new(opts.alpha_params()).integrate(drive, state, t_end, observer)
        }
        IntegratorKind::Rk4 => Rk4::new(opts.h).integrate(drive, state, t_end, observer),
    }?;
    Ok(sol)
}
