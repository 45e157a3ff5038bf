//! The flowing-material belt drive: Ribaric (5.14) with penalty contact (6.1), (6.2).
//!
//! Coordinates `q = [s_b, z, φ_k…, Δθ]`, velocities `v = [v, ż, ω_k…, Δθ̇]`: the belt's travel
//! `s_b` and speed `v` (the material speed at the reference node, [`super::FlowingBasis`]), the
//! modal coordinates `z` of the deflection `δ = T z` of the stationary mesh, the angle and speed
//! of every pulley that is not speed-driven (positive in the belt's travel sense, in pulley
//! order; [`belt::Motion`]) and, with a tensioner ([`belt::Arm`]), the arm's rotation `Δθ` from
//! the angle at which the path (and so the mesh) was laid out, then the carrier's and
//! accessory's angles of every decoupled pulley ([`belt::decoupler`], equations (D1)–(D3); the
//! pulley's own coordinate then carries the hub's inertia and the spring torque). The
//! two-pulley drive of
//! [`FlowingBelt::new`] has `q = [s_b, z, φ₂]`: the driver's speed `ω₁(t)` is prescribed.
//!
//! Any layout (issue 17): the mesh stays fixed in space along the path of the layout (Ribaric's
//! flowing material), and a tensioner's idler moves with its arm, `c(θ) = p + L(cos θ, sin θ)`
//! ([`belt::tensioner`]): its contact sees the node at `d − c(θ)` with the relative velocity
//! `V − ċ` (a translating rigid disk), its speed DOF the reaction torque, and the arm the moment
//! `(c − p) × (−F)` of the contact forces `F` on the belt, with the spring, damper and dry
//! friction of [`belt::Tensioner`]. The belt's deflections follow the idler's displacement
//! (linearised about the laid-out path: valid while the arm turns by a few degrees).
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
//!   J_k ω̇_k = τ_contact,k − M_load,k(t)                (free pulleys)
//!   J_a Δθ̈  = (c − p) × F_hub + M_s + M_d + M_f          (tensioner arm)
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
//!
//! Why the material rate (issue 34): the stiffness-proportional damping models the rubber's
//! viscoelasticity, a Kelvin–Voigt stress `β EA Dε/Dt` on the rate of strain of the material. A
//! Lagrangian belt (the nodal model's material nodes, the ANCF belt) has that rate directly;
//! in the stationary mesh it is the material derivative `Dε/Dt = ∂ε/∂t + v ∂ε/∂s`, which is what
//! `δ̇_m` of Ribaric (5.10) (`T ż + v T_,s z`, the convective part included) gives. With
//! `∂/∂t` alone (`β K_e T ż`) a steady drive would carry no viscous force: the belt leaving a
//! wrap, where its tension changes, would lose the force `β v dT/ds` the Lagrangian models
//! carry (on the default fead drive `β v` = 11–49 mm at 800–3500 rpm against spans of 57 mm
//! and more). Each element's viscous axial force is reported with its elastic force
//! ([`FlowingBelt::element_forces`]); the power these damping forces do on the material is
//! [`FlowingBelt::damping_dissipation`].

use super::config::{AxialForce, FlowingSettings};
use super::contact::{NodeContact, PulleyFrame, node_contact};
use super::coordinates::{ArmState, DriveCoordinates};
use super::model::{BeltFe, FlowingBasis, NODE_DOFS, chord_tensions};
use super::statics::dense_equilibrium;
use belt::tensioner::cross;
use belt::{Arm, Drive, Motion};
use contact::friction::FrictionSpec;
use contact::normal::PolynomialPenalty;
use faer::Mat;
use mbd_core::Workspace;
use mbd_core::{ForceTangent, MbdError, SecondOrderSystem, SysMatrix};

