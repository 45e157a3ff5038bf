//! A rigid multibody system (bodies + constraints + force elements) implementing
//! [`SecondOrderSystem`] with Euler parameters.
//!
//! Per body `q = (r, p)` (7) and `v = (ṙ, ω')` (6, body-frame angular velocity), so that the
//! mass matrix `diag(m I, J')` is constant and the Newton–Euler equations read
//! `m r̈ = f`, `J' ω̇' = n' − ω̃' J' ω'` (Lin (2.25)–(2.26)); `ṗ = ½ Lᵀ ω'` (Lin (2.14)).
//! The constrained equations are Ribaric (2.16) / Lin (2.27), with reactions `−Dᵀλ`.

use crate::body::{
    BodyId, BodyKin, BodyState, RigidBody, frame_integrate, frame_normalize, frame_position_rate,
};
use crate::constraints::{Constraint, ConstraintSet, Equation};
use crate::forces::ForceElement;
use crate::integrators::State;
use crate::kinematics::euler::compose_local_rotation;
use crate::kinematics::tilde::tilde;
use crate::kinematics::tilde::{get3, get4, put3, put4};
use crate::marker::{Carrier, Marker};
use crate::system::ForceTangent;
use crate::{MbdError, SecondOrderSystem, SysMatrix, Workspace};
use faer::sparse::Triplet;
use nalgebra::Vector3;

/// Number of bodies above which matrices are returned sparse.
pub const SPARSE_THRESHOLD: usize = 12;

/// Reaction of one constraint on its two bodies (global force \[N\] at the mass centre and
/// global torque about the mass centre \[N·m\]), from `−Dᵀλ`.
#[derive(Debug, Clone, PartialEq)]
pub struct Reaction {
    /// Constraint name.
    pub name: String,
    /// Force on body i (zero for the ground).
    pub force_i: Vector3<f64>,
    /// Torque on body i.
    pub torque_i: Vector3<f64>,
    /// Force on body j.
    pub force_j: Vector3<f64>,
    /// Torque on body j.
    pub torque_j: Vector3<f64>,
}

/// Rigid bodies, constraints and force elements.
#[derive(Default)]
pub struct MultibodySystem {
    bodies: Vec<RigidBody>,
    constraints: ConstraintSet,
    forces: Vec<Box<dyn ForceElement>>,
    /// Force sparse (`Some(true)`) or dense (`Some(false)`) matrices; `None`: dense up to
    /// [`SPARSE_THRESHOLD`] bodies.
    pub sparse: Option<bool>,
}

impl MultibodySystem {
    /// Empty system.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a body, returns its id.
    pub fn add_body(&mut self, body: RigidBody) -> BodyId {
        self.bodies.push(body);
        self.bodies.len() - 1
    }

    fn check_body(&self, b: Option<BodyId>, what: &str) -> Result<(), MbdError> {
        if let Some(b) = b
            && b >= self.bodies.len()
        {
            return Err(MbdError::InvalidInput {
                item: what.into(),
                reason: format!(
                    "refers to body {b}, but the system has {} bodies",
                    self.bodies.len()
                ),
            });
        }
        Ok(())
    }

    /// Adds a constraint (validates its markers: rigid bodies of this system or the ground);
    /// returns its index.
    pub fn add_constraint(&mut self, c: impl Constraint + 'static) -> Result<usize, MbdError> {
        let n = self.bodies.len();
        self.constraints.add(Box::new(c), |m: &Marker, what: &str| {
            if m.node.is_some() {
                return Err(MbdError::InvalidInput {
                    item: what.into(),
                    reason: "a rigid multibody system has no flexible nodes".into(),
                });
            }
            match m.body {
                Some(b) if b >= n => Err(MbdError::InvalidInput {
                    item: what.into(),
                    reason: format!("refers to body {b}, but the system has {n} bodies"),
                }),
                _ => Ok(()),
            }
        })
    }

    /// Adds a force element (validates its body references).
    pub fn add_force(&mut self, f: impl ForceElement + 'static) -> Result<(), MbdError> {
        let what = format!("force element \"{}\"", f.name());
        f.validate()?;
        for b in f.bodies() {
            self.check_body(b, &what)?;
        }
        self.forces.push(Box::new(f));
        Ok(())
    }

    /// Bodies.
    pub fn bodies(&self) -> &[RigidBody] {
        &self.bodies
    }

    /// Constraints.
    pub fn constraints(&self) -> &[Box<dyn Constraint>] {
        self.constraints.constraints()
    }

