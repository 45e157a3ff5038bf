//! The belt-drive model seen by the speed-loss procedure ([`crate::speed_loss`]), and its
//! implementations for the flowing crate's models: the flowing-material belt (Ribaric (5.14),
//! [`FlowingBelt`]) and the rotating-mesh nodal belt (Ribaric (5.7), [`NodalBelt`]). The ANCF
//! belt's implementation is [`crate::ancf_drive_model::AncfDrive`].

use crate::report::{DriveSnapshot, PulleyRole, PulleyState, SpanState, WrapPoint};
use contact::friction::FrictionSpec;
use fe_model::generate::belt_path::BeltPath;
use flowing::belt::contact::NodeContact;
use flowing::belt::nodal::NodalBelt;
use flowing::belt::{BeltFe, FlowingBelt, Schedule};
use mbd_core::integrators::State;
use mbd_core::{MbdError, SecondOrderSystem};

/// What the procedure's checks need to know about a model's belt.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeltData {
    /// Pre-tension T0 of the mounted belt \[N\].
    pub pretension: f64,
    /// Axial stiffness EA \[N\].
    pub ea: f64,
    /// Radius of the driven pulley's belt line \[m\].
    pub driven_radius: f64,
    /// The belt–pulley friction law.
    pub friction: FrictionSpec,
    /// Whether the model is linearised about the pre-tension (stiffness `K_e + K_g(T0)`,
    /// tension `T0 + EA Δl/l`: the flowing and nodal belts, Ribaric (5.5)): its results hold
    /// only while every span stays taut.
    pub linearised: bool,
}

/// A belt-drive model the speed-loss procedure can run.
pub trait DriveModel: SecondOrderSystem {
    /// Driven pulley speed \[rad/s\] (travel sense) from the velocities.
    fn driven_speed(&self, v: &[f64]) -> f64;
    /// Driver pulley speed \[rad/s\] at time `t`.
    fn driver_speed(&self, t: f64) -> f64;
    /// Consistent state at rest (static equilibrium of the mounted belt) at `t = 0`.
    fn initial_state(&self) -> Result<State, MbdError>;
    /// Replace the driver-speed history.
    fn set_driver_speed(&mut self, s: Schedule);
    /// The load-torque history (extended by the procedure while it runs).
    fn load_mut(&mut self) -> &mut Schedule;
    /// Pre-tension, stiffness, friction law and linearisation of the belt.
    fn belt_data(&self) -> BeltData;
    /// The drive's state at `(t, q, v)` for the engineer's outputs ([`crate::report`]).
    fn snapshot(&self, t: f64, q: &[f64], v: &[f64]) -> Result<DriveSnapshot, MbdError>;
    /// Transverse displacement of each span's mid-point \[m\] (sampled every step for the
    /// vibration amplitude; spans in travel order).
    fn span_transverse(&self, q: &[f64]) -> Result<Vec<f64>, MbdError>;
}

/// Tension and transverse mid-point displacement of every span of `path` for a belt whose
/// deformed nodes are `nodes` (closed polyline) and whose element `i → i+1` carries
/// `tensions[i]`: the mean tension of the elements whose mid-points lie over the middle half
/// of the span ([`BeltPath::span_middle_of`]), and the
/// polyline's crossing of the span's bisector.
pub fn span_states(path: &BeltPath, nodes: &[[f64; 2]], tensions: &[f64]) -> Vec<SpanState> {
    let n = nodes.len();
    let spans = path.spans();
    let mut sum = vec![(0.0, 0usize); spans.len()];
    for i in 0..n {
        let (a, b) = (nodes[i], nodes[(i + 1) % n]);
        let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        if let Some(k) = BeltPath::span_middle_of(&spans, mid) {
            sum[k].0 += tensions[i];
            sum[k].1 += 1;
        }
    }
    spans
        .iter()
        .zip(span_offsets(path, nodes))
        .zip(sum)
        .map(|((sp, transverse), (t, k))| SpanState {
            from: sp.from,
            to: sp.to,
            tension: if k == 0 { f64::NAN } else { t / k as f64 },
            transverse,
        })
        .collect()
}

/// Transverse displacement \[m\] of the mid-point of every span of `path` for the deformed
/// closed polyline `nodes` ([`SpanState::transverse`]).
pub fn span_offsets(path: &BeltPath, nodes: &[[f64; 2]]) -> Vec<f64> {
    path.spans()
        .iter()
        .map(|sp| {
            sp.bisector_crossing(nodes)
                .map_or(f64::NAN, |p| sp.local(p).1)
        })
        .collect()
}

