//! The rolling wheel–tire model with flowing material (Ribaric (7.10)–(7.17)) and its time
//! integration with Lagrange-multiplier contact and Coulomb slip friction (§7.3, §8.4.3).
//!
//! # Equations
//! The mesh frame does not spin (seed note U16): the wheel centre is held by the spindle
//! (U22: after the preload the centre is fixed, camber and steer are locked) and spins freely
//! about its axis `η = ŷ` with `θ̇ = ηᵀω` (U17). The absolute acceleration of the material at mesh
//! location `s` is (7.9), (7.14)–(7.16)
//!
//! ```text
//!   d̈ = r̈ + ω̇ × s + ω × (ω × s) + T z̈ + θ̈ T_,θ z + θ̇² T_,θθ z + 2 θ̇ T_,θ ż      (r̈ = 0)
//! ```
//!
//! Rows 3–4 of (7.17) are projected with `Tᵀ` applied to the mass-weighted nodal equations
//! (`M d̈ = f − K δ − C δ̇`), the Galerkin variant of U15 extended to the contact rows (identical
//! to Ribaric's rows when nothing is truncated, and symmetric in M and K):
//!
//! ```text
//!   M_z z̈ + (m_θ + G₁ z) θ̈ + (2θ̇ G₁ + α M_z + β K_z) ż + (K_z + θ̇² G₂ + β θ̇ K₁) z + θ̇² c_s
//!        = T_cᵀ f^c
//!   J θ̈ = τ − ηᵀ K_θ (z + β (ż + θ̇ ... ))                    (row 2 of (7.10): rim moment)
//! ```
//! Rayleigh damping `C = αM + βK` acts with its `βK` part on the material strain rate
//! `δ̇ = T ż + θ̇ T_,θ z` and its `αM` part on the Eulerian rate `T ż` (seed note U10: no drag
//! in the steady state). The spindle force is the force of the tire on the rim,
//! `F = −(K_r δ + β K_r δ̇)` (7.2). Summing the tire's nodal equations over a rigid translation
//! `e` (`K e = 0`) gives the same force from Newton's second law for the tire,
//! `F = Σ fᶜ − eᵀM d̈ − α eᵀM T ż`, which is the default here ([`SpindleForceMethod`]): the
//! two agree when nothing is truncated, but the truncated model satisfies its projected
//! equations only, and the rim form then carries the elastic residual of loads the basis does
//! not represent, chiefly the centrifugal load of rolling (the steady vertical force misses the
//! load by −2.1 % on the default tire at 60 km/h). The momentum form is the force-summation
//! form of reaction recovery, which, like the mode-acceleration method, converges faster with
//! the number of modes than the mode-displacement form (e.g. Craig & Kurdila, *Fundamentals of
//! Structural Dynamics*).
//!
//! # Contact (E15)
//! A contact node `i` at mesh position `xᵢ = sᵢ + (T_c z)ᵢ` is constrained by its gap `gᵢ ≥ 0`
//! (closest point on the drum/road/cleat), with multiplier `λᵢ ≥ 0` along the normal `nᵢ`; the
//! friction force opposes the slip of the material over the ground,
//! `vᵢ = θ̇ η × sᵢ + (T_c ż + θ̇ T_c,θ z)ᵢ − u_ground`: set-valued Coulomb with stick
//! (`|fᵢ| ≤ μλᵢ`, `fᵢ = −μλᵢ v̂_t` when slipping; default) or Ribaric's slip-only regularised
//! `fᵢ = −μλᵢ v_t/√(|v_t|² + ε²)` (U20), or any law of the contact crate, see [`TireFriction`]. The penalty option replaces the
//! rigid constraint by a compliance `1/k` on the diagonal of the contact problem.
//!
//! # Integration
//! Generalized-α (Chung–Hulbert, in the form of Arnold and Brüls with pseudo-accelerations;
//! spectral radius ρ∞ = 0.5 by default, ρ∞ = 1 is the trapezoidal Newmark rule) with the
//! contact gaps imposed at the end of each step (index-3), a linearly implicit step. The small
//! high-frequency damping of ρ∞ < 1 removes the period-two chatter of the index-3 contact
//! forces at the patch edges that the trapezoidal rule leaves undamped (and with it the
//! sensitivity of the cleat response to round-off and to the contact tolerance).
//!
//! The θ̇-dependent gyroscopic/centrifugal/damping matrix `R = [C_eff K_eff G₁]` is evaluated at
//! a spin rate frozen until it drifts by more than `spin_tolerance` (then re-formed: cheap). The
//! iteration matrix `S = [J ⋯; m_θ M + γ'h C_eff + β'h² K_eff]`, with the generalized-α
//! coefficients `(β', γ') = (β, γ)(1 − α_f)/(1 − α_m)` of the end-of-step accelerations
//! ([`RollingConfig::implicit_coefficients`]), is inverted explicitly, together with the contact
//! responses `X = S⁻¹[0; T_cᵀ]` and `Y = T_c X_z` of all contact nodes, only when θ̇ drifts by
//! more than `matrix_tolerance` (10 %: once per run at constant speed); in between, the
//! gyroscopic part `2γ'h(θ̇_R − θ̇_S)G₁` of `S(θ̇_R) − S(θ̇_S)` is applied to the previous step's
//! accelerations, like the lagged term `G₁ z θ̈`. The normal and friction problems are solved
//! together by a semismooth Newton method on the Alart–Curnier equations in the local contact
//! frames ([`super::contact_solve`]), converged to `contact_tolerance`. Per step the cost is one
//! product with `R` (n × 3 n_z), one with `S⁻¹` (n × n), `T_c z` for the candidate search, and
//! work on the candidates only (the local Delassus matrix is a gather from `Y` and `X`);
//! nothing is allocated once the work arrays have grown. Candidates are the nodes whose free
//! gap is below `contact_margin` (plus `h v` in front of the cleat, whose faces approach at the
//! surface speed); [`StepStats::late_contacts`] counts impacts begun within one step.

use super::contact_solve::{ContactSolver, DelassusSource, SolveOptions};
use super::error::{TireError, invalid};
use super::friction::TireFriction;
use super::ground::{Ground, GroundPoint};
use super::reduced::ReducedTire;
use faer::linalg::matmul::matmul;
use faer::prelude::*;
use faer::{Accum, Mat, Par};
use mbd_core::Validate;
use serde::{Deserialize, Serialize};

/// Normal contact law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "law", deny_unknown_fields)]
pub enum NormalContact {
    /// Rigid unilateral constraint with Lagrange multipliers (Ribaric §7.3).
    Lagrange,
    /// Linear penalty `λ = k · penetration` \[N/m\].
    Penalty {
        /// Stiffness per contact node \[N/m\].
        stiffness: f64,
    },
}

/// How the spindle force (the force of the tire on the wheel) is evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SpindleForceMethod {
    /// Newton's second law for the tire (default): the ground's force on the tire minus the
    /// rate of the tire's translational momentum and the mass-proportional damping force,
    /// `F = Σ fᶜ − eᵀM d̈ − α P ż` (module docs). The force-summation (mode-acceleration)
    /// form: it uses only `M` and the contact forces, so it keeps the exact force balance of
    /// the truncated model (steady rolling: `F = Σ fᶜ`, the load).
    #[default]
    Momentum,
    /// The rim forces of Ribaric (7.2), `F = −K_r (z + β ż) − β θ̇ K_r,θ z` (the
    /// mode-displacement form): equal to `Momentum` when nothing is truncated, but carrying
    /// the elastic residual of the truncated basis otherwise (e.g. the centrifugal load).
    Rim,
}

