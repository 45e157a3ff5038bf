//! Time integrators for [`SecondOrderSystem`]s.
//!
//! * [`Rk4`]: classical fixed-step Runge–Kutta on the index-1 (acceleration-level) equations
//!   with Baumgarte stabilisation and optional projection;
//! * [`DormandPrince`]: Dormand–Prince 5(4) with error control, 4th-order dense output and
//!   event location;
//! * [`GeneralizedAlpha`]: implicit generalized-α (Chung–Hulbert parameters from ρ∞) in the
//!   index-3 form of Arnold & Brüls (2007) with scaled constraint equations, Newton iterations
//!   with analytic or finite-difference Jacobians, dense or sparse LU with symbolic reuse.
//!
//! All three are run through one [`Stepper`] interface (step, stop time, dense output,
//! statistics; outputs through an [`Observer`] or a fixed-interval [`Recorder`]); their
//! `integrate` functions are thin loops over it. All implement [`Integrator`] (a stepper
//! factory) so that applications can pick one at run time. The generalized-α stepper takes a
//! [`StepCorrection`] (nonsmooth contact impulses solved with its iteration matrix);
//! [`ActiveSetStepper`] runs it on a model with unilateral constraints by an active set.

mod accel;
mod active_set;
mod correction;
mod dopri;
mod gen_alpha;
mod recorder;
mod rk4;
mod stepper;

pub use accel::{
    Acceleration, Stabilization, accelerations, project_positions, project_velocities,
};
pub use active_set::{
    ActiveSetStep, ActiveSetStepper, ActiveSetSystem, UnilateralConstraints, UnilateralEval,
};
pub use correction::{AlphaCorrection, NoCorrection, StepCorrection};
pub use dopri::{DopriStepper, DormandPrince, Event, EventAction, EventRecord};
pub use gen_alpha::{
    AlphaCoefficients, AlphaConfig, AlphaStepper, DriftTrigger, GeneralizedAlpha, JacobianMode,
    NewtonUpdate, alpha_coefficients,
};
pub use recorder::Recorder;
pub use rk4::{Rk4, Rk4Stepper};
pub use stepper::{FnObserver, Observer, Proceed, Stepper, observe_fn};

use crate::{MbdError, SecondOrderSystem};

/// State of a second-order system at time `t`: positions `q` (length `n_q`) and velocities
/// `v` (length `n_v`).
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Time \[s\].
    pub t: f64,
    /// Positions.
    pub q: Vec<f64>,
    /// Velocities.
    pub v: Vec<f64>,
}

impl State {
    /// New state.
    pub fn new(t: f64, q: Vec<f64>, v: Vec<f64>) -> Self {
        Self { t, q, v }
    }

    /// Checks sizes against `sys` and that every entry is finite.
    pub fn check<S: SecondOrderSystem + ?Sized>(&self, sys: &S) -> Result<(), MbdError> {
        if !self.t.is_finite() {
            return Err(MbdError::NonFinite {
                what: "time".into(),
                t: self.t,
            });
        }
        if self.q.len() != sys.n_q() || self.v.len() != sys.n_v() {
            return Err(MbdError::InvalidInput {
                item: "state".into(),
                reason: format!(
                    "q has length {} (expected {}), v has length {} (expected {})",
                    self.q.len(),
                    sys.n_q(),
                    self.v.len(),
                    sys.n_v()
                ),
            });
        }
        if let Some(i) = self.q.iter().position(|x| !x.is_finite()) {
            return Err(MbdError::NonFinite {
                what: format!("position q[{i}]"),
                t: self.t,
            });
        }
        if let Some(i) = self.v.iter().position(|x| !x.is_finite()) {
            return Err(MbdError::NonFinite {
                what: format!("velocity v[{i}] ({})", sys.dof_name(i)),
                t: self.t,
            });
        }
        sys.check_state(self.t, &self.q, &self.v)
    }
}

/// Run statistics every integrator reports.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct Stats {
    /// Accepted steps.
    pub steps: usize,
    /// Rejected steps (error control or Newton failure).
    pub rejected_steps: usize,
    /// Newton iterations (implicit integrator, projections).
    pub newton_iterations: usize,
    /// Calls of [`SecondOrderSystem::forces`] (finite differences included).
    pub force_evaluations: usize,
    /// Evaluations of the Newton (tangent) matrix.
    pub jacobian_evaluations: usize,
    /// Numeric factorisations of the augmented or Newton matrix.
    pub factorizations: usize,
    /// Of [`Stats::factorizations`], those done by the banded-plus-border LU
    /// ([`crate::linalg::KktSolver::banded`], generalized-α with [`AlphaConfig::banded_lu`]); the
    /// others went to faer's sparse LU (a zero band pivot, or every band plan rejected by the
    /// backward-error check).
    pub banded_factorizations: usize,
    /// Banded factorisations discarded by the backward-error check
    /// ([`crate::linalg::BAND_BACKWARD_ERROR_LIMIT`]): each moves the pattern to its next band
    /// plan or to faer's sparse LU for good.
    pub banded_rejections: usize,
    /// Of [`Stats::banded_factorizations`], those accepted after their backward error was
    /// measured by a test solve; the others grew at most twice as much as a measured one
    /// ([`crate::linalg::KktSolver::banded_checks`]).
    pub banded_checks: usize,
    /// Located events.
    pub events: usize,
    /// Steps (attempts included) whose Newton iteration started from the model's own
    /// prediction ([`crate::SecondOrderSystem::predict_increment`], generalized-α with
    /// [`AlphaConfig::model_predictor`]) because its residual was the smaller.
    pub model_predictions: usize,
    /// Steps halved after a Newton failure (generalized-α: [`AlphaConfig::max_halvings`],
    /// [`AlphaConfig::subdivisions`]); each also counts as a rejected step.
    pub halvings: usize,
}