/// The rigid pulleys of the path as the nodes see them: centre, contact radius
/// ([`BeltFe::contact_radius`]) and wrap sense (`+1` grooved side inside the loop, `−1` back
/// side).
pub(crate) fn pulley_frames(fe: &BeltFe) -> Vec<PulleyFrame> {
    fe.path()
        .pulleys()
        .iter()
        .zip(&fe.contact_radius)
        .map(|(p, &radius)| PulleyFrame {
            center: p.center,
            radius,
            turn: p.side.turn(),
        })
        .collect()
}

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
    /// The free pulleys', the tensioner arm's and the decouplers' coordinates, after `z`.
    pub coords: DriveCoordinates,
    pulleys: Vec<PulleyFrame>,
    /// The friction law of each pulley, travel order ([`belt::Drive::wrap_friction_law`]).
    friction: Vec<FrictionSpec>,
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
    n_v: usize,
    /// The elements' chords for the co-rotated axial force ([`Self::exact_axial`]).
    bars: Vec<super::model::Bar>,
    /// `D̃ = [Δe_t | ΔT]` (`2 n_bars × (m + 1)`): per bar and direction, the difference of the
    /// stacked tangent `e_t` and of the basis rows `T` between its end nodes, so that the
    /// co-rotated corrections `c` enter the forces as `D̃ᵀ c` and the tangent as `D̃ᵀ G ΔT`.
    bar_dx: Mat<f64>,
    /// Apply each element's axial force `N = F(λ₀ l/l₀)` of the material law ([`super::model::BarLaw`]) along its deformed chord
    /// (issue 34): the linear model (`f0 − (K_e + K_g(T0)) δ`) keeps the increment
    /// `EA Δl/l` along the reference chord, and its elements then do not balance moments once
    /// the belt's tangential displacement `u_t` turns the arc elements by `u_t/R` (a torque
    /// error `Σ N1 Δv` on the wraps). `false`: the linear model of Ribaric (5.5).
    exact_axial: bool,
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
    /// The flowing-material model of `drive` (Ribaric (5.14)): the stationary loop of
    /// `settings.mesh` on the mounted path, the basis of `settings.reduction`, all projections
    /// precomputed; the pulleys turn by the drive's motions, a tensioner's arm (if any) is a
    /// coordinate.
    pub fn new(drive: &Drive, settings: &FlowingSettings) -> Result<Self, crate::FlowError> {
        use mbd_core::Validate;
        settings.validate()?;
        let fe = BeltFe::new(drive, &settings.mesh)?;
        let basis = FlowingBasis::new(&fe, settings.reduction.free_modes)?;
        let mut belt = Self::on(fe, basis, drive.motions(), drive.arm().copied())?;
        belt.exact_axial = settings.axial_force == AxialForce::CoRotated;
        if belt.exact_axial {
            let (t, m) = (&belt.basis.t, belt.m);
            let (tan, bars) = (&belt.fe.tangent, &belt.bars);
            belt.bar_dx = Mat::from_fn(2 * bars.len(), m + 1, |r, k| {
                let (bar, a) = (&bars[r / 2], r % 2);
                if k == 0 {
                    tan[bar.j][a] - tan[bar.i][a]
                } else {
                    t[(3 * bar.j + a, k - 1)] - t[(3 * bar.i + a, k - 1)]
                }
            });
        }
        Ok(belt)
    }

    fn on(
        fe: BeltFe, basis: FlowingBasis, motions: Vec<Motion>, tensioner: Option<Arm>,
    ) -> Result<Self, crate::FlowError> {
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
        let alpha = fe.drive.damping().alpha;
        let beta_k = Mat::from_fn(n, n, |i, j| {
            fe.damping[(i, j)] - if i == j { alpha * mdiag[i] } else { 0.0 }
        });
        // the frame-invariant material strain rate (BeltFe::frame_turn): β K_e (v T_,s z) minus
        // the co-rotation β v Σ ψ'_e K_e J T z of the elements the material passes through
        let beta = fe.drive.damping().beta;
        let turn = Mat::from_fn(n, n, |i, j| beta * fe.frame_turn[(i, j)]);
        let a_cs = project(
            &et,
            &basis.t,
            &(&(&beta_k * &basis.ts) - &(&turn * &basis.t)),
        );
        let men: Vec<f64> = (0..n).map(|i| mdiag[i] * en[i]).collect();
        let p_en = project_vec(&et, &basis.t, &men);
        let p_f0 = project_vec(&et, &basis.t, &fe.pretension);
        let contact = *fe.drive.contact();
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
                        quadratic: contact.penalty_quadratic,
                        linear: contact.penalty_linear,
                        length: fe.tributary[i],
                    },
                });
            }
        }
        let pulleys = pulley_frames(&fe);
        let fe_pos = fe.position.clone();
        let mut n_v = m + 1;
        let coords = DriveCoordinates::number(motions, tensioner, &mut n_v);
        Ok(Self {
            coords,
            friction: fe.drive.wrap_friction_laws(),
            fe,
            basis,
            pulleys,
            n_v,
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
            bar_dx: Mat::zeros(0, 0),
            bars: super::model::Bar::loop_of(&fe_pos),
            exact_axial: false,
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
        &self, r: &ContactRow, z: &[f64], zd: &[f64], vb: f64,
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

    /// Contact of one row at a state; the idler's frame and the relative velocity when the
    /// row's pulley is the tensioner's.
    fn row_contact(
        &self, r: &ContactRow, arm: Option<&ArmState>, t: f64, z: &[f64], zd: &[f64], v: &[f64],
    ) -> (NodeContact, [f64; 2], bool) {
        let (d, mut vel, bs) = self.node_state(r, z, zd, v[0]);
        let w = self.coords.pulley_speed(r.pulley, t, v);
        let mut frame = self.pulleys[r.pulley];
        let idler = match (arm, self.coords.tensioner) {
            (Some(a), Some(tm)) if tm.tensioner.pulley == r.pulley => {
                frame.center = a.center;
                vel[0] -= a.vel[0];
                vel[1] -= a.vel[1];
                true
            }
            _ => false,
        };
        (
            node_contact(&frame, w, d, vel, &r.law, &self.friction[r.pulley]),
            bs,
            idler,
        )
    }

    /// Contact state of every contact node at `(t, q, v)`.
    pub fn contact_report(&self, t: f64, q: &[f64], v: &[f64]) -> Vec<NodeReport> {
        let (z, zd) = (&q[1..=self.m], &v[1..=self.m]);
        let arm = self.coords.arm_state(q, v);
        self.rows
            .iter()
            .map(|r| NodeReport {
                node: r.node,
                pulley: r.pulley,
                s: self.fe.s[r.node],
                contact: self.row_contact(r, arm.as_ref(), t, z, zd, v).0,
            })
            .collect()
    }

    /// Torques of the contact forces on the pulleys in their travel sense \[N m\].
    pub fn pulley_torques(&self, t: f64, q: &[f64], v: &[f64]) -> Vec<f64> {
        let mut tq = vec![0.0; self.pulleys.len()];
        for r in self.contact_report(t, q, v) {
            tq[r.pulley] += r.contact.torque;
        }
        tq
    }

    /// Material rate of the nodal deflections `δ̇_m = T ż + v T_,s z` (`3N`, Ribaric (5.10):
    /// the rate a material point sees as it flows through the stationary mesh) at `(q, v)`.
    pub fn material_rate(&self, q: &[f64], v: &[f64]) -> Vec<f64> {
        let m = self.m;
        let mut r = vec![0.0; self.fe.n_dofs()];
        gemv(&mut r, &self.basis.t, &v[1..=m], 1.0);
        gemv(&mut r, &self.basis.ts, &q[1..=m], v[0]);
        r
    }

    /// Viscous axial force of the belt element starting at each node \[N\]: `β EA Dε/Dt` on
    /// the co-rotated material stretch rate ([`super::model::chord_viscous_forces`] with the
    /// material rate [`Self::material_rate`]), the part of the element's axial force its
    /// `β K_e` damping carries beside the elastic force [`Self::element_tensions`].
    pub fn element_viscous_forces(&self, q: &[f64], v: &[f64]) -> Vec<f64> {
        let dr = &self.fe.drive;
        super::model::chord_viscous_forces(
            &self.fe.position,
            &self.fe.tangent,
            &self.deflection(&q[1..=self.m]),
            &self.material_rate(q, v),
            v[0],
            dr.damping().beta * dr.belt().ea,
        )
    }

    /// The whole axial force the belt element starting at each node carries \[N\]: elastic
    /// ([`Self::element_tensions`]) plus viscous ([`Self::element_viscous_forces`]).
    pub fn element_forces(&self, q: &[f64], v: &[f64]) -> Vec<f64> {
        let mut f = self.element_tensions(&q[1..=self.m]);
        for (a, b) in f.iter_mut().zip(self.element_viscous_forces(q, v)) {
            *a += b;
        }
        f
    }

    /// Power dissipated by the belt's Rayleigh damping at `(q, v)` \[W\]: `−Q_dᵀ δ̇_m`, the
    /// power of the damping forces `Q_d = −α M T ż − β K_e (δ̇_m − v ψ′ J δ)` (module
    /// documentation) on the material, which moves at the rate `δ̇_m` ([`Self::material_rate`])
    /// relative to the path (issue 34 power balance).
    pub fn damping_dissipation(&self, q: &[f64], v: &[f64]) -> f64 {
        let m = self.m;
        let (alpha, beta) = (self.fe.drive.damping().alpha, self.fe.drive.damping().beta);
        let d = self.deflection(&q[1..=m]);
        let rate = self.material_rate(q, v);
        let mut euler = vec![0.0; self.fe.n_dofs()];
        gemv(&mut euler, &self.basis.t, &v[1..=m], 1.0);
        let n = rate.len();
        let mut p = 0.0;
        for i in 0..n {
            let mut acc = 0.0;
            for j in 0..n {
                let ke =
                    self.fe.damping[(i, j)] - if i == j { alpha * self.fe.mass[i] } else { 0.0 };
                acc += ke * rate[j] - beta * v[0] * self.fe.frame_turn[(i, j)] * d[j];
            }
            p += (acc + alpha * self.fe.mass[i] * euler[i]) * rate[i];
        }
        p
    }

    /// Axial tension of the belt element starting at each node \[N\]: `T0 + EA Δl/l`, or with
    /// the co-rotated axial force the material law's ([`super::model::BarLaw`])
    /// ([`chord_tensions`] on the stationary mesh).
    pub fn element_tensions(&self, z: &[f64]) -> Vec<f64> {
        let dr = &self.fe.drive;
        let d = self.deflection(z);
        if self.exact_axial {
            let law = super::model::BarLaw::of(dr);
            return self.bars.iter().map(|e| e.force(&d, &law)).collect();
        }
        chord_tensions(&self.fe.position, &d, dr.tension(), dr.belt().ea)
    }

    /// The friction law of the belt on pulley `pulley` (travel order): the contact's law with
    /// `μ` scaled for the wrap ([`belt::Drive::wrap_friction_law`]: `μ/sin(β/2)` on the grooved
    /// pulleys of a multi-ribbed belt).
    ///
    /// # Panics
    /// `pulley` is not a pulley of the drive.
    pub fn friction_law(&self, pulley: usize) -> &FrictionSpec {
        &self.friction[pulley]
    }

    /// Static equilibrium of the belt on the resting pulleys (`v = 0`, `ż = 0`): the modal
    /// coordinates `z` of [`Self::static_state`].
    pub fn static_equilibrium(&self) -> Result<Vec<f64>, MbdError> {
        Ok(self.static_state()?[1..=self.m].to_vec())
    }

    /// Static equilibrium of the belt on the resting pulleys (`v = 0`, `ż = 0`, every pulley
    /// at rest) and of the tensioner arm: Newton on the modal rows (and the arm's row) with the
    /// analytic tangent (the shared [`mbd_core::newton`] solver). Returns `q` (travel and pulley
    /// angles zero).
    pub fn static_state(&self) -> Result<Vec<f64>, MbdError> {
        let m = self.m;
        let nv = self.n_v;
        let mut q = vec![0.0; nv];
        let v = vec![0.0; nv];
        let mut f = vec![0.0; nv];
        let still = Self {
            coords: self.coords.at_rest(),
            ..self.clone()
        };
        // unknowns: z and the arm rotation; R = −f over their rows, J = K_t restricted to them
        let mut idx: Vec<usize> = (1..=m).collect();
        idx.extend(self.coords.arm_dof());
        let n = idx.len();
        let mut ws = Workspace::new();
        let x = dense_equilibrium("belt", n, n, 1, |x, r| {
            for (k, &i) in idx.iter().enumerate() {
                q[i] = x[k];
            }
            still.forces(0.0, &q, &v, &mut f, &mut ws)?;
            for (k, &i) in idx.iter().enumerate() {
                r[k] = -f[i];
            }
            let tan = still.tangent(0.0, &q, &v);
            Ok(Mat::from_fn(n, n, |a, b| tan.0[(idx[a], idx[b])]))
        })?;
        let mut out = vec![0.0; nv];
        for (k, &i) in idx.iter().enumerate() {
            out[i] = x[k];
        }
        Ok(out)
    }

    /// `(K_t, C_t)` as dense matrices: `−∂f/∂q`, `−∂f/∂v`.
    fn tangent(&self, t: f64, q: &[f64], v: &[f64]) -> (Mat<f64>, Mat<f64>) {
        let m = self.m;
        let (z, zd, vb) = (&q[1..=m], &v[1..=m], v[0]);
        let nv = self.n_v;
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
        if self.exact_axial {
            // −∂/∂z of D̃ᵀ c with ∂c_b/∂z = −G_b ΔT_b: kq[0..=m, 1..=m] += D̃ᵀ (G ΔT)
            let d = self.deflection(z);
            let law = super::model::BarLaw::of(&self.fe.drive);
            let dx = &self.bar_dx;
            let mut gd = Mat::<f64>::zeros(dx.nrows(), m);
            for (b, bar) in self.bars.iter().enumerate() {
                let (_, g) = bar.correction(&d, &law, true);
                for k in 0..m {
                    let (d0, d1) = (dx[(2 * b, k + 1)], dx[(2 * b + 1, k + 1)]);
                    gd[(2 * b, k)] = g[0][0] * d0 + g[0][1] * d1;
                    gd[(2 * b + 1, k)] = g[1][0] * d0 + g[1][1] * d1;
                }
            }
            let add = dx.transpose() * &gd;
            for k in 0..m {
                for r in 0..=m {
                    kq[(r, k + 1)] += add[(r, k)];
                }
            }
        }
        let arm = self.coords.arm_state(q, v);
        // contact: f[0..=m] += Pᵢᵀ F, f[spin] += τ, f[arm] += −(c − p) × F
        for r in &self.rows {
            let (c, bs, idler) = self.row_contact(r, arm.as_ref(), t, z, zd, v);
            if c.normal == 0.0 && c.friction == 0.0 {
                continue;
            }
            let et = self.fe.tangent[r.node];
            // dF/dz = F_d T + v F_V T_s (2 × m), dF/dż = F_V T, dF/dv = F_V b_s
            let mut dfz = [vec![0.0; m], vec![0.0; m]];
            let mut dfzd = [vec![0.0; m], vec![0.0; m]];
            let mut tz = vec![0.0; m];
            let mut tzd = vec![0.0; m];
            for j in 0..m {
                for b in 0..2 {
                    for a in 0..2 {
                        dfz[a][j] +=
                            c.df_dd[a][b] * r.t[(b, j)] + vb * c.df_dv[a][b] * r.ts[(b, j)];
                        dfzd[a][j] += c.df_dv[a][b] * r.t[(b, j)];
                    }
                    tz[j] += c.dt_dd[b] * r.t[(b, j)] + vb * c.dt_dv[b] * r.ts[(b, j)];
                    tzd[j] += c.dt_dv[b] * r.t[(b, j)];
                }
            }
            // the few other columns: (column, in q (true) or v, ∂F, ∂τ)
            let mut extra: Vec<(usize, bool, [f64; 2], f64)> = Vec::with_capacity(4);
            let mv = |mtx: &[[f64; 2]; 2], x: [f64; 2]| {
                [
                    mtx[0][0] * x[0] + mtx[0][1] * x[1],
                    mtx[1][0] * x[0] + mtx[1][1] * x[1],
                ]
            };
            let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
            extra.push((0, false, mv(&c.df_dv, bs), dot(c.dt_dv, bs)));
            if let Some(k) = self.coords.pulley_dof(r.pulley) {
                extra.push((k, false, c.df_dw, c.dt_dw));
            }
            if let (true, Some(a), Some(k)) = (idler, arm.as_ref(), self.coords.arm_dof()) {
                let ((f_q, t_q), (f_v, t_v)) = a.contact_derivatives(&c);
                extra.push((k, true, f_q, t_q));
                extra.push((k, false, f_v, t_v));
            }
            // belt rows 0 (e_tᵀ) and 1..=m (Tᵀ)
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
                for &(col, in_q, df, _) in &extra {
                    let target = if in_q { &mut kq } else { &mut cv };
                    target[(i, col)] -= dot(p, df);
                }
            }
            // the pulley's spin row: τ
            if let Some(k) = self.coords.pulley_dof(r.pulley) {
                for j in 0..m {
                    kq[(k, j + 1)] -= tz[j];
                    cv[(k, j + 1)] -= tzd[j];
                }
                for &(col, in_q, _, dt) in &extra {
                    let target = if in_q { &mut kq } else { &mut cv };
                    target[(k, col)] -= dt;
                }
            }
            // the arm's row: M = −(c − p) × F
            if let (true, Some(a), Some(k)) = (idler, arm.as_ref(), self.coords.arm_dof()) {
                for j in 0..m {
                    kq[(k, j + 1)] += cross(a.arm, [dfz[0][j], dfz[1][j]]);
                    cv[(k, j + 1)] += cross(a.arm, [dfzd[0][j], dfzd[1][j]]);
                }
                for &(col, in_q, df, _) in &extra {
                    let target = if in_q { &mut kq } else { &mut cv };
                    target[(k, col)] += cross(a.arm, df);
                }
                // the lever turns with the arm: ∂(c − p)/∂θ = c'
                kq[(k, k)] += cross(a.dc, c.force);
            }
        }
        self.coords.add_tangent(
            t,
            q,
            v,
            |i, j, x| kq[(i, j)] += x,
            |i, j, x| cv[(i, j)] += x,
        );
        (kq, cv)
    }
}

