//! The travelling string with fixed ends in flowing-material modal coordinates
//! (Ribaric (4.12)–(4.20)).
//!
//! The FE mesh spans the fixed distance between the guide rollers and does not move; the material
//! flows through it with axial speed `ẋ`. With `u = Ψz` (4.16) the material derivative (4.13)
//! gives `u̇ = Ψż + ẋΨ_,x z` (4.17) and `ü = Ψz̈ + ẍΨ_,x z + 2ẋΨ_,x ż + ẋ²Ψ_,xx z` (4.18), and
//! the modal equations (4.20):
//!
//! ```text
//!   z̈ + 2ẋ ΨᵀMΨ_,x ż + (ẍ ΨᵀMΨ_,x + ẋ² ΨᵀMΨ_,xx + Λ) z = Ψᵀf
//! ```
//!
//! The Coriolis term is the velocity-proportional skew ("gyroscopic") term; the model implements
//! [`SecondOrderSystem`] so that mbd-core's integrators integrate it.

use crate::derivative::{DerivativeMethod, FlowLine, mode_shape_derivatives};
use crate::error::{FlowError, invalid};
use crate::gyroscopic::GyroscopicSystem;
use crate::modal::{ModalBasis, sys_mul};
use faer::Mat;
use mbd_core::Workspace;
use mbd_core::{MbdError, SecondOrderSystem, SysMatrix};
use std::f64::consts::PI;

/// Axial motion of the material through the mesh (Ribaric (4.13): `ẋ`, `ẍ`).
#[derive(
    Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields, tag = "kind", rename_all = "snake_case")]
pub enum AxialMotion {
    /// Constant speed `ẋ = speed` \[m/s\].
    Constant {
        /// Axial speed \[m/s\].
        speed: f64,
    },
    /// Prescribed ramp `ẋ = initial_speed + acceleration·t` \[m/s\], `ẍ = acceleration` \[m/s²\].
    Ramp {
        /// Speed at t = 0 \[m/s\].
        initial_speed: f64,
        /// Constant axial acceleration \[m/s²\].
        acceleration: f64,
    },
    /// Prescribed harmonic speed `ẋ = mean + amplitude·sin(2π·frequency·t)`.
    Harmonic {
        /// Mean speed \[m/s\].
        mean: f64,
        /// Speed amplitude \[m/s\].
        amplitude: f64,
        /// Frequency \[Hz\].
        frequency: f64,
    },
    /// Dynamic axial speed: an extra coordinate `x` (axial material displacement) with
    /// `m ẍ = F − d ẋ` (a pulled string of axial inertia `m`); `ẋ(0)` is the initial velocity of
    /// that coordinate.
    Dynamic {
        /// Axial inertia `m` \[kg\].
        mass: f64,
        /// Axial damping `d` \[N·s/m\].
        damping: f64,
        /// Pulling force `F` \[N\].
        force: f64,
    },
}

impl AxialMotion {
    /// Prescribed `(ẋ, ẍ)` at time `t`, or `None` for [`AxialMotion::Dynamic`].
    pub fn prescribed(&self, t: f64) -> Option<(f64, f64)> {
        match *self {
            AxialMotion::Constant { speed } => Some((speed, 0.0)),
            AxialMotion::Ramp {
                initial_speed,
                acceleration,
            } => Some((initial_speed + acceleration * t, acceleration)),
            AxialMotion::Harmonic {
                mean,
                amplitude,
                frequency,
            } => {
                let w = 2.0 * PI * frequency;
                Some((
                    mean + amplitude * (w * t).sin(),
                    amplitude * w * (w * t).cos(),
                ))
            }
            AxialMotion::Dynamic { .. } => None,
        }
    }

    fn validate(&self) -> Result<(), FlowError> {
        let vals: Vec<(&str, f64)> = match *self {
            AxialMotion::Constant { speed } => vec![("speed", speed)],
            AxialMotion::Ramp {
                initial_speed,
                acceleration,
            } => {
                vec![
                    ("initial_speed", initial_speed),
                    ("acceleration", acceleration),
                ]
            }
            AxialMotion::Harmonic {
                mean,
                amplitude,
                frequency,
            } => {
                vec![
                    ("mean", mean),
                    ("amplitude", amplitude),
                    ("frequency", frequency),
                ]
            }
            AxialMotion::Dynamic {
                mass,
                damping,
                force,
            } => {
                if mass.is_nan() || mass <= 0.0 {
                    return Err(invalid(
                        "axial motion: mass",
                        format!("{mass} is not positive"),
                    ));
                }
                vec![("damping", damping), ("force", force)]
            }
        };
        for (n, v) in vals {
            if !v.is_finite() {
                return Err(invalid(
                    format!("axial motion: {n}"),
                    format!("{v} is not finite"),
                ));
            }
        }
        Ok(())
    }
}

