//! Runs of the planar ANCF belt drive (Kerkkänen ch. 3, [`ancf::belt_drive`]): the time loop
//! with sampled outputs, the free-belt closure on the path (example 3.3-A) and the roles of
//! the pulleys and spans in a summary.

use ancf::AncfError;
use ancf::belt_drive::{
    BeltDrive, BeltDriveSpec, ClosureResult, IntegratorKind, SimulationConfig, free_belt_closure,
    post, simulate,
};
use belt::{PulleyState, Role, Snapshot, SpanState, WrapPoint};
use mbd_core::integrators::{GeneralizedAlpha, State, Stepper};

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

/// The snapshot ([`belt::report`]) of the ANCF drive at `(t, q, v)` with the pulleys spinning
/// at the travel-sense speeds `omegas` \[rad/s\]: the contact quadrature points of every wrap
/// ([`post::wrap_records`]), hub loads and torques ([`BeltDrive::pulley_loads_with`]), span
/// forces ([`post::span_tensions`]) and mid-point offsets ([`post::span_transverse`]).
pub fn snapshot(drive: &BeltDrive, t: f64, q: &[f64], v: &[f64], omegas: &[f64]) -> Snapshot {
    let loads = drive.pulley_loads_with(q, v, omegas);
    let pulleys = (0..drive.pulleys().len())
        .map(|k| PulleyState {
            omega: omegas[k],
            hub_load: loads[k].force,
            torque: loads[k].torque,
            center_velocity: drive.pulley_center(k, q, v).1,
        })
        .collect();
    let wrap = post::wrap_records(drive, q, v, omegas)
        .into_iter()
        .filter(|w| w.contact.normal_force > 0.0)
        .map(|w| WrapPoint {
            pulley: w.contact.pulley,
            angle: w.angle,
            length: w.contact.weight,
            tension: w.tension,
            pressure: w.contact.normal_force,
            friction: w.contact.friction_force,
            slip: w.contact.slip,
        })
        .collect();
    let tensions = post::span_tensions(drive, q);
    let offsets = post::span_transverse(drive, q);
    let spans = post::spans(drive)
        .iter()
        .enumerate()
        .map(|(k, sp)| SpanState {
            from: sp.from,
            to: sp.to,
            tension: tensions[k],
            transverse: offsets[k],
        })
        .collect();
    Snapshot {
        time: t,
        pulleys,
        spans,
        wrap,
        belt_dissipation: None,
    }
}

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
}

/// Integrate `drive` from rest at `q0` to `t_end` \[s\] with `opts`. `observer` sees the
/// sampled states with what each is [`Due`] for and may stop the run with an error:
/// generalized-α advances ([`mbd_core::integrators::AlphaStepper::advance_to`]) one history
/// interval at a time and the observer sees the end of each interval (the last one is always a
/// history sample); RK4 ([`simulate()`]) shows it every step. A failed integration is reported in
/// [`DriveRun::failure`] with the state reached.
pub fn run_drive<E>(
    drive: &BeltDrive,
    q0: &[f64],
    t_end: f64,
    opts: &SimulationConfig,
    sampling: Sampling,
    mut observer: impl FnMut(&State, Due) -> Result<(), E>,
) -> Result<DriveRun, E> {
    let s0 = State::new(0.0, q0.to_vec(), vec![0.0; q0.len()]);
    let mut next_hist = sampling.history;
    let mut next_frame = sampling.frame;
    let mut run = DriveRun {
        state: s0.clone(),
        steps: 0,
        newton_iterations: 0,
        failure: None,
    };
    match opts.integrator {
        IntegratorKind::GeneralizedAlpha => {
            let ga = GeneralizedAlpha::new(opts.alpha_params());
            match ga.stepper(drive, s0) {
                Err(e) => run.failure = Some(e.to_string()),
                Ok(mut st) => {
                    while st.state().t < t_end - 1e-12 {
                        let t_next = (st.state().t + sampling.history).min(t_end);
                        if let Err(e) = st.advance_to(drive, t_next, &mut ()) {
                            run.failure = Some(e.to_string());
                            break;
                        }
                        let s = st.state().clone();
                        let history = s.t >= next_hist - 1e-12 || s.t >= t_end - 1e-12;
                        if history {
                            next_hist += sampling.history;
                        }
                        let frame = s.t >= next_frame - 1e-12;
                        if frame {
                            next_frame += sampling.frame;
                        }
                        observer(&s, Due { history, frame })?;
                        run.state = s;
                    }
                    run.steps = st.stats.steps;
                    run.newton_iterations = st.stats.newton_iterations;
                }
            }
        }
        IntegratorKind::Rk4 => {
            let mut stop: Option<E> = None;
            let mut last_history: Option<State> = None;
            let r = simulate(drive, q0, t_end, opts, |s| {
                let history = s.t >= next_hist - 1e-12;
                if history {
                    next_hist += sampling.history;
                    last_history = Some(s.clone());
                }
                let frame = s.t >= next_frame - 1e-12;
                if frame {
                    next_frame += sampling.frame;
                }
                if stop.is_none()
                    && let Err(e) = observer(s, Due { history, frame })
                {
                    stop = Some(e);
                }
            });
            if let Some(e) = stop {
                return Err(e);
            }
            match r {
                Ok(sol) => {
                    run.steps = sol.stats.steps;
                    run.state = sol.state;
                }
                Err(e) => {
                    if let Some(s) = last_history {
                        run.state = s;
                    }
                    run.failure = Some(e.to_string());
                }
            }
        }
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
