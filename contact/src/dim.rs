//! The dimension of a contact problem: what differs between planar (`D = 2`) and spatial
//! (`D = 3`) contact, behind one small trait, so that the point contact
//! ([`crate::point_contact`]), the distributed contact ([`crate::distributed`]) and the
//! unilateral rows ([`crate::unilateral_row`]) are written once for both.
//!
//! Only three things depend on the dimension:
//!
//! * the tangent basis `T` of the contact plane: in the plane the one tangent `t = Ĩ n`
//!   (Kerkkänen (3.6)); in space `t₁ = P t_ref/|P t_ref|` (the surface's reference tangent
//!   projected on the tangent plane, `P = I − n nᵀ`) and `t₂ = n × t₁`;
//! * the friction law's slip argument in that basis: the scalar `v_t = tᵀw` in the plane
//!   ([`FrictionLaw::friction`]), the 2-vector `v_t = Tᵀw` in space
//!   ([`FrictionLaw::friction_tangent`]);
//! * the moment of a force: a scalar (the counter-clockwise torque) in the plane, a vector in
//!   space.

use crate::friction::{FrictionForce, FrictionLaw, TangentFriction};
use crate::spatial::geometry::perpendicular;
use nalgebra::{Matrix3x2, SMatrix, SVector, Vector2, Vector3};
use std::fmt::Debug;
use std::ops::{Add, AddAssign, Mul, Neg, SubAssign};

/// The dimension `D` of a contact problem (2 or 3) as a type, [`Dim<2>`] or [`Dim<3>`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Dim<const D: usize>;

/// The tangential friction force of a contact in world components, with its derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentialForce<const D: usize> {
    /// Force `T f_t` \[N or N/m\].
    pub force: SVector<f64, D>,
    /// `T (∂f_t/∂v_t) Tᵀ`: the derivative with respect to the relative velocity within the
    /// tangent plane.
    pub d_slip: SMatrix<f64, D, D>,
    /// `T ∂f_t/∂f_n`.
    pub d_normal: SVector<f64, D>,
}

/// What the contact machinery needs to know about the dimension `D` (implemented by [`Dim<2>`]
/// and [`Dim<3>`]).
pub trait ContactDim<const D: usize> {
    /// Slip velocity (and tangential force) in the tangent basis: `f64` along `t` in the plane,
    /// [`Vector2`] in `(t₁, t₂)` in space.
    type Slip: Copy + Debug + PartialEq + Send + Sync + 'static;
    /// The friction law's output in the tangent basis: [`FrictionForce`] in the plane,
    /// [`TangentFriction`] in space.
    type Friction: Copy + Debug + PartialEq + Send + Sync + 'static;
    /// Tangent basis `T` (`D × (D − 1)`): [`Vector2`] `t` in the plane, [`Matrix3x2`] in space.
    type Basis: Copy + Debug + PartialEq + Send + Sync + 'static;
    /// Moment of a force about a point: `f64` (counter-clockwise torque) in the plane,
    /// [`Vector3`] in space.
    type Moment: Copy
        + Debug
        + PartialEq
        + Default
        + Send
        + Sync
        + Add<Output = Self::Moment>
        + AddAssign
        + SubAssign
        + Neg<Output = Self::Moment>
        + Mul<f64, Output = Self::Moment>
        + 'static;

    /// Tangent basis at a surface point with unit normal `normal` and reference tangent
    /// `tangent` ([`crate::SurfacePoint::normal`], [`crate::SurfacePoint::tangent`]).
    fn basis(normal: &SVector<f64, D>, tangent: &SVector<f64, D>) -> Self::Basis;

    /// The friction law at the relative velocity `w = ṙ − u_s` and normal force `normal`:
    /// the slip `v_t = Tᵀw` (the normal part of `w` has no tangential component), the law's
    /// output and the force `T f_t(v_t, f_n)` with its derivatives in world components.
    fn friction<FL: FrictionLaw + ?Sized>(
        law: &FL, basis: &Self::Basis, w: &SVector<f64, D>, normal: f64,
    ) -> (Self::Slip, Self::Friction, TangentialForce<D>);

    /// [`ContactDim::friction`] without derivatives: the slip `v_t = Tᵀw`, the friction force
    /// `f_t` in the tangent basis and `T f_t` in world components.
    fn friction_value<FL: FrictionLaw + ?Sized>(
        law: &FL, basis: &Self::Basis, w: &SVector<f64, D>, normal: f64,
    ) -> (Self::Slip, Self::Slip, SVector<f64, D>);

    /// The tangential force of a friction output in the tangent basis (for records).
    fn friction_force(friction: &Self::Friction) -> Self::Slip;

    /// Moment `a × f` of the force `f` at the arm `a`.
    fn cross(a: &SVector<f64, D>, f: &SVector<f64, D>) -> Self::Moment;
}

