//! A multibody system of floating-frame deformable bodies, rigid bodies, joints and drivers
//! between markers (the [`crate::constraints`] vocabulary shared with
//! [`crate::MultibodySystem`]), and loads (Lin (2.27), (5.10), (5.11), (5.18), (5.19), (7.9),
//! (8.29); Ribaric (2.45)–(2.52)).

use super::body::{AxisCondition, ElasticForces, FlexBody, flat, mat_vec};
use crate::body::{
    BodyKin, BodyState, RigidBody, frame_integrate, frame_normalize, frame_position_rate,
};
use crate::constraints::{Constraint, ConstraintSet, Equation};
use crate::integrators::State;
use crate::kinematics::tilde::{get3, get4, put3, put4, tilde};
use crate::marker::{Carrier, FlexNodes, Marker, NodeRotations, Term};
use crate::{MbdError, SecondOrderSystem, SysMatrix, Workspace};
use faer::Mat;
use nalgebra::{Matrix3, Vector3, Vector4};

/// State of one flexible body.
#[derive(Debug, Clone, PartialEq)]
pub struct FlexState {
    /// Frame origin \[m\].
    pub r: Vector3<f64>,
    /// Frame Euler parameters.
    pub p: Vector4<f64>,
    /// Frame origin velocity \[m/s\].
    pub rdot: Vector3<f64>,
    /// Body-frame angular velocity ω' \[rad/s\].
    pub omega_local: Vector3<f64>,
    /// Elastic coordinates z.
    pub z: Vec<f64>,
    /// Elastic velocities ż.
    pub zdot: Vec<f64>,
}

/// A global point force `force(t)` \[N\] applied at a marker point (rigid-body point or
/// flexible node without offset).
pub struct NodeLoad {
    /// Name used in messages.
    pub name: String,
    /// Point of application.
    pub point: Marker,
    /// Global force at time t \[N\].
    pub force: Box<dyn Fn(f64) -> Vector3<f64> + Send + Sync>,
}

struct FlexKin {
    frame: BodyKin,
    z: Vec<f64>,
    zd: Vec<f64>,
    /// deformed local positions b' = s' + Ψ'z
    b: Vec<Vector3<f64>>,
    /// local deflection rates δ̇' = Ψ'ż
    dd: Vec<Vector3<f64>>,
    /// node rotations θ = Φ_θ z and rates θ̇ (empty without slopes)
    theta: Vec<Vector3<f64>>,
    theta_dot: Vec<Vector3<f64>>,
}

/// A reference-condition row of a flexible body: sparse Jacobian entries and right-hand sides.
struct AxisRow {
    cols: Vec<(usize, f64)>,
    phi: f64,
    nu: f64,
    gamma: f64,
}

/// Rigid bodies + floating-frame flexible bodies + joints, drivers and loads; implements
/// [`SecondOrderSystem`].
///
/// Coordinates: rigid bodies first (`q = (r, p)`, `v = (ṙ, ω')`), then flexible bodies
/// (`q = (r, p, z)`, `v = (ṙ, ω', ż)`). Constraint rows: per flexible body the axis-condition
/// rows (6 for mean or principal axes, 0 for nodal-fixed), then the constraints in the order
/// they were added.
///
/// Markers: `node: None` refers to rigid body `body` (index from [`Self::add_rigid`]),
/// `node: Some(n)` to node `n` of flexible body `body` (index from [`Self::add_flex`]).
#[derive(Default)]
pub struct FloatingSystem {
    rigid: Vec<RigidBody>,
    flex: Vec<FlexBody>,
    constraints: ConstraintSet,
    loads: Vec<NodeLoad>,
    /// Gravitational acceleration \[m/s²\] (global).
    pub gravity: Vector3<f64>,
}

impl FloatingSystem {
    /// Empty system without gravity.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a rigid body; returns its rigid-body index.
    pub fn add_rigid(&mut self, b: RigidBody) -> usize {
        self.rigid.push(b);
        self.rigid.len() - 1
    }

    /// Adds a flexible body; returns its flexible-body index.
    pub fn add_flex(&mut self, b: FlexBody) -> usize {
        self.flex.push(b);
        self.flex.len() - 1
    }

    fn check_marker(&self, m: &Marker, what: &str) -> Result<(), MbdError> {
        check_marker(&self.rigid, &self.flex, m, what)
    }

    /// Adds a joint or driver (validates its markers); returns its index.
    pub fn add_constraint(&mut self, c: impl Constraint + 'static) -> Result<usize, MbdError> {
        let (rigid, flex) = (&self.rigid, &self.flex);
        self.constraints
            .add(Box::new(c), |m, what| check_marker(rigid, flex, m, what))
    }

