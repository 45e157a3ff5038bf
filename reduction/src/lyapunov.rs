//! Continuous Lyapunov equation `A S + S Aᵀ + Q = 0` (MATLAB `lyap(A, Q)`, used by Eitelberg's
//! method, Lin Appendix C) by the Bartels–Stewart algorithm on a complex Schur form.
//!
//! faer 0.24 computes real and complex Schur forms internally but does not expose them, so the
//! Schur form is built from faer's eigendecomposition: with the eigenvector matrix `V = U R`
//! (QR, `U` unitary), `A U = U T` where `T = R Λ R⁻¹` is upper triangular. `T` is taken as the
//! upper triangle of `Uᴴ A U`; its dropped strictly lower part measures how far the computed
//! invariant subspaces are from exact (large only for nearly defective `A`). The triangular
//! equation `T Y + Y Tᴴ = C` is solved column by column (Bartels & Stewart 1972), and the result
//! is polished by iterative refinement on the true residual `A S + S Aᵀ + Q`, so that the
//! returned `S` satisfies the defining equation to round-off even when the Schur form is only
//! approximate. Cost O(n³) time and O(n²) memory (the Kronecker form needs O(n⁶) and O(n⁴)).

use crate::error::{ReductionError, Result};
use crate::linalg::{check_finite, check_square, max_abs};
use faer::{Mat, MatRef, c64};

/// Largest number of refinement sweeps.
const MAX_REFINEMENTS: usize = 30;
/// Relative residual at which refinement stops.
const REFINED: f64 = 1e-15;

/// A complex Schur form `A = U T Uᴴ` (`U` unitary, `T` upper triangular) of a real matrix.
#[derive(Debug, Clone)]
pub struct ComplexSchur {
    /// Unitary factor `U`.
    pub u: Mat<c64>,
    /// Upper triangular factor `T` (eigenvalues on the diagonal).
    pub t: Mat<c64>,
    /// `max |(Uᴴ A U)_ij|` over `i > j` divided by `max |A_ij|`: the departure from an exact
    /// Schur form (round-off for a well-conditioned eigenvector basis).
    pub lower_residual: f64,
}

/// Complex Schur form of the real square `a` from faer's eigendecomposition and a QR
/// factorisation of the eigenvectors (see the module docs).
pub fn complex_schur(a: MatRef<'_, f64>) -> Result<ComplexSchur> {
    let n = a.nrows();
    check_square("Schur A", a, n)?;
    check_finite("Schur A", a)?;
    let evd = a.eigen().map_err(|e| ReductionError::Numerical {
        what: "eigendecomposition for the Schur form".into(),
        detail: format!("{e:?}"),
    })?;
    let u = evd.U().qr().compute_Q();
    let ac = to_complex(a);
    let full = u.adjoint() * &ac * &u;
    let scale = max_abs(a).max(f64::MIN_POSITIVE);
    let mut lower = 0.0f64;
    let t = Mat::from_fn(n, n, |i, j| {
        if i > j {
            lower = lower.max(full[(i, j)].norm());
            c64::new(0.0, 0.0)
        } else {
            full[(i, j)]
        }
    });
    Ok(ComplexSchur {
        u,
        t,
        lower_residual: lower / scale,
    })
}

fn to_complex(a: MatRef<'_, f64>) -> Mat<c64> {
    Mat::from_fn(a.nrows(), a.ncols(), |i, j| c64::new(a[(i, j)], 0.0))
}

