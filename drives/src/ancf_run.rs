//! Runs of the ANCF belt drives: the one time loop with sampled outputs of the planar
//! (Kerkkänen ch. 3, [`ancf::belt_drive`]) and plate (ch. 4) drives ([`run_drive`]), the
//! free-belt closure on the path (example 3.3-A) and the roles of the pulleys and spans in a
//! summary.

use ancf::AncfError;
use ancf::belt_drive::{
    BeltDrive, BeltDriveSpec, ClosureResult, IntegratorKind, SimulationConfig, free_belt_closure,
};
use ancf::mounted::AncfDrive;
use belt::{HubLoad, PulleyReport, Report, Role, SpanReport, WrapPoint};
use mbd_core::SecondOrderSystem;
use mbd_core::integrators::{GeneralizedAlpha, Observer, Recorder, Rk4, State, Stats, Stepper};
use mbd_core::validate::{InvalidField, check};
use serde::Serialize;
use std::time::Instant;

/// Which pulleys play driver and driven in a summary of either ANCF drive: the first
/// speed-driven pulley (0 if none) and the first free one.
pub fn roles<D: AncfDrive>(drive: &D) -> (usize, Option<usize>) {
    let free: Vec<bool> = drive.drive_pulleys().iter().map(|p| p.is_free()).collect();
    (
        free.iter().position(|f| !f).unwrap_or(0),
        free.iter().position(|f| *f),
    )
}

/// Role of each pulley of `drive` ([`belt::Motion::role`]).
pub fn pulley_roles<D: AncfDrive>(drive: &D) -> Vec<Role> {
    drive
        .drive_pulleys()
        .iter()
        .map(|p| p.motion.role())
        .collect()
}

/// The spans running into and out of the pulley `driver` of either ANCF drive: (tight, slack)
/// indices into its spans ([`belt::BeltPath::spans`]).
pub fn tight_slack<D: AncfDrive>(drive: &D, driver: usize) -> (Option<usize>, Option<usize>) {
    let spans = drive.drive_path().spans();
    (
        spans.iter().position(|s| s.to == driver),
        spans.iter().position(|s| s.from == driver),
    )
}

/// The snapshot of the planar ANCF drive ([`ancf::belt_drive::post::snapshot`], re-exported).
pub use ancf::belt_drive::post::snapshot;

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

/// Most integration steps `t_end / integrator.h` of one run: 10⁴ times the 10⁴ steps of
/// Kerkkänen's example 3.3-B (1 s at 0.1 ms), days of computing already.
pub const MAX_STEPS: f64 = 1e8;

/// Most rows of `history.csv`, `t_end / output.history_interval` (about 2 GB of text).
pub const MAX_HISTORY_ROWS: f64 = 1e7;

/// Most VTK frames of the belt, `t_end / output.vtk_interval` (`--t-end 1e300` wrote frames
/// until it was killed, issue 20).
pub const MAX_VTK_FRAMES: f64 = 1e5;

