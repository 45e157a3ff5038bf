//! Runs of the ANCF belt drives: the one time loop with sampled outputs of the planar
//! (Kerkkänen ch. 3, [`ancf::belt_drive`]) and plate (ch. 4) drives ([`run_drive`]), the
//! free-belt closure on the path (example 3.3-A) and the roles of the pulleys and spans in a
//! summary.

use ancf::AncfError;
use ancf::belt_drive::{
    BeltDrive, BeltDriveSpec, ClosureResult, IntegratorKind, SimulationConfig, free_belt_closure,
    post,
};
use belt::Role;
use mbd_core::SecondOrderSystem;
use mbd_core::integrators::{GeneralizedAlpha, Observer, Recorder, Rk4, State, Stats, Stepper};

/// Which pulleys play driver and driven in a summary: the first speed-driven pulley (0 if
/// none) and the first free one.
pub fn roles(drive: &BeltDrive) -> (usize, Option<usize>) {
    roles_of(drive.pulleys().iter().map(|p| p.is_free()))
}

/// The roles of [`roles`] from whether each pulley (in order) is free: the first speed-driven
/// pulley (0 if none) and the first free one.
pub fn roles_of(free: impl IntoIterator<Item = bool>) -> (usize, Option<usize>) {
    let free: Vec<bool> = free.into_iter().collect();
    (
        free.iter().position(|f| !f).unwrap_or(0),
        free.iter().position(|f| *f),
    )
}

/// Role of each pulley of `drive` ([`belt::Motion::role`]).
pub fn pulley_roles(drive: &BeltDrive) -> Vec<Role> {
    drive.pulleys().iter().map(|p| p.motion.role()).collect()
}

/// The snapshot of the ANCF drive ([`post::snapshot`], re-exported).
pub use ancf::belt_drive::post::snapshot;

/// The spans running into and out of the pulley `driver`: (tight, slack) indices into `spans`.
pub fn tight_slack(spans: &[post::SpanLine], driver: usize) -> (Option<usize>, Option<usize>) {
    (
        spans.iter().position(|s| s.to == driver),
        spans.iter().position(|s| s.from == driver),
    )
}

/// Example 3.3-A: the free belt of `spec`, stress-free on the path length (Kerkkänen: 1.276 m
/// on the 1.276273 m path), closed by [`free_belt_closure`]. Returns the drive with that
/// belt length and the closure.
pub fn closure_on_path(spec: &BeltDriveSpec) -> Result<(BeltDrive, ClosureResult), AncfError> {
    let mut spec = spec.clone();
    let path = BeltDrive::new(spec.clone())?;
    spec.belt.length = path.path().length();
    let r = free_belt_closure(&spec)?;
    Ok((BeltDrive::new(spec)?, r))
}

/// Output intervals of a run \[s\].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sampling {
    /// Interval of the history samples \[s\].
    pub history: f64,
    /// Interval of the frames (e.g. VTK snapshots) \[s\].
    pub frame: f64,
}

/// What a sampled state is due for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Due {
    /// A history sample.
    pub history: bool,
    /// A frame.
    pub frame: bool,
}

/// The end of a run.
#[derive(Debug, Clone)]
pub struct DriveRun {
    /// Last state reached (generalized-α: the last sampled state; RK4: the end state, or the
    /// last history sample after a failure).
    pub state: State,
    /// Integration steps.
    pub steps: usize,
    /// Newton iterations (generalized-α).
    pub newton_iterations: usize,
    /// Why the integration stopped early, if it did.
    pub failure: Option<String>,
    /// The stepper's counters.
    pub stats: Stats,
}

/// The sink of the [`Recorder`]: forwards each sample with what it is due for and keeps the
/// last sample and the first observer error.
struct Sink<F, E> {
    observer: F,
    frame_interval: f64,
    next_frame: f64,
    last: Option<State>,
    error: Option<E>,
}

impl<F: FnMut(&State, Due) -> Result<(), E>, E> Observer for Sink<F, E> {
    fn observe(&mut self, s: &State, _stats: &Stats) {
        if self.error.is_some() {
            return;
        }
        let frame = s.t >= self.next_frame - 1e-12;
        if frame {
            self.next_frame += self.frame_interval;
        }
        if let Err(e) = (self.observer)(
            s,
            Due {
                history: true,
                frame,
            },
        ) {
            self.error = Some(e);
        }
        self.last = Some(s.clone());
    }
}

