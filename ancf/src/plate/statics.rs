//! Static equilibrium of a plate mesh, `Q_e(q) + λ F = 0`, by Newton–Raphson with load
//! increments and a backtracking line search (the procedure of [`crate::statics`] for the
//! planar elements, Kerkkänen §2.4, applied to the thin plate of §4.3).

use super::mesh::PlateMesh;
use crate::error::{AncfError, invalid};
use crate::statics::{StaticOptions, StaticSolution, check_sizes};
use faer::Mat;
use faer::prelude::Solve;

/// Solve `Q_e(q) + λ F = 0` for `λ = 1/n, …, 1` from `q0`, keeping the coordinates in `fixed`
/// at their `q0` values. `load` is the generalized external force \[N\] (all coordinates).
pub fn solve_plate_static(
    mesh: &PlateMesh,
    q0: &[f64],
    fixed: &[usize],
    load: &[f64],
    opts: &StaticOptions,
) -> Result<StaticSolution, AncfError> {
    let n_all = mesh.n_coords();
    check_sizes("plate statics", n_all, q0, load)?;
    if opts.increments == 0 || opts.max_iterations == 0 {
        return Err(invalid(
            "plate statics: options",
            "increments and max_iterations must be at least 1",
        ));
    }
    let mut map = vec![None; n_all];
    let mut n = 0;
    for (i, m) in map.iter_mut().enumerate() {
        if fixed.contains(&i) {
            continue;
        }
        *m = Some(n);
        n += 1;
    }
    let residual = |q: &[f64], lam: f64| -> Result<(Vec<f64>, f64), AncfError> {
        let f = mesh.elastic_forces(q)?;
        let mut r = vec![0.0; n];
        for (i, m) in map.iter().enumerate() {
            if let Some(row) = m {
                r[*row] = f[i] + lam * load[i];
            }
        }
        let norm = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        Ok((r, norm))
    };
    let potential = |q: &[f64], lam: f64| -> Result<f64, AncfError> {
        let work: f64 = (0..n_all).map(|i| load[i] * (q[i] - q0[i])).sum();
        Ok(mesh.strain_energy(q)? - lam * work)
    };
    let mut q = q0.to_vec();
    let mut iterations = Vec::with_capacity(opts.increments);
    let mut res = 0.0;
    for inc in 1..=opts.increments {
        let lam = inc as f64 / opts.increments as f64;
        let mut converged = false;
        let mut it = 0;
        while it < opts.max_iterations {
            it += 1;
            let (f, k) = mesh.elastic_tangent_mapped(&q, &map, n)?;
            let mut rhs = Mat::<f64>::zeros(n, 1);
            for (i, m) in map.iter().enumerate() {
                if let Some(row) = m {
                    rhs[(*row, 0)] = f[i] + lam * load[i];
                }
            }
            res = (0..n).fold(0.0f64, |m, i| m.max(rhs[(i, 0)].abs()));
            let lu = k.sp_lu().map_err(|e| AncfError::Singular {
                load_factor: lam,
                detail: format!("{e:?} (missing supports?)"),
            })?;
            let dx = lu.solve(&rhs);
            // K Δq = r (K = ∂²U/∂q² = −∂Q_e/∂q), then backtrack on the total potential
            // Π = U − λ Fᵀ(q − q0) (the load is dead, so Π exists and the Newton direction
            // descends it where K is positive definite). A residual-norm search stalls here: the
            // membrane strain of a large-rotation step raises the residual before the next
            // iteration removes it. Without any decrease the full Newton step is taken.
            let mut alpha = 1.0;
            let mut trial = q.clone();
            let set = |alpha: f64, trial: &mut Vec<f64>| {
                for (i, m) in map.iter().enumerate() {
                    if let Some(row) = m {
                        trial[i] = q[i] + alpha * dx[(*row, 0)];
                    }
                }
            };
            set(alpha, &mut trial);
            if opts.line_search {
                let pi0 = potential(&q, lam)?;
                let mut found = false;
                for _ in 0..12 {
                    let pi = potential(&trial, lam)?;
                    if pi.is_finite() && pi <= pi0 + 1e-12 * pi0.abs() {
                        found = true;
                        break;
                    }
                    alpha *= 0.5;
                    set(alpha, &mut trial);
                }
                if !found {
                    alpha = 1.0;
                    set(alpha, &mut trial);
                }
            }
            let step = (0..n).fold(0.0f64, |m, i| m.max((alpha * dx[(i, 0)]).abs()));
            let scale = q.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            q = trial.clone();
            if !step.is_finite() {
                return Err(AncfError::NonFinite {
                    what: format!("plate Newton step at load factor {lam}"),
                });
            }
            if step <= opts.tolerance * (1.0 + scale) {
                converged = true;
                res = residual(&q, lam)?.1;
                break;
            }
        }
        if !converged {
            return Err(AncfError::NoConvergence {
                load_factor: lam,
                iterations: it,
                residual: res,
            });
        }
        iterations.push(it);
    }
    Ok(StaticSolution {
        q,
        iterations,
        residual: res,
    })
}