/// The checks of a run's length and output shared by the ANCF studies, before anything runs
/// or is written ([`RunPlan`]): the integrator's options ([`SimulationConfig::validate`]),
/// `t_end` \[s\] and the output intervals \[s\] positive; the steps
/// `t_end / h`, history rows `t_end / history_interval` and VTK frames `t_end / vtk_interval`
/// within [`MAX_STEPS`], [`MAX_HISTORY_ROWS`] and [`MAX_VTK_FRAMES`] (raised by
/// `--allow-large`, [`mbd_core::validate::limits`]), each refusal naming `t_end` and the
/// interval to raise; `points_per_element` of the distributions in 1..=100.
pub fn validate_run(plan: RunPlan<'_>, points_per_element: usize) -> Result<(), InvalidField> {
    let RunPlan {
        t_end,
        integrator,
        sampling,
    } = plan;
    let (history_interval, vtk_interval) = (sampling.history, sampling.frame);
    integrator.validate().map_err(|e| match e {
        AncfError::InvalidInput { item, reason } => InvalidField::new(item, reason),
        other => InvalidField::new("integrator", other.to_string()),
    })?;
    check::positive("t_end", t_end, "s")?;
    check::positive("output.history_interval", history_interval, "s")?;
    check::positive("output.vtk_interval", vtk_interval, "s")?;
    for (field, interval, what, max) in [
        ("integrator.h", integrator.h, "steps", MAX_STEPS),
        (
            "output.history_interval",
            history_interval,
            "history rows",
            MAX_HISTORY_ROWS,
        ),
        (
            "output.vtk_interval",
            vtk_interval,
            "VTK frames",
            MAX_VTK_FRAMES,
        ),
    ] {
        let n = t_end / interval;
        let max = mbd_core::validate::limits::ceiling(max);
        if n > max {
            return Err(InvalidField::new(
                "t_end",
                format!(
                    "{} s at {field} = {} s is {n:.3e} {what}, more than the {max:e} a run may \
                     take (raise {field} or shorten t_end){}",
                    check::show(t_end),
                    check::show(interval),
                    mbd_core::validate::limits::raise_hint()
                ),
            ));
        }
    }
    if points_per_element == 0 || points_per_element > 100 {
        return Err(InvalidField::new(
            "output.points_per_element",
            "must lie in 1..=100",
        ));
    }
    Ok(())
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
    system: &S, q0: &[f64], t_end: f64, opts: &SimulationConfig, sampling: Sampling,
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

/// The end of a run as both ANCF summaries (`flowmbd-belt ancf`, `plate`) report it,
/// flattened into them.
#[derive(Debug, Clone, Serialize, Default)]
pub struct RunEnd {
    /// Driver (first speed-driven) pulley speed at the end \[rad/s\] (travel sense).
    pub omega_driver_end: f64,
    /// Driven (first free) pulley speed at the end \[rad/s\] (travel sense).
    pub omega_driven_end: f64,
    /// Tension of the span running into the driver (tight) at the end \[N\] (the planar
    /// belt's axial force; the plate's by `output.strain_measure`).
    pub tension_tight: f64,
    /// Tension of the span leaving the driver (slack) at the end \[N\] (as `tension_tight`).
    pub tension_slack: f64,
    /// Wall time of the whole study \[s\].
    pub wall_time_s: f64,
    /// End time reached \[s\].
    pub t_end: f64,
    /// Integration steps.
    pub steps: usize,
    /// Newton iterations.
    pub newton_iterations: usize,
}

impl RunEnd {
    /// The end of `run` of `drive`: the driver's and the driven pulley's speeds ([`roles`]) at
    /// its last state, the tight and slack span tensions `[tight, slack]` \[N\] (each study's
    /// own measure), the wall time since `start` and the stepper's work.
    pub fn of<D: AncfDrive>(
        drive: &D, run: &DriveRun, [tight, slack]: [f64; 2], start: Instant,
    ) -> Self {
        let (driver, driven) = roles(drive);
        let s = &run.state;
        let speed = |p: usize| drive.travel_speed(p, s.t, &s.v);
        Self {
            omega_driver_end: speed(driver),
            omega_driven_end: driven.map(speed).unwrap_or(f64::NAN),
            tension_tight: tight,
            tension_slack: slack,
            wall_time_s: start.elapsed().as_secs_f64(),
            t_end: s.t,
            steps: run.stats.steps,
            newton_iterations: run.stats.newton_iterations,
        }
    }
}

/// How a study runs either ANCF drive ([`run_reported`]): to `t_end` \[s\] with the
/// integrator's options, sampled as `sampling`.
#[derive(Debug, Clone, Copy)]
pub struct RunPlan<'a> {
    /// End time \[s\].
    pub t_end: f64,
    /// The integrator.
    pub integrator: &'a SimulationConfig,
    /// The output intervals.
    pub sampling: Sampling,
}

