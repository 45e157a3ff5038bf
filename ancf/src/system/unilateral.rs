//! Dynamics with frictionless unilateral node contact by Lagrange multipliers: the
//! generalized-α index-3 integrator of mbd-core on an [`AncfSystem`] whose constraint set is
//! extended by `g_i(q) = 0` for the active contact nodes (Ribaric §7.3 / seed-000 note U4;
//! Jacobian row `nᵀ`, `γ = −wᵀ(∂n/∂r)w` from the contact crate's [`unilateral_row`]).
//!
//! Active-set rule per step: if a free node ends a step inside the obstacle, the step is
//! retaken from its start with the deepest such node active (a perfectly plastic impact: the
//! position constraint closes the gap within that step); an active node whose contact force
//! becomes tensile (`λ_i < 0`) is released after the step. Each change restarts the stepper
//! (index-1 accelerations and multipliers recomputed at the current state).

use super::AncfSystem;
use crate::element::Element;
use crate::error::{AncfError, invalid};
use contact::{Surface, unilateral_row};
use faer::sparse::{SparseColMat, Triplet};
use mbd_core::integrators::{AlphaConfig, AlphaStepper, State};
use mbd_core::system::ForceTangent;
use mbd_core::{MbdError, SecondOrderSystem, SysMatrix};
use nalgebra::{Point2, Vector2};

/// An [`AncfSystem`] with the contact rows of the active nodes appended to its constraints.
struct WithContacts<'a, E: Element, S: Surface<2> + ?Sized> {
    base: &'a AncfSystem<E>,
    surface: &'a S,
    /// Active contact nodes (mesh node indices).
    active: Vec<usize>,
}

impl<E: Element, S: Surface<2> + ?Sized> WithContacts<'_, E, S> {
    fn node_r(&self, q: &[f64], node: usize) -> Point2<f64> {
        Point2::from(self.base.mesh.node_position(q, node))
    }
}

