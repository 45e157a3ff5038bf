//! FEAD design as engineers do it (issue 36): the steady solution of a belt drive at each
//! operating point in milliseconds, without time stepping, and the drive's modes about it.
//!
//! For each engine speed of the configuration ([`DesignConfig`], the FEAD study's drive and
//! engine, [`crate::fead`]):
//!
//! * [`statics`]: belt speed and centrifugal tension, the pulley torques (load torque plus
//!   damper, the driver supplying the sum), every span's tension, the tensioner arm's angle
//!   and force (moment balance together with the belt length), each wrap's adhesion and slip
//!   arcs (creep theory, Euler–Eytelwein on the slip arc at the exit), hub loads (magnitude and
//!   direction) and per pulley the slip margin, the torque to gross slip over the torque
//!   carried;
//! * [`modes`]: the linearised rotational model (pulley inertias, arm inertia and spring, the
//!   spans as axial springs) solved by the workspace's generalized symmetric eigen solver, with
//!   each mode's dominant participant, and the spans' transverse travelling-string modes;
//! * [`coupled`]: the spans' transverse motion coupled with the rotational model through the
//!   tensioner arm (Beikmann, Perkins & Ulsoy 1996; travelling strings with their gyroscopic
//!   terms), each coupled mode with its dominant part (a span, the arm or a pulley);
//! * a Campbell diagram ([`Campbell`]): the rotational, span and coupled modes against engine
//!   speed with the engine orders, and their crossings.
//!
//! Before any time stepping it flags, as typed [`DesignIssue`]s (warnings or errors, never a
//! panic): a tensioner on a tight span, an arm within [`DesignSettings::stop_margin_deg`] of a
//! stop of its travel (or on it), a span without quasi-static tension, gross slip (the
//! installation tension too low for the torque: the required Euler–Eytelwein ratio exceeds
//! `e^{μφ}`), a slip margin below [`DesignSettings::slip_margin_warning`], and span modes near a
//! mode of the tensioner arm.

pub mod coupled;
pub mod modes;
pub mod statics;

use crate::fead::{EngineConfig, FeadConfig};
use belt::{Drive, Layout, Motion, Role, WrapSide};
use contact::friction::FrictionLaw;
use coupled::{CoupledMode, CoupledOptions, MAX_SPAN_TERMS, coupled_model};
use mbd_core::roots::illinois;
use mbd_core::validate::{InvalidField, Validate, check};
use modes::{RotationalMode, SpanModes, WrapModel, rotational_model_with, span_modes};
use serde::{Deserialize, Serialize};
use statics::{Loading, SteadyState, WrapState, hub_force, single_driver, solve, state_issues};

/// Most points of the Campbell diagram's engine-speed grid.
pub const MAX_CAMPBELL_POINTS: usize = 2000;
/// Most transverse harmonics per span.
pub const MAX_HARMONICS: usize = 20;

/// Settings of the design study.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct DesignSettings {
    /// An arm angle closer than this to an end of its travel is flagged \[deg\].
    pub stop_margin_deg: f64,
    /// A slip margin below this (but above 1) is flagged \[-\] (below 1: gross slip, an error).
    pub slip_margin_warning: f64,
    /// Transverse harmonics per span `n = 1..=harmonics`.
    pub harmonics: usize,
    /// Engine speeds of the Campbell diagram's grid.
    pub campbell_points: usize,
    /// Engine-speed range of the Campbell diagram \[rpm\] (none: the configured speeds' range).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub campbell_rpm: Option<[f64; 2]>,
    /// A span adjacent to the tensioner whose frequency lies within this fraction of a mode in
    /// which the arm takes at least a quarter of the kinetic energy is flagged \[-\].
    pub coupling_band: f64,
    /// Sine terms per span of the coupled transverse–rotational model ([`coupled`]).
    pub span_terms: usize,
    /// How the rotational model holds the belt on the wraps: `"creep"` on the adhesion arcs
    /// only, each span in series with the slip arc it leaves (creep theory), or `"held"` on the
    /// whole wrap, the spans the only springs (an upper bound; [`modes`]).
    pub wrap: WrapModel,
}

impl Default for DesignSettings {
    /// 3° from a stop, slip margin 1.5, two harmonics, 61 Campbell points, 10 % coupling band,
    /// 16 sine terms per span, the belt held on the adhesion arcs (`wrap = "creep"`).
    fn default() -> Self {
        Self {
            stop_margin_deg: 3.0,
            slip_margin_warning: 1.5,
            harmonics: 2,
            campbell_points: 61,
            campbell_rpm: None,
            coupling_band: 0.1,
            span_terms: 16,
            wrap: WrapModel::Creep,
        }
    }
}

/// The design study's configuration: the FEAD study's `[drive]` and `[engine]` tables
/// ([`FeadConfig`]) and the study's `[design]` settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct DesignConfig {
    /// The drive: pulley 0 is the crankshaft, the one speed-driven pulley.
    pub drive: Layout,
    /// Engine speeds (the operating points) and orders (the Campbell diagram's lines).
    pub engine: EngineConfig,
    /// Study settings.
    pub design: DesignSettings,
}

impl Default for DesignConfig {
    /// The FEAD study's default drive and engine ([`FeadConfig::default`]).
    fn default() -> Self {
        let f = FeadConfig::default();
        Self {
            drive: f.drive,
            engine: f.engine,
            design: DesignSettings::default(),
        }
    }
}

// the layout's merge rules (`tension` / `belt_length`, `pulleys` / `tensioner`)
impl mbd_core::config::PartialRules for DesignConfig {
    const DROPPED_BY: &'static [(&'static str, &'static str)] = belt::PARTIAL_RULES;
}

impl Validate for DesignConfig {
    fn validate(&self) -> Result<(), InvalidField> {
        let drive = crate::fead::resolve_engine_drive(&self.drive)?;
        if single_driver(&drive).is_none() {
            return Err(InvalidField::new(
                "drive.pulleys",
                "the design study needs exactly one speed-driven pulley (the crankshaft): with \
                 several the torque split between them is not determined by statics",
            ));
        }
        self.engine.validate_within("engine")?;
        let d = &self.design;
        check::within(
            "design.stop_margin_deg",
            d.stop_margin_deg,
            0.0,
            90.0,
            "deg",
        )?;
        check::within(
            "design.slip_margin_warning",
            d.slip_margin_warning,
            1.0,
            1e3,
            "",
        )?;
        check::count("design.harmonics", d.harmonics, 1, MAX_HARMONICS)?;
        check::count(
            "design.campbell_points",
            d.campbell_points,
            2,
            MAX_CAMPBELL_POINTS,
        )?;
        if let Some([a, b]) = d.campbell_rpm {
            check::within("design.campbell_rpm[0]", a, 1.0, 20_000.0, "rpm")?;
            check::within("design.campbell_rpm[1]", b, a, 20_000.0, "rpm")?;
        }
        check::within("design.coupling_band", d.coupling_band, 0.0, 1.0, "")?;
        check::count("design.span_terms", d.span_terms, 1, MAX_SPAN_TERMS)
    }
}

/// How serious a finding is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    /// The drive works but is near a limit.
    Warning,
    /// The drive does not work as laid out at this operating point.
    Error,
}

