//! Modes of the loaded tire: the reduced tire (7.17) not rolling, wheel fixed, with the contact
//! nodes that carry the preload held on the ground (sticking contact in all three directions).
//!
//! Ribaric §8.3 identifies the dominant vertical spindle frequency of the cleat test with a
//! vertical in-plane mode of the loaded tire (his 5th mode, 64 Hz). The free-node modes of the
//! reduction (contact and rim nodes fixed) and the rim-fixed modes of `flowmbd-tire modes` are
//! not that tire: in the rig the patch sits on the drum. This module gives those modes and ranks
//! them by how strongly the spindle sees them.
//!
//! With the held contact-node rows `A = T_c,held` (3 h × n_z), the constrained coordinates are
//! `z = N ψ`, `A N = 0` (`N` an orthonormal null-space basis), and `Nᵀ K_z N ψ = ω² Nᵀ M_z N ψ`.
//! Each mode `φ = N ψ` (`φᵀ M_z φ = 1`) has the spindle force `F = −K_r φ` (7.2).
//!
//! **Effective spindle mass.** Let the ground move the held nodes rigidly by `u` along a
//! Cartesian direction `e` (vertical or longitudinal). Write `z = Σ φ_k q_k + z_s u` with the
//! static influence vector `z_s = K_z⁻¹Aᵀ(A K_z⁻¹Aᵀ)⁻¹ d` (`d` = `e` at every held node), which is
//! K-orthogonal to every `φ_k` (`K_z z_s = Aᵀμ`, `A φ_k = 0`). Projecting `M_z z̈ + K_z z = Aᵀλ`
//! gives `q̈_k + ω_k² q_k = −Γ_k ü` with `Γ_k = φ_kᵀ M_z z_s`; below resonance
//! `q_k ≈ −Γ_k ü / ω_k²`, and the spindle force gains `Σ_k m_k ü` along `e` with
//!
//! ```text
//!   m_k = (K_r φ_k)·e Γ_k / ω_k²    [kg],
//! ```
//!
//! the mode's effective spindle mass (the analogue of the effective modal mass of base-excited
//! structures). Its sum over all modes equals `(K_r G M_z z_s)·e` with the constrained
//! flexibility `G = N (Nᵀ K_z N)⁻¹ Nᵀ`, which the tests check against a direct constrained
//! solve. Modes with a large vertical `m_k` are the vertical in-plane modes the cleat excites.

use crate::error::{TireError, invalid, linalg};
use crate::reduced::ReducedTire;
use faer::prelude::*;
use faer::{Mat, Side};
use serde::Serialize;

/// One mode of the loaded tire.
#[derive(Debug, Clone, Serialize)]
pub struct LoadedMode {
    /// Natural frequency \[Hz\].
    pub hz: f64,
    /// Spindle force of the mass-normalised mode `−K_r φ` (7.2): longitudinal `Fx`, vertical
    /// `Fy`, lateral `Fz` \[N/√kg\].
    pub spindle: [f64; 3],
    /// Effective vertical spindle mass `m_k` for vertical ground motion \[kg\] (module docs).
    pub vertical_mass: f64,
    /// Effective longitudinal spindle mass `m_k` for longitudinal ground motion \[kg\].
    pub longitudinal_mass: f64,
}

impl LoadedMode {
    /// Share of the vertical component in the mode's spindle force, `Fy² / |F|²` (1: purely
    /// vertical; in-plane modes have no lateral part).
    pub fn vertical_share(&self) -> f64 {
        let [x, y, z] = self.spindle;
        let n = x * x + y * y + z * z;
        if n > 0.0 { y * y / n } else { 0.0 }
    }
}

/// Wheel-frame component index of the vertical direction (the spindle force's `Fy`).
pub(crate) const VERTICAL: usize = 2;
/// Wheel-frame component index of the longitudinal direction (`Fx`).
pub(crate) const LONGITUDINAL: usize = 0;
/// Wheel-frame component index of the lateral (axle) direction (`Fz`).
const LATERAL: usize = 1;

