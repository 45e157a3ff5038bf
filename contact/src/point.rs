//! Contact of one material point with an obstacle in the plane or in space: penetration and its
//! rate, slip, normal and friction force, and their exact derivatives with respect to the
//! point's position and velocity and to the obstacle's angular velocity (the ingredients of
//! Kerkkänen (3.20)–(3.26), and their spatial form).

use crate::dim::{Basis, ContactDim, Dim, Friction, Slip, TangentialForce};
use crate::friction::FrictionLaw;
use crate::geometry::{Surface, SurfacePoint};
use crate::normal::{NormalForce, NormalLaw};
use nalgebra::{Point, SMatrix, SVector};

/// Contact state and force of one point in contact (penetration `d ≥ 0`) in `D` dimensions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointContact<const D: usize>
where
    Dim<D>: ContactDim<D>,
{
    /// Closest-point data.
    pub surface: SurfacePoint<D>,
    /// Tangent basis: `t = Ĩ n` in the plane (Kerkkänen (3.6)); `T = [t₁ t₂]` in space,
    /// `t₁ = P t_ref/|P t_ref|`, `t₂ = n × t₁`.
    pub tangents: Basis<D>,
    /// Penetration `d = −gap ≥ 0` \[m\], Kerkkänen (3.21).
    pub penetration: f64,
    /// Penetration rate `ḋ = −nᵀ(ṙ − u_s)` \[m/s\].
    pub penetration_rate: f64,
    /// Slip velocity `v_t = Tᵀ(ṙ − u_s)` \[m/s\] (in the plane the scalar `tᵀ(ṙ − u_s)`,
    /// Kerkkänen (3.24)–(3.25)).
    pub slip: Slip<D>,
    /// Normal law output.
    pub normal: NormalForce,
    /// Friction law output (in the tangent basis).
    pub friction: Friction<D>,
    /// Force on the body `f = f_n n + T f_t` (per unit length or area for distributed laws).
    pub force: SVector<f64, D>,
    /// `∂f/∂r`.
    pub df_dp: SMatrix<f64, D, D>,
    /// `∂f/∂ṙ`.
    pub df_dv: SMatrix<f64, D, D>,
    /// `∂f/∂ω` of the obstacle.
    pub df_domega: SVector<f64, D>,
}

impl<const D: usize> PointContact<D>
where
    Dim<D>: ContactDim<D>,
{
    /// The force part of the contact (what [`point_force`] returns for the same point).
    pub fn value(&self) -> PointForce<D> {
        PointForce {
            penetration: self.penetration,
            penetration_rate: self.penetration_rate,
            slip: self.slip,
            normal_force: self.normal.force,
            friction_force: <Dim<D>>::friction_force(&self.friction),
            force: self.force,
        }
    }
}

/// Contact of one point in the plane.
pub type PointContact2 = PointContact<2>;
/// Contact of one point in space.
pub type PointContact3 = PointContact<3>;

