//! Front-end accessory drive (FEAD) study (issue 17 item 5): a passenger-car serpentine drive
//! of six pulleys with an automatic tensioner, run on the flowing-material belt (or, with
//! `model = "nodal"`, on the rotating-mesh nodal belt, with `model = "ancf"` on the ANCF belt:
//! [`FeadModel`]) ([`belt::layout`]) over an engine-speed sweep with the crankshaft's
//! firing-order speed fluctuation and the accessories' load torques. All three models run on
//! the same loop below (a [`BeltSimulation`]: the public stepping, through the trait
//! [`belt::BeltModel`]).
//!
//! Model-appropriate settings (reported in [`FeadSummary::model_settings`]):
//!
//! * **nodal**: two causes stalled its Newton iterations at the study's defaults (0.1 s ramp,
//!   ρ∞ = 0.8), both from the material nodes travelling over the pulleys, and the study
//!   removes both:
//!   1. *Element passing.* On the default mesh (50 mm span elements, 12 mm on the wraps) a
//!      50 mm element arriving on the 28 mm alternator pulley (its chord turning by 1.8 rad)
//!      stalled Newton at the first element passing (`s_b` ≈ 55 mm, t = 0.042 s of the first
//!      ramp), and still did with a gentler 0.3 s ramp and ρ∞ = 0.6 (t = 0.13 s). The nodal
//!      model runs on a uniform loop of the shorter element length everywhere
//!      (`models.nodal.mesh`; default: 12 mm everywhere).
//!   2. *Contact kinks.* The penalty law (6.1), `k₂d² + k₁d`, has a slope that jumps from 0 to
//!      `k₁` at `d = 0`. A material node reaches a wrap tangentially, so near every tangent
//!      point some node sits within micrometres of the pulley surface and, in a rotating mesh,
//!      a node crosses it every few steps (the flowing model's nodes stay put). Full Newton
//!      then cycles across the kink: on the uniform loop the 800 → 1500 rpm ramp stalled at
//!      t = 0.039 s, residual 5e-5 (with the stall exit alone: 0.041 s; without the uniform
//!      loop, line search alone: 0.19 s). The nodal model steps with mbd-core's Armijo line
//!      search (`AlphaConfig::newton_line_search`, the ANCF drive's remedy for the same
//!      kinks); with both, the default sweep runs.
//! * **ancf**: the belt is `ancf.elements` equal ANCF elements (default 120: 12.7 mm, about
//!   five on the smallest wrap) stepped at `ancf.step` (which replaces `run.step`; default
//!   0.25 ms, the ANCF drive's own step, [`SimulationConfig`]) with the ANCF drive's Newton
//!   settings ([`SimulationConfig::alpha_params`]), ρ∞ = `run.ancf_rho_inf` (default 0.6,
//!   which replaces `run.rho_inf`) and the travel limit `run.ancf_max_travel` (default 0.5,
//!   which replaces `run.max_travel`: [`FeadRun::ancf_max_travel`]). It is the expensive model
//!   (README and BENCHMARKS.md for measured times).
//!
//!   *Gross slip at the crank.* The default drive cannot follow the 1500 → 2500 rpm ramp
//!   without slipping on the crankshaft: the accessories' inertia seen at the crank,
//!   `Σ J_k (R_c/R_k)²` ≈ 0.028 kg m², takes ≈ 29 N m at the ramp's mean 1050 rad/s², the
//!   loads another ≈ 19 N m, against a friction capacity `(T_t − T_s) R_c` of about 36 N m
//!   (slack span crank → power steering ≈ 100 N, the tensioner sitting after the alternator).
//!   The ANCF belt then slides over the whole crank wrap (every other pulley 10 → 19 % behind
//!   at t = 0.04 – 0.07 s of the ramp, crank torque saturated at −36 N m). At ρ∞ = 0.8 the
//!   sliding wrap chatters: the saturated friction `μ p` follows the penalty pressure and
//!   couples the belt's contact modes on the crank (`√(k₁/ρA)` ≈ 4 kHz, `ω h` ≈ 6.5 at
//!   0.25 ms: resolved by no step the study can afford, damped only by the integrator) with
//!   its axial motion; the contact points on the crank drop from 44 to 11 – 36 per step,
//!   torques swing by ±40 N m within 2 ms, and the oscillation grows in the accepted steps
//!   until the tensions reach kilonewtons (a/c → crank span 3.2 kN, crank torque 1.5 kN m at
//!   t = 0.0716 s) and Newton fails (t = 0.071 s; the same with 10 step halvings instead of
//!   4: not a step-size limit). At ρ∞ = 0.6 the generalized-α damping at `ω h` ≈ 6.5 removes
//!   it: the wrap slides smoothly (44 contact points), the slip peaks near 20 % at the end of
//!   the ramp and the belt re-adheres in the settle (the loads alone need 19 N m). The same
//!   holds for the 2500 rpm point from rest (fails at 0.8, t = 0.233 s; completes at 0.6 with
//!   gross slip at the crank, as the nodal model).
//!
//! Per engine speed the crank runs at `ω̄ (1 + Σ a_k sin(k_o ω̄ t + φ_k))` (engine orders `k_o`,
//! relative amplitudes `a_k`), reached from the previous speed by a smooth ramp; after a settling
//! time the study observes a window and reports the tensioner arm's motion, every span's
//! tension extremes, each accessory's speed loss against the crank, the drive report at the end
//! of the window (slip arcs, hub loads, gross slip: [`belt::report`]) and every span's first
//! transverse natural frequency from the travelling-string formula with the computed mean span
//! tension `T` and belt speed `v` (Wickert & Mote 1990; Ribaric §3):
//!
//! ```text
//!   f_n = n (c² − v²) / (2 L c),   c = √(T/ρA)
//! ```
//!
//! against the engine orders' frequencies `k_o · rpm/60`: the Campbell diagram of the drive.
//!
//! Instead of the sweep, a measured crank speed record ([`EngineConfig::trace`],
//! [`crate::crank_trace`]) gives one operating point ([`crank_points`]). A decoupled accessory
//! ([`belt::decoupler`]; flowing and nodal models) is reported per point in
//! [`FeadPoint::decouplers`].
//!
//! Defaults ([`FeadConfig::default`]): a plausible four-cylinder passenger-car drive, not one
//! published engine. The belt is Ribaric's Table 6-1 section (a 5PK V-ribbed belt from an
//! automotive drive: EA = 152 kN, ρA = 0.096 kg/m, μ = 1.2); the pulley sizes, accessory loads
//! and inertias, tensioner rate (30 N m/rad), arm (80 mm) and installed tension (400 N) are of
//! the orders reported for such drives by Beikmann, Perkins & Ulsoy (J. Mech. Des. 119, 1997)
//! and Kong & Parker (J. Mech. Des. 127, 2005); the 2nd-order crank speed fluctuation of 2 %
//! (4th: 0.5 %) is a plausible four-cylinder value, held constant over the sweep.

use crate::ancf_model::{AncfBelt, AncfConfig};
use crate::crank_trace::CrankTrace;
use crate::simulation::BeltSimulation;
use crate::speed_loss::{LINEAR_MIN_SLACK, balance_issue, tension_range_issue};
use crate::study::{ModelSettings, NodalConfig};
use ancf::belt_drive::SimulationConfig;
use belt::{
    BeltContact, BeltDamping, BeltModel, Drive, Harmonic, Layout, Motion, Pulley, Report, Section,
    Shape, Signal, Tensioner, WrapSide,
};
use contact::friction::FrictionLaw;
use flowing::belt::{BeltMesh, BeltReduction, FlowingBelt, FlowingSettings, NodalBelt};
use mbd_core::MbdError;
use mbd_core::integrators::{AlphaConfig, State, Stats};
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// Most engine speeds of a sweep.
pub const MAX_SPEEDS: usize = 200;
/// Most steps of a whole sweep.
pub const MAX_STEPS: usize = 2_000_000;

/// One engine order of the crank speed fluctuation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct EngineOrder {
    /// Order \[-\] (cycles per crank revolution; a four-stroke four-cylinder engine fires at order 2).
    pub order: f64,
    /// Speed amplitude relative to the mean speed \[-\] (0.02: ±2 % of the mean crank speed).
    pub amplitude: f64,
    /// Phase \[rad\].
    #[serde(default)]
    pub phase: f64,
}

