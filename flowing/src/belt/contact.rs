//! Contact of one belt node with a rigid pulley: penalty normal force (Ribaric (6.1)) and
//! regularised Coulomb friction (Ribaric (6.2)), with the analytic derivatives used by the
//! implicit integrator.
//!
//! Conventions: the pulley (centre `c`, radius `R`) turns with speed `ω` [rad/s] counted positive
//! in the belt's travel direction; `turn = +1` when the belt wraps the pulley clockwise (pulley
//! inside the loop, Ribaric Fig. 5-1), `−1` for a back-side idler. With `n` the outward unit normal
//! at the node, the travel tangent is `t = turn·(n_y, −n_x)`, the penetration `p = R − |d − c|`,
//! the slip velocity `v_slip = t·V − ω R` (belt material velocity `V` minus pulley surface
//! velocity, seed-000 note B1), and the force on the belt node `F = F_N n + F_T t` with
//! `F_T = f(v_slip, F_N)` opposing the slip. The reaction torque on the pulley in its travel sense
//! is `τ = −F_T R`.

use contact::friction::FrictionLaw;
use contact::normal::NormalLaw;

/// A rigid pulley seen by the belt nodes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PulleyFrame {
    /// Centre [m].
    pub center: [f64; 2],
    /// Radius of the belt line [m].
    pub radius: f64,
    /// +1 clockwise wrap, −1 counter-clockwise (back-side) wrap.
    pub turn: f64,
}

/// Force of one node–pulley contact and its derivatives.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NodeContact {
    /// Penetration `p` [m] (≤ 0: open, no force).
    pub penetration: f64,
    /// Normal force `F_N` [N].
    pub normal: f64,
    /// Tangential (friction) force `F_T` along the travel tangent [N].
    pub friction: f64,
    /// Slip velocity [m/s].
    pub slip: f64,
    /// Force on the belt node [N].
    pub force: [f64; 2],
    /// Reaction torque on the pulley in its travel sense [N m].
    pub torque: f64,
    /// `∂F/∂d` (row i: component i of F).
    pub df_dd: [[f64; 2]; 2],
    /// `∂F/∂V`.
    pub df_dv: [[f64; 2]; 2],
    /// `∂F/∂ω`.
    pub df_dw: [f64; 2],
    /// `∂τ/∂d`.
    pub dt_dd: [f64; 2],
    /// `∂τ/∂V`.
    pub dt_dv: [f64; 2],
    /// `∂τ/∂ω`.
    pub dt_dw: f64,
}

