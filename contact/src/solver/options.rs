//! Settings and outcome of [`ContactSolver::solve`](super::ContactSolver::solve).

use crate::friction::{Coulomb, FrictionLaw};
use std::sync::Arc;

/// Settings of [`ContactSolver::solve`](super::ContactSolver::solve).
#[derive(Debug, Clone)]
pub struct ContactSolverOptions {
    /// Friction law of the contact nodes, any [`FrictionLaw`] (Ribaric §7.3, §8.4.3: set-valued
    /// [`Coulomb`]; seed note U20: [`SlipRegularized`](crate::SlipRegularized)). Its tangential equation is
    /// the Alart–Curnier `Φ_T = f − p(f, u, λ̂)` of [`FrictionLaw::augmented`].
    pub law: Arc<dyn FrictionLaw>,
    /// Relative tolerance on `‖Φ‖∞ / max λ` (forces).
    pub tol: f64,
    /// Newton iterations before the fallback.
    pub max_newton: usize,
    /// Outer rounds of the fallback alternation.
    pub max_rounds: usize,
}

impl Default for ContactSolverOptions {
    fn default() -> Self {
        Self {
            law: Arc::new(Coulomb { mu: 0.0 }),
            tol: 1e-10,
            max_newton: 30,
            max_rounds: 500,
        }
    }
}

/// Outcome of [`ContactSolver::solve`](super::ContactSolver::solve).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactSolverReport {
    /// Whether `‖Φ‖∞ ≤ tol · max λ` at the returned forces.
    pub converged: bool,
    /// Newton iterations (LU factorisations) used.
    pub newton_iterations: usize,
    /// Chord iterations (solves with an earlier LU) used.
    pub chord_iterations: usize,
    /// Whether the fallback alternation was run.
    pub fallback: bool,
    /// Normal LCP solves of the fallback.
    pub lcp_solves: usize,
    /// Friction Gauss–Seidel sweeps of the fallback.
    pub sweeps: usize,
    /// Final `‖Φ‖∞` \[N\].
    pub residual: f64,
}
