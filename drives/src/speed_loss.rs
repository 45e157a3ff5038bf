//! The speed-loss procedure of Ribaric §6.4–6.5, for any belt-drive model.
//!
//! 1. Start from the static equilibrium of the mounted, pre-tensioned belt at rest;
//! 2. spin the driver up to `ω₁` along a smooth ramp (the driven pulley follows through the belt);
//! 3. for each load torque in turn: ramp the load on the driven pulley smoothly to the next value,
//!    then hold it until the speed loss `Δω = ω₁ − ω₂`, averaged over consecutive windows, changes
//!    by less than the tolerance between two windows (steady state, seed-000 note U14); record the
//!    last window's mean. For a belt whose mesh travels with the material (the nodal and ANCF
//!    belts) the means are over whole loop passages, taken a window apart ([`averaging_steps`]).
//!
//! The load schedule is extended while integrating, so each torque is held only as long as it
//! needs. A failure keeps the points already found ([`SweepFailure`]).

use crate::simulation::BeltSimulation;
use belt::report::sliding_speed;
use belt::{BeltModel, Report, Signal, WrapPoint};
use contact::friction::{FrictionLaw, FrictionSpec};
use mbd_core::MbdError;
use mbd_core::integrators::{AlphaConfig, State};
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};

/// Settings of the procedure (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct SpeedLossConfig {
    /// Driver speed ω₁ \[rad/s\] (Ribaric Figs. 6-6, 6-7: 62.8 and 22.6).
    pub omega_driver: f64,
    /// Load torques on the driven pulley \[N m\], applied in this order.
    pub torques: Vec<f64>,
    /// Duration of the driver's spin-up ramp \[s\].
    pub spin_up: f64,
    /// Duration of each load ramp \[s\].
    pub torque_ramp: f64,
    /// Length of the averaging window \[s\] (for a belt whose mesh travels with the
    /// material, the interval between the compared means over whole loop passages,
    /// [`averaging_steps`]).
    pub window: f64,
    /// Steady when consecutive window means differ by less than this \[rad/s\].
    pub tolerance: f64,
    /// Give up on a torque (error) after holding it this long \[s\].
    pub max_hold: f64,
    /// Generalized-α step \[s\].
    pub step: f64,
    /// Generalized-α spectral radius at infinity \[-\].
    pub rho_inf: f64,
}

impl Default for SpeedLossConfig {
    fn default() -> Self {
        Self {
            omega_driver: 62.8,
            torques: vec![0.0, 2.0, 4.0, 6.0, 8.0, 10.0],
            spin_up: 0.3,
            torque_ramp: 0.1,
            window: 0.05,
            tolerance: 2e-4,
            max_hold: 2.0,
            step: 2.5e-4,
            rho_inf: 0.6,
        }
    }
}

impl Validate for SpeedLossConfig {
    /// Every field checked; the error names the field (path relative to this struct).
    fn validate(&self) -> Result<(), InvalidField> {
        let pos = [
            ("spin_up", self.spin_up),
            ("torque_ramp", self.torque_ramp),
            ("window", self.window),
            ("tolerance", self.tolerance),
            ("max_hold", self.max_hold),
            ("step", self.step),
        ];
        for (name, v) in pos {
            if !(v.is_finite() && v > 0.0) {
                return Err(InvalidField::new(
                    name,
                    format!("must be finite and > 0 (got {v})"),
                ));
            }
        }
        if !self.omega_driver.is_finite() {
            return Err(InvalidField::new("omega_driver", "must be finite"));
        }
        if self.torques.is_empty() {
            return Err(InvalidField::new(
                "torques",
                "give at least one load torque",
            ));
        }
        if let Some(i) = self.torques.iter().position(|t| !t.is_finite()) {
            return Err(InvalidField::new(format!("torques[{i}]"), "must be finite"));
        }
        if !(0.0..=1.0).contains(&self.rho_inf) {
            return Err(InvalidField::new("rho_inf", "must lie in [0, 1]"));
        }
        if self.window < 10.0 * self.step {
            return Err(InvalidField::new("window", "must span at least 10 steps"));
        }
        if self.max_hold < 2.0 * self.window {
            return Err(InvalidField::new(
                "max_hold",
                format!(
                    "must allow at least two averaging windows (2 × window = {} s), got {} s",
                    2.0 * self.window,
                    self.max_hold
                ),
            ));
        }
        let run = self.spin_up + self.torques.len() as f64 * (self.torque_ramp + self.max_hold);
        if run / self.step > MAX_STEPS as f64 {
            return Err(InvalidField::new(
                "step",
                format!(
                    "the procedure could take {:.3e} steps (max {MAX_STEPS}): lengthen the step or shorten max_hold",
                    run / self.step
                ),
            ));
        }
        Ok(())
    }
}

/// Most steps the procedure may take (spin-up plus every torque held for `max_hold`).
pub const MAX_STEPS: usize = 20_000_000;

/// What the procedure needs to know about a model's belt.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeltData {
    /// Installation tension T0 of the mounted belt \[N\].
    pub pretension: f64,
    /// Axial stiffness EA \[N\].
    pub ea: f64,
    /// Radius of the driven pulley's belt line \[m\].
    pub driven_radius: f64,
    /// The friction law on the driven pulley's wrap ([`belt::Drive::wrap_friction_law`]:
    /// `μ/sin(β/2)` for a multi-ribbed belt in a grooved pulley).
    pub friction: FrictionSpec,
    /// Whether the model is linearised about the installation tension ([`belt::ModelTraits`]).
    pub linearised: bool,
    /// Whether the model's contact slip follows its elements' strain
    /// ([`belt::ModelTraits::near_coulomb_creep`]).
    pub near_coulomb_creep: bool,
}