/// Integration and contact settings of the rolling tire.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RollingConfig {
    /// Time step `h` \[s\].
    pub time_step: f64,
    /// Newmark β of the generalized-α update (see [`RollingConfig::generalized_alpha`]).
    pub newmark_beta: f64,
    /// Newmark γ of the generalized-α update.
    pub newmark_gamma: f64,
    /// Generalized-α weight α_m of the pseudo-acceleration (0 with `alpha_f = 0`: plain
    /// Newmark).
    pub alpha_m: f64,
    /// Generalized-α weight α_f of the true acceleration.
    pub alpha_f: f64,
    /// Coulomb friction coefficient μ (Ribaric §8.4.3: 0.85 nominal, 0 pure slip).
    pub friction: f64,
    /// Friction law: `coulomb` (set-valued, with stick; default), `regularized`
    /// (Ribaric's slip-only `f = −μλ u/√(|u|²+ε²)`, seed note U20), or a law table
    /// (see [`TireFriction`]).
    pub friction_law: TireFriction,
    /// Slip-velocity regularisation ε of the `regularized` friction law \[m/s\] (unused by
    /// `coulomb`).
    pub slip_regularization: f64,
    /// Relative tolerance of the contact solve: Alart–Curnier residual (complementarity and
    /// friction law, in force units) below this times the largest normal force.
    pub contact_tolerance: f64,
    /// Normal contact law.
    pub normal: NormalContact,
    /// Spin inertia of the wheel (without the rim nodes, which are added) \[kg·m²\].
    pub wheel_spin_inertia: f64,
    /// Relative drift of θ̇ at which the spin-dependent force matrix `R` (gyroscopic,
    /// centrifugal and damping terms) is re-formed.
    pub spin_tolerance: f64,
    /// Relative drift of θ̇ at which the iteration matrix `S` is inverted again; between
    /// inversions its gyroscopic part `2γh(θ̇_R − θ̇_S)G₁` is lagged by one step (see
    /// [`RollingTire::step`]).
    pub matrix_tolerance: f64,
    /// Contact-node candidates: gap below this margin \[m\] (plus `h·v` for nodes facing the
    /// cleat, whose faces approach at up to the surface speed `v`).
    pub contact_margin: f64,
    /// Evaluation of the spindle force: `momentum` (default) or `rim` (Ribaric (7.2)).
    pub spindle_force: SpindleForceMethod,
}

impl Default for RollingConfig {
    fn default() -> Self {
        Self {
            time_step: 2e-4,
            newmark_beta: GA_DEFAULT.2,
            newmark_gamma: GA_DEFAULT.3,
            alpha_m: GA_DEFAULT.0,
            alpha_f: GA_DEFAULT.1,
            friction: 0.85,
            friction_law: TireFriction::Coulomb,
            slip_regularization: 0.05,
            contact_tolerance: 1e-10,
            normal: NormalContact::Lagrange,
            wheel_spin_inertia: 2.0,
            spin_tolerance: 1e-2,
            matrix_tolerance: 0.1,
            contact_margin: 0.0005,
            spindle_force: SpindleForceMethod::Momentum,
        }
    }
}

/// `(α_m, α_f, β, γ)` of the default generalized-α scheme, spectral radius ρ∞ = 0.5.
///
/// Why 0.5: with the index-3 contact of the cleat test the impact leaves the patch nodes
/// bouncing on the ground unless the highest (unresolved) frequencies are damped. On the
/// default cord-reinforced truck tire at 60 km/h on the drum the patch never settles again
/// after the cleat for ρ∞ ≥ 0.75 (0.85: 2171 impacts begun within a step, 15.5 instead of 21
/// contacts per step), settles at ρ∞ = 0.7 on the drum but not on the road at 70 and 100 km/h
/// (and with the rig's impact sub-steps not on the drum either: 746 late impacts), and settles
/// at every speed 20–100 km/h on both grounds at ρ∞ = 0.5 (BENCHMARKS.md, "tire").
/// The dissipation in the resolved band is negligible: at the 76 Hz vertical line and
/// h = 0.2 ms, Ω h ≈ 0.1, where the algorithmic damping ratio is O((Ω h)³).
const GA_DEFAULT: (f64, f64, f64, f64) = {
    // Chung–Hulbert (1993) with ρ∞ = 0.5: α_m = (2ρ∞ − 1)/(ρ∞ + 1) = 0, α_f = ρ∞/(ρ∞ + 1),
    // γ = 1/2 − α_m + α_f, β = (γ + 1/2)²/4 (written out: const fns cannot use powi)
    let (am, af) = (0.0 / 1.5, 0.5 / 1.5);
    let g = 0.5 - am + af;
    (am, af, 0.25 * (g + 0.5) * (g + 0.5), g)
};

impl RollingConfig {
    /// Set the time integration to the generalized-α method of Chung and Hulbert (1993) in the
    /// form of Arnold and Brüls (2007) with spectral radius `rho_inf` ∈ \[0, 1\] at infinite
    /// frequency: `α_m = (2ρ∞ − 1)/(ρ∞ + 1)`, `α_f = ρ∞/(ρ∞ + 1)`, `γ = ½ − α_m + α_f`,
    /// `β = (γ + ½)²/4`. Second-order accurate; ρ∞ = 1 is the trapezoidal rule (Newmark
    /// β = ¼, γ = ½, no numerical damping); ρ∞ < 1 damps the highest frequencies, e.g. the
    /// period-two chatter of index-3 contact at the patch edges. The default is ρ∞ = 0.5
    /// (see `GA_DEFAULT` in the source for why).
    pub fn generalized_alpha(mut self, rho_inf: f64) -> Self {
        let am = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
        let af = rho_inf / (rho_inf + 1.0);
        let g = 0.5 - am + af;
        self.alpha_m = am;
        self.alpha_f = af;
        self.newmark_gamma = g;
        self.newmark_beta = 0.25 * (g + 0.5).powi(2);
        self
    }

    /// The coefficients `(β', γ')` of the end-of-step accelerations `z̈ₙ₊₁` in `zₙ₊₁` (times
    /// h²) and `żₙ₊₁` (times h): `β (1 − α_f)/(1 − α_m)`, `γ (1 − α_f)/(1 − α_m)`.
    pub fn implicit_coefficients(&self) -> (f64, f64) {
        let r = (1.0 - self.alpha_f) / (1.0 - self.alpha_m);
        (self.newmark_beta * r, self.newmark_gamma * r)
    }

