//! Dense generalized eigen solver by the Cholesky transform.
//!
//! `M = L Lᵀ` (faer LLT), `C = L⁻¹ K L⁻ᵀ` (symmetric), `C y = λ y` (faer self-adjoint EVD),
//! `φ = L⁻ᵀ y`, so that `φᵀ M φ = yᵀ y = 1` (Bathe, *Finite Element Procedures*, §10.2.5).
//! Intended for small models (n ≲ 3000): O(n³) time, O(n²) memory.

use super::Modes;
use crate::FeError;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, MatRef, Par, Side};

/// The `count` lowest eigenpairs of `K φ = λ M φ` (all of them if `count ≥ n`).
///
/// `k` symmetric, `m` symmetric positive definite (only their lower triangles are read by the
/// factorisations; `K` is symmetrised as `(K + Kᵀ)/2`). Errors: non-square or mismatched
/// shapes, non-finite entries, M not positive definite.
pub fn dense_modes(k: MatRef<'_, f64>, m: MatRef<'_, f64>, count: usize) -> Result<Modes, FeError> {
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
    let llt = m
        .llt(Side::Lower)
        .map_err(|e| FeError::NotPositiveDefinite {
            name: "M".into(),
            detail: format!(" ({e:?})"),
        })?;
    let l = llt.L();
    // C = L⁻¹ K_sym L⁻ᵀ
    let mut c = Mat::from_fn(n, n, |i, j| 0.5 * (k[(i, j)] + k[(j, i)]));
    solve_lower_triangular_in_place(l, c.as_mut(), Par::Seq);
    let mut ct = c.transpose().to_owned();
    solve_lower_triangular_in_place(l, ct.as_mut(), Par::Seq);
    let c = Mat::from_fn(n, n, |i, j| 0.5 * (ct[(i, j)] + ct[(j, i)]));
    let evd = c
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| FeError::Eigen(format!("dense_modes: EVD failed ({e:?})")))?;
    let s = evd.S();
    let u = evd.U();
    let take = count.min(n);
    // faer returns ascending eigenvalues
    let mut values: Vec<f64> = (0..n).map(|i| s[i]).collect();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    order.truncate(take);
    values = order.iter().map(|&i| values[i]).collect();
    let mut phi = Mat::from_fn(n, take, |i, j| u[(i, order[j])]);
    solve_upper_triangular_in_place(l.transpose(), phi.as_mut(), Par::Seq);
    Ok(Modes::from_parts(values, phi))
}