impl BeltData {
    /// The data of `model`'s belt with the driven pulley `driven`.
    pub fn of(model: &impl BeltModel, driven: usize) -> Self {
        let d = model.drive();
        Self {
            pretension: d.tension(),
            ea: d.belt().ea,
            driven_radius: d.pulleys()[driven].radius,
            friction: d.wrap_friction_law(driven),
            linearised: model.traits().linearised,
            near_coulomb_creep: model.traits().near_coulomb_creep,
        }
    }
}

/// Where and when a pulley slipped as a whole (gross slip): the load exceeded what friction
/// can transmit ([`belt::report`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GrossSlip {
    /// Pulley index (travel order).
    pub pulley: usize,
    /// Pulley name.
    pub name: String,
    /// Simulation time of the detection \[s\].
    pub time: f64,
    /// The criterion that fired, with its figures.
    pub criterion: String,
}

/// One operating point: a steady state, or the gross slip that prevented it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeedLossPoint {
    /// Load torque \[N m\].
    pub torque: f64,
    /// Steady speed loss ω₁ − ω₂ \[rad/s\] (mean over the last averaging span,
    /// [`averaging_steps`]: the last window, or the last whole loop passages of a belt whose mesh
    /// travels with the material); at a gross slip
    /// detected while the driven pulley runs away, the (unsteady) value at detection.
    pub delta_omega: f64,
    /// Steady driven speed \[rad/s\].
    pub omega_driven: f64,
    /// Difference of the last two means \[rad/s\] (over the last averaging span and over the
    /// one a window earlier, [`averaging_steps`]; steady-state residual; `None` when the point
    /// ended in a runaway gross slip).
    pub drift: Option<f64>,
    /// Simulation time at which the point was taken \[s\].
    pub time: f64,
    /// Time from the end of the load ramp to the point \[s\]: how long the drive settled
    /// until two consecutive window means agreed (`SpeedLossConfig::tolerance`).
    pub settled_s: f64,
    /// The gross slip, if the load exceeded the capacity.
    pub gross_slip: Option<GrossSlip>,
    /// Why the results of a model linearised about T0 ([`BeltData::linearised`]) do not hold
    /// at this point (`None`: they hold, or the model is not linearised).
    pub linearisation: Option<String>,
    /// Why the speed loss may understate the creep at this point ([`creep_caveat`]; `None`:
    /// no reason known).
    pub caveat: Option<String>,
    /// What the point's balances say when they miss [`belt::BALANCE_TOLERANCE`]
    /// ([`balance_note`]); `None` within it. The numbers are given.
    pub balance: Option<String>,
    /// Spans and pulleys at the point (vibration amplitudes over the last window).
    pub report: Report,
    /// The contact points of every wrap at the point.
    #[serde(skip)]
    pub wrap: Vec<WrapPoint>,
}

/// Slack-span tension below which a model linearised about T0 no longer describes the belt,
/// as a fraction of T0: the slack span's transverse stiffness `T/L` is then below a tenth of
/// the linearised `T0/L` built into `K_g(T0)`, and a little more load makes the linear tension
/// `T0 + EA Δl/l` negative — a compressed belt, which a real belt cannot carry.
pub const LINEAR_MIN_SLACK: f64 = 0.1;

/// Largest tension ratio `T_max/T0` at which a model linearised about T0 has been shown to
/// hold: 2.5. Evidence: with the co-rotated axial force the flowing model's span tensions, speeds
/// and balances agree with the unlinearised ANCF belt on Table 6-1 up to 42 N m (tight span
/// about 2.4 T0) and with Exudyn's ANCF cable on the Pechstein–Gerstmayr drive (1.66 T0)
/// within 1 % (BENCHMARKS.md); beyond it the modal basis built about the mounted state is not
/// checked.
pub const LINEAR_MAX_TENSION_RATIO: f64 = 2.5;

/// Largest belt strain `T_max/EA` (from the unstretched belt) at which a model linearised about
/// T0 has been shown to hold: 0.1 (the Pechstein–Gerstmayr tight span carries 8.7 %, agreeing
/// with Exudyn's cable within 1 %).
pub const LINEAR_MAX_STRAIN: f64 = 0.1;

/// Utilisation of the friction law at which the runaway bound of [`gross_slip_bound`] is set.
pub const RUNAWAY_UTILISATION: f64 = 0.999;

/// The runaway test of [`speed_loss_sweep`] compares the running mean of the speed loss over
/// the current window with [`gross_slip_bound`] once it spans `1 / RUNAWAY_MIN_FRACTION` of
/// the window (a quarter), not single steps.
pub const RUNAWAY_MIN_FRACTION: usize = 4;