/// The engine: the speed sweep and the crank speed fluctuation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct EngineConfig {
    /// Engine speeds of the sweep \[rpm\].
    pub speeds_rpm: Vec<f64>,
    /// Orders of the crank speed fluctuation.
    pub orders: Vec<EngineOrder>,
    /// A measured crank speed trace ([`crate::crank_trace`]; none: the mean speeds of
    /// `speeds_rpm` with the `orders`). With a trace the study has one operating point: the
    /// crank ramps from rest to the trace's first speed over `run.ramp`, then follows the
    /// trace (repeated when `periodic`); `speeds_rpm` and `orders` are not used and the point
    /// reports the trace's time-mean speed as its engine speed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trace: Option<CrankTrace>,
}

impl Default for EngineConfig {
    /// Idle to 3500 rpm; orders 2 (2 %) and 4 (0.5 %).
    fn default() -> Self {
        Self {
            speeds_rpm: vec![800.0, 1500.0, 2500.0, 3500.0],
            orders: vec![
                EngineOrder {
                    order: 2.0,
                    amplitude: 0.02,
                    phase: 0.0,
                },
                EngineOrder {
                    order: 4.0,
                    amplitude: 0.005,
                    phase: 0.0,
                },
            ],
            trace: None,
        }
    }
}

/// Time stepping of the sweep.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct FeadRun {
    /// Generalized-α step \[s\].
    pub step: f64,
    /// Spectral radius at infinity of the generalized-α method \[-\] (flowing and nodal models).
    pub rho_inf: f64,
    /// Spectral radius at infinity with `model = "ancf"` \[-\] (replaces `rho_inf` for that model:
    /// module documentation, *gross slip at the crank*).
    pub ancf_rho_inf: f64,
    /// Ramp from one engine speed to the next (and of the fluctuation) \[s\].
    pub ramp: f64,
    /// Shortest settling time after the ramp \[s\].
    pub settle: f64,
    /// Observation window \[s\], lengthened to a whole number of periods of the lowest
    /// engine order ([`steady_window`]).
    pub window: f64,
    /// Longest settling time after the ramp \[s\]: windows follow each other from `settle`
    /// on until two consecutive ones agree ([`FeadRun::steady_tolerance`]); a point that has
    /// not converged by then is flagged (`FeadPoint::steady`).
    pub max_settle: f64,
    /// Steady-state criterion between consecutive windows \[-\]: every pulley's mean speed
    /// within this fraction of the crank's mean belt speed (as a speed-loss percentage:
    /// 100 × this), and every span's mean tension within 10 × this fraction of the
    /// installed tension.
    pub steady_tolerance: f64,
    /// Largest belt travel per step on a Lagrangian mesh, as a fraction of its element length
    /// \[-\] (the ANCF and nodal belts, [`belt::BeltModel::material_element`]; the flowing
    /// belt's mesh is stationary and keeps its step). A point whose crank drives the belt at
    /// `v = ω R_crank` steps at the model's step divided into the fewest equal parts with
    /// `v h ≤ max_travel · ℓ` ([`travel_limited_step`]). A node entering a wrap changes its
    /// acceleration by `v²/R` within the step: at the model's 0.25 ms the default drive's ANCF
    /// belt moves half an element per step at 3500 rpm. A convergence control: with 0.25 the
    /// default sweep's 2500 and 3500 rpm points step at 0.125 and 0.083 ms and their span
    /// means move by up to 4 N (1 %), while the torque residual on the alternator → tensioner
    /// span rises to 0.5–0.6 % (BENCHMARKS.md, issue 37 item 4). `0` (the default): the model's
    /// step at every point. The ANCF belt takes [`FeadRun::ancf_max_travel`] instead.
    pub max_travel: f64,
    /// [`FeadRun::max_travel`] for `model = "ancf"` (replaces it for that model) \[-\];
    /// default 0.5. At `models.ancf.step` = 0.25 ms the default drive's 120-element belt
    /// moves 0.54 of an element per step at 3500 rpm (0.39 at 2500 rpm), and 85 % of those
    /// steps failed Newton at the full step and were halved anyway (1379 halvings, 2867
    /// rejected attempts of the 3500 rpm point): with 0.5 that point steps at 0.125 ms from
    /// the start, the others keep 0.25 ms. Every mean of the 800–2500 rpm points stays the
    /// same to the bit, the 3500 rpm spans move by at most 0.63 N and the speed losses by
    /// 7e-4 percentage points (the steady tolerance: 2 N and 0.05), for 0.83 of the sweep's
    /// CPU (BENCHMARKS.md, issue 37 item 4). `0`: the model's step at every point.
    pub ancf_max_travel: f64,
}

impl Default for FeadRun {
    /// 0.25 ms steps (the flowing model's step of Ribaric's drive), 0.1 s ramp, settle and
    /// window; ρ∞ = 0.8 (0.6 for the ANCF belt: module documentation).
    fn default() -> Self {
        Self {
            step: 2.5e-4,
            rho_inf: 0.8,
            ancf_rho_inf: 0.6,
            ramp: 0.1,
            settle: 0.1,
            window: 0.1,
            max_settle: 2.0,
            steady_tolerance: 5e-4,
            max_travel: 0.0,
            ancf_max_travel: 0.5,
        }
    }
}

/// The FEAD study's configuration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct FeadConfig {
    /// The drive: pulley 0 is the crankshaft (its speed is set by the sweep).
    pub drive: Layout,
    /// Engine speeds and fluctuation.
    pub engine: EngineConfig,
    /// Time stepping.
    pub run: FeadRun,
    /// The belt model: `flowing` (Ribaric (5.14), the default), `nodal` (the rotating mesh,
    /// Ribaric (5.7), on its uniform loop: module documentation) or `ancf` (Kerkkänen ch. 3,
    /// [`AncfBelt`]; slow).
    pub model: FeadModel,
    /// Each model's discretisation (`models.flowing`, `models.nodal`, `models.ancf`; the ANCF
    /// belt's step replaces `run.step`).
    pub models: ModelSettings,
}

/// Which belt model the FEAD study runs (same layout, same outputs): the speed-loss study's
/// model kinds ([`crate::ModelKind`]: `flowing`, `nodal`, `ancf`).
pub type FeadModel = crate::ModelKind;

fn load(inertia: f64, torque: f64) -> Motion {
    Motion::load(inertia, Signal::schedule(vec![(0.0, 0.0), (0.1, torque)]))
}

impl Default for FeadConfig {
    /// The plausible passenger-car drive of the module documentation, with Ribaric's contact
    /// ([`BeltContact::ribaric`]: tanh friction (6.2) with κ = 40 s/m, the law its studies in
    /// BENCHMARKS.md and README were measured with), stated: not the layouts' default friction
    /// (`BeltContact::default`, `tanh_slip` at `contact::friction::spec::DEFAULT_SLIP_VELOCITY`),
    /// which a drive with new pulleys gets when it states none (`belt::PARTIAL_RULES`).
    fn default() -> Self {
        let pulley = |name: &str, center: [f64; 2], radius: f64, side: WrapSide, motion: Motion| {
            Pulley::new(name, center, radius, side, motion)
        };
        Self {
            drive: Layout {
                pulleys: vec![
                    pulley(
                        "crankshaft",
                        [0.0, 0.0],
                        0.075,
                        WrapSide::Inside,
                        Motion::speed(Signal::constant(0.0)),
                    ),
                    pulley(
                        "power steering",
                        [-0.05, 0.22],
                        0.065,
                        WrapSide::Inside,
                        load(1e-3, 2.0),
                    ),
                    pulley(
                        "alternator",
                        [0.05, 0.36],
                        0.028,
                        WrapSide::Inside,
                        load(3e-3, 3.0),
                    ),
                    pulley(
                        "tensioner",
                        [0.13, 0.29],
                        0.035,
                        WrapSide::Outside,
                        Motion::idler(5e-5),
                    ),
                    pulley(
                        "water pump",
                        [0.24, 0.28],
                        0.055,
                        WrapSide::Inside,
                        load(8e-4, 1.5),
                    ),
                    pulley(
                        "a/c compressor",
                        [0.25, 0.05],
                        0.06,
                        WrapSide::Inside,
                        load(2e-3, 5.0),
                    ),
                ],
                tensioner: Some(Tensioner {
                    pulley: 3,
                    pivot: [0.05, 0.29],
                    stiffness: 30.0,
                    preload: -25.0,
                    preload_angle: 0.0,
                    damping: 0.5,
                    dry_friction: 2.0,
                    friction_rate: 0.05,
                    inertia: 2e-3,
                    travel: [-0.6, 0.6],
                }),
                belt: Section::default(),
                tension: Some(400.0),
                belt_length: None,
                contact: BeltContact::ribaric(),
                damping: BeltDamping::default(),
            },
            engine: EngineConfig::default(),
            run: FeadRun::default(),
            model: FeadModel::default(),
            models: ModelSettings {
                // 50 mm on the spans, 12 mm on the wraps; every free-node mode kept (no
                // truncation: 218 coordinates). With 12 modes (137) the spans' interior nodes
                // could not balance the convective Kelvin–Voigt force of (5.10) at speed: the
                // static (constraint) modes of K hold the elastic strain uniform over a span,
                // so the viscous force β EA v ∂ε/∂s that the strain's relaxation beyond a wrap
                // exit (over β v = 49 mm at 3500 rpm) should balance stayed unbalanced at the
                // span's nodes, and the span's element forces varied by up to 1.6 kN along the
                // span at 3500 rpm (elastic 550 N uniform, total 543 … 653 N on the a/c →
                // crank span); the report's torque residual grew as v² (0.72 % at 800 rpm,
                // 3.9 % at 3500 rpm), the crank's torque 0.5 N m high there. 24 modes change
                // nothing, 48 and 72 are worse (41 % and 44 %: the crank's wrap); all modes give
                // uniform span forces (BENCHMARKS.md, issue 34 item 2, h-v2)
                flowing: FlowingSettings {
                    mesh: BeltMesh {
                        span_element: 0.05,
                        arc_element: 0.012,
                        contact_margin_nodes: 1,
                    },
                    reduction: BeltReduction { free_modes: None },
                    ..FlowingSettings::default()
                },
                // the flowing mesh's shorter length everywhere (module documentation)
                nodal: NodalConfig {
                    mesh: BeltMesh {
                        span_element: 0.012,
                        arc_element: 0.012,
                        contact_margin_nodes: 1,
                    },
                    ..NodalConfig::default()
                },
                // 12.7 mm elements (about five on the alternator's wrap), the study's 0.25 ms step
                ancf: AncfConfig {
                    elements: 120,
                    step: 2.5e-4,
                    ..Default::default()
                },
            },
        }
    }
}

