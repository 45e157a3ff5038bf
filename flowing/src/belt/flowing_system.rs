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
//!   material velocity   V = v b + T ż,   b = e_t + T_,s z
//!   material accel.     d̈ = a b + T z̈ + v² ε_n + c,   c = v² T_,ss z + 2 v T_,s ż
//! ```
//!
//! Ribaric's equations (5.14), the default: the nodal balance `M d̈ = g`,
//! `g = f0 + f_contact − K δ − C δ̇_m`, projected on `P = [e_t | T]`:
//!
//! ```text
//!   [ e_tᵀ M b   e_tᵀ M T ] [a ]   [ e_tᵀ (g − M (v² ε_n + c)) ]
//!   [ Tᵀ M b     Tᵀ M T   ] [z̈] = [ Tᵀ  (g − M (v² ε_n + c)) ]
//!   J_k ω̇_k = τ_contact,k − M_load,k(t)                (free pulleys)
//!   J_a Δθ̈  = (c − p) × F_hub + M_s + M_d + M_f          (tensioner arm)
//! ```
//!
//! Lagrange's equations ([`FlowingBelt::with_lagrange_equations`], issue 34): the material
//! point with label `X` is at `x = r(s) + T(s) z`, `s = X + s_b`, so `(s_b, z)` are
//! generalized coordinates of the material (`∂x/∂s_b = b`, `∂x/∂z = T`). With the kinetic
//! energy `𝒯 = ½ Vᵀ M V` (lumped `M` at the nodes of the stationary mesh, which the material
//! fills around the closed loop), the elastic energy `U = ½ δᵀ K δ − f0ᵀ δ` (independent of
//! `s_b`), the Rayleigh dissipation function `R = ½ Σ_e w_eᵀ β K_e,e w_e + ½ α (T ż)ᵀ M T ż` of
//! the co-rotated material rate `w_e = T ż + v (T_,s − ψ'_e J) T z` ([`super::BeltFe::frame_turn`],
//! [`super::BeltFe::frame_turn2`]) and the contact forces `F` (generalized forces `bᵀ F`,
//! `Tᵀ F`), the belt rows are
//!
//! ```text
//!   [ bᵀ M b   bᵀ M T ] [a ]   [ bᵀF − ∂R/∂v − 2v bᵀM T_,s ż − żᵀ T_,sᵀ M T ż                  ]
//!   [ Tᵀ M b   Tᵀ M T ] [z̈] = [ TᵀF − ∂U/∂z − ∂R/∂ż + v (T_,sᵀ M T − Tᵀ M T_,s) ż + v² T_,sᵀ M b ]
//! ```
//!
//! and the mechanical energy `E = ½ Vᵀ M V + U` obeys `dE/dt = Vᵀ F − 2R` exactly for any
//! basis, mesh and derivative operator (Jacobi's integral of the autonomous Lagrangian; the
//! `z` rows are those of (5.14) up to the inertia terms, which agree when `M T_,s` is skew,
//! `T_,ss = T_,s T_,s` and `ε_n = D e_t` with `D` the derivative operator of `T_,s`).
//!
//! Why (5.14) is not energy-consistent (issue 34 item 2): the continuous loop conserves energy
//! in both forms, (5.14) through the relabelling invariance of the elastic and viscous forces,
//! `bᵀ (f0 − K δ) = 0` and `bᵀ g_d = −∂R/∂v`. The discrete linear forces keep neither: the
//! `e_t` row's elastic and damping forces do work `v bᵀ g` on the material's slide. Measured on
//! the default fead drive at 800 rpm (window means): the elastic forces put `+32.7 W` into the
//! belt through their linear part `v (f0ᵀ T_,s z − e_tᵀ K δ)` (19 W of it on the alternator's
//! 12 mm wrap elements of 28 mm radius; it falls as the wraps are refined) and `−5.6 W` through
//! their second-order part `−v δᵀ T_,sᵀ K δ`; the inertia terms `−0.07 W`; the damping forces
//! do `+10.8 W` on the material where `2R`, their Kelvin–Voigt dissipation, is 29.8 W (the
//! viscous axial force acts along the mesh's chord, not the deformed one, so its virtual work
//! on the slide misses `Σ_e N_v ψ'_e (J u_e)·Δδ`). Lagrange's equations move that defect from
//! the energy to the one direction the basis leaves to `s_b`, the tangential balance of the
//! reference node 0 on the driver: on the same drive their power residual is 0.65 % (0.36 % on
//! 8.7 mm wraps, 0.04 % on 4 mm wraps) and the crank torque 19.08 N m against the nodal model's
//! 19.00 N m (18.29 N m with (5.14)), but the crank's torque residual against its spans is
//! 4.8 % (0.92 N m against 0.13 N m with (5.14)): the window mean of the defect on the slide,
//! `bᵀ (f0 − K δ) = 4.2 N` and `bᵀ g_d + ∂R/∂v = 6.5 N`, times the crank's 75 mm is the
//! 0.80 N m added (with (5.14) the same 4.3 N and 6.5 N times `v` = 6.28 m/s are the 27 W and
//! 41 W above), and on Table 6-1 at 10 N m
//! 0.76 % (power 0.03 %, Δω 0.18667 rad/s against 0.18630). So (5.14) stays the default; the
//! open fix is elastic and viscous forces that are invariant under the relabelling (both along
//! the deformed chord, and a derivative operator exact on the wraps).
//!
//! Relabelling-invariant damping (issue 34, h-bal4): [`super::ViscousForce::Chord`] carries the
//! axial Kelvin–Voigt force along the deformed chord on the material rate of its length, taken
//! on the chords' stretches ([`FlowingBelt`]'s `chord_viscous`); with Lagrange's equations
//! ([`super::BeltEquations::Lagrange`]) its slide defect is zero by construction (it is
//! `−∂R/∂(v, ż)` of its own Rayleigh function) and the belt loses exactly `2R`. What is left
//! on the default fead drive is elastic, and it is not a discretisation error: the window means
//! of `bᵀ(f0 − K δ)` at 800 rpm are −24.2 N (pre-tension) + 25.6 N (string part of `K_g(T0)`)
//! − 0.4 N (axial) + 4.0 N (bending and the beam part of `K_g`); on 4 mm wraps −24.4, +24.5,
//! +1.6, +4.4 N. The bending part stays because the frame elements of Ribaric (5.5) are
//! stress-free on the mounted polygon: the belt's natural curvature is the path's, which jumps
//! by `1/R` at every tangent point, and `½ ∫ EI (κ − κ₀(s))² ds` is not invariant under the
//! material's slide (its slide force is `Σ EI (κ − κ₀) Δκ₀` at the tangent points; `EI/R²` is
//! 33 N on the drive's 28 mm pulleys, 0.13 N on the Pechstein–Gerstmayr drive). With EI/100 the
//! default formulation closes both balances on that drive (0.31 % / −0.27 %), Lagrange's
//! equations still miss (4.13 % / 0.83 %; with the chord damping 1.59 % / 0.92 %): the other
//! slide defects remain. A naturally
//! straight belt (the pre-moment `EI κ₀` of the mounted state added to `f0`, tried without its
//! geometric stiffness) removes the bending part (0.46 N) but its lift-off at the tangent points
//! is then carried by the linear axial force (its slide defect rises to 11–12 N): a co-rotated
//! bending element is the open step.
//!
//! Choices (documented per the seed-000 note): the unknown vector is `[a; z̈]` (erratum E13);
//! with penalty contact the λ rows of (5.14) vanish (so E12 does not arise); the `z` rows are
//! taken with the whole basis `T` (Galerkin) instead of (5.14)'s mixed projection (`Ψ^fᵀ` on
//! free rows, nodal contact rows), both coinciding when all modes are kept (T square); the
//! damping `β K_e` acts on the co-rotated material deflection rate
//! `δ̇_m − v ψ' J δ` with `δ̇_m = T ż + v T_,s z` (note U10: the viscoelastic strain rate
//! follows the material; the `− v ψ' J δ` term removes the turning of the element frames the
//! material passes through, [`super::BeltFe::frame_turn`] — Ribaric (5.5)'s `C δ̇` on global
//! components is not frame-invariant) and `α M` on the Eulerian rate `T ż` (no drag in the
//! steady state; the same choice as the tire model).
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
//! ([`FlowingBelt::element_forces`]); the power these damping forces take from the belt is
//! [`FlowingBelt::damping_dissipation`].