/// Solves `T Y + Y Tᴴ = C` for upper triangular `T` (column `j` from the last:
/// `(T + conj(T_jj) I) y_j = c_j − Σ_{k>j} conj(T_jk) y_k`).
fn triangular_lyapunov(t: &Mat<c64>, c: &Mat<c64>) -> Result<Mat<c64>> {
    let n = t.nrows();
    let mut y = Mat::<c64>::zeros(n, n);
    let mut rhs = vec![c64::new(0.0, 0.0); n];
    for j in (0..n).rev() {
        for (i, r) in rhs.iter_mut().enumerate() {
            *r = c[(i, j)];
        }
        for k in j + 1..n {
            let f = t[(j, k)].conj();
            if f != c64::new(0.0, 0.0) {
                for (i, r) in rhs.iter_mut().enumerate() {
                    *r -= f * y[(i, k)];
                }
            }
        }
        let shift = t[(j, j)].conj();
        for i in (0..n).rev() {
            let mut s = rhs[i];
            for l in i + 1..n {
                s -= t[(i, l)] * y[(l, j)];
            }
            let d = t[(i, i)] + shift;
            if d.norm() == 0.0 {
                return Err(ReductionError::Numerical {
                    what: "Lyapunov equation".into(),
                    detail: format!(
                        "eigenvalues {} and {} sum to zero: the equation is singular (A must not have eigenvalues λ_i + λ_j = 0)",
                        t[(i, i)],
                        t[(j, j)]
                    ),
                });
            }
            y[(i, j)] = s / d;
        }
    }
    Ok(y)
}

/// `A S + S Aᵀ + Q`.
fn residual(a: MatRef<'_, f64>, s: &Mat<f64>, q: MatRef<'_, f64>) -> Mat<f64> {
    a * s + s * a.transpose() + q
}

/// Solves the continuous Lyapunov equation `A S + S Aᵀ + Q = 0` (MATLAB `lyap(A, Q)`) by
/// Bartels–Stewart on the complex Schur form of `A` with iterative refinement (module docs).
///
/// Requires `λ_i(A) + λ_j(A) ≠ 0` for all pairs (true for asymptotically stable `A`). The
/// result is symmetric when `Q` is. Errors when the refinement does not reach a relative
/// residual `‖A S + S Aᵀ + Q‖ / (2‖A‖‖S‖ + ‖Q‖) ≤ 1e-10` (max norms), i.e. when `A` is too
/// close to defective for the eigenvector-based Schur form.
pub fn lyapunov(a: MatRef<'_, f64>, q: MatRef<'_, f64>) -> Result<Mat<f64>> {
    let n = a.nrows();
    check_square("Lyapunov A", a, n)?;
    check_square("Lyapunov Q", q, n)?;
    check_finite("Lyapunov Q", q)?;
    if n == 0 {
        return Ok(Mat::zeros(0, 0));
    }
    let schur = complex_schur(a)?;
    let u = &schur.u;
    // A X + X Aᵀ = −R  ⇔  T Y + Y Tᴴ = −Uᴴ R U,  X = U Y Uᴴ (real up to round-off)
    let solve = |r: &Mat<f64>| -> Result<Mat<f64>> {
        let c = -(u.adjoint() * to_complex(r.as_ref()) * u);
        let y = triangular_lyapunov(&schur.t, &c)?;
        let x = u * y * u.adjoint();
        Ok(Mat::from_fn(n, n, |i, j| x[(i, j)].re))
    };
    let mut s = solve(&q.to_owned())?;
    let na = max_abs(a);
    let nq = max_abs(q);
    let (mut best, mut best_s) = (f64::INFINITY, s.clone());
    let mut previous = f64::INFINITY;
    for _ in 0..MAX_REFINEMENTS {
        let r = residual(a, &s, q);
        let rel =
            max_abs(r.as_ref()) / (2.0 * na * max_abs(s.as_ref()) + nq).max(f64::MIN_POSITIVE);
        if rel < best {
            best = rel;
            best_s = s.clone();
        }
        // stop at round-off or when a sweep no longer halves the residual
        if rel <= REFINED || rel > 0.5 * previous {
            break;
        }
        previous = rel;
        let ds = solve(&r)?;
        s += &ds;
    }
    let s = best_s;
    check_finite("Lyapunov solution", s.as_ref())?;
    if best > 1e-10 {
        return Err(ReductionError::Numerical {
            what: "Lyapunov equation".into(),
            detail: format!(
                "relative residual {best:e} after refinement (Schur departure {:e}): A is too close to defective",
                schur.lower_residual
            ),
        });
    }
    let symmetric = (0..n).all(|j| (0..j).all(|i| q[(i, j)] == q[(j, i)]));
    Ok(if symmetric {
        crate::linalg::symmetrize(&s)
    } else {
        s
    })
}
