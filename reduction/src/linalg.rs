//! Small dense linear-algebra helpers on faer matrices used by the reduction bases.
//!
//! Every heavy operation is delegated to faer (LU, Cholesky, SVD, self-adjoint EVD); this module
//! only adds index bookkeeping, tolerances and the conventions of Lin (2005) ch. 6-8.

use crate::error::{ReductionError, Result};
use faer::linalg::solvers::Solve;
use faer::{Mat, MatRef, Side};

/// Checks that `m` is `n × n`.
pub fn check_square(what: &str, m: MatRef<'_, f64>, n: usize) -> Result<()> {
    if m.nrows() != n || m.ncols() != n {
        return Err(ReductionError::Shape {
            what: what.to_string(),
            expected: format!("{n}x{n}"),
            rows: m.nrows(),
            cols: m.ncols(),
        });
    }
    Ok(())
}

/// Checks that every entry of `m` is finite.
pub fn check_finite(what: &str, m: MatRef<'_, f64>) -> Result<()> {
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            if !m[(i, j)].is_finite() {
                return Err(ReductionError::Numerical {
                    what: what.to_string(),
                    detail: format!("entry ({i}, {j}) is not finite"),
                });
            }
        }
    }
    Ok(())
}

/// The sub-matrix `a[rows, cols]` (copied).
pub fn select(a: MatRef<'_, f64>, rows: &[usize], cols: &[usize]) -> Mat<f64> {
    Mat::from_fn(rows.len(), cols.len(), |i, j| a[(rows[i], cols[j])])
}

/// The columns `cols` of `a` (copied).
pub fn select_cols(a: MatRef<'_, f64>, cols: &[usize]) -> Mat<f64> {
    Mat::from_fn(a.nrows(), cols.len(), |i, j| a[(i, cols[j])])
}

/// `aᵀ b c` for dense matrices (the Galerkin projection `Ψᵀ K Ψ` when `a = c = Ψ`).
pub fn congruence(a: MatRef<'_, f64>, b: MatRef<'_, f64>, c: MatRef<'_, f64>) -> Mat<f64> {
    let bc = b * c;
    a.transpose() * &bc
}

/// Symmetric part `(a + aᵀ)/2`, used to remove round-off asymmetry of projected matrices.
pub fn symmetrize(a: &Mat<f64>) -> Mat<f64> {
    Mat::from_fn(a.nrows(), a.ncols(), |i, j| 0.5 * (a[(i, j)] + a[(j, i)]))
}

/// Largest absolute entry.
pub fn max_abs(a: MatRef<'_, f64>) -> f64 {
    let mut m = 0.0_f64;
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            m = m.max(a[(i, j)].abs());
        }
    }
    m
}