/// The flowing-material string (4.20) in modal coordinates.
#[derive(Debug, Clone)]
pub struct FlowingString {
    /// Modal basis (mass-normalised, possibly truncated).
    pub basis: ModalBasis,
    /// `Ψ_,x` (`n_dof × k`).
    pub psi_x: Mat<f64>,
    /// `Ψ_,xx` (`n_dof × k`).
    pub psi_xx: Mat<f64>,
    /// `ΨᵀMΨ_,x` (`k × k`; skew for FE-consistent operators).
    pub m_x: Mat<f64>,
    /// `ΨᵀMΨ_,xx` (`k × k`; `−Λ/c²` for FE-consistent operators on the string).
    pub m_xx: Mat<f64>,
    /// `MΨ` (`n_dof × k`), used to project nodal fields.
    pub m_psi: Mat<f64>,
    /// Axial motion.
    pub motion: AxialMotion,
}

impl FlowingString {
    /// Precomputes the constant matrices of (4.20) from the FE mass matrix `M`, a mass-normalised
    /// basis and the flow lines of the model's DOFs.
    pub fn new(
        mass: &SysMatrix, basis: ModalBasis, lines: &[FlowLine], method: DerivativeMethod,
        motion: AxialMotion,
    ) -> Result<Self, FlowError> {
        motion.validate()?;
        let n = basis.psi.nrows();
        if mass.nrows() != n || mass.ncols() != n {
            return Err(invalid(
                "flowing string: mass matrix",
                format!(
                    "is {}×{}, the mode shapes have {n} rows",
                    mass.nrows(),
                    mass.ncols()
                ),
            ));
        }
        let d = mode_shape_derivatives(lines, method, basis.psi.as_ref())?;
        let m_psi = sys_mul(mass, basis.psi.as_ref());
        let m_x = m_psi.transpose() * &d.d1;
        let m_xx = m_psi.transpose() * &d.d2;
        Ok(Self {
            basis,
            psi_x: d.d1,
            psi_xx: d.d2,
            m_x,
            m_xx,
            m_psi,
            motion,
        })
    }

    /// Number of retained modes `k`.
    pub fn n_modes(&self) -> usize {
        self.basis.len()
    }

    /// The linear system of (4.20) frozen at axial speed `ẋ` and acceleration `ẍ`:
    /// `M = I`, `G = 2ẋΨᵀMΨ_,x`, `K = ẍΨᵀMΨ_,x + ẋ²ΨᵀMΨ_,xx + Λ`.
    pub fn frozen(&self, speed: f64, accel: f64) -> GyroscopicSystem {
        let k = self.n_modes();
        let g = Mat::from_fn(k, k, |i, j| 2.0 * speed * self.m_x[(i, j)]);
        let kk = Mat::from_fn(k, k, |i, j| {
            accel * self.m_x[(i, j)]
                + speed * speed * self.m_xx[(i, j)]
                + if i == j { self.basis.lambda[i] } else { 0.0 }
        });
        GyroscopicSystem {
            mass: Mat::identity(k, k),
            gyro: g,
            stiffness: kk,
        }
    }

    /// Modal coordinates of a nodal field, `z = ΨᵀM u` (exact for `u` in the span of Ψ).
    pub fn project(&self, u: &[f64]) -> Result<Vec<f64>, FlowError> {
        if u.len() != self.m_psi.nrows() {
            return Err(invalid(
                "nodal field",
                format!(
                    "has {} entries, the model has {} DOFs",
                    u.len(),
                    self.m_psi.nrows()
                ),
            ));
        }
        Ok((0..self.n_modes())
            .map(|c| (0..u.len()).map(|r| self.m_psi[(r, c)] * u[r]).sum())
            .collect())
    }

    /// Nodal deflection `u = Ψz` (4.16) \[m\].
    pub fn deflection(&self, z: &[f64]) -> Vec<f64> {
        let p = &self.basis.psi;
        (0..p.nrows())
            .map(|r| (0..z.len()).map(|c| p[(r, c)] * z[c]).sum())
            .collect()
    }

    /// Material velocity `u̇ = Ψż + ẋΨ_,x z` (4.17) \[m/s\].
    pub fn material_velocity(&self, z: &[f64], zdot: &[f64], speed: f64) -> Vec<f64> {
        let p = &self.basis.psi;
        (0..p.nrows())
            .map(|r| {
                (0..z.len())
                    .map(|c| p[(r, c)] * zdot[c] + speed * self.psi_x[(r, c)] * z[c])
                    .sum()
            })
            .collect()
    }

    /// `(ẋ, ẍ)` at time `t` for positions `q` and velocities `v` of the system (the last entry
    /// is the axial coordinate for [`AxialMotion::Dynamic`]).
    pub fn axial_state(&self, t: f64, v: &[f64]) -> (f64, f64) {
        match self.motion.prescribed(t) {
            Some(sa) => sa,
            None => {
                let AxialMotion::Dynamic {
                    mass,
                    damping,
                    force,
                } = self.motion
                else {
                    unreachable!()
                };
                let s = v[self.n_modes()];
                (s, (force - damping * s) / mass)
            }
        }
    }