/// A problem the design study finds before any time stepping (module documentation).
#[derive(Debug, Clone, PartialEq, Serialize, thiserror::Error)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum DesignIssue {
    /// The span running onto the tensioner's idler is tighter than the loop's length-weighted
    /// mean: the arm sits on the tight side, where the tension it holds is raised by the
    /// torques (a tensioner belongs on the span leaving the driver).
    #[error(
        "{engine_rpm} rpm: the tensioner '{pulley}' sits on a tight span ({span_tension_n:.1} N \
         against a mean of {mean_tension_n:.1} N)"
    )]
    TensionerOnTightSpan {
        /// Engine speed \[rpm\].
        engine_rpm: f64,
        /// The tensioner's idler.
        pulley: String,
        /// Tension of the span running onto it \[N\].
        span_tension_n: f64,
        /// Length-weighted mean span tension \[N\].
        mean_tension_n: f64,
    },
    /// The arm's steady angle lies within the stop margin of an end of its travel
    /// (`engine_rpm = 0`: the installed arm at rest, set by the spring's preload).
    #[error(
        "{engine_rpm} rpm: the tensioner arm at {angle_deg:.2}° is {margin_deg:.2}° from its \
         stop at {stop_deg:.2}°"
    )]
    NearEndStop {
        /// Engine speed \[rpm\].
        engine_rpm: f64,
        /// Arm angle \[deg\].
        angle_deg: f64,
        /// The nearer stop \[deg\].
        stop_deg: f64,
        /// Distance to it \[deg\].
        margin_deg: f64,
    },
    /// The arm's moment balance has no root in its travel: it rests on a stop (the drive is
    /// solved as a fixed-centre drive there).
    #[error("{engine_rpm} rpm: the tensioner arm rests on its stop at {stop_deg:.2}°")]
    ArmOnStop {
        /// Engine speed \[rpm\].
        engine_rpm: f64,
        /// The stop \[deg\].
        stop_deg: f64,
    },
    /// The belt length cannot be closed with quasi-static tension in every span.
    #[error(
        "{engine_rpm} rpm: span {from} → {to} goes slack ({tension_n:.1} N, centrifugal \
         {centrifugal_n:.1} N)"
    )]
    SlackSpan {
        /// Engine speed \[rpm\].
        engine_rpm: f64,
        /// Pulley the span leaves.
        from: String,
        /// Pulley the span reaches.
        to: String,
        /// Its tension \[N\].
        tension_n: f64,
        /// Centrifugal tension \[N\].
        centrifugal_n: f64,
    },
    /// The wrap cannot carry its torque: the Euler–Eytelwein ratio the torque requires exceeds
    /// `e^{μφ}` (installation tension too low).
    #[error(
        "{engine_rpm} rpm: gross slip on '{pulley}': ratio {required_ratio:.3} required, \
         e^(μφ) = {available_ratio:.3} available"
    )]
    GrossSlip {
        /// Engine speed \[rpm\].
        engine_rpm: f64,
        /// The pulley.
        pulley: String,
        /// `(T − T_c)` ratio the torque requires.
        required_ratio: f64,
        /// `e^{μφ}`.
        available_ratio: f64,
    },
    /// A slip margin below the warning threshold.
    #[error("{engine_rpm} rpm: slip margin of '{pulley}' is {margin:.2} (below {threshold})")]
    LowSlipMargin {
        /// Engine speed \[rpm\].
        engine_rpm: f64,
        /// The pulley.
        pulley: String,
        /// Its slip margin.
        margin: f64,
        /// [`DesignSettings::slip_margin_warning`].
        threshold: f64,
    },
    /// A span adjacent to the tensioner whose transverse frequency lies near a mode the arm
    /// takes part in (Beikmann, Perkins & Ulsoy 1996), at or below the frequency the highest
    /// engine order reaches at this speed (plus [`DesignSettings::coupling_band`]): a coupling
    /// above every order is not driven, directly or parametrically (the principal parametric
    /// resonance of a span lies at half the excitation frequency). Without engine orders every
    /// coupling is reported.
    #[error(
        "{engine_rpm} rpm: span {from} → {to} ({span_hz:.1} Hz) lies near the arm's mode at \
         {mode_hz:.1} Hz: transverse and rotational motion couple through the arm"
    )]
    SpanArmCoupling {
        /// Engine speed \[rpm\].
        engine_rpm: f64,
        /// Pulley the span leaves.
        from: String,
        /// Pulley the span reaches.
        to: String,
        /// The span's frequency \[Hz\].
        span_hz: f64,
        /// The rotational mode's frequency \[Hz\].
        mode_hz: f64,
    },
    /// The rotational model's eigen solution failed (e.g. an arm whose belt pull outweighs its
    /// spring: negative stiffness).
    #[error("{engine_rpm} rpm: no rotational modes: {reason}")]
    ModesFailed {
        /// Engine speed \[rpm\].
        engine_rpm: f64,
        /// The solver's message.
        reason: String,
    },
}

impl DesignIssue {
    /// How serious it is.
    pub fn severity(&self) -> Severity {
        match self {
            DesignIssue::TensionerOnTightSpan { .. }
            | DesignIssue::NearEndStop { .. }
            | DesignIssue::LowSlipMargin { .. }
            | DesignIssue::SpanArmCoupling { .. } => Severity::Warning,
            DesignIssue::ArmOnStop { .. }
            | DesignIssue::SlackSpan { .. }
            | DesignIssue::GrossSlip { .. }
            | DesignIssue::ModesFailed { .. } => Severity::Error,
        }
    }
}

/// A finding of the study: the issue, its severity and its message.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Finding {
    /// Warning or error.
    pub severity: Severity,
    /// One line.
    pub message: String,
    /// The typed issue.
    pub issue: DesignIssue,
}

impl From<DesignIssue> for Finding {
    fn from(issue: DesignIssue) -> Self {
        Self {
            severity: issue.severity(),
            message: issue.to_string(),
            issue,
        }
    }
}

/// The tensioner arm at one operating point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ArmPoint {
    /// Arm angle \[rad\] (counter-clockwise from x).
    pub angle_rad: f64,
    /// Arm angle \[deg\].
    pub angle_deg: f64,
    /// Change from the installed (mounted, at rest) angle \[deg\].
    pub swing_deg: f64,
    /// Spring moment `M_s(θ)` \[N m\].
    pub spring_moment_n_m: f64,
    /// The belt's force on the idler \[N\].
    pub idler_force_n: [f64; 2],
    /// Its magnitude \[N\].
    pub idler_force_magnitude_n: f64,
    /// Distance to the nearer stop of the travel \[deg\].
    pub stop_margin_deg: f64,
    /// Whether it rests on a stop.
    pub on_stop: bool,
}

/// One span at one operating point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DesignSpan {
    /// Pulley the span leaves.
    pub from: String,
    /// Pulley the span reaches.
    pub to: String,
    /// Free length \[m\].
    pub length_m: f64,
    /// Tension (total axial force) \[N\].
    pub tension_n: f64,
    /// Quasi-static tension `T − ρA v²` \[N\].
    pub effective_tension_n: f64,
    /// `"tight"` above the loop's length-weighted mean tension, `"slack"` otherwise.
    pub side: String,
    /// Axial stiffness of the free span `EA_t/L` \[N/m\].
    pub stiffness_n_per_m: f64,
    /// Compliance of the slip arc of the pulley the span leaves `c_w` \[m/N\] (creep theory,
    /// [`modes`]: the belt's extension on that arc per newton of span tension; zero without
    /// load).
    pub wrap_compliance_m_per_n: f64,
    /// The span's spring in the rotational model \[N/m\]: `1/(L/EA_t + c_w)` with
    /// `wrap = "creep"`, `EA_t/L` with `"held"`.
    pub series_stiffness_n_per_m: f64,
    /// Transverse modes.
    pub modes: SpanModes,
}

/// One pulley at one operating point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DesignPulley {
    /// Name.
    pub name: String,
    /// Role.
    pub role: Role,
    /// Wrap angle \[deg\].
    pub wrap_deg: f64,
    /// Speed (travel sense) \[rad/s\].
    pub speed_rad_per_s: f64,
    /// Torque the belt delivers in the travel sense, `(T_out − T_in) r` \[N m\] (negative on the
    /// driver).
    pub torque_n_m: f64,
    /// Tension of the span running on \[N\].
    pub tension_in_n: f64,
    /// Tension of the span running off \[N\].
    pub tension_out_n: f64,
    /// Friction coefficient used.
    pub friction_coefficient: f64,
    /// Adhesion arc (at the inlet) \[deg\].
    pub adhesion_arc_deg: f64,
    /// Slip arc (at the exit) \[deg\].
    pub slip_arc_deg: f64,
    /// Euler–Eytelwein ratio the torque requires (`None`: a side without quasi-static
    /// tension).
    pub required_ratio: Option<f64>,
    /// `e^{μφ}`.
    pub available_ratio: f64,
    /// Torque to gross slip with the slack side as it is, `(T_s − T_c)(e^{μφ} − 1) r` \[N m\].
    pub capacity_n_m: f64,
    /// Capacity over the torque carried (`None`: no torque).
    pub slip_margin: Option<f64>,
    /// Force of the belt on the pulley \[N\].
    pub hub_load_n: [f64; 2],
    /// Its magnitude \[N\].
    pub hub_load_magnitude_n: f64,
    /// Its direction, counter-clockwise from x \[deg\].
    pub hub_load_direction_deg: f64,
}

