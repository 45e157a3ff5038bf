//! Kinematic constraints between two bodies (or a body and the ground): the [`Constraint`]
//! extension point and the standard joints (Nikravesh's dot-1/dot-2/spherical primitives; Lin
//! (2.22)–(2.24) for the spherical joint) and rheonomic rotation drivers.
//!
//! Every equation provides `Φ`, its Jacobian `D` with respect to the body velocities
//! `(ṙ, ω')`, the velocity right-hand side `ν = −Φ_t` and `γ` of `D v̇ = γ`.

use crate::MbdError;
use crate::body::{BodyId, BodyKin, Row, Term};
use nalgebra::Vector3;
use std::sync::Arc;

/// One scalar constraint equation with its right-hand sides.
#[derive(Debug, Clone, Copy, PartialEq)]
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
    /// The two bodies (`None` = ground).
    fn bodies(&self) -> [Option<BodyId>; 2];
    /// Appends the `n_eq` equations at time `t` \[s\] for the kinematics of the two bodies.
    fn eval(&self, t: f64, ki: &BodyKin, kj: &BodyKin, out: &mut Vec<Equation>);
    /// Checks the parameters (called when the constraint is added to a system).
    fn validate(&self) -> Result<(), MbdError> {
        Ok(())
    }
}

fn check_vec(name: &str, field: &str, v: &Vector3<f64>, nonzero: bool) -> Result<(), MbdError> {
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

fn check_reference(
    name: &str,
    field: &str,
    axis: &Vector3<f64>,
    r: &Vector3<f64>,
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

fn check_attachments(name: &str, i: &Attachment, j: &Attachment) -> Result<(), MbdError> {
    check_vec(name, "i.point", &i.point, false)?;
    check_vec(name, "j.point", &j.point, false)?;
    check_vec(name, "i.axis", &i.axis, true)?;
    check_vec(name, "j.axis", &j.axis, true)
}

/// A joint frame on a body: a point `s'` \[m\] and a unit axis `a'` in body coordinates (for the
/// ground: global coordinates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attachment {
    /// Body (`None` = ground).
    pub body: Option<BodyId>,
    /// Point in body coordinates \[m\].
    pub point: Vector3<f64>,
    /// Unit axis in body coordinates.
    pub axis: Vector3<f64>,
}

impl Attachment {
    /// Attachment at `point` with axis `axis` (normalised; must be non-zero).
    pub fn new(body: Option<BodyId>, point: Vector3<f64>, axis: Vector3<f64>) -> Self {
        let n = axis.norm();
        Self {
            body,
            point,
            // a zero axis is kept (and rejected by `Constraint::validate`)
            axis: if n > 0.0 { axis / n } else { axis },
        }
    }

    /// Attachment at `point` (axis irrelevant, set to z).
    pub fn point(body: Option<BodyId>, point: Vector3<f64>) -> Self {
        Self::new(body, point, Vector3::z())
    }
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

macro_rules! common {
    ($n:expr) => {
        fn name(&self) -> &str {
            &self.name
        }
        fn n_eq(&self) -> usize {
            $n
        }
        fn bodies(&self) -> [Option<BodyId>; 2] {
            [self.i.body, self.j.body]
        }
        fn validate(&self) -> Result<(), MbdError> {
            check_attachments(&self.name, &self.i, &self.j)?;
            self.validate_extra()
        }
    };
}

/// Spherical joint: `d_i = d_j` at the attachment points (3 equations; Lin (2.22)–(2.24)).
#[derive(Debug, Clone)]
pub struct Spherical {
    /// Name.
    pub name: String,
    /// Frame on body i.
    pub i: Attachment,
    /// Frame on body j.
    pub j: Attachment,
}

impl Spherical {
    fn validate_extra(&self) -> Result<(), MbdError> {
        Ok(())
    }
}

impl Constraint for Spherical {
    common!(3);
    fn eval(&self, _t: f64, ki: &BodyKin, kj: &BodyKin, out: &mut Vec<Equation>) {
        let d = Term::point(ki, &self.i.point, 0).sub(&Term::point(kj, &self.j.point, 1));
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
    pub i: Attachment,
    /// Frame on body j.
    pub j: Attachment,
}

impl Fixed {
    fn validate_extra(&self) -> Result<(), MbdError> {
        Ok(())
    }
}

impl Constraint for Fixed {
    common!(6);
    fn eval(&self, _t: f64, ki: &BodyKin, kj: &BodyKin, out: &mut Vec<Equation>) {
        let d = Term::point(ki, &self.i.point, 0).sub(&Term::point(kj, &self.j.point, 1));
        for k in 0..3 {
            out.push(d.component(k).into());
        }
        let (hi, gi) = perpendicular_basis(&self.i.axis);
        let (hj, _) = perpendicular_basis(&self.j.axis);
        let hiv = Term::vector(ki, &hi, 0);
        let giv = Term::vector(ki, &gi, 0);
        let aj = Term::vector(kj, &self.j.axis, 1);
        let hjv = Term::vector(kj, &hj, 1);
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
    pub i: Attachment,
    /// Frame on body j.
    pub j: Attachment,
}

impl Revolute {
    fn validate_extra(&self) -> Result<(), MbdError> {
        Ok(())
    }
}

impl Constraint for Revolute {
    common!(5);
    fn eval(&self, _t: f64, ki: &BodyKin, kj: &BodyKin, out: &mut Vec<Equation>) {
        let d = Term::point(ki, &self.i.point, 0).sub(&Term::point(kj, &self.j.point, 1));
        for k in 0..3 {
            out.push(d.component(k).into());
        }
        let (hi, gi) = perpendicular_basis(&self.i.axis);
        let aj = Term::vector(kj, &self.j.axis, 1);
        out.push(Term::vector(ki, &hi, 0).dot(&aj).into());
        out.push(Term::vector(ki, &gi, 0).dot(&aj).into());
    }
}

/// Universal (Hooke) joint: spherical + `a_i ⊥ a_j` (4 equations).
#[derive(Debug, Clone)]
pub struct Universal {
    /// Name.
    pub name: String,
    /// Frame on body i (cross axis of body i).
    pub i: Attachment,
    /// Frame on body j (cross axis of body j, perpendicular to that of i).
    pub j: Attachment,
}

impl Universal {
    fn validate_extra(&self) -> Result<(), MbdError> {
        Ok(())
    }
}

impl Constraint for Universal {
    common!(4);
    fn eval(&self, _t: f64, ki: &BodyKin, kj: &BodyKin, out: &mut Vec<Equation>) {
        let d = Term::point(ki, &self.i.point, 0).sub(&Term::point(kj, &self.j.point, 1));
        for k in 0..3 {
            out.push(d.component(k).into());
        }
        let ai = Term::vector(ki, &self.i.axis, 0);
        let aj = Term::vector(kj, &self.j.axis, 1);
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
    pub i: Attachment,
    /// Frame on body j.
    pub j: Attachment,
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
    fn eval(&self, _t: f64, ki: &BodyKin, kj: &BodyKin, out: &mut Vec<Equation>) {
        let a = self.i.axis;
        let h = (self.reference_i - a * a.dot(&self.reference_i)).normalize();
        let g = a.cross(&h);
        let hv = Term::vector(ki, &h, 0);
        let gv = Term::vector(ki, &g, 0);
        let aj = Term::vector(kj, &self.j.axis, 1);
        let d = Term::point(kj, &self.j.point, 1).sub(&Term::point(ki, &self.i.point, 0));
        let aj_axis = self.j.axis;
        let hj = (self.reference_j - aj_axis * aj_axis.dot(&self.reference_j)).normalize();
        let gj = aj_axis.cross(&hj);
        out.push(hv.dot(&aj).into());
        out.push(gv.dot(&aj).into());
        out.push(hv.dot(&d).into());
        out.push(gv.dot(&d).into());
        out.push(hv.dot(&Term::vector(kj, &gj, 1)).into());
    }
}

/// Distance constraint `(|d_j − d_i|² − L²)/2 = 0` between two points (1 equation).
#[derive(Debug, Clone)]
pub struct Distance {
    /// Name.
    pub name: String,
    /// Point on body i.
    pub i: Attachment,
    /// Point on body j.
    pub j: Attachment,
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
    fn eval(&self, _t: f64, ki: &BodyKin, kj: &BodyKin, out: &mut Vec<Equation>) {
        let d = Term::point(kj, &self.j.point, 1).sub(&Term::point(ki, &self.i.point, 0));
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
    pub i: Attachment,
    /// Point on body j.
    pub j: Attachment,
}

impl PointOnPlane {
    fn validate_extra(&self) -> Result<(), MbdError> {
        Ok(())
    }
}

impl Constraint for PointOnPlane {
    common!(1);
    fn eval(&self, _t: f64, ki: &BodyKin, kj: &BodyKin, out: &mut Vec<Equation>) {
        let d = Term::point(kj, &self.j.point, 1).sub(&Term::point(ki, &self.i.point, 0));
        out.push(Term::vector(ki, &self.i.axis, 0).dot(&d).into());
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
    pub i: Attachment,
    /// Point on body j.
    pub j: Attachment,
}

impl PlanarRevolute {
    fn validate_extra(&self) -> Result<(), MbdError> {
        Ok(())
    }
}

impl Constraint for PlanarRevolute {
    common!(2);
    fn eval(&self, _t: f64, ki: &BodyKin, kj: &BodyKin, out: &mut Vec<Equation>) {
        let (h, g) = perpendicular_basis(&self.i.axis);
        let d = Term::point(kj, &self.j.point, 1).sub(&Term::point(ki, &self.i.point, 0));
        out.push(Term::vector(ki, &h, 0).dot(&d).into());
        out.push(Term::vector(ki, &g, 0).dot(&d).into());
    }
}

/// Prescribed angle of a rotation driver as a function of time.
#[derive(Clone)]
pub enum DriverLaw {
    /// `θ = θ₀ + ω t` \[rad\], ω \[rad/s\].
    ConstantSpeed {
        /// Initial angle \[rad\].
        theta0: f64,
        /// Angular speed \[rad/s\].
        omega: f64,
    },
    /// Smooth start to speed ω \[rad/s\] over `ramp` \[s\] (cubic speed ramp
    /// `ω(t) = ω (3τ² − 2τ³)`, τ = t/ramp), then constant speed.
    SpeedRamp {
        /// Initial angle \[rad\].
        theta0: f64,
        /// Final angular speed \[rad/s\].
        omega: f64,
        /// Ramp duration \[s\].
        ramp: f64,
    },
    /// Piecewise-linear angular speed through the points `(times[k], speeds[k])` \[s, rad/s\]
    /// (constant before the first and after the last point); θ is its exact integral.
    SpeedTable {
        /// Angle at t = 0 \[rad\].
        theta0: f64,
        /// Strictly increasing times \[s\].
        times: Vec<f64>,
        /// Angular speeds \[rad/s\].
        speeds: Vec<f64>,
    },
    /// User function `t ↦ (θ, θ̇, θ̈)` \[rad, rad/s, rad/s²\].
    Custom(Arc<dyn Fn(f64) -> (f64, f64, f64) + Send + Sync>),
}

impl std::fmt::Debug for DriverLaw {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DriverLaw::ConstantSpeed { theta0, omega } => {
                write!(f, "ConstantSpeed {{ theta0: {theta0}, omega: {omega} }}")
            }
            DriverLaw::SpeedRamp {
                theta0,
                omega,
                ramp,
            } => {
                write!(
                    f,
                    "SpeedRamp {{ theta0: {theta0}, omega: {omega}, ramp: {ramp} }}"
                )
            }
            DriverLaw::SpeedTable {
                theta0,
                times,
                speeds,
            } => write!(
                f,
                "SpeedTable {{ theta0: {theta0}, times: {times:?}, speeds: {speeds:?} }}"
            ),
            DriverLaw::Custom(_) => write!(f, "Custom(..)"),
        }
    }
}

impl DriverLaw {
    /// `(θ, θ̇, θ̈)` at time `t` \[s\].
    pub fn eval(&self, t: f64) -> (f64, f64, f64) {
        match self {
            DriverLaw::ConstantSpeed { theta0, omega } => (theta0 + omega * t, *omega, 0.0),
            DriverLaw::SpeedRamp {
                theta0,
                omega,
                ramp,
            } => {
                if *ramp <= 0.0 || t >= *ramp {
                    let r = ramp.max(0.0);
                    // angle accumulated during the ramp: ∫ ω(3τ²−2τ³) dt = ω r / 2
                    (theta0 + omega * (0.5 * r + (t - r)), *omega, 0.0)
                } else if t <= 0.0 {
                    (*theta0, 0.0, 0.0)
                } else {
                    let tau = t / ramp;
                    let th = theta0 + omega * ramp * (tau.powi(3) - 0.5 * tau.powi(4));
                    let w = omega * (3.0 * tau * tau - 2.0 * tau.powi(3));
                    let a = omega / ramp * (6.0 * tau - 6.0 * tau * tau);
                    (th, w, a)
                }
            }
            DriverLaw::SpeedTable {
                theta0,
                times,
                speeds,
            } => speed_table(*theta0, times, speeds, t),
            DriverLaw::Custom(f) => f(t),
        }
    }

    /// Checks the parameters (finite values; speed table sorted and of matching lengths).
    pub fn validate(&self, name: &str) -> Result<(), MbdError> {
        let bad = |reason: String| MbdError::InvalidInput {
            item: format!("driver \"{name}\""),
            reason,
        };
        match self {
            DriverLaw::ConstantSpeed { theta0, omega } => {
                if !(theta0.is_finite() && omega.is_finite()) {
                    return Err(bad("theta0 and omega must be finite".into()));
                }
            }
            DriverLaw::SpeedRamp {
                theta0,
                omega,
                ramp,
            } => {
                if !(theta0.is_finite() && omega.is_finite() && ramp.is_finite() && *ramp >= 0.0) {
                    return Err(bad("theta0, omega finite and ramp >= 0 required".into()));
                }
            }
            DriverLaw::SpeedTable {
                theta0,
                times,
                speeds,
            } => {
                if times.is_empty() || times.len() != speeds.len() {
                    return Err(bad(format!(
                        "speed table needs as many times ({}) as speeds ({}), at least one",
                        times.len(),
                        speeds.len()
                    )));
                }
                if !theta0.is_finite() || times.iter().chain(speeds).any(|x| !x.is_finite()) {
                    return Err(bad("non-finite value in the speed table".into()));
                }
                if let Some(k) = times.windows(2).position(|w| w[1] <= w[0]) {
                    return Err(bad(format!(
                        "times must increase strictly (entry {} = {} s)",
                        k + 1,
                        times[k + 1]
                    )));
                }
            }
            DriverLaw::Custom(_) => {}
        }
        Ok(())
    }
}

/// θ, θ̇, θ̈ of a piecewise-linear speed table (exact integral: trapezoids between breakpoints).
fn speed_table(theta0: f64, times: &[f64], speeds: &[f64], t: f64) -> (f64, f64, f64) {
    let n = times.len();
    if n == 0 || n != speeds.len() {
        return (theta0, 0.0, 0.0);
    }
    let speed = |x: f64| -> (f64, f64) {
        if x <= times[0] {
            (speeds[0], 0.0)
        } else if x >= times[n - 1] {
            (speeds[n - 1], 0.0)
        } else {
            let k = times.partition_point(|&tk| tk <= x) - 1;
            let slope = (speeds[k + 1] - speeds[k]) / (times[k + 1] - times[k]);
            (speeds[k] + slope * (x - times[k]), slope)
        }
    };
    let (a, b, sign) = if t >= 0.0 {
        (0.0, t, 1.0)
    } else {
        (t, 0.0, -1.0)
    };
    let mut acc = 0.0;
    let mut x0 = a;
    for x1 in times.iter().copied().filter(|&x| x > a && x < b).chain([b]) {
        acc += 0.5 * (speed(x0).0 + speed(x1).0) * (x1 - x0);
        x0 = x1;
    }
    let (w, alpha) = speed(t);
    (theta0 + sign * acc, w, alpha)
}

/// Rheonomic rotation driver: the angle θ(t) of body j relative to body i about the axis
/// `i.axis`, measured from `reference_i` (body i, ⊥ axis) to `reference_j` (body j).
/// Use together with a revolute joint (it fixes only the angle):
/// `Φ = cos θ_d (x_j·y_i) − sin θ_d (x_j·x_i) = 0`, i.e. `sin(θ − θ_d) = 0` (1 equation; no
/// angle wrap-around).
#[derive(Debug, Clone)]
pub struct RotationDriver {
    /// Name.
    pub name: String,
    /// Frame on body i (the axis).
    pub i: Attachment,
    /// Body j (point and axis unused).
    pub j: Attachment,
    /// Zero-angle direction on body i (⊥ `i.axis`).
    pub reference_i: Vector3<f64>,
    /// Direction on body j that is rotated by θ from `reference_i`.
    pub reference_j: Vector3<f64>,
    /// Prescribed angle.
    pub law: DriverLaw,
}

impl RotationDriver {
    fn validate_extra(&self) -> Result<(), MbdError> {
        check_reference(&self.name, "reference_i", &self.i.axis, &self.reference_i)?;
        check_vec(&self.name, "reference_j", &self.reference_j, true)?;
        self.law.validate(&self.name)
    }
}

impl Constraint for RotationDriver {
    common!(1);
    fn eval(&self, t: f64, ki: &BodyKin, kj: &BodyKin, out: &mut Vec<Equation>) {
        let a = self.i.axis;
        let xi = (self.reference_i - a * a.dot(&self.reference_i)).normalize();
        let yi = a.cross(&xi);
        let xj = Term::vector(kj, &self.reference_j, 1);
        let c1 = Term::vector(ki, &yi, 0).dot(&xj); // sin θ
        let c2 = Term::vector(ki, &xi, 0).dot(&xj); // cos θ
        let (th, thd, thdd) = self.law.eval(t);
        let (s, c) = th.sin_cos();
        let row = c1.scaled(c).add(&c2.scaled(-s));
        // Φ = C c1 − S c2; Φ_t = −θ̇ (S c1 + C c2)
        let sc = s * c1.phi + c * c2.phi;
        let scdot = s * c1.rate + c * c2.rate;
        let nu = thd * sc;
        // Φ̈ = C c̈1 − S c̈2 − 2θ̇ (S ċ1 + C ċ2) − θ̈ (S c1 + C c2) − θ̇² (C c1 − S c2)
        let gamma = -row.quad + 2.0 * thd * scdot + thdd * sc + thd * thd * row.phi;
        let mut row = row;
        row.rate -= thd * sc; // total Φ̇
        out.push(Equation { row, nu, gamma });
    }
}
