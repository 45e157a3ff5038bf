//! The cleat-test rig of Ribaric §8.3: inflate (the prestressed stiffness of the reduced tire),
//! preload onto the drum or road (1000 lb = 4448 N), run at speed, roll over the cleat and
//! record the spindle forces `F_x` (longitudinal) and `F_y` (vertical); spectra of the response.
//!
//! Sequence (seed note U22): static preload with the spindle free vertically; the spindle is then
//! fixed at that position; the tire starts at the test speed ("accelerated": spin rate
//! `v / R_e` with the effective rolling radius `R_e = R₀ − d/3` of a belted tire with
//! deflection `d`) and rolls freely (no drive torque) for `settle_time` before the cleat reaches
//! the patch centre; recording continues for `record_time` after the hit.

use crate::error::{TireError, invalid};
use crate::ground::{Ground, GroundConfig};
use crate::loaded::{
    LoadedMode, dominant_longitudinal_mode, dominant_vertical_mode, held_nodes, loaded_modes,
};
use crate::motion::CentreMotion;
use crate::reduced::ReducedTire;
use crate::rolling::RollingTire;
use crate::rolling_config::RollingConfig;
use crate::spectrum::{PEAK_BAND_HZ, Spectrum, amplitude_spectrum, rms_fluctuation};
use crate::statics::{PatchSolution, Preload, preload_cambered, preload_rolling_cambered};
use crate::stats::StepStats;
use fe_model::Rayleigh;
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// Rayleigh damping from two target modal damping ratios (Ribaric §8.4.1: the 5th and 12th
/// modes, ≈3 % or ≈1 %), modes of the reduced tire with the wheel fixed (1-based numbers).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct DampingConfig {
    /// First target mode number (1-based).
    pub mode1: usize,
    /// Damping ratio at the first mode \[-\].
    pub zeta1: f64,
    /// Second target mode number (1-based).
    pub mode2: usize,
    /// Damping ratio at the second mode \[-\].
    pub zeta2: f64,
}

impl Default for DampingConfig {
    fn default() -> Self {
        Self {
            mode1: 5,
            zeta1: 0.03,
            mode2: 12,
            zeta2: 0.03,
        }
    }
}

impl Validate for DampingConfig {
    /// Mode numbers at least 1 (their upper bound is the reduced tire's mode count, checked by
    /// [`DampingConfig::rayleigh`]) and damping ratios in \[0, 1\] (Rayleigh damping above
    /// critical at a target mode is no longer the light damping of Ribaric §8.4.1).
    fn validate(&self) -> Result<(), InvalidField> {
        check::count("mode1", self.mode1, 1, usize::MAX)?;
        check::count("mode2", self.mode2, 1, usize::MAX)?;
        check::within("zeta1", self.zeta1, 0.0, 1.0, "")?;
        check::within("zeta2", self.zeta2, 0.0, 1.0, "")
    }
}

impl DampingConfig {
    /// Rayleigh coefficients from the reduced tire's frequencies.
    pub fn rayleigh(&self, red: &ReducedTire) -> Result<Rayleigh, TireError> {
        let f = red.frequencies_hz()?;
        let pick = |m: usize, name: &str| {
            if m == 0 || m > f.len() {
                Err(invalid(
                    format!("damping.{name}"),
                    format!("mode {m} does not exist (1..={})", f.len()),
                ))
            } else {
                Ok(2.0 * std::f64::consts::PI * f[m - 1])
            }
        };
        let (w1, w2) = (pick(self.mode1, "mode1")?, pick(self.mode2, "mode2")?);
        if (w1 - w2).abs() < 1e-9 * w2 {
            return Err(invalid(
                "damping.mode2",
                "has the same frequency as mode1 (choose modes of different frequency)",
            ));
        }
        Ok(Rayleigh::from_modal_ratios(w1, self.zeta1, w2, self.zeta2)?)
    }
}

/// Sub-stepping through the cleat impact: while the cleat is between `lead` ahead of the patch
/// centre and `trail` after it has passed the centre, every time step of the rig is taken as
/// `substeps` equal sub-steps (the samples stay one per time step). The impact of the rigid
/// cleat on the patch is resolved step by step by the index-3 contact; the ring-down that
/// follows (76 Hz, `Ω h ≈ 0.1` at 0.2 ms) is resolved at the normal step.
///
/// Why `trail = 0.06 s`: judged by the mean over eight cleat phases
/// ([`RigConfig::with_cleat_phase`]; single runs scatter by ±2 %) of the dominant vertical
/// line's band rms on the default tire at 60 km/h, the default step (0.2 ms, 4 sub-steps) with
/// a 20 ms trail came out 4 % below the uniform 0.05 ms and 0.025 ms runs (which agree within
/// 0.5 %), and the longitudinal line 17 % above; with a 60 ms trail both lines lie within 0.3 %
/// and 3 % of them, for 15 % more steps (BENCHMARKS.md, tire: convergence over cleat phases).
/// The switch back to the long step while the patch still rings is what a short trail gets
/// wrong; a longer lead does not help (0.3 m: −3.4 %).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct ImpactConfig {
    /// Sub-steps per time step inside the window (1 = off).
    pub substeps: usize,
    /// Start of the window: the cleat this far ahead of the patch centre, along the ground \[m\].
    pub lead: f64,
    /// End of the window: this long after the cleat passed the patch centre \[s\].
    pub trail: f64,
}

