//! The rolling tire driven by a prescribed wheel-centre motion over a flat road (issue 38,
//! items 1, 2 and 4): the co-simulation step of the tire FMU (`apps/tire-fmu`) and of the
//! Python `flowmbd.tire.CoSimulation`, one implementation for both.
//!
//! # Inputs ([`WheelMotion`])
//! Road frame: ISO 8855 earth-fixed axes on the road surface (x forward, y left, z up).
//! - wheel-centre position: its height `z` above the road \[m\] (the horizontal position does
//!   not enter on the flat road);
//! - wheel-centre velocity over the road `(v_x, v_y, v_z)` \[m/s\] in the road frame;
//! - orientation of the wheel: yaw angle ψ of the wheel plane about the road's z axis \[rad\]
//!   (the wheel's heading) and camber angle γ (rim tilt about the wheel's x axis) \[rad\]; the
//!   wheel frame is the road frame turned by ψ about z, then by γ about x (ISO 8855 wheel
//!   frame: x forward in the wheel plane, y along the spin axis, z up). The camber is the
//!   rig's ([`crate::rig::WheelInputs::camber_deg`], ISO 8855: positive when the top of the
//!   wheel leans to the right, within ±[`crate::rig::MAX_CAMBER_DEG`]): the road tilted by −γ
//!   about the x-parallel line through the contact centre ([`crate::Ground::camber`]), whose
//!   plane lies at the perpendicular distance `z` from the wheel centre (the ground's `top`
//!   at `−z/cos γ` on the wheel's vertical).
//! - spin rate Ω of the wheel about its axis \[rad/s\], prescribed
//!   ([`crate::RollingTire::prescribe_spin`]).
//!
//! The wheel frame's velocity over the road is `V_x = cos ψ v_x + sin ψ v_y`,
//! `V_y = −sin ψ v_x + cos ψ v_y` (forward rolling only: `V_x > 0`), so the slip angle is
//! `tan α = −V_y/V_x` and the longitudinal slip `κ = Ω R_e/V_x − 1` (Pacejka, *Tire and
//! Vehicle Dynamics*, §1.2). The rig holds the wheel and moves the road under it: the ground's
//! top at `−z`, surface speed `V_x`, lateral velocity `−V_y` ([`crate::Ground`],
//! [`crate::RollingTire::set_ground`]).
//!
//! # Accelerating spindle
//! The wheel frame translates with the wheel centre; its acceleration `a` over a
//! communication step is the difference quotient of the velocity inputs,
//! `a = R(−ψ) (v(t + H) − v(t))/H` in the wheel frame, and the tire carries the inertial load
//! `−M a` of that rigid translation ([`crate::TireDynamics::set_frame_acceleration`]; the
//! spindle force then includes the tire's `−m a`). Not included: the loads of the frame's
//! rotation (yaw rate ψ̇: centripetal and Coriolis loads of order `m |ψ̇| |V|`, e.g. 0.6 % of a
//! 4.4 kN load for a 50 kg tire at 60 km/h and 0.05 rad/s).
//!
//! # Outputs
//! The six spindle loads of the tire on the wheel in the ISO 8855 wheel frame at the wheel
//! centre ([`WheelLoads`]: `F_x` forward, `F_y` left, `F_z` up = the carried load; `M_x`,
//! `M_y`, `M_z` about the centre; with a camber γ ≠ 0 in the W-axis orientation, z along the
//! road normal and y in the road plane), and the torque that holds the prescribed spin
//! ([`crate::RollingTire::spin_torque`]).
//!
//! # Time stepping
//! A communication step `H` is taken as `n = ⌈H/h⌉` equal internal steps of the rolling tire
//! (`h` = `rig.rolling.time_step`; the last internal step ends on `t + H`, to round-off: an
//! internal step within [`ROUND_OFF`] of the current one is kept). The inputs
//! are held over the communication step (zero-order hold, FMI 3.0 co-simulation); the spin
//! rate goes linearly to the new input over the first internal step
//! ([`PrescribedSpin`](crate::dynamics::PrescribedSpin)), and a changed height is met by the
//! contact at the end of the first internal step.
//!
//! # Prescribed series (`flowmbd-tire cleat`)
//! A [`CentreMotion`] (`[rig.wheel.centre_motion]`) gives the inputs as time series; the rig
//! run ([`run_centre_motion`]) samples them at the communication points `t_k = k H` and takes
//! the communication steps with [`CoSimulation::do_step`]: what an FMI importer does with the
//! FMU and the same input signal, through the same code.

