//! The flowing-material belt drive: Ribaric (5.14) with penalty contact (6.1), (6.2).
//!
//! Coordinates `q = [s_b, z, φ₂]`, velocities `v = [v, ż, ω₂]`: the belt's travel `s_b` and
//! speed `v` (the material speed at the reference node, [`super::FlowingBasis`]), the modal
//! coordinates `z` of the deflection `δ = T z` of the stationary mesh, and the driven pulley's
//! angle and speed (positive in the belt's travel sense). The driver's speed `ω₁(t)` is prescribed.
//!
//! Kinematics (Ribaric (5.10)–(5.13), with erratum E11):
//!
//! ```text
//!   material velocity   ḋ = v e_t + T ż + v T_,s z
//!   material accel.     d̈ = a (e_t + b) + T z̈ + v² ε_n + c,   b = T_,s z,
//!                       c = v² T_,ss z + 2 v T_,s ż
//! ```
//!
//! Nodal balance `M d̈ = g`, `g = f0 + f_contact − K δ − C δ̇_m`, projected on `P = [e_t | T]`:
//!
//! ```text
//!   [ e_tᵀM(e_t + b)   e_tᵀ M T ] [a ]   [ e_tᵀ (g − M (v² ε_n + c)) ]
//!   [ Tᵀ M(e_t + b)    Tᵀ M T   ] [z̈] = [ Tᵀ  (g − M (v² ε_n + c)) ]
//!   J₂ ω̇₂ = τ_contact,2 − M_load(t)
//! ```
//!
//! Choices (documented per the seed-000 note): the unknown vector is `[a; z̈]` (erratum E13);
//! with penalty contact the λ rows of (5.14) vanish (so E12 does not arise); the `z` rows are
//! projected with the whole basis `Tᵀ` (Galerkin) instead of (5.14)'s mixed projection (`Ψ^fᵀ` on
//! free rows, nodal contact rows) — both coincide when all modes are kept (T square), and the
//! Galerkin form keeps the truncated model's energy balance (cf. U15 for the tire); the damping
//! `β K_e` acts on the co-rotated material deflection rate `δ̇_m − v ψ' J δ` with
//! `δ̇_m = T ż + v T_,s z` (note U10: the viscoelastic strain rate follows the material; the
//! `− v ψ' J δ` term removes the turning of the element frames the material passes through,
//! [`super::BeltFe::frame_turn`] — Ribaric (5.5)'s `C δ̇` on global components is not
//! frame-invariant) and `α M` on the Eulerian rate `T ż` (no drag in the steady state; the same
//! choice as the tire model).

use super::contact::{NodeContact, PulleyFrame, node_contact};
use super::model::{BeltFe, FlowingBasis, NODE_DOFS, chord_tensions};
use super::schedule::Schedule;
use super::statics::dense_equilibrium;
use contact::friction::FrictionSpec;
use contact::normal::PolynomialPenalty;
use faer::Mat;
use mbd_core::Workspace;
use mbd_core::{ForceTangent, MbdError, SecondOrderSystem, SysMatrix};

/// A contact node with its rows of the basis.
#[derive(Debug, Clone)]
struct ContactRow {
    node: usize,
    pulley: usize,
    /// Rows of `T` for the node's (x, y) DOFs: `2 × m`.
    t: Mat<f64>,
    /// Rows of `T_,s`.
    ts: Mat<f64>,
    law: PolynomialPenalty,
}

/// The flowing-material belt drive (see the module documentation).
#[derive(Debug, Clone)]
pub struct FlowingBelt {
    /// The belt loop.
    pub fe: BeltFe,
    /// The reduction basis.
    pub basis: FlowingBasis,
    /// Driver pulley speed ω₁(t) \[rad/s\], positive in the travel sense.
    pub driver_speed: Schedule,
    /// Load torque on the driven pulley \[N m\], opposing its rotation.
    pub load_torque: Schedule,
    pulleys: [PulleyFrame; 2],
    friction: FrictionSpec,
    m: usize,
    a_mass: Mat<f64>,
    mts: Mat<f64>,
    a_k: Mat<f64>,
    a_c: Mat<f64>,
    a_cs: Mat<f64>,
    a_mss: Mat<f64>,
    p_en: Vec<f64>,
    p_f0: Vec<f64>,
    rows: Vec<ContactRow>,
    inertia: f64,
}

