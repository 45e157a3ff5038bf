//! Classical fixed-step Runge–Kutta 4 on the index-1 equations of motion.

use super::accel::{AccelSolver, Stabilization};
use super::{Integrator, Solution, State, Stats, check_step};
use crate::{MbdError, SecondOrderSystem};

/// Fixed-step classical RK4 for `q̇ = H(q) v`, `v̇ = a(t, q, v)` where `a` solves the
/// augmented equations at every stage (Ribaric (2.16), Lin (2.27)).
///
/// The last step is shortened to end exactly at `t_end`. Positions are normalised
/// ([`SecondOrderSystem::normalize`]) and, if requested, projected after every step.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
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

    /// Integrates from `state0` to `t_end` \[s\]; `observer` sees the initial state and every
    /// step's end state.
    pub fn integrate<S: SecondOrderSystem + ?Sized>(
        &self,
        sys: &S,
        state0: State,
        t_end: f64,
        mut observer: impl FnMut(&State),
    ) -> Result<Solution, MbdError> {
        check_step(self.h, "RK4 step")?;
        state0.check(sys)?;
        let nq = sys.n_q();
        let nv = sys.n_v();
        let nc = sys.n_c();
        let mut stats = Stats::default();
        let mut solver = AccelSolver::default();
        let mut st = state0;
        observer(&st);
        let mut kq = vec![vec![0.0; nq]; 4];
        let mut kv = vec![vec![0.0; nv]; 4];
        let mut lam = vec![0.0; nc];
        let mut qs = vec![0.0; nq];
        let mut vs = vec![0.0; nv];
        let stab = self.stabilization;
        let t_start = st.t;
        let n_steps = ((t_end - t_start) / self.h - 1e-9).ceil().max(0.0) as usize;
        for k in 0..n_steps {
            let t0 = t_start + k as f64 * self.h;
            let t1 = if k + 1 == n_steps { t_end } else { t0 + self.h };
            let h = t1 - t0;
            for s in 0..4 {
                let (c, base) = match s {
                    0 => (0.0, None),
                    1 => (0.5, Some(0)),
                    2 => (0.5, Some(1)),
                    _ => (1.0, Some(2)),
                };
                match base {
                    None => {
                        qs.copy_from_slice(&st.q);
                        vs.copy_from_slice(&st.v);
                    }
                    Some(b) => {
                        for i in 0..nq {
                            qs[i] = st.q[i] + c * h * kq[b][i];
                        }
                        for i in 0..nv {
                            vs[i] = st.v[i] + c * h * kv[b][i];
                        }
                    }
                }
                let ts = t0 + c * h;
                sys.position_rate(&qs, &vs, &mut kq[s]);
                let (kv_s, _) = kv.split_at_mut(s + 1);
                solver.solve(sys, ts, &qs, &vs, &stab, &mut stats, &mut kv_s[s], &mut lam)?;
            }
            for i in 0..nq {
                st.q[i] += h / 6.0 * (kq[0][i] + 2.0 * kq[1][i] + 2.0 * kq[2][i] + kq[3][i]);
            }
            for i in 0..nv {
                st.v[i] += h / 6.0 * (kv[0][i] + 2.0 * kv[1][i] + 2.0 * kv[2][i] + kv[3][i]);
            }
            st.t = t1;
            sys.normalize(&mut st.q);
            if stab.project {
                solver.project(sys, &mut st, &stab, &mut stats)?;
            }
            st.check(sys)?;
            stats.steps += 1;
            observer(&st);
        }
        Ok(Solution {
            state: st,
            stats,
            events: Vec::new(),
        })
    }
}

impl Integrator for Rk4 {
    fn integrate_dyn(
        &mut self,
        sys: &dyn SecondOrderSystem,
        state0: State,
        t_end: f64,
        observer: &mut dyn FnMut(&State),
    ) -> Result<Solution, MbdError> {
        self.integrate(sys, state0, t_end, observer)
    }
}
