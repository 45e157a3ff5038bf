//! Contact of one material point with a spatial obstacle: penetration, normal force, friction
//! force from the slip 2-vector in the tangent plane, and exact derivatives with respect to the
//! point's position and velocity and the obstacle's angular velocity — the spatial form of
//! Kerkkänen (3.20)–(3.25).

use super::geometry::{Surface3, SurfacePoint3};
use crate::friction::{FrictionLaw, TangentFriction};
use crate::normal::{NormalForce, NormalLaw};
use nalgebra::{Matrix3, Matrix3x2, Point3, Vector2, Vector3};

/// Contact state and force of one point in contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointContact3 {
    /// Surface data.
    pub surface: SurfacePoint3,
    /// Tangent basis `T = [t₁ t₂]`, `t₁ = P t_ref/|P t_ref|`, `t₂ = n × t₁`.
    pub tangents: Matrix3x2<f64>,
    /// Penetration `d = −g ≥ 0` \[m\].
    pub penetration: f64,
    /// Penetration rate `ḋ = −nᵀ(ṙ − u_s)` \[m/s\].
    pub penetration_rate: f64,
    /// Slip `v_t = Tᵀ(ṙ − u_s)` \[m/s\].
    pub slip: Vector2<f64>,
    /// Normal law output.
    pub normal: NormalForce,
    /// Friction law output (in the basis `T`).
    pub friction: TangentFriction,
    /// Force on the body `f = f_n n + T f_t`.
    pub force: Vector3<f64>,
    /// `∂f/∂r`.
    pub df_dp: Matrix3<f64>,
    /// `∂f/∂ṙ`.
    pub df_dv: Matrix3<f64>,
    /// `∂f/∂ω` of the obstacle.
    pub df_domega: Vector3<f64>,
}