    /// Constraints (joints and drivers), in row order after the axis-condition rows.
    pub fn constraints(&self) -> &[Box<dyn Constraint>] {
        self.constraints.constraints()
    }

    /// Adds a point load (validates the point).
    pub fn add_load(&mut self, l: NodeLoad) -> Result<(), MbdError> {
        let what = format!("load \"{}\"", l.name);
        self.check_marker(&l.point, &what)?;
        if l.point.node.is_some() && l.point.point != Vector3::zeros() {
            return Err(MbdError::InvalidInput {
                item: what,
                reason: "a load on a flexible node acts at the node (offset must be zero)".into(),
            });
        }
        self.loads.push(l);
        Ok(())
    }

    /// Flexible bodies.
    pub fn flex_bodies(&self) -> &[FlexBody] {
        &self.flex
    }

    /// Rigid bodies.
    pub fn rigid_bodies(&self) -> &[RigidBody] {
        &self.rigid
    }

    fn flex_offsets(&self) -> Vec<(usize, usize)> {
        let mut q = 7 * self.rigid.len();
        let mut v = 6 * self.rigid.len();
        self.flex
            .iter()
            .map(|f| {
                let o = (q, v);
                q += 7 + f.n_modes();
                v += 6 + f.n_modes();
                o
            })
            .collect()
    }

    fn n_axis_rows(f: &FlexBody) -> usize {
        match f.axis {
            AxisCondition::NodalFixed => 0,
            AxisCondition::MeanAxes | AxisCondition::PrincipalAxes => 6,
        }
    }

    /// Assembles the system state.
    pub fn state(
        &self, t: f64, rigid: &[BodyState], flex: &[FlexState],
    ) -> Result<State, MbdError> {
        if rigid.len() != self.rigid.len() || flex.len() != self.flex.len() {
            return Err(MbdError::InvalidInput {
                item: "initial state".into(),
                reason: format!(
                    "{} rigid and {} flexible states for {} rigid and {} flexible bodies",
                    rigid.len(),
                    flex.len(),
                    self.rigid.len(),
                    self.flex.len()
                ),
            });
        }
        let mut q = vec![0.0; self.n_q()];
        let mut v = vec![0.0; self.n_v()];
        for (k, s) in rigid.iter().enumerate() {
            s.check(&self.rigid[k].name)?;
            put3(&mut q, 7 * k, &s.r);
            put4(&mut q, 7 * k + 3, &s.p);
            put3(&mut v, 6 * k, &s.rdot);
            put3(&mut v, 6 * k + 3, &s.omega_local);
        }
        for ((k, s), (oq, ov)) in flex.iter().enumerate().zip(self.flex_offsets()) {
            let f = &self.flex[k];
            if s.z.len() != f.n_modes() || s.zdot.len() != f.n_modes() {
                return Err(MbdError::InvalidInput {
                    item: format!("flexible body \"{}\": initial state", f.name),
                    reason: format!(
                        "z has {} and ż {} entries, expected {}",
                        s.z.len(),
                        s.zdot.len(),
                        f.n_modes()
                    ),
                });
            }
            crate::kinematics::euler::check_unit(&s.p, &format!("flexible body \"{}\"", f.name))?;
            put3(&mut q, oq, &s.r);
            put4(&mut q, oq + 3, &s.p);
            q[oq + 7..oq + 7 + f.n_modes()].copy_from_slice(&s.z);
            put3(&mut v, ov, &s.rdot);
            put3(&mut v, ov + 3, &s.omega_local);
            v[ov + 6..ov + 6 + f.n_modes()].copy_from_slice(&s.zdot);
        }
        Ok(State::new(t, q, v))
    }

    /// State of flexible body `k`.
    pub fn flex_state(&self, state: &State, k: usize) -> FlexState {
        let (oq, ov) = self.flex_offsets()[k];
        let nz = self.flex[k].n_modes();
        FlexState {
            r: get3(&state.q, oq),
            p: get4(&state.q, oq + 3),
            rdot: get3(&state.v, ov),
            omega_local: get3(&state.v, ov + 3),
            z: state.q[oq + 7..oq + 7 + nz].to_vec(),
            zdot: state.v[ov + 6..ov + 6 + nz].to_vec(),
        }
    }

    /// State of rigid body `k`.
    pub fn rigid_state(&self, state: &State, k: usize) -> BodyState {
        BodyState {
            r: get3(&state.q, 7 * k),
            p: get4(&state.q, 7 * k + 3),
            rdot: get3(&state.v, 6 * k),
            omega_local: get3(&state.v, 6 * k + 3),
        }
    }