impl Default for ImpactConfig {
    fn default() -> Self {
        Self {
            substeps: 4,
            lead: 0.1,
            trail: 0.06,
        }
    }
}

impl ImpactConfig {
    /// Whether the step starting at `t` lies in the window of `ground` (the cleat's or any
    /// obstacle's: [`Ground::obstacle_near`]).
    fn active(&self, ground: &Ground, t: f64) -> bool {
        self.substeps > 1 && ground.obstacle_near(t, self.lead, self.trail)
    }
}

/// Inputs at the wheel (issue 38, item 1): a drive or brake torque on the spin degree of
/// freedom, a slip angle of the road velocity to the wheel plane and a camber angle of the
/// rim to the road normal. The defaults (zero) are the free-rolling, straight-ahead, upright
/// wheel of Ribaric §8.3.
///
/// Frame and signs: the wheel frame of the rig is the ISO 8855 wheel frame (x forward in the
/// travel direction, y left along the spin axis, z up), with the wheel centre at its origin.
/// The wheel rolls forwards with a positive spin rate θ̇ about +y.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct WheelInputs {
    /// Drive torque on the wheel's spin degree of freedom about +y \[N·m\]: positive drives
    /// (accelerates the forward spin, `F_x > 0` in the steady state), negative brakes; 0 =
    /// free rolling. Applied from the start of the run (the tire starts from the free-rolling
    /// steady state).
    pub drive_torque: f64,
    /// Slip angle α \[deg\] (Pacejka, *Tire and Vehicle Dynamics*, §1.2, ISO 8855:
    /// `tan α = −V_y/|V_x|` with the wheel centre's velocity `V` over the road in the wheel
    /// frame): the road under the fixed wheel moves at `(−v, v tan α, 0)` (the longitudinal
    /// speed `v` stays that of `speed_kmh`; [`Ground::lateral_speed`]). A positive α gives a
    /// positive (leftward) side force `F_y` and, with the pneumatic trail behind the contact
    /// centre, a negative aligning moment `M_z`. Within ±45°. A non-zero α breaks the mirror
    /// symmetry: the full model is stepped.
    pub slip_angle_deg: f64,
    /// Prescribed spin rate Ω \[rad/s\] about +y instead of a torque (absent: the spin is
    /// free and `drive_torque` drives it). From the start of the run the spin rate goes
    /// linearly from the free-rolling start's to Ω over the first step and is then held: a
    /// kinematic constraint on the spin coordinate ([`crate::dynamics::PrescribedSpin`],
    /// [`RollingTire::prescribe_spin`]) whose reaction torque is an output
    /// ([`RollingTire::reaction_torque`]). The longitudinal slip follows as
    /// `κ = Ω/Ω₀ − 1` against the free-rolling spin rate Ω₀ (Pacejka §1.2; the steady study's
    /// `slip_ratios` sweep sets Ω this way). Requires `drive_torque = 0`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spin_rate: Option<f64>,
    /// Camber (inclination) angle γ \[deg\] of the rim to the road normal (ISO 8855; Pacejka,
    /// *Tire and Vehicle Dynamics*, §1.2): a right-handed rotation of the wheel about its x
    /// axis, positive when the top of the wheel leans to the right (towards `−y`) seen from
    /// behind. Applied as the road tilted by `−γ` about the x-parallel line through the
    /// contact centre ([`Ground::camber`]; road normal `(0, sin γ, cos γ)` in the wheel frame),
    /// the preload `load` along the road normal. With γ ≠ 0 the loads are reported in the
    /// W-axis orientation (z along the road normal; [`crate::rolling::WheelLoads`]) and the
    /// full model is stepped. The camber thrust of a tire points to the side it leans to
    /// (Pacejka §3.2, §4.3): `F_y < 0` for γ > 0. Within ±[`MAX_CAMBER_DEG`].
    pub camber_deg: f64,
    /// Prescribed wheel-centre motion: time series of the co-simulation inputs (height,
    /// velocity, yaw, camber, spin rate; [`CentreMotion`]), interpolated piecewise linearly,
    /// sampled at every communication step and held over it, and stepped by the tire FMU's
    /// engine ([`crate::motion::CoSimulation`]) on the flat road. Absent (default): the
    /// wheel centre is fixed. Requires `ground.kind = "road"` without cleat, obstacles or
    /// grid, and the other wheel inputs at their defaults (the series gives them).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schemars(extend("x-commented-example" = CENTRE_MOTION_EXAMPLE))]
    pub centre_motion: Option<CentreMotion>,
}

