//! The slider-crank demonstration (`flowmbd-belt demo`, `flowmbd.belt.demo`): the rigid
//! [`SliderCrank`] driven at constant crank speed (mbd-core's rotation driver), integrated by
//! the shared generalized-α stepper with its joints as index-3 constraints, and its slider
//! position compared with the closed-form kinematics `x = a cos θ + √(b² − a² sin² θ)`.
//! Configuration, checks and the run live here so that the CLI and the Python package return
//! the same numbers.

use crate::slider_crank::SliderCrank;
use mbd_core::MbdError;
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha};
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};

/// Configuration of the demo (`flowmbd-belt demo`; SI units).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct DemoConfig {
    /// Crank length a \[m\].
    pub crank_length: f64,
    /// Connecting-rod length b \[m\].
    pub rod_length: f64,
    /// Crank, rod and slider masses \[kg\].
    pub masses: [f64; 3],
    /// Crank speed \[rad/s\].
    pub omega: f64,
    /// Initial crank angle \[rad\] (away from the dead centres 0 and π, where the joint Jacobian is singular).
    pub theta0: f64,
    /// End time \[s\].
    pub t_end: f64,
    /// Time step \[s\].
    pub step: f64,
    /// Generalized-α spectral radius at infinity \[-\].
    pub rho_inf: f64,
}

impl Default for DemoConfig {
    fn default() -> Self {
        Self {
            crank_length: 0.1,
            rod_length: 0.3,
            masses: [1.0, 2.0, 3.0],
            omega: 2.0 * std::f64::consts::PI,
            theta0: 0.3,
            t_end: 2.0,
            step: 1e-3,
            rho_inf: 0.8,
        }
    }
}

/// Most generalized-α steps of a demo run (`t_end / step`; the default run takes 2 000): a
/// documented ceiling, raised 1000-fold by `--allow-large`
/// ([`mbd_core::validate::limits`]), checked before anything runs (issue 35).
pub const MAX_DEMO_STEPS: f64 = 1e6;

/// Fastest crank \[rad/s\] (about 95 000 rpm; the default 2π rad/s).
pub const MAX_OMEGA: f64 = 1e4;

/// Largest crank turn per step \[rad\]: `|omega|·step` above it leaves the crank's motion
/// unresolved (the step's Newton iteration fails or the answer is meaningless).
pub const MAX_TURN_PER_STEP: f64 = 0.5;

impl mbd_core::config::PartialRules for DemoConfig {}

impl Validate for DemoConfig {
    fn validate(&self) -> Result<(), InvalidField> {
        let positive = [
            ("crank_length", self.crank_length),
            ("rod_length", self.rod_length),
            ("masses[0]", self.masses[0]),
            ("masses[1]", self.masses[1]),
            ("masses[2]", self.masses[2]),
            ("t_end", self.t_end),
            ("step", self.step),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(InvalidField::new(
                    name,
                    format!("must be finite and > 0 (got {v})"),
                ));
            }
        }
        if self.rod_length <= self.crank_length {
            return Err(InvalidField::new(
                "rod_length",
                "must exceed crank_length for a full revolution",
            ));
        }
        if !(0.0..=1.0).contains(&self.rho_inf) {
            return Err(InvalidField::new("rho_inf", "must lie in [0, 1]"));
        }
        if !(self.omega.is_finite() && self.omega.abs() <= MAX_OMEGA) {
            return Err(InvalidField::new(
                "omega",
                format!(
                    "must be finite with |omega| <= {MAX_OMEGA:e} rad/s (got {})",
                    mbd_core::validate::check::show(self.omega)
                ),
            ));
        }
        if self.omega.abs() * self.step > MAX_TURN_PER_STEP {
            return Err(InvalidField::new(
                "step",
                format!(
                    "the crank turns |omega|·step = {:e} rad per step, more than \
                     {MAX_TURN_PER_STEP} rad: take a smaller step",
                    self.omega.abs() * self.step
                ),
            ));
        }
        let steps = self.t_end / self.step;
        let max = mbd_core::validate::limits::ceiling(MAX_DEMO_STEPS);
        if steps > max {
            return Err(InvalidField::new(
                "t_end",
                format!(
                    "t_end / step = {steps:e} steps, more than the ceiling of {max:e}{}",
                    mbd_core::validate::limits::raise_hint()
                ),
            ));
        }
        if !self.theta0.is_finite() || self.theta0.sin().abs() < 1e-3 {
            return Err(InvalidField::new(
                "theta0",
                "must be finite and away from the dead centres 0 and π",
            ));
        }
        Ok(())
    }
}

/// Summary of the demo (`summary.json` of `flowmbd-belt demo`).
#[derive(Debug, Clone, Serialize)]
pub struct DemoSummary {
    /// Largest slider-position error against the closed form \[m\].
    pub max_slider_error_m: f64,
    /// Integration steps.
    pub steps: usize,
    /// Newton iterations.
    pub newton_iterations: usize,
    /// Wall time \[s\].
    pub wall_time_s: f64,
    /// What the numbers mean ([`DEMO_MEANING`]).
    pub meaning: String,
}

impl DemoConfig {
    /// The slider-crank of this configuration.
    pub fn case(&self) -> SliderCrank {
        SliderCrank {
            crank_length: self.crank_length,
            rod_length: self.rod_length,
            masses: self.masses,
            omega: self.omega,
            theta0: self.theta0,
        }
    }
}

/// What the summary's keys mean (the CLI's `meaning`).
pub const DEMO_MEANING: &str = "A rigid slider-crank driven at constant crank speed, integrated by the shared \
         generalized-alpha stepper with its joints as index-3 constraints (mbd-core \
         demonstration). max_slider_error_m is the largest difference between the simulated \
         slider position and the closed-form position of the crank-slider kinematics, x = r \
         cos(theta) + sqrt(l^2 - r^2 sin^2(theta)) [m]: it measures the integrator and \
         constraint accuracy and should be tiny compared with the crank length. steps and \
         newton_iterations are the integrator's work.";

/// Columns of `history.csv`: time \[s\], crank angle \[rad\], slider position and its closed
/// form \[m\].
pub const DEMO_HISTORY_HEADER: [&str; 4] = ["t_s", "theta_rad", "slider_x_m", "closed_form_x_m"];

/// Run the demo: generalized-α with `c.step` and `c.rho_inf` to `c.t_end`; `observer` sees the
/// history row ([`DEMO_HISTORY_HEADER`]) of every step.
pub fn slider_crank_demo(
    c: &DemoConfig, observer: &mut dyn FnMut(&[f64; 4]),
) -> Result<DemoSummary, MbdError> {
    let start = std::time::Instant::now();
    let case = c.case();
    let (sys, s0) = case.model()?;
    let mut max_err = 0.0f64;
    let alpha = GeneralizedAlpha::new(AlphaConfig {
        h: c.step,
        rho_inf: c.rho_inf,
        ..Default::default()
    });
    let sol = alpha.integrate(&sys, s0, c.t_end, |s| {
        let theta = case.crank_angle(s.t);
        let (x, x_ref) = (s.q[SliderCrank::SLIDER_X], case.closed_form(theta));
        max_err = max_err.max((x - x_ref).abs());
        observer(&[s.t, theta, x, x_ref]);
    })?;
    Ok(DemoSummary {
        max_slider_error_m: max_err,
        steps: sol.stats.steps,
        newton_iterations: sol.stats.newton_iterations,
        wall_time_s: start.elapsed().as_secs_f64(),
        meaning: DEMO_MEANING.to_string(),
    })
}