impl<'a> RunPlan<'a> {
    /// The plan of a study's configuration: `t_end` \[s\], the integrator, and the
    /// intervals of its history samples and VTK frames \[s\].
    pub fn new(
        t_end: f64, integrator: &'a SimulationConfig, history_interval: f64, vtk_interval: f64,
    ) -> Self {
        Self {
            t_end,
            integrator,
            sampling: Sampling {
                history: history_interval,
                frame: vtk_interval,
            },
        }
    }
}

/// The configuration of a study that runs either ANCF drive over time (`flowmbd-belt ancf`:
/// [`crate::ancf_study::AncfStudyConfig`], `plate`: [`crate::plate_study::PlateStudyConfig`]):
/// its summary and meaning, its end time and its [`RunPlan`]. Implemented by
/// `drive_study_config!`.
pub trait DriveStudyConfig {
    /// The summary of a run.
    type Summary: Serialize;
    /// What the summary's numbers mean.
    const MEANING: &'static str;
    /// The end time `t_end` \[s\] (set by `--t-end`).
    fn t_end_mut(&mut self) -> &mut f64;
    /// The run's plan: `t_end`, the integrator and the output's sampling intervals.
    fn plan(&self) -> RunPlan<'_>;
}

/// Implements [`DriveStudyConfig`] for a study configuration `$config` with the fields `t_end`,
/// `integrator` and `output.history_interval`, `output.vtk_interval`, whose summary is
/// `$summary` with the meaning `$meaning`.
macro_rules! drive_study_config {
    ($config:ty, $summary:ty, $meaning:expr) => {
        impl $crate::ancf_run::DriveStudyConfig for $config {
            type Summary = $summary;
            const MEANING: &'static str = $meaning;

            fn t_end_mut(&mut self) -> &mut f64 {
                &mut self.t_end
            }

            fn plan(&self) -> $crate::ancf_run::RunPlan<'_> {
                let o = &self.output;
                $crate::ancf_run::RunPlan::new(
                    self.t_end,
                    &self.integrator,
                    o.history_interval,
                    o.vtk_interval,
                )
            }
        }
    };
}
pub(crate) use drive_study_config;

/// The end of a study's run of either ANCF drive (`flowmbd-belt ancf`, `plate`).
#[derive(Debug, Clone)]
pub struct StudyEnd<S, H = ()> {
    /// Last state reached.
    pub state: State,
    /// The summary (wall time since the start given to the run).
    pub summary: S,
    /// Why the integration stopped early, if it did (the summary then holds the state
    /// reached).
    pub failure: Option<String>,
    /// The contact points of every wrap at the last state ([`belt::WrapPoint`]).
    pub wrap: Vec<WrapPoint>,
    /// Coefficient μ of the friction law on each pulley's wrap, travel order (for the points'
    /// utilisation).
    pub friction_coefficients: Vec<f64>,
    /// The study's own histories at the history samples (none for the planar drive).
    pub history: H,
}

impl<S, H> StudyEnd<S, H> {
    /// The end of the reported run `end` (friction coefficient `mu[k]` on pulley `k`'s wrap)
    /// with its summary and the study's histories.
    pub fn of(end: ReportedRun, summary: S, mu: Vec<f64>, history: H) -> Self {
        Self {
            state: end.run.state,
            summary,
            failure: end.run.failure,
            wrap: end.wrap,
            friction_coefficients: mu,
            history,
        }
    }
}

/// Fraction of the run at its end over which the span vibration amplitudes of the summary
/// are taken (half the peak-to-peak of the mid-point offsets at the history samples).
pub const VIBRATION_WINDOW: f64 = 0.2;

