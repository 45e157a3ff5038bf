//! The flowing-material and nodal belts as [`BeltModel`]s: their snapshots for the one
//! report ([`belt::report`]) — contact nodes as wrap points, the whole axial force each element
//! carries (elastic `T0 + EA Δl/l` or the co-rotated material law, plus the viscous force of the
//! `β K_e` damping, [`super::model::chord_viscous_forces`]) as span and wrap forces, pulley
//! torques and hub loads summed from the node contacts, and the power of the belt's damping
//! forces ([`FlowingBelt::damping_dissipation`], [`NodalBelt::damping_dissipation`]).

use super::contact::NodeContact;
use super::coordinates::DriveCoordinates;
use super::flowing_system::FlowingBelt;
use super::model::BeltFe;
use super::nodal::NodalBelt;
use belt::report::{span_momentum_fluxes, span_offsets, span_states};
use belt::{BeltModel, Drive, ModelTraits, Motion, PulleyState, Snapshot, WrapPoint};
use mbd_core::MbdError;
use mbd_core::integrators::State;

/// What the linearised models report as the belt's force.
pub const LINEAR_FORCE_MEASURE: &str = "the whole axial force each element carries, elastic \
plus viscous: the elastic part with axial_force = \"co_rotated\" (the nodal model's default) the \
belt's material law (drive.belt.law, stretch from the unstretched belt, mounted at T0) at the \
element's chord length, along the chord, with \"linear\" (the flowing model's default) T0 + EA \
Δl/l linearised about the mounted tension T0 (Ribaric (5.5)); the viscous part beta EA De/Dt of \
the stiffness-proportional damping on the element's co-rotated material stretch rate (in a \
steady drive beta v dT/ds: nonzero over the wraps and a layer of length beta v beyond them); \
spans: mean over each span's middle half";

/// Deformed node positions: `reference` plus the translations of `d` (3 DOFs per node).
fn deformed(reference: &[[f64; 2]], d: &[f64]) -> Vec<[f64; 2]> {
    reference
        .iter()
        .enumerate()
        .map(|(i, r)| [r[0] + d[3 * i], r[1] + d[3 * i + 1]])
        .collect()
}