/// Contact force of a node at position `d` with material velocity `vel` against `pulley`
/// turning at `omega` (see the module documentation for the conventions).
pub fn node_contact(
    pulley: &PulleyFrame,
    omega: f64,
    d: [f64; 2],
    vel: [f64; 2],
    normal_law: &impl NormalLaw,
    friction_law: &impl FrictionLaw,
) -> NodeContact {
    let rel = [d[0] - pulley.center[0], d[1] - pulley.center[1]];
    let r = rel[0].hypot(rel[1]);
    let pen = pulley.radius - r;
    if pen <= 0.0 || r == 0.0 {
        return NodeContact {
            penetration: pen,
            ..Default::default()
        };
    }
    let n = [rel[0] / r, rel[1] / r];
    let tu = pulley.turn;
    let t = [tu * n[1], -tu * n[0]];
    let nf = normal_law.normal(pen, 0.0);
    let slip = t[0] * vel[0] + t[1] * vel[1] - omega * r;
    let ff = friction_law.friction(slip, nf.force);
    let (fn_, ft) = (nf.force, ff.force);
    // dn/dd = (I − n nᵀ)/r ; dt/dd = turn·J·dn/dd with J = [[0, 1], [−1, 0]]
    let pn = [
        [(1.0 - n[0] * n[0]) / r, -n[0] * n[1] / r],
        [-n[1] * n[0] / r, (1.0 - n[1] * n[1]) / r],
    ];
    let dt = [
        [tu * pn[1][0], tu * pn[1][1]],
        [-tu * pn[0][0], -tu * pn[0][1]],
    ];
    let mut dfn_dd = [0.0; 2];
    let mut dslip_dd = [0.0; 2];
    let mut dft_dd = [0.0; 2];
    for j in 0..2 {
        dfn_dd[j] = -nf.d_pen * n[j];
        dslip_dd[j] = vel[0] * dt[0][j] + vel[1] * dt[1][j] - omega * n[j];
        dft_dd[j] = ff.d_slip * dslip_dd[j] + ff.d_normal * dfn_dd[j];
    }
    let mut df_dd = [[0.0; 2]; 2];
    let mut df_dv = [[0.0; 2]; 2];
    let mut df_dw = [0.0; 2];
    for i in 0..2 {
        for j in 0..2 {
            df_dd[i][j] = n[i] * dfn_dd[j] + fn_ * pn[i][j] + t[i] * dft_dd[j] + ft * dt[i][j];
            df_dv[i][j] = t[i] * ff.d_slip * t[j];
        }
        df_dw[i] = -t[i] * ff.d_slip * r;
    }
    NodeContact {
        penetration: pen,
        normal: fn_,
        friction: ft,
        slip,
        force: [fn_ * n[0] + ft * t[0], fn_ * n[1] + ft * t[1]],
        torque: -ft * r,
        df_dd,
        df_dv,
        df_dw,
        dt_dd: [-r * dft_dd[0] - ft * n[0], -r * dft_dd[1] - ft * n[1]],
        dt_dv: [-r * ff.d_slip * t[0], -r * ff.d_slip * t[1]],
        dt_dw: r * r * ff.d_slip,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use contact::friction::CoulombTanh;
    use contact::normal::PolynomialPenalty;

    fn eval(d: [f64; 2], v: [f64; 2], w: f64) -> NodeContact {
        let p = PulleyFrame {
            center: [0.1, -0.02],
            radius: 0.05,
            turn: 1.0,
        };
        node_contact(
            &p,
            w,
            d,
            v,
            &PolynomialPenalty::ribaric(0.01),
            &CoulombTanh {
                mu: 1.2,
                kappa: 40.0,
            },
        )
    }

    // The analytic derivatives against central differences (second formulation of the same law).
    #[test]
    fn derivatives_match_finite_differences() {
        let (d, v, w) = ([0.1 + 0.03, -0.02 + 0.0399], [2.9, -0.4], 60.0);
        let c = eval(d, v, w);
        assert!(c.penetration > 0.0 && c.normal > 0.0);
        let h = 1e-9;
        for j in 0..2 {
            let (mut dp, mut dm) = (d, d);
            dp[j] += h;
            dm[j] -= h;
            let (a, b) = (eval(dp, v, w), eval(dm, v, w));
            for i in 0..2 {
                let fd = (a.force[i] - b.force[i]) / (2.0 * h);
                assert!(
                    (fd - c.df_dd[i][j]).abs() <= 1e-5 * fd.abs().max(1.0),
                    "dF{i}/dd{j}: {fd} vs {}",
                    c.df_dd[i][j]
                );
            }
            let fd = (a.torque - b.torque) / (2.0 * h);
            assert!((fd - c.dt_dd[j]).abs() <= 1e-5 * fd.abs().max(1.0));
            let (mut vp, mut vm) = (v, v);
            vp[j] += 1e-7;
            vm[j] -= 1e-7;
            let (a, b) = (eval(d, vp, w), eval(d, vm, w));
            for i in 0..2 {
                let fd = (a.force[i] - b.force[i]) / 2e-7;
                assert!((fd - c.df_dv[i][j]).abs() <= 1e-5 * fd.abs().max(1.0));
            }
        }
        let (a, b) = (eval(d, v, w + 1e-6), eval(d, v, w - 1e-6));
        assert!(((a.torque - b.torque) / 2e-6 - c.dt_dw).abs() <= 1e-5 * c.dt_dw.abs().max(1.0));
    }

    // Sticking belt node (no slip) carries no friction; a faster belt drives the pulley (τ > 0).
    #[test]
    fn friction_direction_and_open_contact() {
        let n = [0.6f64, 0.8];
        let d = [0.1 + 0.0499 * n[0], -0.02 + 0.0499 * n[1]];
        let t = [n[1], -n[0]];
        // the pulley point under the node (radius 0.0499 m) moves at ω r
        let c = eval(d, [3.0 * t[0], 3.0 * t[1]], 3.0 / 0.0499);
        assert!(c.friction.abs() < 1e-9 && c.normal > 0.0);
        let fast = eval(d, [3.1 * t[0], 3.1 * t[1]], 3.0 / 0.0499);
        assert!(fast.friction < 0.0 && fast.torque > 0.0);
        let open = eval([0.1 + 0.06, -0.02], [0.0, 0.0], 0.0);
        assert_eq!(open.force, [0.0, 0.0]);
    }
}
