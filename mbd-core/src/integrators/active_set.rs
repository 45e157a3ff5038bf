//! Unilateral constraints `g_c(t, q) ≥ 0` with an active set on the generalized-α stepper
//! (Ribaric §7.3, seed-000 note U4): the active candidates are bilateral rows `g_c = 0`
//! appended to the model's constraints ([`ActiveSetSystem`]), and [`ActiveSetStepper`] changes
//! the set between steps.
//!
//! Rule per step: if a free candidate ends a step penetrated (`g_c < 0`), the step is retaken
//! from its start with the deepest such candidate active — a perfectly plastic impact: the
//! index-3 position constraint of generalized-α closes the gap within that step (which is why
//! this driver is written for [`AlphaStepper`]; an index-1 method would only stop the
//! approach). An active candidate whose multiplier turns tensile (compressive force `−λ_c < 0`)
//! is released after the step. Each change restarts the stepper at the current state (index-1
//! accelerations and multipliers recomputed with the new set).
//!
//! A model provides its candidates through [`UnilateralConstraints`] (gap, and the constraint
//! row of an active candidate); the ancf crate's node contact against a rigid obstacle is one.

use super::{AlphaConfig, AlphaStepper, State, Stats, Stepper};
use crate::{MbdError, SecondOrderSystem, SysMatrix, Workspace};
use faer::sparse::Triplet;

/// The constraint row of an active unilateral candidate at `(t, q, v)`: `g = 0` with the
/// Jacobian `∂g/∂q` (velocity coordinates), `ν` and `γ` of `ġ = 0 ⇔ D v = ν` and
/// `D v̇ = γ`, and the curvature `∂²g/∂q²` that enters the constraint-force tangent `λ ∂²g/∂q²`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct UnilateralEval {
    /// Gap `g` \[m\].
    pub gap: f64,
    /// Jacobian entries `(column, ∂g/∂q_column)`.
    pub jacobian: Vec<(usize, f64)>,
    /// `ν` (`−∂g/∂t`: the obstacle's motion).
    pub nu: f64,
    /// `γ` of `D v̇ = γ`.
    pub gamma: f64,
    /// Curvature entries `(row, column, ∂²g/∂q_row∂q_column)`.
    pub curvature: Vec<(usize, usize, f64)>,
}

/// Candidate unilateral constraints `g_c(t, q) ≥ 0`, `c = 0, …, n − 1` of a model (extension
/// point of [`ActiveSetSystem`] and [`ActiveSetStepper`]).
pub trait UnilateralConstraints {
    /// Number of candidates.
    fn n_candidates(&self) -> usize;
    /// Name of candidate `c` (messages, constraint names).
    fn candidate_name(&self, c: usize) -> String;
    /// Gap `g_c(t, q)` \[m\] (> 0 open, < 0 penetrated).
    fn gap(&self, t: f64, q: &[f64], c: usize) -> f64;
    /// The constraint row of candidate `c` at `(t, q, v)` into `row` (empty before the call;
    /// `v` is zero when only the gap, Jacobian, `ν` or curvature are needed).
    fn row(&self, t: f64, q: &[f64], v: &[f64], c: usize, row: &mut UnilateralEval);
}

/// A model `base` with the rows of the active candidates of `set` appended to its constraints
/// (in activation order, after the model's own rows).
pub struct ActiveSetSystem<'a, S: ?Sized, U: ?Sized> {
    base: &'a S,
    set: &'a U,
    active: Vec<usize>,
    /// Whether the stacked matrices are assembled sparsely (the model's mass is sparse).
    sparse: bool,
    zero_v: Vec<f64>,
}

