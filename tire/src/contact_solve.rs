//! The coupled normal + friction contact problem of one time step, solved by a semismooth
//! (generalised) Newton method on the Alart–Curnier augmented-Lagrangian equations, with the
//! alternation of a normal LCP and a friction Gauss–Seidel as the fallback.
//!
//! # Problem (local frames)
//! Contact `k` has the unknowns `x_k = (λ_k, f1_k, f2_k)` (normal multiplier and the two
//! tangential friction components \[N\]) and the outputs `y_k = (g_k, u1_k, u2_k)` (end-of-step
//! gap \[m\] and tangential slip velocity \[m/s\]), linear in the forces through the local Delassus
//! matrix `D` (3m × 3m) and the free values `b`:
//!
//! ```text
//!   y = D x + b,
//!   0 ≤ λ_k ⊥ g_k ≥ 0                                  (Ribaric §7.3, unilateral contact)
//!   Coulomb:     |f_k| ≤ μ λ_k,  u_k = −ν f_k with ν ≥ 0 (stick if |f_k| < μλ_k)
//!   regularised: f_k = −μ λ_k u_k / √(|u_k|² + ε²)      (Ribaric's slip-only law, seed note U20)
//! ```
//!
//! # Alart–Curnier equations
//! With per-contact augmentation parameters `r_N` \[N/m\] and `r_T` \[N·s/m\] (any positive value:
//! the solution does not depend on them; they are set to the inverse diagonal compliances so that
//! Newton is well scaled), the conditions above are the zeros of (Alart & Curnier 1991)
//!
//! ```text
//!   Φ_N = λ − max(0, λ − r_N g)                          = min(λ, r_N g)
//!   Φ_T = f − proj_{disk(μ λ̂)}(f − r_T u),   λ̂ = max(0, λ − r_N g)        (Coulomb)
//!   Φ_T = f + μ λ̂ u / √(|u|² + ε²)                                       (regularised)
//! ```
//!
//! `Φ` is piecewise smooth; Newton uses one element of its generalised Jacobian. A contact with
//! `λ − r_N g ≤ 0` has identity rows (`x_k = 0` after the step), so only the contacts that are
//! pressed enter the small dense system, which is solved by a faer LU (sequential, buffers
//! reused; its triangular solves by faer's algorithm without the per-block dispatch, module
//! `kernels`). A backtracking (Armijo) line search on `½‖Φ‖²` globalises the method; if it
//! stalls, the alternation of the normal LCP ([`LcpWork`], friction frozen) and a block Gauss–Seidel on
//! the friction forces (exact one-contact solve [`FrictionLaw::local_force`] of the law) is run
//! to the same tolerance.
//!
//! The columns of `D` and the tangential free velocities are supplied lazily by the caller
//! ([`DelassusSource`]): only contacts that carry a force or are pressed need them. The
//! linearisation of `Φ` (classification, derivatives of the friction law's target) is formed
//! together with the residual at each evaluated or accepted point and reused by the Newton or
//! chord direction from there.

use crate::kernels::{axpy_cols, col_slice, lu_solve_in_place};
use crate::lcp::LcpWork;
use contact::friction::{Coulomb, FrictionLaw};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::factor::{lu_in_place, lu_in_place_scratch};
use faer::prelude::*;
use faer::{Mat, Par};
use nalgebra::{Matrix2, Vector2};
use std::sync::Arc;

/// Settings of [`ContactSolver::solve`].
#[derive(Debug, Clone)]
pub struct SolveOptions {
    /// Friction law of the contact nodes, any [`FrictionLaw`] (Ribaric §7.3, §8.4.3: set-valued
    /// [`Coulomb`]; seed note U20: [`contact::SlipRegularized`]). Its tangential equation is
    /// the Alart–Curnier `Φ_T = f − p(f, u, λ̂)` of [`FrictionLaw::augmented`].
    pub law: Arc<dyn FrictionLaw>,
    /// Relative tolerance on `‖Φ‖∞ / max λ` (forces).
    pub tol: f64,
    /// Newton iterations before the fallback.
    pub max_newton: usize,
    /// Outer rounds of the fallback alternation.
    pub max_rounds: usize,
}

impl Default for SolveOptions {
    fn default() -> Self {
        Self {
            law: Arc::new(Coulomb { mu: 0.0 }),
            tol: 1e-10,
            max_newton: 30,
            max_rounds: 500,
        }
    }
}

/// Outcome of [`ContactSolver::solve`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SolveReport {
    /// Whether `‖Φ‖∞ ≤ tol · max λ` at the returned forces.
    pub converged: bool,
    /// Newton iterations (LU factorisations) used.
    pub newton_iterations: usize,
    /// Chord iterations (solves with an earlier LU) used.
    pub chord_iterations: usize,
    /// Whether the fallback alternation was run.
    pub fallback: bool,
    /// Normal LCP solves of the fallback.
    pub lcp_solves: usize,
    /// Friction Gauss–Seidel sweeps of the fallback.
    pub sweeps: usize,
    /// Final `‖Φ‖∞` \[N\].
    pub residual: f64,
}

