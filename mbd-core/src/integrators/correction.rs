//! Step correction of the generalized-α stepper: nonsmooth (unilateral, frictional) contact as
//! impulses / multipliers solved with the stepper's factored iteration matrix.
//!
//! After the Newton iteration of a step has converged on the smooth equations
//! `r = M v̇ + Dᵀλ − f(t, q, v) = 0`, `Φ(t, q) = 0` (module [`GeneralizedAlpha`]
//! (super::GeneralizedAlpha)), a [`StepCorrection`] may add generalized contact forces
//! `f_c = Jᵀ λ_c` to the end-of-step balance. Linearised at the converged iterate with the
//! scaled iteration matrix `S = M + (γ'/β') C_t + K_t/β'` of Arnold & Brüls (2007), the
//! corrected end-of-step unknowns solve
//!
//! ```text
//!   [ S   Dᵀ ] [ Δv̇ ]   [ f_c ]        Δv̇ = S⁻¹ Jᵀ λ_c   (on the bilateral constraints D Δv̇ = 0),
//!   [ D   0  ] [ Δλ ] = [ 0   ],
//!   Δq = Δv̇ / β',   Δv = (γ'/β') Δv̇,   β' = (1 − α_m)/(h² β (1 − α_f)),   γ' = γ/(h β),
//! ```
//!
//! so that `q, v, v̇` stay on the generalized-α update formulas and the algorithmic
//! acceleration `a_{n+1} = (α_f v̇_n − α_m a_n + (1 − α_f) v̇_{n+1})/(1 − α_m)` formed at
//! acceptance is consistent with them. A contact `i` with gap `g_i(q)` and Jacobian row `J_i`
//! then sees the Delassus operator `W = J S⁻¹ Jᵀ`: gap `g + W λ_c / β'`, normal/tangential
//! velocity `J v + (γ'/β') W λ_c`. An index-3 (position-level) unilateral law solves
//! `0 ≤ g + W λ_n/β' ⊥ λ_n ≥ 0`; Coulomb friction the set-valued law on the tangential
//! velocity, e.g. by Alart–Curnier's semismooth Newton method on `W` (as the rolling tire
//! does with its explicit `S⁻¹`). The correction is exact for linear models (constant `S`);
//! for nonlinear ones it is the linearisation about the converged smooth step.
//!
//! Impacts: a force correction closes a gap at position level but leaves the contact with the
//! normal velocity `J v + (γ'/β') W λ_c`, which is a rebound after an impact, and the large
//! impact `v̇` stays in the algorithmic acceleration `a`. Impacts are therefore better treated as in the nonsmooth
//! generalized-α scheme (Brüls, Acary & Cardona 2014): a position-only correction
//! ([`AlphaCorrection::apply_position_correction`], `δq = M⁻¹ Jᵀ ν`) and a velocity jump
//! ([`AlphaCorrection::apply_velocity_jump`], `δv = M⁻¹ Jᵀ Λ`, Newton's impact law), which do
//! not enter `v̇` and `a`.

use super::State;
use super::gen_alpha::IterationMatrix;
use crate::{MbdError, SecondOrderSystem};
use faer::{MatMut, MatRef};

