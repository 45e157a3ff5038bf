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
//! `F = −(K_r δ + β K_r δ̇)` (7.2).
//!
//! # Contact (E15)
//! A contact node `i` at mesh position `xᵢ = sᵢ + (T_c z)ᵢ` is constrained by its gap `gᵢ ≥ 0`
//! (closest point on the drum/road/cleat), with multiplier `λᵢ ≥ 0` along the normal `nᵢ`; the
//! friction force of Coulomb slip without stick is `−μ λᵢ t̂ᵢ` along the slip of the material
//! over the ground, `vᵢ = θ̇ η × sᵢ + (T_c ż + θ̇ T_c,θ z)ᵢ − u_ground`, regularised as
//! `t̂ = v_t/√(|v_t|² + ε²)` (U20). The penalty option replaces the rigid constraint by a
//! compliance `1/k` on the diagonal of the contact problem.
//!
//! # Integration
//! Newmark (β_N, γ_N) with the contact gaps imposed at the end of each step (index-3), a
//! linearly implicit step. The θ̇-dependent gyroscopic/centrifugal/damping matrix
//! `R = [C_eff K_eff G₁]` is evaluated at a spin rate frozen until it drifts by more than
//! `spin_tolerance` (then re-formed: cheap). The iteration matrix
//! `S = [J ⋯; m_θ M + γh C_eff + βh² K_eff]` is inverted explicitly, together with the contact
//! responses `X = S⁻¹[0; T_cᵀ]` and `Y = T_c X_z` of all contact nodes, only when θ̇ drifts by
//! more than `matrix_tolerance` (10 %: once per run at constant speed); in between, the
//! gyroscopic part `2γh(θ̇_R − θ̇_S)G₁` of `S(θ̇_R) − S(θ̇_S)` is applied to the previous step's
//! accelerations, like the lagged term `G₁ z θ̈`. The normal (LCP) and friction (projected
//! Gauss–Seidel) problems are alternated up to three times per step. Per step the cost is one
//! product with `R` (n × 3 n_z), one with `S⁻¹` (n × n), `T_c z` for the candidate search, and
//! work on the candidates only (gathers from `Y` and `X`); nothing is allocated once the work
//! arrays have grown. Candidates are the nodes whose free
//! gap is below `contact_margin` (plus `h v` in front of the cleat, whose faces approach at the
//! surface speed); [`StepStats::late_contacts`] counts nodes that were missed.

use super::error::{TireError, invalid};
use super::ground::{Ground, GroundPoint};
use super::lcp::LcpWork;
use super::reduced::ReducedTire;
use faer::linalg::matmul::matmul;
use faer::prelude::*;
use faer::{Accum, Mat, Par};
use serde::{Deserialize, Serialize};

/// Normal contact law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "law", deny_unknown_fields)]
pub enum NormalContact {
    /// Rigid unilateral constraint with Lagrange multipliers (Ribaric §7.3).
    Lagrange,
    /// Linear penalty `λ = k · penetration` [N/m].
    Penalty {
        /// Stiffness per contact node [N/m].
        stiffness: f64,
    },
}

/// Integration and contact settings of the rolling tire.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RollingConfig {
    /// Time step `h` [s].
    pub time_step: f64,
    /// Newmark β.
    pub newmark_beta: f64,
    /// Newmark γ.
    pub newmark_gamma: f64,
    /// Coulomb friction coefficient μ (Ribaric §8.4.3: 0.85 nominal, 0 pure slip).
    pub friction: f64,
    /// Slip-velocity regularisation ε of the Coulomb direction [m/s].
    pub slip_regularization: f64,
    /// Normal contact law.
    pub normal: NormalContact,
    /// Spin inertia of the wheel (without the rim nodes, which are added) [kg·m²].
    pub wheel_spin_inertia: f64,
    /// Relative drift of θ̇ at which the spin-dependent force matrix `R` (gyroscopic,
    /// centrifugal and damping terms) is re-formed.
    pub spin_tolerance: f64,
    /// Relative drift of θ̇ at which the iteration matrix `S` is inverted again; between
    /// inversions its gyroscopic part `2γh(θ̇_R − θ̇_S)G₁` is lagged by one step (see
    /// [`RollingTire::step`]).
    pub matrix_tolerance: f64,
    /// Contact-node candidates: gap below this margin [m] (plus `h·v` for nodes facing the
    /// cleat, whose faces approach at up to the surface speed `v`).
    pub contact_margin: f64,
}