/// The steady solution at one engine speed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DesignPoint {
    /// Engine speed \[rpm\].
    pub engine_rpm: f64,
    /// Crank speed \[rad/s\].
    pub crank_speed_rad_per_s: f64,
    /// Belt speed \[m/s\].
    pub belt_speed_m_per_s: f64,
    /// Centrifugal tension `ρA v²` \[N\].
    pub centrifugal_tension_n: f64,
    /// Path length over the pulleys \[m\] (with the arm at its steady angle).
    pub path_length_m: f64,
    /// Path length minus the unstretched belt length \[m\].
    pub belt_elongation_m: f64,
    /// Power the driver delivers, `Σ Q_k ω_k` over the free pulleys \[W\].
    pub driver_power_w: f64,
    /// Power balance `Σ τ_k ω_k` over all pulleys \[W\] (zero: check).
    pub power_residual_w: f64,
    /// The tensioner arm (`None`: no tensioner).
    pub arm: Option<ArmPoint>,
    /// Spans in travel order.
    pub spans: Vec<DesignSpan>,
    /// Tightest span, `"from → to"`.
    pub tight_span: String,
    /// Tension of the tightest span per rib \[N\] (`None`: a flat belt).
    pub tight_tension_per_rib_n: Option<f64>,
    /// Slackest span, `"from → to"`.
    pub slack_span: String,
    /// Pulleys in travel order.
    pub pulleys: Vec<DesignPulley>,
    /// Coordinates of the rotational model.
    pub rotational_dofs: Vec<String>,
    /// Geometric stiffness of the belt's pull on the arm \[N m/rad\] ([`modes`]).
    pub arm_geometric_stiffness_n_m_per_rad: Option<f64>,
    /// How the rotational model holds the belt on the wraps (`"creep"` or `"held"`,
    /// [`DesignSettings::wrap`]).
    pub wrap_model: String,
    /// Rotational modes, ascending.
    pub rotational_modes: Vec<RotationalMode>,
    /// Frequencies of the rotational modes with the belt held on the whole wrap \[Hz\],
    /// ascending: the upper bound the `"creep"` modes are compared with (the same as
    /// `rotational_modes` with `wrap = "held"`; empty where its eigen solution failed).
    pub held_wrap_frequencies_hz: Vec<f64>,
    /// Parts of the coupled model ([`coupled`]): the rotational coordinates, then the spans.
    pub coupled_parts: Vec<String>,
    /// The lowest modes of the coupled model (as many as the rotational modes and the spans'
    /// harmonics together), ascending, each with its dominant part.
    pub coupled_modes: Vec<CoupledMode>,
}

/// One curve of the Campbell diagram.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CampbellCurve {
    /// `"rotational mode k (dominant)"`, `"span a → b, n = k"` or `"coupled mode k
    /// (dominant)"` (dominant part at the grid's first speed).
    pub name: String,
    /// `"rotational"`, `"transverse"` (a span alone) or `"coupled"` ([`coupled`]).
    pub kind: String,
    /// Frequency at every grid speed \[Hz\] (`None`: none there).
    pub frequencies_hz: Vec<Option<f64>>,
}

/// Where an engine order meets a mode.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Crossing {
    /// The curve's name.
    pub curve: String,
    /// The engine order.
    pub order: f64,
    /// Engine speed \[rpm\].
    pub engine_rpm: f64,
    /// Frequency \[Hz\].
    pub frequency_hz: f64,
}

/// The Campbell diagram: modes against engine speed, the engine orders `f = k·rpm/60`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Campbell {
    /// Grid of engine speeds \[rpm\].
    pub engine_rpm: Vec<f64>,
    /// Engine orders.
    pub orders: Vec<f64>,
    /// The curves.
    pub curves: Vec<CampbellCurve>,
    /// Crossings of every curve with every order in the grid's range.
    pub crossings: Vec<Crossing>,
}

/// The design study's summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DesignSummary {
    /// The layout run, in words.
    pub layout: String,
    /// Travel direction of the belt.
    pub travel_direction: String,
    /// Installation tension \[N\].
    pub installation_tension_n: f64,
    /// Unstretched belt length \[m\].
    pub belt_length_m: f64,
    /// Mounted path length \[m\].
    pub path_length_m: f64,
    /// Installed arm angle \[rad\].
    pub arm_installed_angle_rad: Option<f64>,
    /// Arm travel \[rad\].
    pub arm_travel_rad: Option<[f64; 2]>,
    /// Pulley names.
    pub pulleys: Vec<String>,
    /// One per engine speed.
    pub points: Vec<DesignPoint>,
    /// The Campbell diagram.
    pub campbell: Campbell,
    /// Findings over all points (warnings and errors).
    pub findings: Vec<Finding>,
    /// Number of errors among them.
    pub errors: usize,
    /// Number of warnings among them.
    pub warnings: usize,
    /// What the numbers mean, naming the layout.
    pub meaning: String,
}

/// Friction coefficient of every wrap of `drive`: the contact law's `μ`, for a multi-ribbed
/// belt `μ/sin(β/2)` on grooved pulleys (wrapped inside the loop) and `μ` on flat back-side
/// ones: the coefficient of [`Drive::wrap_friction_law`], the law the time-stepped models
/// contact each pulley with, so that the capacity check and the simulations agree.
pub fn wrap_friction(drive: &Drive) -> Vec<f64> {
    drive.wrap_friction_coefficients()
}

/// The steady state of `drive` with its single driver turning at `driver_speed` \[rad/s\]
/// ([`statics::solve`]).
///
/// # Errors
/// Not exactly one speed-driven pulley (`drive.pulleys`).
pub fn steady_state(drive: &Drive, driver_speed: f64) -> Result<SteadyState, InvalidField> {
    let driver = single_driver(drive).ok_or_else(|| {
        InvalidField::new("drive.pulleys", "needs exactly one speed-driven pulley")
    })?;
    Ok(solve(
        drive,
        Loading::steady(drive, driver, driver_speed),
        wrap_friction(drive),
    ))
}

fn span_name(names: &[String], k: usize) -> String {
    format!("{} → {}", names[k], names[(k + 1) % names.len()])
}

/// The belt's travel direction and every pulley's sense of rotation in words (the loop runs
/// clockwise around the pulleys inside it, seen from +z: [`belt::pulley`]).
pub fn travel_direction(drive: &Drive) -> String {
    let senses: Vec<String> = drive
        .pulleys()
        .iter()
        .map(|p| {
            let sense = match p.side {
                WrapSide::Inside => "clockwise",
                WrapSide::Outside => "counter-clockwise",
            };
            format!("{} {sense}", p.name)
        })
        .collect();
    format!(
        "the belt runs clockwise round the loop seen from +z, from each pulley to the next in \
         travel order (span k leaves pulley k); pulleys turn: {}",
        senses.join(", ")
    )
}

/// The layout in words (the summary's `layout`).
pub fn describe(drive: &Drive) -> String {
    let pulleys: Vec<String> = drive
        .pulleys()
        .iter()
        .zip(drive.wraps())
        .map(|(p, w)| {
            let what = match &p.motion {
                Motion::Speed { .. } => "driver".to_string(),
                Motion::Load { torque, .. } => format!("load {:.2} N m", torque.final_value()),
                Motion::Idler { .. } => "idler".to_string(),
            };
            let side = match p.side {
                WrapSide::Inside => "grooved side",
                WrapSide::Outside => "back side",
            };
            format!(
                "{} (r {:.1} mm, {side}, wrap {:.0}°, {what})",
                p.name,
                1e3 * p.radius,
                w.to_degrees()
            )
        })
        .collect();
    let tensioner = drive.arm().map_or(String::from("no tensioner"), |a| {
        let t = a.tensioner;
        format!(
            "tensioner arm on '{}' (arm {:.1} mm about ({:.3}, {:.3}) m, spring {:.1} N m/rad with \
             {:.1} N m at {:.1}°, travel {:.1}° to {:.1}°, installed at {:.2}°)",
            drive.names()[t.pulley],
            1e3 * a.length,
            t.pivot[0],
            t.pivot[1],
            t.stiffness,
            t.preload,
            t.preload_angle.to_degrees(),
            t.travel[0].to_degrees(),
            t.travel[1].to_degrees(),
            a.angle.to_degrees()
        )
    });
    let b = drive.belt();
    let ribs = b.ribs.map_or(String::from("flat"), |r| {
        format!(
            "{} ribs of {:.0}° (μ/sin(β/2) on grooved pulleys)",
            r.count,
            r.wedge_angle.to_degrees()
        )
    });
    format!(
        "{} pulleys in travel order: {}; {tensioner}; belt {ribs}, EA {:.0} N, ρA {:.4} kg/m, \
         μ {:.2}, {:.4} m unstretched, mounted at {:.1} N",
        drive.pulleys().len(),
        pulleys.join(", "),
        b.ea,
        b.mass_per_length,
        drive.contact().friction.coefficient(),
        drive.belt_length(),
        drive.tension()
    )
}

