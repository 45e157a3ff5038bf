//! Static equilibrium `Q_e(q) + λ F = 0` by Newton–Raphson with load increments and a
//! backtracking line search (Kerkkänen §2.4 and §3.3: "Newton–Raphson iterations"; the
//! increments and the line search are the seed note's §8.3 recommendation).

use crate::element::Element;
use crate::error::{AncfError, invalid};
use crate::mesh::Mesh;
use crate::sparse::Pattern;
use crate::system::MeshForce;
use faer::Mat;
use faer::prelude::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};

mod unilateral;
pub use unilateral::{UnilateralOptions, UnilateralSolution, solve_static_unilateral};

/// Options of the static solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticOptions {
    /// Number of equal load increments (≥ 1).
    pub increments: usize,
    /// Maximum Newton iterations per increment.
    pub max_iterations: usize,
    /// Convergence: `‖Δq‖∞ ≤ tol · (1 + ‖q‖∞)` \[-\].
    pub tolerance: f64,
    /// Backtracking line search on the residual norm.
    pub line_search: bool,
}

impl Default for StaticOptions {
    fn default() -> Self {
        Self {
            increments: 10,
            max_iterations: 50,
            tolerance: 1e-12,
            line_search: true,
        }
    }
}

/// Result of a static solve.
#[derive(Debug, Clone)]
pub struct StaticSolution {
    /// Equilibrium coordinates.
    pub q: Vec<f64>,
    /// Newton iterations per increment.
    pub iterations: Vec<usize>,
    /// Final residual norm \[N\].
    pub residual: f64,
}

/// Check that the start coordinates `q0` and the load `load` both have the `n` entries of the
/// model; `context` names the solver in the error.
pub(crate) fn check_sizes(
    context: &str,
    n: usize,
    q0: &[f64],
    load: &[f64],
) -> Result<(), AncfError> {
    if q0.len() != n || load.len() != n {
        return Err(invalid(
            context,
            format!(
                "q0 has {} and load {} entries, mesh has {n} coordinates",
                q0.len(),
                load.len()
            ),
        ));
    }
    Ok(())
}

/// Eliminate the supported coordinates `fixed` from the `n` unknowns (Kerkkänen §2.4: the
/// supports are prescribed coordinates, not equations): `map[k]` is the row of global
/// coordinate `k` in the reduced system (`None` if fixed) and `free[i]` the global coordinate
/// of reduced row `i`, in increasing order. An index `≥ n` in `fixed` is an error naming
/// `context`.
pub(crate) fn free_coordinates(
    context: &str,
    n: usize,
    fixed: &[usize],
) -> Result<(Vec<Option<usize>>, Vec<usize>), AncfError> {
    let mut map: Vec<Option<usize>> = vec![Some(0); n];
    for &k in fixed {
        if k >= n {
            return Err(invalid(
                format!("{context}: fixed"),
                format!("coordinate {k} out of range 0..{n}"),
            ));
        }
        map[k] = None;
    }
    let mut free = Vec::new();
    for (k, m) in map.iter_mut().enumerate() {
        if m.is_some() {
            *m = Some(free.len());
            free.push(k);
        }
    }
    Ok((map, free))
}

/// Solve `Q_e(q) + λ F = 0` for `λ = 1/n, 2/n, …, 1` starting from `q0`, keeping the global
/// coordinates listed in `fixed` at their `q0` values (supports eliminated from the unknowns).
pub fn solve_static<E: Element>(
    mesh: &Mesh<E>,
    q0: &[f64],
    fixed: &[usize],
    load: &[f64],
    opts: &StaticOptions,
) -> Result<StaticSolution, AncfError> {
    solve_static_with(mesh, q0, fixed, load, &[], opts)
}