use crate::error::TireError;
use crate::ground::GroundKind;
use crate::reduced::ReducedTire;
use crate::rig::{Recording, RigConfig, RigResult, RigStartInfo, record_run, start_rolling};
use crate::rolling::{RollingTire, WheelLoads};
use crate::rolling_config::Symmetry;
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// The wheel-centre motion over the road at one communication point (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct WheelMotion {
    /// Height `z` of the wheel centre above the road surface \[m\].
    pub height: f64,
    /// Velocity of the wheel centre over the road, road frame x, y, z \[m/s\].
    pub velocity: [f64; 3],
    /// Yaw angle ψ of the wheel plane about the road's z axis \[rad\].
    pub yaw: f64,
    /// Camber angle γ about the wheel's x axis \[rad\] (only 0 is supported yet).
    pub camber: f64,
    /// Spin rate Ω of the wheel about its axis \[rad/s\] (positive: rolling forwards).
    pub spin_rate: f64,
}

impl Default for WheelMotion {
    /// The default rig's wheel: 60 km/h straight ahead, at the height and spin of no preload
    /// (take them from the rig's start, [`CoSimulation::rig_start`]).
    fn default() -> Self {
        Self {
            height: 0.5,
            velocity: [60.0 / 3.6, 0.0, 0.0],
            yaw: 0.0,
            camber: 0.0,
            spin_rate: 33.0,
        }
    }
}

/// Largest yaw-angle magnitude of [`WheelMotion::yaw`] \[rad\] (the slip angle's bound of the
/// rig, 45°, is checked on the velocity).
pub const MAX_YAW: f64 = std::f64::consts::PI;

impl Validate for WheelMotion {
    /// Finite values, a positive height, a yaw within ±π, a camber within the rig's
    /// ±[`crate::rig::MAX_CAMBER_DEG`], a forward wheel-frame speed `V_x > 0` and a slip angle
    /// within the rig's ±45°.
    fn validate(&self) -> Result<(), InvalidField> {
        check::positive("height", self.height, "m")?;
        for (c, v) in ["x", "y", "z"].iter().zip(self.velocity) {
            check::finite(&format!("velocity.{c}"), v)?;
        }
        check::within("yaw", self.yaw, -MAX_YAW, MAX_YAW, "rad")?;
        let max = crate::rig::MAX_CAMBER_DEG.to_radians();
        check::within("camber", self.camber, -max, max, "rad")?;
        check::within(
            "spin_rate",
            self.spin_rate,
            -crate::rig::MAX_SPIN_RATE,
            crate::rig::MAX_SPIN_RATE,
            "rad/s",
        )?;
        let [vx, vy] = self.wheel_velocity();
        check::positive("velocity (forward speed in the wheel frame)", vx, "m/s")?;
        let alpha = (-vy / vx).atan().to_degrees();
        check::within(
            "velocity (slip angle in degrees)",
            alpha,
            -crate::rig::MAX_SLIP_ANGLE_DEG,
            crate::rig::MAX_SLIP_ANGLE_DEG,
            "deg",
        )
    }
}

impl WheelMotion {
    /// The horizontal velocity of the wheel centre in the wheel frame `(V_x, V_y)` \[m/s\]:
    /// the road-frame velocity turned by `−ψ`.
    pub fn wheel_velocity(&self) -> [f64; 2] {
        let (s, c) = self.yaw.sin_cos();
        let [vx, vy, _] = self.velocity;
        [c * vx + s * vy, -s * vx + c * vy]
    }

    /// A road-frame vector turned into the wheel frame (by `−ψ` about z).
    fn in_wheel_frame(&self, v: [f64; 3]) -> [f64; 3] {
        let (s, c) = self.yaw.sin_cos();
        [c * v[0] + s * v[1], -s * v[0] + c * v[1], v[2]]
    }
}

/// Relative difference of an internal step from the current one below which
/// [`CoSimulation::do_step`] keeps the current step (round-off of the master's time
/// arithmetic, a few ulps of `H`).
pub const ROUND_OFF: f64 = 1e-12;

/// Errors of the co-simulation: invalid inputs and failures of the tire.
pub type MotionError = TireError;

/// The rolling tire driven by a [`WheelMotion`] (module documentation): the co-simulation
/// slave of the tire FMU.
pub struct CoSimulation<'a> {
    /// The rolling tire (full model: any lateral input may come).
    pub sim: RollingTire<'a>,
    /// The rig it was started on.
    rig: RigConfig,
    /// The inputs of the last communication point.
    last: WheelMotion,
    /// Internal steps taken so far.
    pub internal_steps: usize,
}

