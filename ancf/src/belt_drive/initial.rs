//! The pre-strained initial configuration of the belt on the pulleys.
//!
//! The thesis does not describe it (seed note §11 item 19). Procedure used here:
//!
//! 1. **Placement.** Node `i` is put on the undeformed belt path (spans and wraps, computed
//!    from the pulley geometry by [`BeltPath`](fe_model::generate::belt_path::BeltPath)) at arc
//!    length `s_i = i L_p / n`, with `r_x = (L_p / L_b) e_t` (the uniform stretch that maps the
//!    unstretched belt length `L_b` onto the path length `L_p`) and `r_y = Ĩ e_t`.
//! 2. **Static equilibrium.** With all pulleys at rest, Newton–Raphson with a backtracking line
//!    search solves `Q_e(e) + Q_c(e) = 0` (elastic forces (2.20) and the normal contact forces
//!    (3.20); friction vanishes at rest). Frictionless contact leaves the belt free to slide
//!    around the pulleys, so the tangential position of node 0 is held by a penalty spring of
//!    the axial element stiffness `α₁EA/l`; its force at equilibrium is reported (it vanishes
//!    up to the discretisation's small preference for certain node positions).
//!
//! The dynamic run then starts from this state with zero velocities (the driver ramp (3.29)
//! starts at rest).

use super::model::BeltDrive;
use crate::error::AncfError;
use crate::sparse::Pattern;
use faer::Mat;
use faer::prelude::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use mbd_core::SecondOrderSystem;

/// Result of the initial-configuration solve.
#[derive(Debug, Clone)]
pub struct InitialState {
    /// Equilibrium coordinates of the whole system (pulley angles 0).
    pub q: Vec<f64>,
    /// Newton iterations.
    pub iterations: usize,
    /// Final residual norm \[N\].
    pub residual: f64,
    /// Force in the spring holding node 0 tangentially \[N\].
    pub holding_force: f64,
    /// Mean axial tension of the belt at equilibrium \[N\].
    pub mean_tension: f64,
}

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

impl BeltDrive {
    /// Step 1 of the module documentation: nodes on the path, uniformly stretched.
    pub fn placed_coordinates(&self) -> Vec<f64> {
        let path = self.path();
        let lp = path.length();
        let n = self.mesh().n_nodes();
        let lambda = lp / self.spec().belt.length;
        let mut q = vec![0.0; self.n_q()];
        for i in 0..n {
            let pt = path.point(i as f64 * lp / n as f64);
            let t = pt.tangent;
            let k = 6 * i;
            q[k] = pt.position[0];
            q[k + 1] = pt.position[1];
            q[k + 2] = lambda * t[0];
            q[k + 3] = lambda * t[1];
            q[k + 4] = -t[1];
            q[k + 5] = t[0];
        }
        q
    }

