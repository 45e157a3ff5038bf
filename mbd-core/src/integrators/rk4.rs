//! Classical fixed-step Runge–Kutta 4 on the index-1 equations of motion.

use super::accel::{AccelSolver, Stabilization};
use super::{Solution, State, Stats, Stepper, check_step, impl_integrator, integrate_stepper};
use crate::{MbdError, SecondOrderSystem};

/// Fixed-step classical RK4 for `q̇ = H(q) v`, `v̇ = a(t, q, v)` where `a` solves the
/// augmented equations at every stage (Ribaric (2.16), Lin (2.27)).
///
/// The last step is shortened to end exactly at `t_end`. Positions are normalised
/// ([`SecondOrderSystem::normalize`]) and, if requested, projected after every step.
#[derive(
    Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields)]
pub struct Rk4 {
    /// Step size \[s\].
    pub h: f64,
    /// Constraint stabilisation.
    #[serde(default)]
    pub stabilization: Stabilization,
}

impl Rk4 {
    /// RK4 with step `h` \[s\] and no constraint stabilisation.
    pub fn new(h: f64) -> Self {
        Self {
            h,
            stabilization: Stabilization::default(),
        }
    }

    /// Sets the constraint stabilisation.
    pub fn with_stabilization(mut self, s: Stabilization) -> Self {
        self.stabilization = s;
        self
    }

    /// A stepper started at `state0`.
    pub fn stepper<S: SecondOrderSystem + ?Sized>(
        &self, sys: &S, state0: State,
    ) -> Result<Rk4Stepper, MbdError> {
        Rk4Stepper::new(sys, state0, *self)
    }

    /// Integrates from `state0` to `t_end` \[s\]; `observer` sees the initial state and every
    /// step's end state.
    pub fn integrate<S: SecondOrderSystem + ?Sized, R: super::Proceed>(
        &self, sys: &S, state0: State, t_end: f64, observer: impl FnMut(&State) -> R,
    ) -> Result<Solution, MbdError> {
        integrate_stepper(self.stepper(sys, state0)?, sys, t_end, observer)
    }
}

/// Stepping object of [`Rk4`]: state, statistics and the stage workspaces.
///
/// Step `k` after the grid origin `t₀` runs from `t₀ + k h` to `t₀ + (k + 1) h`; before a stop
/// time `t_s` the number of steps is `⌈(t_s − t₀)/h − 10⁻⁹⌉` and the last one ends on `t_s`,
/// after which `t_s` becomes the new grid origin.
pub struct Rk4Stepper {
    params: Rk4,
    state: State,
    stats: Stats,
    solver: AccelSolver,
    kq: [Vec<f64>; 4],
    kv: [Vec<f64>; 4],
    lam: Vec<f64>,
    qs: Vec<f64>,
    vs: Vec<f64>,
    origin: f64,
    k: usize,
}

impl Rk4Stepper {
    /// Current state (also [`Stepper::state`]).
    pub fn state(&self) -> &State {
        &self.state
    }

    /// Statistics so far (also [`Stepper::stats`]).
    pub fn stats(&self) -> &Stats {
        &self.stats
    }

    /// Starts at `state0`.
    pub fn new<S: SecondOrderSystem + ?Sized>(
        sys: &S, state0: State, params: Rk4,
    ) -> Result<Self, MbdError> {
        check_step(params.h, "RK4 step")?;
        state0.check(sys)?;
        let (nq, nv) = (sys.n_q(), sys.n_v());
        Ok(Self {
            params,
            origin: state0.t,
            k: 0,
            state: state0,
            stats: Stats::default(),
            solver: AccelSolver::default(),
            kq: std::array::from_fn(|_| vec![0.0; nq]),
            kv: std::array::from_fn(|_| vec![0.0; nv]),
            lam: vec![0.0; sys.n_c()],
            qs: vec![0.0; nq],
            vs: vec![0.0; nv],
        })
    }

    /// One RK4 step from `t0` to `t1` (`state.t` is replaced by `t1`).
    fn step_from<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, t0: f64, t1: f64,
    ) -> Result<(), MbdError> {
        let h = t1 - t0;
        let stab = self.params.stabilization;
        let st = &mut self.state;
        for s in 0..4 {
            let (c, base) = match s {
                0 => (0.0, None),
                1 => (0.5, Some(0)),
                2 => (0.5, Some(1)),
                _ => (1.0, Some(2)),
            };
            match base {
                None => {
                    self.qs.copy_from_slice(&st.q);
                    self.vs.copy_from_slice(&st.v);
                }
                Some(b) => {
                    for i in 0..self.qs.len() {
                        self.qs[i] = st.q[i] + c * h * self.kq[b][i];
                    }
                    for i in 0..self.vs.len() {
                        self.vs[i] = st.v[i] + c * h * self.kv[b][i];
                    }
                }
            }
            let ts = t0 + c * h;
            sys.position_rate(&self.qs, &self.vs, &mut self.kq[s]);
            self.solver.solve(
                sys,
                ts,
                &self.qs,
                &self.vs,
                &stab,
                &mut self.stats,
                &mut self.kv[s],
                &mut self.lam,
            )?;
        }
        let (kq, kv) = (&self.kq, &self.kv);
        for i in 0..st.q.len() {
            st.q[i] += h / 6.0 * (kq[0][i] + 2.0 * kq[1][i] + 2.0 * kq[2][i] + kq[3][i]);
        }
        for i in 0..st.v.len() {
            st.v[i] += h / 6.0 * (kv[0][i] + 2.0 * kv[1][i] + 2.0 * kv[2][i] + kv[3][i]);
        }
        st.t = t1;
        sys.normalize(&mut st.q);
        if stab.project {
            self.solver.project(sys, st, &stab, &mut self.stats)?;
        }
        st.check(sys)?;
        self.stats.steps += 1;
        Ok(())
    }
}

impl<S: SecondOrderSystem + ?Sized> Stepper<S> for Rk4Stepper {
    fn state(&self) -> &State {
        &self.state
    }

    fn stats(&self) -> &Stats {
        &self.stats
    }

    fn step(&mut self, sys: &S, h: Option<f64>) -> Result<(), MbdError> {
        match h {
            None => {
                let t0 = self.origin + self.k as f64 * self.params.h;
                self.step_from(sys, t0, t0 + self.params.h)?;
                self.k += 1;
            }
            Some(h) => {
                check_step(h, "RK4 step")?;
                let t0 = self.state.t;
                self.step_from(sys, t0, t0 + h)?;
                self.origin = self.state.t;
                self.k = 0;
            }
        }
        Ok(())
    }

    fn step_until(&mut self, sys: &S, t_stop: f64) -> Result<bool, MbdError> {
        let h = self.params.h;
        let n_steps = ((t_stop - self.origin) / h - 1e-9).ceil().max(0.0) as usize;
        if self.k >= n_steps {
            return Ok(false);
        }
        let t0 = self.origin + self.k as f64 * h;
        let last = self.k + 1 == n_steps;
        let t1 = if last { t_stop } else { t0 + h };
        self.step_from(sys, t0, t1)?;
        self.k += 1;
        if last {
            self.origin = t_stop;
            self.k = 0;
        }
        Ok(true)
    }
}

impl_integrator!(Rk4);
