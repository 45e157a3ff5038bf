//! Force elements (extension point [`ForceElement`]): gravity, translational and rotational
//! spring-dampers, applied forces and torques as functions of time and state.
//!
//! Generalized forces follow the velocity layout `(ṙ, ω')` per body: a global force `f` at
//! body point `s'` contributes `f` and the body-frame moment `n' = s' × (Aᵀ f)` (Lin (2.3),
//! (2.25)–(2.26)).

use crate::MbdError;
use crate::body::{BodyId, BodyKin, RigidBody};
use crate::kinematics::tilde::add3;
use crate::marker::{Carrier, Marker, Term};
use nalgebra::Vector3;
use std::sync::Arc;

/// A force element (extension point).
pub trait ForceElement: Send + Sync {
    /// Name used in messages.
    fn name(&self) -> &str;
    /// Bodies it acts on (`None` = ground), used for validation.
    fn bodies(&self) -> Vec<Option<BodyId>>;
    /// Adds the generalized forces at time `t` \[s\] into `f` (length `6 N`).
    fn apply(&self, t: f64, bodies: &[RigidBody], kin: &[BodyKin], f: &mut [f64]);
    /// Potential energy \[J\] (0 for non-conservative elements).
    fn potential_energy(&self, _bodies: &[RigidBody], _kin: &[BodyKin]) -> f64 {
        0.0
    }
    /// Whether the generalized force is independent of the state (no tangent contribution).
    fn is_state_independent(&self) -> bool {
        false
    }
    /// Checks the parameters (called when the element is added to a system).
    fn validate(&self) -> Result<(), MbdError> {
        Ok(())
    }
}

fn check_params(name: &str, params: &[(&str, f64, bool)]) -> Result<(), MbdError> {
    for &(field, v, nonneg) in params {
        if !v.is_finite() || (nonneg && v < 0.0) {
            return Err(MbdError::InvalidInput {
                item: format!("force element \"{name}\": {field}"),
                reason: format!(
                    "must be finite{}, got {v}",
                    if nonneg { " and non-negative" } else { "" }
                ),
            });
        }
    }
    Ok(())
}

/// Adds the global force `force` \[N\] acting at body point `s'` of body `b` to `f`.
pub fn add_point_force(
    f: &mut [f64], b: BodyId, k: &BodyKin, s: &Vector3<f64>, force: &Vector3<f64>,
) {
    add3(f, 6 * b, force);
    add3(f, 6 * b + 3, &s.cross(&(k.a.transpose() * force)));
}

/// Adds the global torque `torque` \[N·m\] acting on body `b` to `f`.
pub fn add_torque(f: &mut [f64], b: BodyId, k: &BodyKin, torque: &Vector3<f64>) {
    add3(f, 6 * b + 3, &(k.a.transpose() * torque));
}

/// Force elements act on rigid bodies: markers on flexible nodes are rejected.
fn check_rigid(name: &str, markers: [&Marker; 2]) -> Result<(), MbdError> {
    match markers.iter().position(|m| m.node.is_some()) {
        Some(k) => Err(MbdError::InvalidInput {
            item: format!("force element \"{name}\": {}", ["i", "j"][k]),
            reason: "force elements act on rigid bodies; the marker is on a flexible node".into(),
        }),
        None => Ok(()),
    }
}

fn kin_of(kin: &[BodyKin], b: Option<BodyId>) -> BodyKin {
    b.map(|b| kin[b]).unwrap_or_else(BodyKin::ground)
}

/// Uniform gravity `g` \[m/s²\] on every body.
#[derive(Debug, Clone)]
pub struct Gravity {
    /// Gravitational acceleration \[m/s²\].
    pub g: Vector3<f64>,
}

impl ForceElement for Gravity {
    fn name(&self) -> &str {
        "gravity"
    }
    fn bodies(&self) -> Vec<Option<BodyId>> {
        Vec::new()
    }
    fn is_state_independent(&self) -> bool {
        true
    }
    fn validate(&self) -> Result<(), MbdError> {
        check_params(
            "gravity",
            &[
                ("g.x", self.g.x, false),
                ("g.y", self.g.y, false),
                ("g.z", self.g.z, false),
            ],
        )
    }
    fn apply(&self, _t: f64, bodies: &[RigidBody], _kin: &[BodyKin], f: &mut [f64]) {
        for (b, body) in bodies.iter().enumerate() {
            add3(f, 6 * b, &(self.g * body.mass));
        }
    }
    fn potential_energy(&self, bodies: &[RigidBody], kin: &[BodyKin]) -> f64 {
        bodies
            .iter()
            .zip(kin)
            .map(|(b, k)| -b.mass * self.g.dot(&k.r))
            .sum()
    }
}

