//! The nodal belt drive with a rotating (Lagrangian) mesh: Ribaric (5.1)–(5.8) with penalty
//! contact (6.1), (6.2) — the reference formulation the flowing-material form (5.14) replaces.
//!
//! The same [`BeltFe`] data as [`super::FlowingBelt`] (56-element loop, section, T0, lumped
//! mass, Rayleigh convention, contact law), but the material nodes travel along the path: node
//! `i` sits at the path coordinate `s_i(t) = s_i0 + s_b(t)` with its own unit tangent `e_t^i`
//! of the exact path and curvature vector `ε_n^i = e_n^i/ρ^i` (Ribaric (5.3); see the choices
//! below).
//!
//! Coordinates `q = [s_b, δ, φ_k…]`, velocities `v = [v, δ̇, ω_k…]`: the belt's travel `s_b`
//! and speed `v = ṡ_b`, the global nodal deflections `δ` (`3N`: x, y, θ per node;
//! `d^i = r^i(s_i) + δ^i`, (5.1)) and the angle and speed of every pulley that is not
//! speed-driven (pulley order, [`belt::Motion`]), the tensioner arm's rotation, then the
//! carrier's and accessory's angles of every decoupled pulley ([`belt::decoupler`], (D1)–(D3)).
//! The two-pulley drive of Ribaric Table 6-1
//! has `q = [s_b, δ, φ₂]`: the driver's speed `ω₁(t)` is prescribed.
//!
//! Any layout (issue 17): [`NodalBelt::new`] takes the resolved drive ([`belt::Drive`]: N
//! pulleys, grooved or back side, one [`belt::Motion`] each, an optional tensioner), the same
//! input as [`super::FlowingBelt::new`]; the material nodes travel along its path.
//!
//! ```text
//!   d̈ = a e_t + v² ε_n + δ̈                                          (5.3), (5.4)
//!   [ e_tᵀ M e_t   e_tᵀ M ] [a ]   [ e_tᵀ g          ]   [ 0  ]
//!   [ M e_t        M      ] [δ̈] = [ g − v² M ε_n    ] − [ Dᵀλ ]      (5.6)
//!   g = f0 + f_contact − K δ − C δ̇                                  (5.8)
//!   Φ = e_t^k(s_k)ᵀ δ^k = 0     (reference condition, note U5)
//!   J_k ω̇_k = τ_contact,k − M_load,k(t)                            (free pulleys)
//! ```
//!
//! (5.6) is singular along `[1; −e_t]` (a uniform slide of the deflections along the path is a
//! change of `s_b`); the reference condition — zero tangential deflection of material node
//! `k = 0` in its current path frame, a holonomic constraint with multiplier λ — removes the
//! rank deficiency. Its reaction vanishes (the right-hand side is orthogonal to the null vector).
//!
//! Choices (the seed leaves them open; documented per the seed-000 note):
//! - **How K follows the moving nodes.** `K = K_e + K_g(T0)`, the damping `C = αM + βK_e` and
//!   the pre-tension force `f0 = T0 (u_i − u_{i−1})` are rebuilt at every force evaluation from
//!   the element chords of the current reference polygon `r^i(s_i0 + s_b)`: each element keeps
//!   its material nodes, its frame follows its chord. This is the linear model of (5.5) about
//!   the moving reference. When an element passes from a span onto an arc its chord shortens and
//!   turns: the polygonal (element-passing) excitation the stationary mesh avoids.
//! - The node masses (lumped, [`BeltFe::mass`]) and the penalty tributary lengths travel with
//!   the material nodes (constant).
//! - `ε_n^i = e_n^i/ρ^i` (Ribaric (5.3), (5.4)) is evaluated as the discrete curvature of the
//!   current chord polygon, `(u_i − u_{i−1}) / L_i` (`u` unit chords, `L_i` the material
//!   tributary length): the definition of [`BeltFe::curvature`], so both formulations agree at
//!   `s_b = 0` and the centrifugal load stays `ρv²/T0` times the pre-tension force. The exact
//!   path curvature (`1/R` on arcs, 0 on spans) jumps when a node crosses a tangent point, a
//!   force discontinuous in `s_b` on which the Newton iterations of the implicit integrator
//!   stall. Rotational entries of `e_t`, `ε_n` are zero (note U6).
//! - Damping: `β K_e` on the co-rotated rate `δ̇ − ψ̇_e J δ` of each element
//!   ([`BeltFe::frame_turn`]: δ̇, the nodal rate, is the material rate here, but of global
//!   components; the element frames turn at `ψ̇_e = v ψ'_e` as they pass over a pulley, and
//!   `β K_e δ̇` alone would count that turning of an unchanged deflection as a strain rate) and
//!   `α M δ̇` (note U10: the flowing form applies `α M` to the Eulerian rate; the difference,
//!   `α M v δ_,s`, is a drag of order 10⁻³ N for Table 6-1).
//! - Every node can touch either pulley: the penalty law is evaluated for all node–pulley
//!   pairs (the contact set changes as the nodes move); [`node_contact`] returns no force for an
//!   open pair.
//! - Mass, tangent and constraint Jacobian are sparse (banded loop plus the full rows and
//!   columns of `s_b` and `φ₂`), with a state-independent pattern so the integrator's symbolic
//!   LU is reused.
//!
//! Accuracy (tests/tests/flowing_belt_nodal.rs, BENCHMARKS.md): the rotating mesh needs a fine
//! uniform loop. On the 56-element flowing mesh its 45 mm span elements land on the 50 mm
//! pulleys and the polygonal ripple of the driven speed reaches ±1 rad/s; on uniform loops its
//! Δω(8 N m) exceeds the flowing form's on the same loop by 17 % (54 elements), 2.1 % (162) and
//! 1.7 % (216).

use super::config::BeltMesh;
use super::contact::{NodeContact, NodeMotion, PulleyFrame, correction_limit, node_contact};
use super::coordinates::{ArmState, DriveCoordinates};
use super::flowing_system::pulley_frames;
use super::model::{BeltFe, NODE_DOFS, chord_tensions, chord_turn_rate, corotational_rate_block};
use super::statics::dense_equilibrium;
use belt::tensioner::cross;
use belt::{Arm, Drive, Motion};
use contact::friction::{FrictionLaw, FrictionSpec};
use contact::normal::PolynomialPenalty;
use faer::Mat;
use faer::sparse::{SparseColMat, Triplet};
use fe_model::element::{Frame2d, Frame2dSection, FrameElement};
use mbd_core::Workspace;
use mbd_core::{ForceTangent, MbdError, SecondOrderSystem, SysMatrix};

/// What the nodal belt's balance note says ([`NodalBelt::balance_defect`]).
const NODAL_BALANCE_DEFECT: &str = "the nodal belt's linear elastic and damping forces (Ribaric \
(5.5)) are referenced to the path its material travels along, so they do work on the travel \
that is neither stored nor dissipated (+1.7 % of the crank's power on the three-pulley \
example at 12.6 m/s; BENCHMARKS.md, \"The nodal belt on a drive nobody tuned\"): run the ANCF \
model, or the energy-consistent flowing belt (apps/belt/examples/fead-energy-consistent.toml)";

/// 6×6 element matrix in global axes.
type Block = [[f64; 6]; 6];

/// Sparse system matrix.
type Sparse = SparseColMat<usize, f64>;

