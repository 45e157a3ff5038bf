//! A multibody system of floating-frame deformable bodies, rigid bodies, spherical joints,
//! prescribed point motions and loads (Lin (2.27), (5.10), (5.11), (5.18), (5.19), (7.9),
//! (8.29); Ribaric (2.45)–(2.52)).

use super::body::{AxisCondition, ElasticForces, FlexBody, flat, mat_vec};
use crate::body::{BodyState, RigidBody};
use crate::integrators::State;
use crate::kinematics::euler::{a_matrix, compose_local_rotation, pdot_from_omega_local};
use crate::kinematics::tilde::{get3, get4, put3, put4, tilde};
use crate::{MbdError, SecondOrderSystem, SysMatrix};
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

/// A material point of the system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Point {
    /// A fixed point of the ground \[m\].
    Ground(Vector3<f64>),
    /// A point of rigid body `body` at body-frame position `local` (from its mass centre) \[m\].
    Rigid {
        /// Rigid-body index.
        body: usize,
        /// Body-frame position \[m\].
        local: Vector3<f64>,
    },
    /// Node `node` (0-based) of flexible body `body`.
    FlexNode {
        /// Flexible-body index.
        body: usize,
        /// Node index.
        node: usize,
    },
}

/// Spherical joint between two points: `d_a = d_b` (Lin (2.22)–(2.24), (5.1)–(5.7)).
#[derive(Debug, Clone, PartialEq)]
pub struct SphericalJoint {
    /// Name used in messages.
    pub name: String,
    /// First point.
    pub a: Point,
    /// Second point.
    pub b: Point,
}

/// Prescribed motion of one global component of a point (Lin (7.7)–(7.9)): `motion(t)` returns
/// `(x, ẋ, ẍ)` \[m, m/s, m/s²\].
pub struct PrescribedMotion {
    /// Name used in messages.
    pub name: String,
    /// The driven point.
    pub point: Point,
    /// Global component 0, 1, 2 (x, y, z).
    pub component: usize,
    /// Position, velocity and acceleration at time t.
    pub motion: Box<dyn Fn(f64) -> [f64; 3] + Send + Sync>,
}

/// A global point force `force(t)` \[N\] applied at a point.
pub struct NodeLoad {
    /// Name used in messages.
    pub name: String,
    /// Point of application.
    pub point: Point,
    /// Global force at time t \[N\].
    pub force: Box<dyn Fn(f64) -> Vector3<f64> + Send + Sync>,
}

struct RigKin {
    r: Vector3<f64>,
    a: Matrix3<f64>,
    w: Vector3<f64>,
}

struct FlexKin {
    r: Vector3<f64>,
    a: Matrix3<f64>,
    w: Vector3<f64>,
    z: Vec<f64>,
    zd: Vec<f64>,
    /// deformed local positions b' = s' + Ψ'z
    b: Vec<Vector3<f64>>,
    /// local deflection rates δ̇' = Ψ'ż
    dd: Vec<Vector3<f64>>,
}

/// Position, velocity-Jacobian columns `(v index, 3-vector)` and quadratic acceleration term.
type PointKin = (Vector3<f64>, Vec<(usize, Vector3<f64>)>, Vector3<f64>);

struct Row {
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
/// rows (6 for mean or principal axes, 0 for nodal-fixed), then 3 per joint, then 1 per driver.
#[derive(Default)]
pub struct FloatingSystem {
    rigid: Vec<RigidBody>,
    flex: Vec<FlexBody>,
    joints: Vec<SphericalJoint>,
    drivers: Vec<PrescribedMotion>,
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

