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
//! linearly implicit step: the θ̇-dependent gyroscopic/centrifugal matrices are evaluated at a
//! spin rate frozen until it drifts by more than `spin_tolerance` (then the iteration matrix is
//! refactored), the term `G₁ z θ̈` is lagged one step, and the friction directions are
//! iterated twice per step. Per step, the contact problem is a small LCP on the Delassus matrix
//! `W = β_N h² N T_c S⁻¹ T_cᵀ (N − μ T̂)` built from the cached `T_c S⁻¹ T_cᵀ`.

use super::error::{TireError, invalid};
use super::ground::Ground;
use super::lcp::solve_lcp;
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
    /// Relative drift of θ̇ that triggers a refactorisation.
    pub spin_tolerance: f64,
    /// Contact-node candidates: gap below this margin [m].
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
            contact_margin: 0.005,
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

struct Factor {
    spin: f64,
    /// S⁻¹ (n × n), n = 1 + n_z.
    s_inv: Mat<f64>,
    /// Q = [C_eff K_eff] (n_z × 2 n_z), acting on [ż̃; z̃].
    q: Mat<f64>,
    /// X = S⁻¹ [0; T_cᵀ] (n × 3 n_c).
    x: Mat<f64>,
    /// Y = T_c X_z (3 n_c × 3 n_c).
    y: Mat<f64>,
    /// Yv = Y + (η × s) X_θ: material-velocity response of the contact nodes (3 n_c × 3 n_c).
    yv: Mat<f64>,
    /// Spin-row coefficients on [ż̃; z̃].
    spin_row: Vec<f64>,
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
    /// Number of refactorisations so far.
    pub refactors: usize,
}