/// The reference polygon at one belt travel `s_b`: node frames and element matrices.
#[derive(Debug, Clone)]
struct Mesh {
    pos: Vec<[f64; 2]>,
    tan: Vec<[f64; 2]>,
    /// Discrete curvature vector `ε_n,i = (u_i − u_{i−1}) / L_i` of the current chord polygon.
    eps_n: Vec<[f64; 2]>,
    /// `K_e + K_g(T0)` of each element (global axes, DOFs of nodes `e`, `e+1`).
    k: Vec<Block>,
    /// `K_e` of each element (for the β part of the damping).
    ke: Vec<Block>,
    /// `ψ'_e K_e J` of each element \[N/m²\] ([`BeltFe::frame_turn`]: the chord's turn rate
    /// [`chord_turn_rate`] along the path times the co-rotation block
    /// [`corotational_rate_block`]).
    kj: Vec<Block>,
    /// Pre-tension force `f0` (`3N`) \[N\].
    f0: Vec<f64>,
}

/// The nodal rotating-mesh belt drive (see the module documentation).
#[derive(Debug, Clone)]
pub struct NodalBelt {
    /// The belt loop (its `s`, masses and tributary lengths are those of the material nodes at
    /// `s_b = 0`).
    pub fe: BeltFe,
    /// Material node whose tangential deflection is zero (reference condition).
    pub reference_node: usize,
    /// The free pulleys', the tensioner arm's and the decouplers' coordinates, after the
    /// nodal ones.
    pub coords: DriveCoordinates,
    section: Frame2dSection,
    pulleys: Vec<PulleyFrame>,
    /// The friction law of each pulley, travel order ([`belt::Drive::wrap_friction_law`]).
    friction: Vec<FrictionSpec>,
    laws: Vec<PolynomialPenalty>,
    mass_total: f64,
    n_v: usize,
    /// Apply each element's axial force `N = F(λ₀ l/l₀)` of the material law ([`super::model::BarLaw`]) along its deformed chord
    /// (issue 34, [`super::model::Bar`]); `false`: the linear model of Ribaric (5.5).
    exact_axial: bool,
}

/// Rotate a local 6×6 element matrix to global axes: `Tᵀ k T`, `T = diag(R, 1, R, 1)` with
/// `R = [c s; −s c]` (fe-model's [`Frame2d`] convention).
fn rotate(local: &Mat<f64>, c: f64, s: f64) -> Block {
    let mut a = [[0.0; 6]; 6];
    for (i, row) in a.iter_mut().enumerate() {
        for b in [0, 3] {
            let (k0, k1) = (local[(i, b)], local[(i, b + 1)]);
            row[b] = c * k0 - s * k1;
            row[b + 1] = s * k0 + c * k1;
            row[b + 2] = local[(i, b + 2)];
        }
    }
    let mut out = [[0.0; 6]; 6];
    for b in [0, 3] {
        for j in 0..6 {
            let (a0, a1) = (a[b][j], a[b + 1][j]);
            out[b][j] = c * a0 - s * a1;
            out[b + 1][j] = s * a0 + c * a1;
            out[b + 2][j] = a[b + 2][j];
        }
    }
    out
}

/// Triplets of a tangent matrix whose row 0 is `e_tᵀ` times the nodal rows (Ribaric (5.6)).
struct Tangent<'a> {
    trip: Vec<Triplet<usize, usize, f64>>,
    row0: Vec<f64>,
    tan: &'a [[f64; 2]],
    n: usize,
}

impl<'a> Tangent<'a> {
    fn new(n: usize, tan: &'a [[f64; 2]]) -> Self {
        Self {
            trip: Vec::with_capacity(64 * n),
            row0: vec![0.0; n],
            tan,
            n,
        }
    }

    /// Entry `(r, c)` (`r ≥ 1`); a nodal translation row also feeds row 0.
    fn add(&mut self, r: usize, c: usize, x: f64) {
        self.trip.push(Triplet::new(r, c, x));
        let k = r.wrapping_sub(1);
        if r >= 1 && k < NODE_DOFS * self.tan.len() && k % NODE_DOFS < 2 {
            self.row0[c] += self.tan[k / NODE_DOFS][k % NODE_DOFS] * x;
        }
    }

    fn finish_row0(mut self) -> Result<SparseColMat<usize, f64>, MbdError> {
        for c in 0..self.n {
            self.trip.push(Triplet::new(0, c, self.row0[c]));
        }
        SparseColMat::try_new_from_triplets(self.n, self.n, &self.trip).map_err(|e| {
            MbdError::Model {
                t: 0.0,
                message: format!("nodal belt tangent assembly: {e:?}"),
            }
        })
    }

    /// Like [`Self::finish_row0`], with `(0, 0)` given (the difference column's row 0).
    fn finish(mut self, k00: f64) -> Result<SparseColMat<usize, f64>, MbdError> {
        self.row0[0] = k00;
        self.finish_row0()
    }
}

impl NodalBelt {
    /// Whether the contact slip follows the strain the elements carry
    /// (`belt::ModelTraits::near_coulomb_creep`): always, the nodes are material points.
    pub fn contact_rates_follow_the_strain(&self) -> bool {
        true
    }