    /// Check the parameters (field names in the messages).
    pub fn validate(&self) -> Result<(), TireError> {
        let pos = |name: &str, v: f64| {
            if v > 0.0 && v.is_finite() {
                Ok(())
            } else {
                Err(invalid(
                    format!("rolling.{name}"),
                    format!("{v} is not positive"),
                ))
            }
        };
        pos("time_step", self.time_step)?;
        pos("newmark_beta", self.newmark_beta)?;
        pos("newmark_gamma", self.newmark_gamma)?;
        for (name, v) in [("alpha_m", self.alpha_m), ("alpha_f", self.alpha_f)] {
            if !(v.is_finite() && v < 1.0 && v > -1.0) {
                return Err(invalid(
                    format!("rolling.{name}"),
                    format!("{v} is outside (−1, 1)"),
                ));
            }
        }
        pos("slip_regularization", self.slip_regularization)?;
        pos("contact_tolerance", self.contact_tolerance)?;
        pos("wheel_spin_inertia", self.wheel_spin_inertia)?;
        pos("spin_tolerance", self.spin_tolerance)?;
        pos("matrix_tolerance", self.matrix_tolerance)?;
        pos("contact_margin", self.contact_margin)?;
        if !(self.friction >= 0.0 && self.friction.is_finite()) {
            return Err(invalid(
                "rolling.friction",
                format!("{} is negative", self.friction),
            ));
        }
        if let NormalContact::Penalty { stiffness } = self.normal {
            pos("normal.stiffness", stiffness)?;
        }
        if let TireFriction::Law(spec) = self.friction_law {
            spec.validate_within("rolling.friction_law")?;
        }
        Ok(())
    }
}

/// State of the rolling tire.
#[derive(Debug, Clone)]
pub struct RollingState {
    /// Time \[s\].
    pub t: f64,
    /// Reduced coordinates `z`.
    pub z: Vec<f64>,
    /// Their rates `ż`.
    pub zd: Vec<f64>,
    /// Their accelerations `z̈`.
    pub zdd: Vec<f64>,
    /// The generalized-α pseudo-accelerations `a` of `z` (equal to `z̈` for plain Newmark).
    pub acc: Vec<f64>,
    /// Wheel spin angle θ \[rad\].
    pub theta: f64,
    /// Spin rate θ̇ \[rad/s\].
    pub theta_d: f64,
    /// Spin acceleration θ̈ \[rad/s²\].
    pub theta_dd: f64,
    /// Pseudo-acceleration of θ \[rad/s²\].
    pub theta_acc: f64,
    /// Normal multiplier per contact node \[N\].
    pub lambda: Vec<f64>,
    /// Friction force per contact node (wheel frame) \[N\].
    pub friction: Vec<[f64; 3]>,
    /// Net force of the ground on the tire (normal and friction, wheel frame x, y, z) \[N\].
    pub contact_force: [f64; 3],
}

/// Spindle force of the tire on the wheel, in the output frame of U18.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpindleForce {
    /// Longitudinal `F_x` \[N\].
    pub fx: f64,
    /// Vertical `F_y` (up positive: the carried load) \[N\].
    pub fy: f64,
    /// Lateral (along the wheel axis) \[N\].
    pub fz: f64,
}

/// The inverted Newmark iteration matrix `S` (at the spin rate `spin_s`), the spin-dependent
/// force matrix `R` (at the spin rate `spin`) and the responses of the contact nodes.
///
/// `S⁻¹` and `R` are stored transposed so that their products with a vector run over contiguous
/// rows (dot products), which is faster here than the column-major kernel: both products are
/// limited by memory traffic (R is 2.7 MB for the 341-DOF tire).
struct Factor {
    /// Time step at which `S` was inverted \[s\].
    h: f64,
    /// Spin rate at which `R` was formed \[rad/s\].
    spin: f64,
    /// Spin rate at which `S` was inverted \[rad/s\].
    spin_s: f64,
    /// `(S⁻¹)ᵀ` (n × n, n = 1 + n_z).
    sinv_t: Mat<f64>,
    /// `Rᵀ` (3 n_z × n), `R = [Q̂ | [0; G₁]]` acting on `[ż̃; z̃; θ̈ z]`; row 0 of `R` holds the
    /// rim-moment (spin) row, rows 1.. `[C_eff K_eff G₁]`.
    rt: Mat<f64>,
    /// `X = S⁻¹ [0; T_cᵀ]`: response of `[θ̈; z̈]` to unit forces on the contact-node DOF
    /// (n × 3 n_c).
    x: Mat<f64>,
    /// `Y = T_c X_z`: contact-node displacement response (3 n_c × 3 n_c, columns of node j
    /// at 3j..3j+3).
    y: Mat<f64>,
}

/// Per-step work arrays, allocated once (the step itself does not allocate once their
/// capacities are reached, except inside the small contact LCP).
struct Work {
    /// `[ż̃; z̃; θ̈ z]` (3 n_z).
    pred: Vec<f64>,
    /// Known part `wₙ = (α_f z̈ₙ − α_m aₙ)/(1 − α_m)` of the generalized-α pseudo-accelerations
    /// (n_z).
    known: Vec<f64>,
    /// Free accelerations `[θ̈; z̈]`, then with the contact correction (n).
    a: Vec<f64>,
    /// Right-hand side of `S a = …` (n).
    tmp: Vec<f64>,
    z_free: Vec<f64>,
    zd_free: Vec<f64>,
    /// Contact-node displacements `T_c z` (3 n_c).
    dc: Vec<f64>,
    cand: Vec<usize>,
    /// Whether each contact node was a candidate in the previous step.
    was_cand: Vec<bool>,
    gp: Vec<GroundPoint>,
    lambda: Vec<f64>,
    ft: Vec<[f64; 3]>,
    forces: Vec<[f64; 3]>,
    /// Warm starts `(λ, f1, f2)` per candidate (3m; from the last step and the one before)
    /// and diagonal compliances `[d_N, d_T]`.
    x0: Vec<f64>,
    x1: Vec<f64>,
    x2: Vec<f64>,
    /// Normal and friction forces per contact node two steps back \[N\].
    lambda2: Vec<f64>,
    friction2: Vec<[f64; 3]>,
    diag: Vec<[f64; 2]>,
    /// Scaled local frames and rigid-spin coefficients of the candidates ([`TireDelassus`]).
    frames: Vec<[[f64; 3]; 3]>,
    rig_t1: Vec<f64>,
    /// The coupled normal + friction solver (buffers reused).
    solver: ContactSolver,
}

/// Work counters of the time integration (for benchmarks and diagnostics).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct StepStats {
    /// Time steps taken.
    pub steps: usize,
    /// Sum over the steps of the contact candidates.
    pub candidates: usize,
    /// Sum over the steps of the nodes in contact.
    pub active: usize,
    /// Normal LCP solves (of the fallback alternation).
    pub lcp_solves: usize,
    /// Friction Gauss–Seidel sweeps (of the fallback alternation).
    pub friction_sweeps: usize,
    /// Newton iterations (LU factorisations) of the coupled contact solve.
    pub contact_newton: usize,
    /// Chord iterations (solves with an earlier Newton matrix) of the contact solve.
    pub contact_chord: usize,
    /// Steps whose contact solve fell back to the normal/friction alternation.
    pub contact_fallbacks: usize,
    /// Steps whose contact solve missed `contact_tolerance` (forces kept).
    pub contact_unconverged: usize,
    /// Contact-node column sets computed (`S⁻¹` columns of one node).
    pub columns: usize,
    /// Re-formings of the spin-dependent force matrix `R` (drift beyond `spin_tolerance`).
    pub force_matrix_updates: usize,
    /// Nodes whose free end-of-step gap is below −`contact_margin` although they were not
    /// candidates in the previous step: impacts begun within one step. They are part of this
    /// step's contact problem (candidates are chosen from the current free gaps), so no contact
    /// is lost; a large count says that the step resolves the approach coarsely (e.g. the
    /// cleat's faces at high speed, or a lightly damped tread).
    pub late_contacts: usize,
    /// Seconds spent in: free step (products with `R` and `S⁻¹`), candidate search,
    /// re-forming `R`, contact problem, inverting `S` (with the contact-node columns).
    pub seconds: [f64; 5],
}

