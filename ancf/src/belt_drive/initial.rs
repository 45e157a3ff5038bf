//! The pre-strained initial configuration of the belt on the pulleys.
//!
//! The thesis does not describe it (seed note §11 item 19). Procedure used here:
//!
//! 1. **Placement.** Node `i` is put on the undeformed belt path (spans and wraps, computed
//!    from the pulley geometry by [`BeltPath`](belt::BeltPath)) at arc
//!    length `s_i = i L_p / n`, with `r_x = (L_p / L_b) e_t` (the uniform stretch that maps the
//!    unstretched belt length `L_b` onto the path length `L_p`) and `r_y = Ĩ e_t`.
//! 2. **Static equilibrium.** With all pulleys at rest, Newton–Raphson with a backtracking line
//!    search (the shared [`mbd_core::newton`] solver, in the resting problem that the plate
//!    belt shares, [`crate::mounted`]) solves `Q_e(e) + Q_c(e) = 0` (elastic forces (2.20) and
//!    the normal contact forces (3.20); friction vanishes at rest). Frictionless contact leaves the belt free to slide
//!    around the pulleys, so the tangential position of node 0 is held by a penalty spring of
//!    the axial element stiffness `α₁EA/l`; its force at equilibrium is reported (it vanishes
//!    up to the discretisation's small preference for certain node positions).
//!
//! The dynamic run then starts from this state with zero velocities (the driver ramp (3.29)
//! starts at rest).

use super::model::BeltDrive;
use crate::error::AncfError;
use crate::mounted::{Linearisation, RestingBelt, solve_resting};
use mbd_core::SecondOrderSystem;
use mbd_core::Workspace;

pub use crate::mounted::InitialOptions;

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
        &self, q0: Vec<f64>, opts: &InitialOptions,
    ) -> Result<InitialState, AncfError> {
        let r = solve_resting(self, "initial belt equilibrium", q0, opts)?;
        let tension = super::post::tension_samples(self, &r.q, 3);
        let mean_tension =
            tension.iter().map(|s| s.tension).sum::<f64>() / tension.len().max(1) as f64;
        Ok(InitialState {
            iterations: r.iterations,
            residual: r.residual,
            holding_force: r.holding_forces[0],
            mean_tension,
            q: r.q,
        })
    }
}

/// The planar belt at rest ([`crate::mounted::solve_resting`]): node 0 held along the path's
/// tangent at its start by a spring of the axial element stiffness `α₁EA/l`.
impl RestingBelt for BeltDrive {
    const LABEL: &'static str = "belt";

    fn holding(&self) -> (f64, Vec<Vec<f64>>) {
        let b = &self.spec().belt;
        let k_hold = b.alpha1 * b.young * b.width * b.thickness / self.element_length();
        (k_hold, vec![self.path().point(0.0).tangent.to_vec()])
    }

    fn resting_forces(&self, q: &[f64], f: &mut [f64], torques: &mut [f64], ws: &mut Workspace) {
        let omegas = vec![0.0; self.pulleys().len()];
        self.belt_forces(q, &vec![0.0; q.len()], &omegas, f, torques, ws);
    }

    fn resting_tangent(&self, q: &[f64], out: Linearisation<'_>, ws: &mut Workspace) {
        let omegas = vec![0.0; self.pulleys().len()];
        self.belt_stiffness(q, &omegas, out.pattern, out.f, out.kv, ws);
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
        self.roll_pulleys(speed, &mut v);
        v
    }
}
