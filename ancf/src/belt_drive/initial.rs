//! The pre-strained initial configuration of the belt on the pulleys.
//!
//! The thesis does not describe it (seed note §11 item 19). Procedure used here:
//!
//! 1. **Placement.** Node `i` is put on the undeformed belt path (spans and wraps, computed
//!    from the pulley geometry by [`BeltPath`](belt::BeltPath)) at arc
//!    length `s_i = i L_p / n`, with `r_x = (L_p / L_b) e_t` (the uniform stretch that maps the
//!    unstretched belt length `L_b` onto the path length `L_p`) and `r_y = Ĩ e_t`.
//! 2. **Static equilibrium.** With all pulleys at rest, Newton–Raphson with a backtracking line
//!    search (the shared [`mbd_core::newton`] solver) solves `Q_e(e) + Q_c(e) = 0` (elastic forces (2.20) and the normal contact forces
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
use crate::statics::run_newton;
use faer::sparse::linalg::solvers::SymbolicLu;
use mbd_core::SecondOrderSystem;
use mbd_core::Workspace;
use mbd_core::newton::{Fallback, LineSearch, NewtonOptions, NewtonProblem, Tolerances};

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
        if let Some(a) = self.arm() {
            q[a.dof] = a.installed_angle;
        }
        q
    }

    /// Step 2 of the module documentation: static equilibrium from the placed coordinates.
    pub fn initial_state(&self, opts: &InitialOptions) -> Result<InitialState, AncfError> {
        self.initial_state_from(self.placed_coordinates(), opts)
    }

    /// [`Self::initial_state`] from the start `q0` (e.g. a previous equilibrium); the
    /// coordinates beyond the belt's (pulley angles, a tensioner arm's angle, which places
    /// its idler) are held at their values in `q0`.
    pub fn initial_state_from(
        &self,
        q0: Vec<f64>,
        opts: &InitialOptions,
    ) -> Result<InitialState, AncfError> {
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

        let mut problem = Initial {
            drive: self,
            kv: pattern.zeros(),
            pattern,
            symbolic,
            hold,
            k_hold,
            t0,
            x0,
            omegas,
            f: vec![0.0; self.n_q()],
            torques: vec![0.0; self.pulleys().len()],
            zero_v: vec![0.0; self.n_q()],
            iteration: 0,
            ws: Workspace::new(),
        };
        let newton = NewtonOptions {
            max_iterations: opts.max_iterations,
            tolerances: Tolerances::relative(opts.tolerance),
            line_search: Some(LineSearch {
                armijo: 1e-4,
                slack: 0.0,
                accept_below: 1e-9,
                max_trials: 20,
                fallback: Fallback::FullStep,
            }),
            ..Default::default()
        };
        let mut q = q0;
        let report = run_newton("initial belt equilibrium", &mut problem, &mut q, &newton)?;
        let mut r = vec![0.0; self.n_q()];
        problem.residual(&q, 1.0, &mut r)?;
        let (res, iterations) = (problem.residual_norm(&r), report.iterations());
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

/// The belt on resting pulleys with node 0 held tangentially: `x = q` (belt and pulley
/// coordinates; the pulleys are never corrected), `R = −(Q_e + Q_c − k_hold t (t·(x − x0)))`.
struct Initial<'a> {
    drive: &'a BeltDrive,
    pattern: Pattern,
    symbolic: SymbolicLu<usize>,
    kv: Vec<f64>,
    hold: [f64; 4],
    k_hold: f64,
    t0: [f64; 2],
    x0: [f64; 2],
    omegas: Vec<f64>,
    f: Vec<f64>,
    torques: Vec<f64>,
    zero_v: Vec<f64>,
    /// The drive's scratch ([`mbd_core::Workspace`]).
    ws: Workspace,
    /// Linearisations so far (named in errors).
    iteration: usize,
}

impl Initial<'_> {
    /// Subtract the holding spring force from `self.f` and write `r = −f` on the belt rows.
    fn hold_and_scatter(&mut self, q: &[f64], r: &mut [f64]) {
        let (t0, x0) = (self.t0, self.x0);
        let u = t0[0] * (q[0] - x0[0]) + t0[1] * (q[1] - x0[1]);
        self.f[0] -= self.k_hold * u * t0[0];
        self.f[1] -= self.k_hold * u * t0[1];
        let nb = self.drive.n_belt();
        r.fill(0.0);
        for i in 0..nb {
            r[i] = -self.f[i];
        }
    }
}

impl NewtonProblem for Initial<'_> {
    type Error = AncfError;

    fn tangent_dim(&self) -> usize {
        self.f.len()
    }

    fn linearize(&mut self, q: &[f64], _load: f64, r: &mut [f64]) -> Result<(), AncfError> {
        self.iteration += 1;
        self.drive.belt_stiffness(
            q,
            &self.omegas,
            &self.pattern,
            &mut self.f,
            &mut self.kv,
            &mut self.ws,
        );
        let n_el = self.drive.mesh().elements().len();
        self.pattern
            .add_element(&mut self.kv, n_el, &self.hold, 1.0);
        self.hold_and_scatter(q, r);
        Ok(())
    }

    fn residual(&mut self, q: &[f64], _load: f64, r: &mut [f64]) -> Result<(), AncfError> {
        self.drive.belt_forces(
            q,
            &self.zero_v,
            &self.omegas,
            &mut self.f,
            &mut self.torques,
            &mut self.ws,
        );
        self.hold_and_scatter(q, r);
        Ok(())
    }

    fn solve(&mut self, r: &[f64], dx: &mut [f64]) -> Result<(), AncfError> {
        self.pattern
            .lu_correction(&self.symbolic, &self.kv, r, dx)
            .map_err(|e| AncfError::Singular {
                load_factor: 1.0,
                detail: format!(
                    "belt tangent stiffness at iteration {}: {e}",
                    self.iteration
                ),
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
