//! The drive's rigid coordinates beside the belt's, one numbering for the flowing
//! ([`super::FlowingBelt`]) and the nodal ([`super::NodalBelt`]) belt: the free pulleys'
//! rotations (pulley order, [`belt::Motion`]), the tensioner arm's rotation `Δθ` from its static
//! angle ([`belt::Arm`]) and the decouplers' carrier and accessory rotations
//! ([`belt::decoupler`]); with their inertias, applied forces (load torques and dampers, the
//! decouplers' (D3), the arm's spring, damper and dry friction, [`belt::tensioner`]) and the
//! tangent of those forces. The contact forces on these coordinates are each model's own.

use super::contact::NodeContact;
use belt::tensioner::cross;
use belt::{Arm, DecouplerState, Motion, PulleyCoordinates};

/// The local coordinates of a pulley's decoupler ([`belt::decoupler`]): the pulley's own
/// velocity index, then the carrier's (with a clutch) and the accessory's.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct DecouplerDofs {
    /// Pulley index.
    pub pulley: usize,
    /// Velocity indices `[φ_p, (φ_r,) φ_a]`.
    pub dofs: Vec<usize>,
}

/// The rigid coordinates of a belt drive: which velocity index each free pulley, the tensioner
/// arm and each decoupler has, and the motions and arm they follow.
#[derive(Debug, Clone)]
pub struct DriveCoordinates {
    /// How each pulley turns, in pulley order (a changed motion must keep each pulley's
    /// kind: speed-driven or free, with or without a decoupler, as numbered).
    pub motions: Vec<Motion>,
    /// The tensioner's arm, if any (at its static angle on the laid-out path).
    pub tensioner: Option<Arm>,
    /// Velocity index of each free pulley's speed ([`belt::PulleyCoordinates`]).
    pulleys: PulleyCoordinates,
    /// Velocity index of the tensioner arm.
    arm_dof: Option<usize>,
    /// The decouplers' coordinates (after the arm's).
    decouplers: Vec<DecouplerDofs>,
}

impl DriveCoordinates {
    /// Numbers the coordinates from `*next` (advanced past them): the free pulleys in pulley
    /// order, the arm, then the decouplers' carriers and accessories in pulley order.
    pub(crate) fn number(motions: Vec<Motion>, tensioner: Option<Arm>, next: &mut usize) -> Self {
        let pulleys = PulleyCoordinates::new(&motions, *next);
        *next += pulleys.count();
        let arm_dof = tensioner.map(|_| {
            *next += 1;
            *next - 1
        });
        let mut decouplers = Vec::new();
        for (p, k) in pulleys.free() {
            if let Some(d) = motions[p].decoupler() {
                let mut dofs = vec![k];
                dofs.extend(*next..*next + d.n_extra());
                *next += d.n_extra();
                decouplers.push(DecouplerDofs { pulley: p, dofs });
            }
        }
        Self {
            motions,
            tensioner,
            pulleys,
            arm_dof,
            decouplers,
        }
    }

    /// The same numbering with every speed-driven pulley at rest ([`Motion::at_rest`]): the
    /// static problem's coordinates.
    pub(crate) fn at_rest(&self) -> Self {
        Self {
            motions: self.motions.iter().map(Motion::at_rest).collect(),
            ..self.clone()
        }
    }

    /// Velocity index of pulley `p`'s speed (`None`: prescribed).
    pub fn pulley_dof(&self, p: usize) -> Option<usize> {
        self.pulleys.dof(p)
    }

    /// Velocity index of the tensioner arm's rotation `Δθ` (`None`: no tensioner).
    pub fn arm_dof(&self) -> Option<usize> {
        self.arm_dof
    }

    /// Speed of pulley `p` \[rad/s\] at `(t, v)`, positive in the travel sense: its coordinate's
    /// rate, or its prescribed speed.
    pub fn pulley_speed(&self, p: usize, t: f64, v: &[f64]) -> f64 {
        self.pulleys.speed(&self.motions, p, t, v)
    }

    /// Arm angle θ \[rad\] at `q` (`None`: no tensioner).
    pub fn arm_angle(&self, q: &[f64]) -> Option<f64> {
        Some(self.tensioner?.angle + q[self.arm_dof?])
    }

    /// The decoupler of pulley `k` at `(q, v)` (`None`: none on that pulley).
    pub fn decoupler_state(&self, k: usize, q: &[f64], v: &[f64]) -> Option<DecouplerState> {
        let dd = self.decouplers.iter().find(|d| d.pulley == k)?;
        let d = self.motions[k].decoupler()?;
        let (ql, vl) = dd.local(q, v);
        Some(d.state(&ql, &vl))
    }