/// Translational spring-damper between two points: tension `F = k (L − L₀) + c L̇` \[N\] along
/// the line of the points.
#[derive(Debug, Clone)]
pub struct SpringDamper {
    /// Name.
    pub name: String,
    /// Point on body i.
    pub i: Marker,
    /// Point on body j.
    pub j: Marker,
    /// Stiffness k \[N/m\].
    pub stiffness: f64,
    /// Damping c \[N·s/m\].
    pub damping: f64,
    /// Free length L₀ \[m\].
    pub free_length: f64,
}

impl ForceElement for SpringDamper {
    fn name(&self) -> &str {
        &self.name
    }
    fn bodies(&self) -> Vec<Option<BodyId>> {
        vec![self.i.body, self.j.body]
    }
    fn validate(&self) -> Result<(), MbdError> {
        check_rigid(&self.name, [&self.i, &self.j])?;
        check_params(
            &self.name,
            &[
                ("stiffness", self.stiffness, true),
                ("damping", self.damping, true),
                ("free_length", self.free_length, true),
            ],
        )
    }
    fn apply(&self, _t: f64, _bodies: &[RigidBody], kin: &[BodyKin], f: &mut [f64]) {
        let (ki, kj) = (kin_of(kin, self.i.body), kin_of(kin, self.j.body));
        let d = kj.point(&self.j.point) - ki.point(&self.i.point);
        let l = d.norm();
        if l <= 0.0 {
            return;
        }
        let u = d / l;
        let ldot = u.dot(&(kj.point_velocity(&self.j.point) - ki.point_velocity(&self.i.point)));
        let tension = self.stiffness * (l - self.free_length) + self.damping * ldot;
        if let Some(b) = self.i.body {
            add_point_force(f, b, &ki, &self.i.point, &(u * tension));
        }
        if let Some(b) = self.j.body {
            add_point_force(f, b, &kj, &self.j.point, &(-u * tension));
        }
    }
    fn potential_energy(&self, _bodies: &[RigidBody], kin: &[BodyKin]) -> f64 {
        let (ki, kj) = (kin_of(kin, self.i.body), kin_of(kin, self.j.body));
        let l = (kj.point(&self.j.point) - ki.point(&self.i.point)).norm();
        0.5 * self.stiffness * (l - self.free_length).powi(2)
    }
}

/// Rotational spring-damper about the axis `i.axis` (fixed in body i): relative angle
/// `θ = atan2(x_j·y_i, x_j·x_i)` of the body-j direction `reference_j` measured from
/// `reference_i` (|θ| < π), generalized force `−(k (θ − θ₀) + c θ̇) ∂θ̇/∂v` (exact virtual work of
/// the potential `½ k (θ − θ₀)²`; for aligned axes, e.g. with a revolute joint, this is the
/// torque `T = −k (θ − θ₀) − c θ̇` about the axis on body j and `−T` on body i).
#[derive(Debug, Clone)]
pub struct RotationalSpringDamper {
    /// Name.
    pub name: String,
    /// Axis on body i.
    pub i: Marker,
    /// Body j.
    pub j: Marker,
    /// Zero-angle direction on body i.
    pub reference_i: Vector3<f64>,
    /// Direction on body j.
    pub reference_j: Vector3<f64>,
    /// Stiffness \[N·m/rad\].
    pub stiffness: f64,
    /// Damping \[N·m·s/rad\].
    pub damping: f64,
    /// Free angle θ₀ \[rad\].
    pub free_angle: f64,
}

impl RotationalSpringDamper {
    /// Angle θ \[rad\], rate θ̇ \[rad/s\] and `∂θ̇/∂v` of bodies i and j.
    fn angle(&self, ki: &BodyKin, kj: &BodyKin) -> (f64, f64, [f64; 6], [f64; 6]) {
        let a = self.i.axis;
        let xi = (self.reference_i - a * a.dot(&self.reference_i)).normalize();
        let yi = a.cross(&xi);
        let (ci, cj) = (Carrier::rigid(*ki), Carrier::rigid(*kj));
        let xj = Term::vector(&cj, &self.j, &self.reference_j, 1);
        let s = Term::vector(&ci, &self.i, &yi, 0).dot(&xj);
        let c = Term::vector(&ci, &self.i, &xi, 0).dot(&xj);
        let n2 = (s.phi * s.phi + c.phi * c.phi).max(1e-300);
        let th = s.phi.atan2(c.phi);
        let thd = (c.phi * s.rate - s.phi * c.rate) / n2;
        let mut di = [0.0; 6];
        let mut dj = [0.0; 6];
        for k in 0..6 {
            di[k] = (c.phi * s.di[k] - s.phi * c.di[k]) / n2;
            dj[k] = (c.phi * s.dj[k] - s.phi * c.dj[k]) / n2;
        }
        (th, thd, di, dj)
    }
}