impl<'a> CoSimulation<'a> {
    /// Start the tire of `red` on the rig `rig` (damping, integration, friction, the preload
    /// `rig.load`) on the flat road without cleat, rolling steadily at the wheel-frame speed
    /// `V_x` of `motion` (the rolling preload of [`start_rolling`], full model), with its spin
    /// prescribed at `motion.spin_rate` and the ground placed at `motion.height` (a height
    /// other than the preload's `−top` is met by the contact in the first step: start with
    /// [`CoSimulation::rig_start`] for a smooth one). Errors: invalid
    /// settings or inputs (field names `rig.…`, `motion.…`), a failed preload.
    pub fn start(
        red: &'a ReducedTire, rig: &RigConfig, motion: &WheelMotion,
    ) -> Result<Self, MotionError> {
        Self::begin(red, rig, motion).map(|(cs, _)| cs)
    }

    /// [`CoSimulation::start`], also returning what a recorded run reports of the rig's
    /// start ([`start_rolling`]: the Rayleigh coefficients and the preloads;
    /// [`run_centre_motion`]).
    fn begin(
        red: &'a ReducedTire, rig: &RigConfig, motion: &WheelMotion,
    ) -> Result<(Self, RigStartInfo), MotionError> {
        motion.validate_within("motion")?;
        let mut rig = rig.clone();
        // the motion replaces a prescribed series (this is how a series is run)
        rig.wheel.centre_motion = None;
        rig.ground.kind = GroundKind::Road;
        rig.ground.cleat = false;
        rig.rolling.symmetry = Symmetry::Off;
        rig.settle_time = 0.0;
        rig.record_time = 0.0;
        let [vx, vy] = motion.wheel_velocity();
        rig.speed_kmh = vx * 3.6;
        rig.wheel.drive_torque = 0.0;
        rig.wheel.slip_angle_deg = (-vy / vx).atan().to_degrees();
        rig.wheel.spin_rate = Some(motion.spin_rate);
        rig.wheel.camber_deg = motion.camber.to_degrees();
        let start = start_rolling(red, &rig).map_err(|e| prefix("rig", e))?;
        let info = RigStartInfo {
            rayleigh: start.rayleigh,
            static_preload: start.static_preload,
            preload: start.preload,
        };
        let mut cs = Self {
            sim: start.sim,
            rig,
            last: *motion,
            internal_steps: 0,
        };
        cs.apply(motion, [0.0; 3])?;
        Ok((cs, info))
    }

    /// The motion of the rig's steady start ([`start_rolling`] at `rig.load` and
    /// `rig.speed_kmh` on the flat road): the wheel centre at the rolling preload's height
    /// `−top` \[m\], moving straight ahead at the speed, spinning at the start spin rate
    /// `v/(R − d/3)` \[rad/s\]. A [`CoSimulation`] started with it starts smoothly (the tire's
    /// FMU takes it as its inputs' start values).
    pub fn rig_start(red: &ReducedTire, rig: &RigConfig) -> Result<WheelMotion, MotionError> {
        let mut rig = rig.clone();
        rig.wheel.centre_motion = None;
        rig.ground.kind = GroundKind::Road;
        rig.ground.cleat = false;
        rig.settle_time = 0.0;
        rig.record_time = 0.0;
        let start = start_rolling(red, &rig).map_err(|e| prefix("rig", e))?;
        Ok(WheelMotion {
            height: -start.preload.patch.top,
            velocity: [rig.speed_kmh / 3.6, 0.0, 0.0],
            yaw: 0.0,
            camber: 0.0,
            spin_rate: start.sim.state.theta_d,
        })
    }

    /// The rig the tire runs on (flat road, no cleat, full model).
    pub fn rig(&self) -> &RigConfig {
        &self.rig
    }

    /// The inputs of the last communication point.
    pub fn motion(&self) -> &WheelMotion {
        &self.last
    }

    /// Time \[s\].
    pub fn time(&self) -> f64 {
        self.sim.state.t
    }

    /// Sets the ground, the spin and the frame acceleration `a` (wheel frame) of `m`.
    fn apply(&mut self, m: &WheelMotion, a: [f64; 3]) -> Result<(), MotionError> {
        let [vx, vy] = m.wheel_velocity();
        let mut ground = self.sim.ground().clone();
        // the tilted road's plane at the perpendicular distance `height` from the centre
        ground.top = -m.height / m.camber.cos();
        ground.camber = m.camber;
        ground.speed = vx;
        ground.lateral_speed = -vy;
        self.sim.set_ground(ground)?;
        self.sim.prescribe_spin(Some(m.spin_rate))?;
        self.sim.set_frame_acceleration(a)
    }

