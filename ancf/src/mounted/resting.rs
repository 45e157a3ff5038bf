//! The one initial-state problem of the ANCF belt drives (issue 33 item 2): the belt at static
//! equilibrium on resting pulleys, its first node held by penalty springs in the directions the
//! frictionless contact leaves free (the thesis does not describe the procedure, seed note §11
//! item 19; the planar drive's steps are [`crate::belt_drive::initial`], the plate's
//! [`crate::plate::belt_drive::initial`]).
//!
//! With all pulleys at rest, Newton–Raphson with a backtracking line search (the shared
//! [`mbd_core::newton`] solver) solves on the belt rows
//!
//! `R(e) = −(Q_e(e) + Q_c(e) − k_hold Σ_d d (d·(x₀ − x₀⁰))) = 0`
//!
//! with `Q_e` the elastic forces (Kerkkänen (2.20)), `Q_c` the normal contact forces ((3.20);
//! (4.45) over the plate; friction vanishes at rest), `x₀` the position of node 0, `x₀⁰` its
//! placed position and `d` the held unit directions. What differs between the discretisations
//! (the element groups, the forces, the tangent and the held directions) is [`RestingBelt`].

use super::{AncfBeltDrive, DriveKind};
use crate::error::AncfError;
use crate::sparse::Pattern;
use crate::statics::run_newton;
use faer::sparse::linalg::solvers::SymbolicLu;
use mbd_core::newton::{Fallback, LineSearch, NewtonOptions, NewtonProblem, Tolerances};
use mbd_core::{SecondOrderSystem, Workspace};

/// Options of the static solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InitialOptions {
    /// Maximum Newton iterations.
    pub max_iterations: usize,
    /// Convergence: `‖Δe‖∞ ≤ tol (1 + ‖e‖∞)`.
    pub tolerance: f64,
}

impl Default for InitialOptions {
    fn default() -> Self {
        Self {
            max_iterations: 100,
            tolerance: 1e-11,
        }
    }
}

/// An ANCF belt drive whose resting equilibrium [`solve_resting`] finds (module
/// documentation). The belt's coordinates are the first [`AncfBeltDrive::n_belt`] of the
/// system's, grouped by element as [`DriveKind::element_dofs`]; node 0's position is their
/// first `dim`, `dim` the length of each held direction of [`Self::holding`].
pub(crate) trait RestingBelt: SecondOrderSystem {
    /// What the errors call the belt (`"belt"`, `"plate belt"`).
    const LABEL: &'static str;
    /// Stiffness `k_hold` \[N/m\] of the holding springs and their unit directions in node 0's
    /// position coordinates.
    fn holding(&self) -> (f64, Vec<Vec<f64>>);
    /// `Q_e + Q_c` at rest into `f` (the system's length) and the pulley torques into `torques`.
    fn resting_forces(&self, q: &[f64], f: &mut [f64], torques: &mut [f64], ws: &mut Workspace);
    /// `Q_e + Q_c` at rest and their tangent `−∂(Q_e + Q_c)/∂e` into `out`.
    fn resting_tangent(&self, q: &[f64], out: Linearisation<'_>, ws: &mut Workspace);
}

/// Where [`RestingBelt::resting_tangent`] writes: the forces `f` (the system's length) and the
/// tangent's values `kv` in `pattern` (built from [`DriveKind::element_dofs`] plus one holding
/// group: its first groups are the elements, in order).
pub(crate) struct Linearisation<'a> {
    /// The tangent's sparsity pattern.
    pub pattern: &'a Pattern,
    /// The forces.
    pub f: &'a mut [f64],
    /// The tangent's values in `pattern`.
    pub kv: &'a mut [f64],
}

/// The resting equilibrium of [`solve_resting`].
#[derive(Debug, Clone)]
pub(crate) struct Resting {
    /// Equilibrium coordinates of the whole system (those beyond the belt as given).
    pub q: Vec<f64>,
    /// Newton iterations.
    pub iterations: usize,
    /// Final residual norm \[N\].
    pub residual: f64,
    /// Force of each holding spring at equilibrium, `k_hold d·(x₀ − x₀⁰)` \[N\].
    pub holding_forces: Vec<f64>,
}