/// The engine's speeds (1 to 20 000 rpm, at most [`MAX_SPEEDS`]) and orders (order 10⁻³ to
/// 10³, amplitude 0 to 0.5 of the mean speed, finite phase): shared by `fead` and the steady
/// design study ([`crate::fead_design`]).
impl Validate for EngineConfig {
    fn validate(&self) -> Result<(), InvalidField> {
        check::count("speeds_rpm", self.speeds_rpm.len(), 1, MAX_SPEEDS)?;
        for (i, &s) in self.speeds_rpm.iter().enumerate() {
            check::within(&format!("speeds_rpm[{i}]"), s, 1.0, 20_000.0, "rpm")?;
        }
        check::count("orders", self.orders.len(), 0, 100)?;
        for (i, o) in self.orders.iter().enumerate() {
            check::within(&format!("orders[{i}].order"), o.order, 1e-3, 1e3, "")?;
            check::within(&format!("orders[{i}].amplitude"), o.amplitude, 0.0, 0.5, "")?;
            check::finite(&format!("orders[{i}].phase"), o.phase)?;
        }
        Ok(())
    }
}

/// The field `drive` of an engine's accessory drive resolved, its pulley 0 the crankshaft
/// (a speed-driven pulley): shared by `fead` and the steady design study
/// ([`crate::fead_design`]).
pub(crate) fn resolve_engine_drive(layout: &Layout) -> Result<belt::Drive, InvalidField> {
    let drive = layout.resolve().map_err(|e| e.within("drive"))?;
    if !matches!(layout.pulleys[0].motion, Motion::Speed { .. }) {
        return Err(InvalidField::new(
            "drive.pulleys[0].motion",
            "pulley 0 is the crankshaft: its motion kind must be speed",
        ));
    }
    Ok(drive)
}

// the layout's merge rules (`tension` / `belt_length`, `pulleys` / `tensioner`)
impl mbd_core::config::PartialRules for FeadConfig {
    const DROPPED_BY: &'static [(&'static str, &'static str)] = belt::PARTIAL_RULES;
}

impl Validate for FeadConfig {
    fn validate(&self) -> Result<(), InvalidField> {
        let drive = resolve_engine_drive(&self.drive)?;
        self.engine.validate_within("engine")?;
        self.models.validate_within("models")?;
        match self.model {
            FeadModel::Flowing => self
                .models
                .flowing
                .mesh
                .check_on(drive.path())
                .map_err(|e| e.within("models.flowing.mesh"))?,
            FeadModel::Nodal => self
                .models
                .nodal
                .mesh
                .check_on(drive.path())
                .map_err(|e| e.within("models.nodal.mesh"))?,
            FeadModel::Ancf => {}
        }
        check::within("run.step", self.run.step, 1e-8, 0.1, "s")?;
        check::within("run.rho_inf", self.run.rho_inf, 0.0, 1.0, "")?;
        check::within("run.ancf_rho_inf", self.run.ancf_rho_inf, 0.0, 1.0, "")?;
        check::within("run.ramp", self.run.ramp, 0.0, 1e3, "s")?;
        check::within("run.settle", self.run.settle, 0.0, 1e3, "s")?;
        check::within("run.window", self.run.window, 1e-6, 1e3, "s")?;
        check::within(
            "run.max_settle",
            self.run.max_settle,
            self.run.settle,
            1e3,
            "s",
        )?;
        check::within(
            "run.steady_tolerance",
            self.run.steady_tolerance,
            1e-8,
            0.1,
            "",
        )?;
        check::within("run.max_travel", self.run.max_travel, 0.0, 100.0, "")?;
        check::within(
            "run.ancf_max_travel",
            self.run.ancf_max_travel,
            0.0,
            100.0,
            "",
        )?;
        // the longest run of a point: the last window starts at ramp + max_settle and is at
        // most one order period (≤ window at the slowest speed checked below) longer
        let per_point = self.run.ramp + self.run.max_settle + 2.0 * self.run.window;
        let (field, step) = match self.model {
            FeadModel::Ancf => ("models.ancf.step", self.models.ancf.step),
            _ => ("run.step", self.run.step),
        };
        if self.run.window < 10.0 * step {
            return Err(InvalidField::new(
                "run.window",
                format!("must span at least 10 steps of {step} s"),
            ));
        }
        let steps = per_point / step * self.engine.speeds_rpm.len() as f64;
        if steps.is_nan() || steps > MAX_STEPS as f64 {
            return Err(InvalidField::new(
                field,
                format!("the sweep would take {steps:.3e} steps (max {MAX_STEPS})"),
            ));
        }
        Ok(())
    }
}

/// Extremes and mean of a sampled quantity.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Extremes {
    /// Minimum.
    pub min: f64,
    /// Mean.
    pub mean: f64,
    /// Maximum.
    pub max: f64,
}

#[derive(Debug, Clone, Default)]
struct Acc {
    min: f64,
    max: f64,
    sum: f64,
    n: usize,
}

impl Acc {
    fn add(&mut self, x: f64) {
        if self.n == 0 {
            self.min = x;
            self.max = x;
        }
        self.min = self.min.min(x);
        self.max = self.max.max(x);
        self.sum += x;
        self.n += 1;
    }
    /// The extremes, `None` when nothing was added.
    fn get_some(&self) -> Option<Extremes> {
        (self.n > 0).then(|| self.get())
    }
    fn get(&self) -> Extremes {
        if self.n == 0 {
            return Extremes {
                min: f64::NAN,
                mean: f64::NAN,
                max: f64::NAN,
            };
        }
        Extremes {
            min: self.min,
            mean: self.sum / self.n as f64,
            max: self.max,
        }
    }
}

/// One span at one engine speed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FeadSpan {
    /// Pulley the span leaves.
    pub from: String,
    /// Pulley the span reaches.
    pub to: String,
    /// Free length of the span \[m\].
    pub length: f64,
    /// Tension over the window \[N\].
    pub tension: Extremes,
    /// First transverse natural frequency of the travelling string with the mean tension and
    /// belt speed \[Hz\] (module documentation; `None` when the belt runs at or above the
    /// span's critical speed, where the string has no such frequency).
    pub frequency_1_hz: Option<f64>,
}

/// A decoupled accessory at one engine speed ([`belt::decoupler`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FeadDecoupler {
    /// The pulley.
    pub pulley: String,
    /// Accessory speed over the window \[rad/s\].
    pub accessory_speed: Extremes,
    /// Spring torque over the window \[N m\] (D1).
    pub spring_torque: Extremes,
    /// Fraction of the window's steps with the one-way clutch overrunning \[-\] (`None`: no
    /// clutch).
    pub overrunning_fraction: Option<f64>,
    /// The clutch's state at the window's end (`None`: no clutch).
    pub clutch_at_end: Option<belt::ClutchState>,
}