/// Contact of the point at `p` \[m\] moving with `v` \[m/s\] against `surface`; `None` when
/// separated. With `w = ṙ − u_s` and its tangential part `W = P w`, `P = I − n nᵀ`, the friction
/// force is `T f_t(Tᵀ W, f_n)`. The derivatives are exact for isotropic laws (all laws of this
/// crate), for which `T f_t(TᵀW)` does not depend on the choice of the basis `T`:
/// `∂(T f_t)/∂W = T (∂f_t/∂v_t) Tᵀ + (|f_t|/|W|) n nᵀ`.
pub fn point_contact_3d<S, NL, FL>(
    surface: &S,
    normal_law: &NL,
    friction_law: &FL,
    p: &Point3<f64>,
    v: &Vector3<f64>,
) -> Option<PointContact3>
where
    S: Surface3 + ?Sized,
    NL: NormalLaw + ?Sized,
    FL: FrictionLaw + ?Sized,
{
    let sp = surface.closest(p);
    if sp.gap > 0.0 {
        return None;
    }
    let n = sp.normal;
    let proj = Matrix3::identity() - n * n.transpose();
    let t1 = (proj * sp.tangent)
        .try_normalize(1e-300)
        .unwrap_or_else(|| {
            n.cross(&Vector3::x())
                .try_normalize(0.0)
                .unwrap_or(Vector3::y())
        });
    let t2 = n.cross(&t1);
    let tb = Matrix3x2::from_columns(&[t1, t2]);
    let w = v - sp.surface_velocity;
    let pen = -sp.gap;
    let rate = -n.dot(&w);
    let wt = proj * w;
    let slip = tb.transpose() * wt;
    let nf = normal_law.normal(pen, rate);
    let ff = friction_law.friction_tangent(slip, nf.force);

    // ∂W/∂p = −(∂n/∂p)(nᵀw) − n wᵀ(∂n/∂p) − P ∂u_s/∂p, ∂W/∂ṙ = P, ∂W/∂ω = −P ∂u_s/∂ω
    let dn = sp.dn_dp;
    let nw = n.dot(&w);
    let dw_dp = -dn * nw - n * (w.transpose() * dn) - proj * sp.dus_dp;
    let drate_dp = (-(w.transpose() * dn) + n.transpose() * sp.dus_dp).transpose();
    let dfn_dp = -sp.gap_gradient * nf.d_pen + drate_dp * nf.d_rate;
    let dfn_dv = -n * nf.d_rate;
    let s = wt.norm();
    // g/s of the isotropic law f_t = g(s) W/s (≤ 0), its limit g'(0) at rest
    let gs = if s > 0.0 {
        -ff.force.norm() / s
    } else {
        ff.d_slip[(0, 0)]
    };
    let dft_dw = tb * ff.d_slip * tb.transpose() + n * n.transpose() * gs;
    let tdn = tb * ff.d_normal;
    let ft3 = tb * ff.force;
    let df_dp = n * dfn_dp.transpose() + dn * nf.force + dft_dw * dw_dp + tdn * dfn_dp.transpose();
    let df_dv = n * dfn_dv.transpose() + dft_dw * proj + tdn * dfn_dv.transpose();
    let drate_dw = n.dot(&sp.dus_domega);
    let dfn_dw = nf.d_rate * drate_dw;
    let df_dw = n * dfn_dw - dft_dw * (proj * sp.dus_domega) + tdn * dfn_dw;
    Some(PointContact3 {
        surface: sp,
        tangents: tb,
        penetration: pen,
        penetration_rate: rate,
        slip,
        normal: nf,
        friction: ff,
        force: n * nf.force + ft3,
        df_dp,
        df_dv,
        df_domega: df_dw,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::friction::{CoulombTanh, Stribeck};
    use crate::geometry::Disk;
    use crate::normal::LinearPenalty;
    use crate::point::point_contact;
    use crate::spatial::Cylinder;

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

    // Reference: central differences of the force in p, ṙ and ω.
    #[test]
    fn derivatives_match_finite_differences() {
        let nl = LinearPenalty {
            stiffness: 1e7,
            damping: 10.0,
        };
        let fl = Stribeck {
            mu_static: 0.6,
            mu_kinetic: 0.4,
            stribeck_velocity: 0.05,
            kappa: 40.0,
        };
        let p = Point3::new(0.0995, 0.0, 0.01);
        let v = Vector3::new(0.1, 1.9, 0.05);
        let f = |p: &Point3<f64>, v: &Vector3<f64>, w: f64| {
            let mut c = pulley();
            c.omega = w;
            point_contact_3d(&c, &nl, &fl, p, v).unwrap()
        };
        let c = f(&p, &v, 20.0);
        let h = 1e-8;
        for j in 0..3 {
            let mut e = Vector3::zeros();
            e[j] = h;
            let dp = (f(&(p + e), &v, 20.0).force - f(&(p - e), &v, 20.0).force) / (2.0 * h);
            let dv = (f(&p, &(v + e), 20.0).force - f(&p, &(v - e), 20.0).force) / (2.0 * h);
            for i in 0..3 {
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
        let dw = (f(&p, &v, 20.0 + 1e-6).force - f(&p, &v, 20.0 - 1e-6).force) / 2e-6;
        assert!((dw - c.df_domega).amax() < 1e-5 * c.df_domega.amax());
        // friction opposes the slip
        assert!(c.friction.force.dot(&c.slip) <= 0.0);
    }

    // Reference (second formulation): in a cross-section of a straight cylinder about z the
    // spatial contact is the planar one (Kerkkänen (3.20)–(3.25)).
    #[test]
    fn planar_motion_matches_planar_contact() {
        let nl = LinearPenalty {
            stiffness: 1e7,
            damping: 10.0,
        };
        let fl = CoulombTanh {
            mu: 1.2,
            kappa: 40.0,
        };
        let disk = Disk {
            center: [0.0, 0.0],
            radius: 0.1,
            velocity: [0.0, 0.0],
            omega: 20.0,
        };
        let cyl = Cylinder {
            axis: Vector3::z(),
            crown: 0.0,
            ..pulley()
        };
        // slip ≈ 0.01 m/s against the surface speed ωR = 2 m/s: tanh unsaturated
        let (p, v) = ([0.06, 0.0799], [-1.638, 1.166]);
        let a = point_contact(&disk, &nl, &fl, p, v).unwrap();
        let b = point_contact_3d(
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
                assert!((a.df_dp[i][j] - b.df_dp[(i, j)]).abs() < 1e-9 * b.df_dp.amax());
                assert!((a.df_dv[i][j] - b.df_dv[(i, j)]).abs() < 1e-9 * b.df_dv.amax());
            }
            assert!((a.df_domega[i] - b.df_domega[i]).abs() < 1e-9 * b.df_domega.amax());
        }
        assert!(b.force[2].abs() < 1e-12);
    }
}
