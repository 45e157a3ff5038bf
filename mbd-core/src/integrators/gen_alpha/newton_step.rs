//! One generalized-α step as a [`NewtonProblem`] for the workspace's Newton solver
//! [`crate::newton::solve`].
//!
//! The unknown is the stacked end-of-step vector `x = [Δq; v_{n+1}; v̇_{n+1}; λ_{n+1}]`
//! (`3 n_v + n_c` entries) and the correction `[Δx; Δλ/β']` (`n_v + n_c` entries) solves the
//! scaled iteration matrix of the [module documentation](super). The update is
//!
//! ```text
//!   Δq += Δx,   v += γ' Δx,   v̇ += β' Δx,   λ += β' (Δλ/β')
//! ```
//!
//! (Arnold & Brüls 2007, the position correction drives velocities and accelerations through
//! `∂v/∂Δq = γ'`, `∂v̇/∂Δq = β'`); the correction norm is `‖Δx‖∞` and the scale of the mixed
//! test `‖Δx‖∞ ≤ atol + rtol ‖Δq‖∞` is `‖Δq‖∞` after the update.
//!
//! Modified Newton lives in [`NewtonProblem::linearize`]: from the second iteration on it
//! first solves with the factorisation of the previous iteration and re-factors only when that
//! correction is not yet below the tolerance (for [`NewtonUpdate::EveryStep`] and
//! [`NewtonUpdate::Frozen`]: keeps it unless the correction exceeds
//! [`AlphaConfig::refactor_contraction`](super::AlphaConfig::refactor_contraction) times the
//! previous one).

use super::{AlphaStepper, NewtonUpdate};
use crate::integrators::explain_singular;
use crate::newton::{NewtonProblem, max_abs};
use crate::{MbdError, SecondOrderSystem};

/// The Newton problem of one step of [`AlphaStepper`], borrowing its factorisation, statistics
/// and per-step vectors.
pub(super) struct StepProblem<'a, S: ?Sized, C> {
    pub stepper: &'a mut AlphaStepper<C>,
    pub sys: &'a S,
    /// End of the step \[s\].
    pub t1: f64,
    /// Step size \[s\].
    pub h: f64,
    /// `β'` \[1/s²\].
    pub bp: f64,
    /// `γ'` \[1/s\].
    pub gp: f64,
    pub update: NewtonUpdate,
    /// `q_{n+1} = q_n ⊕ Δq` of the current iterate.
    pub q1: &'a mut [f64],
    /// Force scratch (`n_v`).
    pub f: &'a mut [f64],
    /// Correction obtained with the previous factorisation (`n_v + n_c`).
    pub trial: &'a mut [f64],
    /// Iterations so far in this step.
    pub it: usize,
    /// Whether `trial` is the correction of this iteration.
    pub reuse: bool,
    /// Norm `‖Δx‖∞` of the previous correction of the step (contraction trigger).
    pub prev_norm: f64,
    /// Unknowns and residual of the last [`NewtonProblem::residual`] (line-search trial).
    pub cache_x: &'a mut [f64],
    pub cache_r: &'a mut [f64],
    /// Whether the cache holds an evaluation of this step.
    pub cached: bool,
}

/// `rhs = [−r/β'; −Φ]`.
fn fill_rhs(rhs: &mut [f64], r: &[f64], phi: &[f64], bp: f64) {
    let n = r.len();
    for i in 0..n {
        rhs[i] = -r[i] / bp;
    }
    for i in 0..phi.len() {
        rhs[n + i] = -phi[i];
    }
}