use super::config::{
    AxialForce, BeltEquations, BendingForce, ContactVelocity, FlowingSettings, ViscousForce,
};
use super::contact::{NodeContact, NodeMotion, PulleyFrame, correction_limit, node_contact};
use super::coordinates::{ArmState, DriveCoordinates};
use super::model::{BeltFe, BendElement, FlowingBasis, NODE_DOFS, chord_tensions};
use super::statics::dense_equilibrium;
use belt::tensioner::cross;
use belt::{Arm, Drive, Motion};
use contact::friction::{FrictionLaw, FrictionSpec};
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
    /// Lagrange's equations (`true`) or Ribaric's projection (5.14) (`false`, the default):
    /// module documentation, [`Self::with_lagrange_equations`].
    lagrange: bool,
    /// Ribaric (5.14): `Pᵀ M [e_t | T]`, `Pᵀ K T`, `Pᵀ C T`, `Pᵀ β (K_e T_,s − frame_turn T)`,
    /// `Pᵀ M T_,ss`, `Pᵀ M ε_n`, `Pᵀ f0`.
    a_mass: Mat<f64>,
    a_k: Mat<f64>,
    a_c: Mat<f64>,
    a_cs: Mat<f64>,
    a_mss: Mat<f64>,
    p_en: Vec<f64>,
    p_f0: Vec<f64>,
    /// `e_tᵀ M e_t` \[kg\].
    mee: f64,
    /// `Tᵀ M e_t` (`m`).
    mte: Vec<f64>,
    /// `Tᵀ M T` (`m × m`).
    mtt: Mat<f64>,
    /// `Pᵀ M T_,s` (`(m + 1) × m`, `P = [e_t | T]`): row 0 `e_tᵀ M T_,s`, then `Tᵀ M T_,s`.
    mts: Mat<f64>,
    /// `T_,sᵀ M T_,s` (`m × m`).
    mss: Mat<f64>,
    /// `T_,sᵀ M e_t` (`m`).
    mse: Vec<f64>,
    /// `Tᵀ K T` (`m × m`), `K = K_e + K_g(T0)`.
    kz: Mat<f64>,
    /// `Tᵀ f0` (`m`).
    f0z: Vec<f64>,
    /// Rayleigh dissipation `R = ½ żᵀ C_t ż + v żᵀ C_g z + ½ v² zᵀ C_h z`: `C_t` (`m × m`).
    ct: Mat<f64>,
    /// `C_g` of the dissipation function (`m × m`).
    cg: Mat<f64>,
    /// `C_h` of the dissipation function (`m × m`, symmetric).
    ch: Mat<f64>,
    rows: Vec<ContactRow>,
    n_v: usize,
    /// The elements' chords for the co-rotated axial force ([`Self::exact_axial`]).
    bars: Vec<super::model::Bar>,
    /// `D̃ = [Δe_t | ΔT]` (`2 n_bars × (m + 1)`): per bar and direction, the difference of the
    /// stacked tangent `e_t` and of the basis rows `T` between its end nodes, so that the
    /// co-rotated corrections `c` enter the forces as `D̃ᵀ c` and the tangent as `D̃ᵀ G ΔT`.
    bar_dx: Mat<f64>,
    /// `D̃ᵀ` (`(m + 1) × 2 n_bars`): a bar's rows of [`Self::bar_dx`] as contiguous columns.
    bar_dxt: Mat<f64>,
    /// Apply each element's axial force `N = F(λ₀ l/l₀)` of the material law ([`super::model::BarLaw`]) along its deformed chord
    /// (issue 34): the linear model (`f0 − (K_e + K_g(T0)) δ`) keeps the increment
    /// `EA Δl/l` along the reference chord, and its elements then do not balance moments once
    /// the belt's tangential displacement `u_t` turns the arc elements by `u_t/R` (a torque
    /// error `Σ N1 Δv` on the wraps). `false`: the linear model of Ribaric (5.5).
    exact_axial: bool,
    /// The axial damping force along the deformed chord on the material rate of its length
    /// ([`ViscousForce::Chord`], [`Self::chord_viscous`]); the linear damping matrices then
    /// keep only their bending part.
    chord_viscous: bool,
    /// The contact rows' `T_,s` on their elements' chords ([`ContactVelocity::Chord`]).
    chord_contact: bool,
    /// `l₀,e / Δs_e` of each bar: its length over the path distance between the mid-points of
    /// its two neighbours (the centred difference of the stretch, [`Self::chord_viscous`]).
    bar_span: Vec<f64>,
    /// `β EA / l₀` of each bar \[N s/m\].
    bar_kv: Vec<f64>,
    /// The naturally straight, co-rotated bending elements ([`BendingForce::CoRotated`]; empty
    /// with the linear bending of Ribaric (5.5), whose block then stays in the stiffness).
    bend: Vec<BendElement>,
    /// `Tᵀ` (`m × 3N`): the basis rows of a node's dofs as contiguous columns, for the
    /// element-by-element tangent of the co-rotated bending ([`Self::bending_tangent`]).
    tt: Mat<f64>,
}

/// One bar's axial damping force along its deformed chord ([`ViscousForce::Chord`]).
#[derive(Debug, Clone, Copy)]
struct ChordViscous {
    /// Unit deformed chord `û`.
    uh: [f64; 2],
    /// Deformed length `l` \[m\].
    l: f64,
    /// Eulerian velocity difference `ΔT ż` of the end nodes \[m/s\].
    de: [f64; 2],
    /// `l₀ ∂λ/∂s`: the change of the stretch along the path, centred on the bar \[-\].
    grad: f64,
    /// Material rate of the chord length `û·ΔT ż + v l₀ ∂λ/∂s` \[m/s\].
    rate: f64,
    /// Viscous axial force `N_v = (β EA/l₀) · rate` \[N\].
    n: f64,
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

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Column `j` of a dense (column-major) matrix as a slice.
fn col(a: &Mat<f64>, j: usize) -> &[f64] {
    a.col(j)
        .try_as_col_major()
        .expect("an owned matrix's columns are contiguous")
        .as_slice()
}

/// `y += s · Aᵀ x` for a dense `A`, `x` on the rows `r0..r0 + x.len()` of `A` (`y` over the
/// first `y.len()` columns).
fn gemv_t(y: &mut [f64], a: &Mat<f64>, r0: usize, x: &[f64], s: f64) {
    for (j, yj) in y.iter_mut().enumerate() {
        let aj = &col(a, j)[r0..r0 + x.len()];
        *yj += s * aj.iter().zip(x).map(|(a, xi)| a * xi).sum::<f64>();
    }
}

/// `y += s · A x` for a dense `A`.
fn gemv(y: &mut [f64], a: &Mat<f64>, x: &[f64], s: f64) {
    for (j, &xj) in x.iter().enumerate() {
        let c = s * xj;
        if c != 0.0 {
            for (yi, aij) in y.iter_mut().zip(col(a, j)) {
                *yi += aij * c;
            }
        }
    }
}

/// The nodal DOFs `(x_i, y_i, θ_i, x_j, y_j, θ_j)` of a bending element.
fn bend_dofs(e: &BendElement) -> [usize; 6] {
    let (i, j) = (NODE_DOFS * e.i, NODE_DOFS * e.j);
    [i, i + 1, i + 2, j, j + 1, j + 2]
}

/// What the flowing belt's balance note says with Ribaric's path-referenced bending
/// ([`FlowingBelt::balance_defect`]).
const RIBARIC_BALANCE_DEFECT: &str = "the flowing belt of Ribaric (5.5) takes the path's \
curvature as its stress-free shape, which does work on the moving material (the power defect \
grows as the wraps are refined; BENCHMARKS.md, \"Flowing belt balances by formulation\"): \
[models.flowing] bending = \"co_rotated\", axial_force = \"co_rotated\", viscous_force = \
\"chord\", equations = \"lagrange\" with a 6 mm arc_element \
(apps/belt/examples/fead-energy-consistent.toml) closes both balances on the default FEAD drive \
up to 2500 rpm at 6 to 10 times the CPU, or run the nodal or ANCF model";

impl FlowingBelt {
    /// Whether the contact slip follows the strain the elements carry
    /// ([`ContactVelocity::Chord`]; `belt::ModelTraits::near_coulomb_creep`).
    pub fn contact_rates_follow_the_strain(&self) -> bool {
        self.chord_contact
    }

    /// The known cause of a balance miss (`belt::ModelTraits::balance_defect`): with the
    /// path-referenced bending of Ribaric (5.5) ([`BendingForce::Linear`]) the belt's
    /// stress-free shape is the path's, and its re-curving at the tangent points does work on
    /// the moving material (module documentation; on the default FEAD drive the power residual
    /// is −1.9 % and −4.0 % on 4 mm wraps). `None` with the naturally straight belt.
    pub fn balance_defect(&self) -> Option<&'static str> {
        self.bend.is_empty().then_some(RIBARIC_BALANCE_DEFECT)
    }

    /// The flowing-material model of `drive` (Ribaric (5.14)): the stationary loop of
    /// `settings.mesh` on the mounted path, the basis of `settings.reduction`, all projections
    /// precomputed; the pulleys turn by the drive's motions, a tensioner's arm (if any) is a
    /// coordinate.
    pub fn new(drive: &Drive, settings: &FlowingSettings) -> Result<Self, crate::FlowError> {
        use mbd_core::Validate;
        settings.validate()?;
        let mut fe = BeltFe::new(drive, &settings.mesh)?;
        let law = &drive.contact().friction;
        let chord = settings.viscous_force.resolve(law) == ViscousForce::Chord;
        if chord {
            // the axial damping moves out of the linear matrices into Self::chord_viscous
            let (k, t1, t2) = super::model::axial_damping_parts(&fe);
            let beta = fe.drive.damping().beta;
            fe.damping = &fe.damping - &Mat::from_fn(k.nrows(), k.ncols(), |i, j| beta * k[(i, j)]);
            fe.frame_turn = &fe.frame_turn - &t1;
            fe.frame_turn2 = &fe.frame_turn2 - &t2;
        }
        // the basis is built on the linear stiffness of Ribaric (5.5) in either case
        let basis = FlowingBasis::new(&fe, settings.reduction.free_modes)?;
        let bend = if settings.bending == BendingForce::CoRotated {
            // the bending block moves out of the linear stiffness into Self::bending_forces
            let els = BendElement::loop_of(&fe.position, &fe.tangent, drive.belt().ei);
            // ... and out of the Rayleigh damping: β K_b on the natural-straight belt's steady
            // lift-off deflection, advected through the mesh (v T_,s z), dissipated 70 W on the
            // default fead drive at 800 rpm (149 W with Lagrange's equations) where the nodal
            // belt's whole damping takes 25.8 W (issue 34): the bending is undamped
            let beta = fe.drive.damping().beta;
            for e in &els {
                let k = e.linear_stiffness();
                let dofs = bend_dofs(e);
                let turn = super::model::chord_turn_rate(
                    fe.position[e.i],
                    fe.position[e.j],
                    fe.tangent[e.i],
                    fe.tangent[e.j],
                );
                let kj = super::model::corotational_rate_block(&k);
                let kt: [[f64; 6]; 6] = std::array::from_fn(|a| std::array::from_fn(|b| kj[b][a]));
                let jkj = super::model::corotational_rate_block(&kt);
                for a in 0..6 {
                    for b in 0..6 {
                        fe.stiffness[(dofs[a], dofs[b])] -= k[a][b];
                        fe.damping[(dofs[a], dofs[b])] -= beta * k[a][b];
                        fe.frame_turn[(dofs[a], dofs[b])] -= turn * kj[a][b];
                        fe.frame_turn2[(dofs[a], dofs[b])] -= turn * turn * jkj[a][b];
                    }
                }
            }
            els
        } else {
            Vec::new()
        };
        let mut belt = Self::on(fe, basis, drive.motions(), drive.arm().copied())?;
        if settings.contact_velocity.resolve(law) == ContactVelocity::Chord {
            // the contact rows' T_,s on their elements' chords (the slip, its tangent and the
            // contact's force on s_b all read the row's ts)
            for r in &mut belt.rows {
                r.ts = belt.fe.chord_rate_rows(belt.basis.t.as_ref(), r.node);
            }
            belt.chord_contact = true;
        }
        belt.bend = bend;
        belt.exact_axial = settings.axial_force == AxialForce::CoRotated;
        belt.chord_viscous = chord;
        belt.lagrange = settings.equations == BeltEquations::Lagrange;
        if chord {
            let bars = &belt.bars;
            let nb = bars.len();
            belt.bar_span = (0..nb)
                .map(|e| {
                    let (p, n) = (&bars[(e + nb - 1) % nb], &bars[(e + 1) % nb]);
                    bars[e].l / (0.5 * p.l + bars[e].l + 0.5 * n.l)
                })
                .collect();
            let bea = drive.damping().beta * drive.belt().ea;
            belt.bar_kv = bars.iter().map(|b| bea / b.l).collect();
        }
        if belt.exact_axial || chord {
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
            belt.bar_dxt = belt.bar_dx.transpose().to_owned();
        }
        Ok(belt)
    }