/// Deformed node positions: `reference` plus the translations of `d` (3 DOFs per node).
fn deformed(reference: &[[f64; 2]], d: &[f64]) -> Vec<[f64; 2]> {
    reference
        .iter()
        .enumerate()
        .map(|(i, r)| [r[0] + d[3 * i], r[1] + d[3 * i + 1]])
        .collect()
}

/// Names and roles of the pulleys for the speed-loss procedure: pulley 0 the driver,
/// `driven` the driven pulley, any other an idler (`"idler k"`); the two-pulley drive is
/// `["driver", "driven"]`.
fn procedure_roles(n_pulleys: usize, driven: usize) -> Vec<(String, PulleyRole)> {
    (0..n_pulleys)
        .map(|k| match k {
            0 => ("driver".to_string(), PulleyRole::Driver),
            k if k == driven => ("driven".to_string(), PulleyRole::Driven),
            k => (format!("idler {k}"), PulleyRole::Idler),
        })
        .collect()
}

/// The snapshot of a flowing-material belt of any layout ([`FlowingBelt::with_layout`]) at
/// `(t, q, v)`; `pulleys` names each pulley and gives its role (speeds, hub loads and torques
/// are filled in).
pub fn flowing_layout_snapshot(
    belt: &FlowingBelt,
    pulleys: &[(String, PulleyRole)],
    t: f64,
    q: &[f64],
    v: &[f64],
) -> DriveSnapshot {
    let z = &q[1..=belt.n_modes()];
    let nodes = deformed(&belt.fe.position, &belt.deflection(z));
    let tensions = belt.element_tensions(z);
    let contacts = belt
        .contact_report(t, q, v)
        .into_iter()
        .map(|r| (r.node, r.pulley, r.contact));
    let states = named_pulleys(&belt.fe, pulleys, |k| belt.pulley_speed(k, t, v));
    snapshot_with(&belt.fe, t, &nodes, &tensions, contacts, states)
}

/// The snapshot of a rotating-mesh nodal belt of any layout ([`NodalBelt::with_layout`],
/// Ribaric (5.7)) at `(t, q, v)`: the material nodes on the reference polygon at `s_b`,
/// tensions `T0 + EA Δl/l`; `pulleys` as for [`flowing_layout_snapshot`].
pub fn nodal_layout_snapshot(
    belt: &NodalBelt,
    pulleys: &[(String, PulleyRole)],
    t: f64,
    q: &[f64],
    v: &[f64],
) -> Result<DriveSnapshot, MbdError> {
    let nodes = deformed(&belt.reference_positions(q[0]), &q[1..=belt.n_nodal()]);
    let tensions = belt.element_tensions(q);
    let contacts = belt
        .contact_report(t, q, v)?
        .into_iter()
        .map(|(i, p, _, c)| (i, p, c));
    let states = named_pulleys(&belt.fe, pulleys, |k| belt.pulley_speed(k, t, v));
    Ok(snapshot_with(
        &belt.fe, t, &nodes, &tensions, contacts, states,
    ))
}

/// Pulley states named and given their roles by `pulleys`, speeds from `omega(k)` \[rad/s\]
/// (hub loads and torques zero, summed later by `snapshot_with`).
fn named_pulleys(
    fe: &BeltFe,
    pulleys: &[(String, PulleyRole)],
    omega: impl Fn(usize) -> f64,
) -> Vec<PulleyState> {
    pulleys
        .iter()
        .enumerate()
        .map(|(k, (name, role))| PulleyState {
            name: name.clone(),
            role: *role,
            radius: fe.path.pulleys()[k].radius,
            omega: omega(k),
            hub_load: [0.0; 2],
            torque: 0.0,
        })
        .collect()
}

/// The snapshot of a belt of frame elements with nodal contact on `pulleys` (speeds set;
/// hub loads and torques summed here from the contacts).
fn snapshot_with(
    fe: &BeltFe,
    t: f64,
    nodes: &[[f64; 2]],
    tensions: &[f64],
    contacts: impl Iterator<Item = (usize, usize, NodeContact)>,
    mut pulleys: Vec<PulleyState>,
) -> DriveSnapshot {
    let path = &fe.path;
    let nn = nodes.len();
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
            tension: 0.5 * (tensions[i] + tensions[(i + nn - 1) % nn]),
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
    DriveSnapshot {
        time: t,
        pulleys,
        spans: span_states(path, nodes, tensions),
        wrap,
    }
}