/// Contact of the point at `p` \[m\] moving with `v` \[m/s\] against `surface`, in the plane
/// (`D = 2`) or in space (`D = 3`). Returns `None` when the point is separated (`gap > 0`): no
/// force (Kerkkänen (3.20)).
///
/// With `w = ṙ − u_s`, its tangential part `W = P w` (`P = I − n nᵀ`), the normal force
/// `f_n(d, ḋ)` (`d = −g`, `ḋ = −nᵀw`) and the friction force `T f_t(Tᵀw, f_n)` of the
/// dimension's tangent basis `T` ([`ContactDim`]), the force is `f = f_n n + T f_t`. Its
/// derivatives use `∂(T f_t)/∂W = T (∂f_t/∂v_t) Tᵀ + (f_tᵀW/|W|²) n nᵀ` — exact for isotropic
/// laws in space (`T f_t(TᵀW)` does not depend on the choice of the basis), and in the plane
/// the derivative of `t f_t(tᵀw)` for any law (with `∂t/∂p = Ĩ ∂n/∂p`, the rotation of the
/// basis with the normal is the `n nᵀ` term) — and
/// `∂W/∂p = −(∂n/∂p)(nᵀw) − n wᵀ(∂n/∂p) − P ∂u_s/∂p`, `∂W/∂ṙ = P`, `∂W/∂ω = −P ∂u_s/∂ω`.
pub fn point_contact<const D: usize, S, NL, FL>(
    surface: &S, normal_law: &NL, friction_law: &FL, p: &Point<f64, D>, v: &SVector<f64, D>,
) -> Option<PointContact<D>>
where
    Dim<D>: ContactDim<D>,
    S: Surface<D> + ?Sized,
    NL: NormalLaw + ?Sized,
    FL: FrictionLaw + ?Sized,
{
    let sp = surface.closest(p);
    if sp.gap > 0.0 {
        return None;
    }
    let n = sp.normal;
    let tangents = <Dim<D>>::basis(&sp.normal, &sp.tangent);
    let w = v - sp.surface_velocity;
    let pen = -sp.gap;
    let rate = -n.dot(&w);
    let nf = normal_law.normal(pen, rate);
    let (slip, friction, ft) = <Dim<D>>::friction(friction_law, &tangents, &w, nf.force);
    let force = n * nf.force + ft.force;
    let (df_dp, df_dv, df_domega) = point_jacobian(&sp, &nf, &ft, &w);
    Some(PointContact {
        surface: sp,
        tangents,
        penetration: pen,
        penetration_rate: rate,
        slip,
        normal: nf,
        friction,
        force,
        df_dp,
        df_dv,
        df_domega,
    })
}

/// The kinematics of [`point_contact`] without its laws: the gap `g` \[m\] (> 0 separated) and
/// the slip velocity `v_t = Tᵀ(ṙ − u_s)` \[m/s\] (Kerkkänen (3.21), (3.24)–(3.25)) of the point
/// at `p` \[m\] moving with `v` \[m/s\] against `surface`, from its
/// [`Surface::closest_value`] — also for a separated point (where `point_contact` returns
/// `None`). E.g. a model's slip velocities before and after a Newton correction, for the
/// transition-aware limit [`crate::friction::transition_limit`].
pub fn point_slip<const D: usize, S>(
    surface: &S, p: &Point<f64, D>, v: &SVector<f64, D>,
) -> (f64, Slip<D>)
where
    Dim<D>: ContactDim<D>,
    S: Surface<D> + ?Sized,
{
    let sp = surface.closest_value(p);
    let tangents = <Dim<D>>::basis(&sp.normal, &sp.tangent);
    (
        sp.gap,
        <Dim<D>>::slip(&tangents, &(v - sp.surface_velocity)),
    )
}

/// The force of one point in contact without derivatives: what a force-only evaluation (a
/// Newton residual, an output record) needs of [`point_contact`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointForce<const D: usize>
where
    Dim<D>: ContactDim<D>,
{
    /// Penetration `d = −gap ≥ 0` \[m\], Kerkkänen (3.21).
    pub penetration: f64,
    /// Penetration rate `ḋ = −nᵀ(ṙ − u_s)` \[m/s\].
    pub penetration_rate: f64,
    /// Slip velocity `v_t = Tᵀ(ṙ − u_s)` in the tangent basis \[m/s\].
    pub slip: Slip<D>,
    /// Normal force `f_n(d, ḋ)` (per unit length or area for distributed laws).
    pub normal_force: f64,
    /// Friction force `f_t(v_t, f_n)` in the tangent basis.
    pub friction_force: Slip<D>,
    /// Force on the body `f = f_n n + T f_t`.
    pub force: SVector<f64, D>,
}

/// [`point_contact`] without derivatives: the same force `f = f_n n + T f_t` from the
/// surface's [`Surface::closest_value`] ([`point_force_at`]). `None` when the point is
/// separated (Kerkkänen (3.20)).
#[inline(always)]
pub fn point_force<const D: usize, S, NL, FL>(
    surface: &S, normal_law: &NL, friction_law: &FL, p: &Point<f64, D>, v: &SVector<f64, D>,
) -> Option<PointForce<D>>
where
    Dim<D>: ContactDim<D>,
    S: Surface<D> + ?Sized,
    NL: NormalLaw + ?Sized,
    FL: FrictionLaw + ?Sized,
{
    let sp = surface.closest_value(p);
    if sp.gap > 0.0 {
        return None;
    }
    Some(point_force_at(
        (sp.gap, &sp.normal, &sp.tangent, &sp.surface_velocity),
        normal_law,
        friction_law,
        v,
    ))
}

