//! Complex modes of the rotating (rolling) tire in the ground-fixed frame: the quadratic
//! eigenproblem of the flowing-material equations at a constant spin rate.
//!
//! # Equations
//! The mesh frame does not spin (seed note U16), so the reduced coordinates `z` describe the
//! deflection field `δ = T z` seen from the ground. With the spin rate held at `θ̇ = Ω`
//! (`θ̈ = 0`; a speed-controlled wheel, as on a drum) rows 3–4 of Ribaric (7.17), with the
//! material acceleration (7.14)–(7.16) `δ̈ = T z̈ + 2Ω T_,θ ż + Ω² T_,θθ z + ω × (ω × s)` and
//! the Galerkin projection of seed note U15 ([`super::rolling`]), read
//!
//! ```text
//!   M_z z̈ + (2Ω G₁ + α M_z + β K_z) ż + (K_z + Ω² G₂ + β Ω K₁) z = −Ω² c_s + T_cᵀ f^c
//! ```
//!
//! with the gyroscopic (Coriolis) matrix `2Ω G₁`, `G₁ = TᵀM T_,θ` (skew for uniform rings), the
//! convective/centrifugal stiffness `Ω² G₂`, `G₂ = TᵀM T_,θθ` (symmetric, negative: the
//! softening of Ribaric's moving string, seed note §4 "centrifugal"), and the Rayleigh damping
//! `C = αM + βK` acting with `βK` on the material strain rate `T ż + Ω T_,θ z`. The constant
//! load `Ω² c_s` of the rigid rotation only moves the equilibrium: the model is linear (the
//! matrices do not depend on `z`; in particular there is no geometric stiffening by the hoop
//! stress of rotation, as in Ribaric's model), so the modes about the rolling equilibrium are
//! those of the homogeneous equation. Holding the contact nodes `h` of the patch on the ground,
//! `T_{c,h} z = 0` (the loaded tire of [`super::loaded`]), gives the same equation on the null
//! space `z = N y`.
//!
//! With `z = φ e^{λt}` this is the quadratic eigenproblem
//! `(λ² M + λ C_Ω + K_Ω) φ = 0`, solved densely through the state matrix of
//! [`flowing::GyroscopicSystem`] (Ribaric (4.29), faer's non-symmetric eigen solver). Each
//! eigenvalue `λ = σ + iω` with `ω > 0` is one mode: frequency `ω/2π`, growth rate `σ`, damping
//! ratio `−σ/|λ|`; [`super::harmonics`] labels its circumferential order `n` and whether it
//! travels forward (with the rotation) or backward in the ground frame.
//!
//! At `Ω = 0` the eigenvalues are those of `K_z φ = ω² M_z φ` (undamped: `λ = ±iω`; Rayleigh
//! damping: `|λ| = ω`), i.e. the frequencies of `flowmbd-tire modes`.

use crate::error::{TireError, invalid, linalg};
use crate::ground::GroundConfig;
use crate::harmonics::{Harmonic, WaveDirection};
use crate::loaded::{held_nodes, held_rows};
use crate::reduced::{ReducedTire, TreadBasis};
use crate::statics::{preload, preload_rolling};
use faer::{Mat, MatRef, c64};
use flowing::gyroscopic::GyroscopicSystem;
use serde::Serialize;
use std::f64::consts::PI;

/// One complex mode of the rotating tire (module docs).
#[derive(Debug, Clone, Serialize)]
pub struct RotatingMode {
    /// Damped frequency `Im λ / 2π` in the ground frame \[Hz\].
    pub hz: f64,
    /// Undamped natural frequency `|λ| / 2π` \[Hz\].
    pub natural_hz: f64,
    /// Growth rate `Re λ` \[1/s\] (negative: decaying; positive: unstable).
    pub growth_rate: f64,
    /// Damping ratio `−Re λ / |λ|`.
    pub damping_ratio: f64,
    /// Dominant circumferential order `n`.
    pub n: usize,
    /// Forward (with the rotation), backward, or standing.
    pub direction: WaveDirection,
    /// Signed travelling share (+1 forward, −1 backward), [`super::harmonics`].
    pub travelling: f64,
    /// Share of the tread's displacement energy in the harmonics `±n`.
    pub order_share: f64,
    /// Radial, tangential and lateral fractions of the order-`n` energy at the tread
    /// ([`Harmonic::parts`]).
    pub parts: [f64; 3],
    /// Reduced coordinates of the mode `φ` (complex, normalised to `φᴴ M_z φ = 1`).
    #[serde(skip)]
    pub shape: Vec<c64>,
}

/// The matrices of the flowing-material equations (module docs): a [`ReducedTire`]'s
/// projections or the full FE model's nodal ones (`T = I`).
#[derive(Debug, Clone, Copy)]
pub struct FlowingMatrices<'a> {
    /// `M_z` \[kg\].
    pub m: MatRef<'a, f64>,
    /// `K_z` \[N/m\].
    pub k: MatRef<'a, f64>,
    /// `G₁ = TᵀM T_,θ` \[kg/rad\].
    pub g1: MatRef<'a, f64>,
    /// `G₂ = TᵀM T_,θθ` \[kg/rad²\].
    pub g2: MatRef<'a, f64>,
    /// `K₁ = TᵀK T_,θ` \[N/(m·rad)\].
    pub k1: MatRef<'a, f64>,
}

