//! The belt-drive model seen by the speed-loss procedure ([`crate::speed_loss`]), and its
//! implementations for the flowing crate's models: the flowing-material belt (Ribaric (5.14),
//! [`FlowingBelt`]) and the rotating-mesh nodal belt (Ribaric (5.7), [`NodalBelt`]). The ANCF
//! belt's implementation is [`crate::ancf_drive_model::AncfDrive`].

use flowing::belt::nodal::NodalBelt;
use flowing::belt::{FlowingBelt, Schedule};
use mbd_core::integrators::State;
use mbd_core::{MbdError, SecondOrderSystem};

/// A belt-drive model the speed-loss procedure can run.
pub trait DriveModel: SecondOrderSystem {
    /// Driven pulley speed \[rad/s\] (travel sense) from the velocities.
    fn driven_speed(&self, v: &[f64]) -> f64;
    /// Driver pulley speed \[rad/s\] at time `t`.
    fn driver_speed(&self, t: f64) -> f64;
    /// Consistent state at rest (static equilibrium of the mounted belt) at `t = 0`.
    fn initial_state(&self) -> Result<State, MbdError>;
    /// Replace the driver-speed history.
    fn set_driver_speed(&mut self, s: Schedule);
    /// The load-torque history (extended by the procedure while it runs).
    fn load_mut(&mut self) -> &mut Schedule;
}

/// Coordinates `(s_b, z, θ₂)`: belt travel, the `m` reduced coordinates and the driven pulley.
impl DriveModel for FlowingBelt {
    fn driven_speed(&self, v: &[f64]) -> f64 {
        v[self.n_modes() + 1]
    }

    fn driver_speed(&self, t: f64) -> f64 {
        self.driver_speed.value(t)
    }

    fn initial_state(&self) -> Result<State, MbdError> {
        let m = self.n_modes();
        let z = self.static_equilibrium()?;
        let mut q = vec![0.0; m + 2];
        q[1..=m].copy_from_slice(&z);
        Ok(State::new(0.0, q, vec![0.0; m + 2]))
    }

    fn set_driver_speed(&mut self, s: Schedule) {
        self.driver_speed = s;
    }

    fn load_mut(&mut self) -> &mut Schedule {
        &mut self.load_torque
    }
}

/// Coordinates `(s_b, d, θ₂)`: belt travel, the nodal deflections and the driven pulley.
impl DriveModel for NodalBelt {
    fn driven_speed(&self, v: &[f64]) -> f64 {
        v[self.n_nodal() + 1]
    }

    fn driver_speed(&self, t: f64) -> f64 {
        self.driver_speed.value(t)
    }

    fn initial_state(&self) -> Result<State, MbdError> {
        let d = self.static_equilibrium()?;
        let nd = self.n_nodal();
        let mut q = vec![0.0; nd + 2];
        q[1..=nd].copy_from_slice(&d);
        Ok(State::new(0.0, q, vec![0.0; nd + 2]))
    }

    fn set_driver_speed(&mut self, s: Schedule) {
        self.driver_speed = s;
    }

    fn load_mut(&mut self) -> &mut Schedule {
        &mut self.load_torque
    }
}