/// Contact state of one node (for output).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeReport {
    /// Node index.
    pub node: usize,
    /// Pulley index.
    pub pulley: usize,
    /// Arc length of the node \[m\].
    pub s: f64,
    /// The contact evaluation.
    pub contact: NodeContact,
}

/// `Pᵀ A B` with `P = [e | T]`, `A` diagonal or dense.
fn project(e: &[f64], t: &Mat<f64>, ab: &Mat<f64>) -> Mat<f64> {
    let (n, m) = (t.nrows(), ab.ncols());
    let mut out = Mat::<f64>::zeros(t.ncols() + 1, m);
    for j in 0..m {
        out[(0, j)] = (0..n).map(|i| e[i] * ab[(i, j)]).sum();
    }
    let tt = t.transpose() * ab;
    for i in 0..t.ncols() {
        for j in 0..m {
            out[(i + 1, j)] = tt[(i, j)];
        }
    }
    out
}

fn project_vec(e: &[f64], t: &Mat<f64>, x: &[f64]) -> Vec<f64> {
    let n = t.nrows();
    let mut out = vec![(0..n).map(|i| e[i] * x[i]).sum()];
    for j in 0..t.ncols() {
        out.push((0..n).map(|i| t[(i, j)] * x[i]).sum());
    }
    out
}

/// `y += s · A x` for a dense `A`.
fn gemv(y: &mut [f64], a: &Mat<f64>, x: &[f64], s: f64) {
    for (j, &xj) in x.iter().enumerate() {
        let c = s * xj;
        if c != 0.0 {
            for (i, yi) in y.iter_mut().enumerate() {
                *yi += a[(i, j)] * c;
            }
        }
    }
}

impl FlowingBelt {
    /// Build the model: basis with `fe.config.reduction.free_modes` free-node modes, all
    /// projections precomputed.
    pub fn new(
        fe: BeltFe,
        driver_speed: Schedule,
        load_torque: Schedule,
    ) -> Result<Self, crate::FlowError> {
        let basis = FlowingBasis::new(&fe, fe.config.reduction.free_modes)?;
        let n = fe.n_dofs();
        let m = basis.len();
        let et = fe.stacked_tangent();
        let en = fe.stacked_curvature();
        let mdiag = &fe.mass;
        let scale_rows = |a: &Mat<f64>| Mat::from_fn(n, a.ncols(), |i, j| mdiag[i] * a[(i, j)]);
        let mt = scale_rows(&basis.t);
        let mut a_mass = Mat::<f64>::zeros(m + 1, m + 1);
        let met: Vec<f64> = (0..n).map(|i| mdiag[i] * et[i]).collect();
        let col0 = project_vec(&et, &basis.t, &met);
        let blk = project(&et, &basis.t, &mt);
        for i in 0..=m {
            a_mass[(i, 0)] = col0[i];
            for j in 0..m {
                a_mass[(i, j + 1)] = blk[(i, j)];
            }
        }
        let mts = project(&et, &basis.t, &scale_rows(&basis.ts));
        let a_mss = project(&et, &basis.t, &scale_rows(&basis.tss));
        let a_k = project(&et, &basis.t, &(&fe.stiffness * &basis.t));
        let a_c = project(&et, &basis.t, &(&fe.damping * &basis.t));
        // β K_e acts on the material rate, α M on the Eulerian rate only (module docs)
        let alpha = fe.config.damping.alpha;
        let beta_k = Mat::from_fn(n, n, |i, j| {
            fe.damping[(i, j)] - if i == j { alpha * mdiag[i] } else { 0.0 }
        });
        // the frame-invariant material strain rate (BeltFe::frame_turn): β K_e (v T_,s z) minus
        // the co-rotation β v Σ ψ'_e K_e J T z of the elements the material passes through
        let beta = fe.config.damping.beta;
        let turn = Mat::from_fn(n, n, |i, j| beta * fe.frame_turn[(i, j)]);
        let a_cs = project(
            &et,
            &basis.t,
            &(&(&beta_k * &basis.ts) - &(&turn * &basis.t)),
        );
        let men: Vec<f64> = (0..n).map(|i| mdiag[i] * en[i]).collect();
        let p_en = project_vec(&et, &basis.t, &men);
        let p_f0 = project_vec(&et, &basis.t, &fe.pretension);
        let cfg = fe.config;
        let mut rows = Vec::new();
        for (p, set) in fe.contact_nodes.iter().enumerate() {
            for &i in set {
                let take = |a: &Mat<f64>| Mat::from_fn(2, m, |r, j| a[(NODE_DOFS * i + r, j)]);
                rows.push(ContactRow {
                    node: i,
                    pulley: p,
                    t: take(&basis.t),
                    ts: take(&basis.ts),
                    law: PolynomialPenalty {
                        quadratic: cfg.contact.penalty_quadratic,
                        linear: cfg.contact.penalty_linear,
                        length: fe.tributary[i],
                    },
                });
            }
        }
        let pp = fe.path.pulleys();
        let pulleys = [0, 1].map(|k| PulleyFrame {
            center: pp[k].center,
            radius: fe.contact_radius[k],
            turn: 1.0,
        });
        Ok(Self {
            friction: cfg.contact.friction_law(),
            inertia: cfg.driven_inertia,
            fe,
            basis,
            driver_speed,
            load_torque,
            pulleys,
            m,
            a_mass,
            mts,
            a_k,
            a_c,
            a_cs,
            a_mss,
            p_en,
            p_f0,
            rows,
        })
    }