/// The modes of the loaded tire with the contact nodes `held` (indices into the reduced tire's
/// contact nodes, e.g. those with a positive preload multiplier) fixed to the ground; all
/// modes of the constrained pencil, ascending. See the module documentation.
///
/// Errors: a `held` index out of range, a singular stiffness or mass.
pub fn loaded_modes(red: &ReducedTire, held: &[usize]) -> Result<Vec<LoadedMode>, TireError> {
    let a = held_rows(red, held)?;
    let n = reduction::linalg::null_space(a.as_ref(), 1e-12)
        .map_err(|e| linalg("null space of the held contact-node rows", e))?;
    let kn = n.transpose() * &red.k * &n;
    let mn = n.transpose() * &red.m * &n;
    let modes = fe_model::dense_modes(kn.as_ref(), mn.as_ref(), n.ncols())?;
    let phi = &n * &modes.vectors;
    let fr = &red.kr * &phi;
    // static influence vectors for vertical and longitudinal ground motion
    let zs = influence(red, &a, held.len())?;
    let gamma = phi.transpose() * &red.m * &zs;
    Ok((0..phi.ncols())
        .map(|k| {
            let w2 = modes.values[k];
            let mass = |c: usize, col: usize| {
                if w2 > 0.0 {
                    fr[(c, k)] * gamma[(k, col)] / w2
                } else {
                    0.0
                }
            };
            LoadedMode {
                hz: modes.frequencies_hz[k],
                spindle: [
                    -fr[(LONGITUDINAL, k)],
                    -fr[(VERTICAL, k)],
                    -fr[(LATERAL, k)],
                ],
                vertical_mass: mass(VERTICAL, 0),
                longitudinal_mass: mass(LONGITUDINAL, 1),
            }
        })
        .collect())
}

/// Static influence vectors `z_s = K_z⁻¹Aᵀ(A K_z⁻¹Aᵀ)⁻¹ d` (columns: vertical, longitudinal
/// unit motion of the `h` held nodes). Zero columns when nothing is held.
/// The rows of the contact-node basis `T_c` at the contact nodes `held` (indices into the
/// reduced tire's contact nodes; x, y, z rows each): `a` of the constraint `a z = 0` that
/// holds them on the ground.
///
/// Errors: a `held` index out of range.
pub(crate) fn held_rows(red: &ReducedTire, held: &[usize]) -> Result<Mat<f64>, TireError> {
    let nc = red.n_contact();
    if let Some(&i) = held.iter().find(|&&i| i >= nc) {
        return Err(invalid(
            "held",
            format!("contact node {i} out of range (the tire has {nc})"),
        ));
    }
    Ok(Mat::from_fn(3 * held.len(), red.n_z(), |r, j| {
        red.tc[(3 * held[r / 3] + r % 3, j)]
    }))
}

pub(crate) fn influence(red: &ReducedTire, a: &Mat<f64>, h: usize) -> Result<Mat<f64>, TireError> {
    let nz = red.n_z();
    if h == 0 {
        return Ok(Mat::zeros(nz, 2));
    }
    let llt = red
        .k
        .llt(Side::Lower)
        .map_err(|e| linalg("Cholesky of the reduced stiffness K_z", e))?;
    let x = llt.solve(a.transpose().to_owned());
    let y = a * &x;
    let d = Mat::from_fn(3 * h, 2, |r, col| {
        let c = if col == 0 { VERTICAL } else { LONGITUDINAL };
        if r % 3 == c { 1.0 } else { 0.0 }
    });
    let mu = y
        .llt(Side::Lower)
        .map_err(|e| linalg("Cholesky of the held nodes' flexibility A K_z⁻¹ Aᵀ", e))?
        .solve(d);
    Ok(&x * &mu)
}

/// The loaded mode with the largest effective vertical spindle mass (the vertical in-plane mode
/// the spindle sees most), `None` without modes.
pub fn dominant_vertical_mode(modes: &[LoadedMode]) -> Option<&LoadedMode> {
    modes
        .iter()
        .max_by(|a, b| a.vertical_mass.abs().total_cmp(&b.vertical_mass.abs()))
}

/// The loaded mode with the largest effective longitudinal spindle mass, `None` without modes.
pub fn dominant_longitudinal_mode(modes: &[LoadedMode]) -> Option<&LoadedMode> {
    modes.iter().max_by(|a, b| {
        a.longitudinal_mass
            .abs()
            .total_cmp(&b.longitudinal_mass.abs())
    })
}

/// The loaded modes at the static preload: the tire pressed onto `ground` with `load` \[N\]
/// ([`super::statics::preload`]), the contact nodes with a positive multiplier held.
pub fn loaded_modes_at_preload(
    red: &ReducedTire, ground: &super::ground::GroundConfig, load: f64,
) -> Result<(super::statics::Preload, Vec<LoadedMode>), TireError> {
    let pre = super::statics::preload(red, ground, load)?;
    let modes = loaded_modes(red, &held_nodes(&pre.patch))?;
    Ok((pre, modes))
}

/// The contact nodes that carry a patch solution (positive normal multiplier), in order.
pub fn held_nodes(patch: &super::statics::PatchSolution) -> Vec<usize> {
    (0..patch.lambda.len())
        .filter(|&i| patch.lambda[i] > 0.0)
        .collect()
}