impl<S: SecondOrderSystem + ?Sized, C> NewtonProblem for StepProblem<'_, S, C> {
    type Error = MbdError;

    fn tangent_dim(&self) -> usize {
        self.sys.n_v() + self.sys.n_c()
    }

    /// `r = [M v̇ + Dᵀλ − f; Φ]` at `q_n ⊕ Δq`, then the correction with the old
    /// factorisation or a new iteration matrix.
    fn linearize(&mut self, x: &[f64], _load: f64, r: &mut [f64]) -> Result<(), MbdError> {
        let sys = self.sys;
        let (t1, bp, gp) = (self.t1, self.bp, self.gp);
        let n = sys.n_v();
        self.it += 1;
        self.stepper.stats.newton_iterations += 1;
        let (dq, rest) = x.split_at(n);
        let (v1, rest) = rest.split_at(n);
        let (vdot1, lam1) = rest.split_at(n);
        sys.integrate_position(&self.stepper.state.q, dq, self.q1);
        if self.cached && *self.cache_x == *x {
            r.copy_from_slice(self.cache_r);
        } else {
            let (rr, phi) = r.split_at_mut(n);
            self.stepper
                .residual(sys, t1, self.q1, v1, vdot1, lam1, rr, phi, self.f)?;
        }
        let (rr, phi) = r.split_at_mut(n);
        self.reuse = false;
        let frozen = self.update == NewtonUpdate::Frozen;
        if (self.it > 1 || frozen) && self.stepper.matrix.is_factored() {
            fill_rhs(self.trial, rr, phi, bp);
            let st = &mut *self.stepper;
            st.matrix.solve(self.trial, &mut st.scratch, t1)?;
            let p = &self.stepper.params;
            let dxn = max_abs(&self.trial[..n]);
            self.reuse = match self.update {
                NewtonUpdate::EveryIteration => {
                    dxn <= p.newton_atol_at(gp) + p.newton_rtol * max_abs(dq)
                }
                NewtonUpdate::EveryStep | NewtonUpdate::Frozen => p
                    .refactor_contraction
                    .is_none_or(|theta| self.it == 1 || dxn <= theta * self.prev_norm),
            };
        }
        if !self.reuse {
            self.stepper
                .newton_matrix(
                    sys, t1, self.q1, v1, vdot1, lam1, rr, phi, bp, gp, self.h, self.f,
                )
                .map_err(|e| explain_singular(sys, t1, self.q1, e))?;
        }
        Ok(())
    }

    /// `r` at `x` without touching the iteration matrix; kept for the next
    /// [`NewtonProblem::linearize`] at the same `x` (an accepted line-search trial).
    fn residual(&mut self, x: &[f64], _load: f64, r: &mut [f64]) -> Result<(), MbdError> {
        let sys = self.sys;
        let n = sys.n_v();
        let (dq, rest) = x.split_at(n);
        let (v1, rest) = rest.split_at(n);
        let (vdot1, lam1) = rest.split_at(n);
        sys.integrate_position(&self.stepper.state.q, dq, self.q1);
        let (rr, phi) = r.split_at_mut(n);
        self.stepper
            .residual(sys, self.t1, self.q1, v1, vdot1, lam1, rr, phi, self.f)?;
        self.cache_x.copy_from_slice(x);
        self.cache_r.copy_from_slice(r);
        self.cached = true;
        Ok(())
    }

    fn solve(&mut self, r: &[f64], dx: &mut [f64]) -> Result<(), MbdError> {
        let n = self.sys.n_v();
        if self.reuse {
            dx.copy_from_slice(self.trial);
        } else {
            fill_rhs(dx, &r[..n], &r[n..], self.bp);
            let st = &mut *self.stepper;
            st.matrix.solve(dx, &mut st.scratch, self.t1)?;
        }
        self.prev_norm = max_abs(&dx[..n]);
        Ok(())
    }

    fn update(&mut self, x: &[f64], dx: &[f64], x_new: &mut [f64]) -> Result<(), MbdError> {
        let n = self.sys.n_v();
        let (bp, gp) = (self.bp, self.gp);
        for i in 0..n {
            x_new[i] = x[i] + dx[i];
            x_new[n + i] = x[n + i] + gp * dx[i];
            x_new[2 * n + i] = x[2 * n + i] + bp * dx[i];
        }
        for i in 0..self.sys.n_c() {
            x_new[3 * n + i] = x[3 * n + i] + bp * dx[n + i];
        }
        Ok(())
    }

    /// The model's [`SecondOrderSystem::correction_limit`] at the iterate `q = qₙ ⊕ Δq`, `v`,
    /// for the correction `Δq = dx`, `Δv = γ' dx` (`1` unless
    /// [`AlphaConfig::model_correction_limit`](super::AlphaConfig::model_correction_limit)).
    fn step_limit(&mut self, x: &[f64], dx: &[f64]) -> Result<f64, MbdError> {
        if !self.stepper.params.model_correction_limit {
            return Ok(1.0);
        }
        let sys = self.sys;
        let n = sys.n_v();
        let (dq, rest) = x.split_at(n);
        let v1 = &rest[..n];
        sys.integrate_position(&self.stepper.state.q, dq, self.q1);
        // `f` is free between the residual evaluations: it holds Δv here
        let dv = &mut *self.f;
        for (o, d) in dv.iter_mut().zip(&dx[..n]) {
            *o = self.gp * d;
        }
        let st = &mut *self.stepper;
        sys.correction_limit(self.t1, self.q1, v1, &dx[..n], dv, &mut st.ws)
    }

    /// `‖Δx‖∞` over the position part.
    fn correction_norm(&self, dx: &[f64]) -> f64 {
        max_abs(&dx[..self.sys.n_v()])
    }

    /// `‖Δq‖∞` after the update.
    fn scale(&self, _x_old: &[f64], x_new: &[f64]) -> f64 {
        max_abs(&x_new[..self.sys.n_v()])
    }
}