impl<'a, S: SecondOrderSystem + ?Sized, U: UnilateralConstraints + ?Sized>
    ActiveSetSystem<'a, S, U>
{
    /// `base` with no active candidate; the stacked constraint matrices are sparse if the mass
    /// at `(t, q)` is.
    pub fn new(base: &'a S, set: &'a U, t: f64, q: &[f64]) -> Result<Self, MbdError> {
        let sparse = base.mass(t, q)?.is_sparse();
        Ok(Self {
            base,
            set,
            active: Vec::new(),
            sparse,
            zero_v: vec![0.0; base.n_v()],
        })
    }

    /// The model.
    pub fn base(&self) -> &'a S {
        self.base
    }

    /// The candidates.
    pub fn candidates(&self) -> &'a U {
        self.set
    }

    /// Active candidates in activation order (their rows follow the model's).
    pub fn active(&self) -> &[usize] {
        &self.active
    }

    /// Replaces the active set (candidate indices, each at most once).
    pub fn set_active(&mut self, active: Vec<usize>) {
        self.active = active;
    }

    /// Rows of the active candidates at `(t, q, v)`.
    fn rows<'s>(
        &'s self, t: f64, q: &'s [f64], v: Option<&'s [f64]>,
    ) -> impl Iterator<Item = UnilateralEval> + 's {
        let v = v.unwrap_or(&self.zero_v);
        self.active.iter().map(move |&c| {
            let mut row = UnilateralEval::default();
            self.set.row(t, q, v, c, &mut row);
            row
        })
    }
}

impl<S: SecondOrderSystem + ?Sized, U: UnilateralConstraints + ?Sized> SecondOrderSystem
    for ActiveSetSystem<'_, S, U>
{
    crate::forward_dynamics!(base);
    fn n_v(&self) -> usize {
        self.base.n_v()
    }
    fn n_c(&self) -> usize {
        self.base.n_c() + self.active.len()
    }
    fn position_rate(&self, q: &[f64], v: &[f64], qdot: &mut [f64]) {
        self.base.position_rate(q, v, qdot)
    }
    fn normalize(&self, q: &mut [f64]) {
        self.base.normalize(q)
    }
    fn integrate_position(&self, q: &[f64], dq: &[f64], q_new: &mut [f64]) {
        self.base.integrate_position(q, dq, q_new)
    }
    fn check_state(&self, t: f64, q: &[f64], v: &[f64]) -> Result<(), MbdError> {
        self.base.check_state(t, q, v)
    }
    fn constraint_name(&self, row: usize) -> String {
        let nb = self.base.n_c();
        match row.checked_sub(nb).and_then(|i| self.active.get(i)) {
            Some(&c) => self.set.candidate_name(c),
            None => self.base.constraint_name(row),
        }
    }
    fn dynamic_residual(
        &self, t: f64, q: &[f64], v: &[f64], vdot: &[f64], r: &mut [f64], ws: &mut Workspace,
    ) -> Result<bool, MbdError> {
        self.base.dynamic_residual(t, q, v, vdot, r, ws)
    }
    /// The model's tangent plus `Σ λ_c ∂²g_c/∂q²` of the active rows.
    fn constraint_force_tangent(
        &self, t: f64, q: &[f64], lambda: &[f64],
    ) -> Result<Option<SysMatrix>, MbdError> {
        let nb = self.base.n_c();
        let base = if nb > 0 {
            self.base.constraint_force_tangent(t, q, &lambda[..nb])?
        } else {
            None
        };
        let mut entries = Vec::new();
        for (row, &l) in self.rows(t, q, None).zip(&lambda[nb..]) {
            entries.extend(
                row.curvature
                    .iter()
                    .map(|&(i, j, x)| Triplet::new(i, j, l * x)),
            );
        }
        if base.is_none() && self.active.is_empty() {
            return Ok(None);
        }
        let n = self.n_v();
        let blocks: Vec<_> = base.into_iter().map(|m| (0, 0, m)).collect();
        SysMatrix::assemble(&blocks, entries, n, n, self.sparse, t).map(Some)
    }
    fn constraint_residual(&self, t: f64, q: &[f64], phi: &mut [f64]) -> Result<(), MbdError> {
        let nb = self.base.n_c();
        self.base.constraint_residual(t, q, &mut phi[..nb])?;
        for (i, &c) in self.active.iter().enumerate() {
            phi[nb + i] = self.set.gap(t, q, c);
        }
        Ok(())
    }
    fn constraint_jacobian(&self, t: f64, q: &[f64]) -> Result<SysMatrix, MbdError> {
        let nb = self.base.n_c();
        let mut entries = Vec::new();
        for (i, row) in self.rows(t, q, None).enumerate() {
            entries.extend(
                row.jacobian
                    .iter()
                    .map(|&(j, x)| Triplet::new(nb + i, j, x)),
            );
        }
        let base = self.base.constraint_jacobian(t, q)?;
        SysMatrix::assemble(
            &[(0, 0, base)],
            entries,
            self.n_c(),
            self.n_v(),
            self.sparse,
            t,
        )
    }
    fn constraint_velocity_rhs(&self, t: f64, q: &[f64], nu: &mut [f64]) -> Result<(), MbdError> {
        let nb = self.base.n_c();
        self.base.constraint_velocity_rhs(t, q, &mut nu[..nb])?;
        for (x, row) in nu[nb..].iter_mut().zip(self.rows(t, q, None)) {
            *x = row.nu;
        }
        Ok(())
    }
    fn constraint_gamma(
        &self, t: f64, q: &[f64], v: &[f64], gamma: &mut [f64],
    ) -> Result<(), MbdError> {
        let nb = self.base.n_c();
        self.base.constraint_gamma(t, q, v, &mut gamma[..nb])?;
        for (x, row) in gamma[nb..].iter_mut().zip(self.rows(t, q, Some(v))) {
            *x = row.gamma;
        }
        Ok(())
    }
}