/// Speed loss \[rad/s\] above which the driven pulley has left every steady state the belt can
/// hold at driver speed `omega` \[rad/s\] (runaway gross slip): the elastic creep of a belt
/// transmitting its largest tension difference `2 T0` (slack span at zero),
/// `ω · 2T0/EA`, plus sliding on both wraps at the speed where the friction law reaches
/// [`RUNAWAY_UTILISATION`] of μ ([`sliding_speed`]), over the driven radius.
pub fn gross_slip_bound(belt: &BeltData, omega: f64) -> f64 {
    let creep = omega.abs() * 2.0 * belt.pretension / belt.ea;
    creep + 2.0 * sliding_speed(&belt.friction, RUNAWAY_UTILISATION) / belt.driven_radius
}

/// The linearisation check of a model linearised about T0 ([`BeltData::linearised`]): `None`
/// while the slack span keeps [`LINEAR_MIN_SLACK`] of T0, the tight span stays within
/// [`LINEAR_MAX_TENSION_RATIO`] of T0 and [`LINEAR_MAX_STRAIN`], and no wrap slides as a whole.
pub fn linearisation_issue(belt: &BeltData, report: &Report) -> Option<String> {
    if !belt.linearised {
        return None;
    }
    let slack = report.tension_slack();
    let t0 = belt.pretension;
    let tight = report
        .spans
        .iter()
        .map(|s| s.tension_n)
        .fold(report.tension_tight(), f64::max);
    if let Some(why) = tension_range_issue(tight, t0, belt.ea) {
        return Some(why);
    }
    // NaN (no sample over a span) also counts as "not taut".
    if slack.is_nan() || slack < LINEAR_MIN_SLACK * t0 {
        return Some(format!(
            "slack-span tension {slack:.1} N is below {:.0} % of T0 = {t0} N: the model's \
             stiffness K_e + K_g(T0) and tension T0 + EA·Δl/l assume taut spans",
            100.0 * LINEAR_MIN_SLACK
        ));
    }
    if let Some(p) = report.gross_slip() {
        let r = &report.pulleys[p];
        return Some(format!(
            "friction saturated over the whole wrap of pulley '{}' (adhesion arc {:.3} of \
             {:.3} rad): the belt slides, outside the linearised creep regime",
            r.name, r.adhesion_arc_rad, r.contact_arc_rad
        ));
    }
    None
}

/// The caveat of a model whose contact slip does not follow its elements' strain
/// ([`BeltData::near_coulomb_creep`] false: the flowing belt with Ribaric's contact rates,
/// `flowing::belt::ContactVelocity::Ribaric`) at a point whose friction law is sharper than the
/// elastic creep: the law's transition width ([`contact::friction::FrictionLaw::transition_width`];
/// zero for a law without one) below the creep speed `ω₂ R₂ (T_tight − T_slack)/EA` of the
/// point (Grashof) \[m/s\], `omega_driven` \[rad/s\]. There the contact nodes at the tangent
/// points slide by their rates' error and the speed loss falls short of the creep (on Table
/// 6-1 at 10 N m with a 0.05 mm/s law by 31 % on the default mesh, BENCHMARKS.md); `None`
/// otherwise (Ribaric's κ = 40 s/m on Table 6-1: 25 mm/s against 4 mm/s).
pub fn creep_caveat(belt: &BeltData, report: &Report, omega_driven: f64) -> Option<String> {
    let creep = omega_driven.abs()
        * belt.driven_radius
        * (report.tension_tight() - report.tension_slack()).abs()
        / belt.ea;
    creep_caveat_for(belt.near_coulomb_creep, &belt.friction, creep)
}

/// [`creep_caveat`] for a model with [`BeltData::near_coulomb_creep`] `near`, the friction law
/// `law` and the creep speed `creep` \[m/s\] (a FEAD point: the belt speed times the largest
/// tension change over a wrap, over EA).
pub fn creep_caveat_for(near: bool, law: &FrictionSpec, creep: f64) -> Option<String> {
    if near {
        return None;
    }
    let width = law.transition_width().unwrap_or(0.0);
    (width < creep).then(|| {
        format!(
            "the friction law's transition width {width:.2e} m/s is below the elastic creep \
             speed {creep:.2e} m/s: with Ribaric's contact rates (T_,s) the contact nodes at \
             the tangent points slide by their rates' error and the speed loss may understate \
             the creep (31 % near Coulomb on Table 6-1's default mesh); [models.flowing] \
             contact_velocity = \"chord\" with viscous_force = \"chord\" follows the strain \
             (the defaults, \"auto\", take them with any law but Ribaric's kappa law)"
        )
    })
}

/// The upper end of the linearised models' range ([`LINEAR_MAX_TENSION_RATIO`],
/// [`LINEAR_MAX_STRAIN`]) for the largest span tension `tight` \[N\], mounting tension `t0`
/// \[N\] and axial stiffness `ea` \[N\]; `None` inside it.
pub fn tension_range_issue(tight: f64, t0: f64, ea: f64) -> Option<String> {
    if tight > LINEAR_MAX_TENSION_RATIO * t0 {
        return Some(format!(
            "tight-span tension {tight:.1} N is {:.2} T0 (T0 = {t0} N), above the {} T0 up to \
             which the model linearised about T0 has been checked against unlinearised belts",
            tight / t0,
            LINEAR_MAX_TENSION_RATIO
        ));
    }
    if tight > LINEAR_MAX_STRAIN * ea {
        return Some(format!(
            "tight-span strain {:.1} % (T = {tight:.1} N, EA = {ea} N) is above the {:.0} % up \
             to which the model linearised about T0 has been checked against unlinearised belts",
            100.0 * tight / ea,
            100.0 * LINEAR_MAX_STRAIN
        ));
    }
    None
}

