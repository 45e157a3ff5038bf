//! Models shared by the integrator tests (each test binary uses a subset).
#![allow(dead_code)]

use faer::Mat;
use mbd_core::Workspace;
use mbd_core::{ForceTangent, MbdError, SecondOrderSystem, SysMatrix};

/// Diagonal dense matrix.
pub fn diagonal(d: &[f64]) -> SysMatrix {
    SysMatrix::Dense(Mat::from_fn(d.len(), d.len(), |i, j| {
        if i == j { d[i] } else { 0.0 }
    }))
}

/// Undamped linear oscillator `m ẍ + k x = 0` (exact solution `x₀ cos ωt`, `ω = √(k/m)`), with
/// the analytic tangent when `tangent` (else finite differences).
pub struct Oscillator {
    /// Mass \[kg\].
    pub m: f64,
    /// Stiffness \[N/m\].
    pub k: f64,
    /// Whether [`SecondOrderSystem::force_tangent`] is analytic.
    pub tangent: bool,
}

impl Oscillator {
    /// Unit mass, angular frequency `omega` \[rad/s\], analytic tangent.
    pub fn unit(omega: f64) -> Self {
        Self {
            m: 1.0,
            k: omega * omega,
            tangent: true,
        }
    }
}

impl SecondOrderSystem for Oscillator {
    fn n_q(&self) -> usize {
        1
    }
    fn mass_is_constant(&self) -> bool {
        true
    }
    fn mass(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        Ok(diagonal(&[self.m]))
    }
    fn forces(
        &self, _t: f64, q: &[f64], _v: &[f64], f: &mut [f64], _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        f[0] = -self.k * q[0];
        Ok(())
    }
    fn force_tangent(
        &self, _t: f64, _q: &[f64], _v: &[f64], _ws: &mut Workspace,
    ) -> Result<Option<ForceTangent>, MbdError> {
        if !self.tangent {
            return Ok(None);
        }
        Ok(Some(ForceTangent {
            stiffness: diagonal(&[self.k]),
            damping: diagonal(&[0.0]),
        }))
    }
}

/// Point masses `m[i]` with `dim` coordinates each (the last one vertical) under gravity `−g`
/// and, on the vertical coordinate, the lift force `2 m g t/lift` (none for `lift = ∞`).
pub struct PointMasses {
    /// Masses \[kg\].
    pub m: Vec<f64>,
    /// Coordinates per mass.
    pub dim: usize,
    /// Gravity \[m/s²\].
    pub g: f64,
    /// Time \[s\] at which the lift force reaches twice the weight.
    pub lift: f64,
}

impl SecondOrderSystem for PointMasses {
    fn n_q(&self) -> usize {
        self.dim * self.m.len()
    }
    fn mass_is_constant(&self) -> bool {
        true
    }
    fn mass(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        let d: Vec<f64> = self
            .m
            .iter()
            .flat_map(|&m| std::iter::repeat_n(m, self.dim))
            .collect();
        Ok(diagonal(&d))
    }
    fn forces(
        &self, t: f64, _q: &[f64], _v: &[f64], f: &mut [f64], _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        f.fill(0.0);
        for (i, m) in self.m.iter().enumerate() {
            f[self.dim * i + self.dim - 1] = -m * self.g + 2.0 * m * self.g * t / self.lift;
        }
        Ok(())
    }
    fn force_tangent(
        &self, _t: f64, _q: &[f64], _v: &[f64], _ws: &mut Workspace,
    ) -> Result<Option<ForceTangent>, MbdError> {
        let n = self.n_q();
        Ok(Some(ForceTangent {
            stiffness: SysMatrix::Dense(Mat::zeros(n, n)),
            damping: SysMatrix::Dense(Mat::zeros(n, n)),
        }))
    }
}
