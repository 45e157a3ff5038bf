//! The ANCF belt-drive study of Kerkkänen ch. 3 (Table 3.1; examples 3.3-A closure and
//! 3.3-B dynamic run with the driver ramp (3.29)): its configuration, summary and runs, shared
//! by `flowmbd-belt ancf` (which adds the output files) and the Python package
//! (`flowmbd.belt.ancf`). The time loop is [`run_drive`]; the summary's end speeds and the
//! tight/slack span tensions follow [`roles`] and [`tight_slack`].

use crate::ancf_run::{Due, Sampling, closure_on_path, roles, run_drive, snapshot, tight_slack};
use ancf::AncfError;
use ancf::belt_drive::{
    BeltDrive, BeltDriveSpec, ClosureResult, InitialOptions, InitialState, SimulationConfig, post,
};
use belt::{HubLoad, PulleyReport, Report, Role, SpanReport, WrapPoint};
use contact::friction::FrictionLaw;
use mbd_core::integrators::State;
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// What the study computes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Analysis {
    /// Example 3.3-A: static closure of the free belt (no pulleys in the analysis; the belt
    /// length is set to the path length).
    StaticClosure,
    /// Dynamic simulation of the drive.
    Dynamic,
}

/// Output options.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct OutputConfig {
    /// Sampling interval of `history.csv` \[s\].
    pub history_interval: f64,
    /// Interval between VTK frames of the belt \[s\].
    pub vtk_interval: f64,
    /// Points per element in the VTK polyline and `tension.csv`.
    pub points_per_element: usize,
}

impl Default for OutputConfig {
    fn default() -> Self {
        Self {
            history_interval: 1e-3,
            vtk_interval: 0.02,
            points_per_element: 20,
        }
    }
}

/// Most integration steps `t_end / integrator.h` of one run: 10⁴ times the 10⁴ steps of
/// Kerkkänen's example 3.3-B (1 s at 0.1 ms), days of computing already.
pub const MAX_STEPS: f64 = 1e8;

/// Most rows of `history.csv`, `t_end / output.history_interval` (about 2 GB of text).
pub const MAX_HISTORY_ROWS: f64 = 1e7;

/// Most VTK frames of the belt, `t_end / output.vtk_interval` (`--t-end 1e300` wrote frames
/// until it was killed, issue 20).
pub const MAX_VTK_FRAMES: f64 = 1e5;

/// Configuration of the ANCF belt-drive study (the `flowmbd-belt ancf` TOML file, SI units).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AncfStudyConfig {
    /// Static closure (3.3-A) or dynamic run.
    pub analysis: Analysis,
    /// End time \[s\].
    pub t_end: f64,
    /// Reuse tolerance of the elastic tangent (see `BeltDrive::with_tangent_refresh`).
    pub tangent_refresh: f64,
    /// The drive: pulleys (travel order), belt, contact.
    pub drive: BeltDriveSpec,
    /// Integrator.
    pub integrator: SimulationConfig,
    /// Output.
    pub output: OutputConfig,
}

impl Default for AncfStudyConfig {
    /// Kerkkänen example 3.3-B: Table 3.1, 20 elements, driver ramp (3.29) to 12 rad/s.
    fn default() -> Self {
        Self {
            analysis: Analysis::Dynamic,
            t_end: 1.0,
            tangent_refresh: 0.02,
            drive: BeltDriveSpec::default(),
            integrator: SimulationConfig::default(),
            output: OutputConfig::default(),
        }
    }
}

impl mbd_core::config::PartialRules for AncfStudyConfig {}