/// The reduced tire rolling on a ground, with the spindle fixed.
pub struct RollingTire<'a> {
    red: &'a ReducedTire,
    cfg: RollingConfig,
    /// The ground.
    pub ground: Ground,
    /// Rayleigh α \[1/s\].
    pub alpha: f64,
    /// Rayleigh β \[s\].
    pub beta: f64,
    /// Drive torque about the wheel axis \[N·m\] (0: free-rolling spindle).
    pub drive_torque: f64,
    /// Current state.
    pub state: RollingState,
    factor: Option<Factor>,
    /// The factorisation of the other time step after [`RollingTire::set_time_step`], kept to
    /// switch back without inverting again.
    spare: Option<Factor>,
    /// `T_cᵀ` and `T_c,θᵀ` (n_z × 3 n_c): contiguous rows of the contact-node maps.
    tct: Mat<f64>,
    tct_theta: Mat<f64>,
    work: Work,
    /// Number of inversions of the iteration matrix so far.
    pub refactors: usize,
    /// Work counters.
    pub stats: StepStats,
    /// Contact nodes pressed onto the cleat in the last step.
    pub cleat_contacts: usize,
}

fn matvec(a: MatRef<'_, f64>, x: &[f64], out: &mut [f64]) {
    let xv = MatRef::from_column_major_slice(x, x.len(), 1);
    let ov = MatMut::from_column_major_slice_mut(out, a.nrows(), 1);
    matmul(ov, Accum::Replace, a, xv, 1.0, Par::Seq);
}

/// Dot product with four partial sums (vectorisable).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for k in 0..4 {
            acc[k] += x[k] * y[k];
        }
    }
    let tail: f64 = ra.iter().zip(rb).map(|(x, y)| x * y).sum();
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// `y += c x` (vectorisable).
fn axpy(c: f64, x: &[f64], y: &mut [f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += c * xi;
    }
}

/// The contiguous storage of a column of a (column-major) `Mat`.
fn col_slice(m: &Mat<f64>, j: usize) -> &[f64] {
    m.col(j)
        .try_as_col_major()
        .map_or(&[][..], |c| c.as_slice())
}

fn dot3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Tangent basis `t1 = [n_z, 0, −n_x]`, `t2 = ŷ` of a ground normal in the wheel's `(x, z)`
/// plane (the ground is extruded along the axis `y`, so `n_y = 0`).
fn tangents(n: &[f64; 3]) -> ([f64; 3], [f64; 3]) {
    ([n[2], 0.0, -n[0]], [0.0, 1.0, 0.0])
}

/// The local Delassus matrix of the candidates, gathered lazily from the cached columns:
/// rows `(g_k, u1_k, u2_k)`, columns `(λ_l, f1_l, f2_l)`,
///
/// ```text
///   D_N,kl = β_N h² n_kᵀ Y_kl R_l (+ 1/k_penalty on the diagonal),
///   D_T,kl = γ_N h t_kᵀ (Y_kl + (η × s_k) X_θ,l) R_l,     R_l = [n_l t1_l t2_l],
/// ```
///
/// where `Y_kl` moves contact node k under a unit force on node l (end-of-step displacement per
/// unit `Δz̈`) and `(η × s_k) X_θ,l` is the rigid spin part of the material velocity (E15).
struct TireDelassus<'b> {
    fac: &'b Factor,
    red: &'b ReducedTire,
    cand: &'b [usize],
    gp: &'b [GroundPoint],
    /// Local frames `[n, t1, t2]` of the candidates, scaled by `β_N h²` (row n) and `γ_N h`
    /// (rows t1, t2).
    frames: &'b [[[f64; 3]; 3]],
    /// `γ_N h t1ᵀ(η × s)` per candidate (`t2ᵀ(η × s) = 0`).
    rig_t1: &'b [f64],
    penalty: f64,
    tct: &'b Mat<f64>,
    tct_theta: &'b Mat<f64>,
    z_free: &'b [f64],
    zd_free: &'b [f64],
    spin_free: f64,
}

/// The scaled frames and rigid-spin coefficients of the candidates for [`TireDelassus`].
fn candidate_frames(
    red: &ReducedTire,
    cand: &[usize],
    gp: &[GroundPoint],
    c1: f64,
    c2: f64,
    frames: &mut Vec<[[f64; 3]; 3]>,
    rig_t1: &mut Vec<f64>,
) {
    frames.clear();
    rig_t1.clear();
    for (k, &i) in cand.iter().enumerate() {
        let n = gp[k].normal;
        let (t1, t2) = tangents(&n);
        frames.push([
            [c2 * n[0], c2 * n[1], c2 * n[2]],
            [c1 * t1[0], c1 * t1[1], c1 * t1[2]],
            [c1 * t2[0], c1 * t2[1], c1 * t2[2]],
        ]);
        let s = red.contact_positions[i];
        rig_t1.push(c1 * (t1[0] * s[2] - t1[2] * s[0]));
    }
}

impl TireDelassus<'_> {
    /// Unit force directions `[n, t1, t2]` of candidate `l`.
    fn directions(&self, l: usize) -> [[f64; 3]; 3] {
        let n = self.gp[l].normal;
        let (t1, t2) = tangents(&n);
        [n, t1, t2]
    }

    /// Local outputs of node `k` for a unit force `e` (wheel frame) on node `l`.
    fn response(&self, k: usize, l: usize, e: &[f64; 3]) -> [f64; 3] {
        let (i, j) = (self.cand[k], self.cand[l]);
        let mut v = [0.0; 3];
        let mut xth = 0.0;
        for (r, er) in e.iter().enumerate() {
            let col = col_slice(&self.fac.y, 3 * j + r);
            v[0] += er * col[3 * i];
            v[1] += er * col[3 * i + 1];
            v[2] += er * col[3 * i + 2];
            xth += er * self.fac.x[(0, 3 * j + r)];
        }
        let f = &self.frames[k];
        [
            dot3(&f[0], &v),
            dot3(&f[1], &v) + self.rig_t1[k] * xth,
            dot3(&f[2], &v),
        ]
    }

    /// The diagonal compliances `[D_N,kk, (D_T,kk,11 + D_T,kk,22)/2]` of node `k`.
    fn diagonal(&self, k: usize) -> [f64; 2] {
        let e = self.directions(k);
        let dn = self.response(k, k, &e[0])[0] + self.penalty;
        let d1 = self.response(k, k, &e[1])[1];
        let d2 = self.response(k, k, &e[2])[2];
        [dn, 0.5 * (d1 + d2)]
    }
}