/// The snapshot of a belt of frame elements with nodal contacts at `(t, q, v)`: pulley speeds
/// \[rad/s\] and the tensioner idler's centre from the drive's rigid coordinates `coords`, hub
/// loads and torques summed from the contacts, span forces from the element forces (acting
/// along the nodes' line over each span's middle half), wrap points at the contact nodes.
fn snapshot_with(
    fe: &BeltFe, coords: &DriveCoordinates, (t, q, v): (f64, &[f64], &[f64]), nodes: &[[f64; 2]],
    (forces, flux): (&[f64], &[[f64; 2]]),
    contacts: impl Iterator<Item = (usize, usize, NodeContact)>,
) -> Snapshot {
    let path = fe.path();
    let omega = (0..coords.motions.len()).map(|k| coords.pulley_speed(k, t, v));
    let idler = coords.idler_motion(q, v);
    let nn = nodes.len();
    let mut pulleys: Vec<PulleyState> = omega
        .zip(fe.drive.pulleys())
        .map(|(omega, p)| PulleyState {
            omega,
            hub_load: [0.0; 2],
            torque: 0.0,
            center_velocity: [0.0; 2],
            center: p.center,
        })
        .collect();
    if let Some((k, center, vel)) = idler {
        pulleys[k].center = center;
        pulleys[k].center_velocity = vel;
    }
    let mut wrap = Vec::new();
    for (i, p, c) in contacts {
        let pl = &mut pulleys[p];
        pl.hub_load[0] -= c.force[0];
        pl.hub_load[1] -= c.force[1];
        pl.torque += c.torque;
        if c.normal <= 0.0 {
            continue;
        }
        let l = fe.tributary[i];
        wrap.push(WrapPoint {
            pulley: p,
            angle: path.angle_from_inlet(p, nodes[i]).unwrap_or(f64::NAN),
            length: l,
            tension: 0.5 * (forces[i] + forces[(i + nn - 1) % nn]),
            pressure: c.normal / l,
            friction: c.friction / l,
            slip: c.slip,
        });
    }
    wrap.sort_by(|a, b| {
        (a.pulley, a.angle)
            .partial_cmp(&(b.pulley, b.angle))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let mut spans = span_states(path, nodes, forces);
    for (sp, f) in spans
        .iter_mut()
        .zip(span_momentum_fluxes(path, nodes, flux))
    {
        sp.momentum_flux = f;
    }
    Snapshot {
        time: t,
        pulleys,
        spans,
        wrap,
        belt_dissipation: None,
    }
}

/// The [`BeltModel`] methods the flowing and nodal belts share: the same fields (`fe`,
/// `coords`: [`super::DriveCoordinates`]) and the belt travel `s_b` as the first
/// coordinate (`ṡ_b` is the belt speed). A macro because `BeltModel` is the belt crate's trait:
/// a blanket implementation over a trait of this crate is not allowed (orphan rule).
macro_rules! shared_belt_model_methods {
    ($name:literal) => {
        fn drive(&self) -> &Drive {
            &self.fe.drive
        }

        fn traits(&self) -> ModelTraits {
            ModelTraits {
                name: $name,
                linearised: true,
                force_measure: LINEAR_FORCE_MEASURE,
                near_coulomb_creep: self.contact_rates_follow_the_strain(),
                balance_defect: self.balance_defect(),
            }
        }

        fn initial_state(&self) -> Result<State, MbdError> {
            let q = self.static_state()?;
            let n = q.len();
            Ok(State::new(0.0, q, vec![0.0; n]))
        }

        fn motion(&self, k: usize) -> Option<&Motion> {
            self.coords.motions.get(k)
        }

        fn motion_mut(&mut self, k: usize) -> Option<&mut Motion> {
            self.coords.motions.get_mut(k)
        }

        fn pulley_speed(&self, k: usize, t: f64, v: &[f64]) -> f64 {
            self.coords.pulley_speed(k, t, v)
        }

        fn arm_angle(&self, q: &[f64]) -> Option<f64> {
            self.coords.arm_angle(q)
        }

        fn decoupler_state(&self, k: usize, q: &[f64], v: &[f64]) -> Option<belt::DecouplerState> {
            self.coords.decoupler_state(k, q, v)
        }

        /// `ṡ_b`, the speed of the material along the path.
        fn belt_speed(&self, _q: &[f64], v: &[f64]) -> f64 {
            v[0]
        }
    };
}

/// Coordinates `(s_b, z, φ_k…, Δθ)`: belt travel, the reduced coordinates, the free pulleys
/// and the tensioner arm.
impl BeltModel for FlowingBelt {
    shared_belt_model_methods!("flowing");

    /// Contact nodes of the stationary mesh, the elements' whole axial forces
    /// ([`FlowingBelt::element_forces`]).
    fn snapshot(&self, t: f64, q: &[f64], v: &[f64]) -> Result<Snapshot, MbdError> {
        let z = &q[1..=self.n_modes()];
        let nodes = deformed(&self.fe.position, &self.deflection(z));
        let forces = self.element_forces(q, v);
        let contacts = self
            .contact_report(t, q, v)
            .into_iter()
            .map(|r| (r.node, r.pulley, r.contact));
        let flux = self.momentum_flux(q, v);
        let mut snap = snapshot_with(
            &self.fe,
            &self.coords,
            (t, q, v),
            &nodes,
            (&forces, &flux),
            contacts,
        );
        snap.belt_dissipation = Some(self.damping_dissipation(q, v));
        Ok(snap)
    }

    fn span_transverse(&self, q: &[f64]) -> Result<Vec<f64>, MbdError> {
        let z = &q[1..=self.n_modes()];
        let nodes = deformed(&self.fe.position, &self.deflection(z));
        Ok(span_offsets(self.fe.path(), &nodes))
    }
}

/// Coordinates `(s_b, δ, φ_k…, Δθ)`: belt travel, the nodal deflections, the free pulleys and
/// the tensioner arm.
impl BeltModel for NodalBelt {
    shared_belt_model_methods!("nodal");

    /// The rotating mesh's mean element: the mounted path's length over its nodes (the loop
    /// of Ribaric (5.7) carries the nodes with the material).
    fn material_element(&self) -> Option<f64> {
        Some(self.fe.drive.path().length() / self.fe.n_nodes().max(1) as f64)
    }

    /// Material nodes on the reference polygon at `s_b`, the elements' whole axial forces
    /// ([`NodalBelt::element_forces`]).
    fn snapshot(&self, t: f64, q: &[f64], v: &[f64]) -> Result<Snapshot, MbdError> {
        let nodes = deformed(&self.reference_positions(q[0]), &q[1..=self.n_nodal()]);
        let forces = self.element_forces(q, v);
        let contacts = self
            .contact_report(t, q, v)?
            .into_iter()
            .map(|(i, p, _, c)| (i, p, c));
        let flux = self.momentum_flux(q, v);
        let mut snap = snapshot_with(
            &self.fe,
            &self.coords,
            (t, q, v),
            &nodes,
            (&forces, &flux),
            contacts,
        );
        snap.belt_dissipation = Some(self.damping_dissipation(q, v)?);
        Ok(snap)
    }

    fn span_transverse(&self, q: &[f64]) -> Result<Vec<f64>, MbdError> {
        let nodes = deformed(&self.reference_positions(q[0]), &q[1..=self.n_nodal()]);
        Ok(span_offsets(self.fe.path(), &nodes))
    }
}