/// The force of a point in contact moving with `v` \[m/s\] from the closest-point values
/// `(gap ≤ 0, n, t_ref, u_s)` of its surface ([`SurfacePoint`] or one entry of
/// [`crate::SurfaceValues`]): `w = v − u_s`, `d = −g`, `ḋ = −nᵀw`, `f = f_n(d, ḋ) n + T f_t(Tᵀw,
/// f_n)` with the tangent basis `T` of [`ContactDim::basis`] and the friction law's
/// [`FrictionLaw::friction_tangent_force`] (in space), none of the Jacobian terms formed.
#[inline(always)]
pub fn point_force_at<const D: usize, NL, FL>(
    (gap, n, tangent, us): (f64, &SVector<f64, D>, &SVector<f64, D>, &SVector<f64, D>),
    normal_law: &NL, friction_law: &FL, v: &SVector<f64, D>,
) -> PointForce<D>
where
    Dim<D>: ContactDim<D>,
    NL: NormalLaw + ?Sized,
    FL: FrictionLaw + ?Sized,
{
    let tangents = <Dim<D>>::basis(n, tangent);
    let w = v - us;
    let pen = -gap;
    let rate = -n.dot(&w);
    let fn_ = normal_law.normal(pen, rate).force;
    let (slip, ft, ftw) = <Dim<D>>::friction_value(friction_law, &tangents, &w, fn_);
    PointForce {
        penetration: pen,
        penetration_rate: rate,
        slip,
        normal_force: fn_,
        friction_force: ft,
        force: n * fn_ + ftw,
    }
}

