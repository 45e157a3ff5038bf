//! Distributed contact along an element by Gauss quadrature: generalized forces
//! `Q_c = ∫₀ˡ S₀ᵀ (f_n + f_t) dx` (Kerkkänen (3.27)), their Jacobians with respect to the element
//! coordinates, velocities and the obstacle's angular velocity, the reaction torque on the
//! obstacle (Kerkkänen (3.26)), and per-point records of pressure and friction for output.
//!
//! The element enters only through its centreline shape functions `S₀(x) = [N₁I, N₂I, …]`
//! (2-vector blocks), so any ANCF (or other) line element can use it.

use crate::friction::FrictionLaw;
use crate::geometry::Surface;
use crate::normal::NormalLaw;
use crate::point::point_contact;
use crate::quadrature::GaussRule;

/// Largest number of 2-vector blocks per element supported by the stack buffers.
pub const MAX_BLOCKS: usize = 8;

/// Contact state at one quadrature point, for output (force distributions, slip zones).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactRecord {
    /// Element-local coordinate `ξ = x/l`.
    pub xi: f64,
    /// Position of the point \[m\].
    pub position: [f64; 2],
    /// Penetration \[m\].
    pub penetration: f64,
    /// Normal force per unit length \[N/m\] (pressure × width).
    pub normal_force: f64,
    /// Friction force per unit length along `t` \[N/m\].
    pub friction_force: f64,
    /// Slip velocity \[m/s\].
    pub slip: f64,
}

/// Reusable output buffers of [`LineContact::element`] for an element with `ndof` coordinates.
#[derive(Debug, Clone)]
pub struct ElementContact {
    /// Number of element coordinates.
    pub ndof: usize,
    /// Generalized contact force `Q_c` \[N\].
    pub q: Vec<f64>,
    /// `∂Q_c/∂e` (column-major `ndof × ndof`) \[N/m\].
    pub dq_de: Vec<f64>,
    /// `∂Q_c/∂ė` (column-major) \[N·s/m\].
    pub dq_dedot: Vec<f64>,
    /// `∂Q_c/∂ω` \[N·s\].
    pub dq_domega: Vec<f64>,
    /// Torque of the contact forces on the obstacle about its centre \[N·m\], Kerkkänen (3.26).
    pub torque: f64,
    /// `∂τ/∂e`.
    pub dtorque_de: Vec<f64>,
    /// `∂τ/∂ė`.
    pub dtorque_dedot: Vec<f64>,
    /// `∂τ/∂ω`.
    pub dtorque_domega: f64,
    /// Resultant force on the obstacle \[N\].
    pub reaction: [f64; 2],
    /// Number of quadrature points in contact.
    pub active_points: usize,
}

impl ElementContact {
    /// Zeroed buffers for an element with `ndof` coordinates.
    pub fn new(ndof: usize) -> Self {
        Self {
            ndof,
            q: vec![0.0; ndof],
            dq_de: vec![0.0; ndof * ndof],
            dq_dedot: vec![0.0; ndof * ndof],
            dq_domega: vec![0.0; ndof],
            torque: 0.0,
            dtorque_de: vec![0.0; ndof],
            dtorque_dedot: vec![0.0; ndof],
            dtorque_domega: 0.0,
            reaction: [0.0; 2],
            active_points: 0,
        }
    }

    fn clear(&mut self, jac: bool) {
        self.q.fill(0.0);
        if jac {
            self.dq_de.fill(0.0);
            self.dq_dedot.fill(0.0);
            self.dq_domega.fill(0.0);
            self.dtorque_de.fill(0.0);
            self.dtorque_dedot.fill(0.0);
        }
        self.torque = 0.0;
        self.dtorque_domega = 0.0;
        self.reaction = [0.0; 2];
        self.active_points = 0;
    }
}

/// A distributed contact pairing: obstacle, laws and quadrature rule.
#[derive(Debug, Clone)]
pub struct LineContact<S, NL, FL> {
    /// Obstacle.
    pub surface: S,
    /// Normal law (per unit length).
    pub normal: NL,
    /// Friction law (per unit length).
    pub friction: FL,
    /// Gauss rule along the element (Kerkkänen: 5, 7 or 11 points give identical results).
    pub rule: GaussRule,
}