/// The resting equilibrium of `belt` from the start `q0` (module documentation); the
/// coordinates beyond the belt's (pulley angles, a tensioner arm's angle) are held at their
/// values in `q0`. `name` names the solve in errors.
pub(crate) fn solve_resting<K: DriveKind>(
    belt: &AncfBeltDrive<K>, name: &str, q0: Vec<f64>, opts: &InitialOptions,
) -> Result<Resting, AncfError>
where
    AncfBeltDrive<K>: RestingBelt,
{
    let nb = belt.n_belt();
    let (k_hold, dirs) = belt.holding();
    let dim = dirs.first().map_or(0, Vec::len);
    let mut groups = belt.kind.element_dofs();
    let n_el = groups.len();
    groups.push((0..dim).map(Some).collect());
    let pattern = Pattern::new(nb, &groups);
    let symbolic =
        SymbolicLu::try_new(pattern.symbolic().as_ref()).map_err(|e| AncfError::Singular {
            load_factor: 1.0,
            detail: format!(
                "symbolic LU of the {} stiffness: {e:?}",
                <AncfBeltDrive<K> as RestingBelt>::LABEL
            ),
        })?;
    let mut hold = vec![0.0; dim * dim];
    for d in &dirs {
        for i in 0..dim {
            for j in 0..dim {
                hold[i + dim * j] += k_hold * d[i] * d[j];
            }
        }
    }
    let n = belt.n_q();
    let mut problem = Problem {
        belt,
        kv: pattern.zeros(),
        pattern,
        symbolic,
        hold,
        n_el,
        k_hold,
        dirs,
        x0: q0[..dim].to_vec(),
        f: vec![0.0; n],
        torques: vec![0.0; belt.pulleys().len()],
        iteration: 0,
        ws: Workspace::new(),
    };
    let newton = NewtonOptions {
        max_iterations: opts.max_iterations,
        tolerances: Tolerances::relative(opts.tolerance),
        line_search: Some(LineSearch {
            armijo: 1e-4,
            slack: 0.0,
            accept_below: 1e-9,
            max_trials: 20,
            fallback: Fallback::FullStep,
        }),
        ..Default::default()
    };
    let mut q = q0;
    let report = run_newton(name, &mut problem, &mut q, &newton)?;
    let mut r = vec![0.0; n];
    problem.residual(&q, 1.0, &mut r)?;
    let holding_forces = problem.offsets(&q).iter().map(|u| k_hold * u).collect();
    Ok(Resting {
        iterations: report.iterations(),
        residual: problem.residual_norm(&r),
        holding_forces,
        q,
    })
}

/// The problem of [`solve_resting`]: `x = q` (belt and the other coordinates; only the belt's
/// are corrected), `R` of the module documentation on the belt rows.
struct Problem<'a, K: DriveKind> {
    belt: &'a AncfBeltDrive<K>,
    pattern: Pattern,
    symbolic: SymbolicLu<usize>,
    kv: Vec<f64>,
    hold: Vec<f64>,
    /// Index of the holding group in the pattern.
    n_el: usize,
    k_hold: f64,
    dirs: Vec<Vec<f64>>,
    x0: Vec<f64>,
    f: Vec<f64>,
    torques: Vec<f64>,
    /// The belt's scratch ([`mbd_core::Workspace`]).
    ws: Workspace,
    /// Linearisations so far (named in errors).
    iteration: usize,
}

impl<K: DriveKind> Problem<'_, K>
where
    AncfBeltDrive<K>: RestingBelt,
{
    /// `d·(x₀ − x₀⁰)` for each held direction `d` \[m\].
    fn offsets(&self, q: &[f64]) -> Vec<f64> {
        self.dirs
            .iter()
            .map(|d| {
                d.iter()
                    .zip(q.iter().zip(&self.x0))
                    .fold(0.0, |s, (di, (qi, xi))| s + di * (qi - xi))
            })
            .collect()
    }

    /// Subtract the holding spring forces from `self.f` and write `r = −f` on the belt rows.
    fn hold_and_scatter(&mut self, q: &[f64], r: &mut [f64]) {
        let u = self.offsets(q);
        for (d, u) in self.dirs.iter().zip(u) {
            for (fi, di) in self.f.iter_mut().zip(d) {
                *fi -= self.k_hold * u * di;
            }
        }
        let nb = self.belt.n_belt();
        r.fill(0.0);
        for i in 0..nb {
            r[i] = -self.f[i];
        }
    }
}

impl<K: DriveKind> NewtonProblem for Problem<'_, K>
where
    AncfBeltDrive<K>: RestingBelt,
{
    type Error = AncfError;

    fn tangent_dim(&self) -> usize {
        self.f.len()
    }

    fn linearize(&mut self, q: &[f64], _load: f64, r: &mut [f64]) -> Result<(), AncfError> {
        self.iteration += 1;
        let out = Linearisation {
            pattern: &self.pattern,
            f: &mut self.f,
            kv: &mut self.kv,
        };
        self.belt.resting_tangent(q, out, &mut self.ws);
        self.pattern
            .add_element(&mut self.kv, self.n_el, &self.hold, 1.0);
        self.hold_and_scatter(q, r);
        Ok(())
    }

    fn residual(&mut self, q: &[f64], _load: f64, r: &mut [f64]) -> Result<(), AncfError> {
        self.belt
            .resting_forces(q, &mut self.f, &mut self.torques, &mut self.ws);
        self.hold_and_scatter(q, r);
        Ok(())
    }

    fn solve(&mut self, r: &[f64], dx: &mut [f64]) -> Result<(), AncfError> {
        self.pattern
            .lu_correction(&self.symbolic, &self.kv, r, dx)
            .map_err(|e| AncfError::Singular {
                load_factor: 1.0,
                detail: format!(
                    "{} tangent stiffness at iteration {}: {e}",
                    <AncfBeltDrive<K> as RestingBelt>::LABEL,
                    self.iteration
                ),
            })
    }
}