fn linear_belt_data(fe: &BeltFe, friction: FrictionSpec) -> BeltData {
    BeltData {
        pretension: fe.config.belt.tension,
        ea: fe.config.belt.ea,
        driven_radius: fe.config.geometry.radius_driven,
        friction,
        linearised: true,
    }
}

/// Coordinates `(s_b, z, θ₂)`: belt travel, the `m` reduced coordinates and the driven pulley.
impl DriveModel for FlowingBelt {
    fn driven_speed(&self, v: &[f64]) -> f64 {
        v[self.driven_dof()]
    }

    /// Pulley 0's prescribed speed (NaN when pulley 0 is free: no driver speed to report).
    fn driver_speed(&self, t: f64) -> f64 {
        match &self.motions[0] {
            flowing::belt::flowing_system::PulleyMotion::Speed(s) => s.value(t),
            _ => f64::NAN,
        }
    }

    fn initial_state(&self) -> Result<State, MbdError> {
        let q = self.static_state()?;
        let n = q.len();
        Ok(State::new(0.0, q, vec![0.0; n]))
    }

    /// Pulley 0's speed (a speed-driven pulley in every drive the procedure runs).
    fn set_driver_speed(&mut self, s: Schedule) {
        if let Some(d) = self.driver_speed_mut() {
            *d = s.into();
        }
    }

    /// The load of the driven pulley ([`FlowingBelt::driven_dof`]'s pulley).
    fn load_mut(&mut self) -> &mut Schedule {
        let p = self.driven_pulley();
        &mut self
            .load_mut(p)
            .expect("the driven pulley of a flowing drive is free")
            .schedule
    }

    fn belt_data(&self) -> BeltData {
        linear_belt_data(&self.fe, *self.friction_law())
    }

    /// Contact nodes of the stationary mesh, tensions `T0 + EA Δl/l` of its elements.
    fn snapshot(&self, t: f64, q: &[f64], v: &[f64]) -> Result<DriveSnapshot, MbdError> {
        let np = self.fe.path.pulleys().len();
        let driven = self.driven_pulley();
        Ok(flowing_layout_snapshot(
            self,
            &procedure_roles(np, driven),
            t,
            q,
            v,
        ))
    }

    fn span_transverse(&self, q: &[f64]) -> Result<Vec<f64>, MbdError> {
        let z = &q[1..=self.n_modes()];
        let nodes = deformed(&self.fe.position, &self.deflection(z));
        Ok(span_offsets(&self.fe.path, &nodes))
    }
}

/// Coordinates `(s_b, d, θ_k…)`: belt travel, the nodal deflections and the free pulleys
/// (`(s_b, d, θ₂)` for the two-pulley drive).
impl DriveModel for NodalBelt {
    fn driven_speed(&self, v: &[f64]) -> f64 {
        v[self.driven_dof()]
    }

    /// Pulley 0's prescribed speed (NaN when pulley 0 is free: no driver speed to report).
    fn driver_speed(&self, t: f64) -> f64 {
        match &self.motions[0] {
            flowing::belt::flowing_system::PulleyMotion::Speed(s) => s.value(t),
            _ => f64::NAN,
        }
    }

    fn initial_state(&self) -> Result<State, MbdError> {
        let q = self.static_state()?;
        let n = q.len();
        Ok(State::new(0.0, q, vec![0.0; n]))
    }

    /// Pulley 0's speed (a speed-driven pulley in every drive the procedure runs).
    fn set_driver_speed(&mut self, s: Schedule) {
        if let Some(d) = self.driver_speed_mut() {
            *d = s.into();
        }
    }

    /// The load of the driven pulley ([`NodalBelt::driven_dof`]'s pulley).
    fn load_mut(&mut self) -> &mut Schedule {
        let p = self.driven_pulley();
        &mut self
            .load_mut(p)
            .expect("the driven pulley of a nodal drive is free")
            .schedule
    }

    fn belt_data(&self) -> BeltData {
        linear_belt_data(&self.fe, *self.friction_law())
    }

    /// Material nodes on the reference polygon at `s_b`, tensions `T0 + EA Δl/l`.
    fn snapshot(&self, t: f64, q: &[f64], v: &[f64]) -> Result<DriveSnapshot, MbdError> {
        let np = self.fe.path.pulleys().len();
        let driven = self.driven_pulley();
        nodal_layout_snapshot(self, &procedure_roles(np, driven), t, q, v)
    }

    fn span_transverse(&self, q: &[f64]) -> Result<Vec<f64>, MbdError> {
        let nodes = deformed(&self.reference_positions(q[0]), &q[1..=self.n_nodal()]);
        Ok(span_offsets(&self.fe.path, &nodes))
    }
}
