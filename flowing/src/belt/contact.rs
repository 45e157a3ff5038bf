//! Contact of one belt node with a rigid pulley: penalty normal force (Ribaric (6.1)) and
//! regularised Coulomb friction (Ribaric (6.2)), with the analytic derivatives used by the
//! implicit integrator.
//!
//! Conventions: the pulley (centre `c`, radius `R`) turns with speed `ω` \[rad/s\] counted positive
//! in the belt's travel direction; `turn = +1` when the belt wraps the pulley clockwise (pulley
//! inside the loop, Ribaric Fig. 5-1), `−1` for a back-side idler. With `n` the outward unit normal
//! at the node, the travel tangent is `t = turn·(n_y, −n_x)`, the penetration `p = R − |d − c|`,
//! the slip velocity `v_slip = t·V − ω R` (belt material velocity `V` minus pulley surface
//! velocity, seed-000 note B1), and the force on the belt node `F = F_N n + F_T t` with
//! `F_T = f(v_slip, F_N)` opposing the slip. The reaction torque on the pulley in its travel sense
//! is `τ = −F_T R`.

use contact::friction::{FrictionLaw, transition_limit};
use contact::geometry::{Disk, rot90};
use contact::normal::NormalLaw;
use contact::point::{point_contact, point_slip};
use nalgebra::{Point2, Vector2};

/// A rigid pulley seen by the belt nodes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PulleyFrame {
    /// Centre \[m\].
    pub center: [f64; 2],
    /// Radius of the belt line \[m\].
    pub radius: f64,
    /// +1 clockwise wrap, −1 counter-clockwise (back-side) wrap.
    pub turn: f64,
}

impl PulleyFrame {
    /// The pulley as the contact crate's rotating [`Disk`]: at rest, turning
    /// counter-clockwise at `−turn·ω` for the travel-sense speed `omega` \[rad/s\].
    fn disk(&self, omega: f64) -> Disk {
        Disk {
            center: Point2::from(self.center),
            radius: self.radius,
            velocity: Vector2::zeros(),
            omega: -self.turn * omega,
        }
    }
}

/// What a node's slip velocity against a pulley depends on: the pulley's frame and
/// travel-sense speed `omega` \[rad/s\], the node's position \[m\] and material velocity
/// \[m/s\] relative to the pulley's centre (the arguments of [`node_contact`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeMotion {
    /// The pulley (its centre where the node sees it, e.g. an idler moved by its arm).
    pub frame: PulleyFrame,
    /// Pulley speed in the belt's travel sense \[rad/s\].
    pub omega: f64,
    /// Node position `d` \[m\].
    pub position: [f64; 2],
    /// Material velocity `V` of the node relative to the pulley's centre \[m/s\].
    pub velocity: [f64; 2],
}

impl NodeMotion {
    /// Penetration `p = R − |d − c|` \[m\] and slip velocity `v_slip = t·V − ωR` \[m/s\] along the
    /// travel tangent (module documentation), from the contact crate's kinematics
    /// ([`point_slip`], Kerkkänen (3.21), (3.24)–(3.25)): what [`node_contact`] reports, also
    /// for an open contact.
    pub fn penetration_and_slip(&self) -> (f64, f64) {
        let (gap, slip) = point_slip(
            &self.frame.disk(self.omega),
            &Point2::from(self.position),
            &Vector2::from(self.velocity),
        );
        (-gap, -self.frame.turn * slip)
    }
}