/// Largest torque or power balance residual \[-\] ([`belt::Balances`]: the torque each pulley
/// carries against `Σ(T_in − T_out) r` of its spans, the power the drivers deliver against the
/// loads, damping and sliding) at which a linearised model's operating point still counts as
/// valid. The flowing belt misses the balances by a few per cent on drives with small or
/// back-side pulleys (torque 1.9 %, 4.4 %, 9.8 % at 800, 1500, 2500 rpm on the default `fead`
/// drive, BENCHMARKS.md, with the spans' moments taken about the belt-line radius; 1.5 % at
/// 800 rpm about their lines of action, [`belt::report`]; 38 % on a three-pulley drive with a
/// back-side idler, issue 34); beyond
/// this its tensions do not carry the pulley torques and the point is flagged.
pub const BALANCE_LIMIT: f64 = 0.05;

/// Why a linearised model's point is not valid by its balances ([`BALANCE_LIMIT`]), or `None`.
pub fn balance_issue(b: &belt::Balances) -> Option<String> {
    b.beyond(BALANCE_LIMIT).map(|miss| {
        format!(
            "balances: {miss}: the spans' tensions do not carry the pulley torques; the \
             linearised flowing model misses the balances on small or back-side pulleys: check \
             with the nodal or ANCF model"
        )
    })
}

/// What a point's balances say when they miss [`belt::BALANCE_TOLERANCE`] (0.5 %), or `None`;
/// the point's numbers are given (beyond [`BALANCE_LIMIT`] a linearised model's point is
/// invalid instead, [`balance_issue`]). `defect` is the model's known cause
/// ([`belt::ModelTraits::balance_defect`]).
pub fn balance_note(defect: Option<&str>, b: &belt::Balances) -> Option<String> {
    b.beyond(belt::BALANCE_TOLERANCE).map(|miss| {
        let cause = defect.map_or(String::new(), |d| format!("; {d}"));
        format!("balances: {miss}: the model's numbers carry an error of that order{cause}")
    })
}

/// Integration statistics of a sweep.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct SweepStats {
    /// Simulated time \[s\].
    pub simulated_time: f64,
    /// Steps taken.
    pub steps: usize,
    /// Newton iterations.
    pub newton_iterations: usize,
    /// Force evaluations.
    pub force_evaluations: usize,
}

impl SweepStats {
    fn add(&mut self, s: &mbd_core::integrators::Stats) {
        self.steps += s.steps;
        self.newton_iterations += s.newton_iterations;
        self.force_evaluations += s.force_evaluations;
    }
}

/// A failed sweep with the points found before the failure.
#[derive(Debug, Clone)]
pub struct SweepFailure {
    /// What failed.
    pub error: MbdError,
    /// Points already found.
    pub points: Vec<SpeedLossPoint>,
}

/// One sample of the time history handed to the observer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time \[s\].
    pub t: f64,
    /// Driver speed \[rad/s\].
    pub omega_driver: f64,
    /// Driven speed \[rad/s\].
    pub omega_driven: f64,
    /// Load torque \[N m\].
    pub load: f64,
    /// Belt speed \[m/s\] ([`BeltModel::belt_speed`]).
    pub belt_speed: f64,
    /// Steady points found so far.
    pub points: usize,
}

/// Subdivision levels of the belt procedures' steps ([`AlphaConfig::subdivisions`]): a step
/// whose Newton iteration fails is retaken by mbd-core's stepper as two halves, recursively up
/// to this many levels, ending on the procedure's time grid. The rotating-mesh model
/// ([`flowing::belt::nodal::NodalBelt`]) needs it when a coarse element lands on a pulley.
pub const STEP_SUBDIVISIONS: usize = 4;

/// Line-search trial steps of the flowing and nodal belts' Newton iteration
/// ([`AlphaConfig::newton_line_search_trials`]: `1, ½, …, 1/4096`). With the sharp friction
/// law (`tanh_slip` at 0.05 mm/s) the Newton correction moves slip velocities by far more than
/// `v_s`; with mbd-core's 5 trials the full-step fallback throws the iterate onto the opposite
/// saturated branch of tanh and the default FEAD drive fails at t = 0.061 s of its first ramp
/// even with [`STEP_SUBDIVISIONS`] levels (8 levels: t = 0.063 s); with 13 it runs (issue 34
/// item 3, BENCHMARKS.md "friction regularisation"). At Ribaric's κ = 40 s/m no iteration
/// needs more than 5 trials (the default FEAD drive at 800 rpm: the same means to all digits).
pub const BELT_LINE_SEARCH_TRIALS: usize = 13;

/// Newton iterations per step of the flowing and nodal belts
/// ([`AlphaConfig::max_newton_iterations`]): a backtracked iteration progresses in short steps
/// (the nodal belt on the default FEAD drive with the sharp friction law converges
/// quadratically at its 20th to 25th iteration where mbd-core's default of 20 stopped it).
pub const BELT_NEWTON_ITERATIONS: usize = 50;

