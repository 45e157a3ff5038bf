//! The pulleys' coordinates in an ANCF belt system, shared by the planar and the plate drive
//! (issue 33 item 2): each free pulley (idler or loaded, [`belt::Motion`]) has one
//! coordinate, its travel-sense rotation angle `θ`, numbered after the belt's coordinates in
//! pulley order; a speed-driven pulley has none. Its equation is `I θ̈ = τ − T_a(t) − c θ̇`
//! (Kerkkänen (3.26)), `τ` the travel-sense contact torque.

use crate::sparse::Pattern;
use belt::Pulley;
use mbd_core::MbdError;
use mbd_core::validate::{InvalidField, Validate};

/// Most pulleys of an ANCF belt drive (the contact pass keeps one speed and load per pulley
/// on the stack).
pub const MAX_PULLEYS: usize = 16;

/// The checks of a drive's pulley list shared by the planar and the plate drive: 2 to
/// [`MAX_PULLEYS`] pulleys, each valid ([`belt::Pulley`]'s own checks, named
/// `pulleys[i]…`), no name used twice (`pulleys[i].name`).
pub fn validate_pulleys(pulleys: &[Pulley]) -> Result<(), InvalidField> {
    if pulleys.len() < 2 {
        return Err(InvalidField::new(
            "pulleys",
            format!("need at least 2, got {}", pulleys.len()),
        ));
    }
    if pulleys.len() > MAX_PULLEYS {
        return Err(InvalidField::new(
            "pulleys",
            format!("at most {MAX_PULLEYS} supported, got {}", pulleys.len()),
        ));
    }
    for (i, p) in pulleys.iter().enumerate() {
        p.validate_within(&format!("pulleys[{i}]"))?;
        if pulleys[..i].iter().any(|o| o.name == p.name) {
            return Err(InvalidField::new(
                format!("pulleys[{i}].name"),
                format!("'{}' is used twice", p.name),
            ));
        }
    }
    Ok(())
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
    pub fn new(pulleys: &[Pulley], first: usize) -> Self {
        let mut dof = Vec::with_capacity(pulleys.len());
        let mut free = Vec::new();
        for (i, p) in pulleys.iter().enumerate() {
            if p.is_free() {
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
    pub fn speed(&self, pulleys: &[Pulley], p: usize, t: f64, v: &[f64]) -> f64 {
        match self.dof[p] {
            Some(j) => v[j],
            None => pulleys[p].motion.prescribed_speed(t).unwrap_or(0.0),
        }
    }

    /// [`Self::speed`] of every pulley \[rad/s\].
    pub fn speeds(&self, pulleys: &[Pulley], t: f64, v: &[f64]) -> Vec<f64> {
        (0..pulleys.len())
            .map(|p| self.speed(pulleys, p, t, v))
            .collect()
    }

    /// [`Self::speed`] of every pulley \[rad/s\] and its load `−T_a(t, ω) − c ω` \[N·m\] (the
    /// applied torque of its [`belt::Motion`], Kerkkänen (3.26)), on the stack: the first
    /// `pulleys.len()` entries of each array.
    ///
    /// # Errors
    /// [`MbdError::InvalidInput`] for more than [`MAX_PULLEYS`] pulleys.
    pub fn speeds_and_loads(
        &self,
        pulleys: &[Pulley],
        t: f64,
        v: &[f64],
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
            loads[p] = -pulley.motion.applied_torque(t, omegas[p]).0;
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

    /// Add the free pulleys' inertias to the diagonal of the mass values `m` of `pattern`.
    pub(crate) fn add_inertias(&self, pulleys: &[Pulley], pattern: &Pattern, m: &mut [f64]) {
        for (p, j) in self.free() {
            if let Some(inertia) = pulleys[p].motion.inertia() {
                m[pattern.diagonal_position(j)] += inertia;
            }
        }
    }

    /// Add the free pulleys' viscous damping `c` of `−c ω` to the diagonal of the damping
    /// values `c` of `pattern`.
    pub(crate) fn add_damping(&self, pulleys: &[Pulley], pattern: &Pattern, c: &mut [f64]) {
        for (p, j) in self.free() {
            let damping = pulleys[p].motion.damping();
            if damping > 0.0 {
                c[pattern.diagonal_position(j)] += damping;
            }
        }
    }

    /// The name of coordinate `dof` if it is a pulley's (`pulley "name" angle`).
    pub fn dof_name(&self, pulleys: &[Pulley], dof: usize) -> Option<String> {
        self.free()
            .find(|&(_, j)| j == dof)
            .map(|(p, _)| format!("pulley \"{}\" angle", pulleys[p].name))
    }
}
