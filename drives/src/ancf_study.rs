//! The ANCF belt-drive study of Kerkkänen ch. 3 (Table 3.1; examples 3.3-A closure and
//! 3.3-B dynamic run with the driver ramp (3.29)): its configuration, summary and runs, shared
//! by `flowmbd-belt ancf` (which adds the output files) and the Python package
//! (`flowmbd.belt.ancf`). The time loop is [`run_reported`], shared with the plate belt; the
//! summary's end speeds and the tight/slack span tensions follow [`roles`] and
//! [`tight_slack`].

use crate::ancf_run::{
    DriveStudyConfig, Due, EndReport, RunEnd, StudyEnd, closure_on_path, roles, run_reported,
    tight_slack, validate_run,
};
use ancf::AncfError;
use ancf::belt_drive::{
    BeltDrive, BeltDriveSpec, ClosureResult, InitialOptions, InitialState, SimulationConfig, post,
};
use contact::friction::FrictionLaw;
use mbd_core::integrators::State;
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// What the study computes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Analysis {
    /// Example 3.3-A: static closure of the free belt (no pulleys in the analysis; the belt
    /// length is set to the path length).
    StaticClosure,
    /// Dynamic simulation of the drive.
    Dynamic,
}

/// Output options.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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

pub use crate::ancf_run::{MAX_HISTORY_ROWS, MAX_STEPS, MAX_VTK_FRAMES};

/// Configuration of the ANCF belt-drive study (the `flowmbd-belt ancf` TOML file, SI units).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct AncfStudyConfig {
    /// Static closure (3.3-A) or dynamic run.
    pub analysis: Analysis,
    /// End time \[s\].
    pub t_end: f64,
    /// Reuse tolerance of the elastic tangent \[-\] (see `BeltDrive::with_tangent_refresh`).
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

crate::ancf_run::drive_study_config!(AncfStudyConfig, AncfStudySummary, ANCF_MEANING);

impl Validate for AncfStudyConfig {
    fn validate(&self) -> Result<(), InvalidField> {
        let input = |e: ancf::AncfError| match e {
            ancf::AncfError::InvalidInput { item, reason } => {
                InvalidField::new(format!("drive: {item}"), reason)
            }
            other => InvalidField::new("drive", other.to_string()),
        };
        self.drive.validate().map_err(input)?;
        if !(self.tangent_refresh.is_finite() && self.tangent_refresh >= 0.0) {
            return Err(InvalidField::new("tangent_refresh", "must be ≥ 0"));
        }
        validate_run(self.plan(), self.output.points_per_element)
    }
}

pub use crate::ancf_run::VIBRATION_WINDOW;

/// Summary of a run (`summary.json` of `flowmbd-belt ancf`).
#[derive(Debug, Clone, Serialize, Default)]
pub struct AncfStudySummary {
    /// End speeds, span tensions, time and work ([`RunEnd`]).
    #[serde(flatten)]
    pub run: RunEnd,
    /// Pre-tension after the initial static solve (mean over the belt) \[N\].
    pub initial_tension: f64,
    /// Speed ratio driven/driver at the end (`None` while the driver is at rest).
    pub speed_ratio: Option<f64>,
    /// Dynamic run only: the drive at the end ([`EndReport`]: gross slip, slip arcs, hub
    /// loads, pulleys, spans with their vibration amplitudes over the last
    /// [`VIBRATION_WINDOW`] of the run).
    #[serde(flatten)]
    pub report: EndReport,
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
        run: RunEnd {
            wall_time_s: start.elapsed().as_secs_f64(),
            newton_iterations: r.iterations,
            ..Default::default()
        },
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

/// The end of a dynamic run ([`StudyEnd`]: the state reached, the summary, the failure that
/// stopped it early if one did, the wrap points at the end and the friction coefficient).
pub type DynamicEnd = StudyEnd<AncfStudySummary>;

/// Run the drive from `init` to `c.t_end` ([`run_reported`] with the configured sampling; its
/// end report in the summary).
/// `observer` sees every sampled state; the span tensions of the summary are those of the
/// last history sample (the initial state before the first).
pub fn dynamic_run<E>(
    c: &AncfStudyConfig, drive: &BeltDrive, init: &InitialState, start: Instant,
    mut observer: impl FnMut(&State, Due) -> Result<(), E>,
) -> Result<DynamicEnd, E> {
    let (driver, _) = roles(drive);
    let (tight, slack) = tight_slack(drive, driver);
    let mut last_tensions = post::span_tensions(drive, &init.q);
    let mu: Vec<f64> = (0..drive.spec().pulleys.len())
        .map(|p| drive.friction_law(p).coefficient())
        .collect();
    let mut end = run_reported(drive, &init.q, c.plan(), &mu, |s, due| {
        if due.history {
            last_tensions = post::span_tensions(drive, &s.q);
        }
        observer(s, due)
    })?;
    let pick = |k: Option<usize>| k.map(|k| last_tensions[k]).unwrap_or(f64::NAN);
    let run = RunEnd::of(drive, &end.run, [pick(tight), pick(slack)], start);
    let summary = AncfStudySummary {
        report: std::mem::take(&mut end.report),
        speed_ratio: Some(run.omega_driven_end / run.omega_driver_end).filter(|r| r.is_finite()),
        run,
        initial_tension: init.mean_tension,
        closure_radius: None,
        closure_radius_variation: None,
        meaning: ANCF_MEANING.to_string(),
    };
    Ok(StudyEnd::of(end, summary, mu, ()))
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