/// The caller's lazy source of the local Delassus columns and of the free tangential
/// velocities.
pub trait DelassusSource {
    /// Fill the three columns of contact `l` (`λ_l`, `f1_l`, `f2_l`): `cols` is `3 × 3m`
    /// (column-major, leading dimension 3m), rows `(g_k, u1_k, u2_k)` of every contact `k`.
    fn columns(&mut self, l: usize, cols: &mut [f64]);
    /// The free tangential slip velocity `(u1_k, u2_k)` \[m/s\] of contact `k`.
    fn free_slip(&mut self, k: usize) -> [f64; 2];
}

/// A local problem given as a full matrix `D` (column-major, 3m × 3m) and a full `b`.
#[derive(Debug, Clone)]
pub struct DenseProblem<'a> {
    /// Local Delassus matrix, column-major with leading dimension 3m.
    pub d: &'a [f64],
    /// Free values `b` (3m).
    pub b: &'a [f64],
}

impl DelassusSource for DenseProblem<'_> {
    fn columns(&mut self, l: usize, cols: &mut [f64]) {
        let ld = self.b.len();
        cols.copy_from_slice(&self.d[3 * l * ld..(3 * l + 3) * ld]);
    }
    fn free_slip(&mut self, k: usize) -> [f64; 2] {
        [self.b[3 * k + 1], self.b[3 * k + 2]]
    }
}

/// Classification of a contact at the current Newton iterate.
#[derive(Debug, Clone, Copy, PartialEq)]
enum State {
    /// `λ − r_N g ≤ 0`: identity rows.
    Open,
    /// Pressed, friction inside the disk (or regularised law).
    Pressed,
}

/// The linearisation of the Alart–Curnier residual at one point (see
/// [`ContactSolver::residual`]).
#[derive(Default)]
struct Linearization {
    /// Per pressed contact: 3 × 3 matrices `L_k` (own unknowns) and `G_k` (own outputs) of the
    /// Jacobian rows `dΦ_k = L_k dx_k + G_k dy_k` (row-major).
    lk: Vec<[[f64; 3]; 3]>,
    gk: Vec<[[f64; 3]; 3]>,
    /// Classification per contact (0 open, 1 pressed/slip, 2 stick).
    pattern: Vec<u8>,
}

impl Linearization {
    /// Becomes a copy of `other` (buffers reused).
    fn copy_from(&mut self, other: &Self) {
        self.lk.clone_from(&other.lk);
        self.gk.clone_from(&other.gk);
        self.pattern.clone_from(&other.pattern);
    }

    fn reset(&mut self, m: usize) {
        clear_fill(&mut self.lk, m, [[0.0; 3]; 3]);
        clear_fill(&mut self.gk, m, [[0.0; 3]; 3]);
        clear_fill(&mut self.pattern, m, 0);
    }
}

/// A copy of an evaluation ([`ContactSolver::evaluate`]) and the number of free slip
/// velocities fetched before it was made. `b` enters `y = D x + b` first for the contacts
/// fetched before an evaluation, after the columns for those fetched during it, so evaluating
/// the same `x` again gives bitwise the same `y` only if none was fetched during or since the
/// first evaluation: then the copy replaces it.
#[derive(Default)]
struct Evaluation {
    y: Vec<f64>,
    phi: Vec<f64>,
    lin: Linearization,
    fetched: usize,
}

/// A factorised Newton matrix and the classification of the contacts it was built for.
struct LuSlot {
    pattern: Vec<u8>,
    n: usize,
    /// Packed LU factors `P J = L U`.
    lu: Mat<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    valid: bool,
    /// Clock of the last use (least recently used slot is refactorised).
    used: u64,
}

/// Reusable buffers of the contact solve (no allocation once grown).
pub struct ContactSolver {
    m: usize,
    /// Local Delassus matrix (column-major, ld = 3m); column block `l` valid iff `have[l]`.
    d: Vec<f64>,
    have: Vec<bool>,
    /// Free values `b` (3m); tangential entries valid iff `have_b[k]`.
    b: Vec<f64>,
    have_b: Vec<bool>,
    /// Whether the free slip velocities matter (μ > 0).
    need_slip: bool,
    /// Unknowns (warm start in, solution out).
    x: Vec<f64>,
    y: Vec<f64>,
    phi: Vec<f64>,
    rn: Vec<f64>,
    rt: Vec<f64>,
    state: Vec<State>,
    /// The linearisation of `Φ` at the current `(x, y)`, formed with its residual (valid iff
    /// `lin_ok`), and at the line search's trial point.
    lin: Linearization,
    lin_trial: Linearization,
    lin_ok: bool,
    /// The evaluation (`y`, `Φ`, linearisation) of the best warm start so far.
    best: Evaluation,
    act: Vec<usize>,
    /// The last few Newton matrices (LU factors), by classification: chord steps use the one
    /// of the current classification (the patch often alternates between two from step to
    /// step).
    slots: Vec<LuSlot>,
    clock: u64,
    rhs: Vec<f64>,
    tmp: Vec<f64>,
    dx: Vec<f64>,
    dy: Vec<f64>,
    xt: Vec<f64>,
    yt: Vec<f64>,
    mem: Option<MemBuffer>,
    mem_n: usize,
    lcp: LcpWork,
    wn: Mat<f64>,
    q: Vec<f64>,
    warm: Vec<bool>,
}

