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
//! (`h` = `rig.rolling.time_step`; the last internal step ends exactly on `t + H`). The inputs
//! are held over the communication step (zero-order hold, FMI 3.0 co-simulation); the spin
//! rate goes linearly to the new input over the first internal step
//! ([`PrescribedSpin`](crate::dynamics::PrescribedSpin)), and a changed height is met by the
//! contact at the end of the first internal step.

use crate::error::TireError;
use crate::ground::GroundKind;
use crate::reduced::ReducedTire;
use crate::rig::{RigConfig, start_rolling};
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
        motion.validate_within("motion")?;
        let mut rig = rig.clone();
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
        let mut cs = Self {
            sim: start.sim,
            rig,
            last: *motion,
            internal_steps: 0,
        };
        cs.apply(motion, [0.0; 3])?;
        Ok(cs)
    }

    /// The motion of the rig's steady start ([`start_rolling`] at `rig.load` and
    /// `rig.speed_kmh` on the flat road): the wheel centre at the rolling preload's height
    /// `−top` \[m\], moving straight ahead at the speed, spinning at the start spin rate
    /// `v/(R − d/3)` \[rad/s\]. A [`CoSimulation`] started with it starts smoothly (the tire's
    /// FMU takes it as its inputs' start values).
    pub fn rig_start(red: &ReducedTire, rig: &RigConfig) -> Result<WheelMotion, MotionError> {
        let mut rig = rig.clone();
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
        // flat road does not depend on time, so the round-off of n h/n against h is harmless)
        self.sim.set_time_step(h / n as f64)?;
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