impl SecondOrderSystem for FlowingBelt {
    fn n_q(&self) -> usize {
        self.n_v
    }

    fn mass(&self, _t: f64, q: &[f64]) -> Result<SysMatrix, MbdError> {
        let m = self.m;
        let mut mm = Mat::<f64>::zeros(self.n_v, self.n_v);
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
        for (k, j) in self.coords.inertias() {
            mm[(k, k)] = j;
        }
        Ok(SysMatrix::Dense(mm))
    }

    fn forces(
        &self, t: f64, q: &[f64], v: &[f64], f: &mut [f64], _ws: &mut Workspace,
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
        if self.exact_axial {
            let d = self.deflection(z);
            let law = super::model::BarLaw::of(&self.fe.drive);
            let mut c = vec![0.0; 2 * self.bars.len()];
            for (b, bar) in self.bars.iter().enumerate() {
                let (cb, _) = bar.correction(&d, &law, false);
                c[2 * b] = cb[0];
                c[2 * b + 1] = cb[1];
            }
            let dx = &self.bar_dx;
            for (k, h) in head.iter_mut().enumerate().take(m + 1) {
                let mut acc = 0.0;
                for (r, cr) in c.iter().enumerate() {
                    acc += dx[(r, k)] * cr;
                }
                *h += acc;
            }
        }
        tail.fill(0.0);
        let arm = self.coords.arm_state(q, v);
        for r in &self.rows {
            let (c, _, idler) = self.row_contact(r, arm.as_ref(), t, z, zd, v);
            if c.normal == 0.0 && c.friction == 0.0 {
                continue;
            }
            let et = self.fe.tangent[r.node];
            head[0] += et[0] * c.force[0] + et[1] * c.force[1];
            for j in 0..m {
                head[j + 1] += r.t[(0, j)] * c.force[0] + r.t[(1, j)] * c.force[1];
            }
            if let Some(k) = self.coords.pulley_dof(r.pulley) {
                tail[k - m - 1] += c.torque;
            }
            if let (true, Some(a), Some(k)) = (idler, arm.as_ref(), self.coords.arm_dof()) {
                tail[k - m - 1] += a.moment(c.force);
            }
        }
        self.coords.add_forces(t, q, v, f);
        if let Some(i) = f.iter().position(|x| !x.is_finite()) {
            return Err(MbdError::NonFinite {
                what: format!("belt generalized force {i}"),
                t,
            });
        }
        Ok(())
    }