/// Steps of the span over which the steady test and the point average the speed loss, for
/// windows of `per_window` steps of `h` \[s\]: `per_window` for a belt whose mesh stays in place
/// (`material_element` `None`, the flowing belt); for one whose mesh travels with the material
/// ([`BeltModel::material_element`]: the nodal and ANCF belts) the fewest whole loop passages
/// `L/v` (loop length `loop_length` \[m\] at belt speed `belt_speed` \[m/s\]) that span a window.
/// The steady test compares the mean over this span with the mean over the same span a window
/// earlier (for the flowing belt: two consecutive windows), so a drift of `r` rad/s² shows as
/// `r × window` either way, while whatever travels with the material of a Lagrangian mesh
/// (its speed loss repeats every loop passage) is averaged out: on Table 6-1 (loop 1.214 m at
/// 3.14 m/s: 0.387 s) with the nodal belt at `tanh_slip` 0.3 mm/s, 30 N·m, the speed loss
/// carries a ±3.4e-3 rad/s component of that period
/// that did not decay over five passages; the means of 0.1 s windows cycled over 0.2443–0.2512
/// rad/s, those of one passage agreed to 1e-5 rad/s (BENCHMARKS.md, "0.3 mm/s as the default:
/// measured and taken"). A zero or non-finite speed falls back to `per_window`.
pub fn averaging_steps(
    per_window: usize, h: f64, material_element: Option<f64>, loop_length: f64, belt_speed: f64,
) -> usize {
    let passage = loop_length / belt_speed.abs();
    if material_element.is_none() || !(passage.is_finite() && passage > 0.0) {
        return per_window;
    }
    let loop_steps = ((passage / h).round() as usize).max(1);
    loop_steps * per_window.div_ceil(loop_steps)
}

/// The steady test's means of the speed losses `hold` (one a step): over the last `avg` steps
/// and over the `avg` steps ending `per_window` steps earlier ([`averaging_steps`]); `None`
/// while `hold` is shorter than `avg + per_window`.
pub fn means_a_window_apart(hold: &[f64], avg: usize, per_window: usize) -> Option<(f64, f64)> {
    let n = hold.len();
    let mean = |r: std::ops::Range<usize>| {
        let len = r.len() as f64;
        hold[r].iter().sum::<f64>() / len
    };
    (avg > 0 && n >= avg + per_window)
        .then(|| (mean(n - avg..n), mean(n - per_window - avg..n - per_window)))
}

/// Steps between the reports sampled over an averaging window ([`Report::mean`]): every other
/// step, so that the window mean resolves a nodal belt's element-passing ripple (a few steps
/// long) and the balances close on the mean (issue 34).
pub const REPORT_EVERY: usize = 2;

/// What is observed over one averaging window: the running minimum and maximum of each span's
/// mid-point displacement, and the drive's reports every [`REPORT_EVERY`] steps.
#[derive(Debug, Clone, Default)]
struct Window {
    lo: Vec<f64>,
    hi: Vec<f64>,
    reports: Vec<Report>,
}

impl Window {
    fn add(&mut self, x: &[f64]) {
        if self.lo.len() != x.len() {
            self.lo = vec![f64::INFINITY; x.len()];
            self.hi = vec![f64::NEG_INFINITY; x.len()];
        }
        for (k, &v) in x.iter().enumerate() {
            if v.is_finite() {
                self.lo[k] = self.lo[k].min(v);
                self.hi[k] = self.hi[k].max(v);
            }
        }
    }

    /// Half the peak-to-peak of span `k` (`None` if never observed).
    fn amplitude(&self, k: usize) -> Option<f64> {
        match (self.lo.get(k), self.hi.get(k)) {
            (Some(lo), Some(hi)) if hi >= lo => Some(0.5 * (hi - lo)),
            _ => None,
        }
    }
}

/// The report of `model` at `state` ([`BeltModel::snapshot`]) averaged with the reports
/// sampled over `window`, with the span amplitudes of `window`; and the wrap points at `state`.
fn report_of<M: BeltModel>(
    model: &M, state: &State, window: &Window,
) -> Result<(Report, Vec<WrapPoint>), MbdError> {
    let snap = model.snapshot(state.t, &state.q, &state.v)?;
    let now = Report::new(model.drive(), &snap);
    let mut all = window.reports.clone();
    all.push(now);
    let mut report = Report::mean(&all).unwrap_or_else(|| all[0].clone());
    for (k, s) in report.spans.iter_mut().enumerate() {
        s.vibration_amplitude_m = window.amplitude(k);
    }
    Ok((report, snap.wrap))
}

