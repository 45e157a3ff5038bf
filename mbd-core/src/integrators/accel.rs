//! Index-1 (acceleration-level) solution of the augmented equations, Baumgarte stabilisation
//! and position/velocity projection.

use super::{State, Stats, explain_singular};
use crate::linalg::KktSolver;
use crate::{MbdError, SecondOrderSystem, Workspace};

/// Constraint stabilisation for the explicit (index-1) integrators.
///
/// Baumgarte (Nikravesh; Ribaric (2.18)): the acceleration constraint `D v̇ = γ` is replaced by
/// `D v̇ = γ − 2α (D v − ν) − β² Φ`. Projection (optional, after every accepted step) solves
/// `[M Dᵀ; D 0] [Δq; μ] = [0; −Φ]` (mass-weighted minimum-norm correction, Newton iterations)
/// and then `[M Dᵀ; D 0] [Δv; μ] = [0; ν − D v]`.
#[derive(
    Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields, default)]
pub struct Stabilization {
    /// Baumgarte velocity gain α \[1/s\] (0 disables).
    pub baumgarte_alpha: f64,
    /// Baumgarte position gain β \[1/s\] (0 disables).
    pub baumgarte_beta: f64,
    /// Project positions and velocities onto the constraint manifold after each step.
    pub project: bool,
    /// Tolerance on `‖Φ‖∞` for the position projection \[m or rad\].
    pub projection_tol: f64,
    /// Maximum Newton iterations of the position projection.
    pub max_projection_iterations: usize,
}

impl Default for Stabilization {
    fn default() -> Self {
        Self {
            baumgarte_alpha: 0.0,
            baumgarte_beta: 0.0,
            project: false,
            projection_tol: 1e-12,
            max_projection_iterations: 10,
        }
    }
}

/// Accelerations and Lagrange multipliers of the index-1 augmented equations
/// `[M Dᵀ; D 0] [v̇; λ] = [f; γ]` (Ribaric (2.16), Lin (2.27)).
#[derive(Debug, Clone, PartialEq)]
pub struct Acceleration {
    /// Accelerations `v̇` (length `n_v`).
    pub vdot: Vec<f64>,
    /// Lagrange multipliers `λ` (length `n_c`); the generalized reaction forces are `−Dᵀλ`.
    pub lambda: Vec<f64>,
}

/// Reusable solver of the index-1 equations (keeps the factorisation of a constant mass
/// matrix of an unconstrained system) and the model's workspace of the explicit steppers.
#[derive(Default)]
pub(crate) struct AccelSolver {
    kkt: KktSolver,
    /// Scratch of the model's force evaluations ([`SecondOrderSystem::forces`]).
    pub(crate) ws: Workspace,
    constant_factored: bool,
    f: Vec<f64>,
    rhs: Vec<f64>,
}

impl AccelSolver {
    pub(crate) fn solve<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, t: f64, q: &[f64], v: &[f64], stab: &Stabilization, stats: &mut Stats,
        vdot: &mut [f64], lambda: &mut [f64],
    ) -> Result<(), MbdError> {
        let n = sys.n_v();
        let nc = sys.n_c();
        self.f.resize(n, 0.0);
        sys.forces(t, q, v, &mut self.f, &mut self.ws)?;
        stats.force_evaluations += 1;
        if let Some(i) = self.f.iter().position(|x| !x.is_finite()) {
            return Err(MbdError::NonFinite {
                what: format!("force on {}", sys.dof_name(i)),
                t,
            });
        }
        self.rhs.clear();
        self.rhs.extend_from_slice(&self.f);
        self.rhs.resize(n + nc, 0.0);
        let reuse = sys.mass_is_constant() && nc == 0 && self.constant_factored;
        if nc > 0 {
            let d = sys.constraint_jacobian(t, q)?;
            let (g, rest) = self.rhs[n..].split_at_mut(nc);
            debug_assert!(rest.is_empty());
            sys.constraint_gamma(t, q, v, g)?;
            if stab.baumgarte_alpha != 0.0 || stab.baumgarte_beta != 0.0 {
                let mut dv = vec![0.0; nc];
                d.mul_vec(v, &mut dv);
                let mut nu = vec![0.0; nc];
                sys.constraint_velocity_rhs(t, q, &mut nu)?;
                let mut phi = vec![0.0; nc];
                sys.constraint_residual(t, q, &mut phi)?;
                let (a, b) = (stab.baumgarte_alpha, stab.baumgarte_beta);
                for i in 0..nc {
                    g[i] -= 2.0 * a * (dv[i] - nu[i]) + b * b * phi[i];
                }
            }
            let m = sys.mass(t, q)?;
            self.kkt
                .factor(&[(1.0, &m)], Some(&d), t)
                .map_err(|e| explain_singular(sys, t, q, e))?;
            stats.factorizations += 1;
        } else if !reuse {
            let m = sys.mass(t, q)?;
            self.kkt.factor(&[(1.0, &m)], None, t).map_err(|e| {
                if let MbdError::Singular { t, .. } = e {
                    MbdError::Singular {
                        t,
                        detail: "mass matrix is singular".into(),
                    }
                } else {
                    e
                }
            })?;
            stats.factorizations += 1;
            self.constant_factored = sys.mass_is_constant();
        }
        self.kkt.solve(&mut self.rhs, t)?;
        vdot.copy_from_slice(&self.rhs[..n]);
        lambda.copy_from_slice(&self.rhs[n..]);
        Ok(())
    }

    /// Projects `q` then `v` onto the constraint manifold (see [`Stabilization`]).
    pub(crate) fn project<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, state: &mut State, stab: &Stabilization, stats: &mut Stats,
    ) -> Result<(), MbdError> {
        let nc = sys.n_c();
        if nc == 0 {
            return Ok(());
        }
        let t = state.t;
        let n = sys.n_v();
        let mut phi = vec![0.0; nc];
        let mut qn = state.q.clone();
        let mut converged = false;
        let mut res = f64::INFINITY;
        for _ in 0..=stab.max_projection_iterations {
            sys.constraint_residual(t, &state.q, &mut phi)?;
            res = phi.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            if res <= stab.projection_tol {
                converged = true;
                break;
            }
            stats.newton_iterations += 1;
            let m = sys.mass(t, &state.q)?;
            let d = sys.constraint_jacobian(t, &state.q)?;
            self.kkt
                .factor(&[(1.0, &m)], Some(&d), t)
                .map_err(|e| explain_singular(sys, t, &state.q, e))?;
            stats.factorizations += 1;
            self.constant_factored = false;
            let mut rhs = vec![0.0; n + nc];
            for i in 0..nc {
                rhs[n + i] = -phi[i];
            }
            self.kkt.solve(&mut rhs, t)?;
            sys.integrate_position(&state.q, &rhs[..n], &mut qn);
            state.q.copy_from_slice(&qn);
        }
        if !converged {
            return Err(MbdError::NoConvergence {
                t,
                iterations: stab.max_projection_iterations,
                residual: res,
            });
        }
        project_velocities_with(&mut self.kkt, sys, state, stats)?;
        self.constant_factored = false;
        Ok(())
    }
}

