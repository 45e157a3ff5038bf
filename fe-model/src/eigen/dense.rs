//! Dense generalized eigen solver: Cholesky transform in shift-invert form, tridiagonal QR,
//! M-orthonormalisation and Rayleigh-quotient eigenvalues.
//!
//! Steps (Bathe, *Finite Element Procedures*, §10.2.5 with the roles of K and M exchanged;
//! Ericsson & Ruhe 1980 for the spectral transformation):
//! 1. symmetric Jacobi scaling `D K D`, `D M D` with `dᵢ = 1/√Kᵢᵢ` (equilibrates translational
//!    and rotational DOFs; same eigenvalues, `φ = D φ̃`);
//! 2. `A = K − σM = L Lᵀ` (σ = 0 when K is positive definite, otherwise — rigid modes, or
//!    a Cholesky pivot below 10⁻¹² of the largest — `σ = −10⁻³·tr(K)/tr(M)` of the scaled
//!    matrices), `C = L⁻¹ M L⁻ᵀ` whose eigenvalues are
//!    `θ = 1/(λ − σ)`: the lowest modes are the largest θ, which a backward-stable EVD
//!    resolves to their own relative precision;
//! 3. the EVD `C y = θ y` by Householder tridiagonalisation and the implicit **QR** iteration
//!    on the tridiagonal matrix. faer 0.24.4's default for n ≥ 128, tridiagonal divide and
//!    conquer, is *not* backward stable on spectra spanning many decades: on the textbook
//!    transform `L_M⁻¹ K L_M⁻ᵀ` of a 600-DOF simply supported Hermite beam (θ from 97 to 2e13)
//!    it returned `max|CU − UΘ| = 3.6e-4·max|C|` and a first eigenvalue 0.55 % off, where the QR
//!    iteration gives 2e-15 (`fe-model/tests/dense_eigen_accuracy.rs`);
//! 4. `φ = D L⁻ᵀ y`, M-orthonormalised in ascending λ (Cholesky of the Gram matrix `ΦᵀMΦ`,
//!    a Gram–Schmidt in one O(n³) step);
//! 5. `λ = φᵀ K φ` (Rayleigh quotient; `φᵀMφ = 1`): the error is quadratic in the vector
//!    error, which makes the eigenvalues accurate over the whole spectrum from one EVD — the
//!    inverse `σ + 1/θ` alone carries an absolute error `ε·θ_max` that spoils the highest modes
//!    (4e-8 relative on that beam, against 8e-12 for the Rayleigh quotient), while the textbook
//!    transform `M = L Lᵀ` spoils the lowest (`ε·λ_max` absolute: 1e-6 relative on the beam's
//!    first mode even with the QR iteration).
//!
//! The residual `‖Kφ − λMφ‖ / (‖K‖‖φ‖)` (Frobenius norm of K) of every returned mode is
//! reported by [`dense_modes_report`]. Cost: one Cholesky, two triangular solves, one EVD and
//! a few matrix products, all O(n³); intended for n ≲ 3000.

use super::Modes;
use crate::FeError;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::evd::{
    ComputeEigenvectors, SelfAdjointEvdParams, self_adjoint_evd, self_adjoint_evd_scratch,
};
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Auto, Mat, MatRef, Par, Side, Spec};
use serde::Serialize;

/// Diagnostics of a dense eigen solution ([`dense_modes_report`]).
#[derive(Debug, Clone, Serialize)]
pub struct DenseEigenReport {
    /// DOFs.
    pub dof: usize,
    /// Shift σ \[rad²/s²\] of the factorised `K − σM`.
    pub shift: f64,
    /// Largest `‖Kφ − λMφ‖₂ / (‖K‖_F ‖φ‖₂)` over the returned modes.
    pub max_residual: f64,
    /// Largest `|φᵢᵀ M φⱼ − δᵢⱼ|` over the returned modes.
    pub max_orthogonality_error: f64,
}

/// The `count` lowest eigenpairs of `K φ = λ M φ` (all of them if `count ≥ n`), by the
/// method of the module documentation.
///
/// `k` symmetric, positive definite or semi-definite (rigid modes), `m` symmetric positive
/// definite (both are symmetrised as `(A + Aᵀ)/2`). Errors: non-square or mismatched shapes,
/// non-finite entries, M not positive definite, a pencil for which no shift below the
/// spectrum is found.
pub fn dense_modes(k: MatRef<'_, f64>, m: MatRef<'_, f64>, count: usize) -> Result<Modes, FeError> {
    Ok(dense_modes_report(k, m, count, None)?.0)
}

/// [`dense_modes`] with an explicit shift σ \[rad²/s²\] below the wanted spectrum (`None` = auto).
pub fn dense_modes_shifted(
    k: MatRef<'_, f64>, m: MatRef<'_, f64>, count: usize, shift: Option<f64>,
) -> Result<Modes, FeError> {
    Ok(dense_modes_report(k, m, count, shift)?.0)
}

