//! The initial configuration of the plate belt on the pulleys (the thesis does not describe it,
//! seed note §11 item 19), by the procedure of the planar drive
//! ([`crate::belt_drive::initial`]):
//!
//! 1. **Placement.** Cross-section `i` is put on the undeformed path (spans and wraps of the
//!    belt mid-line over the pulleys in the plane `z = 0`) at arc length `s_i = i L_p / n`, the
//!    edge `y = 0` at `z = −w/2` and the edge `y = w` at `z = w/2`, with `r_x = (L_p/L_b) e_t`
//!    (the uniform stretch that maps the unstretched length `L_b` onto the path length `L_p`)
//!    and `r_y = e_z`.
//! 2. **Static equilibrium** with the pulleys at rest at `t = 0`: Newton–Raphson with a
//!    backtracking line search (the shared [`mbd_core::newton`] solver) on
//!    `Q_e(e) + Q_c(e) = 0` (elastic forces (2.20) and normal contact forces (3.20) over the
//!    plate, (4.45); friction vanishes at rest). Frictionless contact leaves the belt free to
//!    slide along the path and along the pulley axes, so the position of node 0 is held in
//!    these two directions by penalty springs of the axial element stiffness `E w h / a`; their
//!    force at equilibrium is reported.
//!
//! The dynamic run starts from this state with zero velocities.

use super::model::PlateBeltDrive;
use crate::error::AncfError;
use crate::sparse::Pattern;
use crate::statics::run_newton;
use faer::sparse::linalg::solvers::SymbolicLu;
use mbd_core::SecondOrderSystem;
use mbd_core::Workspace;
use mbd_core::newton::{Fallback, LineSearch, NewtonOptions, NewtonProblem, Tolerances};

/// Result of the initial-configuration solve.
#[derive(Debug, Clone)]
pub struct PlateInitialState {
    /// Equilibrium coordinates of the whole system (pulley angles 0).
    pub q: Vec<f64>,
    /// Newton iterations.
    pub iterations: usize,
    /// Final residual norm \[N\].
    pub residual: f64,
    /// Forces in the springs holding node 0 along the path and along `z` \[N\].
    pub holding_force: [f64; 2],
}

impl PlateBeltDrive {
    /// Step 1 of the module documentation: nodes on the path, uniformly stretched.
    pub fn placed_coordinates(&self) -> Vec<f64> {
        let path = self.path();
        let lp = path.length();
        let n = self.n_elements();
        let w = self.spec().belt.width;
        let lambda = lp / self.spec().belt.length;
        let mut q = vec![0.0; self.n_q()];
        for i in 0..n {
            let pt = path.point(i as f64 * lp / n as f64);
            let t = pt.tangent;
            for j in 0..2 {
                let k = 9 * (2 * i + j);
                q[k] = pt.position[0];
                q[k + 1] = pt.position[1];
                q[k + 2] = (j as f64 - 0.5) * w;
                q[k + 3] = lambda * t[0];
                q[k + 4] = lambda * t[1];
                q[k + 8] = 1.0;
            }
        }
        q
    }