    /// Number of modal coordinates `m` (the system has `m + 2` DOFs).
    pub fn n_modes(&self) -> usize {
        self.m
    }

    /// Nodal deflections `δ = T z` (`3N`).
    pub fn deflection(&self, z: &[f64]) -> Vec<f64> {
        let mut d = vec![0.0; self.fe.n_dofs()];
        gemv(&mut d, &self.basis.t, z, 1.0);
        d
    }

    fn node_state(
        &self,
        r: &ContactRow,
        z: &[f64],
        zd: &[f64],
        vb: f64,
    ) -> ([f64; 2], [f64; 2], [f64; 2]) {
        let i = r.node;
        let (mut d, mut vel, mut bs) = (self.fe.position[i], [0.0; 2], [0.0; 2]);
        for c in 0..2 {
            let (mut tz, mut tsz, mut tzd) = (0.0, 0.0, 0.0);
            for j in 0..self.m {
                tz += r.t[(c, j)] * z[j];
                tsz += r.ts[(c, j)] * z[j];
                tzd += r.t[(c, j)] * zd[j];
            }
            d[c] += tz;
            bs[c] = self.fe.tangent[i][c] + tsz;
            vel[c] = vb * bs[c] + tzd;
        }
        (d, vel, bs)
    }

    fn pulley_speed(&self, p: usize, t: f64, v: &[f64]) -> f64 {
        if p == 0 {
            self.driver_speed.value(t)
        } else {
            v[self.m + 1]
        }
    }

    /// Contact state of every contact node at `(t, q, v)`.
    pub fn contact_report(&self, t: f64, q: &[f64], v: &[f64]) -> Vec<NodeReport> {
        let (z, zd, vb) = (&q[1..=self.m], &v[1..=self.m], v[0]);
        self.rows
            .iter()
            .map(|r| {
                let (d, vel, _) = self.node_state(r, z, zd, vb);
                let w = self.pulley_speed(r.pulley, t, v);
                NodeReport {
                    node: r.node,
                    pulley: r.pulley,
                    s: self.fe.s[r.node],
                    contact: node_contact(
                        &self.pulleys[r.pulley],
                        w,
                        d,
                        vel,
                        &r.law,
                        &self.friction,
                    ),
                }
            })
            .collect()
    }

    /// Torques of the contact forces on the pulleys in their travel sense \[N m\].
    pub fn pulley_torques(&self, t: f64, q: &[f64], v: &[f64]) -> [f64; 2] {
        let mut tq = [0.0; 2];
        for r in self.contact_report(t, q, v) {
            tq[r.pulley] += r.contact.torque;
        }
        tq
    }

    /// Axial tension of the belt element starting at each node \[N\]: `T0 + EA Δl/l`
    /// ([`chord_tensions`] on the stationary mesh).
    pub fn element_tensions(&self, z: &[f64]) -> Vec<f64> {
        let b = &self.fe.config.belt;
        chord_tensions(&self.fe.position, &self.deflection(z), b.tension, b.ea)
    }