/// The design point of `drive` at `engine_rpm` (pulley `driver` speed-driven at that speed),
/// with its findings.
/// The steady design at `engine_rpm` with its findings; `highest_order` (NaN: none) bounds
/// the span–arm couplings reported ([`DesignIssue::SpanArmCoupling`]).
fn design_point(
    drive: &Drive, engine_rpm: f64, settings: &DesignSettings, highest_order: f64,
) -> Result<(DesignPoint, Vec<DesignIssue>), InvalidField> {
    let omega = engine_rpm * std::f64::consts::PI / 30.0;
    let s = steady_state(drive, omega)?;
    let names = drive.names();
    let n = names.len();
    let section = drive.belt();
    let tc = s.centrifugal;
    let mut issues = state_issues(drive, &s, engine_rpm);
    // spans
    let total: f64 = s.geometry.spans.iter().map(|sp| sp.length).sum();
    let mean = s
        .geometry
        .spans
        .iter()
        .map(|sp| sp.length * s.tensions[sp.from])
        .sum::<f64>()
        / total;
    let transverse = span_modes(drive, &s, settings.harmonics);
    let model = rotational_model_with(drive, &s, settings.wrap);
    let spans: Vec<DesignSpan> = s
        .geometry
        .spans
        .iter()
        .zip(transverse)
        .enumerate()
        .map(|(k, (sp, m))| {
            let t = s.tensions[sp.from];
            DesignSpan {
                from: names[sp.from].clone(),
                to: names[sp.to].clone(),
                length_m: sp.length,
                tension_n: t,
                effective_tension_n: t - tc,
                side: if t > mean { "tight" } else { "slack" }.into(),
                stiffness_n_per_m: section.tangent_stiffness(t) / sp.length,
                wrap_compliance_m_per_n: model.wrap_compliance[k],
                series_stiffness_n_per_m: model.span_stiffness[k],
                modes: m,
            }
        })
        .collect();
    let by_tension = |a: &usize, b: &usize| s.tensions[*a].total_cmp(&s.tensions[*b]);
    let tight = (0..n).max_by(by_tension).unwrap_or(0);
    let slack = (0..n).min_by(by_tension).unwrap_or(0);
    // pulleys
    let loaded = s
        .loading
        .torques
        .iter()
        .any(|q| q.abs() > 1e-12 * drive.tension());
    let pulleys: Vec<DesignPulley> = (0..n)
        .map(|k| {
            let p = &s.geometry.path.pulleys()[k];
            let w: &WrapState = &s.wraps[k];
            let (tin, tout) = (w.tension_in, w.tension_out);
            let f = hub_force(&s.geometry, k, tin, tout, tc);
            let capacity = ((tin.min(tout) - tc).max(0.0)) * (w.available_ratio - 1.0) * p.radius;
            let q = (tout - tin) * p.radius;
            let scale = 1e-9 * drive.tension() * p.radius;
            DesignPulley {
                name: p.name.clone(),
                role: p.motion.role(),
                wrap_deg: w.wrap.to_degrees(),
                speed_rad_per_s: s.loading.speeds[k],
                torque_n_m: q,
                tension_in_n: tin,
                tension_out_n: tout,
                friction_coefficient: s.mu[k],
                adhesion_arc_deg: (w.wrap - w.slip_arc).to_degrees(),
                slip_arc_deg: w.slip_arc.to_degrees(),
                required_ratio: w.required_ratio.is_finite().then_some(w.required_ratio),
                available_ratio: w.available_ratio,
                capacity_n_m: capacity,
                slip_margin: (q.abs() > scale).then(|| capacity / q.abs()),
                hub_load_n: f,
                hub_load_magnitude_n: f[0].hypot(f[1]),
                hub_load_direction_deg: f[1].atan2(f[0]).to_degrees(),
            }
        })
        .collect();
    for p in &pulleys {
        if let Some(m) = p.slip_margin
            && m < settings.slip_margin_warning
            && m >= 1.0
        {
            issues.push(DesignIssue::LowSlipMargin {
                engine_rpm,
                pulley: p.name.clone(),
                margin: m,
                threshold: settings.slip_margin_warning,
            });
        }
    }
    // the arm
    let arm = match (drive.arm(), s.arm_angle) {
        (Some(a), Some(th)) => {
            let t = a.tensioner;
            let k = t.pulley;
            let f = hub_force(
                &s.geometry,
                k,
                s.tensions[(k + n - 1) % n],
                s.tensions[k],
                tc,
            );
            let margin = (th - t.travel[0]).min(t.travel[1] - th).to_degrees();
            let stop = if th - t.travel[0] < t.travel[1] - th {
                t.travel[0]
            } else {
                t.travel[1]
            };
            if s.arm_on_stop.is_none() && margin < settings.stop_margin_deg {
                issues.push(DesignIssue::NearEndStop {
                    engine_rpm,
                    angle_deg: th.to_degrees(),
                    stop_deg: stop.to_degrees(),
                    margin_deg: margin,
                });
            }
            let into = (k + n - 1) % n;
            if loaded && s.tensions[into] > mean * (1.0 + 1e-9) {
                issues.push(DesignIssue::TensionerOnTightSpan {
                    engine_rpm,
                    pulley: names[k].clone(),
                    span_tension_n: s.tensions[into],
                    mean_tension_n: mean,
                });
            }
            Some(ArmPoint {
                angle_rad: th,
                angle_deg: th.to_degrees(),
                swing_deg: (th - a.angle).to_degrees(),
                spring_moment_n_m: t.spring_moment(th).0,
                idler_force_n: f,
                idler_force_magnitude_n: f[0].hypot(f[1]),
                stop_margin_deg: margin,
                on_stop: s.arm_on_stop.is_some(),
            })
        }
        _ => None,
    };
    // modes
    let rotational_modes = match model.modes() {
        Ok(m) => m,
        Err(e) => {
            issues.push(DesignIssue::ModesFailed {
                engine_rpm,
                reason: e.to_string(),
            });
            Vec::new()
        }
    };
    // the held wrap for comparison (its failure is reported by the modes above when it is
    // the study's model, and otherwise leaves the comparison empty)
    let held_wrap_frequencies_hz = match settings.wrap {
        WrapModel::Held => rotational_modes.iter().map(|m| m.frequency_hz).collect(),
        WrapModel::Creep => rotational_model_with(drive, &s, WrapModel::Held)
            .modes()
            .map(|m| m.iter().map(|x| x.frequency_hz).collect())
            .unwrap_or_default(),
    };
    let hybrid = coupled_model(
        drive,
        &s,
        &model,
        &CoupledOptions {
            terms: settings.span_terms,
            hold_arm: false,
        },
    );
    let wanted = model.names.len() + spans.len() * settings.harmonics;
    let coupled_modes = match hybrid.modes(wanted) {
        Ok(m) => m,
        Err(e) => {
            issues.push(DesignIssue::ModesFailed {
                engine_rpm,
                reason: format!("coupled model: {e}"),
            });
            Vec::new()
        }
    };
    let reach = highest_order * engine_rpm / 60.0 * (1.0 + settings.coupling_band);
    if let Some(arm_dof) = model.names.iter().position(|x| x == "tensioner arm") {
        for sp in spans.iter().filter(|sp| sp.modes.coupled_through_arm) {
            for f in sp.modes.frequencies_hz.iter().flatten() {
                for m in rotational_modes
                    .iter()
                    .filter(|m| m.energy_share[arm_dof] >= 0.25)
                {
                    // above the frequency every engine order reaches at this speed (with
                    // the band) the coupling is not driven: no finding
                    let driven = highest_order.is_nan() || f.min(m.frequency_hz) <= reach;
                    if driven && (f / m.frequency_hz - 1.0).abs() <= settings.coupling_band {
                        issues.push(DesignIssue::SpanArmCoupling {
                            engine_rpm,
                            from: sp.from.clone(),
                            to: sp.to.clone(),
                            span_hz: *f,
                            mode_hz: m.frequency_hz,
                        });
                    }
                }
            }
        }
    }
    let driver_power: f64 = (0..n)
        .filter(|&k| k != s.loading.driver)
        .map(|k| s.loading.torques[k] * s.loading.speeds[k])
        .sum();
    let power_residual: f64 = pulleys
        .iter()
        .map(|p| p.torque_n_m * p.speed_rad_per_s)
        .sum();
    let path_length = s.geometry.path.length();
    Ok((
        DesignPoint {
            engine_rpm,
            crank_speed_rad_per_s: omega,
            belt_speed_m_per_s: s.loading.belt_speed,
            centrifugal_tension_n: tc,
            path_length_m: path_length,
            belt_elongation_m: path_length - drive.belt_length(),
            driver_power_w: driver_power,
            power_residual_w: power_residual,
            arm,
            spans,
            tight_span: span_name(&names, tight),
            tight_tension_per_rib_n: section.ribs.map(|r| s.tensions[tight] / r.count as f64),
            slack_span: span_name(&names, slack),
            pulleys,
            rotational_dofs: model.names.clone(),
            arm_geometric_stiffness_n_m_per_rad: model.arm_geometric_stiffness,
            wrap_model: settings.wrap.name().into(),
            rotational_modes,
            held_wrap_frequencies_hz,
            coupled_parts: hybrid.parts.clone(),
            coupled_modes,
        },
        issues,
    ))
}

