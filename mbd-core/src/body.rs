//! Rigid bodies (mass, body-frame inertia about the mass centre) and their kinematic state
//! (Lin (2.1)–(2.3), (2.25)–(2.26)).

use crate::MbdError;
use crate::kinematics::euler::{
    a_matrix, check_unit, compose_local_rotation, pdot_from_omega_local,
};
use crate::kinematics::tilde::{get3, get4, put4};
use nalgebra::{Matrix3, SMatrix, Vector3, Vector4};

/// Index of a body in a [`crate::multibody::MultibodySystem`]; `None` in joint definitions
/// means the ground (inertial frame).
pub type BodyId = usize;

/// A rigid body: mass \[kg\] and inertia tensor about the mass centre in the body frame \[kg·m²\].
#[derive(Debug, Clone, PartialEq)]
pub struct RigidBody {
    /// Name used in messages and output.
    pub name: String,
    /// Mass \[kg\].
    pub mass: f64,
    /// Body-frame inertia about the mass centre `J'` \[kg·m²\] (Lin (2.26)).
    pub inertia: Matrix3<f64>,
}

impl RigidBody {
    /// Validated body: positive finite mass, symmetric positive definite inertia satisfying the
    /// triangle inequalities of the principal moments.
    pub fn new(name: &str, mass: f64, inertia: Matrix3<f64>) -> Result<Self, MbdError> {
        let bad = |field: &str, reason: String| MbdError::InvalidInput {
            item: format!("body \"{name}\": {field}"),
            reason,
        };
        if !(mass.is_finite() && mass > 0.0) {
            return Err(bad(
                "mass",
                format!("must be positive and finite, got {mass} kg"),
            ));
        }
        if !inertia.iter().all(|x| x.is_finite()) {
            return Err(bad("inertia", "non-finite entry".into()));
        }
        let asym = (inertia - inertia.transpose()).abs().max();
        if asym > 1e-12 * inertia.abs().max().max(1e-300) {
            return Err(bad("inertia", "matrix is not symmetric".into()));
        }
        let ev = inertia.symmetric_eigenvalues();
        let (mut a, mut b, mut c) = (ev[0], ev[1], ev[2]);
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        if b > c {
            std::mem::swap(&mut b, &mut c);
        }
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        if a <= 0.0 {
            return Err(bad(
                "inertia",
                format!("must be positive definite, principal moments {a:e}, {b:e}, {c:e} kg·m²"),
            ));
        }
        if c > (a + b) * (1.0 + 1e-9) {
            return Err(bad(
                "inertia",
                format!("principal moments {a:e}, {b:e}, {c:e} violate the triangle inequality"),
            ));
        }
        Ok(Self {
            name: name.into(),
            mass,
            inertia,
        })
    }

    /// Body with a diagonal inertia `diag(jx, jy, jz)`.
    pub fn with_principal(name: &str, mass: f64, j: [f64; 3]) -> Result<Self, MbdError> {
        Self::new(name, mass, Matrix3::from_diagonal(&Vector3::from(j)))
    }
}

/// State of one body: position of the mass centre `r` \[m\], Euler parameters `p`, velocity `ṙ`
/// \[m/s\] and body-frame angular velocity `ω'` \[rad/s\].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyState {
    /// Mass-centre position \[m\].
    pub r: Vector3<f64>,
    /// Euler parameters (unit).
    pub p: Vector4<f64>,
    /// Mass-centre velocity \[m/s\].
    pub rdot: Vector3<f64>,
    /// Body-frame angular velocity `ω'` \[rad/s\].
    pub omega_local: Vector3<f64>,
}

impl BodyState {
    /// Body at `r` with orientation `p`, at rest.
    pub fn at_rest(r: Vector3<f64>, p: Vector4<f64>) -> Self {
        Self {
            r,
            p,
            rdot: Vector3::zeros(),
            omega_local: Vector3::zeros(),
        }
    }