/// The transition-aware limit on a Newton correction (Castro et al. 2019;
/// [`transition_limit`]) over a belt's contact points: for each point its motion at the
/// iterate, its motion at the corrected state (the full correction applied) and its pulley's
/// friction law, the largest fraction `α ∈ (0, 1]` of the correction that takes no point in
/// contact at the iterate (penetration > 0) across the law's steep band
/// ([`FrictionLaw::transition_width`]) in one iteration. The slip change is the difference of
/// the exact slip velocities at the two states, so it carries every nonlinear term of the
/// model's kinematics (the turning normal, the convective term of a flowing belt, a node's
/// path along a wrap); the rule takes the slip as linear in `α` between them. Points of a law
/// without a band (Coulomb, frictionless) and open points do not limit (`1`).
pub fn correction_limit<'a, L: FrictionLaw + 'a>(
    points: impl IntoIterator<Item = (NodeMotion, NodeMotion, &'a L)>,
) -> f64 {
    let mut alpha: f64 = 1.0;
    for (now, next, law) in points {
        let Some(width) = law.transition_width() else {
            continue;
        };
        let (penetration, slip) = now.penetration_and_slip();
        if penetration <= 0.0 {
            continue;
        }
        let (_, end) = next.penetration_and_slip();
        alpha = alpha.min(transition_limit(slip, end - slip, width));
    }
    alpha
}

/// Force of one node–pulley contact and its derivatives.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NodeContact {
    /// Penetration `p` \[m\] (≤ 0: open, no force).
    pub penetration: f64,
    /// Normal force `F_N` \[N\].
    pub normal: f64,
    /// Tangential (friction) force `F_T` along the travel tangent \[N\].
    pub friction: f64,
    /// Slip velocity \[m/s\].
    pub slip: f64,
    /// Force on the belt node \[N\].
    pub force: [f64; 2],
    /// Reaction torque on the pulley in its travel sense \[N m\].
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
///
/// The contact maths is the contact crate's: [`point_contact`] against a rotating [`Disk`]
/// (Kerkkänen (3.21)–(3.25)), which turns counter-clockwise at `−turn·ω`; this function only
/// maps its counter-clockwise tangent `t_ccw = Ĩ n` onto the belt's travel tangent
/// `t = −turn·t_ccw` and adds the reaction torque on the pulley.
pub fn node_contact(
    pulley: &PulleyFrame, omega: f64, d: [f64; 2], vel: [f64; 2], normal_law: &impl NormalLaw,
    friction_law: &impl FrictionLaw,
) -> NodeContact {
    let sgn = -pulley.turn;
    let disk = pulley.disk(omega);
    let Some(c) = point_contact(
        &disk,
        normal_law,
        friction_law,
        &Point2::from(d),
        &Vector2::from(vel),
    ) else {
        let rel = [d[0] - pulley.center[0], d[1] - pulley.center[1]];
        return NodeContact {
            penetration: pulley.radius - rel[0].hypot(rel[1]),
            ..Default::default()
        };
    };
    let n = c.surface.normal;
    let tc = rot90(n);
    let dn = c.surface.dn_dp;
    let dtc = [[-dn[(1, 0)], -dn[(1, 1)]], [dn[(0, 0)], dn[(0, 1)]]];
    let r = pulley.radius;
    let f = c.force;
    // friction along the travel tangent: F_T = sgn·(t_ccw · f); torque τ = −R F_T
    let ft = sgn * c.friction.force;
    let df_dw = [sgn * c.df_domega[0], sgn * c.df_domega[1]];
    let mut dt_dd = [0.0; 2];
    let mut dt_dv = [0.0; 2];
    for j in 0..2 {
        dt_dd[j] = -r
            * sgn
            * (tc[0] * c.df_dp[(0, j)]
                + tc[1] * c.df_dp[(1, j)]
                + f[0] * dtc[0][j]
                + f[1] * dtc[1][j]);
        dt_dv[j] = -r * sgn * (tc[0] * c.df_dv[(0, j)] + tc[1] * c.df_dv[(1, j)]);
    }
    NodeContact {
        penetration: c.penetration,
        normal: c.normal.force,
        friction: ft,
        slip: sgn * c.slip,
        force: f.into(),
        torque: -ft * r,
        df_dd: c.df_dp.transpose().into(),
        df_dv: c.df_dv.transpose().into(),
        df_dw,
        dt_dd,
        dt_dv,
        dt_dw: -r * sgn * (tc[0] * df_dw[0] + tc[1] * df_dw[1]),
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
    // Slip reference: the pulley surface point under the node moves at ω R with R = 0.05 m (the
    // contact crate's nominal radius; re-baselined from ω r at the node, r = 0.0499 m).
    #[test]
    fn friction_direction_and_open_contact() {
        let n = [0.6f64, 0.8];
        let d = [0.1 + 0.0499 * n[0], -0.02 + 0.0499 * n[1]];
        let t = [n[1], -n[0]];
        let c = eval(d, [3.0 * t[0], 3.0 * t[1]], 3.0 / 0.05);
        assert!(c.friction.abs() < 1e-9 && c.normal > 0.0);
        // the old reference (ω r at the node) leaves a slip of ω·p = 6 mm/s here
        let old = eval(d, [3.0 * t[0], 3.0 * t[1]], 3.0 / 0.0499);
        assert!(
            (old.slip + 3.0 * 0.0001 / 0.0499).abs() < 1e-12,
            "{}",
            old.slip
        );
        let fast = eval(d, [3.1 * t[0], 3.1 * t[1]], 3.0 / 0.05);
        assert!(fast.friction < 0.0 && fast.torque > 0.0);
        assert!((fast.torque + fast.friction * 0.05).abs() < 1e-12);
        let open = eval([0.1 + 0.06, -0.02], [0.0, 0.0], 0.0);
        assert_eq!(open.force, [0.0, 0.0]);
    }
}