    /// Local deflection `δ'` of node `node` of flexible body `body` \[m\].
    pub fn node_deflection(&self, state: &State, body: usize, node: usize) -> Vector3<f64> {
        let fs = self.flex_state(state, body);
        let f = &self.flex[body];
        let mut d = Vector3::zeros();
        for (k, zk) in fs.z.iter().enumerate() {
            for c in 0..3 {
                d[c] += f.psi[(3 * node + c, k)] * zk;
            }
        }
        d
    }

    /// Global position of a marker point \[m\].
    pub fn point_position(&self, state: &State, m: &Marker) -> Vector3<f64> {
        let (rk, fk) = self.kinematics(&state.q, None);
        self.carrier(m, &rk, &fk).position(m)
    }

    /// Global velocity of a marker point, `ḋ = J v` \[m/s\] (Lin (5.2)).
    pub fn point_velocity(&self, state: &State, m: &Marker) -> Vector3<f64> {
        self.point_jv(state, &state.v, m, false)
    }

    /// Global acceleration of a marker point for the velocity derivatives `vdot` (e.g. from
    /// [`crate::integrators::accelerations`]): `d̈ = J v̇ + A w'` \[m/s²\] (Lin (5.3), (5.5)).
    ///
    /// # Panics
    /// If `vdot` is shorter than [`SecondOrderSystem::n_v`].
    pub fn point_acceleration(&self, state: &State, vdot: &[f64], m: &Marker) -> Vector3<f64> {
        self.point_jv(state, vdot, m, true)
    }

    /// `J x` (plus the quadratic term if `quad`) of a marker point.
    fn point_jv(&self, state: &State, x: &[f64], m: &Marker, quad: bool) -> Vector3<f64> {
        let (rk, fk) = self.kinematics(&state.q, Some(&state.v));
        let t = Term::point(&self.carrier(m, &rk, &fk), m, 0);
        let mut acc = if quad { t.quad } else { Vector3::zeros() };
        if let Some((f, z)) = self.columns(m) {
            for c in 0..6 {
                acc += t.ji.column(c) * x[f + c];
            }
            for c in 0..t.ei.ncols() {
                acc += t.ei.column(c) * x[z + c];
            }
        }
        acc
    }

    /// The carrier of a marker (ground, rigid body or flexible body with its nodes).
    fn carrier<'a>(&'a self, m: &Marker, rk: &[BodyKin], fk: &'a [FlexKin]) -> Carrier<'a> {
        match (m.body, m.node) {
            (None, _) => Carrier::ground(),
            (Some(b), None) => Carrier::rigid(rk[b]),
            (Some(b), Some(_)) => {
                let (f, k) = (&self.flex[b], &fk[b]);
                Carrier {
                    frame: k.frame,
                    flex: Some(FlexNodes {
                        b: &k.b,
                        bdot: &k.dd,
                        psi: f.psi.as_ref(),
                        rot: f.rot.as_ref().map(|r| NodeRotations {
                            theta: &k.theta,
                            theta_dot: &k.theta_dot,
                            slopes: r.as_ref(),
                        }),
                    }),
                }
            }
        }
    }

    /// First velocity columns of a marker's body frame and elastic coordinates.
    fn columns(&self, m: &Marker) -> Option<(usize, usize)> {
        let b = m.body?;
        Some(match m.node {
            None => (6 * b, 6 * b + 6),
            Some(_) => {
                let (_, ov) = self.flex_offsets()[b];
                (ov, ov + 6)
            }
        })
    }

    /// Mean-axis residuals of flexible body `k` (Lin Table 4-2, local):
    /// `[IhᵀM'δ' (3), IhᵀM'δ̇' (3), b~'ᵀM'δ̇' (3)]`.
    pub fn mean_axis_residuals(&self, state: &State, k: usize) -> [f64; 9] {
        let f = &self.flex[k];
        let fs = self.flex_state(state, k);
        let pz = mat_vec(f.ih_m_psi.as_ref(), &fs.z);
        let pzd = mat_vec(f.ih_m_psi.as_ref(), &fs.zdot);
        let (_, fk) = self.kinematics(&state.q, Some(&state.v));
        let dd = flat(&fk[k].dd);
        let mdd = f.m_mul(&dd);
        let mut rot = Vector3::zeros();
        for (i, b) in fk[k].b.iter().enumerate() {
            let x = Vector3::new(mdd[3 * i], mdd[3 * i + 1], mdd[3 * i + 2]);
            rot += x.cross(b);
        }
        [
            pz[0], pz[1], pz[2], pzd[0], pzd[1], pzd[2], rot.x, rot.y, rot.z,
        ]
    }