impl Default for RollingConfig {
    fn default() -> Self {
        Self {
            time_step: 2e-4,
            newmark_beta: 0.25,
            newmark_gamma: 0.5,
            friction: 0.85,
            slip_regularization: 0.05,
            normal: NormalContact::Lagrange,
            wheel_spin_inertia: 2.0,
            spin_tolerance: 1e-2,
            matrix_tolerance: 0.1,
            contact_margin: 0.0005,
        }
    }
}

impl RollingConfig {
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
        pos("slip_regularization", self.slip_regularization)?;
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
        Ok(())
    }
}

/// State of the rolling tire.
#[derive(Debug, Clone)]
pub struct RollingState {
    /// Time [s].
    pub t: f64,
    /// Reduced coordinates `z`.
    pub z: Vec<f64>,
    /// Their rates `ż`.
    pub zd: Vec<f64>,
    /// Their accelerations `z̈`.
    pub zdd: Vec<f64>,
    /// Wheel spin angle θ [rad].
    pub theta: f64,
    /// Spin rate θ̇ [rad/s].
    pub theta_d: f64,
    /// Spin acceleration θ̈ [rad/s²].
    pub theta_dd: f64,
    /// Normal multiplier per contact node [N].
    pub lambda: Vec<f64>,
    /// Friction force per contact node (wheel frame) [N].
    pub friction: Vec<[f64; 3]>,
}

/// Spindle force of the tire on the wheel, in the output frame of U18.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpindleForce {
    /// Longitudinal `F_x` [N].
    pub fx: f64,
    /// Vertical `F_y` (up positive: the carried load) [N].
    pub fy: f64,
    /// Lateral (along the wheel axis) [N].
    pub fz: f64,
}

