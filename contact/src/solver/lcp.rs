//! Active-set solution of the contact complementarity problem of Lagrange-multiplier contact
//! (Ribaric §7.3, seed note U4): find `λ ≥ 0` with `w = q + W λ ≥ 0` and `λᵢ wᵢ = 0`.
//!
//! `q` are the free gaps \[m\], `W` the (possibly non-symmetric, with slip friction) Delassus
//! matrix \[m/N\]. The active set starts from a warm guess; constraints with tensile multipliers
//! are released and penetrating ones added until both conditions hold (Murty's principal
//! pivoting in its block form).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::factor::{lu_in_place, lu_in_place_scratch};
use faer::linalg::triangular_solve::{
    solve_unit_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::prelude::*;
use faer::{Mat, MatMut, MatRef, Par};

/// Result of [`solve_lcp`].
#[derive(Debug, Clone)]
pub struct LcpSolution {
    /// Multipliers `λ` (≥ 0) \[N\].
    pub lambda: Vec<f64>,
    /// Active-set iterations used.
    pub iterations: usize,
    /// Whether the complementarity conditions hold to the tolerance.
    pub converged: bool,
}

/// Reusable buffers of the active-set LCP solver ([`LcpWork::solve`]): repeated solves of
/// problems of similar size do not allocate, and the small dense factorisations run
/// sequentially (no thread-pool dispatch for a 20 × 20 system).
#[derive(Debug, Clone)]
pub struct LcpWork {
    /// Multipliers of the last solve \[N\].
    pub lambda: Vec<f64>,
    active: Vec<bool>,
    idx: Vec<usize>,
    gaps: Vec<f64>,
    a: Mat<f64>,
    b: Vec<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
}

impl Default for LcpWork {
    fn default() -> Self {
        Self {
            lambda: Vec::new(),
            active: Vec::new(),
            idx: Vec::new(),
            gaps: Vec::new(),
            a: Mat::zeros(0, 0),
            b: Vec::new(),
            perm: Vec::new(),
            perm_inv: Vec::new(),
        }
    }
}

impl LcpWork {
    /// Solve `w = q + W λ ≥ 0, λ ≥ 0, λᵀw = 0` (see [`solve_lcp`]); the multipliers are left in
    /// `self.lambda`. Returns `(converged, iterations)`.
    pub fn solve(
        &mut self, w: MatRef<'_, f64>, q: &[f64], warm: &[bool], tol: f64,
    ) -> (bool, usize) {
        let n = q.len();
        self.active.clear();
        self.active
            .extend((0..n).map(|i| warm.get(i).copied().unwrap_or(false) || q[i] < -tol));
        self.lambda.clear();
        self.lambda.resize(n, 0.0);
        self.gaps.clear();
        self.gaps.resize(n, 0.0);
        let max_iter = 4 * n + 20;
        for it in 0..max_iter {
            self.idx.clear();
            self.idx.extend((0..n).filter(|&i| self.active[i]));
            self.lambda.iter_mut().for_each(|l| *l = 0.0);
            let k = self.idx.len();
            if k > 0 {
                let idx = &self.idx;
                self.a.resize_with(k, k, |_, _| 0.0);
                for (jj, &j) in idx.iter().enumerate() {
                    for (ii, &i) in idx.iter().enumerate() {
                        self.a[(ii, jj)] = w[(i, j)];
                    }
                }
                self.perm.resize(k, 0);
                self.perm_inv.resize(k, 0);
                let mut buf = MemBuffer::new(lu_in_place_scratch::<usize, f64>(
                    k,
                    k,
                    Par::Seq,
                    Default::default(),
                ));
                let _ = lu_in_place(
                    self.a.as_mut(),
                    &mut self.perm,
                    &mut self.perm_inv,
                    Par::Seq,
                    MemStack::new(&mut buf),
                    Default::default(),
                );
                self.b.clear();
                self.b.extend(self.perm.iter().map(|&p| -q[idx[p]]));
                let mut x = MatMut::from_column_major_slice_mut(&mut self.b, k, 1);
                solve_unit_lower_triangular_in_place(self.a.as_ref(), x.rb_mut(), Par::Seq);
                solve_upper_triangular_in_place(self.a.as_ref(), x.rb_mut(), Par::Seq);
                for (kk, &i) in idx.iter().enumerate() {
                    self.lambda[i] = self.b[kk];
                }
            }
            // release tensile multipliers (all of them at once)
            let mut changed = false;
            let lam_scale = self.lambda.iter().fold(0.0f64, |m, l| m.max(l.abs()));
            for &i in &self.idx {
                if self.lambda[i].is_nan() || self.lambda[i] < -1e-12 * lam_scale {
                    self.active[i] = false;
                    changed = true;
                }
            }
            if changed {
                continue;
            }
            // add penetrating constraints (the most violated one first, all beyond 10 % of it)
            let mut worst = 0.0;
            for i in 0..n {
                if self.active[i] {
                    continue;
                }
                let mut g = q[i];
                for &j in &self.idx {
                    g += w[(i, j)] * self.lambda[j];
                }
                self.gaps[i] = g;
                if g < worst {
                    worst = g;
                }
            }
            if worst < -tol {
                for i in 0..n {
                    if !self.active[i] && self.gaps[i] < 0.1 * worst {
                        self.active[i] = true;
                    }
                }
                continue;
            }
            for l in self.lambda.iter_mut() {
                *l = l.max(0.0);
            }
            return (true, it + 1);
        }
        for l in self.lambda.iter_mut() {
            *l = l.max(0.0);
        }
        (false, max_iter)
    }
}

/// Solve the LCP `w = q + W λ ≥ 0, λ ≥ 0, λᵀw = 0` by an active-set iteration starting from
/// `warm` (indices believed active). `tol` is the gap tolerance \[m\].
pub fn solve_lcp(w: &Mat<f64>, q: &[f64], warm: &[bool], tol: f64) -> LcpSolution {
    let mut work = LcpWork::default();
    let (converged, iterations) = work.solve(w.as_ref(), q, warm, tol);
    LcpSolution {
        lambda: work.lambda,
        iterations,
        converged,
    }
}
