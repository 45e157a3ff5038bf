//! Which mode of the rolling, loaded tire carries a line of the spindle-force spectrum: the
//! modal participation of the complex modes of [`super::rotating`] in the spindle force's
//! response to ground motion at the line's frequency.
//!
//! The held patch nodes (the loaded tire of [`super::loaded`]) move rigidly with the ground by
//! `u(t) e` (`e` vertical for the `F_y` line, longitudinal for `F_x`); as in
//! [`super::loaded`], `z = N y + z_s u` with the static influence vector `z_s`. The rotating
//! equations of [`super::rotating`] on `y` become
//!
//! ```text
//!   M_y ÿ + C_y ẏ + K_y y = −Nᵀ(M z_s ü + C_Ω z_s u̇ + K_Ω z_s u),
//! ```
//!
//! and the spindle force of the tire on the rim is `F = −K_r(N y + z_s u)` (Ribaric (7.2)), of
//! which `−K_r N y` is the dynamic (resonant) part. With the state matrix `X = V Λ V⁻¹` of
//! `x = [y; ẏ]` and the harmonic input `u = e^{iωt}` (forcing `g = [0; M_y⁻¹ f(ω)]`), the
//! response is a sum over the eigenvalues `λ_k`,
//!
//! ```text
//!   F_c(ω) = Σ_k (c v_k)(V⁻¹ g)_k / (iω − λ_k),   c = [−(K_r N)_c  0],
//! ```
//!
//! the modal expansion of the frequency response of a non-symmetric (gyroscopic, damped)
//! system. The term of `λ_k` plus that of its conjugate is mode `k`'s contribution to the line;
//! its share of the sum of the contributions' magnitudes is the mode's participation.

use crate::error::{TireError, invalid, linalg};
use crate::harmonics::WaveDirection;
use crate::loaded::{LONGITUDINAL, VERTICAL, held_rows, influence};
use crate::reduced::ReducedTire;
use crate::rotating::{FlowingMatrices, RotatingOptions, spin_matrices, state_eigen};
use faer::linalg::solvers::Solve;
use faer::{Mat, Side, c64};
use serde::Serialize;
use std::f64::consts::PI;

/// Spindle-force component of a spectrum line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SpindleComponent {
    /// `F_x`, excited by longitudinal ground motion.
    Longitudinal,
    /// `F_y`, excited by vertical ground motion.
    Vertical,
}

/// A mode's participation in a spindle-force line (module docs).
#[derive(Debug, Clone, Serialize)]
pub struct LineMode {
    /// Frequency of the line \[Hz\].
    pub line_hz: f64,
    /// Damped frequency of the mode \[Hz\].
    pub hz: f64,
    /// Circumferential order of the mode.
    pub n: usize,
    /// Forward, backward or standing.
    pub direction: WaveDirection,
    /// Damping ratio.
    pub damping_ratio: f64,
    /// Lateral fraction of the order-n tread motion.
    pub lateral_share: f64,
    /// Share of the line's modal sum `Σ_k |F_k|` (0..1).
    pub share: f64,
    /// The mode's complex contribution (real, imaginary) to the dynamic spindle force
    /// `F_c(ω)` per unit amplitude of the ground motion `u = e^{iωt}` \[N/m\].
    pub contribution: [f64; 2],
}