    fn force_tangent(
        &self, t: f64, q: &[f64], v: &[f64], _ws: &mut Workspace,
    ) -> Result<Option<ForceTangent>, MbdError> {
        let (k, c) = self.tangent(t, q, v);
        Ok(Some(ForceTangent {
            stiffness: SysMatrix::Dense(k),
            damping: SysMatrix::Dense(c),
        }))
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::belt::{BeltMesh, BeltReduction};
    use belt::{Layout, Pulley, Section, Signal, Tensioner, WrapSide};
    use mbd_core::central_difference_column;

    /// A four-pulley drive with a back-side idler on a tensioner arm (pulley 2), the idler
    /// and the last pulley damped.
    pub(crate) fn layout_belt(axial_force: AxialForce) -> FlowingBelt {
        let free = |j| Motion::load(j, Signal::constant(1.5));
        let pulleys = vec![
            Pulley::new(
                "a",
                [0.0, 0.0],
                0.06,
                WrapSide::Inside,
                Motion::speed(Signal::constant(50.0)),
            ),
            Pulley::new("b", [0.30, 0.05], 0.05, WrapSide::Inside, free(0.01)),
            Pulley::new(
                "c",
                [0.18, -0.02],
                0.035,
                WrapSide::Outside,
                Motion::Load {
                    inertia: 1e-4,
                    torque: Signal::constant(1.5),
                    damping: 2e-4,
                    decoupler: None,
                },
            ),
            Pulley::new(
                "d",
                [0.12, -0.20],
                0.04,
                WrapSide::Inside,
                Motion::Load {
                    inertia: 0.005,
                    torque: Signal::constant(1.5),
                    damping: 0.01,
                    decoupler: None,
                },
            ),
        ];
        let mut layout = Layout::new(pulleys, Section::default(), 310.0);
        layout.contact = belt::BeltContact::ribaric();
        layout.tensioner = Some(Tensioner {
            pulley: 2,
            pivot: [0.14, 0.04],
            stiffness: 30.0,
            preload: 12.0,
            preload_angle: -1.0,
            damping: 0.3,
            dry_friction: 0.5,
            friction_rate: 0.05,
            inertia: 2e-3,
            travel: [-2.0, 0.0],
        });
        let drive = layout.resolve().unwrap();
        let settings = FlowingSettings {
            mesh: BeltMesh {
                span_element: 0.05,
                arc_element: 0.01,
                contact_margin_nodes: 1,
            },
            reduction: BeltReduction {
                free_modes: Some(10),
            },
            axial_force,
        };
        FlowingBelt::new(&drive, &settings).unwrap()
    }

    // The analytic tangent of the layout model (pulley spins, moving idler, arm moment,
    // spring, damper, dry friction) against central differences of the forces (an independent
    // evaluation of the same equations).
    #[test]
    fn layout_tangent_matches_finite_differences() {
        check_layout_tangent(layout_belt(AxialForce::Linear));
    }

    // The same with the co-rotated axial force (issue 34, model::Bar).
    #[test]
    fn layout_tangent_with_co_rotated_axial_force_matches_finite_differences() {
        check_layout_tangent(layout_belt(AxialForce::CoRotated));
    }

    fn check_layout_tangent(belt: FlowingBelt) {
        let n = belt.n_q();
        let k = belt.coords.arm_dof().unwrap();
        let mut q = vec![0.0; n];
        let mut v = vec![0.0; n];
        for i in 1..=belt.n_modes() {
            q[i] = 1e-5 * ((i as f64) * 0.7).sin();
            v[i] = 1e-3 * ((i as f64) * 1.3).cos();
        }
        v[0] = 3.0;
        for p in 1..4 {
            v[belt.coords.pulley_dof(p).unwrap()] = 3.0 / [0.06, 0.05, 0.035, 0.04][p] * 0.99;
        }
        q[k] = 2e-3;
        v[k] = 0.03;
        let (kt, ct) = belt.tangent(0.1, &q, &v);
        let scale = kt.norm_max().max(ct.norm_max());
        for (j, h) in [
            (k, 1e-7),
            (1, 1e-9),
            (belt.coords.pulley_dof(2).unwrap(), 1e-6),
        ] {
            for in_q in [true, false] {
                let fd = central_difference_column(&belt, (0.1, &q, &v), j, h, in_q).unwrap();
                for (i, fd) in fd.into_iter().enumerate() {
                    let an = if in_q { kt[(i, j)] } else { ct[(i, j)] };
                    let err = (fd - an).abs() / (fd.abs().max(1e-3 * scale));
                    assert!(err < 1e-4, "row {i} col {j} q={in_q}: fd {fd} vs {an}");
                }
            }
        }
    }
}
