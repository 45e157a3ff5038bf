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
use crate::geometry::SurfaceValues;
use crate::normal::NormalLaw;
use crate::point::point_force_at;
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

    /// The slip velocity `v_t = Tᵀw` \[m/s\] in the tangent basis `basis` of the relative
    /// velocity `w = ṙ − u_s` (Kerkkänen (3.24)–(3.25) in the plane: `v_t = tᵀw`).
    fn slip(basis: &Self::Basis, w: &SVector<f64, D>) -> Self::Slip;

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

    /// The force `f_q` of [`crate::point_force_at`] at every point `q` of a batch in contact
    /// (`gap ≤ 0`), zero at the separated points: the surface `values` and the velocities
    /// `velocity` of the points in structure-of-arrays form, `force` sized like them, `work` a
    /// scratch buffer. In space one loop over the points forms `w = ṙ − u_s`, `d = −g`,
    /// `ḋ = −nᵀw`, the basis `t₁ = P t_ref/|P t_ref|`, `t₂ = n × t₁` and the slip `Tᵀw` (the
    /// operations of [`ContactDim::basis`] and [`ContactDim::friction_value`]), the laws run as
    /// batches ([`NormalLaw::normal_forces`], [`FrictionLaw::friction_tangent_forces`]) and a
    /// last loop forms `f = f_n n + T f_t`, all compiled for the machine's vector width
    /// ([`mbd_core::simd`]); in the plane the points are taken one at a time.
    fn batch_forces<NL: NormalLaw + ?Sized, FL: FrictionLaw + ?Sized>(
        normal: &NL, friction: &FL, values: &SurfaceValues<D>, velocity: &[Vec<f64>; D],
        work: &mut Vec<f64>, force: &mut [Vec<f64>; D],
    );

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

    /// `v_t = tᵀw`, Kerkkänen (3.24)–(3.25).
    #[inline]
    fn slip(t: &Vector2<f64>, w: &Vector2<f64>) -> f64 {
        t[0] * w[0] + t[1] * w[1]
    }

    /// `v_t = tᵀw`, `f = f_t(v_t, f_n) t`, Kerkkänen (3.23)–(3.25).
    #[inline]
    fn friction<FL: FrictionLaw + ?Sized>(
        law: &FL, t: &Vector2<f64>, w: &Vector2<f64>, normal: f64,
    ) -> (f64, FrictionForce, TangentialForce<2>) {
        let slip = Self::slip(t, w);
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
        let slip = Self::slip(t, w);
        let f = law.friction(slip, normal).force;
        (slip, f, t * f)
    }

    fn batch_forces<NL: NormalLaw + ?Sized, FL: FrictionLaw + ?Sized>(
        normal: &NL, friction: &FL, values: &SurfaceValues<2>, velocity: &[Vec<f64>; 2],
        _work: &mut Vec<f64>, force: &mut [Vec<f64>; 2],
    ) {
        for (q, &gap) in values.gap.iter().enumerate() {
            let f = if gap > 0.0 {
                Vector2::zeros()
            } else {
                let col = |a: &[Vec<f64>; 2]| Vector2::new(a[0][q], a[1][q]);
                let (n, t, us) = (
                    col(&values.normal),
                    col(&values.tangent),
                    col(&values.surface_velocity),
                );
                point_force_at((gap, &n, &t, &us), normal, friction, &col(velocity)).force
            };
            force[0][q] = f[0];
            force[1][q] = f[1];
        }
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

    /// `v_t = Tᵀw`.
    #[inline]
    fn slip(tb: &Matrix3x2<f64>, w: &Vector3<f64>) -> Vector2<f64> {
        tb.transpose() * w
    }

    /// `v_t = Tᵀw`, `f = T f_t(v_t, f_n)` with the isotropic spatial law
    /// ([`FrictionLaw::friction_tangent`]).
    fn friction<FL: FrictionLaw + ?Sized>(
        law: &FL, tb: &Matrix3x2<f64>, w: &Vector3<f64>, normal: f64,
    ) -> (Vector2<f64>, TangentFriction, TangentialForce<3>) {
        let slip = Self::slip(tb, w);
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
        let slip = Self::slip(tb, w);
        let f = law.friction_tangent_force(slip, normal);
        (slip, f, tb * f)
    }

    fn batch_forces<NL: NormalLaw + ?Sized, FL: FrictionLaw + ?Sized>(
        normal: &NL, friction: &FL, values: &SurfaceValues<3>, velocity: &[Vec<f64>; 3],
        work: &mut Vec<f64>, force: &mut [Vec<f64>; 3],
    ) {
        let n = values.gap.len();
        work.clear();
        work.resize(WORK_ARRAYS * n, 0.0);
        for f in force.iter_mut() {
            f.resize(n, 0.0);
        }
        let degenerate = mbd_core::simd::dispatch(SpatialForces {
            normal,
            friction,
            values,
            velocity,
            work,
            force,
        });
        if degenerate {
            // a reference tangent along the normal: the basis of `ContactDim::basis`
            for (q, &gap) in values.gap.iter().enumerate() {
                let len = work[BASIS_NORM * n + q];
                if gap <= 0.0 && len <= 1e-300 {
                    let col = |a: &[Vec<f64>; 3]| Vector3::new(a[0][q], a[1][q], a[2][q]);
                    let f = point_force_at(
                        (
                            gap,
                            &col(&values.normal),
                            &col(&values.tangent),
                            &col(&values.surface_velocity),
                        ),
                        normal,
                        friction,
                        &col(velocity),
                    )
                    .force;
                    for i in 0..3 {
                        force[i][q] = f[i];
                    }
                }
            }
        }
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

/// Arrays of `n` values in the work buffer of [`Dim<3>`]'s [`ContactDim::batch_forces`], in
/// this order: `d`, `ḋ`, `f_n`, the slip `(v₁, v₂)`, the friction `(f₁, f₂)`, `t₁`, `t₂` (3
/// each) and `|P t_ref|` (the last, at [`BASIS_NORM`] · n).
const WORK_ARRAYS: usize = 14;
/// Offset (× n) of `|P t_ref|` in the work buffer.
const BASIS_NORM: usize = 13;

/// [`Dim<3>`]'s [`ContactDim::batch_forces`] as a [`mbd_core::simd::Kernel`]; returns whether
/// a point in contact has a reference tangent along its normal (`|P t_ref| ≤ 10⁻³⁰⁰`, left to
/// the caller).
struct SpatialForces<'a, NL: ?Sized, FL: ?Sized> {
    normal: &'a NL,
    friction: &'a FL,
    values: &'a SurfaceValues<3>,
    velocity: &'a [Vec<f64>; 3],
    work: &'a mut [f64],
    force: &'a mut [Vec<f64>; 3],
}

impl<NL: NormalLaw + ?Sized, FL: FrictionLaw + ?Sized> mbd_core::simd::Kernel
    for SpatialForces<'_, NL, FL>
{
    type Output = bool;
    #[inline(always)]
    fn run(self) -> bool {
        let vals = self.values;
        let n = vals.gap.len();
        let (work, force) = (self.work, self.force);
        let (pen_rate, rest) = work.split_at_mut(2 * n);
        let (pen, rate) = pen_rate.split_at_mut(n);
        let (fnorm, rest) = rest.split_at_mut(n);
        let (v1, rest) = rest.split_at_mut(n);
        let (v2, rest) = rest.split_at_mut(n);
        let (f1, rest) = rest.split_at_mut(n);
        let (f2, rest) = rest.split_at_mut(n);
        let (t1, rest) = rest.split_at_mut(3 * n);
        let (t2, len_out) = rest.split_at_mut(3 * n);
        let (t1x, t1) = t1.split_at_mut(n);
        let (t1y, t1z) = t1.split_at_mut(n);
        let (t2x, t2) = t2.split_at_mut(n);
        let (t2y, t2z) = t2.split_at_mut(n);
        let gap = &vals.gap[..n];
        let [nx, ny, nz] = &vals.normal;
        let [tx, ty, tz] = &vals.tangent;
        let [ux, uy, uz] = &vals.surface_velocity;
        let [vx, vy, vz] = self.velocity;
        let (nx, ny, nz) = (&nx[..n], &ny[..n], &nz[..n]);
        let (tx, ty, tz) = (&tx[..n], &ty[..n], &tz[..n]);
        let (ux, uy, uz) = (&ux[..n], &uy[..n], &uz[..n]);
        let (vx, vy, vz) = (&vx[..n], &vy[..n], &vz[..n]);
        let mut degenerate = false;
        // groups of LANES points through local arrays: the 11 output arrays are slices of one
        // buffer that the vectoriser cannot prove apart, local arrays it can
        const LANES: usize = 4;
        let mut start = 0;
        while start < n {
            let len = (n - start).min(LANES);
            let lane = |a: &[f64]| crate::lanes::gather::<LANES>(a, start, len);
            let (g, nx, ny, nz) = (lane(gap), lane(nx), lane(ny), lane(nz));
            let (tx, ty, tz) = (lane(tx), lane(ty), lane(tz));
            let (ux, uy, uz) = (lane(ux), lane(uy), lane(uz));
            let (vx, vy, vz) = (lane(vx), lane(vy), lane(vz));
            let mut o = [[0.0; LANES]; 11];
            let mut deg = [false; LANES];
            for q in 0..LANES {
                let (wx, wy, wz) = (vx[q] - ux[q], vy[q] - uy[q], vz[q] - uz[q]);
                o[0][q] = -g[q];
                o[1][q] = -(nx[q] * wx + ny[q] * wy + nz[q] * wz);
                // t₁ = P t_ref/|P t_ref| (`try_normalize`), t₂ = n × t₁
                let nt = nx[q] * tx[q] + ny[q] * ty[q] + nz[q] * tz[q];
                let (px, py, pz) = (tx[q] - nx[q] * nt, ty[q] - ny[q] * nt, tz[q] - nz[q] * nt);
                let l = (px * px + py * py + pz * pz).sqrt();
                o[10][q] = l;
                deg[q] = g[q] <= 0.0 && l <= 1e-300;
                let (ax, ay, az) = (px / l, py / l, pz / l);
                let (bx, by, bz) = (
                    ny[q] * az - nz[q] * ay,
                    nz[q] * ax - nx[q] * az,
                    nx[q] * ay - ny[q] * ax,
                );
                (o[4][q], o[5][q], o[6][q]) = (ax, ay, az);
                (o[7][q], o[8][q], o[9][q]) = (bx, by, bz);
                o[2][q] = ax * wx + ay * wy + az * wz;
                o[3][q] = bx * wx + by * wy + bz * wz;
            }
            degenerate |= deg[..len].iter().any(|&d| d);
            let r = start..start + len;
            let outs: [&mut [f64]; 11] = [
                &mut pen[r.clone()],
                &mut rate[r.clone()],
                &mut v1[r.clone()],
                &mut v2[r.clone()],
                &mut t1x[r.clone()],
                &mut t1y[r.clone()],
                &mut t1z[r.clone()],
                &mut t2x[r.clone()],
                &mut t2y[r.clone()],
                &mut t2z[r.clone()],
                &mut len_out[r],
            ];
            for (dst, src) in outs.into_iter().zip(&o) {
                dst.copy_from_slice(&src[..len]);
            }
            start += len;
        }
        self.normal.normal_forces(pen, rate, fnorm);
        self.friction
            .friction_tangent_forces([v1, v2], fnorm, [&mut *f1, &mut *f2]);
        let [fx, fy, fz] = force;
        let (fx, fy, fz) = (&mut fx[..n], &mut fy[..n], &mut fz[..n]);
        // f = f_n n + T f_t, in groups of LANES points through local arrays as above
        let mut start = 0;
        while start < n {
            let len = (n - start).min(LANES);
            let lane = |a: &[f64]| crate::lanes::gather::<LANES>(a, start, len);
            let (g, a, b, c) = (lane(gap), lane(f1), lane(f2), lane(fnorm));
            let (nx, ny, nz) = (lane(nx), lane(ny), lane(nz));
            let (t1x, t1y, t1z) = (lane(t1x), lane(t1y), lane(t1z));
            let (t2x, t2y, t2z) = (lane(t2x), lane(t2y), lane(t2z));
            let mut o = [[0.0; LANES]; 3];
            for q in 0..LANES {
                let contact = g[q] <= 0.0;
                let (a, b, c) = (a[q], b[q], c[q]);
                let x = nx[q] * c + (t1x[q] * a + t2x[q] * b);
                let y = ny[q] * c + (t1y[q] * a + t2y[q] * b);
                let z = nz[q] * c + (t1z[q] * a + t2z[q] * b);
                o[0][q] = if contact { x } else { 0.0 };
                o[1][q] = if contact { y } else { 0.0 };
                o[2][q] = if contact { z } else { 0.0 };
            }
            fx[start..start + len].copy_from_slice(&o[0][..len]);
            fy[start..start + len].copy_from_slice(&o[1][..len]);
            fz[start..start + len].copy_from_slice(&o[2][..len]);
            start += len;
        }
        degenerate
    }
}
