//! A rigid slider-crank whose crank is driven at constant angular speed (mbd-core's rotation
//! driver): the multibody demonstration of `flowmbd-belt demo`, checked against the closed-form
//! slider kinematics `x = a cos θ + √(b² − a² sin² θ)`.

use mbd_core::body::BodyState;
use mbd_core::constraints::{DriverLaw, Prismatic, Revolute, RotationDriver, Spherical, Universal};
use mbd_core::forces::Gravity;
use mbd_core::integrators::{State, project_velocities};
use mbd_core::kinematics::euler::from_axis_angle;
use mbd_core::marker::Marker;
use mbd_core::{MbdError, MultibodySystem, RigidBody};
use nalgebra::{Vector3, Vector4};

/// The slider-crank (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliderCrank {
    /// Crank length a \[m\].
    pub crank_length: f64,
    /// Connecting-rod length b \[m\].
    pub rod_length: f64,
    /// Crank, rod and slider masses \[kg\].
    pub masses: [f64; 3],
    /// Crank speed \[rad/s\].
    pub omega: f64,
    /// Initial crank angle \[rad\] (away from the dead centres 0 and π, where the joint
    /// Jacobian is singular).
    pub theta0: f64,
}

impl SliderCrank {
    /// Index of the slider's x coordinate in `q` (7 coordinates (r, p) per body; the slider is
    /// body 2).
    pub const SLIDER_X: usize = 2 * 7;

    /// Crank angle \[rad\] at time `t` \[s\] (the driver's law).
    pub fn crank_angle(&self, t: f64) -> f64 {
        self.theta0 + self.omega * t
    }

    /// Slider position `x = a cos θ + √(b² − a² sin² θ)` \[m\] at crank angle `theta` \[rad\]
    /// (closed-form kinematics).
    pub fn closed_form(&self, theta: f64) -> f64 {
        let (a, b) = (self.crank_length, self.rod_length);
        a * theta.cos() + (b * b - (a * theta.sin()).powi(2)).sqrt()
    }

    /// The system (crank, rod, slider; revolute, spherical, universal and prismatic joints; the
    /// motor as a rotation driver; gravity −y) and its consistent initial state at `theta0`.
    pub fn model(&self) -> Result<(MultibodySystem, State), MbdError> {
        let c = self;
        let (a, b) = (c.crank_length, c.rod_length);
        let z = Vector3::z();
        let mut sys = MultibodySystem::new();
        // slender bars about their long x axis (small) and the two transverse axes
        let bar = |m: f64, l: f64| [m * l * l / 120.0, m * l * l / 12.0, m * l * l / 12.0];
        let crank = sys.add_body(RigidBody::with_principal(
            "crank",
            c.masses[0],
            bar(c.masses[0], a),
        )?);
        let rod = sys.add_body(RigidBody::with_principal(
            "rod",
            c.masses[1],
            bar(c.masses[1], b),
        )?);
        let slider = sys.add_body(RigidBody::with_principal("slider", c.masses[2], [1e-3; 3])?);
        sys.add_constraint(Revolute {
            name: "crank bearing".into(),
            i: Marker::new(None, Vector3::zeros(), z),
            j: Marker::new(Some(crank), Vector3::new(-a / 2.0, 0.0, 0.0), z),
        })?;
        sys.add_constraint(Spherical {
            name: "crank pin".into(),
            i: Marker::point(Some(crank), Vector3::new(a / 2.0, 0.0, 0.0)),
            j: Marker::point(Some(rod), Vector3::new(-b / 2.0, 0.0, 0.0)),
        })?;
        sys.add_constraint(Universal {
            name: "wrist pin".into(),
            i: Marker::new(Some(rod), Vector3::new(b / 2.0, 0.0, 0.0), z),
            // The slider's cross axis is the in-plane normal y: z_rod · y = 0 restrains the rod's spin
            // about its own axis in every configuration (with x it would not at the dead centres).
            j: Marker::new(Some(slider), Vector3::zeros(), Vector3::y()),
        })?;
        sys.add_constraint(Prismatic {
            name: "slide".into(),
            i: Marker::new(None, Vector3::zeros(), Vector3::x()),
            j: Marker::new(Some(slider), Vector3::zeros(), Vector3::x()),
            reference_i: Vector3::y(),
            reference_j: Vector3::y(),
        })?;
        sys.add_constraint(RotationDriver {
            name: "motor".into(),
            i: Marker::new(None, Vector3::zeros(), z),
            j: Marker::point(Some(crank), Vector3::zeros()),
            reference_i: Vector3::x(),
            reference_j: Vector3::x(),
            law: DriverLaw::ConstantSpeed {
                theta0: c.theta0,
                omega: c.omega,
            },
        })?;
        sys.add_force(Gravity {
            g: Vector3::new(0.0, -9.81, 0.0),
        })?;
        let th = c.theta0;
        let pin = Vector3::new(a * th.cos(), a * th.sin(), 0.0);
        let s = Vector3::new(c.closed_form(th), 0.0, 0.0);
        let beta = (-pin.y).atan2(s.x - pin.x);
        let states = [
            BodyState::at_rest(pin / 2.0, from_axis_angle(&z, th)),
            BodyState::at_rest((pin + s) / 2.0, from_axis_angle(&z, beta)),
            BodyState::at_rest(s, Vector4::new(1.0, 0.0, 0.0, 0.0)),
        ];
        let mut s0 = sys.state(0.0, &states)?;
        project_velocities(&sys, &mut s0)?;
        Ok((sys, s0))
    }
}