impl Default for ContactSolver {
    fn default() -> Self {
        Self {
            m: 0,
            d: Vec::new(),
            have: Vec::new(),
            b: Vec::new(),
            have_b: Vec::new(),
            need_slip: true,
            x: Vec::new(),
            y: Vec::new(),
            phi: Vec::new(),
            rn: Vec::new(),
            rt: Vec::new(),
            state: Vec::new(),
            lin: Linearization::default(),
            lin_trial: Linearization::default(),
            lin_ok: false,
            best: Evaluation::default(),
            act: Vec::new(),
            slots: (0..3)
                .map(|_| LuSlot {
                    pattern: Vec::new(),
                    n: 0,
                    lu: Mat::zeros(0, 0),
                    perm: Vec::new(),
                    perm_inv: Vec::new(),
                    valid: false,
                    used: 0,
                })
                .collect(),
            clock: 0,
            rhs: Vec::new(),
            tmp: Vec::new(),
            dx: Vec::new(),
            dy: Vec::new(),
            xt: Vec::new(),
            yt: Vec::new(),
            mem: None,
            mem_n: 0,
            lcp: LcpWork::default(),
            wn: Mat::zeros(0, 0),
            q: Vec::new(),
            warm: Vec::new(),
        }
    }
}

impl std::fmt::Debug for ContactSolver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ContactSolver")
            .field("contacts", &self.m)
            .field("x", &self.x)
            .finish_non_exhaustive()
    }
}

fn clear_fill<T: Clone>(v: &mut Vec<T>, n: usize, val: T) {
    v.clear();
    v.resize(n, val);
}

impl ContactSolver {
    /// Start a problem of `m` contacts with the warm start `x0` (3m: `λ, f1, f2` per contact).
    pub fn reset(&mut self, x0: &[f64]) {
        let m = x0.len() / 3;
        self.m = m;
        let n = 3 * m;
        // D is read only in the column blocks marked in `have`: no need to clear it
        if self.d.len() < n * n {
            self.d.resize(n * n, 0.0);
        }
        clear_fill(&mut self.have, m, false);
        clear_fill(&mut self.b, n, 0.0);
        clear_fill(&mut self.have_b, m, false);
        self.x.clear();
        self.x.extend_from_slice(x0);
        for k in 0..m {
            if self.x[3 * k].is_nan() || self.x[3 * k] <= 0.0 {
                self.x[3 * k..3 * k + 3].copy_from_slice(&[0.0; 3]);
            }
        }
        clear_fill(&mut self.y, n, 0.0);
        clear_fill(&mut self.phi, n, 0.0);
        clear_fill(&mut self.rn, m, 0.0);
        clear_fill(&mut self.rt, m, 0.0);
        clear_fill(&mut self.state, m, State::Open);
        self.lin.reset(m);
        self.lin_trial.reset(m);
        self.lin_ok = false;
    }

    /// Set the free gaps `b_N` \[m\] (one per contact).
    pub fn set_gaps(&mut self, gaps: impl IntoIterator<Item = f64>) {
        for (k, g) in gaps.into_iter().enumerate().take(self.m) {
            self.b[3 * k] = g;
        }
    }

    /// The solution (3m: `λ, f1, f2` per contact) \[N\].
    pub fn x(&self) -> &[f64] {
        &self.x
    }

    /// The local outputs `y = D x + b` at the solution (gaps \[m\], slip velocities \[m/s\]) of
    /// the contacts whose columns and free velocities were needed (the others: gap only).
    pub fn y(&self) -> &[f64] {
        &self.y
    }

    fn ensure_col(&mut self, src: &mut dyn DelassusSource, l: usize) {
        if self.have[l] {
            return;
        }
        let n = 3 * self.m;
        src.columns(l, &mut self.d[3 * l * n..(3 * l + 3) * n]);
        self.have[l] = true;
    }

    fn ensure_b(&mut self, src: &mut dyn DelassusSource, k: usize) {
        if self.have_b[k] {
            return;
        }
        let u = src.free_slip(k);
        self.b[3 * k + 1] = u[0];
        self.b[3 * k + 2] = u[1];
        self.have_b[k] = true;
    }

    /// `out = D v + b` over the column blocks with a nonzero `v` (which must be available).
    fn apply(&self, v: &[f64], out: &mut [f64], with_b: bool) {
        let n = 3 * self.m;
        if with_b {
            out.copy_from_slice(&self.b);
        } else {
            out.iter_mut().for_each(|o| *o = 0.0);
        }
        axpy_cols(|c| &self.d[c * n..(c + 1) * n], v, out);
    }