    /// First row of constraint `c` in `Φ` and `λ`.
    pub fn constraint_offset(&self, c: usize) -> usize {
        self.constraints.offset(c)
    }

    /// Assembles the system state from body states (validated: unit `p`, finite values).
    pub fn state(&self, t: f64, states: &[BodyState]) -> Result<State, MbdError> {
        if states.len() != self.bodies.len() {
            return Err(MbdError::InvalidInput {
                item: "initial state".into(),
                reason: format!(
                    "{} body states given for {} bodies",
                    states.len(),
                    self.bodies.len()
                ),
            });
        }
        let mut q = vec![0.0; 7 * states.len()];
        let mut v = vec![0.0; 6 * states.len()];
        for (k, s) in states.iter().enumerate() {
            s.check(&self.bodies[k].name).map_err(|e| match e {
                MbdError::InvalidInput { item, reason } => MbdError::InvalidInput {
                    item: format!("{item} at t = {t} s"),
                    reason,
                },
                other => other,
            })?;
            put3(&mut q, 7 * k, &s.r);
            put4(&mut q, 7 * k + 3, &s.p);
            put3(&mut v, 6 * k, &s.rdot);
            put3(&mut v, 6 * k + 3, &s.omega_local);
        }
        Ok(State::new(t, q, v))
    }

    /// State of body `k`.
    pub fn body_state(&self, state: &State, k: BodyId) -> BodyState {
        BodyState {
            r: get3(&state.q, 7 * k),
            p: get4(&state.q, 7 * k + 3),
            rdot: get3(&state.v, 6 * k),
            omega_local: get3(&state.v, 6 * k + 3),
        }
    }

    /// Kinematics of every body (velocities zero when `v` is `None`).
    pub fn kinematics(&self, q: &[f64], v: Option<&[f64]>) -> Vec<BodyKin> {
        (0..self.bodies.len())
            .map(|k| {
                let (rd, w) = match v {
                    Some(v) => (get3(v, 6 * k), get3(v, 6 * k + 3)),
                    None => (Vector3::zeros(), Vector3::zeros()),
                };
                BodyKin::new(get3(q, 7 * k), get4(q, 7 * k + 3), rd, w)
            })
            .collect()
    }

    /// Checks that every Euler-parameter vector is unit (within 1e-6) at time `t`.
    pub fn check_euler_parameters(&self, t: f64, q: &[f64]) -> Result<(), MbdError> {
        for (k, b) in self.bodies.iter().enumerate() {
            let p = get4(q, 7 * k + 3);
            let n = p.norm_squared();
            if !n.is_finite() {
                return Err(MbdError::NonFinite {
                    what: format!("Euler parameters of body \"{}\"", b.name),
                    t,
                });
            }
            if (n - 1.0).abs() > 1e-6 {
                return Err(MbdError::InvalidInput {
                    item: format!("body \"{}\": Euler parameters at t = {t} s", b.name),
                    reason: format!("pᵀp − 1 = {:.3e}", n - 1.0),
                });
            }
        }
        Ok(())
    }

    fn equations(&self, t: f64, q: &[f64], v: Option<&[f64]>) -> Vec<Equation> {
        let kin = self.kinematics(q, v);
        let mut out = Vec::new();
        self.constraints.eval(
            t,
            |m| {
                m.body
                    .map(|b| Carrier::rigid(kin[b]))
                    .unwrap_or_else(Carrier::ground)
            },
            &mut out,
        );
        out
    }

    fn use_sparse(&self) -> bool {
        self.sparse.unwrap_or(self.bodies.len() > SPARSE_THRESHOLD)
    }

    /// Kinetic energy `½ Σ (m ṙᵀṙ + ω'ᵀ J' ω')` \[J\].
    pub fn kinetic_energy(&self, state: &State) -> f64 {
        self.bodies
            .iter()
            .enumerate()
            .map(|(k, b)| {
                let rd = get3(&state.v, 6 * k);
                let w = get3(&state.v, 6 * k + 3);
                0.5 * (b.mass * rd.norm_squared() + w.dot(&(b.inertia * w)))
            })
            .sum()
    }

    /// Potential energy of the force elements \[J\].
    pub fn potential_energy(&self, state: &State) -> f64 {
        let kin = self.kinematics(&state.q, Some(&state.v));
        self.forces
            .iter()
            .map(|f| f.potential_energy(&self.bodies, &kin))
            .sum()
    }

    /// Linear momentum `Σ m ṙ` \[kg·m/s\].
    pub fn linear_momentum(&self, state: &State) -> Vector3<f64> {
        self.bodies
            .iter()
            .enumerate()
            .map(|(k, b)| get3(&state.v, 6 * k) * b.mass)
            .sum()
    }