/// Slip velocity in the tangent basis of a `D`-dimensional contact.
pub type Slip<const D: usize> = <Dim<D> as ContactDim<D>>::Slip;
/// Friction-law output of a `D`-dimensional contact.
pub type Friction<const D: usize> = <Dim<D> as ContactDim<D>>::Friction;
/// Tangent basis of a `D`-dimensional contact.
pub type Basis<const D: usize> = <Dim<D> as ContactDim<D>>::Basis;
/// Moment of a force in `D` dimensions.
pub type Moment<const D: usize> = <Dim<D> as ContactDim<D>>::Moment;

/// 90° rotation `Ĩ = [[0, −1], [1, 0]]`, Kerkkänen (3.6).
#[inline]
pub fn rot90(v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-v[1], v[0])
}

impl ContactDim<2> for Dim<2> {
    type Slip = f64;
    type Friction = FrictionForce;
    type Basis = Vector2<f64>;
    type Moment = f64;

    /// `t = Ĩ n`, Kerkkänen (3.6).
    #[inline]
    fn basis(normal: &Vector2<f64>, _tangent: &Vector2<f64>) -> Vector2<f64> {
        rot90(*normal)
    }

    /// `v_t = tᵀw`, `f = f_t(v_t, f_n) t`, Kerkkänen (3.23)–(3.25).
    #[inline]
    fn friction<FL: FrictionLaw + ?Sized>(
        law: &FL, t: &Vector2<f64>, w: &Vector2<f64>, normal: f64,
    ) -> (f64, FrictionForce, TangentialForce<2>) {
        let slip = t[0] * w[0] + t[1] * w[1];
        let ff = law.friction(slip, normal);
        let tf = TangentialForce {
            force: t * ff.force,
            d_slip: t * t.transpose() * ff.d_slip,
            d_normal: t * ff.d_normal,
        };
        (slip, ff, tf)
    }

    #[inline]
    fn friction_value<FL: FrictionLaw + ?Sized>(
        law: &FL, t: &Vector2<f64>, w: &Vector2<f64>, normal: f64,
    ) -> (f64, f64, Vector2<f64>) {
        let slip = t[0] * w[0] + t[1] * w[1];
        let f = law.friction(slip, normal).force;
        (slip, f, t * f)
    }

    #[inline]
    fn friction_force(friction: &FrictionForce) -> f64 {
        friction.force
    }

    #[inline]
    fn cross(a: &Vector2<f64>, f: &Vector2<f64>) -> f64 {
        a[0] * f[1] - a[1] * f[0]
    }
}

impl ContactDim<3> for Dim<3> {
    type Slip = Vector2<f64>;
    type Friction = TangentFriction;
    type Basis = Matrix3x2<f64>;
    type Moment = Vector3<f64>;

    /// `t₁ = P t_ref/|P t_ref|`, `t₂ = n × t₁` (any unit vector normal to `n` when the
    /// reference tangent is along `n`), with `P t_ref = t_ref − n (nᵀ t_ref)`.
    #[inline]
    fn basis(normal: &Vector3<f64>, tangent: &Vector3<f64>) -> Matrix3x2<f64> {
        let n = *normal;
        let t1 = (tangent - n * n.dot(tangent))
            .try_normalize(1e-300)
            .unwrap_or_else(|| perpendicular(&n));
        let t2 = n.cross(&t1);
        Matrix3x2::from_columns(&[t1, t2])
    }

    /// `v_t = Tᵀw`, `f = T f_t(v_t, f_n)` with the isotropic spatial law
    /// ([`FrictionLaw::friction_tangent`]).
    fn friction<FL: FrictionLaw + ?Sized>(
        law: &FL, tb: &Matrix3x2<f64>, w: &Vector3<f64>, normal: f64,
    ) -> (Vector2<f64>, TangentFriction, TangentialForce<3>) {
        let slip = tb.transpose() * w;
        let ff = law.friction_tangent(slip, normal);
        let tf = TangentialForce {
            force: tb * ff.force,
            d_slip: tb * ff.d_slip * tb.transpose(),
            d_normal: tb * ff.d_normal,
        };
        (slip, ff, tf)
    }

    #[inline]
    fn friction_value<FL: FrictionLaw + ?Sized>(
        law: &FL, tb: &Matrix3x2<f64>, w: &Vector3<f64>, normal: f64,
    ) -> (Vector2<f64>, Vector2<f64>, Vector3<f64>) {
        let slip = tb.transpose() * w;
        let f = law.friction_tangent_force(slip, normal);
        (slip, f, tb * f)
    }

    #[inline]
    fn friction_force(friction: &TangentFriction) -> Vector2<f64> {
        friction.force
    }

    #[inline]
    fn cross(a: &Vector3<f64>, f: &Vector3<f64>) -> Vector3<f64> {
        a.cross(f)
    }
}