/// Run the procedure on `model`: the driver is the drive's first speed-driven pulley, the
/// driven pulley its first loaded pulley (else its first idler) ([`belt::Drive::driver`],
/// [`belt::Drive::driven`]); their speed and load signals are overwritten. The model is
/// stepped as a [`BeltSimulation`] (the public stepping; a gross slip restarts it from the
/// last sound state). `observer` sees every step (e.g. to write histories or update a
/// progress bar).
///
/// Each point carries the drive's report ([`Report`]: span tensions, per-pulley arcs,
/// hub loads and torques averaged over the last averaging span ([`averaging_steps`]: every
/// [`REPORT_EVERY`] steps and the end state), span vibration amplitudes over the last window) and its wrap distributions at the end. **Gross slip is a result**: when the speed loss, averaged over
/// at least a quarter of the current window ([`RUNAWAY_MIN_FRACTION`]), exceeds
/// [`gross_slip_bound`] while a load is held (the driven pulley runs away: the load exceeds what friction can
/// transmit), or a steady state has a wrap without adhesion arc
/// ([`Report::gross_slip`]: the belt slides over the whole wrap), the point is marked
/// ([`SpeedLossPoint::gross_slip`]), the drive is put back into the last steady state (load
/// and all) and the next torque is ramped from there. A Newton failure, or a torque that never
/// becomes steady within `max_hold` (reported as such, not as a Newton failure), stays an
/// error ([`SweepFailure`]); over whole loop passages `max_hold` is raised to the averaging span
/// plus two windows where it is shorter (a loop passage at a low driver speed: 1.07 s on
/// Table 6-1 at 22.6 rad/s).
pub fn speed_loss_sweep<M: BeltModel>(
    model: &mut M, settings: &SpeedLossConfig, mut observer: impl FnMut(&State, Sample),
) -> Result<(Vec<SpeedLossPoint>, SweepStats), SweepFailure> {
    let mut points: Vec<SpeedLossPoint> = Vec::new();
    let fail = |error: MbdError, points: &Vec<SpeedLossPoint>| SweepFailure {
        error,
        points: points.clone(),
    };
    let input = |m: String| SweepFailure {
        error: MbdError::InvalidInput {
            item: "drive".into(),
            reason: m,
        },
        points: Vec::new(),
    };
    let driver = model
        .drive()
        .driver()
        .ok_or_else(|| input("the speed-loss procedure needs a speed-driven pulley".into()))?;
    let driven = model
        .drive()
        .driven()
        .ok_or_else(|| input("the speed-loss procedure needs a free pulley to load".into()))?;
    let signal =
        |m: &mut M, k: usize, s: Signal| m.set_signal(k, s).map_err(|e| input(e.to_string()));
    signal(
        model,
        driver,
        Signal::schedule(vec![(0.0, 0.0), (settings.spin_up, settings.omega_driver)]),
    )?;
    let mut load_knots: Vec<(f64, f64)> = vec![(0.0, 0.0)];
    signal(model, driven, Signal::schedule(load_knots.clone()))?;
    let belt = BeltData::of(&*model, driven);
    let bound = gross_slip_bound(&belt, settings.omega_driver);
    let alpha = AlphaConfig {
        h: settings.step,
        rho_inf: settings.rho_inf,
        subdivisions: STEP_SUBDIVISIONS,
        // Armijo backtracking: Newton cycles between the saturated branches of a sharp friction
        // law (the ANCF belt on Table 6-1 at v_s ≤ 0.8 mm/s in its first step without it)
        newton_line_search: true,
        newton_line_search_trials: BELT_LINE_SEARCH_TRIALS,
        max_newton_iterations: BELT_NEWTON_ITERATIONS,
        // the model's transition-aware limit (Castro et al. 2019): no contact's slip velocity
        // crosses the friction law's steep band in one Newton iteration (flowing and nodal
        // belts; the ANCF belt's limit, `ancf::SimulationConfig::correction_limit`, is
        // measured on the fead sweep only and stays off here, as in its own settings)
        model_correction_limit: model.traits().name != "ancf",
        ..Default::default()
    };
    // a mesh that travels with the material averages over whole loop passages
    let material_element = model.material_element();
    let loop_length = model.drive().path().length();
    let mut sim: BeltSimulation<M, &mut M> =
        BeltSimulation::new(model, alpha).map_err(|e| fail(e, &points))?;
    let mut stats = SweepStats::default();
    let h = settings.step;
    let per_window = (settings.window / h).round().max(1.0) as usize;
    let mut current = 0.0;
    // the first level starts after the spin-up
    let mut level_start = settings.spin_up;
    // the last sound state to return to after a gross slip, with its load (set at the end of
    // the spin-up, then at every steady point without gross slip)
    let mut anchor: Option<(State, f64)> = None;
    for &target in &settings.torques {
        if target != current {
            let t0 = level_start;
            // after a gross slip the hold knot (t0, current) is already the last one
            if load_knots.last().is_none_or(|k| k.0 < t0) {
                load_knots.push((t0, current));
            }
            load_knots.push((t0 + settings.torque_ramp, target));
            signal(
                sim.model_mut(),
                driven,
                Signal::schedule(load_knots.clone()),
            )?;
            level_start = t0 + settings.torque_ramp;
            current = target;
        }
        // step to the end of the ramp, then average windows until steady: the speed loss of
        // every step of the hold, the span of its means (`averaging_steps`, fixed at the hold's
        // first step) and the reports sampled over it (with their step in the hold)
        let mut hold: Vec<f64> = Vec::new();
        let mut avg: Option<usize> = None;
        let mut sampled: std::collections::VecDeque<(usize, Report)> = Default::default();
        let (mut sum, mut count) = (0.0, 0usize);
        let mut window = Window::default();
        let slipped: Option<(State, String)> = loop {
            sim.step().map_err(|e| fail(e, &points))?;
            let st = sim.state();
            if anchor.is_none() && st.t >= settings.spin_up - 0.5 * h {
                anchor = Some((st.clone(), 0.0));
            }
            let sample = Sample {
                t: st.t,
                omega_driver: sim.model().pulley_speed(driver, st.t, &st.v),
                omega_driven: sim.model().pulley_speed(driven, st.t, &st.v),
                load: sim
                    .model()
                    .motion(driven)
                    .map_or(0.0, |m| m.load_torque(st.t)),
                belt_speed: sim.model().belt_speed(&st.q, &st.v),
                points: points.len(),
            };
            observer(st, sample);
            let dw = sample.omega_driver - sample.omega_driven;
            if st.t < level_start - 0.5 * h {
                continue;
            }
            let avg = *avg.get_or_insert_with(|| {
                averaging_steps(
                    per_window,
                    h,
                    material_element,
                    loop_length,
                    sample.belt_speed,
                )
            });
            hold.push(dw);
            window.add(
                &sim.model()
                    .span_transverse(&st.q)
                    .map_err(|e| fail(e, &points))?,
            );
            sum += dw;
            count += 1;
            // the runaway test, on the window's running mean while the load is held. Not during
            // a load ramp: the spans stretch at the rate of the load and the driven pulley lags
            // by that rate on top of the steady creep (on Table 6-1 at v_s = 0.2 mm/s the
            // 10 → 30 N·m ramp peaks at Δω = 0.31 rad/s against the bound's 0.29 and settles at
            // 0.18). Not on single steps: near the Coulomb limit the ANCF belt's speed loss
            // oscillates about its mean by more than the bound's margin over the steady creep
            // (Table 6-1 at 30 N·m, v_s ≤ 0.125 mm/s: steps above the bound at a point that
            // settles below it). A runaway goes on: its mean passes the bound a quarter window on.
            let mean = sum / count as f64;
            if count >= (per_window / RUNAWAY_MIN_FRACTION).max(1) && mean > bound {
                break Some((
                    st.clone(),
                    format!(
                        "speed loss {mean:.3} rad/s (mean over the last {:.3} s) above \
                         {bound:.3} rad/s, the most any steady creep and sliding allow (the \
                         driven pulley runs away)",
                        count as f64 * h
                    ),
                ));
            }
            let n = hold.len();
            if count % REPORT_EVERY == 0 && count < per_window {
                let report = sim
                    .model()
                    .report_at(st.t, &st.q, &st.v)
                    .map_err(|e| fail(e, &points))?;
                window.reports.push(report.clone());
                sampled.push_back((n, report));
                while sampled.front().is_some_and(|(i, _)| *i + avg <= n) {
                    sampled.pop_front();
                }
            }
            if count == per_window {
                sum = 0.0;
                count = 0;
                let mut last_window = std::mem::take(&mut window);
                let means = means_a_window_apart(&hold, avg, per_window);
                if let Some((last, before)) = means
                    && (last - before).abs() < settings.tolerance
                {
                    let st = sim.state().clone();
                    last_window.reports = sampled
                        .iter()
                        .filter(|(i, _)| *i + avg > n)
                        .map(|(_, r)| r.clone())
                        .collect();
                    let (report, wrap) =
                        report_of(sim.model(), &st, &last_window).map_err(|e| fail(e, &points))?;
                    let gross = report.gross_slip().map(|p| {
                        let r = &report.pulleys[p];
                        GrossSlip {
                            pulley: p,
                            name: r.name.clone(),
                            time: st.t,
                            criterion: format!(
                                "steady sliding over the whole wrap: adhesion arc {:.3} rad \
                                 of a {:.3} rad contact arc",
                                r.adhesion_arc_rad, r.contact_arc_rad
                            ),
                        }
                    });
                    let steady = gross.is_none();
                    points.push(SpeedLossPoint {
                        torque: target,
                        delta_omega: last,
                        omega_driven: sim.model().pulley_speed(driver, st.t, &st.v) - last,
                        drift: Some(last - before),
                        time: st.t,
                        settled_s: st.t - level_start,
                        gross_slip: gross,
                        linearisation: linearisation_issue(&belt, &report),
                        caveat: creep_caveat(
                            &belt,
                            &report,
                            sim.model().pulley_speed(driver, st.t, &st.v) - last,
                        ),
                        balance: balance_note(
                            sim.model().traits().balance_defect,
                            &report.balances,
                        ),
                        report,
                        wrap,
                    });
                    level_start = st.t;
                    if steady {
                        anchor = Some((st, target));
                        break None;
                    }
                    break Some((st, String::new()));
                }
                // over whole loop passages (avg > per_window): at least the averaging span and
                // two windows; a mesh that stays in place keeps the given max_hold (validated
                // to allow two windows)
                let max_hold = if avg > per_window {
                    settings.max_hold.max((avg + 2 * per_window) as f64 * h)
                } else {
                    settings.max_hold
                };
                if sim.state().t - level_start > max_hold {
                    return Err(fail(
                        MbdError::Model {
                            t: sim.state().t,
                            message: format!(
                                "no steady state at {target} N m within max_hold = {max_hold} \
                                 s: the last means of the speed loss over {:.4} s, a window \
                                 ({:.4} s) apart, differ by {:.3e} rad/s (tolerance {:.1e} \
                                 rad/s)",
                                avg as f64 * h,
                                per_window as f64 * h,
                                means.map_or(f64::NAN, |(a, b)| (a - b).abs()),
                                settings.tolerance
                            ),
                        },
                        &points,
                    ));
                }
            }
        };
        let Some((st, criterion)) = slipped else {
            continue;
        };
        if !criterion.is_empty() {
            // runaway: report the pulley whose wrap has the least adhesion left
            let (report, wrap) =
                report_of(sim.model(), &st, &window).map_err(|e| fail(e, &points))?;
            let p = (0..report.pulleys.len())
                .min_by(|&a, &b| {
                    let f = |k: usize| {
                        let r = &report.pulleys[k];
                        r.adhesion_arc_rad / r.contact_arc_rad.max(f64::MIN_POSITIVE)
                    };
                    f(a).total_cmp(&f(b))
                })
                .unwrap_or(0);
            let omega_driven = sim.model().pulley_speed(driven, st.t, &st.v);
            let dw = sim.model().pulley_speed(driver, st.t, &st.v) - omega_driven;
            points.push(SpeedLossPoint {
                torque: target,
                delta_omega: dw,
                omega_driven,
                drift: None,
                time: st.t,
                settled_s: st.t - level_start,
                gross_slip: Some(GrossSlip {
                    pulley: p,
                    name: report.pulleys[p].name.clone(),
                    time: st.t,
                    criterion,
                }),
                linearisation: linearisation_issue(&belt, &report),
                caveat: creep_caveat(&belt, &report, omega_driven),
                balance: balance_note(sim.model().traits().balance_defect, &report.balances),
                report,
                wrap,
            });
        }
        // back to the last sound state, at the present time, with its load
        let (sound, load) = anchor.clone().unwrap_or_else(|| (st.clone(), 0.0));
        load_knots.retain(|k| k.0 < st.t);
        load_knots.push((st.t, load));
        signal(
            sim.model_mut(),
            driven,
            Signal::schedule(load_knots.clone()),
        )?;
        current = load;
        level_start = st.t;
        sim.set_state(State::new(st.t, sound.q, sound.v))
            .map_err(|e| fail(e, &points))?;
    }
    stats.add(&sim.stats());
    stats.simulated_time = sim.state().t;
    Ok((points, stats))
}