impl<S: Surface, NL: NormalLaw, FL: FrictionLaw> LineContact<S, NL, FL> {
    /// Contact of one element of length `length` \[m\] whose centreline shape functions are
    /// `shape(ξ, N)` (`blocks` values), with coordinates `e` and velocities `edot`.
    /// Fills `out` (forces always; Jacobians when `jacobian`), appends point records to
    /// `records` when given.
    #[allow(clippy::too_many_arguments)]
    pub fn element(
        &self,
        length: f64,
        blocks: usize,
        shape: impl Fn(f64, &mut [f64]),
        e: &[f64],
        edot: &[f64],
        jacobian: bool,
        out: &mut ElementContact,
        records: Option<&mut Vec<ContactRecord>>,
    ) {
        self.element_on(
            &self.surface,
            length,
            blocks,
            shape,
            e,
            edot,
            jacobian,
            out,
            records,
        );
    }

    /// As [`LineContact::element`] but against `surface` instead of `self.surface` (an obstacle
    /// whose state — e.g. a pulley's angular velocity — changes between calls, without
    /// rebuilding the pairing).
    #[allow(clippy::too_many_arguments)]
    pub fn element_on(
        &self,
        surface: &S,
        length: f64,
        blocks: usize,
        shape: impl Fn(f64, &mut [f64]),
        e: &[f64],
        edot: &[f64],
        jacobian: bool,
        out: &mut ElementContact,
        mut records: Option<&mut Vec<ContactRecord>>,
    ) {
        let ndof = 2 * blocks;
        debug_assert!(blocks <= MAX_BLOCKS && out.ndof == ndof);
        out.clear(jacobian);
        let c = surface.center();
        let mut s = [0.0; MAX_BLOCKS];
        for (xi, wq) in self.rule.iter() {
            shape(xi, &mut s[..blocks]);
            let mut p = [0.0; 2];
            let mut v = [0.0; 2];
            for k in 0..blocks {
                p[0] += s[k] * e[2 * k];
                p[1] += s[k] * e[2 * k + 1];
                v[0] += s[k] * edot[2 * k];
                v[1] += s[k] * edot[2 * k + 1];
            }
            let Some(pc) = point_contact(surface, &self.normal, &self.friction, p, v) else {
                continue;
            };
            out.active_points += 1;
            let w = wq * length;
            let f = pc.force;
            let arm = [p[0] - c[0], p[1] - c[1]];
            for k in 0..blocks {
                out.q[2 * k] += w * s[k] * f[0];
                out.q[2 * k + 1] += w * s[k] * f[1];
            }
            out.reaction[0] -= w * f[0];
            out.reaction[1] -= w * f[1];
            // τ = arm × (−f)
            out.torque -= w * (arm[0] * f[1] - arm[1] * f[0]);
            if jacobian {
                for j in 0..blocks {
                    for b in 0..2 {
                        let col = 2 * j + b;
                        for i in 0..blocks {
                            let sij = w * s[i] * s[j];
                            for a in 0..2 {
                                let row = 2 * i + a;
                                out.dq_de[row + col * ndof] += sij * pc.df_dp[a][b];
                                out.dq_dedot[row + col * ndof] += sij * pc.df_dv[a][b];
                            }
                        }
                        // ∂τ/∂p_b = −[δ_0b f_y − δ_1b f_x + arm_x ∂f_y/∂p_b − arm_y ∂f_x/∂p_b]
                        let dfp = (arm[0] * pc.df_dp[1][b] - arm[1] * pc.df_dp[0][b])
                            + if b == 0 { f[1] } else { -f[0] };
                        let dfv = arm[0] * pc.df_dv[1][b] - arm[1] * pc.df_dv[0][b];
                        out.dtorque_de[col] -= w * s[j] * dfp;
                        out.dtorque_dedot[col] -= w * s[j] * dfv;
                    }
                    out.dq_domega[2 * j] += w * s[j] * pc.df_domega[0];
                    out.dq_domega[2 * j + 1] += w * s[j] * pc.df_domega[1];
                }
                out.dtorque_domega -= w * (arm[0] * pc.df_domega[1] - arm[1] * pc.df_domega[0]);
            }
            if let Some(r) = records.as_deref_mut() {
                r.push(ContactRecord {
                    xi,
                    position: p,
                    penetration: pc.penetration,
                    normal_force: pc.normal.force,
                    friction_force: pc.friction.force,
                    slip: pc.slip,
                });
            }
        }
    }
}