/// The example of a `centre_motion` table that the printed rig configuration ends with,
/// commented out (`flowmbd_cli::commented`'s `x-commented-example`): its heading, then the
/// table's lines.
pub const CENTRE_MOTION_EXAMPLE: &str = "A prescribed wheel-centre motion: the FMU's inputs as time series (road, no cleat; guide):\n\
time = [0.0, 0.04, 0.05]      # [s] from the start of the run, strictly increasing\n\
velocity_y = [0.0, 0.0, 0.3]  # [m/s] road frame; also height [m], velocity_x, velocity_z [m/s]\n\
camber = [0.0, 0.0, 0.01]     # [rad]; also yaw [rad], spin_rate [rad/s] (absent: the start's)\n\
communication_step = 0.001    # [s] inputs sampled and held (absent: rolling.time_step)\n";

impl Default for WheelInputs {
    fn default() -> Self {
        Self {
            drive_torque: 0.0,
            slip_angle_deg: 0.0,
            spin_rate: None,
            camber_deg: 0.0,
            centre_motion: None,
        }
    }
}

/// Largest prescribed spin rate of [`WheelInputs::spin_rate`] \[rad/s\] (about 16 000 rpm,
/// several times any road tire's at its speed rating).
pub const MAX_SPIN_RATE: f64 = 1700.0;

/// Largest slip angle of [`WheelInputs::slip_angle_deg`] \[deg\].
pub const MAX_SLIP_ANGLE_DEG: f64 = 45.0;

/// Largest camber angle of [`WheelInputs::camber_deg`] \[deg\].
pub const MAX_CAMBER_DEG: f64 = 30.0;

impl Validate for WheelInputs {
    /// A finite torque, a slip angle within ±[`MAX_SLIP_ANGLE_DEG`], a camber angle within
    /// ±[`MAX_CAMBER_DEG`] and a prescribed spin rate within ±[`MAX_SPIN_RATE`] only with
    /// `drive_torque = 0`.
    fn validate(&self) -> Result<(), InvalidField> {
        check::finite("drive_torque", self.drive_torque)?;
        check::within(
            "slip_angle_deg",
            self.slip_angle_deg,
            -MAX_SLIP_ANGLE_DEG,
            MAX_SLIP_ANGLE_DEG,
            "deg",
        )?;
        check::within(
            "camber_deg",
            self.camber_deg,
            -MAX_CAMBER_DEG,
            MAX_CAMBER_DEG,
            "deg",
        )?;
        if let Some(w) = self.spin_rate {
            check::within("spin_rate", w, -MAX_SPIN_RATE, MAX_SPIN_RATE, "rad/s")?;
            if self.drive_torque != 0.0 {
                return Err(InvalidField::new(
                    "drive_torque",
                    format!(
                        "must be 0 with a prescribed spin_rate (got {} N·m): the spin is \
                         either driven by a torque or prescribed",
                        check::show(self.drive_torque)
                    ),
                ));
            }
        }
        if let Some(m) = &self.centre_motion {
            m.validate_within("centre_motion")?;
            // the series prescribes the spin, the slip and the camber itself
            let given = |v: f64| v != 0.0;
            for (field, set) in [
                ("drive_torque", given(self.drive_torque)),
                ("slip_angle_deg", given(self.slip_angle_deg)),
                ("camber_deg", given(self.camber_deg)),
                ("spin_rate", self.spin_rate.is_some()),
            ] {
                if set {
                    return Err(InvalidField::new(
                        field,
                        "must be left at its default with a centre_motion (give it as a \
                         series of centre_motion: velocity_y, camber, spin_rate)",
                    ));
                }
            }
        }
        Ok(())
    }
}

impl WheelInputs {
    /// The road's lateral velocity `v tan α` \[m/s\] at the longitudinal speed `v` \[m/s\].
    pub fn lateral_speed(&self, v: f64) -> f64 {
        v * self.slip_angle_deg.to_radians().tan()
    }

    /// The camber angle γ \[rad\].
    pub fn camber(&self) -> f64 {
        self.camber_deg.to_radians()
    }
}

/// Cleat-test settings (defaults: Ribaric §8.3 at 60 km/h on the drum).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct RigConfig {
    /// Vertical preload \[N\] (1000 lb).
    pub load: f64,
    /// Speed \[km/h\].
    pub speed_kmh: f64,
    /// Time rolled before the cleat reaches the patch centre \[s\].
    pub settle_time: f64,
    /// Time recorded after the cleat hit \[s\].
    pub record_time: f64,
    /// Ground.
    pub ground: GroundConfig,
    /// Damping.
    pub damping: DampingConfig,
    /// Integration and contact.
    pub rolling: RollingConfig,
    /// Sub-stepping through the cleat impact.
    pub impact: ImpactConfig,
    /// Wheel inputs: drive/brake torque, slip angle and camber (default: free rolling,
    /// straight, upright).
    pub wheel: WheelInputs,
}

impl Default for RigConfig {
    fn default() -> Self {
        Self {
            load: 4448.2,
            speed_kmh: 60.0,
            settle_time: 0.4,
            record_time: 0.3,
            ground: GroundConfig::default(),
            damping: DampingConfig::default(),
            rolling: RollingConfig::default(),
            impact: ImpactConfig::default(),
            wheel: WheelInputs::default(),
        }
    }
}