    /// The known cause of a balance miss (`belt::ModelTraits::balance_defect`): the linear
    /// parts of Ribaric (5.5) about the travelling reference polygon (module documentation,
    /// "How K follows the moving nodes") do work on the belt's travel (issue 34 item 2; on the
    /// three-pulley example at 1500 rpm, 12.6 m/s over 35 and 40 mm pulleys, +1.7 % of the crank's
    /// power, of which the `β K_e` damping's work on the travel is +2.6 %).
    pub fn balance_defect(&self) -> Option<&'static str> {
        Some(NODAL_BALANCE_DEFECT)
    }

    /// The rotating-mesh model of `drive` (Ribaric (5.7)) on the loop of `mesh` over the
    /// mounted path (give it near-uniform elements, [`BeltMesh::uniform`]: long span elements
    /// landing on a wrap excite it at the element-passing frequency). Every node can touch
    /// every pulley (Ribaric (6.1), (6.2) against each rigid pulley, grooved or back side). A
    /// tensioner's idler moves with its arm, `c(θ) = p + L(cos θ, sin θ)` ([`belt::tensioner`]):
    /// its contact sees the node at `d − c(θ)` with the relative velocity `V − ċ`, and the arm
    /// the moment `(c − p) × (−F)` of the contact forces `F` on the belt, with the spring,
    /// damper and dry friction (`J_a Δθ̈ = (c − p) × F_hub + M_s + M_d + M_f`); the arm rotation
    /// `Δθ` from the laid-out angle is the last coordinate.
    pub fn new(drive: &Drive, mesh: &BeltMesh) -> Result<Self, crate::FlowError> {
        let fe = BeltFe::new(drive, mesh)?;
        Self::on(fe, drive.motions(), drive.arm().copied())
    }

    pub(crate) fn on(
        fe: BeltFe, motions: Vec<Motion>, tensioner: Option<Arm>,
    ) -> Result<Self, crate::FlowError> {
        let b = *fe.drive.belt();
        let contact = *fe.drive.contact();
        let section = Frame2dSection {
            ea: b.ea,
            ei: b.ei,
            mass_per_length: b.mass_per_length,
        };
        let laws = fe
            .tributary
            .iter()
            .map(|&l| PolynomialPenalty {
                quadratic: contact.penalty_quadratic,
                linear: contact.penalty_linear,
                length: l,
            })
            .collect();
        let pulleys = pulley_frames(&fe);
        let mass_total = fe.mass.chunks(NODE_DOFS).map(|m| m[0]).sum::<f64>();
        let mut n_v = fe.n_dofs() + 1;
        let coords = DriveCoordinates::number(motions, tensioner, &mut n_v);
        let belt = Self {
            coords,
            section,
            pulleys,
            friction: fe.drive.wrap_friction_laws(),
            laws,
            mass_total,
            fe,
            reference_node: 0,
            n_v,
            exact_axial: true,
        };
        // fail early on a degenerate polygon
        belt.mesh(0.0)
            .map_err(|e| crate::FlowError::LinearAlgebra {
                what: "nodal belt mesh".into(),
                reason: e.to_string(),
            })?;
        Ok(belt)
    }

    /// Number of nodal DOFs `3N` (the system has `3N + 1` coordinates, one per free pulley
    /// and one constraint).
    pub fn n_nodal(&self) -> usize {
        self.fe.n_dofs()
    }

    fn n(&self) -> usize {
        self.fe.n_nodes()
    }

    /// Reference positions `r^i(s_i0 + s_b)` of the material nodes \[m\].
    pub fn reference_positions(&self, s_b: f64) -> Vec<[f64; 2]> {
        self.fe
            .s
            .iter()
            .map(|&s| self.fe.path().point(s + s_b).position)
            .collect()
    }

    fn mesh(&self, s_b: f64) -> Result<Mesh, MbdError> {
        let n = self.n();
        let pts: Vec<_> = self
            .fe
            .s
            .iter()
            .map(|&s| self.fe.path().point(s + s_b))
            .collect();
        let t0 = self.fe.tension();
        let mut k = Vec::with_capacity(n);
        let mut ke = Vec::with_capacity(n);
        let mut kj = Vec::with_capacity(n);
        let mut chords = Vec::with_capacity(n);
        for e in 0..n {
            let j = (e + 1) % n;
            let el = Frame2d::new(
                [0, 1, 2, 3, 4, 5],
                pts[e].position,
                pts[j].position,
                self.section,
                t0,
            )
            .map_err(|err| MbdError::Model {
                t: 0.0,
                message: format!("nodal belt element {e} at s_b = {s_b} m: {err}"),
            })?;
            let kel = rotate(&el.local_stiffness(), el.c, el.s);
            let kg = rotate(&el.local_geometric_stiffness(), el.c, el.s);
            let mut kt = kel;
            for a in 0..6 {
                for b in 0..6 {
                    kt[a][b] += kg[a][b];
                }
            }
            k.push(kt);
            let turn = chord_turn_rate(
                pts[e].position,
                pts[j].position,
                pts[e].tangent,
                pts[j].tangent,
            );
            let mut b = corotational_rate_block(&kel);
            b.iter_mut().flatten().for_each(|x| *x *= turn);
            kj.push(b);
            ke.push(kel);
            chords.push([el.c, el.s]);
        }
        let mut f0 = vec![0.0; NODE_DOFS * n];
        let mut eps_n = vec![[0.0; 2]; n];
        for i in 0..n {
            let (u, up) = (chords[i], chords[(i + n - 1) % n]);
            for c in 0..2 {
                f0[NODE_DOFS * i + c] = t0 * (u[c] - up[c]);
                eps_n[i][c] = (u[c] - up[c]) / self.fe.tributary[i];
            }
        }
        Ok(Mesh {
            pos: pts.iter().map(|p| p.position).collect(),
            tan: pts.iter().map(|p| p.tangent).collect(),
            eps_n,
            k,
            ke,
            kj,
            f0,
        })
    }

    fn element_dofs(&self, e: usize) -> [usize; 6] {
        let j = (e + 1) % self.n();
        [3 * e, 3 * e + 1, 3 * e + 2, 3 * j, 3 * j + 1, 3 * j + 2]
    }

    /// Motion of material node `i` against pulley `p` at `(t, q, v)`, the node's reference
    /// position `pos` and unit tangent `tan` on the path at `s_i0 + s_b` given: position
    /// `r^i + δ^i`, material velocity `v e_t^i + δ̇^i` (Ribaric (5.1), (5.3)), relative to the
    /// idler's centre when `p` is the tensioner's (`arm`, a rigid disk translating with the arm).
    #[allow(clippy::too_many_arguments)]
    fn node_motion(
        &self, i: usize, p: usize, pos: [f64; 2], tan: [f64; 2], arm: Option<&ArmState>, t: f64,
        q: &[f64], v: &[f64],
    ) -> NodeMotion {
        let (d, dd, vb) = (&q[1..], &v[1..], v[0]);
        let mut frame = self.pulleys[p];
        let mut frame_vel = [0.0; 2];
        if let (Some(a), Some(k)) = (arm, self.coords.idler())
            && k == p
        {
            frame.center = a.center;
            frame_vel = a.vel;
        }
        NodeMotion {
            frame,
            omega: self.coords.pulley_speed(p, t, v),
            position: [pos[0] + d[NODE_DOFS * i], pos[1] + d[NODE_DOFS * i + 1]],
            velocity: [
                vb * tan[0] + dd[NODE_DOFS * i] - frame_vel[0],
                vb * tan[1] + dd[NODE_DOFS * i + 1] - frame_vel[1],
            ],
        }
    }

    /// Every active node–pulley contact at `(t, q, v)`: `(node, pulley, contact)`.
    fn contacts(
        &self, mesh: &Mesh, t: f64, q: &[f64], v: &[f64],
    ) -> Vec<(usize, usize, NodeContact)> {
        let arm = self.coords.arm_state(q, v);
        let mut out = Vec::new();
        for i in 0..self.n() {
            for p in 0..self.pulleys.len() {
                let m = self.node_motion(i, p, mesh.pos[i], mesh.tan[i], arm.as_ref(), t, q, v);
                let (x, frame) = (m.position, m.frame);
                let rel = [x[0] - frame.center[0], x[1] - frame.center[1]];
                if rel[0].hypot(rel[1]) >= frame.radius {
                    continue;
                }
                let c = node_contact(
                    &frame,
                    m.omega,
                    x,
                    m.velocity,
                    &self.laws[i],
                    &self.friction[p],
                );
                if c.normal != 0.0 || c.friction != 0.0 {
                    out.push((i, p, c));
                }
            }
        }
        out
    }

    /// Contact state of every touching node at `(t, q, v)`: `(node, pulley, path position s
    /// [m], contact)`.
    pub fn contact_report(
        &self, t: f64, q: &[f64], v: &[f64],
    ) -> Result<Vec<(usize, usize, f64, NodeContact)>, MbdError> {
        let mesh = self.mesh(q[0])?;
        Ok(self
            .contacts(&mesh, t, q, v)
            .into_iter()
            .map(|(i, p, c)| (i, p, self.fe.path().wrap_s(self.fe.s[i] + q[0]), c))
            .collect())
    }

    /// The same belt with the elements' axial force `axial` (the nodal model's default:
    /// co-rotated).
    pub fn with_axial_force(mut self, axial: super::config::AxialForce) -> Self {
        self.exact_axial = axial == super::config::AxialForce::CoRotated;
        self
    }

    /// Axial tension of the belt element starting at each material node \[N\]: `T0 + EA Δl/l`
    /// ([`chord_tensions`] on the reference polygon at `s_b = q[0]`).
    pub fn element_tensions(&self, q: &[f64]) -> Vec<f64> {
        let b = &self.fe.drive;
        if self.exact_axial {
            let law = super::model::BarLaw::of(b);
            let d = &q[1..=self.n_nodal()];
            return super::model::Bar::loop_of(&self.reference_positions(q[0]))
                .iter()
                .map(|e| e.force(d, &law))
                .collect();
        }
        chord_tensions(
            &self.reference_positions(q[0]),
            &q[1..=self.n_nodal()],
            b.tension(),
            b.belt().ea,
        )
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

    /// Torques of the contact forces on the pulleys in their travel sense \[N m\] (pulley
    /// order).
    pub fn pulley_torques(&self, t: f64, q: &[f64], v: &[f64]) -> Result<Vec<f64>, MbdError> {
        let mesh = self.mesh(q[0])?;
        let mut tq = vec![0.0; self.pulleys.len()];
        for (_, p, c) in self.contacts(&mesh, t, q, v) {
            tq[p] += c.torque;
        }
        Ok(tq)
    }

    /// Viscous axial force of the belt element starting at each material node \[N\]:
    /// `β EA Dε/Dt` on the co-rotated stretch rate of the material element
    /// ([`super::model::chord_viscous_forces`] on the reference polygon at `s_b = q[0]`, `δ̇`
    /// the material rate), the part of the element's axial force its `β K_e` damping carries
    /// beside the elastic force [`Self::element_tensions`].
    pub fn element_viscous_forces(&self, q: &[f64], v: &[f64]) -> Vec<f64> {
        let dr = &self.fe.drive;
        let nd = self.n_nodal();
        let pts: Vec<_> = self
            .fe
            .s
            .iter()
            .map(|&s| self.fe.path().point(s + q[0]))
            .collect();
        let pos: Vec<[f64; 2]> = pts.iter().map(|p| p.position).collect();
        let tan: Vec<[f64; 2]> = pts.iter().map(|p| p.tangent).collect();
        super::model::chord_viscous_forces(
            &pos,
            &tan,
            &q[1..=nd],
            &v[1..=nd],
            v[0],
            dr.damping().beta * dr.belt().ea,
        )
    }

    /// Momentum the belt carries through a section fixed in space at each material node
    /// \[N\]: `ṁ V` with the node's velocity `V = v e_t + δ̇` and the mass flow
    /// `ṁ = ρ (V·t)/λ` (`t` the belt's unit tangent at the node, the path's tangent turned by
    /// the node's rotation; `λ` the stretch of the node's two half-elements against the
    /// reference polygon; `ρ` the node's lumped mass over its tributary length): the material
    /// label passes the section at `(V·t)/λ`. The belt report subtracts its moment from the
    /// spans' ([`belt::SpanState::momentum_flux`]).
    pub fn momentum_flux(&self, q: &[f64], v: &[f64]) -> Vec<[f64; 2]> {
        let (sb, vb) = (q[0], v[0]);
        let n = self.fe.n_nodes();
        let reference = self.reference_positions(sb);
        let x: Vec<[f64; 2]> = reference
            .iter()
            .enumerate()
            .map(|(i, r)| [r[0] + q[1 + NODE_DOFS * i], r[1] + q[2 + NODE_DOFS * i]])
            .collect();
        let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
        (0..n)
            .map(|i| {
                let (prev, next) = ((i + n - 1) % n, (i + 1) % n);
                let tan = self.fe.path().point(self.fe.s[i] + sb).tangent;
                let (sn, cs) = q[3 + NODE_DOFS * i].sin_cos();
                let t = [cs * tan[0] - sn * tan[1], sn * tan[0] + cs * tan[1]];
                let vel = [
                    vb * tan[0] + v[1 + NODE_DOFS * i],
                    vb * tan[1] + v[2 + NODE_DOFS * i],
                ];
                let lambda = (dist(x[next], x[i]) + dist(x[i], x[prev]))
                    / (dist(reference[next], reference[i]) + dist(reference[i], reference[prev]));
                let rho = self.fe.mass[NODE_DOFS * i] / self.fe.tributary[i];
                let mdot = rho * (vel[0] * t[0] + vel[1] * t[1]) / lambda;
                [mdot * vel[0], mdot * vel[1]]
            })
            .collect()
    }

    /// The whole axial force the belt element starting at each material node carries \[N\]:
    /// elastic ([`Self::element_tensions`]) plus viscous ([`Self::element_viscous_forces`]).
    pub fn element_forces(&self, q: &[f64], v: &[f64]) -> Vec<f64> {
        let mut f = self.element_tensions(q);
        for (a, b) in f.iter_mut().zip(self.element_viscous_forces(q, v)) {
            *a += b;
        }
        f
    }

    /// Power dissipated by the belt's Rayleigh damping at `(q, v)` \[W\]: `−Q_dᵀ δ̇` with the
    /// damping forces `Q_d = −α M δ̇ − β K_e (δ̇ − v ψ′ J δ)` of the nodal forces (the
    /// only non-conservative forces of the belt besides the contact; issue 34 power balance).
    pub fn damping_dissipation(&self, q: &[f64], v: &[f64]) -> Result<f64, MbdError> {
        let mesh = self.mesh(q[0])?;
        let nd = self.n_nodal();
        let (d, dd, vb) = (&q[1..=nd], &v[1..=nd], v[0]);
        let (alpha, beta) = (self.fe.drive.damping().alpha, self.fe.drive.damping().beta);
        let mut p = 0.0;
        for e in 0..self.n() {
            let dofs = self.element_dofs(e);
            let (ke, kj) = (&mesh.ke[e], &mesh.kj[e]);
            for a in 0..6 {
                let mut acc = 0.0;
                for b in 0..6 {
                    acc += ke[a][b] * dd[dofs[b]] - vb * kj[a][b] * d[dofs[b]];
                }
                p += beta * acc * dd[dofs[a]];
            }
        }
        for (mi, di) in self.fe.mass.iter().zip(dd) {
            p += alpha * mi * di * di;
        }
        Ok(p)
    }

    /// Nodal forces `g − v² M ε_n` (`3N`), the contact torque on each pulley \[N m\] and the
    /// moment of the idler's contact forces about the tensioner's pivot \[N m\].
    fn nodal_forces(
        &self, mesh: &Mesh, t: f64, q: &[f64], v: &[f64], g: &mut [f64],
    ) -> (Vec<f64>, f64) {
        let n = self.n();
        let nd = self.n_nodal();
        let (d, dd, vb) = (&q[1..=nd], &v[1..=nd], v[0]);
        let (alpha, beta) = (self.fe.drive.damping().alpha, self.fe.drive.damping().beta);
        g.copy_from_slice(&mesh.f0);
        for e in 0..n {
            let dofs = self.element_dofs(e);
            let (k, ke, kj) = (&mesh.k[e], &mesh.ke[e], &mesh.kj[e]);
            for a in 0..6 {
                let mut acc = 0.0;
                for b in 0..6 {
                    // β K_e on the co-rotated rate δ̇ − v ψ' J δ (BeltFe::frame_turn)
                    acc += k[a][b] * d[dofs[b]]
                        + beta * (ke[a][b] * dd[dofs[b]] - vb * kj[a][b] * d[dofs[b]]);
                }
                g[dofs[a]] -= acc;
            }
        }
        if self.exact_axial {
            let law = super::model::BarLaw::of(&self.fe.drive);
            for bar in super::model::Bar::loop_of(&mesh.pos) {
                let (c, _) = bar.correction(d, &law, false);
                for a in 0..2 {
                    g[NODE_DOFS * bar.j + a] += c[a];
                    g[NODE_DOFS * bar.i + a] -= c[a];
                }
            }
        }
        for (gi, (mi, di)) in g.iter_mut().zip(self.fe.mass.iter().zip(dd)) {
            *gi -= alpha * mi * di;
        }
        for i in 0..n {
            let c = vb * vb * self.fe.mass[NODE_DOFS * i];
            for a in 0..2 {
                g[NODE_DOFS * i + a] -= c * mesh.eps_n[i][a];
            }
        }
        let mut torque = vec![0.0; self.pulleys.len()];
        let mut moment = 0.0;
        let arm = self.coords.arm_state(q, v);
        for (i, p, c) in self.contacts(mesh, t, q, v) {
            g[NODE_DOFS * i] += c.force[0];
            g[NODE_DOFS * i + 1] += c.force[1];
            torque[p] += c.torque;
            if let (Some(a), Some(k)) = (&arm, self.coords.idler())
                && k == p
            {
                moment += a.moment(c.force);
            }
        }
        (torque, moment)
    }

    fn forces_on(
        &self, mesh: &Mesh, t: f64, q: &[f64], v: &[f64], f: &mut [f64],
    ) -> Result<(), MbdError> {
        let nd = self.n_nodal();
        let (torque, moment) = self.nodal_forces(mesh, t, q, v, &mut f[1..=nd]);
        let g = &f[1..=nd];
        f[0] = (0..self.n())
            .map(|i| mesh.tan[i][0] * g[NODE_DOFS * i] + mesh.tan[i][1] * g[NODE_DOFS * i + 1])
            .sum();
        for (p, k) in self.coords.free_pulleys() {
            f[k] = torque[p];
        }
        for i in self.coords.decoupler_extra_dofs() {
            f[i] = 0.0;
        }
        if let Some(k) = self.coords.arm_dof() {
            f[k] = moment;
        }
        self.coords.add_forces(t, q, v, f);
        if let Some(i) = f.iter().position(|x| !x.is_finite()) {
            return Err(MbdError::NonFinite {
                what: format!("nodal belt generalized force {i}"),
                t,
            });
        }
        Ok(())
    }

    /// `(K_t, C_t) = (−∂f/∂q, −∂f/∂v)` as sparse matrices with a pattern independent of the
    /// state (element blocks, every node's contact block, the full rows and columns of `s_b`
    /// and `φ₂`), so the integrator's symbolic LU is reused: analytic in `δ`, `δ̇`, `v`, `ω₂`;
    /// the `s_b` column by a forward difference (it carries the rebuilt element frames).
    fn tangent(&self, t: f64, q: &[f64], v: &[f64]) -> Result<(Sparse, Sparse), MbdError> {
        let n = self.n();
        let nd = self.n_nodal();
        let nv = self.n_v;
        let free = self.coords.free_pulleys();
        let arm = self.coords.arm_state(q, v);
        let mesh = self.mesh(q[0])?;
        let vb = v[0];
        let (alpha, beta) = (self.fe.drive.damping().alpha, self.fe.drive.damping().beta);
        let mut kq = Tangent::new(nv, &mesh.tan);
        let mut cv = Tangent::new(nv, &mesh.tan);
        let d = &q[1..=nd];
        for e in 0..n {
            let dofs = self.element_dofs(e);
            for a in 0..6 {
                let mut kjd = 0.0;
                for b in 0..6 {
                    let kj = mesh.kj[e][a][b];
                    kq.add(1 + dofs[a], 1 + dofs[b], mesh.k[e][a][b] - beta * vb * kj);
                    cv.add(1 + dofs[a], 1 + dofs[b], beta * mesh.ke[e][a][b]);
                    kjd += kj * d[dofs[b]];
                }
                cv.add(1 + dofs[a], 0, -beta * kjd);
            }
        }
        if self.exact_axial {
            let law = super::model::BarLaw::of(&self.fe.drive);
            for bar in super::model::Bar::loop_of(&mesh.pos) {
                let (_, gm) = bar.correction(d, &law, true);
                let (ri, rj) = (1 + NODE_DOFS * bar.i, 1 + NODE_DOFS * bar.j);
                for a in 0..2 {
                    for c in 0..2 {
                        kq.add(rj + a, rj + c, gm[a][c]);
                        kq.add(rj + a, ri + c, -gm[a][c]);
                        kq.add(ri + a, rj + c, -gm[a][c]);
                        kq.add(ri + a, ri + c, gm[a][c]);
                    }
                }
            }
        }
        for i in 0..nd {
            cv.add(1 + i, 1 + i, alpha * self.fe.mass[i]);
        }
        for i in 0..n {
            let c = 2.0 * vb * self.fe.mass[NODE_DOFS * i];
            for a in 0..2 {
                cv.add(1 + NODE_DOFS * i + a, 0, c * mesh.eps_n[i][a]);
            }
        }
        let mut touching = vec![vec![None::<NodeContact>; self.pulleys.len()]; n];
        for (i, p, c) in self.contacts(&mesh, t, q, v) {
            touching[i][p] = Some(c);
        }
        // every node's contact entries with every pulley, zero when open (fixed pattern)
        for (i, pair) in touching.iter().enumerate() {
            let r = 1 + NODE_DOFS * i;
            let et = mesh.tan[i];
            let mut dd = [[0.0; 2]; 2];
            let mut dv = [[0.0; 2]; 2];
            for c in pair.iter().flatten() {
                for a in 0..2 {
                    for b in 0..2 {
                        dd[a][b] += c.df_dd[a][b];
                        dv[a][b] += c.df_dv[a][b];
                    }
                }
            }
            let of = |p: usize| pair[p].unwrap_or_default();
            for a in 0..2 {
                for b in 0..2 {
                    kq.add(r + a, r + b, -dd[a][b]);
                    cv.add(r + a, r + b, -dv[a][b]);
                }
                cv.add(r + a, 0, -(dv[a][0] * et[0] + dv[a][1] * et[1]));
                for &(p, ip) in &free {
                    let c = of(p);
                    cv.add(r + a, ip, -c.df_dw[a]);
                    kq.add(ip, r + a, -c.dt_dd[a]);
                    cv.add(ip, r + a, -c.dt_dv[a]);
                }
            }
            for &(p, ip) in &free {
                let c = of(p);
                cv.add(ip, 0, -(c.dt_dv[0] * et[0] + c.dt_dv[1] * et[1]));
                cv.add(ip, ip, -c.dt_dw);
            }
            if let (Some(arm), Some(ia), Some(pi)) =
                (&arm, self.coords.arm_dof(), self.coords.idler())
            {
                self.add_arm_entries(&mut kq, &mut cv, arm, ia, pi, r, et, &of(pi));
            }
        }
        self.coords.add_tangent(
            t,
            q,
            v,
            |i, j, x| kq.add(i, j, x),
            |i, j, x| cv.add(i, j, x),
        );
        // s_b column: forward difference of the forces (rows 1.. here; row 0 below)
        let eps = 1e-7;
        let mut f0 = vec![0.0; nv];
        let mut f1 = vec![0.0; nv];
        self.forces_on(&mesh, t, q, v, &mut f0)?;
        let mut qp = q.to_vec();
        qp[0] += eps;
        let mesh1 = self.mesh(qp[0])?;
        self.forces_on(&mesh1, t, &qp, v, &mut f1)?;
        for i in 1..nv {
            kq.add(i, 0, -(f1[i] - f0[i]) / eps);
        }
        let k00 = -(f1[0] - f0[0]) / eps;
        Ok((kq.finish(k00)?, cv.finish_row0()?))
    }

    /// Tangent entries of one node's contact `c` with the tensioner's idler `pi` (zero when
    /// open: fixed pattern): the node rows and the idler's spin row in the arm's columns
    /// ([`ArmState::contact_derivatives`]), and the arm's row `M = −(c − p) × F` in the node,
    /// travel, idler-spin and arm columns (the lever turns with the arm: `∂(c − p)/∂θ = c'`).
    #[allow(clippy::too_many_arguments)]
    fn add_arm_entries(
        &self, kq: &mut Tangent<'_>, cv: &mut Tangent<'_>, arm: &ArmState, ia: usize, pi: usize,
        r: usize, et: [f64; 2], c: &NodeContact,
    ) {
        let ((f_q, t_q), (f_v, t_v)) = arm.contact_derivatives(c);
        let lever = |f: [f64; 2]| -arm.moment(f);
        for a in 0..2 {
            kq.add(r + a, ia, -f_q[a]);
            cv.add(r + a, ia, -f_v[a]);
            let (dd, dv) = (
                [c.df_dd[0][a], c.df_dd[1][a]],
                [c.df_dv[0][a], c.df_dv[1][a]],
            );
            kq.add(ia, r + a, lever(dd));
            cv.add(ia, r + a, lever(dv));
        }
        let dv_s = [
            c.df_dv[0][0] * et[0] + c.df_dv[0][1] * et[1],
            c.df_dv[1][0] * et[0] + c.df_dv[1][1] * et[1],
        ];
        cv.add(ia, 0, lever(dv_s));
        if let Some(ip) = self.coords.pulley_dof(pi) {
            kq.add(ip, ia, -t_q);
            cv.add(ip, ia, -t_v);
            cv.add(ia, ip, lever(c.df_dw));
        }
        kq.add(ia, ia, lever(f_q) + cross(arm.dc, c.force));
        cv.add(ia, ia, lever(f_v));
    }

    /// Static equilibrium of the mounted belt on the resting pulleys (`v = 0`, `s_b = 0`) under
    /// the reference condition: the nodal deflections `δ` (`3N`) of [`Self::static_state`].
    pub fn static_equilibrium(&self) -> Result<Vec<f64>, MbdError> {
        let nd = self.n_nodal();
        Ok(self.static_state()?[1..=nd].to_vec())
    }

    /// Static equilibrium of the mounted belt on the resting pulleys (`v = 0`, `s_b = 0`, every
    /// pulley at rest) and of the tensioner arm, under the reference condition: Newton on
    /// `[K_t Dᵀ; D 0]` over the nodal rows and the arm's row (the shared [`mbd_core::newton`]
    /// solver). Returns `q` (travel and pulley angles zero).
    pub fn static_state(&self) -> Result<Vec<f64>, MbdError> {
        let nv = self.n_v;
        let still = Self {
            coords: self.coords.at_rest(),
            ..self.clone()
        };
        let mut q = vec![0.0; nv];
        let v = vec![0.0; nv];
        let mut f = vec![0.0; nv];
        let k = NODE_DOFS * self.reference_node;
        // unknowns: δ and the arm rotation; R = [−f; Φ] over their rows and the reference
        // condition, J = [K_t eᵀ; e 0] (the multiplier is solved for directly); the residual
        // test from the second iteration
        let mut idx: Vec<usize> = (1..=self.n_nodal()).collect();
        idx.extend(self.coords.arm_dof());
        let nx = idx.len();
        let x = dense_equilibrium("nodal belt", nx, nx + 1, 2, |x, r| {
            for (a, &i) in idx.iter().enumerate() {
                q[i] = x[a];
            }
            let mesh = still.mesh(0.0)?;
            still.forces_on(&mesh, 0.0, &q, &v, &mut f)?;
            let kt = still.tangent(0.0, &q, &v)?.0.to_dense();
            let et = mesh.tan[self.reference_node];
            for (a, &i) in idx.iter().enumerate() {
                r[a] = -f[i];
            }
            r[nx] = et[0] * q[1 + k] + et[1] * q[2 + k];
            // the reference condition's row and column: e_t on node k's (x, y) deflections
            let e = |a: usize| match a.checked_sub(k) {
                Some(0) => et[0],
                Some(1) => et[1],
                _ => 0.0,
            };
            Ok(Mat::from_fn(nx + 1, nx + 1, |a, b| {
                match (a < nx, b < nx) {
                    (true, true) => kt[(idx[a], idx[b])],
                    (true, false) => e(a),
                    (false, true) => e(b),
                    (false, false) => 0.0,
                }
            }))
        })?;
        let mut out = vec![0.0; nv];
        for (a, &i) in idx.iter().enumerate() {
            out[i] = x[a];
        }
        Ok(out)
    }
}

