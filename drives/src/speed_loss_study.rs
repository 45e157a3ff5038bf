//! The speed-loss study's configuration and summary (Ribaric §6.4–6.5, Figs. 6-6 and 6-7):
//! what `flowmbd-belt speed-loss` reads from its TOML file and writes to `summary.json`, shared
//! with the Python package (`flowmbd.belt.speed_loss`) so that both accept the same keys, reject
//! the same fields with the same messages and report the same numbers. Each case is the
//! procedure of [`crate::speed_loss`] run by [`run_case`], with
//! Bechtel's line (6.3) at the same torques.

use crate::ancf_model::AncfMapping;
use crate::error::DriveError;
use crate::speed_loss::{GrossSlip, SpeedLossConfig, SpeedLossPoint, SweepStats};
use crate::speed_loss::{Sample, SweepFailure};
use crate::study::{
    AnyModel, ModelKind, ModelSettings, SpeedLossCase, procedure_for, speed_loss_case,
};
use belt::{Balances, HubLoad, Layout, PulleyReport, Role, SpanReport};
use mbd_core::integrators::State;
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// Configuration of the speed-loss study (the `flowmbd-belt speed-loss` TOML file).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct SpeedLossStudyConfig {
    /// Belt model.
    pub model: ModelKind,
    /// Driver speeds \[rad/s\] (Figs. 6-6 and 6-7: 62.8 and 22.6).
    pub omegas: Vec<f64>,
    /// The drive (default: Ribaric Table 6-1, [`crate::table_6_1`]): the driver is its first
    /// speed-driven pulley, the loaded pulley its first free one.
    pub drive: Layout,
    /// The procedure (torques, ramps, steady-state detection, integrator). Its `omega_driver`
    /// is replaced by each entry of `omegas`.
    pub procedure: SpeedLossConfig,
    /// Write every n-th integration step to the history CSV files.
    pub history_every: usize,
    /// Each model's discretisation (`flowing`, `nodal`, `ancf` tables; the nodal model's
    /// window and tolerance and the ANCF belt's step replace the procedure's).
    pub models: ModelSettings,
}

impl Default for SpeedLossStudyConfig {
    fn default() -> Self {
        Self {
            model: ModelKind::Flowing,
            omegas: vec![62.8, 22.6],
            drive: crate::table_6_1::layout(),
            procedure: SpeedLossConfig::default(),
            history_every: 20,
            models: ModelSettings::default(),
        }
    }
}

// the layout's merge rules (`tension` / `belt_length`, `pulleys` / `tensioner`)
impl mbd_core::config::PartialRules for SpeedLossStudyConfig {
    const DROPPED_BY: &'static [(&'static str, &'static str)] = belt::PARTIAL_RULES;
}

impl Validate for SpeedLossStudyConfig {
    fn validate(&self) -> Result<(), InvalidField> {
        if self.omegas.is_empty() {
            return Err(InvalidField::new(
                "omegas",
                "give at least one driver speed",
            ));
        }
        if let Some(i) = self
            .omegas
            .iter()
            .position(|w| !(w.is_finite() && *w > 0.0))
        {
            return Err(InvalidField::new(
                format!("omegas[{i}]"),
                "must be finite and > 0 [rad/s]",
            ));
        }
        check::count("omegas", self.omegas.len(), 1, 100)?;
        check::count("history_every", self.history_every, 1, usize::MAX)?;
        let drive = self.drive.resolve().map_err(|e| e.within("drive"))?;
        if drive.driver().is_none() {
            return Err(InvalidField::new(
                "drive.pulleys",
                "the speed-loss procedure needs a speed-driven pulley (the driver)",
            ));
        }
        if drive.driven().is_none() {
            return Err(InvalidField::new(
                "drive.pulleys",
                "the speed-loss procedure needs a free pulley to load",
            ));
        }
        // the belt speed ω R of the driver below the critical speed c = √(T0/ρA) of the
        // mounted belt, where the spans lose their transverse stiffness (T0 − ρAv² = 0) and
        // the travelling-string models have no steady state (Wickert and Mote; issue 35:
        // `--omega 1e300` ran and failed writing a file named by the speed)
        if let Some(k) = drive.driver() {
            let r = drive.pulleys()[k].radius;
            let c = drive.belt().wave_speed(drive.tension());
            if let Some(i) = self.omegas.iter().position(|w| w * r >= c) {
                return Err(InvalidField::new(
                    format!("omegas[{i}]"),
                    format!(
                        "{} rad/s drives the belt at {} m/s on the driver (radius {r} m), at or \
                         above the critical speed c = √(T0/ρA) = {c:.4} m/s of the mounted belt, \
                         where the spans lose their transverse stiffness",
                        check::show(self.omegas[i]),
                        check::show(self.omegas[i] * r)
                    ),
                ));
            }
        }
        self.models.validate_within("models")?;
        match self.model {
            ModelKind::Flowing => self
                .models
                .flowing
                .mesh
                .check_on(drive.path())
                .map_err(|e| e.within("models.flowing.mesh"))?,
            ModelKind::Nodal => self
                .models
                .nodal
                .mesh
                .check_on(drive.path())
                .map_err(|e| e.within("models.nodal.mesh"))?,
            ModelKind::Ancf => {}
        }
        self.procedure.validate_within("procedure")?;
        procedure_for(self.model, &self.procedure, &self.models).validate_within(&format!(
            "procedure (with models.{} settings)",
            self.model.name()
        ))
    }
}