    /// Angular momentum about the global origin `Σ (r × m ṙ + A J' ω')` \[kg·m²/s\].
    pub fn angular_momentum(&self, state: &State) -> Vector3<f64> {
        let kin = self.kinematics(&state.q, Some(&state.v));
        self.bodies
            .iter()
            .zip(&kin)
            .map(|(b, k)| k.r.cross(&(k.rdot * b.mass)) + k.a * (b.inertia * k.w))
            .sum()
    }

    /// Reaction forces per constraint from the multipliers `λ` (Lin (2.27): reaction `−Dᵀλ`).
    pub fn reactions(&self, state: &State, lambda: &[f64]) -> Result<Vec<Reaction>, MbdError> {
        if lambda.len() != self.n_c() {
            return Err(MbdError::InvalidInput {
                item: "multipliers".into(),
                reason: format!("length {} (expected {})", lambda.len(), self.n_c()),
            });
        }
        let eqs = self.equations(state.t, &state.q, Some(&state.v));
        let kin = self.kinematics(&state.q, None);
        let mut out = Vec::new();
        for (ci, c) in self.constraints().iter().enumerate() {
            let [bi, bj] = c.bodies();
            let mut gi = [0.0; 6];
            let mut gj = [0.0; 6];
            for r in 0..c.n_eq() {
                let row = self.constraint_offset(ci) + r;
                for k in 0..6 {
                    gi[k] -= eqs[row].row.di[k] * lambda[row];
                    gj[k] -= eqs[row].row.dj[k] * lambda[row];
                }
            }
            let torque = |b: Option<BodyId>, g: &[f64; 6]| {
                b.map(|b| kin[b].a * Vector3::new(g[3], g[4], g[5]))
                    .unwrap_or_else(Vector3::zeros)
            };
            let force = |b: Option<BodyId>, g: &[f64; 6]| {
                if b.is_some() {
                    Vector3::new(g[0], g[1], g[2])
                } else {
                    Vector3::zeros()
                }
            };
            out.push(Reaction {
                name: c.name().into(),
                force_i: force(bi, &gi),
                torque_i: torque(bi, &gi),
                force_j: force(bj, &gj),
                torque_j: torque(bj, &gj),
            });
        }
        Ok(out)
    }

    fn matrix_from_triplets(
        &self, nr: usize, nc: usize, trip: Vec<Triplet<usize, usize, f64>>, t: f64,
    ) -> Result<SysMatrix, MbdError> {
        SysMatrix::from_triplets(nr, nc, &trip, self.use_sparse(), t)
    }
}

impl SecondOrderSystem for MultibodySystem {
    fn n_q(&self) -> usize {
        7 * self.bodies.len()
    }
    fn n_v(&self) -> usize {
        6 * self.bodies.len()
    }
    fn n_c(&self) -> usize {
        self.constraints.n_c()
    }

    fn position_rate(&self, q: &[f64], v: &[f64], qdot: &mut [f64]) {
        for k in 0..self.bodies.len() {
            frame_position_rate(q, v, 7 * k, 6 * k, qdot);
        }
    }

    fn normalize(&self, q: &mut [f64]) {
        for k in 0..self.bodies.len() {
            frame_normalize(q, 7 * k);
        }
    }

    /// `r + Δr`, `p ⊗ exp(Δθ'/2)` (exact rotation update, Lie-group generalized-α).
    fn integrate_position(&self, q: &[f64], dq: &[f64], q_new: &mut [f64]) {
        for k in 0..self.bodies.len() {
            frame_integrate(q, dq, 7 * k, 6 * k, q_new);
        }
    }

    fn mass_is_constant(&self) -> bool {
        true
    }

    fn mass(&self, t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        let n = self.n_v();
        let mut trip = Vec::with_capacity(12 * self.bodies.len());
        for (k, b) in self.bodies.iter().enumerate() {
            for c in 0..3 {
                trip.push(Triplet::new(6 * k + c, 6 * k + c, b.mass));
                for d in 0..3 {
                    trip.push(Triplet::new(
                        6 * k + 3 + c,
                        6 * k + 3 + d,
                        b.inertia[(c, d)],
                    ));
                }
            }
        }
        self.matrix_from_triplets(n, n, trip, t)
    }