/// Most time steps (samples) one rig run may take: bounds the memory of the recording
/// (about 64 B a sample) before anything is allocated.
pub const MAX_RIG_STEPS: f64 = 2e7;

/// Most impact sub-steps per time step.
pub const MAX_IMPACT_SUBSTEPS: usize = 1000;

impl mbd_core::config::PartialRules for RigConfig {}

impl Validate for RigConfig {
    /// The rig's own fields and its nested `rolling.…`, `ground.…`, `damping.…` and
    /// `impact.…` settings (paths relative to the rig): positive load and speed, non-negative
    /// times (`record_time = 0` runs to the cleat only), at most [`MAX_RIG_STEPS`] steps and
    /// [`MAX_IMPACT_SUBSTEPS`] sub-steps.
    fn validate(&self) -> Result<(), InvalidField> {
        self.rolling.validate_within("rolling")?;
        self.ground.validate_within("ground")?;
        self.damping.validate_within("damping")?;
        self.wheel.validate_within("wheel")?;
        check::positive("speed_kmh", self.speed_kmh, "km/h")?;
        check::positive("load", self.load, "N")?;
        check::non_negative("settle_time", self.settle_time, "s")?;
        check::non_negative("record_time", self.record_time, "s")?;
        check::size(
            "impact.substeps",
            self.impact.substeps,
            1,
            MAX_IMPACT_SUBSTEPS,
        )?;
        check::non_negative("impact.lead", self.impact.lead, "m")?;
        check::non_negative("impact.trail", self.impact.trail, "s")?;
        if self.wheel.centre_motion.is_some() {
            let needs = |ok: bool, field: &str, reason: &str| {
                if ok {
                    Ok(())
                } else {
                    Err(InvalidField::new(
                        field,
                        format!("{reason} with a wheel.centre_motion (the FMU's flat road)"),
                    ))
                }
            };
            needs(
                self.ground.kind == crate::ground::GroundKind::Road,
                "ground.kind",
                "must be \"road\"",
            )?;
            needs(!self.ground.cleat, "ground.cleat", "must be false")?;
            needs(
                !self.ground.has_obstacles_or_grid(),
                "ground.obstacles",
                "obstacles and a grid_file are not supported",
            )?;
        }
        let h = self.rolling.time_step;
        let steps = (self.settle_time + self.record_time) / h.min(self.sample_step());
        let max = mbd_core::validate::limits::ceiling(MAX_RIG_STEPS);
        if steps > max {
            return Err(InvalidField::new(
                "record_time",
                format!(
                    "settle_time + record_time = {} s at rolling.time_step = {} s is {steps:.3e} \
                     steps, more than the {max:e} a run may record{}",
                    check::show(self.settle_time + self.record_time),
                    check::show(h),
                    mbd_core::validate::limits::raise_hint()
                ),
            ));
        }
        Ok(())
    }
}

impl RigConfig {
    /// The step of the recorded samples \[s\]: the communication step of a prescribed
    /// wheel-centre motion ([`CentreMotion::communication_step`]), else `rolling.time_step`.
    pub fn sample_step(&self) -> f64 {
        self.wheel
            .centre_motion
            .as_ref()
            .and_then(|m| m.communication_step)
            .unwrap_or(self.rolling.time_step)
    }

    /// The step that resolves the cleat impact \[s\]: `rolling.time_step / impact.substeps`
    /// (the sub-steps of the impact window), `rolling.time_step` without sub-steps.
    pub fn impact_step(&self) -> f64 {
        self.rolling.time_step / self.impact.substeps.max(1) as f64
    }

    /// This rig with the cleat arriving `fraction` of an [impact step](Self::impact_step) later
    /// (`settle_time` lengthened by that much; the samples' `t = 0` stays at the cleat hit):
    /// another sampling phase of the cleat's hits on the discrete contact nodes.
    ///
    /// Why it matters: an index-3 contact closes the gap of a node that hits the cleat at
    /// the end of the step in which it crossed the surface, and the velocity that correction
    /// leaves depends on how far into the step the node crossed (`(γ'/β')` times the
    /// penetration over `h`, [`mbd_core::integrators::AlphaCorrection`]): the impulse that
    /// each node hit passes to the tire is a pseudo-random function of the hit's phase on the
    /// step grid that does not settle as `h → 0`. The energy of the rolling tire's lines after
    /// the cleat therefore scatters with the phase (on the default tire at 60 km/h, `h` =
    /// 0.05 ms: ±2 % standard deviation of `fy_band_rms_n` over eight phases, BENCHMARKS.md),
    /// while its mean over phases converges with the step.
    pub fn with_cleat_phase(&self, fraction: f64) -> RigConfig {
        let mut c = self.clone();
        c.settle_time += fraction * self.impact_step();
        c
    }

