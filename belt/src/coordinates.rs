//! The pulleys' coordinates in a belt-drive system, one numbering for every belt model (the
//! flowing and nodal belts' [`crate::Motion`]s, the ANCF drives' [`crate::Pulley`]s): each free
//! pulley (idler or loaded, [`Motion::is_free`]) has one coordinate, its travel-sense rotation
//! angle `θ`, numbered in pulley order from a first index (after the belt's coordinates); a
//! speed-driven pulley has none. Its equation is `I θ̈ = τ − T_a(t) − c θ̇` (Kerkkänen (3.26)),
//! `τ` the travel-sense contact torque.

use crate::layout::MAX_PULLEYS;
use crate::{Motion, Pulley};
use mbd_core::MbdError;

/// What turns with a [`Motion`]: a pulley, or the motion itself.
pub trait HasMotion {
    /// How it turns.
    fn motion(&self) -> &Motion;
}

impl HasMotion for Motion {
    fn motion(&self) -> &Motion {
        self
    }
}

impl HasMotion for Pulley {
    fn motion(&self) -> &Motion {
        &self.motion
    }
}

/// Which pulleys have a coordinate and which (module documentation).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PulleyCoordinates {
    /// Coordinate of each pulley's angle (`None`: speed-driven).
    dof: Vec<Option<usize>>,
    /// The free pulleys, in pulley order.
    free: Vec<usize>,
}

impl PulleyCoordinates {
    /// The free pulleys of `pulleys` numbered from coordinate `first` on.
    pub fn new(pulleys: &[impl HasMotion], first: usize) -> Self {
        let mut dof = Vec::with_capacity(pulleys.len());
        let mut free = Vec::new();
        for (i, p) in pulleys.iter().enumerate() {
            if p.motion().is_free() {
                dof.push(Some(first + free.len()));
                free.push(i);
            } else {
                dof.push(None);
            }
        }
        Self { dof, free }
    }

    /// Number of pulley coordinates.
    pub fn count(&self) -> usize {
        self.free.len()
    }

    /// Coordinate of pulley `p`'s angle, if it is free.
    pub fn dof(&self, p: usize) -> Option<usize> {
        self.dof.get(p).copied().flatten()
    }

    /// The free pulleys with their coordinates, in pulley order.
    pub fn free(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.free
            .iter()
            .filter_map(|&p| self.dof[p].map(|j| (p, j)))
    }

    /// Travel-sense angular speed of pulley `p` of `pulleys` at `(t, v)` \[rad/s\]: the
    /// velocity coordinate of a free pulley, the prescribed history of a speed-driven one.
    pub fn speed(&self, pulleys: &[impl HasMotion], p: usize, t: f64, v: &[f64]) -> f64 {
        match self.dof[p] {
            Some(j) => v[j],
            None => pulleys[p].motion().prescribed_speed(t).unwrap_or(0.0),
        }
    }

    /// [`Self::speed`] of every pulley \[rad/s\].
    pub fn speeds(&self, pulleys: &[impl HasMotion], t: f64, v: &[f64]) -> Vec<f64> {
        (0..pulleys.len())
            .map(|p| self.speed(pulleys, p, t, v))
            .collect()
    }

    /// [`Self::speed`] of every pulley \[rad/s\] and its load `−T_a(t, ω) − c ω` \[N·m\] (the
    /// applied torque of its [`Motion`], Kerkkänen (3.26)), on the stack: the first
    /// `pulleys.len()` entries of each array.
    ///
    /// # Errors
    /// [`MbdError::InvalidInput`] for more than [`MAX_PULLEYS`] pulleys.
    pub fn speeds_and_loads(
        &self, pulleys: &[impl HasMotion], t: f64, v: &[f64],
    ) -> Result<([f64; MAX_PULLEYS], [f64; MAX_PULLEYS]), MbdError> {
        let np = pulleys.len();
        if np > MAX_PULLEYS {
            return Err(MbdError::InvalidInput {
                item: "pulleys".into(),
                reason: format!("at most {MAX_PULLEYS} supported, got {np}"),
            });
        }
        let mut omegas = [0.0; MAX_PULLEYS];
        let mut loads = [0.0; MAX_PULLEYS];
        for (p, pulley) in pulleys.iter().enumerate() {
            omegas[p] = self.speed(pulleys, p, t, v);
            loads[p] = -pulley.motion().applied_torque(t, omegas[p]).0;
        }
        Ok((omegas, loads))
    }

    /// Subtract the load torques `loads` \[N·m\] (one per pulley) from the free pulleys' rows
    /// of `f`.
    pub fn subtract_loads(&self, loads: &[f64], f: &mut [f64]) {
        for (p, j) in self.free() {
            f[j] -= loads[p];
        }
    }

    /// The name of coordinate `dof` if it is a pulley's (`pulley "name" angle`).
    pub fn dof_name(&self, pulleys: &[Pulley], dof: usize) -> Option<String> {
        self.free()
            .find(|&(_, j)| j == dof)
            .map(|(p, _)| format!("pulley \"{}\" angle", pulleys[p].name))
    }
}