    /// Index of the driven pulley's speed in the velocities.
    pub fn driven_dof(&self) -> usize {
        self.m + 1
    }

    /// The friction law of the belt–pulley contact.
    pub fn friction_law(&self) -> &FrictionSpec {
        &self.friction
    }

    /// Static equilibrium of the belt on the resting pulleys (`v = 0`, `ż = 0`): Newton on the
    /// modal rows with the analytic tangent (the shared [`mbd_core::newton`] solver). Returns `z`.
    pub fn static_equilibrium(&self) -> Result<Vec<f64>, MbdError> {
        let m = self.m;
        let mut q = vec![0.0; m + 2];
        let v = vec![0.0; m + 2];
        let mut f = vec![0.0; m + 2];
        let still = Self {
            driver_speed: Schedule::constant(0.0),
            ..self.clone()
        };
        // R = −f over the modal rows, J = K_t restricted to them
        dense_equilibrium("belt", m, m, 1, |z, r| {
            q[1..=m].copy_from_slice(z);
            still.forces(0.0, &q, &v, &mut f, &mut mbd_core::Workspace::new())?;
            for i in 0..m {
                r[i] = -f[i + 1];
            }
            let tan = still.tangent(0.0, &q, &v);
            Ok(Mat::from_fn(m, m, |i, j| tan.0[(i + 1, j + 1)]))
        })
    }

    /// `(K_t, C_t)` as dense matrices: `−∂f/∂q`, `−∂f/∂v`.
    fn tangent(&self, t: f64, q: &[f64], v: &[f64]) -> (Mat<f64>, Mat<f64>) {
        let m = self.m;
        let (z, zd, vb) = (&q[1..=m], &v[1..=m], v[0]);
        let nv = m + 2;
        let mut kq = Mat::<f64>::zeros(nv, nv);
        let mut cv = Mat::<f64>::zeros(nv, nv);
        for i in 0..=m {
            for j in 0..m {
                kq[(i, j + 1)] =
                    self.a_k[(i, j)] + vb * self.a_cs[(i, j)] + vb * vb * self.a_mss[(i, j)];
                cv[(i, j + 1)] = self.a_c[(i, j)] + 2.0 * vb * self.mts[(i, j)];
            }
        }
        // ∂f/∂v_b of the linear part, with a minus sign
        let mut col = vec![0.0; m + 1];
        gemv(&mut col, &self.a_cs, z, 1.0);
        gemv(&mut col, &self.a_mss, z, 2.0 * vb);
        gemv(&mut col, &self.mts, zd, 2.0);
        for i in 0..=m {
            cv[(i, 0)] = col[i] + 2.0 * vb * self.p_en[i];
        }
        // contact: f[0..=m] += Pᵢᵀ F, f[m+1] += τ (driven pulley)
        for r in &self.rows {
            let (d, vel, bs) = self.node_state(r, z, zd, vb);
            let w = self.pulley_speed(r.pulley, t, v);
            let c = node_contact(&self.pulleys[r.pulley], w, d, vel, &r.law, &self.friction);
            if c.normal == 0.0 && c.friction == 0.0 {
                continue;
            }
            let et = self.fe.tangent[r.node];
            // dF/dz = F_d T + v F_V T_s (2 × m), dF/dż = F_V T, dF/dv = F_V b_s
            let mut dfz = [vec![0.0; m], vec![0.0; m]];
            let mut dfzd = [vec![0.0; m], vec![0.0; m]];
            let mut dfv = [0.0; 2];
            for a in 0..2 {
                for j in 0..m {
                    for b in 0..2 {
                        dfz[a][j] +=
                            c.df_dd[a][b] * r.t[(b, j)] + vb * c.df_dv[a][b] * r.ts[(b, j)];
                        dfzd[a][j] += c.df_dv[a][b] * r.t[(b, j)];
                    }
                }
                dfv[a] = c.df_dv[a][0] * bs[0] + c.df_dv[a][1] * bs[1];
            }
            // row 0 (e_tᵀ) and rows 1..=m (Tᵀ)
            for i in 0..=m {
                let p = if i == 0 {
                    et
                } else {
                    [r.t[(0, i - 1)], r.t[(1, i - 1)]]
                };
                if p[0] == 0.0 && p[1] == 0.0 {
                    continue;
                }
                for j in 0..m {
                    kq[(i, j + 1)] -= p[0] * dfz[0][j] + p[1] * dfz[1][j];
                    cv[(i, j + 1)] -= p[0] * dfzd[0][j] + p[1] * dfzd[1][j];
                }
                cv[(i, 0)] -= p[0] * dfv[0] + p[1] * dfv[1];
                if r.pulley == 1 {
                    cv[(i, m + 1)] -= p[0] * c.df_dw[0] + p[1] * c.df_dw[1];
                }
            }
            if r.pulley == 1 {
                for j in 0..m {
                    let mut tz = 0.0;
                    let mut tzd = 0.0;
                    for b in 0..2 {
                        tz += c.dt_dd[b] * r.t[(b, j)] + vb * c.dt_dv[b] * r.ts[(b, j)];
                        tzd += c.dt_dv[b] * r.t[(b, j)];
                    }
                    kq[(m + 1, j + 1)] -= tz;
                    cv[(m + 1, j + 1)] -= tzd;
                }
                cv[(m + 1, 0)] -= c.dt_dv[0] * bs[0] + c.dt_dv[1] * bs[1];
                cv[(m + 1, m + 1)] -= c.dt_dw;
            }
        }
        (kq, cv)
    }
}