    /// What the spindle-force spectra of a cleat test need ([`RigResult::spectra`], peaks
    /// searched in [`PEAK_BAND_HZ`]), beyond [`Validate`]: a Nyquist frequency `1/(2h)` at or
    /// above the band's upper end (a step of 0.05 s resolves nothing above 10 Hz: the peak
    /// search of 8 samples found "0 Hz", issue 20) and a recording of at least 2 steps.
    /// Field paths relative to the rig.
    pub fn validate_spectrum(&self) -> Result<(), InvalidField> {
        let h = self.sample_step();
        let own_step = self
            .wheel
            .centre_motion
            .as_ref()
            .and_then(|m| m.communication_step);
        let field = match own_step {
            Some(_) => "wheel.centre_motion.communication_step",
            None => "rolling.time_step",
        };
        let f_hi = PEAK_BAND_HZ[1];
        if 1.0 / (2.0 * h) < f_hi {
            return Err(InvalidField::new(
                field,
                format!(
                    "{} s cannot resolve the spindle-force spectrum: its Nyquist frequency \
                     1/(2h) = {} Hz is below the {f_hi} Hz up to which peaks are sought \
                     (use a step of at most {} s)",
                    check::show(h),
                    check::show(1.0 / (2.0 * h)),
                    check::show(1.0 / (2.0 * f_hi))
                ),
            ));
        }
        if 2.0 * h > self.record_time {
            return Err(InvalidField::new(
                field,
                format!(
                    "{} s leaves fewer than 2 steps in record_time = {} s",
                    check::show(h),
                    check::show(self.record_time)
                ),
            ));
        }
        Ok(())
    }
}

/// One recorded sample.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Sample {
    /// Time \[s\] (0 at the cleat hit).
    pub t: f64,
    /// Longitudinal spindle force `F_x` \[N\].
    pub fx: f64,
    /// Vertical spindle force `F_y` \[N\] (ISO 8855 `F_z`; with camber along the road normal).
    pub fy: f64,
    /// Lateral spindle force \[N\] (along the wheel axis, left positive: ISO 8855 `F_y`; with
    /// camber in the road plane, W-axis `y`).
    pub fz: f64,
    /// Overturning moment `M_x` of the contact forces about the wheel centre \[N·m\] (ISO 8855
    /// wheel frame, [`crate::rolling::WheelLoads`]).
    pub mx: f64,
    /// Moment `M_y` about the spin axis \[N·m\] (likewise).
    pub my: f64,
    /// Aligning moment `M_z` \[N·m\] (likewise).
    pub mz: f64,
    /// Spin rate \[rad/s\].
    pub spin: f64,
    /// Torque applied to the wheel about +y \[N·m\]: the drive torque plus the reaction of a
    /// prescribed spin ([`RollingTire::spin_torque`]).
    pub spin_torque: f64,
    /// Contact nodes in contact.
    pub active: usize,
    /// Sum of the normal multipliers \[N\].
    pub normal_sum: f64,
    /// Contact nodes pressed onto the cleat or another obstacle.
    pub cleat_nodes: usize,
}

/// Result of a cleat test.
#[derive(Debug, Clone, Serialize)]
pub struct RigResult {
    /// Speed \[km/h\].
    pub speed_kmh: f64,
    /// Preload \[N\].
    pub load: f64,
    /// Camber angle γ \[deg\] (with γ ≠ 0 the samples' loads are in the W-axis orientation,
    /// [`crate::rolling::WheelLoads`]); with a prescribed wheel-centre motion the camber of its
    /// last communication step (each sample's loads are in the orientation of its own camber).
    pub camber_deg: f64,
    /// DOF of the wheel–tire model (6 + n_z).
    pub dof: usize,
    /// Whether the half model of symmetric motion was stepped, and why not
    /// ([`super::rolling::SymmetryUse::describe`]).
    pub symmetry: String,
    /// Preload solution.
    pub preload: PatchSolution,
    /// Rayleigh coefficients.
    pub rayleigh: Rayleigh,
    /// Samples (every time step) from the start of the run.
    pub samples: Vec<Sample>,
    /// Time step \[s\].
    pub dt: f64,
    /// Wall time of the time integration \[s\] (the observer's time excluded).
    pub wall_time_s: f64,
    /// CPU time of the integrating thread and of the split products' worker thread, if any
    /// \[s\] (`clock_gettime` of their thread CPU clocks; `None` elsewhere): the
    /// load-independent cost on a shared machine (with a worker it includes the worker's
    /// spinning between products).
    pub cpu_time_s: Option<f64>,
    /// Simulated time \[s\].
    pub simulated_s: f64,
    /// Refactorisations of the iteration matrix.
    pub refactors: usize,
    /// Work counters of the integration.
    pub stats: StepStats,
    /// The loaded tire's vertical in-plane mode: the mode with the largest effective vertical
    /// spindle mass of the non-rolling tire with the preloaded contact nodes held
    /// ([`super::loaded`]), the reference for the dominant vertical line (Ribaric §8.3).
    /// `None` if that eigenproblem failed.
    pub loaded_vertical_mode: Option<LoadedMode>,
    /// The loaded tire's mode with the largest effective longitudinal spindle mass.
    pub loaded_longitudinal_mode: Option<LoadedMode>,
}