fn check_input(k: MatRef<'_, f64>, m: MatRef<'_, f64>) -> Result<(), FeError> {
    let n = k.nrows();
    for (name, a) in [("K", k), ("M", m)] {
        if a.nrows() != n || a.ncols() != n {
            return Err(FeError::Dimension {
                context: format!("dense_modes: {name} must be {n}×{n}"),
                expected: n,
                got: if a.nrows() != n { a.nrows() } else { a.ncols() },
            });
        }
        for j in 0..n {
            for i in 0..n {
                if !a[(i, j)].is_finite() {
                    return Err(FeError::Eigen(format!(
                        "dense_modes: {name}[{i},{j}] is not finite"
                    )));
                }
            }
        }
    }
    Ok(())
}

/// [`dense_modes_shifted`] returning the residual and orthogonality diagnostics as well.
pub fn dense_modes_report(
    k: MatRef<'_, f64>, m: MatRef<'_, f64>, count: usize, shift: Option<f64>,
) -> Result<(Modes, DenseEigenReport), FeError> {
    check_input(k, m)?;
    let n = k.nrows();
    let d: Vec<f64> = (0..n)
        .map(|i| {
            let kk = k[(i, i)];
            let mm = m[(i, i)];
            if kk > 0.0 {
                1.0 / kk.sqrt()
            } else if mm > 0.0 {
                1.0 / mm.sqrt()
            } else {
                1.0
            }
        })
        .collect();
    let ms = Mat::from_fn(n, n, |i, j| 0.5 * (m[(i, j)] + m[(j, i)]) * d[i] * d[j]);
    let ks = Mat::from_fn(n, n, |i, j| 0.5 * (k[(i, j)] + k[(j, i)]) * d[i] * d[j]);
    // M must be positive definite (checked: the transform below would hide a singular M)
    ms.llt(Side::Lower)
        .map_err(|e| FeError::NotPositiveDefinite {
            name: "M".into(),
            detail: format!(" ({e:?})"),
        })?;
    let shifted = |s: f64| Mat::from_fn(n, n, |i, j| ks[(i, j)] - s * ms[(i, j)]);
    let (sigma, llt) = match shift {
        Some(s) => {
            let l = shifted(s)
                .llt(Side::Lower)
                .map_err(|e| FeError::NotPositiveDefinite {
                    name: "K - sigma M".into(),
                    detail: format!(" (sigma = {s:e}; {e:?})"),
                })?;
            (s, l)
        }
        None => {
            // K positive definite → σ = 0. A Cholesky that succeeds with a pivot below
            // 1e-12 of the largest (unit-diagonal scaled K) means rigid modes lost in
            // round-off: θ = 1/λ of those would dwarf the rest of the spectrum (on a free–free
            // beam it destroyed the highest modes), so such K is shifted like a singular one
            let definite = ks.llt(Side::Lower).ok().filter(|l| {
                let d = l.L().diagonal().column_vector();
                let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
                for i in 0..n {
                    let p = d[i] * d[i];
                    lo = lo.min(p);
                    hi = hi.max(p);
                }
                lo > 1e-12 * hi
            });
            match definite {
                Some(l) => (0.0, l),
                None => {
                    // σ = −10⁻³·tr(K)/tr(M) (scaled): far enough below the rigid modes for
                    // their θ = 1/|σ| not to swamp the elastic ones, and the Rayleigh
                    // quotients keep the low modes exact (module documentation)
                    let tr_k: f64 = (0..n).map(|i| ks[(i, i)]).sum();
                    let tr_m: f64 = (0..n).map(|i| ms[(i, i)]).sum();
                    let s = -1e-3 * tr_k.abs().max(f64::MIN_POSITIVE) / tr_m;
                    let l =
                        shifted(s)
                            .llt(Side::Lower)
                            .map_err(|e| FeError::NotPositiveDefinite {
                                name: "K - sigma M".into(),
                                detail: format!(
                                    " (automatic sigma = {s:e}; K is indefinite? {e:?})"
                                ),
                            })?;
                    (s, l)
                }
            }
        }
    };
    let l = llt.L();
    let (s, u) = congruence_eigen(l, ms.clone())?;
    // largest θ first = lowest λ
    let mut order: Vec<usize> = (0..n).filter(|&i| s[i] > 0.0).collect();
    order.sort_by(|&a, &b| s[b].total_cmp(&s[a]));
    order.truncate(count.min(n));
    let mut phi = Mat::from_fn(n, order.len(), |i, j| u[(i, order[j])] / s[order[j]].sqrt());
    solve_upper_triangular_in_place(l.transpose(), phi.as_mut(), Par::Seq);
    m_orthonormalize(ms.as_ref(), &mut phi)?;
    for j in 0..phi.ncols() {
        for i in 0..n {
            phi[(i, j)] *= d[i];
        }
    }
    // Rayleigh quotients λ = φᵀKφ (φᵀMφ = 1) and residuals, in the original variables
    let k_sym = Mat::from_fn(n, n, |i, j| 0.5 * (k[(i, j)] + k[(j, i)]));
    let m_sym = Mat::from_fn(n, n, |i, j| 0.5 * (m[(i, j)] + m[(j, i)]));
    let kp = &k_sym * &phi;
    let mp = &m_sym * &phi;
    let k_norm = k_sym.norm_l2();
    let mut values = Vec::with_capacity(phi.ncols());
    let mut max_residual: f64 = 0.0;
    for j in 0..phi.ncols() {
        let lam = phi.col(j).transpose() * kp.col(j);
        let r = (kp.col(j) - lam * mp.col(j)).norm_l2();
        let den = k_norm * phi.col(j).norm_l2();
        if den > 0.0 {
            max_residual = max_residual.max(r / den);
        }
        values.push(lam);
    }
    let g = phi.transpose() * &mp;
    let mut orth: f64 = 0.0;
    for j in 0..g.ncols() {
        for i in 0..g.nrows() {
            orth = orth.max((g[(i, j)] - if i == j { 1.0 } else { 0.0 }).abs());
        }
    }
    let report = DenseEigenReport {
        dof: n,
        shift: sigma,
        max_residual,
        max_orthogonality_error: orth,
    };
    Ok((Modes::from_parts(values, phi), report))
}