/// What a run of either ANCF drive reports of the drive at its end, computed once from the
/// model's snapshot ([`belt::Report::of`], [`AncfDrive::snapshot_at`]); flattened into the
/// summaries of `flowmbd-belt ancf` and `plate`.
#[derive(Debug, Clone, Serialize, Default)]
pub struct EndReport {
    /// Whether a wrap slides as a whole at the end ([`Report::gross_slip`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gross_slip: Option<bool>,
    /// Slip arc of the driver at the end \[rad\] ([`belt::report`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slip_arc_driver_rad: Option<f64>,
    /// Slip arc of the driven (first loaded) pulley at the end \[rad\] (none without a loaded
    /// pulley).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slip_arc_driven_rad: Option<f64>,
    /// Force of the belt on every pulley at the end.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub hub_loads: Vec<HubLoad>,
    /// Per pulley at the end: arcs, slip velocity, hub load, torque, sliding loss.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub pulleys: Vec<PulleyReport>,
    /// Per span at the end: tension, mid-point offset and its vibration amplitude over the
    /// last [`VIBRATION_WINDOW`] of the run.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub spans: Vec<SpanReport>,
}

/// A run with its end report ([`run_reported`]).
#[derive(Debug, Clone)]
pub struct ReportedRun {
    /// The run.
    pub run: DriveRun,
    /// The report at its last state.
    pub report: EndReport,
    /// The contact points of every wrap at the last state.
    pub wrap: Vec<WrapPoint>,
}

/// [`run_drive`] of either ANCF drive from rest at `q0` as `plan` says, reporting the drive
/// at the last state ([`EndReport`], friction utilisation against `mu[k]` on pulley `k`) with each span's
/// vibration amplitude, half the peak-to-peak of its mid-point offset
/// ([`AncfDrive::span_offsets`]) at the history samples of the last [`VIBRATION_WINDOW`].
/// A snapshot that cannot be taken at the end is reported as the run's failure.
pub fn run_reported<D: AncfDrive, E>(
    drive: &D, q0: &[f64], plan: RunPlan<'_>, mu: &[f64],
    mut observer: impl FnMut(&State, Due) -> Result<(), E>,
) -> Result<ReportedRun, E> {
    let RunPlan {
        t_end,
        integrator: opts,
        sampling,
    } = plan;
    let window_start = (1.0 - VIBRATION_WINDOW) * t_end;
    let n_spans = drive.drive_path().spans().len();
    let mut range = vec![(f64::INFINITY, f64::NEG_INFINITY); n_spans];
    let mut run = run_drive(drive, q0, t_end, opts, sampling, |s, due| {
        if due.history
            && s.t >= window_start
            && let Ok(offsets) = drive.span_offsets(&s.q)
        {
            for (r, x) in range.iter_mut().zip(offsets) {
                if x.is_finite() {
                    *r = (r.0.min(x), r.1.max(x));
                }
            }
        }
        observer(s, due)
    })?;
    let s = &run.state;
    let snap = match drive.snapshot_at(s.t, &s.q, &s.v) {
        Ok(snap) => snap,
        Err(e) => {
            run.failure
                .get_or_insert_with(|| format!("end report: {e}"));
            return Ok(ReportedRun {
                run,
                report: EndReport::default(),
                wrap: Vec::new(),
            });
        }
    };
    let mut report = Report::of(drive.drive_pulleys(), &snap, mu);
    for (sp, r) in report.spans.iter_mut().zip(&range) {
        if r.1 >= r.0 {
            sp.vibration_amplitude_m = Some(0.5 * (r.1 - r.0));
        }
    }
    let end = EndReport {
        gross_slip: Some(report.gross_slip().is_some()),
        // a drive without a driver or a loaded pulley (e.g. Kerkkänen's Model 1, idler driven)
        // has no such arc: the key is left out rather than NaN
        slip_arc_driver_rad: Some(report.slip_arc(Role::Driver)).filter(|a| a.is_finite()),
        slip_arc_driven_rad: Some(report.slip_arc(Role::Driven)).filter(|a| a.is_finite()),
        hub_loads: report.hub_loads(),
        pulleys: report.pulleys,
        spans: report.spans,
    };
    Ok(ReportedRun {
        run,
        report: end,
        wrap: snap.wrap,
    })
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
        let spans = drive.path().spans();
        let (tight, slack) = tight_slack(&drive, driver);
        assert_eq!(spans[tight.unwrap()].to, driver);
        assert_eq!(spans[slack.unwrap()].from, driver);
    }
}