fn matvec(a: &Mat<f64>, x: &[f64], out: &mut [f64]) {
    let xv = MatRef::from_column_major_slice(x, x.len(), 1);
    let ov = MatMut::from_column_major_slice_mut(out, a.nrows(), 1);
    matmul(ov, Accum::Replace, a.as_ref(), xv, 1.0, Par::Seq);
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
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
                lambda: vec![0.0; red.n_contact()],
                friction: vec![[0.0; 3]; red.n_contact()],
            },
            factor: None,
            refactors: 0,
        })
    }

    /// Settings.
    pub fn config(&self) -> &RollingConfig {
        &self.cfg
    }

    fn spin_inertia(&self) -> f64 {
        self.cfg.wheel_spin_inertia + self.red.rim_spin_inertia
    }

    fn refactor(&mut self, spin: f64) -> Result<(), TireError> {
        let red = self.red;
        let nz = red.n_z();
        let n = nz + 1;
        let (h, bn, gn) = (
            self.cfg.time_step,
            self.cfg.newmark_beta,
            self.cfg.newmark_gamma,
        );
        let (a, b) = (self.alpha, self.beta);
        // C_eff = 2θ̇G₁ + αM + βK, K_eff = K + θ̇²G₂ + βθ̇K₁
        let mut q = Mat::<f64>::zeros(nz, 2 * nz);
        for j in 0..nz {
            for i in 0..nz {
                q[(i, j)] = 2.0 * spin * red.g1[(i, j)] + a * red.m[(i, j)] + b * red.k[(i, j)];
                q[(i, nz + j)] =
                    red.k[(i, j)] + spin * spin * red.g2[(i, j)] + b * spin * red.k1[(i, j)];
            }
        }
        let kt = red.kt.row(1);
        let kt1 = red.kt1.row(1);
        let mut spin_row = vec![0.0; 2 * nz];
        for j in 0..nz {
            spin_row[j] = b * kt[j];
            spin_row[nz + j] = kt[j] + b * spin * kt1[j];
        }
        let mut s = Mat::<f64>::zeros(n, n);
        s[(0, 0)] = self.spin_inertia();
        for j in 0..nz {
            s[(0, 1 + j)] = gn * h * spin_row[j] + bn * h * h * spin_row[nz + j];
            s[(1 + j, 0)] = red.m_theta[j];
        }
        for j in 0..nz {
            for i in 0..nz {
                s[(1 + i, 1 + j)] =
                    red.m[(i, j)] + gn * h * q[(i, j)] + bn * h * h * q[(i, nz + j)];
            }
        }
        let lu = s.partial_piv_lu();
        let s_inv = lu.solve(Mat::<f64>::identity(n, n));
        if !s_inv.as_ref().is_all_finite() {
            return Err(TireError::Simulation {
                time: self.state.t,
                reason: "the Newmark iteration matrix is singular".into(),
            });
        }
        let nc3 = red.tc.nrows();
        let mut tct = Mat::<f64>::zeros(n, nc3);
        for j in 0..nc3 {
            for i in 0..nz {
                tct[(1 + i, j)] = red.tc[(j, i)];
            }
        }
        let x = &s_inv * &tct;
        let y = &red.tc * x.subrows(1, nz);
        let mut yv = y.clone();
        for (i, sp) in red.contact_positions.iter().enumerate() {
            let rig = [sp[2], 0.0, -sp[0]];
            for k in 0..nc3 {
                for a in 0..3 {
                    yv[(3 * i + a, k)] += rig[a] * x[(0, k)];
                }
            }
        }
        self.factor = Some(Factor {
            spin,
            s_inv,
            q,
            x,
            y,
            yv,
            spin_row,
        });
        self.refactors += 1;
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
        matvec(&self.red.tc, &self.state.z, &mut d);
        self.red
            .contact_positions
            .iter()
            .enumerate()
            .map(|(i, s)| [s[0] + d[3 * i], s[1] + d[3 * i + 1], s[2] + d[3 * i + 2]])
            .collect()
    }

    /// Advance one time step.
    pub fn step(&mut self) -> Result<(), TireError> {
        let red = self.red;
        let nz = red.n_z();
        let nc = red.n_contact();
        let (h, bn, gn) = (
            self.cfg.time_step,
            self.cfg.newmark_beta,
            self.cfg.newmark_gamma,
        );
        let st = &self.state;
        let spin_pred = st.theta_d + (1.0 - gn) * h * st.theta_dd;
        let need = match &self.factor {
            None => true,
            Some(f) => (spin_pred - f.spin).abs() > self.cfg.spin_tolerance * f.spin.abs().max(1.0),
        };
        if need {
            self.refactor(spin_pred)?;
        }
        let fac = self.factor.as_ref().ok_or_else(|| TireError::Simulation {
            time: self.state.t,
            reason: "no factorisation".into(),
        })?;
        let st = &self.state;

        // predictors
        let mut pred = vec![0.0; 2 * nz]; // [ż̃; z̃]
        for j in 0..nz {
            pred[j] = st.zd[j] + (1.0 - gn) * h * st.zdd[j];
            pred[nz + j] = st.z[j] + h * st.zd[j] + h * h * (0.5 - bn) * st.zdd[j];
        }
        // right-hand side vector terms: b = [τ; −θ̇²c_s − G₁ z θ̈]
        let mut g1z = vec![0.0; nz];
        matvec(&red.g1, &st.z, &mut g1z);
        let mut bvec = vec![0.0; nz + 1];
        bvec[0] = self.drive_torque;
        for j in 0..nz {
            bvec[1 + j] = -spin_pred * spin_pred * red.c_s[j] - g1z[j] * st.theta_dd;
        }
        let mut qp = vec![0.0; nz];
        matvec(&fac.q, &pred, &mut qp);
        bvec[0] -= dot(&fac.spin_row, &pred);
        for j in 0..nz {
            bvec[1 + j] -= qp[j];
        }
        let mut a_free = vec![0.0; nz + 1];
        matvec(&fac.s_inv, &bvec, &mut a_free);
        // free end-of-step state
        let t1 = st.t + h;
        let z_free: Vec<f64> = (0..nz)
            .map(|j| pred[nz + j] + bn * h * h * a_free[1 + j])
            .collect();
        let zd_free: Vec<f64> = (0..nz).map(|j| pred[j] + gn * h * a_free[1 + j]).collect();
        let spin_free = spin_pred + gn * h * a_free[0];
        let mut dc = vec![0.0; 3 * nc];
        matvec(&red.tc, &z_free, &mut dc);
        // candidates
        let mut cand = Vec::new();
        let mut gp = Vec::new();
        for i in 0..nc {
            let s = red.contact_positions[i];
            let p = [s[0] + dc[3 * i], s[1] + dc[3 * i + 1], s[2] + dc[3 * i + 2]];
            let g = self.ground.query(t1, p);
            if g.gap < self.cfg.contact_margin {
                cand.push(i);
                gp.push(g);
            }
        }
        let m = cand.len();
        let mut lambda_c = vec![0.0; m];
        let mut ft: Vec<[f64; 3]> = cand.iter().map(|&i| self.state.friction[i]).collect();
        if m > 0 {
            let mu = self.cfg.friction;
            let warm: Vec<bool> = cand.iter().map(|&i| self.state.lambda[i] > 0.0).collect();
            // free material slip velocities of the candidates
            let mut vfree = vec![[0.0; 3]; m];
            if mu > 0.0 {
                let mut vc = vec![0.0; 3 * nc];
                let mut vt = vec![0.0; 3 * nc];
                matvec(&red.tc, &zd_free, &mut vc);
                matvec(&red.tc_theta, &z_free, &mut vt);
                for (k, &i) in cand.iter().enumerate() {
                    let s = red.contact_positions[i];
                    let rig = [spin_free * s[2], 0.0, -spin_free * s[0]];
                    for a in 0..3 {
                        vfree[k][a] =
                            rig[a] + vc[3 * i + a] + spin_free * vt[3 * i + a] - gp[k].velocity[a];
                    }
                }
            } else {
                ft.iter_mut().for_each(|f| *f = [0.0; 3]);
            }
            let c2 = bn * h * h;
            let c1 = gn * h;
            let blk = |a: &Mat<f64>, i: usize, j: usize, v: &[f64; 3]| -> [f64; 3] {
                let mut o = [0.0; 3];
                for (r, or) in o.iter_mut().enumerate() {
                    for (c, vc) in v.iter().enumerate() {
                        *or += a[(3 * i + r, 3 * j + c)] * vc;
                    }
                }
                o
            };
            let mut w = Mat::<f64>::zeros(m, m);
            for (kj, &j) in cand.iter().enumerate() {
                for (ki, &i) in cand.iter().enumerate() {
                    w[(ki, kj)] = c2 * dot(&gp[ki].normal, &blk(&fac.y, i, j, &gp[kj].normal));
                }
                if let NormalContact::Penalty { stiffness } = self.cfg.normal {
                    w[(kj, kj)] += 1.0 / stiffness;
                }
            }
            for _outer in 0..3 {
                // normal problem with the tangential forces frozen
                let q: Vec<f64> = (0..m)
                    .map(|ki| {
                        let mut g = gp[ki].gap;
                        for (kj, &j) in cand.iter().enumerate() {
                            if ft[kj] != [0.0; 3] {
                                g += c2 * dot(&gp[ki].normal, &blk(&fac.y, cand[ki], j, &ft[kj]));
                            }
                        }
                        g
                    })
                    .collect();
                let sol = solve_lcp(&w, &q, &warm, 1e-12);
                if !sol.converged {
                    return Err(TireError::Simulation {
                        time: t1,
                        reason: "contact active set did not converge".into(),
                    });
                }
                lambda_c = sol.lambda;
                if mu == 0.0 {
                    break;
                }
                // tangential problem: Coulomb friction (set-valued sign at zero slip) by block
                // Gauss-Seidel with projection onto the friction disk |f_t| <= mu lambda
                let mut dv = vec![[0.0; 3]; m];
                for (kj, &j) in cand.iter().enumerate() {
                    let n = gp[kj].normal;
                    let f = [
                        n[0] * lambda_c[kj] + ft[kj][0],
                        n[1] * lambda_c[kj] + ft[kj][1],
                        n[2] * lambda_c[kj] + ft[kj][2],
                    ];
                    for (ki, &i) in cand.iter().enumerate() {
                        let d = blk(&fac.yv, i, j, &f);
                        for a in 0..3 {
                            dv[ki][a] += c1 * d[a];
                        }
                    }
                }
                let lam_max = lambda_c.iter().fold(0.0f64, |a, &b| a.max(b));
                let act: Vec<usize> = (0..m).filter(|&k| lambda_c[k] > 0.0).collect();
                for k in 0..m {
                    if lambda_c[k] <= 0.0 && ft[k] != [0.0; 3] {
                        // released node: drop its friction and its effect on the others
                        let d = [-ft[k][0], -ft[k][1], -ft[k][2]];
                        ft[k] = [0.0; 3];
                        for &kk in &act {
                            let e = blk(&fac.yv, cand[kk], cand[k], &d);
                            for a in 0..3 {
                                dv[kk][a] += c1 * e[a];
                            }
                        }
                    }
                }
                let mut outer_change = 0.0f64;
                for _sweep in 0..10 {
                    let mut change = 0.0f64;
                    for &ki in &act {
                        let i = cand[ki];
                        let n = gp[ki].normal;
                        let t1v = [n[2], 0.0, -n[0]];
                        let t2v = [0.0, 1.0, 0.0];
                        let v = [
                            vfree[ki][0] + dv[ki][0],
                            vfree[ki][1] + dv[ki][1],
                            vfree[ki][2] + dv[ki][2],
                        ];
                        let r = [dot(&t1v, &v), dot(&t2v, &v)];
                        let bt1 = blk(&fac.yv, i, i, &t1v);
                        let bt2 = blk(&fac.yv, i, i, &t2v);
                        let b = [
                            [c1 * dot(&t1v, &bt1), c1 * dot(&t1v, &bt2)],
                            [c1 * dot(&t2v, &bt1), c1 * dot(&t2v, &bt2)],
                        ];
                        let det = b[0][0] * b[1][1] - b[0][1] * b[1][0];
                        if !(det.abs() > 0.0) {
                            continue;
                        }
                        let old = [dot(&t1v, &ft[ki]), dot(&t2v, &ft[ki])];
                        let mut new = [
                            old[0] - (b[1][1] * r[0] - b[0][1] * r[1]) / det,
                            old[1] - (-b[1][0] * r[0] + b[0][0] * r[1]) / det,
                        ];
                        let cap = mu * lambda_c[ki];
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
                            newv[0] - ft[ki][0],
                            newv[1] - ft[ki][1],
                            newv[2] - ft[ki][2],
                        ];
                        let dm = dot(&d, &d).sqrt();
                        if dm == 0.0 {
                            continue;
                        }
                        change = change.max(dm);
                        ft[ki] = newv;
                        for &kk in &act {
                            let e = blk(&fac.yv, cand[kk], i, &d);
                            for a in 0..3 {
                                dv[kk][a] += c1 * e[a];
                            }
                        }
                    }
                    outer_change = outer_change.max(change);
                    if change <= 1e-5 * (mu * lam_max + 1.0) {
                        break;
                    }
                }
                if outer_change <= 1e-5 * (mu * lam_max + 1.0) {
                    break;
                }
            }
        }
        let forces: Vec<[f64; 3]> = (0..m)
            .map(|k| {
                let n = gp[k].normal;
                [
                    n[0] * lambda_c[k] + ft[k][0],
                    n[1] * lambda_c[k] + ft[k][1],
                    n[2] * lambda_c[k] + ft[k][2],
                ]
            })
            .collect();
        let da = self.contact_correction(&cand, &forces);
        let st = &mut self.state;
        let theta_dd = a_free[0] + da[0];
        st.theta += h * st.theta_d + h * h * ((0.5 - bn) * st.theta_dd + bn * theta_dd);
        st.theta_d = spin_pred + gn * h * theta_dd;
        st.theta_dd = theta_dd;
        for j in 0..nz {
            let a = a_free[1 + j] + da[1 + j];
            st.zdd[j] = a;
            st.z[j] = pred[nz + j] + bn * h * h * a;
            st.zd[j] = pred[j] + gn * h * a;
        }
        st.lambda.iter_mut().for_each(|l| *l = 0.0);
        st.friction.iter_mut().for_each(|f| *f = [0.0; 3]);
        for (k, &i) in cand.iter().enumerate() {
            st.lambda[i] = lambda_c[k];
            st.friction[i] = ft[k];
        }
        st.t = t1;
        if !(st.theta_d.is_finite() && st.z.iter().all(|v| v.is_finite())) {
            return Err(TireError::Simulation {
                time: t1,
                reason: "the state became non-finite".into(),
            });
        }
        Ok(())
    }

    /// Acceleration change `X Σ fⱼ` of the contact-node forces `fⱼ` (normal + friction).
    fn contact_correction(&self, cand: &[usize], forces: &[[f64; 3]]) -> Vec<f64> {
        let nz = self.red.n_z();
        let mut da = vec![0.0; nz + 1];
        let Some(fac) = self.factor.as_ref() else {
            return da;
        };
        for (k, &j) in cand.iter().enumerate() {
            for b in 0..3 {
                let c = forces[k][b];
                if c == 0.0 {
                    continue;
                }
                let col = fac.x.col(3 * j + b);
                for r in 0..=nz {
                    da[r] += col[r] * c;
                }
            }
        }
        da
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

    /// The spin-row coefficients (for diagnostics).
    pub fn spin_row(&self) -> Option<&[f64]> {
        self.factor.as_ref().map(|f| f.spin_row.as_slice())
    }
}