/// Solves `a x = b` with a Cholesky factorization of the symmetric positive definite `a`.
///
/// `what` names the matrix in the error (e.g. `interior stiffness K_ii`).
pub fn solve_spd(what: &str, a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> Result<Mat<f64>> {
    let llt = a
        .llt(Side::Lower)
        .map_err(|_| ReductionError::NotPositiveDefinite {
            what: what.to_string(),
            hint: "the boundary set must restrain every rigid-body motion".to_string(),
        })?;
    Ok(llt.solve(b))
}

/// Solves the general square system `a x = b` (partial-pivoting LU); fails on a singular `a`.
pub fn solve_general(what: &str, a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> Result<Mat<f64>> {
    let lu = a.partial_piv_lu();
    let x = lu.solve(b);
    check_finite(what, x.as_ref())?;
    // residual check: a singular matrix gives huge or inconsistent solutions
    let r = a * &x - b;
    let scale = max_abs(a) * max_abs(x.as_ref()) + max_abs(b);
    if max_abs(r.as_ref()) > 1e-8 * scale.max(f64::MIN_POSITIVE) {
        return Err(ReductionError::Numerical {
            what: what.to_string(),
            detail: format!(
                "the matrix is singular or ill-conditioned (residual {:.3e})",
                max_abs(r.as_ref())
            ),
        });
    }
    Ok(x)
}

/// Inverse of a square matrix (partial-pivoting LU).
pub fn inverse(what: &str, a: MatRef<'_, f64>) -> Result<Mat<f64>> {
    let n = a.nrows();
    solve_general(what, a, Mat::<f64>::identity(n, n).as_ref())
}

/// Orthonormal basis of the column space of `a` (left singular vectors with `σ > tol·σ_max`).
pub fn orth(a: MatRef<'_, f64>, rel_tol: f64) -> Result<Mat<f64>> {
    if a.ncols() == 0 || a.nrows() == 0 {
        return Ok(Mat::zeros(a.nrows(), 0));
    }
    let svd = a.thin_svd().map_err(|e| ReductionError::Numerical {
        what: "SVD (column space)".into(),
        detail: format!("{e:?}"),
    })?;
    let s = svd.S().column_vector();
    let smax = s[0];
    let r = (0..s.nrows()).filter(|&i| s[i] > rel_tol * smax).count();
    Ok(svd.U().subcols(0, r).to_owned())
}

/// Numerical rank of `a` with relative tolerance `rel_tol` on the singular values.
pub fn rank(a: MatRef<'_, f64>, rel_tol: f64) -> Result<usize> {
    Ok(orth(a, rel_tol)?.ncols())
}

/// Orthonormal basis of the null space of `a` (right singular vectors with `σ ≤ tol·σ_max`).
pub fn null_space(a: MatRef<'_, f64>, rel_tol: f64) -> Result<Mat<f64>> {
    let n = a.ncols();
    if a.nrows() == 0 {
        return Ok(Mat::identity(n, n));
    }
    let svd = a.svd().map_err(|e| ReductionError::Numerical {
        what: "SVD (null space)".into(),
        detail: format!("{e:?}"),
    })?;
    let s = svd.S().column_vector();
    let smax = if s.nrows() > 0 { s[0] } else { 0.0 };
    let r = (0..s.nrows())
        .filter(|&i| s[i] > rel_tol * smax.max(f64::MIN_POSITIVE))
        .count();
    Ok(svd.V().subcols(r, n - r).to_owned())
}

/// Sine of the largest principal angle between the column spaces of `a` and `b`
/// (0 when they span the same space; both must have full column rank for a meaningful value).
///
/// Returns `max(‖(I − QaQaᵀ)Qb‖₂, ‖(I − QbQbᵀ)Qa‖₂)` with orthonormal bases `Qa`, `Qb`.
pub fn span_distance(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> Result<f64> {
    let qa = orth(a, 1e-10)?;
    let qb = orth(b, 1e-10)?;
    if qa.ncols() != qb.ncols() {
        return Ok(1.0);
    }
    let res = |q1: &Mat<f64>, q2: &Mat<f64>| -> Result<f64> {
        let p = q1.transpose() * q2;
        let r = q2 - q1 * &p;
        if r.ncols() == 0 {
            return Ok(0.0);
        }
        let sv = r.singular_values().map_err(|e| ReductionError::Numerical {
            what: "SVD (principal angles)".into(),
            detail: format!("{e:?}"),
        })?;
        Ok(sv.first().copied().unwrap_or(0.0))
    };
    Ok(res(&qa, &qb)?.max(res(&qb, &qa)?))
}

/// Least-squares solution of `a x ≈ b` (Householder QR; `a` must have full column rank).
pub fn lstsq(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> Result<Mat<f64>> {
    use faer::linalg::solvers::SolveLstsq;
    if a.nrows() < a.ncols() {
        return Err(ReductionError::Shape {
            what: "least-squares matrix".into(),
            expected: "tall (rows >= cols)".into(),
            rows: a.nrows(),
            cols: a.ncols(),
        });
    }
    let x = a.qr().solve_lstsq(b);
    check_finite("least-squares solution", x.as_ref())?;
    Ok(x)
}

/// Generalized symmetric-definite eigenproblem `K φ = λ M φ` (dense, all pairs), Lin (6.11),
/// MATLAB `eig(K, M)`; delegates to fe-model's Cholesky-transform solver
/// ([`fe_model::dense_modes`]).
///
/// Returns eigenvalues in ascending order and M-normalized eigenvectors (`ΦᵀMΦ = I`), each
/// signed so that its largest-magnitude entry is positive (fe-model's convention).
pub fn sym_gen_eig(
    what: &str, k: MatRef<'_, f64>, m: MatRef<'_, f64>,
) -> Result<(Vec<f64>, Mat<f64>)> {
    let n = k.nrows();
    check_square(what, k, n)?;
    check_square(what, m, n)?;
    if n == 0 {
        return Ok((Vec::new(), Mat::zeros(0, 0)));
    }
    let modes = fe_model::dense_modes(k, m, n).map_err(|e| match e {
        fe_model::FeError::NotPositiveDefinite { .. } => ReductionError::NotPositiveDefinite {
            what: format!("mass matrix of {what}"),
            hint: "every DOF needs positive mass".into(),
        },
        other => ReductionError::Numerical {
            what: format!("eigen solve of {what}"),
            detail: other.to_string(),
        },
    })?;
    Ok((modes.values, modes.vectors))
}

/// Natural frequencies in Hz from eigenvalues `λ = ω²` (negative round-off is clamped to 0).
pub fn eig_to_hz(lam: &[f64]) -> Vec<f64> {
    lam.iter()
        .map(|&l| l.max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
        .collect()
}
