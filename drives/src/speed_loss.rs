//! The speed-loss procedure of Ribaric §6.4–6.5, for any belt-drive model.
//!
//! 1. Start from the static equilibrium of the mounted, pre-tensioned belt at rest;
//! 2. spin the driver up to `ω₁` along a smooth ramp (the driven pulley follows through the belt);
//! 3. for each load torque in turn: ramp the load on the driven pulley smoothly to the next value,
//!    then hold it until the speed loss `Δω = ω₁ − ω₂`, averaged over consecutive windows, changes
//!    by less than the tolerance between two windows (steady state, seed-000 note U14); record the
//!    last window's mean.
//!
//! The load schedule is extended while integrating, so each torque is held only as long as it
//! needs. A failure keeps the points already found ([`SweepFailure`]).

use crate::model::DriveModel;
use flowing::belt::Schedule;
use mbd_core::MbdError;
use mbd_core::integrators::{AlphaConfig, AlphaStepper, GeneralizedAlpha, State};
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};

/// Settings of the procedure (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SpeedLossConfig {
    /// Driver speed ω₁ \[rad/s\] (Ribaric Figs. 6-6, 6-7: 62.8 and 22.6).
    pub omega_driver: f64,
    /// Load torques on the driven pulley \[N m\], applied in this order.
    pub torques: Vec<f64>,
    /// Duration of the driver's spin-up ramp \[s\].
    pub spin_up: f64,
    /// Duration of each load ramp \[s\].
    pub torque_ramp: f64,
    /// Length of the averaging window \[s\].
    pub window: f64,
    /// Steady when consecutive window means differ by less than this \[rad/s\].
    pub tolerance: f64,
    /// Give up on a torque (error) after holding it this long \[s\].
    pub max_hold: f64,
    /// Generalized-α step \[s\].
    pub step: f64,
    /// Generalized-α spectral radius at infinity.
    pub rho_inf: f64,
}

impl Default for SpeedLossConfig {
    fn default() -> Self {
        Self {
            omega_driver: 62.8,
            torques: vec![0.0, 2.0, 4.0, 6.0, 8.0, 10.0],
            spin_up: 0.3,
            torque_ramp: 0.1,
            window: 0.05,
            tolerance: 2e-4,
            max_hold: 2.0,
            step: 2.5e-4,
            rho_inf: 0.6,
        }
    }
}

impl Validate for SpeedLossConfig {
    /// Every field checked; the error names the field (path relative to this struct).
    fn validate(&self) -> Result<(), InvalidField> {
        let pos = [
            ("spin_up", self.spin_up),
            ("torque_ramp", self.torque_ramp),
            ("window", self.window),
            ("tolerance", self.tolerance),
            ("max_hold", self.max_hold),
            ("step", self.step),
        ];
        for (name, v) in pos {
            if !(v.is_finite() && v > 0.0) {
                return Err(InvalidField::new(
                    name,
                    format!("must be finite and > 0 (got {v})"),
                ));
            }
        }
        if !self.omega_driver.is_finite() {
            return Err(InvalidField::new("omega_driver", "must be finite"));
        }
        if self.torques.is_empty() {
            return Err(InvalidField::new(
                "torques",
                "give at least one load torque",
            ));
        }
        if let Some(i) = self.torques.iter().position(|t| !t.is_finite()) {
            return Err(InvalidField::new(format!("torques[{i}]"), "must be finite"));
        }
        if !(0.0..=1.0).contains(&self.rho_inf) {
            return Err(InvalidField::new("rho_inf", "must lie in [0, 1]"));
        }
        if self.window < 10.0 * self.step {
            return Err(InvalidField::new("window", "must span at least 10 steps"));
        }
        Ok(())
    }
}

/// One steady operating point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SpeedLossPoint {
    /// Load torque \[N m\].
    pub torque: f64,
    /// Steady speed loss ω₁ − ω₂ \[rad/s\] (mean over the last window).
    pub delta_omega: f64,
    /// Steady driven speed \[rad/s\].
    pub omega_driven: f64,
    /// Difference of the last two window means \[rad/s\] (steady-state residual).
    pub drift: f64,
    /// Simulation time at which the point was taken \[s\].
    pub time: f64,
}

/// Integration statistics of a sweep.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct SweepStats {
    /// Simulated time \[s\].
    pub simulated_time: f64,
    /// Steps taken.
    pub steps: usize,
    /// Newton iterations.
    pub newton_iterations: usize,
    /// Force evaluations.
    pub force_evaluations: usize,
}

/// A failed sweep with the points found before the failure.
#[derive(Debug, Clone)]
pub struct SweepFailure {
    /// What failed.
    pub error: MbdError,
    /// Points already found.
    pub points: Vec<SpeedLossPoint>,
}

