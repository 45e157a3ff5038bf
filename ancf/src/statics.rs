//! Static equilibrium `Q_e(q) + λ F = 0` by Newton–Raphson with load increments and a
//! backtracking line search (Kerkkänen §2.4 and §3.3: "Newton–Raphson iterations"; the
//! increments and the line search are the seed note's §8.3 recommendation), all on the shared
//! [`mbd_core::newton`] solver.

use crate::element::AncfElement;
use crate::error::{AncfError, invalid};
use crate::mesh::AncfMesh;
use crate::sparse::Pattern;
use crate::system::MeshForce;
use faer::Mat;
use faer::prelude::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use mbd_core::newton::{
    self, Fallback, LineSearch, LoadStepping, NewtonError, NewtonOptions, NewtonProblem,
    NewtonReport, NewtonWorkspace, Tolerances,
};

mod unilateral;
pub use unilateral::{UnilateralOptions, UnilateralSolution, solve_static_unilateral};

/// Options of the static solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AncfStaticOptions {
    /// Number of equal load increments (≥ 1).
    pub increments: usize,
    /// Maximum Newton iterations per increment.
    pub max_iterations: usize,
    /// Convergence: `‖Δq‖∞ ≤ tol · (1 + ‖q‖∞)` \[-\].
    pub tolerance: f64,
    /// Backtracking line search on the residual norm.
    pub line_search: bool,
}

impl Default for AncfStaticOptions {
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
pub struct AncfStaticSolution {
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
    context: &str, n: usize, q0: &[f64], load: &[f64],
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
    context: &str, n: usize, fixed: &[usize],
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
pub fn solve_static<E: AncfElement>(
    mesh: &AncfMesh<E>, q0: &[f64], fixed: &[usize], load: &[f64], opts: &AncfStaticOptions,
) -> Result<AncfStaticSolution, AncfError> {
    solve_static_with(mesh, q0, fixed, load, &[], opts)
}

/// [`solve_static`] with additional (configuration-dependent, velocity-free) forces such as
/// frictionless penalty contact, evaluated at zero velocity; their tangent enters the Newton
/// matrix. The load factor scales `load` only.
///
/// The iteration is the shared [`mbd_core::newton::solve`]: convergence on
/// `‖Δq‖∞ ≤ tol (1 + ‖q‖∞)`; with `line_search`, a conservative problem (no extra forces)
/// backtracks on the total potential `Π = U − λFᵀq` after regularising `K + μI`
/// (Levenberg–Marquardt) until the step descends, otherwise on `‖R‖₂`.
pub fn solve_static_with<E: AncfElement>(
    mesh: &AncfMesh<E>, q0: &[f64], fixed: &[usize], load: &[f64], extra: &[&dyn MeshForce<E>],
    opts: &AncfStaticOptions,
) -> Result<AncfStaticSolution, AncfError> {
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
    let symbolic =
        SymbolicLu::try_new(pattern.symbolic().as_ref()).map_err(|e| AncfError::Singular {
            load_factor: 0.0,
            detail: format!("symbolic LU: {e:?}"),
        })?;
    // conservative problems (no extra forces) use the total potential as merit function
    let energy_merit = extra.is_empty() && opts.line_search;
    let mut problem = MeshStatics {
        mesh,
        load,
        extra,
        free,
        to_reduced,
        diag: (0..nf).map(|i| pattern.diagonal_position(i)).collect(),
        kfull: full.zeros(),
        cfull: full.zeros(),
        kv: pattern.zeros(),
        pattern,
        symbolic,
        f: vec![0.0; n],
        zero_v: vec![0.0; n],
        energy_merit,
        lam: 0.0,
    };
    let line_search = opts.line_search.then_some(if energy_merit {
        LineSearch {
            armijo: 1e-4,
            slack: 1e-14,
            accept_below: f64::NEG_INFINITY,
            max_trials: 31,
            fallback: Fallback::LastTrial,
        }
    } else {
        LineSearch {
            armijo: 1e-4,
            slack: 0.0,
            accept_below: 1e-9,
            max_trials: 13,
            fallback: Fallback::FullStep,
        }
    });
    let mut q = q0.to_vec();
    let report = run_newton("static", &mut problem, &mut q, &opts.newton(line_search))?;
    Ok(AncfStaticSolution {
        q,
        iterations: report.increments.iter().map(|i| i.iterations).collect(),
        residual: report.residual,
    })
}

impl AncfStaticOptions {
    /// The shared solver's options: `increments` equal load steps, `max_iterations`, the
    /// relative correction test `‖Δq‖∞ ≤ tolerance (1 + ‖q‖∞)` and the given line search.
    pub(crate) fn newton(&self, line_search: Option<LineSearch>) -> NewtonOptions {
        NewtonOptions {
            max_iterations: self.max_iterations,
            tolerances: Tolerances::relative(self.tolerance),
            line_search,
            load: LoadStepping {
                increments: self.increments,
                max_cuts: 0,
            },
            ..Default::default()
        }
    }
}

/// [`newton::solve`] from `x` with a fresh workspace, its failures as [`AncfError`] naming
/// `context`.
pub(crate) fn run_newton<P: NewtonProblem<Error = AncfError>>(
    context: &str, problem: &mut P, x: &mut [f64], opts: &NewtonOptions,
) -> Result<NewtonReport, AncfError> {
    newton::solve(problem, x, opts, &mut NewtonWorkspace::new())
        .map_err(|e| newton_error(context, e))
}

/// The typed error of a failed shared Newton solve; `context` names the solver.
fn newton_error(context: &str, e: NewtonError<AncfError>) -> AncfError {
    match e {
        NewtonError::Problem(e) => e,
        NewtonError::InvalidOption { field, reason } => {
            invalid(format!("{context} solve: {field}"), reason)
        }
        NewtonError::NonFinite { what, load, .. } => AncfError::NonFinite {
            what: format!("{context} Newton {what} at load factor {load}"),
        },
        NewtonError::NoConvergence {
            load,
            iterations,
            residual,
            ..
        } => AncfError::NoConvergence {
            load_factor: load,
            iterations,
            residual,
        },
        NewtonError::NotSettled { load, passes } => AncfError::ActiveSet {
            load_factor: load,
            passes,
        },
    }
}

/// `Q_e(q) + Q_x(q) + λ F = 0` over the free coordinates: `x = q` (all coordinates, the
/// fixed ones never corrected), `R = −(Q_e + Q_x + λF)` (zero on fixed rows), `J = K`.
struct MeshStatics<'a, E: AncfElement> {
    mesh: &'a AncfMesh<E>,
    load: &'a [f64],
    extra: &'a [&'a dyn MeshForce<E>],
    free: Vec<usize>,
    /// Position of each full-pattern entry in the reduced pattern.
    to_reduced: Vec<Option<usize>>,
    diag: Vec<usize>,
    kfull: Vec<f64>,
    cfull: Vec<f64>,
    kv: Vec<f64>,
    pattern: Pattern,
    symbolic: SymbolicLu<usize>,
    f: Vec<f64>,
    zero_v: Vec<f64>,
    /// Line search on the potential: regularise the tangent until the step descends.
    energy_merit: bool,
    /// Load factor of the last linearisation.
    lam: f64,
}