    /// Alart–Curnier residual `Φ(x)` for `y = D x + b`; returns `‖Φ‖∞`. With `lin`, also the
    /// linearisation of `Φ` at `(x, y)` used by the Newton direction: per contact its
    /// classification (0 open, 1 pressed/slip, 2 stick) and, if pressed, the 3 × 3 matrices
    /// `L_k`, `G_k` of `dΦ_k = L_k dx_k + G_k dy_k` (the law's target is the same with or
    /// without its derivatives).
    fn residual(
        &self,
        s: &SolveOptions,
        x: &[f64],
        y: &[f64],
        phi: &mut [f64],
        mut lin: Option<&mut Linearization>,
    ) -> f64 {
        let mut norm = 0.0f64;
        for k in 0..self.m {
            let (lam, f) = (x[3 * k], [x[3 * k + 1], x[3 * k + 2]]);
            let sig = lam - self.rn[k] * y[3 * k];
            if sig <= 0.0 {
                phi[3 * k] = lam;
                phi[3 * k + 1] = f[0];
                phi[3 * k + 2] = f[1];
                if let Some(lin) = lin.as_deref_mut() {
                    lin.pattern[k] = 0;
                }
            } else {
                phi[3 * k] = lam - sig;
                let u = Vector2::new(y[3 * k + 1], y[3 * k + 2]);
                let ac =
                    s.law
                        .augmented(Vector2::new(f[0], f[1]), u, sig, self.rt[k], lin.is_some());
                let p = ac.target;
                phi[3 * k + 1] = f[0] - p[0];
                phi[3 * k + 2] = f[1] - p[1];
                if let Some(lin) = lin.as_deref_mut() {
                    // dΦ_N = r_N dg; Φ_T = f − p(f, u, λ̂), λ̂ = λ − r_N g:
                    // dΦ_T = (I − p_f) df − p_u du − p_λ̂ (dλ − r_N dg)
                    let rn = self.rn[k];
                    let mut l = [[0.0; 3]; 3];
                    let mut g = [[0.0; 3]; 3];
                    g[0][0] = rn;
                    for r in 0..2 {
                        l[1 + r][0] = -ac.d_normal[r];
                        g[1 + r][0] = rn * ac.d_normal[r];
                        for c in 0..2 {
                            l[1 + r][1 + c] = if r == c { 1.0 } else { 0.0 } - ac.d_force[(r, c)];
                            g[1 + r][1 + c] = -ac.d_slip[(r, c)];
                        }
                    }
                    lin.lk[k] = l;
                    lin.gk[k] = g;
                    lin.pattern[k] = if ac.stick { 2 } else { 1 };
                }
            }
            for a in 0..3 {
                norm = norm.max(phi[3 * k + a].abs());
            }
        }
        norm
    }

    /// Fetch the free slip velocities of the contacts that are pressed at `(x, y)` and do not
    /// have them yet, adding them to the tangential rows of `y` and of `also` (`b` enters
    /// only these rows).
    fn prefetch(
        &mut self,
        src: &mut dyn DelassusSource,
        x: &[f64],
        y: &mut [f64],
        mut also: Option<&mut [f64]>,
    ) {
        if !self.need_slip {
            return;
        }
        for k in 0..self.m {
            if self.have_b[k] || x[3 * k] - self.rn[k] * y[3 * k] <= 0.0 {
                continue;
            }
            self.ensure_b(src, k);
            for a in 1..3 {
                y[3 * k + a] += self.b[3 * k + a];
                if let Some(o) = also.as_deref_mut() {
                    o[3 * k + a] += self.b[3 * k + a];
                }
            }
        }
    }

    /// `y = D x + b` with the needed columns, and `Φ`; returns `‖Φ‖∞`.
    fn evaluate(&mut self, src: &mut dyn DelassusSource, s: &SolveOptions) -> f64 {
        for l in 0..self.m {
            if self.x[3 * l..3 * l + 3] != [0.0; 3] {
                self.ensure_col(src, l);
            }
        }
        let mut y = std::mem::take(&mut self.y);
        let mut phi = std::mem::take(&mut self.phi);
        let x = std::mem::take(&mut self.x);
        self.apply(&x, &mut y, true);
        self.prefetch(src, &x, &mut y, None);
        let mut lin = std::mem::take(&mut self.lin);
        let norm = self.residual(s, &x, &y, &mut phi, Some(&mut lin));
        self.lin = lin;
        self.lin_ok = true;
        self.x = x;
        self.y = y;
        self.phi = phi;
        norm
    }

    /// The number of free slip velocities fetched so far.
    fn fetched(&self) -> usize {
        self.have_b.iter().filter(|&&h| h).count()
    }