    /// Kinetic energy `½ vᵀ M v` \[J\].
    pub fn kinetic_energy(&self, state: &State) -> Result<f64, MbdError> {
        let m = self.mass(state.t, &state.q)?.to_dense();
        let mv = mat_vec(m.as_ref(), &state.v);
        Ok(0.5 * mv.iter().zip(&state.v).map(|(a, b)| a * b).sum::<f64>())
    }

    /// Potential energy: strain energy plus gravity `−Σ m g·d` \[J\].
    pub fn potential_energy(&self, state: &State) -> f64 {
        let (rk, fk) = self.kinematics(&state.q, None);
        let mut e = 0.0;
        for (b, k) in self.rigid.iter().zip(&rk) {
            e -= b.mass * self.gravity.dot(&k.r);
        }
        for (f, k) in self.flex.iter().zip(&fk) {
            e += f.strain_energy(&k.z);
            let mb = f.m_mul(&flat(&k.b));
            let mut c = Vector3::zeros();
            for (i, x) in mb.iter().enumerate() {
                c[i % 3] += x;
            }
            e -= self.gravity.dot(&(k.frame.r * f.mass() + k.frame.a * c));
        }
        e
    }

    fn kinematics(&self, q: &[f64], v: Option<&[f64]>) -> (Vec<BodyKin>, Vec<FlexKin>) {
        let frame = |oq: usize, ov: usize| {
            let (rd, w) = match v {
                Some(v) => (get3(v, ov), get3(v, ov + 3)),
                None => (Vector3::zeros(), Vector3::zeros()),
            };
            BodyKin::new(get3(q, oq), get4(q, oq + 3), rd, w)
        };
        let rk = (0..self.rigid.len()).map(|k| frame(7 * k, 6 * k)).collect();
        let fk = self
            .flex
            .iter()
            .zip(self.flex_offsets())
            .map(|(f, (oq, ov))| {
                let nz = f.n_modes();
                let z = q[oq + 7..oq + 7 + nz].to_vec();
                let zd = v
                    .map(|v| v[ov + 6..ov + 6 + nz].to_vec())
                    .unwrap_or_else(|| vec![0.0; nz]);
                let d = mat_vec(f.psi.as_ref(), &z);
                let dd = mat_vec(f.psi.as_ref(), &zd);
                let (theta, theta_dot) = match &f.rot {
                    Some(r) => (
                        vectors(&mat_vec(r.as_ref(), &z)),
                        vectors(&mat_vec(r.as_ref(), &zd)),
                    ),
                    None => (Vec::new(), Vec::new()),
                };
                FlexKin {
                    frame: frame(oq, ov),
                    b: f.s
                        .iter()
                        .enumerate()
                        .map(|(i, s)| s + Vector3::new(d[3 * i], d[3 * i + 1], d[3 * i + 2]))
                        .collect(),
                    dd: vectors(&dd),
                    z,
                    zd,
                    theta,
                    theta_dot,
                }
            })
            .collect();
        (rk, fk)
    }