/// Frequencies of every Campbell curve at `engine_rpm`: the rotational modes ascending, then
/// every span's harmonics, then the coupled modes ascending.
fn curve_values(
    drive: &Drive, engine_rpm: f64, settings: &DesignSettings,
) -> Result<Vec<Option<f64>>, InvalidField> {
    let (p, _) = design_point(drive, engine_rpm, settings, f64::NAN)?;
    // one entry per rotational coordinate (`None` where the eigen solution failed)
    let mut out: Vec<Option<f64>> = (0..p.rotational_dofs.len())
        .map(|i| p.rotational_modes.get(i).map(|m| m.frequency_hz))
        .collect();
    for sp in &p.spans {
        out.extend(sp.modes.frequencies_hz.iter().copied());
    }
    let coupled = p.rotational_dofs.len() + p.spans.len() * settings.harmonics;
    out.extend((0..coupled).map(|i| p.coupled_modes.get(i).map(|m| m.frequency_hz)));
    Ok(out)
}

/// The Campbell diagram of `drive` over the settings' engine-speed grid (module
/// documentation); crossings located by the Illinois root finder on the recomputed curves
/// ([`mbd_core::roots::illinois`], 0.01 rpm).
fn campbell(
    drive: &Drive, engine: &EngineConfig, settings: &DesignSettings, first: &DesignPoint,
) -> Result<Campbell, InvalidField> {
    let [lo, hi] = settings.campbell_rpm.unwrap_or_else(|| {
        let lo = engine
            .speeds_rpm
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        let hi = engine.speeds_rpm.iter().copied().fold(0.0, f64::max);
        if hi > lo {
            [lo, hi]
        } else {
            [0.5 * lo, 1.5 * hi]
        }
    });
    let np = settings.campbell_points;
    let rpm: Vec<f64> = (0..np)
        .map(|i| lo + (hi - lo) * i as f64 / (np - 1) as f64)
        .collect();
    let mut names: Vec<(String, String)> = (0..first.rotational_dofs.len())
        .map(|i| {
            let dominant = first
                .rotational_modes
                .get(i)
                .map_or("no solution at the first speed", |m| m.dominant.as_str());
            (
                format!("rotational mode {} ({dominant})", i + 1),
                "rotational".into(),
            )
        })
        .collect();
    for sp in &first.spans {
        for h in 1..=sp.modes.frequencies_hz.len() {
            names.push((
                format!("span {} → {}, n = {h}", sp.from, sp.to),
                "transverse".into(),
            ));
        }
    }
    let coupled = first.rotational_dofs.len() + first.spans.len() * settings.harmonics;
    for i in 0..coupled {
        let dominant = first
            .coupled_modes
            .get(i)
            .map_or("no solution at the first speed", |m| m.dominant.as_str());
        names.push((
            format!("coupled mode {} ({dominant})", i + 1),
            "coupled".into(),
        ));
    }
    let mut values: Vec<Vec<Option<f64>>> = vec![Vec::with_capacity(np); names.len()];
    for &r in &rpm {
        let v = curve_values(drive, r, settings)?;
        for (c, col) in values.iter_mut().enumerate() {
            col.push(v.get(c).copied().flatten());
        }
    }
    let mut crossings = Vec::new();
    for (c, col) in values.iter().enumerate() {
        for o in engine.orders.iter().map(|o| o.order) {
            let line = |r: f64| o * r / 60.0;
            for i in 0..np - 1 {
                let (Some(fa), Some(fb)) = (col[i], col[i + 1]) else {
                    continue;
                };
                let (ga, gb) = (fa - line(rpm[i]), fb - line(rpm[i + 1]));
                if ga == 0.0 || ga * gb >= 0.0 {
                    if ga == 0.0 {
                        crossings.push(Crossing {
                            curve: names[c].0.clone(),
                            order: o,
                            engine_rpm: rpm[i],
                            frequency_hz: fa,
                        });
                    }
                    continue;
                }
                // the curve recomputed between the grid points (linear between them where
                // the recomputation has no value)
                let (ra, rb) = (rpm[i], rpm[i + 1]);
                let g = |r: f64| {
                    let lin = fa + (fb - fa) * (r - ra) / (rb - ra);
                    let f = curve_values(drive, r, settings)
                        .ok()
                        .and_then(|v| v.get(c).copied().flatten())
                        .unwrap_or(lin);
                    f - line(r)
                };
                let r = illinois(g, ra, rb, ga, gb, 1e-2);
                crossings.push(Crossing {
                    curve: names[c].0.clone(),
                    order: o,
                    engine_rpm: r,
                    frequency_hz: line(r),
                });
            }
        }
    }
    crossings.sort_by(|a, b| a.engine_rpm.total_cmp(&b.engine_rpm));
    Ok(Campbell {
        engine_rpm: rpm,
        orders: engine.orders.iter().map(|o| o.order).collect(),
        curves: names
            .into_iter()
            .zip(values)
            .map(|((name, kind), frequencies_hz)| CampbellCurve {
                name,
                kind,
                frequencies_hz,
            })
            .collect(),
        crossings,
    })
}