    /// Keeps a copy of the evaluation at the current `x` (made by [`Self::evaluate`] with
    /// `fetched` free slip velocities fetched before it).
    fn save_best(&mut self, fetched: usize) {
        let b = &mut self.best;
        b.y.clone_from(&self.y);
        b.phi.clone_from(&self.phi);
        b.lin.copy_from(&self.lin);
        b.fetched = fetched;
    }

    fn scale(&self) -> f64 {
        (0..self.m).fold(0.0f64, |a, k| a.max(self.x[3 * k].abs()))
    }

    /// Solve the problem set up by [`reset`](Self::reset) and [`set_gaps`](Self::set_gaps)
    /// (`diag` = the diagonal normal and tangential compliances `D_kk` used for `r_N`, `r_T`,
    /// per contact `[d_N, d_T]`). With `reuse`, the caller states that the contacts are the
    /// same as in the previous solve (a nearby `D`): its last LU may serve for chord steps.
    /// `alts` are further warm starts (3m each), used if their residual is smaller.
    pub fn solve(
        &mut self,
        src: &mut dyn DelassusSource,
        diag: &[[f64; 2]],
        s: &SolveOptions,
        reuse: bool,
        alts: &[&[f64]],
    ) -> SolveReport {
        let m = self.m;
        let n = 3 * m;
        let mut rep = SolveReport::default();
        if m == 0 {
            rep.converged = true;
            return rep;
        }
        self.need_slip = s.law.coefficient() > 0.0;
        for k in 0..m {
            self.rn[k] = 1.0 / diag[k][0].abs().max(1e-300);
            self.rt[k] = 1.0 / diag[k][1].abs().max(1e-300);
        }
        clear_fill(&mut self.dx, n, 0.0);
        clear_fill(&mut self.dy, n, 0.0);
        clear_fill(&mut self.xt, n, 0.0);
        clear_fill(&mut self.yt, n, 0.0);
        clear_fill(&mut self.tmp, n, 0.0);
        let fetched0 = self.fetched();
        let mut norm = self.evaluate(src, s);
        // further warm starts (e.g. the forces two steps back, contact chatter alternating from
        // step to step, or an extrapolation): keep the one with the smallest relative residual
        if alts.iter().any(|a| a.len() == n) {
            let mut best = norm / self.scale().max(1e-300);
            let mut best_is_current = true;
            self.xt.copy_from_slice(&self.x);
            self.save_best(fetched0);
            for alt in alts.iter().filter(|a| a.len() == n) {
                self.x.copy_from_slice(alt);
                for k in 0..m {
                    if self.x[3 * k].is_nan() || self.x[3 * k] <= 0.0 {
                        self.x[3 * k..3 * k + 3].copy_from_slice(&[0.0; 3]);
                    }
                }
                let before = self.fetched();
                let na = self.evaluate(src, s);
                let rel = na / self.scale().max(1e-300);
                if rel < best {
                    best = rel;
                    norm = na;
                    best_is_current = true;
                    self.xt.copy_from_slice(&self.x);
                    self.save_best(before);
                } else {
                    best_is_current = false;
                }
            }
            if !best_is_current {
                std::mem::swap(&mut self.x, &mut self.xt);
                if self.best.fetched == self.fetched() {
                    // the evaluation of the best again, bitwise (see `Evaluation`)
                    self.y.copy_from_slice(&self.best.y);
                    self.phi.copy_from_slice(&self.best.phi);
                    self.lin.copy_from(&self.best.lin);
                    self.lin_ok = true;
                } else {
                    norm = self.evaluate(src, s);
                }
            }
        }
        let mut ok = false;
        // chord steps reuse the last LU (also the previous solve's, when the caller says the
        // problem has the same structure) while the classification of the contacts is
        // unchanged and the residual contracts fast; else a full Newton step
        if !reuse {
            self.slots.iter_mut().for_each(|sl| sl.valid = false);
        }
        let mut chord_ok = reuse && self.slots.iter().any(|sl| sl.valid);
        let mut chords = 0;
        while rep.newton_iterations < s.max_newton {
            if norm <= s.tol * self.scale() {
                ok = true;
                break;
            }
            let chord = chord_ok && chords < 4 * s.max_newton;
            let Some(factored) = self.newton_direction(src, s, chord) else {
                if chord {
                    chord_ok = false;
                    continue;
                }
                break;
            };
            if factored {
                rep.newton_iterations += 1;
            } else {
                rep.chord_iterations += 1;
                chords += 1;
            }
            // line search on ½‖Φ‖² (Armijo) along dx; y is affine in x
            let mut t = 1.0;
            let theta0: f64 = self.phi.iter().map(|p| p * p).sum();
            let mut accepted = false;
            let mut phi_t = std::mem::take(&mut self.tmp);
            for _ in 0..30 {
                // projected trial point: λ ≥ 0 (the solution's normal forces are
                // non-negative; iterates at λ < 0 can stall at the kink of max(0, ·))
                for i in 0..n {
                    self.xt[i] = self.x[i] + t * self.dx[i];
                    self.yt[i] = self.y[i] + t * self.dy[i];
                }
                for k in 0..m {
                    if self.xt[3 * k] < 0.0 {
                        let c = -self.xt[3 * k];
                        self.xt[3 * k] = 0.0;
                        self.ensure_col(src, k);
                        let col = &self.d[3 * k * n..(3 * k + 1) * n];
                        for (yi, &dv) in self.yt.iter_mut().zip(col) {
                            *yi += c * dv;
                        }
                    }
                }
                let (xt, mut yt) = (std::mem::take(&mut self.xt), std::mem::take(&mut self.yt));
                let mut y = std::mem::take(&mut self.y);
                self.prefetch(src, &xt, &mut yt, Some(&mut y));
                self.y = y;
                let mut lin = std::mem::take(&mut self.lin_trial);
                let nt = self.residual(s, &xt, &yt, &mut phi_t, Some(&mut lin));
                self.lin_trial = lin;
                self.xt = xt;
                self.yt = yt;
                let theta: f64 = phi_t.iter().map(|p| p * p).sum();
                // a chord step must contract ‖Φ‖ by 4 (else: a full Newton step next)
                let good = if factored {
                    theta <= (1.0 - 2e-4 * t) * theta0
                } else {
                    theta <= theta0 / 16.0
                };
                if good || theta == 0.0 {
                    std::mem::swap(&mut self.x, &mut self.xt);
                    std::mem::swap(&mut self.y, &mut self.yt);
                    std::mem::swap(&mut self.phi, &mut phi_t);
                    std::mem::swap(&mut self.lin, &mut self.lin_trial);
                    self.lin_ok = true;
                    norm = nt;
                    accepted = true;
                    break;
                }
                if !factored {
                    break;
                }
                t *= 0.5;
            }
            self.tmp = phi_t;
            chord_ok = accepted && t == 1.0;
            if !accepted && !factored {
                continue;
            }
            if !accepted {
                let before = norm;
                norm = self.evaluate(src, s);
                if norm >= before {
                    break;
                }
            }
        }
        if !ok && norm <= s.tol * self.scale() {
            ok = true;
        }
        if !ok {
            rep.fallback = true;
            norm = self.alternation(src, diag, s, &mut rep);
            ok = norm <= s.tol * self.scale();
        }
        for k in 0..m {
            if self.x[3 * k] < 0.0 {
                self.x[3 * k] = 0.0;
            }
        }
        rep.converged = ok;
        rep.residual = norm;
        rep
    }

