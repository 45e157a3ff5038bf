//! Kinematic constraints between two markers ([`crate::marker::Marker`]: a frame on a rigid
//! body, the ground or a node of a floating body): the [`Constraint`] extension point, the
//! standard joints (Nikravesh's dot-1/dot-2/spherical primitives; Lin (2.22)–(2.24), (5.1)–(5.7)
//! for the spherical joint), rheonomic drivers, and the [`ConstraintSet`] that both
//! [`crate::MultibodySystem`] and [`crate::floating::FloatingSystem`] evaluate.
//!
//! Every equation provides `Φ`, its Jacobian `D` with respect to the carrying bodies' velocities
//! `(ṙ, ω', ż)`, the velocity right-hand side `ν = −Φ_t` and `γ` of `D v̇ = γ`.

/// The `name`, `n_eq`, `markers` and `validate` methods of a two-marker constraint with fields
/// `name`, `i`, `j` and an inherent `validate_extra`.
macro_rules! common {
    ($n:expr) => {
        fn name(&self) -> &str {
            &self.name
        }
        fn n_eq(&self) -> usize {
            $n
        }
        fn markers(&self) -> [Marker; 2] {
            [self.i, self.j]
        }
        fn validate(&self) -> Result<(), MbdError> {
            check_markers(&self.name, &self.i, &self.j)?;
            self.validate_extra()
        }
    };
}

mod drivers;
mod set;

pub use drivers::{DriverLaw, PointDriver, RotationDriver};
pub use set::ConstraintSet;

use crate::MbdError;
use crate::body::BodyId;
use crate::marker::{Carrier, Marker, Row, Term};
use nalgebra::Vector3;

/// One scalar constraint equation with its right-hand sides.
#[derive(Debug, Clone, PartialEq)]
pub struct Equation {
    /// Residual, Jacobian, rate and quadratic terms.
    pub row: Row,
    /// `ν = −∂Φ/∂t`.
    pub nu: f64,
    /// `γ` in `D v̇ = γ`.
    pub gamma: f64,
}

impl From<Row> for Equation {
    /// Scleronomic equation: `ν = 0`, `γ = −(velocity-quadratic part of Φ̈)`.
    fn from(row: Row) -> Self {
        Self {
            nu: 0.0,
            gamma: -row.quad,
            row,
        }
    }
}

/// A kinematic constraint (extension point).
pub trait Constraint: Send + Sync {
    /// Name used in messages and reaction output.
    fn name(&self) -> &str;
    /// Number of scalar equations.
    fn n_eq(&self) -> usize;
    /// The markers of sides i and j (a one-sided constraint returns [`Marker::ground`] for j).
    fn markers(&self) -> [Marker; 2];
    /// The two bodies (`None` = ground).
    fn bodies(&self) -> [Option<BodyId>; 2] {
        self.markers().map(|m| m.body)
    }
    /// Appends the `n_eq` equations at time `t` \[s\] for the carriers of the two markers.
    fn eval(&self, t: f64, ci: &Carrier, cj: &Carrier, out: &mut Vec<Equation>);
    /// Checks the parameters (called when the constraint is added to a system).
    fn validate(&self) -> Result<(), MbdError> {
        Ok(())
    }
}

pub(crate) fn check_vec(
    name: &str, field: &str, v: &Vector3<f64>, nonzero: bool,
) -> Result<(), MbdError> {
    if !v.iter().all(|x| x.is_finite()) || (nonzero && v.norm() == 0.0) {
        return Err(MbdError::InvalidInput {
            item: format!("constraint \"{name}\": {field}"),
            reason: format!(
                "must be finite{}, got {:?}",
                if nonzero { " and non-zero" } else { "" },
                v.as_slice()
            ),
        });
    }
    Ok(())
}

pub(crate) fn check_reference(
    name: &str, field: &str, axis: &Vector3<f64>, r: &Vector3<f64>,
) -> Result<(), MbdError> {
    check_vec(name, field, r, true)?;
    if (r - axis * axis.dot(r)).norm() <= 1e-9 * r.norm() {
        return Err(MbdError::InvalidInput {
            item: format!("constraint \"{name}\": {field}"),
            reason: "reference vector is parallel to the axis".into(),
        });
    }
    Ok(())
}

pub(crate) fn check_markers(name: &str, i: &Marker, j: &Marker) -> Result<(), MbdError> {
    check_vec(name, "i.point", &i.point, false)?;
    check_vec(name, "j.point", &j.point, false)?;
    check_vec(name, "i.axis", &i.axis, true)?;
    check_vec(name, "j.axis", &j.axis, true)
}

/// Two unit vectors completing `a` to a right-handed orthonormal basis `(h, g, a)`.
pub fn perpendicular_basis(a: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let t = if a.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let h = (t - a * a.dot(&t)).normalize();
    let g = a.cross(&h);
    (h, g)
}