/// The participation of every oscillating mode of the loaded tire (contact nodes `held`
/// fixed to the ground, spin and damping `opt`) in the `component` line at `line_hz` \[Hz\];
/// largest share first.
///
/// Errors: nothing held, a `held` index out of range, a reduced tire without tread rows,
/// `line_hz` not positive, or a failed solve.
pub fn line_modes(
    red: &ReducedTire, held: &[usize], opt: &RotatingOptions, component: SpindleComponent,
    line_hz: f64,
) -> Result<Vec<LineMode>, TireError> {
    if !(line_hz > 0.0 && line_hz.is_finite()) {
        return Err(invalid("line_hz", format!("{line_hz} is not positive")));
    }
    if held.is_empty() {
        return Err(invalid("held", "no contact node is held: no ground motion"));
    }
    let a = held_rows(red, held)?;
    let tread = red.tread.as_ref().ok_or_else(|| {
        invalid(
            "reduced tire",
            "has no tread rows to label the modes (reduce the tire again)",
        )
    })?;
    let nz = red.n_z();
    let mats = FlowingMatrices::of(red);
    let st = state_eigen(mats, a.as_ref(), opt)?;
    let (c, k) = spin_matrices(mats, opt);
    let zs = influence(red, &a, held.len())?;
    let (zcol, row) = match component {
        SpindleComponent::Vertical => (0, VERTICAL),
        SpindleComponent::Longitudinal => (1, LONGITUDINAL),
    };
    let w = 2.0 * PI * line_hz;
    let z = zs.col(zcol);
    let (mz, cz, kz) = (&red.m * z, &c * z, &k * z);
    // f = −Nᵀ(−ω² M + iω C + K) z_s
    let re = Mat::from_fn(nz, 1, |i, _| -(-w * w * mz[i] + kz[i]));
    let im = Mat::from_fn(nz, 1, |i, _| -(w * cz[i]));
    let nt = st.n.transpose();
    let llt = st
        .sys
        .mass
        .llt(Side::Lower)
        .map_err(|e| linalg("mass of the loaded tire", e))?;
    let (gr, gi) = (llt.solve(nt * &re), llt.solve(nt * &im));
    let ny = st.n.ncols();
    let g = Mat::from_fn(2 * ny, 1, |i, _| {
        if i < ny {
            c64::new(0.0, 0.0)
        } else {
            c64::new(gr[(i - ny, 0)], gi[(i - ny, 0)])
        }
    });
    let q = st.eig.vectors.partial_piv_lu().solve(&g);
    let krn = &red.kr * &st.n;
    let lam = &st.eig.values;
    let contrib: Vec<c64> = (0..2 * ny)
        .map(|kk| {
            let mut out = c64::new(0.0, 0.0);
            for j in 0..ny {
                out -= st.eig.vectors[(j, kk)] * krn[(row, j)];
            }
            out * q[(kk, 0)] / (c64::new(0.0, w) - lam[kk])
        })
        .collect();
    let scale = lam.iter().fold(0.0f64, |s, l| s.max(l.norm()));
    let tol = 1e-9 * scale;
    let mut used = vec![false; 2 * ny];
    let mut terms = Vec::new();
    let mut total = 0.0;
    for kk in 0..2 * ny {
        if lam[kk].im <= tol {
            continue;
        }
        // the conjugate partner
        let partner = (0..2 * ny)
            .filter(|&j| lam[j].im < -tol && !used[j])
            .min_by(|&i, &j| {
                (lam[i] - lam[kk].conj())
                    .norm()
                    .total_cmp(&(lam[j] - lam[kk].conj()).norm())
            });
        let mut f = contrib[kk];
        if let Some(p) = partner {
            used[p] = true;
            f += contrib[p];
        }
        used[kk] = true;
        total += f.norm();
        terms.push((kk, f));
    }
    // overdamped (real) eigenvalues count in the sum
    total += (0..2 * ny)
        .filter(|&j| !used[j])
        .map(|j| contrib[j].norm())
        .sum::<f64>();
    let mut out: Vec<LineMode> = terms
        .into_iter()
        .map(|(kk, f)| {
            let m = st.mode(mats, tread, kk, opt.spin);
            LineMode {
                line_hz,
                hz: m.hz,
                n: m.n,
                direction: m.direction,
                damping_ratio: m.damping_ratio,
                lateral_share: m.parts[2],
                share: if total > 0.0 { f.norm() / total } else { 0.0 },
                contribution: [f.re, f.im],
            }
        })
        .collect();
    out.sort_by(|a, b| b.share.total_cmp(&a.share));
    Ok(out)
}
