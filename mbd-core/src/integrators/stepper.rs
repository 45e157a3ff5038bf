//! The one stepping interface shared by every time integrator, and the observer of its steps.
//!
//! A [`Stepper`] owns the state, the method's history (stages, accelerations, multipliers), its
//! workspaces and its [`Stats`]; the model is passed to every call so that one model can be
//! stepped by several steppers. Implemented by [`Rk4Stepper`](super::Rk4Stepper),
//! [`DopriStepper`](super::DopriStepper) and [`AlphaStepper`](super::AlphaStepper); the
//! `integrate` functions of [`Rk4`](super::Rk4), [`DormandPrince`](super::DormandPrince) and
//! [`GeneralizedAlpha`](super::GeneralizedAlpha) are thin loops over it.

use super::{State, Stats};
use crate::{MbdError, SecondOrderSystem};

/// Sees the state after every accepted step of [`Stepper::advance_to`] (extension point for
/// outputs; [`Recorder`](super::Recorder) samples at a fixed interval instead).
pub trait Observer {
    /// Called with the state and the run statistics after an accepted step.
    fn observe(&mut self, state: &State, stats: &Stats);

    /// Whether the run should stop after the step just observed (a cancelled run, e.g. on
    /// Ctrl-C in an app): [`Stepper::advance_to`] and [`Recorder::run`](super::Recorder::run)
    /// then return `Ok` at the state reached. The caller that asked for the stop knows the run
    /// is incomplete. Default: never.
    fn stop_requested(&self) -> bool {
        false
    }
}

/// What an observer or progress callback returns to the loop that called it: `()` (go on) or
/// [`std::ops::ControlFlow`] (`Break(())` stops the loop after the current step, keeping
/// what was computed). Lets a caller cancel a long run through the callback it already
/// passes, without any global flag: the apps' Ctrl-C handling answers `Break` once a signal
/// arrived (`flowmbd_cli::Cancel`).
pub trait Proceed {
    /// `true` to continue, `false` to stop after the current step.
    fn proceed(&self) -> bool;
}

impl Proceed for () {
    fn proceed(&self) -> bool {
        true
    }
}

impl Proceed for std::ops::ControlFlow<()> {
    fn proceed(&self) -> bool {
        self.is_continue()
    }
}

/// The no-op observer.
impl Observer for () {
    fn observe(&mut self, _state: &State, _stats: &Stats) {}
}

/// A closure `FnMut(&State) -> R` as an [`Observer`] (build it with [`observe_fn`]); `R` is
/// `()` or a [`Proceed`] answer such as `ControlFlow<()>` that can stop the run.
pub struct FnObserver<F> {
    f: F,
    stop: bool,
}

impl<F, R> Observer for FnObserver<F>
where
    F: FnMut(&State) -> R,
    R: Proceed,
{
    fn observe(&mut self, state: &State, _stats: &Stats) {
        if !(self.f)(state).proceed() {
            self.stop = true;
        }
    }

    fn stop_requested(&self) -> bool {
        self.stop
    }
}

/// Wraps a closure as an [`Observer`]: `stepper.advance_to(&sys, t, &mut observe_fn(|s| ..))`.
pub fn observe_fn<F, R>(f: F) -> FnObserver<F>
where
    F: FnMut(&State) -> R,
    R: Proceed,
{
    FnObserver { f, stop: false }
}

impl Observer for crate::History<'_> {
    fn observe(&mut self, state: &State, _stats: &Stats) {
        crate::History::observe(self, state)
    }
}

/// One time-stepping method advancing a [`SecondOrderSystem`] `S` (extension point: a new
/// integrator implements this trait and every study, app and the [`Recorder`](super::Recorder)
/// can run it).
///
/// Step-size rules: RK4 and generalized-α take the nominal step `h` and shorten the last step
/// before a stop time so that it is hit exactly; Dormand–Prince takes the step of its error
/// control (Hairer, Nørsett & Wanner II.4) and stretches or shortens the step that would end
/// within 1 % of the stop time so that it ends on it.
pub trait Stepper<S: SecondOrderSystem + ?Sized> {
    /// Current state (after the last accepted step).
    fn state(&self) -> &State;

    /// Statistics so far.
    fn stats(&self) -> &Stats;

    /// One accepted step. `h = None`: the method's own step (nominal step of the fixed-step
    /// methods, error-controlled step of Dormand–Prince); `Some(h)`: a step of exactly `h` \[s\]
    /// for the fixed-step methods, a step of at most `h` for Dormand–Prince.
    fn step(&mut self, sys: &S, h: Option<f64>) -> Result<(), MbdError>;

    /// One accepted step that does not pass `t_stop` \[s\] (the last one ends exactly on it);
    /// `Ok(false)` without a step if the state is already at `t_stop`.
    fn step_until(&mut self, sys: &S, t_stop: f64) -> Result<bool, MbdError>;

    /// Steps until the state is at `t_stop` \[s\] (hit exactly), calling `observer` after
    /// every accepted step; returns early when the observer asks to stop
    /// ([`Observer::stop_requested`]).
    fn advance_to(
        &mut self, sys: &S, t_stop: f64, observer: &mut dyn Observer,
    ) -> Result<(), MbdError> {
        while self.step_until(sys, t_stop)? {
            observer.observe(self.state(), self.stats());
            if observer.stop_requested() {
                break;
            }
        }
        Ok(())
    }

    /// Whether [`dense_output`](Stepper::dense_output) interpolates within the last step.
    fn has_dense_output(&self) -> bool {
        false
    }

    /// The state at `t` \[s\] within the last accepted step from the method's continuous
    /// extension (Dormand–Prince: the 4th-order interpolant of Hairer's `contd5`); `None` if the
    /// method has none or `t` lies outside the last step.
    fn dense_output(&self, _sys: &S, _t: f64) -> Option<State> {
        None
    }
}
