//! `flowmbd-belt demo`: a rigid slider-crank whose crank is driven at constant angular speed
//! (mbd-core's rotation driver), integrated by generalized-α. The slider position is compared with
//! the closed-form kinematics `x = a cos θ + sqrt(b² − a² sin² θ)`. The model:
//! `flowmbd_cases::slider_crank`.

use flowmbd_cases::slider_crank::SliderCrank;
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, InputError, Study, StudyContext, StudyError, Validate, set_given};
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha};
use serde::{Deserialize, Serialize};

/// Command-line arguments of the demo.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: CommonArgs,
    /// End time [s] (overrides `t_end`).
    #[arg(long)]
    t_end: Option<f64>,
}

/// Demo configuration (SI units).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
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

impl Default for Config {
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

impl flowmbd_cli::PartialRules for Config {}

impl Validate for Config {
    fn validate(&self) -> Result<(), InputError> {
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
                return Err(InputError::new(
                    name,
                    format!("must be finite and > 0 (got {v})"),
                ));
            }
        }
        if self.rod_length <= self.crank_length {
            return Err(InputError::new(
                "rod_length",
                "must exceed crank_length for a full revolution",
            ));
        }
        if !(0.0..=1.0).contains(&self.rho_inf) {
            return Err(InputError::new("rho_inf", "must lie in [0, 1]"));
        }
        if !(self.omega.is_finite() && self.omega.abs() <= MAX_OMEGA) {
            return Err(InputError::new(
                "omega",
                format!(
                    "must be finite with |omega| <= {MAX_OMEGA:e} rad/s (got {})",
                    mbd_core::validate::check::show(self.omega)
                ),
            ));
        }
        if self.omega.abs() * self.step > MAX_TURN_PER_STEP {
            return Err(InputError::new(
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
            return Err(InputError::new(
                "t_end",
                format!(
                    "t_end / step = {steps:e} steps, more than the ceiling of {max:e}{}",
                    mbd_core::validate::limits::raise_hint()
                ),
            ));
        }
        if !self.theta0.is_finite() || self.theta0.sin().abs() < 1e-3 {
            return Err(InputError::new(
                "theta0",
                "must be finite and away from the dead centres 0 and π",
            ));
        }
        Ok(())
    }
}

/// Demo summary.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// Largest slider-position error against the closed form \[m\].
    pub max_slider_error_m: f64,
    /// Integration steps.
    pub steps: usize,
    /// Newton iterations.
    pub newton_iterations: usize,
    /// Wall time \[s\].
    pub wall_time_s: f64,
}

impl Config {
    fn case(&self) -> SliderCrank {
        SliderCrank {
            crank_length: self.crank_length,
            rod_length: self.rod_length,
            masses: self.masses,
            omega: self.omega,
            theta0: self.theta0,
        }
    }
}

impl Study for Args {
    type Config = Config;
    type Summary = Summary;
    const NAME: &'static str = "demo";
    const MEANING: &'static str = "A rigid slider-crank driven at constant crank speed, integrated by the shared \
         generalized-alpha stepper with its joints as index-3 constraints (mbd-core \
         demonstration). max_slider_error_m is the largest difference between the simulated \
         slider position and the closed-form position of the crank-slider kinematics, x = r \
         cos(theta) + sqrt(l^2 - r^2 sin^2(theta)) [m]: it measures the integrator and \
         constraint accuracy and should be tiny compared with the crank length. steps and \
         newton_iterations are the integrator's work.";

    fn apply_overrides(&self, c: &mut Config) {
        set_given(&mut c.t_end, self.t_end);
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let start = std::time::Instant::now();
        let case = c.case();
        let (sys, s0) = case.model().map_err(StudyError::numerical)?;
        let slider_x = SliderCrank::SLIDER_X;
        let mut csv = ctx.out.csv(
            "history.csv",
            &["t_s", "theta_rad", "slider_x_m", "closed_form_x_m"],
        )?;
        let progress = ctx.progress(c.t_end, "slider-crank");
        let mut max_err = 0.0f64;
        let (mut xs, mut refs) = (Vec::new(), Vec::new());
        let mut io_error = None;
        let alpha = GeneralizedAlpha::new(AlphaConfig {
            h: c.step,
            rho_inf: c.rho_inf,
            ..Default::default()
        });
        let sol = alpha
            .integrate(&sys, s0, c.t_end, |s| {
                let theta = case.crank_angle(s.t);
                let (x, x_ref) = (s.q[slider_x], case.closed_form(theta));
                max_err = max_err.max((x - x_ref).abs());
                xs.push((s.t, x));
                refs.push((s.t, x_ref));
                if let Err(e) = csv.row(&[s.t, theta, x, x_ref]) {
                    io_error.get_or_insert(e);
                }
                progress.set(s.t);
            })
            .map_err(StudyError::numerical)?;
        progress.finish();
        if let Some(e) = io_error {
            return Err(e.into());
        }
        csv.finish()?;
        LinePlot::new("Slider-crank: slider position", "t [s]", "x [m]")
            .with(Series::line("generalized-α", xs))
            .with(Series::line("closed form", refs))
            .save(&ctx.out.path("slider"))?;
        Ok(Summary {
            max_slider_error_m: max_err,
            steps: sol.stats.steps,
            newton_iterations: sol.stats.newton_iterations,
            wall_time_s: start.elapsed().as_secs_f64(),
        })
    }
}