impl DelassusSource for TireDelassus<'_> {
    fn columns(&mut self, l: usize, cols: &mut [f64]) {
        let ld = 3 * self.cand.len();
        let e = self.directions(l);
        let j = self.cand[l];
        // the three Y columns of node l combined along the unit force directions:
        // Y e_c = Σ_r e_c[r] Y[:, 3j + r], and X_θ e_c
        let (y0, y1, y2) = (
            col_slice(&self.fac.y, 3 * j),
            col_slice(&self.fac.y, 3 * j + 1),
            col_slice(&self.fac.y, 3 * j + 2),
        );
        let mut xth = [0.0; 3];
        for (c, ec) in e.iter().enumerate() {
            for (r, er) in ec.iter().enumerate() {
                xth[c] += er * self.fac.x[(0, 3 * j + r)];
            }
        }
        // planar ground (n_y = 0): n and t1 lie in the (x, z) plane, t2 = ŷ, so each frame
        // vector has two (n, t1) or one (t2) nonzero component
        let (nx, nz) = (e[0][0], e[0][2]);
        for (k, &i) in self.cand.iter().enumerate() {
            let a = &y0[3 * i..3 * i + 3];
            let b = &y1[3 * i..3 * i + 3];
            let c3 = &y2[3 * i..3 * i + 3];
            let f = &self.frames[k];
            let (fnx, fnz, ftx, ftz, fy) = (f[0][0], f[0][2], f[1][0], f[1][2], f[2][1]);
            let rig = self.rig_t1[k];
            // unit force along n, t1 (combinations of Y columns 0 and 2) and ŷ (column 1)
            let vs = [
                [
                    nx * a[0] + nz * c3[0],
                    nx * a[1] + nz * c3[1],
                    nx * a[2] + nz * c3[2],
                ],
                [
                    nz * a[0] - nx * c3[0],
                    nz * a[1] - nx * c3[1],
                    nz * a[2] - nx * c3[2],
                ],
                [b[0], b[1], b[2]],
            ];
            for (c, v) in vs.iter().enumerate() {
                let o = &mut cols[c * ld + 3 * k..c * ld + 3 * k + 3];
                o[0] = fnx * v[0] + fnz * v[2];
                o[1] = ftx * v[0] + ftz * v[2] + rig * xth[c];
                o[2] = fy * v[1];
            }
        }
        cols[3 * l] += self.penalty;
    }

    fn free_slip(&mut self, k: usize) -> [f64; 2] {
        let i = self.cand[k];
        let s = self.red.contact_positions[i];
        let sf = self.spin_free;
        let rig = [sf * s[2], 0.0, -sf * s[0]];
        let mut v = [0.0; 3];
        for (a, va) in v.iter_mut().enumerate() {
            let c = 3 * i + a;
            let vc = dot(col_slice(self.tct, c), self.zd_free);
            let vt = dot(col_slice(self.tct_theta, c), self.z_free);
            *va = rig[a] + vc + sf * vt - self.gp[k].velocity[a];
        }
        let (t1, t2) = tangents(&self.gp[k].normal);
        [dot3(&t1, &v), dot3(&t2, &v)]
    }
}

impl<'a> RollingTire<'a> {
    /// A tire at the preload coordinates `z0`, spinning at `spin` \[rad/s\], with Rayleigh
    /// coefficients `alpha`, `beta`.
    pub fn new(
        red: &'a ReducedTire,
        cfg: RollingConfig,
        ground: Ground,
        alpha: f64,
        beta: f64,
        z0: Vec<f64>,
        spin: f64,
    ) -> Result<Self, TireError> {
        cfg.validate()?;
        ground.cfg.validate()?;
        let nz = red.n_z();
        if z0.len() != nz {
            return Err(invalid(
                "initial coordinates",
                format!("{} values for {nz} coordinates", z0.len()),
            ));
        }
        let nc = red.n_contact();
        let n = nz + 1;
        let work = Work {
            pred: vec![0.0; 3 * nz],
            known: vec![0.0; nz],
            a: vec![0.0; n],
            tmp: vec![0.0; n],
            z_free: vec![0.0; nz],
            zd_free: vec![0.0; nz],
            dc: vec![0.0; 3 * nc],
            cand: Vec::with_capacity(nc),
            was_cand: vec![true; nc],
            gp: Vec::with_capacity(nc),
            lambda: Vec::with_capacity(nc),
            ft: Vec::with_capacity(nc),
            forces: Vec::with_capacity(nc),
            x0: Vec::with_capacity(3 * nc),
            x1: Vec::with_capacity(3 * nc),
            x2: Vec::with_capacity(3 * nc),
            lambda2: vec![0.0; nc],
            friction2: vec![[0.0; 3]; nc],
            diag: Vec::with_capacity(nc),
            frames: Vec::with_capacity(nc),
            rig_t1: Vec::with_capacity(nc),
            solver: ContactSolver::default(),
        };
        Ok(Self {
            red,
            cfg,
            ground,
            alpha,
            beta,
            drive_torque: 0.0,
            state: RollingState {
                t: 0.0,
                z: z0,
                zd: vec![0.0; nz],
                zdd: vec![0.0; nz],
                acc: vec![0.0; nz],
                theta: 0.0,
                theta_d: spin,
                theta_dd: 0.0,
                theta_acc: 0.0,
                lambda: vec![0.0; nc],
                friction: vec![[0.0; 3]; nc],
                contact_force: [0.0; 3],
            },
            factor: None,
            spare: None,
            tct: red.tc.transpose().to_owned(),
            tct_theta: red.tc_theta.transpose().to_owned(),
            work,
            refactors: 0,
            stats: StepStats::default(),
            cleat_contacts: 0,
        })
    }

    /// Change the time step `h` \[s\] for the following steps (e.g. sub-steps through an impact).
    /// The generalized-α scheme takes variable steps as they come; the iteration matrix of the
    /// previous step size is kept, so switching back and forth between two step sizes inverts
    /// each only once. Errors: `h` not positive.
    pub fn set_time_step(&mut self, h: f64) -> Result<(), TireError> {
        if !(h > 0.0 && h.is_finite()) {
            return Err(invalid("rolling.time_step", format!("{h} is not positive")));
        }
        if h == self.cfg.time_step {
            return Ok(());
        }
        self.cfg.time_step = h;
        if self.spare.as_ref().is_some_and(|f| f.h == h) {
            std::mem::swap(&mut self.factor, &mut self.spare);
        } else {
            self.spare = self.factor.take();
        }
        Ok(())
    }

    /// Settings.
    pub fn config(&self) -> &RollingConfig {
        &self.cfg
    }

    fn spin_inertia(&self) -> f64 {
        self.cfg.wheel_spin_inertia + self.red.rim_spin_inertia
    }