    /// The Newton direction `dx` (and `dy = D dx`) at `x`; `None` if the Jacobian is singular
    /// or (`chord`) the classification changed since the last LU, else whether an LU was made.
    /// With `chord`, the last LU replaces the Jacobian (simplified Newton).
    fn newton_direction(
        &mut self,
        src: &mut dyn DelassusSource,
        s: &SolveOptions,
        chord: bool,
    ) -> Option<bool> {
        let m = self.m;
        let n = 3 * m;
        // the linearisation at (x, y): formed with the residual there (evaluation or line
        // search), else now
        if !self.lin_ok {
            let (x, y) = (std::mem::take(&mut self.x), std::mem::take(&mut self.y));
            let (mut lin, mut phi) = (std::mem::take(&mut self.lin), std::mem::take(&mut self.tmp));
            phi.resize(n, 0.0);
            self.residual(s, &x, &y, &mut phi, Some(&mut lin));
            (self.x, self.y, self.lin, self.tmp) = (x, y, lin, phi);
            self.lin_ok = true;
        }
        self.act.clear();
        for k in 0..m {
            if self.lin.pattern[k] == 0 {
                self.state[k] = State::Open;
            } else {
                self.state[k] = State::Pressed;
                self.act.push(k);
            }
        }
        for i in 0..self.act.len() {
            let k = self.act[i];
            self.ensure_col(src, k);
        }
        let na = 3 * self.act.len();
        // open contacts: dx_k = −x_k; their effect on the pressed rows goes to the rhs
        for k in 0..m {
            if self.state[k] == State::Open {
                for a in 0..3 {
                    self.dx[3 * k + a] = -self.x[3 * k + a];
                }
            } else {
                for a in 0..3 {
                    self.dx[3 * k + a] = 0.0;
                }
            }
        }
        // dy_open = D dx_open (columns available: x_k ≠ 0 had its column)
        let mut dy = std::mem::take(&mut self.dy);
        self.apply(&self.dx, &mut dy, false);
        // a cached LU of the same classification (chord), or the slot to factor into
        let found = self
            .slots
            .iter()
            .position(|sl| sl.valid && sl.pattern == self.lin.pattern);
        let chord = chord && found.is_some();
        self.clock += 1;
        let cur = match found {
            Some(i) => i,
            None => {
                let mut best = 0;
                for (i, sl) in self.slots.iter().enumerate() {
                    if !sl.valid || sl.used < self.slots[best].used {
                        best = i;
                        if !sl.valid {
                            break;
                        }
                    }
                }
                best
            }
        };
        self.slots[cur].used = self.clock;
        if !chord {
            // the slot's old factors are overwritten: valid again only once refactorised
            self.slots[cur].valid = false;
            self.slots[cur].lu.resize_with(na, na, |_, _| 0.0);
        }
        self.rhs.clear();
        for &k in self.act.iter() {
            let g = &self.lin.gk[k];
            for r in 0..3 {
                let mut v = -self.phi[3 * k + r];
                for c in 0..3 {
                    v -= g[r][c] * dy[3 * k + c];
                }
                self.rhs.push(v);
            }
        }
        if !chord {
            // J_kl = δ_kl L_k + G_k D_kl, column by column
            for (ja, &l) in self.act.iter().enumerate() {
                for c in 0..3 {
                    let dcol = &self.d[(3 * l + c) * n..(3 * l + c + 1) * n];
                    let mut jc = self.slots[cur].lu.col_mut(3 * ja + c);
                    let Some(jcol) = jc.rb_mut().try_as_col_major_mut() else {
                        self.dy = dy;
                        return None;
                    };
                    let jcol = jcol.as_slice_mut();
                    for (ia, &k) in self.act.iter().enumerate() {
                        let g = &self.lin.gk[k];
                        let d3 = &dcol[3 * k..3 * k + 3];
                        for r in 0..3 {
                            jcol[3 * ia + r] = g[r][0] * d3[0] + g[r][1] * d3[1] + g[r][2] * d3[2];
                        }
                        if k == l {
                            for r in 0..3 {
                                jcol[3 * ia + r] += self.lin.lk[k][r][c];
                            }
                        }
                    }
                }
            }
        }
        let slot = &mut self.slots[cur];
        if chord && slot.n != na {
            self.dy = dy;
            return None;
        }
        if na > 0 && !chord {
            slot.valid = false;
            if self.mem_n < na {
                self.mem = Some(MemBuffer::new(lu_in_place_scratch::<usize, f64>(
                    na,
                    na,
                    Par::Seq,
                    Default::default(),
                )));
                self.mem_n = na;
            }
            slot.perm.resize(na, 0);
            slot.perm_inv.resize(na, 0);
            let Some(mem) = self.mem.as_mut() else {
                self.dy = dy;
                return None;
            };
            let _ = lu_in_place(
                slot.lu.as_mut(),
                &mut slot.perm,
                &mut slot.perm_inv,
                Par::Seq,
                MemStack::new(mem),
                Default::default(),
            );
            let singular = (0..na).any(|i| {
                let d = slot.lu[(i, i)];
                !(d.is_finite() && d != 0.0)
            });
            if singular {
                self.dy = dy;
                return None;
            }
            slot.valid = true;
            slot.n = na;
            slot.pattern.clear();
            slot.pattern.extend_from_slice(&self.lin.pattern);
        }
        if na > 0 {
            self.tmp.clear();
            self.tmp.extend(slot.perm.iter().map(|&p| self.rhs[p]));
            // (faer's two triangular solves, bitwise, without their per-block dispatch)
            let lu = &slot.lu;
            lu_solve_in_place(|j| col_slice(lu, j), na, &mut self.tmp[..na]);
            for (ia, &k) in self.act.iter().enumerate() {
                for a in 0..3 {
                    self.dx[3 * k + a] = self.tmp[3 * ia + a];
                }
            }
            self.tmp.resize(n, 0.0);
        }
        self.apply(&self.dx, &mut dy, false);
        self.dy = dy;
        self.dx.iter().all(|v| v.is_finite()).then_some(!chord)
    }