impl<'a> FlowingMatrices<'a> {
    /// The reduced tire's matrices.
    pub fn of(red: &'a ReducedTire) -> Self {
        Self {
            m: red.m.as_ref(),
            k: red.k.as_ref(),
            g1: red.g1.as_ref(),
            g2: red.g2.as_ref(),
            k1: red.k1.as_ref(),
        }
    }
}

/// Settings of the rotating-mode solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RotatingOptions {
    /// Spin rate `Ω = θ̇` \[rad/s\] (positive: material moves towards increasing θ).
    pub spin: f64,
    /// Rayleigh α \[1/s\].
    pub alpha: f64,
    /// Rayleigh β \[s\].
    pub beta: f64,
    /// Modes whose undamped frequency `|λ|/2π` is at most this are returned \[Hz\].
    pub max_hz: f64,
}

/// The complex modes of the rotating tire (module docs) with the contact nodes `held` (indices
/// into the reduced tire's contact nodes) held on the ground, ascending in frequency.
///
/// Errors: a `held` index out of range, a reduced tire without the tread rows that label the
/// modes (written before they existed: reduce again), invalid options, or a failed solve.
pub fn rotating_modes(
    red: &ReducedTire, held: &[usize], opt: &RotatingOptions,
) -> Result<Vec<RotatingMode>, TireError> {
    let a = held_rows(red, held)?;
    let tread = red.tread.as_ref().ok_or_else(|| {
        invalid(
            "reduced tire",
            "has no tread rows to label the modes' circumferential order \
             (written by an older flowmbd: reduce the tire again)",
        )
    })?;
    spinning_modes(FlowingMatrices::of(red), tread, a.as_ref(), opt)
}

/// The complex modes of the flowing-material equations given by `mats` (module docs) under
/// the linear constraints `a z = 0` (`a` with no rows: none), labelled with the tread rows
/// `tread` (whose columns are the coordinates of `mats`); ascending in frequency, undamped
/// frequencies up to `opt.max_hz`.
pub fn spinning_modes(
    mats: FlowingMatrices<'_>, tread: &TreadBasis, a: MatRef<'_, f64>, opt: &RotatingOptions,
) -> Result<Vec<RotatingMode>, TireError> {
    for (name, v) in [("spin", opt.spin), ("alpha", opt.alpha), ("beta", opt.beta)] {
        if !v.is_finite() {
            return Err(invalid(name, format!("{v} is not finite")));
        }
    }
    if opt.max_hz.is_nan() || opt.max_hz <= 0.0 {
        return Err(invalid("max_hz", format!("{} is not positive", opt.max_hz)));
    }
    let nz = mats.m.nrows();
    if tread.rows.ncols() != nz || a.ncols() != nz {
        return Err(invalid(
            "tread rows / constraints",
            format!(
                "have {} / {} columns for {nz} coordinates",
                tread.rows.ncols(),
                a.ncols()
            ),
        ));
    }
    let st = state_eigen(mats, a, opt)?;
    let scale = st.eig.values.iter().fold(0.0f64, |s, l| s.max(l.norm()));
    let mut out = Vec::new();
    for (col, &lam) in st.eig.values.iter().enumerate() {
        // oscillating modes whose undamped frequency is in range (not the overdamped high
        // modes, which the gyroscopic term gives a small imaginary part at speed)
        if lam.im <= 1e-9 * scale || lam.norm() / (2.0 * PI) > opt.max_hz {
            continue;
        }
        out.push(st.mode(mats, tread, col, opt.spin));
    }
    out.sort_by(|a, b| a.hz.total_cmp(&b.hz));
    Ok(out)
}

/// The state-space eigen decomposition of the constrained flowing-material equations.
pub(crate) struct StateModes {
    /// Null-space basis `N` of the constraints (`z = N y`).
    pub n: Mat<f64>,
    /// The system on `y` (`M_y = NᵀM N`, `C_y`, `K_y`).
    pub sys: GyroscopicSystem,
    /// Eigenvalues and right eigenvectors of its state matrix.
    pub eig: flowing::gyroscopic::StateEigen,
}

/// `C_Ω = 2ΩG₁ + αM + βK` and `K_Ω = K + Ω²G₂ + βΩK₁` (module docs).
pub(crate) fn spin_matrices(
    mats: FlowingMatrices<'_>, opt: &RotatingOptions,
) -> (Mat<f64>, Mat<f64>) {
    let nz = mats.m.nrows();
    let (w, al, be) = (opt.spin, opt.alpha, opt.beta);
    let c = Mat::from_fn(nz, nz, |i, j| {
        2.0 * w * mats.g1[(i, j)] + al * mats.m[(i, j)] + be * mats.k[(i, j)]
    });
    let k = Mat::from_fn(nz, nz, |i, j| {
        mats.k[(i, j)] + w * w * mats.g2[(i, j)] + be * w * mats.k1[(i, j)]
    });
    (c, k)
}