/// The result at one engine speed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FeadPoint {
    /// Engine speed \[rpm\].
    pub engine_rpm: f64,
    /// Mean belt speed \[m/s\].
    pub belt_speed: f64,
    /// Tensioner arm angle over the window \[rad\] (`None`: the layout has no tensioner;
    /// issue 35: a layout without one gave NaN here, failing the run as implausible).
    pub arm_angle: Option<Extremes>,
    /// Spans in travel order.
    pub spans: Vec<FeadSpan>,
    /// Speed of every pulley over the window \[rad/s\] (travel order).
    pub pulley_speed: Vec<Extremes>,
    /// Speed loss of every pulley against the crank, `1 − ω R / (ω_c R_c)` averaged over the
    /// window \[%\] (belt creep and slip between the crank and the pulley).
    pub speed_loss_percent: Vec<f64>,
    /// Whether any wrap has (almost) no adhesion arc in the window mean
    /// ([`Report::gross_slip`]).
    pub gross_slip: bool,
    /// The pulley that slips, if any.
    pub gross_slip_pulley: Option<String>,
    /// Why the flowing model, linearised about the installed tension, does not describe the
    /// drive at this engine speed (`None`: it does): a span whose tension dips below
    /// [`crate::speed_loss::LINEAR_MIN_SLACK`] of the installed tension during the window
    /// (a slack or resonating span, which the linear model would let carry compression), or
    /// gross slip. The point's numbers are kept, flagged: they show how the limit was left.
    pub linearisation: Option<String>,
    /// Why the speed losses may understate the creep (the flowing belt's default contact rates
    /// under a friction law sharper than the creep, [`crate::speed_loss::creep_caveat_for`]
    /// with the belt speed times the largest tension change over a wrap, over EA); the numbers
    /// are given.
    pub caveat: Option<String>,
    /// What the window's balances say when they miss [`belt::BALANCE_TOLERANCE`]
    /// ([`crate::speed_loss::balance_note`]: the residuals and, for the flowing and nodal belts, the
    /// known cause); `None` within it. The numbers are given.
    pub balance: Option<String>,
    /// The drive report averaged over the window (span forces, slip arcs, hub loads, torques,
    /// torque and power balances; [`Report::mean`]).
    pub report: Report,
    /// Whether the window is steady: its means agree with the previous window's within
    /// [`FeadRun::steady_tolerance`] (`false`: `run.max_settle` ran out first; the numbers
    /// are those of the last window, not of a steady state).
    pub steady: bool,
    /// Time from the end of the ramp to the start of the reported window \[s\].
    pub settled_s: f64,
    /// Length of the reported window \[s\]: whole periods of the lowest engine order
    /// ([`steady_window`]).
    pub window_s: f64,
    /// The generalized-α step of this point \[s\]: the model's step, divided on a Lagrangian
    /// mesh so that the belt travels at most `run.max_travel` (ANCF: `run.ancf_max_travel`)
    /// elements per step ([`travel_limited_step`]).
    pub step_s: f64,
    /// How the tensioner arm moved through its dry friction in the window (`None`: no
    /// tensioner, or no dry friction at its pivot): [`ArmFriction`].
    pub arm_friction: Option<ArmFriction>,
    /// Every decoupled accessory (pulley order; empty without decouplers).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub decouplers: Vec<FeadDecoupler>,
    /// The stepper's work at this point, ramp, settling and windows (accepted and rejected
    /// steps, Newton iterations, Newton-matrix evaluations and factorisations:
    /// [`mbd_core::integrators::Stats`]); load-independent measures of the point's cost.
    pub work: Stats,
}

/// The tensioner arm's motion through its dry friction over one window (issue 34 item 6).
///
/// The pivot's dry friction is the regularised Coulomb law `M_f = −M_c tanh(θ̇/ω_f)`
/// ([`belt::Tensioner::dry_friction`], Ribaric (6.2)): below the rate `ω_f` (`friction_rate`)
/// the arm is in the law's stick band, where the moment follows the rate instead of holding
/// `±M_c`. An arm that slides both ways in a window (`θ̇ > ω_f` and `θ̇ < −ω_f`, dithered by the
/// engine orders) has its mean set by the balance of spring and belt moments, whatever the
/// history: the friction's moment averages out. An arm that does not can be held by its
/// friction near where the ramp left it, up to `M_c` of unbalanced moment (`M_c / k` of arm
/// angle, 67 mrad on the default drive), so the window means can depend on how the point was
/// reached, and the settle criterion ([`FeadRun::steady_tolerance`]) cannot see it (a held arm
/// is steady, or creeps at below `ω_f`). The flag is a bound, not a measured spread: the
/// regularised law lets a held arm creep towards the balance (on the default drive with a
/// steady crank, 1500 rpm reached from 800 and from 2500 rpm gives the same arm angle within
/// 0.01 mrad: BENCHMARKS.md, issue 34 item 6). On the default drive with its engine orders the
/// arm slides both ways at every speed of the sweep (never held).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ArmFriction {
    /// Fraction of the window's steps in which the arm turned slower than `friction_rate`
    /// (`|θ̇| ≤ ω_f`, the rate from consecutive steps' arm angles) \[-\].
    pub stick_fraction: f64,
    /// Fastest arm rate of the window, each way: `[most negative, most positive]` \[rad/s\].
    pub rate_range: [f64; 2],
    /// Whether the arm did not slide both ways (no step with `θ̇ > ω_f`, or none with
    /// `θ̇ < −ω_f`): its dry friction holds it, and the point's means depend on the ramp
    /// history (not unique).
    pub held: bool,
}

/// The arm rate's samples of one window ([`ArmFriction`]).
#[derive(Debug, Clone, Default)]
struct ArmRateAcc {
    previous: Option<f64>,
    slow: usize,
    n: usize,
    range: [f64; 2],
}

impl ArmRateAcc {
    /// Adds the arm angle `angle` \[rad\] of the next step of `h` \[s\]; the rate is counted
    /// against the friction rate `rate` \[rad/s\].
    fn add(&mut self, angle: f64, h: f64, rate: f64) {
        if let Some(a0) = self.previous.replace(angle) {
            let w = (angle - a0) / h;
            if self.n == 0 {
                self.range = [w, w];
            }
            self.range = [self.range[0].min(w), self.range[1].max(w)];
            self.slow += usize::from(w.abs() <= rate);
            self.n += 1;
        }
    }

    fn get(&self, rate: f64) -> Option<ArmFriction> {
        (self.n > 0).then(|| ArmFriction {
            stick_fraction: self.slow as f64 / self.n as f64,
            rate_range: self.range,
            held: !(self.range[0] < -rate && self.range[1] > rate),
        })
    }
}

/// The observation window at the crank speed `omega` \[rad/s\] with the step `h` \[s\]:
/// `window` \[s\] lengthened to a whole number of periods `2π/(k ω)` of the lowest engine
/// order `k` with a non-zero amplitude (the window mean of a periodic steady state is then
/// its period mean, whatever the phase), and its number of steps. Without an order (or at
/// rest) the window as given.
pub fn steady_window(engine: &EngineConfig, window: f64, omega: f64, h: f64) -> (f64, usize) {
    let lowest = engine
        .orders
        .iter()
        .filter(|o| o.amplitude != 0.0 && o.order > 0.0)
        .map(|o| o.order)
        .fold(f64::INFINITY, f64::min);
    let w = if lowest.is_finite() && omega > 0.0 {
        let period = 2.0 * std::f64::consts::PI / (lowest * omega);
        (window / period - 1e-9).ceil().max(1.0) * period
    } else {
        window
    };
    let steps = (w / h).round().max(1.0) as usize;
    (steps as f64 * h, steps)
}

/// The ANCF belt's largest Newton correction in the FEAD sweep \[m\]
/// (`ancf::belt_drive::SimulationConfig::max_correction`, with its convected predictor,
/// `convected_predictor`): under a tenth of the default drive's 13 mm elements and of the
/// 7 mm the belt travels in a 0.25 ms step at 3500 rpm, far above the 5 µm tolerance. On the
/// default sweep at the model's fixed 0.25 ms step the two together took 22 % fewer Newton
/// iterations and 38 % fewer factorisations (0.81 of the CPU time alone on the idle machine,
/// 0.61 side by side under load), with the
/// same means at 800–2500 rpm within the sweep's tolerance (BENCHMARKS.md, issue 37 item 4).
pub const ANCF_MAX_CORRECTION: f64 = 1e-3;