    fn forces(
        &self, t: f64, q: &[f64], v: &[f64], f: &mut [f64], _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        f.fill(0.0);
        let kin = self.kinematics(q, Some(v));
        for (k, b) in self.bodies.iter().enumerate() {
            let w = kin[k].w;
            let gyro = -w.cross(&(b.inertia * w));
            put3(f, 6 * k + 3, &gyro);
        }
        for fe in &self.forces {
            fe.apply(t, &self.bodies, &kin, f);
        }
        if let Some(i) = f.iter().position(|x| !x.is_finite()) {
            return Err(MbdError::NonFinite {
                what: format!("force on {} (element output)", self.dof_name(i)),
                t,
            });
        }
        Ok(())
    }

    /// Analytic gyroscopic damping `C = ω̃'J' − (J'ω')~` per body (from Lin (2.26)) plus, for
    /// each state-dependent force element, forward differences over the (at most two) bodies
    /// it acts on, so that the tangent stays sparse.
    fn force_tangent(
        &self, t: f64, q: &[f64], v: &[f64], _ws: &mut Workspace,
    ) -> Result<Option<ForceTangent>, MbdError> {
        let n = self.n_v();
        let kin = self.kinematics(q, Some(v));
        let mut kt: Vec<Triplet<usize, usize, f64>> = Vec::new();
        let mut ct: Vec<Triplet<usize, usize, f64>> = Vec::new();
        for (k, b) in self.bodies.iter().enumerate() {
            let w = kin[k].w;
            let c = tilde(&w) * b.inertia - tilde(&(b.inertia * w));
            for i in 0..3 {
                for j in 0..3 {
                    ct.push(Triplet::new(6 * k + 3 + i, 6 * k + 3 + j, c[(i, j)]));
                }
            }
        }
        let mut f0 = vec![0.0; n];
        let mut f1 = vec![0.0; n];
        for fe in &self.forces {
            if fe.is_state_independent() {
                continue;
            }
            let mut bs: Vec<usize> = fe.bodies().into_iter().flatten().collect();
            bs.sort_unstable();
            bs.dedup();
            if bs.is_empty() {
                continue;
            }
            f0.fill(0.0);
            fe.apply(t, &self.bodies, &kin, &mut f0);
            // the column `6 b + c` of `−∂f/∂x` by the forward difference of the perturbed
            // kinematics `kp` with step `h`, into `out`
            let mut column = |kp: &[BodyKin], h: f64, b: usize, c: usize, out: &mut Vec<_>| {
                f1.fill(0.0);
                fe.apply(t, &self.bodies, kp, &mut f1);
                for &r in &bs {
                    for i in 0..6 {
                        let d = -(f1[6 * r + i] - f0[6 * r + i]) / h;
                        if d != 0.0 {
                            out.push(Triplet::new(6 * r + i, 6 * b + c, d));
                        }
                    }
                }
            };
            for &b in &bs {
                for c in 0..6 {
                    let mut kp = kin.clone();
                    // position perturbation through ⊕ (translation or body-frame rotation)
                    let eps = 1e-7 * (1.0 + if c < 3 { kin[b].r[c].abs() } else { 0.0 });
                    if c < 3 {
                        kp[b].r[c] += eps;
                    } else {
                        let mut th = Vector3::zeros();
                        th[c - 3] = eps;
                        let p = compose_local_rotation(&kin[b].p, &th);
                        kp[b] = BodyKin::new(kin[b].r, p, kin[b].rdot, kin[b].w);
                    }
                    column(&kp, eps, b, c, &mut kt);
                    // velocity perturbation
                    let mut kp = kin.clone();
                    let ev = 1e-7 * (1.0 + v[6 * b + c].abs());
                    if c < 3 {
                        kp[b].rdot[c] += ev;
                    } else {
                        kp[b].w[c - 3] += ev;
                    }
                    column(&kp, ev, b, c, &mut ct);
                }
            }
        }
        Ok(Some(ForceTangent {
            stiffness: self.matrix_from_triplets(n, n, kt, t)?,
            damping: self.matrix_from_triplets(n, n, ct, t)?,
        }))
    }