    /// Step 2 of the module documentation: static equilibrium from the placed coordinates.
    pub fn initial_state(&self, opts: &InitialOptions) -> Result<InitialState, AncfError> {
        let q0 = self.placed_coordinates();
        let nb = self.n_belt();
        let mesh = self.mesh();
        let n_el = mesh.elements().len();
        // belt pattern + a 2×2 group for the holding spring on node 0's position
        let mut groups: Vec<Vec<Option<usize>>> = (0..n_el)
            .map(|e| (0..12).map(|k| Some(mesh.global_dof(e, k))).collect())
            .collect();
        groups.push(vec![Some(0), Some(1)]);
        let pattern = Pattern::new(nb, &groups);
        let symbolic =
            SymbolicLu::try_new(pattern.symbolic().as_ref()).map_err(|e| AncfError::Singular {
                load_factor: 1.0,
                detail: format!("symbolic LU of the belt stiffness: {e:?}"),
            })?;
        let b = &self.spec().belt;
        let k_hold = b.alpha1 * b.young * b.width * b.thickness / self.element_length();
        let t0 = self.path().point(0.0).tangent;
        let x0 = [q0[0], q0[1]];
        let omegas = vec![0.0; self.pulleys().len()];
        let hold = [
            k_hold * t0[0] * t0[0],
            k_hold * t0[1] * t0[0],
            k_hold * t0[0] * t0[1],
            k_hold * t0[1] * t0[1],
        ];

        let mut q = q0.clone();
        let mut f = vec![0.0; self.n_q()];
        let mut torques = vec![0.0; self.pulleys().len()];
        let zero_v = vec![0.0; self.n_q()];
        // residual r = f − k_hold t (t·(x − x0)) over the belt coordinates
        let residual = |q: &[f64], f: &mut [f64], torques: &mut [f64]| -> f64 {
            self.belt_forces(q, &zero_v, &omegas, f, torques);
            let u = t0[0] * (q[0] - x0[0]) + t0[1] * (q[1] - x0[1]);
            f[0] -= k_hold * u * t0[0];
            f[1] -= k_hold * u * t0[1];
            f[..nb].iter().map(|x| x * x).sum::<f64>().sqrt()
        };
        let mut kv = pattern.zeros();
        let mut res = residual(&q, &mut f, &mut torques);
        let mut iterations = 0;
        let mut converged = false;
        while iterations < opts.max_iterations {
            iterations += 1;
            if !res.is_finite() {
                return Err(AncfError::NonFinite {
                    what: format!("initial belt equilibrium residual (iteration {iterations})"),
                });
            }
            self.belt_stiffness(&q, &omegas, &pattern, &mut f, &mut kv);
            pattern.add_element(&mut kv, n_el, &hold, 1.0);
            let u = t0[0] * (q[0] - x0[0]) + t0[1] * (q[1] - x0[1]);
            f[0] -= k_hold * u * t0[0];
            f[1] -= k_hold * u * t0[1];
            let rhs = Mat::<f64>::from_fn(nb, 1, |i, _| f[i]);
            let kmat = pattern.to_matrix(kv.clone());
            let lu = Lu::try_new_with_symbolic(symbolic.clone(), kmat.as_ref()).map_err(|e| {
                AncfError::Singular {
                    load_factor: 1.0,
                    detail: format!("belt tangent stiffness at iteration {iterations}: {e:?}"),
                }
            })?;
            let dx = lu.solve(&rhs);
            let mut alpha = 1.0;
            let mut trial = q.clone();
            let mut accepted = false;
            for _ in 0..20 {
                for i in 0..nb {
                    trial[i] = q[i] + alpha * dx[(i, 0)];
                }
                let r_new = residual(&trial, &mut f, &mut torques);
                if r_new.is_finite() && (r_new <= (1.0 - 1e-4 * alpha) * res || r_new < 1e-9) {
                    res = r_new;
                    accepted = true;
                    break;
                }
                alpha *= 0.5;
            }
            if !accepted {
                // take the full step: Newton may still converge from there
                for i in 0..nb {
                    trial[i] = q[i] + dx[(i, 0)];
                }
                res = residual(&trial, &mut f, &mut torques);
                alpha = 1.0;
            }
            let step = (0..nb)
                .map(|i| (alpha * dx[(i, 0)]).abs())
                .fold(0.0, f64::max);
            let qmax = q[..nb].iter().map(|v| v.abs()).fold(0.0, f64::max);
            q = trial;
            if !step.is_finite() {
                return Err(AncfError::NonFinite {
                    what: format!("initial belt equilibrium Newton step {iterations}"),
                });
            }
            if step <= opts.tolerance * (1.0 + qmax) {
                converged = true;
                break;
            }
        }
        if !converged {
            return Err(AncfError::NoConvergence {
                load_factor: 1.0,
                iterations,
                residual: res,
            });
        }
        let u = t0[0] * (q[0] - x0[0]) + t0[1] * (q[1] - x0[1]);
        let tension = super::post::tension_samples(self, &q, 3);
        let mean_tension =
            tension.iter().map(|s| s.tension).sum::<f64>() / tension.len().max(1) as f64;
        Ok(InitialState {
            q,
            iterations,
            residual: res,
            holding_force: k_hold * u,
            mean_tension,
        })
    }
}

impl BeltDrive {
    /// Velocities of a belt travelling rigidly along its current centreline at `speed` \[m/s\]
    /// (nodal `ṙ = V r_x/‖r_x‖`, slope rates zero) with every free pulley rolling with it
    /// (`θ̇ = V/R`): a start close to steady running, used by the benchmarks to skip the ramp.
    pub fn travelling_velocity(&self, q: &[f64], speed: f64) -> Vec<f64> {
        let mut v = vec![0.0; self.n_q()];
        for node in 0..self.mesh().n_nodes() {
            let k = 6 * node;
            let n = q[k + 2].hypot(q[k + 3]);
            if n > 0.0 {
                v[k] = speed * q[k + 2] / n;
                v[k + 1] = speed * q[k + 3] / n;
            }
        }
        for (p, pl) in self.pulleys().iter().enumerate() {
            if let Some(j) = self.pulley_dof(p) {
                v[j] = speed / pl.radius;
            }
        }
        v
    }
}