/// The ANCF belt's FEAD settings `base` for a friction law other than Ribaric's κ law (the
/// layouts' default `tanh_slip` at `contact::friction::spec::DEFAULT_SLIP_VELOCITY`): the
/// transition-aware limit on the Newton corrections
/// (`ancf::belt_drive::SimulationConfig::correction_limit`, Castro et al. 2019, which also
/// turns the stall detection off) instead of the 1 mm trust region, the iteration matrix
/// renewed below a contraction of 0.5 (the variant of BENCHMARKS.md issue 37 item 4). With the
/// trust region and the stall detection the ANCF belt's Newton fails on the default FEAD drive
/// at 800 rpm at `v_s` = 0.25 mm/s and on the three-pulley example without its friction table
/// at 1500 rpm at 0.5 mm/s, where κ = 40 s/m runs; with the limit both run, and the default
/// drive at 800 rpm at 0.5 mm/s takes 39 instead of 53 s (BENCHMARKS.md, "friction
/// regularisation"). Ribaric's κ law keeps `base` (the figures of its studies; at 800 rpm the
/// limit gives the same speed losses to 2·10⁻⁵ percentage points, but h-tancf found it moves
/// the default sweep's 3500 rpm point outside the sweep's tolerance).
///
/// The Newton iteration also resolves the velocities to the law's transition width `width`
/// \[m/s\] ([`SimulationConfig::resolving`]): the 5 µm position test alone lets the last
/// correction move slip velocities by up to 40 mm/s, 80–130 widths of the default law, and the
/// friction forces of a converged step are then off by up to `μ f_n` (on the three-pulley
/// example at 0.3 mm/s the balances missed by 3 %, BENCHMARKS.md, issue 34 item 2).
pub fn ancf_sharp_law_settings(base: SimulationConfig, width: Option<f64>) -> SimulationConfig {
    SimulationConfig {
        max_correction: None,
        correction_limit: true,
        refactor_contraction: 0.5,
        ..base
    }
    .resolving(width)
}

/// The step of a sweep point on a Lagrangian mesh ([`FeadRun::max_travel`]) \[s\]: `h` divided
/// into the fewest equal parts `h/k` with `v h/k ≤ max_travel · ℓ` for the belt speed `v`
/// \[m/s\] and the element length `ℓ` \[m\] the material carries
/// ([`belt::BeltModel::material_element`]); `h` itself without an element (a stationary mesh),
/// with `max_travel = 0` or at rest. Whole parts keep the point's windows on whole periods
/// of the lowest engine order ([`steady_window`]).
pub fn travel_limited_step(h: f64, max_travel: f64, element: Option<f64>, v: f64) -> f64 {
    match element {
        Some(l) if max_travel > 0.0 && l > 0.0 && v.abs() > 0.0 => {
            let k = (h * v.abs() / (max_travel * l)).ceil().max(1.0);
            h / k
        }
        _ => h,
    }
}

/// Samples of one observation window.
struct WindowAcc {
    arm: Acc,
    arm_rate: ArmRateAcc,
    tens: Vec<Acc>,
    speed: Vec<Acc>,
    slip: Vec<Acc>,
    reports: Vec<Report>,
    vbelt: Acc,
    /// Per decoupled pulley: accessory speed, spring torque, overrunning steps, last state.
    dec: Vec<DecAcc>,
}

#[derive(Debug, Clone, Default)]
struct DecAcc {
    speed: Acc,
    torque: Acc,
    overrunning: usize,
    last: Option<belt::DecouplerState>,
}

/// The means by which consecutive windows are compared.
struct WindowMeans {
    speed: Vec<f64>,
    tension: Vec<f64>,
    crank_belt_speed: f64,
}

impl WindowAcc {
    fn new(pulleys: usize, spans: usize) -> Self {
        Self {
            arm: Acc::default(),
            arm_rate: ArmRateAcc::default(),
            tens: vec![Acc::default(); spans],
            speed: vec![Acc::default(); pulleys],
            slip: vec![Acc::default(); pulleys],
            reports: Vec::new(),
            vbelt: Acc::default(),
            dec: vec![DecAcc::default(); pulleys],
        }
    }

    fn means(&self) -> WindowMeans {
        WindowMeans {
            speed: self.speed.iter().map(|a| a.get().mean).collect(),
            tension: self.tens.iter().map(|a| a.get().mean).collect(),
            crank_belt_speed: self.vbelt.get().mean,
        }
    }
}

impl WindowMeans {
    /// [`FeadRun::steady_tolerance`]: every pulley's mean belt-line speed `ω R` within `tol`
    /// of the mean belt speed, every span's mean tension within `10 tol` of the installed
    /// tension `t0` \[N\].
    fn agrees(&self, other: &Self, radii: &[f64], tol: f64, t0: f64) -> bool {
        let v = self.crank_belt_speed.abs().max(1e-9);
        let speeds = self
            .speed
            .iter()
            .zip(&other.speed)
            .zip(radii)
            .all(|((a, b), r)| ((a - b) * r).abs() <= tol * v);
        let tensions = self
            .tension
            .iter()
            .zip(&other.tension)
            .all(|(a, b)| (a.is_nan() && b.is_nan()) || (a - b).abs() <= 10.0 * tol * t0);
        speeds && tensions
    }
}

/// The study's summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FeadSummary {
    /// Installed (static) belt tension \[N\].
    pub installed_tension: f64,
    /// Unstretched belt length \[m\].
    pub belt_length: f64,
    /// Static tensioner arm angle (hand statics) \[rad\].
    pub arm_static_angle: Option<f64>,
    /// Tensioner travel \[rad\].
    pub arm_travel: Option<[f64; 2]>,
    /// Wrap angle of every pulley \[deg\].
    pub wraps_deg: Vec<f64>,
    /// Pulley names.
    pub pulleys: Vec<String>,
    /// Engine orders of the fluctuation.
    pub orders: Vec<f64>,
    /// One point per engine speed (those completed).
    pub points: Vec<FeadPoint>,
    /// The belt model run.
    pub model: FeadModel,
    /// The model's discretisation and step as run, and what was chosen for it (module
    /// documentation: the nodal model's uniform loop, the ANCF elements and step).
    pub model_settings: String,
    /// The belt force the model reports ([`belt::ModelTraits::force_measure`]).
    pub force_measure: String,
    /// Degrees of freedom of the model.
    pub dofs: usize,
    /// Steps taken.
    pub steps: usize,
    /// The stepper's work over the whole sweep (the sum of the points' [`FeadPoint::work`]).
    pub work: Stats,
    /// What the numbers mean: the drive's pulleys in travel order with their roles, then
    /// [`FEAD_MEANING`] ([`fead_meaning`]).
    pub meaning: String,
}

/// The FEAD study's "what the numbers mean" paragraph (`meaning` in `summary.json`).
pub const FEAD_MEANING: &str = "run on the flowing-material belt model (with model = \"nodal\": \
the rotating-mesh nodal model on a uniform loop; with model = \"ancf\": the ANCF belt, the slow \
reference; `model_settings` says what was run) over an engine-speed sweep. The crank turns at the mean \
speed plus its firing-order fluctuation; each accessory carries its load torque. Per engine \
speed, after a ramp and the shortest settling time (run.settle), windows of whole periods of the \
lowest engine order (window_s) follow each other until two consecutive ones agree (every \
pulley's mean belt-line speed within run.steady_tolerance of the belt speed, every span's mean \
tension within 10 x that fraction of the installed tension; steady = false when run.max_settle \
ran out first, settled_s = time from the end of the ramp to the reported window; step_s = the \
point's step: on a mesh that travels with the belt (nodal, ANCF) the model's step divided so \
that the belt moves at most run.max_travel elements per step, run.ancf_max_travel on the ANCF belt, if set). The last window gives: the tensioner arm angle \
(min/mean/max, rad), every span's tension extremes (N), each pulley's speed loss against the \
crank (%, creep and slip), the drive report averaged over the window (slip arcs, hub loads, \
gross slip, per-pulley torque residual between the pulley's torque and the spans' \
(T_in - T_out) r, the power balance: power in = sliding losses + belt damping; `balance` says when either \
residual misses 0.5 %) and every span's first transverse natural frequency from the travelling-string formula \
with the computed span tension and belt speed, to be read against the engine orders (the \
Campbell diagram: a span resonates where an order line crosses its frequency). A point where a \
span's tension dips below 10 % of the installed tension, or a wrap slips as a whole, leaves the \
linearised (flowing, nodal) model's range: its `linearisation` says why and its numbers only \
show how the limit was left (the ANCF belt is not linearised: never flagged). With dry friction \
at the tensioner's pivot, `arm_friction` gives the fraction of the window's steps in which the \
arm turned slower than the friction's regularisation rate (friction_rate: the stick band), its \
fastest rates each way, and `held` = true when the arm did not slide both ways in the window: \
the friction can then hold it near where the ramp left it (by up to dry_friction / stiffness of \
arm angle), so the point's means can depend on how it was reached (another sweep history may \
give other means) although the windows agree; an arm that slides both ways has means set by the \
moment balance alone. The defaults are a plausible drive, not one published engine (see drives::fead).";

