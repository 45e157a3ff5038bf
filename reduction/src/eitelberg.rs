//! Eitelberg's equation-error reduction (Lin §6.6 and Appendix C, code by F. E. Cellier), and
//! its application to structures (Lin (6.39)–(6.45)), which reproduces Guyan reduction.

use crate::error::{ReductionError, Result};
use crate::linalg::{check_finite, check_square, inverse, solve_general};
use faer::linalg::solvers::Solve;
use faer::{Mat, MatRef};

/// Largest state dimension accepted by the dense Kronecker Lyapunov solver
/// [`lyapunov_kronecker`] (`n² × n²` system): 48 states, i.e. structures up to 24 DOFs.
/// Eitelberg's method itself uses the Bartels–Stewart solver [`crate::lyapunov::lyapunov`],
/// which has no such limit.
pub const MAX_LYAPUNOV_STATES: usize = 48;

/// Reduced system `ξ̇ = A_r ξ + B_r u`, `η = C_r ξ` of Lin (6.37)–(6.38).
#[derive(Debug, Clone)]
pub struct EitelbergReduction {
    /// `A_r` (v × v).
    pub a_r: Mat<f64>,
    /// `B_r` (v × m).
    pub b_r: Mat<f64>,
    /// `C_r` (p × v).
    pub c_r: Mat<f64>,
}

/// Solves the continuous Lyapunov equation `A S + S Aᵀ + Q = 0` (MATLAB `lyap(A, Q)`) by the
/// Kronecker form `(I⊗A + A⊗I) vec S = −vec Q` (dense LU; at most [`MAX_LYAPUNOV_STATES`]).
/// Kept as an independent reference for [`crate::lyapunov::lyapunov`].
pub fn lyapunov_kronecker(a: MatRef<'_, f64>, q: MatRef<'_, f64>) -> Result<Mat<f64>> {
    let n = a.nrows();
    check_square("Lyapunov A", a, n)?;
    check_square("Lyapunov Q", q, n)?;
    if n > MAX_LYAPUNOV_STATES {
        return Err(ReductionError::InvalidParameter {
            name: "Lyapunov size".into(),
            reason: format!(
                "{n} states exceed the dense Kronecker solver limit of {MAX_LYAPUNOV_STATES}"
            ),
        });
    }
    let nn = n * n;
    // vec index: (i, j) -> j*n + i
    let mut big = Mat::<f64>::zeros(nn, nn);
    for j in 0..n {
        for i in 0..n {
            let row = j * n + i;
            // (A S)_ij = Σ_k A_ik S_kj
            for k in 0..n {
                big[(row, j * n + k)] += a[(i, k)];
            }
            // (S Aᵀ)_ij = Σ_k S_ik A_jk
            for k in 0..n {
                big[(row, k * n + i)] += a[(j, k)];
            }
        }
    }
    let rhs = Mat::from_fn(nn, 1, |r, _| -q[(r % n, r / n)]);
    let lu = big.partial_piv_lu();
    let mut x = lu.solve(&rhs);
    // iterative refinement: the Kronecker system is ill-conditioned when the stable poles are
    // lightly damped (sep(A, −Aᵀ) small), as for structures with output feedback
    for _ in 0..3 {
        let r = &rhs - &big * &x;
        let dx = lu.solve(&r);
        x += &dx;
    }
    check_finite("Lyapunov solution", x.as_ref())?;
    let s = Mat::from_fn(n, n, |i, j| x[(j * n + i, 0)]);
    // S is symmetric in exact arithmetic
    Ok(crate::linalg::symmetrize(&s))
}

/// Eitelberg's method (Lin Appendix C): zero steady-state error and minimal equation error.
///
/// The Lyapunov equation `A S + S Aᵀ = −P Pᵀ` is solved directly by Bartels–Stewart
/// ([`crate::lyapunov::lyapunov`]); Cellier's SVD rotation `Â = Uᵀ A U` of Appendix C only
/// changes the basis of the same equation and is not needed.
///
/// `R` (v × n) selects the kept states (`x_r = R x`), `C = C_r R`. `A` must be asymptotically
/// stable (use output feedback first, see [`eitelberg_structure`]).
pub fn eitelberg(
    a: MatRef<'_, f64>, b: MatRef<'_, f64>, c: MatRef<'_, f64>, r: MatRef<'_, f64>,
) -> Result<EitelbergReduction> {
    eitelberg_with(a, b, c, r, LyapunovSolver::BartelsStewart)
}

/// Which Lyapunov solver Eitelberg's method uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LyapunovSolver {
    /// Bartels–Stewart on a complex Schur form with refinement ([`crate::lyapunov::lyapunov`]),
    /// O(n³): the default, for any size.
    #[default]
    BartelsStewart,
    /// Dense Kronecker form ([`lyapunov_kronecker`]), O(n⁶): reference, at most
    /// [`MAX_LYAPUNOV_STATES`] states.
    Kronecker,
}