/// The inverted Newmark iteration matrix `S` (at the spin rate `spin_s`), the spin-dependent
/// force matrix `R` (at the spin rate `spin`) and the responses of the contact nodes.
///
/// `S⁻¹` and `R` are stored transposed so that their products with a vector run over contiguous
/// rows (dot products), which is faster here than the column-major kernel: both products are
/// limited by memory traffic (R is 2.7 MB for the 341-DOF tire).
struct Factor {
    /// Spin rate at which `R` was formed [rad/s].
    spin: f64,
    /// Spin rate at which `S` was inverted [rad/s].
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
    warm: Vec<bool>,
    vfree: Vec<[f64; 3]>,
    vdone: Vec<bool>,
    /// Candidate blocks of `Y` and `Y_v` (3m × 3m, column-major).
    yc: Vec<f64>,
    yvc: Vec<f64>,
    q: Vec<f64>,
    dv: Vec<[f64; 3]>,
    act: Vec<usize>,
    forces: Vec<[f64; 3]>,
    w: Mat<f64>,
    lcp: LcpWork,
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
    /// Normal LCP solves.
    pub lcp_solves: usize,
    /// Friction Gauss–Seidel sweeps.
    pub friction_sweeps: usize,
    /// Contact-node column sets computed (`S⁻¹` columns of one node).
    pub columns: usize,
    /// Re-formings of the spin-dependent force matrix `R` (drift beyond `spin_tolerance`).
    pub force_matrix_updates: usize,
    /// Nodes found penetrating by more than the contact margin that were not candidates in the
    /// previous step (a candidate margin too small for the approach speed; should stay 0).
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
    /// Rayleigh α [1/s].
    pub alpha: f64,
    /// Rayleigh β [s].
    pub beta: f64,
    /// Drive torque about the wheel axis [N·m] (0: free-rolling spindle).
    pub drive_torque: f64,
    /// Current state.
    pub state: RollingState,
    factor: Option<Factor>,
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

/// 3 × 3 block `(i, j)` of the column-major `ld × ld` array `a` times `v`.
#[inline]
fn blk(a: &[f64], ld: usize, i: usize, j: usize, v: &[f64; 3]) -> [f64; 3] {
    let mut o = [0.0; 3];
    for (c, vc) in v.iter().enumerate() {
        let col = &a[(3 * j + c) * ld + 3 * i..(3 * j + c) * ld + 3 * i + 3];
        o[0] += col[0] * vc;
        o[1] += col[1] * vc;
        o[2] += col[2] * vc;
    }
    o
}

impl<'a> RollingTire<'a> {
    /// A tire at the preload coordinates `z0`, spinning at `spin` [rad/s], with Rayleigh
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
            warm: Vec::with_capacity(nc),
            vfree: Vec::with_capacity(nc),
            vdone: Vec::with_capacity(nc),
            yc: Vec::new(),
            yvc: Vec::new(),
            q: Vec::with_capacity(nc),
            dv: Vec::with_capacity(nc),
            act: Vec::with_capacity(nc),
            forces: Vec::with_capacity(nc),
            w: Mat::zeros(0, 0),
            lcp: LcpWork::default(),
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
                theta: 0.0,
                theta_d: spin,
                theta_dd: 0.0,
                lambda: vec![0.0; nc],
                friction: vec![[0.0; 3]; nc],
            },
            factor: None,
            tct: red.tc.transpose().to_owned(),
            tct_theta: red.tc_theta.transpose().to_owned(),
            work,
            refactors: 0,
            stats: StepStats::default(),
            cleat_contacts: 0,
        })
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
        let (h, bn, gn) = (
            self.cfg.time_step,
            self.cfg.newmark_beta,
            self.cfg.newmark_gamma,
        );
        let (a, b) = (self.alpha, self.beta);
        let sp = spin_s;
        let kt = red.kt.row(1);
        let kt1 = red.kt1.row(1);
        let mut smat = Mat::<f64>::zeros(n, n);
        smat[(0, 0)] = self.spin_inertia();
        for j in 0..nz {
            smat[(0, 1 + j)] = gn * h * b * kt[j] + bn * h * h * (kt[j] + b * sp * kt1[j]);
            smat[(1 + j, 0)] = red.m_theta[j];
            for i in 0..nz {
                let c = 2.0 * sp * red.g1[(i, j)] + a * red.m[(i, j)] + b * red.k[(i, j)];
                let k = red.k[(i, j)] + sp * sp * red.g2[(i, j)] + b * sp * red.k1[(i, j)];
                smat[(1 + i, 1 + j)] = red.m[(i, j)] + gn * h * c + bn * h * h * k;
            }
        }
        let sinv = smat.partial_piv_lu().solve(Mat::<f64>::identity(n, n));
        if !sinv.col_iter().all(|c| c.iter().all(|v| v.is_finite())) {
            return Err(TireError::Simulation {
                time: self.state.t,
                reason: "the Newmark iteration matrix is singular".into(),
            });
        }
        let mut f = match self.factor.take() {
            Some(f) => f,
            None => Factor {
                spin: sp,
                spin_s: sp,
                sinv_t: Mat::zeros(n, n),
                rt: Mat::zeros(3 * nz, n),
                x: Mat::zeros(n, nc3),
                y: Mat::zeros(nc3, nc3),
            },
        };
        f.spin_s = sp;
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
        Self::form_r(&mut f, red, a, b, sp);
        self.factor = Some(f);
        self.refactors += 1;
        self.stats.columns += red.n_contact();
        Ok(())
    }

    /// Spindle force of the tire on the wheel (7.2) in the current state.
    pub fn spindle_force(&self) -> SpindleForce {
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
        SpindleForce {
            fx: f[0],
            fy: f[2],
            fz: f[1],
        }
    }

    /// Deformed contact-node positions `sᵢ + (T_c z)ᵢ` [m].
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
        let (h, bn, gn) = (
            self.cfg.time_step,
            self.cfg.newmark_beta,
            self.cfg.newmark_gamma,
        );
        let spin_pred = self.state.theta_d + (1.0 - gn) * h * self.state.theta_dd;
        let drift = |s: f64, tol: f64| (spin_pred - s).abs() > tol * s.abs().max(1.0);
        let (need_s, need_r) = match &self.factor {
            None => (true, true),
            Some(f) => (
                drift(f.spin_s, self.cfg.matrix_tolerance),
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
                w.pred[j] = st.zd[j] + (1.0 - gn) * h * st.zdd[j];
                w.pred[nz + j] = st.z[j] + h * st.zd[j] + h * h * (0.5 - bn) * st.zdd[j];
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
        st.theta += h * st.theta_d + h * h * ((0.5 - bn) * st.theta_dd + bn * theta_dd);
        st.theta_d = spin_pred + gn * h * theta_dd;
        st.theta_dd = theta_dd;
        for j in 0..nz {
            let a = w.a[1 + j];
            st.zdd[j] = a;
            st.z[j] = w.pred[nz + j] + bn * h * h * a;
            st.zd[j] = w.pred[j] + gn * h * a;
        }
        st.lambda.iter_mut().for_each(|l| *l = 0.0);
        st.friction.iter_mut().for_each(|f| *f = [0.0; 3]);
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

    /// The contact problem of the candidates in `work` (normal LCP on the Delassus matrix with
    /// the friction forces frozen, then Coulomb friction by projected block Gauss–Seidel,
    /// alternated); leaves the contact forces in `work.forces`.
    fn solve_contact(&mut self, t1: f64, spin_free: f64) -> Result<(), TireError> {
        let red = self.red;
        let (h, bn, gn) = (
            self.cfg.time_step,
            self.cfg.newmark_beta,
            self.cfg.newmark_gamma,
        );
        let Some(fac) = self.factor.as_ref() else {
            return Ok(());
        };
        let w = &mut self.work;
        let m = w.cand.len();
        let mu = self.cfg.friction;
        w.lambda.clear();
        w.lambda.resize(m, 0.0);
        w.ft.clear();
        w.warm.clear();
        w.forces.clear();
        for &i in &w.cand {
            w.ft.push(if mu > 0.0 {
                self.state.friction[i]
            } else {
                [0.0; 3]
            });
            w.warm.push(self.state.lambda[i] > 0.0);
        }
        if m == 0 {
            return Ok(());
        }
        // compact candidate blocks of Y and of Y_v = Y + (η × s) X_θ (material velocity)
        let ld = 3 * m;
        w.yc.clear();
        w.yc.resize(ld * ld, 0.0);
        w.yvc.clear();
        w.yvc.resize(ld * ld, 0.0);
        for (kb, &jb) in w.cand.iter().enumerate() {
            for c in 0..3 {
                let col = 3 * jb + c;
                let ycol = fac.y.col(col);
                let xth = fac.x[(0, col)];
                let dst = (3 * kb + c) * ld;
                for (ka, &ia) in w.cand.iter().enumerate() {
                    let sp = red.contact_positions[ia];
                    let rig = [sp[2], 0.0, -sp[0]];
                    for r in 0..3 {
                        let v = ycol[3 * ia + r];
                        w.yc[dst + 3 * ka + r] = v;
                        w.yvc[dst + 3 * ka + r] = v + rig[r] * xth;
                    }
                }
            }
        }
        // free material slip velocities, computed for the nodes that become active
        w.vfree.clear();
        w.vfree.resize(m, [0.0; 3]);
        w.vdone.clear();
        w.vdone.resize(m, false);
        let c2 = bn * h * h;
        let c1 = gn * h;
        w.w.resize_with(m, m, |_, _| 0.0);
        for kj in 0..m {
            for ki in 0..m {
                w.w[(ki, kj)] =
                    c2 * dot3(&w.gp[ki].normal, &blk(&w.yc, ld, ki, kj, &w.gp[kj].normal));
            }
            if let NormalContact::Penalty { stiffness } = self.cfg.normal {
                w.w[(kj, kj)] += 1.0 / stiffness;
            }
        }
        let tol = |lam_max: f64| 1e-5 * (mu * lam_max + 1.0);
        for _outer in 0..3 {
            // normal problem with the tangential forces frozen
            w.q.clear();
            for ki in 0..m {
                let mut g = w.gp[ki].gap;
                for kj in 0..m {
                    if w.ft[kj] != [0.0; 3] {
                        g += c2 * dot3(&w.gp[ki].normal, &blk(&w.yc, ld, ki, kj, &w.ft[kj]));
                    }
                }
                w.q.push(g);
            }
            let (converged, _) = w.lcp.solve(w.w.as_ref(), &w.q, &w.warm, 1e-12);
            self.stats.lcp_solves += 1;
            if !converged {
                return Err(TireError::Simulation {
                    time: t1,
                    reason: "contact active set did not converge".into(),
                });
            }
            w.lambda.copy_from_slice(&w.lcp.lambda);
            if mu == 0.0 {
                break;
            }
            // tangential problem: Coulomb friction (set-valued sign at zero slip) by block
            // Gauss–Seidel with projection onto the friction disk |f_t| ≤ μλ
            w.dv.clear();
            w.dv.resize(m, [0.0; 3]);
            for kj in 0..m {
                let n = w.gp[kj].normal;
                let l = w.lambda[kj];
                let f = [
                    n[0] * l + w.ft[kj][0],
                    n[1] * l + w.ft[kj][1],
                    n[2] * l + w.ft[kj][2],
                ];
                for ki in 0..m {
                    let d = blk(&w.yvc, ld, ki, kj, &f);
                    for a in 0..3 {
                        w.dv[ki][a] += c1 * d[a];
                    }
                }
            }
            let lam_max = w.lambda.iter().fold(0.0f64, |a, &b| a.max(b));
            w.act.clear();
            w.act.extend((0..m).filter(|&k| w.lambda[k] > 0.0));
            for &k in &w.act {
                if w.vdone[k] {
                    continue;
                }
                let i = w.cand[k];
                let s = red.contact_positions[i];
                let rig = [spin_free * s[2], 0.0, -spin_free * s[0]];
                for a in 0..3 {
                    let c = 3 * i + a;
                    let vc = dot(col_slice(&self.tct, c), &w.zd_free);
                    let vt = dot(col_slice(&self.tct_theta, c), &w.z_free);
                    w.vfree[k][a] = rig[a] + vc + spin_free * vt - w.gp[k].velocity[a];
                }
                w.vdone[k] = true;
            }
            for k in 0..m {
                if w.lambda[k] <= 0.0 && w.ft[k] != [0.0; 3] {
                    // released node: drop its friction and its effect on the others
                    let d = [-w.ft[k][0], -w.ft[k][1], -w.ft[k][2]];
                    w.ft[k] = [0.0; 3];
                    for &kk in &w.act {
                        let e = blk(&w.yvc, ld, kk, k, &d);
                        for a in 0..3 {
                            w.dv[kk][a] += c1 * e[a];
                        }
                    }
                }
            }
            let mut outer_change = 0.0f64;
            for _sweep in 0..10 {
                self.stats.friction_sweeps += 1;
                let mut change = 0.0f64;
                for ai in 0..w.act.len() {
                    let ki = w.act[ai];
                    let n = w.gp[ki].normal;
                    let t1v = [n[2], 0.0, -n[0]];
                    let t2v = [0.0, 1.0, 0.0];
                    let v = [
                        w.vfree[ki][0] + w.dv[ki][0],
                        w.vfree[ki][1] + w.dv[ki][1],
                        w.vfree[ki][2] + w.dv[ki][2],
                    ];
                    let r = [dot3(&t1v, &v), dot3(&t2v, &v)];
                    let bt1 = blk(&w.yvc, ld, ki, ki, &t1v);
                    let bt2 = blk(&w.yvc, ld, ki, ki, &t2v);
                    let b = [
                        [c1 * dot3(&t1v, &bt1), c1 * dot3(&t1v, &bt2)],
                        [c1 * dot3(&t2v, &bt1), c1 * dot3(&t2v, &bt2)],
                    ];
                    let det = b[0][0] * b[1][1] - b[0][1] * b[1][0];
                    if det.is_nan() || det == 0.0 {
                        continue;
                    }
                    let old = [dot3(&t1v, &w.ft[ki]), dot3(&t2v, &w.ft[ki])];
                    let mut new = [
                        old[0] - (b[1][1] * r[0] - b[0][1] * r[1]) / det,
                        old[1] - (-b[1][0] * r[0] + b[0][0] * r[1]) / det,
                    ];
                    let cap = mu * w.lambda[ki];
                    let mag = (new[0] * new[0] + new[1] * new[1]).sqrt();
                    if mag > cap {
                        let sc = if mag > 0.0 { cap / mag } else { 0.0 };
                        new = [new[0] * sc, new[1] * sc];
                    }
                    let newv = [
                        new[0] * t1v[0] + new[1] * t2v[0],
                        new[0] * t1v[1] + new[1] * t2v[1],
                        new[0] * t1v[2] + new[1] * t2v[2],
                    ];
                    let d = [
                        newv[0] - w.ft[ki][0],
                        newv[1] - w.ft[ki][1],
                        newv[2] - w.ft[ki][2],
                    ];
                    let dm = dot3(&d, &d).sqrt();
                    if dm == 0.0 {
                        continue;
                    }
                    change = change.max(dm);
                    w.ft[ki] = newv;
                    for &kk in &w.act {
                        let e = blk(&w.yvc, ld, kk, ki, &d);
                        for a in 0..3 {
                            w.dv[kk][a] += c1 * e[a];
                        }
                    }
                }
                outer_change = outer_change.max(change);
                if change <= tol(lam_max) {
                    break;
                }
            }
            if outer_change <= tol(lam_max) {
                break;
            }
        }
        for k in 0..m {
            let n = w.gp[k].normal;
            let l = w.lambda[k];
            w.forces.push([
                n[0] * l + w.ft[k][0],
                n[1] * l + w.ft[k][1],
                n[2] * l + w.ft[k][2],
            ]);
        }
        Ok(())
    }

    /// Total normal contact force vector `Σ λᵢ nᵢ`-weighted vertical component [N] (the
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