/// M-orthonormalise the columns of `phi` in order (Gram–Schmidt in the M inner product, done
/// as `Φ ← Φ R⁻ᵀ` with the Cholesky factor `ΦᵀMΦ = R Rᵀ`; applied twice, the second pass
/// removes the round-off of the first, "CholeskyQR2").
fn m_orthonormalize(m: MatRef<'_, f64>, phi: &mut Mat<f64>) -> Result<(), FeError> {
    for _ in 0..2 {
        let g = phi.transpose() * (m * &*phi);
        let g = Mat::from_fn(g.nrows(), g.ncols(), |i, j| 0.5 * (g[(i, j)] + g[(j, i)]));
        let r = g.llt(Side::Lower).map_err(|e| {
            FeError::Eigen(format!(
                "dense_modes: eigenvectors are linearly dependent in the M inner product ({e:?})"
            ))
        })?;
        // Φ R⁻ᵀ = (R⁻¹ Φᵀ)ᵀ
        let mut t = phi.transpose().to_owned();
        solve_lower_triangular_in_place(r.L(), t.as_mut(), Par::Seq);
        *phi = t.transpose().to_owned();
    }
    Ok(())
}

/// Eigen decomposition of the congruence `C = L⁻¹ A L⁻ᵀ` for a lower-triangular `L` and a
/// symmetric `A` (consumed as workspace): two triangular solves, `C` symmetrised as
/// `½(C + Cᵀ)` against round-off, then the self-adjoint EVD `C y = θ y` with the tridiagonal
/// QR iteration (see the module documentation for why not divide and conquer). Returns θ
/// (ascending) and the orthonormal eigenvectors.
fn congruence_eigen(l: MatRef<'_, f64>, mut a: Mat<f64>) -> Result<(Vec<f64>, Mat<f64>), FeError> {
    let n = a.nrows();
    solve_lower_triangular_in_place(l, a.as_mut(), Par::Seq);
    let mut ct = a.transpose().to_owned();
    solve_lower_triangular_in_place(l, ct.as_mut(), Par::Seq);
    let c = Mat::from_fn(n, n, |i, j| 0.5 * (ct[(i, j)] + ct[(j, i)]));
    let (s, u) = self_adjoint_eigen_qr(c.as_ref())?;
    Ok((s, u))
}

/// Self-adjoint EVD of `c` (lower triangle read) by Householder tridiagonalisation and the
/// implicit QR iteration (faer's `self_adjoint_evd` with the divide-and-conquer threshold set
/// above n). Eigenvalues ascending.
pub fn self_adjoint_eigen_qr(c: MatRef<'_, f64>) -> Result<(Vec<f64>, Mat<f64>), FeError> {
    let n = c.nrows();
    if c.ncols() != n {
        return Err(FeError::Dimension {
            context: "self_adjoint_eigen_qr: square matrix".into(),
            expected: n,
            got: c.ncols(),
        });
    }
    let mut params: SelfAdjointEvdParams = <SelfAdjointEvdParams as Auto<f64>>::auto();
    params.recursion_threshold = usize::MAX;
    let params = Spec::new(params);
    let par = Par::Seq;
    let mut mem = MemBuffer::new(self_adjoint_evd_scratch::<f64>(
        n,
        ComputeEigenvectors::Yes,
        par,
        params,
    ));
    let mut s = faer::diag::Diag::<f64>::zeros(n);
    let mut u = Mat::<f64>::zeros(n, n);
    self_adjoint_evd(
        c,
        s.as_mut(),
        Some(u.as_mut()),
        par,
        MemStack::new(&mut mem),
        params,
    )
    .map_err(|e| FeError::Eigen(format!("dense_modes: EVD failed ({e:?})")))?;
    Ok(((0..n).map(|i| s[i]).collect(), u))
}