impl SecondOrderSystem for NodalBelt {
    fn n_q(&self) -> usize {
        self.n_v
    }

    fn n_c(&self) -> usize {
        1
    }

    fn constraint_name(&self, _row: usize) -> String {
        format!(
            "reference condition (tangential deflection of node {})",
            self.reference_node
        )
    }

    fn dof_name(&self, dof: usize) -> String {
        let nd = self.n_nodal();
        match dof {
            0 => "belt travel s_b".into(),
            d if d > nd => self
                .coords
                .dof_name(d)
                .unwrap_or_else(|| format!("coordinate {d}")),
            d => format!(
                "node {} {}",
                (d - 1) / NODE_DOFS,
                ["x", "y", "θ"][(d - 1) % NODE_DOFS]
            ),
        }
    }

    /// Sparse: `[[m, (M e_t)ᵀ, 0], [M e_t, M, 0], [0, 0, diag J_k]]` (Ribaric (5.6)).
    fn mass(&self, _t: f64, q: &[f64]) -> Result<SysMatrix, MbdError> {
        let nd = self.n_nodal();
        let nv = self.n_v;
        let mut trip = Vec::with_capacity(3 * nv);
        trip.push(Triplet::new(0, 0, self.mass_total));
        for i in 0..self.n() {
            let tan = self.fe.path().point(self.fe.s[i] + q[0]).tangent;
            for a in 0..2 {
                let r = 1 + NODE_DOFS * i + a;
                let m = self.fe.mass[NODE_DOFS * i + a] * tan[a];
                trip.push(Triplet::new(r, 0, m));
                trip.push(Triplet::new(0, r, m));
            }
        }
        for i in 0..nd {
            trip.push(Triplet::new(1 + i, 1 + i, self.fe.mass[i]));
        }
        for (k, j) in self.coords.inertias() {
            trip.push(Triplet::new(k, k, j));
        }
        SparseColMat::try_new_from_triplets(nv, nv, &trip)
            .map(SysMatrix::Sparse)
            .map_err(|e| MbdError::Model {
                t: 0.0,
                message: format!("nodal belt mass assembly: {e:?}"),
            })
    }