impl RigResult {
    /// Samples of the recording window (t ≥ 0).
    pub fn record(&self) -> Vec<Sample> {
        self.samples
            .iter()
            .copied()
            .filter(|s| s.t >= 0.0)
            .collect()
    }

    /// Spectra of the recorded `F_x`, `F_y`.
    pub fn spectra(&self) -> (Spectrum, Spectrum) {
        let r = self.record();
        let fx: Vec<f64> = r.iter().map(|s| s.fx).collect();
        let fy: Vec<f64> = r.iter().map(|s| s.fy).collect();
        (
            amplitude_spectrum(&fx, self.dt),
            amplitude_spectrum(&fy, self.dt),
        )
    }

    /// Samples before the first contact with the cleat (the steadily rolling tire).
    pub fn before_cleat(&self) -> Vec<Sample> {
        self.samples
            .iter()
            .take_while(|s| s.cleat_nodes == 0 && s.t < 0.0)
            .copied()
            .collect()
    }

    /// Mean `(F_x, F_y)` over the last `window` seconds before the first cleat contact \[N\]
    /// (`None` if there are no such samples).
    pub fn mean_before_cleat(&self, window: f64) -> Option<(f64, f64)> {
        let b = self.before_cleat();
        let t_end = b.last()?.t;
        let w: Vec<&Sample> = b.iter().filter(|s| s.t > t_end - window).collect();
        let n = w.len() as f64;
        Some((
            w.iter().map(|s| s.fx).sum::<f64>() / n,
            w.iter().map(|s| s.fy).sum::<f64>() / n,
        ))
    }

    /// Mean moments `(M_x, M_y, M_z)` of the contact forces about the wheel centre over the
    /// last `window` seconds before the first cleat contact \[N·m\] (ISO 8855 wheel frame;
    /// `None` if there are no such samples).
    pub fn mean_moments_before_cleat(&self, window: f64) -> Option<[f64; 3]> {
        let b = self.before_cleat();
        let t_end = b.last()?.t;
        let w: Vec<&Sample> = b.iter().filter(|s| s.t > t_end - window).collect();
        let n = w.len() as f64;
        let m = |f: fn(&Sample) -> f64| w.iter().map(|s| f(s)).sum::<f64>() / n;
        Some([m(|s| s.mx), m(|s| s.my), m(|s| s.mz)])
    }

    /// RMS fluctuations of the recorded `(F_x, F_y)` \[N\].
    pub fn rms(&self) -> (f64, f64) {
        let r = self.record();
        let fx: Vec<f64> = r.iter().map(|s| s.fx).collect();
        let fy: Vec<f64> = r.iter().map(|s| s.fy).collect();
        (rms_fluctuation(&fx), rms_fluctuation(&fy))
    }
}

/// The start of the cleat test (Ribaric §8.3): the tire pressed onto the ground with the load
/// and rolling steadily at the speed, ready to step.
pub struct RigStart<'a> {
    /// The rolling tire in its Eulerian steady state (`preload_rolling`), the cleat reaching the
    /// patch centre at `t = settle_time`.
    pub sim: RollingTire<'a>,
    /// Rayleigh coefficients from the damping targets.
    pub rayleigh: Rayleigh,
    /// The static (non-rolling) preload, which sets the effective rolling radius
    /// `R − deflection/3`.
    pub static_preload: Preload,
    /// The rolling preload the tire starts from.
    pub preload: Preload,
}

/// Press the tire onto the ground and set it rolling steadily (see [`RigStart`]): Rayleigh
/// damping from `cfg.damping`, spin rate `v / (R − d/3)`, the steady state of
/// [`preload_rolling_cambered`] (on the plain, cambered ground) with its contact forces as the
/// initial multipliers. The settings are validated first ([`RigConfig`]'s [`Validate`]; a
/// prescribed `wheel.centre_motion` is refused: [`run_cleat`] runs it); a height-grid file is
/// read here ([`Ground::new`]).
pub fn start_rolling<'a>(red: &'a ReducedTire, cfg: &RigConfig) -> Result<RigStart<'a>, TireError> {
    cfg.validate()?;
    if cfg.wheel.centre_motion.is_some() {
        // the start of a fixed wheel centre: a prescribed motion would be ignored
        return Err(invalid(
            "wheel.centre_motion",
            "is run by the cleat test (run_cleat, `flowmbd-tire cleat` and `sweep`) only: this \
             study steps the tire with its wheel centre fixed",
        ));
    }
    let rayleigh = cfg.damping.rayleigh(red)?;
    let v = cfg.speed_kmh / 3.6;
    let gamma = cfg.wheel.camber();
    let static_preload = preload_cambered(red, &cfg.ground, gamma, cfg.load)?;
    let spin = v / (red.outer_radius - static_preload.patch.deflection / 3.0);
    let pre = preload_rolling_cambered(red, &cfg.ground, gamma, cfg.load, spin, rayleigh.beta)?;
    let mut ground = Ground::new(
        cfg.ground.clone(),
        pre.patch.top,
        v,
        cfg.wheel.lateral_speed(v),
        cfg.settle_time,
    )?
    .with_camber(gamma);
    ground.lateral_reach = red
        .contact_positions
        .iter()
        .map(|s| s[1].abs())
        .fold(0.0, f64::max);
    // a height-grid road: its reference plane lowered by the grid's height under the patch at
    // the start, so that the tire preloaded on the flat road starts on the grid's surface
    if ground.grid().is_some() {
        ground.top -= ground.grid_height_at_centre(0.0);
    }
    let mut sim = RollingTire::new(
        red,
        cfg.rolling.clone(),
        ground,
        rayleigh.alpha,
        rayleigh.beta,
        pre.z.clone(),
        spin,
    )?;
    sim.drive_torque = cfg.wheel.drive_torque;
    if cfg.wheel.spin_rate.is_some() {
        sim.prescribe_spin(cfg.wheel.spin_rate)?;
    }
    sim.state.lambda = pre.patch.lambda.clone();
    for (k, f) in pre.patch.f_c.iter().enumerate() {
        sim.state.contact_force[k % 3] += f;
    }
    Ok(RigStart {
        sim,
        rayleigh,
        static_preload,
        preload: pre,
    })
}

