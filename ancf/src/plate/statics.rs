//! Static equilibrium of a plate mesh, `Q_e(q) + λ F = 0`, by Newton–Raphson with load
//! increments and a backtracking line search (the procedure of [`crate::statics`] for the
//! planar elements, Kerkkänen §2.4, applied to the thin plate of §4.3), on the shared
//! [`mbd_core::newton`] solver.

use super::mesh::PlateMesh;
use crate::error::{AncfError, invalid};
use crate::statics::{AncfStaticOptions, AncfStaticSolution, check_sizes, run_newton};
use faer::Mat;
use faer::prelude::Solve;
use faer::sparse::SparseColMat;
use mbd_core::newton::{self, Fallback, LineSearch, NewtonProblem};

/// Solve `Q_e(q) + λ F = 0` for `λ = 1/n, …, 1` from `q0`, keeping the coordinates in `fixed`
/// at their `q0` values. `load` is the generalized external force \[N\] (all coordinates).
pub fn solve_plate_static(
    mesh: &PlateMesh, q0: &[f64], fixed: &[usize], load: &[f64], opts: &AncfStaticOptions,
) -> Result<AncfStaticSolution, AncfError> {
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
    let mut problem = PlateStatics {
        mesh,
        q0,
        load,
        map,
        n,
        k: None,
        lam: 0.0,
        line_search: opts.line_search,
    };
    // K Δq = r (K = ∂²U/∂q² = −∂Q_e/∂q), then backtrack on the total potential
    // Π = U − λ Fᵀ(q − q0) (the load is dead, so Π exists and the Newton direction descends it
    // where K is positive definite). A residual-norm search stalls here: the membrane strain of
    // a large-rotation step raises the residual before the next iteration removes it. Without
    // any decrease the full Newton step is taken.
    let line_search = opts.line_search.then_some(LineSearch {
        armijo: 0.0,
        slack: 1e-12,
        accept_below: f64::NEG_INFINITY,
        max_trials: 12,
        fallback: Fallback::FullStep,
    });
    let mut q = q0.to_vec();
    let report = run_newton(
        "plate static",
        &mut problem,
        &mut q,
        &opts.newton(line_search),
    )?;
    let mut r = vec![0.0; n_all];
    problem.residual(&q, 1.0, &mut r)?;
    Ok(AncfStaticSolution {
        q,
        iterations: report.increments.iter().map(|i| i.iterations).collect(),
        residual: problem.residual_norm(&r),
    })
}

/// `Q_e(q) + λ F = 0` of the plate: `x = q` (all coordinates, the fixed ones never
/// corrected), `R = −(Q_e + λF)` (zero on fixed rows), `J = K`, potential
/// `Π = U − λ Fᵀ(q − q0)`.
struct PlateStatics<'a> {
    mesh: &'a PlateMesh,
    q0: &'a [f64],
    load: &'a [f64],
    /// Row of each coordinate in the reduced system (`None`: fixed).
    map: Vec<Option<usize>>,
    /// Number of free coordinates.
    n: usize,
    k: Option<SparseColMat<usize, f64>>,
    lam: f64,
    line_search: bool,
}

impl PlateStatics<'_> {
    fn scatter(&self, f: &[f64], lam: f64, r: &mut [f64]) {
        r.fill(0.0);
        for (i, m) in self.map.iter().enumerate() {
            if m.is_some() {
                r[i] = -(f[i] + lam * self.load[i]);
            }
        }
    }
}

impl NewtonProblem for PlateStatics<'_> {
    type Error = AncfError;

    fn tangent_dim(&self) -> usize {
        self.map.len()
    }

    fn linearize(&mut self, q: &[f64], lam: f64, r: &mut [f64]) -> Result<(), AncfError> {
        let (f, k) = self.mesh.elastic_tangent_mapped(q, &self.map, self.n)?;
        self.scatter(&f, lam, r);
        self.k = Some(k);
        self.lam = lam;
        Ok(())
    }

    fn residual(&mut self, q: &[f64], lam: f64, r: &mut [f64]) -> Result<(), AncfError> {
        let f = self.mesh.elastic_forces(q)?;
        self.scatter(&f, lam, r);
        Ok(())
    }

    fn solve(&mut self, r: &[f64], dx: &mut [f64]) -> Result<(), AncfError> {
        let singular = |detail: String| AncfError::Singular {
            load_factor: self.lam,
            detail,
        };
        let k = self
            .k
            .as_ref()
            .ok_or_else(|| singular("no tangent assembled".into()))?;
        let lu = k
            .sp_lu()
            .map_err(|e| singular(format!("{e:?} (missing supports?)")))?;
        let mut rhs = Mat::<f64>::zeros(self.n, 1);
        for (i, m) in self.map.iter().enumerate() {
            if let Some(row) = m {
                rhs[(*row, 0)] = -r[i];
            }
        }
        let d = lu.solve(&rhs);
        for (i, m) in self.map.iter().enumerate() {
            dx[i] = m.map_or(0.0, |row| d[(row, 0)]);
        }
        Ok(())
    }

    /// `‖R‖∞`.
    fn residual_norm(&self, r: &[f64]) -> f64 {
        newton::max_abs(r)
    }

    fn potential(&mut self, q: &[f64], lam: f64) -> Result<Option<f64>, AncfError> {
        if !self.line_search {
            return Ok(None);
        }
        let work: f64 = (0..q.len())
            .map(|i| self.load[i] * (q[i] - self.q0[i]))
            .sum();
        Ok(Some(self.mesh.strain_energy(q)? - lam * work))
    }
}
