//! Contact of one material point with an obstacle: penetration, normal and friction force,
//! and their exact derivatives with respect to the point's position and velocity and to the
//! obstacle's angular velocity (the ingredients of Kerkkänen (3.20)–(3.26)).

use crate::friction::{FrictionForce, FrictionLaw};
use crate::geometry::{Mat2, Surface, SurfacePoint, rot90};
use crate::normal::{NormalForce, NormalLaw};

/// Contact state and force of one point in contact (penetration `d ≥ 0`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointContact {
    /// Closest-point data.
    pub surface: SurfacePoint,
    /// Penetration `d = −gap ≥ 0` \[m\], Kerkkänen (3.21).
    pub penetration: f64,
    /// Penetration rate `ḋ = −nᵀ(ṙ − u_s)` \[m/s\].
    pub penetration_rate: f64,
    /// Slip velocity `v_t = tᵀ(ṙ − u_s)`, `t = Ĩ n` \[m/s\], Kerkkänen (3.24)–(3.25).
    pub slip: f64,
    /// Normal law output.
    pub normal: NormalForce,
    /// Friction law output.
    pub friction: FrictionForce,
    /// Force on the body `f = f_n n + f_t t` (per unit length for distributed laws).
    pub force: [f64; 2],
    /// `∂f/∂r` (row-major).
    pub df_dp: Mat2,
    /// `∂f/∂ṙ` (row-major).
    pub df_dv: Mat2,
    /// `∂f/∂ω` of the obstacle.
    pub df_domega: [f64; 2],
}

/// Evaluate contact of the point at `p` \[m\] moving with `v` \[m/s\] against `surface`.
/// Returns `None` when the point is separated (`gap > 0`): no force (Kerkkänen (3.20)).
pub fn point_contact<S, NL, FL>(
    surface: &S,
    normal_law: &NL,
    friction_law: &FL,
    p: [f64; 2],
    v: [f64; 2],
) -> Option<PointContact>
where
    S: Surface + ?Sized,
    NL: NormalLaw + ?Sized,
    FL: FrictionLaw + ?Sized,
{
    let sp = surface.closest(p);
    if sp.gap > 0.0 {
        return None;
    }
    let n = sp.normal;
    let t = rot90(n);
    let dn = sp.dn_dp;
    let dt: Mat2 = [[-dn[1][0], -dn[1][1]], [dn[0][0], dn[0][1]]];
    let dus = sp.dus_dp;
    let w = [v[0] - sp.surface_velocity[0], v[1] - sp.surface_velocity[1]];
    let pen = -sp.gap;
    let rate = -(n[0] * w[0] + n[1] * w[1]);
    let slip = t[0] * w[0] + t[1] * w[1];
    let nf = normal_law.normal(pen, rate);
    let ff = friction_law.friction(slip, nf.force);

    let mut dfn_dp = [0.0; 2];
    let mut dfn_dv = [0.0; 2];
    let mut dft_dp = [0.0; 2];
    let mut dft_dv = [0.0; 2];
    for j in 0..2 {
        let dd = -n[j];
        let drate = -(w[0] * dn[0][j] + w[1] * dn[1][j]) + (n[0] * dus[0][j] + n[1] * dus[1][j]);
        let dslip = (w[0] * dt[0][j] + w[1] * dt[1][j]) - (t[0] * dus[0][j] + t[1] * dus[1][j]);
        dfn_dp[j] = nf.d_pen * dd + nf.d_rate * drate;
        dfn_dv[j] = nf.d_rate * (-n[j]);
        dft_dp[j] = ff.d_slip * dslip + ff.d_normal * dfn_dp[j];
        dft_dv[j] = ff.d_slip * t[j] + ff.d_normal * dfn_dv[j];
    }
    let dso = sp.dus_domega;
    let drate_dw = n[0] * dso[0] + n[1] * dso[1];
    let dslip_dw = -(t[0] * dso[0] + t[1] * dso[1]);
    let dfn_dw = nf.d_rate * drate_dw;
    let dft_dw = ff.d_slip * dslip_dw + ff.d_normal * dfn_dw;

    let mut df_dp = [[0.0; 2]; 2];
    let mut df_dv = [[0.0; 2]; 2];
    let mut df_dw = [0.0; 2];
    for i in 0..2 {
        for j in 0..2 {
            df_dp[i][j] =
                n[i] * dfn_dp[j] + nf.force * dn[i][j] + t[i] * dft_dp[j] + ff.force * dt[i][j];
            df_dv[i][j] = n[i] * dfn_dv[j] + t[i] * dft_dv[j];
        }
        df_dw[i] = n[i] * dfn_dw + t[i] * dft_dw;
    }
    Some(PointContact {
        surface: sp,
        penetration: pen,
        penetration_rate: rate,
        slip,
        normal: nf,
        friction: ff,
        force: [
            nf.force * n[0] + ff.force * t[0],
            nf.force * n[1] + ff.force * t[1],
        ],
        df_dp,
        df_dv,
        df_domega: df_dw,
    })
}
