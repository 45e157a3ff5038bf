//! [`ContactSolver`]: the problem's state, the Alart–Curnier residual and its linearisation,
//! and the semismooth Newton iteration with line search (module documentation of
//! [`super`]); the Newton direction is in `newton`, the fallback in `fallback`.

use super::lcp::LcpWork;
use super::newton::LuSlot;
use super::options::{ContactSolverOptions, ContactSolverReport};
use super::problem::{DelassusSource, DenseProblem};
use faer::Mat;
use faer::dyn_stack::MemBuffer;
use mbd_core::linalg::axpy_cols;
use nalgebra::Vector2;

/// Classification of a contact at the current Newton iterate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum State {
    /// `λ − r_N g ≤ 0`: identity rows.
    Open,
    /// Pressed, friction inside the disk (or regularised law).
    Pressed,
}

/// The linearisation of the Alart–Curnier residual at one point (see
/// [`ContactSolver::residual`]).
#[derive(Default)]
pub(super) struct Linearization {
    /// Per pressed contact: 3 × 3 matrices `L_k` (own unknowns) and `G_k` (own outputs) of the
    /// Jacobian rows `dΦ_k = L_k dx_k + G_k dy_k` (row-major).
    pub(super) lk: Vec<[[f64; 3]; 3]>,
    pub(super) gk: Vec<[[f64; 3]; 3]>,
    /// Classification per contact (0 open, 1 pressed/slip, 2 stick).
    pub(super) pattern: Vec<u8>,
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
pub(super) struct Evaluation {
    y: Vec<f64>,
    phi: Vec<f64>,
    lin: Linearization,
    fetched: usize,
}

/// Reusable buffers of the contact solve (no allocation once grown).
pub struct ContactSolver {
    pub(super) m: usize,
    /// Local Delassus matrix (column-major, ld = 3m); column block `l` valid iff `have[l]`.
    pub(super) d: Vec<f64>,
    pub(super) have: Vec<bool>,
    /// Free values `b` (3m); tangential entries valid iff `have_b[k]`.
    pub(super) b: Vec<f64>,
    pub(super) have_b: Vec<bool>,
    /// Whether the free slip velocities matter (μ > 0).
    pub(super) need_slip: bool,
    /// Unknowns (warm start in, solution out).
    pub(super) x: Vec<f64>,
    pub(super) y: Vec<f64>,
    pub(super) phi: Vec<f64>,
    pub(super) rn: Vec<f64>,
    pub(super) rt: Vec<f64>,
    pub(super) state: Vec<State>,
    /// The linearisation of `Φ` at the current `(x, y)`, formed with its residual (valid iff
    /// `lin_ok`), and at the line search's trial point.
    pub(super) lin: Linearization,
    pub(super) lin_trial: Linearization,
    pub(super) lin_ok: bool,
    /// The evaluation (`y`, `Φ`, linearisation) of the best warm start so far.
    pub(super) best: Evaluation,
    pub(super) act: Vec<usize>,
    /// The last few Newton matrices (LU factors), by classification: chord steps use the one
    /// of the current classification (the patch often alternates between two from step to
    /// step).
    pub(super) slots: Vec<LuSlot>,
    pub(super) clock: u64,
    pub(super) rhs: Vec<f64>,
    pub(super) tmp: Vec<f64>,
    pub(super) dx: Vec<f64>,
    pub(super) dy: Vec<f64>,
    pub(super) xt: Vec<f64>,
    pub(super) yt: Vec<f64>,
    pub(super) mem: Option<MemBuffer>,
    pub(super) mem_n: usize,
    pub(super) lcp: LcpWork,
    pub(super) wn: Mat<f64>,
    pub(super) q: Vec<f64>,
    pub(super) warm: Vec<bool>,
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
            slots: (0..3).map(|_| LuSlot::empty()).collect(),
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

pub(super) fn clear_fill<T: Clone>(v: &mut Vec<T>, n: usize, val: T) {
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

    /// Solve a problem given as a full matrix ([`DenseProblem`]) from the warm start `x0`
    /// (3m; zeros for none): [`ContactSolver::reset`], the free gaps of `problem.b`, and
    /// [`ContactSolver::solve`] with the diagonal compliances of `problem.d`, without reuse of
    /// earlier Newton matrices. The solution is [`ContactSolver::x`].
    pub fn solve_dense(
        &mut self, problem: &mut DenseProblem<'_>, x0: &[f64], options: &ContactSolverOptions,
    ) -> ContactSolverReport {
        self.reset(x0);
        let m = problem.b.len() / 3;
        self.set_gaps((0..m).map(|k| problem.b[3 * k]));
        let diag = problem.diagonal();
        self.solve(problem, &diag, options, false, &[])
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

    pub(super) fn ensure_col(&mut self, src: &mut dyn DelassusSource, l: usize) {
        if self.have[l] {
            return;
        }
        let n = 3 * self.m;
        src.columns(l, &mut self.d[3 * l * n..(3 * l + 3) * n]);
        self.have[l] = true;
    }

    pub(super) fn ensure_b(&mut self, src: &mut dyn DelassusSource, k: usize) {
        if self.have_b[k] {
            return;
        }
        let u = src.free_slip(k);
        self.b[3 * k + 1] = u[0];
        self.b[3 * k + 2] = u[1];
        self.have_b[k] = true;
    }

    /// `out = D v + b` over the column blocks with a nonzero `v` (which must be available).
    pub(super) fn apply(&self, v: &[f64], out: &mut [f64], with_b: bool) {
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
    pub(super) fn residual(
        &self, s: &ContactSolverOptions, x: &[f64], y: &[f64], phi: &mut [f64],
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
        &mut self, src: &mut dyn DelassusSource, x: &[f64], y: &mut [f64],
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
    pub(super) fn evaluate(
        &mut self, src: &mut dyn DelassusSource, s: &ContactSolverOptions,
    ) -> f64 {
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

    pub(super) fn scale(&self) -> f64 {
        (0..self.m).fold(0.0f64, |a, k| a.max(self.x[3 * k].abs()))
    }

    /// Solve the problem set up by [`reset`](Self::reset) and [`set_gaps`](Self::set_gaps)
    /// (`diag` = the diagonal normal and tangential compliances `D_kk` used for `r_N`, `r_T`,
    /// per contact `[d_N, d_T]`). With `reuse`, the caller states that the contacts are the
    /// same as in the previous solve (a nearby `D`): its last LU may serve for chord steps.
    /// `alts` are further warm starts (3m each), used if their residual is smaller.
    pub fn solve(
        &mut self, src: &mut dyn DelassusSource, diag: &[[f64; 2]], s: &ContactSolverOptions,
        reuse: bool, alts: &[&[f64]],
    ) -> ContactSolverReport {
        let m = self.m;
        let n = 3 * m;
        let mut rep = ContactSolverReport::default();
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

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
            let set = ContactSolverOptions {
                law: Arc::new(crate::SlipRegularized { mu, epsilon: eps }),
                ..ContactSolverOptions::default()
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