    fn forces(
        &self, t: f64, q: &[f64], v: &[f64], f: &mut [f64], _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        let mesh = self.mesh(q[0])?;
        self.forces_on(&mesh, t, q, v, f)
    }

    fn force_tangent(
        &self, t: f64, q: &[f64], v: &[f64], _ws: &mut Workspace,
    ) -> Result<Option<ForceTangent>, MbdError> {
        let (k, c) = self.tangent(t, q, v)?;
        Ok(Some(ForceTangent {
            stiffness: SysMatrix::Sparse(k),
            damping: SysMatrix::Sparse(c),
        }))
    }

    /// The transition-aware limit of the node–pulley friction ([`correction_limit`], Castro
    /// et al. 2019) over the pairs in contact at the iterate: each pair's slip velocity at the
    /// iterate and at the corrected state `(q + dq, v + dv)`, exact at both (the material node
    /// moves to `s_i0 + s_b + Δs_b` along the path, its tangent and the contact normal turn
    /// with it), linear in `α` between them.
    fn correction_limit(
        &self, t: f64, q: &[f64], v: &[f64], dq: &[f64], dv: &[f64], _ws: &mut Workspace,
    ) -> Result<f64, MbdError> {
        if self.friction.iter().all(|f| f.transition_width().is_none()) {
            return Ok(1.0);
        }
        let mut q1 = vec![0.0; q.len()];
        self.integrate_position(q, dq, &mut q1);
        let v1: Vec<f64> = v.iter().zip(dv).map(|(a, b)| a + b).collect();
        let (arm, arm1) = (self.coords.arm_state(q, v), self.coords.arm_state(&q1, &v1));
        let path = self.fe.path();
        let mut pairs = Vec::new();
        for (i, &s) in self.fe.s.iter().enumerate() {
            let mut next = None;
            let here = path.point(s + q[0]);
            for p in 0..self.pulleys.len() {
                let now =
                    self.node_motion(i, p, here.position, here.tangent, arm.as_ref(), t, q, v);
                if now.penetration_and_slip().0 <= 0.0 {
                    continue;
                }
                let there = *next.get_or_insert_with(|| path.point(s + q1[0]));
                let after = self.node_motion(
                    i,
                    p,
                    there.position,
                    there.tangent,
                    arm1.as_ref(),
                    t,
                    &q1,
                    &v1,
                );
                pairs.push((now, after, &self.friction[p]));
            }
        }
        Ok(correction_limit(pairs))
    }