    /// The reference-condition rows of every flexible body (Lin Table 4-2; Ribaric
    /// (2.42)–(2.44)).
    fn axis_rows(&self, fk: &[FlexKin]) -> Vec<AxisRow> {
        let mut rows = Vec::new();
        for ((f, k), (_, ov)) in self.flex.iter().zip(fk).zip(self.flex_offsets()) {
            if f.axis == AxisCondition::NodalFixed {
                continue;
            }
            let nz = f.n_modes();
            let oz = ov + 6;
            // translational mean-axis condition IhᵀM'Ψ'z = 0 (Lin (4.20), (8.26))
            let pz = mat_vec(f.ih_m_psi.as_ref(), &k.z);
            for a in 0..3 {
                rows.push(AxisRow {
                    cols: (0..nz).map(|m| (oz + m, f.ih_m_psi[(a, m)])).collect(),
                    phi: pz[a],
                    nu: 0.0,
                    gamma: 0.0,
                });
            }
            let dd = flat(&k.dd);
            let mdd = f.m_mul(&dd);
            let node = |x: &[f64], i: usize| Vector3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
            match f.axis {
                AxisCondition::MeanAxes => {
                    // b~'ᵀM'Ψ' ż = 0 (Lin (4.15)); b~'ᵀM'Ψ' z̈ = −skwstack(δ̇')ᵀM'δ̇' (4.17)
                    let mut dcols = vec![Vector3::zeros(); nz];
                    for (m, dc) in dcols.iter_mut().enumerate() {
                        for (i, b) in k.b.iter().enumerate() {
                            let x = Vector3::new(
                                f.m_psi[(3 * i, m)],
                                f.m_psi[(3 * i + 1, m)],
                                f.m_psi[(3 * i + 2, m)],
                            );
                            *dc += x.cross(b);
                        }
                    }
                    let mut g = Vector3::zeros();
                    for i in 0..k.dd.len() {
                        g += k.dd[i].cross(&node(&mdd, i));
                    }
                    for a in 0..3 {
                        rows.push(AxisRow {
                            cols: (0..nz).map(|m| (oz + m, dcols[m][a])).collect(),
                            // non-holonomic: no position-level residual (Lin Table 4-2)
                            phi: 0.0,
                            nu: 0.0,
                            gamma: g[a],
                        });
                    }
                }
                AxisCondition::PrincipalAxes => {
                    // J' = b~'ᵀM'b~' with zero products of inertia (Ribaric (2.42)–(2.44))
                    let skw_col = |x: &[Vector3<f64>], a: usize| -> Vec<f64> {
                        let e = Vector3::ith(a, 1.0);
                        x.iter()
                            .flat_map(|xi| {
                                let c = xi.cross(&e);
                                [c.x, c.y, c.z]
                            })
                            .collect()
                    };
                    let bt: Vec<Vec<f64>> = (0..3).map(|a| skw_col(&k.b, a)).collect();
                    let mbt: Vec<Vec<f64>> = bt.iter().map(|x| f.m_mul(x)).collect();
                    let dot =
                        |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
                    let ddt: Vec<Vec<f64>> = (0..3).map(|a| skw_col(&k.dd, a)).collect();
                    let mddt: Vec<Vec<f64>> = ddt.iter().map(|x| f.m_mul(x)).collect();
                    let psi_cols: Vec<Vec<Vec<f64>>> = (0..nz)
                        .map(|m| {
                            let col: Vec<Vector3<f64>> = (0..f.n_nodes())
                                .map(|i| {
                                    Vector3::new(
                                        f.psi[(3 * i, m)],
                                        f.psi[(3 * i + 1, m)],
                                        f.psi[(3 * i + 2, m)],
                                    )
                                })
                                .collect();
                            (0..3).map(|a| skw_col(&col, a)).collect()
                        })
                        .collect();
                    for (a, b) in [(0usize, 1usize), (1, 2), (2, 0)] {
                        let cols = (0..nz)
                            .map(|m| {
                                let d =
                                    dot(&psi_cols[m][a], &mbt[b]) + dot(&psi_cols[m][b], &mbt[a]);
                                (oz + m, d)
                            })
                            .collect();
                        rows.push(AxisRow {
                            cols,
                            phi: dot(&bt[a], &mbt[b]),
                            nu: 0.0,
                            gamma: -2.0 * dot(&ddt[a], &mddt[b]),
                        });
                    }
                }
                AxisCondition::NodalFixed => {}
            }
        }
        rows
    }

    /// Axis-condition rows and the equations of the constraints at `(t, q, v)` (`v = 0` when
    /// `None`).
    fn equations(&self, t: f64, q: &[f64], v: Option<&[f64]>) -> (Vec<AxisRow>, Vec<Equation>) {
        let (rk, fk) = self.kinematics(q, v);
        let mut eqs = Vec::new();
        self.constraints
            .eval(t, |m| self.carrier(m, &rk, &fk), &mut eqs);
        (self.axis_rows(&fk), eqs)
    }
}

impl SecondOrderSystem for FloatingSystem {
    fn n_q(&self) -> usize {
        7 * self.rigid.len() + self.flex.iter().map(|f| 7 + f.n_modes()).sum::<usize>()
    }

    fn n_v(&self) -> usize {
        6 * self.rigid.len() + self.flex.iter().map(|f| 6 + f.n_modes()).sum::<usize>()
    }

    fn n_c(&self) -> usize {
        self.flex.iter().map(Self::n_axis_rows).sum::<usize>() + self.constraints.n_c()
    }

    fn position_rate(&self, q: &[f64], v: &[f64], qdot: &mut [f64]) {
        for k in 0..self.rigid.len() {
            frame_position_rate(q, v, 7 * k, 6 * k, qdot);
        }
        for (f, (oq, ov)) in self.flex.iter().zip(self.flex_offsets()) {
            frame_position_rate(q, v, oq, ov, qdot);
            let nz = f.n_modes();
            qdot[oq + 7..oq + 7 + nz].copy_from_slice(&v[ov + 6..ov + 6 + nz]);
        }
    }

