//! Static equilibrium of a constrained system: Newton on `f(t, q, 0) − Dᵀλ = 0`, `Φ(t, q) = 0`
//! (the static limit of Ribaric (2.16) / Lin (2.27)).

use crate::integrators::State;
use crate::linalg::KktSolver;
use crate::{MbdError, SecondOrderSystem, SysMatrix};
use faer::Mat;

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
/// (finite differences if it has none). A model without stiffness in some direction (a free
/// body) gives [`MbdError::Singular`].
pub fn static_equilibrium<S: SecondOrderSystem + ?Sized>(
    sys: &S,
    t: f64,
    q0: &[f64],
    opts: &StaticOptions,
) -> Result<StaticSolution, MbdError> {
    let n = sys.n_v();
    let nc = sys.n_c();
    let v0 = vec![0.0; n];
    let mut state = State::new(t, q0.to_vec(), v0.clone());
    state.check(sys)?;
    let mut lambda = vec![0.0; nc];
    let mut kkt = KktSolver::new();
    let mut f = vec![0.0; n];
    let mut phi = vec![0.0; nc];
    let mut qn = q0.to_vec();
    let mut last = f64::INFINITY;
    for it in 1..=opts.max_iterations {
        let q = &state.q;
        sys.forces(t, q, &v0, &mut f)?;
        let mut rhs = vec![0.0; n + nc];
        rhs[..n].copy_from_slice(&f);
        let d = if nc > 0 {
            let d = sys.constraint_jacobian(t, q)?;
            d.tmul_vec_add(-1.0, &lambda, &mut rhs[..n]);
            sys.constraint_residual(t, q, &mut phi)?;
            for i in 0..nc {
                rhs[n + i] = -phi[i];
            }
            Some(d)
        } else {
            None
        };
        let kt = match sys.force_tangent(t, q, &v0)? {
            Some(tg) => tg.stiffness,
            None => fd_stiffness(sys, t, q, &f)?,
        };
        let kc = if nc > 0 {
            sys.constraint_force_tangent(t, q, &lambda)?
        } else {
            None
        };
        let mut blocks = vec![(1.0, &kt)];
        if let Some(kc) = &kc {
            blocks.push((1.0, kc));
        }
        kkt.factor(&blocks, d.as_ref(), t)
            .map_err(|e| super::integrators::explain_singular(sys, t, q, e))?;
        kkt.solve(&mut rhs, t)?;
        let mut norm = rhs[..n].iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let scale = if norm > opts.max_step {
            opts.max_step / norm
        } else {
            1.0
        };
        for x in rhs.iter_mut() {
            *x *= scale;
        }
        norm *= scale;
        sys.integrate_position(&state.q, &rhs[..n], &mut qn);
        sys.normalize(&mut qn);
        state.q.copy_from_slice(&qn);
        for i in 0..nc {
            lambda[i] += rhs[n + i];
        }
        state.check(sys)?;
        last = norm;
        if norm <= opts.tol && scale == 1.0 {
            return Ok(StaticSolution {
                state,
                lambda,
                iterations: it,
            });
        }
    }
    Err(MbdError::NoConvergence {
        t,
        iterations: opts.max_iterations,
        residual: last,
    })
}

fn fd_stiffness<S: SecondOrderSystem + ?Sized>(
    sys: &S,
    t: f64,
    q: &[f64],
    f0: &[f64],
) -> Result<SysMatrix, MbdError> {
    let n = sys.n_v();
    let v0 = vec![0.0; n];
    let mut k = Mat::<f64>::zeros(n, n);
    let mut e = vec![0.0; n];
    let mut qp = vec![0.0; q.len()];
    let mut fp = vec![0.0; n];
    for j in 0..n {
        let eps = 1e-7;
        e[j] = eps;
        sys.integrate_position(q, &e, &mut qp);
        e[j] = 0.0;
        sys.forces(t, &qp, &v0, &mut fp)?;
        for i in 0..n {
            k[(i, j)] = -(fp[i] - f0[i]) / eps;
        }
    }
    Ok(SysMatrix::Dense(k))
}