    /// `∂(Dᵀλ)/∂q` by forward differences local to each constraint's two bodies (sparse).
    fn constraint_force_tangent(
        &self, t: f64, q: &[f64], lambda: &[f64],
    ) -> Result<Option<SysMatrix>, MbdError> {
        let n = self.n_v();
        let kin = self.kinematics(q, None);
        let ground = BodyKin::ground();
        let mut trip: Vec<Triplet<usize, usize, f64>> = Vec::new();
        let mut eqs = Vec::new();
        // generalized constraint force Dᵀλ of one constraint on its bodies (12 entries)
        let gen_force = |c: &dyn Constraint,
                         off: usize,
                         ki: &BodyKin,
                         kj: &BodyKin,
                         eqs: &mut Vec<Equation>|
         -> [f64; 12] {
            eqs.clear();
            c.eval(t, &Carrier::rigid(*ki), &Carrier::rigid(*kj), eqs);
            let mut g = [0.0; 12];
            for (r, e) in eqs.iter().enumerate() {
                let l = lambda[off + r];
                for k in 0..6 {
                    g[k] += e.row.di[k] * l;
                    g[6 + k] += e.row.dj[k] * l;
                }
            }
            g
        };
        for (ci, c) in self.constraints().iter().enumerate() {
            let off = self.constraint_offset(ci);
            if lambda[off..off + c.n_eq()].iter().all(|&l| l == 0.0) {
                continue;
            }
            let bodies = c.bodies();
            let kof = |b: Option<BodyId>| b.map(|b| kin[b]).unwrap_or(ground);
            let (ki, kj) = (kof(bodies[0]), kof(bodies[1]));
            let g0 = gen_force(c.as_ref(), off, &ki, &kj, &mut eqs);
            for (side, b) in bodies.iter().enumerate() {
                let Some(b) = *b else { continue };
                let kb = kin[b];
                for col in 0..6 {
                    let eps = 1e-7 * (1.0 + if col < 3 { kb.r[col].abs() } else { 0.0 });
                    let mut kp = kb;
                    if col < 3 {
                        kp.r[col] += eps;
                    } else {
                        let mut th = Vector3::zeros();
                        th[col - 3] = eps;
                        kp = BodyKin::new(kb.r, compose_local_rotation(&kb.p, &th), kb.rdot, kb.w);
                    }
                    let (pi, pj) = if side == 0 { (kp, kj) } else { (ki, kp) };
                    let g1 = gen_force(c.as_ref(), off, &pi, &pj, &mut eqs);
                    for (rs, rb) in bodies.iter().enumerate() {
                        let Some(rb) = *rb else { continue };
                        for k in 0..6 {
                            let d = (g1[6 * rs + k] - g0[6 * rs + k]) / eps;
                            if d != 0.0 {
                                trip.push(Triplet::new(6 * rb + k, 6 * b + col, d));
                            }
                        }
                    }
                }
            }
        }
        Ok(Some(self.matrix_from_triplets(n, n, trip, t)?))
    }

    fn constraint_residual(&self, t: f64, q: &[f64], phi: &mut [f64]) -> Result<(), MbdError> {
        for (p, e) in phi.iter_mut().zip(self.equations(t, q, None)) {
            *p = e.row.phi;
        }
        Ok(())
    }

    fn constraint_jacobian(&self, t: f64, q: &[f64]) -> Result<SysMatrix, MbdError> {
        let eqs = self.equations(t, q, None);
        let mut trip = Vec::with_capacity(12 * eqs.len());
        self.constraints.jacobian_entries(
            &eqs,
            0,
            |m| m.body.map(|b| (6 * b, 6 * b + 6)),
            |r, c, x| trip.push(Triplet::new(r, c, x)),
        );
        self.matrix_from_triplets(self.n_c(), self.n_v(), trip, t)
    }

    fn constraint_velocity_rhs(&self, t: f64, q: &[f64], nu: &mut [f64]) -> Result<(), MbdError> {
        for (p, e) in nu.iter_mut().zip(self.equations(t, q, None)) {
            *p = e.nu;
        }
        Ok(())
    }

    fn constraint_gamma(
        &self, t: f64, q: &[f64], v: &[f64], gamma: &mut [f64],
    ) -> Result<(), MbdError> {
        for (p, e) in gamma.iter_mut().zip(self.equations(t, q, Some(v))) {
            *p = e.gamma;
        }
        Ok(())
    }

    fn check_state(&self, t: f64, q: &[f64], _v: &[f64]) -> Result<(), MbdError> {
        self.check_euler_parameters(t, q)
    }

    fn constraint_name(&self, row: usize) -> String {
        self.constraints
            .row_name(row)
            .unwrap_or_else(|| format!("constraint row {row}"))
    }

    fn dof_name(&self, dof: usize) -> String {
        let k = dof / 6;
        let names = ["x", "y", "z", "ωx'", "ωy'", "ωz'"];
        match self.bodies.get(k) {
            Some(b) => format!("body \"{}\" {}", b.name, names[dof % 6]),
            None => format!("coordinate {dof}"),
        }
    }
}