    /// One communication step of `h` \[s\] with the inputs `m` held over it (module
    /// documentation): `⌈h/time_step⌉` internal steps ending on `t + h`. Returns the loads at
    /// the end. Errors: invalid inputs (nothing is stepped), a failed internal step (the
    /// state is that of the last internal step taken).
    pub fn do_step(&mut self, h: f64, m: &WheelMotion) -> Result<WheelLoads, MotionError> {
        check::positive("communication_step", h, "s").map_err(TireError::from)?;
        m.validate_within("motion")?;
        let hi = self.rig.rolling.time_step;
        let n = (h / hi * (1.0 - 1e-12)).ceil().max(1.0);
        if n > crate::rig::MAX_RIG_STEPS {
            return Err(TireError::from(InvalidField::new(
                "communication_step",
                format!(
                    "{} s is {n:e} internal steps of {} s, more than {:e}",
                    check::show(h),
                    check::show(hi),
                    crate::rig::MAX_RIG_STEPS
                ),
            )));
        }
        let n = n as usize;
        let (v0, v1) = (self.last.velocity, m.velocity);
        let dv = [
            (v1[0] - v0[0]) / h,
            (v1[1] - v0[1]) / h,
            (v1[2] - v0[2]) / h,
        ];
        self.apply(m, m.in_wheel_frame(dv))?;
        self.last = *m;
        // equal internal steps (one factorisation of the iteration matrix per step size; the
        // flat road does not depend on time, so the round-off of n h/n against h is harmless).
        // An internal step that differs from the current one by round-off only keeps it: a
        // master that steps by `t_(k+1) − t_k` (FMPy) passes `H` give or take an ulp, which
        // would otherwise refactor the iteration matrix (and change the stale-matrix iterates
        // within their tolerance) for nothing.
        let hi_new = h / n as f64;
        let hi_now = self.sim.config().time_step;
        if (hi_new - hi_now).abs() > ROUND_OFF * hi_now {
            self.sim.set_time_step(hi_new)?;
        }
        for _ in 0..n {
            self.sim.step()?;
            self.internal_steps += 1;
        }
        Ok(self.sim.wheel_loads())
    }
}

/// `e` with its field prefixed by `root.` (the rig names its fields relative to itself).
fn prefix(root: &str, e: TireError) -> TireError {
    match e {
        TireError::Invalid { item, reason } => TireError::Invalid {
            item: format!("{root}.{item}"),
            reason,
        },
        other => other,
    }
}

/// Most points of a [`CentreMotion`] series (8 columns of 10⁶ values: 64 MB).
pub const MAX_MOTION_POINTS: usize = 1_000_000;

/// A prescribed wheel-centre motion (issue 38, items 1 and 4): the inputs of the
/// co-simulation ([`WheelMotion`], the tire FMU's inputs `z`, `vx`, `vy`, `vz`, `yaw`,
/// `camber`, `spin_rate`) as time series over the rig run, `[rig.wheel.centre_motion]`.
///
/// Each input is piecewise linear in time between the points `(time[i], value[i])` and held at
/// its first and last value outside them; an absent column holds the value of the rig's steady
/// start ([`CoSimulation::rig_start`]: the preload's height, `speed_kmh` straight ahead, yaw and
/// camber 0, the free-rolling spin rate). The run ([`run_centre_motion`]) samples the series
/// at `t_k = k H` (time from the start of the run, `H` = [`communication_step`]) and holds the
/// sample over `[t_k, t_k + H]` (zero-order hold, as an FMI importer does), lasting
/// `settle_time + record_time`; its samples are taken at `t_k + H`, with `t = 0` at
/// `settle_time` as in the cleat test. Frames as in the module documentation (road frame for
/// the velocity, ISO 8855 wheel frame for the loads; W-axis orientation with camber).
///
/// [`communication_step`]: CentreMotion::communication_step
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CentreMotion {
    /// Times of the points \[s\] from the start of the run, finite and strictly increasing
    /// (1 to 10⁶ points).
    pub time: Vec<f64>,
    /// Height `z` of the wheel centre above the road \[m\] at the points (positive).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<Vec<f64>>,
    /// Velocity `v_x` of the wheel centre over the road, road frame \[m/s\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity_x: Option<Vec<f64>>,
    /// Velocity `v_y` of the wheel centre over the road, road frame (left) \[m/s\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity_y: Option<Vec<f64>>,
    /// Velocity `v_z` of the wheel centre over the road, road frame (up) \[m/s\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity_z: Option<Vec<f64>>,
    /// Yaw angle ψ of the wheel plane about the road's z axis \[rad\] (within ±π).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub yaw: Option<Vec<f64>>,
    /// Camber angle γ about the wheel's x axis \[rad\] (ISO 8855, within the rig's ±30°).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camber: Option<Vec<f64>>,
    /// Spin rate Ω of the wheel about its axis \[rad/s\] (prescribed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spin_rate: Option<Vec<f64>>,
    /// Communication step `H` \[s\]: the series is sampled every `H` and each sample held
    /// over `⌈H/h⌉` equal internal steps (`h` = `rolling.time_step`), one recorded sample per
    /// communication step (the cleat study's spectra up to 500 Hz need `H` ≤ 1 ms). Absent:
    /// `rolling.time_step`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub communication_step: Option<f64>,
}