#[cfg(test)]
mod tests {
    use super::*;

    // The span of the means: whole loop passages for a mesh that travels with the material,
    // the window for one that stays in place. Reference: Table 6-1's loop length over the belt
    // speed ω₁ R₁ (62.8 rad/s × 0.05 m, Ribaric Table 6-1) by hand, L / v / h steps.
    #[test]
    fn a_lagrangian_mesh_averages_whole_loop_passages() {
        let drive = crate::table_6_1::drive();
        let l = drive.path().length();
        assert!((l - 1.214).abs() < 0.01, "Table 6-1 loop {l} m");
        let (h, v) = (2.5e-4, 62.8 * 0.05);
        let passage = (l / v / h).round() as usize;
        assert_eq!(averaging_steps(400, h, Some(5.6e-3), l, v), passage);
        assert_eq!(
            averaging_steps(passage + 1, h, Some(5.6e-3), l, v),
            2 * passage
        );
        assert_eq!(averaging_steps(400, h, None, l, v), 400);
        assert_eq!(averaging_steps(400, h, Some(5.6e-3), l, 0.0), 400);
        // a window apart: for the stationary mesh two consecutive windows
        let hold: Vec<f64> = (0..1000).map(|i| i as f64).collect();
        assert_eq!(means_a_window_apart(&hold[..799], 400, 400), None);
        assert_eq!(
            means_a_window_apart(&hold[..800], 400, 400),
            Some((599.5, 199.5))
        );
    }