    /// Form `R` at the spin rate `spin`: row 0 = rim moment about the axis
    /// (`β K_θ ż + (K_θ + β θ̇ K_θ,θ) z`), rows 1.. = `[C_eff  K_eff  G₁]` with
    /// `C_eff = 2θ̇G₁ + αM + βK`, `K_eff = K + θ̇²G₂ + βθ̇K₁` (Ribaric (7.17) with U15–U17).
    fn form_r(f: &mut Factor, red: &ReducedTire, alpha: f64, beta: f64, spin: f64) {
        let nz = red.n_z();
        let (a, b) = (alpha, beta);
        f.spin = spin;
        let kt = red.kt.row(1);
        let kt1 = red.kt1.row(1);
        for j in 0..nz {
            f.rt[(j, 0)] = b * kt[j];
            f.rt[(nz + j, 0)] = kt[j] + b * spin * kt1[j];
            f.rt[(2 * nz + j, 0)] = 0.0;
        }
        // column i of Rᵀ = row 1 + i of R (contiguous writes)
        for i in 0..nz {
            let mut col = f.rt.col_mut(1 + i);
            for j in 0..nz {
                col[j] = 2.0 * spin * red.g1[(i, j)] + a * red.m[(i, j)] + b * red.k[(i, j)];
                col[nz + j] =
                    red.k[(i, j)] + spin * spin * red.g2[(i, j)] + b * spin * red.k1[(i, j)];
                col[2 * nz + j] = red.g1[(i, j)];
            }
        }
    }

    /// Invert the Newmark iteration matrix
    /// `S = [J  γh r₀ᶜ + βh² r₀ᵏ; m_θ  M + γh C_eff + βh² K_eff]` at the spin rate `spin_s`
    /// and compute the contact-node responses `X = S⁻¹[0; T_cᵀ]`, `Y = T_c X_z`.
    fn invert_s(&mut self, spin_s: f64) -> Result<(), TireError> {
        let red = self.red;
        let nz = red.n_z();
        let n = nz + 1;
        let nc3 = 3 * red.n_contact();
        let h = self.cfg.time_step;
        let (bn, gn) = self.cfg.implicit_coefficients();
        let sp = spin_s;
        let mut f = match self.factor.take() {
            Some(f) => f,
            None => Factor {
                h,
                spin: sp,
                spin_s: sp,
                sinv_t: Mat::zeros(n, n),
                rt: Mat::zeros(3 * nz, n),
                x: Mat::zeros(n, nc3),
                y: Mat::zeros(nc3, nc3),
            },
        };
        // R at the same spin rate: its C_eff and K_eff blocks (row 0: the spin row) form S
        Self::form_r(&mut f, red, self.alpha, self.beta, sp);
        let rt = &f.rt;
        let mut smat = Mat::<f64>::zeros(n, n);
        smat[(0, 0)] = self.spin_inertia();
        for j in 0..nz {
            smat[(0, 1 + j)] = gn * h * rt[(j, 0)] + bn * h * h * rt[(nz + j, 0)];
            smat[(1 + j, 0)] = red.m_theta[j];
        }
        for i in 0..nz {
            let row = rt.col(1 + i);
            for j in 0..nz {
                smat[(1 + i, 1 + j)] = red.m[(i, j)] + gn * h * row[j] + bn * h * h * row[nz + j];
            }
        }
        let sinv = smat.partial_piv_lu().solve(Mat::<f64>::identity(n, n));
        if !sinv.col_iter().all(|c| c.iter().all(|v| v.is_finite())) {
            self.factor = Some(f);
            return Err(TireError::Simulation {
                time: self.state.t,
                reason: "the Newmark iteration matrix is singular".into(),
            });
        }
        f.spin_s = sp;
        f.h = h;
        f.sinv_t.copy_from(sinv.transpose());
        matmul(
            f.x.as_mut(),
            Accum::Replace,
            sinv.as_ref().subcols(1, nz),
            self.tct.as_ref(),
            1.0,
            Par::Seq,
        );
        matmul(
            f.y.as_mut(),
            Accum::Replace,
            red.tc.as_ref(),
            f.x.as_ref().subrows(1, nz),
            1.0,
            Par::Seq,
        );
        self.factor = Some(f);
        self.refactors += 1;
        self.stats.columns += red.n_contact();
        Ok(())
    }

    /// Spindle force of the tire on the wheel in the current state, by
    /// [`RollingConfig::spindle_force`]: Newton's second law for the tire (default) or the rim
    /// forces of Ribaric (7.2). See the module documentation.
    pub fn spindle_force(&self) -> SpindleForce {
        let f = match self.cfg.spindle_force {
            SpindleForceMethod::Momentum => self.spindle_force_momentum(),
            SpindleForceMethod::Rim => self.spindle_force_rim(),
        };
        SpindleForce {
            fx: f[0],
            fy: f[2],
            fz: f[1],
        }
    }

    /// The rim forces (7.2): `F = −K_r (z + β ż) − β θ̇ K_r,θ z` (wheel frame).
    fn spindle_force_rim(&self) -> [f64; 3] {
        let red = self.red;
        let st = &self.state;
        let b = self.beta;
        let mut f = [0.0; 3];
        for (c, fc) in f.iter_mut().enumerate() {
            let kr = red.kr.row(c);
            let kr1 = red.kr1.row(c);
            let mut s = 0.0;
            for j in 0..red.n_z() {
                s += kr[j] * (st.z[j] + b * st.zd[j]) + b * st.theta_d * kr1[j] * st.z[j];
            }
            *fc = -s;
        }
        f
    }

    /// Newton's second law for the tire (wheel frame): with the absolute acceleration of the
    /// material (module docs) and the mass-proportional damping force `αM T ż`,
    /// `F = Σ fᶜ − [P z̈ + θ̈ (P₁ z + eᵀM s_,θ) + θ̇² (P₂ z + eᵀM s_,θθ) + 2θ̇ P₁ ż] − α P ż`.
    /// (Summing the tire's nodal equations and using `K e = 0` for the rigid translation `e`
    /// turns the elastic and stiffness-damping forces into the rim forces of (7.2), so both
    /// forms agree for the untruncated model.)
    fn spindle_force_momentum(&self) -> [f64; 3] {
        let red = self.red;
        let st = &self.state;
        let (w, w2) = (st.theta_d, st.theta_d * st.theta_d);
        let mut f = [0.0; 3];
        for (c, fc) in f.iter_mut().enumerate() {
            let (p, p1, p2) = (red.p_e.row(c), red.p_e1.row(c), red.p_e2.row(c));
            let mut inertia = st.theta_dd * red.p_s[0][c] + w2 * red.p_s[1][c];
            for j in 0..red.n_z() {
                inertia += p[j] * (st.zdd[j] + self.alpha * st.zd[j])
                    + p1[j] * (st.theta_dd * st.z[j] + 2.0 * w * st.zd[j])
                    + w2 * p2[j] * st.z[j];
            }
            *fc = st.contact_force[c] - inertia;
        }
        f
    }

    /// Deformed contact-node positions `sᵢ + (T_c z)ᵢ` \[m\].
    pub fn contact_positions(&self) -> Vec<[f64; 3]> {
        let mut d = vec![0.0; self.red.tc.nrows()];
        matvec(self.red.tc.as_ref(), &self.state.z, &mut d);
        self.red
            .contact_positions
            .iter()
            .enumerate()
            .map(|(i, s)| [s[0] + d[3 * i], s[1] + d[3 * i + 1], s[2] + d[3 * i + 2]])
            .collect()
    }