    /// Validates finiteness and `pᵀp = 1` (Lin (2.8)); `name` labels the error.
    pub fn check(&self, name: &str) -> Result<(), MbdError> {
        check_unit(&self.p, &format!("body \"{name}\""))?;
        for (what, v) in [
            ("r", &self.r),
            ("rdot", &self.rdot),
            ("omega", &self.omega_local),
        ] {
            if !v.iter().all(|x| x.is_finite()) {
                return Err(MbdError::InvalidInput {
                    item: format!("body \"{name}\": {what}"),
                    reason: "non-finite value".into(),
                });
            }
        }
        Ok(())
    }
}

/// Derivative block of a body vector with respect to the body velocities `(ṙ, ω')`.
pub type Jac3x6 = SMatrix<f64, 3, 6>;

/// Kinematic quantities of one body used by constraints and force elements.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyKin {
    /// Mass-centre position \[m\].
    pub r: Vector3<f64>,
    /// Euler parameters.
    pub p: Vector4<f64>,
    /// Rotation matrix `A(p)` (Lin (2.7)).
    pub a: Matrix3<f64>,
    /// Mass-centre velocity \[m/s\].
    pub rdot: Vector3<f64>,
    /// Body-frame angular velocity ω' \[rad/s\].
    pub w: Vector3<f64>,
}

impl BodyKin {
    /// The ground (identity pose, at rest).
    pub fn ground() -> Self {
        Self {
            r: Vector3::zeros(),
            p: Vector4::new(1.0, 0.0, 0.0, 0.0),
            a: Matrix3::identity(),
            rdot: Vector3::zeros(),
            w: Vector3::zeros(),
        }
    }

    /// Kinematics from position, Euler parameters and velocities.
    pub fn new(r: Vector3<f64>, p: Vector4<f64>, rdot: Vector3<f64>, w: Vector3<f64>) -> Self {
        Self {
            r,
            p,
            a: a_matrix(&p),
            rdot,
            w,
        }
    }

    /// Global angular velocity `ω = A ω'` (Lin (2.16)).
    pub fn omega_global(&self) -> Vector3<f64> {
        self.a * self.w
    }

    /// Global position of body point `s'` (Lin (2.1)): `d = r + A s'`.
    pub fn point(&self, s: &Vector3<f64>) -> Vector3<f64> {
        self.r + self.a * s
    }

    /// Velocity of body point `s'`: `ḋ = ṙ − A s̃' ω'` (Lin (2.2) in body-frame ω').
    pub fn point_velocity(&self, s: &Vector3<f64>) -> Vector3<f64> {
        self.rdot + self.a * self.w.cross(s)
    }
}

/// Rate of the frame coordinates `(r, p)` at `q[oq..oq + 7]` from the velocities `(ṙ, ω')` at
/// `v[ov..ov + 6]`: `ṙ` and `ṗ = ½ Lᵀ ω'` (Lin (2.14)), written to `qdot[oq..oq + 7]`.
pub fn frame_position_rate(q: &[f64], v: &[f64], oq: usize, ov: usize, qdot: &mut [f64]) {
    qdot[oq..oq + 3].copy_from_slice(&v[ov..ov + 3]);
    let pd = pdot_from_omega_local(&get4(q, oq + 3), &get3(v, ov + 3));
    put4(qdot, oq + 3, &pd);
}

/// Normalises the Euler parameters at `q[oq + 3..oq + 7]` (left alone if zero or not finite).
pub fn frame_normalize(q: &mut [f64], oq: usize) {
    let p = get4(q, oq + 3);
    let n = p.norm();
    if n > 0.0 && n.is_finite() {
        put4(q, oq + 3, &(p / n));
    }
}

/// Frame update `r + Δr`, `p ⊗ exp(Δθ'/2)` (exact rotation update, Lie-group generalized-α)
/// of `q[oq..oq + 7]` by `dq[ov..ov + 6]`, written to `q_new[oq..oq + 7]`.
pub fn frame_integrate(q: &[f64], dq: &[f64], oq: usize, ov: usize, q_new: &mut [f64]) {
    for c in 0..3 {
        q_new[oq + c] = q[oq + c] + dq[ov + c];
    }
    let p = compose_local_rotation(&get4(q, oq + 3), &get3(dq, ov + 3));
    put4(q_new, oq + 3, &p);
}