fn project_velocities_with<S: SecondOrderSystem + ?Sized>(
    kkt: &mut KktSolver, sys: &S, state: &mut State, stats: &mut Stats,
) -> Result<(), MbdError> {
    let nc = sys.n_c();
    if nc == 0 {
        return Ok(());
    }
    let t = state.t;
    let n = sys.n_v();
    let m = sys.mass(t, &state.q)?;
    let d = sys.constraint_jacobian(t, &state.q)?;
    let mut rhs = vec![0.0; n + nc];
    sys.constraint_velocity_rhs(t, &state.q, &mut rhs[n..])?;
    let mut dv = vec![0.0; nc];
    d.mul_vec(&state.v, &mut dv);
    for i in 0..nc {
        rhs[n + i] -= dv[i];
    }
    kkt.factor(&[(1.0, &m)], Some(&d), t)
        .map_err(|e| explain_singular(sys, t, &state.q, e))?;
    stats.factorizations += 1;
    kkt.solve(&mut rhs, t)?;
    for i in 0..n {
        state.v[i] += rhs[i];
    }
    Ok(())
}

/// Accelerations and multipliers of `sys` at `state` from the index-1 augmented equations
/// (Ribaric (2.16), Lin (2.27)), with the Baumgarte terms of `stab`.
pub fn accelerations<S: SecondOrderSystem + ?Sized>(
    sys: &S, state: &State, stab: &Stabilization,
) -> Result<Acceleration, MbdError> {
    state.check(sys)?;
    let mut solver = AccelSolver::default();
    let mut vdot = vec![0.0; sys.n_v()];
    let mut lambda = vec![0.0; sys.n_c()];
    let mut stats = Stats::default();
    solver.solve(
        sys,
        state.t,
        &state.q,
        &state.v,
        stab,
        &mut stats,
        &mut vdot,
        &mut lambda,
    )?;
    Ok(Acceleration { vdot, lambda })
}

/// Projects the positions of `state` onto `Φ(t, q) = 0` (mass-weighted minimum-norm Newton
/// correction) and then the velocities onto `D v = ν`. Returns the number of Newton iterations.
pub fn project_positions<S: SecondOrderSystem + ?Sized>(
    sys: &S, state: &mut State, stab: &Stabilization,
) -> Result<usize, MbdError> {
    state.check(sys)?;
    let mut solver = AccelSolver::default();
    let mut stats = Stats::default();
    solver.project(sys, state, stab, &mut stats)?;
    Ok(stats.newton_iterations)
}

/// Projects the velocities of `state` onto `D v = ν` (mass-weighted minimum-norm correction).
pub fn project_velocities<S: SecondOrderSystem + ?Sized>(
    sys: &S, state: &mut State,
) -> Result<(), MbdError> {
    state.check(sys)?;
    let mut kkt = KktSolver::new();
    let mut stats = Stats::default();
    project_velocities_with(&mut kkt, sys, state, &mut stats)
}