    /// Name of a rigid coordinate `d` (`None`: not one of them).
    pub(crate) fn dof_name(&self, d: usize) -> Option<String> {
        if let Some((p, _)) = self.pulleys.free().find(|&(_, k)| k == d) {
            return Some(format!("pulley {p} angle"));
        }
        if Some(d) == self.arm_dof {
            return Some("tensioner arm rotation".into());
        }
        self.decouplers.iter().find_map(|dd| {
            let a = dd.dofs.iter().position(|&i| i == d)?;
            let what = if a + 1 == dd.dofs.len() {
                "accessory"
            } else {
                "decoupler carrier"
            };
            Some(format!("pulley {} {what} angle", dd.pulley))
        })
    }

    /// The tensioner's idler (`None`: no tensioner).
    pub(crate) fn idler(&self) -> Option<usize> {
        self.tensioner.map(|a| a.tensioner.pulley)
    }

    /// The tensioner's idler: (pulley, centre \[m\], centre velocity \[m/s\]) at `(q, v)`
    /// (`None`: no tensioner).
    pub(crate) fn idler_motion(&self, q: &[f64], v: &[f64]) -> Option<(usize, [f64; 2], [f64; 2])> {
        let arm = self.arm_state(q, v)?;
        Some((self.tensioner?.tensioner.pulley, arm.center, arm.vel))
    }

    /// The arm's state at `(q, v)` (`None`: no tensioner).
    pub(crate) fn arm_state(&self, q: &[f64], v: &[f64]) -> Option<ArmState> {
        ArmState::at(self.tensioner?, self.arm_dof?, q, v)
    }

    /// The free pulleys: `(pulley, velocity index)`.
    pub(crate) fn free_pulleys(&self) -> Vec<(usize, usize)> {
        self.pulleys.free().collect()
    }

    /// The decouplers' extra coordinates (carrier, accessory): on them no contact acts.
    pub(crate) fn decoupler_extra_dofs(&self) -> impl Iterator<Item = usize> + '_ {
        self.decouplers
            .iter()
            .flat_map(|dd| dd.dofs[1..].iter().copied())
    }

    /// The diagonal of the mass matrix on the rigid coordinates, `(index, J)`: the free
    /// pulleys' inertias \[kg m²\] (a decoupled pulley's own), the decouplers' carrier and
    /// accessory inertias and the arm's.
    pub(crate) fn inertias(&self) -> Vec<(usize, f64)> {
        let mut out = Vec::new();
        for (p, k) in self.pulleys.free() {
            if let Some(inertia) = self.motions[p].pulley_inertia() {
                out.push((k, inertia));
            }
        }
        for dd in &self.decouplers {
            let mo = &self.motions[dd.pulley];
            if let (Some(d), Some(j)) = (mo.decoupler(), mo.inertia()) {
                for (&i, &jj) in dd.dofs.iter().zip(&d.inertias(j)).skip(1) {
                    out.push((i, jj));
                }
            }
        }
        if let (Some(a), Some(k)) = (self.tensioner, self.arm_dof) {
            out.push((k, a.tensioner.inertia));
        }
        out
    }

    /// Adds the forces on the rigid coordinates other than contact to `f` at `(t, q, v)`: the
    /// load torques and dampers of the pulleys without a decoupler, the decouplers' forces
    /// (D3; the accessory's load and damping act on its own coordinate,
    /// [`belt::Decoupler::forces`]) and the arm's spring, damper and friction moment
    /// ([`belt::Tensioner::moment`]).
    pub(crate) fn add_forces(&self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        for (p, k) in self.pulleys.free() {
            let mo = &self.motions[p];
            if mo.decoupler().is_none() {
                f[k] += mo.applied_torque(t, v[k]).0;
            }
        }
        for (dofs, d) in self.decoupler_forces(t, q, v) {
            for (&i, fi) in dofs.iter().zip(&d.f) {
                f[i] += fi;
            }
        }
        if let (Some(a), Some(tm), Some(k)) = (self.arm_state(q, v), self.tensioner, self.arm_dof) {
            f[k] += tm.tensioner.moment(a.angle, a.rate).0;
        }
    }

    /// The tangent of [`Self::add_forces`]: `add_k(i, j, −∂f_i/∂q_j)` and
    /// `add_c(i, j, −∂f_i/∂v_j)` for every non-zero entry (the arm's spring and damper, the
    /// pulleys' dampers, the decouplers' (D3)).
    pub(crate) fn add_tangent(
        &self, t: f64, q: &[f64], v: &[f64], mut add_k: impl FnMut(usize, usize, f64),
        mut add_c: impl FnMut(usize, usize, f64),
    ) {
        if let (Some(a), Some(tm), Some(k)) = (self.arm_state(q, v), self.tensioner, self.arm_dof) {
            let (_, ks, cs) = tm.tensioner.moment(a.angle, a.rate);
            add_k(k, k, -ks);
            add_c(k, k, -cs);
        }
        // the free pulleys' dampers: −c ω (behind a decoupler: the chain (D3))
        for (p, k) in self.pulleys.free() {
            let mo = &self.motions[p];
            if mo.decoupler().is_none() {
                add_c(k, k, -mo.applied_torque(t, v[k]).1);
            }
        }
        for (dofs, d) in self.decoupler_forces(t, q, v) {
            for (a, &i) in dofs.iter().enumerate() {
                for (b, &j) in dofs.iter().enumerate() {
                    add_k(i, j, -d.df_dq[a][b]);
                    add_c(i, j, -d.df_dv[a][b]);
                }
            }
        }
    }

    /// Forces (D3) of every decoupler at `(t, q, v)` with their local coordinates
    /// ([`belt::Decoupler::forces`]).
    fn decoupler_forces(
        &self, t: f64, q: &[f64], v: &[f64],
    ) -> Vec<(&[usize], belt::DecouplerForces)> {
        self.decouplers
            .iter()
            .filter_map(|dd| {
                let mo = &self.motions[dd.pulley];
                let d = mo.decoupler()?;
                let (ql, vl) = dd.local(q, v);
                let acc = mo.applied_torque(t, vl[vl.len() - 1]);
                Some((dd.dofs.as_slice(), d.forces(&ql, &vl, acc)))
            })
            .collect()
    }
}