/// A correction of the converged generalized-α step (extension point for nonsmooth contact:
/// implement [`correct`](StepCorrection::correct), compute gaps and Jacobians from
/// [`AlphaCorrection::q`], solve the contact law with [`AlphaCorrection::solve`] and apply the
/// result with [`AlphaCorrection::apply`]).
pub trait StepCorrection<S: SecondOrderSystem + ?Sized> {
    /// Corrects the end-of-step solution in `step` (called once per accepted Newton solve).
    fn correct(&mut self, sys: &S, step: &mut AlphaCorrection<'_>) -> Result<(), MbdError>;
}

/// No correction (smooth models).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoCorrection;

impl<S: SecondOrderSystem + ?Sized> StepCorrection<S> for NoCorrection {
    fn correct(&mut self, _sys: &S, _step: &mut AlphaCorrection<'_>) -> Result<(), MbdError> {
        Ok(())
    }
}

/// `(q_n, Δq, q_{n+1}) ↦ q_{n+1} = q_n ⊕ Δq` ([`SecondOrderSystem::integrate_position`]).
pub(crate) type PositionUpdate<'a> = &'a dyn Fn(&[f64], &[f64], &mut [f64]);

/// The converged generalized-α step handed to a [`StepCorrection`]: the end-of-step unknowns
/// and the factored iteration matrix (see the module documentation for the formulas).
pub struct AlphaCorrection<'a> {
    pub(crate) h: f64,
    pub(crate) beta_prime: f64,
    pub(crate) gamma_prime: f64,
    pub(crate) start: &'a State,
    pub(crate) t1: f64,
    pub(crate) dq: &'a mut [f64],
    pub(crate) q: &'a mut [f64],
    pub(crate) v: &'a mut [f64],
    pub(crate) vdot: &'a mut [f64],
    pub(crate) lambda: &'a mut [f64],
    pub(crate) matrix: &'a mut IterationMatrix,
    pub(crate) rhs: &'a mut [f64],
    /// Solve scratch of the explicit inverse (`n_v + n_c`).
    pub(crate) scratch: &'a mut [f64],
    pub(crate) integrate_position: PositionUpdate<'a>,
    pub(crate) factorizations: usize,
    pub(crate) factor_id: usize,
}