    /// Energy-like invariant `H = ½żᵀż + ½zᵀ(ẋ²ΨᵀMΨ_,xx + Λ)z` \[J per unit modal mass\], conserved
    /// at constant speed when `ΨᵀMΨ_,x` is skew (FE-consistent derivatives).
    pub fn hamiltonian(&self, z: &[f64], zdot: &[f64], speed: f64) -> f64 {
        let k = self.n_modes();
        let mut h = 0.5 * zdot.iter().map(|x| x * x).sum::<f64>();
        for i in 0..k {
            h += 0.5 * self.basis.lambda[i] * z[i] * z[i];
            for j in 0..k {
                h += 0.5 * speed * speed * z[i] * self.m_xx[(i, j)] * z[j];
            }
        }
        h
    }
}

/// `q = [z; x]` (the axial coordinate only for dynamic motion), `M = diag(I, m)`.
impl SecondOrderSystem for FlowingString {
    fn n_q(&self) -> usize {
        self.n_modes() + usize::from(matches!(self.motion, AxialMotion::Dynamic { .. }))
    }

    fn mass_is_constant(&self) -> bool {
        true
    }

    fn mass(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        let n = self.n_q();
        let k = self.n_modes();
        let m = match self.motion {
            AxialMotion::Dynamic { mass, .. } => mass,
            _ => 1.0,
        };
        Ok(SysMatrix::Dense(Mat::from_fn(n, n, |i, j| {
            if i != j {
                0.0
            } else if i < k {
                1.0
            } else {
                m
            }
        })))
    }

    fn forces(
        &self, t: f64, q: &[f64], v: &[f64], f: &mut [f64], _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        let k = self.n_modes();
        let (s, a) = self.axial_state(t, v);
        if !(s.is_finite() && a.is_finite()) {
            return Err(MbdError::NonFinite {
                what: "axial speed of the flowing string".into(),
                t,
            });
        }
        for i in 0..k {
            let mut r = -self.basis.lambda[i] * q[i];
            for j in 0..k {
                r -= 2.0 * s * self.m_x[(i, j)] * v[j]
                    + (a * self.m_x[(i, j)] + s * s * self.m_xx[(i, j)]) * q[j];
            }
            f[i] = r;
        }
        if let AxialMotion::Dynamic { damping, force, .. } = self.motion {
            f[k] = force - damping * v[k];
        }
        Ok(())
    }
}

/// Triangular pluck `u(x)` of peak `amplitude` \[m\] at `x_peak` \[m\] on a string between fixed ends
/// at `a` and `b`, sampled at `positions` (the initial condition of Ribaric Fig. 4-6).
pub fn triangular_pluck(
    positions: &[f64], a: f64, b: f64, x_peak: f64, amplitude: f64,
) -> Result<Vec<f64>, FlowError> {
    if !(x_peak > a && x_peak < b) {
        return Err(invalid(
            "pluck position",
            format!("{x_peak} m must lie strictly between the ends {a} and {b} m"),
        ));
    }
    if !amplitude.is_finite() {
        return Err(invalid("pluck amplitude", "not finite"));
    }
    Ok(positions
        .iter()
        .map(|&x| {
            if x <= a || x >= b {
                0.0
            } else if x <= x_peak {
                amplitude * (x - a) / (x_peak - a)
            } else {
                amplitude * (b - x) / (b - x_peak)
            }
        })
        .collect())
}

/// Uniformly sampled time history of a [`FlowingString`] run.
#[derive(Debug, Clone, Default)]
pub struct TimeHistory {
    /// Sample times \[s\].
    pub t: Vec<f64>,
    /// Positions `q` (modal coordinates, then the axial coordinate if dynamic) per sample.
    pub q: Vec<Vec<f64>>,
    /// Velocities per sample.
    pub v: Vec<Vec<f64>>,
}

/// Integrates `sys` from `(q0, v0)` at t = 0 to `t_end` \[s\] with mbd-core's fixed-step RK4 of
/// step `h` \[s\], keeping every `every`-th step (sampling period `every · h`). `progress` sees the
/// current time at every kept sample; answering `ControlFlow::Break(())` stops the run there,
/// returning the samples so far (a cancelled run).
pub fn simulate_rk4<R: mbd_core::integrators::Proceed>(
    sys: &FlowingString, q0: Vec<f64>, v0: Vec<f64>, t_end: f64, h: f64, every: usize,
    mut progress: impl FnMut(f64) -> R,
) -> Result<TimeHistory, FlowError> {
    if every == 0 {
        return Err(invalid("sampling", "every must be at least 1"));
    }
    let mut hist = TimeHistory::default();
    let mut count = 0usize;
    mbd_core::Rk4::new(h).integrate(sys, mbd_core::State::new(0.0, q0, v0), t_end, |s| {
        let mut go_on = true;
        if count.is_multiple_of(every) {
            hist.t.push(s.t);
            hist.q.push(s.q.clone());
            hist.v.push(s.v.clone());
            go_on = progress(s.t).proceed();
        }
        count += 1;
        if go_on {
            std::ops::ControlFlow::Continue(())
        } else {
            std::ops::ControlFlow::Break(())
        }
    })?;
    Ok(hist)
}