/// The state after one step of [`ActiveSetStepper`], for observers.
#[derive(Debug, Clone, Copy)]
pub struct ActiveSetStep<'s> {
    /// State after the step.
    pub state: &'s State,
    /// Candidates active during the step (activation order).
    pub active: &'s [usize],
    /// Compressive force `−λ_c` of each active candidate \[N\] (same order as `active`); the
    /// tensile ones are released after the step.
    pub forces: &'s [f64],
}

/// Generalized-α ([`AlphaStepper`]) on a model with unilateral constraints by an active set
/// (see the module documentation for the rule).
pub struct ActiveSetStepper<'a, S: ?Sized, U: ?Sized> {
    sys: ActiveSetSystem<'a, S, U>,
    stepper: AlphaStepper,
    params: AlphaConfig,
    /// Statistics of the steppers replaced at restarts.
    done: Stats,
    retakes: usize,
    restarts: usize,
    step_active: Vec<usize>,
    step_forces: Vec<f64>,
}

impl<'a, S: SecondOrderSystem + ?Sized, U: UnilateralConstraints + ?Sized>
    ActiveSetStepper<'a, S, U>
{
    /// Starts at `state0` with no candidate active; every candidate must start open
    /// (`g_c ≥ 0`).
    pub fn new(
        base: &'a S, set: &'a U, state0: State, params: AlphaConfig,
    ) -> Result<Self, MbdError> {
        state0.check(base)?;
        for c in 0..set.n_candidates() {
            let g = set.gap(state0.t, &state0.q, c);
            // a NaN gap is rejected too
            if g.is_nan() || g < 0.0 {
                return Err(MbdError::InvalidInput {
                    item: format!("unilateral constraint {}", set.candidate_name(c)),
                    reason: format!("starts penetrated (gap {g:e} m at t = {} s)", state0.t),
                });
            }
        }
        let sys = ActiveSetSystem::new(base, set, state0.t, &state0.q)?;
        let stepper = AlphaStepper::new(&sys, state0, params)?;
        Ok(Self {
            sys,
            stepper,
            params,
            done: Stats::default(),
            retakes: 0,
            restarts: 0,
            step_active: Vec::new(),
            step_forces: Vec::new(),
        })
    }

    /// Current state.
    pub fn state(&self) -> &State {
        self.stepper.state()
    }

    /// The model with the current active rows.
    pub fn system(&self) -> &ActiveSetSystem<'a, S, U> {
        &self.sys
    }

    /// Candidates active now (after the releases of the last step).
    pub fn active(&self) -> &[usize] {
        self.sys.active()
    }

    /// Candidates active during the last step and their compressive forces \[N\].
    pub fn last_step(&self) -> ActiveSetStep<'_> {
        ActiveSetStep {
            state: self.stepper.state(),
            active: &self.step_active,
            forces: &self.step_forces,
        }
    }

    /// Statistics of all steppers so far (the stepper restarts at every change of the set).
    pub fn stats(&self) -> Stats {
        let mut s = self.done;
        s.accumulate(&self.stepper.stats);
        s
    }

    /// Retaken steps (activations) and restarts (activations and releases) so far.
    pub fn changes(&self) -> (usize, usize) {
        (self.retakes, self.restarts)
    }

    fn restart(&mut self, state: State) -> Result<(), MbdError> {
        self.done.accumulate(&self.stepper.stats);
        self.stepper = AlphaStepper::new(&self.sys, state, self.params)?;
        self.restarts += 1;
        Ok(())
    }

    /// One step of size `h` \[s\]: retaken with the deepest penetrated free candidate active
    /// until no free candidate ends penetrated (at most `n + 1` retakes, then
    /// [`MbdError::ActiveSet`]); then the active candidates with a tensile multiplier are
    /// released. [`Self::last_step`] reports the set and forces of the accepted step.
    pub fn step(&mut self, h: f64) -> Result<(), MbdError> {
        let start = self.stepper.state().clone();
        let n = self.sys.set.n_candidates();
        let mut retakes = 0usize;
        loop {
            self.stepper.step(&self.sys, Some(h))?;
            let st = self.stepper.state();
            let deepest = (0..n)
                .filter(|c| !self.sys.active.contains(c))
                .map(|c| (c, self.sys.set.gap(st.t, &st.q, c)))
                .filter(|(_, g)| *g < 0.0)
                .min_by(|a, b| a.1.total_cmp(&b.1));
            let Some((c, _)) = deepest else { break };
            retakes += 1;
            if retakes > n + 1 {
                return Err(MbdError::ActiveSet {
                    t: start.t,
                    retakes,
                });
            }
            self.retakes += 1;
            self.sys.active.push(c);
            self.restart(start.clone())?;
        }
        // integrator reaction −Dᵀλ ⇒ compressive force −λ
        let nb = self.sys.base.n_c();
        self.step_active.clone_from(&self.sys.active);
        self.step_forces.clear();
        self.step_forces
            .extend(self.stepper.lambda()[nb..].iter().map(|l| -l));
        if self.step_forces.iter().any(|f| *f < 0.0) {
            let keep: Vec<usize> = self
                .step_active
                .iter()
                .zip(&self.step_forces)
                .filter(|(_, f)| **f >= 0.0)
                .map(|(c, _)| *c)
                .collect();
            self.sys.active = keep;
            let s = self.stepper.state().clone();
            self.restart(s)?;
        }
        Ok(())
    }

    /// Steps with the nominal step `params.h` (the last one shortened) until `t_end` \[s\],
    /// calling `observer` after every accepted step (before its releases take effect).
    pub fn advance_to(
        &mut self, t_end: f64, observer: &mut dyn FnMut(&ActiveSetStep),
    ) -> Result<(), MbdError> {
        let h = self.params.h;
        while self.stepper.state().t < t_end - 1e-9 * h {
            let hs = h.min(t_end - self.stepper.state().t);
            self.step(hs)?;
            observer(&self.last_step());
        }
        Ok(())
    }
}