    fn constraint_residual(&self, _t: f64, q: &[f64], phi: &mut [f64]) -> Result<(), MbdError> {
        let k = self.reference_node;
        let p = self.fe.path().point(self.fe.s[k] + q[0]);
        let d = &q[1 + NODE_DOFS * k..];
        phi[0] = p.tangent[0] * d[0] + p.tangent[1] * d[1];
        Ok(())
    }

    /// `D = [κ e_nᵀ δ^k, e_tᵀ (node k), 0]` (`∂e_t/∂s = κ e_n`).
    fn constraint_jacobian(&self, _t: f64, q: &[f64]) -> Result<SysMatrix, MbdError> {
        let k = self.reference_node;
        let p = self.fe.path().point(self.fe.s[k] + q[0]);
        let d = &q[1 + NODE_DOFS * k..];
        let trip = [
            Triplet::new(
                0,
                0,
                p.curvature * (p.normal[0] * d[0] + p.normal[1] * d[1]),
            ),
            Triplet::new(0, 1 + NODE_DOFS * k, p.tangent[0]),
            Triplet::new(0, 2 + NODE_DOFS * k, p.tangent[1]),
        ];
        SparseColMat::try_new_from_triplets(1, self.n_q(), &trip)
            .map(SysMatrix::Sparse)
            .map_err(|e| MbdError::Model {
                t: 0.0,
                message: format!("nodal belt constraint Jacobian: {e:?}"),
            })
    }