/// Solve the state-space eigenproblem of the equations on the null space of `a`.
pub(crate) fn state_eigen(
    mats: FlowingMatrices<'_>, a: MatRef<'_, f64>, opt: &RotatingOptions,
) -> Result<StateModes, TireError> {
    let nz = mats.m.nrows();
    let (c, k) = spin_matrices(mats, opt);
    let n = if a.nrows() == 0 {
        Mat::<f64>::identity(nz, nz)
    } else {
        reduction::linalg::null_space(a, 1e-12)
            .map_err(|e| linalg("null space of the held contact-node rows", e))?
    };
    let nt = n.transpose();
    let sys = GyroscopicSystem::new(nt * mats.m * &n, nt * &c * &n, nt * &k * &n)
        .map_err(|e| linalg("rotating tire", e))?;
    let eig = sys
        .state_eigen()
        .map_err(|e| linalg("rotating tire eigenproblem", e))?;
    Ok(StateModes { n, sys, eig })
}

impl StateModes {
    /// The labelled mode of the eigenvalue `col` (module docs).
    pub fn mode(
        &self, mats: FlowingMatrices<'_>, tread: &TreadBasis, col: usize, spin: f64,
    ) -> RotatingMode {
        let nz = mats.m.nrows();
        let ny = self.n.ncols();
        let lam = self.eig.values[col];
        // z = N y, normalised to φᴴ M φ = 1
        let mut z = vec![c64::new(0.0, 0.0); nz];
        for (i, zi) in z.iter_mut().enumerate() {
            for j in 0..ny {
                *zi += self.eig.vectors[(j, col)] * self.n[(i, j)];
            }
        }
        let mut mass = 0.0;
        for i in 0..nz {
            for j in 0..nz {
                mass += (z[i].conj() * z[j]).re * mats.m[(i, j)];
            }
        }
        let s = if mass > 0.0 { 1.0 / mass.sqrt() } else { 1.0 };
        z.iter_mut().for_each(|v| *v *= s);
        let d: Vec<c64> = (0..tread.rows.nrows())
            .map(|r| (0..nz).fold(c64::new(0.0, 0.0), |acc, j| acc + z[j] * tread.rows[(r, j)]))
            .collect();
        let Harmonic {
            order,
            order_share,
            travelling,
            direction,
            parts,
        } = tread.harmonic(&d, spin);
        let mag = lam.norm();
        RotatingMode {
            hz: lam.im / (2.0 * PI),
            natural_hz: mag / (2.0 * PI),
            growth_rate: lam.re,
            damping_ratio: if mag > 0.0 { -lam.re / mag } else { 0.0 },
            n: order,
            direction,
            travelling,
            order_share,
            parts,
            shape: z,
        }
    }
}

/// The modes of the rotating tire at one rolling speed, free and loaded.
#[derive(Debug, Clone, Serialize)]
pub struct SpeedModes {
    /// Rolling speed \[km/h\].
    pub speed_kmh: f64,
    /// Spin rate `Ω = v / R_e` with the effective rolling radius `R_e = R₀ − d/3` of the rig
    /// ([`super::rig::start_rolling`]) \[rad/s\].
    pub spin: f64,
    /// Contact nodes held in the loaded tire (positive multiplier of the rolling preload).
    pub held_nodes: usize,
    /// Modes of the free tire (rim fixed, nothing held).
    pub free: Vec<RotatingMode>,
    /// Modes of the loaded tire (the rolling preload's patch held).
    pub loaded: Vec<RotatingMode>,
}

/// The free and loaded modes of the tire rolling at `speed_kmh` on `ground` under the vertical
/// `load` \[N\]: spin rate as in the cleat rig, `Ω = v/(R₀ − d/3)` with the static preload's
/// deflection `d`; the loaded tire holds the contact nodes that carry the rolling preload
/// ([`preload_rolling`], spin `Ω`, Rayleigh `β`). `alpha`, `beta`, `max_hz` as in
/// [`RotatingOptions`].
pub fn modes_at_speed(
    red: &ReducedTire, ground: &GroundConfig, load: f64, speed_kmh: f64, (alpha, beta): (f64, f64),
    max_hz: f64,
) -> Result<SpeedModes, TireError> {
    if !(speed_kmh.is_finite() && speed_kmh >= 0.0) {
        return Err(invalid("speed", format!("{speed_kmh} km/h is not ≥ 0")));
    }
    let d = preload(red, ground, load)?.patch.deflection;
    let spin = speed_kmh / 3.6 / (red.outer_radius - d / 3.0);
    let held = held_nodes(&preload_rolling(red, ground, load, spin, beta)?.patch);
    let opt = RotatingOptions {
        spin,
        alpha,
        beta,
        max_hz,
    };
    Ok(SpeedModes {
        speed_kmh,
        spin,
        held_nodes: held.len(),
        free: rotating_modes(red, &[], &opt)?,
        loaded: rotating_modes(red, &held, &opt)?,
    })
}