    fn normalize(&self, q: &mut [f64]) {
        for k in 0..self.rigid.len() {
            frame_normalize(q, 7 * k);
        }
        for (oq, _) in self.flex_offsets() {
            frame_normalize(q, oq);
        }
    }

    fn integrate_position(&self, q: &[f64], dq: &[f64], q_new: &mut [f64]) {
        for k in 0..self.rigid.len() {
            frame_integrate(q, dq, 7 * k, 6 * k, q_new);
        }
        for (f, (oq, ov)) in self.flex.iter().zip(self.flex_offsets()) {
            frame_integrate(q, dq, oq, ov, q_new);
            for m in 0..f.n_modes() {
                q_new[oq + 7 + m] = q[oq + 7 + m] + dq[ov + 6 + m];
            }
        }
    }

    /// Lin (3.38)/(5.19) mass blocks in local components: `[mI, −A skw(IhᵀM'b'), A IhᵀM'Ψ';
    /// ·, J' = b~'ᵀM'b~', −b~'ᵀM'Ψ'; ·, ·, Ψ'ᵀM'Ψ']`, plus the rigid core (Ribaric (2.50)).
    fn mass(&self, _t: f64, q: &[f64]) -> Result<SysMatrix, MbdError> {
        let n = self.n_v();
        let mut m = Mat::<f64>::zeros(n, n);
        for (k, b) in self.rigid.iter().enumerate() {
            for c in 0..3 {
                m[(6 * k + c, 6 * k + c)] = b.mass;
                for d in 0..3 {
                    m[(6 * k + 3 + c, 6 * k + 3 + d)] = b.inertia[(c, d)];
                }
            }
        }
        let (_, fk) = self.kinematics(q, None);
        for ((f, k), (_, o)) in self.flex.iter().zip(&fk).zip(self.flex_offsets()) {
            let nz = f.n_modes();
            let mb = f.m_mul(&flat(&k.b));
            let mut c1 = Vector3::zeros();
            for (i, x) in mb.iter().enumerate() {
                c1[i % 3] += x;
            }
            let rw = -(k.frame.a * tilde(&c1));
            // J' = b~'ᵀM'b~'
            let skw_cols: Vec<Vec<f64>> = (0..3)
                .map(|a| {
                    let e = Vector3::ith(a, 1.0);
                    k.b.iter()
                        .flat_map(|b| {
                            let c = b.cross(&e);
                            [c.x, c.y, c.z]
                        })
                        .collect()
                })
                .collect();
            let mcols: Vec<Vec<f64>> = skw_cols.iter().map(|x| f.m_mul(x)).collect();
            let mut jl = Matrix3::zeros();
            for a in 0..3 {
                for bb in 0..3 {
                    jl[(a, bb)] = skw_cols[a].iter().zip(&mcols[bb]).map(|(x, y)| x * y).sum();
                }
            }
            let mtot = f.total_mass + f.core.map(|c| c.mass).unwrap_or(0.0);
            if let Some(core) = f.core {
                jl += core.inertia;
            }
            let arz = k.frame.a * nalgebra::DMatrix::from_fn(3, nz, |i, j| f.ih_m_psi[(i, j)]);
            for a in 0..3 {
                m[(o + a, o + a)] = mtot;
                for bb in 0..3 {
                    m[(o + a, o + 3 + bb)] = rw[(a, bb)];
                    m[(o + 3 + bb, o + a)] = rw[(a, bb)];
                    m[(o + 3 + a, o + 3 + bb)] = jl[(a, bb)];
                }
                for j in 0..nz {
                    m[(o + a, o + 6 + j)] = arz[(a, j)];
                    m[(o + 6 + j, o + a)] = arz[(a, j)];
                }
            }
            // −b~'ᵀM'Ψ' = Σ_i b'_i × (M'Ψ')_i
            for j in 0..nz {
                let mut col = Vector3::zeros();
                for (i, b) in k.b.iter().enumerate() {
                    let x = Vector3::new(
                        f.m_psi[(3 * i, j)],
                        f.m_psi[(3 * i + 1, j)],
                        f.m_psi[(3 * i + 2, j)],
                    );
                    col += b.cross(&x);
                }
                for a in 0..3 {
                    m[(o + 3 + a, o + 6 + j)] = col[a];
                    m[(o + 6 + j, o + 3 + a)] = col[a];
                }
                for i in 0..nz {
                    m[(o + 6 + i, o + 6 + j)] = f.m_zz[(i, j)];
                }
            }
        }
        Ok(SysMatrix::Dense(m))
    }