/// The summary's `meaning` for `drive`: its pulleys in travel order with their roles (the
/// crank, loaded accessories, idlers, the tensioner's idler), then [`FEAD_MEANING`].
pub fn fead_meaning(drive: &Drive) -> String {
    let tensioner = drive.arm().map(|a| a.tensioner.pulley);
    let pulleys: Vec<String> = drive
        .names()
        .into_iter()
        .zip(drive.roles())
        .enumerate()
        .map(|(k, (name, role))| {
            let what = match role {
                _ if k == 0 => "the crank",
                _ if Some(k) == tensioner => "the tensioner's idler on its arm",
                belt::Role::Driver => "speed-driven",
                belt::Role::Driven => "loaded",
                belt::Role::Idler => "idler",
            };
            format!("{name} ({what})")
        })
        .collect();
    format!(
        "A front-end accessory drive of {} pulleys in travel order: {}, {FEAD_MEANING}",
        pulleys.len(),
        pulleys.join(", ")
    )
}

/// A sweep that stopped on a numerical failure, with the points completed before it.
#[derive(Debug)]
pub struct FeadFailure {
    /// What failed.
    pub error: MbdError,
    /// The summary up to the failure.
    pub partial: Box<FeadSummary>,
}

/// Progress seen by the observer at every step: engine-speed index, time within it.
#[derive(Debug, Clone, Copy)]
pub struct FeadProgress {
    /// Index of the engine speed.
    pub point: usize,
    /// Time within the point \[s\].
    pub t: f64,
    /// Duration of the point \[s\].
    pub duration: f64,
}

/// The crank speed signal of one sweep point: from `from` to `to` \[rad/s\] over `ramp`, with
/// the engine orders at `to` faded in over the ramp. `previous`: the end time \[s\] of the
/// previous point, whose orders (at `from`) the signal carries on with their phases continued
/// and fades out over the ramp, so that the crank speed and its rate stay continuous across
/// the restart of time (a jump of the orders' sum, 2 % of the speed by default, made the first
/// steps of the next point fail to converge).
pub fn crank_signal(
    engine: &EngineConfig, from: f64, to: f64, ramp: f64, previous: Option<f64>,
) -> Signal {
    let knots = if ramp > 0.0 {
        vec![(0.0, from), (ramp, to)]
    } else {
        vec![(0.0, to)]
    };
    let orders = |speed: f64, t0: f64, fade_out: bool| {
        engine.orders.iter().map(move |o| Harmonic {
            amplitude: o.amplitude * speed,
            frequency: o.order * speed,
            phase: o.phase + o.order * speed * t0,
            fade_out,
        })
    };
    let mut harmonics: Vec<Harmonic> = orders(to, 0.0, false).collect();
    if let Some(t_end) = previous {
        harmonics.extend(orders(from, t_end, true));
    }
    Signal {
        shape: Shape::Schedule(knots),
        harmonics,
        fade: ramp,
    }
}

/// One operating point of the sweep ([`crank_points`]).
#[derive(Debug, Clone, PartialEq)]
pub struct CrankPoint {
    /// The engine speed the point reports \[rpm\].
    pub rpm: f64,
    /// The crank's speed from the point's start (`t = 0`) \[rad/s\].
    pub signal: Signal,
    /// The observation window \[s\] and its number of steps of `h`.
    pub window: (f64, usize),
}

/// The operating points of `cfg` with the step `h` \[s\]: per engine speed, the crank
/// signal from the previous speed ([`crank_signal`]) and the window ([`steady_window`]); with
/// a trace ([`EngineConfig::trace`]), its one point: a linear ramp from rest to the trace's
/// first speed over `run.ramp`, then the trace (repeated when periodic: the period is the time
/// from the first to the last sample, whose speed starts the next period), the window
/// lengthened to whole periods, the engine speed the trace's time mean `∫ω dt / T`
/// (trapezoidal, exact for the linear trace).
///
/// # Errors
/// The trace file ([`crate::crank_trace::TraceError`], as `engine.trace.file`), or a trace
/// whose run would exceed [`MAX_STEPS`] or [`belt::signal::MAX_KNOTS`] (`engine.trace`).
pub fn crank_points(cfg: &FeadConfig, h: f64) -> Result<Vec<CrankPoint>, InvalidField> {
    let run = &cfg.run;
    let Some(trace) = &cfg.engine.trace else {
        let mut prev = 0.0;
        return Ok(cfg
            .engine
            .speeds_rpm
            .iter()
            .map(|&rpm| {
                let omega = rpm * std::f64::consts::PI / 30.0;
                let p = CrankPoint {
                    rpm,
                    signal: crank_signal(&cfg.engine, prev, omega, run.ramp, None),
                    window: steady_window(&cfg.engine, run.window, omega, h),
                };
                prev = omega;
                p
            })
            .collect());
    };
    let knots = trace.load().map_err(|e| e.within("engine.trace.file"))?;
    let period = knots[knots.len() - 1].0;
    let mean = knots
        .windows(2)
        .map(|p| 0.5 * (p[0].1 + p[1].1) * (p[1].0 - p[0].0))
        .sum::<f64>()
        / period;
    let window = if trace.periodic {
        // (a measured period is not exact: a window within 10⁻⁶ of whole periods is whole)
        (run.window / period - 1e-6).ceil().max(1.0) * period
    } else {
        run.window
    };
    let steps = (window / h).round().max(1.0) as usize;
    let window = (steps as f64 * h, steps);
    let total = run.ramp + run.max_settle + window.0;
    if total / h > MAX_STEPS as f64 {
        return Err(InvalidField::new(
            "engine.trace",
            format!(
                "the run would take {:.3e} steps (max {MAX_STEPS})",
                total / h
            ),
        ));
    }
    let mut out = Vec::new();
    if run.ramp > 0.0 {
        out.push((0.0, 0.0));
    }
    let repeats = if trace.periodic {
        ((total - run.ramp) / period).ceil() as usize + 1
    } else {
        1
    };
    if repeats.saturating_mul(knots.len()) > belt::signal::MAX_KNOTS {
        return Err(InvalidField::new(
            "engine.trace",
            format!(
                "{repeats} periods of {} samples exceed {} knots: a longer period or fewer samples",
                knots.len(),
                belt::signal::MAX_KNOTS
            ),
        ));
    }
    for r in 0..repeats {
        let start = run.ramp + r as f64 * period;
        out.extend(
            knots
                .iter()
                .skip(usize::from(r > 0))
                .map(|&(t, w)| (start + t, w)),
        );
    }
    Ok(vec![CrankPoint {
        rpm: mean * 30.0 / std::f64::consts::PI,
        signal: Shape::Trace(out).into(),
        window,
    }])
}