impl ForceElement for RotationalSpringDamper {
    fn name(&self) -> &str {
        &self.name
    }
    fn bodies(&self) -> Vec<Option<BodyId>> {
        vec![self.i.body, self.j.body]
    }
    fn validate(&self) -> Result<(), MbdError> {
        check_rigid(&self.name, [&self.i, &self.j])?;
        check_params(
            &self.name,
            &[
                ("stiffness", self.stiffness, true),
                ("damping", self.damping, true),
                ("free_angle", self.free_angle, false),
            ],
        )?;
        let a = self.i.axis;
        let r = self.reference_i;
        if a.norm() == 0.0 || (r - a * a.dot(&r) / a.norm_squared()).norm() <= 1e-9 * r.norm() {
            return Err(MbdError::InvalidInput {
                item: format!("force element \"{}\": reference_i", self.name),
                reason: "axis is zero or reference vector is parallel to it".into(),
            });
        }
        Ok(())
    }
    fn apply(&self, _t: f64, _bodies: &[RigidBody], kin: &[BodyKin], f: &mut [f64]) {
        let (ki, kj) = (kin_of(kin, self.i.body), kin_of(kin, self.j.body));
        let (th, thd, di, dj) = self.angle(&ki, &kj);
        let torque = -self.stiffness * (th - self.free_angle) - self.damping * thd;
        if let Some(b) = self.i.body {
            for k in 0..6 {
                f[6 * b + k] += torque * di[k];
            }
        }
        if let Some(b) = self.j.body {
            for k in 0..6 {
                f[6 * b + k] += torque * dj[k];
            }
        }
    }
    fn potential_energy(&self, _bodies: &[RigidBody], kin: &[BodyKin]) -> f64 {
        let (ki, kj) = (kin_of(kin, self.i.body), kin_of(kin, self.j.body));
        let (th, ..) = self.angle(&ki, &kj);
        0.5 * self.stiffness * (th - self.free_angle).powi(2)
    }
}

/// Function of time and body kinematics returning a global vector (force \[N\] or torque \[N·m\]).
pub type VectorLaw = Arc<dyn Fn(f64, &BodyKin) -> Vector3<f64> + Send + Sync>;

/// Applied global force at a body point, a function of time and the body's state.
#[derive(Clone)]
pub struct AppliedForce {
    /// Name.
    pub name: String,
    /// Body.
    pub body: BodyId,
    /// Application point in body coordinates \[m\].
    pub point: Vector3<f64>,
    /// `(t, kinematics) ↦ force` \[N\], global.
    pub law: VectorLaw,
}

impl ForceElement for AppliedForce {
    fn name(&self) -> &str {
        &self.name
    }
    fn bodies(&self) -> Vec<Option<BodyId>> {
        vec![Some(self.body)]
    }
    fn apply(&self, t: f64, _bodies: &[RigidBody], kin: &[BodyKin], f: &mut [f64]) {
        let k = kin[self.body];
        add_point_force(f, self.body, &k, &self.point, &(self.law)(t, &k));
    }
}

/// Applied global torque on a body, a function of time and the body's state.
#[derive(Clone)]
pub struct AppliedTorque {
    /// Name.
    pub name: String,
    /// Body.
    pub body: BodyId,
    /// `(t, kinematics) ↦ torque` \[N·m\], global.
    pub law: VectorLaw,
}

impl ForceElement for AppliedTorque {
    fn name(&self) -> &str {
        &self.name
    }
    fn bodies(&self) -> Vec<Option<BodyId>> {
        vec![Some(self.body)]
    }
    fn apply(&self, t: f64, _bodies: &[RigidBody], kin: &[BodyKin], f: &mut [f64]) {
        let k = kin[self.body];
        add_torque(f, self.body, &k, &(self.law)(t, &k));
    }
}