/// Spherical joint: `d_i = d_j` at the attachment points (3 equations; Lin (2.22)–(2.24)).
#[derive(Debug, Clone)]
pub struct Spherical {
    /// Name.
    pub name: String,
    /// Frame on body i.
    pub i: Marker,
    /// Frame on body j.
    pub j: Marker,
}

impl Spherical {
    fn validate_extra(&self) -> Result<(), MbdError> {
        Ok(())
    }
}

impl Constraint for Spherical {
    common!(3);
    fn eval(&self, _t: f64, ci: &Carrier, cj: &Carrier, out: &mut Vec<Equation>) {
        let d = Term::point(ci, &self.i, 0).sub(&Term::point(cj, &self.j, 1));
        for k in 0..3 {
            out.push(d.component(k).into());
        }
    }
}

/// Fixed (welded) joint or ground fixation: spherical + 3 rotational equations locking the
/// relative orientation (6 equations: `h_i·a_j = g_i·a_j = g_i·h_j = 0`). The frames
/// `(h, g, a)` built by [`perpendicular_basis`] from the two axes must coincide initially.
#[derive(Debug, Clone)]
pub struct Fixed {
    /// Name.
    pub name: String,
    /// Frame on body i.
    pub i: Marker,
    /// Frame on body j.
    pub j: Marker,
}

impl Fixed {
    fn validate_extra(&self) -> Result<(), MbdError> {
        Ok(())
    }
}

impl Constraint for Fixed {
    common!(6);
    fn eval(&self, _t: f64, ci: &Carrier, cj: &Carrier, out: &mut Vec<Equation>) {
        let d = Term::point(ci, &self.i, 0).sub(&Term::point(cj, &self.j, 1));
        for k in 0..3 {
            out.push(d.component(k).into());
        }
        let (hi, gi) = perpendicular_basis(&self.i.axis);
        let (hj, _) = perpendicular_basis(&self.j.axis);
        let hiv = Term::vector(ci, &self.i, &hi, 0);
        let giv = Term::vector(ci, &self.i, &gi, 0);
        let aj = Term::vector(cj, &self.j, &self.j.axis, 1);
        let hjv = Term::vector(cj, &self.j, &hj, 1);
        out.push(hiv.dot(&aj).into());
        out.push(giv.dot(&aj).into());
        out.push(giv.dot(&hjv).into());
    }
}

/// Revolute joint about the common axis `a_i = a_j` through the attachment points
/// (spherical + 2 dot-1 equations: 5 equations).
#[derive(Debug, Clone)]
pub struct Revolute {
    /// Name.
    pub name: String,
    /// Frame on body i.
    pub i: Marker,
    /// Frame on body j.
    pub j: Marker,
}

impl Revolute {
    fn validate_extra(&self) -> Result<(), MbdError> {
        Ok(())
    }
}

impl Constraint for Revolute {
    common!(5);
    fn eval(&self, _t: f64, ci: &Carrier, cj: &Carrier, out: &mut Vec<Equation>) {
        let d = Term::point(ci, &self.i, 0).sub(&Term::point(cj, &self.j, 1));
        for k in 0..3 {
            out.push(d.component(k).into());
        }
        let (hi, gi) = perpendicular_basis(&self.i.axis);
        let aj = Term::vector(cj, &self.j, &self.j.axis, 1);
        out.push(Term::vector(ci, &self.i, &hi, 0).dot(&aj).into());
        out.push(Term::vector(ci, &self.i, &gi, 0).dot(&aj).into());
    }
}

/// Universal (Hooke) joint: spherical + `a_i ⊥ a_j` (4 equations).
#[derive(Debug, Clone)]
pub struct Universal {
    /// Name.
    pub name: String,
    /// Frame on body i (cross axis of body i).
    pub i: Marker,
    /// Frame on body j (cross axis of body j, perpendicular to that of i).
    pub j: Marker,
}

impl Universal {
    fn validate_extra(&self) -> Result<(), MbdError> {
        Ok(())
    }
}

impl Constraint for Universal {
    common!(4);
    fn eval(&self, _t: f64, ci: &Carrier, cj: &Carrier, out: &mut Vec<Equation>) {
        let d = Term::point(ci, &self.i, 0).sub(&Term::point(cj, &self.j, 1));
        for k in 0..3 {
            out.push(d.component(k).into());
        }
        let ai = Term::vector(ci, &self.i, &self.i.axis, 0);
        let aj = Term::vector(cj, &self.j, &self.j.axis, 1);
        out.push(ai.dot(&aj).into());
    }
}

/// Prismatic (translational) joint along `a_i`: parallel axes (2), the connecting vector
/// along the axis (2) and no relative rotation about it (1): 5 equations. `reference_i` and
/// `reference_j` are body-fixed vectors perpendicular to the axes that stay parallel.
#[derive(Debug, Clone)]
pub struct Prismatic {
    /// Name.
    pub name: String,
    /// Frame on body i.
    pub i: Marker,
    /// Frame on body j.
    pub j: Marker,
    /// Reference vector on body i, perpendicular to `i.axis`.
    pub reference_i: Vector3<f64>,
    /// Reference vector on body j, perpendicular to `j.axis` (parallel to `reference_i`).
    pub reference_j: Vector3<f64>,
}