    /// Advance one time step.
    ///
    /// Cost per step: one product with `R` (n × 3 n_z), one LU solve, `T_c z` for the
    /// candidate search, and the candidate rows of the cached `Y`, `X`; the iteration matrix is
    /// refactorised only when θ̇ drifts by more than `spin_tolerance`.
    pub fn step(&mut self) -> Result<(), TireError> {
        let red = self.red;
        let nz = red.n_z();
        let nc = red.n_contact();
        // Generalized-α (Arnold–Brüls form): with the pseudo-accelerations a,
        //   zₙ₊₁ = zₙ + h żₙ + h²(½ − β) aₙ + h² β aₙ₊₁,   żₙ₊₁ = żₙ + h(1 − γ) aₙ + h γ aₙ₊₁,
        //   (1 − α_m) aₙ₊₁ = (1 − α_f) z̈ₙ₊₁ + α_f z̈ₙ − α_m aₙ,
        // and the equations of motion at tₙ₊₁. Eliminating aₙ₊₁ leaves a Newmark-like step in
        // z̈ₙ₊₁ with the coefficients (β', γ') = (β, γ)(1 − α_f)/(1 − α_m) and the known part
        // wₙ = (α_f z̈ₙ − α_m aₙ)/(1 − α_m) in the predictors.
        let h = self.cfg.time_step;
        let (bn0, gn0) = (self.cfg.newmark_beta, self.cfg.newmark_gamma);
        let (bn, gn) = self.cfg.implicit_coefficients();
        let (am, af) = (self.cfg.alpha_m, self.cfg.alpha_f);
        let known = |zdd: f64, acc: f64| (af * zdd - am * acc) / (1.0 - am);
        let w_theta = known(self.state.theta_dd, self.state.theta_acc);
        let spin_pred =
            self.state.theta_d + h * ((1.0 - gn0) * self.state.theta_acc + gn0 * w_theta);
        let drift = |s: f64, tol: f64| (spin_pred - s).abs() > tol * s.abs().max(1.0);
        let (need_s, need_r) = match &self.factor {
            None => (true, true),
            Some(f) => (
                f.h != h || drift(f.spin_s, self.cfg.matrix_tolerance),
                drift(f.spin, self.cfg.spin_tolerance),
            ),
        };
        let clk = std::time::Instant::now();
        if need_s {
            self.invert_s(spin_pred)?;
        }
        let c0 = clk.elapsed().as_secs_f64();
        if need_r && !need_s {
            if let Some(f) = self.factor.as_mut() {
                Self::form_r(f, red, self.alpha, self.beta, spin_pred);
            }
            self.stats.force_matrix_updates += 1;
        }
        let c_r = clk.elapsed().as_secs_f64();
        self.stats.seconds[2] += c_r - c0;
        let cb;
        let t1 = self.state.t + h;
        {
            let Some(fac) = self.factor.as_ref() else {
                return Err(TireError::Simulation {
                    time: self.state.t,
                    reason: "no factorisation".into(),
                });
            };
            let st = &self.state;
            let w = &mut self.work;
            // Predictors [ż̃; z̃] and the lagged θ̈ z of the G₁ z θ̈ term. `S` was inverted at
            // θ̇_S, `R` formed at θ̇_R: the gyroscopic difference S(θ̇_R) − S(θ̇_S) =
            // 2γh(θ̇_R − θ̇_S)G₁ (z rows and columns) is applied to the previous step's z̈ through
            // the G₁ block of R (one-step lag, like the θ̈ z term). The remaining differences,
            // βh²[(θ̇_R² − θ̇_S²)G₂ + β(θ̇_R − θ̇_S)K₁] and the β θ̇ K_θ,θ term of the spin row, are
            // smaller by the factor h θ̇ β_N/γ_N ≈ 3e-3 at 60 km/h and h = 0.2 ms and are not
            // corrected (the test `frozen_iteration_matrix_matches_exact_newmark` bounds the
            // effect).
            let lag = 2.0 * gn * h * (fac.spin - fac.spin_s);
            for j in 0..nz {
                let (acc, wj) = (st.acc[j], known(st.zdd[j], st.acc[j]));
                w.known[j] = wj;
                w.pred[j] = st.zd[j] + h * ((1.0 - gn0) * acc + gn0 * wj);
                w.pred[nz + j] = st.z[j] + h * st.zd[j] + h * h * ((0.5 - bn0) * acc + bn0 * wj);
                w.pred[2 * nz + j] = st.theta_dd * st.z[j] + lag * st.zdd[j];
            }
            // S a = [τ; −θ̇²c_s] − R [ż̃; z̃; θ̈ z]
            matvec(fac.rt.as_ref().transpose(), &w.pred, &mut w.tmp);
            w.tmp[0] = self.drive_torque - w.tmp[0];
            for j in 0..nz {
                w.tmp[1 + j] = -spin_pred * spin_pred * red.c_s[j] - w.tmp[1 + j];
            }
            matvec(fac.sinv_t.as_ref().transpose(), &w.tmp, &mut w.a);
            for j in 0..nz {
                w.z_free[j] = w.pred[nz + j] + bn * h * h * w.a[1 + j];
                w.zd_free[j] = w.pred[j] + gn * h * w.a[1 + j];
            }
            cb = clk.elapsed().as_secs_f64();
            self.stats.seconds[0] += cb - c_r;
            matvec(self.tct.as_ref().transpose(), &w.z_free, &mut w.dc);
            // candidates
            w.cand.clear();
            w.gp.clear();
            for i in 0..nc {
                let s = red.contact_positions[i];
                let p = [
                    s[0] + w.dc[3 * i],
                    s[1] + w.dc[3 * i + 1],
                    s[2] + w.dc[3 * i + 2],
                ];
                let g = self.ground.query(t1, p);
                // the cleat's faces approach the nodes at up to the surface speed
                let margin = if g.on_cleat {
                    self.cfg.contact_margin + h * self.ground.speed.abs()
                } else {
                    self.cfg.contact_margin
                };
                if g.gap < margin {
                    if g.gap < -self.cfg.contact_margin && !w.was_cand[i] {
                        self.stats.late_contacts += 1;
                    }
                    w.cand.push(i);
                    w.gp.push(g);
                }
            }
        }
        let c2 = clk.elapsed().as_secs_f64();
        self.stats.seconds[1] += c2 - cb;
        let spin_free = spin_pred + gn * h * self.work.a[0];
        self.solve_contact(t1, spin_free)?;
        self.stats.seconds[3] += clk.elapsed().as_secs_f64() - c2;
        self.stats.seconds[4] += c0;
        let Some(fac) = self.factor.as_ref() else {
            return Err(TireError::Simulation {
                time: self.state.t,
                reason: "no factorisation".into(),
            });
        };
        let w = &mut self.work;
        // contact correction a += X Σ fⱼ
        for (k, &j) in w.cand.iter().enumerate() {
            for b in 0..3 {
                let c = w.forces[k][b];
                if c == 0.0 {
                    continue;
                }
                axpy(c, col_slice(&fac.x, 3 * j + b), &mut w.a);
            }
        }
        let st = &mut self.state;
        let theta_dd = w.a[0];
        let r = (1.0 - af) / (1.0 - am);
        let theta_acc = w_theta + r * theta_dd;
        st.theta += h * st.theta_d + h * h * ((0.5 - bn0) * st.theta_acc + bn0 * theta_acc);
        st.theta_d = spin_pred + gn * h * theta_dd;
        st.theta_dd = theta_dd;
        st.theta_acc = theta_acc;
        for j in 0..nz {
            let a = w.a[1 + j];
            st.acc[j] = w.known[j] + r * a;
            st.zdd[j] = a;
            st.z[j] = w.pred[nz + j] + bn * h * h * a;
            st.zd[j] = w.pred[j] + gn * h * a;
        }
        st.lambda.iter_mut().for_each(|l| *l = 0.0);
        st.friction.iter_mut().for_each(|f| *f = [0.0; 3]);
        st.contact_force = [0.0; 3];
        for f in &w.forces {
            for b in 0..3 {
                st.contact_force[b] += f[b];
            }
        }
        w.was_cand.iter_mut().for_each(|c| *c = false);
        for &i in &w.cand {
            w.was_cand[i] = true;
        }
        for (k, &i) in w.cand.iter().enumerate() {
            st.lambda[i] = w.lambda[k];
            st.friction[i] = w.ft[k];
        }
        st.t = t1;
        self.stats.steps += 1;
        self.stats.candidates += w.cand.len();
        self.stats.active += w.lambda.iter().filter(|&&l| l > 0.0).count();
        self.cleat_contacts = (0..w.cand.len())
            .filter(|&k| w.lambda[k] > 0.0 && w.gp[k].on_cleat)
            .count();
        if !(st.theta_d.is_finite() && st.z.iter().all(|v| v.is_finite())) {
            return Err(TireError::Simulation {
                time: t1,
                reason: "the state became non-finite".into(),
            });
        }
        Ok(())
    }