/// Run the cleat test. `progress` receives the fraction done (0..1).
pub fn run_cleat(
    red: &ReducedTire, cfg: &RigConfig, progress: &mut dyn FnMut(f64),
) -> Result<RigResult, TireError> {
    run_cleat_observed(red, cfg, progress, &mut |_, _| Ok(()))
}

/// One step of the rig: the rolling tire advanced by `cfg.rolling.time_step` \[s\], in
/// `cfg.impact.substeps` equal sub-steps while the cleat impact is active
/// (the window of [`ImpactConfig`]). The step of [`run_cleat`]; a tire started with
/// [`start_rolling`] and stepped by it runs the cleat test.
pub fn rig_step(sim: &mut RollingTire<'_>, cfg: &RigConfig) -> Result<(), TireError> {
    let n = if cfg.impact.active(sim.ground(), sim.state.t) {
        cfg.impact.substeps
    } else {
        1
    };
    sim.set_time_step(cfg.rolling.time_step / n as f64)?;
    for _ in 0..n {
        sim.step()?;
    }
    Ok(())
}

/// [`run_cleat`] with an observer called after every step with the step number and the model
/// (e.g. to write VTK snapshots of the patch). With a prescribed wheel-centre motion
/// (`cfg.wheel.centre_motion`) the run is that of [`crate::motion::run_centre_motion`].
pub fn run_cleat_observed(
    red: &ReducedTire, cfg: &RigConfig, progress: &mut dyn FnMut(f64),
    observer: &mut dyn FnMut(usize, &RollingTire) -> Result<(), TireError>,
) -> Result<RigResult, TireError> {
    cfg.validate()?;
    if let Some(motion) = &cfg.wheel.centre_motion {
        return crate::motion::run_centre_motion(red, cfg, motion, progress, observer);
    }
    let RigStart {
        mut sim,
        rayleigh,
        static_preload,
        preload,
    } = start_rolling(red, cfg)?;
    let h = cfg.rolling.time_step;
    let steps = ((cfg.settle_time + cfg.record_time) / h).round() as usize;
    let rec = Recording {
        start: RigStartInfo {
            rayleigh,
            static_preload,
            preload,
        },
        steps,
        dt: h,
    };
    let step = |sim: &mut RollingTire<'_>, _k: usize| rig_step(sim, cfg);
    record_run(red, cfg, rec, &mut sim, |s| s, step, progress, observer)
}

/// What a recorded rig run reports of its start ([`RigStart`] without the rolling tire).
pub(crate) struct RigStartInfo {
    /// Rayleigh coefficients from the damping targets.
    pub rayleigh: Rayleigh,
    /// The static (non-rolling) preload (the loaded modes are those of its patch).
    pub static_preload: Preload,
    /// The rolling preload the tire starts from.
    pub preload: Preload,
}

/// A recorded run: its start, the number of samples and the time between them \[s\].
pub(crate) struct Recording {
    /// The start.
    pub start: RigStartInfo,
    /// Samples (one after every `step`).
    pub steps: usize,
    /// Time between samples \[s\].
    pub dt: f64,
}

/// The sample of the rolling tire after a step (`settle` \[s\]: the time that is `t = 0` of
/// the samples).
fn sample_of(sim: &RollingTire, settle: f64) -> Sample {
    let f = sim.wheel_loads();
    Sample {
        t: sim.state.t - settle,
        fx: f.fx,
        fy: f.fz,
        fz: f.fy,
        mx: f.mx,
        my: f.my,
        mz: f.mz,
        spin: sim.state.theta_d,
        spin_torque: sim.spin_torque(),
        active: sim.active_count(),
        normal_sum: sim.total_normal_force(),
        cleat_nodes: sim.cleat_contacts,
    }
}