impl<E: AncfElement> MeshStatics<'_, E> {
    /// `r = −(f + λF)` on the free rows from the forces in `self.f`.
    fn scatter_residual(&self, lam: f64, r: &mut [f64]) {
        r.fill(0.0);
        for &k in &self.free {
            r[k] = -(self.f[k] + lam * self.load[k]);
        }
    }

    fn factor(&self, kv: Vec<f64>) -> Result<Lu<usize, f64>, AncfError> {
        Lu::try_new_with_symbolic(self.symbolic.clone(), self.pattern.to_matrix(kv).as_ref())
            .map_err(|e| AncfError::Singular {
                load_factor: self.lam,
                detail: format!("{e:?}"),
            })
    }
}

impl<E: AncfElement> NewtonProblem for MeshStatics<'_, E> {
    type Error = AncfError;

    fn tangent_dim(&self) -> usize {
        self.f.len()
    }

    fn linearize(&mut self, q: &[f64], lam: f64, r: &mut [f64]) -> Result<(), AncfError> {
        self.lam = lam;
        self.kfull.fill(0.0);
        let full = self.mesh.pattern();
        self.mesh
            .elastic_tangent_into(q, &mut self.f, full, &mut self.kfull, 1.0);
        for x in self.extra {
            x.add_forces(self.mesh, 0.0, q, &self.zero_v, &mut self.f);
            x.add_tangent(
                self.mesh,
                0.0,
                q,
                &self.zero_v,
                &mut self.kfull,
                &mut self.cfull,
            );
        }
        self.kv.fill(0.0);
        for (p, r) in self.to_reduced.iter().enumerate() {
            if let Some(r) = r {
                self.kv[*r] += self.kfull[p];
            }
        }
        self.scatter_residual(lam, r);
        Ok(())
    }

    fn residual(&mut self, q: &[f64], lam: f64, r: &mut [f64]) -> Result<(), AncfError> {
        self.mesh.elastic_forces(q, &mut self.f);
        for x in self.extra {
            x.add_forces(self.mesh, 0.0, q, &self.zero_v, &mut self.f);
        }
        self.scatter_residual(lam, r);
        Ok(())
    }

    fn solve(&mut self, r: &[f64], dx: &mut [f64]) -> Result<(), AncfError> {
        let nf = self.free.len();
        let rhs = Mat::<f64>::from_fn(nf, 1, |i, _| -r[self.free[i]]);
        let mut d = self.factor(self.kv.clone())?.solve(&rhs);
        if self.energy_merit {
            // Π = U − λFᵀq decreases along Δ iff RᵀΔ < 0; otherwise regularise K + μI
            // (Levenberg–Marquardt) until it does
            let slope = |d: &Mat<f64>| (0..nf).map(|i| rhs[(i, 0)] * d[(i, 0)]).sum::<f64>();
            let dmax = self
                .diag
                .iter()
                .map(|&p| self.kv[p].abs())
                .fold(0.0, f64::max);
            let mut mu_rel = 1e-8;
            while slope(&d) <= 0.0 && mu_rel < 1e3 {
                let mut kreg = self.kv.clone();
                for &p in &self.diag {
                    kreg[p] += mu_rel * dmax;
                }
                if let Ok(lu) = self.factor(kreg) {
                    d = lu.solve(&rhs);
                }
                mu_rel *= 10.0;
            }
        }
        dx.fill(0.0);
        for (i, &k) in self.free.iter().enumerate() {
            dx[k] = d[(i, 0)];
        }
        Ok(())
    }

    fn potential(&mut self, q: &[f64], lam: f64) -> Result<Option<f64>, AncfError> {
        Ok(self.energy_merit.then(|| {
            self.mesh.strain_energy(q)
                - lam * q.iter().zip(self.load).map(|(a, b)| a * b).sum::<f64>()
        }))
    }
}