    /// Step 2 of the module documentation: static equilibrium from the placed coordinates.
    pub fn initial_state(
        &self,
        max_iterations: usize,
        tolerance: f64,
    ) -> Result<PlateInitialState, AncfError> {
        let q0 = self.placed_coordinates();
        let nb = self.n_belt();
        let mut groups: Vec<Vec<Option<usize>>> = self
            .mesh()
            .cells
            .iter()
            .map(|c| self.mesh().cell_dofs(c).iter().map(|&d| Some(d)).collect())
            .collect();
        groups.push(vec![Some(0), Some(1), Some(2)]);
        // same element groups as the system pattern: the belt block of the drive's pattern
        let pattern = Pattern::new(nb, &groups);
        let symbolic =
            SymbolicLu::try_new(pattern.symbolic().as_ref()).map_err(|e| AncfError::Singular {
                load_factor: 1.0,
                detail: format!("symbolic LU of the plate belt stiffness: {e:?}"),
            })?;
        let b = &self.spec().belt;
        let k_hold = b.young * b.width * b.thickness / self.element_length();
        let t0 = self.path().point(0.0).tangent;
        let dirs = [[t0[0], t0[1], 0.0], [0.0, 0.0, 1.0]];
        let mut hold = [0.0; 9];
        for d in &dirs {
            for i in 0..3 {
                for j in 0..3 {
                    hold[i + 3 * j] += k_hold * d[i] * d[j];
                }
            }
        }
        let mut problem = Initial {
            drive: self,
            full: self.pattern().zeros(),
            kv: pattern.zeros(),
            pattern,
            symbolic,
            hold,
            k_hold,
            dirs,
            x0: [q0[0], q0[1], q0[2]],
            omegas: vec![0.0; self.pulleys().len()],
            f: vec![0.0; self.n_q()],
            torques: vec![0.0; self.pulleys().len()],
            zero_v: vec![0.0; self.n_q()],
            iteration: 0,
            ws: Workspace::new(),
        };
        let newton = NewtonOptions {
            max_iterations,
            tolerances: Tolerances::relative(tolerance),
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
        let report = run_newton(
            "initial plate-belt equilibrium",
            &mut problem,
            &mut q,
            &newton,
        )?;
        let mut r = vec![0.0; self.n_q()];
        problem.residual(&q, 1.0, &mut r)?;
        let u = problem.offsets(&q);
        Ok(PlateInitialState {
            iterations: report.iterations(),
            residual: problem.residual_norm(&r),
            holding_force: [k_hold * u[0], k_hold * u[1]],
            q,
        })
    }
}

/// The belt on resting pulleys with node 0 held along the path and `z`:
/// `R = −(Q_e + Q_c − k_hold Σ_d d (d·(x₀ − x₀⁰)))` on the belt rows.
struct Initial<'a> {
    drive: &'a PlateBeltDrive,
    /// Value array in the drive's pattern (tangent of the belt).
    full: Vec<f64>,
    pattern: Pattern,
    symbolic: SymbolicLu<usize>,
    kv: Vec<f64>,
    hold: [f64; 9],
    k_hold: f64,
    dirs: [[f64; 3]; 2],
    x0: [f64; 3],
    omegas: Vec<f64>,
    f: Vec<f64>,
    torques: Vec<f64>,
    zero_v: Vec<f64>,
    /// The drive's scratch ([`mbd_core::Workspace`]).
    ws: Workspace,
    iteration: usize,
}

impl Initial<'_> {
    fn offsets(&self, q: &[f64]) -> [f64; 2] {
        let d = [q[0] - self.x0[0], q[1] - self.x0[1], q[2] - self.x0[2]];
        self.dirs
            .map(|dir| dir[0] * d[0] + dir[1] * d[1] + dir[2] * d[2])
    }

    /// Subtract the holding spring forces from `self.f` and write `r = −f` on the belt rows.
    fn hold_and_scatter(&mut self, q: &[f64], r: &mut [f64]) {
        let u = self.offsets(q);
        for (k, dir) in self.dirs.iter().enumerate() {
            for i in 0..3 {
                self.f[i] -= self.k_hold * u[k] * dir[i];
            }
        }
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
            0.0,
            q,
            &self.zero_v,
            &self.omegas,
            &mut self.f,
            &mut self.full,
            &mut self.ws,
        );
        // the belt block of the drive's pattern → this pattern
        self.kv.fill(0.0);
        let nb = self.drive.n_belt();
        for (i, j, pos) in self.drive.pattern().entries() {
            if i < nb && j < nb {
                let v = self.full[pos];
                if v != 0.0
                    && let Some(p) = self.pattern.position(i, j)
                {
                    self.kv[p] += v;
                }
            }
        }
        let n_el = self.drive.n_elements();
        self.pattern
            .add_element(&mut self.kv, n_el, &self.hold, 1.0);
        self.hold_and_scatter(q, r);
        Ok(())
    }

    fn residual(&mut self, q: &[f64], _load: f64, r: &mut [f64]) -> Result<(), AncfError> {
        self.drive.belt_forces(
            0.0,
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
                    "plate belt tangent stiffness at iteration {}: {e}",
                    self.iteration
                ),
            })
    }
}

impl PlateBeltDrive {
    /// Velocities of a belt travelling rigidly along its current mid-surface at `speed`
    /// \[m/s\] (nodal `ṙ = V r_x/‖r_x‖`, gradient rates zero) with every free pulley rolling with
    /// it (`θ̇ = V/R`): a start close to steady running, used by the benchmarks to skip the ramp.
    pub fn travelling_velocity(&self, q: &[f64], speed: f64) -> Vec<f64> {
        let mut v = vec![0.0; self.n_q()];
        for node in 0..self.mesh().n_nodes {
            let k = 9 * node;
            let n = (q[k + 3] * q[k + 3] + q[k + 4] * q[k + 4] + q[k + 5] * q[k + 5]).sqrt();
            if n > 0.0 {
                for c in 0..3 {
                    v[k + c] = speed * q[k + 3 + c] / n;
                }
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