    fn on(
        fe: BeltFe, basis: FlowingBasis, motions: Vec<Motion>, tensioner: Option<Arm>,
    ) -> Result<Self, crate::FlowError> {
        let n = fe.n_dofs();
        let m = basis.len();
        let et = fe.stacked_tangent();
        let mdiag = &fe.mass;
        let scale_rows = |a: &Mat<f64>| Mat::from_fn(n, a.ncols(), |i, j| mdiag[i] * a[(i, j)]);
        let en = fe.stacked_curvature();
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
        let (alpha, beta) = (fe.drive.damping().alpha, fe.drive.damping().beta);
        let beta_k = Mat::from_fn(n, n, |i, j| {
            fe.damping[(i, j)] - if i == j { alpha * mdiag[i] } else { 0.0 }
        });
        // the frame-invariant material strain rate (BeltFe::frame_turn): β K_e (v T_,s z) minus
        // the co-rotation β v Σ ψ'_e K_e J T z of the elements the material passes through
        let turn = Mat::from_fn(n, n, |i, j| beta * fe.frame_turn[(i, j)]);
        let a_cs = project(
            &et,
            &basis.t,
            &(&(&beta_k * &basis.ts) - &(&turn * &basis.t)),
        );
        let men: Vec<f64> = (0..n).map(|i| mdiag[i] * en[i]).collect();
        let p_en = project_vec(&et, &basis.t, &men);
        let p_f0 = project_vec(&et, &basis.t, &fe.pretension);
        // Lagrange's equations (module documentation)
        let (t, ts) = (&basis.t, &basis.ts);
        let mee = (0..n).map(|i| et[i] * met[i]).sum();
        let mte = t.transpose() * Mat::from_fn(n, 1, |i, _| met[i]);
        let mse = ts.transpose() * Mat::from_fn(n, 1, |i, _| met[i]);
        let mtt = t.transpose() * &mt;
        let mss = ts.transpose() * scale_rows(ts);
        let kz = t.transpose() * (&fe.stiffness * t);
        let f0z = t.transpose() * Mat::from_fn(n, 1, |i, _| fe.pretension[i]);
        // the Rayleigh dissipation of the co-rotated material rate (module documentation):
        // Σ_e w_eᵀ β K_e,e w_e with w = T ż + v (T_,s − ψ' J T) z, and α M on T ż
        let ke = &beta_k;
        let ct = t.transpose() * (&fe.damping * t);
        let sc = |a: Mat<f64>| Mat::from_fn(a.nrows(), a.ncols(), |i, j| beta * a[(i, j)]);
        let ft = sc(&fe.frame_turn * t);
        let cg = t.transpose() * &(&(ke * ts) - &ft);
        let sft = ts.transpose() * &ft;
        let ch0 = &(ts.transpose() * (ke * ts)) + &sc(t.transpose() * (&fe.frame_turn2 * t));
        let ch = Mat::from_fn(m, m, |i, j| {
            0.5 * (ch0[(i, j)] + ch0[(j, i)]) - (sft[(i, j)] + sft[(j, i)])
        });
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
        let tt = basis.t.transpose().to_owned();
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
            lagrange: false,
            a_mass,
            a_k,
            a_c,
            a_cs,
            a_mss,
            p_en,
            p_f0,
            mee,
            mte: (0..m).map(|i| mte[(i, 0)]).collect(),
            mtt,
            mts,
            mss,
            mse: (0..m).map(|i| mse[(i, 0)]).collect(),
            kz,
            f0z: (0..m).map(|i| f0z[(i, 0)]).collect(),
            ct,
            cg,
            ch,
            rows,
            bar_dx: Mat::zeros(0, 0),
            bar_dxt: Mat::zeros(0, 0),
            bars: super::model::Bar::loop_of(&fe_pos),
            exact_axial: false,
            chord_viscous: false,
            chord_contact: false,
            bar_span: Vec::new(),
            bar_kv: Vec::new(),
            bend: Vec::new(),
            tt,
        })
    }

    /// The same model with Lagrange's equations of `(s_b, z)` instead of Ribaric's projection
    /// (5.14) (module documentation): the belt's mechanical energy then changes exactly by the
    /// power of its contact forces less its damping dissipation (issue 34).
    /// [`super::BeltEquations::Lagrange`] selects it from the settings.
    #[must_use]
    pub fn with_lagrange_equations(mut self) -> Self {
        self.lagrange = true;
        self
    }

    /// Whether the model runs Lagrange's equations ([`Self::with_lagrange_equations`]).
    pub fn lagrange_equations(&self) -> bool {
        self.lagrange
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

    /// Motion of one row's node against its pulley at a state (position `x₀ + T z`, material
    /// velocity `v (b + T_,s z) + T ż`, Ribaric (5.10)); the idler's frame and the relative
    /// velocity when the row's pulley is the tensioner's. Also returns `b + T_,s z` and
    /// whether the pulley is the tensioner's idler.
    fn row_motion(
        &self, r: &ContactRow, arm: Option<&ArmState>, t: f64, z: &[f64], zd: &[f64], v: &[f64],
    ) -> (NodeMotion, [f64; 2], bool) {
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
        let motion = NodeMotion {
            frame,
            omega: w,
            position: d,
            velocity: vel,
        };
        (motion, bs, idler)
    }

    /// Contact of one row at a state ([`Self::row_motion`]).
    fn row_contact(
        &self, r: &ContactRow, arm: Option<&ArmState>, t: f64, z: &[f64], zd: &[f64], v: &[f64],
    ) -> (NodeContact, [f64; 2], bool) {
        let (m, bs, idler) = self.row_motion(r, arm, t, z, zd, v);
        (
            node_contact(
                &m.frame,
                m.omega,
                m.position,
                m.velocity,
                &r.law,
                &self.friction[r.pulley],
            ),
            bs,
            idler,
        )
    }

    /// The motion of every contact node at `(t, q, v)` ([`Self::row_motion`]).
    fn row_motions(&self, t: f64, q: &[f64], v: &[f64]) -> Vec<NodeMotion> {
        let (z, zd) = (&q[1..=self.m], &v[1..=self.m]);
        let arm = self.coords.arm_state(q, v);
        self.rows
            .iter()
            .map(|r| self.row_motion(r, arm.as_ref(), t, z, zd, v).0)
            .collect()
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

    /// Momentum the belt carries through a section at each node of the stationary mesh \[N\]:
    /// `ṁ V` with the mass flow `ṁ = ρ v` (the material label passes every mesh point at the
    /// belt speed `v = ṡ_b`, Ribaric (5.10); `ρ` the node's lumped mass over its tributary
    /// length) and the material velocity `V = v b + T ż = v e_t + δ̇_m` ([`Self::material_rate`]).
    /// The belt report subtracts its moment from the spans' ([`belt::SpanState::momentum_flux`]).
    pub fn momentum_flux(&self, q: &[f64], v: &[f64]) -> Vec<[f64; 2]> {
        let vb = v[0];
        let rate = self.material_rate(q, v);
        (0..self.fe.n_nodes())
            .map(|i| {
                let mdot = vb * self.fe.mass[NODE_DOFS * i] / self.fe.tributary[i];
                let t = self.fe.tangent[i];
                [
                    mdot * (vb * t[0] + rate[NODE_DOFS * i]),
                    mdot * (vb * t[1] + rate[NODE_DOFS * i + 1]),
                ]
            })
            .collect()
    }

    /// Viscous axial force of the belt element starting at each node \[N\]: `β EA Dε/Dt` on
    /// the co-rotated material stretch rate ([`super::model::chord_viscous_forces`] with the
    /// material rate [`Self::material_rate`]), the part of the element's axial force its
    /// `β K_e` damping carries beside the elastic force [`Self::element_tensions`].
    pub fn element_viscous_forces(&self, q: &[f64], v: &[f64]) -> Vec<f64> {
        if self.chord_viscous {
            let m = self.m;
            return self
                .chord_viscous(&q[1..=m], &v[1..=m], v[0])
                .iter()
                .map(|c| c.n)
                .collect();
        }
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

    /// Power dissipated by the belt's Rayleigh damping at `(q, v)` \[W\]: twice the
    /// dissipation function `R` of the model (module documentation),
    ///
    /// ```text
    ///   2R = Σ_e w_eᵀ β K_e,e w_e + α (T ż)ᵀ M (T ż) = żᵀ C_t ż + 2 v żᵀ C_g z + v² zᵀ C_h z,
    ///   w_e = T ż + v (T_,s z − ψ'_e J T z)
    /// ```
    ///
    /// the Kelvin–Voigt dissipation of every element's co-rotated material rate (`≥ 0`), which
    /// is the power the damping forces `−∂R/∂(v, ż)` take from the belt (issue 34 power
    /// balance). With Ribaric's projection (5.14) (the default, [`Self::with_lagrange_equations`])
    /// the power of its damping forces `Q_d = −α M T ż − β K_e (δ̇_m − v ψ′ J δ)` on the
    /// material's rate relative to the path, `−Q_dᵀ δ̇_m`, which is not sign-definite (issue 34:
    /// −10.8 W on the default fead drive at 800 rpm where `2R` is 29.4 W). With the chord
    /// damping ([`ViscousForce::Chord`]) the axial part is `Σ_e N_v Dl_e/Dt = Σ_e (l₀/β EA) N_v²`
    /// (exactly `2R` of its Rayleigh function) and the matrices carry the bending part only.
    pub fn damping_dissipation(&self, q: &[f64], v: &[f64]) -> f64 {
        // the chord damping's Σ N_v Dl/Dt = 2R_axial
        let axial: f64 = if self.chord_viscous {
            let m = self.m;
            self.chord_viscous(&q[1..=m], &v[1..=m], v[0])
                .iter()
                .map(|c| c.n * c.rate)
                .sum()
        } else {
            0.0
        };
        axial + self.linear_dissipation(q, v)
    }

    /// The dissipation of the linear damping matrices (all of `β K_e`, or its bending part
    /// with [`ViscousForce::Chord`]).
    fn linear_dissipation(&self, q: &[f64], v: &[f64]) -> f64 {
        if !self.lagrange {
            return self.projected_dissipation(q, v);
        }
        let m = self.m;
        let (z, zd, vb) = (&q[1..=m], &v[1..=m], v[0]);
        let (mut c, mut g, mut h) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
        gemv(&mut c, &self.ct, zd, 1.0);
        gemv(&mut g, &self.cg, z, 1.0);
        gemv(&mut h, &self.ch, z, 1.0);
        dot(zd, &c) + 2.0 * vb * dot(zd, &g) + vb * vb * dot(z, &h)
    }

    /// Ribaric (5.14)'s damping power at `(q, v)` \[W\]: `−Q_dᵀ δ̇_m`, the
    /// power of the damping forces `Q_d = −α M T ż − β K_e (δ̇_m − v ψ′ J δ)` (module
    /// documentation) on the material, which moves at the rate `δ̇_m` ([`Self::material_rate`])
    /// relative to the path (issue 34 power balance).
    fn projected_dissipation(&self, q: &[f64], v: &[f64]) -> f64 {
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

    /// The axial damping force of every bar along its deformed chord ([`ViscousForce::Chord`],
    /// issue 34): the Kelvin–Voigt force `β EA Dε/Dt` on the material rate of the chord's
    /// length, taken from the stretches `λ = l/l₀` of the deformed chords,
    ///
    /// ```text
    ///   Dl/Dt = û·(T ż)_j − û·(T ż)_i + v l₀ (λ_{e+1} − λ_{e−1}) / Δs_e
    ///   N_v = (β EA/l₀) Dl/Dt,   on node j −N_v û, on node i +N_v û
    /// ```
    ///
    /// (`Δs_e` the path distance between the mid-points of the neighbouring bars): the
    /// Eulerian rate of the chord plus the convective rate `v ∂l/∂s` of Ribaric (5.10), with the
    /// derivative along `s` taken on the stretches themselves, so that a rigid motion of the
    /// deflected belt and the mounted state carry no viscous force. These are the forces of the
    /// Rayleigh function `R = Σ_e ½ (β EA/l₀) (Dl/Dt)²`, so with Lagrange's equations they take
    /// exactly `2R` from the belt ([`Self::damping_dissipation`]).
    ///
    /// Departure from the seed: Ribaric (5.5) damps `C δ̇` on the mesh's (reference) chords and
    /// takes the convective rate as `v T_,s z`; on a wrap of radius `R` meshed with `h`, the
    /// three-point `T_,s` turns a rigid rotation `φ` of the wrap into a spurious chord rate of
    /// order `v φ (h/R)³` (more at the span–wrap nodes, where the stencil is uneven; `û·ΔV`
    /// with `V = v (e_t + T_,s z) + T ż` gave 38 W of dissipation on 12 mm wraps and 12 W on
    /// 4 mm wraps of the default fead drive), and the linear form's virtual work on the slide
    /// misses `Σ_e N_v ψ′_e (J u_e)·Δδ` (issue 34). On Ribaric's rows (5.14) the nodal forces
    /// are projected on `e_t` as the linear ones are.
    fn chord_viscous(&self, z: &[f64], zd: &[f64], vb: f64) -> Vec<ChordViscous> {
        let dxt = &self.bar_dxt;
        let nb = self.bars.len();
        // deformed chords and Eulerian velocity differences
        let geo: Vec<([f64; 2], f64, [f64; 2])> = self
            .bars
            .iter()
            .enumerate()
            .map(|(b, bar)| {
                let (mut chord, mut de) = ([0.0; 2], [0.0; 2]);
                for a in 0..2 {
                    let (mut dd, mut dzd) = (0.0, 0.0);
                    let row = &col(dxt, 2 * b + a)[1..=self.m];
                    for ((d, zk), zdk) in row.iter().zip(z).zip(zd) {
                        dd += d * zk;
                        dzd += d * zdk;
                    }
                    chord[a] = bar.l * bar.u[a] + dd;
                    de[a] = dzd;
                }
                let l = chord[0].hypot(chord[1]);
                ([chord[0] / l, chord[1] / l], l, de)
            })
            .collect();
        (0..nb)
            .map(|b| {
                let (uh, l, de) = geo[b];
                let (p, n) = ((b + nb - 1) % nb, (b + 1) % nb);
                let lam = |e: usize| geo[e].1 / self.bars[e].l;
                let grad = self.bar_span[b] * (lam(n) - lam(p));
                let rate = uh[0] * de[0] + uh[1] * de[1] + vb * grad;
                ChordViscous {
                    uh,
                    l,
                    de,
                    grad,
                    rate,
                    n: self.bar_kv[b] * rate,
                }
            })
            .collect()
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

    /// The belt rows `[s_b; z]` of Lagrange's equations without the contact forces (module
    /// documentation).
    fn lagrange_forces(&self, z: &[f64], zd: &[f64], vb: f64, head: &mut [f64]) {
        let m = self.m;
        let (mut g, mut h, mut sz, mut szd) =
            (vec![0.0; m], vec![0.0; m], vec![0.0; m], vec![0.0; m]);
        gemv(&mut g, &self.cg, z, 1.0);
        gemv(&mut h, &self.ch, z, 1.0);
        gemv(&mut sz, &self.mss, z, 1.0);
        gemv(&mut szd, &self.mss, zd, 1.0);
        let mut tszd = vec![0.0; m + 1];
        gemv(&mut tszd, &self.mts, zd, 1.0);
        // the transposed product T_,sᵀ M T ż
        let mut tszd_t = vec![0.0; m];
        gemv_t(&mut tszd_t, &self.mts, 1, zd, 1.0);
        // row 0: −∂R/∂v and the velocity terms of d/dt(∂𝒯/∂v)
        head[0] = -dot(zd, &g)
            - vb * dot(z, &h)
            - 2.0 * vb * (tszd[0] + dot(z, &szd))
            - dot(zd, &tszd[1..]);
        let z_rows = &mut head[1..];
        for (i, r) in z_rows.iter_mut().enumerate() {
            // (T_,sᵀ M T − Tᵀ M T_,s) ż: the skew gyroscopic matrix
            let skew = tszd_t[i] - tszd[i + 1];
            *r = self.f0z[i] - vb * g[i] + vb * skew + vb * vb * (self.mse[i] + sz[i]);
        }
        gemv(z_rows, &self.kz, z, -1.0);
        gemv(z_rows, &self.ct, zd, -1.0);
    }

    /// `e_t,j − e_t,i` of bar `b` from node `i` to node `j`: on Ribaric's row 0 (5.14) a bar's
    /// chord force `N û` (on `j`, `−N û` on `i`) contributes `N û·(e_t,j − e_t,i)`.
    fn bar_tangent_step(&self, b: usize) -> [f64; 2] {
        let (i, j) = (self.bars[b].i, self.bars[b].j);
        let t = &self.fe.tangent;
        [t[j][0] - t[i][0], t[j][1] - t[i][1]]
    }

    /// `−∂Q/∂(z, v, ż)` of the chord damping ([`Self::chord_viscous`]) added to `kq`, `cv`.
    /// With `A_e = ∂(Dl_e/Dt)/∂(row's velocity)` the bar's share of each row (`û·ΔP`, on
    /// Lagrange's row 0 `l₀ ∂λ/∂s`), `B = û·ΔT`, `k = β EA/l₀` and
    ///
    /// ```text
    ///   ∂(Dl/Dt)/∂z = v G + (n̂·ΔT ż)(n̂·ΔT)/l,   G_e = l₀,e/Δs_e (B_{e+1}/l₀,e+1 − B_{e−1}/l₀,e−1)
    ///   −∂Q/∂z = Σ_e k A ∂(Dl/Dt)/∂z + N_v ∂A/∂z,   −∂Q/∂ż = Σ_e k A B,   −∂Q/∂v = Σ_e k A l₀ ∂λ/∂s
    /// ```
    ///
    /// (`n̂ = J û`; `∂(û·ΔP)/∂z = (n̂·ΔP)(n̂·ΔT)/l`, on Lagrange's row 0 `G`).
    fn chord_viscous_tangent(
        &self, z: &[f64], zd: &[f64], vb: f64, kq: &mut Mat<f64>, cv: &mut Mat<f64>,
    ) {
        let m = self.m;
        let bars = self.chord_viscous(z, zd, vb);
        let nb = bars.len();
        let dx = &self.bar_dx;
        // per bar: n̂, its neighbours, and the scalars of its rows
        let nh: Vec<[f64; 2]> = bars.iter().map(|c| [-c.uh[1], c.uh[0]]).collect();
        let ne: Vec<f64> = (0..nb)
            .map(|b| nh[b][0] * bars[b].de[0] + nh[b][1] * bars[b].de[1])
            .collect();
        let mut a = Mat::<f64>::zeros(nb, m + 1);
        let mut ap = Mat::<f64>::zeros(nb, m + 1);
        let mut g = Mat::<f64>::zeros(nb, m);
        let mut rz = Mat::<f64>::zeros(nb, m);
        let mut nbp = Mat::<f64>::zeros(nb, m);
        let mut kb = Mat::<f64>::zeros(nb, m);
        let c0: Vec<f64> = (0..nb).map(|b| self.bar_kv[b] * bars[b].grad).collect();
        for (b, c) in bars.iter().enumerate() {
            if self.lagrange {
                a[(b, 0)] = c.grad;
            } else {
                let det = self.bar_tangent_step(b);
                a[(b, 0)] = c.uh[0] * det[0] + c.uh[1] * det[1];
                ap[(b, 0)] = nh[b][0] * det[0] + nh[b][1] * det[1];
            }
        }
        // column by column (the matrices are column-major): B = û·ΔT and B⊥ = n̂·ΔT of every
        // bar in column k of A and A⊥, then the bar's G (its neighbours' B), R_z, N B⊥/l, k B
        for k in 0..m {
            for (b, c) in bars.iter().enumerate() {
                let (d0, d1) = (dx[(2 * b, k + 1)], dx[(2 * b + 1, k + 1)]);
                a[(b, k + 1)] = c.uh[0] * d0 + c.uh[1] * d1;
                ap[(b, k + 1)] = nh[b][0] * d0 + nh[b][1] * d1;
            }
            for (b, c) in bars.iter().enumerate() {
                let (p, n) = ((b + nb - 1) % nb, (b + 1) % nb);
                let kv = self.bar_kv[b];
                let (bm, bp) = (a[(b, k + 1)], ap[(b, k + 1)]);
                g[(b, k)] = self.bar_span[b]
                    * (a[(n, k + 1)] / self.bars[n].l - a[(p, k + 1)] / self.bars[p].l);
                rz[(b, k)] = kv * (vb * g[(b, k)] + ne[b] * bp / c.l);
                nbp[(b, k)] = c.n * bp / c.l;
                kb[(b, k)] = kv * bm;
            }
        }
        let at = a.transpose();
        let dq = &(at * &rz) + &(ap.transpose() * &nbp);
        let dv = at * &kb;
        for r in 0..=m {
            cv[(r, 0)] += (0..nb).map(|b| a[(b, r)] * c0[b]).sum::<f64>();
        }
        for k in 0..m {
            for r in 0..=m {
                kq[(r, k + 1)] += dq[(r, k)];
                cv[(r, k + 1)] += dv[(r, k)];
            }
        }
        if self.lagrange {
            for k in 0..m {
                kq[(0, k + 1)] += (0..nb).map(|b| bars[b].n * g[(b, k)]).sum::<f64>();
            }
        }
    }

    /// The nodal forces `−∂U_b/∂δ` (`3N`) of the co-rotated bending elements
    /// ([`BendingForce::CoRotated`], [`BendElement::forces`]) at the deflection `δ = T z`.
    fn bending_forces(&self, z: &[f64]) -> Vec<f64> {
        let d = self.deflection(z);
        let mut f = vec![0.0; self.fe.n_dofs()];
        for e in &self.bend {
            let (fe, _) = e.forces(&d, false);
            for (&r, x) in bend_dofs(e).iter().zip(fe) {
                f[r] += x;
            }
        }
        f
    }

    /// The co-rotated bending elements' stiffness `K_b = ∂²U_b/∂δ²` at `δ = T z`
    /// ([`BendElement::forces`]) projected on the basis: `Tᵀ K_b T` (`m × m`) and with Ribaric's
    /// projection (5.14) the row `e_tᵀ K_b T` (`m`; empty with Lagrange's equations, where
    /// `U_b` does not depend on `s_b`). `K_b T` is formed transposed, `(K_b T)ᵀ = Tᵀ K_b`
    /// (`m × 3N`), element by element on contiguous columns of [`Self::tt`].
    fn bending_tangent(&self, z: &[f64]) -> (Mat<f64>, Vec<f64>) {
        let d = self.deflection(z);
        let (n, m, tt) = (self.fe.n_dofs(), self.m, &self.tt);
        let mut ktt = Mat::<f64>::zeros(m, n);
        for e in &self.bend {
            let (_, ke) = e.forces(&d, true);
            let dofs = bend_dofs(e);
            for (a, krow) in ke.iter().enumerate() {
                for (b, &k) in krow.iter().enumerate() {
                    if k == 0.0 {
                        continue;
                    }
                    let src = col(tt, dofs[b]);
                    let dst = ktt
                        .col_mut(dofs[a])
                        .try_as_col_major_mut()
                        .expect("an owned matrix's columns are contiguous")
                        .as_slice_mut();
                    for (x, y) in dst.iter_mut().zip(src) {
                        *x += k * y;
                    }
                }
            }
        }
        let row0 = if self.lagrange {
            Vec::new()
        } else {
            (0..m)
                .map(|k| {
                    self.fe
                        .tangent
                        .iter()
                        .enumerate()
                        .map(|(i, e)| {
                            e[0] * ktt[(k, NODE_DOFS * i)] + e[1] * ktt[(k, NODE_DOFS * i + 1)]
                        })
                        .sum()
                })
                .collect()
        };
        (tt * ktt.transpose(), row0)
    }

    /// Bending energy `U_b = Σ_e ½ θ̄ᵀ B θ̄` \[J\] of the co-rotated bending elements at the
    /// modal coordinates `z` ([`BendElement::energy`]; 0 with the linear bending of Ribaric
    /// (5.5), whose energy is part of `½ δᵀ K δ`).
    pub fn bending_energy(&self, z: &[f64]) -> f64 {
        let d = self.deflection(z);
        self.bend.iter().map(|e| e.energy(&d)).sum()
    }

    /// `(K_t, C_t)` as dense matrices: `−∂f/∂q`, `−∂f/∂v`.
    fn tangent(&self, t: f64, q: &[f64], v: &[f64]) -> (Mat<f64>, Mat<f64>) {
        let m = self.m;
        let (z, zd, vb) = (&q[1..=m], &v[1..=m], v[0]);
        let nv = self.n_v;
        let mut kq = Mat::<f64>::zeros(nv, nv);
        let mut cv = Mat::<f64>::zeros(nv, nv);
        if self.lagrange {
            let (mut g, mut gt, mut h, mut sz, mut szd) = (
                vec![0.0; m],
                vec![0.0; m],
                vec![0.0; m],
                vec![0.0; m],
                vec![0.0; m],
            );
            gemv(&mut g, &self.cg, z, 1.0);
            gemv_t(&mut gt, &self.cg, 0, zd, 1.0);
            gemv(&mut h, &self.ch, z, 1.0);
            gemv(&mut sz, &self.mss, z, 1.0);
            gemv(&mut szd, &self.mss, zd, 1.0);
            let mut tszd = vec![0.0; m + 1];
            gemv(&mut tszd, &self.mts, zd, 1.0);
            // the transposed product T_,sᵀ M T ż
            let mut tszd_t = vec![0.0; m];
            gemv_t(&mut tszd_t, &self.mts, 1, zd, 1.0);
            // row 0 (forces(): −żᵀC_g z − v zᵀC_h z − 2v (e_tᵀ M T_,s ż + zᵀ M_ss ż) − żᵀ M_ts ż)
            for j in 0..m {
                kq[(0, j + 1)] = gt[j] + 2.0 * vb * (h[j] + szd[j]);
                cv[(0, j + 1)] =
                    g[j] + 2.0 * vb * (self.mts[(0, j)] + sz[j]) + tszd[j + 1] + tszd_t[j];
            }
            cv[(0, 0)] = dot(z, &h) + 2.0 * (tszd[0] + dot(z, &szd));
            // rows of z
            // column by column: the matrices are column-major
            for j in 0..m {
                for i in 0..m {
                    kq[(i + 1, j + 1)] =
                        self.kz[(i, j)] + vb * self.cg[(i, j)] - vb * vb * self.mss[(i, j)];
                    cv[(i + 1, j + 1)] =
                        self.ct[(i, j)] - vb * (self.mts[(j + 1, i)] - self.mts[(i + 1, j)]);
                }
            }
            for i in 0..m {
                cv[(i + 1, 0)] =
                    g[i] - (tszd_t[i] - tszd[i + 1]) - 2.0 * vb * (self.mse[i] + sz[i]);
            }
        } else {
            for j in 0..m {
                for i in 0..=m {
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
                for r in usize::from(self.lagrange)..=m {
                    kq[(r, k + 1)] += add[(r, k)];
                }
            }
        }
        if self.chord_viscous {
            self.chord_viscous_tangent(z, zd, vb, &mut kq, &mut cv);
        }
        if !self.bend.is_empty() {
            // −∂/∂z of Pᵀ f_b = Pᵀ K_b T (row 0 e_t with Ribaric's projection (5.14) only:
            // with Lagrange's equations U_b does not depend on s_b)
            let (tk, row0) = self.bending_tangent(z);
            for k in 0..m {
                if !self.lagrange {
                    kq[(0, k + 1)] += row0[k];
                }
                for r in 0..m {
                    kq[(r + 1, k + 1)] += tk[(r, k)];
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
            // Lagrange: row 0 is bᵀ F (b = e_t + T_,s z at the node, ∂b/∂z = T_,s);
            // Ribaric (5.14): e_tᵀ F
            if self.lagrange {
                for j in 0..m {
                    kq[(0, j + 1)] -= c.force[0] * r.ts[(0, j)] + c.force[1] * r.ts[(1, j)];
                }
            }
            let p0 = if self.lagrange {
                bs
            } else {
                self.fe.tangent[r.node]
            };
            // belt rows 0 and 1..=m (Tᵀ): the node's nonzero rows, column by column
            let ps: Vec<(usize, [f64; 2])> = (0..=m)
                .filter_map(|i| {
                    let p = if i == 0 {
                        p0
                    } else {
                        [r.t[(0, i - 1)], r.t[(1, i - 1)]]
                    };
                    (p[0] != 0.0 || p[1] != 0.0).then_some((i, p))
                })
                .collect();
            for j in 0..m {
                let (fz, fzd) = ([dfz[0][j], dfz[1][j]], [dfzd[0][j], dfzd[1][j]]);
                if fz == [0.0; 2] && fzd == [0.0; 2] {
                    continue;
                }
                for &(i, p) in &ps {
                    kq[(i, j + 1)] -= p[0] * fz[0] + p[1] * fz[1];
                    cv[(i, j + 1)] -= p[0] * fzd[0] + p[1] * fzd[1];
                }
            }
            for &(i, p) in &ps {
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
        let z = &q[1..=m];
        let mut mm = Mat::<f64>::zeros(self.n_v, self.n_v);
        if !self.lagrange {
            // Ribaric (5.14): Pᵀ M [e_t + b | T], b = T_,s z
            let mut col = vec![0.0; m + 1];
            gemv(&mut col, &self.mts, z, 1.0);
            for j in 0..=m {
                for i in 0..=m {
                    mm[(i, j)] = self.a_mass[(i, j)];
                }
            }
            for i in 0..=m {
                mm[(i, 0)] += col[i];
            }
            for (k, j) in self.coords.inertias() {
                mm[(k, k)] = j;
            }
            return Ok(SysMatrix::Dense(mm));
        }
        // [bᵀ M b, bᵀ M T; Tᵀ M b, Tᵀ M T] with b = e_t + T_,s z (∂V/∂v)
        let mut tsz = vec![0.0; m + 1];
        gemv(&mut tsz, &self.mts, z, 1.0);
        let mut sz = vec![0.0; m];
        gemv(&mut sz, &self.mss, z, 1.0);
        mm[(0, 0)] = self.mee + 2.0 * tsz[0] + dot(z, &sz);
        for i in 0..m {
            let c = self.mte[i] + tsz[i + 1];
            mm[(0, i + 1)] = c;
            mm[(i + 1, 0)] = c;
        }
        for j in 0..m {
            for i in 0..m {
                mm[(i + 1, j + 1)] = self.mtt[(i, j)];
            }
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
        if self.lagrange {
            self.lagrange_forces(z, zd, vb, head);
        } else {
            for i in 0..=m {
                head[i] = self.p_f0[i] - vb * vb * self.p_en[i];
            }
            gemv(head, &self.a_k, z, -1.0);
            gemv(head, &self.a_c, zd, -1.0);
            gemv(head, &self.a_cs, z, -vb);
            gemv(head, &self.a_mss, z, -vb * vb);
            gemv(head, &self.mts, zd, -2.0 * vb);
        }
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
            // Lagrange: the elastic forces do no work on the slide s_b (module documentation)
            for (k, h) in head.iter_mut().enumerate().skip(usize::from(self.lagrange)) {
                let mut acc = 0.0;
                for (r, cr) in c.iter().enumerate() {
                    acc += dx[(r, k)] * cr;
                }
                *h += acc;
            }
        }
        if self.chord_viscous {
            // Q_k = −Σ N_v û·ΔP_k: row 0 P = b (Lagrange) or e_t (Ribaric (5.14)), rows of z T
            for (b, c) in self.chord_viscous(z, zd, vb).iter().enumerate() {
                // Lagrange: −∂R/∂v = −Σ N_v ∂(Dl/Dt)/∂v; Ribaric (5.14): e_tᵀ of the nodal forces
                head[0] -= c.n
                    * if self.lagrange {
                        c.grad
                    } else {
                        let det = self.bar_tangent_step(b);
                        c.uh[0] * det[0] + c.uh[1] * det[1]
                    };
                let (r0, r1) = (col(&self.bar_dxt, 2 * b), col(&self.bar_dxt, 2 * b + 1));
                for k in 0..m {
                    head[k + 1] -= c.n * (c.uh[0] * r0[k + 1] + c.uh[1] * r1[k + 1]);
                }
            }
        }
        if !self.bend.is_empty() {
            let fb = self.bending_forces(z);
            if !self.lagrange {
                head[0] += self
                    .fe
                    .tangent
                    .iter()
                    .enumerate()
                    .map(|(i, e)| e[0] * fb[NODE_DOFS * i] + e[1] * fb[NODE_DOFS * i + 1])
                    .sum::<f64>();
            }
            gemv_t(&mut head[1..], &self.basis.t, 0, &fb, 1.0);
        }
        tail.fill(0.0);
        let arm = self.coords.arm_state(q, v);
        for r in &self.rows {
            let (c, bs, idler) = self.row_contact(r, arm.as_ref(), t, z, zd, v);
            if c.normal == 0.0 && c.friction == 0.0 {
                continue;
            }
            // generalized force on s_b: Lagrange, the work of F on the material's displacement
            // b δs_b; Ribaric (5.14), the projection on e_t
            let p0 = if self.lagrange {
                bs
            } else {
                self.fe.tangent[r.node]
            };
            head[0] += p0[0] * c.force[0] + p0[1] * c.force[1];
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

    /// The transition-aware limit of the contact rows' friction ([`correction_limit`], Castro
    /// et al. 2019): each row's slip velocity at the iterate and at the corrected state
    /// `(q + dq, v + dv)`, exact at both (the slip `t·(v (b + T_,s z) + T ż) − ωR` of the
    /// material flowing through the mesh is bilinear in `v` and `z`, and its tangent turns
    /// with the node: the end point carries both), linear in `α` between them.
    fn correction_limit(
        &self, t: f64, q: &[f64], v: &[f64], dq: &[f64], dv: &[f64], _ws: &mut Workspace,
    ) -> Result<f64, MbdError> {
        if self.friction.iter().all(|f| f.transition_width().is_none()) {
            return Ok(1.0);
        }
        let mut q1 = vec![0.0; q.len()];
        self.integrate_position(q, dq, &mut q1);
        let v1: Vec<f64> = v.iter().zip(dv).map(|(a, b)| a + b).collect();
        let now = self.row_motions(t, q, v);
        let next = self.row_motions(t, &q1, &v1);
        Ok(correction_limit(
            now.into_iter()
                .zip(next)
                .zip(&self.rows)
                .map(|((a, b), r)| (a, b, &self.friction[r.pulley])),
        ))
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
        layout_belt_with(axial_force, ViscousForce::Linear)
    }

    /// [`layout_belt`] with the axial damping force `viscous_force`.
    pub(crate) fn layout_belt_with(
        axial_force: AxialForce, viscous_force: ViscousForce,
    ) -> FlowingBelt {
        layout_belt_bending(axial_force, viscous_force, BendingForce::Linear)
    }

    /// [`layout_belt_with`] with the bending force `bending`.
    pub(crate) fn layout_belt_bending(
        axial_force: AxialForce, viscous_force: ViscousForce, bending: BendingForce,
    ) -> FlowingBelt {
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
            viscous_force,
            bending,
            ..FlowingSettings::default()
        };
        FlowingBelt::new(&drive, &settings).unwrap()
    }

    /// The belt's mechanical energy `E = ½ Vᵀ M V + ½ δᵀ K δ − f0ᵀ δ` at `(q, v)` and its rate
    /// along the equations of motion with every contact removed (the loop floating free of its
    /// pulleys): `(dE/dt, E)`, with `V = v (e_t + T_,s z) + T ż` the material velocity of the nodes
    /// (Ribaric (5.10)) and the accelerations `[a; z̈] = M(q)⁻¹ f(q, v)` of the model; the
    /// second value is the sum of the magnitudes of the terms that cancel in the rate.
    fn free_energy_rate(belt: &FlowingBelt, q: &[f64], v: &[f64]) -> (f64, f64) {
        let m = belt.n_modes();
        let n = belt.fe.n_dofs();
        let (z, zd, vb) = (&q[1..=m], &v[1..=m], v[0]);
        let mut ws = Workspace::new();
        let mut f = vec![0.0; belt.n_q()];
        belt.forces(0.0, q, v, &mut f, &mut ws).unwrap();
        let SysMatrix::Dense(mm) = belt.mass(0.0, q).unwrap() else {
            panic!("dense mass")
        };
        let blk = Mat::from_fn(m + 1, m + 1, |i, j| mm[(i, j)]);
        let rhs = Mat::from_fn(m + 1, 1, |i, _| f[i]);
        let acc = faer::prelude::Solve::solve(&blk.partial_piv_lu(), &rhs);
        let et = belt.fe.stacked_tangent();
        let d = belt.deflection(z);
        let mut b = et;
        gemv(&mut b, &belt.basis.ts, z, 1.0);
        let mut vel: Vec<f64> = b.iter().map(|x| vb * x).collect();
        gemv(&mut vel, &belt.basis.t, zd, 1.0);
        let mv: Vec<f64> = (0..n).map(|i| belt.fe.mass[i] * vel[i]).collect();
        let kd: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| belt.fe.stiffness[(i, j)] * d[j]).sum())
            .collect();
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        // ∂E/∂v = bᵀ M V, ∂E/∂ż = Tᵀ M V, ∂E/∂z = v T_,sᵀ M V + Tᵀ (K δ − f0)
        let el: Vec<f64> = (0..n).map(|i| kd[i] - belt.fe.pretension[i]).collect();
        let mut terms = vec![acc[(0, 0)] * dot(&b, &mv)];
        for j in 0..m {
            let col = |a: &Mat<f64>, x: &[f64]| (0..n).map(|i| a[(i, j)] * x[i]).sum::<f64>();
            terms.push(acc[(j + 1, 0)] * col(&belt.basis.t, &mv));
            terms.push(zd[j] * vb * col(&belt.basis.ts, &mv));
            terms.push(zd[j] * col(&belt.basis.t, &el));
        }
        (terms.iter().sum(), terms.iter().map(|x| x.abs()).sum())
    }

    /// A deflected, moving state of `belt`: every mode excited, the largest nodal deflection
    /// 0.1 mm and the largest deflection rate 10 mm/s; belt speed `speed` \[m/s\].
    fn moving_state(belt: &FlowingBelt, speed: f64) -> (Vec<f64>, Vec<f64>) {
        let (n, m) = (belt.n_q(), belt.n_modes());
        let (mut q, mut v) = (vec![0.0; n], vec![0.0; n]);
        let z: Vec<f64> = (0..m).map(|i| ((i as f64) * 0.7).sin()).collect();
        let zd: Vec<f64> = (0..m).map(|i| ((i as f64) * 1.3).cos()).collect();
        let big = |x: &[f64]| {
            belt.deflection(x)
                .iter()
                .fold(0.0f64, |a, y| a.max(y.abs()))
        };
        let (sz, szd) = (1e-4 / big(&z), 1e-2 / big(&zd));
        for i in 0..m {
            q[i + 1] = sz * z[i];
            v[i + 1] = szd * zd[i];
        }
        v[0] = speed;
        (q, v)
    }

    // Reference: the Eulerian steady flow in closed form. A belt moving rigidly along its
    // mounted path at v (no deflection, no deflection rate) carries ρ v² along the path's
    // tangent through every section (ρ = mass per length of the drive's belt, up to the lumped
    // mass of the chord polygon over the arc length, 1 − (l/R)²/24 on the smallest pulley).
    #[test]
    fn momentum_flux_of_a_rigid_flow_is_rho_v_squared_along_the_path() {
        let belt = layout_belt(AxialForce::Linear);
        let (n, speed) = (belt.n_q(), 12.0);
        let mut v = vec![0.0; n];
        v[0] = speed;
        let rho = belt.fe.drive.belt().mass_per_length;
        let flux = belt.momentum_flux(&vec![0.0; n], &v);
        assert_eq!(flux.len(), belt.fe.n_nodes());
        let scale = rho * speed * speed;
        let r_min = (belt.fe.drive.pulleys().iter())
            .map(|p| p.radius)
            .fold(f64::INFINITY, f64::min);
        let chord = 1.1 * (belt.fe.mesh.arc_element / r_min).powi(2) / 24.0;
        for (phi, t) in flux.iter().zip(&belt.fe.tangent) {
            let along = phi[0] * t[0] + phi[1] * t[1];
            let across = -phi[0] * t[1] + phi[1] * t[0];
            assert!((along / scale - 1.0).abs() < chord, "{along} of {scale}");
            assert!(across.abs() < 1e-12 * scale, "{across}");
        }
    }

    /// `|dE/dt|` and the scale of its terms for the free undamped belt of every case of the
    /// energy tests (Table 6-1's loop and the four-pulley layout's non-uniform loop, all modes
    /// and 10 free-node modes), with Lagrange's equations or Ribaric's projection (5.14).
    fn free_undamped_energy_rates(lagrange: bool) -> Vec<(String, f64, f64)> {
        let four = layout_belt(AxialForce::Linear).fe;
        let mut out = Vec::new();
        for (name, drive, mesh) in [
            (
                "Table 6-1",
                crate::belt::table_6_1(0.0, 0.0),
                BeltMesh::default(),
            ),
            ("layout", four.drive.clone(), four.mesh),
        ] {
            let mut layout = drive.layout().clone();
            layout.damping = belt::BeltDamping {
                alpha: 0.0,
                beta: 0.0,
            };
            let drive = layout.resolve().unwrap();
            for free_modes in [None, Some(10)] {
                let settings = FlowingSettings {
                    mesh,
                    reduction: BeltReduction { free_modes },
                    ..FlowingSettings::default()
                };
                let mut belt = FlowingBelt::new(&drive, &settings).unwrap();
                if lagrange {
                    belt = belt.with_lagrange_equations();
                }
                belt.rows.clear();
                let (q, v) = moving_state(&belt, 5.0);
                let (rate, scale) = free_energy_rate(&belt, &q, &v);
                let name = format!("{name} {free_modes:?}");
                println!("{name}: dE/dt {rate:.3e} W (terms {scale:.3e} W)");
                out.push((name, rate, scale));
            }
        }
        out
    }

    // Issue 34 item 2, the invariant behind the power balance: with no contact and no damping
    // the floating belt is a conservative system, so the rate of its mechanical energy along
    // the equations of motion is zero at every state (reference: the energy theorem of the
    // closed loop; the material flux through the stationary mesh cancels around the loop).
    // Lagrange's equations keep it to round-off: measured |dE/dt| ≤ 4e-12 W against terms of
    // 1e4 W. Checked on Table 6-1's loop (56 elements, uniform on each span and arc) and on the
    // four-pulley layout's non-uniform loop (50 mm spans against 10 mm arcs), all modes and
    // reduced, at 5 m/s, 0.1 mm and 10 mm/s.
    #[test]
    fn the_free_undamped_belt_conserves_its_energy() {
        for (name, rate, scale) in free_undamped_energy_rates(true) {
            assert!(rate.abs() < 1e-9 * scale, "{name}: dE/dt = {rate} W");
        }
    }

    // The same invariant on Ribaric's projection (5.14), the default equations: it fails. At
    // the test's states dE/dt = −0.39 W (Table 6-1, all modes), 8.7e-3 W (10 modes), −0.35 W
    // (layout, all modes), −6.3e-3 W (10 modes), 6e-5 to 4e-5 of the terms: on the default fead
    // drive at 800 rpm the projection's elastic forces do +32.7 W on the flowing material
    // (v (f0ᵀ T_,s z − e_tᵀ K δ), 19 W of it on the alternator's 12 mm wrap elements) and −5.6 W
    // at second order (−v δᵀ T_,sᵀ K δ), its inertia −0.07 W, and its damping forces +10.8 W
    // (their Kelvin–Voigt dissipation is 29.8 W): the work of the e_t row's elastic and damping
    // forces on the slide (module documentation). Kept as the record of the defect; run with
    // `--ignored`.
    #[test]
    #[ignore = "fails: Ribaric's projection (5.14) is not energy-consistent (issue 34)"]
    fn the_free_undamped_belt_conserves_its_energy_with_ribaric_projection() {
        for (name, rate, scale) in free_undamped_energy_rates(false) {
            assert!(rate.abs() < 1e-9 * scale, "{name}: dE/dt = {rate} W");
        }
    }

    // Issue 34 item 2: with the belt's Rayleigh damping (Table 6-1's α = 2.8 1/s, β = 1.8 ms) and
    // Lagrange's equations the free belt's energy falls at exactly the rate damping_dissipation reports (reference: the
    // energy theorem, dE/dt = −2R), and that dissipation is at least the Kelvin–Voigt
    // dissipation Σ N_v² l/(β EA) of the elements' viscous axial forces (chord_viscous_forces,
    // an independent element-by-element evaluation; the rest is bending and α).
    #[test]
    fn the_free_damped_belt_loses_what_its_damping_dissipates() {
        free_damped_belt_loses_what_its_damping_dissipates(ViscousForce::Linear);
    }

    // The same with the axial damping along the deformed chords (ViscousForce::Chord): the
    // reference is the energy balance dE/dt = −2R of the undriven belt (Lagrange's equations,
    // Jacobi's integral), with 2R the Kelvin–Voigt dissipation Σ N_v²·l₀/(β EA) of the axial
    // forces plus that of the bending part.
    #[test]
    fn the_free_damped_belt_loses_what_its_chord_damping_dissipates() {
        free_damped_belt_loses_what_its_damping_dissipates(ViscousForce::Chord);
    }

    fn free_damped_belt_loses_what_its_damping_dissipates(viscous_force: ViscousForce) {
        let four = layout_belt(AxialForce::Linear).fe;
        for (name, drive, mesh) in [
            (
                "Table 6-1",
                crate::belt::table_6_1(0.0, 0.0),
                BeltMesh::default(),
            ),
            ("layout", four.drive.clone(), four.mesh),
        ] {
            let settings = FlowingSettings {
                mesh,
                reduction: BeltReduction { free_modes: None },
                viscous_force,
                ..FlowingSettings::default()
            };
            let mut belt = FlowingBelt::new(&drive, &settings)
                .unwrap()
                .with_lagrange_equations();
            belt.rows.clear();
            let (q, v) = moving_state(&belt, 5.0);
            let (rate, scale) = free_energy_rate(&belt, &q, &v);
            let diss = belt.damping_dissipation(&q, &v);
            let bea = drive.damping().beta * drive.belt().ea;
            let nv = belt.element_viscous_forces(&q, &v);
            let n = belt.fe.n_nodes();
            let kv: f64 = (0..n)
                .map(|i| {
                    let (a, b) = (belt.fe.position[i], belt.fe.position[(i + 1) % n]);
                    nv[i] * nv[i] * (b[0] - a[0]).hypot(b[1] - a[1]) / bea
                })
                .sum();
            println!("{name}: dE/dt {rate:.6e} W, dissipation {diss:.6e} W, axial KV {kv:.6e} W");
            assert!(
                kv > 0.0 && diss >= kv * (1.0 - 1e-9),
                "{name}: {diss} < {kv}"
            );
            assert!(
                (rate + diss).abs() < 1e-9 * scale,
                "{name}: {rate} + {diss} (scale {scale})"
            );
        }
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

    // The same with Lagrange's equations (issue 34), linear and co-rotated axial force.
    #[test]
    fn layout_tangent_of_lagrange_equations_matches_finite_differences() {
        check_layout_tangent(layout_belt(AxialForce::Linear).with_lagrange_equations());
        check_layout_tangent(layout_belt(AxialForce::CoRotated).with_lagrange_equations());
    }

    // The analytic tangent of the chord damping (ViscousForce::Chord) against central
    // differences of the forces, with both equations of motion.
    #[test]
    fn layout_tangent_with_chord_damping_matches_finite_differences() {
        for axial in [AxialForce::Linear, AxialForce::CoRotated] {
            check_layout_tangent(layout_belt_with(axial, ViscousForce::Chord));
            check_layout_tangent(
                layout_belt_with(axial, ViscousForce::Chord).with_lagrange_equations(),
            );
        }
    }

    /// The chord damping's tangent as it was before its loops ran column by column
    /// (2026-12-07), the reference of
    /// `column_order_tangent_equals_the_row_order_loops`.
    fn chord_viscous_tangent_dense(
        belt: &FlowingBelt, z: &[f64], zd: &[f64], vb: f64, kq: &mut Mat<f64>, cv: &mut Mat<f64>,
    ) {
        let this = belt;
        let m = this.m;
        let bars = this.chord_viscous(z, zd, vb);
        let nb = bars.len();
        let dx = &this.bar_dx;
        let proj =
            |w: [f64; 2], b: usize, k: usize| w[0] * dx[(2 * b, k)] + w[1] * dx[(2 * b + 1, k)];
        // B and B⊥ per bar over z
        let mut bm = Mat::<f64>::zeros(nb, m);
        let mut bp = Mat::<f64>::zeros(nb, m);
        for (b, c) in bars.iter().enumerate() {
            let nh = [-c.uh[1], c.uh[0]];
            for k in 0..m {
                bm[(b, k)] = proj(c.uh, b, k + 1);
                bp[(b, k)] = proj(nh, b, k + 1);
            }
        }
        let mut a = Mat::<f64>::zeros(nb, m + 1);
        let mut ap = Mat::<f64>::zeros(nb, m + 1);
        let mut g = Mat::<f64>::zeros(nb, m);
        let mut rz = Mat::<f64>::zeros(nb, m);
        let mut nbp = Mat::<f64>::zeros(nb, m);
        let mut kb = Mat::<f64>::zeros(nb, m);
        let mut c0 = vec![0.0; nb];
        for (b, c) in bars.iter().enumerate() {
            let nh = [-c.uh[1], c.uh[0]];
            let (p, n) = ((b + nb - 1) % nb, (b + 1) % nb);
            let kv = this.bar_kv[b];
            if this.lagrange {
                a[(b, 0)] = c.grad;
            } else {
                let det = this.bar_tangent_step(b);
                a[(b, 0)] = c.uh[0] * det[0] + c.uh[1] * det[1];
                ap[(b, 0)] = nh[0] * det[0] + nh[1] * det[1];
            }
            let ne = nh[0] * c.de[0] + nh[1] * c.de[1];
            c0[b] = kv * c.grad;
            for k in 0..m {
                a[(b, k + 1)] = bm[(b, k)];
                ap[(b, k + 1)] = bp[(b, k)];
                g[(b, k)] =
                    this.bar_span[b] * (bm[(n, k)] / this.bars[n].l - bm[(p, k)] / this.bars[p].l);
                rz[(b, k)] = kv * (vb * g[(b, k)] + ne * bp[(b, k)] / c.l);
                nbp[(b, k)] = c.n * bp[(b, k)] / c.l;
                kb[(b, k)] = kv * bm[(b, k)];
            }
        }
        let at = a.transpose();
        let dq = &(at * &rz) + &(ap.transpose() * &nbp);
        let dv = at * &kb;
        for r in 0..=m {
            cv[(r, 0)] += (0..nb).map(|b| a[(b, r)] * c0[b]).sum::<f64>();
            for k in 0..m {
                kq[(r, k + 1)] += dq[(r, k)];
                cv[(r, k + 1)] += dv[(r, k)];
            }
        }
        if this.lagrange {
            for k in 0..m {
                kq[(0, k + 1)] += (0..nb).map(|b| bars[b].n * g[(b, k)]).sum::<f64>();
            }
        }
    }

    /// The co-rotated bending stiffness projected as before (2026-12-07): `K_b T` (`3N × m`)
    /// scattered element by element, then `Tᵀ (K_b T)` and Ribaric's row `e_tᵀ K_b T`.
    fn bending_tangent_dense(belt: &FlowingBelt, z: &[f64]) -> (Mat<f64>, Vec<f64>) {
        let d = belt.deflection(z);
        let (n, m, t) = (belt.fe.n_dofs(), belt.m, &belt.basis.t);
        let mut kt = Mat::<f64>::zeros(n, m);
        for e in &belt.bend {
            let (_, ke) = e.forces(&d, true);
            let dofs = bend_dofs(e);
            for a in 0..6 {
                for b in 0..6 {
                    for c in 0..m {
                        kt[(dofs[a], c)] += ke[a][b] * t[(dofs[b], c)];
                    }
                }
            }
        }
        let row0 = (0..m)
            .map(|k| {
                (0..belt.fe.n_nodes())
                    .map(|i| {
                        let e = belt.fe.tangent[i];
                        e[0] * kt[(NODE_DOFS * i, k)] + e[1] * kt[(NODE_DOFS * i + 1, k)]
                    })
                    .sum()
            })
            .collect();
        (t.transpose() * &kt, row0)
    }

    // The tangent with its loops in column order (`Tᵀ` stored, `K_b T` formed transposed)
    // against the loops it replaced (the functions above, reference: the same formulas in row
    // order), for both equations of motion and both axial forces, to round-off.
    #[test]
    fn column_order_tangent_equals_the_row_order_loops() {
        for axial in [AxialForce::Linear, AxialForce::CoRotated] {
            for lagrange in [false, true] {
                let mut belt =
                    layout_belt_bending(axial, ViscousForce::Chord, BendingForce::CoRotated);
                if lagrange {
                    belt = belt.with_lagrange_equations();
                }
                let n = belt.n_q();
                let m = belt.n_modes();
                let (mut q, mut v) = (vec![0.0; n], vec![0.0; n]);
                for i in 1..=m {
                    q[i] = 1e-4 * ((i as f64) * 0.7).sin();
                    v[i] = 1e-2 * ((i as f64) * 1.3).cos();
                }
                v[0] = 3.0;
                let (kq, cv) = belt.tangent(0.1, &q, &v);
                // the reference: the rest of the tangent, plus the dense parts
                let mut rest = belt.clone();
                rest.chord_viscous = false;
                rest.bend.clear();
                let (mut kr, mut cr) = rest.tangent(0.1, &q, &v);
                let (z, zd) = (&q[1..=m], &v[1..=m]);
                chord_viscous_tangent_dense(&belt, z, zd, v[0], &mut kr, &mut cr);
                let (tk, row0) = bending_tangent_dense(&belt, z);
                for k in 0..m {
                    if !lagrange {
                        kr[(0, k + 1)] += row0[k];
                    }
                    for r in 0..m {
                        kr[(r + 1, k + 1)] += tk[(r, k)];
                    }
                }
                let scale = kr.norm_max().max(cr.norm_max());
                let dk = (&kq - &kr).norm_max();
                let dc = (&cv - &cr).norm_max();
                assert!(
                    dk < 1e-12 * scale && dc < 1e-12 * scale,
                    "{axial:?} lagrange {lagrange}: |Δk| {dk:e}, |Δc| {dc:e}, scale {scale:e}"
                );
            }
        }
    }

    // The analytic tangent of the co-rotated bending elements (BendingForce::CoRotated, issue
    // 34) against central differences of the forces, with both equations of motion and both
    // axial forces.
    #[test]
    fn layout_tangent_with_co_rotated_bending_matches_finite_differences() {
        for axial in [AxialForce::Linear, AxialForce::CoRotated] {
            for viscous in [ViscousForce::Linear, ViscousForce::Chord] {
                let b = || layout_belt_bending(axial, viscous, BendingForce::CoRotated);
                check_layout_tangent(b());
                check_layout_tangent(b().with_lagrange_equations());
            }
        }
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
            (0, 1e-6),
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

    // Reference: the closed-form slip change of a pulley-speed correction
    // (crate::belt::check_pulley_speed_limit).
    #[test]
    fn correction_limit_stops_the_driven_wrap_inside_the_band() {
        let drive = crate::belt::table_6_1_sharp(60.0);
        let belt = FlowingBelt::new(&drive, &FlowingSettings::default()).unwrap();
        let q = belt.static_state().unwrap();
        let (_, dof) = belt.coords.free_pulleys()[0];
        let radius = belt.pulleys[1].radius;
        crate::belt::check_pulley_speed_limit(&belt, &q, dof, radius, |v| {
            belt.contact_report(0.0, &q, v)
                .iter()
                .map(|r| (r.pulley, r.contact.penetration, r.contact.slip))
                .collect()
        });
    }
}