impl DecouplerDofs {
    /// The decoupler's local coordinates and rates.
    fn local(&self, q: &[f64], v: &[f64]) -> (Vec<f64>, Vec<f64>) {
        (
            self.dofs.iter().map(|&i| q[i]).collect(),
            self.dofs.iter().map(|&i| v[i]).collect(),
        )
    }
}

impl ArmState {
    /// The idler's kinematics with the arm `a` at rotation `q[k]` from its static angle, rate
    /// `v[k]`: `c(θ) = p + L(cos θ, sin θ)` ([`belt::tensioner`]).
    pub(crate) fn at(a: Arm, k: usize, q: &[f64], v: &[f64]) -> Option<Self> {
        let angle = a.angle + q[k];
        let (center, dc) = a.tensioner.center(a.length, angle);
        let rate = v[k];
        Some(Self {
            center,
            dc,
            vel: [dc[0] * rate, dc[1] * rate],
            arm: [
                center[0] - a.tensioner.pivot[0],
                center[1] - a.tensioner.pivot[1],
            ],
            angle,
            rate,
        })
    }

    /// Derivatives of a node's contact force `F` and the idler's torque `τ` with respect to
    /// the arm rotation and its rate, `((∂F/∂θ, ∂τ/∂θ), (∂F/∂θ̇, ∂τ/∂θ̇))`: the contact sees
    /// `F(d − c(θ), V − c'θ̇, ω)`, so `∂/∂θ = −F_d c' + F_V (c − p) θ̇` (`c'' = −(c − p)`) and
    /// `∂/∂θ̇ = −F_V c'`.
    #[allow(clippy::type_complexity)]
    pub(crate) fn contact_derivatives(
        &self, c: &NodeContact,
    ) -> (([f64; 2], f64), ([f64; 2], f64)) {
        let mv = |m: &[[f64; 2]; 2], x: [f64; 2]| {
            [
                m[0][0] * x[0] + m[0][1] * x[1],
                m[1][0] * x[0] + m[1][1] * x[1],
            ]
        };
        let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
        let w = [self.arm[0] * self.rate, self.arm[1] * self.rate];
        let (fd, fv) = (mv(&c.df_dd, self.dc), mv(&c.df_dv, w));
        let fq = [fv[0] - fd[0], fv[1] - fd[1]];
        let tq = dot(c.dt_dv, w) - dot(c.dt_dd, self.dc);
        let fv = mv(&c.df_dv, self.dc);
        ((fq, tq), ([-fv[0], -fv[1]], -dot(c.dt_dv, self.dc)))
    }

    /// Moment about the pivot of the contact force `f` on the belt: `−(c − p) × f` (the force
    /// on the idler is `−f`).
    pub(crate) fn moment(&self, f: [f64; 2]) -> f64 {
        -cross(self.arm, f)
    }
}

/// The idler's kinematics at an arm state: centre, `c'`, centre velocity, `c − p`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ArmState {
    pub(crate) center: [f64; 2],
    pub(crate) dc: [f64; 2],
    pub(crate) vel: [f64; 2],
    pub(crate) arm: [f64; 2],
    pub(crate) angle: f64,
    pub(crate) rate: f64,
}