    /// `γ = v² κ² e_tᵀ δ^k − 2 v κ e_nᵀ δ̇^k` (`∂e_n/∂s = −κ e_t`).
    fn constraint_gamma(
        &self, _t: f64, q: &[f64], v: &[f64], gamma: &mut [f64],
    ) -> Result<(), MbdError> {
        let k = self.reference_node;
        let p = self.fe.path().point(self.fe.s[k] + q[0]);
        let (d, dd, vb) = (&q[1 + NODE_DOFS * k..], &v[1 + NODE_DOFS * k..], v[0]);
        let kap = p.curvature;
        gamma[0] = vb * vb * kap * kap * (p.tangent[0] * d[0] + p.tangent[1] * d[1])
            - 2.0 * vb * kap * (p.normal[0] * dd[0] + p.normal[1] * dd[1]);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::belt::{AxialForce, BeltReduction, FlowingBelt, FlowingSettings, table_6_1};
    use mbd_core::central_difference_column;

    fn belt() -> NodalBelt {
        NodalBelt::new(&table_6_1(60.0, 3.0), &BeltMesh::default()).unwrap()
    }

    // Reference: the steady flow in closed form. The undeformed belt travelling at v (any s_b)
    // carries ρ v² along the path's tangent through a fixed section at every material node,
    // with ρ the belt's mass per length up to the lumped mass of the chord polygon over the arc
    // length, 1 − (l/R)²/24 = 1 − 1.3e-3 on the 8.7 mm wrap elements of 50 mm pulleys.
    #[test]
    fn momentum_flux_of_a_rigid_flow_is_rho_v_squared_along_the_path() {
        let b = belt();
        let (n, speed, sb) = (b.n_q(), 12.0, 0.0137);
        let mut q = vec![0.0; n];
        q[0] = sb;
        let mut v = vec![0.0; n];
        v[0] = speed;
        let rho = b.fe.drive.belt().mass_per_length;
        let scale = rho * speed * speed;
        for (i, phi) in b.momentum_flux(&q, &v).iter().enumerate() {
            let t = b.fe.path().point(b.fe.s[i] + sb).tangent;
            let along = phi[0] * t[0] + phi[1] * t[1];
            let across = -phi[0] * t[1] + phi[1] * t[0];
            assert!(
                (along / scale - 1.0).abs() < 1.5e-3,
                "node {i}: {along} of {scale}"
            );
            assert!(across.abs() < 1e-12 * scale, "node {i}: {across}");
        }
    }

    // At s_b = 0 the rebuilt element matrices reproduce BeltFe's assembled K (fe-model's global
    // Frame2d matrices: a second assembly of the same data).
    #[test]
    fn rebuilt_stiffness_matches_the_assembled_loop_at_rest() {
        let b = belt();
        let mesh = b.mesh(0.0).unwrap();
        let nd = b.n_nodal();
        let mut k = Mat::<f64>::zeros(nd, nd);
        for e in 0..b.n() {
            let dofs = b.element_dofs(e);
            for a in 0..6 {
                for c in 0..6 {
                    k[(dofs[a], dofs[c])] += mesh.k[e][a][c];
                }
            }
        }
        let scale = b.fe.stiffness.norm_max();
        let err = (&k - &b.fe.stiffness).norm_max();
        assert!(err < 1e-12 * scale, "{err} vs {scale}");
        for i in 0..nd {
            assert!((mesh.f0[i] - b.fe.pretension[i]).abs() < 1e-9);
        }
    }

    // Analytic tangent against central differences of the forces (second evaluation of the
    // same model) at a deflected, moving, sliding state with nodes in contact.
    #[test]
    fn tangent_matches_finite_differences() {
        check_tangent(belt().with_axial_force(AxialForce::Linear));
    }

    // The same with the co-rotated axial force (issue 34, model::Bar).
    #[test]
    fn tangent_with_co_rotated_axial_force_matches_finite_differences() {
        check_tangent(belt().with_axial_force(AxialForce::CoRotated));
    }

    /// A deflected, moving state of `b`: material coordinate `s0` \[m\], belt speed 3 m/s, a
    /// small smooth deflection and deflection rate at every node.
    fn moving_state(b: &NodalBelt, s0: f64) -> (Vec<f64>, Vec<f64>) {
        let nv = b.n_q();
        let mut q = vec![0.0; nv];
        let mut v = vec![0.0; nv];
        q[0] = s0;
        v[0] = 3.0;
        for i in 1..=b.n_nodal() {
            q[i] = 2e-5 * ((i as f64) * 0.7).sin();
            v[i] = 1e-2 * ((i as f64) * 1.3).cos();
        }
        (q, v)
    }

    fn check_tangent(b: NodalBelt) {
        let nv = b.n_q();
        let (q, mut v) = moving_state(&b, 0.0123);
        v[nv - 1] = 59.0;
        let (kt, ct) = b.tangent(0.5, &q, &v).unwrap();
        let (kt, ct) = (kt.to_dense(), ct.to_dense());
        let mut worst: f64 = 0.0;
        for j in 1..nv {
            let fd = central_difference_column(&b, (0.5, &q, &v), j, 1e-9, true).unwrap();
            for (i, fd) in fd.into_iter().enumerate() {
                worst = worst.max((fd - kt[(i, j)]).abs() / kt.norm_max());
            }
        }
        for j in 0..nv {
            let fd = central_difference_column(&b, (0.5, &q, &v), j, 1e-7, false).unwrap();
            for (i, fd) in fd.into_iter().enumerate() {
                assert!(
                    (fd - ct[(i, j)]).abs() < 1e-6 * ct.norm_max().max(1.0),
                    "C[{i},{j}]: {fd} vs {}",
                    ct[(i, j)]
                );
            }
        }
        assert!(worst < 1e-6, "K error {worst}");
    }

    // Frame invariance of the β damping (BeltFe::frame_turn) in the rotating mesh: at s_b = 0,
    // a rigid rotation of the belt about any point, carried by the moving material nodes
    // (δ̇ = v φ J t_i), has no strain rate: the β part of the nodal forces (the difference of
    // the models with and without β at the same state) vanishes.
    #[test]
    fn damping_of_a_carried_rigid_rotation_vanishes() {
        let b = belt();
        let mut layout = b.fe.drive.layout().clone();
        layout.damping.beta = 0.0;
        let b0 = NodalBelt::new(&layout.resolve().unwrap(), &BeltMesh::default()).unwrap();
        let nv = b.n_q();
        let v_belt = 3.0;
        for c in [[0.0, 0.0], [0.45, 0.0], [0.17, -0.3]] {
            let (delta, rate) =
                crate::belt::model::tests::rigid_rotation(&b.fe.position, &b.fe.tangent, c, 1e-3);
            let mut q = vec![0.0; nv];
            let mut v = vec![0.0; nv];
            q[1..=b.n_nodal()].copy_from_slice(&delta);
            v[0] = v_belt;
            for (x, r) in v[1..=b.n_nodal()].iter_mut().zip(&rate) {
                *x = v_belt * r;
            }
            v[nv - 1] = 59.0;
            let (mut f, mut f0) = (vec![0.0; nv], vec![0.0; nv]);
            b.forces(0.5, &q, &v, &mut f, &mut mbd_core::Workspace::new())
                .unwrap();
            b0.forces(0.5, &q, &v, &mut f0, &mut mbd_core::Workspace::new())
                .unwrap();
            let diff = f
                .iter()
                .zip(&f0)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
            // β EA v φ / R ≈ 16 N is the scale of the global-component form's error
            assert!(diff < 1e-8, "β forces of a rigid rotation: {diff} N");
        }
    }

    // Any layout with a tensioner (four pulleys, a back-side idler on the arm): the analytic
    // tangent (pulley spins, moving idler, arm moment, spring, damper, dry friction) against
    // central differences of the forces (an independent evaluation of the same equations), at
    // a moving, deflected state with the arm turned and turning.
    #[test]
    fn layout_tangent_with_tensioner_matches_finite_differences() {
        let fl = crate::belt::flowing_system::tests::layout_belt(AxialForce::CoRotated);
        let b = NodalBelt::on(
            fl.fe.clone(),
            fl.coords.motions.clone(),
            fl.coords.tensioner,
        )
        .unwrap();
        let ka = b.coords.arm_dof().unwrap();
        let (mut q, mut v) = moving_state(&b, 0.0071);
        for p in 1..4 {
            v[b.coords.pulley_dof(p).unwrap()] = 3.0 / [0.06, 0.05, 0.035, 0.04][p] * 0.99;
        }
        q[ka] = 2e-3;
        v[ka] = 0.03;
        // the idler touches the belt at this state
        let touching = b
            .contact_report(0.1, &q, &v)
            .unwrap()
            .iter()
            .filter(|c| c.1 == 2)
            .count();
        assert!(touching > 2, "{touching} idler contacts");
        let (kt, ct) = b.tangent(0.1, &q, &v).unwrap();
        let (kt, ct) = (kt.to_dense(), ct.to_dense());
        let scale = kt.norm_max().max(ct.norm_max());
        let mut cols: Vec<(usize, f64)> = vec![(ka, 1e-7), (b.coords.pulley_dof(2).unwrap(), 1e-6)];
        // the nodes of the idler's wrap
        for (i, p, _, _) in b.contact_report(0.1, &q, &v).unwrap() {
            if p == 2 {
                cols.push((1 + NODE_DOFS * i, 1e-9));
                cols.push((2 + NODE_DOFS * i, 1e-9));
            }
        }
        for (j, h) in cols {
            for in_q in [true, false] {
                let fd = central_difference_column(&b, (0.1, &q, &v), j, h, in_q).unwrap();
                for (i, fd) in fd.into_iter().enumerate() {
                    let an = if in_q { kt[(i, j)] } else { ct[(i, j)] };
                    let err = (fd - an).abs() / fd.abs().max(1e-4 * scale);
                    assert!(err < 1e-4, "row {i} col {j} q={in_q}: fd {fd} vs {an}");
                }
            }
        }
    }

    // At rest the nodal and the untruncated flowing models describe the same structure on the
    // same nodes: equal static deflections (second formulation).
    #[test]
    fn static_equilibrium_matches_the_untruncated_flowing_model() {
        let drive = table_6_1(0.0, 0.0);
        let settings = FlowingSettings {
            reduction: BeltReduction { free_modes: None },
            ..Default::default()
        };
        let fl = FlowingBelt::new(&drive, &settings).unwrap();
        let z = fl.static_equilibrium().unwrap();
        let d_flow = fl.deflection(&z);
        let nb = NodalBelt::new(&drive, &settings.mesh)
            .unwrap()
            .with_axial_force(settings.axial_force);
        let d = nb.static_equilibrium().unwrap();
        let scale = d_flow.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let err = d
            .iter()
            .zip(&d_flow)
            .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        assert!(
            scale > 1e-9 && err < 1e-6 * scale.max(1e-6),
            "{err} vs {scale}"
        );
    }

    // Reference: the closed-form slip change of a pulley-speed correction
    // (crate::belt::check_pulley_speed_limit).
    #[test]
    fn correction_limit_stops_the_driven_wrap_inside_the_band() {
        let drive = crate::belt::table_6_1_sharp(60.0);
        let b = NodalBelt::new(&drive, &BeltMesh::default()).unwrap();
        let q = b.static_state().unwrap();
        let (_, dof) = b.coords.free_pulleys()[0];
        let radius = b.pulleys[1].radius;
        crate::belt::check_pulley_speed_limit(&b, &q, dof, radius, |v| {
            b.contact_report(0.0, &q, v)
                .unwrap()
                .iter()
                .map(|&(_, p, _, c)| (p, c.penetration, c.slip))
                .collect()
        });
    }
}