impl Validate for AncfStudyConfig {
    fn validate(&self) -> Result<(), InvalidField> {
        let input = |e: ancf::AncfError| match e {
            ancf::AncfError::InvalidInput { item, reason } => {
                InvalidField::new(format!("drive: {item}"), reason)
            }
            other => InvalidField::new("drive", other.to_string()),
        };
        self.drive.validate().map_err(input)?;
        self.integrator.validate().map_err(|e| match e {
            ancf::AncfError::InvalidInput { item, reason } => InvalidField::new(item, reason),
            other => InvalidField::new("integrator", other.to_string()),
        })?;
        check::positive("t_end", self.t_end, "s")?;
        if !(self.tangent_refresh.is_finite() && self.tangent_refresh >= 0.0) {
            return Err(InvalidField::new("tangent_refresh", "must be ≥ 0"));
        }
        let o = &self.output;
        check::positive("output.history_interval", o.history_interval, "s")?;
        check::positive("output.vtk_interval", o.vtk_interval, "s")?;
        // sizes of the run and its output, checked before anything runs or is written
        for (field, interval, what, max) in [
            ("integrator.h", self.integrator.h, "steps", MAX_STEPS),
            (
                "output.history_interval",
                o.history_interval,
                "history rows",
                MAX_HISTORY_ROWS,
            ),
            (
                "output.vtk_interval",
                o.vtk_interval,
                "VTK frames",
                MAX_VTK_FRAMES,
            ),
        ] {
            let n = self.t_end / interval;
            let max = mbd_core::validate::limits::ceiling(max);
            if n > max {
                return Err(InvalidField::new(
                    "t_end",
                    format!(
                        "{} s at {field} = {} s is {n:.3e} {what}, more than the {max:e} a run \
                         may take (raise {field} or shorten t_end){}",
                        check::show(self.t_end),
                        check::show(interval),
                        mbd_core::validate::limits::raise_hint()
                    ),
                ));
            }
        }
        if o.points_per_element == 0 || o.points_per_element > 100 {
            return Err(InvalidField::new(
                "output.points_per_element",
                "must lie in 1..=100",
            ));
        }
        Ok(())
    }
}

/// Fraction of the run at its end over which the span vibration amplitudes of the summary
/// are taken (half the peak-to-peak of the mid-point offsets at the history samples).
pub const VIBRATION_WINDOW: f64 = 0.2;

/// Summary of a run (`summary.json` of `flowmbd-belt ancf`).
#[derive(Debug, Clone, Serialize, Default)]
pub struct AncfStudySummary {
    /// Driver pulley speed at the end \[rad/s\] (travel sense).
    pub omega_driver_end: f64,
    /// Driven (first free) pulley speed at the end \[rad/s\] (travel sense).
    pub omega_driven_end: f64,
    /// Tension of the span running into the driver at the end \[N\].
    pub tension_tight: f64,
    /// Tension of the span leaving the driver at the end \[N\].
    pub tension_slack: f64,
    /// Wall time of the whole study \[s\].
    pub wall_time_s: f64,
    /// End time reached \[s\].
    pub t_end: f64,
    /// Integration steps.
    pub steps: usize,
    /// Newton iterations.
    pub newton_iterations: usize,
    /// Pre-tension after the initial static solve (mean over the belt) \[N\].
    pub initial_tension: f64,
    /// Speed ratio driven/driver at the end (`None` while the driver is at rest).
    pub speed_ratio: Option<f64>,
    /// Dynamic run only: whether a wrap slides as a whole at the end
    /// ([`Report::gross_slip`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gross_slip: Option<bool>,
    /// Dynamic run only: slip arc of the driver at the end \[rad\] ([`belt::report`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slip_arc_driver_rad: Option<f64>,
    /// Dynamic run only: slip arc of the driven (first loaded) pulley at the end \[rad\].
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
    /// Static closure only: mean radius of the closed belt \[m\].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub closure_radius: Option<f64>,
    /// Static closure only: relative radius variation (max − min)/mean.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub closure_radius_variation: Option<f64>,
    /// What the numbers mean ([`ANCF_MEANING`]).
    pub meaning: String,
}