    fn check_point(&self, p: &Point, what: &str) -> Result<(), MbdError> {
        let err = |reason: String| MbdError::InvalidInput {
            item: what.to_string(),
            reason,
        };
        match *p {
            Point::Ground(x) if !x.iter().all(|v| v.is_finite()) => {
                Err(err("ground point is not finite".into()))
            }
            Point::Rigid { body, .. } if body >= self.rigid.len() => Err(err(format!(
                "rigid body {body} does not exist ({} rigid bodies)",
                self.rigid.len()
            ))),
            Point::FlexNode { body, node } => match self.flex.get(body) {
                None => Err(err(format!(
                    "flexible body {body} does not exist ({} flexible bodies)",
                    self.flex.len()
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

    /// Adds a spherical joint (validates its points).
    pub fn add_joint(&mut self, j: SphericalJoint) -> Result<(), MbdError> {
        let what = format!("joint \"{}\"", j.name);
        self.check_point(&j.a, &what)?;
        self.check_point(&j.b, &what)?;
        if matches!((j.a, j.b), (Point::Ground(_), Point::Ground(_))) {
            return Err(MbdError::InvalidInput {
                item: what,
                reason: "connects the ground to the ground".into(),
            });
        }
        self.joints.push(j);
        Ok(())
    }

    /// Adds a prescribed motion (validates the point and component).
    pub fn add_driver(&mut self, d: PrescribedMotion) -> Result<(), MbdError> {
        let what = format!("driver \"{}\"", d.name);
        self.check_point(&d.point, &what)?;
        if d.component > 2 {
            return Err(MbdError::InvalidInput {
                item: what,
                reason: format!("component {} is not 0, 1 or 2", d.component),
            });
        }
        self.drivers.push(d);
        Ok(())
    }

    /// Adds a point load (validates the point).
    pub fn add_load(&mut self, l: NodeLoad) -> Result<(), MbdError> {
        self.check_point(&l.point, &format!("load \"{}\"", l.name))?;
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
        &self,
        t: f64,
        rigid: &[BodyState],
        flex: &[FlexState],
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

    /// Global position of a point \[m\].
    pub fn point_position(&self, state: &State, p: &Point) -> Vector3<f64> {
        let (rk, fk) = self.kinematics(&state.q, None);
        self.point_kin(p, &rk, &fk).0
    }

    /// Global velocity of a point, `ḋ = J v` \[m/s\] (Lin (5.2)).
    pub fn point_velocity(&self, state: &State, p: &Point) -> Vector3<f64> {
        let (rk, fk) = self.kinematics(&state.q, Some(&state.v));
        let (_, jac, _) = self.point_kin(p, &rk, &fk);
        jac.iter()
            .fold(Vector3::zeros(), |acc, (i, col)| acc + col * state.v[*i])
    }

    /// Global acceleration of a point for the velocity derivatives `vdot` (e.g. from
    /// [`crate::integrators::accelerations`]): `d̈ = J v̇ + A w'` \[m/s²\] (Lin (5.3), (5.5)).
    ///
    /// # Panics
    /// If `vdot` is shorter than [`SecondOrderSystem::n_v`].
    pub fn point_acceleration(&self, state: &State, vdot: &[f64], p: &Point) -> Vector3<f64> {
        let (rk, fk) = self.kinematics(&state.q, Some(&state.v));
        let (_, jac, aq) = self.point_kin(p, &rk, &fk);
        jac.iter().fold(aq, |acc, (i, col)| acc + col * vdot[*i])
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
            e -= self.gravity.dot(&(k.r * f.mass() + k.a * c));
        }
        e
    }

    fn kinematics(&self, q: &[f64], v: Option<&[f64]>) -> (Vec<RigKin>, Vec<FlexKin>) {
        let rk = (0..self.rigid.len())
            .map(|k| RigKin {
                r: get3(q, 7 * k),
                a: a_matrix(&get4(q, 7 * k + 3)),
                w: v.map(|v| get3(v, 6 * k + 3)).unwrap_or_else(Vector3::zeros),
            })
            .collect();
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
                FlexKin {
                    r: get3(q, oq),
                    a: a_matrix(&get4(q, oq + 3)),
                    w: v.map(|v| get3(v, ov + 3)).unwrap_or_else(Vector3::zeros),
                    b: f.s
                        .iter()
                        .enumerate()
                        .map(|(i, s)| s + Vector3::new(d[3 * i], d[3 * i + 1], d[3 * i + 2]))
                        .collect(),
                    dd: dd
                        .chunks(3)
                        .map(|c| Vector3::new(c[0], c[1], c[2]))
                        .collect(),
                    z,
                    zd,
                }
            })
            .collect();
        (rk, fk)
    }

    /// Position, velocity-Jacobian columns `(v index, 3-vector)` and quadratic acceleration
    /// term (`d̈ = J v̇ + a_q`) of a point.
    fn point_kin(&self, p: &Point, rk: &[RigKin], fk: &[FlexKin]) -> PointKin {
        match *p {
            Point::Ground(x) => (x, Vec::new(), Vector3::zeros()),
            Point::Rigid { body, local } => {
                let k = &rk[body];
                let mut jac = Vec::with_capacity(6);
                for c in 0..3 {
                    jac.push((6 * body + c, Vector3::ith(c, 1.0)));
                }
                let ms = -(k.a * tilde(&local));
                for c in 0..3 {
                    jac.push((6 * body + 3 + c, ms.column(c).into_owned()));
                }
                let aq = k.a * k.w.cross(&k.w.cross(&local));
                (k.r + k.a * local, jac, aq)
            }
            Point::FlexNode { body, node } => {
                let f = &self.flex[body];
                let k = &fk[body];
                let (_, ov) = self.flex_offsets()[body];
                let b = k.b[node];
                let mut jac = Vec::with_capacity(6 + f.n_modes());
                for c in 0..3 {
                    jac.push((ov + c, Vector3::ith(c, 1.0)));
                }
                let mb = -(k.a * tilde(&b));
                for c in 0..3 {
                    jac.push((ov + 3 + c, mb.column(c).into_owned()));
                }
                for m in 0..f.n_modes() {
                    let col = Vector3::new(
                        f.psi[(3 * node, m)],
                        f.psi[(3 * node + 1, m)],
                        f.psi[(3 * node + 2, m)],
                    );
                    if col != Vector3::zeros() {
                        jac.push((ov + 6 + m, k.a * col));
                    }
                }
                let wq = k.w.cross(&k.w.cross(&b)) + 2.0 * k.w.cross(&k.dd[node]);
                (k.r + k.a * b, jac, k.a * wq)
            }
        }
    }

    fn rows(&self, t: f64, q: &[f64], v: Option<&[f64]>) -> Vec<Row> {
        let (rk, fk) = self.kinematics(q, v);
        let mut rows = Vec::with_capacity(self.n_c());
        for ((f, k), (_, ov)) in self.flex.iter().zip(&fk).zip(self.flex_offsets()) {
            if f.axis == AxisCondition::NodalFixed {
                continue;
            }
            let nz = f.n_modes();
            let oz = ov + 6;
            // translational mean-axis condition IhᵀM'Ψ'z = 0 (Lin (4.20), (8.26))
            let pz = mat_vec(f.ih_m_psi.as_ref(), &k.z);
            for a in 0..3 {
                rows.push(Row {
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
                        rows.push(Row {
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
                        rows.push(Row {
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
        for j in &self.joints {
            let (da, ja, aa) = self.point_kin(&j.a, &rk, &fk);
            let (db, jb, ab) = self.point_kin(&j.b, &rk, &fk);
            for c in 0..3 {
                let mut cols: Vec<(usize, f64)> = ja.iter().map(|(i, x)| (*i, x[c])).collect();
                cols.extend(jb.iter().map(|(i, x)| (*i, -x[c])));
                rows.push(Row {
                    cols,
                    phi: da[c] - db[c],
                    nu: 0.0,
                    gamma: -(aa[c] - ab[c]),
                });
            }
        }
        for d in &self.drivers {
            let (x, jx, ax) = self.point_kin(&d.point, &rk, &fk);
            let [pos, vel, acc] = (d.motion)(t);
            let c = d.component;
            rows.push(Row {
                cols: jx.iter().map(|(i, v)| (*i, v[c])).collect(),
                phi: x[c] - pos,
                nu: vel,
                gamma: acc - ax[c],
            });
        }
        rows
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
        self.flex.iter().map(Self::n_axis_rows).sum::<usize>()
            + 3 * self.joints.len()
            + self.drivers.len()
    }

    fn position_rate(&self, q: &[f64], v: &[f64], qdot: &mut [f64]) {
        for k in 0..self.rigid.len() {
            qdot[7 * k..7 * k + 3].copy_from_slice(&v[6 * k..6 * k + 3]);
            let pd = pdot_from_omega_local(&get4(q, 7 * k + 3), &get3(v, 6 * k + 3));
            put4(qdot, 7 * k + 3, &pd);
        }
        for (f, (oq, ov)) in self.flex.iter().zip(self.flex_offsets()) {
            qdot[oq..oq + 3].copy_from_slice(&v[ov..ov + 3]);
            let pd = pdot_from_omega_local(&get4(q, oq + 3), &get3(v, ov + 3));
            put4(qdot, oq + 3, &pd);
            let nz = f.n_modes();
            qdot[oq + 7..oq + 7 + nz].copy_from_slice(&v[ov + 6..ov + 6 + nz]);
        }
    }

    fn normalize(&self, q: &mut [f64]) {
        let mut at: Vec<usize> = (0..self.rigid.len()).map(|k| 7 * k + 3).collect();
        at.extend(self.flex_offsets().iter().map(|(oq, _)| oq + 3));
        for o in at {
            let p = get4(q, o);
            let n = p.norm();
            if n > 0.0 && n.is_finite() {
                put4(q, o, &(p / n));
            }
        }
    }

    fn integrate_position(&self, q: &[f64], dq: &[f64], q_new: &mut [f64]) {
        for k in 0..self.rigid.len() {
            for c in 0..3 {
                q_new[7 * k + c] = q[7 * k + c] + dq[6 * k + c];
            }
            let p = compose_local_rotation(&get4(q, 7 * k + 3), &get3(dq, 6 * k + 3));
            put4(q_new, 7 * k + 3, &p);
        }
        for (f, (oq, ov)) in self.flex.iter().zip(self.flex_offsets()) {
            for c in 0..3 {
                q_new[oq + c] = q[oq + c] + dq[ov + c];
            }
            let p = compose_local_rotation(&get4(q, oq + 3), &get3(dq, ov + 3));
            put4(q_new, oq + 3, &p);
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
            let rw = -(k.a * tilde(&c1));
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
            let arz = k.a * nalgebra::DMatrix::from_fn(3, nz, |i, j| f.ih_m_psi[(i, j)]);
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
    fn forces(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) -> Result<(), MbdError> {
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
            match l.point {
                Point::Ground(_) => {}
                Point::Rigid { body, local } => {
                    let kin = &rk[body];
                    for c in 0..3 {
                        out[6 * body + c] += force[c];
                    }
                    let m = local.cross(&(kin.a.transpose() * force));
                    for c in 0..3 {
                        out[6 * body + 3 + c] += m[c];
                    }
                }
                Point::FlexNode { body, node } => {
                    let fl = fk[body].a.transpose() * force;
                    for c in 0..3 {
                        ext[body][3 * node + c] += fl[c];
                    }
                }
            }
        }
        for (kf, (f, kin)) in self.flex.iter().zip(&fk).enumerate() {
            let (_, o) = offs[kf];
            let gl = kin.a.transpose() * self.gravity;
            let mut x = vec![0.0; 3 * f.n_nodes()];
            for (i, b) in kin.b.iter().enumerate() {
                let w = kin.w.cross(&kin.w.cross(b)) + 2.0 * kin.w.cross(&kin.dd[i]);
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
            let mut fr = kin.a * res;
            if let Some(core) = f.core {
                fr += self.gravity * core.mass;
                mom -= kin.w.cross(&(core.inertia * kin.w));
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
        for (p, r) in phi.iter_mut().zip(self.rows(t, q, None)) {
            *p = r.phi;
        }
        Ok(())
    }

    fn constraint_jacobian(&self, t: f64, q: &[f64]) -> Result<SysMatrix, MbdError> {
        let rows = self.rows(t, q, None);
        let mut d = Mat::<f64>::zeros(rows.len(), self.n_v());
        for (i, r) in rows.iter().enumerate() {
            for &(c, x) in &r.cols {
                d[(i, c)] += x;
            }
        }
        Ok(SysMatrix::Dense(d))
    }

    fn constraint_velocity_rhs(&self, t: f64, q: &[f64], nu: &mut [f64]) -> Result<(), MbdError> {
        for (p, r) in nu.iter_mut().zip(self.rows(t, q, None)) {
            *p = r.nu;
        }
        Ok(())
    }

    fn constraint_gamma(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        gamma: &mut [f64],
    ) -> Result<(), MbdError> {
        for (p, r) in gamma.iter_mut().zip(self.rows(t, q, Some(v))) {
            *p = r.gamma;
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
        if r < 3 * self.joints.len() {
            return format!(
                "joint \"{}\" (component {})",
                self.joints[r / 3].name,
                r % 3
            );
        }
        r -= 3 * self.joints.len();
        match self.drivers.get(r) {
            Some(d) => format!("driver \"{}\"", d.name),
            None => format!("constraint row {row}"),
        }
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