/// One sample of the time history handed to the observer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time \[s\].
    pub t: f64,
    /// Driver speed \[rad/s\].
    pub omega_driver: f64,
    /// Driven speed \[rad/s\].
    pub omega_driven: f64,
    /// Load torque \[N m\].
    pub load: f64,
    /// Steady points found so far.
    pub points: usize,
}

/// How often a step whose Newton iterations fail is split in two halves (recursively).
pub const MAX_HALVINGS: usize = 4;

/// One step of size `h` \[s\]; if Newton fails, two steps of `h/2` (recursively, `depth`
/// levels). The rotating-mesh model ([`flowing::belt::nodal::NodalBelt`]) needs it when a coarse
/// element lands on a pulley.
pub fn robust_step<M: DriveModel>(
    stepper: &mut AlphaStepper,
    model: &M,
    h: f64,
    depth: usize,
) -> Result<(), MbdError> {
    match stepper.step(model, h) {
        Err(MbdError::NoConvergence { .. }) if depth > 0 => {
            robust_step(stepper, model, 0.5 * h, depth - 1)?;
            robust_step(stepper, model, 0.5 * h, depth - 1)
        }
        other => other,
    }
}

/// Run the procedure on `model` (its driver and load schedules are overwritten). `observer`
/// sees every step (e.g. to write histories or update a progress bar).
pub fn speed_loss_sweep<M: DriveModel>(
    model: &mut M,
    settings: &SpeedLossConfig,
    mut observer: impl FnMut(&State, Sample),
) -> Result<(Vec<SpeedLossPoint>, SweepStats), SweepFailure> {
    let mut points = Vec::new();
    let fail = |error: MbdError, points: &Vec<SpeedLossPoint>| SweepFailure {
        error,
        points: points.clone(),
    };
    model.set_driver_speed(Schedule {
        knots: vec![(0.0, 0.0), (settings.spin_up, settings.omega_driver)],
    });
    *model.load_mut() = Schedule::constant(0.0);
    let s0 = model.initial_state().map_err(|e| fail(e, &points))?;
    let alpha = GeneralizedAlpha::new(AlphaConfig {
        h: settings.step,
        rho_inf: settings.rho_inf,
        ..Default::default()
    });
    let mut stepper: AlphaStepper = alpha.stepper(&*model, s0).map_err(|e| fail(e, &points))?;
    let h = settings.step;
    let per_window = (settings.window / h).round().max(1.0) as usize;
    let mut current = 0.0;
    // the first level starts after the spin-up
    let mut level_start = settings.spin_up;
    for &target in &settings.torques {
        if target != current {
            let t0 = level_start;
            model.load_mut().knots.push((t0, current));
            model
                .load_mut()
                .knots
                .push((t0 + settings.torque_ramp, target));
            level_start = t0 + settings.torque_ramp;
            current = target;
        }
        // step to the end of the ramp, then average windows until steady
        let mut means: Vec<f64> = Vec::new();
        let (mut sum, mut count) = (0.0, 0usize);
        loop {
            robust_step(&mut stepper, &*model, h, MAX_HALVINGS).map_err(|e| fail(e, &points))?;
            let st = stepper.state();
            let sample = Sample {
                t: st.t,
                omega_driver: model.driver_speed(st.t),
                omega_driven: model.driven_speed(&st.v),
                load: model.load_mut().value(st.t),
                points: points.len(),
            };
            observer(st, sample);
            if st.t < level_start - 0.5 * h {
                continue;
            }
            sum += sample.omega_driver - sample.omega_driven;
            count += 1;
            if count == per_window {
                means.push(sum / count as f64);
                sum = 0.0;
                count = 0;
                let k = means.len();
                if k >= 2 && (means[k - 1] - means[k - 2]).abs() < settings.tolerance {
                    let st = stepper.state();
                    points.push(SpeedLossPoint {
                        torque: target,
                        delta_omega: means[k - 1],
                        omega_driven: model.driver_speed(st.t) - means[k - 1],
                        drift: means[k - 1] - means[k - 2],
                        time: st.t,
                    });
                    level_start = st.t;
                    break;
                }
                if st.t - level_start > settings.max_hold {
                    return Err(fail(
                        MbdError::NoConvergence {
                            t: st.t,
                            iterations: k,
                            residual: (means[k - 1] - means[k - 2]).abs(),
                        },
                        &points,
                    ));
                }
            }
        }
    }
    let st = stepper.state();
    let s = &stepper.stats;
    Ok((
        points,
        SweepStats {
            simulated_time: st.t,
            steps: s.steps,
            newton_iterations: s.newton_iterations,
            force_evaluations: s.force_evaluations,
        },
    ))
}