impl CentreMotion {
    /// The columns given, with their field names, in [`WheelMotion`] order.
    fn columns(&self) -> [(&'static str, Option<&Vec<f64>>); 7] {
        [
            ("height", self.height.as_ref()),
            ("velocity_x", self.velocity_x.as_ref()),
            ("velocity_y", self.velocity_y.as_ref()),
            ("velocity_z", self.velocity_z.as_ref()),
            ("yaw", self.yaw.as_ref()),
            ("camber", self.camber.as_ref()),
            ("spin_rate", self.spin_rate.as_ref()),
        ]
    }

    /// The piecewise-linear value of `column` at `t` \[s\], held beyond the ends: between
    /// the points `i`, `i + 1` the weighted mean `w v_i + (1 − w) v_{i+1}` with
    /// `w = (t_{i+1} − t)/(t_{i+1} − t_i)` (exact at the points; the arithmetic of FMPy's
    /// `Input.interpolate`, so that an FMI importer given the same table feeds the FMU the
    /// same numbers).
    fn interpolate(&self, column: &[f64], t: f64) -> f64 {
        let time = &self.time;
        // (a series that fails validation gives NaN, refused by the step's input check)
        let at = |i: usize| column.get(i).copied().unwrap_or(f64::NAN);
        let i = time.partition_point(|&s| s <= t);
        if i == 0 {
            return at(0);
        }
        if i == time.len() {
            return at(i - 1);
        }
        let (t0, t1) = (time[i - 1], time[i]);
        let w = (t1 - t) / (t1 - t0);
        w * at(i - 1) + (1.0 - w) * at(i)
    }

    /// The inputs at `t` \[s\]: the given columns interpolated, the others those of `base`.
    pub fn at(&self, t: f64, base: &WheelMotion) -> WheelMotion {
        let v = |c: &Option<Vec<f64>>, b: f64| c.as_ref().map_or(b, |c| self.interpolate(c, t));
        WheelMotion {
            height: v(&self.height, base.height),
            velocity: [
                v(&self.velocity_x, base.velocity[0]),
                v(&self.velocity_y, base.velocity[1]),
                v(&self.velocity_z, base.velocity[2]),
            ],
            yaw: v(&self.yaw, base.yaw),
            camber: v(&self.camber, base.camber),
            spin_rate: v(&self.spin_rate, base.spin_rate),
        }
    }

    /// The values of the absent columns: the rig's steady start ([`CoSimulation::rig_start`],
    /// solved only when the height or the spin rate is absent), else `speed_kmh` straight
    /// ahead, upright.
    pub fn base(&self, red: &ReducedTire, rig: &RigConfig) -> Result<WheelMotion, MotionError> {
        if self.height.is_none() || self.spin_rate.is_none() {
            return CoSimulation::rig_start(red, rig);
        }
        Ok(WheelMotion {
            height: self.height.as_ref().map_or(0.0, |h| h[0]),
            velocity: [rig.speed_kmh / 3.6, 0.0, 0.0],
            yaw: 0.0,
            camber: 0.0,
            spin_rate: self.spin_rate.as_ref().map_or(0.0, |w| w[0]),
        })
    }
}

impl Validate for CentreMotion {
    /// 1 to [`MAX_MOTION_POINTS`] points of finite, strictly increasing time; every column
    /// given as long as `time` (checked before its values) with finite values, a positive
    /// height, a yaw within ±π, a camber within the rig's ±30° and a spin rate within
    /// ±[`crate::rig::MAX_SPIN_RATE`]; a positive communication step. The forward speed and the
    /// slip angle of the interpolated inputs are checked at each communication point
    /// ([`WheelMotion`]'s `Validate`).
    fn validate(&self) -> Result<(), InvalidField> {
        let n = self.time.len();
        check::size("time", n, 1, MAX_MOTION_POINTS)?;
        for (name, col) in self.columns() {
            if let Some(c) = col
                && c.len() != n
            {
                return Err(InvalidField::new(
                    name,
                    format!("has {} values, time has {n}", c.len()),
                ));
            }
        }
        for (i, t) in self.time.iter().enumerate() {
            check::finite(&format!("time[{i}]"), *t)?;
            if i > 0 && *t <= self.time[i - 1] {
                return Err(InvalidField::new(
                    format!("time[{i}]"),
                    format!(
                        "must be greater than time[{}] = {} s (strictly increasing), got {} s",
                        i - 1,
                        check::show(self.time[i - 1]),
                        check::show(*t)
                    ),
                ));
            }
        }
        let camber = crate::rig::MAX_CAMBER_DEG.to_radians();
        let spin = crate::rig::MAX_SPIN_RATE;
        for (name, col) in self.columns() {
            for (i, v) in col.into_iter().flatten().enumerate() {
                let field = format!("{name}[{i}]");
                match name {
                    "height" => check::positive(&field, *v, "m")?,
                    "yaw" => check::within(&field, *v, -MAX_YAW, MAX_YAW, "rad")?,
                    "camber" => check::within(&field, *v, -camber, camber, "rad")?,
                    "spin_rate" => check::within(&field, *v, -spin, spin, "rad/s")?,
                    _ => check::finite(&field, *v)?,
                }
            }
        }
        if let Some(h) = self.communication_step {
            check::positive("communication_step", h, "s")?;
        }
        Ok(())
    }
}

/// The rig run of a prescribed wheel-centre motion `motion` (= `rig.wheel.centre_motion`;
/// [`CentreMotion`]): the co-simulation of the tire FMU ([`CoSimulation`]) started at the
/// inputs of `t = 0` and stepped by communication steps `H` with the inputs sampled at each
/// step's start, recorded as a cleat-test result ([`RigResult`]: one sample per
/// communication step, `dt = H`, `t = 0` at `settle_time`; the loads of the samples as in
/// [`crate::rig::Sample`]). The observer sees the rolling tire after every communication
/// step. Errors: the rig's (`rig.validate`), an input that is invalid at a communication point
/// (field `wheel.centre_motion`, the time and the input named), a failed step.
pub fn run_centre_motion(
    red: &ReducedTire, rig: &RigConfig, motion: &CentreMotion, progress: &mut dyn FnMut(f64),
    observer: &mut dyn FnMut(usize, &RollingTire) -> Result<(), TireError>,
) -> Result<RigResult, TireError> {
    rig.validate()?;
    let base = motion.base(red, rig)?;
    let h = rig.sample_step();
    let steps = ((rig.settle_time + rig.record_time) / h).round() as usize;
    let (mut cs, start) =
        CoSimulation::begin(red, rig, &motion.at(0.0, &base)).map_err(|e| at_time(0.0, e))?;
    let rec = Recording {
        start,
        steps,
        dt: h,
    };
    let step = |cs: &mut CoSimulation<'_>, k: usize| {
        let t = k as f64 * h;
        cs.do_step(h, &motion.at(t, &base))
            .map(|_| ())
            .map_err(|e| at_time(t, e))
    };
    let mut r = record_run(
        red,
        rig,
        rec,
        &mut cs,
        |cs| &cs.sim,
        step,
        progress,
        observer,
    )?;
    // the frame of the loads at the end of the run (W-axis orientation with a camber)
    r.camber_deg = cs.motion().camber.to_degrees();
    Ok(r)
}

/// An invalid input `motion.…` of the co-simulation at time `t` \[s\] as an error of the
/// rig's `wheel.centre_motion` naming the time and the input; other errors unchanged.
fn at_time(t: f64, e: TireError) -> TireError {
    match e {
        TireError::Invalid { item, reason } if item.starts_with("motion") => TireError::Invalid {
            item: "wheel.centre_motion".into(),
            reason: format!(
                "the input at t = {} s: {}: {reason}",
                check::show(t),
                item.trim_start_matches("motion.")
            ),
        },
        other => other,
    }
}