    /// Generalized forces `Lᵀ(f' − M'w')` with gravity, point loads, the quadratic-velocity
    /// vector `w' = ω̃'ω̃'b' + 2ω̃'δ̇'` (Lin (3.19), (5.5)) and the elastic and damping forces
    /// `−Ψ'ᵀK'Ψ'z − Ψ'ᵀC'Ψ'ż` on the elastic rows.
    ///
    /// Elastic forces act on the elastic coordinates only (the strain energy `½zᵀK_r z` does not
    /// depend on the frame motion), so the system is conservative; Lin's `−b~ᵀ(−Kδ)` rotational
    /// row is zero to first order and is omitted (the energy-consistent choice).
    fn forces(
        &self, t: f64, q: &[f64], v: &[f64], out: &mut [f64], _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        out.fill(0.0);
        let (rk, fk) = self.kinematics(q, Some(v));
        for (k, (b, kin)) in self.rigid.iter().zip(&rk).enumerate() {
            put3(out, 6 * k, &(self.gravity * b.mass));
            let gyro = -kin.w.cross(&(b.inertia * kin.w));
            put3(out, 6 * k + 3, &gyro);
        }
        let offs = self.flex_offsets();
        // nodal loads on flexible bodies (local components), per body
        let mut ext: Vec<Vec<f64>> = self
            .flex
            .iter()
            .map(|f| vec![0.0; 3 * f.n_nodes()])
            .collect();
        for l in &self.loads {
            let force = (l.force)(t);
            match (l.point.body, l.point.node) {
                (None, _) => {}
                (Some(body), None) => {
                    let local = l.point.point;
                    let kin = &rk[body];
                    for c in 0..3 {
                        out[6 * body + c] += force[c];
                    }
                    let m = local.cross(&(kin.a.transpose() * force));
                    for c in 0..3 {
                        out[6 * body + 3 + c] += m[c];
                    }
                }
                (Some(body), Some(node)) => {
                    let fl = fk[body].frame.a.transpose() * force;
                    for c in 0..3 {
                        ext[body][3 * node + c] += fl[c];
                    }
                }
            }
        }
        for (kf, (f, kin)) in self.flex.iter().zip(&fk).enumerate() {
            let (_, o) = offs[kf];
            let gl = kin.frame.a.transpose() * self.gravity;
            let mut x = vec![0.0; 3 * f.n_nodes()];
            for (i, b) in kin.b.iter().enumerate() {
                let w =
                    kin.frame.w.cross(&kin.frame.w.cross(b)) + 2.0 * kin.frame.w.cross(&kin.dd[i]);
                for c in 0..3 {
                    x[3 * i + c] = gl[c] - w[c];
                }
            }
            let mut fl = f.m_mul(&x);
            for (a, e) in fl.iter_mut().zip(&ext[kf]) {
                *a += e;
            }
            let nodal_elastic = f.elastic == ElasticForces::Nodal;
            if nodal_elastic {
                let kd = mat_vec(f.k_psi.as_ref(), &kin.z);
                for (a, e) in fl.iter_mut().zip(&kd) {
                    *a -= e;
                }
            }
            let mut res = Vector3::zeros();
            let mut mom = Vector3::zeros();
            for (i, b) in kin.b.iter().enumerate() {
                let fi = Vector3::new(fl[3 * i], fl[3 * i + 1], fl[3 * i + 2]);
                res += fi;
                mom += b.cross(&fi);
            }
            let mut fr = kin.frame.a * res;
            if let Some(core) = f.core {
                fr += self.gravity * core.mass;
                mom -= kin.frame.w.cross(&(core.inertia * kin.frame.w));
            }
            put3(out, o, &fr);
            put3(out, o + 3, &mom);
            let nz = f.n_modes();
            let kz = mat_vec(f.k_r.as_ref(), &kin.z);
            let cz = f.c_r.as_ref().map(|c| mat_vec(c.as_ref(), &kin.zd));
            for m in 0..nz {
                let mut s = 0.0;
                for (i, fli) in fl.iter().enumerate() {
                    s += f.psi[(i, m)] * fli;
                }
                if !nodal_elastic {
                    s -= kz[m];
                }
                if let Some(cz) = &cz {
                    s -= cz[m];
                }
                out[o + 6 + m] = s;
            }
        }
        if let Some(i) = out.iter().position(|x| !x.is_finite()) {
            return Err(MbdError::NonFinite {
                what: format!("generalized force on {}", self.dof_name(i)),
                t,
            });
        }
        Ok(())
    }