/// The recording loop of a rig run: `rec.steps` times `step(state, k)`, then the observer and
/// a [`Sample`] of the rolling tire `sim_of(state)`; the wall and CPU time of the stepping
/// (the observer's excluded) and the loaded modes of the static preload's patch. One loop
/// for the cleat rig ([`run_cleat_observed`], the state its rolling tire) and the prescribed
/// wheel-centre motion ([`crate::motion::run_centre_motion`], a
/// [`crate::motion::CoSimulation`]).
#[allow(clippy::too_many_arguments)]
pub(crate) fn record_run<'a, S>(
    red: &ReducedTire, cfg: &RigConfig, rec: Recording, state: &mut S,
    sim_of: impl Fn(&S) -> &RollingTire<'a>,
    mut step: impl FnMut(&mut S, usize) -> Result<(), TireError>, progress: &mut dyn FnMut(f64),
    observer: &mut dyn FnMut(usize, &RollingTire) -> Result<(), TireError>,
) -> Result<RigResult, TireError> {
    let Recording {
        start:
            RigStartInfo {
                rayleigh: ray,
                static_preload: pre0,
                preload: pre,
            },
        steps,
        dt,
    } = rec;
    // a failure here only loses the reference mode, not the run
    let loaded = loaded_modes(red, &held_nodes(&pre0.patch)).unwrap_or_default();
    let loaded_vertical_mode = dominant_vertical_mode(&loaded).cloned();
    let loaded_longitudinal_mode = dominant_longitudinal_mode(&loaded).cloned();
    let mut samples = Vec::with_capacity(steps);
    let t0 = Instant::now();
    // CPU time of this thread and of the products' worker thread, if any
    let run_cpu = |sim: &RollingTire| {
        thread_cpu_s().map(|c| c + sim.product_worker().and_then(worker_cpu_s).unwrap_or(0.0))
    };
    let c0 = run_cpu(sim_of(state));
    let (mut obs_wall, mut obs_cpu) = (0.0, 0.0);
    for k in 0..steps {
        step(state, k)?;
        let sim = sim_of(state);
        // the observer's output (e.g. VTK files) is not part of the integration cost
        let (w_obs, c_obs) = (Instant::now(), thread_cpu_s());
        observer(k, sim)?;
        obs_wall += w_obs.elapsed().as_secs_f64();
        obs_cpu += thread_cpu_s().zip(c_obs).map_or(0.0, |(b, a)| b - a);
        samples.push(sample_of(sim, cfg.settle_time));
        if k % 200 == 0 {
            progress(k as f64 / steps as f64);
        }
    }
    progress(1.0);
    let sim = sim_of(state);
    Ok(RigResult {
        speed_kmh: cfg.speed_kmh,
        load: cfg.load,
        camber_deg: cfg.wheel.camber_deg,
        dof: red.dof(),
        symmetry: sim.symmetry().describe(),
        preload: pre.patch,
        rayleigh: ray,
        samples,
        dt,
        wall_time_s: t0.elapsed().as_secs_f64() - obs_wall,
        cpu_time_s: c0.zip(run_cpu(sim)).map(|(a, b)| b - a - obs_cpu),
        simulated_s: steps as f64 * dt,
        refactors: sim.refactors,
        stats: sim.stats,
        loaded_vertical_mode,
        loaded_longitudinal_mode,
    })
}

/// CPU time consumed by the calling thread so far \[s\] (`clock_gettime` with
/// `CLOCK_THREAD_CPUTIME_ID`, a cheap vDSO call, so it can be read around every step's
/// observer); `None` where the clock is not available.
#[cfg(unix)]
pub fn thread_cpu_s() -> Option<f64> {
    clock_s(libc::CLOCK_THREAD_CPUTIME_ID)
}

/// The reading of `clock` \[s\] (`clock_gettime`), `None` on failure.
#[cfg(unix)]
fn clock_s(clock: libc::clockid_t) -> Option<f64> {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec for the duration of the call.
    let rc = unsafe { libc::clock_gettime(clock, &mut ts) };
    (rc == 0).then_some(ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9)
}

/// CPU time consumed by the worker thread of the split products so far \[s\]
/// (`pthread_getcpuclockid`); `None` where the clock is not available.
#[cfg(unix)]
pub fn worker_cpu_s(w: &mbd_core::parallel::ProductWorker) -> Option<f64> {
    let thread = w.pthread()?;
    let mut clock: libc::clockid_t = 0;
    // SAFETY: `thread` is the handle of a thread that is still running (the worker is joined
    // only when dropped, and `w` borrows it); `clock` is a valid, writable clockid_t.
    if unsafe { libc::pthread_getcpuclockid(thread as libc::pthread_t, &mut clock) } != 0 {
        return None;
    }
    clock_s(clock)
}

/// CPU time of the worker thread (not available on this platform).
#[cfg(not(unix))]
pub fn worker_cpu_s(_w: &mbd_core::parallel::ProductWorker) -> Option<f64> {
    None
}

/// CPU time of the calling thread (not available on this platform).
#[cfg(not(unix))]
pub fn thread_cpu_s() -> Option<f64> {
    None
}