    /// The fallback: normal LCP with the friction frozen, alternated with block Gauss–Seidel
    /// sweeps on the friction forces (exact local Coulomb / regularised solve per contact),
    /// until `‖Φ‖∞ ≤ tol · max λ` or `max_rounds`. Returns `‖Φ‖∞`.
    fn alternation(
        &mut self,
        src: &mut dyn DelassusSource,
        diag: &[[f64; 2]],
        s: &SolveOptions,
        rep: &mut SolveReport,
    ) -> f64 {
        // x changes below without a residual: no linearisation at it
        self.lin_ok = false;
        let m = self.m;
        let n = 3 * m;
        for l in 0..m {
            self.ensure_col(src, l);
        }
        let mut norm = f64::INFINITY;
        for _round in 0..s.max_rounds {
            // normal problem: W = D_NN, q = b_N + D_NT f
            self.wn.resize_with(m, m, |_, _| 0.0);
            self.q.clear();
            self.warm.clear();
            for k in 0..m {
                let mut g = self.b[3 * k];
                for l in 0..m {
                    self.wn[(k, l)] = self.d[3 * l * n + 3 * k];
                    for a in 1..3 {
                        g += self.d[(3 * l + a) * n + 3 * k] * self.x[3 * l + a];
                    }
                }
                self.q.push(g);
                self.warm.push(self.x[3 * k] > 0.0);
            }
            let tol_gap = 1e-3 * s.tol * diag.iter().fold(0.0f64, |a, d| a.max(d[0])) * {
                let sc = self.scale();
                if sc > 0.0 { sc } else { 1.0 }
            };
            let _ = self
                .lcp
                .solve(self.wn.as_ref(), &self.q, &self.warm, tol_gap);
            rep.lcp_solves += 1;
            for k in 0..m {
                self.x[3 * k] = self.lcp.lambda[k];
                if self.x[3 * k] <= 0.0 {
                    self.x[3 * k + 1] = 0.0;
                    self.x[3 * k + 2] = 0.0;
                }
            }
            for k in 0..m {
                if self.need_slip && self.x[3 * k] > 0.0 {
                    self.ensure_b(src, k);
                }
            }
            let mut y = std::mem::take(&mut self.y);
            self.apply(&self.x, &mut y, true);
            // friction sweeps
            if s.law.coefficient() > 0.0 {
                for _ in 0..50 {
                    rep.sweeps += 1;
                    let mut change = 0.0f64;
                    for k in 0..m {
                        let lam = self.x[3 * k];
                        if lam <= 0.0 {
                            continue;
                        }
                        let bt = [
                            [
                                self.d[(3 * k + 1) * n + 3 * k + 1],
                                self.d[(3 * k + 2) * n + 3 * k + 1],
                            ],
                            [
                                self.d[(3 * k + 1) * n + 3 * k + 2],
                                self.d[(3 * k + 2) * n + 3 * k + 2],
                            ],
                        ];
                        let f = [self.x[3 * k + 1], self.x[3 * k + 2]];
                        // slip velocity without the contact's own friction
                        let r = [
                            y[3 * k + 1] - bt[0][0] * f[0] - bt[0][1] * f[1],
                            y[3 * k + 2] - bt[1][0] * f[0] - bt[1][1] * f[1],
                        ];
                        let new = s.law.local_force(
                            Matrix2::new(bt[0][0], bt[0][1], bt[1][0], bt[1][1]),
                            Vector2::new(r[0], r[1]),
                            lam,
                        );
                        let new = [new[0], new[1]];
                        let d = [new[0] - f[0], new[1] - f[1]];
                        if d == [0.0, 0.0] {
                            continue;
                        }
                        change = change.max(d[0].abs().max(d[1].abs()));
                        self.x[3 * k + 1] = new[0];
                        self.x[3 * k + 2] = new[1];
                        for a in 0..2 {
                            let col = &self.d[(3 * k + 1 + a) * n..(3 * k + 2 + a) * n];
                            for (yi, &c) in y.iter_mut().zip(col) {
                                *yi += d[a] * c;
                            }
                        }
                    }
                    if change <= 1e-3 * s.tol * self.scale() {
                        break;
                    }
                }
            }
            self.y = y;
            norm = self.evaluate(src, s);
            if norm <= s.tol * self.scale() {
                break;
            }
        }
        norm
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One node, regularised law: `λ = −g/d_N`; `u = v + d_T f`, `f = −μλ u/√(u²+ε²)` reduces
    /// to a monotone scalar equation in `u`, solved here by bisection (independent reference).
    #[test]
    fn single_node_regularized_against_bisection() {
        for &(dn, dt, g, v, mu, eps) in &[
            (1.0, 1.0, -1.0, 1.0, 0.5, 0.1),
            (2e-7, 4e-3, -1e-4, 3.0, 0.85, 0.05),
            (2e-7, 4e-3, -1e-4, -0.2, 0.85, 0.05),
            (1.0, 0.5, -2.0, 0.01, 1.0, 0.01),
        ] {
            let d = [dn, 0.0, 0.0, 0.0, dt, 0.0, 0.0, 0.0, dt];
            let b = [g, v, 0.0];
            let mut s = ContactSolver::default();
            s.reset(&[0.0; 3]);
            s.set_gaps([g]);
            let set = SolveOptions {
                law: Arc::new(contact::SlipRegularized { mu, epsilon: eps }),
                ..SolveOptions::default()
            };
            let rep = s.solve(
                &mut DenseProblem { d: &d, b: &b },
                &[[dn, dt]],
                &set,
                false,
                &[],
            );
            let lam = -g / dn;
            // u − v + d_T μλ u/√(u²+ε²) = 0, increasing in u
            let h = |u: f64| u - v + dt * mu * lam * u / (u * u + eps * eps).sqrt();
            let (mut lo, mut hi) = (-v.abs() - 1.0, v.abs() + 1.0);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if h(mid) > 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let u = 0.5 * (lo + hi);
            let f = -mu * lam * u / (u * u + eps * eps).sqrt();
            assert!(rep.converged, "{rep:?}");
            assert!((s.x()[0] - lam).abs() <= 1e-9 * lam);
            assert!((s.x()[1] - f).abs() <= 1e-9 * lam, "{} vs {f}", s.x()[1]);
            assert!(s.x()[2].abs() <= 1e-9 * lam);
        }
    }
}