/// Run the design study (module documentation): validate, solve every operating point, the
/// modes and the Campbell diagram.
///
/// # Errors
/// The configuration is invalid ([`InvalidField`] naming the field).
pub fn run_design(cfg: &DesignConfig) -> Result<DesignSummary, InvalidField> {
    cfg.validate()?;
    let drive = cfg.drive.resolve().map_err(|e| e.within("drive"))?;
    let mut points = Vec::new();
    let mut findings: Vec<Finding> = Vec::new();
    // the installed arm (at rest, the mounting's statics): its preload may put it near a stop
    if let Some(a) = drive.arm() {
        let [lo, hi] = a.tensioner.travel;
        let (margin, stop) = if a.angle - lo < hi - a.angle {
            (a.angle - lo, lo)
        } else {
            (hi - a.angle, hi)
        };
        if margin.to_degrees() < cfg.design.stop_margin_deg {
            findings.push(
                DesignIssue::NearEndStop {
                    engine_rpm: 0.0,
                    angle_deg: a.angle.to_degrees(),
                    stop_deg: stop.to_degrees(),
                    margin_deg: margin.to_degrees(),
                }
                .into(),
            );
        }
    }
    // the highest engine order (NaN without orders: every span–arm coupling is reported)
    let highest_order = cfg
        .engine
        .orders
        .iter()
        .map(|o| o.order)
        .fold(f64::NAN, f64::max);
    for &rpm in &cfg.engine.speeds_rpm {
        let (p, issues) = design_point(&drive, rpm, &cfg.design, highest_order)?;
        findings.extend(issues.into_iter().map(Finding::from));
        points.push(p);
    }
    let campbell = campbell(&drive, &cfg.engine, &cfg.design, &points[0])?;
    let errors = findings
        .iter()
        .filter(|f| f.severity == Severity::Error)
        .count();
    let warnings = findings.len() - errors;
    let layout = describe(&drive);
    let travel_direction = travel_direction(&drive);
    let wrap = match cfg.design.wrap {
        WrapModel::Creep => {
            "wrap = \"creep\": the belt held on each wrap's adhesion arc and stretching on its slip \
             arc by the capstan law (creep theory), each span an axial spring EA/L in series with \
             the slip arc it leaves, wrap_compliance_m_per_n = r |T_out − T_in|/(μ EA (T_out − \
             ρAv²)) for the linear law"
        }
        WrapModel::Held => {
            "wrap = \"held\": the belt held on the whole wrap, the spans the only springs EA/L \
             (no slip-arc compliance)"
        }
    };
    let meaning = format!(
        "Steady design of the belt drive without time stepping (drives::fead_design): {layout}. \
         Per engine speed (points): belt speed and centrifugal tension ρA v²; every pulley's \
         torque (load torque plus damper at ω = v/r, the driver supplying the sum); span \
         tensions from the torques (T_k = T_(k−1) + Q_k/r_k), their level closing the \
         unstretched belt length (and, with the tensioner, the arm's moment balance at the \
         angle that takes up the belt's stretch); each wrap's adhesion arc at the inlet and \
         slip arc at the exit by creep theory ((T_out − ρAv²)/(T_in − ρAv²) = e^(μ φ_slip)); \
         hub loads (magnitude, direction); slip margin = torque to gross slip over torque \
         carried. Modes: the linearised rotational model (free pulleys and the arm, the crank \
         held; {wrap}; held_wrap_frequencies_hz: the belt held on the whole wrap, the spans the \
         only springs EA/L, an upper bound; the belt's mass and transport are left out, so the \
         frequencies are upper bounds: on the default fead drive the flowing model's first mode \
         (κ = 40 s/m) lies 7.6 % below the creep model's 45.8 Hz, 3.1 % extrapolated to a sharp \
         friction law, 14 % below the held one's 49.4 Hz, drives/tests/fead_sweep.rs) and every \
         span's travelling-string frequencies; the coupled modes (coupled_modes: the spans' transverse \
         motion, travelling strings with their gyroscopic terms, coupled with the rotational \
         model through the tensioner arm, Beikmann, Perkins & Ulsoy 1996; each with its \
         dominant part); the Campbell diagram (campbell: rotational, separate span and coupled \
         curves) with the engine orders and their crossings. Findings: warnings and errors before any time stepping \
         (tensioner on a tight span, arm near or on a stop, slack span, gross slip, low slip \
         margin, spans coupled with the arm's mode)."
    );
    Ok(DesignSummary {
        layout,
        travel_direction,
        installation_tension_n: drive.tension(),
        belt_length_m: drive.belt_length(),
        path_length_m: drive.path().length(),
        arm_installed_angle_rad: drive.arm().map(|a| a.angle),
        arm_travel_rad: drive.arm().map(|a| a.tensioner.travel),
        pulleys: drive.names(),
        points,
        campbell,
        findings,
        errors,
        warnings,
        meaning,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use belt::{MaterialLaw, Section, Signal};
    use modes::rotational_model;

    fn two_pulley(r1: f64, r2: f64, j: f64, torque: f64, law: MaterialLaw) -> Drive {
        Layout::two_pulley(
            0.45,
            r1,
            r2,
            Signal::constant(0.0),
            j,
            Signal::constant(torque),
            Section {
                law,
                ..Section::default()
            },
            310.0,
        )
        .resolve()
        .unwrap()
    }

    // Closed form: two pulleys, the driver held, the driven pulley of inertia J and radius r
    // on two spans of length L (axial springs k = EA/L, wrap compliance not modelled):
    // J θ̈ + 2 k r² θ = 0, f = √(2 k r²/J)/(2π).
    #[test]
    fn two_pulley_rotational_mode_is_the_closed_form() {
        let (r, j) = (0.08, 0.013);
        let drive = two_pulley(0.05, r, j, 0.0, MaterialLaw::Linear);
        let s = steady_state(&drive, 0.0).unwrap();
        let l = s.geometry.spans[0].length;
        assert!((s.geometry.spans[1].length - l).abs() < 1e-12);
        let model = rotational_model(&drive, &s);
        let modes = model.modes().unwrap();
        assert_eq!(modes.len(), 1);
        let k = drive.belt().ea / l;
        let f = (2.0 * k * r * r / j).sqrt() / (2.0 * std::f64::consts::PI);
        assert!(
            (modes[0].frequency_hz / f - 1.0).abs() < 1e-6,
            "{} vs {f}",
            modes[0].frequency_hz
        );
        assert_eq!(modes[0].dominant, "driven");
    }

    // Closed form of the loaded two-pulley drive (modes module, "Wrap compliance"): driver
    // held at 300 rad/s (T_c = ρA v² ≈ 21.6 N), driven pulley (J, r), linear law, the slip arcs
    // φ_s of the statics. The driver's slip arc (its exit onto the slack span 0) adds
    // ℓ_0 = r (e^{μ φ_s,0} − 1)/μ of belt to span 0, the driven one's (its exit onto the tight
    // span 1) ℓ_1 = r (1 − e^{−μ φ_s,1})/μ to span 1: f = √((k_0 + k_1) r²/J)/(2π) with
    // k_i = EA/(L + ℓ_i). As the load → 0 the slip arcs vanish and f → √(2 EA r²/(L J))/(2π),
    // the held wrap's closed form, with a gap proportional to the load (ℓ ∝ φ_s ∝ Q).
    #[test]
    fn two_pulley_creep_mode_is_the_series_spring_closed_form() {
        let (r, j, w) = (0.05, 0.013, 300.0);
        let mut gaps = Vec::new();
        for q in [8.0, 0.8, 0.08] {
            let drive = two_pulley(r, r, j, q, MaterialLaw::Linear);
            let s = steady_state(&drive, w).unwrap();
            assert!(!s.wraps.iter().any(WrapState::gross_slip));
            assert!(
                s.wraps[1].tension_out > s.wraps[1].tension_in,
                "driven: tight exit"
            );
            let mu = drive.contact().friction.coefficient();
            let (ea, l) = (drive.belt().ea, s.geometry.spans[0].length);
            let l0 = r * ((mu * s.wraps[0].slip_arc).exp() - 1.0) / mu;
            let l1 = r * (1.0 - (-mu * s.wraps[1].slip_arc).exp()) / mu;
            let k = ea / (l + l0) + ea / (l + l1);
            let f = (k * r * r / j).sqrt() / (2.0 * std::f64::consts::PI);
            let modes = rotational_model(&drive, &s).modes().unwrap();
            assert!(
                (modes[0].frequency_hz / f - 1.0).abs() < 1e-6,
                "{q} N m: {} vs {f}",
                modes[0].frequency_hz
            );
            let held = (2.0 * ea / l * r * r / j).sqrt() / (2.0 * std::f64::consts::PI);
            let gap = 1.0 - modes[0].frequency_hz / held;
            assert!(gap > 0.0);
            gaps.push(gap / q);
        }
        // gap per load: constant to first order in the load (measured 0.00332, 0.00320,
        // 0.00321 per N m), so the gap vanishes with the load: 2.6e-4 at 0.08 N m
        assert!((gaps[2] / gaps[0] - 1.0).abs() < 0.15, "{gaps:?}");
        assert!((gaps[2] / gaps[1] - 1.0).abs() < 0.01, "{gaps:?}");
        assert!(gaps[2] * 0.08 < 3e-4, "{gaps:?}");
    }

    // The slip arc's compliance by a second route: the extension of the belt on the slip arc
    // E(δ) = ∫ (λ(T_δ(ψ)) − 1) r dψ, with the perturbed profile of the modes module
    // T_δ = T_c + (T(ψ) − T_c)(T_out + δ − T_c)/(T_out − T_c) and the section's stretch λ(T)
    // (St Venant–Kirchhoff: the law inverted, not its tangent stiffness), differenced
    // centrally over δ = ±1 N and integrated by the trapezoidal rule on 4000 intervals; on
    // the default drive at 1500 rpm (every loaded wrap).
    #[test]
    fn slip_arc_compliance_is_the_derivative_of_its_extension() {
        let cfg = DesignConfig::default();
        let drive = cfg.drive.resolve().unwrap();
        assert_eq!(drive.belt().law, MaterialLaw::StVenantKirchhoff);
        let s = steady_state(&drive, 1500.0 * std::f64::consts::PI / 30.0).unwrap();
        let tc = s.centrifugal;
        let mut checked = 0;
        for (k, w) in s.wraps.iter().enumerate() {
            let r = drive.pulleys()[k].radius;
            let c = w.exit_compliance(r, tc, drive.belt());
            if w.slip_arc == 0.0 {
                assert_eq!(c, 0.0);
                continue;
            }
            let a = w.wrap - w.slip_arc;
            let ext = |d: f64| {
                let n = 4000;
                let h = w.slip_arc / n as f64;
                (0..=n)
                    .map(|i| {
                        let t = w.tension_at(a + i as f64 * h, tc);
                        let t = tc + (t - tc) * (w.tension_out + d - tc) / (w.tension_out - tc);
                        let wt = if i == 0 || i == n { 0.5 } else { 1.0 };
                        wt * (drive.belt().stretch(t) - 1.0) * r * h
                    })
                    .sum::<f64>()
            };
            let fd = 0.5 * (ext(1.0) - ext(-1.0));
            assert!(
                (c / fd - 1.0).abs() < 1e-6,
                "{}: {c} vs {fd}",
                drive.names()[k]
            );
            checked += 1;
        }
        assert!(checked >= 4, "{checked} loaded wraps");
    }

    // Invariants of the wrap models on the default drive at 1500 rpm: the creep model's spans
    // are the held model's springs in series with a compliance, so K_creep ≤ K_held (Loewner
    // order) and every creep frequency lies at or below the held one (Courant–Fischer), the
    // first strictly (the loaded wraps have slip arcs); `held_wrap_frequencies_hz` is the held
    // model's; with `wrap = "held"` the rotational modes are those frequencies and every span's
    // series stiffness is its EA_t/L.
    #[test]
    fn creep_wrap_frequencies_lie_below_the_held_ones() {
        let mut cfg = DesignConfig::default();
        let drive = cfg.drive.resolve().unwrap();
        let (p, _) = design_point(&drive, 1500.0, &cfg.design, f64::NAN).unwrap();
        assert_eq!(p.wrap_model, "creep");
        let creep: Vec<f64> = p.rotational_modes.iter().map(|m| m.frequency_hz).collect();
        assert_eq!(creep.len(), p.held_wrap_frequencies_hz.len());
        for (c, h) in creep.iter().zip(&p.held_wrap_frequencies_hz) {
            assert!(c <= &(h * (1.0 + 1e-12)), "{c} vs {h}");
        }
        assert!(creep[0] < 0.99 * p.held_wrap_frequencies_hz[0]);
        assert!(p.spans.iter().any(|sp| sp.wrap_compliance_m_per_n > 0.0));
        cfg.design.wrap = WrapModel::Held;
        let (h, _) = design_point(&drive, 1500.0, &cfg.design, f64::NAN).unwrap();
        assert_eq!(h.wrap_model, "held");
        let held: Vec<f64> = h.rotational_modes.iter().map(|m| m.frequency_hz).collect();
        assert_eq!(held, p.held_wrap_frequencies_hz);
        assert_eq!(h.held_wrap_frequencies_hz, held);
        for sp in &h.spans {
            assert_eq!(sp.wrap_compliance_m_per_n, 0.0);
            assert!((sp.series_stiffness_n_per_m / sp.stiffness_n_per_m - 1.0).abs() < 1e-12);
        }
    }

    // Closed forms of the two-pulley drive with equal radii, the linear law, at rest, under a
    // load torque Q on the driven pulley: T_t − T_s = Q/r (torque balance), (T_t + T_s)/2 = T0
    // within 1e-3 (mean-tension model, equal wraps: the slip arcs carry the logarithmic mean
    // of T_t and T_s, a little below the arithmetic one, which lifts both by 0.04 N), the driven wrap's
    // slip arc ln(T_t/T_s)/μ (Euler–Eytelwein), and the driver's torque −Q (driver supplies
    // the sum).
    #[test]
    fn two_pulley_statics_are_the_closed_form() {
        let (r, q) = (0.05, 4.0);
        let drive = two_pulley(r, r, 0.013, q, MaterialLaw::Linear);
        let s = steady_state(&drive, 0.0).unwrap();
        let (ts, tt) = (s.tensions[0], s.tensions[1]);
        assert!(((tt - ts) - q / r).abs() < 1e-9, "{tt} {ts}");
        assert!((0.5 * (tt + ts) / 310.0 - 1.0).abs() < 1e-3, "{tt} {ts}");
        let mu = drive.contact().friction.coefficient();
        assert!((s.wraps[1].slip_arc - (tt / ts).ln() / mu).abs() < 1e-12);
        assert!((s.loading.torques[0] + q).abs() < 1e-12);
        assert!(!s.slack && !s.wraps.iter().any(WrapState::gross_slip));
        // a torque beyond the Euler–Eytelwein capacity of the mounted tension (μ = 0.3:
        // capacity 2 T0 (e^{μπ} − 1)/(e^{μπ} + 1) r with T_t + T_s = 2 T0) is gross slip
        let mu = 0.3;
        let e = (mu * std::f64::consts::PI).exp();
        let cap = 2.0 * 310.0 * (e - 1.0) / (e + 1.0) * r;
        let slipping = |torque: f64| {
            let mut l = two_pulley(r, r, 0.013, torque, MaterialLaw::Linear)
                .layout()
                .clone();
            l.contact.friction = contact::friction::FrictionSpec::Tanh { mu, kappa: 40.0 };
            let drive = l.resolve().unwrap();
            let s = steady_state(&drive, 0.0).unwrap();
            state_issues(&drive, &s, 1000.0)
        };
        let issues = slipping(1.05 * cap);
        assert!(
            issues
                .iter()
                .any(|i| matches!(i, DesignIssue::GrossSlip { pulley, .. } if pulley == "driven")),
            "{issues:?}"
        );
        assert!(slipping(0.95 * cap).is_empty());
    }

    // Ribs (item 3): with 40° ribs the grooved wraps hold μ/sin 20°, the flat back side μ; the
    // capacity (T_s − T_c)(e^{μ_eff φ} − 1) r of each wrap follows (closed form from the
    // solved tensions and wraps).
    #[test]
    fn ribs_raise_the_capacity_of_grooved_wraps_only() {
        let mut cfg = DesignConfig::default();
        cfg.drive.belt.ribs = Some(belt::Ribs {
            count: 5,
            wedge_angle: 40f64.to_radians(),
        });
        let drive = cfg.drive.resolve().unwrap();
        let (p, _) = design_point(&drive, 1500.0, &cfg.design, f64::NAN).unwrap();
        let mu = drive.contact().friction.coefficient();
        for (pl, pulley) in p.pulleys.iter().zip(drive.pulleys()) {
            let eff = match pulley.side {
                WrapSide::Inside => mu / 20f64.to_radians().sin(),
                WrapSide::Outside => mu,
            };
            assert!((pl.friction_coefficient - eff).abs() < 1e-12, "{}", pl.name);
            let ts = pl.tension_in_n.min(pl.tension_out_n) - p.centrifugal_tension_n;
            let cap = ts * ((eff * pl.wrap_deg.to_radians()).exp() - 1.0) * pulley.radius;
            assert!((pl.capacity_n_m / cap - 1.0).abs() < 1e-12, "{}", pl.name);
        }
        let per_rib = p.tight_tension_per_rib_n.unwrap();
        assert!(
            (per_rib * 5.0 - p.spans.iter().map(|s| s.tension_n).fold(0.0, f64::max)).abs() < 1e-9
        );
    }

    // The findings' triggers: the default drive's tensioner follows the alternator, on a
    // span tighter than the loop's mean (drives::fead's documentation: the slack span is
    // crank → power steering); with the only load on the pulley before the crank the spans
    // from the crank to it carry the lower tension and the arm is on the slack side. A travel
    // ending 2° above the installed angle is flagged near its stop, at rest (rpm 0) and under
    // load.
    // The span–arm coupling finding stands where an engine order reaches it (its documentation):
    // the default drive's alternator → tensioner span (about 550 Hz at 1500 rpm) lies within
    // 10 % of an arm mode (about 516 Hz) that the default orders 2 and 4 (50 and 100 Hz) never
    // reach: no finding; an order 24 (600 Hz) reaches it, and without orders it is reported.
    #[test]
    fn span_arm_coupling_only_where_an_order_reaches_it() {
        let couplings = |cfg: &DesignConfig| -> Vec<(f64, f64)> {
            run_design(cfg)
                .unwrap()
                .findings
                .into_iter()
                .filter_map(|f| match f.issue {
                    DesignIssue::SpanArmCoupling {
                        span_hz, mode_hz, ..
                    } => Some((span_hz, mode_hz)),
                    _ => None,
                })
                .collect()
        };
        let mut cfg = DesignConfig::default();
        cfg.engine.speeds_rpm = vec![1500.0];
        cfg.design.campbell_points = 2;
        assert!(couplings(&cfg).is_empty(), "{:?}", couplings(&cfg));
        cfg.engine.orders.push(crate::fead::EngineOrder {
            order: 24.0,
            amplitude: 0.001,
            phase: 0.0,
        });
        let reached = couplings(&cfg);
        assert_eq!(reached.len(), 1, "{reached:?}");
        let (span, mode) = reached[0];
        assert!((span / mode - 1.0).abs() <= 0.1 && span.min(mode) <= 24.0 * 25.0 * 1.1);
        cfg.engine.orders.clear();
        assert_eq!(couplings(&cfg), reached);
    }

    #[test]
    fn tight_span_and_end_stop_findings() {
        let kinds = |cfg: &DesignConfig| -> Vec<DesignIssue> {
            run_design(cfg)
                .unwrap()
                .findings
                .into_iter()
                .map(|f| f.issue)
                .collect()
        };
        let mut cfg = DesignConfig::default();
        cfg.engine.speeds_rpm = vec![1500.0];
        cfg.design.campbell_points = 2;
        let tight = |i: &DesignIssue| matches!(i, DesignIssue::TensionerOnTightSpan { .. });
        assert!(kinds(&cfg).iter().any(tight));
        let mut slack = cfg.clone();
        for p in &mut slack.drive.pulleys[1..5] {
            if let Motion::Load { torque, .. } = &mut p.motion {
                *torque = belt::Signal::constant(0.0);
            }
        }
        assert!(!kinds(&slack).iter().any(tight), "{:?}", kinds(&slack));
        let mut near = cfg.clone();
        let installed = cfg.drive.resolve().unwrap().arm().unwrap().angle;
        near.drive.tensioner.as_mut().unwrap().travel[1] = installed + 2f64.to_radians();
        let stops: Vec<f64> = kinds(&near)
            .iter()
            .filter_map(|i| match i {
                DesignIssue::NearEndStop { engine_rpm, .. } => Some(*engine_rpm),
                _ => None,
            })
            .collect();
        assert_eq!(stops, vec![0.0, 1500.0]);
    }

    // Campbell diagram: every crossing lies on its order line, f = k·rpm/60, and on its curve
    // recomputed at that speed (to the root finder's 0.01 rpm); the spans' first frequency is
    // the travelling string's by hand, f₁ = (1 − v²/c²) c/(2L), c = √(T/ρA) (Wickert & Mote
    // 1990), the second twice it.
    #[test]
    fn campbell_crossings_lie_on_both_curves() {
        let cfg = DesignConfig::default();
        let drive = cfg.drive.resolve().unwrap();
        let s = run_design(&cfg).unwrap();
        assert!(!s.campbell.crossings.is_empty());
        for x in &s.campbell.crossings {
            let c = s
                .campbell
                .curves
                .iter()
                .position(|cv| cv.name == x.curve)
                .unwrap();
            assert!((x.frequency_hz - x.order * x.engine_rpm / 60.0).abs() < 1e-9);
            let f = curve_values(&drive, x.engine_rpm, &cfg.design).unwrap()[c].unwrap();
            let residual = (f - x.order * x.engine_rpm / 60.0).abs();
            assert!(
                residual < 0.01 * x.order / 60.0 + 1e-6,
                "{}: {f} vs {}",
                x.curve,
                x.frequency_hz
            );
        }
        let p = &s.points[0];
        let rho = drive.belt().mass_per_length;
        for sp in &p.spans {
            let c = (sp.tension_n / rho).sqrt();
            let v = p.belt_speed_m_per_s;
            let f1 = (1.0 - v * v / (c * c)) * c / (2.0 * sp.length_m);
            let got = sp.modes.frequencies_hz[0].unwrap();
            assert!((got / f1 - 1.0).abs() < 1e-12, "{} → {}", sp.from, sp.to);
            assert!((sp.modes.frequencies_hz[1].unwrap() / got - 2.0).abs() < 1e-12);
        }
    }

    // Fixed centres: the path and the belt length fix the stretch, so the running belt keeps
    // its total tension T0 and the centrifugal tension ρA v² comes off the pressure T − ρAv²
    // (closed form of the fixed-centre drive).
    #[test]
    fn fixed_centre_drive_keeps_its_tension_at_speed() {
        let drive = two_pulley(0.05, 0.05, 0.013, 0.0, MaterialLaw::StVenantKirchhoff);
        let s = steady_state(&drive, 400.0).unwrap();
        let tc = drive.belt().mass_per_length * (400.0f64 * 0.05).powi(2);
        assert!((s.centrifugal - tc).abs() < 1e-12);
        for t in &s.tensions {
            assert!((t / 310.0 - 1.0).abs() < 1e-9, "{t}");
        }
    }

    // The default FEAD at 1500 rpm: invariants (independent of the traverse that built the
    // tensions): every free pulley carries −applied_torque of its motion at ω = v/r; the
    // pulley powers sum to zero (power balance, no creep); the hub loads of a closed belt sum
    // to zero (the belt as a free body: Σ_k [(T_k − T_c) d_k − (T_(k−1) − T_c) d_(k−1)] = 0);
    // the arm's moments balance (spring + (c − p) × F_idler = 0); at rest without loads the
    // arm angle is the layout's (found by bisection in belt::Layout::resolve) and every span
    // carries the installation tension.
    #[test]
    fn default_fead_invariants() {
        let cfg = DesignConfig::default();
        let drive = cfg.drive.resolve().unwrap();
        let (p, _) = design_point(&drive, 1500.0, &cfg.design, f64::NAN).unwrap();
        for (k, pl) in p.pulleys.iter().enumerate() {
            let m = &drive.pulleys()[k].motion;
            if m.is_free() {
                let q = -m.applied_torque(1e3, pl.speed_rad_per_s).0;
                assert!((pl.torque_n_m - q).abs() < 1e-9, "{}: {}", pl.name, q);
            }
        }
        assert!(p.power_residual_w.abs() < 1e-9 * p.driver_power_w);
        let sum = p.pulleys.iter().fold([0.0, 0.0], |a, x| {
            [a[0] + x.hub_load_n[0], a[1] + x.hub_load_n[1]]
        });
        assert!(sum[0].hypot(sum[1]) < 1e-9 * 400.0, "{sum:?}");
        let arm = p.arm.as_ref().unwrap();
        let spec = drive.arm().unwrap().tensioner;
        let len = drive.arm().unwrap().length;
        let c = spec.center(len, arm.angle_rad).0;
        let lever = [c[0] - spec.pivot[0], c[1] - spec.pivot[1]];
        let m = arm.spring_moment_n_m + belt::tensioner::cross(lever, arm.idler_force_n);
        assert!(m.abs() < 1e-8, "arm moment residual {m}");
        // at rest without loads: the layout's statics
        let mut rest = cfg.drive.clone();
        for p in &mut rest.pulleys {
            p.motion = p.motion.at_rest();
        }
        let drive = rest.resolve().unwrap();
        let s = steady_state(&drive, 0.0).unwrap();
        assert!((s.arm_angle.unwrap() - drive.arm().unwrap().angle).abs() < 1e-9);
        for t in &s.tensions {
            assert!((t / 400.0 - 1.0).abs() < 1e-9, "{t}");
        }
    }
}