    // A speed loss that repeats every loop passage, as the nodal belt's on Table 6-1 at
    // `tanh_slip` 0.3 mm/s and 30 N·m (its history: mean 0.24767 rad/s, ±3.44e-3 rad/s at the
    // passage 0.387 s, ±2.7e-3 rad/s at 42 Hz; BENCHMARKS.md): the means of 0.1 s windows
    // never agree within the 2e-4 rad/s tolerance, those over a passage a window apart do, and
    // a drift shows as the drift over a window either way (the invariant of the comparison).
    #[test]
    fn a_loop_passage_modulation_is_averaged_and_a_drift_is_not() {
        let (h, passage, window) = (2.5e-4, 0.3866_f64, 400);
        let loop_steps = averaging_steps(window, h, Some(5.6e-3), passage, 1.0);
        let signal = |t: f64, drift: f64| {
            0.24767
                + 3.44e-3 * (std::f64::consts::TAU * t / passage + 0.3).sin()
                + 2.7e-3 * (std::f64::consts::TAU * 42.0 * t).sin()
                + drift * t
        };
        let hold =
            |drift: f64| -> Vec<f64> { (0..8000).map(|i| signal(i as f64 * h, drift)).collect() };
        let steady = hold(0.0);
        let ends = (2..=20).map(|k| k * window);
        let windows = ends
            .clone()
            .filter_map(|n| means_a_window_apart(&steady[..n], window, window))
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(windows > 4e-3, "0.1 s windows: {windows}");
        let passages = ends
            .clone()
            .filter_map(|n| means_a_window_apart(&steady[..n], loop_steps, window))
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(passages < 2e-4, "loop passages: {passages}");
        let drifting = hold(1e-2);
        let (a, b) = means_a_window_apart(&drifting, loop_steps, window).unwrap();
        let (c, d) = means_a_window_apart(&steady, loop_steps, window).unwrap();
        let shift = (a - b) - (c - d);
        assert!((shift - 1e-2 * window as f64 * h).abs() < 1e-12, "{shift}");
    }
}
