//! Active-set solution of the contact complementarity problem of the Lagrange-multiplier contact
//! (Ribaric §7.3, seed note U4): find `λ ≥ 0` with `w = q + W λ ≥ 0` and `λᵢ wᵢ = 0`.
//!
//! `q` are the free gaps [m], `W` the (possibly non-symmetric, with slip friction) Delassus
//! matrix [m/N]. The active set starts from a warm guess; constraints with tensile multipliers
//! are released and penetrating ones added until both conditions hold (Murty's principal
//! pivoting in its block form).

use faer::Mat;
use faer::prelude::*;

/// Result of [`solve_lcp`].
#[derive(Debug, Clone)]
pub struct LcpSolution {
    /// Multipliers `λ` (≥ 0) [N].
    pub lambda: Vec<f64>,
    /// Active-set iterations used.
    pub iterations: usize,
    /// Whether the complementarity conditions hold to the tolerance.
    pub converged: bool,
}

/// Solve the LCP `w = q + W λ ≥ 0, λ ≥ 0, λᵀw = 0` by an active-set iteration starting from
/// `warm` (indices believed active). `tol` is the gap tolerance [m].
pub fn solve_lcp(w: &Mat<f64>, q: &[f64], warm: &[bool], tol: f64) -> LcpSolution {
    let n = q.len();
    let mut active: Vec<bool> = (0..n)
        .map(|i| warm.get(i).copied().unwrap_or(false) || q[i] < -tol)
        .collect();
    let mut lambda = vec![0.0; n];
    let max_iter = 4 * n + 20;
    for it in 0..max_iter {
        let idx: Vec<usize> = (0..n).filter(|&i| active[i]).collect();
        lambda.iter_mut().for_each(|l| *l = 0.0);
        if !idx.is_empty() {
            let a = Mat::from_fn(idx.len(), idx.len(), |i, j| w[(idx[i], idx[j])]);
            let b = Mat::from_fn(idx.len(), 1, |i, _| -q[idx[i]]);
            let x = a.partial_piv_lu().solve(&b);
            for (k, &i) in idx.iter().enumerate() {
                lambda[i] = x[(k, 0)];
            }
        }
        // release tensile multipliers (all of them at once)
        let mut changed = false;
        let lam_scale = lambda.iter().fold(0.0f64, |m, l| m.max(l.abs()));
        for &i in &idx {
            if !(lambda[i] >= -1e-12 * lam_scale) {
                active[i] = false;
                changed = true;
            }
        }
        if changed {
            continue;
        }
        // add penetrating constraints (the most violated one first, all beyond 10 % of it)
        let mut worst = 0.0;
        let mut gaps = vec![0.0; n];
        for i in 0..n {
            if active[i] {
                continue;
            }
            let mut g = q[i];
            for &j in &idx {
                g += w[(i, j)] * lambda[j];
            }
            gaps[i] = g;
            if g < worst {
                worst = g;
            }
        }
        if worst < -tol {
            for i in 0..n {
                if !active[i] && gaps[i] < 0.1 * worst {
                    active[i] = true;
                }
            }
            continue;
        }
        for l in lambda.iter_mut() {
            *l = l.max(0.0);
        }
        return LcpSolution {
            lambda,
            iterations: it + 1,
            converged: true,
        };
    }
    for l in lambda.iter_mut() {
        *l = l.max(0.0);
    }
    LcpSolution {
        lambda,
        iterations: max_iter,
        converged: false,
    }
}
