//! Rigid bodies (mass, body-frame inertia about the mass centre) and their kinematic state
//! (Lin (2.1)–(2.3), (2.25)–(2.26)).

use crate::MbdError;
use crate::kinematics::euler::{a_matrix, check_unit};
use crate::kinematics::tilde::tilde;
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

/// A vector-valued kinematic expression with its derivatives: value `x`, Jacobians with respect
/// to the velocities of the two bodies of a joint, rate `ẋ`, and the velocity-quadratic part
/// `ẍ − (∂ẋ/∂v) v̇` of its second derivative (Lin (2.3): `A ω̃'ω̃' s'`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Term {
    /// Value.
    pub x: Vector3<f64>,
    /// `∂ẋ/∂v_i` (body i).
    pub ji: Jac3x6,
    /// `∂ẋ/∂v_j` (body j).
    pub jj: Jac3x6,
    /// Rate `ẋ`.
    pub xdot: Vector3<f64>,
    /// Quadratic velocity part of `ẍ`.
    pub quad: Vector3<f64>,
}

impl Term {
    /// Body point `s'` of body `k` (side 0 = i, 1 = j): `d = r + A s'`.
    pub fn point(k: &BodyKin, s: &Vector3<f64>, side: usize) -> Self {
        let mut jac = Jac3x6::zeros();
        jac.fixed_view_mut::<3, 3>(0, 0)
            .copy_from(&Matrix3::identity());
        jac.fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&(-k.a * tilde(s)));
        let (ji, jj) = if side == 0 {
            (jac, Jac3x6::zeros())
        } else {
            (Jac3x6::zeros(), jac)
        };
        Self {
            x: k.point(s),
            ji,
            jj,
            xdot: k.point_velocity(s),
            quad: k.a * k.w.cross(&k.w.cross(s)),
        }
    }

    /// Body-fixed direction `a'` of body `k`: `a = A a'`.
    pub fn vector(k: &BodyKin, a: &Vector3<f64>, side: usize) -> Self {
        let mut jac = Jac3x6::zeros();
        jac.fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&(-k.a * tilde(a)));
        let (ji, jj) = if side == 0 {
            (jac, Jac3x6::zeros())
        } else {
            (Jac3x6::zeros(), jac)
        };
        Self {
            x: k.a * a,
            ji,
            jj,
            xdot: k.a * k.w.cross(a),
            quad: k.a * k.w.cross(&k.w.cross(a)),
        }
    }

    /// `self − o`.
    pub fn sub(&self, o: &Term) -> Term {
        Term {
            x: self.x - o.x,
            ji: self.ji - o.ji,
            jj: self.jj - o.jj,
            xdot: self.xdot - o.xdot,
            quad: self.quad - o.quad,
        }
    }

    /// Row `k` of the term as a scalar constraint row.
    pub fn component(&self, k: usize) -> Row {
        let mut di = [0.0; 6];
        let mut dj = [0.0; 6];
        for c in 0..6 {
            di[c] = self.ji[(k, c)];
            dj[c] = self.jj[(k, c)];
        }
        Row {
            phi: self.x[k],
            di,
            dj,
            rate: self.xdot[k],
            quad: self.quad[k],
        }
    }

    /// Scalar product `self · o` as a constraint row (Nikravesh's dot-1/dot-2 constraints).
    pub fn dot(&self, o: &Term) -> Row {
        let gi = self.ji.transpose() * o.x + o.ji.transpose() * self.x;
        let gj = self.jj.transpose() * o.x + o.jj.transpose() * self.x;
        Row {
            phi: self.x.dot(&o.x),
            di: gi.into(),
            dj: gj.into(),
            rate: self.xdot.dot(&o.x) + self.x.dot(&o.xdot),
            quad: self.quad.dot(&o.x) + self.x.dot(&o.quad) + 2.0 * self.xdot.dot(&o.xdot),
        }
    }
}

/// One scalar constraint equation: residual, Jacobian blocks (w.r.t. `(ṙ, ω')` of bodies i
/// and j), rate `Φ̇` at the current velocities (scleronomic part) and the velocity-quadratic part
/// of `Φ̈` (so that `γ = −quad` for a scleronomic row).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    /// Residual `Φ`.
    pub phi: f64,
    /// `∂Φ̇/∂v_i`.
    pub di: [f64; 6],
    /// `∂Φ̇/∂v_j`.
    pub dj: [f64; 6],
    /// `Φ̇ = D v` at the current velocities.
    pub rate: f64,
    /// Velocity-quadratic part of `Φ̈`.
    pub quad: f64,
}

impl Row {
    /// `c · self` (linear combination helper for drivers).
    pub fn scaled(&self, c: f64) -> Row {
        let mut r = *self;
        r.phi *= c;
        r.rate *= c;
        r.quad *= c;
        r.di.iter_mut().for_each(|x| *x *= c);
        r.dj.iter_mut().for_each(|x| *x *= c);
        r
    }

    /// `self + o`.
    pub fn add(&self, o: &Row) -> Row {
        let mut r = *self;
        r.phi += o.phi;
        r.rate += o.rate;
        r.quad += o.quad;
        for k in 0..6 {
            r.di[k] += o.di[k];
            r.dj[k] += o.dj[k];
        }
        r
    }
}
