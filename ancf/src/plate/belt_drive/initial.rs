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
use crate::mounted::{InitialOptions, Linearisation, RestingBelt, solve_resting};
use mbd_core::SecondOrderSystem;
use mbd_core::Workspace;

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

    /// Step 2 of the module documentation: static equilibrium from the placed coordinates
    /// (the planar drive's problem, [`crate::mounted`]).
    pub fn initial_state(&self, opts: &InitialOptions) -> Result<PlateInitialState, AncfError> {
        let r = solve_resting(
            self,
            "initial plate-belt equilibrium",
            self.placed_coordinates(),
            opts,
        )?;
        Ok(PlateInitialState {
            iterations: r.iterations,
            residual: r.residual,
            holding_force: [r.holding_forces[0], r.holding_forces[1]],
            q: r.q,
        })
    }
}

/// The plate belt at rest ([`crate::mounted::solve_resting`]): node 0 held along the path's
/// tangent at its start and along the pulley axes `z` by springs of the axial element
/// stiffness `E w h / a`.
impl RestingBelt for PlateBeltDrive {
    const LABEL: &'static str = "plate belt";

    fn holding(&self) -> (f64, Vec<Vec<f64>>) {
        let b = &self.spec().belt;
        let k_hold = b.young * b.width * b.thickness / self.element_length();
        let t0 = self.path().point(0.0).tangent;
        (k_hold, vec![vec![t0[0], t0[1], 0.0], vec![0.0, 0.0, 1.0]])
    }

    fn resting_forces(&self, q: &[f64], f: &mut [f64], torques: &mut [f64], ws: &mut Workspace) {
        let omegas = vec![0.0; self.pulleys().len()];
        self.belt_forces(0.0, q, &vec![0.0; q.len()], &omegas, f, torques, ws);
    }

    fn resting_tangent(&self, q: &[f64], out: Linearisation<'_>, ws: &mut Workspace) {
        let omegas = vec![0.0; self.pulleys().len()];
        let zero_v = vec![0.0; q.len()];
        let Linearisation { pattern, f, kv } = out;
        self.belt_stiffness(0.0, q, &zero_v, &omegas, pattern, f, kv, ws);
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
        self.roll_pulleys(speed, &mut v);
        v
    }
}