/// The derivatives `(df_dp, df_dv, df_domega)` of [`point_contact`]'s force (its rustdoc).
fn point_jacobian<const D: usize>(
    sp: &SurfacePoint<D>, nf: &NormalForce, ft: &TangentialForce<D>, w: &SVector<f64, D>,
) -> (SMatrix<f64, D, D>, SMatrix<f64, D, D>, SVector<f64, D>)
where
    Dim<D>: ContactDim<D>,
{
    let n = sp.normal;
    let nw = n.dot(w);
    let dn = sp.dn_dp;
    let dus = sp.dus_dp;
    let nnt = n * n.transpose();
    let proj = SMatrix::<f64, D, D>::identity() - nnt;
    let wdn = w.transpose() * dn;
    // ḋ = −nᵀw: ∂ḋ/∂p = −wᵀ ∂n/∂p + nᵀ ∂u_s/∂p, ∂ḋ/∂ṙ = −nᵀ
    let drate_dp = (n.transpose() * dus - wdn).transpose();
    let dfn_dp = sp.gap_gradient * (-nf.d_pen) + drate_dp * nf.d_rate;
    let dfn_dv = n * (-nf.d_rate);
    let dw_dp = -dn * nw - n * wdn - proj * dus;
    let wt = w - n * nw;
    let s2 = wt.norm_squared();
    // f_tᵀW/|W|² (= g/|W| of an isotropic law f_t = g W/|W|), its limit g'(0) at rest
    let gs = if s2 > 0.0 {
        ft.force.dot(&wt) / s2
    } else {
        ft.d_slip.trace() / (D - 1) as f64
    };
    let dft_dw = ft.d_slip + nnt * gs;
    let df_dp =
        n * dfn_dp.transpose() + dn * nf.force + dft_dw * dw_dp + ft.d_normal * dfn_dp.transpose();
    let df_dv = n * dfn_dv.transpose() + dft_dw * proj + ft.d_normal * dfn_dv.transpose();
    let dfn_dw = nf.d_rate * n.dot(&sp.dus_domega);
    let df_dw = n * dfn_dw - dft_dw * (proj * sp.dus_domega) + ft.d_normal * dfn_dw;
    (df_dp, df_dv, df_dw)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::friction::{CoulombTanh, CreepRate, Stribeck};
    use crate::geometry::{CleatedDrum, Disk, rot90};
    use crate::normal::{LinearPenalty, PolynomialPenalty};
    use crate::spatial::Cylinder;
    use nalgebra::{Matrix2, Point2, Point3, Vector2, Vector3};

    /// Central differences of the force of `eval(p, v, ω)` in `p`, `ṙ` and `ω` against the
    /// exact derivatives, relative to the largest entry of each derivative.
    fn fd_check<const D: usize>(
        eval: impl Fn(&Point<f64, D>, &SVector<f64, D>, f64) -> PointContact<D>, p: Point<f64, D>,
        v: SVector<f64, D>, w: f64,
    ) where
        Dim<D>: ContactDim<D>,
    {
        let c = eval(&p, &v, w);
        let h = 1e-8;
        for j in 0..D {
            let mut e = SVector::<f64, D>::zeros();
            e[j] = h;
            let dp = (eval(&(p + e), &v, w).force - eval(&(p - e), &v, w).force) / (2.0 * h);
            let dv = (eval(&p, &(v + e), w).force - eval(&p, &(v - e), w).force) / (2.0 * h);
            for i in 0..D {
                let sc = 1e-5 * c.df_dp.amax();
                assert!(
                    (dp[i] - c.df_dp[(i, j)]).abs() < sc,
                    "df{i}/dp{j}: {} vs {}",
                    dp[i],
                    c.df_dp[(i, j)]
                );
                let sc = 1e-5 * c.df_dv.amax();
                assert!(
                    (dv[i] - c.df_dv[(i, j)]).abs() < sc,
                    "df{i}/dv{j}: {} vs {}",
                    dv[i],
                    c.df_dv[(i, j)]
                );
            }
        }
        let dw = (eval(&p, &v, w + 1e-6).force - eval(&p, &v, w - 1e-6).force) / 2e-6;
        assert!((dw - c.df_domega).amax() < 1e-5 * c.df_domega.amax().max(1e-300));
    }

    /// Linear penalty of Kerkkänen (3.20).
    fn penalty() -> LinearPenalty {
        LinearPenalty {
            stiffness: 1e7,
            damping: 10.0,
        }
    }

    /// Regularised Coulomb law of Ribaric (6.2).
    fn tanh() -> CoulombTanh {
        CoulombTanh {
            mu: 1.2,
            kappa: 40.0,
        }
    }

    fn stribeck() -> Stribeck {
        Stribeck {
            mu_static: 0.6,
            mu_kinetic: 0.4,
            stribeck_velocity: 0.05,
            kappa: 40.0,
        }
    }

    fn pulley() -> Cylinder {
        Cylinder {
            center: Point3::new(0.0, 0.0, 0.0),
            axis: Vector3::new(0.1, 0.0, 1.0).normalize(),
            radius: 0.1,
            crown: 0.5,
            velocity: Vector3::zeros(),
            omega: 20.0,
        }
    }

    // Reference: central differences of the force in p, ṙ and ω (spatial: crowned, tilted
    // pulley, Stribeck law).
    #[test]
    fn spatial_derivatives_match_finite_differences() {
        let (nl, fl) = (penalty(), stribeck());
        let f = |p: &Point3<f64>, v: &Vector3<f64>, w: f64| {
            let mut c = pulley();
            c.omega = w;
            point_contact(&c, &nl, &fl, p, v).unwrap()
        };
        let p = Point3::new(0.0995, 0.0, 0.01);
        let v = Vector3::new(0.1, 1.9, 0.05);
        fd_check(f, p, v, 20.0);
        let c = f(&p, &v, 20.0);
        // friction opposes the slip
        assert!(c.friction.force.dot(&c.slip) <= 0.0);
    }

    // Reference: central differences of the force in p, ṙ and ω (planar: a moving, rotating
    // disk and the cleat of a cleated drum, with penalty laws of Kerkkänen (3.20) and
    // Ribaric (6.1) and the creep-rate and Stribeck friction laws).
    #[test]
    fn planar_derivatives_match_finite_differences() {
        let nl = LinearPenalty {
            stiffness: 2e6,
            damping: 30.0,
        };
        let fl = CreepRate {
            mu: 0.8,
            creep: 300.0,
        };
        let disk = |w: f64| Disk {
            center: Point2::new(0.01, -0.02),
            radius: 0.1,
            velocity: Vector2::new(0.3, -0.1),
            omega: w,
        };
        let f = |p: &Point2<f64>, v: &Vector2<f64>, w: f64| {
            point_contact(&disk(w), &nl, &fl, p, v).unwrap()
        };
        let p = Point2::new(0.01 + 0.0599, -0.02 + 0.0799);
        fd_check(f, p, Vector2::new(-1.2, 1.1), 15.0);
        let drum = |w: f64| CleatedDrum {
            drum: disk(w),
            cleat_radius: 0.01,
            cleat_angle: 0.3,
        };
        let tip = drum(15.0).cleat().center;
        let pl = PolynomialPenalty::ribaric(0.01);
        let st = stribeck();
        let g = |p: &Point2<f64>, v: &Vector2<f64>, w: f64| {
            point_contact(&drum(w), &pl, &st, p, v).unwrap()
        };
        let p = tip + Vector2::new(0.006, 0.0078);
        let sp = drum(15.0).closest(&p);
        assert_eq!(sp.part, 1);
        // slip 0.02 m/s (Stribeck branch unsaturated) and an approaching normal velocity
        let v = sp.surface_velocity + rot90(sp.normal) * 0.02 - sp.normal * 0.05;
        fd_check(g, p, v, 15.0);
    }

    // Reference (second formulation): the planar contact written out in the tangent
    // t = Ĩn of Kerkkänen (3.6), f = f_n n + f_t(tᵀw) t, differentiated with ∂t/∂p = Ĩ ∂n/∂p —
    // the formula of the planar contact before it became dimension-generic.
    #[test]
    fn planar_contact_matches_the_rotated_tangent_formula() {
        let (nl, fl) = (penalty(), tanh());
        let disk = Disk {
            center: Point2::new(0.02, -0.01),
            radius: 0.1,
            velocity: Vector2::new(0.1, 0.05),
            omega: 20.0,
        };
        let (p, v) = (Point2::new(0.08, 0.0699), Vector2::new(-1.6, 1.2));
        let c = point_contact(&disk, &nl, &fl, &p, &v).unwrap();
        let sp = disk.closest(&p);
        let n = sp.normal;
        let t = rot90(n);
        let dn = sp.dn_dp;
        let dt = Matrix2::new(-dn[(1, 0)], -dn[(1, 1)], dn[(0, 0)], dn[(0, 1)]);
        let w = v - sp.surface_velocity;
        let nf = nl.normal(-sp.gap, -n.dot(&w));
        let ff = fl.friction(t.dot(&w), nf.force);
        let force = n * nf.force + t * ff.force;
        let dfn_dp = -n * nf.d_pen
            + (n.transpose() * sp.dus_dp - w.transpose() * dn).transpose() * nf.d_rate;
        let dslip_dp = (w.transpose() * dt - t.transpose() * sp.dus_dp).transpose();
        let dft_dp = dslip_dp * ff.d_slip + dfn_dp * ff.d_normal;
        let df_dp = n * dfn_dp.transpose() + dn * nf.force + t * dft_dp.transpose() + dt * ff.force;
        let dfn_dv = -n * nf.d_rate;
        let dft_dv = t * ff.d_slip + dfn_dv * ff.d_normal;
        let df_dv = n * dfn_dv.transpose() + t * dft_dv.transpose();
        let dfn_dw = nf.d_rate * n.dot(&sp.dus_domega);
        let dft_dw = -ff.d_slip * t.dot(&sp.dus_domega) + ff.d_normal * dfn_dw;
        let df_dw = n * dfn_dw + t * dft_dw;
        assert!((c.force - force).amax() <= 1e-14 * force.amax());
        assert!((c.df_dp - df_dp).amax() <= 1e-12 * df_dp.amax());
        assert!((c.df_dv - df_dv).amax() <= 1e-12 * df_dv.amax());
        assert!((c.df_domega - df_dw).amax() <= 1e-12 * df_dw.amax());
        assert_eq!(c.slip, t.dot(&w));
        assert_eq!(c.tangents, t);
    }

    // Reference (second formulation): in a cross-section of a straight cylinder about z the
    // spatial contact is the planar one (Kerkkänen (3.20)–(3.25)): force and derivatives.
    #[test]
    fn planar_motion_matches_planar_contact() {
        let (nl, fl) = (penalty(), tanh());
        let disk = Disk {
            center: Point2::new(0.0, 0.0),
            radius: 0.1,
            velocity: Vector2::zeros(),
            omega: 20.0,
        };
        let cyl = Cylinder {
            axis: Vector3::z(),
            crown: 0.0,
            ..pulley()
        };
        // slip ≈ 0.01 m/s against the surface speed ωR = 2 m/s: tanh unsaturated
        let (p, v) = ([0.06, 0.0799], [-1.638, 1.166]);
        let a = point_contact(&disk, &nl, &fl, &Point2::from(p), &Vector2::from(v)).unwrap();
        let b = point_contact(
            &cyl,
            &nl,
            &fl,
            &Point3::new(p[0], p[1], 0.3),
            &Vector3::new(v[0], v[1], 0.0),
        )
        .unwrap();
        for i in 0..2 {
            assert!((a.force[i] - b.force[i]).abs() < 1e-9 * a.force[0].abs().max(1.0));
            for j in 0..2 {
                assert!((a.df_dp[(i, j)] - b.df_dp[(i, j)]).abs() < 1e-9 * b.df_dp.amax());
                assert!((a.df_dv[(i, j)] - b.df_dv[(i, j)]).abs() < 1e-9 * b.df_dv.amax());
            }
            assert!((a.df_domega[i] - b.df_domega[i]).abs() < 1e-9 * b.df_domega.amax());
        }
        assert!(b.force[2].abs() < 1e-12);
        // the slip along t = Ĩn is the spatial slip along t₁ = a × e_r (same direction)
        assert!((a.slip - b.slip[0]).abs() < 1e-12 && b.slip[1].abs() < 1e-12);
    }

    // Reference: the slip of point_contact (in contact) and the closed form of a rotating,
    // translating disk, `t·(v − ṙ_o) − ωR` with `t = Ĩ n`, for a separated point.
    #[test]
    fn point_slip_is_the_contact_slip_and_extends_to_separated_points() {
        let disk = Disk {
            center: Point2::new(0.02, -0.01),
            radius: 0.1,
            velocity: Vector2::new(0.1, 0.05),
            omega: 20.0,
        };
        let v = Vector2::new(-1.6, 1.2);
        let p = Point2::new(0.08, 0.0699);
        let c = point_contact(&disk, &penalty(), &tanh(), &p, &v).unwrap();
        let (gap, slip) = point_slip(&disk, &p, &v);
        assert_eq!((gap, slip), (-c.penetration, c.slip));
        // separated by 5 mm along the normal at 30°
        let n = Vector2::new(30f64.to_radians().cos(), 30f64.to_radians().sin());
        let p = disk.center + 0.105 * n;
        let (gap, slip) = point_slip(&disk, &p, &v);
        let exact = rot90(n).dot(&(v - disk.velocity)) - disk.omega * disk.radius;
        assert!((gap - 0.005).abs() < 1e-15, "{gap}");
        assert!((slip - exact).abs() < 1e-14, "{slip} vs {exact}");
        assert!(point_contact(&disk, &penalty(), &tanh(), &p, &v).is_none());
        // in space: the spatial contact's slip
        let (q, u) = (
            Point3::new(0.06, 0.0799, 0.3),
            Vector3::new(-1.638, 1.166, 0.2),
        );
        let cyl = Cylinder {
            axis: Vector3::z(),
            crown: 0.0,
            ..pulley()
        };
        let (gap, slip) = point_slip(&cyl, &q, &u);
        let c = point_contact(&cyl, &penalty(), &tanh(), &q, &u).unwrap();
        assert_eq!((gap, slip), (-c.penetration, c.slip));
    }
}