/// The one time loop of the ANCF belt drives, planar ([`BeltDrive`]) and plate
/// ([`ancf::plate::belt_drive::PlateBeltDrive`]): integrate `system` from rest at `q0` (t = 0)
/// to `t_end` \[s\] with the configured mbd-core stepper (generalized-α with the analytic
/// tangent, or RK4, [`SimulationConfig`]) driven by mbd-core's [`Recorder`], which stops the
/// stepper at every history time `k · sampling.history` (and at `t_end`). `observer` sees each
/// sampled state (every one a history sample; one every `sampling.frame` also a frame) and may
/// stop the run with an error. A failed integration is reported in [`DriveRun::failure`] with
/// the last sampled state.
pub fn run_drive<S: SecondOrderSystem, E>(
    system: &S,
    q0: &[f64],
    t_end: f64,
    opts: &SimulationConfig,
    sampling: Sampling,
    observer: impl FnMut(&State, Due) -> Result<(), E>,
) -> Result<DriveRun, E> {
    let s0 = State::new(0.0, q0.to_vec(), vec![0.0; q0.len()]);
    let mut run = DriveRun {
        state: s0.clone(),
        steps: 0,
        newton_iterations: 0,
        failure: None,
        stats: Stats::default(),
    };
    if let Err(e) = opts.validate() {
        run.failure = Some(e.to_string());
        return Ok(run);
    }
    let sink = Sink {
        observer,
        frame_interval: sampling.frame,
        next_frame: sampling.frame,
        last: None,
        error: None,
    };
    let mut rec = match Recorder::new(sink, sampling.history, sampling.history) {
        Ok(r) => r,
        Err(e) => {
            run.failure = Some(e.to_string());
            return Ok(run);
        }
    };
    let stepper: Result<Box<dyn Stepper<S>>, _> = match opts.integrator {
        IntegratorKind::GeneralizedAlpha => GeneralizedAlpha::new(opts.alpha_params())
            .stepper(system, s0.clone())
            .map(|s| Box::new(s) as Box<dyn Stepper<S>>),
        IntegratorKind::Rk4 => Rk4::new(opts.h)
            .stepper(system, s0.clone())
            .map(|s| Box::new(s) as Box<dyn Stepper<S>>),
    };
    match stepper {
        Err(e) => run.failure = Some(e.to_string()),
        Ok(mut st) => {
            // chunks of 50 samples, so that an observer error stops the run
            let chunk = 50.0 * sampling.history;
            let mut t_stop = 0.0;
            while st.state().t < t_end - 1e-12 {
                t_stop = (t_stop + chunk).min(t_end);
                if let Err(e) = rec.run(st.as_mut(), system, t_stop, &mut ()) {
                    run.failure = Some(e.to_string());
                    break;
                }
                if rec.sink.error.is_some() {
                    break;
                }
            }
            // the end time is always a sample, on the history grid or not
            let end = st.state().clone();
            let sampled = rec.sink.last.as_ref().is_some_and(|l| l.t >= end.t - 1e-12);
            if run.failure.is_none() && rec.sink.error.is_none() && !sampled && end.t > 0.0 {
                let stats = *st.stats();
                rec.sink.observe(&end, &stats);
            }
            run.stats = *st.stats();
            run.steps = run.stats.steps;
            run.newton_iterations = run.stats.newton_iterations;
        }
    }
    let mut sink = rec.sink;
    if let Some(e) = sink.error.take() {
        return Err(e);
    }
    if let Some(last) = sink.last {
        run.state = last;
    }
    Ok(run)
}

#[cfg(test)]
mod tests {
    use super::*;
    use ancf::belt_drive::InitialOptions;

    // The observer sees the history samples at the requested interval and the last one at the
    // end time; the run's step count is the stepper's (definition of the sampling).
    #[test]
    fn generalized_alpha_run_samples_every_history_interval() {
        let drive = BeltDrive::new(BeltDriveSpec::default()).unwrap();
        let init = drive.initial_state(&InitialOptions::default()).unwrap();
        let opts = SimulationConfig::default();
        let mut times = Vec::new();
        let run = run_drive(
            &drive,
            &init.q,
            0.004,
            &opts,
            Sampling {
                history: 1e-3,
                frame: 2e-3,
            },
            |s, due| -> Result<(), ()> {
                times.push((s.t, due));
                Ok(())
            },
        )
        .unwrap();
        assert!(run.failure.is_none(), "{:?}", run.failure);
        assert_eq!(times.len(), 4);
        assert!(times.iter().all(|(_, d)| d.history));
        let frames: Vec<f64> = times.iter().filter(|(_, d)| d.frame).map(|p| p.0).collect();
        assert_eq!(frames.len(), 2);
        assert!((run.state.t - 0.004).abs() < 1e-12);
        assert!(run.steps > 0 && run.newton_iterations >= run.steps);
    }

    // the roles of Table 3.1's drive: the driver is the speed-driven pulley, the tight span runs
    // into it and the slack span leaves it (definition)
    #[test]
    fn roles_pick_the_driven_pulley_and_its_spans() {
        let drive = BeltDrive::new(BeltDriveSpec::default()).unwrap();
        let (driver, driven) = roles(&drive);
        assert!(!drive.pulleys()[driver].is_free());
        assert!(drive.pulleys()[driven.unwrap()].is_free());
        let spans = post::spans(&drive);
        let (tight, slack) = tight_slack(&spans, driver);
        assert_eq!(spans[tight.unwrap()].to, driver);
        assert_eq!(spans[slack.unwrap()].from, driver);
    }
}