impl<E: Element, S: Surface<2> + ?Sized> SecondOrderSystem for WithContacts<'_, E, S> {
    fn n_q(&self) -> usize {
        self.base.n_q()
    }
    fn n_c(&self) -> usize {
        self.base.n_c() + self.active.len()
    }
    fn constraint_name(&self, row: usize) -> String {
        let nb = self.base.n_c();
        if row < nb {
            self.base.constraint_name(row)
        } else {
            format!("contact of node {}", self.active[row - nb])
        }
    }
    fn dof_name(&self, dof: usize) -> String {
        self.base.dof_name(dof)
    }
    fn mass_is_constant(&self) -> bool {
        true
    }
    fn mass(&self, t: f64, q: &[f64]) -> Result<SysMatrix, MbdError> {
        self.base.mass(t, q)
    }
    fn forces(&self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]) -> Result<(), MbdError> {
        self.base.forces(t, q, v, f)
    }
    fn force_tangent(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
    ) -> Result<Option<ForceTangent>, MbdError> {
        self.base.force_tangent(t, q, v)
    }
    fn constraint_force_tangent(
        &self,
        _t: f64,
        q: &[f64],
        lambda: &[f64],
    ) -> Result<Option<SysMatrix>, MbdError> {
        // ∂(Dᵀλ)/∂q: the prescribed rows are linear; a contact row contributes λ ∂n/∂r
        let nb = self.base.n_c();
        let mut trip = Vec::new();
        for (i, &nd) in self.active.iter().enumerate() {
            let sp = self.surface.closest(&self.node_r(q, nd));
            let k = self.base.mesh.node_dof(nd, 0);
            for a in 0..2 {
                for b in 0..2 {
                    trip.push(Triplet::new(
                        k + a,
                        k + b,
                        lambda[nb + i] * sp.dn_dp[(a, b)],
                    ));
                }
            }
        }
        let n = self.n_q();
        let m = SparseColMat::try_new_from_triplets(n, n, &trip).map_err(|e| {
            MbdError::InvalidInput {
                item: "contact constraint tangent".into(),
                reason: format!("{e:?}"),
            }
        })?;
        Ok(Some(SysMatrix::Sparse(m)))
    }
    fn constraint_residual(&self, t: f64, q: &[f64], phi: &mut [f64]) -> Result<(), MbdError> {
        let nb = self.base.n_c();
        self.base.constraint_residual(t, q, &mut phi[..nb])?;
        for (i, &nd) in self.active.iter().enumerate() {
            phi[nb + i] = self.surface.closest(&self.node_r(q, nd)).gap;
        }
        Ok(())
    }
    fn constraint_jacobian(&self, _t: f64, q: &[f64]) -> Result<SysMatrix, MbdError> {
        let nb = self.base.n_c();
        let mut trip: Vec<_> = self
            .base
            .prescribed
            .iter()
            .enumerate()
            .map(|(i, p)| Triplet::new(i, p.dof, 1.0))
            .collect();
        for (i, &nd) in self.active.iter().enumerate() {
            let n = self.surface.closest(&self.node_r(q, nd)).normal;
            let k = self.base.mesh.node_dof(nd, 0);
            trip.push(Triplet::new(nb + i, k, n[0]));
            trip.push(Triplet::new(nb + i, k + 1, n[1]));
        }
        let m =
            SparseColMat::try_new_from_triplets(self.n_c(), self.n_q(), &trip).map_err(|e| {
                MbdError::InvalidInput {
                    item: "contact constraint Jacobian".into(),
                    reason: format!("{e:?}"),
                }
            })?;
        Ok(SysMatrix::Sparse(m))
    }
    fn constraint_velocity_rhs(&self, t: f64, q: &[f64], nu: &mut [f64]) -> Result<(), MbdError> {
        let nb = self.base.n_c();
        self.base.constraint_velocity_rhs(t, q, &mut nu[..nb])?;
        for (i, &nd) in self.active.iter().enumerate() {
            let sp = self.surface.closest(&self.node_r(q, nd));
            let (n, u) = (sp.normal, sp.surface_velocity);
            nu[nb + i] = n[0] * u[0] + n[1] * u[1];
        }
        Ok(())
    }
    fn constraint_gamma(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        gamma: &mut [f64],
    ) -> Result<(), MbdError> {
        let nb = self.base.n_c();
        self.base.constraint_gamma(t, q, v, &mut gamma[..nb])?;
        for (i, &nd) in self.active.iter().enumerate() {
            let k = self.base.mesh.node_dof(nd, 0);
            let row = unilateral_row(
                self.surface,
                &self.node_r(q, nd),
                &Vector2::new(v[k], v[k + 1]),
            );
            gamma[nb + i] = row.gamma;
        }
        Ok(())
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
/// frictionless unilateral contact of `nodes` against `surface`; `observer` sees every
/// accepted step. The nodes must start outside the obstacle.
pub fn integrate_unilateral<E: Element, S: Surface<2> + ?Sized>(
    system: &AncfSystem<E>,
    surface: &S,
    nodes: &[usize],
    state0: State,
    params: AlphaConfig,
    t_end: f64,
    observer: &mut dyn FnMut(&ContactStep),
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
    let h = params.h;
    let mut sys = WithContacts {
        base: system,
        surface,
        active: Vec::new(),
    };
    let mut stepper = AlphaStepper::new(&sys, state0, params)?;
    let nb = system.n_c();
    let mut retakes = 0usize;
    while stepper.state().t < t_end - 1e-9 * h {
        let start = stepper.state().clone();
        let hs = h.min(t_end - start.t);
        stepper.step(&sys, hs)?;
        // a free node inside the obstacle: retake the step with the deepest one active
        let deepest = nodes
            .iter()
            .filter(|nd| !sys.active.contains(nd))
            .map(|&nd| {
                (
                    nd,
                    surface
                        .closest(&Point2::from(mesh.node_position(&stepper.state().q, nd)))
                        .gap,
                )
            })
            .filter(|(_, g)| *g < 0.0)
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((nd, _)) = deepest {
            retakes += 1;
            if retakes > nodes.len() + 1 {
                return Err(AncfError::ActiveSet {
                    load_factor: start.t,
                    passes: retakes,
                });
            }
            sys.active.push(nd);
            stepper = AlphaStepper::new(&sys, start, params)?;
            continue;
        }
        retakes = 0;
        // release tensile contacts (integrator reaction −Dᵀλ ⇒ compressive force −λ)
        let lam = stepper.lambda();
        let forces: Vec<f64> = (0..sys.active.len()).map(|i| -lam[nb + i]).collect();
        let step = ContactStep {
            state: stepper.state().clone(),
            active: sys.active.clone(),
            forces: forces.clone(),
        };
        observer(&step);
        if forces.iter().any(|f| *f < 0.0) {
            let keep: Vec<usize> = sys
                .active
                .iter()
                .zip(&forces)
                .filter(|(_, f)| **f >= 0.0)
                .map(|(nd, _)| *nd)
                .collect();
            sys.active = keep;
            let s = stepper.state().clone();
            stepper = AlphaStepper::new(&sys, s, params)?;
        }
    }
    Ok(())
}