/// The ANCF study's "what the numbers mean" paragraph (`meaning` in the summary).
pub const ANCF_MEANING: &str = "The planar belt drive of Kerkkanen ch. 3 with ANCF beam \
elements and distributed penalty contact (3.20)-(3.25). Dynamic run (example 3.3-B): the \
driver follows the speed ramp (3.29) to its final speed; omega_driver_end and \
omega_driven_end are the pulley speeds at t_end [rad/s] (travel sense) and speed_ratio their \
ratio (below 1 by the creep of the belt on the driven pulley); tension_tight / tension_slack \
are the span tensions [N] entering / leaving the driver, their difference times the radius \
being the torque the belt carries; initial_tension is the pre-tension of the static \
initial state [N]; steps and newton_iterations the integrator's work. Static closure \
(example 3.3-A): the free belt closed into a ring, closure_radius its mean radius [m] \
(L / 2 pi for an inextensible ring) and closure_radius_variation (max - min) / mean, which \
measures how round the ANCF elements keep it (0 for a perfect circle).";

/// Example 3.3-A: the closure of the free belt ([`closure_on_path`]) and its summary
/// (wall time of the closure only).
pub fn closure_study(
    c: &AncfStudyConfig,
) -> Result<(BeltDrive, ClosureResult, AncfStudySummary), AncfError> {
    let start = Instant::now();
    let (drive, r) = closure_on_path(&c.drive)?;
    let summary = AncfStudySummary {
        wall_time_s: start.elapsed().as_secs_f64(),
        newton_iterations: r.iterations,
        closure_radius: Some(r.mean_radius),
        closure_radius_variation: Some((r.radius_range[1] - r.radius_range[0]) / r.mean_radius),
        meaning: ANCF_MEANING.to_string(),
        ..Default::default()
    };
    Ok((drive, r, summary))
}

/// The drive of a dynamic run and its pre-tensioned initial state (Kerkkänen §3.2.4).
pub fn dynamic_setup(c: &AncfStudyConfig) -> Result<(BeltDrive, InitialState), AncfError> {
    let drive = BeltDrive::new(c.drive.clone())?.with_tangent_refresh(c.tangent_refresh);
    let init = drive.initial_state(&InitialOptions::default())?;
    Ok((drive, init))
}

/// The end of a dynamic run.
#[derive(Debug, Clone)]
pub struct DynamicEnd {
    /// Last state reached.
    pub state: State,
    /// The summary (wall time since `start`).
    pub summary: AncfStudySummary,
    /// Why the integration stopped early, if it did (the summary then holds the state
    /// reached).
    pub failure: Option<String>,
    /// The contact points of every wrap at the last state ([`belt::WrapPoint`]).
    pub wrap: Vec<WrapPoint>,
    /// Coefficient μ of the friction law (for the points' utilisation).
    pub friction_coefficient: f64,
}

