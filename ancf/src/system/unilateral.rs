//! Dynamics with frictionless unilateral node contact by Lagrange multipliers: the
//! generalized-α index-3 integrator of mbd-core on an [`AncfSystem`] whose constraint set is
//! extended by `g_i(q) = 0` for the active contact nodes (Ribaric §7.3 / seed-000 note U4;
//! Jacobian row `nᵀ`, `γ = −wᵀ(∂n/∂r)w` from the contact crate's [`unilateral_row`]).
//!
//! The active-set stepping is mbd-core's [`ActiveSetStepper`] (a free node that ends a step
//! inside the obstacle retakes the step with the deepest such node active; a node whose
//! contact force turns tensile is released); this module only supplies the contact rows of the
//! nodes ([`NodeContacts`]).

use super::AncfSystem;
use crate::element::AncfElement;
use crate::error::{AncfError, invalid};
use crate::mesh::AncfMesh;
use contact::{Surface, unilateral_row};
use mbd_core::MbdError;
use mbd_core::integrators::{
    ActiveSetStepper, AlphaConfig, State, UnilateralConstraints, UnilateralEval,
};
use nalgebra::{Point2, Vector2};

/// The frictionless unilateral contact of mesh nodes against a rigid obstacle, as candidates of
/// mbd-core's active set: gap `g = ` signed distance of the node position `r`, Jacobian row
/// `nᵀ` on the node's position coordinates, `ν = nᵀu_s`, `γ = −wᵀ(∂n/∂r)w` (`w = ṙ − u_s`) and
/// curvature `∂n/∂r` (the contact crate's closest-point data).
pub struct NodeContacts<'a, E: AncfElement, S: Surface<2> + ?Sized> {
    mesh: &'a AncfMesh<E>,
    surface: &'a S,
    nodes: &'a [usize],
}

impl<'a, E: AncfElement, S: Surface<2> + ?Sized> NodeContacts<'a, E, S> {
    /// The contact of `nodes` of `mesh` against `surface`.
    pub fn new(mesh: &'a AncfMesh<E>, surface: &'a S, nodes: &'a [usize]) -> Self {
        Self {
            mesh,
            surface,
            nodes,
        }
    }

    fn node_r(&self, q: &[f64], node: usize) -> Point2<f64> {
        Point2::from(self.mesh.node_position(q, node))
    }
}

impl<E: AncfElement, S: Surface<2> + ?Sized> UnilateralConstraints for NodeContacts<'_, E, S> {
    fn n_candidates(&self) -> usize {
        self.nodes.len()
    }
    fn candidate_name(&self, c: usize) -> String {
        format!("contact of node {}", self.nodes[c])
    }
    fn gap(&self, _t: f64, q: &[f64], c: usize) -> f64 {
        self.surface.closest(&self.node_r(q, self.nodes[c])).gap
    }
    fn row(&self, _t: f64, q: &[f64], v: &[f64], c: usize, row: &mut UnilateralEval) {
        let nd = self.nodes[c];
        let p = self.node_r(q, nd);
        let sp = self.surface.closest(&p);
        let k = self.mesh.node_dof(nd, 0);
        let (n, u) = (sp.normal, sp.surface_velocity);
        row.gap = sp.gap;
        row.jacobian.extend([(k, n[0]), (k + 1, n[1])]);
        row.nu = n[0] * u[0] + n[1] * u[1];
        row.gamma = unilateral_row(self.surface, &p, &Vector2::new(v[k], v[k + 1])).gamma;
        for a in 0..2 {
            for b in 0..2 {
                row.curvature.push((k + a, k + b, sp.dn_dp[(a, b)]));
            }
        }
    }
}

/// One recorded step of [`integrate_unilateral`].
#[derive(Debug, Clone)]
pub struct ContactStep {
    /// State after the step.
    pub state: State,
    /// Active contact nodes after the step.
    pub active: Vec<usize>,
    /// Compressive contact force of each active node \[N\] (same order as `active`).
    pub forces: Vec<f64>,
}

/// Integrate `system` from `state0` to `t_end` \[s\] with generalized-α (`params`) and the
/// frictionless unilateral contact of `nodes` against `surface` (mbd-core's
/// [`ActiveSetStepper`] with [`NodeContacts`]); `observer` sees every accepted step. The nodes
/// must start outside the obstacle.
pub fn integrate_unilateral<E: AncfElement, S: Surface<2> + ?Sized>(
    system: &AncfSystem<E>, surface: &S, nodes: &[usize], state0: State, params: AlphaConfig,
    t_end: f64, observer: &mut dyn FnMut(&ContactStep),
) -> Result<(), AncfError> {
    let mesh = &system.mesh;
    for &nd in nodes {
        if nd >= mesh.n_nodes() {
            return Err(invalid(
                "unilateral dynamics: contact nodes",
                format!("node {nd} out of range 0..{}", mesh.n_nodes()),
            ));
        }
        let g = surface
            .closest(&Point2::from(mesh.node_position(&state0.q, nd)))
            .gap;
        if g < 0.0 {
            return Err(invalid(
                format!("unilateral dynamics: contact node {nd}"),
                format!(
                    "starts inside the obstacle (gap {g:e} m at t = {} s)",
                    state0.t
                ),
            ));
        }
    }
    let contacts = NodeContacts::new(mesh, surface, nodes);
    let mut stepper = ActiveSetStepper::new(system, &contacts, state0, params)?;
    stepper
        .advance_to(t_end, &mut |s| {
            observer(&ContactStep {
                state: s.state.clone(),
                active: s.active.iter().map(|&c| nodes[c]).collect(),
                forces: s.forces.to_vec(),
            })
        })
        .map_err(|e| match e {
            MbdError::ActiveSet { t, retakes } => AncfError::ActiveSet {
                load_factor: t,
                passes: retakes,
            },
            e => e.into(),
        })
}