impl SecondOrderSystem for FlowingBelt {
    fn n_q(&self) -> usize {
        self.m + 2
    }

    fn mass(&self, _t: f64, q: &[f64]) -> Result<SysMatrix, MbdError> {
        let m = self.m;
        let mut mm = Mat::<f64>::zeros(m + 2, m + 2);
        for i in 0..=m {
            for j in 0..=m {
                mm[(i, j)] = self.a_mass[(i, j)];
            }
        }
        // the b = T_,s z part of the first column: Pᵀ M T_,s z
        let mut col = vec![0.0; m + 1];
        gemv(&mut col, &self.mts, &q[1..=m], 1.0);
        for (i, c) in col.iter().enumerate() {
            mm[(i, 0)] += c;
        }
        mm[(m + 1, m + 1)] = self.inertia;
        Ok(SysMatrix::Dense(mm))
    }

    fn forces(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        f: &mut [f64],
        _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        let m = self.m;
        let (z, zd, vb) = (&q[1..=m], &v[1..=m], v[0]);
        let (head, tail) = f.split_at_mut(m + 1);
        for i in 0..=m {
            head[i] = self.p_f0[i] - vb * vb * self.p_en[i];
        }
        gemv(head, &self.a_k, z, -1.0);
        gemv(head, &self.a_c, zd, -1.0);
        gemv(head, &self.a_cs, z, -vb);
        gemv(head, &self.a_mss, z, -vb * vb);
        gemv(head, &self.mts, zd, -2.0 * vb);
        let mut torque = 0.0;
        for r in &self.rows {
            let (d, vel, _) = self.node_state(r, z, zd, vb);
            let w = self.pulley_speed(r.pulley, t, v);
            let c = node_contact(&self.pulleys[r.pulley], w, d, vel, &r.law, &self.friction);
            if c.normal == 0.0 && c.friction == 0.0 {
                continue;
            }
            let et = self.fe.tangent[r.node];
            head[0] += et[0] * c.force[0] + et[1] * c.force[1];
            for j in 0..m {
                head[j + 1] += r.t[(0, j)] * c.force[0] + r.t[(1, j)] * c.force[1];
            }
            if r.pulley == 1 {
                torque += c.torque;
            }
        }
        tail[0] = torque - self.load_torque.value(t);
        if let Some(i) = f.iter().position(|x| !x.is_finite()) {
            return Err(MbdError::NonFinite {
                what: format!("belt generalized force {i}"),
                t,
            });
        }
        Ok(())
    }

    fn force_tangent(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        _ws: &mut Workspace,
    ) -> Result<Option<ForceTangent>, MbdError> {
        let (k, c) = self.tangent(t, q, v);
        Ok(Some(ForceTangent {
            stiffness: SysMatrix::Dense(k),
            damping: SysMatrix::Dense(c),
        }))
    }
}