/// Run the drive from `init` to `c.t_end` ([`run_drive`] with the configured sampling).
/// `observer` sees every sampled state; the span tensions of the summary are those of the
/// last history sample (the initial state before the first).
pub fn dynamic_run<E>(
    c: &AncfStudyConfig,
    drive: &BeltDrive,
    init: &InitialState,
    start: Instant,
    mut observer: impl FnMut(&State, Due) -> Result<(), E>,
) -> Result<DynamicEnd, E> {
    let (driver, driven) = roles(drive);
    let (tight, slack) = tight_slack(&post::spans(drive), driver);
    let mut last_tensions = post::span_tensions(drive, &init.q);
    let n_spans = post::spans(drive).len();
    let mut range = vec![(f64::INFINITY, f64::NEG_INFINITY); n_spans];
    let window_start = (1.0 - VIBRATION_WINDOW) * c.t_end;
    let sampling = Sampling {
        history: c.output.history_interval,
        frame: c.output.vtk_interval,
    };
    let run = run_drive(
        drive,
        &init.q,
        c.t_end,
        &c.integrator,
        sampling,
        |s, due| {
            if due.history {
                last_tensions = post::span_tensions(drive, &s.q);
                if s.t >= window_start {
                    for (r, x) in range.iter_mut().zip(post::span_transverse(drive, &s.q)) {
                        if x.is_finite() {
                            *r = (r.0.min(x), r.1.max(x));
                        }
                    }
                }
            }
            observer(s, due)
        },
    )?;
    let s = &run.state;
    let w_driver = drive.pulley_speed(driver, s.t, &s.v);
    let w_driven = driven
        .map(|p| drive.pulley_speed(p, s.t, &s.v))
        .unwrap_or(f64::NAN);
    let omegas: Vec<f64> = (0..drive.pulleys().len())
        .map(|p| drive.pulley_speed(p, s.t, &s.v))
        .collect();
    let snap = snapshot(drive, s.t, &s.q, &s.v, &omegas);
    let mu = drive.spec().contact.friction.coefficient();
    let mut report = Report::of(drive.pulleys(), &snap, mu);
    for (sp, r) in report.spans.iter_mut().zip(&range) {
        if r.1 >= r.0 {
            sp.vibration_amplitude_m = Some(0.5 * (r.1 - r.0));
        }
    }
    let summary = AncfStudySummary {
        gross_slip: Some(report.gross_slip().is_some()),
        slip_arc_driver_rad: Some(report.slip_arc(Role::Driver)),
        slip_arc_driven_rad: Some(report.slip_arc(Role::Driven)),
        hub_loads: report.hub_loads(),
        pulleys: report.pulleys,
        spans: report.spans,
        omega_driver_end: w_driver,
        omega_driven_end: w_driven,
        tension_tight: tight.map(|k| last_tensions[k]).unwrap_or(f64::NAN),
        tension_slack: slack.map(|k| last_tensions[k]).unwrap_or(f64::NAN),
        wall_time_s: start.elapsed().as_secs_f64(),
        t_end: s.t,
        steps: run.steps,
        newton_iterations: run.newton_iterations,
        initial_tension: init.mean_tension,
        speed_ratio: Some(w_driven / w_driver).filter(|r| r.is_finite()),
        closure_radius: None,
        closure_radius_variation: None,
        meaning: ANCF_MEANING.to_string(),
    };
    Ok(DynamicEnd {
        state: run.state,
        summary,
        failure: run.failure,
        wrap: snap.wrap,
        friction_coefficient: mu,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    // the defaults are Kerkkänen's example 3.3-B (dynamic, 1 s) and pass validation; a bad end
    // time is named (definition of the checks)
    #[test]
    fn defaults_are_example_3_3_b_and_valid() {
        let c = AncfStudyConfig::default();
        assert_eq!(c.analysis, Analysis::Dynamic);
        assert!(c.validate().is_ok());
        let bad = AncfStudyConfig {
            t_end: -1.0,
            ..Default::default()
        };
        assert_eq!(bad.validate().unwrap_err().field, "t_end");
    }

    // issue 20: `flowmbd-belt ancf --t-end 1e300` wrote VTK frames until killed; the run's
    // size is checked first (1e300 s / 0.1 ms steps exceeds MAX_STEPS = 1e8)
    #[test]
    fn absurd_end_times_are_refused_before_running() {
        let bad = AncfStudyConfig {
            t_end: 1e300,
            ..Default::default()
        };
        let e = bad.validate().unwrap_err();
        assert_eq!(e.field, "t_end");
        assert!(
            e.reason.contains("1e300 s") && e.reason.contains("steps"),
            "{e}"
        );
        // fine steps but frames every 1 ms for 10^3 s: 10^6 frames > MAX_VTK_FRAMES
        let mut c = AncfStudyConfig {
            t_end: 1e3,
            ..Default::default()
        };
        c.output.vtk_interval = 1e-3;
        c.output.history_interval = 1.0;
        let e = c.validate().unwrap_err();
        assert!(e.reason.contains("VTK frames"), "{e}");
        // 5·10⁴ frames (half the ceiling) pass
        c.output.vtk_interval = 0.02;
        assert!(c.validate().is_ok());
    }
}