/// [`eitelberg`] with a chosen Lyapunov solver.
pub fn eitelberg_with(
    a: MatRef<'_, f64>, b: MatRef<'_, f64>, c: MatRef<'_, f64>, r: MatRef<'_, f64>,
    solver: LyapunovSolver,
) -> Result<EitelbergReduction> {
    let n = a.nrows();
    check_square("Eitelberg A", a, n)?;
    let ev = a.eigenvalues().map_err(|e| ReductionError::Numerical {
        what: "eigenvalues of Eitelberg A".into(),
        detail: format!("{e:?}"),
    })?;
    let lmax = ev.iter().map(|z| z.re).fold(f64::NEG_INFINITY, f64::max);
    if lmax >= 0.0 {
        return Err(ReductionError::InvalidParameter {
            name: "Eitelberg A".into(),
            reason: format!(
                "the system is not asymptotically stable (max Re λ = {lmax:e}); apply output feedback first"
            ),
        });
    }
    // C_r = C / R = C Rᵀ (R Rᵀ)⁻¹   (MATLAB mrdivide for full-row-rank R)
    let rrt = r * r.transpose();
    let rrt_inv = inverse("R Rᵀ", rrt.as_ref())?;
    let c_r = c * r.transpose() * &rrt_inv;
    // P = A⁻¹ B
    let p = solve_general("A P = B", a, b)?;
    let q = &p * p.transpose();
    let s = match solver {
        LyapunovSolver::BartelsStewart => crate::lyapunov::lyapunov(a, q.as_ref())?,
        LyapunovSolver::Kronecker => lyapunov_kronecker(a, q.as_ref())?,
    };
    let rsr = r * &s * r.transpose();
    let rasr = r * a * &s * r.transpose();
    // A_r = (R A S Rᵀ)(R S Rᵀ)⁻¹ = ((R S Rᵀ)⁻ᵀ (R A S Rᵀ)ᵀ)ᵀ
    let a_r_t = solve_general(
        "R S Rᵀ",
        rsr.transpose().to_owned().as_ref(),
        rasr.transpose().to_owned().as_ref(),
    )?;
    let a_r = a_r_t.transpose().to_owned();
    let b_r = &a_r * r * &p;
    Ok(EitelbergReduction { a_r, b_r, c_r })
}

/// Eitelberg applied to a structure `M δ̈ + K δ = f_b` (Lin (6.42)–(6.45), §6.6.4): state
/// `x = {δ; δ̇}`, input the boundary forces, `R = C` selecting `{δ_b; δ̇_b}`, the stabilising
/// output feedback `L = [I I]` (mandatory: the undamped A is not stable), restored afterwards
/// (`A_r ← A_r + B_r L C_r`).
///
/// Returns the reduced `M_⁻¹K_ = −A_r[n_b.., ..n_b]` (n_b × n_b, Lin §6.6.4 printed matrix) and
/// the full reduction.
pub fn eitelberg_structure(
    k: MatRef<'_, f64>, m: MatRef<'_, f64>, boundary: &[usize],
) -> Result<(Mat<f64>, EitelbergReduction)> {
    eitelberg_structure_with(k, m, boundary, LyapunovSolver::BartelsStewart)
}

/// [`eitelberg_structure`] with a chosen Lyapunov solver.
pub fn eitelberg_structure_with(
    k: MatRef<'_, f64>, m: MatRef<'_, f64>, boundary: &[usize], solver: LyapunovSolver,
) -> Result<(Mat<f64>, EitelbergReduction)> {
    let n = k.nrows();
    check_square("stiffness matrix K", k, n)?;
    check_square("mass matrix M", m, n)?;
    let nb = boundary.len();
    if let Some(&d) = boundary.iter().find(|&&d| d >= n) {
        return Err(ReductionError::InvalidDofs {
            what: "boundary DOF set".into(),
            reason: format!("DOF {d} out of range ({n} DOFs)"),
        });
    }
    let minv = inverse("mass matrix M", m)?;
    let minvk = &minv * k;
    let a = Mat::from_fn(2 * n, 2 * n, |i, j| {
        if i < n {
            (j == n + i) as u8 as f64
        } else if j < n {
            -minvk[(i - n, j)]
        } else {
            0.0
        }
    });
    let b = Mat::from_fn(2 * n, nb, |i, j| {
        if i < n {
            0.0
        } else {
            minv[(i - n, boundary[j])]
        }
    });
    let r = Mat::from_fn(2 * nb, 2 * n, |i, j| {
        if i < nb {
            (j == boundary[i]) as u8 as f64
        } else {
            (j == n + boundary[i - nb]) as u8 as f64
        }
    });
    let l = Mat::from_fn(nb, 2 * nb, |i, j| ((j == i) || (j == nb + i)) as u8 as f64);
    let a_fb = &a - &b * &l * &r;
    let mut red = eitelberg_with(a_fb.as_ref(), b.as_ref(), r.as_ref(), r.as_ref(), solver)?;
    red.a_r = &red.a_r + &red.b_r * &l * &red.c_r;
    let minvk_r = Mat::from_fn(nb, nb, |i, j| -red.a_r[(nb + i, j)]);
    Ok((minvk_r, red))
}