/// [`solve_static`] with additional (configuration-dependent, velocity-free) forces such as
/// frictionless penalty contact, evaluated at zero velocity; their tangent enters the Newton
/// matrix. The load factor scales `load` only.
pub fn solve_static_with<E: Element>(
    mesh: &Mesh<E>,
    q0: &[f64],
    fixed: &[usize],
    load: &[f64],
    extra: &[&dyn MeshForce<E>],
    opts: &StaticOptions,
) -> Result<StaticSolution, AncfError> {
    let n = mesh.n_dof();
    check_sizes("static solve", n, q0, load)?;
    if opts.increments == 0 {
        return Err(invalid("static solve: increments", "must be ≥ 1"));
    }
    let (map, free) = free_coordinates("static solve", n, fixed)?;
    let nf = free.len();
    let dofs: Vec<Vec<Option<usize>>> = (0..mesh.elements().len())
        .map(|el| {
            (0..mesh.elements()[el].ndof())
                .map(|k| map[mesh.global_dof(el, k)])
                .collect()
        })
        .collect();
    let pattern = Pattern::new(nf, &dofs);
    let full = mesh.pattern();
    let to_reduced: Vec<Option<usize>> = full
        .entries()
        .map(|(i, j, _)| match (map[i], map[j]) {
            (Some(a), Some(b)) => pattern.position(a, b),
            _ => None,
        })
        .collect();
    let zero_v = vec![0.0; n];
    let mut kfull = full.zeros();
    let mut cfull = full.zeros();
    let symbolic =
        SymbolicLu::try_new(pattern.symbolic().as_ref()).map_err(|e| AncfError::Singular {
            load_factor: 0.0,
            detail: format!("symbolic LU: {e:?}"),
        })?;

    // conservative problems (no extra forces) use the total potential as merit function
    let energy_merit = extra.is_empty();
    let potential = |q: &[f64], lam: f64| -> f64 {
        mesh.strain_energy(q) - lam * q.iter().zip(load).map(|(a, b)| a * b).sum::<f64>()
    };
    let diag: Vec<usize> = (0..nf).map(|i| pattern.diagonal_position(i)).collect();
    let mut q = q0.to_vec();
    let mut f = vec![0.0; n];
    let mut kv = pattern.zeros();
    let mut iterations = Vec::with_capacity(opts.increments);
    let residual_of = |q: &[f64], lam: f64, f: &mut [f64]| -> f64 {
        mesh.elastic_forces(q, f);
        for x in extra {
            x.add_forces(mesh, 0.0, q, &zero_v, f);
        }
        free.iter()
            .map(|&k| {
                let r = f[k] + lam * load[k];
                r * r
            })
            .sum::<f64>()
            .sqrt()
    };
    let mut last_res = 0.0;
    for inc in 1..=opts.increments {
        let lam = inc as f64 / opts.increments as f64;
        let mut converged = false;
        let mut it = 0;
        while it < opts.max_iterations {
            it += 1;
            kfull.fill(0.0);
            mesh.elastic_tangent_into(&q, &mut f, full, &mut kfull, 1.0);
            for x in extra {
                x.add_forces(mesh, 0.0, &q, &zero_v, &mut f);
                x.add_tangent(mesh, 0.0, &q, &zero_v, &mut kfull, &mut cfull);
            }
            kv.fill(0.0);
            for (p, r) in to_reduced.iter().enumerate() {
                if let Some(r) = r {
                    kv[*r] += kfull[p];
                }
            }
            let mut rhs = Mat::<f64>::zeros(nf, 1);
            let mut res = 0.0;
            for (i, &k) in free.iter().enumerate() {
                let r = f[k] + lam * load[k];
                rhs[(i, 0)] = r;
                res += r * r;
            }
            let res = res.sqrt();
            if !res.is_finite() {
                return Err(AncfError::NonFinite {
                    what: format!("static residual at load factor {lam}"),
                });
            }
            let kmat = pattern.to_matrix(kv.clone());
            let lu = Lu::try_new_with_symbolic(symbolic.clone(), kmat.as_ref()).map_err(|e| {
                AncfError::Singular {
                    load_factor: lam,
                    detail: format!("{e:?}"),
                }
            })?;
            let mut dx = lu.solve(&rhs);
            let mut alpha = 1.0;
            let mut trial = q.clone();
            let apply = |alpha: f64, dx: &Mat<f64>, trial: &mut [f64]| {
                for (i, &k) in free.iter().enumerate() {
                    trial[k] = q[k] + alpha * dx[(i, 0)];
                }
            };
            let slope = |d: &Mat<f64>| (0..nf).map(|i| rhs[(i, 0)] * d[(i, 0)]).sum::<f64>();
            if opts.line_search && energy_merit {
                // Π = U − λFᵀq decreases along Δ iff RᵀΔ > 0; otherwise regularise K + μI
                // (Levenberg–Marquardt) until it does. Then Armijo backtracking on Π.
                let dmax = diag.iter().map(|&p| kv[p].abs()).fold(0.0, f64::max);
                let mut mu_rel = 1e-8;
                while slope(&dx) <= 0.0 && mu_rel < 1e3 {
                    let mut kreg = kv.clone();
                    for &p in &diag {
                        kreg[p] += mu_rel * dmax;
                    }
                    if let Ok(lu) = Lu::try_new_with_symbolic(
                        symbolic.clone(),
                        pattern.to_matrix(kreg).as_ref(),
                    ) {
                        dx = lu.solve(&rhs);
                    }
                    mu_rel *= 10.0;
                }
                let s0 = slope(&dx);
                let pi0 = potential(&q, lam);
                apply(alpha, &dx, &mut trial);
                let mut tries = 0;
                while potential(&trial, lam) > pi0 - 1e-4 * alpha * s0 + 1e-14 * pi0.abs()
                    && tries < 30
                {
                    alpha *= 0.5;
                    apply(alpha, &dx, &mut trial);
                    tries += 1;
                }
            } else if opts.line_search {
                apply(alpha, &dx, &mut trial);
                let accept = |r_new: f64, alpha: f64| {
                    r_new <= (1.0 - 1e-4 * alpha) * res || r_new < 1e-9 * res.max(1.0)
                };
                let mut r_new = residual_of(&trial, lam, &mut f);
                let mut tries = 0;
                while !accept(r_new, alpha) && tries < 12 {
                    alpha *= 0.5;
                    apply(alpha, &dx, &mut trial);
                    r_new = residual_of(&trial, lam, &mut f);
                    tries += 1;
                }
                if !accept(r_new, alpha) {
                    alpha = 1.0;
                    apply(alpha, &dx, &mut trial);
                }
            } else {
                apply(alpha, &dx, &mut trial);
            }
            let step = (0..nf)
                .map(|i| (alpha * dx[(i, 0)]).abs())
                .fold(0.0, f64::max);
            let qmax = q.iter().map(|v| v.abs()).fold(0.0, f64::max);
            q = trial;
            last_res = res;
            if !step.is_finite() {
                return Err(AncfError::NonFinite {
                    what: format!("Newton step at load factor {lam}"),
                });
            }
            if step <= opts.tolerance * (1.0 + qmax) {
                converged = true;
                break;
            }
        }
        iterations.push(it);
        if !converged {
            return Err(AncfError::NoConvergence {
                load_factor: lam,
                iterations: it,
                residual: last_res,
            });
        }
    }
    Ok(StaticSolution {
        q,
        iterations,
        residual: last_res,
    })
}