/// Run the sweep (configuration validated first; bad input is `Err(FeadFailure)` only for
/// numerical failures: a bad configuration returns [`crate::DriveError::Invalid`] through
/// `Validate` before this is called by the apps).
pub fn run_fead(
    cfg: &FeadConfig, observer: impl FnMut(FeadProgress),
) -> Result<FeadSummary, Box<FeadFailureOrInvalid>> {
    cfg.validate()
        .map_err(|e| Box::new(FeadFailureOrInvalid::Invalid(e)))?;
    // a model that cannot be built from the input is bad input (naming the field), any other
    // build failure numerical
    let build = |e: crate::DriveError| {
        Box::new(match (crate::speed_loss_study::drive_input_error(&e), e) {
            (Some(field), _) => FeadFailureOrInvalid::Invalid(field),
            (None, crate::DriveError::Invalid(m)) => {
                FeadFailureOrInvalid::Invalid(InvalidField::new("drive", m))
            }
            (None, e) => FeadFailureOrInvalid::Build(e),
        })
    };
    let drive = cfg
        .drive
        .resolve()
        .map_err(|e| Box::new(FeadFailureOrInvalid::Invalid(e.within("drive"))))?;
    let h = cfg.run.step;
    let elements = |n: usize, l: f64| format!("{n} elements, {:.1} mm mean", 1e3 * l / n as f64);
    let m = &cfg.models;
    // the travel limit of the flowing and nodal belts (the ANCF belt has its own)
    let travel = ("run.max_travel", cfg.run.max_travel);
    match cfg.model {
        FeadModel::Flowing => {
            let base = FlowingBelt::new(&drive, &m.flowing).map_err(|e| build(e.into()))?;
            let note = format!(
                "flowing: {} (spans {:.1} mm, wraps {:.1} mm), {} modes, step {:.3} ms",
                elements(base.fe.n_nodes(), drive.path().length()),
                1e3 * m.flowing.mesh.span_element,
                1e3 * m.flowing.mesh.arc_element,
                base.n_modes(),
                1e3 * h
            );
            sweep(cfg, base, &drive, belt_alpha(cfg), travel, note, observer)
        }
        FeadModel::Nodal => {
            let base = NodalBelt::new(&drive, &m.nodal.mesh)
                .map_err(|e| build(e.into()))?
                .with_axial_force(m.nodal.axial_force);
            let mut note = format!(
                "nodal: loop of {} (models.nodal.mesh), step {:.3} ms",
                elements(base.fe.n_nodes(), drive.path().length()),
                1e3 * h
            );
            note.push_str(", Newton with line search");
            sweep(cfg, base, &drive, belt_alpha(cfg), travel, note, observer)
        }
        FeadModel::Ancf => {
            let base = AncfBelt::new(&drive, &m.ancf).map_err(|e| build(e.into()))?;
            let note = format!(
                "ancf: {} (models.ancf.elements), {} contact points each, step {:.3} ms \
                 (models.ancf.step replaces run.step), rho_inf {} (run.ancf_rho_inf); belt length \
                 {:.5} m mounted at {:.1} N",
                elements(m.ancf.elements, base.mapping().belt_length),
                m.ancf.contact_points,
                1e3 * m.ancf.step,
                cfg.run.ancf_rho_inf,
                base.mapping().belt_length,
                base.mapping().mounted_tension
            );
            // the ANCF drive's own Newton settings (frozen iteration matrix, line search, 5 µm
            // tolerance: ancf::belt_drive::SimulationConfig) with the convected predictor and,
            // with Ribaric's κ law, the stall detection and a 1 mm trust region
            // (ANCF_MAX_CORRECTION); with any other law (the layouts' default tanh_slip) the
            // transition-aware limit instead (ancf_sharp_law_settings); ρ∞ = run.ancf_rho_inf
            // (module documentation: the sliding crank wrap's contact modes grow at 0.8)
            let ribaric = drive.contact().friction.is_ribaric_tanh();
            let own = SimulationConfig {
                h: m.ancf.step,
                rho_inf: cfg.run.ancf_rho_inf,
                convected_predictor: true,
                max_correction: Some(ANCF_MAX_CORRECTION),
                ..Default::default()
            };
            let alpha = if ribaric {
                own
            } else {
                ancf_sharp_law_settings(own, drive.contact().friction.transition_width())
            }
            .alpha_params();
            sweep(
                cfg,
                base,
                &drive,
                alpha,
                ("run.ancf_max_travel", cfg.run.ancf_max_travel),
                note,
                observer,
            )
        }
    }
}

/// The generalized-α settings of the flowing and nodal models in the FEAD study: `run.step`,
/// `run.rho_inf`, the belt procedures' Newton settings (as the speed-loss procedure:
/// [`crate::speed_loss::BELT_LINE_SEARCH_TRIALS`], [`crate::speed_loss::BELT_NEWTON_ITERATIONS`],
/// the models' transition-aware correction limit [`AlphaConfig::model_correction_limit`]) and
/// Armijo's line search: with a sharp friction law (issue 34 item 3) full Newton cycles between
/// the saturated branches of tanh(v_t/v_s) at the first steps of the default drive, and the
/// nodal belt's Newton cycles at the penalty's kink as its nodes cross the pulley surface near
/// the tangent points (module documentation).
pub fn belt_alpha(cfg: &FeadConfig) -> AlphaConfig {
    AlphaConfig {
        newton_line_search: true,
        h: cfg.run.step,
        rho_inf: cfg.run.rho_inf,
        newton_line_search_trials: crate::speed_loss::BELT_LINE_SEARCH_TRIALS,
        max_newton_iterations: crate::speed_loss::BELT_NEWTON_ITERATIONS,
        model_correction_limit: true,
        ..Default::default()
    }
}