    /// The contact problem of the candidates in `work`: normal contact and friction coupled,
    /// solved by the semismooth Newton method of [`ContactSolver`] on the local Delassus
    /// matrix (gathered lazily from the cached `Y`, `X`), warm-started from the previous
    /// step's forces; leaves the contact forces in `work.forces`.
    fn solve_contact(&mut self, t1: f64, spin_free: f64) -> Result<(), TireError> {
        let red = self.red;
        let h = self.cfg.time_step;
        let (bn, gn) = self.cfg.implicit_coefficients();
        let Some(fac) = self.factor.as_ref() else {
            return Ok(());
        };
        let w = &mut self.work;
        let m = w.cand.len();
        let law = self
            .cfg
            .friction_law
            .law(self.cfg.friction, self.cfg.slip_regularization);
        let mu = law.coefficient();
        w.lambda.clear();
        w.ft.clear();
        w.forces.clear();
        if m == 0 {
            return Ok(());
        }
        // warm starts: the forces of the last step and of the one before (contact nodes at the
        // patch edges chatter with period two), in the local frames (n, t1, t2)
        w.x0.clear();
        w.x1.clear();
        for (k, &i) in w.cand.iter().enumerate() {
            let (t1v, t2v) = tangents(&w.gp[k].normal);
            for (x, lam, f) in [
                (&mut w.x0, self.state.lambda[i], self.state.friction[i]),
                (&mut w.x1, w.lambda2[i], w.friction2[i]),
            ] {
                let f = if mu > 0.0 { f } else { [0.0; 3] };
                x.extend([lam, dot3(&t1v, &f), dot3(&t2v, &f)]);
            }
        }
        // and the linear extrapolation of the last two
        w.x2.clear();
        w.x2.extend(w.x0.iter().zip(&w.x1).map(|(a, b)| 2.0 * a - b));
        w.lambda2.copy_from_slice(&self.state.lambda);
        w.friction2.copy_from_slice(&self.state.friction);
        let penalty = match self.cfg.normal {
            NormalContact::Penalty { stiffness } => 1.0 / stiffness,
            NormalContact::Lagrange => 0.0,
        };
        let (c1, c2) = (gn * h, bn * h * h);
        candidate_frames(red, &w.cand, &w.gp, c1, c2, &mut w.frames, &mut w.rig_t1);
        let mut src = TireDelassus {
            fac,
            red,
            cand: &w.cand,
            gp: &w.gp,
            frames: &w.frames,
            rig_t1: &w.rig_t1,
            penalty,
            tct: &self.tct,
            tct_theta: &self.tct_theta,
            z_free: &w.z_free,
            zd_free: &w.zd_free,
            spin_free,
        };
        w.diag.clear();
        for k in 0..m {
            w.diag.push(src.diagonal(k));
        }
        w.solver.reset(&w.x0);
        w.solver.set_gaps(w.gp.iter().map(|g| g.gap));
        let settings = SolveOptions {
            law,
            tol: self.cfg.contact_tolerance,
            ..SolveOptions::default()
        };
        // same candidates as in the last step: its Newton matrix may serve for chord steps
        let same = w.cand.iter().all(|&i| w.was_cand[i])
            && w.cand.len() == w.was_cand.iter().filter(|&&c| c).count();
        let alts = [&w.x1[..], &w.x2[..]];
        let rep = w.solver.solve(
            &mut src,
            &w.diag,
            &settings,
            same,
            if same { &alts[..] } else { &[] },
        );
        self.stats.contact_newton += rep.newton_iterations;
        self.stats.contact_chord += rep.chord_iterations;
        self.stats.lcp_solves += rep.lcp_solves;
        self.stats.friction_sweeps += rep.sweeps;
        if rep.fallback {
            self.stats.contact_fallbacks += 1;
        }
        if !rep.converged {
            self.stats.contact_unconverged += 1;
        }
        let x = w.solver.x();
        if !x.iter().all(|v| v.is_finite()) {
            return Err(TireError::Simulation {
                time: t1,
                reason: "the contact forces became non-finite".into(),
            });
        }
        for k in 0..m {
            let n = w.gp[k].normal;
            let (t1v, t2v) = tangents(&n);
            let (l, f1, f2) = (x[3 * k], x[3 * k + 1], x[3 * k + 2]);
            let ft = [
                f1 * t1v[0] + f2 * t2v[0],
                f1 * t1v[1] + f2 * t2v[1],
                f1 * t1v[2] + f2 * t2v[2],
            ];
            w.lambda.push(l);
            w.ft.push(ft);
            w.forces
                .push([n[0] * l + ft[0], n[1] * l + ft[1], n[2] * l + ft[2]]);
        }
        Ok(())
    }

    /// Total normal contact force vector `Σ λᵢ nᵢ`-weighted vertical component \[N\] (the
    /// vertical force the ground exerts, friction excluded).
    pub fn total_normal_force(&self) -> f64 {
        self.state.lambda.iter().sum()
    }

    /// Number of contact nodes in contact.
    pub fn active_count(&self) -> usize {
        self.state.lambda.iter().filter(|&&l| l > 0.0).count()
    }

    /// The spin-row coefficients `[β K_θ; K_θ + β θ̇ K_θ,θ]` of the current factorisation (for
    /// diagnostics).
    pub fn spin_row(&self) -> Option<Vec<f64>> {
        let nz = self.red.n_z();
        self.factor
            .as_ref()
            .map(|f| (0..2 * nz).map(|j| f.rt[(j, 0)]).collect())
    }
}
