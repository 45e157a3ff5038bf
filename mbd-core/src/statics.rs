//! Static equilibrium of a constrained system: Newton on `f(t, q, 0) − Dᵀλ = 0`, `Φ(t, q) = 0`
//! (the static limit of Ribaric (2.16) / Lin (2.27)), solved by the shared [`crate::newton`] solver.

use crate::integrators::State;
use crate::linalg::KktSolver;
use crate::newton::{self, NewtonOptions, NewtonProblem, NewtonWorkspace, Tolerances};
use crate::system::finite_difference_tangent;
use crate::{MbdError, SecondOrderSystem, Workspace};

/// Options of [`static_equilibrium`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticOptions {
    /// Tolerance on the correction `‖Δx‖∞` \[m or rad\].
    pub tol: f64,
    /// Maximum Newton iterations.
    pub max_iterations: usize,
    /// Largest correction per iteration `‖Δx‖∞` (damped Newton) \[m or rad\].
    pub max_step: f64,
}

impl Default for StaticOptions {
    fn default() -> Self {
        Self {
            tol: 1e-10,
            max_iterations: 50,
            max_step: f64::INFINITY,
        }
    }
}

/// Result of [`static_equilibrium`].
#[derive(Debug, Clone)]
pub struct StaticSolution {
    /// Equilibrium state (velocities zero).
    pub state: State,
    /// Lagrange multipliers (reactions `−Dᵀλ`).
    pub lambda: Vec<f64>,
    /// Newton iterations.
    pub iterations: usize,
}

/// Static equilibrium at time `t` \[s\] from the guess `q0`: Newton iterations on
/// `[K_t + K_c, Dᵀ; D, 0] [Δx; Δλ] = [f − Dᵀλ; −Φ]`, `q ← q ⊕ Δx`, with the model's tangent
/// (finite differences, [`finite_difference_tangent`], if it has none), by the shared
/// [`newton::solve`]. A model without stiffness in some direction (a free body) gives
/// [`MbdError::Singular`].
pub fn static_equilibrium<S: SecondOrderSystem + ?Sized>(
    sys: &S, t: f64, q0: &[f64], opts: &StaticOptions,
) -> Result<StaticSolution, MbdError> {
    let n = sys.n_v();
    let nc = sys.n_c();
    let state = State::new(t, q0.to_vec(), vec![0.0; n]);
    state.check(sys)?;
    let mut problem = Statics {
        sys,
        state,
        kkt: KktSolver::new(),
        f: vec![0.0; n],
        phi: vec![0.0; nc],
        ws: Workspace::new(),
    };
    let mut x = q0.to_vec();
    x.resize(q0.len() + nc, 0.0);
    let newton = NewtonOptions {
        max_iterations: opts.max_iterations,
        tolerances: Tolerances::absolute(opts.tol),
        max_step: opts.max_step,
        ..Default::default()
    };
    let report = newton::solve(&mut problem, &mut x, &newton, &mut NewtonWorkspace::new())
        .map_err(|e| e.into_mbd(t))?;
    let lambda = x.split_off(q0.len());
    problem.state.q.copy_from_slice(&x);
    Ok(StaticSolution {
        state: problem.state,
        lambda,
        iterations: report.iterations(),
    })
}

/// The static KKT problem: unknowns `x = (q, λ)`, residual `R = [Dᵀλ − f; Φ]`, correction
/// `(Δx, Δλ)` with `Δx` in the model's velocity space.
struct Statics<'a, S: ?Sized> {
    sys: &'a S,
    /// Zero-velocity state at `t` (holds `q` for the finiteness check).
    state: State,
    kkt: KktSolver,
    f: Vec<f64>,
    phi: Vec<f64>,
    /// The model's scratch.
    ws: Workspace,
}

impl<S: SecondOrderSystem + ?Sized> NewtonProblem for Statics<'_, S> {
    type Error = MbdError;

    fn tangent_dim(&self) -> usize {
        self.f.len() + self.phi.len()
    }

    fn linearize(&mut self, x: &[f64], _load: f64, r: &mut [f64]) -> Result<(), MbdError> {
        let (sys, t) = (self.sys, self.state.t);
        let (n, nc) = (self.f.len(), self.phi.len());
        let (q, lambda) = x.split_at(x.len() - nc);
        let v0 = &self.state.v;
        sys.forces(t, q, v0, &mut self.f, &mut self.ws)?;
        // rhs = [f − Dᵀλ; −Φ] = −R
        r[..n].copy_from_slice(&self.f);
        let d = if nc > 0 {
            let d = sys.constraint_jacobian(t, q)?;
            d.tmul_vec_add(-1.0, lambda, &mut r[..n]);
            sys.constraint_residual(t, q, &mut self.phi)?;
            for i in 0..nc {
                r[n + i] = -self.phi[i];
            }
            Some(d)
        } else {
            None
        };
        for ri in r.iter_mut() {
            *ri = -*ri;
        }
        let kt = match sys.force_tangent(t, q, v0, &mut self.ws)? {
            Some(tg) => tg.stiffness,
            None => finite_difference_tangent(sys, t, q, v0, &mut self.ws)?.stiffness,
        };
        let kc = if nc > 0 {
            sys.constraint_force_tangent(t, q, lambda)?
        } else {
            None
        };
        let mut blocks = vec![(1.0, &kt)];
        if let Some(kc) = &kc {
            blocks.push((1.0, kc));
        }
        self.kkt
            .factor(&blocks, d.as_ref(), t)
            .map_err(|e| crate::integrators::explain_singular(sys, t, q, e))
    }

    fn solve(&mut self, r: &[f64], dx: &mut [f64]) -> Result<(), MbdError> {
        for (d, ri) in dx.iter_mut().zip(r) {
            *d = -ri;
        }
        self.kkt.solve(dx, self.state.t)
    }

    fn update(&mut self, x: &[f64], dx: &[f64], x_new: &mut [f64]) -> Result<(), MbdError> {
        let n = self.f.len();
        let nq = x.len() - self.phi.len();
        self.sys
            .integrate_position(&x[..nq], &dx[..n], &mut x_new[..nq]);
        self.sys.normalize(&mut x_new[..nq]);
        for i in nq..x.len() {
            x_new[i] = x[i] + dx[n + i - nq];
        }
        self.state.q.copy_from_slice(&x_new[..nq]);
        self.state.check(self.sys)
    }

    /// `‖Δx‖∞` over the coordinates only (the multipliers have force units).
    fn correction_norm(&self, dx: &[f64]) -> f64 {
        newton::max_abs(&dx[..self.f.len()])
    }
}