/// The engine-speed sweep of [`run_fead`] on the built model `model` with the stepping
/// `alpha` and the travel limit `max_travel` of the model (`travel_field` names it in errors).
fn sweep<M: BeltModel>(
    cfg: &FeadConfig, mut model: M, drive: &Drive, alpha: AlphaConfig,
    (travel_field, max_travel): (&'static str, f64), model_settings: String,
    mut observer: impl FnMut(FeadProgress),
) -> Result<FeadSummary, Box<FeadFailureOrInvalid>> {
    let names = drive.names();
    let spans = drive.spans();
    let rho = drive.belt().mass_per_length;
    let radii: Vec<f64> = drive.pulleys().iter().map(|p| p.radius).collect();
    // the tensioner's dry friction, if any (ArmFriction)
    let (dry, friction_rate) = drive.arm().map_or((false, f64::INFINITY), |a| {
        (a.tensioner.dry_friction > 0.0, a.tensioner.friction_rate)
    });
    let mut summary = FeadSummary {
        installed_tension: drive.tension(),
        belt_length: drive.belt_length(),
        arm_static_angle: drive.arm().map(|a| a.angle),
        arm_travel: drive.arm().map(|a| a.tensioner.travel),
        wraps_deg: drive.wraps().iter().map(|w| w.to_degrees()).collect(),
        pulleys: names.clone(),
        orders: cfg.engine.orders.iter().map(|o| o.order).collect(),
        points: Vec::new(),
        model: cfg.model,
        model_settings,
        force_measure: model.traits().force_measure.to_string(),
        dofs: model.n_q(),
        steps: 0,
        work: Stats::default(),
        meaning: fead_meaning(drive),
    };
    let fail = |error: MbdError, summary: &FeadSummary| {
        Box::new(FeadFailureOrInvalid::Numerical(FeadFailure {
            error,
            partial: Box::new(summary.clone()),
        }))
    };
    let invalid = |e: InvalidField| Box::new(FeadFailureOrInvalid::Invalid(e));
    let h = alpha.h;
    let linearised = model.traits().linearised;
    let near_coulomb = model.traits().near_coulomb_creep;
    let balance_defect = model.traits().balance_defect;
    let mut state: Option<State> = None;
    let points = crank_points(cfg, h).map_err(invalid)?;
    if cfg.engine.trace.is_some() {
        summary.orders.clear();
    }
    // each point's step: the belt's travel per step on a Lagrangian mesh (FeadRun::max_travel,
    // FeadRun::ancf_max_travel)
    // at the fastest crank speed of its ramp, fluctuation included
    let element = model.material_element();
    let fluctuation: f64 = match cfg.engine.trace {
        None => cfg.engine.orders.iter().map(|o| o.amplitude.abs()).sum(),
        Some(_) => 0.0,
    };
    let point_steps: Vec<f64> = points
        .iter()
        .scan(0.0_f64, |prev, p| {
            let omega = p.rpm * std::f64::consts::PI / 30.0;
            let v = omega.max(*prev) * radii[0] * (1.0 + fluctuation);
            *prev = omega;
            Some(travel_limited_step(h, max_travel, element, v))
        })
        .collect();
    let per_point = cfg.run.ramp + cfg.run.max_settle + 2.0 * cfg.run.window;
    let total_steps: f64 = point_steps.iter().map(|hp| per_point / hp).sum();
    if total_steps > MAX_STEPS as f64 {
        return Err(invalid(InvalidField::new(
            travel_field,
            format!(
                "with the belt's travel per step limited the sweep would take {total_steps:.3e} \
                 steps (max {MAX_STEPS})"
            ),
        )));
    }
    let mut omega_prev = 0.0;
    for (ip, point) in points.into_iter().enumerate() {
        let rpm = point.rpm;
        let omega = rpm * std::f64::consts::PI / 30.0;
        let h = point_steps[ip];
        let alpha = AlphaConfig { h, ..alpha };
        // the crank's speed; the loads at their final values after the first point (time
        // restarts at 0 at every point). After the first engine speed the orders of the
        // previous one are carried on and faded out ([`crank_signal`]), so the crank speed
        // stays continuous across the restart.
        let signal = match state.as_ref().map(|s| s.t) {
            Some(t_end) if cfg.engine.trace.is_none() => {
                crank_signal(&cfg.engine, omega_prev, omega, cfg.run.ramp, Some(t_end))
            }
            _ => point.signal,
        };
        model.set_signal(0, signal).map_err(invalid)?;
        if ip > 0 {
            for k in 0..names.len() {
                if let Some(Motion::Load { torque, .. }) = model.motion(k) {
                    let held = torque.held();
                    model.set_signal(k, held).map_err(invalid)?;
                }
            }
        }
        let s0 = match state.take() {
            Some(s) => State::new(0.0, s.q, s.v),
            None => model.initial_state().map_err(|e| fail(e, &summary))?,
        };
        let mut sim: BeltSimulation<M, &mut M> =
            BeltSimulation::from_state(&mut model, alpha, s0).map_err(|e| fail(e, &summary))?;
        // the window's whole periods in steps of this point's h (h divides the model's step)
        let window_s = point.window.0;
        let per_window = ((window_s / h).round() as usize).max(1);
        let t_min = cfg.run.ramp + cfg.run.settle;
        let t_last = cfg.run.ramp + cfg.run.max_settle;
        let duration = t_last + window_s;
        // ramp and the shortest settling time
        while sim.state().t < t_min - 0.5 * h {
            sim.step().map_err(|e| fail(e, &summary))?;
            summary.steps += 1;
            observer(FeadProgress {
                point: ip,
                t: sim.state().t,
                duration,
            });
        }
        // windows of whole periods until two consecutive ones agree (FeadRun::steady_tolerance)
        let mut previous: Option<WindowMeans> = None;
        let (w, steady, window_start) = loop {
            let window_start = sim.state().t;
            let mut w = WindowAcc::new(names.len(), spans.len());
            // the arm rate from the window's first step on (ArmFriction)
            w.arm_rate.previous = sim.model().arm_angle(&sim.state().q);
            for i in 0..per_window {
                sim.step().map_err(|e| fail(e, &summary))?;
                summary.steps += 1;
                let st = sim.state();
                observer(FeadProgress {
                    point: ip,
                    t: st.t,
                    duration,
                });
                if let Some(a) = sim.model().arm_angle(&st.q) {
                    w.arm.add(a);
                    w.arm_rate.add(a, h, friction_rate);
                }
                w.vbelt.add(sim.model().belt_speed(&st.q, &st.v));
                for (k, d) in w.dec.iter_mut().enumerate() {
                    if let Some(s) = sim.model().decoupler_state(k, &st.q, &st.v) {
                        d.speed.add(s.accessory_speed);
                        d.torque.add(s.spring_torque);
                        d.overrunning +=
                            usize::from(s.clutch == Some(belt::ClutchState::Overrunning));
                        d.last = Some(s);
                    }
                }
                let wc = sim.model().pulley_speed(0, st.t, &st.v) * radii[0];
                for (k, r) in radii.iter().enumerate() {
                    let s = sim.model().pulley_speed(k, st.t, &st.v);
                    w.speed[k].add(s);
                    w.slip[k].add(100.0 * (1.0 - s * r / wc));
                }
                // the report every other step
                if i % 2 == 0 {
                    let report = sim
                        .model()
                        .report_at(st.t, &st.q, &st.v)
                        .map_err(|e| fail(e, &summary))?;
                    for (a, s) in w.tens.iter_mut().zip(&report.spans) {
                        if s.tension_n.is_finite() {
                            a.add(s.tension_n);
                        }
                    }
                    w.reports.push(report);
                }
            }
            let means = w.means();
            let agree = previous.as_ref().is_some_and(|p| {
                p.agrees(
                    &means,
                    &radii,
                    cfg.run.steady_tolerance,
                    summary.installed_tension,
                )
            });
            if agree || sim.state().t >= t_last - 0.5 * h {
                break (w, agree, window_start);
            }
            previous = Some(means);
        };
        let WindowAcc {
            arm,
            arm_rate,
            tens,
            speed,
            slip,
            mut reports,
            vbelt,
            dec,
        } = w;
        let st = sim.state().clone();
        let work = sim.stats();
        summary.work.accumulate(&work);
        drop(sim);
        if reports.is_empty() {
            reports.push(
                model
                    .report_at(st.t, &st.q, &st.v)
                    .map_err(|e| fail(e, &summary))?,
            );
        }
        let report = Report::mean(&reports).unwrap_or_else(|| reports[0].clone());
        let slipping = report.gross_slip();
        let v = vbelt.get().mean;
        let t_min = LINEAR_MIN_SLACK * summary.installed_tension;
        let slack = spans
            .iter()
            .zip(&tens)
            .map(|(sp, a)| (sp, a.get().min))
            .filter(|(_, t)| t.is_nan() || *t < t_min)
            .min_by(|a, b| a.1.total_cmp(&b.1));
        let tight = tens.iter().map(|a| a.get().max).fold(f64::NAN, f64::max);
        let range = tension_range_issue(tight, summary.installed_tension, drive.belt().ea);
        let linearisation = match (slack, slipping, range) {
            // the ANCF belt is not linearised: a slack span or a slipping wrap is a result
            _ if !linearised => None,
            (Some((sp, t)), _, _) => Some(format!(
                "span {}→{} tension falls to {t:.1} N, below {:.0} % of the installed {:.1} N: \
                 the linear model's stiffness K_e + K_g(T0) assumes taut spans",
                names[sp.from],
                names[sp.to],
                100.0 * LINEAR_MIN_SLACK,
                summary.installed_tension
            )),
            (None, Some(k), _) => Some(format!(
                "gross slip on pulley '{}': outside the linearised creep regime",
                names[k]
            )),
            (None, None, range) => range.or_else(|| balance_issue(&report.balances)),
        };
        summary.points.push(FeadPoint {
            engine_rpm: rpm,
            step_s: h,
            belt_speed: v,
            arm_angle: arm.get_some(),
            spans: spans
                .iter()
                .zip(&tens)
                .map(|(sp, a)| {
                    let t = a.get().mean;
                    let c = (t / rho).sqrt();
                    FeadSpan {
                        from: names[sp.from].clone(),
                        to: names[sp.to].clone(),
                        length: sp.length,
                        tension: a.get(),
                        frequency_1_hz: (t > rho * v * v)
                            .then(|| (c * c - v * v) / (2.0 * sp.length * c)),
                    }
                })
                .collect(),
            pulley_speed: speed.iter().map(Acc::get).collect(),
            speed_loss_percent: slip.iter().map(|a| a.get().mean).collect(),
            gross_slip: slipping.is_some(),
            gross_slip_pulley: slipping.map(|k| names[k].clone()),
            linearisation,
            caveat: {
                let dt = report
                    .pulleys
                    .iter()
                    .map(|p| (p.tension_in_n - p.tension_out_n).abs())
                    .fold(0.0, f64::max);
                // the wraps' laws differ in μ only (a grooved wrap scales μ, not the width)
                let law = drive.wrap_friction_law(0);
                crate::speed_loss::creep_caveat_for(
                    near_coulomb,
                    &law,
                    v.abs() * dt / drive.belt().ea,
                )
            },
            balance: crate::speed_loss::balance_note(balance_defect, &report.balances),
            report,
            steady,
            settled_s: window_start - cfg.run.ramp,
            window_s,
            arm_friction: dry.then(|| arm_rate.get(friction_rate)).flatten(),
            work,
            decouplers: dec
                .iter()
                .enumerate()
                .filter_map(|(k, d)| {
                    let last = d.last?;
                    Some(FeadDecoupler {
                        pulley: names[k].clone(),
                        accessory_speed: d.speed.get(),
                        spring_torque: d.torque.get(),
                        overrunning_fraction: last
                            .clutch
                            .map(|_| d.overrunning as f64 / d.speed.n.max(1) as f64),
                        clutch_at_end: last.clutch,
                    })
                })
                .collect(),
        });
        omega_prev = omega;
        state = Some(st);
    }
    Ok(summary)
}

/// Why a sweep did not complete.
#[derive(Debug)]
pub enum FeadFailureOrInvalid {
    /// The configuration was rejected (names the field).
    Invalid(InvalidField),
    /// The model could not be built (a numerical failure of its static solve; input the
    /// model rejects is [`Self::Invalid`]).
    Build(crate::DriveError),
    /// A numerical failure during the sweep, with the points completed.
    Numerical(FeadFailure),
}

impl std::fmt::Display for FeadFailureOrInvalid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Invalid(e) => write!(f, "{e}"),
            Self::Build(e) => write!(f, "{e}"),
            Self::Numerical(e) => write!(f, "numerical failure: {}", e.error),
        }
    }
}

impl std::error::Error for FeadFailureOrInvalid {}