impl Stats {
    /// Adds the counters of `o` to `self`.
    pub fn accumulate(&mut self, o: &Stats) {
        self.steps += o.steps;
        self.rejected_steps += o.rejected_steps;
        self.newton_iterations += o.newton_iterations;
        self.force_evaluations += o.force_evaluations;
        self.jacobian_evaluations += o.jacobian_evaluations;
        self.factorizations += o.factorizations;
        self.banded_factorizations += o.banded_factorizations;
        self.banded_rejections += o.banded_rejections;
        self.banded_checks += o.banded_checks;
        self.events += o.events;
        self.halvings += o.halvings;
        self.model_predictions += o.model_predictions;
    }
}

/// Result of an integration run.
#[derive(Debug, Clone)]
pub struct Solution {
    /// Final state (at `t_end`, or at the event that stopped the run).
    pub state: State,
    /// Run statistics.
    pub stats: Stats,
    /// Events located during the run (Dormand–Prince only).
    pub events: Vec<EventRecord>,
}

/// A time integrator (extension point: the user picks the integrator at run time).
pub trait Integrator {
    /// Integrates `sys` from `state0` to `t_end` \[s\], calling `observer` with the initial state
    /// and after every accepted step.
    fn integrate_dyn(
        &mut self, sys: &dyn SecondOrderSystem, state0: State, t_end: f64,
        observer: &mut dyn FnMut(&State),
    ) -> Result<Solution, MbdError>;

    /// A [`Stepper`] of this method started at `state0` (the stepper factory: run it with
    /// [`Stepper::advance_to`] or a [`Recorder`]).
    fn stepper_dyn<'a>(
        &self, sys: &(dyn SecondOrderSystem + 'a), state0: State,
    ) -> Result<Box<dyn Stepper<dyn SecondOrderSystem + 'a>>, MbdError>;
}

/// Runs `stepper` to `t_end` \[s\], `observer` seeing the initial state and every accepted
/// step: the `integrate` function of the fixed-step methods.
///
/// The observer may return `()` or a [`Proceed`] answer: `ControlFlow::Break(())` ends the
/// run after that step with `Ok` and the state reached (a cancelled run; the caller knows).
pub(crate) fn integrate_stepper<S: SecondOrderSystem + ?Sized, St: Stepper<S>, R: Proceed>(
    mut stepper: St, sys: &S, t_end: f64, mut observer: impl FnMut(&State) -> R,
) -> Result<Solution, MbdError> {
    if observer(stepper.state()).proceed() {
        stepper.advance_to(sys, t_end, &mut observe_fn(observer))?;
    }
    Ok(Solution {
        state: stepper.state().clone(),
        stats: *stepper.stats(),
        events: Vec::new(),
    })
}

/// [`Integrator`] for a method with inherent `integrate` and `stepper` functions generic over
/// the system (one definition for [`Rk4`], [`DormandPrince`] and [`GeneralizedAlpha`]).
macro_rules! impl_integrator {
    ($method:ty) => {
        impl $crate::integrators::Integrator for $method {
            fn integrate_dyn(
                &mut self, sys: &dyn $crate::SecondOrderSystem, state0: $crate::integrators::State,
                t_end: f64, observer: &mut dyn FnMut(&$crate::integrators::State),
            ) -> Result<$crate::integrators::Solution, $crate::MbdError> {
                self.integrate(sys, state0, t_end, observer)
            }

            fn stepper_dyn<'a>(
                &self, sys: &(dyn $crate::SecondOrderSystem + 'a),
                state0: $crate::integrators::State,
            ) -> Result<
                Box<dyn $crate::integrators::Stepper<dyn $crate::SecondOrderSystem + 'a>>,
                $crate::MbdError,
            > {
                Ok(Box::new(self.stepper(sys, state0)?))
            }
        }
    };
}
pub(crate) use impl_integrator;

pub(crate) fn check_step(h: f64, what: &str) -> Result<(), MbdError> {
    if !(h.is_finite() && h > 0.0) {
        return Err(MbdError::InvalidInput {
            item: what.into(),
            reason: format!("step size must be positive and finite, got {h}"),
        });
    }
    Ok(())
}

/// Names the redundant constraints of `sys` at `(t, q)` if its Jacobian is rank deficient.
pub(crate) fn explain_singular<S: SecondOrderSystem + ?Sized>(
    sys: &S, t: f64, q: &[f64], err: MbdError,
) -> MbdError {
    if let MbdError::Singular { .. } = err
        && sys.n_c() > 0
        && let Ok(d) = sys.constraint_jacobian(t, q)
    {
        let dep = crate::linalg::dependent_rows(&d, 1e-9);
        if !dep.is_empty() {
            let names: Vec<String> = dep.iter().map(|&r| sys.constraint_name(r)).collect();
            return MbdError::Singular {
                t,
                detail: format!(
                    "redundant constraints (Jacobian rows linearly dependent): {}",
                    names.join(", ")
                ),
            };
        }
    }
    err
}