    fn constraint_residual(&self, t: f64, q: &[f64], phi: &mut [f64]) -> Result<(), MbdError> {
        let (axis, eqs) = self.equations(t, q, None);
        let all = axis
            .iter()
            .map(|r| r.phi)
            .chain(eqs.iter().map(|e| e.row.phi));
        for (p, x) in phi.iter_mut().zip(all) {
            *p = x;
        }
        Ok(())
    }

    fn constraint_jacobian(&self, t: f64, q: &[f64]) -> Result<SysMatrix, MbdError> {
        let (axis, eqs) = self.equations(t, q, None);
        let mut d = Mat::<f64>::zeros(axis.len() + eqs.len(), self.n_v());
        for (i, r) in axis.iter().enumerate() {
            for &(c, x) in &r.cols {
                d[(i, c)] += x;
            }
        }
        self.constraints.jacobian_entries(
            &eqs,
            axis.len(),
            |m| self.columns(m),
            |r, c, x| d[(r, c)] += x,
        );
        Ok(SysMatrix::Dense(d))
    }

    fn constraint_velocity_rhs(&self, t: f64, q: &[f64], nu: &mut [f64]) -> Result<(), MbdError> {
        let (axis, eqs) = self.equations(t, q, None);
        let all = axis.iter().map(|r| r.nu).chain(eqs.iter().map(|e| e.nu));
        for (p, x) in nu.iter_mut().zip(all) {
            *p = x;
        }
        Ok(())
    }

    fn constraint_gamma(
        &self, t: f64, q: &[f64], v: &[f64], gamma: &mut [f64],
    ) -> Result<(), MbdError> {
        let (axis, eqs) = self.equations(t, q, Some(v));
        let all = axis
            .iter()
            .map(|r| r.gamma)
            .chain(eqs.iter().map(|e| e.gamma));
        for (p, x) in gamma.iter_mut().zip(all) {
            *p = x;
        }
        Ok(())
    }

    fn constraint_name(&self, row: usize) -> String {
        let mut r = row;
        for f in &self.flex {
            let n = Self::n_axis_rows(f);
            if r < n {
                return format!("axis condition of flexible body \"{}\" (row {r})", f.name);
            }
            r -= n;
        }
        self.constraints
            .row_name(r)
            .unwrap_or_else(|| format!("constraint row {row}"))
    }

    fn dof_name(&self, dof: usize) -> String {
        let names = ["x", "y", "z", "ωx'", "ωy'", "ωz'"];
        if dof < 6 * self.rigid.len() {
            return format!(
                "rigid body \"{}\" {}",
                self.rigid[dof / 6].name,
                names[dof % 6]
            );
        }
        for (f, (_, o)) in self.flex.iter().zip(self.flex_offsets()) {
            if dof >= o && dof < o + 6 + f.n_modes() {
                let l = dof - o;
                return if l < 6 {
                    format!("flexible body \"{}\" frame {}", f.name, names[l])
                } else {
                    format!("flexible body \"{}\" elastic coordinate {}", f.name, l - 6)
                };
            }
        }
        format!("coordinate {dof}")
    }
}

/// 3-vectors from a flat slice.
fn vectors(x: &[f64]) -> Vec<Vector3<f64>> {
    x.chunks(3)
        .map(|c| Vector3::new(c[0], c[1], c[2]))
        .collect()
}

/// A marker must name an existing rigid body (`node: None`) or an existing node of a flexible
/// body (`node: Some`), or the ground.
fn check_marker(
    rigid: &[RigidBody], flex: &[FlexBody], m: &Marker, what: &str,
) -> Result<(), MbdError> {
    let err = |reason: String| MbdError::InvalidInput {
        item: what.to_string(),
        reason,
    };
    match (m.body, m.node) {
        (None, _) if m.node.is_some() => Err(err("a ground marker has no node".into())),
        (Some(body), None) if body >= rigid.len() => Err(err(format!(
            "rigid body {body} does not exist ({} rigid bodies)",
            rigid.len()
        ))),
        (Some(body), Some(node)) => match flex.get(body) {
            None => Err(err(format!(
                "flexible body {body} does not exist ({} flexible bodies)",
                flex.len()
            ))),
            Some(f) if node >= f.n_nodes() => Err(err(format!(
                "node {node} of flexible body \"{}\" does not exist ({} nodes)",
                f.name,
                f.n_nodes()
            ))),
            _ => Ok(()),
        },
        _ => Ok(()),
    }
}