/// The input error hidden in a model-building failure: a model's rejection of its derived
/// inputs (named by the model's item); `None` for a numerical failure.
pub fn drive_input_error(e: &DriveError) -> Option<InvalidField> {
    match e {
        DriveError::Ancf(ancf::AncfError::InvalidInput { item, reason }) => {
            Some(InvalidField::new(format!("ancf: {item}"), reason.clone()))
        }
        DriveError::Flowing(flowing::FlowError::InvalidInput { item, reason }) => {
            Some(InvalidField::new(item.clone(), reason.clone()))
        }
        DriveError::Invalid(m) => Some(InvalidField::new("drive", m.clone())),
        _ => None,
    }
}

/// Why one driver speed of the study did not complete.
#[derive(Debug)]
pub enum CaseFailure {
    /// The input was rejected (names the field).
    Input(InvalidField),
    /// The model could not be built (a numerical failure of its static solve).
    Build(DriveError),
    /// The procedure failed, with the points found before.
    Sweep(SweepFailure),
}

/// One driver speed of the study `c` (validated first): the model `c.model` of `c.drive` with
/// its settings, the procedure at `omega` \[rad/s\] ([`procedure_for`]). Returns the case, the
/// number of coordinates and the ANCF mapping (ANCF model only). `observer` sees every step.
pub fn run_case(
    c: &SpeedLossStudyConfig, omega: f64, observer: impl FnMut(&State, Sample),
) -> Result<(SpeedLossCase, usize, Option<AncfMapping>), CaseFailure> {
    c.validate().map_err(CaseFailure::Input)?;
    let drive = c
        .drive
        .resolve()
        .map_err(|e| CaseFailure::Input(e.within("drive")))?;
    let mut model =
        AnyModel::new(c.model, &drive, &c.models).map_err(|e| match drive_input_error(&e) {
            Some(field) => CaseFailure::Input(field),
            None => CaseFailure::Build(e),
        })?;
    let mut settings = procedure_for(c.model, &c.procedure, &c.models);
    settings.omega_driver = omega;
    let case = speed_loss_case(&mut model, &settings, observer).map_err(CaseFailure::Sweep)?;
    Ok((case, model.coordinates(), model.ancf_mapping().cloned()))
}

/// One point of the summary: the issue-17 keys per load torque. Where the results of a model
/// linearised about T0 do not hold ([`SummaryPoint::linearisation`]), the numbers are `null`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SummaryPoint {
    /// Load torque \[N m\].
    pub torque: f64,
    /// Steady speed loss ω₁ − ω₂ \[rad/s\] (`null` after a runaway gross slip or where the
    /// linearisation does not hold).
    pub delta_omega: Option<f64>,
    /// Tension of the tight span (running onto the driver) \[N\].
    pub tension_tight: Option<f64>,
    /// Tension of the slack span (leaving the driver) \[N\].
    pub tension_slack: Option<f64>,
    /// Whether the load exceeded what friction can transmit ([`GrossSlip`]).
    pub gross_slip: bool,
    /// Where and when it slipped.
    pub gross_slip_at: Option<GrossSlip>,
    /// Slip arc of the driver (saturated friction, [`belt::report`]) \[rad\].
    pub slip_arc_driver_rad: Option<f64>,
    /// Slip arc of the driven pulley \[rad\].
    pub slip_arc_driven_rad: Option<f64>,
    /// Force of the belt on every pulley.
    pub hub_loads: Option<Vec<HubLoad>>,
    /// Whether the model's results hold at this point (always for the ANCF belt; for the
    /// flowing and nodal belts, linearised about T0, while the spans stay taut and no wrap
    /// slides as a whole).
    pub linearisation_valid: bool,
    /// Why they do not.
    pub linearisation: Option<String>,
    /// Why the speed loss may understate the creep (a flowing belt with Ribaric's contact rates
    /// under a friction law sharper than the creep: [`crate::speed_loss::creep_caveat`]); the
    /// numbers are still given.
    pub caveat: Option<String>,
    /// What the balances say when they miss 0.5 % ([`crate::speed_loss::balance_note`]); the
    /// numbers are still given.
    pub balance: Option<String>,
    /// Per pulley: arcs, slip velocity, hub load, torque, sliding loss.
    pub pulleys: Option<Vec<PulleyReport>>,
    /// Per span: force and transverse vibration amplitude.
    pub spans: Option<Vec<SpanReport>>,
    /// Torque and power balances of the report (always given: they hold on any model).
    pub balances: Balances,
}

fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

impl SummaryPoint {
    /// The summary of the procedure's point `p`.
    pub fn new(p: &SpeedLossPoint) -> Self {
        let valid = p.linearisation.is_none();
        let r = &p.report;
        let runaway = p.gross_slip.is_some() && p.drift.is_none();
        let arc = |role| {
            r.find(role)
                .and_then(|k| finite(r.pulleys[k].slip_arc_rad))
                .filter(|_| valid)
        };
        Self {
            torque: p.torque,
            delta_omega: finite(p.delta_omega).filter(|_| valid && !runaway),
            tension_tight: finite(r.tension_tight()).filter(|_| valid),
            tension_slack: finite(r.tension_slack()).filter(|_| valid),
            gross_slip: p.gross_slip.is_some(),
            gross_slip_at: p.gross_slip.clone(),
            slip_arc_driver_rad: arc(Role::Driver),
            slip_arc_driven_rad: arc(Role::Driven),
            hub_loads: valid.then(|| r.hub_loads()),
            linearisation_valid: valid,
            linearisation: p.linearisation.clone(),
            caveat: p.caveat.clone(),
            balance: p.balance.clone(),
            pulleys: valid.then(|| r.pulleys.clone()),
            spans: valid.then(|| r.spans.clone()),
            balances: r.balances,
        }
    }
}

/// One driver speed's result in the summary.
#[derive(Debug, Clone, Serialize)]
pub struct SummaryCase {
    /// Driver speed \[rad/s\].
    pub omega_driver: f64,
    /// Operating points.
    pub points: Vec<SummaryPoint>,
    /// Bechtel's Δω (6.3) at the same torques \[rad/s\].
    pub analytical: Vec<f64>,
    /// Euler–Eytelwein capacity of the drive at this speed \[N·m\]
    /// ([`crate::euler_eytelwein_capacity`]).
    pub capacity_euler_eytelwein: f64,
    /// Integration statistics.
    pub stats: SweepStats,
    /// Wall time of this case \[s\].
    pub wall_time_s: f64,
}

impl SummaryCase {
    /// The summary of `case`, which took `wall_time_s` \[s\].
    pub fn new(case: SpeedLossCase, wall_time_s: f64) -> Self {
        Self {
            omega_driver: case.omega_driver,
            points: case.points.iter().map(SummaryPoint::new).collect(),
            analytical: case.analytical,
            capacity_euler_eytelwein: case.capacity,
            stats: case.stats,
            wall_time_s,
        }
    }
}

/// Summary: the first speed's case at the top level (the `--omega` contract), all cases below.
#[derive(Debug, Clone, Serialize)]
pub struct SpeedLossSummary {
    /// Driver speed of the first case \[rad/s\].
    pub omega_driver: f64,
    /// Model.
    pub model: ModelKind,
    /// Points of the first case.
    pub points: Vec<SummaryPoint>,
    /// Analytical Δω of the first case \[rad/s\].
    pub analytical: Vec<f64>,
    /// Every driver speed.
    pub cases: Vec<SummaryCase>,
    /// Number of coordinates of the model (modal + belt + pulley for the flowing model,
    /// nodal + belt + pulley for the nodal model).
    pub modal_coordinates: usize,
    /// Total wall time \[s\].
    pub wall_time_s: f64,
    /// What the numbers mean ([`SPEED_LOSS_MEANING`]).
    pub meaning: String,
}