impl AlphaCorrection<'_> {
    /// End time `t_{n+1}` \[s\].
    pub fn t(&self) -> f64 {
        self.t1
    }

    /// Step size `h` \[s\].
    pub fn h(&self) -> f64 {
        self.h
    }

    /// `β' = (1 − α_m)/(h² β (1 − α_f))` \[1/s²\]: `Δq = Δv̇/β'`.
    pub fn beta_prime(&self) -> f64 {
        self.beta_prime
    }

    /// `γ' = γ/(h β)` \[1/s\]: `Δv = (γ'/β') Δv̇`.
    pub fn gamma_prime(&self) -> f64 {
        self.gamma_prime
    }

    /// State at the start of the step `t_n`.
    pub fn start(&self) -> &State {
        self.start
    }

    /// Number of factorisations of the iteration matrix so far: while it is unchanged, columns
    /// `S⁻¹ Jᵀ` (or an explicit `S⁻¹`) computed with [`solve`](Self::solve) in an earlier step
    /// are still valid and may be cached.
    pub fn factorizations(&self) -> usize {
        self.factorizations
    }

    /// Identity of the factorisation [`solve`](Self::solve) uses: results of earlier solves
    /// (e.g. cached columns `S⁻¹ Jᵀ`) stay valid while it is unchanged. Unlike
    /// [`factorizations`](Self::factorizations) it also changes when the stepper swaps in the
    /// kept factorisation of another step size
    /// ([`NewtonUpdate::Frozen`](super::NewtonUpdate::Frozen)).
    pub fn factor_id(&self) -> usize {
        self.factor_id
    }

    /// `out = S⁻¹ f` (on the bilateral constraints) for the columns of `f` (`n_v × k`; `out`
    /// is `(n_v + n_c) × k`, its last `n_c` rows the multipliers): many solves at once, one
    /// matrix product with [`AlphaConfig::explicit_inverse`](super::AlphaConfig::explicit_inverse).
    pub fn solve_columns(&self, f: MatRef<'_, f64>, out: MatMut<'_, f64>) -> Result<(), MbdError> {
        if f.nrows() != self.v.len() || out.nrows() != self.v.len() + self.lambda.len() {
            return Err(MbdError::InvalidInput {
                item: "step correction solve".into(),
                reason: format!(
                    "f has {} rows (expected n_v = {}), out {} (expected n_v + n_c = {})",
                    f.nrows(),
                    self.v.len(),
                    out.nrows(),
                    self.v.len() + self.lambda.len()
                ),
            });
        }
        self.matrix.solve_columns(f, out, self.t1)
    }

    /// End-of-step positions `q_{n+1}` (not yet normalised).
    pub fn q(&self) -> &[f64] {
        self.q
    }

    /// End-of-step velocities `v_{n+1}`.
    pub fn v(&self) -> &[f64] {
        self.v
    }

    /// End-of-step accelerations `v̇_{n+1}`.
    pub fn vdot(&self) -> &[f64] {
        self.vdot
    }

    /// End-of-step multipliers `λ_{n+1}` of the bilateral constraints.
    pub fn lambda(&self) -> &[f64] {
        self.lambda
    }

    /// Solves `[S Dᵀ; D 0] [Δv̇; Δλ] = [f; 0]` with the factored iteration matrix: `dvdot =
    /// S⁻¹ f` on the bilateral constraints (length `n_v`), `dlambda` their multipliers
    /// (length `n_c`).
    pub fn solve(
        &mut self, f: &[f64], dvdot: &mut [f64], dlambda: &mut [f64],
    ) -> Result<(), MbdError> {
        let n = self.v.len();
        let nc = self.lambda.len();
        if f.len() != n || dvdot.len() != n || dlambda.len() != nc {
            return Err(MbdError::InvalidInput {
                item: "step correction solve".into(),
                reason: format!(
                    "f, dvdot have lengths {}, {} (expected n_v = {n}), dlambda {} (expected n_c = {nc})",
                    f.len(),
                    dvdot.len(),
                    dlambda.len()
                ),
            });
        }
        self.rhs[..n].copy_from_slice(f);
        self.rhs[n..].iter_mut().for_each(|x| *x = 0.0);
        self.matrix.solve(self.rhs, self.scratch, self.t1)?;
        dvdot.copy_from_slice(&self.rhs[..n]);
        dlambda.copy_from_slice(&self.rhs[n..]);
        Ok(())
    }

    /// Applies the increments `Δv̇`, `Δλ` consistently: `Δq = Δv̇/β'`, `Δv = (γ'/β') Δv̇`
    /// (positions through [`SecondOrderSystem::integrate_position`]).
    pub fn apply(&mut self, dvdot: &[f64], dlambda: &[f64]) {
        let (bp, gp) = (self.beta_prime, self.gamma_prime);
        for i in 0..self.v.len() {
            let dx = dvdot[i] / bp;
            self.dq[i] += dx;
            self.v[i] += gp * dx;
            self.vdot[i] += dvdot[i];
        }
        for (l, d) in self.lambda.iter_mut().zip(dlambda) {
            *l += d;
        }
        (self.integrate_position)(&self.start.q, self.dq, self.q);
    }

    /// A position correction `q_{n+1} = q_n ⊕ (Δq + δq)` that leaves `v`, `v̇` and `a` unchanged
    /// (e.g. `δq = M⁻¹ Jᵀ ν` closing the gaps, the position-level multiplier of the nonsmooth
    /// generalized-α scheme of Brüls, Acary & Cardona 2014).
    pub fn apply_position_correction(&mut self, dq: &[f64]) {
        for (x, d) in self.dq.iter_mut().zip(dq) {
            *x += d;
        }
        (self.integrate_position)(&self.start.q, self.dq, self.q);
    }

    /// An impulsive velocity jump `v_{n+1} += Δv` (e.g. `Δv = M⁻¹ Jᵀ Λ` of a Newton impact
    /// law with restitution 0 that keeps a closed contact at zero normal velocity, as in the
    /// nonsmooth generalized-α scheme of Brüls, Acary & Cardona 2014). Only `v` changes: `q`,
    /// `v̇` and hence `a` keep their values (the index-3 position correction by
    /// [`apply`](Self::apply) alone leaves a closed contact with the velocity
    /// `(γ'/β') W λ` and so rebounds).
    pub fn apply_velocity_jump(&mut self, dv: &[f64]) {
        for (v, d) in self.v.iter_mut().zip(dv) {
            *v += d;
        }
    }

    /// Adds the generalized force `f` \[N or N·m\] to the end-of-step balance:
    /// [`solve`](Self::solve) then [`apply`](Self::apply).
    pub fn apply_force(&mut self, f: &[f64]) -> Result<(), MbdError> {
        let mut dvdot = vec![0.0; self.v.len()];
        let mut dlambda = vec![0.0; self.lambda.len()];
        self.solve(f, &mut dvdot, &mut dlambda)?;
        self.apply(&dvdot, &dlambda);
        Ok(())
    }
}
