//! Fixed-interval sampling of a run (into a [`History`](crate::History), whose columns are
//! written as CSV, or into any [`Observer`]).

use super::{Observer, State, Stepper};
use crate::{MbdError, SecondOrderSystem};

/// Hands the states at the output times `t_k = t_first + k Δt` \[s\] to the sink `O` (a
/// [`History`](crate::History) of [`Probe`](crate::Probe)s or any [`Observer`]) while a
/// [`Stepper`] runs.
///
/// With a method that has dense output (Dormand–Prince) the stepper takes its own steps and the
/// samples are interpolated (4th order); otherwise the stepper is advanced to every sample time
/// (the fixed-step methods shorten the step before a sample time that is not on their grid).
/// Either way the recorded times are exactly `t_k`.
pub struct Recorder<O: Observer> {
    /// The sink of the samples (e.g. a [`History`](crate::History) holding the columns).
    pub sink: O,
    t_first: f64,
    dt: f64,
    next: usize,
}

impl<O: Observer> Recorder<O> {
    /// Samples into `sink` every `dt` \[s\] from `t_first` \[s\] on.
    pub fn new(sink: O, t_first: f64, dt: f64) -> Result<Self, MbdError> {
        if !(dt.is_finite() && dt > 0.0 && t_first.is_finite()) {
            return Err(MbdError::InvalidInput {
                item: "recorder output interval".into(),
                reason: format!("dt = {dt} must be positive and t_first = {t_first} finite"),
            });
        }
        Ok(Self {
            sink,
            t_first,
            dt,
            next: 0,
        })
    }

    /// The next output time \[s\].
    pub fn next_time(&self) -> f64 {
        self.t_first + self.next as f64 * self.dt
    }

    /// Runs `stepper` to `t_end` \[s\] (hit exactly), recording every output time in
    /// `[state time, t_end]` (a sample within `10⁻⁹ Δt` after `t_end` counts as `t_end`).
    /// `observer` sees every accepted step. The sample's time is `t_k` exactly.
    pub fn run<S: SecondOrderSystem + ?Sized>(
        &mut self, stepper: &mut dyn Stepper<S>, sys: &S, t_end: f64, observer: &mut dyn Observer,
    ) -> Result<(), MbdError> {
        let tol = 1e-9 * self.dt;
        // output times before the current state are skipped
        while self.next_time() < stepper.state().t - tol {
            self.next += 1;
        }
        if stepper.has_dense_output() {
            loop {
                let t_now = stepper.state().t;
                while self.next_time() <= t_now + tol && self.next_time() <= t_end + tol {
                    let tk = self.next_time();
                    if (tk - t_now).abs() <= tol {
                        self.sample(stepper.state(), tk, stepper);
                    } else {
                        let s = stepper
                            .dense_output(sys, tk)
                            .ok_or_else(|| MbdError::Model {
                                t: tk,
                                message: "no dense output at the sample time".into(),
                            })?;
                        self.sink.observe(&s, stepper.stats());
                    }
                    self.next += 1;
                }
                if self.sink.stop_requested() || !stepper.step_until(sys, t_end)? {
                    break;
                }
                observer.observe(stepper.state(), stepper.stats());
                if observer.stop_requested() {
                    break;
                }
            }
        } else {
            while self.next_time() <= t_end + tol {
                let tk = self.next_time().min(t_end);
                stepper.advance_to(sys, tk, observer)?;
                if observer.stop_requested() {
                    return Ok(());
                }
                self.sample(stepper.state(), self.next_time(), stepper);
                self.next += 1;
                if self.sink.stop_requested() {
                    return Ok(());
                }
            }
            stepper.advance_to(sys, t_end, observer)?;
        }
        Ok(())
    }

    /// Hands `state` to the sink, its time set to the output time `t` (equal up to rounding).
    fn sample<S: SecondOrderSystem + ?Sized>(
        &mut self, state: &State, t: f64, stepper: &dyn Stepper<S>,
    ) {
        if state.t == t {
            self.sink.observe(state, stepper.stats());
        } else {
            let mut s = state.clone();
            s.t = t;
            self.sink.observe(&s, stepper.stats());
        }
    }
}