/// The speed-loss study's "what the numbers mean" paragraph (`meaning` in the summary), in
/// two parts around the run's own comparison with Bechtel's line ([`SpeedLossSummary::new`]).
pub const SPEED_LOSS_MEANING: [&str; 2] = [
    "points, analytical and omega_driver: those of the first driver speed; cases: every driver \
speed with its points. points: the steady angular speed loss \
delta_omega = omega_driver - omega_driven [rad/s] of the two-pulley belt drive of Ribaric \
Table 6-1 at each load torque [N m] on the driven pulley (the driver held at omega_driver); \
analytical: Bechtel's line (6.3) at the same torques, 2 M omega / (2R(T0 + EA) + M). Bechtel \
counts only the elastic creep of an extensible belt on rigid pulleys: the belt stretches by \
the tension change T1 - T2 = M/R along the contact arc. The FE model (flowing material, or \
nodal / ANCF belt) loses more speed (",
    "), mostly by the slip of the regularised friction law (6.2), whose force needs a relative \
velocity everywhere on the arc (no true stick, so the whole arc creeps; with Ribaric's \
kappa = 40 s/m that slip is about twice the creep). Near Coulomb friction (a slip-velocity \
scale well below the creep speed) the models approach (6.3) itself: on Table 6-1 at 10 N m \
the nodal belt lies 0.6 % and the flowing belt with its chord contact rates and damping \
(contact_velocity and viscous_force = \"auto\", the defaults, with any law but Ribaric's kappa \
law) 0.7 % below it (BENCHMARKS.md), so the radial contact compliance of the penalty law (6.1) \
and the radius at which the speeds are compared add little; a point's caveat says where the \
flowing belt's contact rates of Ribaric's T_,s understate the creep. Shear of the belt section is not modelled (beam \
elements), so the FE figures still lie below Ribaric's measurements. The speed loss grows \
about linearly with the torque and with the driver speed.",
];

/// The run's comparison with Bechtel's line for the meaning: per driver speed, the FE speed
/// loss over Bechtel's (6.3) at its largest load torque.
fn bechtel_ratios(cases: &[SummaryCase]) -> String {
    let parts: Vec<String> = cases
        .iter()
        .filter_map(|c| {
            let (k, p) = c
                .points
                .iter()
                .enumerate()
                .filter(|(_, p)| p.torque > 0.0 && p.delta_omega.is_some_and(f64::is_finite))
                .max_by(|a, b| a.1.torque.total_cmp(&b.1.torque))?;
            let (dw, a) = (p.delta_omega?, *c.analytical.get(k)?);
            (a > 0.0).then(|| {
                format!(
                    "{:.2} times Bechtel's at {} N m and {} rad/s",
                    dw / a,
                    p.torque,
                    c.omega_driver
                )
            })
        })
        .collect();
    if parts.is_empty() {
        "no loaded steady point to compare in this run".into()
    } else {
        format!("in this run {}", parts.join(", "))
    }
}

impl SpeedLossSummary {
    /// The summary of `cases` (in the configured order of speeds, at least one) of `model`
    /// with `coordinates` coordinates, which took `wall_time_s` \[s\] in all.
    pub fn new(
        model: ModelKind, cases: Vec<SummaryCase>, coordinates: usize, wall_time_s: f64,
    ) -> Self {
        let (omega_driver, points, analytical) = cases
            .first()
            .map(|c| (c.omega_driver, c.points.clone(), c.analytical.clone()))
            .unwrap_or_default();
        let meaning = format!(
            "{}{}{}",
            SPEED_LOSS_MEANING[0],
            bechtel_ratios(&cases),
            SPEED_LOSS_MEANING[1]
        );
        Self {
            omega_driver,
            model,
            points,
            analytical,
            modal_coordinates: coordinates,
            cases,
            wall_time_s,
            meaning,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // the defaults are Ribaric's Figs. 6-6 and 6-7 (62.8 and 22.6 rad/s) and pass validation
    #[test]
    fn defaults_are_the_papers_speeds_and_valid() {
        let c = SpeedLossStudyConfig::default();
        assert_eq!(c.omegas, vec![62.8, 22.6]);
        assert!(c.validate().is_ok());
    }

    // a bad speed is named by its index (definition of the message)
    #[test]
    fn bad_speed_is_named() {
        let c = SpeedLossStudyConfig {
            omegas: vec![62.8, -1.0],
            ..Default::default()
        };
        let e = c.validate().unwrap_err();
        assert_eq!(e.field, "omegas[1]");
    }
}