impl Prismatic {
    fn validate_extra(&self) -> Result<(), MbdError> {
        check_reference(&self.name, "reference_i", &self.i.axis, &self.reference_i)?;
        check_reference(&self.name, "reference_j", &self.j.axis, &self.reference_j)
    }
}

impl Constraint for Prismatic {
    common!(5);
    fn eval(&self, _t: f64, ci: &Carrier, cj: &Carrier, out: &mut Vec<Equation>) {
        let a = self.i.axis;
        let h = (self.reference_i - a * a.dot(&self.reference_i)).normalize();
        let g = a.cross(&h);
        let hv = Term::vector(ci, &self.i, &h, 0);
        let gv = Term::vector(ci, &self.i, &g, 0);
        let aj = Term::vector(cj, &self.j, &self.j.axis, 1);
        let d = Term::point(cj, &self.j, 1).sub(&Term::point(ci, &self.i, 0));
        let aj_axis = self.j.axis;
        let hj = (self.reference_j - aj_axis * aj_axis.dot(&self.reference_j)).normalize();
        let gj = aj_axis.cross(&hj);
        out.push(hv.dot(&aj).into());
        out.push(gv.dot(&aj).into());
        out.push(hv.dot(&d).into());
        out.push(gv.dot(&d).into());
        out.push(hv.dot(&Term::vector(cj, &self.j, &gj, 1)).into());
    }
}

/// Distance constraint `(|d_j − d_i|² − L²)/2 = 0` between two points (1 equation).
#[derive(Debug, Clone)]
pub struct Distance {
    /// Name.
    pub name: String,
    /// Point on body i.
    pub i: Marker,
    /// Point on body j.
    pub j: Marker,
    /// Distance L \[m\].
    pub length: f64,
}

impl Distance {
    fn validate_extra(&self) -> Result<(), MbdError> {
        if !(self.length.is_finite() && self.length > 0.0) {
            return Err(MbdError::InvalidInput {
                item: format!("constraint \"{}\": length", self.name),
                reason: format!("must be positive and finite, got {} m", self.length),
            });
        }
        Ok(())
    }
}

impl Constraint for Distance {
    common!(1);
    fn eval(&self, _t: f64, ci: &Carrier, cj: &Carrier, out: &mut Vec<Equation>) {
        let d = Term::point(cj, &self.j, 1).sub(&Term::point(ci, &self.i, 0));
        let mut r = d.dot(&d).scaled(0.5);
        r.phi -= 0.5 * self.length * self.length;
        out.push(r.into());
    }
}

/// Point `j.point` of body j stays in the plane through `i.point` with normal `i.axis`
/// (fixed in body i): `n_iᵀ (d_j − d_i) = 0` (1 equation).
#[derive(Debug, Clone)]
pub struct PointOnPlane {
    /// Name.
    pub name: String,
    /// Plane (point and normal) on body i.
    pub i: Marker,
    /// Point on body j.
    pub j: Marker,
}

impl PointOnPlane {
    fn validate_extra(&self) -> Result<(), MbdError> {
        Ok(())
    }
}

impl Constraint for PointOnPlane {
    common!(1);
    fn eval(&self, _t: f64, ci: &Carrier, cj: &Carrier, out: &mut Vec<Equation>) {
        let d = Term::point(cj, &self.j, 1).sub(&Term::point(ci, &self.i, 0));
        out.push(Term::vector(ci, &self.i, &self.i.axis, 0).dot(&d).into());
    }
}

/// Planar revolute joint for mechanisms moving in the plane normal to the joint axis: the
/// two in-plane components of the point coincidence (2 equations). Use it instead of
/// [`Revolute`] where the out-of-plane motion is already fixed by other joints (a planar
/// loop closed with full revolutes is redundant in 3-D).
#[derive(Debug, Clone)]
pub struct PlanarRevolute {
    /// Name.
    pub name: String,
    /// Frame on body i (axis = plane normal, fixed in body i).
    pub i: Marker,
    /// Point on body j.
    pub j: Marker,
}

impl PlanarRevolute {
    fn validate_extra(&self) -> Result<(), MbdError> {
        Ok(())
    }
}

impl Constraint for PlanarRevolute {
    common!(2);
    fn eval(&self, _t: f64, ci: &Carrier, cj: &Carrier, out: &mut Vec<Equation>) {
        let (h, g) = perpendicular_basis(&self.i.axis);
        let d = Term::point(cj, &self.j, 1).sub(&Term::point(ci, &self.i, 0));
        out.push(Term::vector(ci, &self.i, &h, 0).dot(&d).into());
        out.push(Term::vector(ci, &self.i, &g, 0).dot(&d).into());
    }
}
